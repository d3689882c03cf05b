// certcyl/certified/detail/triangle_double_double.hpp -- the double-double stage of the
// triangle-cylinder decision: the decision of triangle_slab.hpp evaluated in QD's double-double
// arithmetic (the DD type of line_double_double.hpp) with a forward error bound derived from
// the same expression trees as the double filter's, for the inputs the double filter leaves
// undecided (a vertex, an edge or the face within a few ulps of the wall, a cap plane or a rim).
//
// Arithmetic. DD's addition and product each return (x op y)(1 + delta), |delta| <= 2^-100
// (line_double_double.hpp: Joldes, Muller and Popescu's bounds for QD's accurate addition and
// its product), given round-to-nearest, binary64 operations rounded once, and no underflow or
// overflow. The leaves a_i = v_i - P and A = p1 - p0 are exact (the two-difference of two
// doubles) and r is an input: every leaf is exact. The calculus of triangle_static_filter.hpp
// (derive_bounds) run with u = 2^-100 and exact leaves bounded by 1 gives, for each sign test of
// degree d, a constant e with |v^ - v| <= e M2^d when every leaf is at most M2 = 2^k in
// magnitude (scaling by a power of two commutes with the relative error model when nothing
// underflows or overflows). The sign is taken from the high part h of v^ when |h| > 4 e M2^d:
// then |v^| >= |h| (1 - 2^-53) > e M2^d >= |v^ - v| (the factor 4 also covers the rounding of the
// bound itself, a product of powers of two and e, exact since M2 >= 1).
//
// The window (checked before the stage runs): every input double is zero or of magnitude in
// [2^-24, 2^60]. Then every input, and every leaf, is an integer multiple of 2^-76 and at most
// 2^61 in magnitude. Sums, differences and roundings of multiples of 2^-g are multiples of 2^-g
// (rounding to 53 bits keeps a multiple of 2^-g: the value either has at most 53 bits from 2^-g
// up and is exact, or its ulp is a multiple of 2^-g), so is Dekker's splitting (a product by the
// integer 2^27 + 1, then differences), and a product of multiples of 2^-g and 2^-h is a
// multiple of 2^-(g + h). The tests have degree at most 14 in the leaves, so every double
// formed is a multiple of 2^-1064; one below 2^-1022 has at most 42 significant bits and is an
// exact subnormal: every operation rounds as with an unbounded exponent range. Magnitudes stay
// below b (2^61)^14 with b < 2^40 (the largest bound of the calculus), below 2^900, under QD's
// splitting threshold (2^996): no overflow, and QD's two_prod never rescales. Round-to-nearest
// is checked before the stage runs; line_double_double.hpp refuses FMA code generation and
// extended evaluation.
#pragma once

#include <CGAL/FPU.h>
#include <CGAL/Interval_nt.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include "certcyl/certified/detail/line_double_double.hpp"
#include "certcyl/certified/detail/triangle_slab.hpp"
#include "certcyl/certified/detail/triangle_static_filter.hpp"
#include "certcyl/primitives.hpp"

namespace certcyl::detail {

struct DoubleDoubleUnit {
  static constexpr double value = 0x1p-100;
};

inline const StaticBounds& triangle_double_double_bounds() {
  static const StaticBounds bounds = derive_bounds(ErrorBoundIn<DoubleDoubleUnit>{1, 0, 1});
  return bounds;
}

// The sign of a double-double value is read from its high part (the proof above).
inline double leading_part(const DD& v) { return v.hi(); }

// The window of the proof: zero, or a magnitude in [2^-24, 2^60].
inline bool in_triangle_double_double_window(double x) {
  const double m = std::fabs(x);
  return m == 0 || (m >= 0x1p-24 && m <= 0x1p60);
}

// The double-double stage's input (exact leaves) and the bound's power of two M2; nothing
// when an input is outside the window or the rounding mode is not to nearest.
struct DoubleDoubleTriangleInput {
  SlabInput<DD> in;
  double M2;
};
inline std::optional<DoubleDoubleTriangleInput> double_double_triangle_input(const Triangle<double>& T, const Cylinder<double>& C) {
  bool ok = in_triangle_double_double_window(C.radius);
  const auto take = [&ok](const Point3<double>& p) {
    ok &= in_triangle_double_double_window(p.x) && in_triangle_double_double_window(p.y) && in_triangle_double_double_window(p.z);
  };
  for (const Point3<double>& v : T.v) take(v);
  take(C.p0);
  take(C.p1);
  if (!ok || !rounding_to_nearest()) return std::nullopt;
  const auto difference = [](const Point3<double>& x, const Point3<double>& y) {
    return Vec3<DD>{dd_difference(x.x, y.x), dd_difference(x.y, y.y), dd_difference(x.z, y.z)};
  };
  const SlabInput<DD> in{{difference(T.v[0], C.p0), difference(T.v[1], C.p0), difference(T.v[2], C.p0)},
                         difference(C.p1, C.p0),
                         DD(C.radius),
                         DD(1.0)};
  // M2: a power of two >= 1 bounding every leaf (its high part, times 1 + 2^-53, is below the
  // next power of two above it).
  double m = 1;
  const auto bound = [&m](const Vec3<DD>& v) {
    for (const DD* x : {&v.x, &v.y, &v.z}) m = std::max(m, std::fabs(x->hi()));
  };
  for (const Vec3<DD>& a : in.a) bound(a);
  bound(in.A);
  m = std::max(m, C.radius);
  int exponent = 0;
  std::frexp(m, &exponent);  // m < 2^exponent
  return DoubleDoubleTriangleInput{in, std::ldexp(1.0, exponent)};
}

// The double-double stage on binary64 input, the whole decision in double-double: the answer,
// or nothing if some sign was too close to zero, an input was outside the window or the
// rounding mode is not to nearest.
inline std::optional<SlabDecision> double_double_decide_triangle_cylinder(const Triangle<double>& T, const Cylinder<double>& C) {
  const std::optional<DoubleDoubleTriangleInput> x = double_double_triangle_input(T, C);
  if (!x) return std::nullopt;
  try {
    // Factor 4: the bound of the proof above.
    return decide_slab(x->in, BoundedSigns<DD>(triangle_double_double_bounds(), x->M2, 4));
  } catch (const StaticUndecided&) {
    return std::nullopt;
  }
}

// The static stage with the double-double stage per sign. The decision runs in double
// (triangle_static_filter.hpp); a sign the double filter leaves undecided is evaluated again,
// that test alone, in double-double: the same expression tree (triangle_slab.hpp) on the exact
// double-double leaves, the points named by their SlabRef (a vertex, or the crossing of an edge
// with a cap plane, rebuilt from the double-double axial values as clip_to_slab builds it), and
// decided with the same bound as the whole double-double stage (the proof above holds for each
// test on its own: it bounds one tree's value from the exact leaves). Every sign either policy
// returns is right, so the control flow is the exact decision's, and the answer is the one the
// whole double-double stage would give; only the tests the double filter cannot decide pay for
// double-double. A sign neither decides (or an input outside the double-double window) gives
// up: StaticUndecided, as the whole double-double stage would.
class EscalatingTriangleSigns {
 public:
  EscalatingTriangleSigns(const Triangle<double>& T, const Cylinder<double>& C, double M2)
      : T_(T), C_(C), double_(triangle_static_bounds(), M2) {}

  CGAL::Sign operator()(double v, SlabTest t, SlabRef a = {}, SlabRef b = {}, SlabRef x = {}) const {
    const CGAL::Sign s = double_.sign_or_zero(v, t, a, b, x);
    return s != CGAL::ZERO ? s : escalated(t, a, b, x);
  }

  // Whether some sign needed double-double.
  bool escalated_any() const { return context_.has_value(); }

 private:
  struct Context {
    SlabInput<DD> in;
    DD AA, R;
    std::array<DD, 3> s, top;
    BoundedSigns<DD> sign;
    double M2;
  };

  const Context& context() const {
    if (!context_) {
      const std::optional<DoubleDoubleTriangleInput> x = double_double_triangle_input(T_, C_);
      if (!x) throw StaticUndecided{};
      const DD AA = dot(x->in.A, x->in.A);
      std::array<DD, 3> s, top;
      for (int i = 0; i < 3; ++i) {
        s[i] = slab_axial(x->in.a[i], x->in.A);
        top[i] = slab_axial_top(AA, s[i]);
      }
      // Factor 4: the bound of the proof above.
      context_.emplace(
          Context{x->in, AA, slab_radius_term(x->in.r, AA), s, top, BoundedSigns<DD>(triangle_double_double_bounds(), x->M2, 4), x->M2});
    }
    return *context_;
  }

  // The point a SlabRef names, as decide_slab builds it in double-double.
  static SlabPoint<DD> point(const Context& c, SlabRef r) {
    if (r.src < 0 || r.src >= slab_crossing_src(2, 0, 0)) throw StaticUndecided{};  // not recorded
    if (r.src < 3) return {c.in.a[r.src], c.in.one, SlabKind::vertex, r.src};
    const int k = r.src - 3, plane = k / 9, pos = k % 9 / 3, neg = k % 3;
    const std::array<DD, 3>& h = plane == 0 ? c.s : c.top;
    return slab_crossing(c.in.a[pos], h[pos], c.in.a[neg], h[neg]);
  }

  [[gnu::noinline]] CGAL::Sign escalated(SlabTest t, SlabRef a, SlabRef b, SlabRef x) const {
    const Context& c = context();
    DD v;
    switch (t) {
      case SlabTest::axial:
      case SlabTest::axial_top:
        if (a.src < 0 || a.src > 2) throw StaticUndecided{};
        v = t == SlabTest::axial ? c.s[a.src] : c.top[a.src];
        break;
      case SlabTest::point: v = slab_point_minus_R(point(c, a), c.in.A, c.R); break;
      case SlabTest::pierce: v = slab_det(point(c, a), point(c, b), c.in.A); break;
      case SlabTest::slope: v = slab_slope(point(c, x), slab_edge_V(point(c, a), point(c, b), c.in.A), c.in.A); break;
      case SlabTest::gap: {
        const SlabPoint<DD> pa = point(c, a), pb = point(c, b);
        v = slab_gap(slab_det(pa, pb, c.in.A), slab_edge_V(pa, pb, c.in.A), c.in.r);
        break;
      }
      case SlabTest::count: throw StaticUndecided{};
    }
    const CGAL::Sign sg = c.sign.sign_or_zero(v, t, a, b, x);
    return sg != CGAL::ZERO ? sg : enclosed(c, t, a, b, x);
  }

  // The test's value enclosed in Interval_nt (directed rounding: an enclosure by construction)
  // from enclosures of its leaves: a_i, A and r exactly (each double-double hi + lo), and the
  // axial values s_i and A.A - s_i as their double-double values plus or minus their proved
  // bound e M2^2 (the proof above). Near a cap plane these axial values are tiny (about 2^-53
  // of A.A) and known to about 2^-47 of themselves; a crossing point and the tests on it are
  // products of them, far below the homogeneous bound e M2^d of their degree, yet their
  // enclosure is as narrow, relative to their value, as the axial values'. StaticUndecided
  // when the enclosure contains 0.
  static CGAL::Sign enclosed(const Context& c, SlabTest t, SlabRef ra, SlabRef rb, SlabRef rx) {
    using I = CGAL::Interval_nt<false>;
    const double Es = triangle_double_double_bounds().axial.e * (c.M2 * c.M2);
    const double Et = triangle_double_double_bounds().axial_top.e * (c.M2 * c.M2);
    const CGAL::Protect_FPU_rounding<true> upward;  // no double-double operation below
    const auto exact = [](const DD& v) { return I(v.v.x[0]) + I(v.v.x[1]); };
    const auto vec = [&](const Vec3<DD>& v) { return Vec3<I>{exact(v.x), exact(v.y), exact(v.z)}; };
    const std::array<Vec3<I>, 3> a{vec(c.in.a[0]), vec(c.in.a[1]), vec(c.in.a[2])};
    const Vec3<I> A = vec(c.in.A);
    const I r = exact(c.in.r), AA = dot(A, A), R = slab_radius_term(r, AA);
    std::array<I, 3> s, top;
    for (int i = 0; i < 3; ++i) {
      s[i] = exact(c.s[i]) + I(-Es, Es);
      top[i] = exact(c.top[i]) + I(-Et, Et);
    }
    const auto point = [&](SlabRef p) -> SlabPoint<I> {
      if (p.src < 0 || p.src >= slab_crossing_src(2, 0, 0)) throw StaticUndecided{};
      if (p.src < 3) return {a[p.src], I(1), SlabKind::vertex, p.src};
      const int k = p.src - 3, plane = k / 9, pos = k % 9 / 3, neg = k % 3;
      const std::array<I, 3>& h = plane == 0 ? s : top;
      return slab_crossing(a[pos], h[pos], a[neg], h[neg]);
    };
    const I v = [&]() -> I {
      switch (t) {
        case SlabTest::point: return slab_point_minus_R(point(ra), A, R);
        case SlabTest::pierce: return slab_det(point(ra), point(rb), A);
        case SlabTest::slope: return slab_slope(point(rx), slab_edge_V(point(ra), point(rb), A), A);
        case SlabTest::gap: {
          const SlabPoint<I> pa = point(ra), pb = point(rb);
          return slab_gap(slab_det(pa, pb, A), slab_edge_V(pa, pb, A), r);
        }
        default: throw StaticUndecided{};  // axial values: the enclosure above is no better
      }
    }();
    if (v.inf() > 0) return CGAL::POSITIVE;
    if (v.sup() < 0) return CGAL::NEGATIVE;
    throw StaticUndecided{};
  }

  const Triangle<double>& T_;
  const Cylinder<double>& C_;
  StaticSigns double_;
  mutable std::optional<Context> context_;
};

// The static stage with per-sign double-double (EscalatingTriangleSigns).
struct EscalatedTriangleDecision {
  std::optional<SlabDecision> decision;
  bool in_static_range = false;  // the static stage ran (else nothing was tried)
  bool escalated = false;        // some sign needed double-double
};
inline EscalatedTriangleDecision escalating_decide_triangle_cylinder(const Triangle<double>& T, const Cylinder<double>& C) {
  EscalatedTriangleDecision r;
  const std::optional<StaticTriangleInput> x = static_triangle_input(T, C);
  if (!x) return r;
  r.in_static_range = true;
  const EscalatingTriangleSigns signs(T, C, x->M2);
  try {
    r.decision = decide_slab(x->in, signs);
  } catch (const StaticUndecided&) {
  }
  r.escalated = signs.escalated_any();
  return r;
}

}  // namespace certcyl::detail
