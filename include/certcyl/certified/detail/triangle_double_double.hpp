// certcyl/certified/detail/triangle_double_double.hpp -- the double-double stage of the
// triangle-cylinder decision: the decision of triangle_slab.hpp evaluated in QD's double-double
// arithmetic (the DD type of line_double_double.hpp) with a forward error bound derived from
// the same expression trees as the double filter's, for the inputs the double filter leaves
// undecided (a vertex, an edge or the face within a few ulps of the wall, a cap plane or a rim).
//
// Arithmetic. DD's addition and product each return (x op y)(1 + delta), |delta| <= 2^-100
// (line_double_double.hpp: Joldes, Muller and Popescu's bounds for QD's accurate addition and
// its product), given round-to-nearest, binary64 operations rounded once, and no underflow or
// overflow. The leaves a_i = v_i - P and A = p1 - p0 are exact (the two-difference of two
// doubles) and r is an input: every leaf is exact. The calculus of triangle_static_filter.hpp
// (derive_bounds) run with u = 2^-100 and exact leaves bounded by 1 gives, for each sign test of
// degree d, a constant e with |v^ - v| <= e M2^d when every leaf is at most M2 = 2^k in
// magnitude (scaling by a power of two commutes with the relative error model when nothing
// underflows or overflows). The sign is taken from the high part h of v^ when |h| > 4 e M2^d:
// then |v^| >= |h| (1 - 2^-53) > e M2^d >= |v^ - v| (the factor 4 also covers the rounding of the
// bound itself, a product of powers of two and e, exact since M2 >= 1).
//
// The window (checked before the stage runs): every input double is zero or of magnitude in
// [2^-24, 2^60]. Then every input, and every leaf, is an integer multiple of 2^-76 and at most
// 2^61 in magnitude. Sums, differences and roundings of multiples of 2^-g are multiples of 2^-g
// (rounding to 53 bits keeps a multiple of 2^-g: the value either has at most 53 bits from 2^-g
// up and is exact, or its ulp is a multiple of 2^-g), so is Dekker's splitting (a product by the
// integer 2^27 + 1, then differences), and a product of multiples of 2^-g and 2^-h is a
// multiple of 2^-(g + h). The tests have degree at most 14 in the leaves, so every double
// formed is a multiple of 2^-1064; one below 2^-1022 has at most 42 significant bits and is an
// exact subnormal: every operation rounds as with an unbounded exponent range. Magnitudes stay
// below b (2^61)^14 with b < 2^40 (the largest bound of the calculus), below 2^900, under QD's
// splitting threshold (2^996): no overflow, and QD's two_prod never rescales. Round-to-nearest
// is checked before the stage runs; line_double_double.hpp refuses FMA code generation and
// extended evaluation.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include "certcyl/certified/detail/line_double_double.hpp"
#include "certcyl/certified/detail/triangle_slab.hpp"
#include "certcyl/certified/detail/triangle_static_filter.hpp"
#include "certcyl/primitives.hpp"

namespace certcyl::detail {

struct DoubleDoubleUnit {
  static constexpr double value = 0x1p-100;
};

inline const StaticBounds& triangle_double_double_bounds() {
  static const StaticBounds bounds = derive_bounds(ErrorBoundIn<DoubleDoubleUnit>{1, 0, 1});
  return bounds;
}

// The sign of a double-double value is read from its high part (the proof above).
inline double leading_part(const DD& v) { return v.hi(); }

// The window of the proof: zero, or a magnitude in [2^-24, 2^60].
inline bool in_triangle_double_double_window(double x) {
  const double m = std::fabs(x);
  return m == 0 || (m >= 0x1p-24 && m <= 0x1p60);
}

// The double-double stage on binary64 input: the answer, or nothing if some sign was too close
// to zero, an input was outside the window or the rounding mode is not to nearest.
inline std::optional<SlabDecision> double_double_decide_triangle_cylinder(const Triangle<double>& T, const Cylinder<double>& C) {
  bool ok = in_triangle_double_double_window(C.radius);
  const auto take = [&ok](const Point3<double>& p) {
    ok &= in_triangle_double_double_window(p.x) && in_triangle_double_double_window(p.y) && in_triangle_double_double_window(p.z);
  };
  for (const Point3<double>& v : T.v) take(v);
  take(C.p0);
  take(C.p1);
  if (!ok || !rounding_to_nearest()) return std::nullopt;
  const auto difference = [](const Point3<double>& x, const Point3<double>& y) {
    return Vec3<DD>{dd_difference(x.x, y.x), dd_difference(x.y, y.y), dd_difference(x.z, y.z)};
  };
  const SlabInput<DD> in{{difference(T.v[0], C.p0), difference(T.v[1], C.p0), difference(T.v[2], C.p0)},
                         difference(C.p1, C.p0),
                         DD(C.radius),
                         DD(1.0)};
  // M2: a power of two >= 1 bounding every leaf (its high part, times 1 + 2^-53, is below the
  // next power of two above it).
  double m = 1;
  const auto bound = [&m](const Vec3<DD>& v) {
    for (const DD* x : {&v.x, &v.y, &v.z}) m = std::max(m, std::fabs(x->hi()));
  };
  for (const Vec3<DD>& a : in.a) bound(a);
  bound(in.A);
  m = std::max(m, C.radius);
  int exponent = 0;
  std::frexp(m, &exponent);  // m < 2^exponent
  const double M2 = std::ldexp(1.0, exponent);
  try {
    // Factor 4: the bound of the proof above.
    return decide_slab(in, BoundedSigns<DD>(triangle_double_double_bounds(), M2, 4));
  } catch (const StaticUndecided&) {
    return std::nullopt;
  }
}

}  // namespace certcyl::detail
