// certcyl/seeds/eberly_triangle_cylinder.hpp -- Eberly's triangle-cylinder test-intersection,
// as the seed writes it ("Intersection of a Triangle and a Cylinder", Geometric Tools, 2010,
// section 2), generic over any number type with a square root (double, long double,
// Interval_nt, Gmpfr, CORE::Expr). This is the algorithm the experiments judge, not a
// certified method: see certified/triangle_cylinder.hpp for that.
//
// Semantics: closed triangle, closed solid cylinder; returns the seed's Boolean "intersect"
// and the case of the seed's Figure 1 that the triangle fell into.
//
// Construction, step by step as in the seed:
//   1. Frame. From certcyl's Cylinder{p0, p1, r}: C = (p0 + p1)/2, h = |p1 - p0|,
//      D = (p1 - p0)/h (one sqrt). U, V complete D to a right-handed orthonormal frame with
//      Geometric Tools' ComputeOrthogonalComplement: if |D.x| > |D.y|,
//      U = (-D.z, 0, D.x)/sqrt(D.x^2 + D.z^2), else U = (0, D.z, -D.y)/sqrt(D.y^2 + D.z^2);
//      V = D x U (so U x V = D).
//   2. Q_i = (U.(P_i - C), V.(P_i - C), D.(P_i - C)), sorted so that z0 <= z1 <= z2.
//   3. The case table of Figure 1, with the seed's comparisons exactly as printed (note the
//      mixed strictness: 0a/0b use strict tests, 3a non-strict, and so on).
//   4. The clipped triangle projected on the xy-plane: a point, a segment or a convex polygon,
//      tested against the disk x^2 + y^2 <= r^2 as the seed says: a point by its squared
//      length, a segment by its squared distance to the origin, a polygon by "contains the
//      origin, or some edge within squared distance r^2".
//
// Choices the seed leaves open, made here and recorded:
//   - Figure 1 is not reproduced in the seed's text; the sub-labels inside a pseudocode branch
//     are read as "strict" versus "on the plane": 3b z1 < -h/2, 3c z1 = -h/2; 3d z1 > h/2,
//     3e z1 = h/2; 4a z1 > h/2, 4b z1 = h/2; 4c z1 < -h/2, 4d z1 = -h/2. Both members of a
//     pair are handled by the same code, as in the seed.
//   - "(0,0) is contained in the polygon" is the usual convex-polygon test: the 2-D cross
//     products of consecutive vertices all >= 0 or all <= 0. When the projected polygon is
//     degenerate (the triangle's plane contains the axis direction) and its supporting line
//     passes through the origin, every cross product is zero and the test says "contained"
//     even when the projected segment misses the origin (tests/test_triangle_seed.cpp shows
//     the case; it is a flaw of the seed's polygon branch, and exact arithmetic keeps it).
//   - The squared distance from the origin to a segment clamps the parameter to [0, 1]; a
//     zero-length segment is its endpoint.
// Interval_nt: every comparison that intervals cannot decide throws
// CGAL::Uncertain_conversion_exception, as for every seed algorithm.
#pragma once

#include <array>
#include <utility>

#include "certcyl/number_traits.hpp"
#include "certcyl/primitives.hpp"

namespace certcyl {

// The cases of the seed's Figure 1.
enum class EberlyTriangleCase { c0a, c0b, c1a, c1b, c2a, c2b, c3a, c3b, c3c, c3d, c3e, c4a, c4b, c4c, c4d, c4e, c4f, c5 };

inline const char* to_string(EberlyTriangleCase c) {
  constexpr const char* names[] = {"0a", "0b", "1a", "1b", "2a", "2b", "3a", "3b", "3c",
                                   "3d", "3e", "4a", "4b", "4c", "4d", "4e", "4f", "5"};
  return names[static_cast<int>(c)];
}

struct EberlyTriangleCylinderResult {
  bool intersect = false;
  EberlyTriangleCase label = EberlyTriangleCase::c0a;
};

namespace detail {

template <class NT>
struct Eberly2 {
  NT x, y;
};

// Q = (x, y, z) in the cylinder's frame.
template <class NT>
struct EberlyQ {
  NT x, y, z;
};

// The point of segment QaQb at height zc (za != zc, za != zb), projected on the xy-plane.
template <class NT>
Eberly2<NT> eberly_at_height(const EberlyQ<NT>& a, const EberlyQ<NT>& b, const NT& zc) {
  const NT t = (zc - a.z) / (b.z - a.z);
  return {a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)};
}

template <class NT>
Eberly2<NT> eberly_xy(const EberlyQ<NT>& q) {
  return {q.x, q.y};
}

// Squared distance from the origin to the segment [a, b].
template <class NT>
NT eberly_segment_sqr_distance(const Eberly2<NT>& a, const Eberly2<NT>& b) {
  const NT dx = b.x - a.x, dy = b.y - a.y;
  const NT dd = dx * dx + dy * dy;
  const NT ad = -(a.x * dx + a.y * dy);  // t = ad / dd minimises |a + t (b - a)|
  if (nt::sign(dd) != CGAL::POSITIVE || nt::sign(ad) != CGAL::POSITIVE) return a.x * a.x + a.y * a.y;
  if (nt::compare(ad, dd) != CGAL::SMALLER) return b.x * b.x + b.y * b.y;
  const NT t = ad / dd;
  const NT px = a.x + t * dx, py = a.y + t * dy;
  return px * px + py * py;
}

template <class NT>
bool eberly_polygon_meets_disk(const Eberly2<NT>* poly, int n, const NT& r2) {
  if (n == 1) return nt::compare(NT(poly[0].x * poly[0].x + poly[0].y * poly[0].y), r2) != CGAL::LARGER;
  if (n == 2) return nt::compare(eberly_segment_sqr_distance(poly[0], poly[1]), r2) != CGAL::LARGER;
  // Origin contained: consecutive cross products all of one sign (zero allowed).
  bool has_positive = false, has_negative = false;
  for (int i = 0; i < n; ++i) {
    const Eberly2<NT>& a = poly[i];
    const Eberly2<NT>& b = poly[(i + 1) % n];
    const CGAL::Sign sg = nt::sign(NT(a.x * b.y - a.y * b.x));
    has_positive |= sg == CGAL::POSITIVE;
    has_negative |= sg == CGAL::NEGATIVE;
  }
  if (!(has_positive && has_negative)) return true;
  // else: some edge within distance r.
  for (int i = 0; i < n; ++i)
    if (nt::compare(eberly_segment_sqr_distance(poly[i], poly[(i + 1) % n]), r2) != CGAL::LARGER) return true;
  return false;
}

}  // namespace detail

template <class NT>
EberlyTriangleCylinderResult eberly_triangle_cylinder(const Triangle<NT>& T, const Cylinder<NT>& cyl) {
  using Q = detail::EberlyQ<NT>;
  using P2 = detail::Eberly2<NT>;
  using Case = EberlyTriangleCase;
  const NT two = nt::constant<NT>(2);

  // Step 1: the frame.
  const Point3<NT> C = (cyl.p0 + cyl.p1) / two;
  const Vec3<NT> axis = cyl.p1 - cyl.p0;
  const NT h = nt::sqrt(squared_length(axis));
  const Vec3<NT> D = axis / h;
  Vec3<NT> U;
  const auto magnitude = [](const NT& x) { return nt::sign(x) == CGAL::NEGATIVE ? NT(-x) : x; };
  if (nt::compare(magnitude(D.x), magnitude(D.y)) == CGAL::LARGER) {
    const NT len = nt::sqrt(NT(D.x * D.x + D.z * D.z));
    U = Vec3<NT>{-D.z, nt::constant<NT>(0), D.x} / len;
  } else {
    const NT len = nt::sqrt(NT(D.y * D.y + D.z * D.z));
    U = Vec3<NT>{nt::constant<NT>(0), D.z, -D.y} / len;
  }
  const Vec3<NT> V = cross(D, U);

  // Step 2: the triangle in the frame, sorted by z.
  std::array<Q, 3> q;
  for (int i = 0; i < 3; ++i) {
    const Vec3<NT> w = T.v[i] - C;
    q[i] = Q{dot(U, w), dot(V, w), dot(D, w)};
  }
  const auto order = [&q](int a, int b) {
    if (nt::compare(q[b].z, q[a].z) == CGAL::SMALLER) std::swap(q[a], q[b]);
  };
  order(0, 1);
  order(1, 2);
  order(0, 1);
  const NT& z0 = q[0].z;
  const NT& z1 = q[1].z;
  const NT& z2 = q[2].z;
  const NT hh = h / two;
  const NT mhh = -hh;
  const auto lt = [](const NT& a, const NT& b) { return nt::compare(a, b) == CGAL::SMALLER; };
  const auto le = [](const NT& a, const NT& b) { return nt::compare(a, b) != CGAL::LARGER; };
  const auto eq = [](const NT& a, const NT& b) { return nt::compare(a, b) == CGAL::EQUAL; };

  // Step 3: the case table, and the clipped triangle projected on the xy-plane.
  std::array<P2, 5> poly;
  int n = 0;
  Case label = Case::c3a;
  const auto push = [&](const P2& p) { poly[n++] = p; };
  if (lt(z2, mhh)) return {false, Case::c0a};
  if (lt(hh, z0)) return {false, Case::c0b};
  if (le(mhh, z0) && le(z2, hh)) {
    label = Case::c3a;
    for (const Q& qi : q) push(detail::eberly_xy(qi));
  } else if (lt(z0, mhh)) {
    if (lt(hh, z2)) {
      if (le(hh, z1)) {
        // 4a/4b: P0 below, P1 and P2 at or above the top plane.
        label = eq(z1, hh) ? Case::c4b : Case::c4a;
        push(detail::eberly_at_height(q[0], q[1], mhh));
        push(detail::eberly_at_height(q[0], q[1], hh));
        push(detail::eberly_at_height(q[0], q[2], hh));
        push(detail::eberly_at_height(q[0], q[2], mhh));
      } else if (le(z1, mhh)) {
        // 4c/4d: P0 and P1 at or below the bottom plane, P2 above.
        label = eq(z1, mhh) ? Case::c4d : Case::c4c;
        push(detail::eberly_at_height(q[0], q[2], mhh));
        push(detail::eberly_at_height(q[0], q[2], hh));
        push(detail::eberly_at_height(q[1], q[2], hh));
        push(detail::eberly_at_height(q[1], q[2], mhh));
      } else {
        // 5: one vertex below, one inside, one above.
        label = Case::c5;
        push(detail::eberly_at_height(q[0], q[1], mhh));
        push(detail::eberly_xy(q[1]));
        push(detail::eberly_at_height(q[1], q[2], hh));
        push(detail::eberly_at_height(q[0], q[2], hh));
        push(detail::eberly_at_height(q[0], q[2], mhh));
      }
    } else if (lt(mhh, z2)) {
      if (le(z1, mhh)) {
        // 3b/3c: P0 below, P1 below or on the bottom plane, P2 inside.
        label = eq(z1, mhh) ? Case::c3c : Case::c3b;
        push(detail::eberly_at_height(q[0], q[2], mhh));
        push(detail::eberly_at_height(q[1], q[2], mhh));
        push(detail::eberly_xy(q[2]));
      } else {
        // 4e: P0 below, P1 and P2 inside.
        label = Case::c4e;
        push(detail::eberly_at_height(q[0], q[1], mhh));
        push(detail::eberly_xy(q[1]));
        push(detail::eberly_xy(q[2]));
        push(detail::eberly_at_height(q[0], q[2], mhh));
      }
    } else {
      // else: z2 = -h/2.
      if (lt(z1, mhh)) {
        label = Case::c1a;
        push(detail::eberly_xy(q[2]));
      } else {
        label = Case::c2a;
        push(detail::eberly_xy(q[1]));
        push(detail::eberly_xy(q[2]));
      }
    }
  } else if (lt(z0, hh)) {
    if (le(hh, z1)) {
      // 3d/3e: P0 inside, P1 and P2 at or above the top plane.
      label = eq(z1, hh) ? Case::c3e : Case::c3d;
      push(detail::eberly_xy(q[0]));
      push(detail::eberly_at_height(q[0], q[1], hh));
      push(detail::eberly_at_height(q[0], q[2], hh));
    } else {
      // 4f: P0 and P1 inside, P2 above.
      label = Case::c4f;
      push(detail::eberly_xy(q[0]));
      push(detail::eberly_xy(q[1]));
      push(detail::eberly_at_height(q[1], q[2], hh));
      push(detail::eberly_at_height(q[0], q[2], hh));
    }
  } else {
    // else: z0 = h/2.
    if (lt(hh, z1)) {
      label = Case::c1b;
      push(detail::eberly_xy(q[0]));
    } else {
      label = Case::c2b;
      push(detail::eberly_xy(q[0]));
      push(detail::eberly_xy(q[1]));
    }
  }

  // Step 4: point, segment or polygon against the disk.
  return {detail::eberly_polygon_meets_disk(poly.data(), n, NT(cyl.radius * cyl.radius)), label};
}

}  // namespace certcyl
