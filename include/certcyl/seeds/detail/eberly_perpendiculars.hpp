// certcyl/seeds/detail/eberly_perpendiculars.hpp -- SeparatedByCylinderPerpendiculars
// (seed sections 6 and 8): directions perpendicular to the axis W0 of the first cylinder.
//
// With V0 = (W1 - c1 W0)/|W1 - c1 W0|, U0 = V0 x W0, c1 = W0.W1, b1 = W1.V0, a2 = Delta.U0,
// b2 = Delta.V0, the quarter circle D(t) = (1-t) U0 + t V0, t in [0,1], gives (equation (8))
//   F(t) = r0 sqrt((1-t)^2 + t^2) + r1 sqrt((1-t)^2 + c1^2 t^2) + (h1 b1/2) t - |(1-t) a2 + t b2|
// and the second quarter is the same with a2 replaced by -a2 (D(t) = (1-t)(-U0) + t V0).
// D.W1 = t b1 >= 0 on both quarters, which is why |D.W1| needs no absolute value.
//
// F is NOT convex on [0,1] in general, contrary to the seed's claim: its last term
// -|(1-t) a2 + t b2| is concave, with a kink at t* = a2/(a2 - b2) when a2 and b2 have opposite
// signs (equation (10) omits it; it also has 3 r0 where the second derivative of the first
// term is r0 / ((1-t)^2 + t^2)^(3/2)). F is convex on each side of t*, and F(t*) > 0 since
// D(t*) is perpendicular to Delta (seed section 4). The corrected variant therefore splits
// each quarter at t* and minimises each convex piece; the as-written variant bisects on the
// sign of F' over the whole quarter, as the pseudocode does.
#pragma once

#include "certcyl/number_traits.hpp"
#include "certcyl/seeds/detail/eberly_common.hpp"
#include "certcyl/vec3.hpp"

namespace certcyl::detail {

// The seed's constants for one ordering of the cylinders (the arguments of F and FDer).
template <class NT>
struct PerpendicularFrame {
  NT r0, r1, h1b1Div2, c1sqr, a2, b2;
  Vec3<NT> U0, V0;
};

template <class NT>
NT eberly_F(const NT& t, const PerpendicularFrame<NT>& q, const NT& a2, EberlyCounters& counters) {
  ++counters.F;
  const NT one = nt::constant<NT>(1);
  const NT omt = one - t;
  const NT tsqr = t * t;
  const NT omtsqr = omt * omt;
  const NT term0 = q.r0 * nt::sqrt(NT(omtsqr + tsqr));
  const NT term1 = q.r1 * nt::sqrt(NT(omtsqr + q.c1sqr * tsqr));
  const NT term2 = q.h1b1Div2 * t;
  const NT term3 = nt::abs(NT(omt * a2 + t * q.b2));
  return term0 + term1 + term2 - term3;
}

// F'(t) (equation (9)). `sign_override`, when given, replaces Sign((1-t) a2 + t b2): the
// corrected variant passes the constant sign of that expression on the piece it minimises.
// `left_at_one`: the derivative is the one-sided one from the left at t = 1, the only place
// where the second square root can vanish (c1 = 0, perpendicular axes: then
// r1 sqrt((1-t)^2) = r1 (1-t) has left derivative -r1). Without it, a vanishing square root
// makes F' undefined (0/0), as IEEE arithmetic does.
template <class NT>
std::optional<NT> eberly_FDer(const NT& t, const PerpendicularFrame<NT>& q, const NT& a2,
                              std::optional<CGAL::Sign> sign_override, bool left_at_one, EberlyCounters& counters) {
  ++counters.F_derivative;
  const NT one = nt::constant<NT>(1);
  const NT two = nt::constant<NT>(2);
  const NT omt = one - t;
  const NT tsqr = t * t;
  const NT omtsqr = omt * omt;
  const NT term0 = q.r0 * (two * t - one) / nt::sqrt(NT(omtsqr + tsqr));
  const NT root1 = nt::sqrt(NT(omtsqr + q.c1sqr * tsqr));
  NT term1;
  if (!is_nan(root1) && nt::is_zero(root1)) {
    if (!left_at_one) return std::nullopt;
    term1 = -q.r1;
  } else {
    term1 = q.r1 * ((one + q.c1sqr) * t - one) / root1;
  }
  const NT term2 = q.h1b1Div2;
  const CGAL::Sign s = sign_override ? *sign_override : nt::sign(NT(omt * a2 + t * q.b2));
  const NT term3 = s == CGAL::ZERO ? nt::constant<NT>(0) : (s == CGAL::POSITIVE ? NT(q.b2 - a2) : NT(a2 - q.b2));
  return term0 + term1 + term2 - term3;
}

template <class NT>
Vec3<NT> perpendicular_direction(const PerpendicularFrame<NT>& q, const NT& t, bool negated_u0) {
  const NT one = nt::constant<NT>(1);
  const Vec3<NT> u = negated_u0 ? Vec3<NT>(-q.U0) : q.U0;
  return NT(one - t) * u + t * q.V0;
}

// Builds the frame for directions perpendicular to W0 (the roles of the cylinders as given).
// As written: b1 = sqrt(1 - c1^2) and V0 = (W1 - c1 W0)/b1, as the pseudocode. Corrected:
// b1 = |W1 - c1 W0|, the normalisation of section 6, which stays consistent with V0 when the
// axes are not exactly unit (rounded input) instead of taking the root of 1 - c1^2 < 0.
// Returns nullopt when b1 vanishes (the axes are parallel to the precision at hand).
template <class NT>
std::optional<PerpendicularFrame<NT>> perpendicular_frame(const Vec3<NT>& C0, const Vec3<NT>& W0, const NT& r0,
                                                          const Vec3<NT>& C1, const Vec3<NT>& W1, const NT& r1,
                                                          const NT& h1, bool corrected) {
  const Vec3<NT> Delta = C1 - C0;
  const NT c1 = dot(W0, W1);
  const Vec3<NT> w1perp = W1 - c1 * W0;
  const NT b1 = corrected ? nt::sqrt(squared_length(w1perp)) : nt::sqrt(NT(nt::constant<NT>(1) - c1 * c1));
  if (is_nan(b1) || nt::is_zero(b1)) return std::nullopt;
  PerpendicularFrame<NT> q;
  q.V0 = w1perp / b1;
  q.U0 = cross(q.V0, W0);
  q.r0 = r0;
  q.r1 = r1;
  q.h1b1Div2 = h1 * b1 / nt::constant<NT>(2);
  q.c1sqr = c1 * c1;
  q.a2 = dot(Delta, q.U0);
  q.b2 = dot(Delta, q.V0);
  return q;
}

// One quarter circle exactly as the pseudocode: returns +1 when separated, -1 for its
// `return false` (no separation by perpendicular directions, the other quarter skipped),
// 0 when it falls through to the next quarter.
template <class NT>
int quarter_as_written(EberlyRun<NT>& run, const PerpendicularFrame<NT>& q, const NT& a2, bool negated_u0,
                       EberlyTest test) {
  EberlyCounters& k = run.result.counters;
  const Strictness st = run.params.perpendicular_tests;
  using P = EberlyParam<NT>;
  const P zero = nt::constant<P>(0), one = nt::constant<P>(1), two = nt::constant<P>(2);
  auto at = [&](const P& t) {
    return [&q, t, negated_u0] { return perpendicular_direction(q, param_to_nt<NT>(t), negated_u0); };
  };
  auto F = [&](const P& t) { return eberly_F(param_to_nt<NT>(t), q, a2, k); };
  auto FDer = [&](const P& t) { return eberly_FDer(param_to_nt<NT>(t), q, a2, std::nullopt, false, k); };

  if (run.judge(F(zero), st, test, at(zero))) return 1;
  if (run.judge(F(one), st, test, at(one))) return 1;
  if (greater_equal_zero(FDer(zero))) return -1;
  if (less_equal_zero(FDer(one))) return -1;

  P t0 = zero, t1 = one;
  for (int i = 0; i < run.params.perpendicular_bisections; ++i) {
    const P tmid = (t0 + t1) / two;
    if (run.judge(F(tmid), st, test, at(tmid))) return 1;
    const auto fdmid = FDer(tmid);
    if (greater_zero(fdmid)) {
      t1 = tmid;
    } else if (less_zero(fdmid)) {
      t0 = tmid;
    } else {
      break;
    }
  }
  return 0;
}

// The corrected minimisation of F on one convex piece [lo, hi] of a quarter, on which
// (1-t) a2 + t b2 has the constant sign `piece_sign`. Returns true when separated.
template <class NT>
bool piece_corrected(EberlyRun<NT>& run, const PerpendicularFrame<NT>& q, const NT& a2, bool negated_u0,
                     const EberlyParam<NT>& lo, const EberlyParam<NT>& hi, bool lo_is_kink, bool hi_is_kink,
                     CGAL::Sign piece_sign, EberlyTest test) {
  const bool hi_is_one = !hi_is_kink;
  using P = EberlyParam<NT>;
  EberlyCounters& k = run.result.counters;
  const Strictness st = run.params.perpendicular_tests;
  const P two = nt::constant<P>(2);
  auto at = [&](const P& t) {
    return [&q, t, negated_u0] { return perpendicular_direction(q, param_to_nt<NT>(t), negated_u0); };
  };
  auto F = [&](const P& t) { return eberly_F(param_to_nt<NT>(t), q, a2, k); };
  auto FDer = [&](const P& t, bool left_at_one) {
    return eberly_FDer(param_to_nt<NT>(t), q, a2, piece_sign, left_at_one, k);
  };

  // F at the kink is positive (D(t*) is perpendicular to Delta, seed section 4): not evaluated.
  if (!lo_is_kink && run.judge(F(lo), st, test, at(lo))) return true;
  if (!hi_is_kink && run.judge(F(hi), st, test, at(hi))) return true;
  // The derivatives at the ends are the one-sided ones into the piece.
  if (greater_equal_zero(FDer(lo, false))) return false;
  if (less_equal_zero(FDer(hi, hi_is_one))) return false;

  P t0 = lo, t1 = hi;
  for (int i = 0; i < run.params.perpendicular_bisections; ++i) {
    const P tmid = (t0 + t1) / two;
    if (run.judge(F(tmid), st, test, at(tmid))) return true;
    const auto fdmid = FDer(tmid, false);
    if (greater_zero(fdmid)) {
      t1 = tmid;
    } else if (less_zero(fdmid)) {
      t0 = tmid;
    } else {
      break;  // F'(tmid) = 0 (or undefined): tmid is the minimum of the piece
    }
  }
  return false;
}

// One quarter, corrected: split at the kink t* of |(1-t) a2 + t b2| when it lies inside.
template <class NT>
bool quarter_corrected(EberlyRun<NT>& run, const PerpendicularFrame<NT>& q, const NT& a2, bool negated_u0,
                       EberlyTest test) {
  using P = EberlyParam<NT>;
  const P zero = nt::constant<P>(0), one = nt::constant<P>(1);
  const CGAL::Sign sa = nt::sign(a2), sb = nt::sign(q.b2);
  if (sa != CGAL::ZERO && sb != CGAL::ZERO && sa != sb) {
    // t* in the parameter type: rounded to binary64 for CORE::Expr and intervals, so the
    // pieces may overlap the kink by an ulp; F is still judged exactly at every point.
    const P tstar = nt_to_param(NT(a2 / (a2 - q.b2)));
    if (piece_corrected(run, q, a2, negated_u0, zero, tstar, false, true, sa, test)) return true;
    return piece_corrected(run, q, a2, negated_u0, tstar, one, true, false, sb, test);
  }
  // else: one convex piece; the sign of (1-t) a2 + t b2 inside (0,1) is that of a2 or b2.
  const CGAL::Sign s = sa != CGAL::ZERO ? sa : sb;
  return piece_corrected(run, q, a2, negated_u0, zero, one, false, false, s, test);
}

// SeparatedByCylinderPerpendiculars(C0,W0,r0,h0, C1,W1,r1,h1): directions perpendicular to W0.
// As written, the function's end has no return statement in the pseudocode; it returns false.
template <class NT>
bool separated_by_cylinder_perpendiculars(EberlyRun<NT>& run, const Vec3<NT>& C0, const Vec3<NT>& W0, const NT& r0,
                                          const Vec3<NT>& C1, const Vec3<NT>& W1, const NT& r1, const NT& h1,
                                          EberlyTest test) {
  const auto frame = perpendicular_frame(C0, W0, r0, C1, W1, r1, h1, run.corrected());
  if (!frame) return false;  // b1 = 0: no quarter circle can be built
  const PerpendicularFrame<NT>& q = *frame;
  const NT minus_a2 = -q.a2;
  if (!run.corrected()) {
    // Test directions (1-t)*U0 + t*V0, then (1-t)*(-U0) + t*V0.
    const int first = quarter_as_written(run, q, q.a2, false, test);
    if (first != 0) return first > 0;
    return quarter_as_written(run, q, minus_a2, true, test) > 0;
  }
  // Corrected: both quarters always.
  if (quarter_corrected(run, q, q.a2, false, test)) return true;
  return quarter_corrected(run, q, minus_a2, true, test);
}

}  // namespace certcyl::detail
