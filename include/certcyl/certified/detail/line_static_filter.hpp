// certcyl/certified/detail/line_static_filter.hpp -- the semi-static double stage of the
// certified line/ray/segment against circular cylinder decision (before Interval_nt and Gmpq).
//
// Each sign the skeleton (certified/detail/line_shape.hpp) needs is the sign of a polynomial of
// low degree in the input, evaluated in binary64 with a forward error bound computed from the
// input magnitudes (Shewchuk; CGAL's Static_filters): the sign of the computed value v is
// returned when |v| > bound. Otherwise, adaptively and for that one sign only, the same
// polynomial is evaluated again in double-double with its own proved bound
// (certified/detail/line_double_double.hpp), and where that is still undecided (in practice an
// exact zero: a tangency, an end on a cap plane, a line parallel to the axis) exactly in
// CGAL::Mpzf from the same input doubles. So a near-tangent line costs one or two polynomials
// in double-double, not the skeleton in intervals and Gmpq. Without escalation (the stage
// alone, as the tests check it) the stage gives up (`undecided()`) on the first such sign and
// the caller runs the interval stage, then Gmpq. No stage decides a sign wrongly, for any
// finite input.
//
// The polynomials (P = p0, A = p1 - p0, w = O - P, w1 = O - p1; a segment S0 S1 has d = S1 - S0,
// e0 = S1 - p0, e1 = S1 - p1). Circular quadric of line_shape.hpp: a t^2 + 2 b t + c <= 0,
// a = |d x A|^2, b = (w x A).(d x A), c = |w x A|^2 - r^2 A.A, disc = A.A (r^2 a - e^2),
// e = A.(w x d); caps t0 = -(w.A)/(d.A), t1 = -(w1.A)/(d.A); centre = -b/a.
//   sign(a)             a                                             degree (len, dir) (2, 2)
//   sign(disc)          r^2 a - e^2         (A.A > 0)                                    (4, 2)
//   sign(c), f(0)       |w x A|^2 - r^2 A.A                                              (4, 0)
//   sign(d.A)           d.A                                                              (1, 1)
//   sign(w.A), sign(w1.A)                                                                (2, 0)
//   sign(b)             (w x A).(d x A)     (centre vs 0: sign(0 - centre) = sign(b))    (3, 1)
//   f(1), 1 - centre    |e0 x A|^2 - r^2 A.A and (e0 x A).(d x A) = a + b                 (4, 0), (3, 1)
//   f(t0)               |A x (w x d)|^2 - r^2 (d.A)^2: since w + t0 d = A x (w x d) / (d.A)
//                       is orthogonal to A, (d.A)^2 f(t0) = A.A (|A x (w x d)|^2 - r^2 (d.A)^2)
//                                                                                        (4, 2)
//   t0 - centre         -sign(d.A) sign((d.d)(w.A) - (w.d)(d.A)): a w.A - b d.A equals
//                       A.A ((d.d)(w.A) - (w.d)(d.A)) by Lagrange and Binet-Cauchy          (2, 2)
//   the same two with w1 for t1; t0 - 0 = -(w.A)/(d.A); t0 - 1 = -(e0.A)/(d.A); t1 - 1 = -(e1.A)/(d.A).
// A tube root against a rational rho follows from F = sign f(rho) and G = sign(rho - centre)
// (a > 0): F < 0 puts rho strictly between the roots; F > 0 puts it beyond the root on G's side;
// F = 0 makes rho the root on G's side (both roots when G = 0).
//
// Error bound (proved here; the constants are derived at compile time from the same code that
// runs, see ErrorTerm). Let u = 2^-52: in every IEEE rounding mode a rounded operation returns
// (x op y)(1 + delta), |delta| <= u, plus, for a product in the subnormal range, an absolute
// eta with |eta| <= 2^-1074 (sums and differences of doubles are exact there).
//   Leaves: the differences A, w, w1, d (segment), e0, e1 are computed once from the inputs:
//   x^ = x (1 + delta) (k = 1); r and a line's d are exact (k = 0). A program of + - * then gives
//   v^ = sum_j t_j prod_{i <= k} (1 + delta_ij) + E, where t_j are the terms of the expanded
//   program (no cancellation combined) and k is its rounding depth: k(x +- y) = max(kx, ky) + 1,
//   k(x y) = kx + ky + 1 (induction on the program). So |v^ - v| <= ((1 + u)^k - 1) T + |E|,
//   T = sum_j |t_j| <= N mlen^i mdir^j, where mlen bounds every length leaf (|A|, |w|, |w1|,
//   |e0|, |e1| componentwise and r) and mdir every component of d, both for the exact leaves
//   (m^ / (1 - u) from the computed ones), and N is the program evaluated with every leaf
//   replaced by 1 and every - by + (ErrorTerm::N). Every polynomial here is homogeneous of
//   degree (i, j) in (lengths, directions).
//   E collects the underflow terms: by induction |E| <= F 2^-1074 S 2^(L D), S = mlen^i mdir^j,
//   D = i + j, when both magnitudes lie in [2^-L, 2^L], with F <= 2 (1 + u)^k P N, P the number
//   of products (induction, the rounded operands carrying their (1 + u) factors:
//   F(xy) <= (1 + u)^k 2 (P_x + P_y) N_x N_y + (1 + u) F_x F_y 2^-1074 + 1, F(x +- y) <= (1 + u)
//   (F_x + F_y); the paper's Lemma "line, double" gives the details). With L = 150, D <= 6, fewer
//   than 2^6 products and k <= 40: |E| <= 2^(8 - 1074 + 900) N S < 2^-150 N S.
//   The bound actually used, B = fl(fl(C * mlen^i) * mdir^j), C = (k + 1) N u, computed
//   without underflow or overflow in the window, is at least C (1 - u)^(D+1) m^^(i+j), and
//   (k + 1) u (1 - u)^(2D+1) >= (1 + u)^k - 1 + 2^-150 for k <= 40, D <= 6 (the difference is
//   u - O(k^2 u^2)). Hence |v^ - v| < B, and |v^| > B implies sign(v^) = sign(v).
//   Overflow: every intermediate value is at most (1 + u)^k N' 2^(150 D) < 2^1000.
// Outside the window (a magnitude above 2^150 or below 2^-150) the stage is skipped.
//
// A line in or near a cap plane. There s = d.A and sigma = x.A (x = w or w1) are both small,
// and cap_excess, of the order of s^2 |x|^2, can sink below the double-double bound (about
// 2^-92 of the magnitudes) although s and sigma themselves are known to about 2^-47 of their
// values. Since A x (x x d) = s x - sigma d,
//   cap_excess = s^2 (x.x - r^2) - 2 s sigma (x.d) + sigma^2 (d.d),
// and the double-double stage evaluates this form in CGAL::Interval_nt (directed rounding,
// an enclosure by construction) from the enclosures s in [s^ - B_s, s^ + B_s], sigma in
// [sigma^ - B_sigma, sigma^ + B_sigma] (s^, sigma^ the double-double values, hi + lo enclosed
// exactly; B their proved double-double bounds, dot_ld and dot_ll) and the exact leaves x, d, r
// (each hi + lo, enclosed exactly). A sign is taken when the enclosure excludes 0; otherwise
// the exact stage decides. Overflow gives an infinite, undeciding enclosure.
// Exact zeros (tangencies, lines parallel to the axis or to the caps, ends on a cap plane) are
// never decided here: |v^| > B > 0 fails for v^ = 0, and those cases go to the next stage.
#pragma once

#include <CGAL/Interval_nt.h>
#include <CGAL/Mpzf.h>
#include <CGAL/enum.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>

#include "certcyl/certified/detail/line_double_double.hpp"
#include "certcyl/certified/detail/line_shape.hpp"
#include "certcyl/primitives.hpp"

namespace certcyl::detail {

// ---- Compile-time error bookkeeping --------------------------------------------------------

// The magnitude coefficient N, rounding depth k and bi-degree (length, direction) of a
// polynomial program, propagated by the same code that evaluates it in double.
struct ErrorTerm {
  double N = 0;
  int k = 0;
  int deg_len = 0, deg_dir = 0;

  static constexpr ErrorTerm same_degree(const ErrorTerm& x, const ErrorTerm& y) {
    // A sum of terms of different degrees has no bound of the form N mlen^i mdir^j: refuse to
    // compile (a constexpr evaluation cannot throw).
    if (x.deg_len != y.deg_len || x.deg_dir != y.deg_dir) throw "line_static_filter: inhomogeneous sum";
    return {x.N + y.N, std::max(x.k, y.k) + 1, x.deg_len, x.deg_dir};
  }
  friend constexpr ErrorTerm operator+(const ErrorTerm& x, const ErrorTerm& y) { return same_degree(x, y); }
  friend constexpr ErrorTerm operator-(const ErrorTerm& x, const ErrorTerm& y) { return same_degree(x, y); }
  friend constexpr ErrorTerm operator*(const ErrorTerm& x, const ErrorTerm& y) {
    return {x.N * y.N, x.k + y.k + 1, x.deg_len + y.deg_len, x.deg_dir + y.deg_dir};
  }
};

// The bound's constant: C = (k + 1) N 2^-52, and the degrees it multiplies.
struct StaticBound {
  double C;
  int deg_len, deg_dir;
};

constexpr StaticBound static_bound(const ErrorTerm& t) {
  if (t.k > 40 || t.deg_len + t.deg_dir > 6) throw "line_static_filter: outside the proved range";
  return {(t.k + 1) * t.N * 0x1p-52, t.deg_len, t.deg_dir};
}

// ---- The decision polynomials, generic over double and ErrorTerm -----------------------------

template <class T>
struct SV3 {
  T x, y, z;
};

template <class T>
constexpr T sdot(const SV3<T>& a, const SV3<T>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <class T>
constexpr SV3<T> scross(const SV3<T>& a, const SV3<T>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

template <class T>
struct CircularPolynomials {
  // a = |d x A|^2                                  (2, 2)
  static constexpr T a(const SV3<T>& A, const SV3<T>& d) {
    const SV3<T> v = scross(d, A);
    return sdot(v, v);
  }
  // r^2 |d x A|^2 - (A.(w x d))^2                  (4, 2)
  static constexpr T disc(const SV3<T>& A, const SV3<T>& w, const SV3<T>& d, const T& r) {
    const T e = sdot(A, scross(w, d));
    return r * r * a(A, d) - e * e;
  }
  // |x x A|^2 - r^2 A.A: f at the parameter where x = X - P (x = w: f(0); x = e0: f(1)) (4, 0)
  static constexpr T excess(const SV3<T>& A, const SV3<T>& x, const T& r) {
    const SV3<T> u = scross(x, A);
    return sdot(u, u) - r * r * sdot(A, A);
  }
  // x.y for two vectors of degrees that the caller knows ((1,1) or (2,0))
  static constexpr T dot(const SV3<T>& x, const SV3<T>& y) { return sdot(x, y); }
  // (x x A).(d x A): b for x = w, a + b for x = e0                              (3, 1)
  static constexpr T b(const SV3<T>& A, const SV3<T>& x, const SV3<T>& d) { return sdot(scross(x, A), scross(d, A)); }
  // |A x (x x d)|^2 - r^2 (d.A)^2: the sign of f at the cap plane through x's end     (4, 2)
  static constexpr T cap_excess(const SV3<T>& A, const SV3<T>& x, const SV3<T>& d, const T& r) {
    const SV3<T> X = scross(A, scross(x, d));
    const T sd = sdot(d, A);
    return sdot(X, X) - r * r * sd * sd;
  }
  // (d.d)(x.A) - (x.d)(d.A): minus the sign of (cap - centre) times sign(d.A)          (2, 2)
  static constexpr T cap_side(const SV3<T>& A, const SV3<T>& x, const SV3<T>& d) {
    return sdot(d, d) * sdot(x, A) - sdot(x, d) * sdot(d, A);
  }
};

namespace line_static_bounds {
inline constexpr ErrorTerm len{1, 1, 1, 0};    // a rounded length leaf
inline constexpr ErrorTerm dir{1, 1, 0, 1};    // a direction component (rounded for segments)
inline constexpr ErrorTerm radius{1, 0, 1, 0};  // r, exact
inline constexpr SV3<ErrorTerm> L{len, len, len}, Dv{dir, dir, dir};
using P = CircularPolynomials<ErrorTerm>;
inline constexpr StaticBound a = static_bound(P::a(L, Dv));
inline constexpr StaticBound disc = static_bound(P::disc(L, L, Dv, radius));
inline constexpr StaticBound excess = static_bound(P::excess(L, L, radius));
inline constexpr StaticBound dot_ld = static_bound(P::dot(L, Dv));
inline constexpr StaticBound dot_ll = static_bound(P::dot(L, L));
inline constexpr StaticBound b = static_bound(P::b(L, L, Dv));
inline constexpr StaticBound cap_excess = static_bound(P::cap_excess(L, L, Dv, radius));
inline constexpr StaticBound cap_side = static_bound(P::cap_side(L, L, Dv));

// The same constants derived by hand, as a check of the bookkeeping (C = (k + 1) N u; a
// rounded leaf has k 1, r has k 0):
//   x.y: products k 3, N 1; two sums: k 5, N 3.
static_assert(dot_ld.C == 6 * 3 * 0x1p-52 && dot_ll.C == 6 * 3 * 0x1p-52);
//   a cross component: k 4, N 2; |.|^2: squares k 9, N 4, two sums: k 11, N 12.
static_assert(a.C == 12 * 12 * 0x1p-52 && a.deg_len == 2 && a.deg_dir == 2);
//   e = A.(w x d): products k 1+4+1 = 6, N 2, sums: k 8, N 6; e^2: k 17, N 36;
//   (r r) a: k 1+11+1 = 13, N 12; difference: k 18, N 48.
static_assert(disc.C == 19 * 48 * 0x1p-52 && disc.deg_len == 4 && disc.deg_dir == 2);
//   |x x A|^2: k 11, N 12; (r r)(A.A): k 1+5+1 = 7, N 3; difference: k 12, N 15.
static_assert(excess.C == 13 * 15 * 0x1p-52 && excess.deg_len == 4 && excess.deg_dir == 0);
//   (x x A).(d x A): products k 9, N 4; sums: k 11, N 12.
static_assert(b.C == 12 * 12 * 0x1p-52 && b.deg_len == 3 && b.deg_dir == 1);
//   X = A x (x x d): products k 1+4+1 = 6, N 2, difference k 7, N 4; |X|^2: k 17, N 48;
//   ((r r) sd) sd with sd = d.A (k 5, N 3): k 7 then 13, N 9; difference: k 18, N 57.
static_assert(cap_excess.C == 19 * 57 * 0x1p-52 && cap_excess.deg_len == 4 && cap_excess.deg_dir == 2);
//   (d.d)(x.A) and (x.d)(d.A): k 5+5+1 = 11, N 9 each; difference: k 12, N 18.
static_assert(cap_side.C == 13 * 18 * 0x1p-52 && cap_side.deg_len == 2 && cap_side.deg_dir == 2);
}  // namespace line_static_bounds

// The same constants for the double-double stage (certified/detail/line_double_double.hpp):
// every leaf exact (k 0), C = 2 (k + 1) N 2^-100.
namespace line_dd_bounds {
inline constexpr ErrorTerm len{1, 0, 1, 0};
inline constexpr ErrorTerm dir{1, 0, 0, 1};
inline constexpr ErrorTerm radius{1, 0, 1, 0};
inline constexpr SV3<ErrorTerm> L{len, len, len}, Dv{dir, dir, dir};
using P = CircularPolynomials<ErrorTerm>;

constexpr StaticBound dd_bound(const ErrorTerm& t) {
  if (t.k > 40 || t.deg_len + t.deg_dir > 6) throw "line_static_filter: outside the proved range";
  return {2 * (t.k + 1) * t.N * 0x1p-100, t.deg_len, t.deg_dir};
}
inline constexpr StaticBound a = dd_bound(P::a(L, Dv));
inline constexpr StaticBound disc = dd_bound(P::disc(L, L, Dv, radius));
inline constexpr StaticBound excess = dd_bound(P::excess(L, L, radius));
inline constexpr StaticBound dot_ld = dd_bound(P::dot(L, Dv));
inline constexpr StaticBound dot_ll = dd_bound(P::dot(L, L));
inline constexpr StaticBound b = dd_bound(P::b(L, L, Dv));
inline constexpr StaticBound cap_excess = dd_bound(P::cap_excess(L, L, Dv, radius));
inline constexpr StaticBound cap_side = dd_bound(P::cap_side(L, L, Dv));
// By hand, as above with exact leaves: x.y: products k 1, sums k 3, N 3; |d x A|^2: cross
// k 2, squares k 5, sums k 7, N 12; disc: e = A.(w x d) k 5 (cross 2, products 3, sums 5), e^2
// k 11, N 36; (r r) a: k 1+7+1 = 9, N 12; difference k 12, N 48.
static_assert(dot_ll.C == 2 * 4 * 3 * 0x1p-100 && a.C == 2 * 8 * 12 * 0x1p-100);
static_assert(disc.C == 2 * 13 * 48 * 0x1p-100 && disc.deg_len == 4 && disc.deg_dir == 2);
}  // namespace line_dd_bounds

// ---- The stage -----------------------------------------------------------------------------

// The leaves of the decision polynomials (header comment) in a number type T.
template <class T>
struct CircularLeaves {
  SV3<T> A, w, w1, d, e0, e1;
  T r;
};

// The skeleton's sign source for a line, ray or segment (binary64) against a circular cylinder
// (binary64). Each polynomial sign is computed once, when first needed, in double with the
// bound above. What the double evaluation leaves undecided is, with `escalate`, evaluated again
// in double-double (certified/detail/line_double_double.hpp; inside its window and under
// round-to-nearest) and, if still undecided (an exact zero: a tangency, an end on a cap plane),
// exactly in CGAL::Mpzf from the same input doubles, so that every sign is decided. Without
// `escalate` the source gives up (`undecided()`) on the first such sign.
class StaticCircularSigns {
 public:
  // The deepest arithmetic a sign needed: double, double-double, exact (Mpzf).
  enum class Depth : unsigned char { binary64, double_double, exact };

  StaticCircularSigns(const Vec3<double>& origin, const Vec3<double>& second, bool second_is_point, const Cylinder<double>& cyl,
                      bool escalate = false)
      : origin_(origin), second_(second), p0_(cyl.p0), p1_(cyl.p1), second_is_point_(second_is_point), escalate_(escalate) {
    CircularLeaves<double>& l = leaves_;
    l.r = cyl.radius;
    l.A = diff(cyl.p1, cyl.p0);
    l.w = diff(origin, cyl.p0);
    l.w1 = diff(origin, cyl.p1);
    double ml = std::max({std::fabs(l.r), vmax(l.A), vmax(l.w), vmax(l.w1)});
    if (second_is_point) {
      l.d = diff(second, origin);
      l.e0 = diff(second, cyl.p0);
      l.e1 = diff(second, cyl.p1);
      ml = std::max({ml, vmax(l.e0), vmax(l.e1)});
    } else {
      l.d = {second.x, second.y, second.z};
      // A ray or line has no t = 1 bound; e0 and e1 are never read.
      l.e0 = l.e1 = {0, 0, 0};
    }
    const double md = vmax(l.d);
    // The window of the proof (header comment); NaN (an overflowed difference) fails it too.
    usable_ = ml >= 0x1p-150 && ml <= 0x1p150 && md >= 0x1p-150 && md <= 0x1p150;
    len_pow_[0] = dir_pow_[0] = 1;
    for (int i = 1; i < 5; ++i) len_pow_[i] = len_pow_[i - 1] * ml;
    for (int i = 1; i < 3; ++i) dir_pow_[i] = dir_pow_[i - 1] * md;
  }

  bool usable() const { return usable_; }
  bool undecided() const { return undecided_; }
  Depth depth() const { return depth_; }

  // The leaves in double-double (every difference exact), made when first needed; nullptr
  // outside the double-double window or under a rounding mode other than to nearest. A
  // decision polynomial evaluated from them by CircularPolynomials<DD> (the same program as the
  // stage's) has the bound dd_bound_value(line_dd_bounds::<its constant>).
  const CircularLeaves<DD>* double_double_leaves() {
    if (!dd_) make_dd_leaves();
    return dd_usable_ ? &*dd_ : nullptr;
  }
  // B = fl(fl(C mlen^i) mdir^j) with the double-double leaves' magnitudes (after
  // double_double_leaves()): at least 1.9 times the error of the double-double value.
  double dd_bound_value(const StaticBound& b) const { return b.C * dd_len_pow_[b.deg_len] * dd_dir_pow_[b.deg_dir]; }

  // B = fl(fl(C mlen^i) mdir^j) of the header comment, for this input's magnitudes.
  double bound(const StaticBound& b) const { return b.C * len_pow_[b.deg_len] * dir_pow_[b.deg_dir]; }

  // Step 1 and 2 signs of line_shape.
  CGAL::Sign sign_a() { return sign(kA); }
  CGAL::Sign sign_disc() { return sign(kDisc); }
  CGAL::Sign sign_c() { return sign(kC); }
  CGAL::Sign sign_sd() { return sign(kSd); }
  CGAL::Sign sign_sw() { return sign(kSw); }
  // H - sw = A.A - w.A = -(w1.A)
  CGAL::Sign sign_H_minus_sw() { return CGAL::opposite(sign(kSw1)); }
  // b = (w x A).(d x A): minus the sign of the tube's centre -b/a (a > 0)
  CGAL::Sign sign_b() { return sign(kB); }

  // The tube's a, b and c in plain double from the double leaves, without an error bound: an
  // estimate for deciding which proof to try, never for a sign.
  void approximate_tube(double& a, double& b, double& c) const {
    using Q = CircularPolynomials<double>;
    const CircularLeaves<double>& l = leaves_;
    a = Q::a(l.A, l.d);
    b = Q::b(l.A, l.w, l.d);
    c = Q::excess(l.A, l.w, l.r);
  }

  // Bounds are compared by this object itself once the tube and slab states are known.
  StaticCircularSigns& bounds(TubeState tube, SlabState) {
    tube_ = tube;
    return *this;
  }

  // Sign of value(x) - value(y), as BoundValues::compare.
  CGAL::Sign compare(BoundKind x, BoundKind y) {
    if (x == y) return CGAL::ZERO;
    const bool tx = is_tube(x), ty = is_tube(y);
    if (tx && ty) {
      if (tube_ == TubeState::point) return CGAL::ZERO;
      return x == BoundKind::tube_lo ? CGAL::NEGATIVE : CGAL::POSITIVE;
    }
    if (tx) return tube_versus(x, y);
    if (ty) return CGAL::opposite(tube_versus(y, x));
    return rational_compare(x, y);
  }

 private:
  enum Slot { kA, kDisc, kC, kSd, kSw, kSw1, kB, kF1, kB1, kCapEx0, kCapEx1, kCapSide0, kCapSide1, kE0A, kE1A, kSlots };

  // The polynomial of each slot, in any number type.
  template <class T>
  static T slot_value(Slot s, const CircularLeaves<T>& l) {
    using Q = CircularPolynomials<T>;
    switch (s) {
      case kA: return Q::a(l.A, l.d);
      case kDisc: return Q::disc(l.A, l.w, l.d, l.r);
      case kC: return Q::excess(l.A, l.w, l.r);
      case kSd: return Q::dot(l.d, l.A);
      case kSw: return Q::dot(l.w, l.A);
      case kSw1: return Q::dot(l.w1, l.A);
      case kB: return Q::b(l.A, l.w, l.d);
      case kF1: return Q::excess(l.A, l.e0, l.r);
      case kB1: return Q::b(l.A, l.e0, l.d);
      case kCapEx0: return Q::cap_excess(l.A, l.w, l.d, l.r);
      case kCapEx1: return Q::cap_excess(l.A, l.w1, l.d, l.r);
      case kCapSide0: return Q::cap_side(l.A, l.w, l.d);
      case kCapSide1: return Q::cap_side(l.A, l.w1, l.d);
      case kE0A: return Q::dot(l.e0, l.A);
      case kE1A: return Q::dot(l.e1, l.A);
      case kSlots: break;
    }
    return l.r;  // not reached
  }

  // The bound of each slot in double and in double-double.
  static const StaticBound& double_bound(Slot s) {
    namespace b = line_static_bounds;
    static constexpr StaticBound table[kSlots] = {b::a,          b::disc,       b::excess,   b::dot_ld,   b::dot_ll,
                                                  b::dot_ll,     b::b,          b::excess,   b::b,        b::cap_excess,
                                                  b::cap_excess, b::cap_side,   b::cap_side, b::dot_ll,   b::dot_ll};
    return table[s];
  }
  static const StaticBound& dd_bound(Slot s) {
    namespace b = line_dd_bounds;
    static constexpr StaticBound table[kSlots] = {b::a,          b::disc,       b::excess,   b::dot_ld,   b::dot_ll,
                                                  b::dot_ll,     b::b,          b::excess,   b::b,        b::cap_excess,
                                                  b::cap_excess, b::cap_side,   b::cap_side, b::dot_ll,   b::dot_ll};
    return table[s];
  }

  static SV3<double> diff(const Vec3<double>& p, const Vec3<double>& q) { return {p.x - q.x, p.y - q.y, p.z - q.z}; }
  static double vmax(const SV3<double>& v) { return std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)}); }
  static bool is_tube(BoundKind k) { return k == BoundKind::tube_lo || k == BoundKind::tube_hi; }

  CGAL::Sign sign(Slot s) {
    if (!known_[s]) {
      const double v = slot_value(s, leaves_);
      const double bound = this->bound(double_bound(s));
      CGAL::Sign r;
      if (v > bound)
        r = CGAL::POSITIVE;
      else if (v < -bound)
        r = CGAL::NEGATIVE;
      else
        r = escalated_sign(s);  // |v| within the error bound
      sign_[s] = static_cast<std::int8_t>(r);
      known_[s] = true;
    }
    return static_cast<CGAL::Sign>(sign_[s]);
  }

  // The sign of slot s in double-double, else exactly; or give up (no `escalate`).
  [[gnu::noinline]] CGAL::Sign escalated_sign(Slot s) {
    if (!escalate_) {
      undecided_ = true;  // the result is never used
      return CGAL::ZERO;
    }
    if (!dd_) make_dd_leaves();
    if (dd_usable_) {
      const DD v = slot_value(s, *dd_);
      const double bound = dd_bound_value(dd_bound(s));
      depth_ = std::max(depth_, Depth::double_double);
      if (v.hi() > bound) return CGAL::POSITIVE;
      if (v.hi() < -bound) return CGAL::NEGATIVE;
      if (s == kCapEx0 || s == kCapEx1) {
        const CGAL::Sign f = factored_cap_excess_sign(s == kCapEx0 ? dd_->w : dd_->w1);
        if (f != CGAL::ZERO) return f;
      }
    }
    if (!exact_) exact_ = make_leaves<CGAL::Mpzf>([](double x, double y) { return CGAL::Mpzf(x) - CGAL::Mpzf(y); });
    depth_ = Depth::exact;
    return slot_value(s, *exact_).sign();
  }

  // The sign of cap_excess(A, x, d, r) when its double-double value is within its bound, from
  // the factored form (header comment, "A line in or near a cap plane"); ZERO when that
  // enclosure does not decide either.
  CGAL::Sign factored_cap_excess_sign(const SV3<DD>& x) const {
    using Q = CircularPolynomials<DD>;
    const CircularLeaves<DD>& l = *dd_;
    const DD s = Q::dot(l.d, l.A), sigma = Q::dot(x, l.A);
    const double es = line_dd_bounds::dot_ld.C * dd_len_pow_[1] * dd_dir_pow_[1];
    const double esigma = line_dd_bounds::dot_ll.C * dd_len_pow_[2];
    using I = CGAL::Interval_nt<false>;
    const CGAL::Protect_FPU_rounding<true> upward;  // no double-double operation below
    auto vec = [](const SV3<DD>& v) { return SV3<I>{dd_enclosure(v.x), dd_enclosure(v.y), dd_enclosure(v.z)}; };
    const SV3<I> xi = vec(x), di = vec(l.d);
    const I si = dd_enclosure(s, es), gi = dd_enclosure(sigma, esigma), r = dd_enclosure(l.r);
    const I V = CGAL::square(si) * (sdot(xi, xi) - CGAL::square(r)) - I(2) * si * gi * sdot(xi, di) + CGAL::square(gi) * sdot(di, di);
    if (V.inf() > 0) return CGAL::POSITIVE;
    if (V.sup() < 0) return CGAL::NEGATIVE;
    return CGAL::ZERO;
  }

  // The leaves in T, each difference formed by sub(x, y) (exact for DD and Mpzf).
  template <class T, class Sub>
  CircularLeaves<T> make_leaves(Sub sub) const {
    auto vsub = [&](const Vec3<double>& p, const Vec3<double>& q) { return SV3<T>{sub(p.x, q.x), sub(p.y, q.y), sub(p.z, q.z)}; };
    CircularLeaves<T> l;
    l.r = T(leaves_.r);
    l.A = vsub(p1_, p0_);
    l.w = vsub(origin_, p0_);
    l.w1 = vsub(origin_, p1_);
    if (second_is_point_) {
      l.d = vsub(second_, origin_);
      l.e0 = vsub(second_, p0_);
      l.e1 = vsub(second_, p1_);
    } else {
      l.d = {T(second_.x), T(second_.y), T(second_.z)};
      l.e0 = l.e1 = {T(0.0), T(0.0), T(0.0)};
    }
    return l;
  }

  void make_dd_leaves() {
    dd_ = make_leaves<DD>([](double x, double y) { return dd_difference(x, y); });
    auto in = [](const Vec3<double>& p) {
      return in_double_double_window(p.x) && in_double_double_window(p.y) && in_double_double_window(p.z);
    };
    dd_usable_ = in_double_double_window(leaves_.r) && in(origin_) && in(second_) && in(p0_) && in(p1_) && rounding_to_nearest();
    // The bound's magnitudes: the largest high parts, at least 2^-120 (a larger m only raises
    // the bound; this keeps its computation clear of underflow).
    auto hmax = [](const SV3<DD>& v) { return std::max({std::fabs(v.x.hi()), std::fabs(v.y.hi()), std::fabs(v.z.hi())}); };
    const CircularLeaves<DD>& l = *dd_;
    const double ml = std::max({0x1p-120, std::fabs(leaves_.r), hmax(l.A), hmax(l.w), hmax(l.w1), hmax(l.e0), hmax(l.e1)});
    const double md = std::max(0x1p-120, hmax(l.d));
    dd_len_pow_[0] = dd_dir_pow_[0] = 1;
    for (int i = 1; i < 5; ++i) dd_len_pow_[i] = dd_len_pow_[i - 1] * ml;
    for (int i = 1; i < 3; ++i) dd_dir_pow_[i] = dd_dir_pow_[i - 1] * md;
  }

  // Sign of tube root T - rho for rho a cap or range bound (header comment: F and G).
  CGAL::Sign tube_versus(BoundKind T, BoundKind rho) {
    CGAL::Sign F, G;  // sign f(rho), sign(rho - centre)
    switch (rho) {
      case BoundKind::range_lo:
        F = sign_c();
        G = F == CGAL::NEGATIVE ? CGAL::ZERO : sign(kB);
        break;
      case BoundKind::range_hi:
        F = sign(kF1);
        G = F == CGAL::NEGATIVE ? CGAL::ZERO : sign(kB1);
        break;
      case BoundKind::cap0:
        F = sign(kCapEx0);
        G = F == CGAL::NEGATIVE ? CGAL::ZERO : CGAL::opposite(sign_sd() * sign(kCapSide0));
        break;
      case BoundKind::cap1:
        F = sign(kCapEx1);
        G = F == CGAL::NEGATIVE ? CGAL::ZERO : CGAL::opposite(sign_sd() * sign(kCapSide1));
        break;
      default: return CGAL::ZERO;  // tube against tube is handled by compare
    }
    const bool lo = T == BoundKind::tube_lo;
    if (F == CGAL::NEGATIVE) return lo ? CGAL::NEGATIVE : CGAL::POSITIVE;
    if (F == CGAL::POSITIVE) return CGAL::opposite(G);  // both roots on the side opposite to rho's
    // else: rho is the root on G's side
    if (G == CGAL::POSITIVE) return lo ? CGAL::NEGATIVE : CGAL::ZERO;
    if (G == CGAL::NEGATIVE) return lo ? CGAL::ZERO : CGAL::POSITIVE;
    return CGAL::ZERO;
  }

  // Sign of value(x) - value(y) for two of cap0, cap1, range_lo, range_hi.
  CGAL::Sign rational_compare(BoundKind x, BoundKind y) {
    const bool cx = x == BoundKind::cap0 || x == BoundKind::cap1;
    const bool cy = y == BoundKind::cap0 || y == BoundKind::cap1;
    if (cx && cy) return x == BoundKind::cap1 ? sign_sd() : CGAL::opposite(sign_sd());  // cap1 - cap0 = H / sd
    if (!cx && !cy) return x == BoundKind::range_lo ? CGAL::NEGATIVE : CGAL::POSITIVE;  // 0 - 1
    if (!cx) return CGAL::opposite(rational_compare(y, x));
    // cap - 0 = -(x.A)/sd with x = w or w1; cap - 1 = -(e.A)/sd with e = e0 or e1.
    CGAL::Sign num;
    if (y == BoundKind::range_lo)
      num = x == BoundKind::cap0 ? sign_sw() : CGAL::opposite(sign_H_minus_sw());
    else
      num = sign(x == BoundKind::cap0 ? kE0A : kE1A);
    return CGAL::opposite(num * sign_sd());
  }

  CircularLeaves<double> leaves_;
  Vec3<double> origin_, second_, p0_, p1_;
  bool second_is_point_, escalate_;
  double len_pow_[5], dir_pow_[3];
  bool usable_ = false, undecided_ = false;
  TubeState tube_ = TubeState::empty;
  bool known_[kSlots] = {};
  std::int8_t sign_[kSlots] = {};
  Depth depth_ = Depth::binary64;
  // The later stages' leaves, made when first needed.
  std::optional<CircularLeaves<DD>> dd_;
  bool dd_usable_ = false;
  double dd_len_pow_[5], dd_dir_pow_[3];
  std::optional<CircularLeaves<CGAL::Mpzf>> exact_;
};

}  // namespace certcyl::detail
