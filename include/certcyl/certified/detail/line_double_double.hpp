// certcyl/certified/detail/line_double_double.hpp -- the double-double stage of the certified
// line decision: the decision polynomials of certified/detail/line_static_filter.hpp evaluated
// in QD's double-double arithmetic (Debian libqd-dev) with a proved forward error bound, for the
// signs the double stage leaves undecided (near tangencies, rims, cap planes).
//
// Arithmetic. DD wraps QD's dd_real with its accurate addition (dd_real::ieee_add, Algorithm 6
// "AccurateDWPlusDW" of Joldes, Muller, Popescu, "Tight and rigorous error bounds for basic
// building blocks of double-word arithmetic", ACM TOMS 44(2), 2017: relative error at most
// 3u^2 + 13u^3, u = 2^-53) and its product (operator*, their Algorithm 10 "DWTimesDW1":
// relative error at most 7u^2). Both need round-to-nearest, no underflow and no overflow, and
// double-word operands (|lo| <= ulp(hi) / 2; QD returns such, and the leaves below are such).
// So each operation returns (x op y)(1 + delta) with |delta| <= eps = 2^-100 (> 8u^2).
//
// Leaves. Every difference of two input doubles is formed exactly (dd_real::sub: the exact
// two-difference); the radius and a line's direction are inputs. All leaves are exact (rounding
// depth 0), so the induction of line_static_filter.hpp (ErrorTerm: k(x +- y) = max + 1,
// k(x y) = kx + ky + 1, N the program with leaves 1 and - as +) gives
//   |v^ - v| <= ((1 + eps)^k - 1) N mlen^i mdir^j <= (k + 1) eps N mlen^i mdir^j   (k <= 40).
// The bound used is B = fl(fl(C mlen^^i) mdir^^j) with C = 2 (k + 1) N eps and mlen^, mdir^ the
// largest high parts (a leaf is at most its high part times 1 + u): the factor 2 covers
// (1 + u)^6 / (1 - u)^7, so B >= 1.9 |v^ - v|. A sign is taken from the high part h of v^ when
// |h| > B: then |v^| >= |h| (1 - u) > |v^ - v|.
//
// No underflow, no overflow (the window, checked before the stage runs). Let every nonzero
// input double lie in [2^-120, 2^100]. Then every input, and every double the evaluation forms,
// is an integer multiple of 2^-172 per degree: the sum, difference or rounded sum of multiples
// of 2^-g is one (rounding to 53 bits keeps a multiple of 2^-g: either the value has at most 53
// bits from 2^-g up and is exact, or its ulp is a multiple of 2^-g), and so is Dekker's
// splitting (a product by the integer 2^27 + 1, then differences); a product of multiples of
// 2^-g and 2^-h is a multiple of 2^-(g + h). The polynomials have degree at most 6 in the
// leaves, so every double formed is a multiple of 2^-1032 and every exact intermediate result
// that is not a normal number is a multiple of 2^-1074 below 2^-1022: a subnormal, exact. So
// every operation rounds as with an unbounded exponent range. Magnitudes stay below
// N (2^101)^6 (1 + eps)^k < 2^650 (N < 2^20), below QD's splitting threshold (2^996): no
// overflow, and QD's two_prod never rescales.
// Round-to-nearest is checked (std::fegetround) before the stage runs. Every operation must
// be a binary64 operation rounded once: no extended evaluation (FLT_EVAL_METHOD 0, checked
// below) and no contraction into fused multiply-adds, which would break Dekker's splitting in
// QD's two_prod (hi = t - (t - a) with t = (2^27 + 1) a contracted to t - fma(2^27 + 1, a, -a)
// is no longer a 26-bit half). The project builds without FMA code generation; a build that
// enables it (__FMA__) is refused below rather than left to the compiler's contraction mode.
//
// The fused product (DDFused). The exact error of a product of doubles, a b - fl(a b), is a
// double in the window (the argument above: no underflow, no overflow); Dekker's split forms it
// exactly with 17 operations, a fused multiply-add fma(a, b, -fl(a b)) with one. DDFused is DD
// with that one replacement, so its results are DD's bit for bit and the proof above applies
// unchanged. It is used only inside functions compiled for a processor with FMA
// ([[gnu::target("fma"), gnu::flatten]], chosen at run time by has_fused_multiply_add()), where
// the fused multiply-add is one instruction (a part the compiler does not inline calls the C
// library's fma, correctly rounded as well) and every other operation must still be rounded
// once: the library is compiled with -ffp-contract=off (the CMake target adds it), and the tests
// compare the fused and the Dekker results bit for bit.
#pragma once

#include <CGAL/Interval_nt.h>
#include <qd/dd_real.h>

#include <cfenv>
#include <cfloat>
#include <cmath>

#if defined(__FMA__) || defined(QD_FMA)
#error "certcyl's double-double stage needs binary64 operations rounded once: build without -mfma (or -march enabling FMA)"
#endif
static_assert(FLT_EVAL_METHOD == 0, "certcyl's double-double stage needs binary64 evaluation (FLT_EVAL_METHOD 0)");

#include "certcyl/certified/detail/line_shape.hpp"

namespace certcyl::detail {

// A double-double value with QD's accurate addition and its product (the operations of the
// proof above, nothing else); Fused: the product's exact error term by a fused multiply-add
// (header comment), for code compiled for a processor with FMA only.
template <bool Fused>
struct DDT {
  dd_real v;

  DDT() = default;
  explicit DDT(double x) : v(x) {}
  explicit DDT(const dd_real& x) : v(x) {}
  template <bool F>
  explicit DDT(const DDT<F>& x) : v(x.v) {}

  double hi() const { return v.x[0]; }

  friend DDT operator+(const DDT& x, const DDT& y) { return DDT(dd_real::ieee_add(x.v, y.v)); }
  friend DDT operator-(const DDT& x, const DDT& y) { return DDT(dd_real::ieee_add(x.v, -y.v)); }
  // QD's operator* (qd/dd_inline.h: two_prod of the high parts, the cross terms, quick_two_sum)
  // written out, with Dekker's split (qd/inline.h split) without QD's rescaling branch for
  // operands above 2^996: in the window no operand reaches it (header comment), so the result
  // is QD's, bit for bit, at fewer instructions and inlined.
  [[gnu::always_inline]] friend DDT operator*(const DDT& x, const DDT& y) {
    const double a = x.v.x[0], b = y.v.x[0];
    const double p = a * b;
    double e;
    if constexpr (Fused) {
      e = __builtin_fma(a, b, -p);  // a b - p, exactly
    } else {
      const double ta = 134217729.0 * a, tb = 134217729.0 * b;  // 2^27 + 1
      const double ah = ta - (ta - a), bh = tb - (tb - b);
      const double al = a - ah, bl = b - bh;
      e = ((ah * bh - p) + ah * bl + al * bh) + al * bl;
    }
    e += (a * y.v.x[1] + x.v.x[1] * b);
    const double s = p + e;  // quick_two_sum(p, e)
    return DDT(dd_real(s, e - (s - p)));
  }
};
using DD = DDT<false>;
using DDFused = DDT<true>;

// Whether this processor has fused multiply-add (the FMA3 extension), once per process; only
// x86-64 with GCC or Clang dispatches ([[gnu::target("fma")]]), elsewhere DD alone is used.
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define CERTCYL_FUSED_DISPATCH 1
inline bool has_fused_multiply_add() {
  static const bool fused = __builtin_cpu_supports("fma");
  return fused;
}
#else
#define CERTCYL_FUSED_DISPATCH 0
inline bool has_fused_multiply_add() { return false; }
#endif

// x - y exactly (the two-difference of two doubles).
inline DD dd_difference(double x, double y) { return DD(dd_real::sub(x, y)); }

// The window of the proof: zero, or a magnitude in [2^-120, 2^100].
inline bool in_double_double_window(double x) {
  const double m = std::fabs(x);
  return m == 0 || (m >= 0x1p-120 && m <= 0x1p100);
}

inline bool rounding_to_nearest() { return std::fegetround() == FE_TONEAREST; }

// An Interval_nt enclosing v.hi + v.lo (exactly) plus or minus err: a double-double value with
// its proved bound. Under upward rounding only (CGAL::Protect_FPU_rounding<true>).
inline CGAL::Interval_nt<false> dd_enclosure(const DD& v, double err = 0) {
  using I = CGAL::Interval_nt<false>;
  return I(v.v.x[0]) + I(v.v.x[1]) + I(-err, err);
}

}  // namespace certcyl::detail
