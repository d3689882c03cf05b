// certcyl/robust/line_cylinder.hpp -- line/ray/segment against a solid circular or elliptic
// cylinder in double, with the numerically careful formulas (design note, section 3; pbrt-v4
// style): no certificate, but no avoidable cancellation.
//
//   - difference of products a*b - c*d by Kahan's FMA algorithm (error within 1.5 ulp) for the
//     cross products and the discriminant;
//   - the cancellation-free discriminant disc = A.A (r^2 |d x A|^2 - (A.(w x d))^2) (circular)
//     or D^2 a - (U1 V2 - U2 V1)^2 (elliptic, D = det M), the same forms as the certified
//     skeleton (certified/detail/line_shape.hpp), rather than b^2 - ac;
//   - the stable roots q = -(b + sign(b) sqrt(disc)), t = q / a and t = c / q.
// The interval is then the intersection of the tube, slab and range intervals, decided with
// ordinary double comparisons (ties are taken as ties: rims and clipped ends by equality).
// Same result type and semantics as the certified query (certcyl/line_result.hpp).
#pragma once

#include <cmath>
#include <utility>

#include "certcyl/line_result.hpp"
#include "certcyl/primitives.hpp"

namespace certcyl {
namespace detail {

// a*b - c*d with one rounding error compensated (Kahan).
inline double difference_of_products(double a, double b, double c, double d) {
  const double cd = c * d;
  const double err = std::fma(-c, d, cd);
  return std::fma(a, b, -cd) + err;
}

inline Vec3<double> robust_cross(const Vec3<double>& a, const Vec3<double>& b) {
  return {difference_of_products(a.y, b.z, a.z, b.y), difference_of_products(a.z, b.x, a.x, b.z),
          difference_of_products(a.x, b.y, a.y, b.x)};
}

struct RobustQuadric {
  double a, b, c, disc, sw, sd, H;
};

inline RobustQuadric robust_quadric(const Vec3<double>& O, const Vec3<double>& d, const Cylinder<double>& cyl) {
  const Vec3<double> A = cyl.axis(), w = O - cyl.p0;
  const Vec3<double> u = robust_cross(w, A), v = robust_cross(d, A);
  const double AA = dot(A, A), r2 = cyl.radius * cyl.radius;
  const double a = dot(v, v);
  const double e = dot(A, robust_cross(w, d));
  const double c = std::fma(-r2, AA, dot(u, u));
  return {a, dot(u, v), c, AA * difference_of_products(r2, a, e, e), dot(w, A), dot(d, A), AA};
}

inline RobustQuadric robust_quadric(const Vec3<double>& O, const Vec3<double>& d, const EllipticCylinder<double>& e) {
  const Vec3<double> w = O - e.base;
  const Vec3<double> R1 = robust_cross(e.b, e.c), R2 = robust_cross(e.c, e.a), R3 = robust_cross(e.a, e.b);
  const double D = dot(e.a, R1);
  const double U1 = dot(R1, w), U2 = dot(R2, w), U3 = dot(R3, w);
  const double V1 = dot(R1, d), V2 = dot(R2, d), V3 = dot(R3, d);
  const double a = std::fma(V1, V1, V2 * V2);
  const double cr = difference_of_products(U1, V2, U2, V1);
  const double c = std::fma(U1, U1, difference_of_products(U2, U2, D, D));
  return {a, std::fma(U1, V1, U2 * V2), c, difference_of_products(D * D, a, cr, cr), D * U3, D * V3, D * D};
}

inline LineInterval<double> robust_solve(const RobustQuadric& q, LineRange range) {
  LineInterval<double> result;
  // Tube.
  double tube_lo = -INFINITY, tube_hi = INFINITY;
  bool tube_open = true;
  if (q.a == 0) {
    if (q.c > 0) return result;
    tube_open = q.c < 0;
  } else {
    if (q.disc < 0) return result;
    const double root = std::sqrt(q.disc);
    const double qq = -(q.b + std::copysign(root, q.b));
    double t1 = qq == 0 ? -q.b / q.a : qq / q.a, t2 = qq == 0 ? t1 : q.c / qq;
    if (t1 > t2) std::swap(t1, t2);
    tube_lo = t1, tube_hi = t2;
    tube_open = q.disc > 0;
  }
  // Slab.
  double slab_lo = -INFINITY, slab_hi = INFINITY;
  LineFeature lo_cap = LineFeature::cap0, hi_cap = LineFeature::cap1;
  bool slab_open = true, plane0 = false, plane1 = false;
  if (q.sd == 0) {
    if (q.sw < 0 || q.sw > q.H) return result;
    plane0 = q.sw == 0, plane1 = q.sw == q.H;
    slab_open = !plane0 && !plane1;
  } else {
    slab_lo = -q.sw / q.sd, slab_hi = (q.H - q.sw) / q.sd;
    if (q.sd < 0) std::swap(slab_lo, slab_hi), std::swap(lo_cap, hi_cap);
  }
  const double range_lo = range == LineRange::line ? -INFINITY : 0.0, range_hi = range == LineRange::segment ? 1.0 : INFINITY;
  const double in = std::fmax(range_lo, std::fmax(slab_lo, tube_lo));
  const double out = std::fmin(range_hi, std::fmin(slab_hi, tube_hi));
  if (!(in <= out)) return result;
  auto describe = [&](double t) {
    const bool wall = (q.a == 0 && q.c == 0) || t == tube_lo || t == tube_hi;
    const bool cap0 = plane0 || (lo_cap == LineFeature::cap0 ? t == slab_lo : t == slab_hi);
    const bool cap1 = plane1 || (lo_cap == LineFeature::cap1 ? t == slab_lo : t == slab_hi);
    LineFeature surface = wall ? (cap0 ? LineFeature::rim0 : (cap1 ? LineFeature::rim1 : LineFeature::wall))
                               : (cap0 ? LineFeature::cap0 : (cap1 ? LineFeature::cap1 : LineFeature::none));
    LineFeature feature = (range != LineRange::line && t == 0) ? LineFeature::origin : ((range == LineRange::segment && t == 1) ? LineFeature::end : surface);
    return LineEndpoint<double>{t, feature, surface};
  };
  result.in = describe(in);
  result.out = describe(out);
  result.answer = (in < out && tube_open && slab_open) ? Answer::overlapping : Answer::touching;
  return result;
}

}  // namespace detail

inline LineInterval<double> robust_line_cylinder(const Line<double>& l, const Cylinder<double>& c) {
  return detail::robust_solve(detail::robust_quadric(l.origin, l.direction, c), LineRange::line);
}
inline LineInterval<double> robust_line_cylinder(const Ray<double>& r, const Cylinder<double>& c) {
  return detail::robust_solve(detail::robust_quadric(r.origin, r.direction, c), LineRange::ray);
}
inline LineInterval<double> robust_line_cylinder(const Segment<double>& s, const Cylinder<double>& c) {
  return detail::robust_solve(detail::robust_quadric(s.p0, s.direction(), c), LineRange::segment);
}
inline LineInterval<double> robust_line_cylinder(const Line<double>& l, const EllipticCylinder<double>& e) {
  return detail::robust_solve(detail::robust_quadric(l.origin, l.direction, e), LineRange::line);
}
inline LineInterval<double> robust_line_cylinder(const Ray<double>& r, const EllipticCylinder<double>& e) {
  return detail::robust_solve(detail::robust_quadric(r.origin, r.direction, e), LineRange::ray);
}
inline LineInterval<double> robust_line_cylinder(const Segment<double>& s, const EllipticCylinder<double>& e) {
  return detail::robust_solve(detail::robust_quadric(s.p0, s.direction(), e), LineRange::segment);
}

}  // namespace certcyl
