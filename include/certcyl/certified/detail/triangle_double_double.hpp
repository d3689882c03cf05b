// certcyl/certified/detail/triangle_double_double.hpp -- the double-double stage of the
// triangle-cylinder decision: the decision of triangle_slab.hpp evaluated in QD's double-double
// arithmetic (the DD type of line_double_double.hpp) with a forward error bound derived from
// the same expression trees as the double filter's, for the inputs the double filter leaves
// undecided (a vertex, an edge or the face within a few ulps of the wall, a cap plane or a rim):
// one sign at a time inside the double filter (EscalatingTriangleSigns, below), with interval
// enclosures for the signs that are small products of small factors, or the whole decision
// where the double filter's range is left (double_double_decide_triangle_cylinder).
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

// ---- vertex forms: every test as a form in the points' vertex coordinates ------------------
//
// Every point of the decision is a combination of the vertices: X = sum_i c_i a_i, w = sum_i c_i
// (a vertex: c = e_i; the crossing of slab_crossing(a_p, h_p, a_n, h_n): c_n = h_p, c_p = -h_n).
// With, for the vertices and the edges E_01 = a_1 - a_0, E_02 = a_2 - a_0, E_12 = a_2 - a_1,
//   D_ij = det(a_i, a_j, A),   P_ij = (a_i x A).(a_j x A) - R,
//   G_kl = D_k D_l - r^2 (E_k x A).(E_l x A),
// and, for an edge a b of the clipped polygon, the minors M_ij = ca_i cb_j - ca_j cb_i (i < j) and
// d = cb w_a - ca w_b, so that d_0 = -(M_01 + M_02), d_1 = M_01 - M_12, d_2 = M_02 + M_12 and
// sum_i d_i = 0, the tests of triangle_slab.hpp are, identically,
//   point   U.U - R w^2       = sum_ij c_i c_j P_ij
//   pierce  det(X_a, X_b, A)  = sum_{i<j} M_ij D_ij
//   slope   U_x.V             = sum_ij cx_i P_ij d_j            (the R terms cancel: sum d = 0)
//   gap     det^2 - r^2 V.V   = sum_kl M_k M_l G_kl              (V = sum_j d_j (a_j x A))
// A crossing next to a vertex, on an edge from it, has c close to a multiple of that vertex's
// e_i; in these forms the multiple cancels exactly (a minor ca_i cb_i - ca_i cb_i is never
// formed), and the tiny axial factor multiplies a vertex-level value known to double-double
// accuracy.

template <class NT>
NT vertex_point_form(const Vec3<NT>& ai, const Vec3<NT>& aj, const Vec3<NT>& A, const NT& R) {
  return dot(cross(ai, A), cross(aj, A)) - R;
}
template <class NT>
NT vertex_gap_form(const NT& Dk, const NT& Dl, const Vec3<NT>& Ek, const Vec3<NT>& El, const Vec3<NT>& A, const NT& r) {
  return Dk * Dl - (r * r) * dot(cross(Ek, A), cross(El, A));
}

// Their double-double error constants (the calculus of triangle_static_filter.hpp with
// u = 2^-100 on exact leaves bounded by 1, as triangle_double_double_bounds): degrees 3, 4, 6.
struct VertexFormBounds {
  double D, P, G;
};
inline const VertexFormBounds& vertex_form_bounds() {
  static const VertexFormBounds bounds = [] {
    using EB = ErrorBoundIn<DoubleDoubleUnit>;
    CGAL::Protect_FPU_rounding<true> upward;
    const EB leaf{1, 0, 1};
    const Vec3<EB> a{leaf, leaf, leaf}, A = a;
    const EB AA = dot(A, A), R = slab_radius_term(leaf, AA);
    const SlabPoint<EB> v{a, EB{1, 0, 0}, SlabKind::vertex};
    const EB D = slab_det(v, v, A);
    const Vec3<EB> E = a - a;
    const EB P = vertex_point_form(a, a, A, R), G = vertex_gap_form(D, D, E, E, A, leaf);
    return VertexFormBounds{D.e * (1 + 0x1p-20), P.e * (1 + 0x1p-20), G.e * (1 + 0x1p-20)};
  }();
  return bounds;
}

// The vertex-level values in double-double: D_01, D_02, D_12; P_00, P_01, P_02, P_11, P_12,
// P_22; G over the pairs (01, 02, 12) in the same upper-triangle order. Each group is made when
// a test first needs it (pierce: D; point and slope: P; gap: D and G).
struct VertexForms {
  std::array<DD, 3> D;
  std::array<DD, 6> P, G;
  bool has_D = false, has_P = false, has_G = false;
};
inline constexpr int vertex_pair_i[3] = {0, 0, 1}, vertex_pair_j[3] = {1, 2, 2};
inline constexpr int symmetric_index(int i, int j) { return i <= j ? (i == 0 ? j : (i == 1 ? 2 + j : 5)) : symmetric_index(j, i); }
inline void make_vertex_forms(VertexForms& f, const SlabInput<DD>& in, const DD& R, SlabTest t) {
  const auto& a = in.a;
  if ((t == SlabTest::pierce || t == SlabTest::gap) && !f.has_D) {
    for (int k = 0; k < 3; ++k)
      f.D[k] = slab_det(SlabPoint<DD>{a[vertex_pair_i[k]], in.one}, SlabPoint<DD>{a[vertex_pair_j[k]], in.one}, in.A);
    f.has_D = true;
  }
  if ((t == SlabTest::point || t == SlabTest::slope) && !f.has_P) {
    for (int i = 0; i < 3; ++i)
      for (int j = i; j < 3; ++j) f.P[symmetric_index(i, j)] = vertex_point_form(a[i], a[j], in.A, R);
    f.has_P = true;
  }
  if (t == SlabTest::gap && !f.has_G) {
    std::array<Vec3<DD>, 3> E;
    for (int k = 0; k < 3; ++k) E[k] = a[vertex_pair_j[k]] - a[vertex_pair_i[k]];
    for (int k = 0; k < 3; ++k)
      for (int l = k; l < 3; ++l) f.G[symmetric_index(k, l)] = vertex_gap_form(f.D[k], f.D[l], E[k], E[l], in.A, in.r);
    f.has_G = true;
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
    mutable VertexForms forms;  // made when first needed
    mutable std::array<std::optional<SlabPoint<DD>>, slab_src_count> points;  // by SlabRef::src, made when first needed
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
          Context{x->in, AA, slab_radius_term(x->in.r, AA), s, top, BoundedSigns<DD>(triangle_double_double_bounds(), x->M2, 4), x->M2, VertexForms{}, {}});
    }
    return *context_;
  }

  // The point a SlabRef names, as decide_slab builds it in double-double.
  static const SlabPoint<DD>& point(const Context& c, SlabRef r) {
    if (r.src < 0 || r.src >= slab_src_count) throw StaticUndecided{};  // not recorded
    std::optional<SlabPoint<DD>>& p = c.points[r.src];
    if (!p) {
      if (r.src < 3) {
        p = SlabPoint<DD>{c.in.a[r.src], c.in.one, SlabKind::vertex, r.src};
      } else {
        const auto [plane, pos, neg] = slab_crossing_of(r.src);
        const std::array<DD, 3>& h = plane == 0 ? c.s : c.top;
        p = slab_crossing(c.in.a[pos], h[pos], c.in.a[neg], h[neg]);
      }
    }
    return *p;
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
        const SlabPoint<DD>&pa = point(c, a), &pb = point(c, b);
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
  // enclosure is as narrow, relative to their value, as the axial values'. When it contains 0,
  // the vertex forms decide (in_vertex_forms), or StaticUndecided.
  static CGAL::Sign enclosed(const Context& c, SlabTest t, SlabRef ra, SlabRef rb, SlabRef rx) {
    using I = CGAL::Interval_nt<false>;
    const double Es = triangle_double_double_bounds().axial.e * (c.M2 * c.M2);
    const double Et = triangle_double_double_bounds().axial_top.e * (c.M2 * c.M2);
    if (t == SlabTest::axial || t == SlabTest::axial_top) throw StaticUndecided{};  // the enclosure below is no better
    std::array<I, 3> s, top;
    {
      const CGAL::Protect_FPU_rounding<true> upward;  // no double-double operation in this scope
      const auto vec = [](const Vec3<DD>& v) { return Vec3<I>{dd_enclosure(v.x), dd_enclosure(v.y), dd_enclosure(v.z)}; };
      const std::array<Vec3<I>, 3> a{vec(c.in.a[0]), vec(c.in.a[1]), vec(c.in.a[2])};
      const Vec3<I> A = vec(c.in.A);
      const I r = dd_enclosure(c.in.r), AA = dot(A, A), R = slab_radius_term(r, AA);
      for (int i = 0; i < 3; ++i) {
        s[i] = dd_enclosure(c.s[i], Es);
        top[i] = dd_enclosure(c.top[i], Et);
      }
      const auto point = [&](SlabRef p) -> SlabPoint<I> {
        if (p.src < 0 || p.src >= slab_src_count) throw StaticUndecided{};
        if (p.src < 3) return {a[p.src], I(1), SlabKind::vertex, p.src};
        const auto [plane, pos, neg] = slab_crossing_of(p.src);
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
    }
    make_vertex_forms(c.forms, c.in, c.R, t);  // double-double: round-to-nearest
    const CGAL::Protect_FPU_rounding<true> upward;
    return in_vertex_forms(c, t, ra, rb, rx, s, top);
  }

  // The test enclosed through the vertex forms above: the double-double vertex-level values
  // plus or minus their proved bounds e M2^d, combined in Interval_nt with the coordinates c.
  // Must run under upward rounding (the caller's scope); the forms are made in double-double
  // before it and are the only double-double work here.
  static CGAL::Sign in_vertex_forms(const Context& c, SlabTest t, SlabRef ra, SlabRef rb, SlabRef rx,
                                    const std::array<CGAL::Interval_nt<false>, 3>& s, const std::array<CGAL::Interval_nt<false>, 3>& top) {
    using I = CGAL::Interval_nt<false>;
    const VertexForms& f = c.forms;  // made by enclosed() beforehand, for this test
    const VertexFormBounds& e = vertex_form_bounds();
    const double M3 = c.M2 * c.M2 * c.M2;
    std::array<I, 3> D;
    std::array<I, 6> P, G;
    if (f.has_D)
      for (int k = 0; k < 3; ++k) D[k] = dd_enclosure(f.D[k], e.D * M3);
    if (f.has_P)
      for (int k = 0; k < 6; ++k) P[k] = dd_enclosure(f.P[k], e.P * (M3 * c.M2));
    if (f.has_G)
      for (int k = 0; k < 6; ++k) G[k] = dd_enclosure(f.G[k], e.G * (M3 * M3));
    const auto coords = [&](SlabRef p) {
      if (p.src < 0 || p.src >= slab_src_count) throw StaticUndecided{};
      std::array<I, 3> x{I(0), I(0), I(0)};
      if (p.src < 3) {
        x[p.src] = I(1);
        return x;
      }
      const auto [plane, pos, neg] = slab_crossing_of(p.src);
      const std::array<I, 3>& h = plane == 0 ? s : top;
      x[neg] = h[pos];
      x[pos] = -h[neg];
      return x;
    };
    const auto minors = [](const std::array<I, 3>& x, const std::array<I, 3>& y) {
      std::array<I, 3> M;
      for (int k = 0; k < 3; ++k) M[k] = x[vertex_pair_i[k]] * y[vertex_pair_j[k]] - x[vertex_pair_j[k]] * y[vertex_pair_i[k]];
      return M;
    };
    const auto form = [](const std::array<I, 3>& x, const std::array<I, 6>& Q, const std::array<I, 3>& y) {
      I v(0);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) v += x[i] * Q[symmetric_index(i, j)] * y[j];
      return v;
    };
    I v(0);
    switch (t) {
      case SlabTest::point: {
        const std::array<I, 3> x = coords(ra);
        v = form(x, P, x);
        break;
      }
      case SlabTest::pierce: {
        const std::array<I, 3> M = minors(coords(ra), coords(rb));
        v = M[0] * D[0] + M[1] * D[1] + M[2] * D[2];
        break;
      }
      case SlabTest::slope: {
        const std::array<I, 3> M = minors(coords(ra), coords(rb));
        const std::array<I, 3> d{-(M[0] + M[1]), M[0] - M[2], M[1] + M[2]};
        v = form(coords(rx), P, d);
        break;
      }
      case SlabTest::gap: {
        const std::array<I, 3> M = minors(coords(ra), coords(rb));
        v = form(M, G, M);
        break;
      }
      default: throw StaticUndecided{};
    }
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
