// certcyl/certified/line_cylinder.hpp -- certified find-intersection of a line, ray or
// segment with a solid, closed circular or elliptic cylinder.
//
// Semantics: see certcyl/line_result.hpp. The result is the exact parameter interval of the
// line inside the solid, restricted to t >= 0 (ray) or t in [0, 1] (segment), the feature of
// each endpoint, and the three-valued answer:
//   separated    no common point
//   touching     common points, none in the open interior: a tangent point, a line on the
//                wall, a chord in a cap plane, a graze of a rim, a ray or segment ending on
//                the boundary from outside
//   overlapping  some allowed t puts the point in the open interior
// Every endpoint is an exact number alpha + beta sqrt(gamma) (alpha, beta rational, gamma an
// integer; design note section 3: the roots of the tube quadratic, the cap planes' rational
// parameters, or 0 / 1), printed exactly, and comes with the binary64 value nearest to it,
// proved by an enclosure (certified/detail/quadratic_number.hpp). `undecided` never occurs.
//
// Method (design note, sections 3 and 5): the division-free quadratic of the tube with its
// cancellation-free discriminant, the slab of the caps, and a sign skeleton that decides
// every comparison of symbolic bounds by the sign of p + q sqrt(disc)
// (certified/detail/line_shape.hpp). Filtered: the skeleton runs in Interval_nt first and in
// Gmpq only where an interval sign is undecided (ties, tangencies, on-boundary cases, near
// misses); `FilterCounter` records the fall-backs.
//
// Inputs: exact Rational primitives (the command's input) or double primitives (each double
// is taken as the exact binary64 value it holds, so the answer is the exact one for those
// values). Preconditions (checked by `validate` at the input boundary, not here): direction
// != 0, p0 != p1, radius > 0, det[a b c] != 0.
//
// API
//   certified_line_cylinder(line | ray | segment, cylinder | elliptic cylinder)
//       -> CertifiedLineResult: answer, endpoints (exact, nearest double, features), counter
//   certified_line_cylinder_shape(line | ray | segment, cylinder | elliptic cylinder, counter)
//       -> detail::LineShape: the answer and the features without building the exact
//          endpoints (the fast path; the same decision as above).
#pragma once

#include <optional>
#include <string>
#include <type_traits>

#include "certcyl/answer.hpp"
#include "certcyl/certified/detail/line_shape.hpp"
#include "certcyl/certified/detail/quadratic_number.hpp"
#include "certcyl/filtered.hpp"
#include "certcyl/line_result.hpp"
#include "certcyl/primitives.hpp"

namespace certcyl {

using QuadraticNumber = detail::QuadraticNumber;

// One endpoint of the certified interval.
struct CertifiedEndpoint {
  QuadraticNumber value;  // exact parameter t = alpha + beta sqrt(gamma)
  double nearest = 0;     // the binary64 value nearest to `value` (ties to even)
  LineFeature feature = LineFeature::none;
  LineFeature surface = LineFeature::none;

  std::string exact() const { return value.to_string(); }
};

struct CertifiedLineResult {
  Answer answer = Answer::separated;
  LineRange range = LineRange::line;
  std::optional<CertifiedEndpoint> in, out;  // set unless separated; equal values for a point
  FilterCounter counter;                      // this query: calls = 1, exact = 1 if intervals could not decide
};

namespace detail {

// A line-like input: origin and either a direction or a second point (segments), so that a
// segment's direction p1 - p0 is formed in the number type of the computation.
template <class In>
struct LineInput {
  Vec3<In> origin, second;
  bool second_is_point = false;
  LineRange range = LineRange::line;
};

template <class In>
LineInput<In> line_input(const Line<In>& l) {
  return {l.origin, l.direction, false, LineRange::line};
}
template <class In>
LineInput<In> line_input(const Ray<In>& r) {
  return {r.origin, r.direction, false, LineRange::ray};
}
template <class In>
LineInput<In> line_input(const Segment<In>& s) {
  return {s.p0, s.p1, true, LineRange::segment};
}

template <class NT, class In, class Solid>
LineQuadric<NT> line_quadric_in(const LineInput<In>& in, const Solid& solid) {
  const Vec3<NT> O = input_to<NT>(in.origin);
  const Vec3<NT> second = input_to<NT>(in.second);
  const Vec3<NT> d = in.second_is_point ? Vec3<NT>(second - O) : second;
  return line_quadric(O, d, solid.map([](const In& x) { return input_to<NT>(x); }));
}

template <class In, class Solid>
LineShape certified_shape(const LineInput<In>& in, const Solid& solid, FilterCounter& counter) {
  return filtered_call([&]<class NT>() { return line_shape(line_quadric_in<NT>(in, solid), in.range); }, counter);
}

template <class In, class Solid>
CertifiedLineResult certified_result(const LineInput<In>& in, const Solid& solid) {
  CertifiedLineResult result;
  result.range = in.range;
  const LineShape shape = certified_shape(in, solid, result.counter);
  result.answer = shape.answer;
  if (shape.answer == Answer::separated) return result;
  const LineQuadric<Rational> q = line_quadric_in<Rational>(in, solid);
  auto endpoint = [&](BoundKind k, LineFeature feature, LineFeature surface) {
    CertifiedEndpoint e;
    e.value = bound_value(k, q, shape.tube);
    e.nearest = nearest_double(e.value);
    e.feature = feature;
    e.surface = surface;
    return e;
  };
  result.in = endpoint(shape.in, shape.in_feature, shape.in_surface);
  result.out = endpoint(shape.out, shape.out_feature, shape.out_surface);
  return result;
}

template <class T>
concept CertifiedInput = std::is_same_v<T, double> || std::is_same_v<T, Rational>;

}  // namespace detail

// ---- The public entry points (In = Rational or double) --------------------------------------

template <detail::CertifiedInput In>
CertifiedLineResult certified_line_cylinder(const Line<In>& line, const Cylinder<In>& cyl) {
  return detail::certified_result(detail::line_input(line), cyl);
}
template <detail::CertifiedInput In>
CertifiedLineResult certified_line_cylinder(const Ray<In>& ray, const Cylinder<In>& cyl) {
  return detail::certified_result(detail::line_input(ray), cyl);
}
template <detail::CertifiedInput In>
CertifiedLineResult certified_line_cylinder(const Segment<In>& seg, const Cylinder<In>& cyl) {
  return detail::certified_result(detail::line_input(seg), cyl);
}
template <detail::CertifiedInput In>
CertifiedLineResult certified_line_cylinder(const Line<In>& line, const EllipticCylinder<In>& e) {
  return detail::certified_result(detail::line_input(line), e);
}
template <detail::CertifiedInput In>
CertifiedLineResult certified_line_cylinder(const Ray<In>& ray, const EllipticCylinder<In>& e) {
  return detail::certified_result(detail::line_input(ray), e);
}
template <detail::CertifiedInput In>
CertifiedLineResult certified_line_cylinder(const Segment<In>& seg, const EllipticCylinder<In>& e) {
  return detail::certified_result(detail::line_input(seg), e);
}

// The decision alone (answer and features), accumulating the filter statistics in `counter`.
template <class LineLike, class Solid>
detail::LineShape certified_line_cylinder_shape(const LineLike& line, const Solid& solid, FilterCounter& counter) {
  return detail::certified_shape(detail::line_input(line), solid, counter);
}

}  // namespace certcyl
