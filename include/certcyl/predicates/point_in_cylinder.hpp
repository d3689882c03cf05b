// certcyl/predicates/point_in_cylinder.hpp -- where a point lies relative to a closed cylinder.
//
// Circular cylinder (P = p0, A = p1 - p0), design note section 3:
//   axial   s = (X-P).A           inside the slab iff 0 <= s <= A.A        (degree 2)
//   radial  q = |(X-P) x A|^2     inside the tube iff q <= r^2 A.A         (degree 4)
// Elliptic cylinder (base C, M = [a b c], det = det M, u = adj(M) (X - C) = det * M^-1 (X - C)):
//   radial  u1^2 + u2^2 <= det^2                                            (degree 6)
//   axial   0 <= det * u3 <= det^2                                           (degree 6)
// Strict inequalities give the interior. Every step is a sign of a polynomial in the input,
// so the classification is exact for exact types, certified (or throwing) for intervals, and
// merely approximate for floating types.
#pragma once

#include <ostream>

#include "certcyl/number_traits.hpp"
#include "certcyl/primitives.hpp"

namespace certcyl {

enum class Side { inside, boundary, outside };

inline constexpr const char* to_string(Side s) {
  return s == Side::inside ? "inside" : (s == Side::boundary ? "boundary" : "outside");
}

namespace detail {
// Combines the signs of the two constraint slacks (positive: strictly satisfied).
inline Side combine_slacks(CGAL::Sign a, CGAL::Sign b, CGAL::Sign c) {
  if (a == CGAL::NEGATIVE || b == CGAL::NEGATIVE || c == CGAL::NEGATIVE) return Side::outside;
  if (a == CGAL::ZERO || b == CGAL::ZERO || c == CGAL::ZERO) return Side::boundary;
  return Side::inside;
}
}  // namespace detail

template <class NT>
Side classify_point(const Point3<NT>& x, const Cylinder<NT>& cyl) {
  const Vec3<NT> A = cyl.axis();
  const Vec3<NT> w = x - cyl.p0;
  const NT AA = squared_length(A);
  const NT s = dot(w, A);
  const NT q = squared_length(cross(w, A));
  return detail::combine_slacks(nt::sign(s), nt::sign(NT(AA - s)), nt::sign(NT(cyl.radius * cyl.radius * AA - q)));
}

template <class NT>
Side classify_point(const Point3<NT>& x, const EllipticCylinder<NT>& e) {
  // adj(M) rows are the cross products of the columns: adj(M) v = (b x c . v, c x a . v, a x b . v).
  const Vec3<NT> w = x - e.base;
  const NT det = determinant(e.a, e.b, e.c);
  const NT u1 = dot(cross(e.b, e.c), w);
  const NT u2 = dot(cross(e.c, e.a), w);
  const NT u3 = dot(cross(e.a, e.b), w);
  const NT det2 = det * det;
  const NT z = det * u3;  // det^2 * (axial coordinate)
  return detail::combine_slacks(nt::sign(z), nt::sign(NT(det2 - z)), nt::sign(NT(det2 - (u1 * u1 + u2 * u2))));
}

inline std::ostream& operator<<(std::ostream& os, Side s) { return os << to_string(s); }

}  // namespace certcyl
