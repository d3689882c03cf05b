// certcyl/answer.hpp -- the three-valued answer of every test-intersection query.
//
// separated    the two sets have no common point
// touching     common points exist, but none interior to both solids (for a line, ray, segment
//              or triangle: it meets the cylinder but not its open interior)
// overlapping  some point is interior to both (for a line-like or planar set: it meets the
//              cylinder's open interior)
// undecided    a certified method could not decide within its limits; it never guesses
//
// The boolean "intersect" of the seeds is `touching || overlapping`.
#pragma once

#include <optional>
#include <ostream>
#include <string>
#include <string_view>

namespace certcyl {

enum class Answer { separated, touching, overlapping, undecided };

inline constexpr std::string_view to_string(Answer a) {
  switch (a) {
    case Answer::separated: return "separated";
    case Answer::touching: return "touching";
    case Answer::overlapping: return "overlapping";
    case Answer::undecided: return "undecided";
  }
  return "undecided";
}

inline std::optional<Answer> answer_from_string(std::string_view s) {
  for (Answer a : {Answer::separated, Answer::touching, Answer::overlapping, Answer::undecided})
    if (to_string(a) == s) return a;
  return std::nullopt;
}

// The seeds' boolean: do the sets share a point?
inline constexpr bool intersects(Answer a) { return a == Answer::touching || a == Answer::overlapping; }

inline std::ostream& operator<<(std::ostream& os, Answer a) { return os << to_string(a); }

}  // namespace certcyl
