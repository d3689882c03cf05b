// study/methods.hpp -- the methods the robustness study judges, and how an answer is
// judged against the certified one.
//
// A method is one algorithm in one number type (or one peer library in its own arithmetic)
// for one query: a callable from the instance's binary64 coordinates (study/instance.hpp) to
// its answer. Three-valued methods return separated / touching / overlapping (and, for line
// queries, the computed entry parameter); boolean methods (the seeds that only say
// "intersect", the peer libraries) return `intersecting` or separated; certified number types
// may say undecided. Adding a method is adding one Method to a registry.
//
// Judgement against the certified answer C (outcome):
//   false_positive   the method says the sets meet, C = separated
//   false_negative   the method says separated, C = touching or overlapping
//   class_mismatch   both say they meet, but a three-valued method picks the other of
//                    touching / overlapping
//   undecided        the method declined (an interval type)
//   error            the method threw (for instance a degenerate division it cannot handle)
//   invalid          a value the method reports left the finite doubles (an overflow, a 0/0):
//                    its answer came from comparisons with an infinity or a NaN, counted apart
//                    as `certcyl query` answers "invalid"
//   agree            otherwise
#pragma once

#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "certcyl/answer.hpp"
#include "study/instance.hpp"

namespace certcyl::study {

// What a method says. `intersecting` marks a boolean method's "they meet".
struct MethodOutput {
  Answer answer = Answer::undecided;
  bool intersecting = false;  // a boolean method's positive answer (answer is then unused)
  bool error = false;
  bool invalid = false;       // a reported value is not finite (answer keeps what was computed)
  double t_in = std::numeric_limits<double>::quiet_NaN();  // line queries: computed entry parameter
};

inline MethodOutput three_valued(Answer a, double t_in = std::numeric_limits<double>::quiet_NaN()) {
  MethodOutput m;
  m.answer = a;
  m.t_in = t_in;
  return m;
}
inline MethodOutput boolean_answer(bool meet) {
  MethodOutput m;
  m.intersecting = meet;
  m.answer = meet ? Answer::overlapping : Answer::separated;
  return m;
}

// How a method is built, for grouping in tables and plots.
enum class MethodKind { certified, seed_as_written, seed_corrected, robust, sweep, peer };

inline constexpr std::string_view to_string(MethodKind k) {
  switch (k) {
    case MethodKind::certified: return "certified";
    case MethodKind::seed_as_written: return "seed_as_written";
    case MethodKind::seed_corrected: return "seed_corrected";
    case MethodKind::robust: return "robust";
    case MethodKind::sweep: return "sweep";
    case MethodKind::peer: return "peer";
  }
  return "?";
}

// What a method's positive answer promises (study/contract.hpp): the solid answer, or a ray
// cast's surface entry or surface hit.
enum class Contract { solid, surface_entry, surface_hit };

inline constexpr std::string_view to_string(Contract c) {
  switch (c) {
    case Contract::solid: return "solid";
    case Contract::surface_entry: return "surface_entry";
    case Contract::surface_hit: return "surface_hit";
  }
  return "?";
}

struct Conversion;  // study/conversion.hpp

// A method's share of the failure maps and the failure hunting. Every method takes part; a
// slow one evaluates a map on every map_stride-th row and column only (the rows and columns
// through the degenerate centre cell: map_stride^2 times fewer cells), and the hunt spends
// hunt_evaluations / hunt_divisor evaluations on it.
struct Effort {
  unsigned map_stride = 1;
  unsigned hunt_divisor = 1;
};

struct Method {
  std::string base;  // the algorithm: "shene", "gullotti_as_written", "fcl", ...
  std::string nt;    // its arithmetic: "double", "gmpfr<113>", "float (Bullet)", ...
  MethodKind kind = MethodKind::seed_corrected;
  Query query = Query::line_cylinder;
  // Runs on a pseudo-random 1/stride of each family's instances only (slow number types).
  unsigned stride = 1;
  Effort effort{};
  std::function<MethodOutput(const std::vector<double>&)> run;
  // Runs one call at a time, on the study's main thread only, after the parallel work of each
  // phase: CORE::Expr (two threads at once crashed; calls from two threads in turn, even one
  // at a time, ended in CORE's "zero divisor" exit on the failure maps) and ODE's trimesh
  // collider (its OPCODE caches are not thread-safe: a segmentation fault with two threads).
  bool serial = false;
  // What its answer promises for this query (study/contract.hpp); judged against it.
  Contract contract = Contract::solid;
  // The instance it receives, when that is not the binary64 input itself (study/conversion.hpp:
  // Gmpfr below 53 bits, Bullet's floats); null otherwise.
  std::shared_ptr<const Conversion> conversion = nullptr;

  std::string name() const { return base + "/" + nt; }
};

using Registry = std::vector<Method>;

enum class Outcome { agree, false_positive, false_negative, class_mismatch, undecided, error, invalid };

inline constexpr std::string_view to_string(Outcome o) {
  switch (o) {
    case Outcome::agree: return "agree";
    case Outcome::false_positive: return "false_positive";
    case Outcome::false_negative: return "false_negative";
    case Outcome::class_mismatch: return "class_mismatch";
    case Outcome::undecided: return "undecided";
    case Outcome::error: return "error";
    case Outcome::invalid: return "invalid";
  }
  return "?";
}

inline std::ostream& operator<<(std::ostream& os, Outcome o) { return os << to_string(o); }

inline std::string answer_label(const MethodOutput& m) {
  if (m.error) return "error";
  if (m.invalid) return "invalid";
  if (m.intersecting) return "intersecting";
  return std::string(to_string(m.answer));
}

// The judgement of a method's output against a certified (decided) answer.
inline Outcome judge(const MethodOutput& m, Answer certified) {
  if (m.error) return Outcome::error;
  if (m.invalid) return Outcome::invalid;
  if (!m.intersecting && m.answer == Answer::undecided) return Outcome::undecided;
  const bool says_meet = m.intersecting || intersects(m.answer);
  const bool meets = intersects(certified);
  if (says_meet && !meets) return Outcome::false_positive;
  if (!says_meet && meets) return Outcome::false_negative;
  if (says_meet && !m.intersecting && m.answer != certified) return Outcome::class_mismatch;
  return Outcome::agree;
}

// A disagreement is a wrong boolean answer; class mismatches are reported apart.
inline bool disagrees(Outcome o) { return o == Outcome::false_positive || o == Outcome::false_negative; }

}  // namespace certcyl::study
