// Certified cylinder-cylinder query: hand-made and constructed cases whose answer is known by
// construction (tests/test_cylinder_cylinder_cases.hpp). Every answer's certificate is also
// rechecked exactly by independent code (CORE::Expr square roots, the point test from its
// definition).
#define BOOST_TEST_MODULE certified_cylinder_cylinder
#include <boost/test/unit_test.hpp>

#include <cmath>

#include "test_cylinder_cylinder_cases.hpp"

using namespace cctest;
using certcyl::Answer;
using certcyl::certified_cylinder_cylinder;
using certcyl::CylinderStage;

namespace {

certcyl::CylinderCylinderResult query(const Cylinder<Q>& a, const Cylinder<Q>& b) {
  const certcyl::CylinderCylinderResult r = certified_cylinder_cylinder(a, b);
  BOOST_TEST(certificate_error(a, b, r) == "");
  return r;
}

// The answer must be the same after swapping, flipping both axes, an integer translation and a
// power-of-two scaling (all exact).
void check_invariance(const Cylinder<Q>& a, const Cylinder<Q>& b, Answer expected) {
  BOOST_TEST(to_string(query(b, a).answer) == to_string(expected));
  BOOST_TEST(to_string(query(flip(a), flip(b)).answer) == to_string(expected));
  const Vec3<Q> t{Q(1 << 30), Q(-(1 << 30)), Q(7)};
  BOOST_TEST(to_string(query(translate(a, t), translate(b, t)).answer) == to_string(expected));
  const Q s = Q(1) / Q(1 << 20);
  BOOST_TEST(to_string(query(scale(a, s), scale(b, s)).answer) == to_string(expected));
}

const Q two_m40 = Q(1) / Q(1LL << 40);
const Q two_m52 = Q(1) / Q(static_cast<double>(1LL << 52));  // one ulp of 1

}  // namespace

BOOST_AUTO_TEST_CASE(simple_separated_and_overlapping) {
  //  [a]  gap 1  [b]       two unit-radius cylinders along z, axes 3 apart
  const Cylinder<Q> a{{0, 0, 0}, {0, 0, 1}, 1};
  const auto sep = query(a, cyl({3, 0, 0}, {3, 0, 1}, 1));
  BOOST_TEST(to_string(sep.answer) == "separated");
  // phi* = (r0 + r1) / 3 = 2/3 exactly: the enclosure must contain it.
  BOOST_TEST(sep.gap_known);
  BOOST_TEST((sep.phi_lower <= 2.0 / 3 + 1e-16 && 2.0 / 3 - 1e-16 <= sep.phi_upper));
  BOOST_TEST((sep.log_gap_lower <= std::log(2.0 / 3) + 1e-15 && std::log(2.0 / 3) - 1e-15 <= sep.log_gap_upper));
  const auto ovl = query(a, cyl({1, 0, 0}, {1, 0, 1}, 1));
  BOOST_TEST(to_string(ovl.answer) == "overlapping");
  // phi* = (r0 + r1) / 1 = 2.
  BOOST_TEST((ovl.phi_lower <= 2 && 2 <= ovl.phi_upper));
  check_invariance(a, cyl({3, 0, 0}, {3, 0, 1}, 1), Answer::separated);
  check_invariance(a, cyl({1, 0, 0}, {1, 0, 1}, 1), Answer::overlapping);
}

BOOST_AUTO_TEST_CASE(equal_midpoints_overlap) {
  // A thin needle through the middle of a flat disk, sharing the midpoint (0, 0, 0).
  const Cylinder<Q> a{{-1, 0, 0}, {1, 0, 0}, Q(1, 8)};
  const Cylinder<Q> b{{0, -3, 0}, {0, 3, 0}, Q(1, 1000)};
  const auto r = query(a, b);
  BOOST_TEST(to_string(r.answer) == "overlapping");
  BOOST_TEST(to_string(r.stage) == "midpoints");
  BOOST_TEST(!r.gap_known);
  BOOST_TEST((*r.witness == Point3<Q>{0, 0, 0}));
}

BOOST_AUTO_TEST_CASE(rejects_invalid_input) {
  const Cylinder<Q> a{{0, 0, 0}, {0, 0, 1}, 1};
  BOOST_CHECK_THROW(certified_cylinder_cylinder(a, cyl({1, 1, 1}, {1, 1, 1}, 1)), certcyl::InvalidInput);
  BOOST_CHECK_THROW(certified_cylinder_cylinder(a, cyl({1, 1, 1}, {1, 1, 2}, 0)), certcyl::InvalidInput);
}

// Each contact type, exactly touching, under three rigid motions; then moved 2^-40 and one ulp
// of 1 along the contact normal each way: away separates, towards overlaps (the contact normal
// is unique in every base case, so pushing along it enters the interior).
BOOST_AUTO_TEST_CASE(contact_types_touch_and_move) {
  const std::array<Rotation, 3> rotations{Rotation::from_quaternion(1, 0, 0, 0), Rotation::from_quaternion(1, 2, 2, 4),
                                          Rotation::from_quaternion(3, -1, 5, 2)};
  const std::array<Vec3<Q>, 3> translations{Vec3<Q>{0, 0, 0}, Vec3<Q>{Q(1, 3), Q(-7, 2), 5},
                                            Vec3<Q>{Q(1 << 30), Q(1 << 30), Q(-(1 << 30))}};
  for (const TouchingCase& base : base_touching_cases()) {
    for (std::size_t m = 0; m < rotations.size(); ++m) {
      const TouchingCase c = moved(base, rotations[m], translations[m]);
      BOOST_TEST_CONTEXT(c.name << " motion " << m) {
        const auto r = query(c.a, c.b);
        BOOST_TEST(to_string(r.answer) == "touching");
        if (r.contact) {
          BOOST_TEST(r.contact->type() == c.type);
          if (c.point_contact) BOOST_TEST((r.contact->point == c.contact));
          // The normal found is parallel to the constructed one.
          const Vec3<Q> x = cross(r.contact->normal, c.normal);
          BOOST_TEST((x == Vec3<Q>{0, 0, 0}));
        }
        BOOST_TEST((r.gap_known && r.phi_lower == 1 && r.phi_upper == 1));
        // Swapped, the features swap.
        const auto s = query(c.b, c.a);
        BOOST_TEST(to_string(s.answer) == "touching");
        if (s.contact) BOOST_TEST(std::string(to_string(s.contact->feature1)) + "-" + to_string(s.contact->feature0) == c.type);
        for (const Q& eps : {two_m40, two_m52}) {
          const auto away = query(c.a, translate(c.b, eps * c.normal));
          const auto into = query(c.a, translate(c.b, -eps * c.normal));
          BOOST_TEST(to_string(away.answer) == "separated", "eps " << eps);
          BOOST_TEST(to_string(into.answer) == "overlapping", "eps " << eps);
        }
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(coaxial_pairs) {
  //  a: z in [0, 2], radius 1;  b: radius 1/2 on the same axis.
  const Cylinder<Q> a{{0, 0, 0}, {0, 0, 2}, 1};
  BOOST_TEST(to_string(query(a, cyl({0, 0, 1}, {0, 0, 3}, Q(1, 2))).answer) == "overlapping");
  const auto touch = query(a, cyl({0, 0, 2}, {0, 0, 3}, Q(1, 2)));
  BOOST_TEST(to_string(touch.answer) == "touching");
  if (touch.contact) BOOST_TEST(touch.contact->type() == "cap-cap");
  BOOST_TEST(to_string(query(a, cyl({0, 0, 2 + two_m52}, {0, 0, 3}, Q(1, 2))).answer) == "separated");
  BOOST_TEST(to_string(query(a, cyl({0, 0, 2 - two_m52}, {0, 0, 3}, Q(1, 2))).answer) == "overlapping");
  // b inside a entirely, coaxial, different midpoints.
  BOOST_TEST(to_string(query(a, cyl({0, 0, Q(1, 4)}, {0, 0, Q(1, 2)}, Q(1, 2))).answer) == "overlapping");
  check_invariance(a, cyl({0, 0, 2}, {0, 0, 3}, Q(1, 2)), Answer::touching);
}

BOOST_AUTO_TEST_CASE(near_parallel_pairs) {
  // a: z in [0, 2], radius 1. b: radius 1, axis from (x0, 0, 0) to (x0 + d, 0, 2), leaning away
  // from a by d = 2^-30. The smallest x over b is x0 - 2/sqrt(4 + d^2) < x0 - 1 + d^2/8, and
  // b's bottom rim point (x0 - 2/sqrt(4+d^2), 0, d/sqrt(4+d^2)) is strictly inside a when
  // x0 = 2 - d (x < 1 - d + d^2/8, 0 < z < 2): overlapping. With x0 = 2, the direction e_x
  // separates: min over b of x = 2 - 2/sqrt(4 + d^2) > 1 = max over a (gap about d^2/8 = 2^-63).
  const Q d = Q(1) / Q(1 << 30);
  const Cylinder<Q> a{{0, 0, 0}, {0, 0, 2}, 1};
  BOOST_TEST(to_string(query(a, cyl({2 - d, 0, 0}, {2, 0, 2}, 1)).answer) == "overlapping");
  const auto sep = query(a, cyl({2, 0, 0}, {2 + d, 0, 2}, 1));
  BOOST_TEST(to_string(sep.answer) == "separated");
  BOOST_TEST(to_string(sep.stage) == "gmpfr");
  // Exactly parallel and exactly touching (wall-wall along a segment), then 2^-40 apart.
  BOOST_TEST(to_string(query(a, cyl({2, 0, 1}, {2, 0, 4}, 1)).answer) == "touching");
  BOOST_TEST(to_string(query(a, cyl({2 + two_m40, 0, 1}, {2 + two_m40, 0, 4}, 1)).answer) == "separated");
}

BOOST_AUTO_TEST_CASE(double_overload_matches_rational) {
  const certcyl::Cylinder<double> a{{0, 0, 0}, {0, 0, 2}, 1}, b{{2, 0, 1}, {2, 0, 3}, 1};
  const auto r = certified_cylinder_cylinder(a, b);
  BOOST_TEST(to_string(r.answer) == "touching");
  const certcyl::Cylinder<double> c{{2, 0, 1}, {2, 0, 3}, 0x1.fffffffffffffp-1};  // radius 1 - 2^-53
  BOOST_TEST(to_string(certified_cylinder_cylinder(a, c).answer) == "separated");
  BOOST_CHECK_THROW(certified_cylinder_cylinder(a, certcyl::Cylinder<double>{{0, 0, 0}, {0, 0, NAN}, 1}), certcyl::InvalidInput);
}
