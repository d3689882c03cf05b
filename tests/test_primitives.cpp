// Primitives, the seeds' cylinder convention, validation at the boundary and the JSON reader.
#define BOOST_TEST_MODULE primitives
#include <boost/mpl/list.hpp>
#include <boost/test/unit_test.hpp>

#include <cmath>

#include "certcyl/io/json_input.hpp"
#include "certcyl/number_traits_core.hpp"
#include "certcyl/predicates/point_in_cylinder.hpp"
#include "certcyl/primitives.hpp"

using namespace certcyl;
using json = nlohmann::json;

namespace {

// Runs f and returns the field named by the InvalidInput it throws ("<none>" if it does not).
template <class F>
std::string error_field(F&& f) {
  try {
    f();
  } catch (const InvalidInput& e) {
    return e.field();
  }
  return "<none>";
}

Rational q(const char* s) { return parse_rational(s); }

}  // namespace

BOOST_AUTO_TEST_CASE(center_axis_form_converts_exactly_as_written) {
  // C = (1, 2, 3), W = (0, 0, 1), h = 4: p0 = C - 2W, p1 = C + 2W.
  auto c = Cylinder<Rational>::from_center_axis({1, 2, 3}, {0, 0, 1}, q("1/2"), 4);
  BOOST_TEST((c.p0 == Vec3<Rational>{1, 2, 1}));
  BOOST_TEST((c.p1 == Vec3<Rational>{1, 2, 5}));
  BOOST_TEST(c.radius == q("1/2"));
  // W is not renormalised: |W| = 1 + 1e-7 stretches the height to h |W|.
  const Rational w = q("1.0000001");
  c = Cylinder<Rational>::from_center_axis({0, 0, 0}, {0, w, 0}, 1, q("0.3"));
  BOOST_TEST((c.p0 == Vec3<Rational>{0, -q("0.150000015"), 0}));
  BOOST_TEST((c.p1 == Vec3<Rational>{0, q("0.150000015"), 0}));
  // An oblique unit-ish axis (3/5, 4/5, 0), h = 10: endpoints C -/+ (3, 4, 0).
  c = Cylinder<Rational>::from_center_axis({1, 1, 1}, {q("0.6"), q("0.8"), 0}, 2, 10);
  BOOST_TEST((c.p0 == Vec3<Rational>{-2, -3, 1}));
  BOOST_TEST((c.p1 == Vec3<Rational>{4, 5, 1}));
}

BOOST_AUTO_TEST_CASE(json_center_form_matches_the_convention) {
  JsonReader r;
  const auto c = r.cylinder(json::parse(R"({"center": [1, 2, 3], "axis": [0, 0, "1/3"], "radius": 1, "height": 6})"), "a");
  // p0 = C - 3 * (0, 0, 1/3) = (1, 2, 2), p1 = (1, 2, 4).
  BOOST_TEST((c.p0 == Vec3<Rational>{1, 2, 2}));
  BOOST_TEST((c.p1 == Vec3<Rational>{1, 2, 4}));
  BOOST_TEST(!r.all_binary64());  // "1/3" is not a binary64
}

BOOST_AUTO_TEST_CASE(conversion_rounds_each_coordinate) {
  const Segment<Rational> s{{q("0.1"), 0, 0}, {1, q("1/3"), 2}};
  const auto d = convert<double>(s);
  BOOST_TEST(d.p0.x == 0.1);
  BOOST_TEST(d.p1.y == 0x1.5555555555555p-2);
  BOOST_TEST(d.p1.z == 2.0);
  NumberScope<Interval> scope;
  const auto i = convert<Interval>(s);
  BOOST_TEST(Rational(i.p0.x.inf()) < q("0.1"));
  BOOST_TEST(q("0.1") < Rational(i.p0.x.sup()));
  BOOST_TEST(i.p1.z.is_point());
}

BOOST_AUTO_TEST_CASE(each_invalid_input_gets_its_own_error) {
  JsonReader r;
  auto cyl = [&](const char* text) { return error_field([&] { r.cylinder(json::parse(text), "a"); }); };
  BOOST_TEST(cyl(R"({"p0": [0,0,0], "p1": [0,0,1], "radius": 0})") == "a.radius");
  BOOST_TEST(cyl(R"({"p0": [0,0,0], "p1": [0,0,1], "radius": "-1/2"})") == "a.radius");
  BOOST_TEST(cyl(R"({"p0": [1,2,3], "p1": [1,2,3], "radius": 1})") == "a");  // zero-length axis
  BOOST_TEST(cyl(R"({"p0": [0,0,0], "radius": 1})") == "a.p1");              // missing
  BOOST_TEST(cyl(R"({"p0": [0,0], "p1": [0,0,1], "radius": 1})") == "a.p0");  // arity
  BOOST_TEST(cyl(R"({"p0": [0,0,0,0], "p1": [0,0,1], "radius": 1})") == "a.p0");
  BOOST_TEST(cyl(R"({"p0": [0,"x",0], "p1": [0,0,1], "radius": 1})") == "a.p0[1]");
  BOOST_TEST(cyl(R"({"p0": [0,true,0], "p1": [0,0,1], "radius": 1})") == "a.p0[1]");
  BOOST_TEST(cyl(R"({"p0": [0,null,0], "p1": [0,0,1], "radius": 1})") == "a.p0[1]");
  BOOST_TEST(cyl(R"({"p0": [0,[1],0], "p1": [0,0,1], "radius": 1})") == "a.p0[1]");
  BOOST_TEST(cyl(R"({"p0": "0,0,0", "p1": [0,0,1], "radius": 1})") == "a.p0");
  BOOST_TEST(cyl(R"({"p0": [0,0,0], "p1": [0,0,1], "radius": 1, "raduis": 2})") == "a.raduis");
  // Non-finite: nlohmann's parser already refuses the text 1e400; a value built in memory is
  // refused by the reader.
  BOOST_CHECK_THROW(const json j = json::parse(R"({"radius": 1e400})"), json::exception);
  json inf_radius = json::parse(R"({"p0": [0,0,0], "p1": [0,0,1], "radius": 1})");
  inf_radius["radius"] = HUGE_VAL;
  BOOST_TEST(error_field([&] { r.cylinder(inf_radius, "a"); }) == "a.radius");
  inf_radius["radius"] = std::nan("");
  BOOST_TEST(error_field([&] { r.cylinder(inf_radius, "a"); }) == "a.radius");
  BOOST_TEST(cyl(R"({"p0": [0,0,0], "p1": [0,0,1], "radius": "inf"})") == "a.radius");
  BOOST_TEST(cyl(R"({"center": [0,0,0], "axis": [0,0,0], "radius": 1, "height": 1})") == "a.axis");
  BOOST_TEST(cyl(R"({"center": [0,0,0], "axis": [0,0,1], "radius": 1, "height": 0})") == "a.height");
  BOOST_TEST(cyl(R"({"center": [0,0,0], "axis": [0,0,1], "radius": 1})") == "a.height");
  BOOST_TEST(cyl(R"({"center": [0,0,0], "p1": [0,0,1], "radius": 1})") == "a.center");  // mixed forms
  BOOST_TEST(cyl(R"([0, 0, 1])") == "a");
  BOOST_TEST(cyl(R"({})") == "a");

  BOOST_TEST(error_field([&] {
               r.elliptic_cylinder(json::parse(R"({"base": [0,0,0], "a": [1,0,0], "b": [2,0,0], "c": [0,0,1]})"), "e");
             }) == "e");  // det[a b c] = 0
  BOOST_TEST(error_field([&] { r.elliptic_cylinder(json::parse(R"({"base": [0,0,0], "a": [1,0,0], "b": [0,1,0]})"), "e"); }) ==
             "e.c");
  BOOST_TEST(error_field([&] { r.line(json::parse(R"({"origin": [0,0,0], "direction": [0,0,0]})"), "line"); }) ==
             "line.direction");
  BOOST_TEST(error_field([&] { r.ray(json::parse(R"({"origin": [0,0,0], "direction": ["0", "0/5", "-0"]})"), "ray"); }) ==
             "ray.direction");
  BOOST_TEST(error_field([&] { r.segment(json::parse(R"({"p0": [1,1,1], "p1": [1,1,1]})"), "segment"); }) == "segment");
  BOOST_TEST(error_field([&] { r.triangle(json::parse(R"([[0,0,0],[1,0,0]])"), "triangle"); }) == "triangle");
  BOOST_TEST(error_field([&] { r.triangle(json::parse(R"([[0,0,0],[1,0,0],[1,"1/0",0]])"), "triangle"); }) ==
             "triangle[2][1]");
}

BOOST_AUTO_TEST_CASE(valid_inputs_are_accepted) {
  JsonReader r;
  // Degenerate triangles are valid: a segment and a point.
  BOOST_TEST(error_field([&] { r.triangle(json::parse(R"([[0,0,0],[1,1,1],[2,2,2]])"), "t"); }) == "<none>");
  BOOST_TEST(error_field([&] { r.triangle(json::parse(R"([[1,1,1],[1,1,1],[1,1,1]])"), "t"); }) == "<none>");
  const auto e = r.elliptic_cylinder(json::parse(R"({"base": [0,0,0], "a": [2,0,0], "b": [0,1,0], "c": [1,0,1]})"), "e");
  BOOST_TEST(determinant(e.a, e.b, e.c) == Rational(2));
  const auto line = r.line(json::parse(R"({"origin": [0, "0.1", 0], "direction": ["0x1p-3", 0, 0]})"), "line");
  BOOST_TEST(line.direction.x == Rational(1, 8));
  BOOST_TEST(line.origin.y == Rational(1, 10));
  BOOST_TEST(!r.all_binary64());
  JsonReader r2;
  r2.segment(json::parse(R"({"p0": [0, 0.1, 9007199254740993], "p1": [1, 2, 3]})"), "s");
  BOOST_TEST(r2.all_binary64());  // JSON numbers are binary64 values by definition
  const auto big = JsonReader::read_number(json::parse("9007199254740993"), "x");
  BOOST_TEST(big.value == Rational(9007199254740992.0));  // its binary64 value, 2^53
}

using ClassifyTypes = boost::mpl::list<double, Interval, CGAL::Gmpq, CGAL::Gmpfr, LazyRational, CORE::Expr>;

BOOST_AUTO_TEST_CASE_TEMPLATE(point_classification_is_exact_in_exact_types, NT, ClassifyTypes) {
  NumberScope<NT> scope;
  // Radius 5 around the z axis from z = 0 to z = 2 (hand-checked positions).
  const Cylinder<Rational> c{{0, 0, 0}, {0, 0, 2}, 5};
  struct Case {
    Point3<Rational> x;
    Side expected;
  };
  const std::vector<Case> cases{
      {{3, 4, 1}, Side::boundary},                  // on the wall (3-4-5)
      {{3, 4, 2}, Side::boundary},                  // on the top rim
      {{0, 0, 0}, Side::boundary},                  // centre of the bottom cap
      {{1, 1, 1}, Side::inside},                    //
      {{3, 4, q("2.5")}, Side::outside},            // above the top
      {{q("3.0000001"), 4, 1}, Side::outside},      // just outside the wall
      {{q("2.9999999"), 4, 1}, Side::inside},       // just inside
  };
  for (const auto& k : cases) {
    try {
      const Side s = classify_point(convert<NT>(k.x), convert<NT>(c));
      // Certified types must be right; double and Gmpfr are held to it only where the input
      // is exactly representable (they are not certified, the experiments measure them).
      if (NumberTraits<NT>::is_certified || (is_binary64(k.x.x) && is_binary64(k.x.y) && is_binary64(k.x.z)))
        BOOST_TEST(s == k.expected);
    } catch (const CGAL::Uncertain_conversion_exception&) {
      // Intervals may refuse (boundary cases), never answer wrongly.
      BOOST_TEST((std::is_same_v<NT, Interval>));
    }
  }
  // Oblique elliptic cylinder: base 0, a = (2,0,0), b = (0,1,0), c = (1,0,1).
  const EllipticCylinder<Rational> e{{0, 0, 0}, {2, 0, 0}, {0, 1, 0}, {1, 0, 1}};
  // World point = base + x a + y b + z c: (x, y, z) = (1, 0, 1) -> (3, 0, 1) on the top rim;
  // (1, 0, 1/2) -> (5/2, 0, 1/2) and (-1, 0, 1/2) -> (-3/2, 0, 1/2) on the wall;
  // (-3/4, 0, 1/2) -> (-1, 0, 1/2) inside (9/16 < 1); (0, 0, -1/1000) below the base cap.
  const std::vector<Case> ecases{{{3, 0, 1}, Side::boundary},
                                 {{q("5/2"), 0, q("1/2")}, Side::boundary},
                                 {{q("-3/2"), 0, q("1/2")}, Side::boundary},
                                 {{-1, 0, q("1/2")}, Side::inside},
                                 {{1, q("1/2"), q("1/2")}, Side::inside},
                                 {{0, 0, q("-0.001")}, Side::outside}};
  for (const auto& k : ecases) {
    try {
      const Side s = classify_point(convert<NT>(k.x), convert<NT>(e));
      if (NumberTraits<NT>::is_certified || (is_binary64(k.x.x) && is_binary64(k.x.y) && is_binary64(k.x.z)))
        BOOST_TEST(s == k.expected);
    } catch (const CGAL::Uncertain_conversion_exception&) {
      BOOST_TEST((std::is_same_v<NT, Interval>));
    }
  }
}
