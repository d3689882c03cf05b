// certcyl/certified/detail/line_nearest.hpp -- the binary64 value nearest to an endpoint of the
// certified line interval (circular cylinder, binary64 input), proved in double-double without
// building the exact endpoint; `nullopt` where the proof does not go through (the caller then
// rounds the exact value with MPFR, certified/detail/quadratic_number.hpp).
//
// Certificate. Every endpoint other than 0 and 1 is a simple root t of a polynomial p whose
// coefficients are decision polynomials of certified/detail/line_static_filter.hpp:
//   a tube root           p(m) = a m^2 + 2 b m + c   (a > 0, disc > 0; t the lower or upper root)
//   a tangent point       p(m) = a m + b             (disc = 0: t = -b/a)
//   cap0, cap1            p(m) = sd m + sw,  sd m + w1.A   (t0 = -sw/sd, t1 = -(w1.A)/sd)
// Let t^ be a double, 2^-60 <= |t^| <= 2^60, with neighbours t- < t^ < t+, and m- = (t- + t^)/2,
// m+ = (t^ + t+)/2: the reals that round to t^ (ties to even) include the open (m-, m+). If
// p(m-) and p(m+) are nonzero with opposite signs, a root lies in (m-, m+); it is t when p is
// linear, and for the quadratic when the signs are (-, +) for the upper root, (+, -) for the
// lower: p(m-) < 0 puts m- strictly between the roots and p(m+) > 0 puts m+ (> m- > lower
// root) above the upper one (symmetrically for the lower). Then t is in (m-, m+), not on a
// midpoint, and rounds to t^.
//
// Evaluation. m = t0 + H with t0 and H doubles (t0 the point of expansion, H = (t^ - t0) plus
// or minus half a gap, formed exactly: checked), p(t0 + H) = g0 + H (g1 + c2 H) with
// g0 = (c2 t0 + c1) t0 + c0 and g1 = 2 c2 t0 + c1, in double-double (DD of
// line_double_double.hpp: each operation returns (x op y)(1 + delta), |delta| <= eps = 2^-100;
// the doubling is exact) from the coefficients' double-double values c^i, whose errors are
// at most their proved bounds Ei (line_dd_bounds; c1 = 2b has 2 E_b). The program has rounding
// depth 5 and its expanded terms (c2 t0^2, c1 t0, c0, 2 c2 t0 H, c1 H, c2 H^2) sum in magnitude
// to at most T = |c^2| M^2 + |c^1| M + |c^0|, M = |t0| + |H|, so
//   |p^(m) - p(m)| <= E2 M^2 + E1 M + E0 + ((1 + eps)^5 - 1) T,
// the first part from the coefficients, the second from the rounding (the induction of
// line_static_filter.hpp). The bound used is twice that sum computed in double with
// 6 eps for (1 + eps)^5 - 1 and the high parts for |c^i| (|hi + lo| <= |hi| (1 + 2^-53)): it is
// at least 1.9 times the error, so the sign of p(m) is that of the high part of p^(m) when the
// high part exceeds it (as in line_double_double.hpp).
// No underflow, no overflow: inside the double-double window (nonzero inputs in
// [2^-120, 2^100]) the leaves are multiples of 2^-172 and at most 2^101; the coefficients have
// degree at most 4 in them; t0, t^ and H are multiples of 2^-114 (|t0|, |t^| >= 2^-60) and at
// most 2^61. So every double formed is a multiple of 2^-916 (> 2^-1074: rounding as with an
// unbounded exponent range, as in line_double_double.hpp) and below 2^20 2^404 2^122 < 2^996.
// Round-to-nearest is required (checked with the leaves).
// Where the processor has FMA, the coefficients and the expansions are formed in DDFused (the
// product's exact error term by one fused multiply-add; line_double_double.hpp), whose results
// are DD's bit for bit: the same proof, at about 40% fewer instructions for the coefficients.
//
// Signs in double first. With g0^, g1^, c2^ the double-double values above (high parts h, low
// parts l), each sign is first taken from v = fl(fl(g0h + fl(fl(fl(c2h H) + g1h) H)) + g0l)
// (five operations in binary64). Its distance to p(m):
//   |v - V| <= gamma_5 (|g0h| + |g0l| + (|g1h| + |c2h| |H|) |H|) + |g1l| |H| + |c2l| H^2,
// V = g0^ + (g1^ + c2^ H) H in exact arithmetic (the standard bound of a program of depth 5,
// gamma_5 = 5u / (1 - 5u) <= 6u, u = 2^-53, plus the low parts left out), and V is the
// double-double program above with its last three operations exact, a special case of the
// induction (each of its terms has at most five factors (1 + delta)), so |V - p(m)| is within
// the coefficients' and rounding's bound above. The bound used is twice the sum of the two,
// computed in double with M = |t0| + max(|H-|, |H+|) for both midpoints (the bound grows with M),
// so at least 1.9 times |v - p(m)|; the sign of v is taken when |v| exceeds it. The products
// are those of the double-double program (the exponent argument above applies; every term of
// the bound is a multiple of 2^-968, a normal number or zero). A sign it leaves undecided is
// evaluated in double-double as above. This replaces four double-double products an endpoint
// by about twenty flops on all but about 2^-48 of the candidates.
//
// Near-tangent lines. A tangent point t = -b/a with b = 0 exactly (the sign of b from the
// decision's adaptive signs, exact when it must be) is t = 0, rounded exactly. Where the
// decision needed more than double (the line is near a tangency, a rim or a cap plane) and the
// tube's roots lie so close to 0 and to each other that |p(m)| ~ |p'(t)| ulp(t) / 2 is below the
// bound (the roots of a line tangent near its foot point: |p(m)| ~ 2^-100 against a bound of
// about 2^-90 of the coefficients' magnitude), the proof cannot succeed and is not tried: an
// estimate in plain double (approximate_tube of line_static_filter.hpp) of |p'(t)| ulp(t) below
// an eighth of the estimated bound sends the endpoint straight to the exact rounding. The
// estimate only chooses which proof runs; it never gives an answer.
//
// Candidate. t0 from the high parts (the stable quadratic formula, or -c0/c1), then Newton
// steps t^ = t0 - g0 / g1 in double, re-expanding at t^ while it moves by more than 2^-40 |t0|
// (at most three times). The candidate only has to be right for the proof to succeed; a wrong
// one makes it fail, never give a wrong answer.
#pragma once

#include <qd/inline.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <optional>
#include <utility>

#include "certcyl/certified/detail/line_double_double.hpp"
#include "certcyl/certified/detail/line_shape.hpp"
#include "certcyl/certified/detail/line_static_filter.hpp"

namespace certcyl::detail {

// p(m) = c2 m^2 + c1 m + c0 (c2 = 0 for a linear p) with |c^i - ci| <= ei.
struct DDQuadratic {
  DD c0, c1, c2;
  double e0 = 0, e1 = 0, e2 = 0;
  bool linear = false;
};

// 2 x, exact (both parts doubled; no overflow in the window).
template <bool F>
DDT<F> dd_twice(const DDT<F>& x) {
  return DDT<F>(dd_real(2 * x.v.x[0], 2 * x.v.x[1]));
}

// The sign of p(t0 + H) when the bound decides it, ZERO otherwise (header comment); in the
// arithmetic T (DD, or DDFused with the same results where FMA is available).
template <class T>
class DDExpansion {
 public:
  DDExpansion(const DDQuadratic& p, double t0) : p_(p), c2_(p.c2), t0_(t0) {
    const T t(t0), c1(p.c1), c0(p.c0);
    if (p.linear) {
      g1_ = c1;
      g0_ = c1 * t + c0;
    } else {
      const T P = c2_ * t;
      g1_ = dd_twice(P) + c1;
      g0_ = (P + c1) * t + c0;
    }
  }

  // The Newton step from t0 (in double).
  double step() const { return -g0_.hi() / g1_.hi(); }

  // The signs of p(t0 + H_lo) and p(t0 + H_hi): in double where that decides, else in
  // double-double (header comment, "Signs in double first").
  std::pair<CGAL::Sign, CGAL::Sign> signs_at(double H_lo, double H_hi) const {
    const double e = half_bound(std::fabs(t0_) + std::max(std::fabs(H_lo), std::fabs(H_hi)));
    CGAL::Sign lo = sign_in_double(H_lo, e), hi = sign_in_double(H_hi, e);
    if (lo == CGAL::ZERO) lo = sign_at(H_lo);
    if (hi == CGAL::ZERO) hi = sign_at(H_hi);
    return {lo, hi};
  }

  // In double-double.
  CGAL::Sign sign_at(double H) const {
    const T h(H);
    const T v = p_.linear ? T(g0_ + g1_ * h) : T(g0_ + (g1_ + c2_ * h) * h);
    const double bound = 2 * half_bound(std::fabs(t0_) + std::fabs(H));
    if (v.hi() > bound) return CGAL::POSITIVE;
    if (v.hi() < -bound) return CGAL::NEGATIVE;
    return CGAL::ZERO;
  }

 private:
  // The coefficients' and the rounding's part of the bound at |m| <= M (before the factor 2).
  double half_bound(double M) const {
    constexpr double rounding = 6 * 0x1p-100;
    const double coefficients = (p_.e2 * M + p_.e1) * M + p_.e0;
    const double magnitude = (std::fabs(p_.c2.hi()) * M + std::fabs(p_.c1.hi())) * M + std::fabs(p_.c0.hi());
    return coefficients + rounding * magnitude;
  }

  // From the double-double values' parts in binary64; e = half_bound(M) with M >= |t0| + |H|.
  CGAL::Sign sign_in_double(double H, double e) const {
    constexpr double gamma5 = 6 * 0x1p-53;
    const double c2h = p_.c2.v.x[0], c2l = p_.c2.v.x[1];
    const double g1h = g1_.v.x[0], g1l = g1_.v.x[1], g0h = g0_.v.x[0], g0l = g0_.v.x[1];
    const double c2H = c2h * H, aH = std::fabs(H);
    const double v = (g0h + (c2H + g1h) * H) + g0l;
    const double local = gamma5 * (std::fabs(g0h) + std::fabs(g0l) + (std::fabs(g1h) + std::fabs(c2H)) * aH) +
                         (std::fabs(g1l) + std::fabs(c2l) * aH) * aH;
    const double bound = 2 * (e + local);
    if (v > bound) return CGAL::POSITIVE;
    if (v < -bound) return CGAL::NEGATIVE;
    return CGAL::ZERO;
  }

  const DDQuadratic& p_;
  T c2_;
  double t0_;
  T g0_, g1_;
};

inline bool in_parameter_window(double t) {
  const double m = std::fabs(t);
  return m >= 0x1p-60 && m <= 0x1p60;  // false for NaN
}

// Half the gaps from t to its neighbours below and above (t a nonzero normal double below the
// largest: the neighbours are the adjacent encodings; the differences are exact, Sterbenz, and
// so are the halvings, a gap being at least 2^-113 in the window).
inline void half_gaps(double t, double& below, double& above) {
  const auto bits = std::bit_cast<std::uint64_t>(t);
  const double up = std::bit_cast<double>(bits + 1), down = std::bit_cast<double>(bits - 1);  // in magnitude
  const double toward_plus = t > 0 ? up : down, toward_minus = t > 0 ? down : up;
  below = (toward_minus - t) / 2;
  above = (toward_plus - t) / 2;
}

// The double nearest to the root of p between the signs (lower, upper) at m- and m+ (for a
// linear p: any two opposite signs), starting from t0; nullopt when not proved.
template <class T>
std::optional<double> nearest_root(const DDQuadratic& p, double t0, CGAL::Sign upper_sign) {
  for (int step = 0;; ++step) {
    if (!in_parameter_window(t0)) return std::nullopt;
    const DDExpansion<T> x(p, t0);
    const double t = t0 + x.step();
    if (!in_parameter_window(t)) return std::nullopt;
    const double dt = t - t0;  // exact when |dt| <= |t0| / 2 (Sterbenz)
    if (!(std::fabs(dt) <= std::fabs(t0) * 0x1p-40)) {
      if (step == 3) return std::nullopt;
      t0 = t;
      continue;
    }
    // Half the gaps to the neighbours of t (exact: a gap is a power of two >= 2^-113).
    double below = 0, above = 0;
    half_gaps(t, below, above);
    double err_lo = 0, err_hi = 0;
    const double H_lo = qd::two_sum(dt, below, err_lo), H_hi = qd::two_sum(dt, above, err_hi);
    if (err_lo != 0 || err_hi != 0) return std::nullopt;
    const auto [s_lo, s_hi] = x.signs_at(H_lo, H_hi);
    if (s_lo == CGAL::ZERO || s_hi == CGAL::ZERO || s_lo == s_hi) return std::nullopt;
    if (upper_sign != CGAL::ZERO && s_hi != upper_sign) return std::nullopt;
    return t;
  }
}

// A proved nearest double; `exact` when the endpoint is that double (0, 1, a tangent point at 0).
struct ProvedNearest {
  double nearest;
  bool exact;
};

// The nearest doubles of a query's endpoints from its sign source (the double-double leaves
// and the bounds of line_static_filter.hpp); the tube's coefficients are made once.
class LineNearest {
 public:
  explicit LineNearest(StaticCircularSigns& s) : leaves_(s.double_double_leaves()), signs_(s) {}

  std::optional<ProvedNearest> operator()(BoundKind k, TubeState tube) {
    switch (k) {
      case BoundKind::range_lo: return ProvedNearest{0.0, true};
      case BoundKind::range_hi: return ProvedNearest{1.0, true};
      default: break;
    }
    if (leaves_ == nullptr) return std::nullopt;
    // A tangent point -b/a with b = 0 (header comment, "Near-tangent lines").
    if (tube == TubeState::point && k != BoundKind::cap0 && k != BoundKind::cap1 && signs_.sign_b() == CGAL::ZERO)
      return ProvedNearest{0.0, true};
    if ((k == BoundKind::tube_lo || k == BoundKind::tube_hi) && tube == TubeState::interval && hopeless_tube()) return std::nullopt;
    const std::optional<double> t = proved_with(k, tube, has_fused_multiply_add());
    if (!t) return std::nullopt;
    return ProvedNearest{*t, false};
  }

  // The same proof (without the shortcuts above) with the product's error term from Dekker's
  // split (`fused` false) or from a fused multiply-add (true; nullopt where the processor has
  // none): the same results, bit for bit (line_double_double.hpp). For the tests.
  std::optional<ProvedNearest> with_product(BoundKind k, TubeState tube, bool fused) {
    if (fused && !has_fused_multiply_add()) return std::nullopt;
    tube_.reset();
    const std::optional<double> t = proved_with(k, tube, fused);
    if (!t) return std::nullopt;
    return ProvedNearest{*t, false};
  }

 private:
  std::optional<double> proved_with(BoundKind k, TubeState tube, bool fused) {
#if CERTCYL_FUSED_DISPATCH
    if (fused) return proved_fused(k, tube);
#endif
    return proved<DD>(k, tube);
  }
#if CERTCYL_FUSED_DISPATCH
  [[gnu::target("fma"), gnu::flatten]] std::optional<double> proved_fused(BoundKind k, TubeState tube) {
    return proved<DDFused>(k, tube);
  }
#endif

  template <class T>
  std::optional<double> proved(BoundKind k, TubeState tube) {
    const CircularLeaves<DD>& l = *leaves_;
    namespace b = line_dd_bounds;
    using Q = CircularPolynomials<T>;
    if (k == BoundKind::cap0 || k == BoundKind::cap1) {
      DDQuadratic p;
      p.linear = true;
      const SV3<T> A = in<T>(l.A);
      p.c1 = DD(Q::dot(in<T>(l.d), A));
      p.e1 = signs_.dd_bound_value(b::dot_ld);
      p.c0 = DD(Q::dot(in<T>(k == BoundKind::cap0 ? l.w : l.w1), A));
      p.e0 = signs_.dd_bound_value(b::dot_ll);
      return nearest_root<T>(p, -p.c0.hi() / p.c1.hi(), CGAL::ZERO);
    }
    if (!tube_) make_tube<T>();
    const DDQuadratic& q = *tube_;
    const double a = q.c2.hi(), b2 = q.c1.hi(), c = q.c0.hi();
    if (tube == TubeState::point) {
      // a m + b: the same coefficients, halved middle one (exact).
      DDQuadratic p;
      p.linear = true;
      p.c1 = q.c2;
      p.e1 = q.e2;
      p.c0 = DD(dd_real(q.c1.v.x[0] / 2, q.c1.v.x[1] / 2));
      p.e0 = q.e1 / 2;
      return nearest_root<T>(p, -b2 / (2 * a), CGAL::ZERO);
    }
    // The stable formula from the high parts: roots of a m^2 + b2 m + c.
    const double disc = b2 * b2 - 4 * a * c;
    if (!(disc > 0)) return std::nullopt;
    const double qq = -0.5 * (b2 + std::copysign(std::sqrt(disc), b2));
    const double r1 = qq / a, r2 = c / qq;
    const bool upper = k == BoundKind::tube_hi;
    const double t0 = upper ? std::max(r1, r2) : std::min(r1, r2);
    return nearest_root<T>(q, t0, upper ? CGAL::POSITIVE : CGAL::NEGATIVE);
  }

  // Whether the tube roots' proof cannot succeed (header comment, "Near-tangent lines"): only
  // after a decision that needed more than double; an estimate, never a sign.
  bool hopeless_tube() {
    if (!hopeless_) hopeless_ = estimate_hopeless();
    return *hopeless_;
  }
  bool estimate_hopeless() const {
    if (signs_.depth() == StaticCircularSigns::Depth::binary64) return false;
    double a = 0, b = 0, c = 0;
    signs_.approximate_tube(a, b, c);
    if (!(a > 0)) return false;
    // |p'(t)| = 2 sqrt(b^2 - a c) at either root, with room for the double's cancellation.
    const double disc = b * b - a * c, slack = 0x1p-48 * (b * b + std::fabs(a * c));
    const double slope = 2 * std::sqrt(std::max(disc, 0.0) + slack);
    const double t = (std::fabs(b) + std::sqrt(std::max(disc, 0.0) + slack)) / a;  // at least either root's size
    namespace bd = line_dd_bounds;
    const double e2 = signs_.dd_bound_value(bd::a), e1 = 2 * signs_.dd_bound_value(bd::b), e0 = signs_.dd_bound_value(bd::excess);
    const double bound = 2 * ((e2 * t + e1) * t + e0);
    const double change = slope * t * 0x1p-52;  // |p'(t)| times the gap above |t|, at least
    return 8 * change < bound;
  }

  // A leaf vector in the arithmetic T.
  template <class T>
  static SV3<T> in(const SV3<DD>& x) {
    return {T(x.x), T(x.y), T(x.z)};
  }

  // a, 2b and c (header comment), with u = w x A and v = d x A shared: the same programs as
  // CircularPolynomials a, b and excess, so their bounds apply.
  template <class T>
  void make_tube() {
    const CircularLeaves<DD>& l = *leaves_;
    namespace bd = line_dd_bounds;
    const SV3<T> w = in<T>(l.w), A = in<T>(l.A);
    const T r(l.r);
    const SV3<T> u = scross(w, A), v = scross(in<T>(l.d), A);
    DDQuadratic p;
    p.c2 = DD(sdot(v, v));
    p.e2 = signs_.dd_bound_value(bd::a);
    p.c1 = DD(dd_twice(sdot(u, v)));
    p.e1 = 2 * signs_.dd_bound_value(bd::b);
    p.c0 = DD(sdot(u, u) - r * r * sdot(A, A));
    p.e0 = signs_.dd_bound_value(bd::excess);
    tube_ = p;
  }

  const CircularLeaves<DD>* leaves_;
  StaticCircularSigns& signs_;
  std::optional<DDQuadratic> tube_;
  std::optional<bool> hopeless_;
};

}  // namespace certcyl::detail
