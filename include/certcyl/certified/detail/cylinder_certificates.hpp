// certcyl/certified/detail/cylinder_certificates.hpp -- the exact checks behind every answer of
// certified_cylinder_cylinder.
//
// Notation (design note, section 4). Cylinder i has endpoints p0_i, p1_i, axis A_i = p1_i - p0_i,
// radius r_i, midpoint m_i. We work with T = 2 Delta = (p0_1 + p1_1) - (p0_0 + p1_0), which needs
// no division, and with
//   phi2(D) = |D.A0| + |D.A1| + 2 r0 |D x A0| / |A0| + 2 r1 |D x A1| / |A1|  ( = 2 phi(D) ),
// so that phi(D) / (D.Delta) = phi2(D) / (D.T) and
//   phi* = min { phi2(D) : D.T = 1 }   (separated iff phi* < 1, touching iff = 1).
//
// Checks (each a sign of a polynomial in the input and the certificate):
//   separation_sign(D)  sign of |D.T| - phi2(D) = c - sqrt(p) - sqrt(q) with
//                         c = |D.T| - |D.A0| - |D.A1|,  p = 4 r0^2 |D x A0|^2 / A0.A0,
//                         q = 4 r1^2 |D x A1|^2 / A1.A1,
//                       decided by squaring (sign_c_minus_roots), in the exact types after
//                       outward-rounded 128-bit MPFR bounds (separation_sign_bounds) left it
//                       open. POSITIVE: D separates
//                       (phi* < 1). ZERO: phi(D) = D.Delta, so phi* <= 1 (not overlapping).
//                       Degree: c is 2 in D and the input; the final comparison is degree 8 in
//                       D and 12 in the input (after clearing the denominators A_i.A_i).
//   classify_point      the polynomial point-in-cylinder test (predicates/point_in_cylinder.hpp):
//                       a point strictly inside both proves overlapping; a point in both closed
//                       cylinders proves "not separated".
// Run on Interval_nt these either decide correctly or throw Uncertain_conversion_exception;
// the caller catches it in one place (interval_attempt) and reruns on Gmpq.
//
// Bounds on phi* (growth-distance duality, design note section 4): for any D with D.T != 0,
//   phi* <= phi2(D) / |D.T|;
// for any point X, with sigma(X) = max_i max( |(2X - p0_i - p1_i).A_i| / A_i.A_i,
//                                           |(X - p0_i) x A_i| / (r_i |A_i|) ),
// X lies in both cylinders scaled by sigma(X) about their midpoints, so the growth distance
// 1/phi* is at most sigma(X):  phi* >= 1 / sigma(X).
// (Proof: the scaled cylinders m_i + s (K_i - m_i) meet iff s phi(D) >= D.Delta for every D,
// i.e. iff s >= 1/phi*.)
#pragma once

#include <CGAL/FPU.h>
#include <CGAL/Interval_nt.h>
#include <CGAL/Gmpq.h>
#include <CGAL/Gmpz.h>
#include <CGAL/Mpzf.h>
#include <gmp.h>
#include <mpfr.h>

#include <cmath>
#include <limits>
#include <optional>
#include <type_traits>
#include <utility>

#include "certcyl/number_traits.hpp"
#include "certcyl/predicates/point_in_cylinder.hpp"
#include "certcyl/primitives.hpp"

namespace certcyl::detail {

// |x| as an enclosure: for an interval that straddles zero, [0, max]; never throws. (Not named
// `magnitude`: ADL would then pick CGAL::magnitude(Interval_nt), which returns the double max |x|.)
template <class NT>
NT abs_enclosure(const NT& x) {
  if constexpr (std::is_same_v<NT, Interval>) {
    return CGAL::abs(x);
  } else {
    return nt::sign(x) == CGAL::NEGATIVE ? NT(-x) : x;
  }
}

// Sign tests through nt::sign (nt::is_zero and friends are ambiguous with CGAL's under ADL).
template <class NT>
bool sign_is(const NT& x, CGAL::Sign s) {
  return nt::sign(x) == s;
}

// x^2 as an enclosure with a non-negative lower end for intervals.
template <class NT>
NT squared(const NT& x) {
  if constexpr (std::is_same_v<NT, Interval>) {
    return CGAL::square(x);
  } else {
    return x * x;
  }
}

template <class NT>
NT squared_norm(const Vec3<NT>& v) {
  return squared(v.x) + squared(v.y) + squared(v.z);
}

// A stop predicate that never asks an iteration (an ellipsoid run, the optimiser's Newton
// steps) to stop; the query passes its time-limit check instead.
struct NeverStop {
  bool operator()() const { return false; }
};

// The quantities every check needs, in one number type.
template <class NT>
struct CylinderPair {
  Cylinder<NT> c0, c1;
  Vec3<NT> A0, A1, T;  // axes and T = 2 Delta
  NT AA0, AA1;         // squared axis lengths

  static CylinderPair make(const Cylinder<NT>& c0, const Cylinder<NT>& c1) {
    CylinderPair d{c0, c1, c0.axis(), c1.axis(), (c1.p0 + c1.p1) - (c0.p0 + c0.p1), NT(), NT()};
    d.AA0 = squared_norm(d.A0);
    d.AA1 = squared_norm(d.A1);
    return d;
  }
};

// Sign of c - sqrt(p) - sqrt(q) for p, q >= 0, by squaring (design note, section 4):
// c < 0: negative; c = 0: zero iff p = q = 0; c > 0: with e = c^2 - p - q, positive iff
// e >= 0 and e^2 > 4pq, zero iff e >= 0 and e^2 = 4pq.
template <class NT>
CGAL::Sign sign_c_minus_roots(const NT& c, const NT& p, const NT& q) {
  const CGAL::Sign sc = nt::sign(c);
  if (sc == CGAL::NEGATIVE) return CGAL::NEGATIVE;
  if (sc == CGAL::ZERO) return (sign_is(p, CGAL::ZERO) && sign_is(q, CGAL::ZERO)) ? CGAL::ZERO : CGAL::NEGATIVE;
  const NT e = squared(c) - p - q;
  if (sign_is(e, CGAL::NEGATIVE)) return CGAL::NEGATIVE;
  // else: e >= 0, so c > sqrt(p) + sqrt(q) iff e > 2 sqrt(pq) iff e^2 > 4pq.
  return nt::sign(NT(squared(e) - nt::constant<NT>(4) * p * q));
}

// The three numbers of separation_sign for direction D.
template <class NT>
struct SeparationTerms {
  NT c, p, q;
};

// For a ring without division (Mpzf), the three numbers times k = A0.A0 A1.A1 > 0 (c k, p k^2,
// q k^2): the sign of c - sqrt(p) - sqrt(q) is unchanged.
template <class NT>
SeparationTerms<NT> separation_terms(const CylinderPair<NT>& d, const Vec3<NT>& D) {
  const NT four = nt::constant<NT>(4);
  const NT c = abs_enclosure(dot(D, d.T)) - abs_enclosure(dot(D, d.A0)) - abs_enclosure(dot(D, d.A1));
  const NT p = four * squared(d.c0.radius) * squared_norm(cross(D, d.A0));
  const NT q = four * squared(d.c1.radius) * squared_norm(cross(D, d.A1));
  if constexpr (NumberTraits<NT>::is_field) {
    return {c, p / d.AA0, q / d.AA1};
  } else {
    return {c * d.AA0 * d.AA1, p * d.AA0 * squared(d.AA1), q * squared(d.AA0) * d.AA1};
  }
}

// Sign of |D.T| - phi2(D) by squaring (sign_c_minus_roots), in NT.
template <class NT>
CGAL::Sign separation_sign_exact(const CylinderPair<NT>& d, const Vec3<NT>& D) {
  const SeparationTerms<NT> t = separation_terms(d, D);
  return sign_c_minus_roots(t.c, t.p, t.q);
}

template <class NT>
inline constexpr bool is_exact_ring_v = std::is_same_v<NT, CGAL::Gmpz> || std::is_same_v<NT, CGAL::Mpzf> || std::is_same_v<NT, Rational>;

// x rounded to MPFR in the direction rnd, for the exact types Gmpz, Mpzf and Rational.
template <class NT>
void mpfr_set_exact(mpfr_t y, const NT& x, mpfr_rnd_t rnd) {
  if constexpr (std::is_same_v<NT, CGAL::Gmpz>) {
    mpfr_set_z(y, x.mpz(), rnd);
  } else if constexpr (std::is_same_v<NT, Rational>) {
    mpfr_set_q(y, x.mpq(), rnd);
  } else {
    const CGAL::Gmpq q = static_cast<CGAL::Gmpq>(x);
    mpfr_set_q(y, q.mpq(), rnd);
  }
}

// A bound on 2 r |x| / sqrt(AA) (r, AA > 0) in MPFR: below it for rnd = MPFR_RNDD, above it for
// MPFR_RNDU. Every operation is monotone in its operands and rounded in rnd's direction (the
// divisor AA the other way, each |x_k| in rnd's direction), so the bound holds whatever y's
// precision.
template <class NT>
void bound_radial_term(mpfr_t y, const Vec3<NT>& x, const NT& r, const NT& AA, mpfr_rnd_t rnd) {
  const mpfr_rnd_t other = rnd == MPFR_RNDD ? MPFR_RNDU : MPFR_RNDD;
  mpfr_t t;
  mpfr_init2(t, mpfr_get_prec(y));
  mpfr_set_zero(y, 1);
  for (const NT* c : {&x.x, &x.y, &x.z}) {
    mpfr_set_exact(t, *c, nt::sign(*c) == CGAL::NEGATIVE ? other : rnd);
    mpfr_sqr(t, t, rnd);
    mpfr_add(y, y, t, rnd);
  }
  mpfr_set_exact(t, AA, other);
  mpfr_div(y, y, t, rnd);
  mpfr_sqrt(y, y, rnd);
  mpfr_set_exact(t, r, rnd);
  mpfr_mul(y, y, t, rnd);
  mpfr_mul_2ui(y, y, 1, rnd);
  mpfr_clear(t);
}

// The sign of |D.T| - phi2(D) = c - sqrt(p) - sqrt(q) (separation_terms) when cheap bounds
// decide it, for the exact types; nullopt otherwise. c (exact) decides alone when it is not
// positive; else c - sqrt(p) - sqrt(q) lies between two 128-bit MPFR bounds whose every
// operation is rounded outwards (bound_radial_term), and a bound of one sign decides. They leave
// open only directions within about 2^-120 (relative to the terms) of the boundary of S, where
// the squaring of separation_sign_exact, on numbers of tens of thousands of bits for wide
// input, runs.
template <class NT>
std::optional<CGAL::Sign> separation_sign_bounds(const CylinderPair<NT>& d, const Vec3<NT>& D) {
  static_assert(is_exact_ring_v<NT>);
  const NT c = abs_enclosure(dot(D, d.T)) - abs_enclosure(dot(D, d.A0)) - abs_enclosure(dot(D, d.A1));
  const CGAL::Sign sc = nt::sign(c);
  if (sc == CGAL::NEGATIVE) return CGAL::NEGATIVE;
  const Vec3<NT> x0 = cross(D, d.A0), x1 = cross(D, d.A1);
  const auto zero = [](const Vec3<NT>& v) { return CGAL::is_zero(v.x) && CGAL::is_zero(v.y) && CGAL::is_zero(v.z); };
  if (sc == CGAL::ZERO) return zero(x0) && zero(x1) ? CGAL::ZERO : CGAL::NEGATIVE;
  constexpr mpfr_prec_t kBits = 128;
  mpfr_t lo, hi, t;  // lo <= c - sqrt(p) - sqrt(q) <= hi
  mpfr_init2(lo, kBits);
  mpfr_init2(hi, kBits);
  mpfr_init2(t, kBits);
  mpfr_set_exact(lo, c, MPFR_RNDD);
  mpfr_set_exact(hi, c, MPFR_RNDU);
  for (const mpfr_rnd_t rnd : {MPFR_RNDU, MPFR_RNDD}) {
    mpfr_ptr bound = rnd == MPFR_RNDU ? lo : hi;  // less an upper bound of a root for lo
    const mpfr_rnd_t out = rnd == MPFR_RNDU ? MPFR_RNDD : MPFR_RNDU;
    bound_radial_term(t, x0, d.c0.radius, d.AA0, rnd);
    mpfr_sub(bound, bound, t, out);
    bound_radial_term(t, x1, d.c1.radius, d.AA1, rnd);
    mpfr_sub(bound, bound, t, out);
  }
  const int s_lo = mpfr_sgn(lo), s_hi = mpfr_sgn(hi);
  mpfr_clear(lo);
  mpfr_clear(hi);
  mpfr_clear(t);
  if (s_lo > 0) return CGAL::POSITIVE;
  if (s_hi < 0) return CGAL::NEGATIVE;
  return std::nullopt;
}

// Sign of |D.T| - phi2(D): POSITIVE when D separates the cylinders, ZERO when it supports
// both at a common plane (phi(D) = |D.Delta|). For the exact types, separation_sign_bounds
// first.
template <class NT>
CGAL::Sign separation_sign(const CylinderPair<NT>& d, const Vec3<NT>& D) {
  if constexpr (is_exact_ring_v<NT>) {
    if (const std::optional<CGAL::Sign> s = separation_sign_bounds(d, D)) return *s;
  }
  return separation_sign_exact(d, D);
}

template <class NT>
bool strictly_inside_both(const CylinderPair<NT>& d, const Point3<NT>& X) {
  return classify_point(X, d.c0) == Side::inside && classify_point(X, d.c1) == Side::inside;
}

template <class NT>
bool in_both_closed(const CylinderPair<NT>& d, const Point3<NT>& X) {
  return classify_point(X, d.c0) != Side::outside && classify_point(X, d.c1) != Side::outside;
}

// Runs f() on intervals under upward rounding; nullopt when an interval comparison could not
// be decided. This is the one place where Uncertain_conversion_exception is caught.
template <class F>
auto interval_attempt(F&& f) -> std::optional<decltype(f())> {
  CGAL::Protect_FPU_rounding<true> upward;
  try {
    return f();
  } catch (const CGAL::Uncertain_conversion_exception&) {
    return std::nullopt;
  }
}

// ---- conversions of exact input --------------------------------------------------------------

// x 2^j for a Rational, exactly.
// The result is a new number: Gmpq copies share their representation (CGAL's Handle_for), and
// writing through mpq() of a copy would change the caller's value too.
inline Rational times_two_power(const Rational& x, long j) {
  Rational y;
  if (j >= 0) mpq_mul_2exp(y.mpq(), x.mpq(), static_cast<mp_bitcnt_t>(j));
  if (j < 0) mpq_div_2exp(y.mpq(), x.mpq(), static_cast<mp_bitcnt_t>(-j));
  return y;
}

// The least common multiple of the denominators of a pair's 14 input numbers; nullopt once it
// exceeds max_bits bits.
inline std::optional<CGAL::Gmpz> denominator_lcm(const Cylinder<Rational>& c0, const Cylinder<Rational>& c1,
                                                 std::size_t max_bits = std::numeric_limits<std::size_t>::max()) {
  CGAL::Gmpz L = 1;
  for (const Cylinder<Rational>* c : {&c0, &c1})
    for (const Rational* q : {&c->p0.x, &c->p0.y, &c->p0.z, &c->p1.x, &c->p1.y, &c->p1.z, &c->radius}) {
      mpz_lcm(L.mpz(), L.mpz(), mpq_denref(q->mpq()));
      if (mpz_sizeinbase(L.mpz(), 2) > max_bits) return std::nullopt;
    }
  return L;
}

// q L as an integer, for L a multiple of q's denominator (denominator_lcm).
inline CGAL::Gmpz scaled_integer(const Rational& q, const CGAL::Gmpz& L) {
  CGAL::Gmpz n;
  mpz_divexact(n.mpz(), L.mpz(), mpq_denref(q.mpq()));
  mpz_mul(n.mpz(), n.mpz(), mpq_numref(q.mpq()));
  return n;
}

// True (and d set) when q is exactly a normal binary64 value (or zero) with a numerator below
// 2^53 and a denominator 2^k: the common case of binary64 input, read from the limbs without
// allocation or division. (Integers of 54 bits or more and subnormals are left out.)
inline bool exact_double(const Rational& q, double& d) {
  static_assert(GMP_LIMB_BITS == 64, "exact_double reads 64-bit limbs");
  mpz_srcptr num = mpq_numref(q.mpq());
  mpz_srcptr den = mpq_denref(q.mpq());
  const std::size_t num_limbs = mpz_size(num), den_limbs = mpz_size(den);
  if (num_limbs > 1 || den_limbs > 18) return false;
  for (std::size_t i = 0; i + 1 < den_limbs; ++i)
    if (mpz_getlimbn(den, static_cast<mp_size_t>(i)) != 0) return false;
  const mp_limb_t top = mpz_getlimbn(den, static_cast<mp_size_t>(den_limbs - 1));
  if ((top & (top - 1)) != 0) return false;  // not a power of two
  const mp_limb_t n = num_limbs == 0 ? 0 : mpz_getlimbn(num, 0);
  if (n >> 53 != 0) return false;
  const int k = static_cast<int>(64 * (den_limbs - 1)) + __builtin_ctzll(top);
  if (k > 1100) return false;
  const double magnitude = std::ldexp(static_cast<double>(n), -k);  // exact when normal
  if (n != 0 && !(magnitude >= std::numeric_limits<double>::min())) return false;
  d = mpz_sgn(num) < 0 ? -magnitude : magnitude;
  return true;
}

inline Interval enclose_interval(const Rational& q) {
  double d;
  if (exact_double(q, d)) return Interval(d);
  auto [lo, hi] = certcyl::enclose(q);  // qualified: detail::enclose (quadratic_number.hpp) would hide it
  return Interval(lo, hi);
}

inline double nearest_double(const Rational& q) {
  double d;
  if (exact_double(q, d)) return d;
  return round_to_nearest<double>(q);
}

// ---- bounds on phi* (intervals only; call under upward rounding) -----------------------------

// An enclosure of phi2(D) / |D.T|, the upper bound on phi* that D gives; nullopt when D.T may
// vanish.
inline std::optional<Interval> ratio_enclosure(const CylinderPair<Interval>& d, const Vec3<Interval>& D) {
  const Interval dt = CGAL::abs(dot(D, d.T));
  if (!(dt.inf() > 0)) return std::nullopt;
  const Interval two(2);
  const Interval phi2 = CGAL::abs(dot(D, d.A0)) + CGAL::abs(dot(D, d.A1)) +
                        two * d.c0.radius * CGAL::sqrt(squared_norm(cross(D, d.A0)) / d.AA0) +
                        two * d.c1.radius * CGAL::sqrt(squared_norm(cross(D, d.A1)) / d.AA1);
  return phi2 / dt;
}

// An enclosure of sigma(X) (header comment): X lies in both cylinders scaled by sigma(X).
inline Interval scale_enclosure(const CylinderPair<Interval>& d, const Point3<Interval>& X) {
  auto one = [&X](const Cylinder<Interval>& c, const Vec3<Interval>& A, const Interval& AA) {
    const Interval axial = CGAL::abs(dot(Interval(2) * X - c.p0 - c.p1, A)) / AA;
    const Interval radial = CGAL::sqrt(squared_norm(cross(X - c.p0, A)) / (CGAL::square(c.radius) * AA));
    return Interval(std::max(axial.inf(), radial.inf()), std::max(axial.sup(), radial.sup()));
  };
  const Interval s0 = one(d.c0, d.A0, d.AA0), s1 = one(d.c1, d.A1, d.AA1);
  return Interval(std::max(s0.inf(), s1.inf()), std::max(s0.sup(), s1.sup()));
}

}  // namespace certcyl::detail
