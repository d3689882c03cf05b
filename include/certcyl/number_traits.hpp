// certcyl/number_traits.hpp -- the one layer through which algorithms reach their number type.
//
// Algorithms are templates on `NT` and use only: ring arithmetic (+, -, *), division where the
// type is a field, and the functions of namespace `certcyl::nt` below:
//   nt::sign(x), nt::compare(a, b)   CGAL::Sign / CGAL::Comparison_result; for Interval_nt a
//                                     sign the interval cannot decide throws
//                                     CGAL::Uncertain_conversion_exception (catch it in one place)
//   nt::is_zero, is_positive, is_negative, abs, min, max
//   nt::sqrt(x)                      only where the type has one; a clear compile-time error
//                                     otherwise (Gmpq, Mpzf, Lazy_exact_nt<Gmpq>)
//   nt::to_interval(x)               a binary64 interval that encloses x
//   nt::constant<NT>(k)              the integer k in NT (see the Gmpfr note below)
//   nt::from_rational<NT>(q)         an exact input in NT: correctly rounded for the floating
//                                     types, enclosing for intervals, exact for the exact types
//   NumberTraits<NT>::is_exact       every operation the type offers is exact
//   NumberTraits<NT>::is_certified   every comparison it answers is right (exact types and
//                                     intervals, which refuse to answer rather than guess)
//   NumberTraits<NT>::name()         a printable name ("double", "Gmpfr<113>", ...)
//
// Types: double, long double, CGAL::Interval_nt<false>, CGAL::Gmpq, CGAL::Gmpz, CGAL::Mpzf, CGAL::Gmpfr,
// CGAL::Lazy_exact_nt<CGAL::Gmpq>, and QD's dd_real (double-double, 106 bits); CORE::Expr with
// certcyl/number_traits_core.hpp, a header of its own because CGAL's CORE_Expr.h alone costs
// about two thirds of the compile time of a one-query program.
//
// Pitfalls this layer absorbs (design note, section 2):
// - Interval_nt<false> is only correct while the FPU rounds upward: run interval code inside a
//   `CGAL::Protect_FPU_rounding<true>` (see `with_interval_rounding`), and compile with
//   -frounding-math (the certcyl::certcyl target sets it).
// - Gmpfr's precision is chosen at run time by `GmpfrPrecision` (a scope that sets MPFR's
//   thread-local default precision). Arithmetic results take the larger of the operands' and
//   the default precision, so every value must be created at the chosen precision:
//   `Gmpfr(double)` makes 512 bits and `Gmpfr(int)` 256 bits, which would silently raise the
//   precision of everything they touch. Use nt::constant and nt::from_rational, never
//   `NT(2)` or `NT(0.5)`, in generic code.
// - Mpzf is a ring of dyadic numbers: no division; from_rational rejects non-dyadic input.
// - dd_real (Debian's libqd-dev) is an unevaluated sum of two doubles: 106 bits, but binary64's
//   exponent range (a leading term near the overflow threshold or a trailing term in the
//   subnormals loses the extra bits), and correct only while the FPU rounds to nearest (never
//   inside `with_interval_rounding`). The value is a sum of doubles, so it converts to a
//   Rational exactly (`nt::to_rational`). CGAL has no traits for it: sign, compare and the
//   Eigen traits are here.
#pragma once

#include <CGAL/FPU.h>
#include <CGAL/Gmpfr.h>
#include <CGAL/Gmpq.h>
#include <CGAL/Interval_nt.h>
#include <CGAL/Lazy_exact_nt.h>
#include <CGAL/Mpzf.h>
#include <CGAL/long_double.h>
#include <CGAL/number_utils.h>
#include <mpfr.h>
#include <qd/dd_real.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <iterator>
#include <string>
#include <type_traits>
#include <utility>

#include "certcyl/errors.hpp"
#include "certcyl/rational.hpp"

namespace certcyl {

using Interval = CGAL::Interval_nt<false>;
using LazyRational = CGAL::Lazy_exact_nt<CGAL::Gmpq>;

// Sets the precision (in bits) of Gmpfr values created in this thread for the lifetime of the
// object, and restores the previous one on exit.
class GmpfrPrecision {
 public:
  explicit GmpfrPrecision(long bits) : old_(CGAL::Gmpfr::set_default_precision(bits)) {}
  ~GmpfrPrecision() { CGAL::Gmpfr::set_default_precision(old_); }
  GmpfrPrecision(const GmpfrPrecision&) = delete;
  GmpfrPrecision& operator=(const GmpfrPrecision&) = delete;

 private:
  CGAL::Gmpfr::Precision_type old_;
};

// The binade of a Gmpfr: e with 2^(e-1) <= |x| < 2^e; LONG_MIN for zero, NaN and infinities.
inline long gmpfr_exponent(const CGAL::Gmpfr& x) { return mpfr_regular_p(x.fr()) ? static_cast<long>(mpfr_get_exp(x.fr())) : LONG_MIN; }

// x 2^-shift rounded to a double; 0 for zero, NaN and infinities. The power of two is clamped to
// [-1100, 1100], beyond which the result underflows to 0 or overflows to infinity anyway.
inline double gmpfr_scaled_double(const CGAL::Gmpfr& x, long shift) {
  if (!mpfr_regular_p(x.fr())) return 0.0;
  long e = 0;
  const double m = mpfr_get_d_2exp(&e, x.fr(), MPFR_RNDN);
  return std::ldexp(m, static_cast<int>(std::clamp(e - shift, -1100L, 1100L)));
}

// Runs f() with the FPU rounding toward +infinity, as Interval_nt<false> requires.
template <class F>
decltype(auto) with_interval_rounding(F&& f) {
  CGAL::Protect_FPU_rounding<true> protect;
  return std::forward<F>(f)();
}

// What a number type needs around its use, as one RAII object: upward rounding for
// Interval_nt<false>, a precision for Gmpfr (`bits`, default 53), nothing for the others.
template <class NT>
class NumberScope {
 public:
  explicit NumberScope(long /*bits*/ = 53) {}
};
template <>
class NumberScope<CGAL::Interval_nt<false>> {
 public:
  explicit NumberScope(long /*bits*/ = 53) {}

 private:
  CGAL::Protect_FPU_rounding<true> protect_;
};
template <>
class NumberScope<CGAL::Gmpfr> {
 public:
  explicit NumberScope(long bits = 53) : precision_(bits) {}

 private:
  GmpfrPrecision precision_;
};

// The primary template is left undefined: using an unsupported type fails to compile here.
template <class NT>
struct NumberTraits;

template <>
struct NumberTraits<double> {
  static constexpr bool is_exact = false, is_certified = false, has_sqrt = true, is_field = true;
  static std::string name() { return "double"; }
  static double from_rational(const Rational& q) { return round_to_nearest<double>(q); }
  static double constant(long k) { return static_cast<double>(k); }
};

template <>
struct NumberTraits<long double> {
  static constexpr bool is_exact = false, is_certified = false, has_sqrt = true, is_field = true;
  static std::string name() { return "long double"; }
  static long double from_rational(const Rational& q) { return round_to_nearest<long double>(q); }
  static long double constant(long k) { return static_cast<long double>(k); }
};

template <>
struct NumberTraits<Interval> {
  static constexpr bool is_exact = false, is_certified = true, has_sqrt = true, is_field = true;
  static std::string name() { return "Interval_nt"; }
  static Interval from_rational(const Rational& q) {
    auto [lo, hi] = enclose(q);
    return Interval(lo, hi);
  }
  static Interval constant(long k) { return Interval(static_cast<double>(k)); }
};

template <>
struct NumberTraits<CGAL::Gmpq> {
  static constexpr bool is_exact = true, is_certified = true, has_sqrt = false, is_field = true;
  static std::string name() { return "Gmpq"; }
  static CGAL::Gmpq from_rational(const Rational& q) { return q; }
  static CGAL::Gmpq constant(long k) { return CGAL::Gmpq(k); }
};

// Integers: a ring without the exponent limit of Mpzf and without Gmpq's canonicalisation, for
// exact evaluation on input scaled to integers (from_rational rejects anything else).
template <>
struct NumberTraits<CGAL::Gmpz> {
  static constexpr bool is_exact = true, is_certified = true, has_sqrt = false, is_field = false;
  static std::string name() { return "Gmpz"; }
  static CGAL::Gmpz from_rational(const Rational& q) {
    if (mpz_cmp_ui(mpq_denref(q.mpq()), 1) != 0) throw InvalidInput("", "Gmpz cannot represent the non-integer " + to_exact_string(q));
    return q.numerator();
  }
  static CGAL::Gmpz constant(long k) { return CGAL::Gmpz(k); }
};

template <>
struct NumberTraits<CGAL::Mpzf> {
  static constexpr bool is_exact = true, is_certified = true, has_sqrt = false, is_field = false;
  static std::string name() { return "Mpzf"; }
  // Exact for dyadic rationals (denominator a power of two) within binary64's exponent reach;
  // anything else cannot be an Mpzf and is rejected.
  static CGAL::Mpzf from_rational(const Rational& q) {
    const CGAL::Gmpz denominator = q.denominator();
    const mpz_srcptr den = denominator.mpz();
    const auto shift = mpz_scan1(den, 0);
    if (mpz_sizeinbase(den, 2) != shift + 1)
      throw InvalidInput("", "Mpzf cannot represent the non-dyadic rational " + to_exact_string(q));
    if (shift > 1074) throw InvalidInput("", "Mpzf conversion: denominator 2^" + std::to_string(shift) + " too large");
    return integer_to_mpzf(q.numerator()) * CGAL::Mpzf(std::ldexp(1.0, -static_cast<int>(shift)));
  }
  // CGAL 5.5's Mpzf(const Gmpz&) drops the sign and corrupts zero (Mpzf(Gmpz(-3)) == 3,
  // Mpzf(Gmpz(0)) * 2 != 0), so integers are assembled exactly from 32-bit chunks through
  // Mpzf(double), which is exact.
  static CGAL::Mpzf integer_to_mpzf(const CGAL::Gmpz& n) {
    // A new number: a copy of n would share its representation, and the loop writes to it.
    CGAL::Gmpz magnitude;
    mpz_abs(magnitude.mpz(), n.mpz());
    CGAL::Mpzf result(0), scale(1);
    const CGAL::Mpzf chunk_base(4294967296.0);  // 2^32
    CGAL::Gmpz chunk;
    while (magnitude.sign() != CGAL::ZERO) {
      mpz_fdiv_r_2exp(chunk.mpz(), magnitude.mpz(), 32);
      mpz_fdiv_q_2exp(magnitude.mpz(), magnitude.mpz(), 32);
      result = result + scale * CGAL::Mpzf(static_cast<double>(mpz_get_ui(chunk.mpz())));
      scale = scale * chunk_base;
    }
    return n.sign() == CGAL::NEGATIVE ? CGAL::Mpzf(-result) : result;
  }
  static CGAL::Mpzf constant(long k) { return CGAL::Mpzf(k); }
};

template <>
struct NumberTraits<CGAL::Gmpfr> {
  static constexpr bool is_exact = false, is_certified = false, has_sqrt = true, is_field = true;
  static std::string name() { return "Gmpfr<" + std::to_string(CGAL::Gmpfr::get_default_precision()) + ">"; }
  // Correctly rounded to the current GmpfrPrecision (MPFR's exponent range is far wider than
  // any input's, so there is no overflow or subnormal case).
  static CGAL::Gmpfr from_rational(const Rational& q) {
    CGAL::Gmpfr x(0, CGAL::Gmpfr::get_default_precision());
    mpfr_set_q(x.fr(), q.mpq(), MPFR_RNDN);
    return x;
  }
  static CGAL::Gmpfr constant(long k) { return CGAL::Gmpfr(k, CGAL::Gmpfr::get_default_precision()); }
};

template <>
struct NumberTraits<LazyRational> {
  static constexpr bool is_exact = true, is_certified = true, has_sqrt = false, is_field = true;
  static std::string name() { return "Lazy_exact_nt<Gmpq>"; }
  static LazyRational from_rational(const Rational& q) { return LazyRational(q); }
  static LazyRational constant(long k) { return LazyRational(static_cast<int>(k)); }
};

// QD's double-double.
template <class NT>
inline constexpr bool is_qd_v = std::is_same_v<NT, dd_real>;

// q 2^e as a dd_real: each term the double nearest what the previous one leaves of q 2^e
// rounded to 256 bits (so correctly rounded to 106 bits while the terms are normal numbers).
template <class NT>
  requires is_qd_v<NT>
NT qd_from_rational(const Rational& q, long e = 0) {
  constexpr int terms = 2;
  double t[2] = {0, 0};
  mpfr_t x;
  mpfr_init2(x, 256);
  mpfr_set_q(x, q.mpq(), MPFR_RNDN);
  mpfr_mul_2si(x, x, e, MPFR_RNDN);
  for (int i = 0; i < terms; ++i) {
    t[i] = mpfr_get_d(x, MPFR_RNDN);
    if (!std::isfinite(t[i]) || t[i] == 0) break;
    mpfr_sub_d(x, x, t[i], MPFR_RNDN);
  }
  mpfr_clear(x);
  return dd_real(t[0], t[1]);
}

template <>
struct NumberTraits<dd_real> {
  static constexpr bool is_exact = false, is_certified = false, has_sqrt = true, is_field = true;
  static std::string name() { return "dd_real"; }
  static dd_real from_rational(const Rational& q) { return qd_from_rational<dd_real>(q); }
  static dd_real constant(long k) { return dd_real(static_cast<double>(k)); }
};

// Satisfied by the types above.
template <class NT>
concept SupportedNumber = requires { NumberTraits<NT>::is_exact; };

namespace nt {

template <class NT>
inline constexpr bool has_sqrt_v = NumberTraits<NT>::has_sqrt;

template <class NT>
NT from_rational(const Rational& q) {
  return NumberTraits<NT>::from_rational(q);
}

template <class NT>
NT constant(long k) {
  return NumberTraits<NT>::constant(k);
}

template <class NT>
std::string name() {
  return NumberTraits<NT>::name();
}

template <class NT>
CGAL::Sign sign(const NT& x) {
  if constexpr (is_qd_v<NT>) {
    return x.is_positive() ? CGAL::POSITIVE : x.is_negative() ? CGAL::NEGATIVE : CGAL::ZERO;
  } else {
    // For Interval_nt the Uncertain<Sign> converts here, throwing when undecided.
    return static_cast<CGAL::Sign>(CGAL::sign(x));
  }
}

template <class NT>
CGAL::Comparison_result compare(const NT& a, const NT& b) {
  if constexpr (is_qd_v<NT>) {
    return a < b ? CGAL::SMALLER : b < a ? CGAL::LARGER : CGAL::EQUAL;
  } else {
    return static_cast<CGAL::Comparison_result>(CGAL::compare(a, b));
  }
}

template <class NT>
bool is_zero(const NT& x) {
  return nt::sign(x) == CGAL::ZERO;
}
template <class NT>
bool is_positive(const NT& x) {
  return nt::sign(x) == CGAL::POSITIVE;
}
template <class NT>
bool is_negative(const NT& x) {
  return nt::sign(x) == CGAL::NEGATIVE;
}

template <class NT>
NT abs(const NT& x) {
  return nt::is_negative(x) ? NT(-x) : x;
}
template <class NT>
const NT& min(const NT& a, const NT& b) {
  return nt::compare(b, a) == CGAL::SMALLER ? b : a;
}
template <class NT>
const NT& max(const NT& a, const NT& b) {
  return nt::compare(a, b) == CGAL::SMALLER ? b : a;
}

template <class NT>
NT sqrt(const NT& x) {
  static_assert(NumberTraits<NT>::has_sqrt,
                "certcyl::nt::sqrt: this number type has no square root (Gmpq, Mpzf and "
                "Lazy_exact_nt<Gmpq> are exact only for rational operations); use CORE::Expr, "
                "Gmpfr or an interval, or a square-root-free formulation");
  if constexpr (std::is_floating_point_v<NT>) {
    return std::sqrt(x);
  } else if constexpr (is_qd_v<NT>) {
    return ::sqrt(x);
  } else {
    return CGAL::sqrt(x);
  }
}

// A binary64 interval enclosing x. For double it is the point [x, x]; for long double, Gmpq,
// Mpzf, Gmpfr, Lazy_exact_nt and CORE::Expr it is CGAL's enclosing conversion.
template <class NT>
std::pair<double, double> to_interval(const NT& x) {
  if constexpr (is_qd_v<NT>) {
    CGAL::Protect_FPU_rounding<true> upward;
    Interval sum(x.x[0]);
    for (std::size_t i = 1; i < std::size(x.x); ++i) sum += Interval(x.x[i]);
    return {sum.inf(), sum.sup()};
  } else {
    return CGAL::to_interval(x);
  }
}

// The double nearest x where the type can tell it (exact types), an approximation otherwise.
template <class NT>
double to_double(const NT& x) {
  if constexpr (is_qd_v<NT>) {
    return x.x[0];
  } else {
    return CGAL::to_double(x);
  }
}

// The exact value of a finite dd_real.
template <class NT>
  requires is_qd_v<NT>
Rational to_rational(const NT& x) {
  Rational r(x.x[0]);
  for (std::size_t i = 1; i < std::size(x.x); ++i) r = r + Rational(x.x[i]);
  return r;
}

}  // namespace nt
}  // namespace certcyl

// Eigen's traits for dd_real (CGAL provides those of its own types), so that Eigen's dense
// solvers run on it.
namespace Eigen {
template <class>
struct NumTraits;
template <class QD>
  requires certcyl::is_qd_v<QD>
struct QdNumTraits {
  using Real = QD;
  using NonInteger = QD;
  using Nested = QD;
  using Literal = QD;
  static inline Real epsilon() { return QD::_eps; }
  static inline Real dummy_precision() { return QD(QD::_eps * 1024); }
  static inline Real highest() { return QD::_max; }
  static inline Real lowest() { return -QD::_max; }
  static inline int digits10() { return 31; }
  enum { IsInteger = 0, IsSigned = 1, IsComplex = 0, RequireInitialization = 1, ReadCost = 2, AddCost = 10, MulCost = 10 };
};
template <>
struct NumTraits<dd_real> : QdNumTraits<dd_real> {};
}  // namespace Eigen
