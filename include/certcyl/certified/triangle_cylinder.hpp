// certcyl/certified/triangle_cylinder.hpp -- certified test-intersection of a triangle and a
// closed solid cylinder, with no square root and no orthonormal frame.
//
// Semantics (design note, sections 1 and 3): the triangle is the closed convex hull of its
// three vertices (a degenerate triangle is a segment or a point); the cylinder is the closed
// solid {X : 0 <= s(X) <= A.A, q(X) <= R}, with P = p0, A = p1 - p0, R = r^2 A.A,
// s(X) = (X-P).A and q(X) = |(X-P) x A|^2. The answer is
//   overlapping  the triangle meets the open interior of the cylinder;
//   touching     it meets the cylinder but not its open interior;
//   separated    no common point.
// This is the Eberly seed's query ("Intersection of a Triangle and a Cylinder", section 2)
// reformulated without the U, V frame: the triangle is clipped to the slab 0 <= s <= A.A
// with rational clip points, and the minimum of q over the clipped polygon is compared with R
// by sign tests (detail/triangle_slab.hpp has the outline and the degrees).
//
// Two entry points:
//   classify_triangle_cylinder(T, C, counter)   the answer only; filtered: Interval_nt first,
//       Gmpq only where an interval sign is undecided (counted in `counter`).
//   certified_triangle_cylinder(T, C)           the answer (filtered, as above) and its
//       certificate, built in exact rational arithmetic and checked exactly before it is
//       returned (check_triangle_cylinder_certificate):
//     overlapping  a rational point of the triangle strictly inside the cylinder;
//     touching     a rational point of the triangle on the cylinder's boundary, the pair of
//                  features that meet there, and why no point is interior: the triangle lies
//                  on the outer side of a cap plane, or a supporting plane parallel to the axis
//                  at distance exactly r (normal n = X* - foot of X* on the axis, |n| = r)
//                  leaves the clipped triangle on its outer side;
//     separated    beyond a cap plane (all s_i < 0 or all s_i > A.A), or a plane parallel to
//                  the axis at distance |n| > r with the clipped triangle on its outer side.
//   X* is the point of T ∩ slab nearest the axis line (rational: a vertex, a clip point, the
//   foot of a perpendicular on an edge, or the point where the axis pierces the triangle).
//
// Degenerate cases handled: degenerate triangles (segment, point), triangles in a cap plane,
// edges parallel to the axis, triangles whose plane contains the axis, contact on a rim.
// Preconditions: valid cylinder (p0 != p1, r > 0); any triangle.
#pragma once

#include <CGAL/Gmpq.h>

#include <array>
#include <optional>
#include <stdexcept>
#include <string>

#include "certcyl/answer.hpp"
#include "certcyl/certified/detail/triangle_slab.hpp"
#include "certcyl/filtered.hpp"
#include "certcyl/number_traits.hpp"
#include "certcyl/predicates/point_in_cylinder.hpp"
#include "certcyl/primitives.hpp"

namespace certcyl {

struct TriangleCylinderResult {
  // The smallest feature of the triangle containing the witness: vertex {i}, edge {i, j}, face.
  enum class TriangleFeature { vertex, edge, face };
  // The boundary feature of the cylinder at the witness: cap = the open disk in a cap plane,
  // rim = its boundary circle, wall = the lateral surface strictly between the cap planes.
  enum class CylinderFeature { wall, cap0, cap1, rim0, rim1 };
  enum class Separation { none, beyond_cap0, beyond_cap1, outside_tube };

  Answer answer = Answer::undecided;

  // overlapping: a point of T strictly inside; touching: a point of T on the boundary.
  std::optional<Point3<Rational>> witness;
  // touching: the features meeting at the witness.
  TriangleFeature triangle_feature = TriangleFeature::face;
  std::array<int, 2> triangle_indices{-1, -1};
  CylinderFeature cylinder_feature = CylinderFeature::wall;

  // separated: why.
  Separation separation = Separation::none;

  // Whenever T meets the closed slab: X*, the point of T ∩ slab nearest the axis line, its
  // squared distance to the axis, and n = X* - (foot of X* on the axis), n.A = 0. For
  // outside_tube and for touching through the wall or a rim, the plane n.(Y - X*) = 0 has
  // T ∩ slab on its side n.(Y - X*) >= 0 and the open tube on the other.
  std::optional<Point3<Rational>> closest;
  Rational squared_distance;
  Vec3<Rational> normal{0, 0, 0};

  // The filtered decision: 1 call, and whether it needed exact arithmetic.
  FilterCounter counter;
};

inline const char* to_string(TriangleCylinderResult::TriangleFeature f) {
  using F = TriangleCylinderResult::TriangleFeature;
  return f == F::vertex ? "vertex" : (f == F::edge ? "edge" : "face");
}
inline const char* to_string(TriangleCylinderResult::CylinderFeature f) {
  using F = TriangleCylinderResult::CylinderFeature;
  switch (f) {
    case F::wall: return "wall";
    case F::cap0: return "cap0";
    case F::cap1: return "cap1";
    case F::rim0: return "rim0";
    case F::rim1: return "rim1";
  }
  return "?";
}
inline const char* to_string(TriangleCylinderResult::Separation s) {
  using S = TriangleCylinderResult::Separation;
  switch (s) {
    case S::none: return "none";
    case S::beyond_cap0: return "beyond_cap0";
    case S::beyond_cap1: return "beyond_cap1";
    case S::outside_tube: return "outside_tube";
  }
  return "?";
}

namespace detail {

// An exact input value in a certified number type: Interval_nt encloses, Gmpq is exact.
template <class NT, class In>
NT certified_image(const In& x) {
  if constexpr (std::is_same_v<NT, In>) {
    return x;
  } else if constexpr (std::is_same_v<In, double>) {
    return NT(x);  // binary64 is exact in both Interval_nt and Gmpq
  } else {
    static_assert(std::is_same_v<NT, Interval>, "certified_image: Rational input goes to Interval or Gmpq");
    return NT(nt::to_interval(x));
  }
}

// The filtered decision as a generic callable for filtered_call.
template <class In>
struct TriangleCylinderDecision {
  const Triangle<In>& T;
  const Cylinder<In>& C;

  template <class NT>
  Answer operator()() const {
    const auto f = [](const In& x) { return certified_image<NT>(x); };
    return decide_triangle_cylinder(T.map(f), C.map(f));
  }
};

inline bool on_segment(const Point3<Rational>& x, const Point3<Rational>& a, const Point3<Rational>& b) {
  const Vec3<Rational> d = b - a, w = x - a;
  if (!(cross(d, w) == Vec3<Rational>{0, 0, 0})) return false;
  const Rational t = dot(w, d);
  return t >= 0 && t <= dot(d, d);
}

// The smallest feature of T containing x, or nothing if x is not in T. Exact.
inline std::optional<std::pair<TriangleCylinderResult::TriangleFeature, std::array<int, 2>>> locate_on_triangle(
    const Point3<Rational>& x, const Triangle<Rational>& T) {
  using F = TriangleCylinderResult::TriangleFeature;
  for (int i = 0; i < 3; ++i)
    if (x == T.v[i]) return std::pair{F::vertex, std::array<int, 2>{i, -1}};
  for (auto [i, j] : {std::pair{0, 1}, std::pair{1, 2}, std::pair{0, 2}})
    if (T.v[i] != T.v[j] && on_segment(x, T.v[i], T.v[j])) return std::pair{F::edge, std::array<int, 2>{i, j}};
  const Vec3<Rational> N = cross(Vec3<Rational>(T.v[1] - T.v[0]), Vec3<Rational>(T.v[2] - T.v[0]));
  if (N == Vec3<Rational>{0, 0, 0} || dot(N, Vec3<Rational>(x - T.v[0])) != 0) return std::nullopt;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    if (dot(N, cross(Vec3<Rational>(T.v[j] - T.v[i]), Vec3<Rational>(x - T.v[i]))) < 0) return std::nullopt;
  }
  return std::pair{F::face, std::array<int, 2>{-1, -1}};
}

// X*: the point of S nearest the axis line (S not empty), by the same case split as the sign
// tests, evaluated exactly.
inline Point3<Rational> nearest_to_axis(const SlabPolygon<Rational>& S, const Triangle<Rational>& T,
                                        const Point3<Rational>& P, const Vec3<Rational>& A) {
  const auto q = [&](const Point3<Rational>& x) { return squared_length(cross(Vec3<Rational>(x - P), A)); };
  if (axis_pierces(S, P, A)) {
    // The axis line crosses the plane of S (its projection along A is not degenerate, so the
    // plane's normal N has N.A != 0) at P + t A, t = N.(v0 - P) / N.A.
    const Vec3<Rational> N = cross(Vec3<Rational>(T.v[1] - T.v[0]), Vec3<Rational>(T.v[2] - T.v[0]));
    const Rational NA = dot(N, A);
    if (NA == 0) throw std::logic_error("triangle_cylinder: pierced polygon parallel to the axis");
    return P + (dot(N, Vec3<Rational>(T.v[0] - P)) / NA) * A;
  }
  Point3<Rational> best = S.p[0].x;
  Rational best_q = q(best);
  const int edges = S.n == 1 ? 0 : (S.n == 2 ? 1 : S.n);
  for (int i = 0; i < edges; ++i) {
    const Point3<Rational>& a = S.p[i].x;
    const Point3<Rational>& b = S.p[(i + 1) % S.n].x;
    const EdgeQuadratic<Rational> e(a, b, P, A);
    Point3<Rational> x;
    Rational qx;
    switch (locate_edge_minimum(e)) {
      case EdgeMinimum::at_a: x = a, qx = e.uu; break;
      case EdgeMinimum::at_b: x = b, qx = e.uu + 2 * e.uv + e.vv; break;
      case EdgeMinimum::inside:
        x = a + (-e.uv / e.vv) * Vec3<Rational>(b - a);
        qx = e.uu - e.uv * e.uv / e.vv;
        break;
    }
    if (qx < best_q) best = x, best_q = qx;
  }
  return best;
}

// A point of T strictly inside the cylinder, from x in T ∩ slab with q(x) < R, when T crosses
// the open slab. c, the centroid of S's vertices, is in T and strictly between the cap planes;
// q is convex, so on y = x + lambda (c - x), q(y) <= q(x) + lambda (q(c) - q(x)), and
// lambda = (R - q(x)) / (2 (q(c) - q(x))) (or c itself if q(c) < R) gives q(y) < R, with y
// strictly inside the slab because lambda > 0. One exact construction, no search.
inline Point3<Rational> interior_witness(const Point3<Rational>& x, const SlabPolygon<Rational>& S,
                                         const Cylinder<Rational>& C) {
  if (classify_point(x, C) == Side::inside) return x;
  const Vec3<Rational> A = C.axis();
  const Rational R = C.radius * C.radius * squared_length(A);
  const auto q = [&](const Point3<Rational>& y) { return squared_length(cross(Vec3<Rational>(y - C.p0), A)); };
  Vec3<Rational> c{0, 0, 0};
  for (int i = 0; i < S.n; ++i) c += S.p[i].x;
  c = c / Rational(S.n);
  const Rational qx = q(x), qc = q(c);
  if (qc < R) return c;
  const Rational lambda = (R - qx) / (2 * (qc - qx));
  return x + lambda * Vec3<Rational>(c - x);
}

}  // namespace detail

// The answer only, filtered. Exact input.
inline Answer classify_triangle_cylinder(const Triangle<Rational>& T, const Cylinder<Rational>& C,
                                         FilterCounter& counter) {
  return filtered_call(detail::TriangleCylinderDecision<Rational>{T, C}, counter);
}

// The same for input given as binary64 values, each meaning exactly the value it holds.
inline Answer classify_triangle_cylinder(const Triangle<double>& T, const Cylinder<double>& C, FilterCounter& counter) {
  return filtered_call(detail::TriangleCylinderDecision<double>{T, C}, counter);
}

// Checks a certificate in exact arithmetic, independently of how it was found (see the header
// comment for what each answer's certificate proves). Returns an empty string when it holds,
// otherwise what failed.
inline std::string check_triangle_cylinder_certificate(const TriangleCylinderResult& res, const Triangle<Rational>& T,
                                                       const Cylinder<Rational>& C) {
  using Sep = TriangleCylinderResult::Separation;
  using CF = TriangleCylinderResult::CylinderFeature;
  const Point3<Rational>& P = C.p0;
  const Vec3<Rational> A = C.axis();
  const Rational AA = squared_length(A);
  const Rational r2 = C.radius * C.radius;
  std::array<Rational, 3> s;
  for (int i = 0; i < 3; ++i) s[i] = dot(Vec3<Rational>(T.v[i] - P), A);

  // The plane n.(Y - X*) = 0, parallel to the axis, with T ∩ slab on the side >= 0 (checked
  // on the clipped polygon's vertices) and the open tube of radius r on the other side.
  const auto plane_holds = [&](bool strict_gap) -> std::string {
    if (!res.closest) return "no nearest point";
    const Point3<Rational>& X = *res.closest;
    if (dot(res.normal, A) != 0) return "normal not perpendicular to the axis";
    const Vec3<Rational> w = X - P;
    if (!(Vec3<Rational>(w - (dot(w, A) / AA) * A) == res.normal)) return "normal is not X* minus its foot";
    const Rational nn = squared_length(res.normal);
    if (strict_gap ? !(nn > r2) : nn != r2) return "wrong distance from the axis";
    const detail::SlabPolygon<Rational> S = detail::clip_to_slab(T, s, AA);
    for (int i = 0; i < S.n; ++i)
      if (dot(res.normal, Vec3<Rational>(S.p[i].x - X)) < 0) return "clipped triangle on both sides of the plane";
    return "";
  };

  switch (res.answer) {
    case Answer::overlapping:
      if (!res.witness) return "no witness";
      if (!detail::locate_on_triangle(*res.witness, T)) return "witness not in the triangle";
      if (classify_point(*res.witness, C) != Side::inside) return "witness not interior to the cylinder";
      return "";
    case Answer::touching: {
      if (!res.witness) return "no witness";
      const auto where = detail::locate_on_triangle(*res.witness, T);
      if (!where) return "witness not in the triangle";
      if (where->first != res.triangle_feature || where->second != res.triangle_indices) return "wrong triangle feature";
      if (classify_point(*res.witness, C) != Side::boundary) return "witness not on the cylinder's boundary";
      const bool cap_only0 = s[0] <= 0 && s[1] <= 0 && s[2] <= 0;
      const bool cap_only1 = s[0] >= AA && s[1] >= AA && s[2] >= AA;
      if (cap_only0 || cap_only1) return "";  // no point of T is strictly between the cap planes
      if (res.cylinder_feature == CF::cap0 || res.cylinder_feature == CF::cap1)
        return "cap contact for a triangle crossing the slab";
      return plane_holds(false);
    }
    case Answer::separated:
      switch (res.separation) {
        case Sep::beyond_cap0: return s[0] < 0 && s[1] < 0 && s[2] < 0 ? "" : "not beyond cap plane 0";
        case Sep::beyond_cap1: return s[0] > AA && s[1] > AA && s[2] > AA ? "" : "not beyond cap plane 1";
        case Sep::outside_tube: return plane_holds(true);
        case Sep::none: return "no separation reason";
      }
      return "bad separation reason";
    case Answer::undecided: return "undecided";
  }
  return "bad answer";
}

// The answer with its exact, checked certificate. Throws std::logic_error if the filtered
// answer and the exact construction disagree or the certificate fails its check (either would
// be a defect of this code, never a property of the input).
inline TriangleCylinderResult certified_triangle_cylinder(const Triangle<Rational>& T, const Cylinder<Rational>& C) {
  using Res = TriangleCylinderResult;
  Res res;
  res.answer = classify_triangle_cylinder(T, C, res.counter);

  const Point3<Rational>& P = C.p0;
  const Vec3<Rational> A = C.axis();
  const Rational AA = squared_length(A);
  const Rational R = C.radius * C.radius * AA;
  const std::array<Rational, 3> s{dot(Vec3<Rational>(T.v[0] - P), A), dot(Vec3<Rational>(T.v[1] - P), A),
                                  dot(Vec3<Rational>(T.v[2] - P), A)};
  const detail::SlabContact where = detail::locate_in_slab(s, AA);

  Answer exact = Answer::separated;
  if (where == detail::SlabContact::beyond_cap0 || where == detail::SlabContact::beyond_cap1) {
    res.separation = where == detail::SlabContact::beyond_cap0 ? Res::Separation::beyond_cap0 : Res::Separation::beyond_cap1;
  } else {
    const detail::SlabPolygon<Rational> S = detail::clip_to_slab(T, s, AA);
    const Point3<Rational> X = detail::nearest_to_axis(S, T, P, A);
    const Vec3<Rational> w = X - P;
    const Rational sx = dot(w, A);
    const Rational qx = squared_length(cross(w, A));
    res.closest = X;
    res.squared_distance = qx / AA;
    res.normal = w - (sx / AA) * A;
    const bool crosses = where == detail::SlabContact::crosses_open_slab;
    if (qx > R) {
      res.separation = Res::Separation::outside_tube;
    } else if (crosses && qx < R) {
      exact = Answer::overlapping;
      res.witness = detail::interior_witness(X, S, C);
    } else {
      exact = Answer::touching;
      res.witness = X;
      const auto feature = detail::locate_on_triangle(X, T);
      if (!feature) throw std::logic_error("triangle_cylinder: nearest point not in the triangle");
      res.triangle_feature = feature->first;
      res.triangle_indices = feature->second;
      const bool on_wall = qx == R;
      if (sx == 0) res.cylinder_feature = on_wall ? Res::CylinderFeature::rim0 : Res::CylinderFeature::cap0;
      else if (sx == AA) res.cylinder_feature = on_wall ? Res::CylinderFeature::rim1 : Res::CylinderFeature::cap1;
      else res.cylinder_feature = Res::CylinderFeature::wall;
    }
  }
  if (exact != res.answer)
    throw std::logic_error("triangle_cylinder: filtered answer " + std::string(to_string(res.answer)) +
                           " but exact construction " + std::string(to_string(exact)));
  if (const std::string failure = check_triangle_cylinder_certificate(res, T, C); !failure.empty())
    throw std::logic_error("triangle_cylinder: certificate check failed: " + failure);
  return res;
}

}  // namespace certcyl
