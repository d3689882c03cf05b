// study/gap.hpp -- the certified answer of a study instance and its certified signed
// gap, a number whose sign is the answer's (< 0 separated, = 0 touching, > 0 overlapping) and
// whose size measures how far the input is from a change of answer.
//
// Line, ray and segment (circular or elliptic cylinder) and triangle: the depth margin
//   gap = min( m_tube, m_cap0, m_cap1, 1 )
// over the query set X (the line's allowed parameter range, or the triangle), in the cylinder's
// own units: with s(X) the axial coordinate (circular: (X-P).A / A.A; elliptic: z of
// M^-1 (X - base)) and q(X) the squared radial coordinate (circular: |(X-P) x A|^2 / (r^2 A.A);
// elliptic: x^2 + y^2),
//   m_cap0 = max_X s(X),    m_cap1 = max_X (1 - s(X))      (each clamped to 1 when unbounded),
//   m_tube = 1 - min { q(X) : X in the query set, 0 <= s(X) <= 1 }
//            (left out when the query set misses the closed slab; then m_cap0 or m_cap1 < 0).
// The set meets the open solid iff all three are positive, and meets the closed solid iff all
// three are >= 0 (the three constraints are convex and the set is connected), so the sign of the
// gap is the answer's. When it is negative, its size is instead the largest depth
// d(X) = min(1 - q(X), s(X), 1 - s(X)) over a few rational sample points X of the set (the
// point nearest the axis, the slab crossings, the mid-height crossing): every d(X) is at most
// max_X d(X) < 0, so the sign stays exact and |gap| bounds the depth the set lacks. Every term
// is a rational function of the input evaluated at a rational
// point (the minimiser of a quadratic on an interval with rational ends, or the triangle's
// point nearest the axis, from the certified query's exact construction), computed in Gmpq and enclosed in doubles.
//
// Point (circular or elliptic cylinder): the depth of the one point,
//   gap = d(X) = min( 1 - q(X), s(X), 1 - s(X) ),
// the margin above for the set {X} (its clamp to 1 never binds: min(s, 1 - s) <= 1/2). It is
// > 0 iff X is in the open solid, = 0 iff on the boundary, < 0 iff outside; exact, in Gmpq.
//
// Cylinder against cylinder: log(phi*), the certified enclosure of certified_cylinder_cylinder
// (design note section 4; 1/phi* is the growth distance). Equal midpoints: +infinity.
//
// The study checks the gap's sign against the certified answer on every instance.
#pragma once

#include <algorithm>
#include <limits>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

#include "certcyl/certified/cylinder_cylinder.hpp"
#include "certcyl/certified/line_cylinder.hpp"
#include "certcyl/certified/triangle_cylinder.hpp"
#include "study/instance.hpp"

namespace certcyl::study {
namespace detail {

// min over t in [lo, hi] (either end may be open to infinity) of a t^2 + b t + c, a >= 0.
inline Rational min_quadratic(const Rational& a, const Rational& b, const Rational& c, const std::optional<Rational>& lo,
                              const std::optional<Rational>& hi) {
  Rational t = 0;
  if (a == 0) {
    // b == 0 for a squared length with a == 0: q is constant.
    t = lo ? *lo : (hi ? *hi : Rational(0));
  } else {
    t = -b / (2 * a);
    if (lo && t < *lo) t = *lo;
    if (hi && t > *hi) t = *hi;
  }
  return (a * t + b) * t + c;
}

// The depth margin of a line-like set {t in range} with q(t) = qa t^2 + qb t + qc (in units of
// the radius squared) and s(t) = s0 + s1 t (in units of the height).
inline Rational line_depth(const Rational& qa, const Rational& qb, const Rational& qc, const Rational& s0, const Rational& s1,
                           LineRange range) {
  std::optional<Rational> lo, hi;
  if (range != LineRange::line) lo = Rational(0);
  if (range == LineRange::segment) hi = Rational(1);
  const Rational one = 1;
  // sup of s and of 1 - s over the range, clamped to 1.
  auto sup_linear = [&](const Rational& c0, const Rational& c1) -> Rational {
    if (c1 > 0) return hi ? std::min(one, c0 + c1 * *hi) : one;
    if (c1 < 0) return lo ? std::min(one, c0 + c1 * *lo) : one;
    return std::min(one, c0);
  };
  const Rational m0 = sup_linear(s0, s1), m1 = sup_linear(one - s0, -s1);
  Rational gap = std::min(m0, m1);
  // The range within the closed slab 0 <= s <= 1.
  std::optional<Rational> slo = lo, shi = hi;
  if (s1 != 0) {
    Rational a = -s0 / s1, b = (one - s0) / s1;
    if (a > b) std::swap(a, b);
    if (!slo || a > *slo) slo = a;
    if (!shi || b < *shi) shi = b;
  }
  if (gap >= 0) gap = std::min(gap, one - min_quadratic(qa, qb, qc, slo, shi));
  if (gap >= 0) return gap;
  // Separated: the size is taken from the depth d(t) = min(1 - q, s, 1 - s) of sample points,
  // each a lower bound of max_t d(t) < 0 (so |gap| bounds the depth the set lacks). Without
  // this, a line nearly parallel to a cap plane just outside the slab would be measured at its
  // far crossing of the slab.
  auto clamp = [&](Rational t) {
    if (lo && t < *lo) t = *lo;
    if (hi && t > *hi) t = *hi;
    return t;
  };
  std::vector<Rational> ts{clamp(0)};
  if (qa != 0) ts.push_back(clamp(-qb / (2 * qa)));
  if (s1 != 0) ts.push_back(clamp((Rational(1, 2) - s0) / s1));
  if (slo) ts.push_back(clamp(*slo));
  if (shi) ts.push_back(clamp(*shi));
  Rational best = gap;
  bool first = true;
  for (const Rational& t : ts) {
    const Rational s = s0 + s1 * t;
    const Rational d = std::min({one - ((qa * t + qb) * t + qc), s, one - s});
    if (first || d > best) best = d, first = false;
  }
  return best;
}

inline std::pair<double, double> enclose_rational(const Rational& q) {
  const auto iv = CGAL::to_interval(q);
  return {iv.first, iv.second};
}

template <class LineLike>
Rational circular_line_gap(const LineLike& l, const Cylinder<Rational>& c, LineRange range) {
  const Vec3<Rational> A = c.axis();
  const Rational AA = squared_length(A);
  const Rational R = c.radius * c.radius * AA;
  const Vec3<Rational> O = l.origin;
  const Vec3<Rational> d = l.direction;
  const Vec3<Rational> w = O - c.p0;
  const Vec3<Rational> u = cross(w, A), v = cross(d, A);
  return line_depth(dot(v, v) / R, 2 * dot(u, v) / R, dot(u, u) / R, dot(w, A) / AA, dot(d, A) / AA, range);
}

// The unit frame of an elliptic cylinder: y = M^-1 v, M = [a b c] (M^-1's rows are the cross
// products over det); a point X maps to y(X - base).
struct EllipticFrame {
  explicit EllipticFrame(const EllipticCylinder<Rational>& e)
      : base(e.base), det(determinant(e.a, e.b, e.c)), r0(cross(e.b, e.c)), r1(cross(e.c, e.a)), r2(cross(e.a, e.b)) {}
  Vec3<Rational> operator()(const Vec3<Rational>& v) const { return {dot(r0, v) / det, dot(r1, v) / det, dot(r2, v) / det}; }
  Vec3<Rational> base;
  Rational det;
  Vec3<Rational> r0, r1, r2;
};

// LineLike: a line or ray (origin, direction) or a segment as Line{p0, p1 - p0} with its range.
template <class LineLike>
Rational elliptic_line_gap(const LineLike& l, const EllipticCylinder<Rational>& e, LineRange range) {
  const EllipticFrame unit(e);
  const Vec3<Rational> w = unit(l.origin - unit.base), v = unit(l.direction);
  return line_depth(v.x * v.x + v.y * v.y, 2 * (w.x * v.x + w.y * v.y), w.x * w.x + w.y * w.y, w.z, v.z, range);
}

// The depth of one point from its squared radial coordinate q and axial coordinate s.
inline Rational point_depth(const Rational& q, const Rational& s) {
  const Rational one = 1;
  return std::min({one - q, s, one - s});
}

inline Rational circular_point_gap(const Point3<Rational>& X, const Cylinder<Rational>& c) {
  const Vec3<Rational> A = c.axis(), w = X - c.p0, u = cross(w, A);
  const Rational AA = squared_length(A);
  return point_depth(dot(u, u) / (c.radius * c.radius * AA), dot(w, A) / AA);
}

inline Rational elliptic_point_gap(const Point3<Rational>& X, const EllipticCylinder<Rational>& e) {
  const EllipticFrame unit(e);
  const Vec3<Rational> y = unit(X - unit.base);
  return point_depth(y.x * y.x + y.y * y.y, y.z);
}

inline Rational triangle_gap(const Triangle<Rational>& T, const Cylinder<Rational>& c, const TriangleCylinderResult& r) {
  const Vec3<Rational> A = c.axis();
  const Rational AA = squared_length(A);
  Rational smax = dot(Vec3<Rational>(T.v[0] - c.p0), A), smin = smax;
  for (int i = 1; i < 3; ++i) {
    const Rational s = dot(Vec3<Rational>(T.v[i] - c.p0), A);
    smax = std::max(smax, s);
    smin = std::min(smin, s);
  }
  const Rational one = 1;
  Rational gap = std::min({one, smax / AA, one - smin / AA});
  if (gap < 0) return gap;
  // The certified query builds X* (the point of T in the closed slab nearest the axis) only when
  // its certificate needs it; otherwise the exact construction supplies it here.
  if (r.closest) return std::min(gap, one - r.squared_distance / (c.radius * c.radius));
  TriangleCylinderResult full;
  full.answer = r.answer;
  certcyl::detail::exact_certificate(full, T, c);
  if (!full.closest) throw std::logic_error("study gap: the triangle meets the slab but has no nearest point");
  return std::min(gap, one - full.squared_distance / (c.radius * c.radius));
}

inline Answer answer_of_sign(const Rational& g) {
  return g < 0 ? Answer::separated : (g > 0 ? Answer::overlapping : Answer::touching);
}

}  // namespace detail

// Computes inst.certified, the gap enclosure, (line queries) t_in and (cylinder pairs) the stage,
// arithmetic and Gmpfr precision that decided. Sets certified_ok to false when the gap's sign
// and the certified answer differ (a defect the study reports).
// The cylinder pairs' gap enclosure comes from the ranked fast path (refine_gap).
inline CylinderCylinderOptions refined_gap_options() {
  CylinderCylinderOptions o;
  o.refine_gap = true;
  return o;
}

inline void certify(Instance& inst, const CylinderCylinderOptions& cyl_options = refined_gap_options()) {
  using namespace detail;
  const std::vector<double>& x = inst.x;
  auto finish_line = [&](const CertifiedLineResult& r, const Rational& gap) {
    inst.certified = r.answer;
    if (r.in) inst.t_in = r.in->nearest;
    std::tie(inst.gap_lo, inst.gap_hi) = enclose_rational(gap);
    inst.certified_ok = answer_of_sign(gap) == r.answer;
  };
  const std::vector<Rational> q = exact(x);
  switch (inst.query) {
    case Query::line_cylinder:
      finish_line(certified_line_cylinder(line_at(x), cylinder_at(x, 6)),
                  circular_line_gap(line_at(q), cylinder_at(q, 6), LineRange::line));
      return;
    case Query::ray_cylinder:
      finish_line(certified_line_cylinder(ray_at(x), cylinder_at(x, 6)),
                  circular_line_gap(ray_at(q), cylinder_at(q, 6), LineRange::ray));
      return;
    case Query::segment_cylinder: {
      const Segment<Rational> s = segment_at(q);
      finish_line(certified_line_cylinder(segment_at(x), cylinder_at(x, 6)),
                  circular_line_gap(Line<Rational>{s.p0, s.direction()}, cylinder_at(q, 6), LineRange::segment));
      return;
    }
    case Query::line_elliptic_cylinder:
      finish_line(certified_line_cylinder(line_at(x), elliptic_at(x, 6)),
                  elliptic_line_gap(line_at(q), elliptic_at(q, 6), LineRange::line));
      return;
    case Query::triangle_cylinder: {
      const Triangle<Rational> T = triangle_at(q);
      const Cylinder<Rational> C = cylinder_at(q, 9);
      const TriangleCylinderResult r = certified_triangle_cylinder(T, C);
      const Rational gap = triangle_gap(T, C, r);
      inst.certified = r.answer;
      std::tie(inst.gap_lo, inst.gap_hi) = enclose_rational(gap);
      inst.certified_ok = answer_of_sign(gap) == r.answer;
      return;
    }
    case Query::cylinder_cylinder: {
      const CylinderCylinderResult r = certified_cylinder_cylinder(cylinder_at(x, 0), cylinder_at(x, 7), cyl_options);
      inst.certified = r.answer;
      inst.stage = to_string(r.stage);
      inst.certified_by = to_string(r.certified_by);
      inst.gmpfr_precision = r.gmpfr_precision;
      const CylinderGap gap = r.gap();
      if (gap.known) {
        inst.gap_lo = gap.log_lower();
        inst.gap_hi = gap.log_upper();
      } else {
        inst.gap_lo = inst.gap_hi = std::numeric_limits<double>::infinity();
      }
      // The enclosure must allow the answer's sign (touching: it contains 0).
      const Answer a = r.answer;
      inst.certified_ok = a == Answer::undecided || !gap.known ||
                          (a == Answer::separated && inst.gap_lo < 0) || (a == Answer::overlapping && inst.gap_hi > 0) ||
                          (a == Answer::touching && inst.gap_lo <= 0 && inst.gap_hi >= 0);
      return;
    }
  }
}

}  // namespace certcyl::study
