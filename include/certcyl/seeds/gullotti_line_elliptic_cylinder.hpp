// certcyl/seeds/gullotti_line_elliptic_cylinder.hpp -- Gullotti's line/elliptic-cylinder
// intersection ("Line and elliptic cylinder intersection"), generic over the number type.
//
// The note: map the line by the inverse of M (the cylinder becomes x^2 + y^2 <= 1,
// 0 <= z <= 1), with w = M^-1 (L0 - C), v' = M^-1 v, h = (0, 0, 1):
//   a = v'.v' - (v'.h)^2, b = 2 (v'.w - (v'.h)(w.h)), c = w.w - (w.h)^2 - 1,
//   b^2 - 4ac > 0: t = (-b -+ sqrt(b^2 - 4ac)) / 2a; = 0: tangent at -b/2a, or, when
//   |v^.h^| = 1, "the line lies on the cylinder surface"; < 0: no intersection.
// then each hit is kept if its axial coordinate is within the height, else the base or top
// cap is tested.
//
// Where this implementation departs from the text (design note, section 5), each a flaw of
// the seed:
//   - M = T R S with R built from normalised axes assumes orthogonal a, b, c; M = [a b c] is
//     used directly (equal to T R S when the axes are orthogonal), M^-1 = adj(M) / det(M).
//   - The cap test "0 <= (L_int - C).h <= |h|" mixes the world point with the unit-space h;
//     the axial coordinate y3 = w.h + t v'.h is tested against [0, 1] in the unit space.
//   - The cap test itself is left open by the text; here: the crossing of the cap plane
//     y3 = 0 (y3 = 1) is an endpoint when x^2 + y^2 <= 1 there, else the line misses.
//   - |v^.h^| = 1 (v' parallel to the axis) makes a = b = 0, so b^2 - 4ac = 0 for EVERY line
//     parallel to the axis, inside, on or outside the wall: "lies on the surface" is only
//     right when c = 0. `GullottiVariant::as_written` keeps the text (the line is reported on
//     the wall, touching, between the caps); `corrected` (the default) decides by the sign of c.
//     |v^.h^| = 1 is tested without normalising as (v'.h)^2 = v'.v'.
// For the circular cylinder the same steps run on the implicit quadratic of design note
// section 3 (w = O - P, u = w x A, v = d x A): a = v.v, b = 2 u.v, c = u.u - r^2 A.A, the caps
// at 0 <= w.A + t d.A <= A.A, the disk test |(X - P) x A|^2 <= r^2 A.A; the textbook
// discriminant b^2 - 4ac (not the cancellation-free form) is what this method uses.
//
// NT needs sqrt and division: double, long double, Interval_nt, Gmpfr, CORE::Expr. The answer
// is the method's: two distinct endpoints overlapping, one (or the on-surface case) touching.
#pragma once

#include <utility>

#include "certcyl/line_result.hpp"
#include "certcyl/number_traits.hpp"
#include "certcyl/primitives.hpp"

namespace certcyl {

enum class GullottiVariant { as_written, corrected };

namespace detail {

// The unit-space (or implicit) data the method works on: the tube a t^2 + b t + c <= 0 and
// the axial coordinate s0 + t s1 in [0, H].
template <class NT>
struct GullottiQuadratic {
  NT a, b, c, s0, s1, H;
  bool axis_parallel;  // |v^.h^| = 1, tested exactly as written in squared form
};

template <class NT>
LineInterval<NT> gullotti_solve(const GullottiQuadratic<NT>& g, GullottiVariant variant) {
  const NT two = nt::constant<NT>(2), four = nt::constant<NT>(4);
  LineInterval<NT> result;
  auto radial = [&](const NT& t) { return NT((g.a * t + g.b) * t + g.c); };  // x^2 + y^2 - 1, scaled
  auto caps_between = [&](LineFeature f0, LineFeature f1) {
    NT t0 = -g.s0 / g.s1, t1 = (g.H - g.s0) / g.s1;
    if (nt::sign(g.s1) == CGAL::NEGATIVE) std::swap(t0, t1), std::swap(f0, f1);
    result.in = LineEndpoint<NT>{t0, f0, f0};
    result.out = LineEndpoint<NT>{t1, f1, f1};
  };

  const NT disc = g.b * g.b - four * g.a * g.c;
  const CGAL::Sign sd = nt::sign(disc);
  if (sd == CGAL::NEGATIVE) return result;
  NT t_hit[2];
  if (sd == CGAL::ZERO && g.axis_parallel) {
    // "The line lies on the cylinder surface": as written for every line parallel to the axis.
    const CGAL::Sign sc = nt::sign(g.c);
    if (variant == GullottiVariant::corrected && sc == CGAL::POSITIVE) return result;
    const bool on_wall = variant == GullottiVariant::as_written || sc == CGAL::ZERO;
    caps_between(on_wall ? LineFeature::rim0 : LineFeature::cap0, on_wall ? LineFeature::rim1 : LineFeature::cap1);
    result.answer = on_wall ? Answer::touching : Answer::overlapping;
    return result;
  }
  if (sd == CGAL::ZERO) {
    t_hit[0] = t_hit[1] = -g.b / (two * g.a);
  } else {
    const NT root = nt::sqrt(disc);
    t_hit[0] = (-g.b - root) / (two * g.a);
    t_hit[1] = (-g.b + root) / (two * g.a);
  }

  // Cap tests in the unit space.
  LineEndpoint<NT> ends[2];
  for (int k = 0; k < 2; ++k) {
    const NT y3 = g.s0 + t_hit[k] * g.s1;
    const CGAL::Sign below = nt::sign(y3), above = nt::sign(NT(y3 - g.H));
    if (below != CGAL::NEGATIVE && above != CGAL::POSITIVE) {
      const LineFeature f = below == CGAL::ZERO ? LineFeature::rim0 : (above == CGAL::ZERO ? LineFeature::rim1 : LineFeature::wall);
      ends[k] = {t_hit[k], f, f};
      continue;
    }
    if (nt::sign(g.s1) == CGAL::ZERO) return result;
    const bool base = below == CGAL::NEGATIVE;
    const NT tc = base ? NT(-g.s0 / g.s1) : NT((g.H - g.s0) / g.s1);
    const CGAL::Sign in_disk = nt::sign(radial(tc));
    if (in_disk == CGAL::POSITIVE) return result;
    const LineFeature f = in_disk == CGAL::ZERO ? (base ? LineFeature::rim0 : LineFeature::rim1) : (base ? LineFeature::cap0 : LineFeature::cap1);
    ends[k] = {tc, f, f};
  }
  if (nt::compare(ends[0].t, ends[1].t) == CGAL::LARGER) std::swap(ends[0], ends[1]);
  result.answer = nt::compare(ends[0].t, ends[1].t) == CGAL::EQUAL ? Answer::touching : Answer::overlapping;
  result.in = ends[0];
  result.out = ends[1];
  return result;
}

template <class NT>
GullottiQuadratic<NT> gullotti_quadratic(const Line<NT>& line, const EllipticCylinder<NT>& e) {
  // M^-1 = adj(M) / det(M); the rows of adj(M) are b x c, c x a, a x b.
  const NT det = determinant(e.a, e.b, e.c);
  const Vec3<NT> R1 = cross(e.b, e.c), R2 = cross(e.c, e.a), R3 = cross(e.a, e.b);
  auto inverse = [&](const Vec3<NT>& x) { return Vec3<NT>{dot(R1, x) / det, dot(R2, x) / det, dot(R3, x) / det}; };
  const Vec3<NT> w = inverse(line.origin - e.base), v = inverse(line.direction);
  const NT vh = v.z, wh = w.z, vv = squared_length(v);
  const NT two = nt::constant<NT>(2);
  return {NT(vv - vh * vh), NT(two * (dot(v, w) - vh * wh)), NT(squared_length(w) - wh * wh - nt::constant<NT>(1)), wh, vh,
          nt::constant<NT>(1), nt::sign(NT(vh * vh - vv)) == CGAL::ZERO};
}

template <class NT>
GullottiQuadratic<NT> gullotti_quadratic(const Line<NT>& line, const Cylinder<NT>& cyl) {
  const Vec3<NT> A = cyl.axis(), w = line.origin - cyl.p0;
  const Vec3<NT> u = cross(w, A), v = cross(line.direction, A);
  const NT AA = squared_length(A);
  const NT a = squared_length(v);
  return {a, NT(nt::constant<NT>(2) * dot(u, v)), NT(squared_length(u) - cyl.radius * cyl.radius * AA), dot(w, A),
          dot(line.direction, A), AA, nt::sign(a) == CGAL::ZERO};
}

}  // namespace detail

// Line against an elliptic (possibly oblique) cylinder.
template <class NT>
LineInterval<NT> gullotti_line_elliptic_cylinder(const Line<NT>& line, const EllipticCylinder<NT>& e,
                                                 GullottiVariant variant = GullottiVariant::corrected) {
  return detail::gullotti_solve(detail::gullotti_quadratic(line, e), variant);
}

// Line against a circular cylinder, through the implicit quadratic.
template <class NT>
LineInterval<NT> gullotti_line_cylinder(const Line<NT>& line, const Cylinder<NT>& cyl,
                                        GullottiVariant variant = GullottiVariant::corrected) {
  return detail::gullotti_solve(detail::gullotti_quadratic(line, cyl), variant);
}

// Rays and segments: the line's interval clipped to t >= 0 or [0, 1].
template <class NT, class Solid>
LineInterval<NT> gullotti_line_elliptic_cylinder(const Ray<NT>& ray, const Solid& s, GullottiVariant variant = GullottiVariant::corrected) {
  return clip_to_range(detail::gullotti_solve(detail::gullotti_quadratic(Line<NT>{ray.origin, ray.direction}, s), variant), LineRange::ray);
}
template <class NT, class Solid>
LineInterval<NT> gullotti_line_elliptic_cylinder(const Segment<NT>& seg, const Solid& s, GullottiVariant variant = GullottiVariant::corrected) {
  return clip_to_range(detail::gullotti_solve(detail::gullotti_quadratic(Line<NT>{seg.p0, seg.direction()}, s), variant), LineRange::segment);
}

}  // namespace certcyl
