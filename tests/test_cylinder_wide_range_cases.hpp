// Wide-range cylinder pairs with answers known by construction: operands of very different sizes
// (from subnormal radii to coordinates near 2^1000) in every contact type, exactly touching and
// moved 2^-k either side along the contact normal.
//
// Construction. Each base touching case of test_cylinder_cylinder_cases.hpp is multiplied by 20
// (every coordinate becomes an integer), translated so that a contact point P is the origin, and
// then a and b are scaled independently about P by powers of two (a homothety about a common
// point keeps P common and keeps the normal cones at P, so the supporting plane through P still
// separates weakly: the pair still touches with the same normal). Moving b by d n (n the unit
// normal from a to b) separates for d > 0; for d < 0 the point P + (d/2) n is interior to both,
// since n is interior to the normal cone of a at P and -n to that of b (every base case has
// n inside both cones, by inspection of the pictures), so the pair overlaps.
// Needles: in the caps-parallel and crossing-walls cases b is also stretched along its own axis
// (the contact point stays inside b's slab), so that b's length and radius differ by up to 2^2000.
// Binary64 variants keep every number a double (n has denominator 1 or 5 and d is a multiple of
// 5); rational variants also turn the pair by a rational rotation, translate it by 2^900 + 1/3,
// and divide by a 500-digit prime-free odd number.
#pragma once

#include <string>
#include <vector>

#include "test_cylinder_cylinder_cases.hpp"

namespace cctest {

struct WideCase {
  std::string name;
  Cylinder<Q> a, b;
  certcyl::Answer expected;
  bool binary64;  // every number is a double
};

inline Q two_power(long e) { return certcyl::detail::times_two_power(Q(1), e); }

// A contact point of each base case (the single contact point, or one point of the contact set).
inline Point3<Q> base_contact_point(const TouchingCase& c) {
  if (c.point_contact) return c.contact;
  if (c.type == "cap-cap") return {Q(1, 2), 0, 2};
  if (c.type == "cap-wall") return {0, 0, 2};
  return {1, 0, Q(3, 2)};  // wall-wall parallel: the contact segment x = 1, y = 0, z in [1, 2]
}

// Stretch c by t along its axis about the foot of the origin on the axis line (the contact
// point P is the origin: its foot, and so P's place in the slab, is kept), then scale it about
// the origin by s.
inline Cylinder<Q> scaled_stretched(const Cylinder<Q>& c, const Q& s, const Q& t) {
  const Vec3<Q> A = c.p1 - c.p0;
  const Point3<Q> f = c.p0 + (dot(Point3<Q>{0, 0, 0} - c.p0, A) / dot(A, A)) * A;
  return {s * (f + t * (c.p0 - f)), s * (f + t * (c.p1 - f)), s * c.radius};
}

// 10^500 + 1 (odd, not a power of two): divides everything in the rational variants.
inline Q big_denominator() {
  CGAL::Gmpz z;
  mpz_ui_pow_ui(z.mpz(), 10, 500);
  z += 1;
  return Q(z);
}

// Whether every number of c is a finite binary64 value, subnormals and large integers included
// (detail::exact_double leaves those out).
inline bool all_binary64(const Cylinder<Q>& c) {
  for (const Q* q : {&c.p0.x, &c.p0.y, &c.p0.z, &c.p1.x, &c.p1.y, &c.p1.z, &c.radius}) {
    const double x = CGAL::to_double(*q);
    if (!std::isfinite(x) || Q(x) != *q) return false;
  }
  return true;
}

inline std::vector<WideCase> wide_range_cases() {
  std::vector<WideCase> out;
  // (exponent of a's scale, exponent of b's scale, stretch of b along its axis)
  struct Sizes {
    long ea, eb, stretch;
  };
  const std::vector<Sizes> sizes = {{0, 0, 0},     {0, -60, 0},    {0, -600, 0},  {-600, 0, 0},  {900, -900, 0},
                                    {-1000, 0, 0}, {1000, -40, 0}, {0, -1040, 0}, {960, -1000, 0}, {0, -1030, 1000},
                                    {0, -300, 300}};
  const Rotation R = Rotation::from_quaternion(1, 2, 3, 4);
  const Q D = big_denominator();
  const Vec3<Q> far = {two_power(900) + Q(1, 3), -two_power(899), Q(7, 3)};
  for (const TouchingCase& base : base_touching_cases()) {
    const Point3<Q> P = base_contact_point(base);
    const Q twenty(20);
    const Vec3<Q> to_origin = Point3<Q>{0, 0, 0} - twenty * P;
    const Cylinder<Q> a0 = translate(scale(base.a, twenty), to_origin);
    const Cylinder<Q> b0 = translate(scale(base.b, twenty), to_origin);
    const bool stretchable = base.type == "cap-cap" || base.name == "wall-wall crossing";
    for (const Sizes& sz : sizes) {
      if (sz.stretch != 0 && !stretchable) continue;
      const Cylinder<Q> a = scaled_stretched(a0, two_power(sz.ea), Q(1));
      const Cylinder<Q> b = scaled_stretched(b0, two_power(sz.eb), two_power(sz.stretch));
      // d = 5 2^(e - k), 2^e the smaller of the two scales: small against both cylinders, so
      // that moving b by -d n does not carry it through a (every base cylinder has radius 20 and
      // length at least 40 after the factor 20); d n = 2^(e - k) (3, 0, 4) or 5 2^(e - k) e_x
      // (binary64 when the coordinates allow it); and d = 0.
      struct Move {
        Q d;
        certcyl::Answer expected;
        std::string label;
      };
      std::vector<Move> moves = {{Q(0), certcyl::Answer::touching, "0"}};
      for (long k : {2L, 20L, 45L, 80L}) {
        const Q d = Q(5) * two_power(std::min(sz.ea, sz.eb) - k);
        moves.push_back({d, certcyl::Answer::separated, "+2^-" + std::to_string(k)});
        moves.push_back({-d, certcyl::Answer::overlapping, "-2^-" + std::to_string(k)});
      }
      for (const auto& [d, expected, label] : moves) {
        const Cylinder<Q> bm = translate(b, d * base.normal);
        const std::string name = base.name + " ea=" + std::to_string(sz.ea) + " eb=" + std::to_string(sz.eb) +
                                 " stretch=" + std::to_string(sz.stretch) + " d=" + label;
        out.push_back({name, a, bm, expected, all_binary64(a) && all_binary64(bm)});
        // Turned, translated by far and divided by 10^500 + 1: rational strings of 500 digits.
        const auto shrink = [&D](const Q& x) { return x / D; };
        out.push_back({name + " turned", move(a, R, far).map(shrink), move(bm, R, far).map(shrink), expected, false});
      }
    }
  }
  return out;
}

}  // namespace cctest
