// certcyl/certified/detail/cylinder_ring_frame.hpp -- the exact input of a cylinder pair as
// dyadic numbers (CGAL::Mpzf), for exact checks without Gmpq's gcds and allocations.
//
// Semantics: the ring frame is the input multiplied by a positive rational s,
//   s = L 2^e,  L a positive integer, e an integer,
// chosen so that every coordinate and radius is a dyadic number (an integer times a power of
// two), exactly representable as Mpzf:
//   binary64 input     L = 1, e = the world frame's exponent (the input is dyadic already);
//   other rational     L = the least common multiple of the 14 denominators, e = 0 (the
//                      input becomes integers).
// Every check of detail/cylinder_certificates.hpp is a sign of a polynomial that is homogeneous
// in the lengths (the coordinates and radii together) and in the direction, so its sign in the
// ring frame is its sign in the input frame: separation_sign (c, sqrt(p), sqrt(q) all scale by
// s), classify_point (each slack scales by a positive power of s), and the touching proof of
// detail/cylinder_touching.hpp (prove_touching_ring). Directions are the same in both frames;
// points are divided by s on the way out (to_input, in Gmpq, once per answer).
//
// Method: L from mpz_lcm of the denominators; integers converted limb by limb (mpzf_from_integer).
// When L exceeds kRingFrameMaxBits bits (rational input with large, unrelated denominators) the
// frame is not built and the caller keeps Gmpq: Mpzf numbers then are as large as Gmpq's and
// no faster.
#pragma once

#include <CGAL/Gmpfr.h>
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

#include "certcyl/certified/detail/cylinder_certificates.hpp"
#include "certcyl/certified/detail/cylinder_ellipsoid.hpp"
#include "certcyl/number_traits.hpp"

namespace certcyl::detail {

inline constexpr std::size_t kRingFrameMaxBits = 4096;

// The integer n as an Mpzf, exactly. CGAL's Mpzf(const Gmpz&) copies the magnitude's limbs
// (it ignores the sign, and reads garbage for zero): zero is made apart and the sign applied
// after.
inline CGAL::Mpzf mpzf_from_integer(const CGAL::Gmpz& n) {
  const int sign = mpz_sgn(n.mpz());
  if (sign == 0) return CGAL::Mpzf(0);
  const CGAL::Mpzf magnitude(n);
  return sign < 0 ? CGAL::Mpzf(-magnitude) : magnitude;
}

// x 2^k as an Mpzf, exactly (by powers of two of at most 2^512 in magnitude, each a double).
inline CGAL::Mpzf mpzf_times_two_power(CGAL::Mpzf x, long k) {
  while (k != 0) {
    const long step = k > 512 ? 512 : (k < -512 ? -512 : k);
    x = x * CGAL::Mpzf(std::ldexp(1.0, static_cast<int>(step)));
    k -= step;
  }
  return x;
}

// The pair in the ring frame, and s = L 2^e.
struct RingFrame {
  CylinderPair<CGAL::Mpzf> pair;
  CGAL::Gmpz L = 1;
  int e = 0;
  CGAL::Mpzf L_mpzf = CGAL::Mpzf(1);  // L

  // Binary64 world input (already s = 2^e times the input, e the world frame's exponent).
  static RingFrame from_world(const Cylinder<double>& w0, const Cylinder<double>& w1, int world_exponent) {
    const auto to_m = [](double x) { return CGAL::Mpzf(x); };
    return {CylinderPair<CGAL::Mpzf>::make(w0.map(to_m), w1.map(to_m)), CGAL::Gmpz(1), world_exponent, CGAL::Mpzf(1)};
  }

  // Rational input: L the lcm of the denominators; nullopt when L is too large.
  static std::optional<RingFrame> from_rational(const Cylinder<Rational>& c0, const Cylinder<Rational>& c1) {
    const std::optional<CGAL::Gmpz> lcm = denominator_lcm(c0, c1, kRingFrameMaxBits);
    if (!lcm) return std::nullopt;
    const CGAL::Gmpz& L = *lcm;
    const auto to_m = [&L](const Rational& q) { return mpzf_from_integer(scaled_integer(q, L)); };
    RingFrame f{CylinderPair<CGAL::Mpzf>::make(c0.map(to_m), c1.map(to_m)), L, 0};
    f.L_mpzf = mpzf_from_integer(L);
    return f;
  }

  // A point of the world frame (input times 2^world_exponent), in the ring frame.
  CGAL::Mpzf from_world(const CGAL::Mpzf& x, int world_exponent) const {
    CGAL::Mpzf y = mpzf_times_two_power(x, static_cast<long>(e) - world_exponent);
    if (L != 1) y = y * L_mpzf;
    return y;
  }

  // The ring point n / w (w != 0) in the input frame: n / (w L 2^e), exactly. With the dyadic
  // n = a / 2^i and w = b / 2^j: (a 2^j) / (b L 2^(i + e)), put in lowest terms once.
  Rational to_input(const CGAL::Mpzf& n, const CGAL::Mpzf& w) const {
    const CGAL::Gmpq a = static_cast<CGAL::Gmpq>(n), b = static_cast<CGAL::Gmpq>(w);
    Rational y;
    mpz_ptr num = mpq_numref(y.mpq()), den = mpq_denref(y.mpq());
    mpz_mul(num, mpq_numref(a.mpq()), mpq_denref(b.mpq()));
    mpz_mul(den, mpq_numref(b.mpq()), mpq_denref(a.mpq()));
    if (L != 1) mpz_mul(den, den, L.mpz());
    if (e >= 0) mpz_mul_2exp(den, den, static_cast<mp_bitcnt_t>(e));
    if (e < 0) mpz_mul_2exp(num, num, static_cast<mp_bitcnt_t>(-e));
    mpq_canonicalize(y.mpq());  // also makes the denominator positive (w < 0)
    return y;
  }
};

// The dyadic rational q as an Mpzf, exactly; nullopt when q is not dyadic.
inline std::optional<CGAL::Mpzf> mpzf_from_dyadic(const Rational& q) {
  mpz_srcptr den = mpq_denref(q.mpq());
  const std::size_t shift = mpz_scan1(den, 0);
  if (mpz_sizeinbase(den, 2) != shift + 1) return std::nullopt;  // not a power of two
  CGAL::Mpzf x = mpzf_from_integer(CGAL::Gmpz(mpq_numref(q.mpq())));
  return mpzf_times_two_power(x, -static_cast<long>(shift));
}

// A rational direction as a parallel direction of dyadic numbers: its coordinates times the
// least common multiple of their denominators (integers), exactly. Directions need no frame.
// l is set to that least common multiple.
inline Vec3<CGAL::Mpzf> ring_direction(const Vec3<Rational>& D, CGAL::Gmpz& l) {
  l = 1;
  for (std::size_t i = 0; i < 3; ++i) mpz_lcm(l.mpz(), l.mpz(), mpq_denref(D[i].mpq()));
  return D.map([&l](const Rational& q) { return mpzf_from_integer(scaled_integer(q, l)); });
}
inline Vec3<CGAL::Mpzf> ring_direction(const Vec3<Rational>& D) {
  CGAL::Gmpz l;
  return ring_direction(D, l);
}

// floor(log2 |q|) within one, for q != 0 (exactly, for a dyadic q).
inline long binade(const Rational& q) {
  return static_cast<long>(mpz_sizeinbase(mpq_numref(q.mpq()), 2)) - static_cast<long>(mpz_sizeinbase(mpq_denref(q.mpq()), 2));
}

// floor(log2 |x|) of a dyadic x != 0, exactly: from CGAL's enclosure of x between two doubles
// when both ends lie in one binade (then x does too), else (x just below a power of two, or
// below the normal range, where the enclosure widens to 0) from x in Gmpq.
inline long binade(const CGAL::Mpzf& x) {
  const std::pair<double, double> b = CGAL::to_interval(x);
  const double lo = std::min(std::abs(b.first), std::abs(b.second)), hi = std::max(std::abs(b.first), std::abs(b.second));
  if (lo >= std::numeric_limits<double>::min() && std::isfinite(hi) && (b.first < 0) == (b.second < 0)) {
    const int e = std::ilogb(lo);
    if (e == std::ilogb(hi)) return e;
  }
  return binade(Rational(static_cast<CGAL::Gmpq>(x)));
}

// The exact rings' (R = Rational or CGAL::Mpzf) conversions: a Gmpfr of the scope's precision
// from R (rounded), R from a Gmpfr (exactly), and 2^k in R (their binades are above).
inline CGAL::Gmpfr ring_gmpfr(const Rational& q) { return nt::from_rational<CGAL::Gmpfr>(q); }
inline CGAL::Gmpfr ring_gmpfr(const CGAL::Mpzf& x) {
  if (CGAL::is_zero(x)) return nt::constant<CGAL::Gmpfr>(0);
  const CGAL::Gmpq q = static_cast<CGAL::Gmpq>(x);  // dyadic: the denominator is a power of two
  return gmpfr_of(CGAL::Gmpz(mpq_numref(q.mpq())), 1 - static_cast<long>(mpz_sizeinbase(mpq_denref(q.mpq()), 2)));
}
template <class R>
R ring_exact(const CGAL::Gmpfr& x) {
  if constexpr (std::is_same_v<R, CGAL::Mpzf>) {
    if (!mpfr_regular_p(x.fr())) return CGAL::Mpzf(0);
    CGAL::Gmpz m;
    const long e = mpfr_get_z_2exp(m.mpz(), x.fr());  // x = m 2^e
    return mpzf_times_two_power(mpzf_from_integer(m), e);
  } else {
    return to_rational(x);
  }
}
template <class R>
R ring_two_power(long k) {
  if constexpr (std::is_same_v<R, CGAL::Mpzf>) {
    return mpzf_times_two_power(CGAL::Mpzf(1), k);
  } else {
    return times_two_power(Rational(1), k);
  }
}

inline Vec3<Rational> mpzf_to_rational(const Vec3<CGAL::Mpzf>& v) {
  return v.map([](const CGAL::Mpzf& x) { return Rational(static_cast<CGAL::Gmpq>(x)); });
}

}  // namespace certcyl::detail
