// certcyl/seeds/shene_line_cylinder.hpp -- Shene's geometric line/cylinder intersection
// (Graphics Gems IV, ed. Heckbert, 1994, pp. 353-355: "Computing the intersection of a line and
// a cylinder"), as written and corrected, generic over the number type and completed for the
// finite solid cylinder.
//
// The text, for a line l(A, u) and the infinite cylinder C(B, v, r) with unit u, v:
//   - parallel axes: the line misses the surface unless its distance to B is r (then it lies
//     on it);
//   - otherwise, with the common perpendicular OP (O on the axis, P on l), |d| = |OP| and
//     w = u (x) v (normalised), d = (B - A).w and the plane through l and OP cuts the cylinder
//     in an ellipse with semi-axes r / sin(theta) and r, so l meets it at
//         P +- sqrt((r^2 - d^2) / (1 - (u.v)^2)) u.
//     The text says "If r < |d|, ell intersects C at two points [...]; if r = |d|, tangent
//     at P; otherwise, ell does not intersect C". The first condition is a slip: it must read
//     r > |d| (design note, section 5). Printed as it is, the three cases are swapped: a line
//     crossing the wall (r > |d|) falls under "otherwise" and is reported missing, and a line
//     missing it (r < |d|) is reported to meet C at two points whose parameter offset x has
//     x^2 = (r^2 - d^2) / (1 - (u.v)^2) < 0, so they are not real (the text's formula would
//     take the square root of a negative number: NaN in IEEE arithmetic, an error in exact
//     types). r = |d| is tangency in both readings, an exact equality that floating point
//     almost never meets.
//     `SheneVariant::corrected` (the default) reads r > |d|. `SheneVariant::as_written`
//     follows the printed text: r < |d| answers overlapping (the text's "two points") with no
//     endpoints, since there are no real points to locate, to clip to a ray or a segment, or to
//     compare with the caps; r = |d| is the same tangency as corrected; r > |d| answers
//     separated. Both variants test the same computed quantity, the sign of r^2 - d^2, so they
//     differ by the slip alone.
//   - P from equation (1), A + s u + d w = B + s' v, crossed with v and dotted with u x v:
//     s = ((B - A) x v).(u x v) / |u x v|^2 (the text's remark is cut off before this step).
// Completion for the solid, finite cylinder (as the Gullotti note describes): a wall hit whose
// axial coordinate h = (X - B).v lies in [0, |axis|] is an endpoint on the wall; below 0 (above
// |axis|) the endpoint is the crossing of the cap0 (cap1) plane, valid when it lies in the cap
// disk, |X - B|^2 <= r^2 (|X - B - axis|^2 <= r^2); otherwise the line misses the solid. With
// parallel axes the solid is met when the distance is <= r, between the two cap crossings.
//
// Parallel test: the axes are parallel when |u x v|^2 is zero in NT; in an exact type also when
// 1 - (u.v)^2 is. Both are sin^2 theta, and the text divides by the second: in an exact type they
// are the same number, but CORE::Expr (CGAL 5.5.1) finds 1 - (u.v)^2 zero for some positive
// values (u = d/|d| with d = (2^-300, 0, -0.890625), v = e_z) and aborts the process on the
// division. In floating point the test is |u x v|^2 alone, as the method is usually written
// (1 - (u.v)^2 rounding to 0 then makes the wall hits infinite and the caps decide).
//
// Normalisation (u = d/|d|, v = axis/|axis|) and the ellipse formula need sqrt, so NT is double,
// long double, Interval_nt, Gmpfr or CORE::Expr. The three-valued answer is the one the method
// implies: two distinct endpoints -> overlapping, one -> touching, none -> separated (it
// cannot see a chord lying in a cap plane, which it reports as overlapping, unlike the exact
// answer touching). Comparisons go through nt::, so Interval_nt throws when one is undecided.
#pragma once

#include <utility>

#include "certcyl/line_result.hpp"
#include "certcyl/number_traits.hpp"
#include "certcyl/primitives.hpp"

namespace certcyl {

enum class SheneVariant { as_written, corrected };

template <class NT>
LineInterval<NT> shene_line_cylinder(const Line<NT>& line, const Cylinder<NT>& cyl, SheneVariant variant = SheneVariant::corrected) {
  const NT one = nt::constant<NT>(1);
  const Point3<NT>& A = line.origin;
  const Point3<NT>& B = cyl.p0;
  const NT r = cyl.radius;
  // Unit directions, as the text assumes; t counts in units of the given direction.
  const NT lu = nt::sqrt(squared_length(line.direction));
  const Vec3<NT> u = line.direction / lu;
  const NT height = nt::sqrt(squared_length(cyl.axis()));
  const Vec3<NT> v = cyl.axis() / height;
  const Vec3<NT> BA = B - A;
  const NT dv = dot(line.direction, v);  // d(axial)/dt
  const NT h0 = -dot(BA, v);             // axial coordinate of A

  LineInterval<NT> result;
  auto axial = [&](const NT& t) { return NT(h0 + t * dv); };
  auto radial2_at_cap = [&](const NT& t, const Point3<NT>& centre) { return squared_length(line.at(t) - centre); };

  const Vec3<NT> uxv = cross(u, v);
  const NT s2 = squared_length(uxv);  // sin^2 theta, as |u x v|^2
  const NT uv = dot(u, v);
  const NT sin2 = one - uv * uv;      // sin^2 theta, as the text's formula writes it
  if (nt::sign(s2) == CGAL::ZERO || (NumberTraits<NT>::is_exact && nt::sign(sin2) == CGAL::ZERO)) {
    // Parallel axes: distance from B to the line.
    const NT dist2 = squared_length(cross(BA, u));
    const CGAL::Comparison_result c = nt::compare(dist2, NT(r * r));
    if (c == CGAL::LARGER) return result;
    // Solid completion: between the cap crossings.
    NT t0 = -h0 / dv, t1 = (height - h0) / dv;
    LineFeature f0 = c == CGAL::EQUAL ? LineFeature::rim0 : LineFeature::cap0;
    LineFeature f1 = c == CGAL::EQUAL ? LineFeature::rim1 : LineFeature::cap1;
    if (nt::sign(dv) == CGAL::NEGATIVE) std::swap(t0, t1), std::swap(f0, f1);
    result.answer = c == CGAL::EQUAL ? Answer::touching : Answer::overlapping;
    result.in = LineEndpoint<NT>{t0, f0, f0};
    result.out = LineEndpoint<NT>{t1, f1, f1};
    return result;
  }

  // Common perpendicular: w = u (x) v, d = (B - A).w, P = A + s u.
  const Vec3<NT> w = uxv / nt::sqrt(s2);
  const NT d = dot(BA, w);
  const NT s = dot(cross(BA, v), uxv) / s2;
  const NT r2_d2 = r * r - d * d;
  const CGAL::Sign wall = nt::sign(r2_d2);
  if (variant == SheneVariant::as_written) {
    // The text as printed: "r < |d|: two points" (not real ones: x^2 < 0), "otherwise" (here
    // r > |d|) no intersection; r = |d| falls through to the tangency below.
    if (wall == CGAL::NEGATIVE) {
      result.answer = Answer::overlapping;
      return result;
    }
    if (wall == CGAL::POSITIVE) return result;
  }
  // The text's "r < |d|" corrected to r > |d| (two points), r = |d| tangent.
  if (wall == CGAL::NEGATIVE) return result;
  const NT x = nt::sqrt(NT(r2_d2 / sin2));
  const NT t_wall[2] = {NT((s - x) / lu), NT((s + x) / lu)};

  // Completion: each wall hit is kept inside the slab, replaced by a cap hit in the disk below
  // or above it, or the line misses.
  LineEndpoint<NT> ends[2];
  for (int k = 0; k < 2; ++k) {
    const NT h = axial(t_wall[k]);
    const CGAL::Sign below = nt::sign(h), above = nt::sign(NT(h - height));
    if (below != CGAL::NEGATIVE && above != CGAL::POSITIVE) {
      const LineFeature f = below == CGAL::ZERO ? LineFeature::rim0 : (above == CGAL::ZERO ? LineFeature::rim1 : LineFeature::wall);
      ends[k] = {t_wall[k], f, f};
      continue;
    }
    if (nt::sign(dv) == CGAL::ZERO) return result;  // parallel to the caps: no cap crossing
    const bool base = below == CGAL::NEGATIVE;
    const NT tc = base ? NT(-h0 / dv) : NT((height - h0) / dv);
    const Point3<NT> centre = base ? cyl.p0 : cyl.p1;
    const CGAL::Comparison_result in_disk = nt::compare(radial2_at_cap(tc, centre), NT(r * r));
    if (in_disk == CGAL::LARGER) return result;
    const LineFeature f = in_disk == CGAL::EQUAL ? (base ? LineFeature::rim0 : LineFeature::rim1) : (base ? LineFeature::cap0 : LineFeature::cap1);
    ends[k] = {tc, f, f};
  }
  if (nt::compare(ends[0].t, ends[1].t) == CGAL::LARGER) std::swap(ends[0], ends[1]);
  result.answer = nt::compare(ends[0].t, ends[1].t) == CGAL::EQUAL ? Answer::touching : Answer::overlapping;
  result.in = ends[0];
  result.out = ends[1];
  return result;
}

// A ray or a segment: the line's interval clipped to the range. The as-written variant's
// "two points" that are not real have nothing to clip: its line answer is returned as is.
template <class NT>
LineInterval<NT> shene_line_cylinder(const Ray<NT>& ray, const Cylinder<NT>& cyl, SheneVariant variant = SheneVariant::corrected) {
  LineInterval<NT> r = shene_line_cylinder(Line<NT>{ray.origin, ray.direction}, cyl, variant);
  if (r.answer != Answer::separated && !r.in) return r;
  return clip_to_range(std::move(r), LineRange::ray);
}

template <class NT>
LineInterval<NT> shene_line_cylinder(const Segment<NT>& seg, const Cylinder<NT>& cyl, SheneVariant variant = SheneVariant::corrected) {
  LineInterval<NT> r = shene_line_cylinder(Line<NT>{seg.p0, seg.direction()}, cyl, variant);
  if (r.answer != Answer::separated && !r.in) return r;
  return clip_to_range(std::move(r), LineRange::segment);
}

}  // namespace certcyl
