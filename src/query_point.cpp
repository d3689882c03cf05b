// Point against cylinder queries: point_cylinder, point_elliptic_cylinder.
//
// The answer maps the point's position to the three values: outside -> separated,
// on the boundary -> touching, interior -> overlapping. The certified method also reports the
// certified signed gap, the point's depth min(1 - q, s, 1 - s) (study/gap.hpp).
#include "certcyl/io/json_input.hpp"
#include "certcyl/predicates/point_in_cylinder.hpp"
#include "query.hpp"
#include "query_support.hpp"

namespace certcyl::cli {
namespace {

Answer answer_of(Side s) {
  return s == Side::inside ? Answer::overlapping : (s == Side::boundary ? Answer::touching : Answer::separated);
}

// The certified signed gap: the depth of the point (study/gap.hpp).
Rational point_gap(const Point3<Rational>& x, const Cylinder<Rational>& c) { return study::detail::circular_point_gap(x, c); }
Rational point_gap(const Point3<Rational>& x, const EllipticCylinder<Rational>& e) {
  return study::detail::elliptic_point_gap(x, e);
}

template <class Solid>
ojson point_query(const json& input, const QueryOptions& options, const char* solid_field,
                 Solid (JsonReader::*read_solid)(const json&, const std::string&)) {
  JsonReader reader;
  const Point3<Rational> x = reader.vec3(JsonReader::member(input, "", "point"), "point");
  const Solid solid = (reader.*read_solid)(JsonReader::member(input, "", solid_field), solid_field);
  if (options.method == "certified") {
    FilterCounter counter;
    const Side s = filtered_call([&]<class NT>() { return classify_point(convert<NT>(x), convert<NT>(solid)); }, counter);
    ojson out = answer_json(answer_of(s), true, options.method, counter.exact ? "exact" : "interval");
    out["certificate"] = ojson{{"position", to_string(s)}, {"point", exact_json(x)}};
    return with_gap(out, gap_json(point_gap(x, solid)));
  }
  // "polynomial": the same predicate in the number type of --nt, certified only if that type is.
  return run_in_number_type(options, reader.all_binary64(), true, [&]<class NT>() {
    return answer_of(classify_point(convert<NT>(x), convert<NT>(solid)));
  });
}

}  // namespace

void register_point_queries(std::map<std::string, QueryKind>& kinds) {
  kinds["point_cylinder"] = {"point_cylinder", {"certified", "polynomial"}, [](const json& in, const QueryOptions& o) {
                               return point_query(in, o, "cylinder", &JsonReader::cylinder);
                             },
                             {"point", "cylinder"}};
  kinds["point_elliptic_cylinder"] = {
      "point_elliptic_cylinder", {"certified", "polynomial"}, [](const json& in, const QueryOptions& o) {
        return point_query(in, o, "elliptic_cylinder", &JsonReader::elliptic_cylinder);
      },
      {"point", "elliptic_cylinder"}};
}

}  // namespace certcyl::cli
