// Shared by the test_eberly_*.cpp files: the named cases and an independent separation check.
#pragma once

#include <string>
#include <vector>

#include "certcyl/number_traits.hpp"
#include "certcyl/number_traits_core.hpp"
#include "certcyl/primitives.hpp"
#include "certcyl/rational.hpp"
#include "certcyl/seeds/eberly_cylinders.hpp"

namespace eberly_test {

using namespace certcyl;

inline Rational q(long n, long d = 1) { return Rational(n, d); }
inline Vec3<Rational> v(Rational x, Rational y, Rational z) { return {x, y, z}; }

// The seed's form (C, unit W, r, h) as an exact Cylinder {C - (h/2) W, C + (h/2) W, r}.
inline Cylinder<Rational> seed_cylinder(Vec3<Rational> C, Vec3<Rational> W, Rational r, Rational h) {
  return Cylinder<Rational>::from_center_axis(C, W, r, h);
}

// phi(D) - |D.Delta| for Cylinder {p0, p1, r} (design note, section 4), written from the
// support function h_K(D) = D.m + |D.A|/2 + r |D x A|/|A| and not from the seed's formulas:
// negative exactly when D separates, zero when the projections touch.
template <class NT>
NT support_gap(const Cylinder<NT>& a, const Cylinder<NT>& b, const Vec3<NT>& D) {
  const NT two = nt::constant<NT>(2);
  const Vec3<NT> A0 = a.axis(), A1 = b.axis();
  const Vec3<NT> Delta = (b.p0 + b.p1) / two - (a.p0 + a.p1) / two;
  auto radial = [&](const Vec3<NT>& A, const NT& r) {
    return r * nt::sqrt(NT(squared_length(cross(D, A)) / squared_length(A)));
  };
  return nt::abs(dot(D, A0)) / two + nt::abs(dot(D, A1)) / two + radial(A0, a.radius) + radial(A1, b.radius) -
         nt::abs(dot(D, Delta));
}

// A named pair whose answer is known by construction (the comment of each case derives it).
struct Case {
  std::string name;
  Cylinder<Rational> c0, c1;
  Answer answer;        // the true answer
  EberlyTest test;      // the corrected variant's first test that finds it (none: overlapping)
  Answer as_written;    // the as-written variant's answer in exact arithmetic
  EberlyTest as_written_test;
  // Checked exactly by the tests: a separating direction (separated), a point interior to
  // both (overlapping), a direction whose projections touch (touching).
  Vec3<Rational> certificate;
};

inline const Vec3<Rational> X = v(1, 0, 0), Y = v(0, 1, 0), Z = v(0, 0, 1), O = v(0, 0, 0);

inline std::vector<Case> known_cases() {
  std::vector<Case> cs;
  // W0 only. A wide disk (axis z, r 10, h 2: top cap at z = 1) under a tilted rod
  // (W1 = (4/5, 0, 3/5), r 1/2, h 10) centred at height 5:
  //   f(W0) = r1 |W0xW1| + h0/2 + (h1/2)|W0.W1| - |W0.Delta| = 2/5 + 1 + 3 - 5 = -3/5;
  //   f(W1) = 8 + 3/5 + 5 - 3 > 0; W0 x W1 is perpendicular to Delta; every D perpendicular to
  //   W0 is perpendicular to Delta; perpendicular to W1, min f = 3.3 (D = (-3/5, 0, 4/5)).
  const Cylinder<Rational> disk = seed_cylinder(O, Z, 10, 2);
  const Cylinder<Rational> rod = seed_cylinder(v(0, 0, 5), v(q(4, 5), 0, q(3, 5)), q(1, 2), 10);
  cs.push_back({"w0_only", disk, rod, Answer::separated, EberlyTest::w0, Answer::separated, EberlyTest::w0, Z});
  cs.push_back({"w1_only", rod, disk, Answer::separated, EberlyTest::w1, Answer::separated, EberlyTest::w1, Z});

  // W0 x W1. Two rods (r 1, h 10) along x and y, the second 3 above the first:
  //   f(W0 x W1) = (r0 + r1) - 3 = -1, f(W0) = f(W1) = 1 + 5 > 0.
  cs.push_back({"w0xw1", seed_cylinder(O, X, 1, 10), seed_cylinder(v(0, 0, 3), Y, 1, 10), Answer::separated,
                EberlyTest::w0xw1, Answer::separated, EberlyTest::w0xw1, Z});

  // Perpendicular to W0 only. A long rod (axis z, r 1, h 20) and a disk (W1 = (3/5, 0, 4/5),
  // r 3, h 1/2) at Delta = (16/5, 16/5, 0). D = (1, 1, 0)/sqrt2 gives
  //   f = 1 + 3 sqrt(41/50) + (1/4)(3/(5 sqrt2)) - (16/5) sqrt2 = -0.70;
  //   f(W0) = 9/5 + 10 > 0, f(W1) = 3/5 + 8 + 1/4 - 48/25 > 0, f(W0 x W1 = y dir) = 1 + 3 - 16/5 > 0,
  //   perpendicular to W1 the minimum is 0.8 (D = y). The separating directions form an arc
  //   of the second quarter circle around 45 degrees; on the first quarter (U0 = -y, V0 = x),
  //   (1-t) a2 + t b2 changes sign at t = 1/2 and F'(0) = 2.55 > 0, so the as-written code
  //   returns false before the second quarter: its perpendicular test misses, and only its
  //   other-direction search separates.
  const Cylinder<Rational> long_rod = seed_cylinder(O, Z, 1, 20);
  const Cylinder<Rational> tilted_disk = seed_cylinder(v(q(16, 5), q(16, 5), 0), v(q(3, 5), 0, q(4, 5)), 3, q(1, 2));
  cs.push_back({"perpendicular_w0_only", long_rod, tilted_disk, Answer::separated, EberlyTest::perpendicular_w0,
                Answer::separated, EberlyTest::other_directions, v(1, 1, 0)});
  cs.push_back({"perpendicular_w1_only", tilted_disk, long_rod, Answer::separated, EberlyTest::perpendicular_w1,
                Answer::separated, EberlyTest::other_directions, v(1, 1, 0)});

  // Other directions only (found by a numerical search, then checked): a disk (axis z, r 3/2,
  // h 3/2) and a disk (W1 = (0, -4/5, 3/5), r 2, h 3/2) at Delta = (3, 1/2, -5/2).
  // f(W0) = 0.3, f(W1) = 0.5, f(W0 x W1) = 0.5, min over the circle perpendicular to W0
  // 0.50, to W1 0.22; min over the sphere -0.28 near D = (0.78, 0.07, -0.62) (the test
  // checks the rational D = (4/5, 0, -3/5) exactly).
  cs.push_back({"other_directions_only", seed_cylinder(O, Z, q(3, 2), q(3, 2)),
                seed_cylinder(v(3, q(1, 2), q(-5, 2)), v(0, q(-4, 5), q(3, 5)), 2, q(3, 2)), Answer::separated,
                EberlyTest::other_directions, Answer::separated, EberlyTest::other_directions, v(4, 0, -3)});

  // Parallel, by height: coaxial-ish (offset 1/2) r 1, h 2, 3 apart along z: 2 - 3 < 0, radial 2 - 1/2 > 0.
  cs.push_back({"parallel_height", seed_cylinder(O, Z, 1, 2), seed_cylinder(v(q(1, 2), 0, 3), Z, 1, 2),
                Answer::separated, EberlyTest::parallel_height, Answer::separated, EberlyTest::parallel_height, Z});
  // Parallel, radially: side by side 3 apart, heights overlapping (offset 1/2).
  cs.push_back({"parallel_radial", seed_cylinder(O, Z, 1, 2), seed_cylinder(v(3, 0, q(1, 2)), Z, 1, 2),
                Answer::separated, EberlyTest::parallel_radial, Answer::separated, EberlyTest::parallel_radial, X});

  // Overlapping: crossing rods 1 apart (r 1): (0, 0, 1/2) is interior to both.
  cs.push_back({"crossing_rods_overlap", seed_cylinder(O, X, 1, 10), seed_cylinder(v(0, 0, 1), Y, 1, 10),
                Answer::overlapping, EberlyTest::none, Answer::overlapping, EberlyTest::none, v(0, 0, q(1, 2))});
  // Overlapping: the disk and rod of w0_only with the rod lowered to height 3 (its lowest
  // axis passes through the disk): the axis point (-16/5, 0, 3/5) is interior to both.
  cs.push_back({"disk_rod_overlap", disk, seed_cylinder(v(0, 0, 3), v(q(4, 5), 0, q(3, 5)), q(1, 2), 10),
                Answer::overlapping, EberlyTest::none, Answer::overlapping, EberlyTest::none, v(q(-16, 5), 0, q(3, 5))});
  // Overlapping: the other_directions_only pair moved halfway towards each other; the
  // midpoint of the centres (3/4, 1/8, -5/8) is interior to both.
  cs.push_back({"disks_overlap", seed_cylinder(O, Z, q(3, 2), q(3, 2)),
                seed_cylinder(v(q(3, 2), q(1, 4), q(-5, 4)), v(0, q(-4, 5), q(3, 5)), 2, q(3, 2)), Answer::overlapping,
                EberlyTest::none, Answer::overlapping, EberlyTest::none, v(q(3, 4), q(1, 8), q(-5, 8))});
  // Overlapping, parallel: coaxial, overlapping in height.
  cs.push_back({"parallel_overlap", seed_cylinder(O, Z, 1, 2), seed_cylinder(v(q(1, 2), 0, 1), Z, 1, 2),
                Answer::overlapping, EberlyTest::none, Answer::overlapping, EberlyTest::none, v(q(1, 4), 0, q(1, 2))});
  // Overlapping, same centre (Delta = 0).
  cs.push_back({"same_centre", seed_cylinder(O, Z, 1, 2), seed_cylinder(O, v(q(3, 5), 0, q(4, 5)), q(1, 2), 3),
                Answer::overlapping, EberlyTest::delta_zero, Answer::overlapping, EberlyTest::none, O});

  // Touching, parallel cap on cap: height 2 - 2 = 0, radial 2 - 1/2 > 0. As written (strict
  // top-level test): not separated.
  cs.push_back({"touching_cap_cap", seed_cylinder(O, Z, 1, 2), seed_cylinder(v(q(1, 2), 0, 2), Z, 1, 2),
                Answer::touching, EberlyTest::parallel_height, Answer::overlapping, EberlyTest::none, Z});
  // Touching, wall on wall: rods along x and y, 2 apart (r 1): f(W0 x W1) = 0. As written the
  // strict W0xW1 test fails, then the perpendicular test, non-strict, finds F(0) = f(-z) = 0
  // and says separated.
  cs.push_back({"touching_wall_wall", seed_cylinder(O, X, 1, 10), seed_cylinder(v(0, 0, 2), Y, 1, 10),
                Answer::touching, EberlyTest::w0xw1, Answer::separated, EberlyTest::perpendicular_w0, Z});
  // Touching, wall on cap: a rod (axis x, r 1, h 4) lying on the top cap (z = 1) of a
  // cylinder (axis z, r 1, h 2): f(W0) = 1 + 1 - 2 = 0. As written: W0 strict fails, the
  // perpendiculars of W0 return early (F'(0) = 0), those of W1 find F(1) = f(z) = 0 <= 0.
  cs.push_back({"touching_wall_cap", seed_cylinder(O, Z, 1, 2), seed_cylinder(v(0, 0, 2), X, 1, 4),
                Answer::touching, EberlyTest::w0, Answer::separated, EberlyTest::perpendicular_w1, Z});
  return cs;
}

// The tests whose direction sets contain those of `t` (so they separate whenever `t` does).
inline std::vector<EberlyTest> containing(EberlyTest t) {
  switch (t) {
    case EberlyTest::w0xw1:
      return {EberlyTest::perpendicular_w0, EberlyTest::perpendicular_w1, EberlyTest::other_directions};
    case EberlyTest::w0:
    case EberlyTest::w1:
    case EberlyTest::perpendicular_w0:
    case EberlyTest::perpendicular_w1: return {EberlyTest::other_directions};
    default: return {};
  }
}

inline constexpr EberlyTest all_tests[] = {EberlyTest::w0,
                                           EberlyTest::w1,
                                           EberlyTest::w0xw1,
                                           EberlyTest::perpendicular_w0,
                                           EberlyTest::perpendicular_w1,
                                           EberlyTest::other_directions,
                                           EberlyTest::parallel_height,
                                           EberlyTest::parallel_radial};

// Parameters light enough for CORE::Expr.
inline EberlyParameters light(EberlyParameters p) {
  p.perpendicular_bisections = 12;
  p.line_search_bisections = 12;
  p.max_line_searches = 6;
  return p;
}

}  // namespace eberly_test
