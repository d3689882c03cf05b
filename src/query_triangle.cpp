// Triangle against cylinder. Methods: certified (exact three-valued predicate with certificate;
// the query, not `certcyl scene`, adds the certified signed gap, the depth margin of
// study/gap.hpp), eberly (the seed's clip method, generic: --nt).
#include "certcyl/certified/triangle_cylinder.hpp"
#include "certcyl/io/json_input.hpp"
#include "certcyl/seeds/eberly_triangle_cylinder.hpp"
#include "query.hpp"
#include "query_support.hpp"
#include "query_triangle.hpp"

namespace certcyl::cli {

ojson triangle_cylinder_json(const TriangleCylinderResult& r) {
  const std::string stage = r.stages.exact ? "exact" : r.stages.interval ? "interval" : r.stages.double_double ? "double_double" : "static";
  ojson out = answer_json(r.answer, true, "certified", stage);
  ojson cert;
  if (r.witness) cert["witness"] = exact_json(*r.witness);
  if (r.answer == Answer::touching) {
    ojson tri{{"feature", to_string(r.triangle_feature)}};
    ojson indices = ojson::array();
    for (int i : r.triangle_indices)
      if (i >= 0) indices.push_back(i);
    tri["indices"] = indices;
    cert["triangle_feature"] = tri;
    cert["cylinder_feature"] = to_string(r.cylinder_feature);
  }
  if (r.answer == Answer::separated) cert["separation"] = to_string(r.separation);
  if (r.closest) {
    cert["closest_point"] = exact_json(*r.closest);
    cert["squared_distance_to_axis"] = exact_json(r.squared_distance);
    if (!(r.normal == Vec3<Rational>{0, 0, 0})) cert["normal"] = exact_json(r.normal);
  }
  cert["decided_by"] = stage;
  out["certificate"] = cert;
  return out;
}

namespace {

ojson answer_triangle(const json& in, const QueryOptions& o) {
  JsonReader reader;
  const Triangle<Rational> t = reader.triangle(JsonReader::member(in, "", "triangle"), "triangle");
  const Cylinder<Rational> c = reader.cylinder(JsonReader::member(in, "", "cylinder"), "cylinder");
  if (o.method == "certified") {
    const TriangleCylinderResult r = certified_triangle_cylinder(t, c);
    return with_gap(triangle_cylinder_json(r), gap_json(study::detail::triangle_margin(t, c)));
  }
  std::string label;
  ojson out = run_in_number_type(o, reader.all_binary64(), false, [&]<class NT>() -> Answer {
    if constexpr (!(NumberTraits<NT>::has_sqrt && NumberTraits<NT>::is_field)) {
      throw InvalidInput("nt", "method eberly needs a square root and division; " + o.nt.name() +
                                   " has none (use double, long_double, interval, gmpfr<BITS> or core_expr)");
    } else {
      const auto r = eberly_triangle_cylinder(convert<NT>(t), convert<NT>(c));
      label = to_string(r.label);
      // The seed's boolean: intersect (touching or overlapping, it cannot tell) or not.
      return r.intersect ? Answer::overlapping : Answer::separated;
    }
  });
  if (out["answer"] != "undecided") {
    out["intersect"] = out["answer"] == "overlapping";
    out["answer"] = out["intersect"] == true ? "intersecting" : "separated";
    out["seed_case"] = label;
  }
  return out;
}

}  // namespace

void register_triangle_queries(std::map<std::string, QueryKind>& kinds) {
  kinds["triangle_cylinder"] = {"triangle_cylinder", {"certified", "eberly"}, answer_triangle, {"triangle", "cylinder"}};
}

}  // namespace certcyl::cli
