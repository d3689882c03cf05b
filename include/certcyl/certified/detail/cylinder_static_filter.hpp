// certcyl/certified/detail/cylinder_static_filter.hpp -- a semi-static floating-point filter for
// the checks of cylinder_certificates.hpp: plain double arithmetic with a rigorous error bound
// carried alongside, no rounding-mode switch, no allocation. It decides a sign only when the
// computed value exceeds its bound; otherwise it says "unknown" and the caller runs the interval
// and then the Gmpq check. It never decides on a tolerance.
//
// Scope. The filter runs in the "world" frame: the input multiplied by a power of two 2^k chosen
// so that every input number (coordinates and radii) has magnitude < 2. The scaling is exact
// (the caller checks it) and every check is invariant under it: separation_sign is homogeneous
// in the input, phi2(D) / |D.T| and sigma(X) (X scaled along) do not change. Directions D are
// scaled by a power of two to |D_i| < 2 (the scaled D is the certificate), points need |X_i| <= 4
// (a point farther out is outside both world cylinders). Guard: A_i.A_i >= 2^-200 (certainly).
//
// Error model. Every floating operation, in every rounding mode (the filter does not assume
// round-to-nearest, so it may also run under CGAL's upward rounding), satisfies
//   fl(a op b) = (a op b)(1 + d) + h,   |d| <= eps = 2^-52,  |h| <= 2^-1074 (underflow),
// with h = 0 for + and - (a subnormal sum is exact); in particular |fl(x) - x| <= eps |fl(x)|
// for a normal result, and fl is monotone.
// Bounded {v, e} pairs a computed value v with e such that |v - x| <= e for the exact value x;
// e follows these rules (each valid when evaluated exactly on the computed values, underflow
// aside):
//   a +- b : v = fl(a.v +- b.v),  e = a.e + b.e + eps |v|
//   a * b  : v = fl(a.v * b.v),   e = eps |v| + |a.v| b.e + |b.v| a.e + a.e b.e
//   a / b  : (b.v > b.e)  e = eps |v| + (a.e + |v| (1 + 2^-50) b.e) / (b.v - b.e)
//            (|a.v / b.v| <= |v| / (1 - eps) <= |v| (1 + 2^-50), and
//             |a.v/b.v - a/b| <= (a.e + |a.v/b.v| b.e) / (b.v - b.e) by expanding a/b)
//   |a|, 2^j a : e unchanged, scaled by 2^j (|.| does not increase |v - x|).
// The rules are evaluated in floating point: sums, products and quotients of non-negative
// numbers, each rounded by a factor >= 1 - eps (a rounded divisor counts once more), so the
// computed e is at least (1 - eps)^K times the exact rule, K well below 2^10 here.
// Underflow: in the world frame every value and every bound has magnitude < 2^28 (inputs < 2,
// D < 2, X <= 4, degree <= 4 before the one division, and p, q <= 4 r^2 |D|^2 < 2^8 after it).
// A perturbation of at most 2^-1074 at one of the fewer than 2^8 operations of an evaluation
// reaches the result multiplied by at most 8 later factors (< 2^224) and divided at most once
// by a divisor >= 2^-200: in all less than 2^-1074 * 2^8 * 2^224 * 2^200 = 2^-642.
// A sign is decided against w(t) = fl(fl(t.e kappa) + tau), kappa = 1 + 2^-40, tau = 2^-600:
// (1 - eps)^(K + 2) kappa >= 1 covers the rounding of e, tau (1 - eps) > 2 * 2^-642 covers
// underflow in v and in e, so |t.v - x| <= w(t); t.v > w(t) proves x > 0, t.v < -w(t) proves
// x < 0. Every bound built from w(t) (upper_of, lower_of) is at least tau away from rounding
// trouble: quotients and roots of them are normal numbers, so they lose only factors 1 +- eps,
// at most 8 of them, which a final factor rho = 1 + 2^-48 >= (1 - eps)^-8 (or rho' = 1 - 2^-48
// for lower bounds) repays (counted at each function below). rho costs a relative margin of
// 2^-48 in the decisions; kappa, on the error bound only, costs nothing measurable.
#pragma once

#include <CGAL/enum.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "certcyl/primitives.hpp"
#include "certcyl/vec3.hpp"

namespace certcyl::detail {

inline constexpr double kStaticEps = 0x1p-52;            // eps: relative error of one operation
inline constexpr double kStaticKappaUp = 1 + 0x1p-40;    // kappa: inflates error bounds
inline constexpr double kStaticRoundUp = 1 + 0x1p-48;    // rho: repays a few roundings of a value
inline constexpr double kStaticRoundDown = 1 - 0x1p-48;  // rho': the same for lower bounds
inline constexpr double kStaticTau = 0x1p-600;           // tau: absolute slack for underflow
inline constexpr double kStaticAxisGuard = 0x1p-200;     // A.A >= this (world frame)

struct Bounded {
  double v = 0, e = 0;  // |v - x| <= e (header comment)

  [[gnu::always_inline]] friend Bounded operator+(const Bounded& a, const Bounded& b) {
    const double v = a.v + b.v;
    return {v, a.e + b.e + kStaticEps * std::abs(v)};
  }
  [[gnu::always_inline]] friend Bounded operator-(const Bounded& a, const Bounded& b) {
    const double v = a.v - b.v;
    return {v, a.e + b.e + kStaticEps * std::abs(v)};
  }
  [[gnu::always_inline]] friend Bounded operator-(const Bounded& a) { return {-a.v, a.e}; }
  [[gnu::always_inline]] friend Bounded operator*(const Bounded& a, const Bounded& b) {
    const double v = a.v * b.v;
    return {v, kStaticEps * std::abs(v) + std::abs(a.v) * b.e + std::abs(b.v) * a.e + a.e * b.e};
  }
};

[[gnu::always_inline]] inline Bounded exactly(double x) { return {x, 0}; }
[[gnu::always_inline]] inline Bounded abs(const Bounded& a) { return {std::abs(a.v), a.e}; }
// a * b for an exact a: the product rule with a.e = 0.
[[gnu::always_inline]] inline Bounded times_exact(double a, const Bounded& b) {
  const double v = a * b.v;
  return {v, kStaticEps * std::abs(v) + std::abs(a) * b.e};
}
// a - b for exact a, b: the difference rule with a.e = b.e = 0.
[[gnu::always_inline]] inline Bounded difference(double a, double b) {
  const double v = a - b;
  return {v, kStaticEps * std::abs(v)};
}
// 2^j a for a small j >= 0 (exact: no overflow in the world frame).
[[gnu::always_inline]] inline Bounded times_power_of_two(const Bounded& a, double two_j) { return {two_j * a.v, two_j * a.e}; }
// a / b for b certainly positive (b.v > b.e; the caller checks).
[[gnu::always_inline]] inline Bounded divide_positive(const Bounded& a, const Bounded& b) {
  const double v = a.v / b.v;
  return {v, kStaticEps * std::abs(v) + (a.e + std::abs(v) * (1 + 0x1p-50) * b.e) / (b.v - b.e)};
}

// w(t): covers |t.v - x| (header comment).
[[gnu::always_inline]] inline double radius_of(const Bounded& t) { return t.e * kStaticKappaUp + kStaticTau; }
// Certified upper and lower bounds of x, as doubles: fl(t.v +- w(t)) is within (1 +- eps) of
// t.v +- w(t); callers account for that factor where they combine them.
[[gnu::always_inline]] inline double upper_of(const Bounded& t) { return t.v + radius_of(t); }
[[gnu::always_inline]] inline double lower_of(const Bounded& t) { return t.v - radius_of(t); }

enum class StaticSign { negative, positive, unknown };

inline StaticSign static_sign(const Bounded& t) {
  const double w = radius_of(t);
  if (t.v > w) return StaticSign::positive;
  if (t.v < -w) return StaticSign::negative;
  return StaticSign::unknown;
}

// Vector forms of the rules (the same rules, written out so that they inline).
[[gnu::always_inline]] inline Vec3<Bounded> difference(const Vec3<double>& a, const Vec3<double>& b) {
  return {difference(a.x, b.x), difference(a.y, b.y), difference(a.z, b.z)};
}
[[gnu::always_inline]] inline Bounded dot(const Vec3<Bounded>& a, const Vec3<Bounded>& b) {
  return (a.x * b.x + a.y * b.y) + a.z * b.z;
}
[[gnu::always_inline]] inline Bounded dot(const Vec3<double>& a, const Vec3<Bounded>& b) {
  return (times_exact(a.x, b.x) + times_exact(a.y, b.y)) + times_exact(a.z, b.z);
}
[[gnu::always_inline]] inline Vec3<Bounded> cross(const Vec3<Bounded>& a, const Vec3<Bounded>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
[[gnu::always_inline]] inline Vec3<Bounded> cross(const Vec3<double>& a, const Vec3<Bounded>& b) {
  return {times_exact(a.y, b.z) - times_exact(a.z, b.y), times_exact(a.z, b.x) - times_exact(a.x, b.z),
          times_exact(a.x, b.y) - times_exact(a.y, b.x)};
}

// 2^-floor(log2 m) for a normal m > 0, so that m times it lies in [1, 2); 0 when m is zero,
// subnormal, infinite or NaN, or when the factor itself would not be a normal double.
inline double power_of_two_normaliser(double m) {
  const std::uint64_t bits = std::bit_cast<std::uint64_t>(m);
  const std::uint64_t e = (bits >> 52) & 0x7ff;  // biased exponent of m
  if (e == 0 || e >= 2046) return 0;
  return std::bit_cast<double>(static_cast<std::uint64_t>(2046 - e) << 52);  // 2^(1023 - (e - 1023)) biased
}

// The world frame of a pair of binary64 cylinders with the filter's quantities.
struct StaticPair {
  Cylinder<double> c0, c1;  // world input (exact)
  Vec3<Bounded> A0, A1, T;  // axes, T = (p0_1 + p1_1) - (p0_0 + p1_0)
  Bounded AA0, AA1;         // squared axis lengths
  Bounded rr0, rr1;         // squared radii
  bool usable = false;      // the guards of the header comment hold

  static StaticPair make(const Cylinder<double>& c0, const Cylinder<double>& c1) {
    StaticPair s;
    s.c0 = c0;
    s.c1 = c1;
    s.A0 = difference(c0.p1, c0.p0);
    s.A1 = difference(c1.p1, c1.p0);
    const auto sum = [](const Point3<double>& a, const Point3<double>& b) {
      const Point3<double> v = a + b;
      return Vec3<Bounded>{{v.x, kStaticEps * std::abs(v.x)}, {v.y, kStaticEps * std::abs(v.y)}, {v.z, kStaticEps * std::abs(v.z)}};
    };
    s.T = sum(c1.p0, c1.p1) - sum(c0.p0, c0.p1);
    s.AA0 = dot(s.A0, s.A0);
    s.AA1 = dot(s.A1, s.A1);
    s.rr0 = times_exact(c0.radius, exactly(c0.radius));
    s.rr1 = times_exact(c1.radius, exactly(c1.radius));
    s.usable = lower_of(s.AA0) >= kStaticAxisGuard && lower_of(s.AA1) >= kStaticAxisGuard;
    return s;
  }
};

// ---- direction D: sign of |D.T| - phi2(D) and an upper bound of phi2(D) / |D.T| ---------------
// The terms of separation_terms: c = |D.T| - |D.A0| - |D.A1|, p = 4 r0^2 |D x A0|^2 / A0.A0,
// q likewise; kept apart so that the ratio bound reuses them. Degree: c 2, p and q 4 over 2.
// |D x A|^2 is evaluated as (D.D)(A.A) - (D.A)^2 (Lagrange's identity, exact in the reals), which
// reuses D.A and costs fewer operations than the cross product; its error bound follows the
// same rules.
struct StaticDirection {
  Bounded dT, dA0, dA1, p, q;
};

[[gnu::always_inline]] inline Bounded exact_dot(const Vec3<double>& a, const Vec3<double>& b) {
  const Bounded x = exactly(a.x) * exactly(b.x), y = exactly(a.y) * exactly(b.y), z = exactly(a.z) * exactly(b.z);
  return (x + y) + z;
}

inline StaticDirection static_direction(const StaticPair& s, const Vec3<double>& D) {
  const Bounded DD = exact_dot(D, D), DA0 = dot(D, s.A0), DA1 = dot(D, s.A1);
  const Bounded x0 = DD * s.AA0 - DA0 * DA0, x1 = DD * s.AA1 - DA1 * DA1;
  return {abs(dot(D, s.T)), abs(DA0), abs(DA1), divide_positive(times_power_of_two(s.rr0 * x0, 4), s.AA0),
          divide_positive(times_power_of_two(s.rr1 * x1, 4), s.AA1)};
}

// Sign of c - sqrt(p) - sqrt(q) (= separation_sign), or unknown.
//   positive: L = fl(lower(c)) > fl(rho * fl(sqrt(fl(upper p)) + sqrt(fl(upper q)))).
//     c >= L / (1 + eps) when L > 0; sqrt(p) + sqrt(q) <= R / (1 - eps)^2.5 with R the rounded
//     sum of rounded roots; fl(rho R) >= rho (1 - eps) R >= R (1 + eps) / (1 - eps)^2.5.
//   negative: H = fl(upper c) < 0, or fl(rho H) < fl(rho' S) with S the rounded sum of the
//     rounded roots of the rounded lower bounds of p, q (clamped at 0):
//     c <= H / (1 - eps) <= fl(rho H) (exact when H is subnormal: fl is monotone);
//     sqrt(p) + sqrt(q) >= S / (1 + eps)^2.5 >= fl(rho' S).
inline StaticSign static_separation_sign(const StaticDirection& t) {
  const Bounded c = t.dT - t.dA0 - t.dA1;
  const double L = lower_of(c);
  if (L > 0) {
    const double R = std::sqrt(upper_of(t.p)) + std::sqrt(upper_of(t.q));
    if (L > kStaticRoundUp * R) return StaticSign::positive;
  }
  const double H = upper_of(c);
  if (H < 0) return StaticSign::negative;
  const double S = std::sqrt(std::max(lower_of(t.p), 0.0)) + std::sqrt(std::max(lower_of(t.q), 0.0));
  if (kStaticRoundUp * H < kStaticRoundDown * S) return StaticSign::negative;
  return StaticSign::unknown;
}

// A certified upper bound of phi2(D) / |D.T| (>= phi*), or +infinity when |D.T| may vanish.
// N = rounded sum of the four rounded upper bounds (>= phi2 (1 - eps)^5), M = fl(lower |D.T|)
// (<= |D.T| (1 + eps)): fl(rho fl(N / M)) >= (phi2 / |D.T|) rho (1 - eps)^8 >= the ratio.
inline double static_ratio_upper(const StaticDirection& t) {
  const double M = lower_of(t.dT);
  if (!(M > 0)) return std::numeric_limits<double>::infinity();
  const double N = (upper_of(t.dA0) + upper_of(t.dA1)) + (std::sqrt(upper_of(t.p)) + std::sqrt(upper_of(t.q)));
  return kStaticRoundUp * (N / M);
}

// ---- point X: strictly inside both cylinders, and sigma(X) ---------------------------------
// Per cylinder (predicates/point_in_cylinder.hpp): with w = X - p0, s = w.A (degree 2),
// AA - s (degree 2), r^2 AA - |w x A|^2 (degree 4); X is interior iff all three are positive.
struct StaticPointSide {
  Bounded s, AA_minus_s, radial_slack, ww;  // ww = |w x A|^2
};

inline StaticPointSide static_point_side(const Cylinder<double>& c, const Vec3<Bounded>& A, const Bounded& AA, const Bounded& rr,
                                         const Point3<double>& X) {
  const Vec3<Bounded> w = difference(X, c.p0);
  const Bounded s = dot(w, A);
  const Vec3<Bounded> x = cross(w, A);
  const Bounded ww = dot(x, x);
  return {s, AA - s, rr * AA - ww, ww};
}

struct StaticPoint {
  StaticPointSide side0, side1;
  bool far = false;  // some |X_i| > 4: outside both world boxes, hence outside the cylinders
};

inline StaticPoint static_point(const StaticPair& s, const Point3<double>& X) {
  StaticPoint p;
  // A point of a world cylinder is within r < 2 of its axis segment, whose coordinates are < 2.
  if (!(std::abs(X.x) <= 4 && std::abs(X.y) <= 4 && std::abs(X.z) <= 4)) {
    p.far = true;
    return p;
  }
  p.side0 = static_point_side(s.c0, s.A0, s.AA0, s.rr0, X);
  p.side1 = static_point_side(s.c1, s.A1, s.AA1, s.rr1, X);
  return p;
}

// positive: X strictly inside both; negative: X not strictly inside both; unknown.
inline StaticSign static_inside_both(const StaticPoint& p) {
  if (p.far) return StaticSign::negative;
  bool all_positive = true;
  for (const StaticPointSide* side : {&p.side0, &p.side1}) {
    for (const Bounded* t : {&side->s, &side->AA_minus_s, &side->radial_slack}) {
      const StaticSign g = static_sign(*t);
      if (g == StaticSign::negative) return StaticSign::negative;
      all_positive = all_positive && g == StaticSign::positive;
    }
  }
  return all_positive ? StaticSign::positive : StaticSign::unknown;
}

// A certified upper bound of sigma(X) (cylinder_certificates.hpp), or +infinity.
//   axial  |2s - AA| / AA:     fl(U / M) with U = fl(upper |2s - AA|) >= (1 - eps) |2s - AA|,
//                              M = fl(lower AA) <= (1 + eps) AA: >= (1 - eps)^3 times the term;
//   radial sqrt(ww / (r^2 AA)): fl(sqrt(fl(U / M))) likewise, >= (1 - eps)^3.5 times the term;
// fl(rho max) >= (1 - eps)^4.5 rho (the largest term) >= sigma(X).
inline double static_sigma_upper(const StaticPair& s, const StaticPoint& p) {
  if (p.far) return std::numeric_limits<double>::infinity();
  double sigma = 0;
  const auto one = [&sigma](const StaticPointSide& side, const Bounded& AA, const Bounded& rr) {
    const double axial = upper_of(abs(times_power_of_two(side.s, 2) - AA)) / lower_of(AA);
    const double rAA = lower_of(rr * AA);
    const double radial = rAA > 0 ? std::sqrt(upper_of(side.ww) / rAA) : std::numeric_limits<double>::infinity();
    sigma = std::max({sigma, axial, radial});
  };
  one(p.side0, s.AA0, s.rr0);
  one(p.side1, s.AA1, s.rr1);
  return kStaticRoundUp * sigma;
}

// A certified lower bound of phi* from the segment between the midpoints, or 0. The point
// X_t = m0 + t Delta has sigma_0(X_t) = t sigma_0(m1) and sigma_1(X_t) = (1 - t) sigma_1(m0),
// so min over t of sigma(X_t) = s0 s1 / (s0 + s1) with s0 = sigma_0(m1), s1 = sigma_1(m0), and
// phi* >= 1 / sigma(X_t) gives phi* >= 1/s0 + 1/s1 (equality for two balls). With w = m1 - m0
// = T/2:  s0 = max(|T.A0| / A0.A0, sqrt(|T x A0|^2 / (4 r0^2 A0.A0))),
// |T x A0|^2 = (T.T)(A0.A0) - (T.A0)^2; s1 likewise (|T.A1|, |T x A1|).
// Upper bounds of s0, s1 as in static_sigma_upper: >= (1 - eps)^4.5 rho s_i >= s_i. Then
// fl(rho' fl(fl(1/u0) + fl(1/u1))) <= rho' (1 + eps)^3 (1/u0 + 1/u1) <= 1/u0 + 1/u1.
inline double static_segment_phi_lower(const StaticPair& s) {
  const Bounded TT = dot(s.T, s.T);
  const auto sigma_upper = [&TT, &s](const Vec3<Bounded>& A, const Bounded& AA, const Bounded& rr) {
    const Bounded TA = dot(s.T, A);
    const double axial = upper_of(abs(TA)) / lower_of(AA);
    const double den = lower_of(times_power_of_two(rr * AA, 4));
    const double radial = den > 0 ? std::sqrt(upper_of(TT * AA - TA * TA) / den) : std::numeric_limits<double>::infinity();
    return kStaticRoundUp * std::max(axial, radial);
  };
  const double u0 = sigma_upper(s.A0, s.AA0, s.rr0), u1 = sigma_upper(s.A1, s.AA1, s.rr1);
  if (!(u0 > 0 && u1 > 0)) return 0;  // T may vanish: no bound
  const double lower = kStaticRoundDown * (1 / u0 + 1 / u1);
  return std::isfinite(lower) ? lower : 0;
}

}  // namespace certcyl::detail
