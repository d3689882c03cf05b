// certcyl/certified/detail/triangle_double_double.hpp -- the double-double stage of the
// triangle-cylinder decision: the decision of triangle_slab.hpp evaluated in QD's double-double
// arithmetic (the DD type of line_double_double.hpp) with a forward error bound derived from
// the same expression trees as the double filter's, for the inputs the double filter leaves
// undecided (a vertex, an edge or the face within a few ulps of the wall, a cap plane or a rim):
// one sign at a time inside the double filter (EscalatingTriangleSigns, below), with the tests
// on crossings with a cap plane decided through forms in the vertices' values (double values
// first, double-double ones where needed) and interval enclosures for the signs that are small
// products of small factors, or the whole decision where the double filter's range is left
// (double_double_decide_triangle_cylinder).
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
#include <bit>
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <type_traits>

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
  // m in [1, 2^62) is normal: with E its biased exponent field, m < 2^(E - 1022).
  const auto field = (std::bit_cast<std::uint64_t>(m) >> 52) & 0x7ff;
  return DoubleDoubleTriangleInput{in, std::bit_cast<double>((field + 1) << 52)};
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
//
// The vertex-level values are made twice over, in the same trees (VertexForms, each entry when
// first needed): in double on the static stage's leaves a_i = fl(v_i - P), A = fl(p1 - p0), r,
// with the static stage's calculus and scale (triangle_static_filter.hpp: |v' - v| <= e M2^d in
// any rounding mode, M2 the static power of two, d = 3, 4, 6 for D, P, G; these trees are
// smaller than the decision's (degree at most 6, b < 2^40, checked by the tests), so its
// overflow and underflow argument and its factor 1 + 2^-20 cover them), and in double-double on
// the exact leaves (the proof above, M2 the double-double power of two). A sign test on a
// crossing is decided first through the forms: the form is evaluated in Interval_nt, as
// sum_k coef_k entry_k, on the enclosures [v' - e M2^d, v' + e M2^d] of the entries and on
// enclosures of the coordinates c (the double-double axial values plus or minus their proved
// bound, as in enclosed() below); the interval contains the test's exact value (the identities
// above are exact; directed rounding gives an enclosure by construction, underflow included),
// so its sign is the test's when it excludes 0. In turn: all entries in double; the entries with
// the large coefficients in double-double and the others in double; all in double-double. On a
// face in a cap plane the crossings lie anywhere along their edges (the rounding places them),
// and their tests are far from zero relative to the vertex-level values: the double values
// decide them, and no double-double tree of degree up to 14 is evaluated. At a rim the
// crossings lie next to the rim's vertex, whose own entry (a few ulps from zero) carries the
// coefficient c_i^2 and the others tiny ones: that entry alone is made in double-double.
inline constexpr int vertex_pair_i[3] = {0, 0, 1}, vertex_pair_j[3] = {1, 2, 2};
inline constexpr int symmetric_index(int i, int j) { return i <= j ? (i == 0 ? j : (i == 1 ? 2 + j : 5)) : symmetric_index(j, i); }
// The pair (i, j), i <= j, of a symmetric_index k.
inline constexpr int symmetric_i[6] = {0, 0, 0, 1, 1, 2}, symmetric_j[6] = {0, 1, 2, 1, 2, 2};

// u x v, written out for the vertex forms (the same expression tree as cross() in vec3.hpp; a
// function of its own so that cross<double> of the static stage's hot path keeps its inlining).
template <class NT>
Vec3<NT> vertex_cross(const Vec3<NT>& u, const Vec3<NT>& v) {
  return {u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x};
}

template <class NT>
NT vertex_point_form(const Vec3<NT>& Ui, const Vec3<NT>& Uj, const NT& R) {
  return dot(Ui, Uj) - R;
}
template <class NT>
NT vertex_gap_form(const NT& Dk, const NT& Dl, const Vec3<NT>& Fk, const Vec3<NT>& Fl, const NT& r) {
  return Dk * Dl - (r * r) * dot(Fk, Fl);
}

// The vertex-level values, each made when first asked for: D_k (k over the pairs 01, 02, 12),
// P_k and G_k (k a symmetric_index). U_i = a_i x A and F_k = E_k x A are made once and shared
// (the same computed values in every tree that uses them): D_k = a_i.U_j (slab_det) for the
// pair (i, j) = k, P_ij = U_i.U_j - R, G_kl = D_k D_l - r^2 F_k.F_l. Each entry's tree is fixed,
// whichever entries were made before it.
enum class VertexFormGroup : int { D = 0, P = 1, G = 2 };
template <class NT>
class VertexForms {
 public:
  VertexForms(const SlabInput<NT>& in, const NT& R) : in_(in), R_(R) {}

  const NT& entry(VertexFormGroup g, int k) {
    switch (g) {
      case VertexFormGroup::D: return D(k);
      case VertexFormGroup::P: return P(k);
      case VertexFormGroup::G: break;
    }
    return G(k);
  }
  const NT& D(int k) {
    if (!(made_D_ >> k & 1)) D_[k] = dot(in_.a[vertex_pair_i[k]], U(vertex_pair_j[k])), made_D_ |= 1u << k;
    return D_[k];
  }
  const NT& P(int k) {
    if (!(made_P_ >> k & 1)) P_[k] = vertex_point_form(U(symmetric_i[k]), U(symmetric_j[k]), R_), made_P_ |= 1u << k;
    return P_[k];
  }
  const NT& G(int k) {
    if (!(made_G_ >> k & 1)) {
      const int i = symmetric_i[k], j = symmetric_j[k];
      G_[k] = vertex_gap_form(D(i), D(j), F(i), F(j), in_.r);
      made_G_ |= 1u << k;
    }
    return G_[k];
  }

 private:
  const Vec3<NT>& U(int i) {
    if (!(made_U_ >> i & 1)) U_[i] = vertex_cross(in_.a[i], in_.A), made_U_ |= 1u << i;
    return U_[i];
  }
  const Vec3<NT>& F(int k) {
    if (!(made_F_ >> k & 1))
      F_[k] = vertex_cross(Vec3<NT>(in_.a[vertex_pair_j[k]] - in_.a[vertex_pair_i[k]]), in_.A), made_F_ |= 1u << k;
    return F_[k];
  }

  const SlabInput<NT>& in_;
  NT R_;
  unsigned made_U_ = 0, made_F_ = 0, made_D_ = 0, made_P_ = 0, made_G_ = 0;
  std::array<Vec3<NT>, 3> U_, F_;
  std::array<NT, 3> D_;
  std::array<NT, 6> P_, G_;
};

// Their error constants for leaves bounded by 1, times (1 + 2^-20): VertexForms run on the
// calculus EB of triangle_static_filter.hpp, from the bound of a leaf a_i, A (r is exact).
// Degrees 3, 4, 6.
struct VertexFormBounds {
  double D, P, G;
  double b;  // the largest bound on a computed value (for the overflow margin)
};
template <class EB>
VertexFormBounds derive_vertex_form_bounds(const EB& difference) {
  CGAL::Protect_FPU_rounding<true> upward;
  const EB exact_leaf{1, 0, 1};
  const Vec3<EB> a{difference, difference, difference};
  const Vec3<EB> A = a;
  const EB AA = dot(A, A), R = slab_radius_term(exact_leaf, AA);
  const SlabInput<EB> in{{a, a, a}, A, exact_leaf, EB{1, 0, 0}};
  VertexForms<EB> f(in, R);
  VertexFormBounds out{0, 0, 0, 0};
  for (int k = 0; k < 6; ++k) {
    const EB& P = f.P(k);
    const EB& G = f.G(k);
    out.P = std::max(out.P, P.e * (1 + 0x1p-20)), out.G = std::max(out.G, G.e * (1 + 0x1p-20));
    out.b = std::max({out.b, P.b, G.b});
  }
  for (int k = 0; k < 3; ++k) out.D = std::max(out.D, f.D(k).e * (1 + 0x1p-20)), out.b = std::max(out.b, f.D(k).b);
  return out;
}
// Double-double, exact leaves.
inline const VertexFormBounds& vertex_form_bounds() {
  static const VertexFormBounds bounds = derive_vertex_form_bounds(ErrorBoundIn<DoubleDoubleUnit>{1, 0, 1});
  return bounds;
}
// Double, the static stage's rounded leaves (derive_static_bounds).
inline const VertexFormBounds& static_vertex_form_bounds() {
  static const VertexFormBounds bounds = derive_vertex_form_bounds(ErrorBound{1, ErrorBound::u * (1 + 0x1p-50), 1});
  return bounds;
}

// Which stage decided each sign of a decision by EscalatingTriangleSigns (below) that the double
// filter left undecided.
struct EscalatedSigns {
  int double_forms = 0;  // vertex forms from double values, coordinates from double-double
  int mixed_forms = 0;   // the same, double-double values for the large coefficients
  int dd_forms = 0;      // vertex forms from double-double values
  int dd_tree = 0;       // the test's own tree in double-double (axial values included)
  int enclosure = 0;     // the test's own tree in Interval_nt on exact leaves
  int crossing_trees = 0;  // tests on a crossing that the vertex forms left to the trees
};

// The static stage with the double-double stage per sign. The decision runs in double
// (triangle_static_filter.hpp); a sign the double filter leaves undecided is evaluated again,
// that test alone: a test on a crossing first through the vertex forms (in_forms: double values,
// then mixed, then double-double values), then every test in double-double on its own tree (the same
// expression tree as triangle_slab.hpp on the exact double-double leaves, the points named by
// their SlabRef: a vertex, or the crossing of an edge with a cap plane, rebuilt from the
// double-double axial values as clip_to_slab builds it, decided with the same bound as the
// whole double-double stage: the proof above holds for each test on its own, it bounds one
// tree's value from the exact leaves), then the same tree in Interval_nt (enclosed), then, for
// a test on vertices only, the double-double vertex forms. Every sign any of them returns is
// right, so the control flow is the exact decision's, and whenever the whole double-double
// stage decides, so does this (its test comes up in turn). A sign none decides (or an input
// outside the double-double window) gives up: StaticUndecided, as the whole double-double
// stage would.
class EscalatingTriangleSigns {
 public:
  EscalatingTriangleSigns(const Triangle<double>& T, const Cylinder<double>& C, const SlabInput<double>& in, double M2)
      : T_(T), C_(C), in_(in), M2_(M2), double_(triangle_static_bounds(), M2) {}

  CGAL::Sign operator()(double v, SlabTest t, SlabRef a = {}, SlabRef b = {}, SlabRef x = {}) const {
    const CGAL::Sign s = double_.sign_or_zero(v, t, a, b, x);
    return s != CGAL::ZERO ? s : escalated(t, a, b, x);
  }

  // Whether some sign needed double-double.
  bool escalated_any() const { return context_.has_value(); }
  const EscalatedSigns& escalated_signs() const { return count_; }

 private:
  using I = CGAL::Interval_nt<false>;

  struct Context {
    // Built in place (it is large): the axial values and R in double-double; factor 4: the
    // bound of the proof above.
    explicit Context(const DoubleDoubleTriangleInput& x)
        : in(x.in), AA(dot(in.A, in.A)), R(slab_radius_term(in.r, AA)), sign(triangle_double_double_bounds(), x.M2, 4), M2(x.M2) {
      for (int i = 0; i < 3; ++i) {
        s[i] = slab_axial(in.a[i], in.A);
        top[i] = slab_axial_top(AA, s[i]);
      }
    }
    SlabInput<DD> in;
    DD AA, R;
    std::array<DD, 3> s, top;
    BoundedSigns<DD> sign;
    double M2;
    mutable std::optional<VertexForms<DD>> forms;  // made when first needed
    // The points by SlabRef::src, each made when first needed (bit src of made_points): left
    // unconstructed until then (SlabPoint<DD> is trivially destructible).
    union PointSlot {
      PointSlot() {}
      SlabPoint<DD> p;
    };
    mutable std::array<PointSlot, slab_src_count> points;
    mutable std::uint32_t made_points = 0;
    static_assert(std::is_trivially_destructible_v<SlabPoint<DD>> && slab_src_count <= 32);
    // Enclosures of s_i and A.A - s_i (axial_enclosures), made when first needed.
    mutable bool has_axial_enclosures = false;
    mutable std::array<I, 3> s_enclosure, top_enclosure;
  };

  const Context& context() const {
    if (!context_) {
      const std::optional<DoubleDoubleTriangleInput> x = double_double_triangle_input(T_, C_);
      if (!x) throw StaticUndecided{};
      context_.emplace(*x);
    }
    return *context_;
  }

  // The point a SlabRef names, as decide_slab builds it in double-double.
  static const SlabPoint<DD>& point(const Context& c, SlabRef r) {
    if (r.src < 0 || r.src >= slab_src_count) throw StaticUndecided{};  // not recorded
    auto& slot = c.points[r.src];
    if (!(c.made_points >> r.src & 1)) {
      if (r.src < 3) {
        std::construct_at(&slot.p, SlabPoint<DD>{c.in.a[r.src], c.in.one, SlabKind::vertex, r.src});
      } else {
        const auto [plane, pos, neg] = slab_crossing_of(r.src);
        const std::array<DD, 3>& h = plane == 0 ? c.s : c.top;
        std::construct_at(&slot.p, slab_crossing(c.in.a[pos], h[pos], c.in.a[neg], h[neg]));
      }
      c.made_points |= 1u << r.src;
    }
    return slot.p;
  }

  [[gnu::noinline]] CGAL::Sign escalated(SlabTest t, SlabRef a, SlabRef b, SlabRef x) const {
    const Context& c = context();
    if (t == SlabTest::axial || t == SlabTest::axial_top) {
      if (a.src < 0 || a.src > 2) throw StaticUndecided{};
      const CGAL::Sign sg = c.sign.sign_or_zero(t == SlabTest::axial ? c.s[a.src] : c.top[a.src], t, a, b, x);
      if (sg == CGAL::ZERO) throw StaticUndecided{};  // the enclosures below are no better
      ++count_.dd_tree;
      return sg;
    }
    if (t == SlabTest::count) throw StaticUndecided{};
    const bool on_crossing = a.kind == SlabKind::crossing || b.kind == SlabKind::crossing || x.kind == SlabKind::crossing;
    if (on_crossing) {
      if (const CGAL::Sign sg = in_forms(c, t, a, b, x, true); sg != CGAL::ZERO) return sg;
      ++count_.crossing_trees;
    }
    DD v;
    switch (t) {
      case SlabTest::point: v = slab_point_minus_R(point(c, a), c.in.A, c.R); break;
      case SlabTest::pierce: v = slab_det(point(c, a), point(c, b), c.in.A); break;
      case SlabTest::slope: v = slab_slope(point(c, x), slab_edge_V(point(c, a), point(c, b), c.in.A), c.in.A); break;
      case SlabTest::gap: {
        const SlabPoint<DD>&pa = point(c, a), &pb = point(c, b);
        v = slab_gap(slab_det(pa, pb, c.in.A), slab_edge_V(pa, pb, c.in.A), c.in.r);
        break;
      }
      default: throw StaticUndecided{};
    }
    if (const CGAL::Sign sg = c.sign.sign_or_zero(v, t, a, b, x); sg != CGAL::ZERO) return ++count_.dd_tree, sg;
    if (const CGAL::Sign sg = enclosed(c, t, a, b, x); sg != CGAL::ZERO) return ++count_.enclosure, sg;
    if (!on_crossing)
      if (const CGAL::Sign sg = in_forms(c, t, a, b, x, false); sg != CGAL::ZERO) return sg;
    throw StaticUndecided{};
  }

  // Enclosures of the axial values s_i and A.A - s_i: their double-double values plus or minus
  // their proved bound e M2^2 (the proof above). Under upward rounding.
  static void axial_enclosures(const Context& c, std::array<I, 3>& s, std::array<I, 3>& top) {
    if (!c.has_axial_enclosures) {
      const double Es = triangle_double_double_bounds().axial.e * (c.M2 * c.M2);
      const double Et = triangle_double_double_bounds().axial_top.e * (c.M2 * c.M2);
      for (int i = 0; i < 3; ++i) {
        c.s_enclosure[i] = dd_enclosure(c.s[i], Es);
        c.top_enclosure[i] = dd_enclosure(c.top[i], Et);
      }
      c.has_axial_enclosures = true;
    }
    s = c.s_enclosure;
    top = c.top_enclosure;
  }

  // The test's value enclosed in Interval_nt (directed rounding: an enclosure by construction)
  // from enclosures of its leaves: a_i, A and r exactly (each double-double hi + lo), and the
  // axial values s_i and A.A - s_i (axial_enclosures). Near a cap plane these axial values are
  // tiny (about 2^-53 of A.A) and known to about 2^-47 of themselves; a crossing point and the
  // tests on it are products of them, far below the homogeneous bound e M2^d of their degree,
  // yet their enclosure is as narrow, relative to their value, as the axial values'. ZERO when
  // the enclosure contains 0.
  static CGAL::Sign enclosed(const Context& c, SlabTest t, SlabRef ra, SlabRef rb, SlabRef rx) {
    const CGAL::Protect_FPU_rounding<true> upward;  // no double-double operation in this scope
    std::array<I, 3> s, top;
    axial_enclosures(c, s, top);
    const auto vec = [](const Vec3<DD>& v) { return Vec3<I>{dd_enclosure(v.x), dd_enclosure(v.y), dd_enclosure(v.z)}; };
    const std::array<Vec3<I>, 3> a{vec(c.in.a[0]), vec(c.in.a[1]), vec(c.in.a[2])};
    const Vec3<I> A = vec(c.in.A);
    const I r = dd_enclosure(c.in.r), AA = dot(A, A), R = slab_radius_term(r, AA);
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
        default: throw StaticUndecided{};  // axial values: decided in escalated() or not at all
      }
    }();
    return interval_sign(v);
  }

  static CGAL::Sign interval_sign(const I& v) {
    if (v.inf() > 0) return CGAL::POSITIVE;
    if (v.sup() < 0) return CGAL::NEGATIVE;
    return CGAL::ZERO;
  }

  // A test's form in the vertex-level values of one group: value = sum_k coef[k] entry(group, k)
  // over k < n (the identities above, the symmetric sums folded: x^T Q y = sum over i <= j of
  // Q_ij (x_i y_j + x_j y_i), or x_i y_i when i = j).
  struct FormCoefficients {
    VertexFormGroup group = VertexFormGroup::P;
    int n = 0;
    std::array<I, 6> coef;
  };
  static bool is_zero(const I& v) { return v.inf() == 0 && v.sup() == 0; }

  // The coefficients enclosed, from the coordinates c of the points (axial_enclosures). Under
  // upward rounding.
  static FormCoefficients coefficients(const Context& c, SlabTest t, SlabRef ra, SlabRef rb, SlabRef rx) {
    std::array<I, 3> s, top;
    axial_enclosures(c, s, top);
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
    // A product with an exact zero is an exact zero (most coordinates are).
    const auto product = [](const I& x, const I& y) { return is_zero(x) || is_zero(y) ? I(0) : x * y; };
    const auto minors = [&](const std::array<I, 3>& x, const std::array<I, 3>& y) {
      std::array<I, 3> M;
      for (int k = 0; k < 3; ++k)
        M[k] = product(x[vertex_pair_i[k]], y[vertex_pair_j[k]]) - product(x[vertex_pair_j[k]], y[vertex_pair_i[k]]);
      return M;
    };
    const auto quadratic = [&](const std::array<I, 3>& x, const std::array<I, 3>& y, std::array<I, 6>& k) {
      for (int m = 0; m < 6; ++m) {
        const int i = symmetric_i[m], j = symmetric_j[m];
        k[m] = i == j ? product(x[i], y[i]) : product(x[i], y[j]) + product(x[j], y[i]);
      }
    };
    FormCoefficients f;
    switch (t) {
      case SlabTest::point: {
        const std::array<I, 3> x = coords(ra);
        quadratic(x, x, f.coef);
        f.group = VertexFormGroup::P, f.n = 6;
        break;
      }
      case SlabTest::pierce: {
        const std::array<I, 3> M = minors(coords(ra), coords(rb));
        for (int k = 0; k < 3; ++k) f.coef[k] = M[k];
        f.group = VertexFormGroup::D, f.n = 3;
        break;
      }
      case SlabTest::slope: {
        const std::array<I, 3> M = minors(coords(ra), coords(rb));
        const std::array<I, 3> d{-(M[0] + M[1]), M[0] - M[2], M[1] + M[2]};
        quadratic(coords(rx), d, f.coef);
        f.group = VertexFormGroup::P, f.n = 6;
        break;
      }
      case SlabTest::gap: {
        const std::array<I, 3> M = minors(coords(ra), coords(rb));
        quadratic(M, M, f.coef);
        f.group = VertexFormGroup::G, f.n = 6;
        break;
      }
      default: throw StaticUndecided{};
    }
    return f;
  }

  // The sign of sum_k coef[k] entry(k) (entry(k): an enclosure of the exact vertex-level value),
  // ZERO when the enclosure contains 0. Under upward rounding.
  template <class Entry>
  static CGAL::Sign form_sign(const FormCoefficients& f, Entry&& entry) {
    I v(0);
    for (int k = 0; k < f.n; ++k)
      if (!is_zero(f.coef[k])) v += f.coef[k] * entry(k);
    return interval_sign(v);
  }

  // A test through the vertex forms (the comment above them): with the values in double and
  // their static bounds (when with_double), then with the double-double values, with their
  // bounds, for the large coefficients (at least 2^-24 of the largest in magnitude) and the
  // double values for the others, then with the double-double values for all. Every entry is
  // enclosed with its own proved bound, so each of the three is an enclosure of the test's
  // exact value; the mixed one serves a crossing next to a vertex on a rim, whose form is
  // dominated by that vertex's own entries. ZERO when none decides. Counts the stage deciding.
  CGAL::Sign in_forms(const Context& c, SlabTest t, SlabRef ra, SlabRef rb, SlabRef rx, bool with_double) const {
    FormCoefficients f;
    std::array<bool, 6> large{};
    bool all_large = true;
    const double M3 = M2_ * M2_ * M2_, N3 = c.M2 * c.M2 * c.M2;
    const auto bound = [](const VertexFormBounds& e, VertexFormGroup g, double M, double M3) {
      return g == VertexFormGroup::D ? e.D * M3 : (g == VertexFormGroup::P ? e.P * (M3 * M) : e.G * (M3 * M3));
    };
    if (!dforms_) dforms_.emplace(in_, double_R());
    VertexForms<double>& df = *dforms_;
    {
      const CGAL::Protect_FPU_rounding<true> upward;
      f = coefficients(c, t, ra, rb, rx);
      const double Ed = bound(static_vertex_form_bounds(), f.group, M2_, M3);
      // Double: the static calculus holds in any rounding mode.
      const auto in_double = [&](int k) { return I(df.entry(f.group, k)) + I(-Ed, Ed); };
      if (with_double) {
        if (const CGAL::Sign sg = form_sign(f, in_double); sg != CGAL::ZERO) return ++count_.double_forms, sg;
        double largest = 0;
        for (int k = 0; k < f.n; ++k) largest = std::max(largest, CGAL::abs(f.coef[k]).sup());
        for (int k = 0; k < f.n; ++k) {
          large[k] = CGAL::abs(f.coef[k]).sup() >= largest * 0x1p-24;
          all_large &= large[k] || is_zero(f.coef[k]);
        }
      }
    }
    if (!c.forms) c.forms.emplace(c.in, c.R);
    VertexForms<DD>& ddf = *c.forms;
    const double Edd = bound(vertex_form_bounds(), f.group, c.M2, N3);
    const double Ed = bound(static_vertex_form_bounds(), f.group, M2_, M3);
    if (with_double && !all_large) {
      for (int k = 0; k < f.n; ++k)
        if (large[k]) ddf.entry(f.group, k);  // double-double: round-to-nearest
      const CGAL::Protect_FPU_rounding<true> upward;
      const auto mixed = [&](int k) {
        return large[k] ? dd_enclosure(ddf.entry(f.group, k), Edd) : I(df.entry(f.group, k)) + I(-Ed, Ed);
      };
      if (const CGAL::Sign sg = form_sign(f, mixed); sg != CGAL::ZERO) return ++count_.mixed_forms, sg;
    }
    for (int k = 0; k < f.n; ++k)
      if (!is_zero(f.coef[k])) ddf.entry(f.group, k);  // double-double: round-to-nearest
    const CGAL::Protect_FPU_rounding<true> upward;
    const auto in_dd = [&](int k) { return dd_enclosure(ddf.entry(f.group, k), Edd); };
    if (const CGAL::Sign sg = form_sign(f, in_dd); sg != CGAL::ZERO) return ++count_.dd_forms, sg;
    return CGAL::ZERO;
  }

  // R = r^2 A.A in double, as the static stage computes it (slab_radius_term(r, dot(A, A))).
  double double_R() const { return slab_radius_term(in_.r, dot(in_.A, in_.A)); }

  const Triangle<double>& T_;
  const Cylinder<double>& C_;
  const SlabInput<double>& in_;
  double M2_;
  StaticSigns double_;
  mutable std::optional<Context> context_;
  mutable std::optional<VertexForms<double>> dforms_;  // made when first needed
  mutable EscalatedSigns count_;
};
// The static stage with per-sign double-double (EscalatingTriangleSigns).
struct EscalatedTriangleDecision {
  std::optional<SlabDecision> decision;
  bool in_static_range = false;  // the static stage ran (else nothing was tried)
  bool escalated = false;        // some sign needed double-double
  EscalatedSigns signs;          // which stage decided each sign the double filter left
};
inline EscalatedTriangleDecision escalating_decide_triangle_cylinder(const Triangle<double>& T, const Cylinder<double>& C) {
  EscalatedTriangleDecision r;
  const std::optional<StaticTriangleInput> x = static_triangle_input(T, C);
  if (!x) return r;
  r.in_static_range = true;
  const EscalatingTriangleSigns signs(T, C, x->in, x->M2);
  try {
    r.decision = decide_slab(x->in, signs);
  } catch (const StaticUndecided&) {
  }
  r.escalated = signs.escalated_any();
  r.signs = signs.escalated_signs();
  return r;
}

}  // namespace certcyl::detail
