// Cylinder against cylinder. Methods: certified (exact three-valued answer with certificate and
// a certified enclosure of the signed gap log(phi*)); eberly_as_written and eberly_corrected
// (the seed's separating-axis test, generic: --nt; its choices can be set per line through an
// optional "parameters" object).
#include "query_cylinder.hpp"

#include "certcyl/io/json_input.hpp"
#include "certcyl/seeds/eberly_cylinders.hpp"
#include "gmp_memory.hpp"
#include "query_support.hpp"

namespace certcyl::cli {

// The command reports the tighter gap enclosure of the ranked fast path, passes on the time
// limit of --time-limit, and stops when the line's GMP memory has an event (--memory-limit, a
// failed allocation; answer_line turns the line into an error).
CylinderCylinderOptions command_options(const QueryOptions& q) {
  CylinderCylinderOptions o;
  o.refine_gap = true;
  o.time_limit_seconds = q.time_limit_seconds;
  o.stop = gmp_memory_stop;
  return o;
}

ojson cylinder_cylinder_json(const CylinderCylinderResult& r) {
  ojson out = answer_json(r.answer, r.answer != Answer::undecided, "certified", std::string(to_string(r.certified_by)));
  out["stage"] = std::string(to_string(r.stage));
  if (r.time_limit_reached) out["reason"] = "time limit reached (--time-limit)";
  // log(phi*): negative when separated, 0 when touching, positive when overlapping; null when
  // the midpoints coincide (phi* is undefined: overlapping at every scale).
  const CylinderGap gap = r.gap();
  out["gap"] = gap.known ? ojson::array({gap.log_lower(), gap.log_upper()}) : ojson(nullptr);
  out["gap_quantity"] = std::string(study::to_string(study::GapQuantity::log_phi));
  ojson cert;
  if (const auto d = r.exact_direction()) cert["direction"] = exact_json(*d);
  if (const auto x = r.exact_witness()) cert["witness"] = exact_json(*x);
  if (r.contact) {
    cert["contact"] = ojson{{"type", r.contact->type()},
                            {"features", ojson::array({std::string(to_string(r.contact->feature0)),
                                                       std::string(to_string(r.contact->feature1))})},
                            {"normal", exact_json(r.contact->normal)},
                            {"point", exact_json(r.contact->point)}};
  }
  if (r.answer == Answer::undecided) cert["phi_bounds"] = ojson::array({gap.phi_lower, gap.phi_upper});
  if (r.gmpfr_precision) cert["gmpfr_precision"] = r.gmpfr_precision;
  if (r.ellipsoid_precision) cert["ellipsoid_precision"] = r.ellipsoid_precision;
  out["certificate"] = cert;
  return out;
}

namespace {

// Reads the optional "parameters" member: the Eberly choices a study sweeps.
EberlyParameters eberly_parameters(const json& in, EberlyVariant variant) {
  EberlyParameters p = EberlyParameters::of(variant);
  auto it = in.find("parameters");
  if (it == in.end()) return p;
  if (!it->is_object()) throw InvalidInput("parameters", "expected an object");
  for (auto m = it->begin(); m != it->end(); ++m) {
    const std::string field = "parameters." + m.key();
    auto integer = [&] {
      if (!m->is_number_integer() || m->get<long long>() < 0 || m->get<long long>() > 100000)
        throw InvalidInput(field, "expected an integer in [0, 100000]");
      return static_cast<int>(m->get<long long>());
    };
    auto strictness = [&] {
      if (*m == "strict") return Strictness::strict;
      if (*m == "non_strict") return Strictness::non_strict;
      throw InvalidInput(field, "expected \"strict\" or \"non_strict\"");
    };
    if (m.key() == "perpendicular_bisections") p.perpendicular_bisections = integer();
    else if (m.key() == "line_search_bisections") p.line_search_bisections = integer();
    else if (m.key() == "max_line_searches") p.max_line_searches = integer();
    else if (m.key() == "axis_tests") p.axis_tests = strictness();
    else if (m.key() == "perpendicular_tests") p.perpendicular_tests = strictness();
    else if (m.key() == "other_direction_tests") p.other_direction_tests = strictness();
    else if (m.key() == "parallel_tests") p.parallel_tests = strictness();
    else if (m.key() == "parallel_threshold") {
      if (!m->is_number() || !(m->get<double>() >= 0)) throw InvalidInput(field, "expected a number >= 0");
      p.parallel_threshold = m->get<double>();
      p.parallel_test = p.parallel_threshold > 0 ? ParallelTest::threshold : ParallelTest::exact_zero;
    } else {
      throw InvalidInput(field, "unknown parameter (expected: perpendicular_bisections, line_search_bisections, "
                                "max_line_searches, axis_tests, perpendicular_tests, other_direction_tests, "
                                "parallel_tests, parallel_threshold)");
    }
  }
  p.validate();
  return p;
}

ojson answer_cylinders(const json& in, const QueryOptions& o) {
  JsonReader reader;
  const Cylinder<Rational> a = reader.cylinder(JsonReader::member(in, "", "a"), "a");
  const Cylinder<Rational> b = reader.cylinder(JsonReader::member(in, "", "b"), "b");
  if (o.method == "certified") return cylinder_cylinder_json(certified_cylinder_cylinder(a, b, command_options(o)));
  const EberlyVariant variant = o.method == "eberly_as_written" ? EberlyVariant::as_written : EberlyVariant::corrected;
  const EberlyParameters params = eberly_parameters(in, variant);
  ojson details;
  std::string non_finite;
  ojson out = run_in_number_type(o, reader.all_binary64(), false, [&]<class NT>() -> Answer {
    if constexpr (!(NumberTraits<NT>::has_sqrt && NumberTraits<NT>::is_field)) {
      throw InvalidInput("nt", "method " + o.method + " needs a square root and division; " + o.nt.name() +
                                   " has none (use double, long_double, interval, gmpfr<BITS> or core_expr)");
    } else {
      const auto r = eberly_separated(convert<NT>(a), convert<NT>(b), params);
      details = ojson{{"test", std::string(to_string(r.test))},
                      {"direction", ojson::array({nt::to_double(r.direction.x), nt::to_double(r.direction.y),
                                                  nt::to_double(r.direction.z)})},
                      {"evaluations", ojson{{"F", r.counters.F},
                                            {"F_derivative", r.counters.F_derivative},
                                            {"G", r.counters.G},
                                            {"G_gradient", r.counters.G_gradient},
                                            {"line_searches", r.counters.line_searches}}}};
      // A value that left the finite numbers of NT (an overflow): no answer.
      if (!r.non_finite.empty()) {
        non_finite = r.non_finite;
        return Answer::undecided;
      }
      // As written, the seed returns a boolean: not separated means intersecting.
      if (variant == EberlyVariant::as_written && !r.separated) return Answer::overlapping;
      return r.answer;
    }
  });
  if (!non_finite.empty()) {
    out["answer"] = "invalid";
    out["reason"] = "non-finite value in " + non_finite;
    for (auto it = details.begin(); it != details.end(); ++it) out[it.key()] = it.value();
  } else if (out["answer"] != "undecided") {
    if (variant == EberlyVariant::as_written && out["answer"] == "overlapping") out["answer"] = "intersecting";
    out["separated"] = out["answer"] == "separated";
    for (auto it = details.begin(); it != details.end(); ++it) out[it.key()] = it.value();
  }
  return out;
}

}  // namespace

void register_cylinder_queries(std::map<std::string, QueryKind>& kinds) {
  kinds["cylinder_cylinder"] = {"cylinder_cylinder",
                                {"certified", "eberly_corrected", "eberly_as_written"},
                                answer_cylinders,
                                {"a", "b"},
                                {{"eberly_corrected", {"parameters"}}, {"eberly_as_written", {"parameters"}}}};
}

}  // namespace certcyl::cli
