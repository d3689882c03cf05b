// certcyl/rational.hpp -- exact rational input and its correctly rounded images.
//
// Semantics (design note, section 1): every input is an exact rational. A JSON number means
// the binary64 value it denotes; a string means the exact rational it spells:
//   "p/q"        integers p and q != 0, optional sign on p       "-3/4"
//   decimal      optional sign, digits, point, exponent           "0.1", "-1.25e-3", ".5"
//   hexfloat     C99 hexadecimal floating literal, 'p' optional   "0x1.8p-3", "-0x10"
// "0.1" is exactly one tenth, not the binary64 0.1.
//
// Rounding: `round_to_nearest<F>` gives the floating value of type F (float, double, long
// double) nearest to q, ties to even, with F's subnormals and overflow to infinity honoured;
// `enclose` gives the tightest binary64 interval [lo, hi] containing q. Both go through MPFR
// with F's exponent range emulated (mpfr_set_emin/emax + mpfr_subnormalize), so there is no
// double rounding anywhere.
#pragma once

#include <CGAL/Gmpq.h>
#include <CGAL/Gmpz.h>
#include <mpfr.h>

#include <charconv>
#include <cmath>
#include <limits>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>

#include "certcyl/errors.hpp"

namespace certcyl {

// The exact number type of all input.
using Rational = CGAL::Gmpq;

// An exact input value and whether it is exactly a binary64 value (so a kernel that computes
// in double sees it unrounded).
struct ExactValue {
  Rational value;
  bool is_binary64 = true;
};

namespace detail {

// Emulates the exponent range of a binary floating type with `digits` significand bits in
// MPFR for the lifetime of the object (MPFR's exponent range is thread-local here).
class MpfrExponentRange {
 public:
  MpfrExponentRange(mpfr_exp_t emin, mpfr_exp_t emax) : old_min_(mpfr_get_emin()), old_max_(mpfr_get_emax()) {
    mpfr_set_emin(emin);
    mpfr_set_emax(emax);
  }
  ~MpfrExponentRange() {
    mpfr_set_emin(old_min_);
    mpfr_set_emax(old_max_);
  }
  MpfrExponentRange(const MpfrExponentRange&) = delete;
  MpfrExponentRange& operator=(const MpfrExponentRange&) = delete;

 private:
  mpfr_exp_t old_min_, old_max_;
};

// Rounds q into floating type F with the given MPFR rounding mode, honouring F's range; sets
// *inexact (when given) to whether the result differs from q.
template <class F>
F round_rational(const Rational& q, mpfr_rnd_t rnd, bool* inexact = nullptr) {
  static_assert(std::numeric_limits<F>::is_iec559 || std::numeric_limits<F>::radix == 2,
                "round_rational needs a binary floating type");
  using L = std::numeric_limits<F>;
  mpfr_t x;
  mpfr_init2(x, L::digits);
  F result;
  {
    // MPFR writes x = m * 2^e with 1/2 <= m < 1, so F's range is [min_exponent - digits + 1,
    // max_exponent] in MPFR's convention (for binary64: [-1073, 1024]).
    MpfrExponentRange range(L::min_exponent - L::digits + 1, L::max_exponent);
    int ternary = mpfr_set_q(x, q.mpq(), rnd);
    ternary = mpfr_subnormalize(x, ternary, rnd);
    if (inexact) *inexact = ternary != 0;
    // x is now representable in F, so the conversion below is exact.
    if constexpr (std::is_same_v<F, float>) {
      result = mpfr_get_flt(x, rnd);
    } else if constexpr (std::is_same_v<F, double>) {
      result = mpfr_get_d(x, rnd);
    } else {
      result = mpfr_get_ld(x, rnd);
    }
  }
  mpfr_clear(x);
  return result;
}

inline std::string to_string(const CGAL::Gmpz& z) {
  std::string s(mpz_sizeinbase(z.mpz(), 10) + 2, '\0');
  mpz_get_str(s.data(), 10, z.mpz());
  s.resize(std::char_traits<char>::length(s.c_str()));
  return s;
}

inline bool is_digit(char c) { return c >= '0' && c <= '9'; }
inline int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// Exponents beyond this magnitude are rejected: they spell numbers no geometry input needs
// and whose exact expansion would exhaust memory.
inline constexpr long kMaxDecimalExponent = 100000;
inline constexpr long kMaxBinaryExponent = 400000;

inline long parse_exponent(std::string_view s, const std::string& field, long limit) {
  if (s.empty()) throw InvalidInput(field, "missing exponent digits");
  bool negative = false;
  if (s[0] == '+' || s[0] == '-') {
    negative = s[0] == '-';
    s.remove_prefix(1);
  }
  if (s.empty()) throw InvalidInput(field, "missing exponent digits");
  long e = 0;
  for (char c : s) {
    if (!is_digit(c)) throw InvalidInput(field, "malformed exponent");
    e = e * 10 + (c - '0');
    if (e > limit) throw InvalidInput(field, "exponent out of range (|e| > " + std::to_string(limit) + ")");
  }
  return negative ? -e : e;
}

// 10^k or 2^k as an exact integer.
inline CGAL::Gmpz power(unsigned long base, unsigned long k) {
  CGAL::Gmpz r;
  mpz_ui_pow_ui(r.mpz(), base, k);
  return r;
}

inline Rational scaled(const CGAL::Gmpz& mantissa, unsigned long base, long exponent) {
  if (exponent >= 0) return Rational(mantissa * power(base, static_cast<unsigned long>(exponent)));
  return Rational(mantissa, power(base, static_cast<unsigned long>(-exponent)));
}

inline Rational parse_decimal(std::string_view s, bool negative, const std::string& field) {
  std::string digits;
  long exponent = 0;
  std::size_t i = 0;
  bool any_digit = false;
  for (; i < s.size() && is_digit(s[i]); ++i) digits += s[i], any_digit = true;
  if (i < s.size() && s[i] == '.') {
    for (++i; i < s.size() && is_digit(s[i]); ++i) digits += s[i], --exponent, any_digit = true;
  }
  if (!any_digit) throw InvalidInput(field, "not a number: expected digits");
  if (i < s.size()) {
    if (s[i] != 'e' && s[i] != 'E') throw InvalidInput(field, "not a number: unexpected character '" + std::string(1, s[i]) + "'");
    exponent += parse_exponent(s.substr(i + 1), field, kMaxDecimalExponent);
  }
  CGAL::Gmpz mantissa(digits);
  if (negative) mantissa = -mantissa;
  return scaled(mantissa, 10, exponent);
}

inline Rational parse_hexfloat(std::string_view s, bool negative, const std::string& field) {
  CGAL::Gmpz mantissa(0);
  long exponent = 0;
  std::size_t i = 0;
  bool any_digit = false;
  for (; i < s.size() && hex_value(s[i]) >= 0; ++i) mantissa = mantissa * 16 + hex_value(s[i]), any_digit = true;
  if (i < s.size() && s[i] == '.') {
    for (++i; i < s.size() && hex_value(s[i]) >= 0; ++i) {
      mantissa = mantissa * 16 + hex_value(s[i]);
      exponent -= 4;
      any_digit = true;
      if (-exponent > kMaxBinaryExponent) throw InvalidInput(field, "too many hexadecimal digits");
    }
  }
  if (!any_digit) throw InvalidInput(field, "not a number: expected hexadecimal digits");
  if (i < s.size()) {
    if (s[i] != 'p' && s[i] != 'P') throw InvalidInput(field, "not a number: unexpected character '" + std::string(1, s[i]) + "'");
    exponent += parse_exponent(s.substr(i + 1), field, kMaxBinaryExponent);
  }
  if (negative) mantissa = -mantissa;
  return scaled(mantissa, 2, exponent);
}

inline CGAL::Gmpz parse_integer(std::string_view s, const std::string& field) {
  if (s.empty()) throw InvalidInput(field, "not a number: expected an integer");
  for (char c : s)
    if (!is_digit(c)) throw InvalidInput(field, "not a number: expected an integer, found '" + std::string(1, c) + "'");
  return CGAL::Gmpz(std::string(s));
}

}  // namespace detail

// Nearest value of floating type F (float, double or long double) to q, ties to even.
template <class F>
F round_to_nearest(const Rational& q) {
  return detail::round_rational<F>(q, MPFR_RNDN);
}

// Tightest binary64 interval containing q: lo <= q <= hi, lo == hi exactly when q is binary64.
// One rounding: q rounded down, and when that is inexact, the next double up (q rounded up: q
// lies strictly between two consecutive doubles, or -inf and -DBL_MAX, or DBL_MAX and +inf).
inline std::pair<double, double> enclose(const Rational& q) {
  bool inexact = false;
  const double lo = detail::round_rational<double>(q, MPFR_RNDD, &inexact);
  return {lo, inexact ? std::nextafter(lo, std::numeric_limits<double>::infinity()) : lo};
}

// True when q is exactly a finite binary64 value.
inline bool is_binary64(const Rational& q) {
  double d = round_to_nearest<double>(q);
  return std::isfinite(d) && Rational(d) == q;
}

// Parses the exact rational a string spells (see the grammar at the top of this file).
// Throws InvalidInput naming `field` on anything else, including "inf" and "nan".
inline Rational parse_rational(std::string_view text, const std::string& field = "") {
  std::string_view s = text;
  if (s.empty()) throw InvalidInput(field, "empty string is not a number");
  if (s.size() > 100000) throw InvalidInput(field, "number string too long");
  bool negative = false;
  if (s[0] == '+' || s[0] == '-') {
    negative = s[0] == '-';
    s.remove_prefix(1);
  }
  if (s.size() >= 2 && s[0] == '0' && (s[1] == 'x' || s[1] == 'X')) return detail::parse_hexfloat(s.substr(2), negative, field);
  if (auto slash = s.find('/'); slash != std::string_view::npos) {
    CGAL::Gmpz p = detail::parse_integer(s.substr(0, slash), field);
    CGAL::Gmpz q = detail::parse_integer(s.substr(slash + 1), field);
    if (q == 0) throw InvalidInput(field, "zero denominator in '" + std::string(text) + "'");
    return Rational(negative ? CGAL::Gmpz(-p) : p, q);
  }
  return detail::parse_decimal(s, negative, field);
}

// Exact text of q: "p" for an integer, "p/q" otherwise (lowest terms, q > 0). It parses back
// to q with parse_rational.
inline std::string to_exact_string(const Rational& q) {
  std::string num = detail::to_string(q.numerator());
  if (q.denominator() == 1) return num;
  return num + "/" + detail::to_string(q.denominator());
}

// Hexadecimal text of a binary64 value, "0x1.8p-3"; exact, and parse_rational reads it back.
// Non-finite values print as "inf", "-inf" and "nan", which parse_rational rejects.
inline std::string to_hex_string(double d) {
  if (std::isnan(d)) return "nan";
  if (std::isinf(d)) return d < 0 ? "-inf" : "inf";
  char buf[64];
  char* p = buf;
  if (std::signbit(d)) *p++ = '-', d = -d;
  *p++ = '0';
  *p++ = 'x';
  auto res = std::to_chars(p, buf + sizeof buf, d, std::chars_format::hex);
  return std::string(buf, res.ptr);
}

// Shortest decimal text that reads back (as a binary64, e.g. by a JSON parser) to d.
inline std::string to_shortest_string(double d) {
  char buf[64];
  auto res = std::to_chars(buf, buf + sizeof buf, d);
  return std::string(buf, res.ptr);
}

}  // namespace certcyl
