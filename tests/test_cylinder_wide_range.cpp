// Cylinder pairs whose operands span many binades (test_cylinder_wide_range_cases.hpp): sizes
// from 2^-1040 to 2^1000 in one query, subnormal radii beside coordinates near 2^1000, needles
// 2^2000 times longer than wide, and the same pairs turned by a rational rotation, translated by
// 2^900 + 1/3 and divided by 10^500 + 1 (500-digit rationals). Answers are known by
// construction; every certificate is re-checked exactly by fuzz/recheck.hpp.
//
// Asserted: no answer ever contradicts the construction; every exactly touching pair, in every
// contact type and at every size, is decided (the touching stage is complete: paper, Theorem 2);
// the cap-cap (needles included) and cap-wall families are decided at every distance, and so is
// every pair whose numbers are all binary64; and the needle found by the pair fuzz harness is
// decided; and, since the query is complete (the paper's completeness theorem: the ellipsoid stage), every
// other pair too, binary64 or rational. The ellipsoid stage's cuts are checked against the
// targets they must keep, and its rounded runs (the ones its proof is about) are run on their
// own. The line, ray, segment and triangle queries run on the same operands and must decide,
// consistently with the pair where the construction implies it.
#define BOOST_TEST_MODULE cylinder_wide_range
#include <boost/test/unit_test.hpp>

#include "../fuzz/recheck.hpp"
#include "certcyl/certified/line_cylinder.hpp"
#include "certcyl/certified/triangle_cylinder.hpp"
#include "test_cylinder_wide_range_cases.hpp"

#include <cmath>
#include <limits>
#include <random>

using namespace cctest;
using certcyl::Answer;

// The query on a case in both orders: f(a, b, swapped, result).
template <class F>
void for_both_orders(const WideCase& c, F f) {
  for (const bool swap : {false, true}) {
    const Cylinder<Q>& a = swap ? c.b : c.a;
    const Cylinder<Q>& b = swap ? c.a : c.b;
    f(a, b, swap, certcyl::certified_cylinder_cylinder(a, b));
  }
}

BOOST_AUTO_TEST_CASE(wide_range_pairs_are_all_decided_and_right) {
  int undecided = 0, checked = 0;
  for (const WideCase& c : wide_range_cases()) {
    for_both_orders(c, [&](const Cylinder<Q>& a, const Cylinder<Q>& b, bool swap, const certcyl::CylinderCylinderResult& r) {
      ++checked;
      BOOST_TEST_CONTEXT(c.name << (swap ? " swapped" : "")) {
        BOOST_TEST(certcyl::recheck::check_cylinder_pair(a, b, r) == "");
        undecided += r.answer == Answer::undecided;
        BOOST_TEST(r.answer == c.expected);
      }
    });
  }
  BOOST_TEST_MESSAGE(checked << " queries, " << undecided << " undecided");
  BOOST_TEST(undecided == 0);
  BOOST_TEST(checked > 1000);
}

// The short ellipsoid runs in the frames of the slab and tube bounds (ellipsoid_probe) and the
// corner candidates (detail/cylinder_corner_plane.hpp) decide the binary64 pairs of a huge and a
// tiny cylinder (scales 2^900 against 2^-900, and 2^960 against 2^-1000) off touching, in every
// contact type, before any Gmpfr round: without them these took Gmpfr rounds of 2,048 to 4,096
// bits or the ellipsoid stage's rounds (seconds). Asserted through the result: no Gmpfr round,
// and no ellipsoid step beyond the short runs (24 point and 24 direction steps at 128 bits).
BOOST_AUTO_TEST_CASE(corner_candidates_decide_huge_against_tiny_pairs) {
  int checked = 0;
  for (const WideCase& c : wide_range_cases()) {
    if (!c.binary64 || c.expected == Answer::touching) continue;
    if (c.name.find("ea=900 eb=-900") == std::string::npos && c.name.find("ea=960 eb=-1000") == std::string::npos) continue;
    for_both_orders(c, [&](const Cylinder<Q>& a, const Cylinder<Q>& b, bool swap, const certcyl::CylinderCylinderResult& r) {
      ++checked;
      BOOST_TEST_CONTEXT(c.name << (swap ? " swapped" : "") << ": stage " << certcyl::to_string(r.stage)) {
        BOOST_TEST(r.answer == c.expected);
        BOOST_TEST(certcyl::recheck::check_cylinder_pair(a, b, r) == "");
        if (r.stage == certcyl::CylinderStage::gmpfr || r.stage == certcyl::CylinderStage::ellipsoid) {
          BOOST_TEST(r.gmpfr_precision == 0);
          BOOST_TEST(r.counters.ellipsoid_steps <= 48u);
          BOOST_TEST(r.ellipsoid_precision <= 128);
        }
      }
    });
  }
  BOOST_TEST(checked >= 100);
}

// Exactly touching wide-range pairs are proved touching right after the corner candidates' first
// 1,024 bits (ellipsoid_probe): no Gmpfr round, no ellipsoid step, and no corner plane above
// 1,024 bits can decide a touching pair, so none runs. Before, every such pair spanning over
// 256 binades paid for the candidates up to 4,096 bits and 48 ellipsoid steps first (up to
// 35 ms a query at 2^900 against 2^-900).
BOOST_AUTO_TEST_CASE(touching_wide_range_pairs_are_proved_before_the_high_precisions) {
  int checked = 0;
  for (const WideCase& c : wide_range_cases()) {
    if (c.expected != Answer::touching) continue;
    for_both_orders(c, [&](const Cylinder<Q>&, const Cylinder<Q>&, bool swap, const certcyl::CylinderCylinderResult& r) {
      ++checked;
      BOOST_TEST_CONTEXT(c.name << (swap ? " swapped" : "") << ": stage " << certcyl::to_string(r.stage)) {
        BOOST_TEST(r.answer == Answer::touching);
        BOOST_TEST((r.stage == certcyl::CylinderStage::touching_exact));
        BOOST_TEST(r.gmpfr_precision == 0);
        BOOST_TEST(r.counters.ellipsoid_steps == 0u);
      }
    });
  }
  BOOST_TEST(checked >= 100);
}

// The other certified queries on the same operands: the line, ray and segment along b's axis
// and the triangle (b.p0, b.p1, a.p0) against a (a degenerate triangle is valid input). They
// must decide. The axis segment of b lies in b, and its points other than the ends are
// interior to b: if the pair is separated, so is the segment; if the segment overlaps a, so does
// the pair (a point of the segment interior to a can be moved along it, staying interior to a,
// off the ends). The segment lies in the ray, the ray in the line; a.p0 lies in a.
BOOST_AUTO_TEST_CASE(line_and_triangle_queries_decide_on_wide_range_operands) {
  int checked = 0;
  for (const WideCase& c : wide_range_cases()) {
    if (!c.binary64 && c.expected != Answer::touching) continue;  // the rational copies of the same operands
    const Cylinder<Q>& a = c.a;
    const Cylinder<Q>& b = c.b;
    const certcyl::Vec3<Q> axis = b.p1 - b.p0;
    BOOST_TEST_CONTEXT(c.name) {
      const auto line = certcyl::certified_line_cylinder(certcyl::Line<Q>{b.p0, axis}, a);
      const auto ray = certcyl::certified_line_cylinder(certcyl::Ray<Q>{b.p0, axis}, a);
      const auto segment = certcyl::certified_line_cylinder(certcyl::Segment<Q>{b.p0, b.p1}, a);
      BOOST_TEST(line.answer != Answer::undecided);
      BOOST_TEST(ray.answer != Answer::undecided);
      BOOST_TEST(segment.answer != Answer::undecided);
      if (c.expected == Answer::separated) BOOST_TEST(segment.answer == Answer::separated);
      if (segment.answer == Answer::overlapping) BOOST_TEST(c.expected == Answer::overlapping);
      if (line.answer == Answer::separated) BOOST_TEST(ray.answer == Answer::separated);
      if (ray.answer == Answer::separated) BOOST_TEST(segment.answer == Answer::separated);
      const auto t = certcyl::certified_triangle_cylinder(certcyl::Triangle<Q>{{b.p0, b.p1, a.p0}}, a);
      BOOST_TEST(t.answer != Answer::undecided);
      BOOST_TEST(t.answer != Answer::separated);
      ++checked;
    }
  }
  BOOST_TEST_MESSAGE(checked << " operand pairs");
  BOOST_TEST(checked > 100);
}

// Found by the pair fuzz harness: a needle of radius ~2^-1007 through the interior of a unit
// cylinder, tilted by ~2^-501, answered undecided at 1,024 bits although its own bounds gave
// phi* in [2, 3]. Its midpoint is interior to both, which the exact candidates now check.
BOOST_AUTO_TEST_CASE(fuzz_needle_is_overlapping) {
  const certcyl::Cylinder<double> a{{0, 0, 0}, {0, 0, 2}, 1};
  const certcyl::Cylinder<double> b{{-1, 0, 1}, {1, -0x1.0a0a0a0a0a09bp-501, -0x1.0a0a098a0a0a0p-501}, 0x1.201000030a02ap-1007};
  for (const bool swap : {false, true}) {
    const auto r = swap ? certcyl::certified_cylinder_cylinder(b, a) : certcyl::certified_cylinder_cylinder(a, b);
    BOOST_TEST(r.answer == Answer::overlapping);
    const auto to_q = [](double x) { return Q(x); };
    BOOST_TEST(certcyl::recheck::check_cylinder_pair(swap ? b.map(to_q) : a.map(to_q), swap ? a.map(to_q) : b.map(to_q), r) == "");
  }
}

// Found by a random wide-exponent run of the pair fuzz harness (7 s per query before the fitted
// frames): a needle a of radius 2^107 and length 2^859, ending near the origin, crossed by a
// pancake b of radius 2^566 and thickness 47.5 whose slab is tilted by 2/47.5 against the
// needle's end disc. By construction X = (-3.65625, 42031, 10^6) is interior to both:
// (X - b.p0).A_b is about 1176 in (0, A_b.A_b = 2260.25), X is about 10^6 from either axis, and
// (X - a.p1).A_a < 0 < (X - a.p0).A_a. In the frame of b's slab across a's tube the common
// interior fills a fixed part of the ball: the short runs decide it, with no Gmpfr round; the
// exact candidates' witnesses beside the caps now decide it before them.
BOOST_AUTO_TEST_CASE(needle_crossing_a_pancake_is_decided_without_a_gmpfr_round) {
  const certcyl::Cylinder<double> a{{-0x1.ap-2, 0x1.b971f3ec2802bp+859, -0x1.9996d1f70baf3p+658},
                                    {-0x1.d4p+1, 0x1.b8p-2, 0x1.fe0a370d2c607p-195}, 0x1.9727d283c561bp+107};
  const certcyl::Cylinder<double> b{{0x1.40e199c96f487p-146, -0x1.8cp+5, -0x1.7d0642a08f7b7p-925},
                                    {0x1.4c880de718d33p-32, -0x1.84p+6, 0x1p+1}, 0x1.9277ddd0b0cc6p+566};
  const auto to_q = [](double x) { return Q(x); };
  const Cylinder<Q> qa = a.map(to_q), qb = b.map(to_q);
  BOOST_REQUIRE(certcyl::detail::strictly_inside_both(certcyl::detail::CylinderPair<Q>::make(qa, qb),
                                                      certcyl::Point3<Q>{Q(-3.65625), Q(42031), Q(1000000)}));
  for (const bool swap : {false, true}) {
    const auto r = swap ? certcyl::certified_cylinder_cylinder(b, a) : certcyl::certified_cylinder_cylinder(a, b);
    BOOST_TEST_CONTEXT((swap ? "swapped: " : "") << "stage " << to_string(r.stage)) {
      BOOST_TEST(r.answer == Answer::overlapping);
      BOOST_TEST(certcyl::recheck::check_cylinder_pair(swap ? qb : qa, swap ? qa : qb, r) == "");
      BOOST_TEST((r.stage == certcyl::CylinderStage::ellipsoid || r.stage == certcyl::CylinderStage::gmpfr));
      BOOST_TEST(r.gmpfr_precision == 0);
      BOOST_TEST(r.counters.ellipsoid_steps <= 24u);
    }
  }
}

// Found by the pair fuzz harness run without a resource limit: a needle of subnormal radius
// (about 2^-1026) whose end p1 = (0, 2, -1) lies on a's cap plane inside its disc, its axis
// leaving a's slab: the common interior is a sliver of the needle's end disc (phi* - 1 about
// 2e-311). The Gmpfr rounds up to 4,096 bits left it undecided; the end-disc candidates prove
// it overlapping.
BOOST_AUTO_TEST_CASE(needle_ending_on_a_cap_is_overlapping) {
  const certcyl::Cylinder<double> a{{0, 2, 1}, {3, -1, 1}, 3};
  const certcyl::Cylinder<double> b{{0, 0x1.e8p+6, 0}, {0, 2, -1}, 0x0.100010000b8bfp-1022};
  const auto to_q = [](double x) { return Q(x); };
  for (const bool swap : {false, true}) {
    const auto r = swap ? certcyl::certified_cylinder_cylinder(b, a) : certcyl::certified_cylinder_cylinder(a, b);
    BOOST_TEST(r.answer == Answer::overlapping);
    BOOST_TEST(certcyl::recheck::check_cylinder_pair(swap ? b.map(to_q) : a.map(to_q), swap ? a.map(to_q) : b.map(to_q), r) == "");
  }
}

// Found by the pair fuzz harness: a pancake a (the disc of radius r = 0x1.1cp-1 about the z axis,
// thickness h about 1.5 2^-425) and a cylinder b of the same radius lying on a's lower cap plane
// z = 0, its axis at height r, with b's lower end p0 = (0, r, r) straight above the point
// Q = (0, r, 0) of a's rim. Q is on a's rim, on b's lowest line and on b's cap plane: the common
// interior is a wedge about Q some 2^-216 by 2^-212 by 2^-425. With u = b.p1 - b.p0 (horizontal)
// and v = (u_y, -u_x, 0), X = Q + 2^-216 u + 2^-214 v + 2^-426 e_z is interior to both: 0 < z < h;
// x^2 + y^2 - r^2 = 2 r (2^-216 u_y - 2^-214 u_x) + O(2^-428) < 0; X is in b's slab (axial
// 2^-216 |u|^2 > 0); and its squared distance from b's axis, (r - 2^-426)^2 + 2^-428 |v|^2, is
// below r^2 since |v|^2 < 4 r. The cap-disk candidate on b's cap plane at a's mid-height, on a's
// wall, moved toward a's axis within that plane (cap_disk_toward_axis), decides it before any
// Gmpfr round or ellipsoid step; before that candidate the Gmpfr rounds ran to 1,024 bits and
// the ellipsoid rounds decided it, some 200 ms a query (bench/RESULTS.md).
BOOST_AUTO_TEST_CASE(pancake_on_a_rim_wall_and_cap_edge_is_overlapping) {
  const double radius = 0x1.1cp-1;
  const certcyl::Cylinder<double> a{{0, 0, 0}, {0, 0, 0x1.8000001ffff2bp-425}, radius};
  const certcyl::Cylinder<double> b{{0, radius, radius}, {radius, 0x1.f8p-1, radius}, radius};
  const auto to_q = [](double x) { return Q(x); };
  const Cylinder<Q> qa = a.map(to_q), qb = b.map(to_q);
  const certcyl::Vec3<Q> u = qb.p1 - qb.p0, v{u.y, -u.x, Q(0)};
  const auto two_power = [](int k) { return certcyl::detail::times_two_power(Q(1), k); };
  const certcyl::Point3<Q> X = certcyl::Point3<Q>{Q(0), Q(radius), Q(0)} + two_power(-216) * u + two_power(-214) * v +
                               certcyl::Vec3<Q>{Q(0), Q(0), two_power(-426)};
  BOOST_REQUIRE(certcyl::detail::strictly_inside_both(certcyl::detail::CylinderPair<Q>::make(qa, qb), X));
  for (const bool swap : {false, true}) {
    const auto r = swap ? certcyl::certified_cylinder_cylinder(b, a) : certcyl::certified_cylinder_cylinder(a, b);
    BOOST_TEST(r.answer == Answer::overlapping);
    BOOST_TEST(certcyl::recheck::check_cylinder_pair(swap ? qb : qa, swap ? qa : qb, r) == "");
    BOOST_TEST(r.gmpfr_precision == 0);
    BOOST_TEST(r.ellipsoid_precision == 0);
  }
}

// A pair separated by construction: D is checked to separate them exactly, then the query in
// both orders must answer separated with a certificate the independent re-check accepts, and
// satisfy `more` (what the test is about: the stage, the precisions).
template <class More>
void check_separated_in_both_orders(const certcyl::Cylinder<double>& a, const certcyl::Cylinder<double>& b, const certcyl::Vec3<Q>& D,
                                    More&& more) {
  const auto to_q = [](double x) { return Q(x); };
  const Cylinder<Q> qa = a.map(to_q), qb = b.map(to_q);
  BOOST_REQUIRE(certcyl::detail::separation_sign(certcyl::detail::CylinderPair<Q>::make(qa, qb), D) == CGAL::POSITIVE);
  for (const bool swap : {false, true}) {
    const auto r = swap ? certcyl::certified_cylinder_cylinder(b, a) : certcyl::certified_cylinder_cylinder(a, b);
    BOOST_TEST_CONTEXT((swap ? "swapped: " : "") << "stage " << to_string(r.stage)) {
      BOOST_TEST(r.answer == Answer::separated);
      BOOST_TEST(certcyl::recheck::check_cylinder_pair(swap ? qb : qa, swap ? qa : qb, r) == "");
      more(r);
    }
  }
}

// Found by the pair fuzz harness: a needle a of radius about 2^-45 from (0, 0, 99) to
// (2, 22.5, 0.703125), and a disc b of radius 2.75 about (0, 0, 90), 2^-1008 thick along x.
// D = (50, 0, 1) separates them by construction: D.X <= 92.75 on b (x <= 0, z <= 92.75) and
// D.X >= 99 - 50 2^-44 on a (50 x + z = 99 + 1.70 t along a's axis, t in [0, 1]). In the world
// frame b's axis is about 2^-1014 long and its squared length underflows in double; the
// optimiser scales each axis by a power of two for its radial terms, so the double stages
// decide the pair (before, they failed and the ellipsoid stage decided it, some 10 ms a query).
BOOST_AUTO_TEST_CASE(needle_above_a_disc_thinner_than_the_double_range_is_decided_in_double) {
  const certcyl::Cylinder<double> a{{0, 0, 0x1.8cp+6}, {2, 0x1.68p+4, 0x1.68p-1}, 0x1.7d580d90001p-45};
  const certcyl::Cylinder<double> b{{0, 0, 0x1.68p+6}, {-0x1.fffffff2d01p-1008, 0, 0x1.68p+6}, 0x1.6p+1};
  check_separated_in_both_orders(a, b, {Q(50), Q(0), Q(1)}, [](const certcyl::CylinderCylinderResult& r) {
    BOOST_TEST((r.stage == certcyl::CylinderStage::optimiser || r.stage == certcyl::CylinderStage::refine));
  });
}

// A needle a of length about 2^701 and radius 2^-700 passing beside a short fat cylinder b
// (0 <= x <= 4, y^2 + z^2 <= 64): a's axis is x = 5 + 4y/L, z = 3 (L = 2^700), so at |y| <= 8,
// where b lies, it runs at x >= 5 - 32/L. D = (L, -4, 0) separates them by construction: D.X / L
// = x - 4y/L is 5 on a's axis (within 2^-699 on a) and at most 4 + 32/L on b. D is the part of
// b's axis orthogonal to a's; T, its parts orthogonal to the axes, the axes, A0 x A1 and the
// difference of the axes' closest points do not separate. The pattern of the slowest of 3,000
// random wide pairs (fuzz input format): before the exact candidates included the part of each
// axis orthogonal to the other, the ellipsoid stage's direction runs decided them (some 10 ms).
BOOST_AUTO_TEST_CASE(needle_beside_a_fat_cylinder_is_separated_by_an_axis_part_orthogonal_to_the_other) {
  const double L = 0x1p700;
  const certcyl::Cylinder<double> a{{9, L, 3}, {1, -L, 3}, 0x1p-700};
  const certcyl::Cylinder<double> b{{0, 0, 0}, {4, 0, 0}, 8};
  check_separated_in_both_orders(a, b, {Q(L), Q(-4), Q(0)}, [](const certcyl::CylinderCylinderResult& r) {
    BOOST_TEST(r.gmpfr_precision == 0);
    BOOST_TEST(r.ellipsoid_precision == 0);
  });
}

// Found by the pair fuzz harness (15 s and 6.5 s per query before): two overlapping pairs whose
// common interior is a sliver around a point of the larger cylinder's rim or cap, far too thin
// for the Gmpfr rounds below 8,192 bits.
//   Needle: a runs from p0 = (127, -M, s) (M about 2^1009, s subnormal) to the origin, radius 2;
//   b runs from (1, 0, 2) to (1, 2, 43), radius 3. With x = 10/M, y = 635/M^2 and z = 2 - 2y/41
//   + 1/M^3, X = (x, y, z) is interior to both: (X - b.p0).A_b = 41/M^3 > 0 and X is about 1 from
//   b's axis; X.(a.p0) = 127x - My + sz > 0, and X's squared distance from a's axis is about
//   x^2 + z^2 = 4 - (8y/41 - x^2) < 4.
//   Pancake: a runs from the origin to (0, -L, d) (L about 2^-228, d subnormal), radius 5.75; b
//   from (5.75, 1, 2) to (2.25, 1, 1), radius 1. X = (2.25 + 3.5/8, d/(2L), 1 + 1/8) lies 1/8
//   of b's axis in from b.p1 and d/(2L) above b's lowest line (so within 1 of b's axis), and
//   X.(a.p1) = d (1 + 1/8) - d/2 > 0, about 2.6 from a's axis.
// The corner candidates decide both before any Gmpfr round or ellipsoid step: the closed-form
// maximiser of the wedge's gain, the next plane through the witness found (the sliver of the
// pancake is where b's lowest line crosses a's rim, which the planes reach in a few passes), and
// precisions up to 4,096 bits.
BOOST_AUTO_TEST_CASE(corner_candidates_decide_slivers_at_a_rim_and_a_cap) {
  const auto to_q = [](double x) { return Q(x); };
  struct Sliver {
    const char* name;
    certcyl::Cylinder<double> a, b;
    certcyl::Point3<Q> witness;
  };
  const Q M(0x1.0ffffffffff2dp+1009), L(0x1.1b10100020021p-228), d(0x0.00006000000b1p-1022);
  const Q x = Q(10) / M, y = Q(635) / (M * M);
  const std::vector<Sliver> slivers = {
      {"needle", {{0x1.fcp+6, -0x1.0ffffffffff2dp+1009, 0x0.0008fffffffffp-1022}, {0, 0, 0}, 2}, {{1, 0, 2}, {1, 2, 43}, 3},
       {x, y, Q(2) - Q(2) * y / Q(41) + Q(1) / (M * M * M)}},
      {"pancake", {{0, 0, 0}, {0, -0x1.1b10100020021p-228, 0x0.00006000000b1p-1022}, 5.75}, {{5.75, 1, 2}, {2.25, 1, 1}, 1},
       {Q(2.25) + Q(3.5) / Q(8), d / (Q(2) * L), Q(1) + Q(1) / Q(8)}},
  };
  for (const Sliver& c : slivers) {
    const Cylinder<Q> qa = c.a.map(to_q), qb = c.b.map(to_q);
    BOOST_TEST_CONTEXT(c.name) {
      BOOST_REQUIRE(certcyl::detail::strictly_inside_both(certcyl::detail::CylinderPair<Q>::make(qa, qb), c.witness));
      for (const bool swap : {false, true}) {
        const auto r = swap ? certcyl::certified_cylinder_cylinder(c.b, c.a) : certcyl::certified_cylinder_cylinder(c.a, c.b);
        BOOST_TEST_CONTEXT((swap ? "swapped: " : "") << "stage " << to_string(r.stage)) {
          BOOST_TEST(r.answer == Answer::overlapping);
          BOOST_TEST(certcyl::recheck::check_cylinder_pair(swap ? qb : qa, swap ? qa : qb, r) == "");
          BOOST_TEST(r.gmpfr_precision == 0);
          BOOST_TEST(r.counters.ellipsoid_steps == 0u);
        }
      }
    }
  }
}

// Rationals of 5,000 digits: every base contact type, turned by a rational rotation, translated
// by 1/3, divided by 10^5000 + 1, exactly touching and moved 2^-20 either side. The Gmpfr rounds
// take their precision from the binades the geometry spans, not from the digits (once, from the
// digits, such a pair ran for minutes); all must be decided and right.
BOOST_AUTO_TEST_CASE(five_thousand_digit_pairs_are_decided) {
  CGAL::Gmpz z(std::string("1") + std::string(5000, '0'));
  z += 1;
  const Q D(z);
  const Rotation R = Rotation::from_quaternion(1, 2, 3, 4);
  const auto shrink = [&D](const Q& x) { return x / D; };
  for (const TouchingCase& base : base_touching_cases()) {
    for (const int side : {0, 1, -1}) {
      const Q d = Q(side) / Q(1 << 20);
      const Cylinder<Q> a = move(base.a, R, {Q(1, 3), 0, 0}).map(shrink);
      const Cylinder<Q> b = move(translate(base.b, d * base.normal), R, {Q(1, 3), 0, 0}).map(shrink);
      const Answer expected = side == 0 ? Answer::touching : (side > 0 ? Answer::separated : Answer::overlapping);
      const certcyl::CylinderCylinderResult r = certcyl::certified_cylinder_cylinder(a, b);
      BOOST_TEST_CONTEXT(base.name << " side " << side) {
        BOOST_TEST(r.answer == expected);
        BOOST_TEST(certcyl::recheck::check_cylinder_pair(a, b, r) == "");
        // The geometry spans a few binades: no round above the first ones (from the digits it
        // started at 32,768 bits).
        BOOST_TEST(r.gmpfr_precision <= 256);
      }
    }
  }
}

// Each base contact type, turned by a rational rotation, translated by t and moved
// eps along its contact normal either side: the answer must be right, its certificate must pass
// the independent re-check, and `check` asserts what a test adds. Returns the pairs checked.
template <class Check>
int check_moved_contacts(const Q& eps, const Vec3<Q>& t, Check&& check) {
  const Rotation R = Rotation::from_quaternion(1, 2, 3, 4);
  int checked = 0;
  for (const TouchingCase& base : base_touching_cases()) {
    for (const int side : {1, -1}) {
      const Cylinder<Q> a = move(base.a, R, t);
      const Cylinder<Q> b = move(translate(base.b, (Q(side) * eps) * base.normal), R, t);
      const Answer expected = side > 0 ? Answer::separated : Answer::overlapping;
      const certcyl::CylinderCylinderResult r = certcyl::certified_cylinder_cylinder(a, b);
      ++checked;
      BOOST_TEST_CONTEXT(base.name << " side " << side << " stage " << to_string(r.stage)) {
        BOOST_TEST(r.answer == expected);
        BOOST_TEST(certcyl::recheck::check_cylinder_pair(a, b, r) == "");
        check(r);
      }
    }
  }
  return checked;
}

// Every base contact type moved 10^-400 (far below any fixed precision: the Gmpfr rounds stop
// near 2^-1100 for this geometry) off touching, either side, with operands of a few hundred
// digits (turned by a rational rotation, translated by 1/3). The exact candidates decide ten of
// the fourteen: wall-wall crossings by the closest points of the axes (the r0:r1 point inside
// both, or c1 - c0 separating), the others by the axis directions and end-disc witnesses. Rim
// contacts moved into overlap (rim-cap, rim-wall, rim-rim) and rim-wall moved apart have no exact
// candidate: the corner candidates decide them (at 1,536 to 4,096 bits; they took the ellipsoid
// stage 1.8 to 7.5 s when the corner candidates stopped at 1,024 bits). Asserted: every answer
// right, and no Gmpfr round or ellipsoid step (the ellipsoid stage's rounded runs are tested on
// their own below).
BOOST_AUTO_TEST_CASE(pairs_ten_to_the_minus_400_off_touching) {
  CGAL::Gmpz z(std::string("1") + std::string(400, '0'));
  const int checked = check_moved_contacts(Q(1) / Q(z), {Q(1, 3), 0, 0}, [](const certcyl::CylinderCylinderResult& r) {
    BOOST_TEST(r.gmpfr_precision == 0);
    BOOST_TEST(r.counters.ellipsoid_steps == 0u);
  });
  BOOST_TEST(checked == 14);
}

// Every base contact type moved 2^-5000 off touching, either side, with operands of about a
// hundred digits: beyond the 4,096 bits the corner candidates stop at before the Gmpfr and
// ellipsoid rounds. The rim contacts need a corner plane at about 5,000 bits; the plane left
// short of bits goes on between the rounds (at least twice the input numbers' bit size, 64 times
// the ellipsoid's precision), before any ellipsoid step. When it stopped at 4,096 bits, the
// ellipsoid stage decided rim-cap after 232 s; when raising a plane's precision counted as one of
// its twelve planes (so rim-rim, whose planes converge like Newton's method on both rims and
// each need more bits, ran out of planes near 3,000 bits and kept no plane to resume), rim-rim
// 2^-4000 off touching took 66 and 90 s. Asserted: every answer right, and no ellipsoid step.
BOOST_AUTO_TEST_CASE(contacts_two_to_the_minus_5000_off_touching) {
  const Q shift(CGAL::Gmpz(std::string("1") + std::string(60, '0')) + 7, CGAL::Gmpz(std::string("3") + std::string(59, '0')) + 1);
  const int checked = check_moved_contacts(Q(1) / Q(CGAL::Gmpz(1) << 5000), {shift, Q(1, 3), 0},
                                           [](const certcyl::CylinderCylinderResult& r) { BOOST_TEST(r.counters.ellipsoid_steps == 0u); });
  BOOST_TEST(checked == 14);
}

namespace {

// The base contact types, turned and moved 2^-10 apart (side 1) or into each other (side -1).
std::pair<Cylinder<Q>, Cylinder<Q>> moved_pair(const TouchingCase& base, int side) {
  const Rotation R = Rotation::from_quaternion(1, 2, 3, 4);
  return {move(base.a, R, {Q(1, 3), 0, 0}), move(translate(base.b, (Q(side) * two_power(-10)) * base.normal), R, {Q(1, 3), 0, 0})};
}

template <int n>
certcyl::detail::DyadicVector<n> random_centre(std::mt19937_64& rng) {
  certcyl::detail::DyadicVector<n> y;
  y.s = 20;
  for (CGAL::Gmpz& U : y.U) U = CGAL::Gmpz(static_cast<long>(rng() % (2 << 20)) - (1L << 20));
  return y;
}

template <int n>
Q coordinate(const certcyl::detail::DyadicVector<n>& y, int i) {
  return Q(y.U[i]) * two_power(-y.s);
}

}  // namespace

// Lemma "cuts" of the paper's completeness proof, on each base contact type: a point cut at a
// centre outside P keeps the query's own (exactly checked) interior witness strictly on its side
// (c.(u* - y) < 0), and every minorant l <= phi, so that l(D*) < D*.Delta at the query's
// separating direction D*. Both exactly, at random centres.
BOOST_AUTO_TEST_CASE(ellipsoid_cuts_keep_their_targets) {
  using namespace certcyl::detail;
  std::mt19937_64 rng(7);
  int point_cuts = 0, minorants = 0;
  for (const TouchingCase& base : base_touching_cases()) {
    for (const int side : {1, -1}) {
      const auto [a, b] = moved_pair(base, side);
      const certcyl::CylinderCylinderResult r = certcyl::certified_cylinder_cylinder(a, b);
      BOOST_TEST_CONTEXT(base.name << " side " << side) {
        BOOST_REQUIRE(r.answer == (side > 0 ? Answer::separated : Answer::overlapping));
        const IntegerPair z(CylinderPair<Q>::make(a, b));
        for (const bool fitted : {false, true})
        if (side < 0) {
          const PointProblem points(z, fitted);
          const std::array<Q, 3> target = points.coordinates(*r.exact_witness());
          for (int t = 0; t < 300; ++t) {
            const DyadicVector<3> y = random_centre<3>(rng);
            const std::optional<EllipsoidCut<3>> k = points.cut(y, 128);
            if (!k) continue;  // a centre inside both: nothing to cut
            ++point_cuts;
            Q along = 0;
            for (int i = 0; i < 3; ++i) along += Q(k->C[i]) * (target[i] - coordinate<3>(y, i));
            BOOST_TEST(along < 0);
          }
        } else {
          const DirectionProblem directions(z, fitted);
          Vec3<Q> D = *r.exact_direction();
          const Vec3<Q> delta = z.delta.map([](const CGAL::Gmpz& x) { return Q(x); });
          if (dot(D, delta) < 0) D = -D;
          for (int t = 0; t < 300; ++t) {
            long sigma = 0, h = 0;
            const Vec3<CGAL::Gmpz> Ds = directions.direction(random_centre<2>(rng), sigma);
            const Vec3<Q> V = directions.minorant(Ds, 128, h).map([](const CGAL::Gmpz& x) { return Q(x); });
            ++minorants;
            // V 2^-h . D < D . Delta (integer frame)
            BOOST_TEST(dot(V, D) < two_power(h) * dot(D, delta));
          }
        }
      }
    }
  }
  BOOST_TEST(point_cuts > 2000);
  BOOST_TEST(minorants > 2000);
}

// The frames fitted to the slab and tube bounds (PointProblem, DirectionProblem with `fitted`)
// must hold their targets in the open unit ball, which the completeness proof assumes: the
// exactly checked interior witness, or separating direction, of every decided pair has
// coordinates of norm below 1, in the frame taken and in the ball and disc frames. Run on the
// wide-range pairs and on random binary64 pairs whose exponents spread over the whole range (the
// pair fuzz harness's kind of input: needles, pancakes, huge against tiny), where both kinds of
// fitted frame are taken.
BOOST_AUTO_TEST_CASE(fitted_frames_hold_their_targets) {
  using namespace certcyl::detail;
  std::vector<std::pair<Cylinder<Q>, Cylinder<Q>>> pairs;
  for (const WideCase& c : wide_range_cases())
    if (c.binary64 && c.expected != Answer::touching) pairs.emplace_back(c.a, c.b);
  std::mt19937_64 rng(11);
  const auto number = [&rng]() {
    if (rng() % 3 != 0) return std::ldexp(static_cast<double>(static_cast<int>(rng() % 256) - 128), -static_cast<int>(rng() % 8));
    return std::ldexp(std::ldexp(static_cast<double>(rng() >> 11), -53) * (rng() % 2 ? 1 : -1), static_cast<int>(rng() % 2000) - 1000);
  };
  for (int i = 0; i < 400; ++i) {
    std::array<Cylinder<Q>, 2> c;
    for (Cylinder<Q>& ci : c) {
      ci.p0 = {Q(number()), Q(number()), Q(number())};
      ci.p1 = {Q(number()), Q(number()), Q(number())};
      ci.radius = CGAL::abs(Q(number()));
    }
    if (c[0].radius > 0 && c[1].radius > 0 && !(c[0].p0 == c[0].p1) && !(c[1].p0 == c[1].p1)) pairs.emplace_back(c[0], c[1]);
  }
  int points = 0, directions = 0, fitted_points = 0, fitted_directions = 0;
  for (const auto& [a, b] : pairs) {
    const certcyl::CylinderCylinderResult r = certcyl::certified_cylinder_cylinder(a, b);
    BOOST_REQUIRE(r.answer != Answer::undecided);
    const IntegerPair z(CylinderPair<Q>::make(a, b));
    if (z.delta.x == 0 && z.delta.y == 0 && z.delta.z == 0) continue;
    for (const bool fitted : {false, true}) {
      if (r.exact_witness()) {
        const PointProblem frame(z, fitted);
        const std::array<Q, 3> u = frame.coordinates(*r.exact_witness());
        BOOST_TEST(u[0] * u[0] + u[1] * u[1] + u[2] * u[2] < 1);
        ++points;
        fitted_points += frame.fitted();
      }
      if (r.exact_direction()) {
        const DirectionProblem frame(z, fitted);
        const std::optional<std::array<Q, 2>> u = frame.coordinates(*r.exact_direction());
        BOOST_REQUIRE(u);
        BOOST_TEST((*u)[0] * (*u)[0] + (*u)[1] * (*u)[1] < 1);
        ++directions;
        fitted_directions += frame.fitted();
      }
    }
  }
  BOOST_TEST_MESSAGE(points << " witnesses (" << fitted_points << " in fitted frames), " << directions << " directions (" << fitted_directions << ")");
  BOOST_TEST(fitted_points >= 50);
  BOOST_TEST(fitted_directions >= 50);
}

// The rounded runs alone (the runs the completeness proof is about, p/8 steps at p bits, central
// cuts, entries rounded to p bits after the point) reach a certificate on each base contact type
// moved 2^-10 off touching, at some p <= 2^14: the point found is strictly inside both, the
// direction separates, each checked in Gmpq.
BOOST_AUTO_TEST_CASE(rounded_ellipsoid_runs_reach_certificates) {
  using namespace certcyl::detail;
  for (const TouchingCase& base : base_touching_cases()) {
    for (const int side : {1, -1}) {
      const auto [a, b] = moved_pair(base, side);
      const CylinderPair<Q> e = CylinderPair<Q>::make(a, b);
      const IntegerPair z(e);
      const PointProblem points(z, false);
      const DirectionProblem directions(z, false);
      bool found = false;
      long precision = 0;
      for (long p = 128; !found && p <= (1L << 14); p *= 2) {
        std::uint32_t steps = 0;
        precision = p;
        if (side < 0) {
          found = run_ellipsoid<3>(EllipsoidMode::rounded, p, p / 8, steps, [&](const DyadicVector<3>& y, long bits) -> std::optional<EllipsoidCut<3>> {
            std::optional<EllipsoidCut<3>> k = points.cut(y, bits);
            if (!k) BOOST_TEST(strictly_inside_both(e, points.point(y)));
            return k;
          });
        } else {
          found = run_ellipsoid<2>(EllipsoidMode::rounded, p, p / 8, steps, [&](const DyadicVector<2>& y, long bits) -> std::optional<EllipsoidCut<2>> {
            long sigma = 0;
            const Vec3<CGAL::Gmpz> Ds = directions.direction(y, sigma);
            const Vec3<Q> D = Ds.map([](const CGAL::Gmpz& x) { return Q(x); });
            if (separation_sign(e, D) == CGAL::POSITIVE) return std::nullopt;
            bool cuts_off = false;
            for (long w = bits;; w *= 2) {
              EllipsoidCut<2> k = directions.minorant_cut(Ds, sigma, w, p / 4, &cuts_off);
              if (cuts_off) return k;
            }
          });
        }
      }
      BOOST_TEST_CONTEXT(base.name << " side " << side << " p " << precision) { BOOST_TEST(found); }
    }
  }
}

// A run asks its stop predicate before each step (the query passes its time limit there): a
// predicate that says stop before the k-th step ends the run unfinished after k - 1 steps, with
// the oracle asked k - 1 times. The pair is separated (the first base contact moved off
// touching, side 1), so no centre is an interior point and the run would go on to its 64 steps.
BOOST_AUTO_TEST_CASE(an_ellipsoid_run_stops_before_the_step_its_predicate_refuses) {
  using namespace certcyl::detail;
  const auto [a, b] = moved_pair(base_touching_cases().front(), 1);
  const CylinderPair<Q> e = CylinderPair<Q>::make(a, b);
  const IntegerPair z(e);
  const PointProblem points(z, false);
  for (const long k : {1L, 2L, 5L}) {
    long asked = 0, oracle_calls = 0;
    std::uint32_t steps = 0;
    const bool found = run_ellipsoid<3>(
        EllipsoidMode::fast, 128, 64, steps,
        [&](const DyadicVector<3>& y, long bits) -> std::optional<EllipsoidCut<3>> {
          ++oracle_calls;
          std::optional<EllipsoidCut<3>> cut = points.cut(y, bits);
          BOOST_REQUIRE(cut);  // separated: no centre is interior to both
          return cut;
        },
        nullptr, 0, [&] { return ++asked == k; });
    BOOST_TEST_CONTEXT("stop before step " << k) {
      BOOST_TEST(!found);
      BOOST_TEST(asked == k);
      BOOST_TEST(oracle_calls == k - 1);
      BOOST_TEST(steps == static_cast<std::uint32_t>(k - 1));
    }
  }
}

// The optimiser asks its stop predicate before each Newton step (the Gmpfr rounds pass the
// query's time limit there): stopped before the k-th step, it returns after k - 1 steps.
BOOST_AUTO_TEST_CASE(the_optimiser_stops_before_the_newton_step_its_predicate_refuses) {
  using namespace certcyl::detail;
  const certcyl::Cylinder<double> a{{0, 0, 0}, {0, 0, 4}, 1}, b{{-2, 2.25, 1}, {2, 2.25, 3}, 1.25};
  const CylinderPair<double> d = CylinderPair<double>::make(a, b);
  const PlaneMinimum<double> full = PlaneProblem<double>(d, 44).minimise(true, 30);
  BOOST_REQUIRE(full.iterations >= 4);
  for (const int k : {1, 2, 4}) {
    int asked = 0;
    const PlaneMinimum<double> m = PlaneProblem<double>(d, 44).minimise(true, 30, [&] { return ++asked == k; });
    BOOST_TEST_CONTEXT("stop before step " << k) {
      BOOST_TEST(asked == k);
      BOOST_TEST(m.iterations == k - 1);
    }
  }
}

// Slivers that the exact candidates decide before the corner candidates, the touching proofs and
// the ellipsoid stage. b is a slab 2^40 deep below the plane z = 0, radius 2^900.
//   End in: a needle (radius 1/2, 2^125 long, tilted) whose end centre lies 2^-k below z = 0,
//   so inside b: overlapping. Decided by the end's step along a's axis, sized from the end's
//   depth in b (at most eight points checked; the corner candidates checked fourteen).
//   End out: the same needle upright (its end disk horizontal) ending 2^-k above z = 0:
//   separated.
//   Tube on the cap: a tube of radius 1/4 lying 2^-k above z = 0 along x, 2^601 long: its tube
//   reaches 1/4 - 2^-k into b: overlapping.
//   Two flat cylinders: a from (-2^744, 0, 0) to (-16, 0, 0), radius 2^752, and b from the
//   origin to (2^286, 2^-14, 0), radius 2^968. Near the axes the slabs x < -16 and 0 < x < 2^286
//   are apart, but W = (-2^400, 2^700 + 2^500, 0) has (W - b.p0).A_b = -2^686 + 2^686 + 2^486,
//   between 0 and A_b.A_b > 2^572, lies about 2^700 from both axes, and has -2^744 < W.x < -16:
//   overlapping. Decided by a point of a's cap disk inside b pushed into a, after the corner
//   candidates and before any ellipsoid step (the short runs decided it before).
BOOST_AUTO_TEST_CASE(slivers_beside_a_cap_are_decided_by_the_exact_candidates) {
  const auto two = [](int e) { return std::ldexp(1.0, e); };
  const certcyl::Cylinder<double> slab{{0, 0, -two(40)}, {0, 0, 0}, two(900)};
  const auto to_q = [](double x) { return Q(x); };
  const auto both_orders = [&](const certcyl::Cylinder<double>& a, const certcyl::Cylinder<double>& b, Answer expected, auto&& extra) {
    for (const bool swap : {false, true}) {
      const certcyl::Cylinder<double>& x = swap ? b : a;
      const certcyl::Cylinder<double>& y = swap ? a : b;
      const auto r = certcyl::certified_cylinder_cylinder(x, y);
      BOOST_TEST_CONTEXT((swap ? "swapped" : "in order") << ", points checked " << r.counters.points_checked) {
        BOOST_TEST(r.answer == expected);
        BOOST_TEST(certcyl::recheck::check_cylinder_pair(x.map(to_q), y.map(to_q), r) == "");
        extra(r);
      }
    }
  };
  const auto nothing = [](const certcyl::CylinderCylinderResult&) {};
  for (const int k : {100, 400, 1000}) {
    BOOST_TEST_CONTEXT("k = " << k) {
      const double d = two(-k);
      both_orders({{two(-30), 3, two(125)}, {1, 2, -d}, 0.5}, slab, Answer::overlapping, [](const certcyl::CylinderCylinderResult& r) {
        BOOST_TEST(r.counters.points_checked <= 8u);
        BOOST_TEST(r.counters.ellipsoid_steps == 0u);
      });
      both_orders({{1, 2, two(125)}, {1, 2, d}, 0.5}, slab, Answer::separated, nothing);
      both_orders({{-two(600), 1, d}, {two(601), 3, d}, 0.25}, slab, Answer::overlapping, nothing);
    }
  }
  both_orders({{-two(744), 0, 0}, {-16, 0, 0}, two(752)}, {{0, 0, 0}, {two(286), two(-14), 0}, two(968)}, Answer::overlapping,
              [](const certcyl::CylinderCylinderResult& r) {
                BOOST_TEST((r.stage == certcyl::CylinderStage::gmpfr));
                BOOST_TEST(r.gmpfr_precision == 0);
                BOOST_TEST(r.counters.ellipsoid_steps == 0u);
              });
}

// A wall sunk 2^-1035 into a tilted cap (found by the pair fuzz harness, and took seconds in
// the ellipsoid stage at 2,048 bits). a is the unit cylinder from (eps, 0, 0) to (0, 0, 2),
// eps = 0x0.000fffb0008p-1022 (about 2^-1034): its cap plane z = 2 + eps x / 2 rises above
// z = 2 for x > 0. b (radius 1, axis from (-1, 96, 3) to (1, 0, 3)) has its lowest line in
// z = 2, and that line crosses a's cap disk near (1, 0, 2): there b dips about 2^-1035 below
// a's cap: overlapping. Decided by the cap-disk point nearest a's centre on b's axis projected
// onto a's cap plane, pushed into a: no Gmpfr round, no ellipsoid step.
BOOST_AUTO_TEST_CASE(a_wall_sunk_into_a_tilted_cap_is_decided_by_the_exact_candidates) {
  const double eps = 0x0.000fffb0008p-1022;
  const auto to_q = [](double x) { return Q(x); };
  const certcyl::Cylinder<double> a{{eps, 0, 0}, {0, 0, 2}, 1};
  const certcyl::Cylinder<double> b{{-1, 96, 3}, {1, 0, 3}, 1};
  for (const bool swap : {false, true}) {
    const certcyl::Cylinder<double>& x = swap ? b : a;
    const certcyl::Cylinder<double>& y = swap ? a : b;
    const auto r = certcyl::certified_cylinder_cylinder(x, y);
    BOOST_TEST_CONTEXT((swap ? "swapped" : "in order") << ", stage " << certcyl::to_string(r.stage)) {
      BOOST_TEST(r.answer == Answer::overlapping);
      BOOST_TEST(certcyl::recheck::check_cylinder_pair(x.map(to_q), y.map(to_q), r) == "");
      BOOST_TEST((r.stage == certcyl::CylinderStage::gmpfr));
      BOOST_TEST(r.gmpfr_precision == 0);
      BOOST_TEST(r.counters.ellipsoid_steps == 0u);
    }
  }
}

// Rims dipping into the other cylinder far below an ulp (found by the pair fuzz harness, 1 to 2 s
// per query in the ellipsoid stage at 2,048 bits before the rim points nearest the other's axis
// were candidates).
//   Needles: a is the y axis from the origin to (0, 2^422, 0), radius 45/2; b runs from
//   (2^422, 35/4, 45/2) to its end p1 = (45/2, 45/2, 45/2), radius 45/2, so its cap disk at p1
//   touches a's wall x^2 + z^2 = (45/2)^2 at (45/2, 45/2, 0), and its cap plane D.(X - p1) = 0,
//   D = (2^422 - 45/2, -55/4, 0), is tilted by about 2^-422 toward a. With k = (55/4) / (2^422 -
//   45/2), eta = 2^-140 and zeta = 2^-280, the point X = p1 + (-k eta, -eta, zeta - 45/2) lies
//   on the cap plane, in the open disk (|X - p1|^2 = (1 + k^2) eta^2 + (45/2 - zeta)^2 < (45/2)^2
//   since (1 + k^2) 2^-280 + 2^-560 < 45 2^-280), and inside a: x^2 + z^2 = (45/2 - k eta)^2 +
//   zeta^2 < (45/2)^2 since zeta^2 = 2^-560 < 45 k eta - k^2 eta^2 (about 154 2^-560). So
//   X + (2^-570, 0, 0), which is strictly behind b's cap plane and moves x^2 by about 45 2^-570,
//   is interior to both: overlapping.
//   Quarter: rim_line_tangent_400 of bench_cylinder_wide_range with b's end moved from x = r to
//   x = -1/4, where b's lowest line crosses a's tilted cap plane beside a's rim at x = -1/4
//   (answer checked by its certificate only).
// Both are decided by the candidates (no Gmpfr round, no ellipsoid step), in both orders.
BOOST_AUTO_TEST_CASE(rims_dipping_below_an_ulp_are_decided_by_the_rim_points_nearest_the_axis) {
  const auto to_q = [](double x) { return Q(x); };
  const double r = 0x1.38p-2;
  const certcyl::Cylinder<double> needle_a{{0, 0, 0}, {0, 0x1p+422, 0}, 22.5};
  const certcyl::Cylinder<double> needle_b{{0x1p+422, 8.75, 22.5}, {22.5, 22.5, 22.5}, 22.5};
  {
    const Q k = Q(55, 4) / (Q(0x1p+422) - Q(45, 2)), eta = Q(0x1p-140), zeta = Q(0x1p-280);
    const certcyl::Point3<Q> X{Q(45, 2) - k * eta + Q(0x1p-570), Q(45, 2) - eta, zeta};
    BOOST_REQUIRE(certcyl::detail::strictly_inside_both(
        certcyl::detail::CylinderPair<Q>::make(needle_a.map(to_q), needle_b.map(to_q)), X));
  }
  const certcyl::Cylinder<double> quarter_a{{0, 0, 0x1.8cp+6}, {2, -0x1.01414fb0000fap+401, 0x1.72727275a27d5p-397}, r};
  const certcyl::Cylinder<double> quarter_b{{r, 0, 0x1.00002p+417}, {-0.25, r, r}, r};
  const std::vector<std::tuple<const char*, certcyl::Cylinder<double>, certcyl::Cylinder<double>>> pairs = {
      {"needles", needle_a, needle_b}, {"quarter", quarter_a, quarter_b}};
  for (const auto& [name, a, b] : pairs) {
    for (const bool swap : {false, true}) {
      const certcyl::Cylinder<double>& x = swap ? b : a;
      const certcyl::Cylinder<double>& y = swap ? a : b;
      const auto res = certcyl::certified_cylinder_cylinder(x, y);
      BOOST_TEST_CONTEXT(name << (swap ? ", swapped" : "") << ", stage " << certcyl::to_string(res.stage)) {
        BOOST_TEST(res.answer == Answer::overlapping);
        BOOST_TEST(certcyl::recheck::check_cylinder_pair(x.map(to_q), y.map(to_q), res) == "");
        BOOST_TEST(res.gmpfr_precision == 0);
        BOOST_TEST(res.counters.ellipsoid_steps == 0u);
      }
    }
  }
}

// The caller's time limit (CylinderCylinderOptions::time_limit_seconds, off by default): the
// needles of the case above overlap (their common point X is checked exactly there), and the
// query decides them only after the optimiser, so with a limit that has run out before the first
// check the answer is undecided with time_limit_reached, and without one it is overlapping. Two
// unit cylinders 10 apart are decided by the midpoints and fast-path stages, before any check:
// the limit leaves them decided.
BOOST_AUTO_TEST_CASE(a_time_limit_that_runs_out_answers_undecided_and_says_so) {
  const certcyl::Cylinder<double> needle_a{{0, 0, 0}, {0, 0x1p+422, 0}, 22.5};
  const certcyl::Cylinder<double> needle_b{{0x1p+422, 8.75, 22.5}, {22.5, 22.5, 22.5}, 22.5};
  certcyl::CylinderCylinderOptions limited;
  limited.time_limit_seconds = 1e-9;
  const auto stopped = certcyl::certified_cylinder_cylinder(needle_a, needle_b, limited);
  BOOST_TEST(stopped.answer == Answer::undecided);
  BOOST_TEST(stopped.time_limit_reached);
  BOOST_TEST((stopped.stage == certcyl::CylinderStage::none));
  const auto decided = certcyl::certified_cylinder_cylinder(needle_a, needle_b);
  BOOST_TEST(decided.answer == Answer::overlapping);
  BOOST_TEST(!decided.time_limit_reached);
  // A limit far beyond any clock (taken as 10^9 s) and NaN (no limit) leave the needles decided.
  for (const double huge : {1e300, std::numeric_limits<double>::quiet_NaN()}) {
    certcyl::CylinderCylinderOptions o;
    o.time_limit_seconds = huge;
    const auto r = certcyl::certified_cylinder_cylinder(needle_a, needle_b, o);
    BOOST_TEST(r.answer == Answer::overlapping);
    BOOST_TEST(!r.time_limit_reached);
  }
  const certcyl::Cylinder<double> unit_a{{0, 0, 0}, {0, 0, 1}, 1}, unit_b{{10, 0, 0}, {10, 0, 1}, 1};
  const auto quick = certcyl::certified_cylinder_cylinder(unit_a, unit_b, limited);
  BOOST_TEST(quick.answer == Answer::separated);
  BOOST_TEST(!quick.time_limit_reached);
}

// The caller's stop predicate (CylinderCylinderOptions::stop), asked at the time limit's checks
// with stop_context: on the needles above, one that says stop at once leaves them undecided with
// stopped set (and not time_limit_reached); one that never does is asked and leaves them
// overlapping; the unit cylinders are decided before any check, so it is never asked.
BOOST_AUTO_TEST_CASE(a_stop_predicate_that_says_stop_answers_undecided_and_says_so) {
  const certcyl::Cylinder<double> needle_a{{0, 0, 0}, {0, 0x1p+422, 0}, 22.5};
  const certcyl::Cylinder<double> needle_b{{0x1p+422, 8.75, 22.5}, {22.5, 22.5, 22.5}, 22.5};
  struct Asked {
    bool answer;
    int calls = 0;
  };
  const auto ask = [](void* context) {
    auto* a = static_cast<Asked*>(context);
    ++a->calls;
    return a->answer;
  };
  Asked stop{true}, go_on{false};
  certcyl::CylinderCylinderOptions o;
  o.stop = ask;
  o.stop_context = &stop;
  const auto stopped = certcyl::certified_cylinder_cylinder(needle_a, needle_b, o);
  BOOST_TEST(stopped.answer == Answer::undecided);
  BOOST_TEST(stopped.stopped);
  BOOST_TEST(!stopped.time_limit_reached);
  BOOST_TEST(stop.calls == 1);  // once true, the query does not ask again
  o.stop_context = &go_on;
  const auto decided = certcyl::certified_cylinder_cylinder(needle_a, needle_b, o);
  BOOST_TEST(decided.answer == Answer::overlapping);
  BOOST_TEST(!decided.stopped);
  BOOST_TEST(go_on.calls > 0);
  const certcyl::Cylinder<double> unit_a{{0, 0, 0}, {0, 0, 1}, 1}, unit_b{{10, 0, 0}, {10, 0, 1}, 1};
  Asked quick_stop{true};
  o.stop_context = &quick_stop;
  const auto quick = certcyl::certified_cylinder_cylinder(unit_a, unit_b, o);
  BOOST_TEST(quick.answer == Answer::separated);
  BOOST_TEST(!quick.stopped);
  BOOST_TEST(quick_stop.calls == 0);
}
