// certcyl/seeds/eberly_cylinders.hpp -- Eberly's separating-axis test for two solid cylinders
// ("Intersection of Cylinders", Geometric Tools, 2000/2017; the seed
// eberly-intersection-of-cylinders.md), as written and as corrected, generic over the number
// type. This is the floating-point algorithm the project measures; it is NOT certified: its
// answer is only as good as its bisections, its minimiser and its number type.
//
// Semantics. Cylinder i has centre C_i, unit axis W_i, radius r_i, height h_i (seed section 2),
// solid and closed. With Delta = C1 - C0 and P_i = I - W_i W_i^T, a direction D separates when
//   f(D) = r0 |P0 D| + r1 |P1 D| + (h0/2)|D.W0| + (h1/2)|D.W1| - |D.Delta|   (equation (6))
// is negative (f(D) = 0: the projections touch). The algorithm tests, in this order
// (SeparatedCylinders, section 8): if |W0 x W1| > 0, the directions W0, W1, W0 x W1, the
// directions perpendicular to W0, those perpendicular to W1 (bisection on F', section 6,
// detail/eberly_perpendiculars.hpp), then the other directions (a 2-D minimiser of the convex
// G(s,t) over four octant triangles, section 7, detail/eberly_other_directions.hpp); if the
// axes are parallel, separation by height and radially. It returns at the first test that
// separates.
//
// Entries:
//   eberly_separated(C0, W0, r0, h0, C1, W1, r1, h1, params)   the seed's form, in NT
//   eberly_separated(cylinder0, cylinder1, params)             Cylinder<NT> {p0, p1, radius}:
//       C = (p0 + p1)/2, h = |p1 - p0| (nt::sqrt), W = (p1 - p0)/h
// The square roots exclude the rational types (Gmpq, Mpzf, Lazy_exact_nt<Gmpq>): CORE::Expr is
// the exact type that runs this algorithm. Interval_nt runs either decide every comparison
// (and then take exactly the path CORE::Expr takes, so they return the same result) or throw
// CGAL::Uncertain_conversion_exception; run them under CGAL::Protect_FPU_rounding<true>.
// Preconditions: r_i > 0, h_i > 0, |W_i| = 1 (to the precision of NT; W is not renormalised).
//
// The result: the seed's boolean, a three-valued answer (the corrected variant reports
// touching when a test found f(D) = 0 and none found f(D) < 0; as written, the answer only
// restates the boolean), the direction found, which test found it, and evaluation counts.
//
// Where the pseudocode needed a decision (variant as_written keeps the pseudocode; corrected
// fixes it; every other choice is an EberlyParameters field):
//  1. Mixed strictness: `< 0` at the top level (W0, W1, W0 x W1, height, radial), `<= 0` in the
//     perpendicular tests and in "G <= 0" for the other directions; section 3.1 says equality
//     is allowed. As written keeps the mix; corrected uses `< 0` everywhere and reports
//     f(D) = 0 as touching. Each site's strictness is a parameter.
//  2. SeparatedByCylinderPerpendiculars returns false after the first quarter circle whenever
//     F'(0) >= 0 or F'(1) <= 0, so the quarter (-U0, V0) is then never tested. Corrected tests
//     both quarters.
//  3. F is not convex on a quarter circle: -|(1-t) a2 + t b2| has a concave kink inside (0,1)
//     when a2 b2 < 0, so F may have two local minima, F'(0) >= 0 does not make F(0) the
//     minimum, and bisection on F' may converge to the wrong one. Corrected splits the quarter
//     at the kink (where F > 0) and minimises each convex piece. (Equation (10) also has 3 r0
//     for r0; harmless, the omitted kink is not.)
//  4. The second quarter's code ends without a return statement: it returns false.
//  5. maxIterations is undefined: `perpendicular_bisections`. `c1sqr` / `c1Sqr` is one variable.
//  6. F'(1) divides 0 by 0 when the axes are perpendicular (c1 = 0). As written, the value is
//     undefined and compared as IEEE compares NaN (false), for every number type; corrected
//     uses the left derivative -r1 there. Undefined values (0/0, sqrt of a negative rounding
//     error) are treated this way throughout the as-written variant.
//  7. b1 = sqrt(1 - c1^2) is NaN when rounding makes |c1| > 1, and V0 = (W1 - c1 W0)/b1 then
//     fails; corrected normalises by |W1 - c1 W0|, as section 6 defines V0. When the
//     normaliser is 0 (axes parallel to the working precision but |W0 x W1| > 0), no quarter
//     circle exists and the perpendicular test does not separate.
//  8. The parallel branch is `lenW0xW1 > 0`, an exact zero test: parameter `parallel_test`
//     (exact_zero, or threshold on |W0 x W1|; the parallel branch then uses W0's direction).
//  9. Delta = 0 leaves W = Delta/|Delta| undefined in the other directions. Both variants
//     report no separation (f > 0 for every D, section 4): corrected answers before any test
//     (test delta_zero), as written inside SeparatedByOtherDirections.
// 10. SeparatedByOtherDirections is empty: start point, line directions, stopping rule and the
//     treatment of the kinks of G are the choices listed in detail/eberly_other_directions.hpp;
//     as written follows section 8's advice to search only the boundary once a line minimum
//     lies on it, which is wrong for a convex function; corrected keeps descending.
// 11. GDer divides by sqrt(Q_i), zero where D is parallel to W_i (D = Delta when an axis is
//     parallel to Delta): undefined as written, exact one-sided derivatives in the corrected
//     variant, whose bisection then also decides correctly at the kinks L_i = 0, where the
//     seed's Sign(0) = 0 averages the two one-sided derivatives.
// 12. The frame {U, V} around Delta is not specified: Geometric Tools' orthogonal complement.
// 13. The search parameters (t on the quarter circles, s, t, the line direction and r in the
//     2-D minimiser) are NT for double, long double and Gmpfr, exactly the seed's code; for
//     CORE::Expr and Interval_nt they are rationals (line directions rounded to binary64),
//     since iterates computed from iterates make CORE::Expr's DAG grow without bound (a 2-D
//     search then takes minutes per query) and widen intervals. Every judged value is still
//     computed in NT (detail/eberly_common.hpp, EberlyParam).
// 14. Corrected, F is not evaluated at the kink t*: it is positive there by construction, and
//     |(1-t) a2 + t b2| at its zero is undecidable in intervals.
// 15. Overflow. The seed form (C_i, W_i, r_i, h_i, Delta, |Delta|^2) must be finite in NT: in
//     double, an axis longer than about 1.3e154 makes h = |p1 - p0| infinite and W = A/h zero,
//     so perpendicular axes look parallel and the radial test "separates" cylinders that
//     overlap. Both variants then stop with no answer (`non_finite` names the value; the
//     command answers "invalid"). The corrected variant also stops at any value f(D) that is
//     not finite; as written compares it as the pseudocode would.
//
// Measured (bench/bench_eberly_cylinders.cpp, 200 random separated and 200 overlapping pairs,
// default parameters, CPU ns per query; evaluations of F, F', G, grad G per query):
//                      separated            overlapping
//   double      as written 161 ns (6.3)     6.9 us (325)    corrected 130 ns (8.0)   11.7 us (548)
//   long double as written 695 ns           30 us           corrected 494 ns         46 us
//   interval    as written 8.8 us           505 us          corrected 5.4 us         562 us
//   Gmpfr<113>  as written 38 us            1.27 ms         corrected 30 us          2.28 ms
//   Gmpfr<256>  as written 41 us            1.72 ms         corrected 32 us          2.54 ms
//   CORE::Expr  as written 227 us           14.7 ms         corrected 59 us          9.2 ms
// As written misses 1% of the separated pairs in every number type, CORE::Expr included: an
// algorithmic failure (items 2 and 10), not rounding.
#pragma once

#include <string>
#include <utility>

#include "certcyl/answer.hpp"
#include "certcyl/number_traits.hpp"
#include "certcyl/primitives.hpp"
#include "certcyl/seeds/detail/eberly_common.hpp"
#include "certcyl/seeds/detail/eberly_other_directions.hpp"
#include "certcyl/seeds/detail/eberly_perpendiculars.hpp"
#include "certcyl/vec3.hpp"

namespace certcyl {

// SeparatedCylinders(C0, W0, r0, h0, C1, W1, r1, h1) of section 8, with the answer details.
template <class NT>
EberlySeparationResult<NT> eberly_separated(const Point3<NT>& C0, const Vec3<NT>& W0, const NT& r0, const NT& h0,
                                            const Point3<NT>& C1, const Vec3<NT>& W1, const NT& r1, const NT& h1,
                                            const EberlyParameters& params = {}) {
  static_assert(nt::has_sqrt_v<NT>, "eberly_separated needs a number type with sqrt (double, long double, "
                                    "Interval_nt, Gmpfr, CORE::Expr)");
  params.validate();
  detail::EberlyRun<NT> run(params);
  const EberlyTestMask& on = params.enabled;
  const NT two = nt::constant<NT>(2);

  const Vec3<NT> Delta = C1 - C0;
  // The seed form must be finite: an overflow here (|p1 - p0| of an axis longer than about
  // 1.3e154 in double, a centre or Delta beyond the largest double) makes W = A/h zero or
  // infinite, and every test after it meaningless (perpendicular axes then look parallel).
  {
    const std::pair<const char*, bool> checks[] = {
        {"C0", detail::finite_value(C0)}, {"C1", detail::finite_value(C1)},
        {"W0", detail::finite_value(W0)}, {"W1", detail::finite_value(W1)},
        {"r0", detail::finite_value(r0)}, {"r1", detail::finite_value(r1)},
        {"h0", detail::finite_value(h0)}, {"h1", detail::finite_value(h1)},
        {"Delta", detail::finite_value(Delta)}, {"|Delta|^2", detail::finite_value(NT(squared_length(Delta)))}};
    for (const auto& [name, finite] : checks)
      if (!finite) return run.stop_non_finite(name);
  }
  // Corrected: coincident centres overlap (the common centre is interior to both).
  if (run.corrected() && nt::is_zero(Delta.x) && nt::is_zero(Delta.y) && nt::is_zero(Delta.z)) {
    run.result.test = EberlyTest::delta_zero;
    run.result.answer = Answer::overlapping;
    return run.result;
  }
  const Vec3<NT> W0xW1 = cross(W0, W1);
  const NT lenW0xW1 = nt::sqrt(squared_length(W0xW1));
  const NT h0Div2 = h0 / two, h1Div2 = h1 / two, rSum = r0 + r1;
  const NT dotW0W1 = nt::abs(dot(W0, W1));
  const NT dotW0Delta = nt::abs(dot(W0, Delta));

  const bool not_parallel =
      params.parallel_test == ParallelTest::exact_zero
          ? nt::is_positive(lenW0xW1)
          : nt::is_positive(NT(lenW0xW1 - nt::from_rational<NT>(Rational(params.parallel_threshold))));
  if (not_parallel) {
    // Test for separation by W0.
    if (on.w0 && run.judge(NT(r1 * lenW0xW1 + h0Div2 + h1Div2 * dotW0W1 - dotW0Delta), params.axis_tests,
                           EberlyTest::w0, [&] { return W0; }))
      return run.result;
    // Test for separation by W1.
    if (on.w1 && run.judge(NT(r0 * lenW0xW1 + h0Div2 * dotW0W1 + h1Div2 - nt::abs(dot(W1, Delta))),
                           params.axis_tests, EberlyTest::w1, [&] { return W1; }))
      return run.result;
    // Test for separation by W0xW1.
    if (on.w0xw1 && run.judge(NT(rSum * lenW0xW1 - nt::abs(dot(W0xW1, Delta))), params.axis_tests,
                              EberlyTest::w0xw1, [&] { return W0xW1; }))
      return run.result;
    // Test for separation by directions perpendicular to W0.
    if (on.perpendicular_w0 &&
        detail::separated_by_cylinder_perpendiculars(run, C0, W0, r0, C1, W1, r1, h1, EberlyTest::perpendicular_w0))
      return run.result;
    // Test for separation by directions perpendicular to W1.
    if (on.perpendicular_w1 &&
        detail::separated_by_cylinder_perpendiculars(run, C1, W1, r1, C0, W0, r0, h0, EberlyTest::perpendicular_w1))
      return run.result;
    // Test for separation by other directions.
    if (on.other_directions && detail::separated_by_other_directions(run, W0, r0, h0, W1, r1, h1, Delta))
      return run.result;
  } else {
    // Test for separation by height.
    if (on.parallel_height && run.judge(NT(h0Div2 + h1Div2 - dotW0Delta), params.parallel_tests,
                                        EberlyTest::parallel_height, [&] { return W0; }))
      return run.result;
    // Test for separation radially.
    const Vec3<NT> radial = Delta - dot(W0, Delta) * W0;
    if (on.parallel_radial && run.judge(NT(rSum - nt::sqrt(squared_length(radial))), params.parallel_tests,
                                        EberlyTest::parallel_radial, [&] { return radial; }))
      return run.result;
    // else: parallel cylinders not separated by height or radial distance overlap.
  }
  return run.finish_not_separated();
}

// The same for Cylinder<NT> {p0, p1, radius}: C = (p0 + p1)/2, h = |p1 - p0|, W = (p1 - p0)/h.
template <class NT>
EberlySeparationResult<NT> eberly_separated(const Cylinder<NT>& cylinder0, const Cylinder<NT>& cylinder1,
                                            const EberlyParameters& params = {}) {
  auto seed_form = [](const Cylinder<NT>& c, Point3<NT>& C, Vec3<NT>& W, NT& h) {
    const Vec3<NT> A = c.axis();
    C = (c.p0 + c.p1) / nt::constant<NT>(2);
    h = nt::sqrt(squared_length(A));
    W = A / h;
  };
  Point3<NT> C0, C1;
  Vec3<NT> W0, W1;
  NT h0, h1;
  seed_form(cylinder0, C0, W0, h0);
  seed_form(cylinder1, C1, W1, h1);
  return eberly_separated(C0, W0, cylinder0.radius, h0, C1, W1, cylinder1.radius, h1, params);
}

}  // namespace certcyl
