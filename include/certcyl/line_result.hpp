// certcyl/line_result.hpp -- the result of every line/ray/segment against cylinder query.
//
// Each query is a find-intersection on a solid, closed cylinder (circular or elliptic). Its
// result is the set of parameters t for which X = origin + t * direction lies in the solid
// (direction not normalised; for a segment, origin = p0 and direction = p1 - p0, so t in [0,1]):
//   empty              answer separated, no endpoints
//   one point          answer touching, in == out (a tangent point, a rim graze, a ray or
//                      segment that ends exactly on the boundary)
//   an interval        [in, out] with in < out; answer overlapping when some t of the allowed
//                      range puts the point in the open interior, touching otherwise (a line
//                      on the wall, a chord in a cap plane)
//
// Each endpoint names the feature it lies on:
//   wall          the lateral surface (circular: |(X-P) x A| = r |A|; elliptic: x^2 + y^2 = 1)
//   cap0, cap1    the disk at p0 (elliptic: z = 0) and at p1 (elliptic: z = 1)
//   rim0, rim1    the circle (ellipse) where the wall meets cap0 or cap1
//   origin        t = 0 of a ray or a segment: the interval was clipped there
//   end           t = 1 of a segment: the interval was clipped there
// and, separately, `surface`: the boundary feature the point lies on (none when it is interior
// to the solid). For a wall/cap/rim endpoint feature == surface; for an origin/end endpoint the
// surface tells whether the clipped point lies on the boundary too.
#pragma once

#include <optional>
#include <string_view>

#include "certcyl/answer.hpp"
#include "certcyl/number_traits.hpp"

namespace certcyl {

enum class LineFeature { none, wall, cap0, cap1, rim0, rim1, origin, end };

inline constexpr std::string_view to_string(LineFeature f) {
  switch (f) {
    case LineFeature::none: return "none";
    case LineFeature::wall: return "wall";
    case LineFeature::cap0: return "cap0";
    case LineFeature::cap1: return "cap1";
    case LineFeature::rim0: return "rim0";
    case LineFeature::rim1: return "rim1";
    case LineFeature::origin: return "origin";
    case LineFeature::end: return "end";
  }
  return "none";
}

// Which part of the line a query uses: all t, t >= 0 (ray), t in [0, 1] (segment).
enum class LineRange { line, ray, segment };

inline constexpr std::string_view to_string(LineRange r) {
  return r == LineRange::line ? "line" : (r == LineRange::ray ? "ray" : "segment");
}

// An endpoint of the parameter interval, its value in type T.
template <class T>
struct LineEndpoint {
  T t;
  LineFeature feature = LineFeature::none;
  LineFeature surface = LineFeature::none;
};

// The parameter interval of a line inside a solid cylinder, with the three-valued answer.
// `in` and `out` are set exactly when answer is touching or overlapping.
template <class T>
struct LineInterval {
  Answer answer = Answer::separated;
  std::optional<LineEndpoint<T>> in, out;
};

// Restricts a line's interval to a ray (t >= 0) or a segment (t in [0, 1]), for the seeds'
// methods, which answer for lines: a clipped end becomes origin/end (its surface is kept only
// when the end coincides with the old endpoint; a clipped end strictly inside the old interval
// gets surface none: the seeds do not classify it). Overlapping stays overlapping only if the
// clipped interval keeps a positive length (the line's open part is a sub-interval of it).
template <class NT>
LineInterval<NT> clip_to_range(LineInterval<NT> r, LineRange range) {
  if (range == LineRange::line || r.answer == Answer::separated) return r;
  const NT zero = nt::constant<NT>(0), one = nt::constant<NT>(1);
  // Raise `in` to 0 (and lower `out` to 1 for a segment); an endpoint equal to a range end
  // takes that end's feature and keeps its own as the surface.
  auto clip = [&](LineEndpoint<NT>& e, const NT& bound, CGAL::Comparison_result beyond, LineFeature f) {
    const CGAL::Comparison_result c = nt::compare(e.t, bound);
    if (c == CGAL::EQUAL) {
      if (e.feature != f) e.surface = e.feature;
      e.feature = f;
    } else if (c == beyond) {
      e = {bound, f, LineFeature::none};
    }
  };
  auto mark = [&](LineEndpoint<NT>& e, const NT& bound, LineFeature f) {
    if (nt::compare(e.t, bound) == CGAL::EQUAL && e.feature != f) e.surface = e.feature, e.feature = f;
  };
  clip(*r.in, zero, CGAL::SMALLER, LineFeature::origin);
  mark(*r.out, zero, LineFeature::origin);
  if (range == LineRange::segment) {
    clip(*r.out, one, CGAL::LARGER, LineFeature::end);
    mark(*r.in, one, LineFeature::end);
  }
  const CGAL::Comparison_result width = nt::compare(r.in->t, r.out->t);
  if (width == CGAL::LARGER) return LineInterval<NT>{};
  if (width == CGAL::EQUAL) r.answer = Answer::touching;
  return r;
}

}  // namespace certcyl
