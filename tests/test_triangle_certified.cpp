// Tests of the certified triangle-cylinder predicate (certified/triangle_cylinder.hpp).
//
// Hand cases: the cylinder Z is the z axis from z = 0 to z = 2, radius 1 (A = (0,0,2),
// A.A = 4, R = 4). Every expected answer and feature is derived by hand from the picture in
// the comment; each degenerate case is also moved by one binary64 ulp (or by 2^-52) to each
// side along the contact normal, where the answer is derived the same way.
// Property tests: agreement with an independent exact minimisation (test_triangle_oracle.hpp)
// on thousands of random inputs, three generators, seeds printed; invariance under vertex
// order, axis flip, integer translation and power-of-two scaling.
#define BOOST_TEST_MODULE test_triangle_certified
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>

#include "certcyl/certified/triangle_cylinder.hpp"
#include "test_triangle_oracle.hpp"

using namespace certcyl;
using Res = TriangleCylinderResult;
using TF = Res::TriangleFeature;
using CF = Res::CylinderFeature;
using Sep = Res::Separation;

namespace {

Rational Q(const char* s) { return parse_rational(s); }
Point3<Rational> pt(Rational x, Rational y, Rational z) { return {x, y, z}; }
Triangle<Rational> tri(Point3<Rational> a, Point3<Rational> b, Point3<Rational> c) { return {{a, b, c}}; }

const Cylinder<Rational> Z{{0, 0, 0}, {0, 0, 2}, Rational(1)};

// The binary64 neighbours of x, exactly.
Rational below(double x) { return Rational(std::nextafter(x, -INFINITY)); }
Rational above(double x) { return Rational(std::nextafter(x, INFINITY)); }
const Rational delta = Rational(1) / Rational(4503599627370496);  // 2^-52

Triangle<Rational> translated(const Triangle<Rational>& t, const Vec3<Rational>& d) {
  return tri(t.v[0] + d, t.v[1] + d, t.v[2] + d);
}

void expect_touching(const Triangle<Rational>& t, const Cylinder<Rational>& c, TF tf, std::array<int, 2> idx, CF cf,
                     std::optional<Point3<Rational>> witness = std::nullopt) {
  const Res r = certified_triangle_cylinder(t, c);
  BOOST_TEST_REQUIRE(to_string(r.answer) == "touching");
  BOOST_TEST(to_string(r.triangle_feature) == to_string(tf));
  BOOST_TEST((r.triangle_indices == idx));
  BOOST_TEST(to_string(r.cylinder_feature) == to_string(cf));
  if (witness) BOOST_TEST((*r.witness == *witness));
}

void expect_answer(const Triangle<Rational>& t, const Cylinder<Rational>& c, Answer a, Sep sep = Sep::none) {
  const Res r = certified_triangle_cylinder(t, c);
  BOOST_TEST(to_string(r.answer) == to_string(a));
  BOOST_TEST(oracle::triangle_cylinder(t, c) == a);
  if (a == Answer::separated) BOOST_TEST(to_string(r.separation) == to_string(sep));
}

}  // namespace

// ---- A vertex, an edge, the face on the wall -------------------------------------------------

//   top view (z = 1)        v0 = (1,0,1) on the wall, v1 = (3,0,1), v2 = (3,1,1)
//     ( o )v0------v1       the rest of the triangle has x >= 1, so only v0 touches.
//           `-.    |
//               `-.v2
BOOST_AUTO_TEST_CASE(vertex_on_wall) {
  expect_touching(tri(pt(1, 0, 1), pt(3, 0, 1), pt(3, 1, 1)), Z, TF::vertex, {0, -1}, CF::wall, pt(1, 0, 1));
  expect_answer(tri(pt(below(1), 0, 1), pt(3, 0, 1), pt(3, 1, 1)), Z, Answer::overlapping);
  expect_answer(tri(pt(above(1), 0, 1), pt(3, 0, 1), pt(3, 1, 1)), Z, Answer::separated, Sep::outside_tube);
}

//   top view (z = 1): edge v0 v1 on the tangent line x = 1, touching at (1,0,1); v2 = (2,0,1).
BOOST_AUTO_TEST_CASE(edge_on_wall) {
  expect_touching(tri(pt(1, -1, 1), pt(1, 1, 1), pt(2, 0, 1)), Z, TF::edge, {0, 1}, CF::wall, pt(1, 0, 1));
  expect_answer(tri(pt(below(1), -1, 1), pt(below(1), 1, 1), pt(2, 0, 1)), Z, Answer::overlapping);
  expect_answer(tri(pt(above(1), -1, 1), pt(above(1), 1, 1), pt(2, 0, 1)), Z, Answer::separated, Sep::outside_tube);
}

//   The face lies in the tangent plane x = 1; it meets the wall along its part of the line
//   y = 0, from (1,0,1/2) on edge v0 v1 to v2 = (1,0,3/2).
BOOST_AUTO_TEST_CASE(face_on_wall) {
  const auto t = [](Rational x) { return tri(pt(x, -1, Q("1/2")), pt(x, 1, Q("1/2")), pt(x, 0, Q("3/2"))); };
  const Res r = certified_triangle_cylinder(t(1), Z);
  BOOST_TEST_REQUIRE(to_string(r.answer) == "touching");
  BOOST_TEST(r.witness->x == 1);
  BOOST_TEST(r.witness->y == 0);
  BOOST_TEST(to_string(r.cylinder_feature) == "wall");
  BOOST_TEST((r.normal == Vec3<Rational>{1, 0, 0}));  // the supporting plane is the tangent plane
  expect_answer(t(below(1)), Z, Answer::overlapping);
  expect_answer(t(above(1)), Z, Answer::separated, Sep::outside_tube);
}

// A sliver: the long edge v0 v1 runs along the tangent line y = 1 (z = 1); v2 is 2^-50 above it.
BOOST_AUTO_TEST_CASE(sliver_on_wall) {
  const Rational eps = Rational(1) / Rational(1125899906842624);  // 2^-50
  const auto t = [&](Rational y) { return tri(pt(-4, y, 1), pt(4, y, 1), pt(4, y + eps, 1)); };
  expect_touching(t(1), Z, TF::edge, {0, 1}, CF::wall, pt(0, 1, 1));
  expect_answer(t(below(1)), Z, Answer::overlapping);
  expect_answer(t(above(1)), Z, Answer::separated, Sep::outside_tube);
  // The same sliver turned toward the axis: v2 is 2^-50 inside, the edge on the wall.
  expect_answer(tri(pt(-4, 1, 1), pt(4, 1, 1), pt(4, 1 - eps, 1)), Z, Answer::overlapping);
}

// ---- On a cap ---------------------------------------------------------------------------------

//   side view: v0 = (1/2,0,2) on the top cap, v1 = (1/2,0,3), v2 = (1,1,3) above it.
BOOST_AUTO_TEST_CASE(vertex_on_cap) {
  const auto t = [](Rational z) { return tri(pt(Q("1/2"), 0, z), pt(Q("1/2"), 0, 3), pt(1, 1, 3)); };
  expect_touching(t(2), Z, TF::vertex, {0, -1}, CF::cap1, pt(Q("1/2"), 0, 2));
  expect_answer(t(below(2)), Z, Answer::overlapping);
  expect_answer(t(above(2)), Z, Answer::separated, Sep::beyond_cap1);
}

//   edge v0 v1 in the plane z = 2 through the disk, v2 = (0,0,3) above: nearest point to the
//   axis is (0,0,2), inside edge v0 v1. Bottom cap: the mirror image at z = 0.
BOOST_AUTO_TEST_CASE(edge_on_cap) {
  const auto t = [](Rational z, Rational apex) {
    return tri(pt(Q("-1/2"), 0, z), pt(Q("1/2"), 0, z), pt(0, Q("1/5"), apex));
  };
  expect_touching(t(2, 3), Z, TF::edge, {0, 1}, CF::cap1, pt(0, 0, 2));
  expect_answer(t(below(2), 3), Z, Answer::overlapping);
  expect_answer(t(above(2), 3), Z, Answer::separated, Sep::beyond_cap1);
  expect_touching(t(0, -1), Z, TF::edge, {0, 1}, CF::cap0, pt(0, 0, 0));
  expect_answer(t(below(0), -1), Z, Answer::separated, Sep::beyond_cap0);
  expect_answer(t(above(0), -1), Z, Answer::overlapping);
}

// ---- Triangles lying in a cap plane -----------------------------------------------------------

//   z = 2: the triangle (-1,-1) (2,-1) (-1,2) contains the disk's centre: it covers part of the
//   top disk but no interior point: touching, face on cap.
BOOST_AUTO_TEST_CASE(face_in_cap_plane) {
  const auto t = [](Rational z) { return tri(pt(-1, -1, z), pt(2, -1, z), pt(-1, 2, z)); };
  expect_touching(t(2), Z, TF::face, {-1, -1}, CF::cap1, pt(0, 0, 2));
  expect_touching(t(0), Z, TF::face, {-1, -1}, CF::cap0, pt(0, 0, 0));
  expect_answer(t(below(2)), Z, Answer::overlapping);
  expect_answer(t(above(2)), Z, Answer::separated, Sep::beyond_cap1);
  expect_answer(t(below(0)), Z, Answer::separated, Sep::beyond_cap0);
  expect_answer(t(above(0)), Z, Answer::overlapping);
  // In the cap plane but away from the disk: separated by a plane parallel to the axis.
  expect_answer(tri(pt(2, 0, 2), pt(3, 0, 2), pt(2, 1, 2)), Z, Answer::separated, Sep::outside_tube);
}

//   z = 2: edge v0 v1 on the line x = 1, tangent to the rim at (1,0,2); v2 = (2,0,2).
BOOST_AUTO_TEST_CASE(cap_plane_triangle_tangent_to_rim) {
  const auto t = [](Rational x) { return tri(pt(x, -1, 2), pt(x, 1, 2), pt(2, 0, 2)); };
  expect_touching(t(1), Z, TF::edge, {0, 1}, CF::rim1, pt(1, 0, 2));
  // Moved inward it covers part of the disk, still in the cap plane: touching on the cap.
  expect_touching(t(below(1)), Z, TF::edge, {0, 1}, CF::cap1, pt(below(1), 0, 2));
  expect_answer(t(above(1)), Z, Answer::separated, Sep::outside_tube);
}

// ---- On a rim -----------------------------------------------------------------------------------

//   v0 = (1,0,2) on the top rim, v1 = (2,0,3), v2 = (2,1,3) outward and above. Moved by 2^-52
//   along (1,0,1) (the outward normal of the rim's cone of normals): outward, every vertex is
//   above the cap plane; inward, v0 is strictly inside.
BOOST_AUTO_TEST_CASE(vertex_on_rim) {
  const Triangle<Rational> t = tri(pt(1, 0, 2), pt(2, 0, 3), pt(2, 1, 3));
  expect_touching(t, Z, TF::vertex, {0, -1}, CF::rim1, pt(1, 0, 2));
  expect_answer(translated(t, {-delta, 0, -delta}), Z, Answer::overlapping);
  expect_answer(translated(t, {delta, 0, delta}), Z, Answer::separated, Sep::beyond_cap1);
  // The mirror image on the bottom rim.
  expect_touching(tri(pt(1, 0, 0), pt(2, 0, -1), pt(2, 1, -1)), Z, TF::vertex, {0, -1}, CF::rim0, pt(1, 0, 0));
}

//   Edge v0 v1 tangent to the top rim at (1,0,2), in the cap plane; v2 = (2,0,3) above.
BOOST_AUTO_TEST_CASE(edge_on_rim) {
  const Triangle<Rational> t = tri(pt(1, -1, 2), pt(1, 1, 2), pt(2, 0, 3));
  expect_touching(t, Z, TF::edge, {0, 1}, CF::rim1, pt(1, 0, 2));
  // x - 2^-52: the edge crosses the disk but stays in the cap plane: touching on the cap.
  expect_touching(translated(t, {-delta, 0, 0}), Z, TF::edge, {0, 1}, CF::cap1, pt(1 - delta, 0, 2));
  expect_answer(translated(t, {delta, 0, 0}), Z, Answer::separated, Sep::outside_tube);
  // z - 2^-52: the edge dips below the cap plane onto the tangent line of the wall, touching the
  // wall at (1, 0, 2 - 2^-52) only.
  expect_touching(translated(t, {0, 0, -delta}), Z, TF::edge, {0, 1}, CF::wall, pt(1, 0, 2 - delta));
  expect_answer(translated(t, {-delta, 0, -delta}), Z, Answer::overlapping);
}

//   Edge v0 v1 from (0,0,3) to (2,0,1) crosses the rim at (1,0,2) from outside: in the slab
//   (z <= 2) its points (t,0,3-t), t >= 1, are at distance t >= 1 from the axis. The face
//   (third vertex (2,1,1)) stays outside too: x^2 + y^2 >= 4 (a+b)^2 >= 1 where z <= 2.
BOOST_AUTO_TEST_CASE(edge_through_rim) {
  const Triangle<Rational> t = tri(pt(0, 0, 3), pt(2, 0, 1), pt(2, 1, 1));
  expect_touching(t, Z, TF::edge, {0, 1}, CF::rim1, pt(1, 0, 2));
  expect_answer(translated(t, {-delta, 0, -delta}), Z, Answer::overlapping);
  expect_answer(translated(t, {delta, 0, delta}), Z, Answer::separated, Sep::outside_tube);
}

// ---- Other configurations -----------------------------------------------------------------------

// The triangle's plane y = 0 contains the axis; the triangle is 2 away from it.
BOOST_AUTO_TEST_CASE(plane_containing_axis) {
  expect_answer(tri(pt(2, 0, Q("1/2")), pt(3, 0, Q("1/2")), pt(Q("5/2"), 0, Q("3/2"))), Z, Answer::separated,
                Sep::outside_tube);
  // The same plane, reaching the wall at x = 1 along a vertical edge.
  const Res r = certified_triangle_cylinder(tri(pt(1, 0, Q("1/2")), pt(3, 0, Q("1/2")), pt(1, 0, Q("3/2"))), Z);
  BOOST_TEST(to_string(r.answer) == "touching");
  BOOST_TEST(r.witness->x == 1);
}

// A large triangle crossing both cap planes, pierced by the axis (clipped to a pentagon).
BOOST_AUTO_TEST_CASE(pentagon_pierced) {
  const Triangle<Rational> t = tri(pt(-10, -10, -1), pt(10, -10, 1), pt(0, 10, 3));
  expect_answer(t, Z, Answer::overlapping);
  // No vertex is inside: the witness is a point of the face strictly inside Z.
  const Res r = certified_triangle_cylinder(t, Z);
  BOOST_TEST_REQUIRE(r.witness.has_value());
  BOOST_TEST(classify_point(*r.witness, Z) == Side::inside);
}

// Degenerate triangles: a segment and a point.
BOOST_AUTO_TEST_CASE(degenerate_triangles) {
  expect_touching(tri(pt(1, 0, 1), pt(3, 0, 1), pt(3, 0, 1)), Z, TF::vertex, {0, -1}, CF::wall, pt(1, 0, 1));
  expect_touching(tri(pt(3, 0, 1), pt(3, 0, 1), pt(1, 0, 1)), Z, TF::vertex, {2, -1}, CF::wall, pt(1, 0, 1));
  expect_touching(tri(pt(1, 0, 1), pt(1, 0, 1), pt(1, 0, 1)), Z, TF::vertex, {0, -1}, CF::wall, pt(1, 0, 1));
  expect_touching(tri(pt(1, 0, 2), pt(1, 0, 2), pt(1, 0, 2)), Z, TF::vertex, {0, -1}, CF::rim1, pt(1, 0, 2));
  expect_answer(tri(pt(Q("1/2"), 0, 1), pt(Q("1/2"), 0, 1), pt(Q("1/2"), 0, 1)), Z, Answer::overlapping);
  expect_answer(tri(pt(2, 0, 1), pt(2, 0, 1), pt(2, 0, 1)), Z, Answer::separated, Sep::outside_tube);
  expect_answer(tri(pt(0, 0, 3), pt(0, 0, 3), pt(0, 0, 3)), Z, Answer::separated, Sep::beyond_cap1);
  // A segment through the cylinder along the axis, and one on the wall, parallel to the axis.
  expect_answer(tri(pt(0, 0, -1), pt(0, 0, 3), pt(0, 0, 3)), Z, Answer::overlapping);
  const Res r = certified_triangle_cylinder(tri(pt(1, 0, -1), pt(1, 0, 3), pt(1, 0, 3)), Z);
  BOOST_TEST(to_string(r.answer) == "touching");
  BOOST_TEST((r.witness->x == 1 && r.witness->y == 0));
  // A vertical segment 2^-52 outside the wall, crossing both cap planes.
  expect_answer(tri(pt(1 + delta, 0, 3), pt(1 + delta, 0, 1 + delta), pt(1 + delta, 0, 3)), Z, Answer::separated,
                Sep::outside_tube);
}

// An oblique cylinder, touching by construction: the cylinder from (0,0,0) to (2,2,1)
// (|A| = 3), radius 1. The unit vector n = (2,-1,-2)/3 is perpendicular to A, so
// X = (1,1,1/2) + n, at mid-height, is on the wall, and the plane through X with normal n is
// tangent to the wall along a line parallel to A.
BOOST_AUTO_TEST_CASE(oblique_wall_contact) {
  const Cylinder<Rational> c{{0, 0, 0}, {2, 2, 1}, Rational(1)};
  const Point3<Rational> X = pt(Q("5/3"), Q("2/3"), Q("-1/6"));
  // A triangle in the tangent plane through X, normal (2,-1,-2): spanned by A and (1,2,0).
  const Vec3<Rational> a{2, 2, 1}, b{1, 2, 0};
  const Triangle<Rational> t = tri(X, X + a, X + b);
  expect_touching(t, c, TF::vertex, {0, -1}, CF::wall, X);
  const Vec3<Rational> n{Q("2/3"), Q("-1/3"), Q("-2/3")};
  expect_answer(translated(t, -delta * n), c, Answer::overlapping);
  expect_answer(translated(t, delta * n), c, Answer::separated, Sep::outside_tube);
}

// Far from the origin: the hand cases translated by (2^40, -3 * 2^40, 2^41) keep their answers.
BOOST_AUTO_TEST_CASE(large_translation) {
  const Rational big(1099511627776.0);  // 2^40
  const Vec3<Rational> d{big, -3 * big, 2 * big};
  const Cylinder<Rational> c{Z.p0 + d, Z.p1 + d, Z.radius};
  const Triangle<Rational> t0 = tri(pt(1, -1, 1), pt(1, 1, 1), pt(2, 0, 1));
  expect_touching(translated(t0, d), c, TF::edge, {0, 1}, CF::wall, pt(1, 0, 1) + d);
  expect_answer(translated(t0, d + Vec3<Rational>{-delta, 0, 0}), c, Answer::overlapping);
  expect_answer(translated(t0, d + Vec3<Rational>{delta, 0, 0}), c, Answer::separated, Sep::outside_tube);
  expect_touching(translated(tri(pt(1, 0, 2), pt(2, 0, 3), pt(2, 1, 3)), d), c, TF::vertex, {0, -1}, CF::rim1,
                  pt(1, 0, 2) + d);
}

// Regression (found by fuzz_triangle_cylinder): a cylinder whose axis is subnormal, so A.A
// underflows to 0 in double. The certificate guessed in double then had NaN barycentric
// coordinates, and converting them to Mpzf failed CGAL's assertion (an exception out of the
// query where assertions are on, as in the sanitizer build; under NDEBUG a garbage guess that
// the exact check rejected).
//   The cylinder is a disk of thickness 2^-1074 * 0x301 in 0 <= x <= that, radius 2, about the
//   x axis; v1 = (0, 0, 2^-7) lies on its cap x = 0, and the points v1 + s (v0 - v1) with
//   0 < s < thickness are interior: overlapping.
BOOST_AUTO_TEST_CASE(subnormal_axis_no_guess_from_nan) {
  const Cylinder<Rational> c{{0, 0, 0}, {Rational(0x0.00000000301p-1022), 0, 0}, Rational(2)};
  const Triangle<Rational> t = tri(pt(1, 0, 0), pt(0, 0, Rational(0x1p-7)), pt(-1, -90, Rational(0x0.001a6a6a6a6a6p-1022)));
  const Res r = certified_triangle_cylinder(t, c);
  BOOST_TEST(to_string(r.answer) == "overlapping");
  BOOST_TEST(check_triangle_cylinder_certificate(r, t, c) == "");
  BOOST_TEST(oracle::triangle_cylinder(t, c) == Answer::overlapping);
}

// ---- Property tests ---------------------------------------------------------------------------

namespace {

struct Instance {
  Triangle<Rational> t;
  Cylinder<Rational> c;
};

// Small integer coordinates and radii: many exact contacts. Radius 5 with integer points on
// circles x^2 + y^2 = 25 (3-4-5) gives exact wall and rim contacts on an oblique grid too.
Instance integer_instance(std::mt19937_64& g) {
  std::uniform_int_distribution<int> coord(-3, 3), big(-6, 6), which(0, 3);
  const int kind = which(g);
  if (kind == 0) {
    // axis-aligned cylinder radius 5, height 4: vertices on the grid, caps at z = 0 and 4.
    std::uniform_int_distribution<int> z(-1, 5);
    Instance in{{}, {{0, 0, 0}, {0, 0, 4}, Rational(5)}};
    for (auto& v : in.t.v) v = pt(big(g), big(g), z(g));
    return in;
  }
  Instance in;
  do {
    in.c.p0 = pt(coord(g), coord(g), coord(g));
    in.c.p1 = pt(coord(g), coord(g), coord(g));
  } while (in.c.p0 == in.c.p1);
  const Rational radii[] = {Q("1/2"), Rational(1), Q("3/2"), Rational(2)};
  in.c.radius = radii[which(g)];
  for (auto& v : in.t.v) v = pt(coord(g), coord(g), coord(g));
  if (kind == 3) in.t.v[2] = in.t.v[which(g) % 2];  // degenerate: a segment or a point
  return in;
}

// Random binary64 coordinates: generic position.
Instance double_instance(std::mt19937_64& g) {
  std::uniform_real_distribution<double> u(-2, 2), rad(0.1, 1.5);
  Instance in;
  in.c = {pt(Rational(u(g)), Rational(u(g)), Rational(u(g))), pt(Rational(u(g)), Rational(u(g)), Rational(u(g))),
          Rational(rad(g))};
  for (auto& v : in.t.v) v = pt(Rational(u(g)), Rational(u(g)), Rational(u(g)));
  return in;
}

// Triangles with vertices on the caps' planes and on half-integer grids near Z's wall.
Instance cap_instance(std::mt19937_64& g) {
  std::uniform_int_distribution<int> c(-4, 4), z(0, 4), keep(0, 2);
  Instance in{{}, Z};
  const Rational zs[] = {Rational(0), Rational(2), Rational(0), Rational(2), Q("1/2")};
  const Rational zplane = zs[z(g)];
  for (auto& v : in.t.v) v = pt(Rational(c(g), 2), Rational(c(g), 2), keep(g) == 0 ? Rational(c(g), 2) : zplane);
  return in;
}

}  // namespace

BOOST_AUTO_TEST_CASE(agrees_with_independent_minimisation) {
  const unsigned long seed = 20240611;
  std::cout << "agrees_with_independent_minimisation: seed " << seed << "\n";
  std::mt19937_64 g(seed);
  int counts[3][3] = {};
  FilterCounter filter;
  for (int gen = 0; gen < 3; ++gen) {
    for (int i = 0; i < 2000; ++i) {
      const Instance in = gen == 0 ? integer_instance(g) : (gen == 1 ? double_instance(g) : cap_instance(g));
      const Res r = certified_triangle_cylinder(in.t, in.c);
      filter += r.counter;
      const Answer expected = oracle::triangle_cylinder(in.t, in.c);
      BOOST_TEST_REQUIRE(to_string(r.answer) == to_string(expected),
                         "generator " << gen << " instance " << i << ": certified " << to_string(r.answer)
                                      << ", independent " << to_string(expected));
      ++counts[gen][static_cast<int>(r.answer)];
      if (gen == 1) {
        // Binary64 input: the double entry point must give the same answer.
        const auto d = [](const Rational& q) { return CGAL::to_double(q); };
        FilterCounter fc;
        BOOST_TEST(classify_triangle_cylinder(in.t.map(d), in.c.map(d), fc) == r.answer);
      }
    }
    std::cout << "  generator " << gen << ": separated " << counts[gen][0] << ", touching " << counts[gen][1]
              << ", overlapping " << counts[gen][2] << "\n";
  }
  std::cout << "  filter: " << filter.calls << " calls, " << filter.exact << " exact\n";
  // The generators must exercise every answer, touching included, or the agreement means little.
  BOOST_TEST(counts[0][1] > 10);
  BOOST_TEST(counts[2][1] > 50);
  for (int a = 0; a < 3; ++a) BOOST_TEST(counts[0][a] + counts[1][a] + counts[2][a] > 100);
  BOOST_TEST(counts[1][0] > 0);
  BOOST_TEST(counts[1][2] > 0);
}

BOOST_AUTO_TEST_CASE(invariance) {
  const unsigned long seed = 777;
  std::cout << "invariance: seed " << seed << "\n";
  std::mt19937_64 g(seed);
  for (int i = 0; i < 600; ++i) {
    const Instance in = i % 2 == 0 ? integer_instance(g) : cap_instance(g);
    const Answer a = certified_triangle_cylinder(in.t, in.c).answer;
    // Vertex order: all six permutations.
    std::array<int, 3> p{0, 1, 2};
    do {
      const Triangle<Rational> t = tri(in.t.v[p[0]], in.t.v[p[1]], in.t.v[p[2]]);
      BOOST_TEST_REQUIRE(certified_triangle_cylinder(t, in.c).answer == a);
    } while (std::next_permutation(p.begin(), p.end()));
    // Flipping the axis.
    const Cylinder<Rational> flipped{in.c.p1, in.c.p0, in.c.radius};
    BOOST_TEST_REQUIRE(certified_triangle_cylinder(in.t, flipped).answer == a);
    // Integer translation.
    const Vec3<Rational> d{Rational(12345), Rational(-678), Rational(91011)};
    BOOST_TEST_REQUIRE(certified_triangle_cylinder(translated(in.t, d), {in.c.p0 + d, in.c.p1 + d, in.c.radius}).answer == a);
    // Power-of-two scaling, up and down.
    for (const Rational& k : {Rational(1024), Rational(1, 1) / Rational(65536)}) {
      const auto s = [&](const Point3<Rational>& v) { return Point3<Rational>(k * v); };
      BOOST_TEST_REQUIRE(
          certified_triangle_cylinder(tri(s(in.t.v[0]), s(in.t.v[1]), s(in.t.v[2])), {s(in.c.p0), s(in.c.p1), k * in.c.radius})
              .answer == a);
    }
  }
}

// The flipped axis exchanges the caps in the certificate.
BOOST_AUTO_TEST_CASE(flip_exchanges_caps) {
  const Cylinder<Rational> flipped{Z.p1, Z.p0, Z.radius};
  expect_touching(tri(pt(1, 0, 2), pt(2, 0, 3), pt(2, 1, 3)), flipped, TF::vertex, {0, -1}, CF::rim0, pt(1, 0, 2));
  expect_answer(tri(pt(0, 0, 3), pt(1, 0, 3), pt(0, 1, 3)), flipped, Answer::separated, Sep::beyond_cap0);
}

// The filter decides generic input with intervals alone. An exact contact needs Gmpq when the
// input is not binary64 (with small binary64 integers the intervals are points and decide
// zero signs exactly).
BOOST_AUTO_TEST_CASE(filter_counter) {
  FilterCounter fc;
  BOOST_TEST(classify_triangle_cylinder(tri(pt(Q("1/3"), 0, 1), pt(3, 0, 1), pt(3, 1, 1)), Z, fc) == Answer::overlapping);
  BOOST_TEST(fc.calls == 1u);
  BOOST_TEST(fc.exact == 0u);
  BOOST_TEST(classify_triangle_cylinder(tri(pt(1, -1, 1), pt(1, 1, 1), pt(2, 0, 1)), Z, fc) == Answer::touching);
  BOOST_TEST(fc.exact == 0u);
  const Cylinder<Rational> third{{0, 0, 0}, {0, 0, 2}, Q("1/3")};
  BOOST_TEST(classify_triangle_cylinder(tri(pt(Q("1/3"), -1, 1), pt(Q("1/3"), 1, 1), pt(2, 0, 1)), third, fc) ==
             Answer::touching);
  BOOST_TEST(fc.calls == 3u);
  BOOST_TEST(fc.exact == 1u);
  // The stages: generic binary64 input is decided by the static filter; an exact contact in
  // binary64 (the edge on the wall) never is (the filter never answers zero), intervals decide
  // it (small integers: point intervals); with 1/3 the contact needs Gmpq.
  TriangleFilterStages st;
  BOOST_TEST(classify_triangle_cylinder(tri(pt(Q("1/4"), 0, 1), pt(3, 0, 1), pt(3, 1, 1)), Z, st) == Answer::overlapping);
  BOOST_TEST(st.semi_static == 1u);
  BOOST_TEST(classify_triangle_cylinder(tri(pt(1, -1, 1), pt(1, 1, 1), pt(2, 0, 1)), Z, st) == Answer::touching);
  BOOST_TEST(st.semi_static == 1u);
  BOOST_TEST(st.interval == 1u);
  BOOST_TEST(classify_triangle_cylinder(tri(pt(Q("1/3"), -1, 1), pt(Q("1/3"), 1, 1), pt(2, 0, 1)), third, st) ==
             Answer::touching);
  BOOST_TEST(st.calls == 3u);
  BOOST_TEST(st.exact == 1u);
}
