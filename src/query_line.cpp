// Line, ray and segment against circular and elliptic cylinders.
//
// Methods: certified (exact endpoints a + b sqrt(c), correctly rounded doubles, and the certified
// signed gap: the depth margin of study/gap.hpp), shene and
// gullotti (the seeds' methods, generic: --nt), shene_as_written (the text's "r < |d|"
// unchanged), gullotti_as_written (the seed's tangency rule unchanged), robust_double
// (cancellation-free discriminant, stable roots, FMA).
#include <cmath>

#include "certcyl/certified/line_cylinder.hpp"
#include "certcyl/io/json_input.hpp"
#include "certcyl/robust/line_cylinder.hpp"
#include "certcyl/seeds/gullotti_line_elliptic_cylinder.hpp"
#include "certcyl/seeds/shene_line_cylinder.hpp"
#include "query.hpp"
#include "query_support.hpp"

namespace certcyl::cli {
namespace {

ojson certified_json(const CertifiedLineResult& r) {
  const std::string stage = r.stage == LineStage::semi_static ? "static" : std::string(to_string(r.stage));
  ojson out = answer_json(r.answer, true, "certified", stage);
  ojson interval = ojson::array();
  if (r.in) {
    const auto [in, out] = r.exact_values();
    for (const auto& [e, value] : {std::pair{&*r.in, &in}, std::pair{&*r.out, &out}}) {
      interval.push_back(ojson{{"exact", value->to_string()},
                               {"approx", e->nearest},
                               {"feature", std::string(to_string(e->feature))},
                               {"surface", std::string(to_string(e->surface))}});
    }
  }
  out["interval"] = interval;
  // The endpoints are the proof: each is an exact root of the tube quadratic or a cap plane's
  // parameter, and the decision between them was made by exact signs.
  out["certificate"] = ojson{{"endpoints", "exact roots of the wall quadratic and cap-plane parameters"},
                             {"decided_by", stage}};
  return out;
}

// The certified signed gap of a line, ray or segment (study/gap.hpp: the depth margin
// G = max d(x) over the allowed range of t, enclosed; a segment as the line p0 + t (p1 - p0),
// t in [0, 1]).
template <class Solid>
study::MarginEnclosure depth_margin(const Line<Rational>& l, const Solid& s, LineRange range) {
  if constexpr (std::is_same_v<Solid, Cylinder<Rational>>)
    return study::detail::circular_line_gap(l, s, range);
  else
    return study::detail::elliptic_line_gap(l, s, range);
}
template <class Solid>
study::MarginEnclosure line_gap(const Line<Rational>& l, const Solid& s) {
  return depth_margin(l, s, LineRange::line);
}
template <class Solid>
study::MarginEnclosure line_gap(const Ray<Rational>& r, const Solid& s) {
  return depth_margin(Line<Rational>{r.origin, r.direction}, s, LineRange::ray);
}
template <class Solid>
study::MarginEnclosure line_gap(const Segment<Rational>& g, const Solid& s) {
  return depth_margin(Line<Rational>{g.p0, g.direction()}, s, LineRange::segment);
}

// The interval of a floating or generic method: the computed endpoints with an enclosure of
// each computed value (a point for floating types) and its feature.
template <class NT>
ojson interval_json(const LineInterval<NT>& r) {
  ojson interval = ojson::array();
  for (const auto* e : {&r.in, &r.out}) {
    if (!*e) continue;
    const auto [lo, hi] = nt::to_interval((*e)->t);
    ojson ep{{"approx", nt::to_double((*e)->t)}, {"feature", std::string(to_string((*e)->feature))}};
    if (!std::isfinite(lo) || !std::isfinite(hi)) {
      ep["enclosure"] = ojson::array({lo, hi});  // not a number: the answer becomes "invalid"
    } else if (lo == hi) {
      ep["exact"] = to_exact_string(Rational(lo));  // the computed value is this binary64 number
    } else {
      ep["enclosure"] = ojson::array({lo, hi});
    }
    interval.push_back(ep);
  }
  return interval;
}

// Gullotti's method on any line-like input: the line's interval, clipped to the range.
template <class NT, class Solid>
LineInterval<NT> gullotti_on_line(const Line<NT>& l, const Solid& s, GullottiVariant v) {
  if constexpr (std::is_same_v<Solid, Cylinder<NT>>)
    return gullotti_line_cylinder(l, s, v);
  else
    return gullotti_line_elliptic_cylinder(l, s, v);
}
template <class NT, class Solid>
LineInterval<NT> gullotti_any(const Line<NT>& l, const Solid& s, GullottiVariant v) {
  return gullotti_on_line(l, s, v);
}
template <class NT, class Solid>
LineInterval<NT> gullotti_any(const Ray<NT>& r, const Solid& s, GullottiVariant v) {
  return clip_to_range(gullotti_on_line(Line<NT>{r.origin, r.direction}, s, v), LineRange::ray);
}
template <class NT, class Solid>
LineInterval<NT> gullotti_any(const Segment<NT>& g, const Solid& s, GullottiVariant v) {
  return clip_to_range(gullotti_on_line(Line<NT>{g.p0, g.direction()}, s, v), LineRange::segment);
}

template <class NT>
constexpr bool has_sqrt_field = NumberTraits<NT>::has_sqrt && NumberTraits<NT>::is_field;

template <class LineLike, class Solid>
ojson answer_line_query(const LineLike& x, const Solid& solid, bool all_binary64, const QueryOptions& options) {
  const std::string& m = options.method;
  if (m == "certified") return with_gap(certified_json(certified_line_cylinder(x, solid)), gap_json(line_gap(x, solid)));
  if (m == "robust_double") {
    const LineInterval<double> r = robust_line_cylinder(convert<double>(x), convert<double>(solid));
    ojson out = answer_json(r.answer, false, m, "double");
    out["interval"] = interval_json(r);
    if (!all_binary64) out["input_rounded"] = true;
    return out;
  }
  // The seeds' generic methods, in the number type of --nt.
  ojson interval;
  std::string note;
  ojson out = run_in_number_type(options, all_binary64, false, [&]<class NT>() -> Answer {
    if constexpr (!has_sqrt_field<NT>) {
      throw InvalidInput("nt", "method " + m + " needs a square root and division; " + options.nt.name() +
                                   " has none (use double, long_double, interval, gmpfr<BITS> or core_expr)");
    } else {
      const auto xn = convert<NT>(x);
      const auto sn = convert<NT>(solid);
      LineInterval<NT> r;
      if (m == "shene" || m == "shene_as_written") {
        const auto variant = m == "shene" ? SheneVariant::corrected : SheneVariant::as_written;
        if constexpr (std::is_same_v<Solid, Cylinder<Rational>>) r = shene_line_cylinder(xn, sn, variant);
        if (r.answer == Answer::overlapping && !r.in)
          note = "the text's two points are not real: (r^2 - d^2) / (1 - (u.v)^2) < 0; no endpoints";
      } else {
        const auto variant = m == "gullotti_as_written" ? GullottiVariant::as_written : GullottiVariant::corrected;
        r = gullotti_any(xn, sn, variant);
      }
      interval = interval_json(r);
      return r.answer;
    }
  });
  if (out["answer"] != "undecided") out["interval"] = interval;
  if (!note.empty()) out["note"] = note;
  return out;
}

template <class LineLike, class Solid>
void register_kind(std::map<std::string, QueryKind>& kinds, const std::string& name, const char* line_field,
                   LineLike (JsonReader::*read_line)(const json&, const std::string&), const char* solid_field,
                   Solid (JsonReader::*read_solid)(const json&, const std::string&)) {
  std::vector<std::string> methods{"certified", "robust_double", "gullotti", "gullotti_as_written"};
  if constexpr (std::is_same_v<Solid, Cylinder<Rational>>) {
    methods.push_back("shene");
    methods.push_back("shene_as_written");
  }
  kinds[name] = {name, methods, [=](const json& in, const QueryOptions& o) {
                   JsonReader reader;
                   const LineLike x = (reader.*read_line)(JsonReader::member(in, "", line_field), line_field);
                   const Solid s = (reader.*read_solid)(JsonReader::member(in, "", solid_field), solid_field);
                   return answer_line_query(x, s, reader.all_binary64(), o);
                 },
                 {line_field, solid_field}};
}

}  // namespace

void register_line_queries(std::map<std::string, QueryKind>& kinds) {
  register_kind(kinds, "line_cylinder", "line", &JsonReader::line, "cylinder", &JsonReader::cylinder);
  register_kind(kinds, "ray_cylinder", "ray", &JsonReader::ray, "cylinder", &JsonReader::cylinder);
  register_kind(kinds, "segment_cylinder", "segment", &JsonReader::segment, "cylinder", &JsonReader::cylinder);
  register_kind(kinds, "line_elliptic_cylinder", "line", &JsonReader::line, "elliptic_cylinder", &JsonReader::elliptic_cylinder);
  register_kind(kinds, "ray_elliptic_cylinder", "ray", &JsonReader::ray, "elliptic_cylinder", &JsonReader::elliptic_cylinder);
  register_kind(kinds, "segment_elliptic_cylinder", "segment", &JsonReader::segment, "elliptic_cylinder",
                &JsonReader::elliptic_cylinder);
}

}  // namespace certcyl::cli
