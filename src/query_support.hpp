// Shared pieces of the query handlers: exact values as JSON, the common answer fields, the
// certified signed gap, and running a generic method in the number type of --nt.
#pragma once

#include <nlohmann/json.hpp>

#include <cmath>
#include <string>

#include "certcyl/answer.hpp"
#include "certcyl/dispatch.hpp"
#include "certcyl/filtered.hpp"
#include "certcyl/rational.hpp"
#include "certcyl/vec3.hpp"
#include "query.hpp"
#include "study/gap.hpp"

namespace certcyl::cli {

inline ojson exact_json(const Rational& q) { return to_exact_string(q); }

inline ojson exact_json(const Vec3<Rational>& v) { return ojson::array({exact_json(v.x), exact_json(v.y), exact_json(v.z)}); }

// The fields every answer carries.
inline ojson answer_json(Answer a, bool certified, const std::string& method, const std::string& nt) {
  return ojson{{"answer", std::string(to_string(a))}, {"certified", certified}, {"method", method}, {"nt", nt}};
}

// The certified signed gap (study/gap.hpp) of a query other than a cylinder pair, the depth
// margin G: the enclosure [lo, hi] in doubles of G (lo == hi when G is that double), as
// `certcyl cases` writes it in meta.gap; null when G lies beyond the finite doubles (JSON has no
// infinity).
inline ojson gap_json(const study::MarginEnclosure& gap) {
  const auto [lo, hi] = study::detail::enclose_margin_doubles(gap);
  if (!std::isfinite(lo) || !std::isfinite(hi)) return nullptr;
  return ojson::array({lo, hi});
}
// The same for a point's margin, its depth, an exact rational.
inline ojson gap_json(const Rational& gap) { return gap_json(study::MarginEnclosure{gap, gap}); }

// `answer` with "gap" and "gap_quantity" (the depth margin's name, study/gap_quantity.hpp)
// placed where the cylinder pair has them: after the common fields (answer, certified, method,
// nt) and the pair's stage, before the query's own.
inline ojson with_gap(const ojson& answer, const ojson& gap) {
  ojson out = ojson::object();
  bool placed = false;
  const auto place = [&] {
    out["gap"] = gap;
    out["gap_quantity"] = std::string(study::to_string(study::GapQuantity::depth_margin));
    placed = true;
  };
  for (auto it = answer.begin(); it != answer.end(); ++it) {
    const std::string& key = it.key();
    const bool common = key == "answer" || key == "certified" || key == "method" || key == "nt" || key == "stage";
    if (!common && !placed) place();
    out[key] = it.value();
  }
  if (!placed) place();
  return out;
}

// Runs body.template operator()<NT>() -> Answer in the number type of --nt. The answer is
// "certified" only when the method is a correct algorithm for the query (`exact_algorithm`:
// an exact predicate, not a seed whose control flow can be wrong even in exact arithmetic) and
// the type is certified. A certified type that cannot decide (an interval) gives "undecided"; a type that cannot hold the input
// (Mpzf and a non-dyadic value) is an error for that line. When the type rounds and some input
// was not a binary64 value, the answer says so ("input_rounded": true).
template <class Body>
ojson run_in_number_type(const QueryOptions& options, bool input_all_binary64, bool exact_algorithm, Body body) {
  const NumberTypeSpec& spec = options.nt;
  Answer a = Answer::undecided;
  bool certified = false;
  dispatch(spec, [&]<class NT>() {
    certified = exact_algorithm && NumberTraits<NT>::is_certified;
    try {
      a = body.template operator()<NT>();
    } catch (const CGAL::Uncertain_conversion_exception&) {
      a = Answer::undecided;
    }
    return 0;
  });
  ojson out = answer_json(a, certified && a != Answer::undecided, options.method, spec.name());
  const bool rounds = spec.kind == NumberKind::double_ || spec.kind == NumberKind::long_double ||
                      spec.kind == NumberKind::gmpfr;
  if (rounds && !input_all_binary64) out["input_rounded"] = true;
  return out;
}

}  // namespace certcyl::cli
