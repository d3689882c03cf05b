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
// (certified/detail/line_shape.hpp). For a circular cylinder with binary64 input, each sign is
// one division-free decision polynomial of degree <= 6 (certified/detail/line_static_filter.hpp),
// evaluated adaptively: in double with a proved forward error bound; where that bound does not
// decide, in double-double with its proved bound (certified/detail/line_double_double.hpp);
// where that does not decide either (exact zeros: tangencies, on-boundary cases), exactly in
// Mpzf. Other input (elliptic cylinders, magnitudes outside the stages' windows, rational
// input that is not binary64) runs the skeleton in Interval_nt, then in Gmpq where an interval
// sign is undecided. Rational input whose numbers are all binary64 values takes the double
// path. `FilterCounter` records the Gmpq fall-backs,
// `LineStageCounter` / `CertifiedLineResult::stage` the stage that decided.
// Endpoints: from binary64 input against a circular cylinder, each endpoint's nearest double is
// proved in double-double by the signs of its defining polynomial at the two midpoints around
// it (certified/detail/line_nearest.hpp; a tangent point at t = 0 by the exact sign of b), and
// its exact value is built only when asked for (CertifiedEndpoint::value(), exact()).
// Otherwise, and where that proof does not go through (an endpoint on or within about 2^-90 of
// a midpoint, roots so near 0 that the bound cannot separate them from the midpoints,
// magnitudes outside its window): the
// quadric in Mpzf from binary64 input (Gmpq otherwise), one Gmpq normalisation per endpoint,
// the nearest double from the rational or an MPFR enclosure. Either way the exact value and
// the nearest double are the same; CertifiedEndpoint::rounding says which proof was used.
//
// Inputs: exact Rational primitives (the command's input) or double primitives (each double
// is taken as the exact binary64 value it holds, so the answer is the exact one for those
// values). Every entry point validates its operands as the command does (primitives.hpp:
// direction != 0, p0 != p1, radius > 0, det[a b c] != 0, finite doubles) and throws
// InvalidInput naming the operand: "line", "ray", "segment", "cylinder", "elliptic_cylinder"
// ("cylinder.radius: must be positive, got -1").
//
// API
//   certified_line_cylinder(line | ray | segment, cylinder | elliptic cylinder)
//       -> CertifiedLineResult: answer, endpoints (nearest double, features, exact value on
//          request), counter
//   certified_line_cylinder_shape(line | ray | segment, cylinder | elliptic cylinder, counter)
//       -> detail::LineShape: the answer and the features without building the exact
//          endpoints (the fast path; the same decision as above). counter: FilterCounter or
//          LineStageCounter (decisions per stage).
#pragma once

#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>

#include "certcyl/answer.hpp"
#include "certcyl/certified/detail/line_nearest.hpp"
#include "certcyl/certified/detail/line_shape.hpp"
#include "certcyl/certified/detail/line_static_filter.hpp"
#include "certcyl/certified/detail/quadratic_number.hpp"
#include "certcyl/filtered.hpp"
#include "certcyl/line_result.hpp"
#include "certcyl/primitives.hpp"

namespace certcyl {

using QuadraticNumber = detail::QuadraticNumber;

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

// What rebuilds one bound exactly from binary64 input against a circular cylinder.
struct LineBoundSource {
  LineInput<double> input;
  Cylinder<double> cylinder;
  BoundKind kind = BoundKind::range_lo;
  TubeState tube = TubeState::empty;
};

}  // namespace detail

// How an endpoint's nearest double was proved: the endpoint is 0 or 1, or a rational rounded
// exactly; by the signs at the two midpoints in double-double (certified/detail/line_nearest.hpp);
// by an MPFR enclosure of the exact value (certified/detail/quadratic_number.hpp).
enum class EndpointRounding : unsigned char { exact_rational, double_double, mpfr };

inline constexpr std::string_view to_string(EndpointRounding r) {
  switch (r) {
    case EndpointRounding::exact_rational: return "exact_rational";
    case EndpointRounding::double_double: return "double_double";
    case EndpointRounding::mpfr: break;
  }
  return "mpfr";
}

// One endpoint of the certified interval: the exact parameter t = alpha + beta sqrt(gamma)
// (value(), printed by exact()), the binary64 value nearest to it (ties to even) and its
// features. The exact value is computed on request: an endpoint whose nearest double was proved
// in double-double keeps the binary64 input and which bound it is, and value() rebuilds the
// exact number from them on each call (the same number, in the same normal form, as the eager
// computation: keep the result to use it more than once); any other endpoint holds its value.
class CertifiedEndpoint {
 public:
  double nearest = 0;  // the binary64 value nearest to value() (ties to even)
  LineFeature feature = LineFeature::none;
  LineFeature surface = LineFeature::none;
  EndpointRounding rounding = EndpointRounding::mpfr;

  CertifiedEndpoint() = default;
  CertifiedEndpoint(QuadraticNumber value, double nearest_double, LineFeature feature_, LineFeature surface_,
                    EndpointRounding how = EndpointRounding::mpfr)
      : nearest(nearest_double), feature(feature_), surface(surface_), rounding(how), value_(std::move(value)) {}
  CertifiedEndpoint(const detail::LineBoundSource& source, double nearest_double, LineFeature feature_, LineFeature surface_,
                    EndpointRounding how)
      : nearest(nearest_double), feature(feature_), surface(surface_), rounding(how), value_(source) {}

  QuadraticNumber value() const;  // defined below
  std::string exact() const { return value().to_string(); }
  // What value() rebuilds the exact number from, or nullptr when it holds the number.
  const detail::LineBoundSource* source() const { return std::get_if<detail::LineBoundSource>(&value_); }

 private:
  std::variant<QuadraticNumber, detail::LineBoundSource> value_;
};

// Which stage of the filter decided (the deepest arithmetic any sign needed): the semi-static
// double stage (circular cylinder, binary64 input), its double-double escalation,
// Interval_nt, or exact arithmetic (Mpzf signs of the same polynomials, or the Gmpq skeleton).
enum class LineStage : unsigned char { semi_static, interval, exact, double_double };

inline constexpr std::string_view to_string(LineStage s) {
  switch (s) {
    case LineStage::semi_static: return "semi_static";
    case LineStage::double_double: return "double_double";
    case LineStage::interval: return "interval";
    case LineStage::exact: break;
  }
  return "exact";
}

// How many decisions each stage took.
struct LineStageCounter {
  std::uint64_t calls = 0, semi_static = 0, interval = 0, exact = 0, double_double = 0;

  void count(LineStage s) {
    ++calls;
    switch (s) {
      case LineStage::semi_static: ++semi_static; break;
      case LineStage::double_double: ++double_double; break;
      case LineStage::interval: ++interval; break;
      case LineStage::exact: ++exact; break;
    }
  }
  LineStageCounter& operator+=(const LineStageCounter& o) {
    calls += o.calls, semi_static += o.semi_static, interval += o.interval, exact += o.exact;
    double_double += o.double_double;
    return *this;
  }
};

struct CertifiedLineResult {
  Answer answer = Answer::separated;
  LineRange range = LineRange::line;
  std::optional<CertifiedEndpoint> in, out;  // set unless separated; equal values for a point
  FilterCounter counter;                      // this query: calls = 1, exact = 1 if intervals could not decide
  LineStage stage = LineStage::exact;         // the stage that decided

  // Both endpoints' exact values (in, out; the result must not be separated), the exact quadric
  // built once for the two: what in->value() and out->value() give, at about half their cost.
  std::pair<QuadraticNumber, QuadraticNumber> exact_values() const;  // defined below
};

namespace detail {

template <class NT, class In, class Solid>
LineQuadric<NT> line_quadric_in(const LineInput<In>& in, const Solid& solid) {
  const Vec3<NT> O = input_to<NT>(in.origin);
  const Vec3<NT> second = input_to<NT>(in.second);
  const Vec3<NT> d = in.second_is_point ? Vec3<NT>(second - O) : second;
  return line_quadric(O, d, solid.map([](const In& x) { return input_to<NT>(x); }));
}

// The input as binary64 values when every number is one; the whole computation then starts
// from doubles, which the intervals, Mpzf and Gmpq take exactly. q = m 2^e with m odd is a
// binary64 value iff m has at most 53 bits, e >= -1074 and m 2^e < 2^1024 (for m < 2^53 and
// e >= -1074, m 2^e is a normal or a subnormal double).
inline bool binary64_value(const Rational& q, double& out) {
  const mpz_srcptr num = mpq_numref(q.mpq()), den = mpq_denref(q.mpq());
  if (mpz_sgn(num) == 0) {
    out = 0;
    return true;
  }
  const auto den_shift = mpz_scan1(den, 0);
  if (mpz_sizeinbase(den, 2) != den_shift + 1) return false;  // the denominator is not 2^k
  const auto low = mpz_scan1(num, 0), bits = mpz_sizeinbase(num, 2);
  if (bits - low > 53) return false;
  const long e = static_cast<long>(low) - static_cast<long>(den_shift);
  if (e < -1074 || e + static_cast<long>(bits - low) > 1024) return false;
  // m = |num| >> low fits in 53 bits: read it from the (at most two) limbs it spans.
  static_assert(GMP_NUMB_BITS == 64, "64-bit limbs");
  const auto limb = static_cast<mp_size_t>(low / 64);
  const unsigned shift = low % 64;
  std::uint64_t m = mpz_getlimbn(num, limb) >> shift;
  if (shift != 0 && limb + 1 < static_cast<mp_size_t>(mpz_size(num))) m |= mpz_getlimbn(num, limb + 1) << (64 - shift);
  const double magnitude = std::ldexp(static_cast<double>(m), static_cast<int>(e));  // both steps exact
  out = mpz_sgn(num) < 0 ? -magnitude : magnitude;
  return true;
}

template <template <class> class Solid>
std::optional<std::pair<LineInput<double>, Solid<double>>> as_binary64(const LineInput<Rational>& in, const Solid<Rational>& solid) {
  bool exact = true;
  auto to_double = [&](const Rational& q) {
    double x = 0;
    exact = exact && binary64_value(q, x);
    return x;
  };
  LineInput<double> din{in.origin.map(to_double), in.second.map(to_double), in.second_is_point, in.range};
  Solid<double> dsolid = solid.map(to_double);
  if (!exact) return std::nullopt;
  return std::pair{din, dsolid};
}

// The stage of a decision by the adaptive signs.
inline LineStage static_stage(const StaticCircularSigns& s) {
  using Depth = StaticCircularSigns::Depth;
  return s.depth() == Depth::binary64 ? LineStage::semi_static
                                      : (s.depth() == Depth::double_double ? LineStage::double_double : LineStage::exact);
}

// The filtered decision: the adaptive polynomial signs (circular cylinders, binary64 input
// inside the double stage's window: double, double-double, Mpzf per sign), else Interval_nt,
// then Gmpq. Input in double (exact binary64 values) or Rational.
template <class In, class Solid>
LineShape certified_shape(const LineInput<In>& in, const Solid& solid, LineStage& stage) {
  if constexpr (std::is_same_v<In, Rational>) {
    if (const auto d = as_binary64(in, solid)) return certified_shape(d->first, d->second, stage);
  } else if constexpr (std::is_same_v<Solid, Cylinder<double>>) {
    StaticCircularSigns s(in.origin, in.second, in.second_is_point, solid, /*escalate=*/true);
    if (s.usable()) {
      const LineShape shape = line_shape_from(s, in.range);
      // else: never undecided with escalation (every sign reaches Mpzf if it must)
      stage = static_stage(s);
      return shape;
    }
  }
  FilterCounter counter;
  const LineShape shape =
      filtered_call([&]<class NT>() { return line_shape(line_quadric_in<NT>(in, solid), in.range); }, counter);
  stage = counter.exact != 0 ? LineStage::exact : LineStage::interval;
  return shape;
}

template <class In, class Solid>
LineShape certified_shape(const LineInput<In>& in, const Solid& solid, FilterCounter& counter) {
  LineStage stage{};
  const LineShape shape = certified_shape(in, solid, stage);
  ++counter.calls;
  if (stage == LineStage::exact) ++counter.exact;
  return shape;
}

// The exact quadric as rationals. From binary64 input it is computed in Mpzf (dyadic
// integers, no normalisation per operation; line_quadric is division-free) and converted once.
template <class In, class Solid>
LineQuadric<Rational> exact_quadric(const LineInput<In>& in, const Solid& solid) {
  if constexpr (std::is_same_v<In, double>) {
    const LineQuadric<CGAL::Mpzf> m = line_quadric_in<CGAL::Mpzf>(in, solid);
    auto q = [](const CGAL::Mpzf& x) { return static_cast<Rational>(x); };
    return {q(m.a), q(m.b), q(m.c), q(m.disc), q(m.sw), q(m.sd), q(m.H)};
  } else {
    return line_quadric_in<Rational>(in, solid);
  }
}

// The exact values of a query's bounds: 0 and 1 directly, the others from the exact quadric,
// built on the first request and kept for the next.
template <class In, class Solid>
class ExactBounds {
 public:
  ExactBounds(const LineInput<In>& in, const Solid& solid, TubeState tube) : in_(in), solid_(solid), tube_(tube) {}
  ExactBounds(const ExactBounds&) = delete;  // bounds_ refers to q_
  ExactBounds& operator=(const ExactBounds&) = delete;

  QuadraticNumber operator()(BoundKind k) {
    if (k == BoundKind::range_lo) return {0, 0, 0};
    if (k == BoundKind::range_hi) return {1, 0, 0};
    if (!bounds_) {
      q_ = exact_quadric(in_, solid_);
      bounds_.emplace(*q_, tube_);
    }
    return (*bounds_)(k);
  }

 private:
  const LineInput<In>& in_;
  const Solid& solid_;
  TubeState tube_;
  std::optional<LineQuadric<Rational>> q_;
  std::optional<BoundValuesExact> bounds_;
};

// The endpoints of a decided shape. With `signs` (binary64 input against a circular cylinder,
// decided by them), each endpoint's nearest double is first proved in double-double from the
// same leaves (certified/detail/line_nearest.hpp) and its exact value left to be built on
// request. Otherwise, and for an endpoint that proof does not reach: the exact quadric (made
// once per query), the endpoint's exact value, its nearest double from the rational or an MPFR
// enclosure.
template <class In, class Solid>
void certified_endpoints(const LineInput<In>& in, const Solid& solid, const LineShape& shape, StaticCircularSigns* signs,
                         CertifiedLineResult& result) {
  std::optional<LineNearest> fast;
  ExactBounds exact(in, solid, shape.tube);
  auto endpoint = [&](BoundKind k, LineFeature feature, LineFeature surface) {
    if constexpr (std::is_same_v<In, double> && std::is_same_v<Solid, Cylinder<double>>) {
      if (signs != nullptr) {
        if (!fast) fast.emplace(*signs);
        if (const std::optional<ProvedNearest> n = (*fast)(k, shape.tube)) {
          return CertifiedEndpoint(LineBoundSource{in, solid, k, shape.tube}, n->nearest, feature, surface,
                                   n->exact ? EndpointRounding::exact_rational : EndpointRounding::double_double);
        }
      }
    }
    QuadraticNumber v = exact(k);
    const double n = nearest_double(v);
    const EndpointRounding how = v.is_rational() ? EndpointRounding::exact_rational : EndpointRounding::mpfr;
    return CertifiedEndpoint(std::move(v), n, feature, surface, how);
  };
  result.in = endpoint(shape.in, shape.in_feature, shape.in_surface);
  result.out = endpoint(shape.out, shape.out_feature, shape.out_surface);
}

template <class In, class Solid>
CertifiedLineResult certified_result(const LineInput<In>& in, const Solid& solid) {
  if constexpr (std::is_same_v<In, Rational>) {
    if (const auto d = as_binary64(in, solid)) return certified_result(d->first, d->second);
  }
  CertifiedLineResult result;
  result.range = in.range;
  result.counter.calls = 1;
  if constexpr (std::is_same_v<In, double> && std::is_same_v<Solid, Cylinder<double>>) {
    StaticCircularSigns s(in.origin, in.second, in.second_is_point, solid, /*escalate=*/true);
    if (s.usable()) {
      const LineShape shape = line_shape_from(s, in.range);
      result.stage = static_stage(s);
      result.counter.exact = result.stage == LineStage::exact ? 1 : 0;
      result.answer = shape.answer;
      if (shape.answer != Answer::separated) certified_endpoints(in, solid, shape, &s, result);
      return result;
    }
  }
  const LineShape shape = certified_shape(in, solid, result.stage);
  result.counter.exact = result.stage == LineStage::exact ? 1 : 0;
  result.answer = shape.answer;
  if (shape.answer != Answer::separated) certified_endpoints(in, solid, shape, nullptr, result);
  return result;
}

template <class T>
concept CertifiedInput = std::is_same_v<T, double> || std::is_same_v<T, Rational>;

// The operands' names in InvalidInput, as in the command's input.
template <class In>
constexpr const char* operand_name(const Line<In>&) {
  return "line";
}
template <class In>
constexpr const char* operand_name(const Ray<In>&) {
  return "ray";
}
template <class In>
constexpr const char* operand_name(const Segment<In>&) {
  return "segment";
}
template <class In>
constexpr const char* operand_name(const Cylinder<In>&) {
  return "cylinder";
}
template <class In>
constexpr const char* operand_name(const EllipticCylinder<In>&) {
  return "elliptic_cylinder";
}

template <class LineLike, class Solid>
void validate_line_operands(const LineLike& line, const Solid& solid) {
  validate_operand(line, operand_name(line));
  validate_operand(solid, operand_name(solid));
}

template <class LineLike, class Solid>
CertifiedLineResult certified_line_query(const LineLike& line, const Solid& solid) {
  validate_line_operands(line, solid);
  return certified_result(line_input(line), solid);
}

}  // namespace detail

inline QuadraticNumber CertifiedEndpoint::value() const {
  if (const QuadraticNumber* v = std::get_if<QuadraticNumber>(&value_)) return *v;
  const detail::LineBoundSource& s = std::get<detail::LineBoundSource>(value_);
  return detail::ExactBounds(s.input, s.cylinder, s.tube)(s.kind);
}

inline std::pair<QuadraticNumber, QuadraticNumber> CertifiedLineResult::exact_values() const {
  const detail::LineBoundSource* a = in->source();
  const detail::LineBoundSource* b = out->source();
  if (a == nullptr || b == nullptr) return {in->value(), out->value()};
  detail::ExactBounds bounds(a->input, a->cylinder, a->tube);
  QuadraticNumber first = bounds(a->kind);
  return {std::move(first), bounds(b->kind)};
}

// ---- The public entry points (In = Rational or double) --------------------------------------

template <detail::CertifiedInput In>
CertifiedLineResult certified_line_cylinder(const Line<In>& line, const Cylinder<In>& cyl) {
  return detail::certified_line_query(line, cyl);
}
template <detail::CertifiedInput In>
CertifiedLineResult certified_line_cylinder(const Ray<In>& ray, const Cylinder<In>& cyl) {
  return detail::certified_line_query(ray, cyl);
}
template <detail::CertifiedInput In>
CertifiedLineResult certified_line_cylinder(const Segment<In>& seg, const Cylinder<In>& cyl) {
  return detail::certified_line_query(seg, cyl);
}
template <detail::CertifiedInput In>
CertifiedLineResult certified_line_cylinder(const Line<In>& line, const EllipticCylinder<In>& e) {
  return detail::certified_line_query(line, e);
}
template <detail::CertifiedInput In>
CertifiedLineResult certified_line_cylinder(const Ray<In>& ray, const EllipticCylinder<In>& e) {
  return detail::certified_line_query(ray, e);
}
template <detail::CertifiedInput In>
CertifiedLineResult certified_line_cylinder(const Segment<In>& seg, const EllipticCylinder<In>& e) {
  return detail::certified_line_query(seg, e);
}

// The decision alone (answer and features), accumulating the filter statistics in `counter`
// (calls, and exact = the decisions that needed Gmpq) or, per stage, in a LineStageCounter.
template <class LineLike, class Solid>
detail::LineShape certified_line_cylinder_shape(const LineLike& line, const Solid& solid, FilterCounter& counter) {
  detail::validate_line_operands(line, solid);
  return detail::certified_shape(detail::line_input(line), solid, counter);
}
template <class LineLike, class Solid>
detail::LineShape certified_line_cylinder_shape(const LineLike& line, const Solid& solid, LineStageCounter& counter) {
  detail::validate_line_operands(line, solid);
  LineStage stage{};
  const detail::LineShape shape = detail::certified_shape(detail::line_input(line), solid, stage);
  counter.count(stage);
  return shape;
}

}  // namespace certcyl
