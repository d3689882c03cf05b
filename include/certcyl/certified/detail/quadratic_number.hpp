// certcyl/certified/detail/quadratic_number.hpp -- exact numbers alpha + beta * sqrt(gamma).
//
// alpha, beta rational, gamma a non-negative integer. Normal form (made by `make`): either
// beta = 0 and gamma = 0 (a rational), or gamma > 1 is not a perfect square and beta != 0 (an
// irrational: it is then neither a binary64 value nor a midpoint between two of them, which is
// what lets `nearest_double` terminate).
//
// nearest_double: the binary64 value nearest to x (ties to even), proved by an enclosure:
// [lo, hi] is computed in MPFR with directed rounding at p bits (sqrt rounded down/up, then the
// product with beta and the sum with alpha rounded outward); both ends are rounded to nearest
// binary64 (through the exact rational of the MPFR number, so subnormals and overflow follow
// binary64's rules); when the two agree, rounding to nearest being monotone, x rounds to the
// same value. Otherwise p doubles. A rational x is rounded directly.
#pragma once

#include <CGAL/Gmpq.h>
#include <CGAL/Gmpz.h>
#include <mpfr.h>

#include <stdexcept>
#include <string>
#include <utility>

#include "certcyl/number_traits.hpp"
#include "certcyl/rational.hpp"

namespace certcyl::detail {

struct QuadraticNumber {
  Rational alpha{0}, beta{0};
  CGAL::Gmpz gamma{0};

  bool is_rational() const { return beta == 0; }

  // alpha + beta * sqrt(g), g >= 0 rational, brought to normal form:
  // sqrt(n/m) = sqrt(n m) / m; a perfect square n m makes a rational, and squares of small
  // primes are taken out of the radicand.
  static QuadraticNumber make(const Rational& alpha, const Rational& beta, const Rational& g) {
    if (beta == 0 || g == 0) return {alpha, 0, 0};
    if (g < 0) throw std::domain_error("QuadraticNumber: negative radicand");
    const CGAL::Gmpz n = g.numerator(), m = g.denominator();
    CGAL::Gmpz nm = n * m;
    Rational b = beta / Rational(m);
    if (mpz_perfect_square_p(nm.mpz())) {
      CGAL::Gmpz root;
      mpz_sqrt(root.mpz(), nm.mpz());
      return {alpha + b * Rational(root), 0, 0};
    }
    // Take out square factors of small primes, for readable output: sqrt(12) = 2 sqrt(3).
    // Dyadic inputs make nm carry a large power of two: each prime's multiplicity is found at
    // once (mpz_scan1, mpz_remove) and its even part moved to b in one step.
    mpq_t& bq = b.mpq();
    const auto twos = mpz_scan1(nm.mpz(), 0);
    if (twos >= 2) {
      mpz_tdiv_q_2exp(nm.mpz(), nm.mpz(), 2 * (twos / 2));
      mpq_mul_2exp(bq, bq, twos / 2);
    }
    // The odd primes up to 47, their squares tested on two word-sized residues.
    constexpr unsigned long primes[] = {3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37, 41, 43, 47};
    constexpr unsigned long squares_low = 9ul * 25 * 49 * 121 * 169 * 289 * 361 * 529 * 841;  // 3..29, < 2^64
    constexpr unsigned long squares_high = 961ul * 1369 * 1681 * 1849 * 2209;                // 31..47
    const unsigned long residue_low = mpz_fdiv_ui(nm.mpz(), squares_low);
    const unsigned long residue_high = mpz_fdiv_ui(nm.mpz(), squares_high);
    CGAL::Gmpz factor, power;
    for (int i = 0; i < 14; ++i) {
      const unsigned long p = primes[i];
      if ((i < 9 ? residue_low : residue_high) % (p * p) != 0) continue;
      mpz_set_ui(factor.mpz(), p);
      const auto k = mpz_remove(nm.mpz(), nm.mpz(), factor.mpz());
      if (k % 2 == 1) mpz_mul_ui(nm.mpz(), nm.mpz(), p);
      mpz_pow_ui(power.mpz(), factor.mpz(), k / 2);
      mpz_mul(mpq_numref(bq), mpq_numref(bq), power.mpz());
      mpq_canonicalize(bq);
    }
    return {alpha, b, nm};
  }

  // Exact text "alpha + beta*sqrt(gamma)" in lowest terms, e.g. "1/2 - 3/4*sqrt(5)"; a
  // rational prints as itself, a zero alpha is left out ("-1/3*sqrt(7)").
  std::string to_string() const {
    if (is_rational()) return to_exact_string(alpha);
    const bool negative = beta < 0;
    const std::string magnitude = to_exact_string(negative ? Rational(-beta) : beta);
    const std::string root = (magnitude == "1" ? std::string() : magnitude + "*") + "sqrt(" + detail::to_string(gamma) + ")";
    if (alpha == 0) return (negative ? "-" : "") + root;
    return to_exact_string(alpha) + (negative ? " - " : " + ") + root;
  }
};

// Sign of alpha + beta * sqrt(gamma), gamma >= 0, in any ring NT with nt::sign (exact, or an
// interval that throws when undecided). Degree 2 in the parts.
template <class NT>
CGAL::Sign sign_of_root_form(const NT& alpha, const NT& beta, const NT& gamma) {
  const CGAL::Sign sa = nt::sign(alpha), sb = nt::sign(beta);
  if (sb == CGAL::ZERO || nt::sign(gamma) == CGAL::ZERO) return sa;
  if (sa == CGAL::ZERO || sa == sb) return sb;
  // else: opposite signs; |alpha| vs |beta| sqrt(gamma) by squaring.
  const CGAL::Sign s = nt::sign(NT(alpha * alpha - beta * beta * gamma));
  return sa == CGAL::POSITIVE ? s : CGAL::opposite(s);
}

// Sign of x - q.
inline CGAL::Sign compare_with(const QuadraticNumber& x, const Rational& q) {
  return sign_of_root_form(Rational(x.alpha - q), x.beta, Rational(x.gamma));
}

// Sign of x - y when both share the radicand or one is rational.
inline CGAL::Sign compare(const QuadraticNumber& x, const QuadraticNumber& y) {
  if (y.is_rational()) return compare_with(x, y.alpha);
  if (x.is_rational()) return CGAL::opposite(compare_with(y, x.alpha));
  if (x.gamma != y.gamma) throw std::domain_error("QuadraticNumber::compare: different radicands");
  return sign_of_root_form(Rational(x.alpha - y.alpha), Rational(x.beta - y.beta), Rational(x.gamma));
}

// An MPFR number of a given precision, freed on scope exit.
class MpfrValue {
 public:
  explicit MpfrValue(mpfr_prec_t p) { mpfr_init2(x_, p); }
  ~MpfrValue() { mpfr_clear(x_); }
  MpfrValue(const MpfrValue&) = delete;
  MpfrValue& operator=(const MpfrValue&) = delete;
  mpfr_ptr get() { return x_; }

 private:
  mpfr_t x_;
};

// [lo, hi] containing x, at the precision of lo and hi.
inline void enclose(const QuadraticNumber& x, MpfrValue& lo, MpfrValue& hi) {
  const mpfr_prec_t bits = mpfr_get_prec(lo.get());
  MpfrValue root_lo(bits), root_hi(bits);
  // Step 1: sqrt(gamma) in [root_lo, root_hi] (gamma rounded outward first).
  mpfr_set_z(root_lo.get(), x.gamma.mpz(), MPFR_RNDD);
  mpfr_set_z(root_hi.get(), x.gamma.mpz(), MPFR_RNDU);
  mpfr_sqrt(root_lo.get(), root_lo.get(), MPFR_RNDD);
  mpfr_sqrt(root_hi.get(), root_hi.get(), MPFR_RNDU);
  // Step 2: beta * sqrt(gamma), the ends swapped when beta < 0.
  if (x.beta > 0) {
    mpfr_mul_q(lo.get(), root_lo.get(), x.beta.mpq(), MPFR_RNDD);
    mpfr_mul_q(hi.get(), root_hi.get(), x.beta.mpq(), MPFR_RNDU);
  } else {
    mpfr_mul_q(lo.get(), root_hi.get(), x.beta.mpq(), MPFR_RNDD);
    mpfr_mul_q(hi.get(), root_lo.get(), x.beta.mpq(), MPFR_RNDU);
  }
  // Step 3: + alpha, rounded outward.
  mpfr_add_q(lo.get(), lo.get(), x.alpha.mpq(), MPFR_RNDD);
  mpfr_add_q(hi.get(), hi.get(), x.alpha.mpq(), MPFR_RNDU);
}

// The binary64 value nearest to an MPFR number, ties to even. MPFR's mpfr_get_d rounds
// correctly where the result is a normal binary64 value (|x| in [2^-1000, 2^1000) here);
// elsewhere (subnormal results, overflow, zero) through the exact rational, which follows
// binary64's rules (rational.hpp).
inline double nearest_double(MpfrValue& x) {
  if (!mpfr_zero_p(x.get())) {
    const mpfr_exp_t e = mpfr_get_exp(x.get());  // |x| in [2^(e-1), 2^e)
    if (e > -999 && e < 1000) return mpfr_get_d(x.get(), MPFR_RNDN);
  }
  Rational q;
  mpfr_get_q(q.mpq(), x.get());
  return round_to_nearest<double>(q);
}

// The binary64 value nearest to x, ties to even (see the header comment for the proof).
inline double nearest_double(const QuadraticNumber& x) {
  if (x.is_rational()) return round_to_nearest<double>(x.alpha);
  for (mpfr_prec_t bits = 96; bits <= (mpfr_prec_t{1} << 22); bits *= 2) {
    MpfrValue lo(bits), hi(bits);
    enclose(x, lo, hi);
    const double dlo = nearest_double(lo), dhi = nearest_double(hi);
    if (dlo == dhi) return dlo;
  }
  // Unreachable for the normal form: an irrational is at a positive distance from every
  // midpoint, so some precision separates it.
  throw std::logic_error("nearest_double: no convergence");
}

}  // namespace certcyl::detail
