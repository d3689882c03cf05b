// Validation at every query's entry point: each certified query (point, line, ray and segment
// against circular and elliptic cylinders, triangle, cylinder pair) with each kind of invalid operand, in
// Rational and in double, throws the InvalidInput the command gives for the same input; valid
// extreme operands pass.
#define BOOST_TEST_MODULE validation
#include <boost/test/unit_test.hpp>

#include <functional>
#include <limits>
#include <string>
#include <utility>

#include "certcyl/certified/cylinder_cylinder.hpp"
#include "certcyl/certified/line_cylinder.hpp"
#include "certcyl/certified/point_cylinder.hpp"
#include "certcyl/certified/triangle_cylinder.hpp"
#include "certcyl/io/json_input.hpp"

using namespace certcyl;
using json = nlohmann::json;

namespace {

// The message of the InvalidInput that f throws, "<none>" if it throws none.
std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "<none>";
}

Rational q(const char* s) { return parse_rational(s); }

template <class P>
auto exact(const P& p) {
  return p.map([](double x) { return Rational(x); });
}

// p in the number type of the cylinder `like` (double or Rational).
template <class NT>
NT number_of(const Cylinder<NT>&);
template <class NT>
NT number_of(const EllipticCylinder<NT>&);

template <class P, class Like>
auto as_in(const P& p, const Like&) {
  return p.map([](double x) { return decltype(number_of(std::declval<Like>()))(x); });
}

const double infinity = std::numeric_limits<double>::infinity();
const double not_a_number = std::numeric_limits<double>::quiet_NaN();

// Valid operands: the cylinder of radius 1 around the z axis from 0 to 2, the same as an
// elliptic cylinder, a line, a ray and a segment crossing it, a triangle, a point.
const Cylinder<double> good_cylinder{{0, 0, 0}, {0, 0, 2}, 1};
const EllipticCylinder<double> good_elliptic{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 2}};
const Line<double> good_line{{-2, 0, 1}, {1, 0, 0}};
const Ray<double> good_ray{{-2, 0, 1}, {1, 0, 0}};
const Segment<double> good_segment{{-2, 0, 1}, {2, 0, 1}};
const Triangle<double> good_triangle{{Point3<double>{-1, 0, 1}, Point3<double>{1, 0, 1}, Point3<double>{0, 1, 1}}};
const Point3<double> good_point{0, 0, 1};

// Invalid cylinders and the message each gets under the field "cylinder".
struct BadCylinder {
  Cylinder<double> c;
  const char* message;
};
const BadCylinder bad_cylinders[] = {
    {{{0, 0, 0}, {0, 0, 2}, -1}, "cylinder.radius: must be positive, got -1"},
    {{{0, 0, 0}, {0, 0, 2}, 0}, "cylinder.radius: must be positive, got 0"},
    {{{0, 0, 0}, {0, 0, 2}, -0.0}, "cylinder.radius: must be positive, got 0"},
    {{{0, 0, 0}, {0, 0, 2}, -0.375}, "cylinder.radius: must be positive, got -3/8"},
    {{{1, 2, 3}, {1, 2, 3}, 1}, "cylinder: zero-length axis (p0 == p1)"},
};

// Messages every query must give for its cylinder operand, in both number types.
template <class Query>
void check_cylinder_operand(Query&& query, const std::string& what) {
  for (const BadCylinder& b : bad_cylinders) {
    BOOST_TEST(message_of([&] { query(b.c); }) == b.message, what << " (double)");
    BOOST_TEST(message_of([&] { query(exact(b.c)); }) == b.message, what << " (Rational)");
  }
  BOOST_TEST(message_of([&] { query(Cylinder<double>{{0, 0, 0}, {0, 0, 2}, infinity}); }) == "cylinder.radius: non-finite number", what);
  BOOST_TEST(message_of([&] { query(Cylinder<double>{{0, 0, 0}, {0, not_a_number, 2}, 1}); }) == "cylinder.p1[1]: non-finite number", what);
  BOOST_TEST(message_of([&] { query(Cylinder<double>{{-infinity, 0, 0}, {0, 0, 2}, 1}); }) == "cylinder.p0[0]: non-finite number", what);
  // The valid cylinder passes in both types.
  BOOST_TEST(message_of([&] { query(good_cylinder); }) == "<none>", what);
  BOOST_TEST(message_of([&] { query(exact(good_cylinder)); }) == "<none>", what);
}

// The same for an elliptic cylinder.
template <class Query>
void check_elliptic_operand(Query&& query, const std::string& what) {
  // c = a + b: det[a b c] = 0 exactly.
  const EllipticCylinder<double> flat{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  BOOST_TEST(message_of([&] { query(flat); }) == "elliptic_cylinder: singular frame: det[a b c] = 0", what);
  BOOST_TEST(message_of([&] { query(exact(flat)); }) == "elliptic_cylinder: singular frame: det[a b c] = 0", what);
  // det = 2^-1074 (the least subnormal): the interval contains 0, the exact test decides valid.
  const EllipticCylinder<double> thin{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, std::numeric_limits<double>::denorm_min()}};
  BOOST_TEST(message_of([&] { query(thin); }) == "<none>", what);
  BOOST_TEST(message_of([&] { query(EllipticCylinder<double>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, not_a_number}}); }) ==
                 "elliptic_cylinder.c[2]: non-finite number",
             what);
  BOOST_TEST(message_of([&] { query(EllipticCylinder<double>{{0, infinity, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}); }) ==
                 "elliptic_cylinder.base[1]: non-finite number",
             what);
  BOOST_TEST(message_of([&] { query(good_elliptic); }) == "<none>", what);
  BOOST_TEST(message_of([&] { query(exact(good_elliptic)); }) == "<none>", what);
}

}  // namespace

BOOST_AUTO_TEST_CASE(line_queries_validate_the_cylinder) {
  check_cylinder_operand([](const auto& c) { certified_line_cylinder(as_in(good_line, c), c); }, "line");
  check_cylinder_operand([](const auto& c) { certified_line_cylinder(as_in(good_ray, c), c); }, "ray");
  check_cylinder_operand([](const auto& c) { certified_line_cylinder(as_in(good_segment, c), c); }, "segment");
  FilterCounter counter;
  check_cylinder_operand([&](const auto& c) { certified_line_cylinder_shape(as_in(good_line, c), c, counter); }, "line shape");
}

BOOST_AUTO_TEST_CASE(line_queries_validate_the_elliptic_cylinder) {
  check_elliptic_operand([](const auto& e) { certified_line_cylinder(as_in(good_line, e), e); }, "line");
  check_elliptic_operand([](const auto& e) { certified_line_cylinder(as_in(good_ray, e), e); }, "ray");
  check_elliptic_operand([](const auto& e) { certified_line_cylinder(as_in(good_segment, e), e); }, "segment");
  LineStageCounter stages;
  check_elliptic_operand([&](const auto& e) { certified_line_cylinder_shape(as_in(good_ray, e), e, stages); }, "ray shape");
}

BOOST_AUTO_TEST_CASE(line_queries_validate_the_line) {
  const Line<double> zero_line{{1, 2, 3}, {0, -0.0, 0}};
  const Ray<double> zero_ray{{1, 2, 3}, {0, 0, 0}};
  const Segment<double> zero_segment{{1, 2, 3}, {1, 2, 3}};
  const char* line_zero = "line.direction: zero-length direction";
  const char* ray_zero = "ray.direction: zero-length direction";
  BOOST_TEST(message_of([&] { certified_line_cylinder(zero_line, good_cylinder); }) == line_zero);
  BOOST_TEST(message_of([&] { certified_line_cylinder(zero_line, good_elliptic); }) == line_zero);
  BOOST_TEST(message_of([&] { certified_line_cylinder(exact(zero_line), exact(good_cylinder)); }) == line_zero);
  BOOST_TEST(message_of([&] { certified_line_cylinder(exact(zero_line), exact(good_elliptic)); }) == line_zero);
  BOOST_TEST(message_of([&] { certified_line_cylinder(zero_ray, good_cylinder); }) == ray_zero);
  BOOST_TEST(message_of([&] { certified_line_cylinder(zero_ray, good_elliptic); }) == ray_zero);
  BOOST_TEST(message_of([&] { certified_line_cylinder(exact(zero_ray), exact(good_cylinder)); }) == ray_zero);
  BOOST_TEST(message_of([&] { certified_line_cylinder(exact(zero_ray), exact(good_elliptic)); }) == ray_zero);
  const char* zero_length = "segment: zero-length segment (p0 == p1): its direction is zero";
  BOOST_TEST(message_of([&] { certified_line_cylinder(zero_segment, good_cylinder); }) == zero_length);
  BOOST_TEST(message_of([&] { certified_line_cylinder(zero_segment, good_elliptic); }) == zero_length);
  BOOST_TEST(message_of([&] { certified_line_cylinder(exact(zero_segment), exact(good_cylinder)); }) == zero_length);
  BOOST_TEST(message_of([&] { certified_line_cylinder(exact(zero_segment), exact(good_elliptic)); }) == zero_length);
  // The line is checked before the cylinder, as the command reads it first.
  BOOST_TEST(message_of([&] { certified_line_cylinder(zero_line, Cylinder<double>{{0, 0, 0}, {0, 0, 0}, -1}); }) ==
             "line.direction: zero-length direction");
  // Non-finite numbers, each named.
  BOOST_TEST(message_of([&] { certified_line_cylinder(Line<double>{{1, 2, infinity}, {1, 0, 0}}, good_cylinder); }) ==
             "line.origin[2]: non-finite number");
  BOOST_TEST(message_of([&] { certified_line_cylinder(Ray<double>{{1, 2, 3}, {not_a_number, 0, 0}}, good_elliptic); }) ==
             "ray.direction[0]: non-finite number");
  BOOST_TEST(message_of([&] { certified_line_cylinder(Segment<double>{{1, 2, 3}, {1, -infinity, 3}}, good_cylinder); }) ==
             "segment.p1[1]: non-finite number");
  FilterCounter counter;
  BOOST_TEST(message_of([&] { certified_line_cylinder_shape(zero_ray, good_cylinder, counter); }) == ray_zero);
}

BOOST_AUTO_TEST_CASE(triangle_queries_validate_their_operands) {
  check_cylinder_operand([](const auto& c) { certified_triangle_cylinder(as_in(good_triangle, c), c); }, "certified triangle");
  TriangleFilterStages stages;
  FilterCounter counter;
  check_cylinder_operand([&](const auto& c) { classify_triangle_cylinder(as_in(good_triangle, c), c, stages); }, "classify, stages");
  check_cylinder_operand([&](const auto& c) { classify_triangle_cylinder(as_in(good_triangle, c), c, counter); }, "classify, counter");
  const Triangle<double> far{{Point3<double>{0, 0, 1}, Point3<double>{1, 0, 1}, Point3<double>{0, 1, infinity}}};
  BOOST_TEST(message_of([&] { certified_triangle_cylinder(far, good_cylinder); }) == "triangle[2][2]: non-finite number");
  BOOST_TEST(message_of([&] { classify_triangle_cylinder(far, good_cylinder, counter); }) == "triangle[2][2]: non-finite number");
  // A degenerate triangle (a point) is valid.
  const Triangle<double> point{{good_point, good_point, good_point}};
  BOOST_TEST(message_of([&] { certified_triangle_cylinder(point, good_cylinder); }) == "<none>");
}

BOOST_AUTO_TEST_CASE(point_queries_validate_their_operands) {
  check_cylinder_operand([](const auto& c) { certified_point_cylinder(as_in(good_point, c), c); }, "point");
  check_elliptic_operand([](const auto& e) { certified_point_cylinder(as_in(good_point, e), e); }, "point, elliptic");
  BOOST_TEST(message_of([&] { certified_point_cylinder(Point3<double>{not_a_number, 0, 0}, good_cylinder); }) == "point[0]: non-finite number");
  BOOST_TEST(message_of([&] { certified_point_cylinder(Point3<double>{0, 0, -infinity}, good_elliptic); }) == "point[2]: non-finite number");
}

// The pair query names its operands a and b: the messages of the other queries under those
// fields, in both number types, and those of the command's reader.
BOOST_AUTO_TEST_CASE(pair_query_validates_its_operands) {
  const auto renamed = [](const std::string& message, const std::string& field) { return field + message.substr(std::string("cylinder").size()); };
  for (const BadCylinder& bad : bad_cylinders) {
    BOOST_TEST(message_of([&] { certified_cylinder_cylinder(bad.c, good_cylinder); }) == renamed(bad.message, "a"));
    BOOST_TEST(message_of([&] { certified_cylinder_cylinder(good_cylinder, bad.c); }) == renamed(bad.message, "b"));
    BOOST_TEST(message_of([&] { certified_cylinder_cylinder(exact(bad.c), exact(good_cylinder)); }) == renamed(bad.message, "a"));
    BOOST_TEST(message_of([&] { certified_cylinder_cylinder(exact(good_cylinder), exact(bad.c)); }) == renamed(bad.message, "b"));
  }
  BOOST_TEST(message_of([&] { certified_cylinder_cylinder(Cylinder<double>{{0, 0, 0}, {0, 0, 2}, infinity}, good_cylinder); }) ==
             "a.radius: non-finite number");
  BOOST_TEST(message_of([&] { certified_cylinder_cylinder(good_cylinder, Cylinder<double>{{0, 0, 0}, {0, not_a_number, 2}, 1}); }) ==
             "b.p1[1]: non-finite number");
  BOOST_TEST(message_of([&] { certified_cylinder_cylinder(good_cylinder, good_cylinder); }) == "<none>");
  BOOST_TEST(message_of([&] { certified_cylinder_cylinder(exact(good_cylinder), exact(good_cylinder)); }) == "<none>");
  JsonReader reader;
  BOOST_TEST(message_of([&] { reader.cylinder(json::parse(R"({"p0": [0,0,0], "p1": [0,0,2], "radius": -1})"), "b"); }) ==
             message_of([] { certified_cylinder_cylinder(good_cylinder, Cylinder<double>{{0, 0, 0}, {0, 0, 2}, -1}); }));
  BOOST_TEST(message_of([&] { reader.cylinder(json::parse(R"({"p0": [1,2,3], "p1": [1,2,3], "radius": 1})"), "a"); }) ==
             message_of([] { certified_cylinder_cylinder(Cylinder<double>{{1, 2, 3}, {1, 2, 3}, 1}, good_cylinder); }));
}

BOOST_AUTO_TEST_CASE(binary64_and_rational_overloads_agree) {
  // The triangle's binary64 overload answers as the Rational one, certificate included.
  const TriangleCylinderResult d = certified_triangle_cylinder(good_triangle, good_cylinder);
  const TriangleCylinderResult r = certified_triangle_cylinder(exact(good_triangle), exact(good_cylinder));
  BOOST_TEST(d.answer == Answer::overlapping);
  BOOST_TEST(r.answer == Answer::overlapping);
  BOOST_TEST(check_triangle_cylinder_certificate(d, exact(good_triangle), exact(good_cylinder)).empty());
  // The triangle z = 3, above the cap: separated; the triangle z = 2 through the axis: touching.
  const auto lifted = [](double z) {
    return Triangle<double>{{Point3<double>{-1, 0, z}, Point3<double>{1, 0, z}, Point3<double>{0, 1, z}}};
  };
  BOOST_TEST(certified_triangle_cylinder(lifted(3), good_cylinder).answer == Answer::separated);
  BOOST_TEST(certified_triangle_cylinder(lifted(2), good_cylinder).answer == Answer::touching);
  // 0.1 as a double is 3602879701896397/2^55, just above 1/10: a cylinder of that radius
  // contains the point (1/10, 0, 1) strictly, and the double overload means the double.
  const Cylinder<double> c{{0, 0, 0}, {0, 0, 2}, 0.1};
  BOOST_TEST(certified_point_cylinder(Point3<double>{0.1, 0, 1}, c).answer == Answer::touching);
  BOOST_TEST(certified_point_cylinder(Point3<Rational>{q("1/10"), 0, 1}, exact(c)).answer == Answer::overlapping);
  BOOST_TEST(certified_point_cylinder(Point3<Rational>{q("1/10"), 0, 1}, exact(c)).side == Side::inside);
}

BOOST_AUTO_TEST_CASE(messages_equal_the_json_readers) {
  // The command reads its operands with JsonReader, which validates the same way.
  JsonReader reader;
  BOOST_TEST(message_of([&] { reader.cylinder(json::parse(R"({"p0": [0,0,0], "p1": [0,0,2], "radius": -1})"), "cylinder"); }) ==
             message_of([] { certified_point_cylinder(good_point, Cylinder<double>{{0, 0, 0}, {0, 0, 2}, -1}); }));
  BOOST_TEST(message_of([&] { reader.cylinder(json::parse(R"({"p0": [1,2,3], "p1": [1,2,3], "radius": 1})"), "cylinder"); }) ==
             message_of([] { certified_point_cylinder(good_point, Cylinder<double>{{1, 2, 3}, {1, 2, 3}, 1}); }));
  BOOST_TEST(message_of([&] { reader.ray(json::parse(R"({"origin": [1,2,3], "direction": [0,0,0]})"), "ray"); }) ==
             message_of([] { certified_line_cylinder(Ray<double>{{1, 2, 3}, {0, 0, 0}}, good_cylinder); }));
  BOOST_TEST(message_of([&] { reader.segment(json::parse(R"({"p0": [1,2,3], "p1": [1,2,3]})"), "segment"); }) ==
             message_of([] { certified_line_cylinder(Segment<double>{{1, 2, 3}, {1, 2, 3}}, good_cylinder); }));
  BOOST_TEST(message_of([&] {
               reader.elliptic_cylinder(json::parse(R"({"base": [0,0,0], "a": [1,0,0], "b": [0,1,0], "c": [1,1,0]})"), "elliptic_cylinder");
             }) == message_of([] {
               certified_line_cylinder(good_line, EllipticCylinder<double>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}});
             }));
}
