// Cylinder against cylinder. Methods: certified (exact three-valued answer with certificate and
// a certified enclosure of the signed gap log(phi*)).
#include "query_cylinder.hpp"

#include "certcyl/io/json_input.hpp"
#include "query_support.hpp"

namespace certcyl::cli {

ojson cylinder_cylinder_json(const CylinderCylinderResult& r) {
  ojson out = answer_json(r.answer, r.answer != Answer::undecided, "certified",
                          r.gmpfr_precision ? "gmpfr+gmpq" : (r.counters.exact_checks ? "gmpq" : "interval"));
  out["stage"] = std::string(to_string(r.stage));
  // log(phi*): negative when separated, 0 when touching, positive when overlapping; null when
  // the midpoints coincide (phi* is undefined: overlapping at every scale).
  out["gap"] = r.gap_known ? ojson::array({r.log_gap_lower, r.log_gap_upper}) : ojson(nullptr);
  ojson cert;
  if (r.direction) cert["direction"] = exact_json(*r.direction);
  if (r.witness) cert["witness"] = exact_json(*r.witness);
  if (r.contact) {
    cert["contact"] = ojson{{"type", r.contact->type()},
                            {"features", ojson::array({std::string(to_string(r.contact->feature0)),
                                                       std::string(to_string(r.contact->feature1))})},
                            {"normal", exact_json(r.contact->normal)},
                            {"point", exact_json(r.contact->point)}};
  }
  if (r.answer == Answer::undecided) cert["phi_bounds"] = ojson::array({r.phi_lower, r.phi_upper});
  if (r.gmpfr_precision) cert["gmpfr_precision"] = r.gmpfr_precision;
  out["certificate"] = cert;
  return out;
}

namespace {

ojson answer_cylinders(const json& in, const QueryOptions& o) {
  JsonReader reader;
  const Cylinder<Rational> a = reader.cylinder(JsonReader::member(in, "", "a"), "a");
  const Cylinder<Rational> b = reader.cylinder(JsonReader::member(in, "", "b"), "b");
  (void)o;
  return cylinder_cylinder_json(certified_cylinder_cylinder(a, b));
}

}  // namespace

void register_cylinder_queries(std::map<std::string, QueryKind>& kinds) {
  kinds["cylinder_cylinder"] = {"cylinder_cylinder", {"certified"}, answer_cylinders};
}

}  // namespace certcyl::cli
