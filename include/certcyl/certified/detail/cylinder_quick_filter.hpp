// certcyl/certified/detail/cylinder_quick_filter.hpp -- the first checks of the certified
// cylinder-cylinder query: does the direction D = T = 2 Delta (twice the difference of the
// midpoints) separate the two cylinders, and is a given point strictly inside both? They run in
// plain double arithmetic with error bounds fixed in advance (static filters in the sense of
// CGAL's), so that the common cases, a pair that Delta separates or a cheap point proves
// overlapping with some margin, cost a few dozen floating-point operations. When they cannot
// decide they say so and the caller goes on with the semi-static filter
// (cylinder_static_filter.hpp), intervals and Gmpq. They never decide on a tolerance.
//
// Scope: binary64 cylinders, evaluated where they are (no copy, no scaling). The error analysis
// is written for the world frame: the input multiplied by a power of two 1/w so that every input
// number x (coordinates and radii) has |x| < 2 (w = 2^k from the largest binary exponent of the
// fourteen numbers, read off their bits by quick_frame, which also detects non-finite input and
// puts no division or rounding on the way to the thresholds), with squared axis lengths
// A.A >= 2^-199 there (checked here). Every rounding error is relative, so
// each bound holds in the input frame multiplied by w^d for a quantity of degree d (DT, DA, c, TA,
// AA, s, S, G: 2; p, q, x, Y, g, K: 4; the ratios and scales: 0; the direction is T itself). Underflow is
// the exception: an underflow adds at most 2^-1074 in the input frame, 2^-1074 / w <= 2^-974 in
// the world frame; the caller ensures 2^-100 <= w <= 2^100 (which also keeps every constant
// below normal and rules out overflow), and the world-frame bounds are written for that.
// Notation: starred quantities are exact, unstarred ones computed. u = 2^-52 bounds the relative
// error of one operation in every rounding mode (|fl(y) - y| <= u |y| for a normal result).
//   A_k = fl(p1 - p0):  |A_k,i - A*_k,i| <= u |A*_k,i|, |A_k,i| <= 4; alpha_k^2 = A*_k.A*_k.
//   T = fl(fl(p0_1 + p1_1) - fl(p0_0 + p1_0)):  |T_i - T*_i| <= 4u + 4u + 8(1 + u)u <= 16.0001u,
//     |T_i| <= 8 (T* = 2 Delta). The direction D is T as computed: the certificate, exact as given.
//   AA_k = fl-dot(A_k, A_k) = alpha_k^2 (1 + theta), |theta| <= (1 + u)^2 (1 + gamma_3) - 1 <= 5.0003u.
// Dot products (gamma_3 = 3u / (1 - 3u) <= 3.0001u):
//   DT = fl-dot(T, T):   |DT - T.T*| <= gamma_3 sum T_i^2 + sum |T_i| |T_i - T*_i|
//                                    <= 3.0001u * 192 + 24 * 16.0001u <= 960.03u;
//   DA_k = fl-dot(T, A_k): |DA_k - T.A*_k| <= gamma_3 |T| |A_k| + u |T| alpha_k <= 55.43u alpha_k
//                                    (|T| <= sqrt(192) <= 13.857), and a priori <= 3.0001u 96 + 96u <= 384.01u.
// c = fl(fl(|DT| - |DA0|) - |DA1|), c* = |T.T*| - |T.A*0| - |T.A*1| (the c of separation_terms):
//   |c - c*| <= 960.03u + 2 * 384.01u + 192.03u + 192.03u <= 2112.11u  <  E_c = 2^-40 = 4096u.
// x_k = fl(fl(DT AA_k) - fl(DA_k^2)), x*_k = |T x A*_k|^2 = (T.T) alpha_k^2 - (T.A*_k)^2:
//   |DA_k^2 - (T.A*_k)^2| <= 55.43u alpha 2 * 13.858 alpha + 192.1u alpha^2 <= 1728.4u alpha^2,
//   |DT AA_k - (T.T) alpha^2| <= 576.02u alpha^2 (1 + 5.0003u) + 192 * 5.0003u alpha^2 + 192.1u alpha^2
//                            <= 1728.2u alpha^2,
//   the subtraction <= 192.2u alpha^2:  |x_k - x*_k| <= 3648.8u alpha_k^2.
// p = fl(k_0 x_0) with k_0 = fl(fl(4 fl(r0 r0)) / AA_0) (the division does not wait for x_0),
// p* = 4 r0^2 x*_0 / alpha_0^2 (the p of separation_terms):
//   p = 4 r0^2 x_0 F / alpha_0^2 with |F - 1| <= 8.001u, and x*_0 <= 192 alpha_0^2, so
//   |p - p*| <= 4 r0^2 (192 * 8.001u + 3648.8u * 1.0001) <= 20741.6u r0^2.
//   P = fl(p + E_p), E_p = fl(2^-37 fl(r0 r0) + 2^-600) >= 32767.9u r0^2: p + E_p > 0 and
//   P >= (p + E_p)(1 - u) >= p* + (32767.9 - 20741.6) u r0^2 - u (768.1 + 32768u) r0^2 >= p*.
//   q and Q likewise.
// Underflow adds at most 2^-1074 / w^d <= 2^(100 d - 1074) in the world frame to a result of
//   degree d. c (degree 2, a few operations) changes by less than 2^-860 (covered by E_c); x_k
//   (degree 4) by less than 2^-670, fl(r0 r0) by 2^-874 and k_0 by 2^-1074 + 4 2^-874 / AA_0, so
//   p changes by less than 2^-670 k_0 + 2^-650 <= 2^-468 r0^2 + 2^-650 with k_0 <= 2^202 r0^2
//   (AA_0 >= 2^-199): covered by the 2^-37 fl(r0 r0) and the 2^-600 in E_p (which also covers a
//   subnormal r0^2).
// Decision (separated: c* > sqrt(p*) + sqrt(q*)): L = fl(c - E_c) > 0 gives c* >= c - E_c >= L / (1 + u);
// rho = 1 + 2^-48.
//  - First a sufficient test without division or square root: sqrt(p*) = 2 r0 |T x A*0| / alpha_0
//    <= 2 r0 |T|, so c* > 2 (r0 + r1) |T| separates (it decides about four separated random pairs
//    in five). With rs = fl(r0 + r1) >= (1 - u)(r0 + r1), RR = fl(rs rs) and K = 4 fl(RR DT)
//    both normal, and DT >= (1 - gamma_3) T.T (a sum of squares):
//    4 (r0 + r1)^2 T.T <= K / ((1 - u)^4 (1 - 3.0001u)) <= (1 + 7.0003u) K; fl(L L) > fl(rho K)
//    (then normal) gives c*^2 >= L^2 / (1 + u)^2 >= fl(L L) / (1 + u)^3 > rho K (1 - u) / (1 + u)^3
//    >= (1 + 11.9u) K > 4 (r0 + r1)^2 T.T, with c* > 0 from L > 0.
//  - Then the test itself: R = fl(fl(sqrt P) + fl(sqrt Q)) >= (sqrt p* + sqrt q*)(1 - u)^2;
//    L > fl(rho R) gives c* > rho R (1 - u) / (1 + u) >= rho (1 - u)^3 / (1 + u) (sqrt p* + sqrt q*)
//    >= sqrt p* + sqrt q*.
// Upper bound of phi2(T) / |T.T*| (>= phi*): N = fl(fl(a0 + a1) + R), a_k = fl(|DA_k| + 2^-43)
// (512u >= 384.01u): N >= (1 - u)^3 phi2(T); M = fl(|DT| - 2^-41) (2048u >= 960.03u)
// <= (1 + u) |T.T*|; fl(rho fl(N / M)) >= rho (1 - u)^5 / (1 + u) ratio >= ratio.
//
// Lower bound of phi* from the segment between the midpoints (the argument of
// static_segment_phi_lower): phi* >= 1/s0 + 1/s1 with s_k the scale of cylinder k at the other
// midpoint, s_k = max(|T*.A*_k| / alpha_k^2, |T* x A*_k| / (2 r_k alpha_k)), so
// 1/s_k = min(alpha_k^2 / |T*.A*_k|, 2 r_k alpha_k / |T* x A*_k|). Only when T separates (so P,
// Q are at hand); one division and no square root beyond sqrt P, sqrt Q:
//   axial: |DA_k - T*.A*_k| <= 384.01u + sum |T_i - T*_i| |A*_i| <= 384.01u + 192.01u < 927u, and
//     G_k = fl(|DA_k| + 2^-42) >= |DA_k| + 927u > |T*.A*_k| (2^-42 = 1024u), so
//     alpha_k^2 / |T*.A*_k| >= AA_k / ((1 + 5.0003u) G_k);
//   radial: |T* x A*_k| <= |T x A*_k| + |T - T*| alpha_k <= |T x A*_k| + 27.72u alpha_k, so
//     2 r |T* x A*| / alpha <= sqrt(p*) + 55.44u r <= sqrt(P) + 55.44u r; with S_k =
//     fl(fl(fl(sqrt P)(1 + 2^-49)) + 2^-45 r) >= sqrt(P)(1 - u)^3 (1 + 8u) + 127.9u r
//     >= sqrt(P) + 55.44u r: 2 r alpha / |T* x A*| >= 4 r^2 / S_k >= fl(4 fl(r r)) / ((1 + u) S_k)
//     when fl(r r) is normal (r w and 2^-45 r w are then exact);
//   1/s_k >= min(e1, e2) / (1 + 5.0003u) with e1 = AA_k / G_k, e2 = fl(4 r r) / S_k (real
//     quotients of the computed numbers). The smaller is chosen by comparing fl(AA_k S_k) with
//     fl(4 r r G_k) (normal, so each within u): the one chosen, n_k / d_k, is at most
//     (1 + u) / (1 - u) <= 1 + 2.0001u times the smaller;
//   n0/d0 + n1/d1 = (n0 d1 + n1 d0) / (d0 d1), computed with every product and the quotient
//     normal (the quotient at least 2^-1000), is at most (1 + u)^3 / (1 - u) <= 1 + 4.0001u times
//     its value; in all the computed sum is at most (1 + 11.001u)(1/s0 + 1/s1), and
//     fl(rho' sum), rho' = 1 - 2^-48, is at most 1/s0 + 1/s1.
//   When some product is not normal (radii or axes far below the frame's scale) there is no lower
//   bound from the quick path (0). Degrees: AA, G, 4 r r, S are 2, the products 4: with
//   2^-100 <= w <= 2^100 and world values below 2^7 nothing overflows.
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cmath>
#include <limits>

#include "certcyl/certified/detail/cylinder_static_filter.hpp"
#include "certcyl/primitives.hpp"
#include "certcyl/vec3.hpp"

namespace certcyl::detail {

struct QuickSeparation {
  Vec3<double> direction;  // T (exact as given)
  // Certified bounds of phi*, only when asked for: the upper one from T whether or not T
  // separates (+infinity when the filter's guards fail or |T.T*| may vanish); the lower one from
  // the segment between the midpoints, only when T separates (0: none).
  double phi_upper = std::numeric_limits<double>::infinity();
  double phi_lower = 0;
  bool by_radius_sum = false;  // separated by the sufficient test c* > 2 (r0 + r1) |T|
};

// The frame of the header comment: w = 2^k with every one of the fourteen numbers below 2w in
// magnitude (the largest biased exponent among them, as a double: 2^(e - 1023)); 0 when w lies
// outside [2^-100, 2^100], which includes all-zero-or-subnormal and non-finite input.
inline double quick_frame(const Cylinder<double>& c0, const Cylinder<double>& c1) {
  const auto e = [](double x) { return std::bit_cast<std::uint64_t>(x) & 0x7ff0000000000000u; };
  const auto cylinder = [&e](const Cylinder<double>& c) {
    return std::max({e(c.p0.x), e(c.p0.y), e(c.p0.z), e(c.p1.x), e(c.p1.y), e(c.p1.z), e(c.radius)});
  };
  const double w = std::bit_cast<double>(std::max(cylinder(c0), cylinder(c1)));
  return w >= 0x1p-100 && w <= 0x1p100 ? w : 0;
}

// Whether T provably separates c0, c1 (header comment); w is the frame's power of two; the bounds
// of phi* are filled when `bounds`.
inline bool quick_separation(const Cylinder<double>& c0, const Cylinder<double>& c1, double w, bool bounds, QuickSeparation& out) {
  constexpr double kRho = 1 + 0x1p-48, kRhoDown = 1 - 0x1p-48;
  constexpr double kMin = std::numeric_limits<double>::min();
  const double ww = w * w;
  const Vec3<double> A0 = c0.p1 - c0.p0, A1 = c1.p1 - c1.p0;
  const Vec3<double> T = (c1.p0 + c1.p1) - (c0.p0 + c0.p1);
  const double AA0 = dot(A0, A0), AA1 = dot(A1, A1);
  if (!(AA0 >= 0x1p-199 * ww && AA1 >= 0x1p-199 * ww)) return false;
  out.direction = T;
  const double DT = dot(T, T), DA0 = dot(T, A0), DA1 = dot(T, A1);
  const double L = ((DT - std::abs(DA0)) - std::abs(DA1)) - 0x1p-40 * ww;
  // The sufficient test c* > 2 (r0 + r1) |T|.
  const double rs = c0.radius + c1.radius, RR = rs * rs, K = 4 * (RR * DT);
  out.by_radius_sum = L > 0 && RR >= kMin && K >= kMin && L * L > kRho * K;
  if (out.by_radius_sum && !bounds) return true;
  const double rr0 = c0.radius * c0.radius, rr1 = c1.radius * c1.radius;
  const double k0 = (4 * rr0) / AA0, k1 = (4 * rr1) / AA1;
  const double x0 = DT * AA0 - DA0 * DA0, x1 = DT * AA1 - DA1 * DA1;
  const double tau = 0x1p-600 * (ww * ww);
  const double P = k0 * x0 + (0x1p-37 * ww * rr0 + tau);
  const double Q = k1 * x1 + (0x1p-37 * ww * rr1 + tau);
  const double sP = std::sqrt(P), sQ = std::sqrt(Q), roots = sP + sQ;
  const bool separated = out.by_radius_sum || (L > 0 && L > kRho * roots);
  if (!bounds) return separated;
  const double M = DT - 0x1p-41 * ww;
  if (M > 0) out.phi_upper = kRho * ((((std::abs(DA0) + 0x1p-43 * ww) + (std::abs(DA1) + 0x1p-43 * ww)) + roots) / M);
  if (!separated) return false;  // the caller's lower bound then comes from a point
  // 1/s_k from above within 1 + 7.0005u, as a fraction n_k / d_k (header comment).
  bool normal = rr0 >= kMin && rr1 >= kMin;
  const auto inverse_scale = [ww, w, &normal](double DA, double AA, double r, double rr, double sqrt_p, double& n, double& d) {
    const double G = std::abs(DA) + 0x1p-42 * ww, S = sqrt_p * (1 + 0x1p-49) + 0x1p-45 * (w * r), R4 = 4 * rr;
    const double axial = AA * S, radial = R4 * G;  // axial <= radial: AA / G is the smaller
    normal = normal && axial >= kMin && radial >= kMin;
    const bool by_axis = axial <= radial;
    n = by_axis ? AA : R4;
    d = by_axis ? G : S;
  };
  double n0, d0, n1, d1;
  inverse_scale(DA0, AA0, c0.radius, rr0, sP, n0, d0);
  inverse_scale(DA1, AA1, c1.radius, rr1, sQ, n1, d1);
  const double a = n0 * d1, b = n1 * d0, den = d0 * d1, sum = (a + b) / den;
  if (normal && a >= kMin && b >= kMin && den >= kMin && sum >= 0x1p-1000) out.phi_lower = kRhoDown * sum;
  return separated;
}

// ---- a candidate point strictly inside both cylinders ------------------------------------------
// For a point X (exact as given) and cylinder k, with w = fl(X - p0), the world bounds (|X_i| <= 4,
// else X is outside both world cylinders, whose points are within r < 2 of an axis segment with
// coordinates < 2; |w*_i| <= 6):
//   s = fl-dot(w, A):   |s - w*.A*| <= gamma_3 72 + 72u + 72u <= 360.01u;
//   X is interior iff s* > 0, AA* - s* > 0 and g* = r^2 AA* - |w* x A*|^2 > 0, with
//   |w x A|^2 = (w.w)(A.A) - (w.A)^2:
//   fl(AA - s):  |.| error <= 360.01u + 5.0003u * 48 + u (48 + 72) <= 720.03u  < 2^-42;
//   g = fl(fl(rr AA) - fl(fl(ww AA) - fl(s s))), ww = fl-dot(w, w) (|ww - w*.w*| <= 5.0003u 108):
//     rr AA: 7.0004u * 192 = 1344.1u; ww AA: 540.04u * 48.01 + 108 * 240.02u + 5200u <= 57049u;
//     s^2: 360.01u * 144.02 + 5185u <= 57034u; the two subtractions: 5186u + 5378u;
//     in all <= 125991u < 2^-35 = 131072u.
//   Degrees (input frame): s and AA - s 2, g 4. Underflows (2^-974 each, world) are far inside.
// sigma_k(X) = max(|2s* - AA*| / AA*, sqrt(|w* x A*|^2 / (r^2 AA*))) from above:
//   |2s - AA| within 2 * 360.01u + 240.02u + u (144 + 48) <= 1152.04u < 2^-41;
//   |w x A|^2 within 57049u + 57034u + 5186u <= 119269u, and fl(. + 2^-35) covers it and its
//   own rounding; fl(rr AA) <= (1 + 7.0004u) r^2 AA* when rr and rr AA are normal (required).
//   Each term >= (1 - u)^3 / (1 + 7.0004u) times its exact value; rho repays that.
struct QuickPoint {
  bool inside = false;       // X is proved strictly inside both
  double sigma_upper = 0;    // certified upper bound of sigma(X) (+infinity: none)
};

inline QuickPoint quick_point(const Cylinder<double>& c0, const Cylinder<double>& c1, double w, const Point3<double>& X) {
  constexpr double kRho = 1 + 0x1p-48;
  QuickPoint out;
  out.sigma_upper = std::numeric_limits<double>::infinity();
  const double limit = 4 * w;
  if (!(std::abs(X.x) <= limit && std::abs(X.y) <= limit && std::abs(X.z) <= limit)) return out;
  const double ww2 = w * w, ww4 = ww2 * ww2;
  bool inside = true;
  double sigma = 0;
  for (const Cylinder<double>* c : {&c0, &c1}) {
    const Vec3<double> A = c->p1 - c->p0, v = X - c->p0;
    const double AA = dot(A, A);
    if (!(AA >= 0x1p-199 * ww2)) return out;
    const double s = dot(v, A), vv = dot(v, v);
    const double rr = c->radius * c->radius, rAA = rr * AA;
    const double x = vv * AA - s * s;
    inside = inside && s > 0x1p-43 * ww2 && AA - s > 0x1p-42 * ww2 && rAA - x > 0x1p-35 * ww4;
    if (!(rr >= std::numeric_limits<double>::min() && rAA >= std::numeric_limits<double>::min())) {
      sigma = std::numeric_limits<double>::infinity();
      continue;
    }
    const double axial = (std::abs(2 * s - AA) + 0x1p-41 * ww2) / AA;
    const double radial = std::sqrt((x + 0x1p-35 * ww4) / rAA);
    sigma = std::max({sigma, axial, radial});
  }
  out.inside = inside;
  out.sigma_upper = kRho * sigma;
  return out;
}

}  // namespace certcyl::detail
