// certcyl/primitives.hpp -- the inputs of every query, generic over the number type.
//
// All primitives are closed solids or closed point sets (design note, section 1):
//
// Cylinder{p0, p1, radius}
//   The points within distance `radius` of the axis segment [p0, p1] whose projection on the
//   axis falls inside the segment: X with 0 <= (X-p0).A <= A.A and |(X-p0) x A|^2 <= r^2 A.A,
//   A = p1 - p0 (never normalised, so every predicate stays polynomial in the input).
//   The seeds' form (center C, unit axis W, radius r, height h) converts by
//   `Cylinder::from_center_axis` to p0 = C - (h/2) W, p1 = C + (h/2) W EXACTLY AS WRITTEN:
//   W is not renormalised, so a W of length 1 +- eps describes a cylinder of height h |W|.
//   Build it on exact input (Rational) and convert afterwards, so no kernel rounds it twice.
//
// EllipticCylinder{base, a, b, c}
//   { base + x a + y b + z c : x^2 + y^2 <= 1, 0 <= z <= 1 }, M = [a b c] invertible. Oblique
//   frames (c not perpendicular to a, b) and non-orthogonal a, b are allowed (Gullotti seed,
//   with M used directly: design note, section 1).
//
// Line{origin, direction}     X = origin + t direction, t real; direction != 0.
// Ray{origin, direction}      the same with t >= 0.
// Segment{p0, p1}             X = p0 + t (p1 - p0), t in [0, 1]; p0 != p1.
// Triangle{v0, v1, v2}        the convex hull of the three points. A degenerate triangle
//                             (collinear or coincident vertices) is valid: it is a segment or
//                             a point.
//
// Conversion: `p.map(f)` applies f to every number, so `convert<NT>(p)` takes an exact input
// into NT through nt::from_rational (correctly rounded, enclosing or exact).
// Validation: `validate(p, field)` throws InvalidInput naming the field when p is not one of the
// primitives above (radius <= 0, p0 == p1, a zero direction, det[a b c] = 0): on exact input,
// and on binary64 input, where every number must also be finite ("line.origin[2]: non-finite
// number") and the checks are those of the exact values the doubles denote. `valid(p)` is the
// same test without a message (on binary64 input, without an allocation but for an elliptic
// frame whose determinant intervals cannot sign); `validate_operand(p, field)` runs it and
// builds the message only on failure: the check at every query's entry point.
#pragma once

#include <CGAL/FPU.h>
#include <CGAL/Interval_nt.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <string>

#include "certcyl/errors.hpp"
#include "certcyl/number_traits.hpp"
#include "certcyl/vec3.hpp"

namespace certcyl {

template <class NT>
using Point3 = Vec3<NT>;

template <class NT>
struct Cylinder {
  Point3<NT> p0, p1;
  NT radius;

  Vec3<NT> axis() const { return p1 - p0; }

  // The seeds' form, converted as the header comment says. Needs a field (h/2).
  static Cylinder from_center_axis(const Point3<NT>& center, const Vec3<NT>& axis, const NT& radius, const NT& height) {
    const NT half = height / nt::constant<NT>(2);
    return {center - half * axis, center + half * axis, radius};
  }

  template <class F>
  auto map(F&& f) const -> Cylinder<decltype(f(radius))> {
    return {p0.map(f), p1.map(f), f(radius)};
  }
};

template <class NT>
struct EllipticCylinder {
  Point3<NT> base;
  Vec3<NT> a, b, c;

  template <class F>
  auto map(F&& f) const -> EllipticCylinder<decltype(f(base.x))> {
    return {base.map(f), a.map(f), b.map(f), c.map(f)};
  }
};

template <class NT>
struct Line {
  Point3<NT> origin;
  Vec3<NT> direction;

  Point3<NT> at(const NT& t) const { return origin + t * direction; }

  template <class F>
  auto map(F&& f) const -> Line<decltype(f(origin.x))> {
    return {origin.map(f), direction.map(f)};
  }
};

template <class NT>
struct Ray {
  Point3<NT> origin;
  Vec3<NT> direction;

  Point3<NT> at(const NT& t) const { return origin + t * direction; }

  template <class F>
  auto map(F&& f) const -> Ray<decltype(f(origin.x))> {
    return {origin.map(f), direction.map(f)};
  }
};

template <class NT>
struct Segment {
  Point3<NT> p0, p1;

  Vec3<NT> direction() const { return p1 - p0; }
  Point3<NT> at(const NT& t) const { return p0 + t * (p1 - p0); }

  template <class F>
  auto map(F&& f) const -> Segment<decltype(f(p0.x))> {
    return {p0.map(f), p1.map(f)};
  }
};

template <class NT>
struct Triangle {
  std::array<Point3<NT>, 3> v;

  template <class F>
  auto map(F&& f) const -> Triangle<decltype(f(v[0].x))> {
    return {{v[0].map(f), v[1].map(f), v[2].map(f)}};
  }
};

// Converts an exact primitive (or vector) into number type NT.
template <class NT, class Primitive>
auto convert(const Primitive& p) {
  return p.map([](const Rational& q) { return nt::from_rational<NT>(q); });
}

// ---- Validation ---------------------------------------------------------------------------

namespace detail {
template <class NT>
bool is_null(const Vec3<NT>& v) {
  return v.x == 0 && v.y == 0 && v.z == 0;
}
}  // namespace detail

inline void validate(const Cylinder<Rational>& c, const std::string& field) {
  if (c.radius <= 0) throw InvalidInput(join_field(field, "radius"), "must be positive, got " + to_exact_string(c.radius));
  if (c.p0 == c.p1) throw InvalidInput(field, "zero-length axis (p0 == p1)");
}

// Validates the seeds' form before conversion: axis != 0, radius > 0, height > 0.
inline void validate_center_axis(const Vec3<Rational>& axis, const Rational& radius, const Rational& height,
                                 const std::string& field) {
  if (detail::is_null(axis)) throw InvalidInput(join_field(field, "axis"), "zero-length axis");
  if (radius <= 0) throw InvalidInput(join_field(field, "radius"), "must be positive, got " + to_exact_string(radius));
  if (height <= 0) throw InvalidInput(join_field(field, "height"), "must be positive, got " + to_exact_string(height));
}

inline void validate(const EllipticCylinder<Rational>& e, const std::string& field) {
  if (determinant(e.a, e.b, e.c) == 0) throw InvalidInput(field, "singular frame: det[a b c] = 0");
}

inline void validate(const Line<Rational>& l, const std::string& field) {
  if (detail::is_null(l.direction)) throw InvalidInput(join_field(field, "direction"), "zero-length direction");
}

inline void validate(const Ray<Rational>& r, const std::string& field) {
  if (detail::is_null(r.direction)) throw InvalidInput(join_field(field, "direction"), "zero-length direction");
}

inline void validate(const Segment<Rational>& s, const std::string& field) {
  if (s.p0 == s.p1) throw InvalidInput(field, "zero-length segment (p0 == p1): its direction is zero");
}

// Every triangle is valid, degenerate ones included.
inline void validate(const Triangle<Rational>&, const std::string&) {}

// Every point is valid.
inline void validate(const Point3<Rational>&, const std::string&) {}

// ---- Validation of binary64 input: finite numbers, then the checks above ----------------------

namespace detail {
inline bool finite(const Vec3<double>& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

inline void validate_finite(double x, const std::string& field) {
  if (!std::isfinite(x)) throw InvalidInput(field, "non-finite number");
}
inline void validate_finite(const Vec3<double>& v, const std::string& field) {
  for (std::size_t i = 0; i < 3; ++i) validate_finite(v[i], index_field(field, i));
}

// det[a b c] = 0 for finite binary64 vectors, exactly: in Interval_nt, then in Rational when the
// interval contains 0.
inline bool singular_frame(const EllipticCylinder<double>& e) {
  {
    CGAL::Protect_FPU_rounding<true> upward;
    using I = CGAL::Interval_nt<false>;
    const auto iv = [](const Vec3<double>& v) { return v.map([](double x) { return I(x); }); };
    const I det = determinant(iv(e.a), iv(e.b), iv(e.c));
    if (det.inf() > 0 || det.sup() < 0) return false;
  }
  const auto q = [](const Vec3<double>& v) { return v.map([](double x) { return Rational(x); }); };
  return determinant(q(e.a), q(e.b), q(e.c)) == 0;
}
}  // namespace detail

inline void validate(const Cylinder<double>& c, const std::string& field) {
  detail::validate_finite(c.p0, join_field(field, "p0"));
  detail::validate_finite(c.p1, join_field(field, "p1"));
  detail::validate_finite(c.radius, join_field(field, "radius"));
  if (!(c.radius > 0)) throw InvalidInput(join_field(field, "radius"), "must be positive, got " + to_exact_string(Rational(c.radius)));
  if (c.p0 == c.p1) throw InvalidInput(field, "zero-length axis (p0 == p1)");
}

inline void validate(const EllipticCylinder<double>& e, const std::string& field) {
  detail::validate_finite(e.base, join_field(field, "base"));
  detail::validate_finite(e.a, join_field(field, "a"));
  detail::validate_finite(e.b, join_field(field, "b"));
  detail::validate_finite(e.c, join_field(field, "c"));
  if (detail::singular_frame(e)) throw InvalidInput(field, "singular frame: det[a b c] = 0");
}

inline void validate(const Line<double>& l, const std::string& field) {
  detail::validate_finite(l.origin, join_field(field, "origin"));
  detail::validate_finite(l.direction, join_field(field, "direction"));
  if (detail::is_null(l.direction)) throw InvalidInput(join_field(field, "direction"), "zero-length direction");
}

inline void validate(const Ray<double>& r, const std::string& field) {
  detail::validate_finite(r.origin, join_field(field, "origin"));
  detail::validate_finite(r.direction, join_field(field, "direction"));
  if (detail::is_null(r.direction)) throw InvalidInput(join_field(field, "direction"), "zero-length direction");
}

inline void validate(const Segment<double>& s, const std::string& field) {
  detail::validate_finite(s.p0, join_field(field, "p0"));
  detail::validate_finite(s.p1, join_field(field, "p1"));
  if (s.p0 == s.p1) throw InvalidInput(field, "zero-length segment (p0 == p1): its direction is zero");
}

inline void validate(const Triangle<double>& t, const std::string& field) {
  for (std::size_t i = 0; i < 3; ++i) detail::validate_finite(t.v[i], index_field(field, i));
}

inline void validate(const Point3<double>& x, const std::string& field) { detail::validate_finite(x, field); }

// ---- The same tests without a message ---------------------------------------------------------

inline bool valid(const Cylinder<Rational>& c) { return c.radius > 0 && !(c.p0 == c.p1); }
inline bool valid(const EllipticCylinder<Rational>& e) { return determinant(e.a, e.b, e.c) != 0; }
inline bool valid(const Line<Rational>& l) { return !detail::is_null(l.direction); }
inline bool valid(const Ray<Rational>& r) { return !detail::is_null(r.direction); }
inline bool valid(const Segment<Rational>& s) { return !(s.p0 == s.p1); }
inline bool valid(const Triangle<Rational>&) { return true; }
inline bool valid(const Point3<Rational>&) { return true; }

inline bool valid(const Cylinder<double>& c) {
  return detail::finite(c.p0) && detail::finite(c.p1) && std::isfinite(c.radius) && c.radius > 0 && !(c.p0 == c.p1);
}
inline bool valid(const EllipticCylinder<double>& e) {
  return detail::finite(e.base) && detail::finite(e.a) && detail::finite(e.b) && detail::finite(e.c) && !detail::singular_frame(e);
}
inline bool valid(const Line<double>& l) { return detail::finite(l.origin) && detail::finite(l.direction) && !detail::is_null(l.direction); }
inline bool valid(const Ray<double>& r) { return detail::finite(r.origin) && detail::finite(r.direction) && !detail::is_null(r.direction); }
inline bool valid(const Segment<double>& s) { return detail::finite(s.p0) && detail::finite(s.p1) && !(s.p0 == s.p1); }
inline bool valid(const Triangle<double>& t) { return detail::finite(t.v[0]) && detail::finite(t.v[1]) && detail::finite(t.v[2]); }
inline bool valid(const Point3<double>& x) { return detail::finite(x); }

// The check of a query's operand: `valid`, then `validate` for the message when it fails.
template <class Primitive>
void validate_operand(const Primitive& p, const char* field) {
  if (!valid(p)) validate(p, field);
}

}  // namespace certcyl
