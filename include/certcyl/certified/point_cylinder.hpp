// certcyl/certified/point_cylinder.hpp -- certified classification of a point against a solid,
// closed circular or elliptic cylinder.
//
// Semantics: the point is `overlapping` strictly inside (Side::inside), `touching` on the
// boundary (Side::boundary), `separated` outside (Side::outside); `undecided` never occurs.
//
// Method: the polynomial sign tests of predicates/point_in_cylinder.hpp (degree 4 for a circular
// cylinder, 6 for an elliptic one), in Interval_nt, then in Gmpq where an interval cannot decide
// (a point on the boundary or very near it). The input numbers are exact rationals, or doubles
// each taken as the exact rational it denotes; both are exact in the intervals and in Gmpq.
//
// The operands are validated as the command does (primitives.hpp: radius > 0, p0 != p1,
// det[a b c] != 0, finite doubles) and an invalid one throws InvalidInput naming "point",
// "cylinder" or "elliptic_cylinder". classify_point (predicates/point_in_cylinder.hpp) is the
// same test in any number type, without validation.
#pragma once

#include <type_traits>

#include "certcyl/answer.hpp"
#include "certcyl/filtered.hpp"
#include "certcyl/predicates/point_in_cylinder.hpp"
#include "certcyl/primitives.hpp"

namespace certcyl {

struct CertifiedPointResult {
  Answer answer = Answer::separated;
  Side side = Side::outside;
  FilterCounter counter;  // this query: calls = 1, exact = 1 if the intervals could not decide
};

namespace detail {

template <class In, class Solid>
CertifiedPointResult certified_point(const Point3<In>& x, const Solid& solid, const char* solid_name) {
  validate_operand(x, "point");
  validate_operand(solid, solid_name);
  CertifiedPointResult r;
  r.side = filtered_call(
      [&]<class NT>() {
        const auto image = [](const In& v) {
          if constexpr (std::is_same_v<In, double>) {
            return NT(v);  // binary64 is exact in Interval_nt and in Gmpq
          } else {
            return nt::from_rational<NT>(v);  // enclosing in Interval_nt, exact in Gmpq
          }
        };
        return classify_point(x.map(image), solid.map(image));
      },
      r.counter);
  r.answer = r.side == Side::inside ? Answer::overlapping : (r.side == Side::boundary ? Answer::touching : Answer::separated);
  return r;
}

}  // namespace detail

// In = Rational or double.
template <class In>
  requires std::is_same_v<In, double> || std::is_same_v<In, Rational>
CertifiedPointResult certified_point_cylinder(const Point3<In>& x, const Cylinder<In>& cylinder) {
  return detail::certified_point(x, cylinder, "cylinder");
}
template <class In>
  requires std::is_same_v<In, double> || std::is_same_v<In, Rational>
CertifiedPointResult certified_point_cylinder(const Point3<In>& x, const EllipticCylinder<In>& cylinder) {
  return detail::certified_point(x, cylinder, "elliptic_cylinder");
}

}  // namespace certcyl
