// certcyl/certified/detail/triangle_static_filter.hpp -- the semi-static double filter of the
// triangle-cylinder decision (the stage before Interval_nt; Shewchuk, and CGAL's
// Static_filters with Static_filter_error, are the models).
//
// What it does. The decision of triangle_slab.hpp runs in double on the input relative to P,
// a_i = fl(v_i - P), A = fl(p1 - p0), r. Every sign it asks for is the sign of one polynomial
// of a fixed expression tree and homogeneous degree d (SlabTest, with the kinds of the points
// involved). With M2 a power of two bounding every |a_i coordinate|, |A coordinate| and r, the
// computed value v' of a polynomial with exact value v satisfies |v' - v| <= E = e * M2^d,
// where e is a constant derived from the tree (below). The sign is decided when |v'| > E;
// otherwise the stage gives up (StaticUndecided) and the caller moves on to intervals. The
// filter never answers zero: every zero sign is left to the later stages.
//
// Derivation of e (the calculus of CGAL's Static_filter_error). Each node carries b, a bound
// on |computed value|, and e, a bound on |computed value - exact value|, for leaves bounded by
// 1. With u = 2^-52 (a bound on the relative rounding error of +, -, * in ANY rounding mode,
// so the filter is sound inside an upward-rounding scope too):
//   leaf a difference fl(x - y):  b = 1,  e = u (1 + 2^-50)     (|fl(d) - d| <= u |d|, |d| <= b/(1-u))
//   leaf r (exact input):          b = 1,  e = 0;   leaf 1 (vertex weight): b = 1, e = 0, degree 0
//   x +- y:  b = (b_x + b_y)(1 + u),   e = e_x + e_y + u (b_x + b_y)
//   x * y:   b = b_x b_y (1 + u),      e = e_x b_y + b_x e_y + e_x e_y + u b_x b_y
// (x*y - X*Y = (x - X) y + X (y - Y) with |X| <= b_x + e_x.) The rules are evaluated once, in
// double under upward rounding, by running the very functions the decision uses
// (slab_axial, slab_crossing, slab_point_minus_R, slab_det, slab_edge_V, slab_slope, slab_gap)
// on the type ErrorBound: the tree the bound is derived from is the tree that is evaluated.
// A crossing point's bound is the larger of those of its two trees (plane s = 0 from s_i, plane
// s = A.A from A.A - s_i). A contracted a*b+c (FMA) rounds once, inside the bound above.
//
// Scaling. With leaves bounded by M2 = 2^k instead of 1, every b and e of degree d is
// multiplied by 2^(k d) exactly (scaling by a power of two commutes with rounding), provided
// nothing overflows or underflows. The stage runs only when 2^-64 <= M2 <= 2^64:
//   overflow: |value| <= b M2^14 with b < 2^40 (the largest b, see the test) is < 2^940;
//   underflow: an operation whose result is subnormal errs by < 2^-1074 more than the
//     relative model says; at most 2^10 operations, each propagated to the root by a factor
//     <= 2^41 M2^(d-k) (k >= 1 its degree), add < 2^(10 - 1074 + 41) M2^d M2^-k
//     <= 2^-1023 2^(64 14) M2^d = 2^-127 M2^d (M2 >= 2^-64, k <= 14), far below 2^-20 e M2^d
//     (e >= 2^-53): the bounds are multiplied by (1 + 2^-20) to absorb it.
// So E = e (1 + 2^-20) M2^d, computed exactly (M2^d is a power of two in range).
#pragma once

#include <CGAL/FPU.h>
#include <CGAL/enum.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <optional>

#include "certcyl/answer.hpp"
#include "certcyl/certified/detail/triangle_slab.hpp"
#include "certcyl/primitives.hpp"

namespace certcyl::detail {

// The error calculus above, for an arithmetic whose operations err by at most Unit::value
// relatively (2^-52 here; 2^-100 for the double-double stage, triangle_double_double.hpp).
// Operations must run under upward rounding.
struct DoubleUnit {
  static constexpr double value = 0x1p-52;
};

template <class Unit>
struct ErrorBoundIn {
  static constexpr double u = Unit::value;
  double b = 0, e = 0;
  int d = 0;

  friend ErrorBoundIn operator+(const ErrorBoundIn& x, const ErrorBoundIn& y) {
    // A sum of terms of different degrees would not scale with M2^d: marked by degree -1.
    const double s = x.b + y.b;
    return {s * (1 + u), x.e + y.e + u * s, x.d == y.d ? x.d : -1};
  }
  friend ErrorBoundIn operator-(const ErrorBoundIn& x, const ErrorBoundIn& y) { return x + y; }
  friend ErrorBoundIn operator-(const ErrorBoundIn& x) { return x; }
  friend ErrorBoundIn operator*(const ErrorBoundIn& x, const ErrorBoundIn& y) {
    const double p = x.b * y.b;
    return {p * (1 + u), x.e * y.b + x.b * y.e + x.e * y.e + u * p, x.d < 0 || y.d < 0 ? -1 : x.d + y.d};
  }
  static ErrorBoundIn larger(const ErrorBoundIn& x, const ErrorBoundIn& y) {
    return {std::max(x.b, y.b), std::max(x.e, y.e), x.d == y.d ? x.d : -1};
  }
};
using ErrorBound = ErrorBoundIn<DoubleUnit>;

// The constant e and degree d of every sign test, by the kinds of the points involved.
struct StaticBounds {
  struct Entry {
    double e = 0;     // error constant for leaves bounded by 1, times (1 + 2^-20)
    int degree = 0;
    double b = 0;     // bound on the computed value for leaves bounded by 1 (for the overflow margin)
  };
  Entry axial, axial_top;
  std::array<Entry, 2> point;                            // [kind]
  std::array<std::array<Entry, 2>, 2> pierce, gap;       // [kind a][kind b]
  std::array<std::array<std::array<Entry, 2>, 2>, 2> slope;  // [kind a][kind b][kind of the endpoint]

  const Entry& entry(SlabTest t, SlabKind ka, SlabKind kb, SlabKind kx) const {
    const int a = static_cast<int>(ka), b = static_cast<int>(kb), x = static_cast<int>(kx);
    switch (t) {
      case SlabTest::axial: return axial;
      case SlabTest::axial_top: return axial_top;
      case SlabTest::point: return point[a];
      case SlabTest::pierce: return pierce[a][b];
      case SlabTest::slope: return slope[a][b][x];
      case SlabTest::gap: return gap[a][b];
      case SlabTest::count: break;
    }
    return axial;
  }
};

// Runs the decision's expression trees on an error calculus EB (see the header comment), from
// the bound of a leaf a_i, A (the rounded difference of two inputs in double; exact in
// double-double).
template <class EB>
StaticBounds derive_bounds(const EB& difference) {
  CGAL::Protect_FPU_rounding<true> upward;
  const EB exact_leaf{1, 0, 1}, one{1, 0, 0};
  const Vec3<EB> a{difference, difference, difference};
  const Vec3<EB> A = a;
  const EB AA = dot(A, A);
  const EB s = slab_axial(a, A);
  const EB top = slab_axial_top(AA, s);
  const EB R = slab_radius_term(exact_leaf, AA);
  const SlabPoint<EB> vertex{a, one, SlabKind::vertex};
  const SlabPoint<EB> c0 = slab_crossing(a, s, a, s), c1 = slab_crossing(a, top, a, top);
  SlabPoint<EB> crossing{{EB::larger(c0.X.x, c1.X.x), EB::larger(c0.X.y, c1.X.y), EB::larger(c0.X.z, c1.X.z)},
                         EB::larger(c0.w, c1.w), SlabKind::crossing};
  const std::array<SlabPoint<EB>, 2> kinds{vertex, crossing};

  const auto entry = [](const EB& x) {
    return StaticBounds::Entry{x.e * (1 + 0x1p-20), x.d, x.b};
  };
  StaticBounds t;
  t.axial = entry(s);
  t.axial_top = entry(top);
  for (int i = 0; i < 2; ++i) {
    t.point[i] = entry(slab_point_minus_R(kinds[i], A, R));
    for (int j = 0; j < 2; ++j) {
      const EB det = slab_det(kinds[i], kinds[j], A);
      const Vec3<EB> V = slab_edge_V(kinds[i], kinds[j], A);
      t.pierce[i][j] = entry(det);
      t.gap[i][j] = entry(slab_gap(det, V, exact_leaf));
      t.slope[i][j][0] = entry(slab_slope(kinds[0], V, A));
      t.slope[i][j][1] = entry(slab_slope(kinds[1], V, A));
    }
  }
  return t;
}

inline StaticBounds derive_static_bounds() {
  return derive_bounds(ErrorBound{1, ErrorBound::u * (1 + 0x1p-50), 1});
}

inline const StaticBounds& triangle_static_bounds() {
  static const StaticBounds bounds = derive_static_bounds();
  return bounds;
}

// Thrown when |value| <= E: the static stage cannot decide.
struct StaticUndecided {};

// The part of a computed value a sign is read from: the value itself in double (the
// double-double stage overloads it with the high part, triangle_double_double.hpp).
inline double leading_part(double v) { return v; }

// The sign policy of a stage with error bounds: the sign of the value when its leading part
// exceeds factor e M2^d (factor M2^d for d = 0..14 precomputed), else StaticUndecided. The
// static stage uses factor 1 on doubles.
template <class NT>
class BoundedSigns {
 public:
  BoundedSigns(const StaticBounds& bounds, double M2, double factor = 1) : bounds_(bounds) {
    power_[0] = factor;
    for (int d = 1; d < kMaxDegree + 1; ++d) power_[d] = power_[d - 1] * M2;
  }

  CGAL::Sign operator()(const NT& v, SlabTest t, SlabRef a = {}, SlabRef b = {}, SlabRef x = {}) const {
    const CGAL::Sign s = sign_or_zero(v, t, a, b, x);
    if (s == CGAL::ZERO) throw StaticUndecided{};
    return s;
  }

  // The sign, or ZERO when |leading part| <= factor e M2^d (undecided: never a zero sign).
  CGAL::Sign sign_or_zero(const NT& v, SlabTest t, SlabRef a, SlabRef b, SlabRef x) const {
    const StaticBounds::Entry& en = bounds_.entry(t, a.kind, b.kind, x.kind);
    const double E = en.e * power_[en.degree];
    const double h = leading_part(v);
    if (h > E) return CGAL::POSITIVE;
    if (h < -E) return CGAL::NEGATIVE;
    return CGAL::ZERO;
  }

  static constexpr int kMaxDegree = 14;

 private:
  const StaticBounds& bounds_;
  std::array<double, kMaxDegree + 1> power_;
};
using StaticSigns = BoundedSigns<double>;

// The power of two 2^k > m, k in [kMinExponent, kMaxExponent]; nothing when m is outside the
// range (or not a number).
inline std::optional<double> static_scale(double m) {
  constexpr int kMinExponent = -64, kMaxExponent = 64;
  if (!(m >= 0x1p-65 && m < 0x1p64)) return std::nullopt;
  // m is normal here: its biased exponent field E gives m < 2^(E - 1022).
  const auto bits = std::bit_cast<std::uint64_t>(m);
  const int k = static_cast<int>((bits >> 52) & 0x7ff) - 1022;
  if (k < kMinExponent || k > kMaxExponent) return std::nullopt;
  return std::bit_cast<double>(static_cast<std::uint64_t>(k + 1023) << 52);
}

// The static stage's input on binary64 input, relative to P, with its power-of-two scale M2;
// nothing when the magnitudes leave the safe range.
struct StaticTriangleInput {
  SlabInput<double> in;
  double M2;
};
inline std::optional<StaticTriangleInput> static_triangle_input(const Triangle<double>& T, const Cylinder<double>& C) {
  const SlabInput<double> in{{Vec3<double>(T.v[0] - C.p0), Vec3<double>(T.v[1] - C.p0), Vec3<double>(T.v[2] - C.p0)},
                             C.axis(),
                             C.radius,
                             1.0};
  double m = std::fabs(in.r);
  bool finite = m < 0x1p64;
  const auto take = [&](const Vec3<double>& v) {
    for (const double x : {v.x, v.y, v.z}) {
      const double ax = std::fabs(x);
      finite &= ax < 0x1p64;
      m = ax > m ? ax : m;
    }
  };
  for (const auto& a : in.a) take(a);
  take(in.A);
  if (!finite) return std::nullopt;
  const std::optional<double> M2 = static_scale(m);
  if (!M2) return std::nullopt;
  return StaticTriangleInput{in, *M2};
}

// The static stage on binary64 input: the answer, or nothing if some sign was too close to
// zero or the magnitudes left the safe range.
inline std::optional<SlabDecision> static_decide_triangle_cylinder(const Triangle<double>& T, const Cylinder<double>& C) {
  const std::optional<StaticTriangleInput> x = static_triangle_input(T, C);
  if (!x) return std::nullopt;
  try {
    return decide_slab(x->in, StaticSigns(triangle_static_bounds(), x->M2));
  } catch (const StaticUndecided&) {
    return std::nullopt;
  }
}

}  // namespace certcyl::detail
