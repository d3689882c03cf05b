// certcyl/certified/detail/triangle_slab.hpp -- the sign tests behind the certified
// triangle-cylinder predicate, generic over the number type and over the way a sign is decided
// (a sign policy): exact or interval signs (nt::sign), or the semi-static double filter of
// triangle_static_filter.hpp, which needs to know which polynomial it is looking at.
//
// Notation (design note, section 3): P = p0, A = p1 - p0, a_i = v_i - P, r the radius, and
//   s_i = a_i.A                axial coordinate of v_i, times A.A               (degree 2)
//   q(X) = |(X-P) x A|^2       squared distance to the axis, times A.A          (degree 4)
//   R = r^2 A.A
// The closed cylinder is {0 <= s <= A.A, q <= R}; its interior uses strict inequalities.
// Everything below is division-free: a point is homogeneous, X/w + P with w > 0.
//
// Outline (each step a sign test):
//   1. T entirely beyond a cap plane (all s_i < 0, or all s_i > A.A): separated.
//      Shortcut: a vertex strictly inside the cylinder: overlapping.
//   2. S = T clipped to the closed slab 0 <= s <= A.A: T's boundary walked once, keeping the
//      vertices in the slab and the strict crossings of each edge with the cap planes (at most
//      5 points). A crossing of edge v_i v_j with the plane where the affine function h
//      (h = s, or h = A.A - s) vanishes, with h_+ > 0 > h_- at the two ends a_+, a_-, is
//        X = h_+ a_- - h_- a_+,  w = h_+ - h_- > 0                 (degrees 3 and 2).
//   3. m = min over S of q. Either the axis line pierces S (m = 0) or m is attained on an edge
//      of S (q is convex; where its minimum over the plane of S is not unique, the minimising
//      line meets S only if it meets S's boundary). For an edge a b of S, with
//        D = X_b w_a - X_a w_b (direction),  U_a = X_a x A,  U_b = X_b x A,  V = D x A,
//      q(a + t (b - a)) is a convex quadratic in t whose slope at a has the sign of U_a.V and
//      at b the sign of U_b.V. If U_a.V >= 0 the minimum is at a; else (then V != 0) if
//      U_b.V <= 0 it is at b; else it is inside, with V != 0. There, with u = U_a / w_a and
//      v = V / (w_a w_b), q_min = u.u - (u.v)^2 / v.v, and Lagrange's identities
//      u.u v.v - (u.v)^2 = |u x v|^2 and (X_a x A) x (D x A) = det(X_a, D, A) A = w_a det(X_a, X_b, A) A
//      give (q_min - R) v.v = A.A (det(X_a, X_b, A)^2 - r^2 V.V) / (w_a w_b)^2, so the sign of
//      q_min - R is the sign of
//        gap = det(X_a, X_b, A)^2 - r^2 V.V
//      (the squared distance between the edge's line and the axis line, against r^2). The
//      endpoint tests are q - R = (U.U - R w^2) / w^2.
//      "The axis pierces S" is the sign test of det(X_a, X_b, A) over S's edges: one sign,
//      not all zero.
//   4. If T meets the open slab, the closure of T ∩ open slab is S, so
//        m < R  overlapping,   m = R  touching,   m > R  separated.
//      Otherwise T touches the slab only in a cap plane, where no point is interior:
//        m <= R touching,      m > R  separated.
//
// Degrees (vertex: X degree 1, w degree 0; crossing: X degree 3, w degree 2), by edge kind
// vertex-vertex / vertex-crossing / crossing-crossing:
//   det 3 / 5 / 7,   U.V 4 / 6 or 8 / 10,   gap 6 / 10 / 14,   point q - R 4 (vertex), 8.
#pragma once

#include <CGAL/Uncertain.h>
#include <CGAL/enum.h>

#include <array>
#include <utility>

#include "certcyl/answer.hpp"
#include "certcyl/number_traits.hpp"
#include "certcyl/primitives.hpp"

namespace certcyl::detail {

// A vertex of the clipped polygon: the input vertex (X = a_i, w = 1) or a crossing with a cap
// plane (X, w from the formula above). The kind selects the static filter's error bound.
enum class SlabKind : int { vertex = 0, crossing = 1 };

// Which point of the decision a sign test is about, for sign policies that re-evaluate one test
// in another arithmetic (triangle_static_filter.hpp): its kind, and where it comes from, `src`:
// vertex i is i (0..2); the crossing of the edge v_i v_j with the plane h = 0 (h = s: plane 0,
// h = A.A - s: plane 1), h_i > 0 > h_j, is 3 + 9 plane + 3 i + j; -1 when not recorded.
struct SlabRef {
  SlabKind kind = SlabKind::vertex;
  int src = -1;
};
inline constexpr int slab_crossing_src(int plane, int pos, int neg) { return 3 + 9 * plane + 3 * pos + neg; }
inline constexpr int slab_src_count = slab_crossing_src(2, 0, 0);  // vertices and crossings: 0 .. 20
// A crossing's src read back (3 <= src < slab_src_count).
struct SlabCrossingSrc {
  int plane, pos, neg;
};
inline constexpr SlabCrossingSrc slab_crossing_of(int src) { return {(src - 3) / 9, (src - 3) % 9 / 3, (src - 3) % 3}; }
static_assert(slab_crossing_of(slab_crossing_src(1, 2, 0)).plane == 1 && slab_crossing_of(slab_crossing_src(1, 2, 0)).pos == 2 &&
              slab_crossing_of(slab_crossing_src(1, 2, 0)).neg == 0);

template <class NT>
struct SlabPoint {
  Vec3<NT> X;  // the point is P + X / w
  NT w;        // w > 0
  SlabKind kind = SlabKind::vertex;
  int src = -1;  // SlabRef::src

  SlabRef ref() const { return {kind, src}; }
};

// A convex polygon (possibly degenerate: repeated or collinear vertices) in boundary order.
template <class NT>
struct SlabPolygon {
  std::array<SlabPoint<NT>, 5> p;
  int n = 0;

  void push(const SlabPoint<NT>& x) { p[n++] = x; }
};

// The polynomials whose signs decide the answer. Each is one fixed expression tree (the
// functions below), so the static filter's error bound for it is derived from that tree.
enum class SlabTest : int {
  axial,       // s_i                        degree 2
  axial_top,   // A.A - s_i                  degree 2
  point,       // U.U - R w^2                degree 4 (vertex) or 8 (crossing)
  pierce,      // det(X_a, X_b, A)           3 / 5 / 7
  slope,       // U_a.V (or U_b.V)           by the kinds of the edge and of the point
  gap,         // det^2 - r^2 V.V            6 / 10 / 14
  count
};

// ---- the expression trees -----------------------------------------------------------------

template <class NT>
NT slab_axial(const Vec3<NT>& a, const Vec3<NT>& A) {
  return dot(a, A);
}

template <class NT>
NT slab_axial_top(const NT& AA, const NT& s) {
  return AA - s;
}

template <class NT>
NT slab_radius_term(const NT& r, const NT& AA) {
  return (r * r) * AA;
}

// The crossing of the segment a_+ a_- with the plane h = 0, from h_+ > 0 > h_-.
template <class NT>
SlabPoint<NT> slab_crossing(const Vec3<NT>& a_pos, const NT& h_pos, const Vec3<NT>& a_neg, const NT& h_neg) {
  return {Vec3<NT>(a_neg * h_pos - a_pos * h_neg), NT(h_pos - h_neg), SlabKind::crossing};
}

// q - R at a point, times w^2.
template <class NT>
NT slab_point_minus_R(const SlabPoint<NT>& x, const Vec3<NT>& A, const NT& R) {
  const Vec3<NT> U = cross(x.X, A);
  return dot(U, U) - R * (x.w * x.w);
}

template <class NT>
NT slab_det(const SlabPoint<NT>& a, const SlabPoint<NT>& b, const Vec3<NT>& A) {
  return dot(a.X, cross(b.X, A));
}

// V = D x A for the edge a b.
template <class NT>
Vec3<NT> slab_edge_V(const SlabPoint<NT>& a, const SlabPoint<NT>& b, const Vec3<NT>& A) {
  return cross(Vec3<NT>(b.X * a.w - a.X * b.w), A);
}

template <class NT>
NT slab_slope(const SlabPoint<NT>& x, const Vec3<NT>& V, const Vec3<NT>& A) {
  return dot(cross(x.X, A), V);
}

template <class NT>
NT slab_gap(const NT& det, const Vec3<NT>& V, const NT& r) {
  return det * det - (r * r) * dot(V, V);
}

// ---- sign policies --------------------------------------------------------------------------

// Exact types and intervals: the number type decides (an undecided interval sign throws
// CGAL::Uncertain_conversion_exception).
struct ExactSigns {
  template <class NT>
  CGAL::Sign operator()(const NT& v, SlabTest, SlabRef = {}, SlabRef = {}, SlabRef = {}) const {
    return nt::sign(v);
  }
};

// ---- the algorithm --------------------------------------------------------------------------

// The input of the decision, relative to P: a_i = v_i - P, the axis A, the radius r, and the
// number one (the weight of an input vertex).
template <class NT>
struct SlabInput {
  std::array<Vec3<NT>, 3> a;
  Vec3<NT> A;
  NT r;
  NT one;
};

// Where T lies along the axis.
enum class SlabContact { beyond_cap0, beyond_cap1, cap0_plane_only, cap1_plane_only, crosses_open_slab };

inline SlabContact locate_in_slab(const std::array<CGAL::Sign, 3>& lo, const std::array<CGAL::Sign, 3>& hi) {
  int below = 0, above = 0, reaches_up = 0, reaches_down = 0;
  for (int i = 0; i < 3; ++i) {
    below += lo[i] == CGAL::NEGATIVE;
    above += hi[i] == CGAL::NEGATIVE;
    reaches_up += lo[i] == CGAL::POSITIVE;
    reaches_down += hi[i] == CGAL::POSITIVE;
  }
  if (below == 3) return SlabContact::beyond_cap0;
  if (above == 3) return SlabContact::beyond_cap1;
  // s is affine on T, so T meets 0 < s < A.A iff max s > 0 and min s < A.A.
  if (reaches_up == 0) return SlabContact::cap0_plane_only;
  if (reaches_down == 0) return SlabContact::cap1_plane_only;
  return SlabContact::crosses_open_slab;
}

// T ∩ closed slab (step 2). lo_i = sign(s_i), hi_i = sign(A.A - s_i).
template <class NT>
SlabPolygon<NT> clip_to_slab(const SlabInput<NT>& in, const std::array<NT, 3>& s, const std::array<NT, 3>& top,
                             const std::array<CGAL::Sign, 3>& lo, const std::array<CGAL::Sign, 3>& hi) {
  SlabPolygon<NT> S;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    if (lo[i] != CGAL::NEGATIVE && hi[i] != CGAL::NEGATIVE) S.push({in.a[i], in.one, SlabKind::vertex, i});
    const bool cross0 = lo[i] * lo[j] == CGAL::NEGATIVE;
    const bool cross1 = hi[i] * hi[j] == CGAL::NEGATIVE;
    const auto crossing0 = [&] {
      SlabPoint<NT> x = lo[i] == CGAL::POSITIVE ? slab_crossing(in.a[i], s[i], in.a[j], s[j]) : slab_crossing(in.a[j], s[j], in.a[i], s[i]);
      x.src = lo[i] == CGAL::POSITIVE ? slab_crossing_src(0, i, j) : slab_crossing_src(0, j, i);
      return x;
    };
    const auto crossing1 = [&] {
      SlabPoint<NT> x = hi[i] == CGAL::POSITIVE ? slab_crossing(in.a[i], top[i], in.a[j], top[j])
                                                : slab_crossing(in.a[j], top[j], in.a[i], top[i]);
      x.src = hi[i] == CGAL::POSITIVE ? slab_crossing_src(1, i, j) : slab_crossing_src(1, j, i);
      return x;
    };
    // Along the edge from v_i, the plane on v_i's side comes first.
    if (lo[i] == CGAL::NEGATIVE) {
      if (cross0) S.push(crossing0());
      if (cross1) S.push(crossing1());
    } else {
      if (cross1) S.push(crossing1());
      if (cross0) S.push(crossing0());
    }
  }
  return S;
}

// Does the axis line meet S? Its projection along A contains the projection of P,
// non-degenerately: det(X_a, X_b, A) over S's edges has one sign, not all zero (for a polygon
// whose projection is a segment, or a point, they are either of both signs or all zero, and
// the edges then decide).
template <class NT, class Signs>
bool axis_pierces(const SlabPolygon<NT>& S, const Vec3<NT>& A, const Signs& sign) {
  if (S.n < 3) return false;
  bool has_positive = false, has_negative = false;
  for (int i = 0; i < S.n; ++i) {
    const SlabPoint<NT>& a = S.p[i];
    const SlabPoint<NT>& b = S.p[(i + 1) % S.n];
    const CGAL::Sign sg = sign(slab_det(a, b, A), SlabTest::pierce, a.ref(), b.ref());
    has_positive |= sg == CGAL::POSITIVE;
    has_negative |= sg == CGAL::NEGATIVE;
    if (has_positive && has_negative) return false;
  }
  return has_positive != has_negative;
}

// Where the minimum of q over an edge lies.
enum class EdgeMinimum { at_a, at_b, inside };

template <class NT, class Signs>
EdgeMinimum locate_edge_minimum(const SlabPoint<NT>& a, const SlabPoint<NT>& b, const Vec3<NT>& V, const Vec3<NT>& A,
                                const Signs& sign) {
  // Slope at a >= 0 (this includes V = 0: q constant along the edge).
  if (sign(slab_slope(a, V, A), SlabTest::slope, a.ref(), b.ref(), a.ref()) != CGAL::NEGATIVE) return EdgeMinimum::at_a;
  if (sign(slab_slope(b, V, A), SlabTest::slope, a.ref(), b.ref(), b.ref()) != CGAL::POSITIVE) return EdgeMinimum::at_b;
  return EdgeMinimum::inside;
}

// sign(min over the edge a b of q  -  R).
template <class NT, class Signs>
CGAL::Sign edge_minimum_minus(const SlabPoint<NT>& a, const SlabPoint<NT>& b, const SlabInput<NT>& in, const NT& R,
                              const Signs& sign) {
  const Vec3<NT> V = slab_edge_V(a, b, in.A);
  switch (locate_edge_minimum(a, b, V, in.A, sign)) {
    case EdgeMinimum::at_a: return sign(slab_point_minus_R(a, in.A, R), SlabTest::point, a.ref());
    case EdgeMinimum::at_b: return sign(slab_point_minus_R(b, in.A, R), SlabTest::point, b.ref());
    case EdgeMinimum::inside: break;
  }
  return sign(slab_gap(slab_det(a, b, in.A), V, in.r), SlabTest::gap, a.ref(), b.ref());
}

// sign(min over S of q  -  R), S not empty.
template <class NT, class Signs>
CGAL::Sign polygon_minimum_minus(const SlabPolygon<NT>& S, const SlabInput<NT>& in, const NT& R, const Signs& sign) {
  if (S.n == 1) return sign(slab_point_minus_R(S.p[0], in.A, R), SlabTest::point, S.p[0].ref());
  CGAL::Sign best = CGAL::POSITIVE;
  // A 2-gon is one segment: its second edge is the first reversed.
  const int edges = S.n == 2 ? 1 : S.n;
  for (int i = 0; i < edges; ++i) {
    const CGAL::Sign sg = edge_minimum_minus(S.p[i], S.p[(i + 1) % S.n], in, R, sign);
    if (sg == CGAL::NEGATIVE) return sg;
    if (sg == CGAL::ZERO) best = CGAL::ZERO;
  }
  return best;
}

// The axial data of T: s_i, A.A - s_i and their signs.
template <class NT>
struct SlabAxial {
  NT AA;
  std::array<NT, 3> s, top;
  std::array<CGAL::Sign, 3> lo, hi;
};

template <class NT, class Signs>
SlabAxial<NT> slab_axial_data(const SlabInput<NT>& in, const Signs& sign) {
  SlabAxial<NT> ax;
  ax.AA = dot(in.A, in.A);
  for (int i = 0; i < 3; ++i) {
    ax.s[i] = slab_axial(in.a[i], in.A);
    ax.top[i] = slab_axial_top(ax.AA, ax.s[i]);
    ax.lo[i] = sign(ax.s[i], SlabTest::axial, SlabRef{SlabKind::vertex, i});
    ax.hi[i] = sign(ax.top[i], SlabTest::axial_top, SlabRef{SlabKind::vertex, i});
  }
  return ax;
}

// The answer and the facts that decided it (each one certified by the sign policy).
struct SlabDecision {
  Answer answer = Answer::undecided;
  SlabContact where = SlabContact::crosses_open_slab;
  int inside_vertex = -1;  // a vertex strictly inside the cylinder, if the shortcut found one
};

// The three-valued answer, by sign tests only (outline at the top of this file).
template <class NT, class Signs>
SlabDecision decide_slab(const SlabInput<NT>& in, const Signs& sign) {
  // Step 1: beyond a cap plane.
  const SlabAxial<NT> ax = slab_axial_data(in, sign);
  const SlabContact where = locate_in_slab(ax.lo, ax.hi);
  if (where == SlabContact::beyond_cap0 || where == SlabContact::beyond_cap1) return {Answer::separated, where};

  // Shortcut: a vertex strictly inside the cylinder (a common case, and cheap).
  const NT R = slab_radius_term(in.r, ax.AA);
  for (int i = 0; i < 3; ++i) {
    if (ax.lo[i] == CGAL::POSITIVE && ax.hi[i] == CGAL::POSITIVE &&
        sign(slab_point_minus_R(SlabPoint<NT>{in.a[i], in.one, SlabKind::vertex, i}, in.A, R), SlabTest::point,
             SlabRef{SlabKind::vertex, i}) == CGAL::NEGATIVE)
      return {Answer::overlapping, where, i};
  }

  // Steps 2 and 3: clip, then the minimum of q against R.
  const SlabPolygon<NT> S = clip_to_slab(in, ax.s, ax.top, ax.lo, ax.hi);
  const CGAL::Sign m = axis_pierces(S, in.A, sign) ? CGAL::NEGATIVE : polygon_minimum_minus(S, in, R, sign);

  // Step 4.
  if (where == SlabContact::crosses_open_slab)
    return {m == CGAL::NEGATIVE ? Answer::overlapping : (m == CGAL::ZERO ? Answer::touching : Answer::separated), where};
  // else: T meets the slab only in a cap plane, where no point is interior.
  return {m == CGAL::POSITIVE ? Answer::separated : Answer::touching, where};
}

template <class NT, class Signs>
Answer decide_triangle_cylinder(const SlabInput<NT>& in, const Signs& sign) {
  return decide_slab(in, sign).answer;
}

// The input relative to P, in a certified number type (exact, or enclosing for intervals).
template <class NT>
SlabInput<NT> slab_input(const Triangle<NT>& T, const Cylinder<NT>& C) {
  return {{Vec3<NT>(T.v[0] - C.p0), Vec3<NT>(T.v[1] - C.p0), Vec3<NT>(T.v[2] - C.p0)},
          C.axis(),
          C.radius,
          nt::constant<NT>(1)};
}

template <class NT>
Answer decide_triangle_cylinder(const Triangle<NT>& T, const Cylinder<NT>& C) {
  return decide_triangle_cylinder(slab_input(T, C), ExactSigns{});
}

}  // namespace certcyl::detail
