#include "demo.hpp"

#include <functional>
#include <iomanip>
#include <string>
#include <vector>

#include "certcyl/certcyl.hpp"
#include "certcyl/certified/cylinder_cylinder.hpp"
#include "certcyl/certified/line_cylinder.hpp"
#include "certcyl/certified/triangle_cylinder.hpp"
#include "certcyl/seeds/eberly_cylinders.hpp"
#include "certcyl/seeds/eberly_triangle_cylinder.hpp"
#include "certcyl/seeds/gullotti_line_elliptic_cylinder.hpp"
#include "certcyl/seeds/shene_line_cylinder.hpp"

namespace certcyl::cli {
namespace {

// The number types of the demo's columns.
std::vector<NumberTypeSpec> demo_types() {
  return {{NumberKind::double_, 53},     {NumberKind::long_double, 64}, {NumberKind::interval, 53},
          {NumberKind::gmpfr, 24},       {NumberKind::gmpfr, 256},      {NumberKind::gmpq, 53},
          {NumberKind::mpzf, 53},        {NumberKind::lazy_gmpq, 53},   {NumberKind::core_expr, 53}};
}

// One demo row: a query on exact input, answered by `answer` in a given number type.
struct DemoCase {
  std::string query;
  std::string input;
  std::function<std::string(const NumberTypeSpec&)> answer;  // the method in each number type
  std::function<std::string()> certified;                     // the certified answer
};

// Runs a generic query body in the number type `spec`, turning the honest refusals into
// text: an interval that cannot decide, an input the type cannot hold.
template <class Body>
std::string answer_in(const NumberTypeSpec& spec, Body body) {
  try {
    return dispatch(spec, body);
  } catch (const CGAL::Uncertain_conversion_exception&) {
    return "undecided";
  } catch (const InvalidInput&) {
    return "n/a";  // e.g. Mpzf cannot hold a non-dyadic input
  }
}

// The seeds need a square root and division; the exact rational types have neither.
template <class NT>
constexpr bool seed_capable = NumberTraits<NT>::has_sqrt && NumberTraits<NT>::is_field;

template <class Run>
std::string seed_in(const NumberTypeSpec& spec, Run run) {
  return answer_in(spec, [&]<class NT>() -> std::string {
    if constexpr (seed_capable<NT>)
      return run.template operator()<NT>();
    else
      return "n/a";
  });
}

DemoCase shene_case(std::string input, Line<Rational> line, Cylinder<Rational> cyl) {
  return {"line_cylinder (shene)", std::move(input),
          [=](const NumberTypeSpec& spec) {
            return seed_in(spec, [&]<class NT>() { return std::string(to_string(shene_line_cylinder(convert<NT>(line), convert<NT>(cyl)).answer)); });
          },
          [=] { return std::string(to_string(certified_line_cylinder(line, cyl).answer)); }};
}

DemoCase gullotti_case(std::string input, Line<Rational> line, EllipticCylinder<Rational> e) {
  return {"line_elliptic (gullotti)", std::move(input),
          [=](const NumberTypeSpec& spec) {
            return seed_in(spec, [&]<class NT>() {
              return std::string(to_string(gullotti_line_elliptic_cylinder(convert<NT>(line), convert<NT>(e)).answer));
            });
          },
          [=] { return std::string(to_string(certified_line_cylinder(line, e).answer)); }};
}

DemoCase eberly_triangle_case(std::string input, Triangle<Rational> t, Cylinder<Rational> cyl) {
  return {"triangle_cylinder (eberly)", std::move(input),
          [=](const NumberTypeSpec& spec) {
            return seed_in(spec, [&]<class NT>() {
              return std::string(eberly_triangle_cylinder(convert<NT>(t), convert<NT>(cyl)).intersect ? "intersect" : "separated");
            });
          },
          [=] { return std::string(to_string(certified_triangle_cylinder(t, cyl).answer)); }};
}

DemoCase point_case(std::string input, Cylinder<Rational> cyl, Point3<Rational> x) {
  return {"point_in_cylinder", std::move(input), [cyl, x](const NumberTypeSpec& spec) {
            return answer_in(spec, [&]<class NT>() -> std::string {
              return to_string(classify_point(convert<NT>(x), convert<NT>(cyl)));
            });
          },
          [cyl, x] { return std::string(to_string(classify_point(x, cyl))); }};
}

DemoCase point_elliptic_case(std::string input, EllipticCylinder<Rational> e, Point3<Rational> x) {
  return {"point_in_elliptic_cylinder", std::move(input), [e, x](const NumberTypeSpec& spec) {
            return answer_in(spec, [&]<class NT>() -> std::string {
              return to_string(classify_point(convert<NT>(x), convert<NT>(e)));
            });
          },
          [e, x] { return std::string(to_string(classify_point(x, e))); }};
}

DemoCase eberly_cylinders_case(std::string input, Cylinder<Rational> a, Cylinder<Rational> b) {
  return {"cylinder_cylinder (eberly corr.)", std::move(input),
          [=](const NumberTypeSpec& spec) {
            return seed_in(spec, [&]<class NT>() {
              return std::string(to_string(eberly_separated(convert<NT>(a), convert<NT>(b), EberlyParameters::corrected()).answer));
            });
          },
          [=] { return std::string(to_string(certified_cylinder_cylinder(a, b).answer)); }};
}

Triangle<Rational> tri(const Point3<Rational>& a, const Point3<Rational>& b, const Point3<Rational>& c) {
  return Triangle<Rational>{{a, b, c}};
}

std::vector<DemoCase> demo_cases() {
  const Rational third = parse_rational("1/3"), tenth = parse_rational("0.1");
  // Unit-radius cylinder around the z axis, z in [0, 1].
  const Cylinder<Rational> unit{{0, 0, 0}, {0, 0, 1}, 1};
  // The same cylinder with radius 1/10 and its seeds' center/axis form.
  const Cylinder<Rational> thin = Cylinder<Rational>::from_center_axis({0, 0, 0}, {0, 0, 1}, tenth, 2);
  // An oblique elliptic cylinder: semi-axes 2 and 1, sheared height vector.
  const EllipticCylinder<Rational> oblique{{0, 0, 0}, {2, 0, 0}, {0, 1, 0}, {1, 0, 1}};
  return {
      point_case("(0.6, 0.8, 0.5) on the wall of r=1", unit, {parse_rational("0.6"), parse_rational("0.8"), parse_rational("1/2")}),
      point_case("(1/3, 1/3, 1/3) inside r=1", unit, {third, third, third}),
      point_case("(0.1, 0, 0) on the wall of r=0.1", thin, {tenth, 0, 0}),
      point_case("(0, 0, 1+2^-30) just above a cap, r=1", unit, {0, 0, Rational(1) + parse_rational("0x1p-30")}),
      point_elliptic_case("(3, 0, 1) on the top rim, oblique", oblique, {3, 0, 1}),
      point_elliptic_case("(1, 1/2, 1/2) inside, oblique", oblique, {1, parse_rational("1/2"), parse_rational("1/2")}),
      // Lines against the unit cylinder: tangent at (0, 1, 1/2); 2^-30 inside and outside of it;
      // a line through the wall with a direction that is not a binary64 value.
      shene_case("tangent y=1", {{-5, 1, parse_rational("1/2")}, {1, 0, 0}}, unit),
      shene_case("y=1-2^-30 (crosses)", {{-5, Rational(1) - parse_rational("0x1p-30"), parse_rational("1/2")}, {1, 0, 0}}, unit),
      shene_case("y=1+2^-30 (misses)", {{-5, Rational(1) + parse_rational("0x1p-30"), parse_rational("1/2")}, {1, 0, 0}}, unit),
      shene_case("y=1+2^-60 (misses; rounds to y=1)", {{-5, Rational(1) + parse_rational("0x1p-60"), parse_rational("1/2")}, {1, 0, 0}}, unit),
      shene_case("y=0.1x+1/10 (crosses)", {{0, tenth, parse_rational("1/2")}, {1, tenth, 0}}, unit),
      gullotti_case("axis-parallel on the wall x'=1", {{1, 0, -1}, {1, 0, 1}}, oblique),
      gullotti_case("axis-parallel outside x'=1+2^-40", {{Rational(1) + parse_rational("0x1p-39"), 0, -1}, {1, 0, 1}}, oblique),
      gullotti_case("through the oblique solid", {{-5, 0, parse_rational("1/2")}, {1, 0, 0}}, oblique),
      // Triangles against the unit cylinder.
      eberly_triangle_case("in the cap plane z=1, over the disk", tri({0, 0, 1}, {5, 0, 1}, {0, 5, 1}), unit),
      eberly_triangle_case("vertex on the wall (1,0,1/2)", tri({1, 0, parse_rational("1/2")}, {5, 0, 0}, {5, 1, 1}), unit),
      eberly_triangle_case("2^-30 off the wall", tri({Rational(1) + parse_rational("0x1p-30"), 0, parse_rational("1/2")}, {5, 0, 0}, {5, 1, 1}), unit),
      // Cylinder pairs: parallel unit cylinders 2 apart touch along a wall line; 2^-40 more
      // and they are separated; a crossing pair whose skew axes pass 2 - 2^-30 apart overlaps.
      eberly_cylinders_case("parallel walls touching", {{0, 0, 0}, {0, 0, 2}, 1}, {{2, 0, 0}, {2, 0, 2}, 1}),
      eberly_cylinders_case("parallel, 2^-40 apart", {{0, 0, 0}, {0, 0, 2}, 1}, {{Rational(2) + parse_rational("0x1p-40"), 0, 0}, {Rational(2) + parse_rational("0x1p-40"), 0, 2}, 1}),
      eberly_cylinders_case("crossing, axes 2-2^-30 apart", {{0, 0, -2}, {0, 0, 2}, 1}, {{-2, Rational(2) - parse_rational("0x1p-30"), 0}, {2, Rational(2) - parse_rational("0x1p-30"), 0}, 1}),
      eberly_triangle_case("face crossing the axis", tri({-1, -1, parse_rational("1/3")}, {2, -1, parse_rational("1/3")}, {0, 2, parse_rational("2/3")}), unit),
  };
}

}  // namespace

int run_demo(std::ostream& out) {
  const auto types = demo_types();
  const auto cases = demo_cases();
  out << "certcyl demo: each query on exact input, answered in every number type.\n"
         "undecided = an interval could not decide; n/a = the type cannot hold the input.\n\n";
  const int query_w = 28, input_w = 40, col_w = 13;
  out << std::left << std::setw(query_w) << "query" << std::setw(input_w) << "input";
  for (const auto& t : types) out << std::setw(col_w) << t.name();
  out << "certified\n";
  int status = 0;
  for (const auto& c : cases) {
    out << std::setw(query_w) << c.query << std::setw(input_w) << c.input;
    const std::string truth = c.certified();
    std::string exact_answer;
    for (const auto& t : types) {
      const std::string a = c.answer(t);
      out << std::setw(col_w) << a;
      const bool exact = t.kind == NumberKind::gmpq || t.kind == NumberKind::mpzf || t.kind == NumberKind::lazy_gmpq ||
                         t.kind == NumberKind::core_expr;
      if (exact && a != "n/a") {
        if (!exact_answer.empty() && a != exact_answer) status = 1;
        exact_answer = a;
      }
    }
    out << truth << "\n";
  }
  if (status != 0) out << "\nerror: exact number types disagree\n";
  return status;
}

}  // namespace certcyl::cli
