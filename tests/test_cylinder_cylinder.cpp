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
  const certcyl::CylinderGap sg = sep.gap();
  BOOST_TEST(sg.known);
  BOOST_TEST((sg.phi_lower <= 2.0 / 3 + 1e-16 && 2.0 / 3 - 1e-16 <= sg.phi_upper));
  BOOST_TEST((sg.log_lower() <= std::log(2.0 / 3) + 1e-15 && std::log(2.0 / 3) - 1e-15 <= sg.log_upper()));
  const auto ovl = query(a, cyl({1, 0, 0}, {1, 0, 1}, 1));
  BOOST_TEST(to_string(ovl.answer) == "overlapping");
  // phi* = (r0 + r1) / 1 = 2.
  const certcyl::CylinderGap og = ovl.gap();
  BOOST_TEST(og.known);
  BOOST_TEST((og.phi_lower <= 2 && 2 <= og.phi_upper));
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
  BOOST_TEST(!r.gap().known);
  BOOST_TEST((*r.witness == Point3<Q>{0, 0, 0}));
}

BOOST_AUTO_TEST_CASE(a_known_gap_enclosure_is_finite) {
  // Found by the pair fuzz harness: a direction's ratio bound overflowed to +inf and the gap
  // was reported known with phi_upper = inf. The pair overlaps (the centre of b's first end disc lies inside a);
  // an overflowed bound is dropped, so the enclosure is finite or not known, in both orders.
  const Cylinder<Q> a{{Q(0x1.6cp+6), Q(-1), Q(-0x1.dd6fafeffffffp+356)}, {Q(-0x1p-5), Q(0), Q(0x1.8p-1)}, Q(1)};
  const Cylinder<Q> b{{Q(0x1.4p-1), Q(-0.25), Q(-1)}, {Q(-0x1.afeffffffff02p+368), Q(0x1.3005a0200a5a5p+417), Q(0.125)}, Q(0x1.08p+3)};
  for (const auto& r : {query(a, b), query(b, a)}) {
    BOOST_TEST(to_string(r.answer) == "overlapping");
    const certcyl::CylinderGap g = r.gap();
    BOOST_TEST((!g.known || (std::isfinite(g.phi_upper) && g.phi_upper > 1 && g.phi_lower <= g.phi_upper)));
  }
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
        BOOST_TEST((r.gap().known && r.gap().phi_lower == 1 && r.gap().phi_upper == 1));
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
  // A gap of 2^-63 is beyond double precision and within double-double's: the refine stage.
  BOOST_TEST(to_string(sep.stage) == "refine");
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

// Binary64 input: touching constructions with binary64 coordinates, at the exact contact and
// with the touching coordinate moved one ulp either way (away: separated, into: overlapping,
// by construction), at three magnitudes (scaled by 2^996 ~ 6.7e299 and 2^-996 ~ 1.5e-300,
// exactly). Every answer's certificate is rechecked exactly; the static filter must never be
// the one that decides a touching answer, and it must decide the clear cases (moved 1/4).
BOOST_AUTO_TEST_CASE(binary64_one_ulp_and_extreme_magnitudes) {
  using C = certcyl::Cylinder<double>;
  struct Case {
    const char* name;
    C a;
    // b with its touching coordinate(s) set to t (the contact at t = t0; larger t is away).
    C (*b)(double t);
    double t0;
  };
  const C a{{0, 0, 0}, {0, 0, 2}, 1};  // z in [0, 2], radius 1
  const std::array<Case, 4> cases{
      Case{"cap-cap", a, [](double t) { return C{{1, 0, t}, {1, 0, 5}, 1}; }, 2},
      Case{"cap-wall", a, [](double t) { return C{{-1, 0, t}, {1, 0, t}, 1}; }, 3},
      Case{"wall-wall crossing", C{{0, 0, -1}, {0, 0, 1}, 1}, [](double t) { return C{{t, -1, 0}, {t, 1, 0}, 1}; }, 2},
      Case{"wall-wall parallel", a, [](double t) { return C{{t, 0, 1}, {t, 0, 3}, 1}; }, 2}};
  const auto scaled = [](const C& c, double s) { return C{s * c.p0, s * c.p1, s * c.radius}; };
  const auto exact_of = [](const C& c) { return c.map([](double x) { return Q(x); }); };
  for (const Case& c : cases) {
    for (const double s : {1.0, std::ldexp(1.0, 996), std::ldexp(1.0, -996)}) {
      const double up = std::nextafter(c.t0, INFINITY), down = std::nextafter(c.t0, -INFINITY);
      const std::array<std::pair<double, const char*>, 5> moves{std::pair{c.t0, "touching"}, std::pair{up, "separated"},
                                                                std::pair{down, "overlapping"}, std::pair{c.t0 + 0.25, "separated"},
                                                                std::pair{c.t0 - 0.25, "overlapping"}};
      for (const auto& [t, expected] : moves) {
        const C A = scaled(c.a, s), B = scaled(c.b(t), s);
        BOOST_TEST_CONTEXT(c.name << " scale " << s << " t " << t) {
          const auto r = certified_cylinder_cylinder(A, B);
          BOOST_TEST(to_string(r.answer) == expected);
          BOOST_TEST(certificate_error(exact_of(A), exact_of(B), r) == "");
          if (r.answer == Answer::touching) BOOST_TEST(to_string(r.certified_by) == "exact");
          if (t == c.t0 + 0.25 || t == c.t0 - 0.25) BOOST_TEST(to_string(r.certified_by) == "static");
          // The Rational overload agrees.
          BOOST_TEST(to_string(certified_cylinder_cylinder(exact_of(A), exact_of(B)).answer) == expected);
        }
      }
    }
  }
}

// Where the filter's guards fail, the intervals and Gmpq decide. (1) Unit cylinders at
// x = 2^120: in the scaled frame A.A = 2^-240 < 2^-200. (2) A radius 2^-1000 beside a
// coordinate 2^1000: the power-of-two scaling would underflow, so the frame is not scaled.
BOOST_AUTO_TEST_CASE(binary64_outside_the_filter_guards) {
  using C = certcyl::Cylinder<double>;
  const double X = std::ldexp(1.0, 120);
  const C a{{X, 0, 0}, {X, 0, 1}, 1};
  const auto exact_of = [](const C& c) { return c.map([](double x) { return Q(x); }); };
  for (const auto& [y, expected] : {std::pair{3.0, "separated"}, std::pair{1.0, "overlapping"}, std::pair{2.0, "touching"}}) {
    const C b{{X, y, 0}, {X, y, 1}, 1};
    const auto r = certified_cylinder_cylinder(a, b);
    BOOST_TEST(to_string(r.answer) == expected, "y " << y);
    BOOST_TEST(to_string(r.certified_by) != "static");
    BOOST_TEST(certificate_error(exact_of(a), exact_of(b), r) == "");
  }
  const double big = std::ldexp(1.0, 1000), tiny = std::ldexp(1.0, -1000);
  const C c{{0, 0, 0}, {0, 0, 1}, 1}, d{{big, 0, 0}, {big, 0, 1}, tiny};
  const auto r = certified_cylinder_cylinder(c, d);
  BOOST_TEST(to_string(r.answer) == "separated");
  BOOST_TEST(to_string(r.certified_by) != "static");
  BOOST_TEST(certificate_error(exact_of(c), exact_of(d), r) == "");
}

// Options that change the cost, not the answer: without Rational certificates (the default) the
// binary64 ones are given (and are the same exact numbers); without the clock (the default) the
// stage times are zero; with rational_certificates the Rational fields hold the same numbers.
BOOST_AUTO_TEST_CASE(lean_options_same_answers) {
  certcyl::CylinderCylinderOptions lean;
  BOOST_TEST(!lean.rational_certificates);
  BOOST_TEST(!lean.time_stages);
  const certcyl::Cylinder<double> a{{0, 0, 0}, {0, 0, 1}, 1}, sep{{3, 0, 0}, {3, 0, 1}, 1}, ovl{{1, 0, 0}, {1, 0, 1}, 1};
  const auto r = certified_cylinder_cylinder(a, sep, lean);
  BOOST_TEST(to_string(r.answer) == "separated");
  BOOST_TEST(!r.direction.has_value());
  BOOST_TEST(r.direction_binary64.has_value());
  BOOST_TEST(r.exact_direction().has_value());
  BOOST_TEST(certificate_error(cyl({0, 0, 0}, {0, 0, 1}, 1), cyl({3, 0, 0}, {3, 0, 1}, 1), [&] {
               auto full = r;
               full.direction = r.exact_direction();
               return full;
             }()) == "");
  for (double t : r.stage_seconds) BOOST_TEST(t == 0);
  const auto o = certified_cylinder_cylinder(a, ovl, lean);
  BOOST_TEST(to_string(o.answer) == "overlapping");
  BOOST_TEST(!o.witness.has_value());
  BOOST_TEST(o.witness_binary64.has_value());
  certcyl::CylinderCylinderOptions full;
  full.rational_certificates = true;
  full.time_stages = true;
  full.refine_gap = true;
  const auto d = certified_cylinder_cylinder(a, ovl, full);
  BOOST_TEST(to_string(d.answer) == "overlapping");
  BOOST_TEST(d.witness.has_value());
  BOOST_TEST((*d.witness == *o.exact_witness()));
}
