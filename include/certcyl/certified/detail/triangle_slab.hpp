// certcyl/certified/detail/triangle_slab.hpp -- the sign tests behind the certified
// triangle-cylinder predicate, generic over a certified number type (Interval_nt, Gmpq).
//
// Notation (design note, section 3): P = p0, A = p1 - p0, R = r^2 A.A, and for a point X
//   s(X) = (X-P).A             axial coordinate, times A.A             (degree 2)
//   q(X) = |(X-P) x A|^2       squared distance to the axis, times A.A (degree 4)
// The closed cylinder is {0 <= s <= A.A, q <= R}; its interior uses strict inequalities.
//
// Outline (each step a sign test; the clip points are rational functions of the input):
//   1. T entirely beyond a cap plane (all s_i < 0, or all s_i > A.A): separated.
//   2. S = T clipped to the closed slab 0 <= s <= A.A (Sutherland-Hodgman, at most 5 vertices,
//      every clip point tagged with its exact axial coordinate 0 or A.A).
//   3. m = min over S of q. Either the axis line pierces S (m = 0) or m is attained on an edge
//      of S: q is convex, and where its minimum over the plane of S is not unique (axis
//      parallel to that plane) the minimising line meets S only if it meets S's boundary.
//   4. If T meets the open slab, the closure of T ∩ open slab is S, so
//        m < R  overlapping,   m = R  touching,   m > R  separated.
//      Otherwise T touches the slab only in a cap plane, where no point is interior:
//        m <= R touching,      m > R  separated.
#pragma once

#include <CGAL/enum.h>

#include <array>
#include <utility>

#include "certcyl/answer.hpp"
#include "certcyl/number_traits.hpp"
#include "certcyl/primitives.hpp"

namespace certcyl::detail {

// A vertex of the clipped polygon and its axial coordinate s, exact for clip points (0 or A.A).
template <class NT>
struct SlabPoint {
  Point3<NT> x;
  NT s;
};

// A convex polygon (possibly degenerate: repeated or collinear vertices) in boundary order.
// Clipping a triangle by two parallel planes leaves at most 5 vertices.
template <class NT>
struct SlabPolygon {
  std::array<SlabPoint<NT>, 5> p;
  int n = 0;

  void push(const Point3<NT>& x, const NT& s) { p[n++] = {x, s}; }
};

// Keeps the part of `in` on the side `side(s) >= 0`, where side(s) is s (lower cap plane) or
// A.A - s (upper cap plane). A clip point is made only where the two ends lie strictly on
// opposite sides, so a vertex on the plane is kept once and never duplicated.
template <class NT, class Side>
SlabPolygon<NT> clip_by_plane(const SlabPolygon<NT>& in, Side side, const NT& plane_s) {
  SlabPolygon<NT> out;
  std::array<CGAL::Sign, 5> sg{};
  for (int i = 0; i < in.n; ++i) sg[i] = nt::sign(side(in.p[i].s));
  for (int i = 0; i < in.n; ++i) {
    const int j = (i + 1) % in.n;
    const SlabPoint<NT>& a = in.p[i];
    const SlabPoint<NT>& b = in.p[j];
    if (sg[i] != CGAL::NEGATIVE) out.push(a.x, a.s);
    if (sg[i] * sg[j] == CGAL::NEGATIVE) {
      // t = side(a) / (side(a) - side(b)) in (0, 1); side is affine in s.
      const NT sa = side(a.s);
      const NT t = sa / (sa - side(b.s));
      out.push(a.x + t * (b.x - a.x), plane_s);
    }
  }
  return out;
}

// T ∩ closed slab, vertices in T's boundary order.
template <class NT>
SlabPolygon<NT> clip_to_slab(const Triangle<NT>& T, const std::array<NT, 3>& s, const NT& AA) {
  SlabPolygon<NT> tri;
  for (int i = 0; i < 3; ++i) tri.push(T.v[i], s[i]);
  const NT zero = nt::constant<NT>(0);
  SlabPolygon<NT> lower = clip_by_plane(tri, [](const NT& x) { return x; }, zero);
  return clip_by_plane(lower, [&AA](const NT& x) { return NT(AA - x); }, AA);
}

// Does the axis line meet S? Its projection along A contains the projection of P,
// non-degenerately: the triple products det(a-P, b-P, A) over S's edges have one sign, not
// all zero (for a polygon whose projection is a segment, or a point, they are either of both
// signs or all zero, and the edges then decide). Degree 5 per edge.
template <class NT>
bool axis_pierces(const SlabPolygon<NT>& S, const Point3<NT>& P, const Vec3<NT>& A) {
  if (S.n < 3) return false;
  bool has_positive = false, has_negative = false;
  for (int i = 0; i < S.n; ++i) {
    const Point3<NT>& a = S.p[i].x;
    const Point3<NT>& b = S.p[(i + 1) % S.n].x;
    const CGAL::Sign sg = nt::sign(determinant(Vec3<NT>(a - P), Vec3<NT>(b - P), A));
    has_positive |= sg == CGAL::POSITIVE;
    has_negative |= sg == CGAL::NEGATIVE;
    if (has_positive && has_negative) return false;
  }
  return has_positive != has_negative;
}

// The quadratic q(a + t (b - a)) = uu + 2 uv t + vv t^2 of an edge, t in [0, 1].
template <class NT>
struct EdgeQuadratic {
  NT uu, uv, vv;

  EdgeQuadratic(const Point3<NT>& a, const Point3<NT>& b, const Point3<NT>& P, const Vec3<NT>& A) {
    const Vec3<NT> u = cross(Vec3<NT>(a - P), A);
    const Vec3<NT> v = cross(Vec3<NT>(b - a), A);
    uu = dot(u, u);
    uv = dot(u, v);
    vv = dot(v, v);
  }
};

// Where the minimum of q over an edge lies.
enum class EdgeMinimum { at_a, at_b, inside };

template <class NT>
EdgeMinimum locate_edge_minimum(const EdgeQuadratic<NT>& e) {
  // vv = 0: q is constant along the edge (edge parallel to the axis, or a repeated vertex).
  if (nt::sign(e.vv) == CGAL::ZERO || nt::sign(e.uv) != CGAL::NEGATIVE) return EdgeMinimum::at_a;
  if (nt::sign(NT(e.uv + e.vv)) != CGAL::POSITIVE) return EdgeMinimum::at_b;
  return EdgeMinimum::inside;
}

// sign(min over the edge of q  -  R). Degree 8 in the input for an interior minimum
// ((uu - R) vv - uv^2), times the powers of the clip denominators.
template <class NT>
CGAL::Sign edge_minimum_minus(const EdgeQuadratic<NT>& e, const NT& R) {
  switch (locate_edge_minimum(e)) {
    case EdgeMinimum::at_a: return nt::sign(NT(e.uu - R));
    case EdgeMinimum::at_b: return nt::sign(NT(e.uu + (e.uv + e.uv) + e.vv - R));
    case EdgeMinimum::inside: break;
  }
  // else: t* = -uv/vv in (0, 1), q* = uu - uv^2/vv, and vv > 0.
  return nt::sign(NT((e.uu - R) * e.vv - e.uv * e.uv));
}

// sign(min over S of q  -  R), S not empty.
template <class NT>
CGAL::Sign polygon_minimum_minus(const SlabPolygon<NT>& S, const Point3<NT>& P, const Vec3<NT>& A, const NT& R) {
  if (S.n == 1) return nt::sign(NT(squared_length(cross(Vec3<NT>(S.p[0].x - P), A)) - R));
  CGAL::Sign best = CGAL::POSITIVE;
  // A 2-gon is one segment: its second edge is the first reversed.
  const int edges = S.n == 2 ? 1 : S.n;
  for (int i = 0; i < edges; ++i) {
    const CGAL::Sign sg = edge_minimum_minus(EdgeQuadratic<NT>(S.p[i].x, S.p[(i + 1) % S.n].x, P, A), R);
    if (sg == CGAL::NEGATIVE) return sg;
    if (sg == CGAL::ZERO) best = CGAL::ZERO;
  }
  return best;
}

// Where T lies along the axis.
enum class SlabContact { beyond_cap0, beyond_cap1, cap0_plane_only, cap1_plane_only, crosses_open_slab };

template <class NT>
SlabContact locate_in_slab(const std::array<NT, 3>& s, const NT& AA) {
  int below = 0, above = 0, reaches_up = 0, reaches_down = 0;
  for (const NT& si : s) {
    const CGAL::Sign lo = nt::sign(si);
    const CGAL::Sign hi = nt::sign(NT(AA - si));
    below += lo == CGAL::NEGATIVE;
    above += hi == CGAL::NEGATIVE;
    reaches_up += lo == CGAL::POSITIVE;
    reaches_down += hi == CGAL::POSITIVE;
  }
  if (below == 3) return SlabContact::beyond_cap0;
  if (above == 3) return SlabContact::beyond_cap1;
  // s is affine on T, so T meets 0 < s < A.A iff max s > 0 and min s < A.A.
  if (reaches_up == 0) return SlabContact::cap0_plane_only;
  if (reaches_down == 0) return SlabContact::cap1_plane_only;
  return SlabContact::crosses_open_slab;
}

// The three-valued answer, by sign tests only (outline at the top of this file). For
// Interval_nt an undecided sign throws CGAL::Uncertain_conversion_exception.
template <class NT>
Answer decide_triangle_cylinder(const Triangle<NT>& T, const Cylinder<NT>& C) {
  const Point3<NT>& P = C.p0;
  const Vec3<NT> A = C.axis();
  const NT AA = squared_length(A);
  const NT R = C.radius * C.radius * AA;
  const std::array<NT, 3> s{dot(Vec3<NT>(T.v[0] - P), A), dot(Vec3<NT>(T.v[1] - P), A),
                            dot(Vec3<NT>(T.v[2] - P), A)};

  // Step 1: beyond a cap plane.
  const SlabContact where = locate_in_slab(s, AA);
  if (where == SlabContact::beyond_cap0 || where == SlabContact::beyond_cap1) return Answer::separated;

  // Shortcut: a vertex strictly inside the cylinder (a common case, and cheap).
  for (int i = 0; i < 3; ++i) {
    if (nt::sign(s[i]) == CGAL::POSITIVE && nt::sign(NT(AA - s[i])) == CGAL::POSITIVE &&
        nt::sign(NT(R - squared_length(cross(Vec3<NT>(T.v[i] - P), A)))) == CGAL::POSITIVE)
      return Answer::overlapping;
  }

  // Steps 2 and 3: clip, then the minimum of q against R.
  const SlabPolygon<NT> S = clip_to_slab(T, s, AA);
  const CGAL::Sign m = axis_pierces(S, P, A) ? CGAL::NEGATIVE : polygon_minimum_minus(S, P, A, R);

  // Step 4.
  if (where == SlabContact::crosses_open_slab)
    return m == CGAL::NEGATIVE ? Answer::overlapping : (m == CGAL::ZERO ? Answer::touching : Answer::separated);
  // else: T meets the slab only in a cap plane, where no point is interior.
  return m == CGAL::POSITIVE ? Answer::separated : Answer::touching;
}

}  // namespace certcyl::detail
