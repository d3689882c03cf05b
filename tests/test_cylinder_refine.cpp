// The refine stage of the certified cylinder-pair query (Newton's method in double-double on the
// optimality conditions, detail/cylinder_active_set.hpp): near-touching pairs of every contact
// type, whose answers are known by construction, are decided there (not by the Gmpfr stage),
// with certificates re-checked independently (tests/test_cylinder_cylinder_cases.hpp).
#define BOOST_TEST_MODULE cylinder_refine
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <random>
#include <string>

#include "test_cylinder_cylinder_cases.hpp"

using namespace cctest;
using certcyl::Answer;

namespace {

// 2^-k exactly.
Q two_power(int k) {
  Q r = 1;
  for (int i = 0; i < k; ++i) r = r / 2;
  return r;
}

// The pair of case c with b moved by t along the unit contact normal (t > 0: apart).
Cylinder<Q> moved_b(const TouchingCase& c, const Q& t) { return translate(c.b, t * c.normal); }

// Whether the case's answer after a move of +-2^-k is known by construction: a translation
// along a contact normal n separates touching convex bodies (the plane moves with b); a
// translation by -t n makes them overlap when n is the only contact normal (a point or segment
// contact on smooth parts, or a face contact), which holds for every base case but rim-rim
// (whose normal cone is two-dimensional: there only the + side is asserted).
bool overlap_known(const TouchingCase& c) { return c.type != "rim-rim"; }

}  // namespace

// Both sides of every contact type at 2^-60 and 2^-80 (rational input: no binary64 pair can
// sit that close to these configurations), in the axis-aligned frame and turned by a rational
// rotation: decided by the refine stage, certificates independent-checked.
BOOST_AUTO_TEST_CASE(near_touching_pairs_are_decided_by_the_refine_stage) {
  const Rotation R = Rotation::from_quaternion(1, 2, 2, 4);
  for (const TouchingCase& base : base_touching_cases()) {
    for (const bool turned : {false, true}) {
      const TouchingCase c = turned ? moved(base, R, {3, -1, 2}) : base;
      for (const int k : {60, 80}) {
        for (const int side : {1, -1}) {
          if (side < 0 && !overlap_known(c)) continue;
          const Cylinder<Q> b = moved_b(c, side * two_power(k));
          const certcyl::CylinderCylinderResult r = certcyl::certified_cylinder_cylinder(c.a, b);
          BOOST_TEST_CONTEXT(c.name << (turned ? " turned" : "") << " moved " << side << " 2^-" << k) {
            BOOST_TEST(to_string(r.answer) == (side > 0 ? "separated" : "overlapping"));
            BOOST_TEST(to_string(r.stage) == "refine");
            BOOST_TEST(r.gmpfr_precision == 0);
            BOOST_TEST(certificate_error(c.a, b, r) == "");
          }
        }
      }
    }
  }
}

// Binary64 pairs a few units in the last place from touching, in an integer frame (the
// configuration times 100, so every coordinate and radius is an integer below 2^10): b moved by
// 2^-40 times the signs of the normal's coordinates (a vector with a positive product with the
// normal), or by minus that. Decided without the Gmpfr stage; with the refine stage off the
// other stages give the same answers.
BOOST_AUTO_TEST_CASE(binary64_pairs_a_few_ulps_from_touching) {
  for (const TouchingCase& base : base_touching_cases()) {
    const Cylinder<Q> a = scale(base.a, Q(100));
    const Cylinder<Q> b0 = scale(base.b, Q(100));
    // The signs of the normal's coordinates: a translation with a positive product with n.
    const auto sgn = [](const Q& x) { return x > 0 ? 1 : x < 0 ? -1 : 0; };
    const Vec3<Q> v{sgn(base.normal.x), sgn(base.normal.y), sgn(base.normal.z)};
    for (const int side : {1, -1}) {
      if (side < 0 && !overlap_known(base)) continue;
      const Cylinder<Q> b = translate(b0, (side * two_power(40)) * v);
      const auto to_d = [](const Q& q) { return CGAL::to_double(q); };
      const Cylinder<double> da = a.map(to_d), db = b.map(to_d);
      BOOST_TEST_CONTEXT(base.name << " side " << side) {
        // The doubles are the rationals exactly.
        BOOST_TEST((da.map([](double x) { return Q(x); }).p1 == a.p1 && db.map([](double x) { return Q(x); }).p0 == b.p0));
        const certcyl::CylinderCylinderResult r = certcyl::certified_cylinder_cylinder(da, db);
        BOOST_TEST(to_string(r.answer) == (side > 0 ? "separated" : "overlapping"));
        BOOST_TEST(r.gmpfr_precision == 0);
        BOOST_TEST(certificate_error(a, b, r) == "");
        certcyl::CylinderCylinderOptions off;
        off.refine = false;
        const certcyl::CylinderCylinderResult s = certcyl::certified_cylinder_cylinder(da, db, off);
        BOOST_TEST(to_string(s.answer) == to_string(r.answer));
        BOOST_TEST(to_string(s.stage) != "refine");
      }
    }
  }
}

// Every contact type turned by a random double rotation and rounded to binary64 (the pair then
// sits within about an ulp of touching, on either side; bench/bench_cylinder_hard.cpp's
// "rounded" families): decided by the refine stage or before it, never by the Gmpfr or
// ellipsoid stages, with certificates re-checked independently; the answers are those of the
// query with the refine stage off. Caps meeting almost flat (cap-cap) go through the vertex
// start of the refine stage, other contacts through its usual start.
BOOST_AUTO_TEST_CASE(rounded_pairs_of_every_contact_type_are_decided_by_the_refine_stage) {
  std::mt19937_64 g(20261126);
  std::normal_distribution<double> gauss;
  int refined = 0;
  for (const TouchingCase& c : base_touching_cases()) {
    for (int i = 0; i < 12; ++i) {
      const RoundedRotation R(g, gauss, 20);
      const Cylinder<double> da = R.rounded(c.a), db = R.rounded(c.b);
      const auto to_q = [](double x) { return Q(x); };
      BOOST_TEST_CONTEXT(c.name << " rotation " << i) {
        const certcyl::CylinderCylinderResult r = certcyl::certified_cylinder_cylinder(da, db);
        BOOST_TEST((to_string(r.stage) == "refine" || to_string(r.stage) == "fast_path" || to_string(r.stage) == "optimiser"));
        BOOST_TEST(r.gmpfr_precision == 0);
        BOOST_TEST(r.ellipsoid_precision == 0);
        BOOST_TEST(certificate_error(da.map(to_q), db.map(to_q), r) == "");
        certcyl::CylinderCylinderOptions off;
        off.refine = false;
        BOOST_TEST(to_string(certcyl::certified_cylinder_cylinder(da, db, off).answer) == to_string(r.answer));
        refined += to_string(r.stage) == "refine";
      }
    }
  }
  BOOST_TEST_MESSAGE("rounded pairs decided by the refine stage: " << refined << " of 84");
  // Most rounded pairs are too close to touching for the double stages.
  BOOST_TEST(refined >= 42);
}
