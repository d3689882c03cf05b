// certcyl/certified/detail/line_shape.hpp -- the sign skeleton of a line against a solid
// cylinder, generic over a number type that decides signs exactly or refuses (Interval_nt,
// Gmpq).
//
// Both cylinder kinds reduce to one form (design note, section 3), division-free:
//   tube  a t^2 + 2 b t + c <= 0,    disc = b^2 - a c given in cancellation-free form
//   slab  0 <= sw + t sd <= H
// Circular (P = p0, A = p1 - p0, w = O - P, u = w x A, v = d x A):
//   a = v.v, b = u.v, c = u.u - r^2 A.A, disc = A.A (r^2 a - (A.(w x d))^2),
//   sw = w.A, sd = d.A, H = A.A.                       (degrees: a 4, b 4, c 4, disc 6)
// Elliptic (base C, M = [a b c], D = det M, adj(M) rows R1 = b x c, R2 = c x a, R3 = a x b,
// U = adj(M)(O - C) = D M^-1 (O - C), V = adj(M) d):
//   a = V1^2 + V2^2, b = U1 V1 + U2 V2, c = U1^2 + U2^2 - D^2,
//   disc = D^2 a - (U1 V2 - U2 V1)^2   (Lagrange identity),
//   sw = D U3, sd = D V3, H = D^2.                     (degrees: a 4, b 5, c 6, disc 8)
//
// The skeleton: every bound of the parameter interval is symbolic (a tube root, a cap plane,
// t = 0 or t = 1) and every decision is the sign of p + q sqrt(disc) with p, q in NT, taken by
// squaring (detail::sign_of_root_form). So the same code runs in intervals (it throws
// CGAL::Uncertain_conversion_exception when a sign is not decided, ties included) and in Gmpq
// (always decides). Degenerate states are exact zero tests: a = 0 (line parallel to the
// axis), sd = 0 (line parallel to the cap planes), disc = 0 (tangent), c = 0 with a = 0 (line
// on the wall), sw in {0, H} with sd = 0 (line in a cap plane).
#pragma once

#include <optional>
#include <stdexcept>
#include <type_traits>

#include "certcyl/answer.hpp"
#include "certcyl/certified/detail/quadratic_number.hpp"
#include "certcyl/line_result.hpp"
#include "certcyl/number_traits.hpp"
#include "certcyl/primitives.hpp"

namespace certcyl::detail {

template <class NT>
struct LineQuadric {
  NT a, b, c, disc, sw, sd, H;
};

// An input number (double or Rational) in NT: exact for double into Interval or Gmpq.
template <class NT, class In>
NT input_to(const In& x) {
  if constexpr (std::is_same_v<In, Rational>) {
    return nt::from_rational<NT>(x);
  } else {
    static_assert(std::is_same_v<In, double>, "inputs are double or Rational");
    return NT(x);
  }
}

template <class NT, class In>
Vec3<NT> input_to(const Vec3<In>& v) {
  return {input_to<NT>(v.x), input_to<NT>(v.y), input_to<NT>(v.z)};
}

template <class NT>
LineQuadric<NT> line_quadric(const Vec3<NT>& O, const Vec3<NT>& d, const Cylinder<NT>& cyl) {
  const Vec3<NT> A = cyl.axis();
  const Vec3<NT> w = O - cyl.p0;
  const Vec3<NT> u = cross(w, A), v = cross(d, A);
  const NT AA = squared_length(A);
  const NT r2AA = cyl.radius * cyl.radius * AA;
  const NT a = squared_length(v);
  const NT e = dot(A, cross(w, d));
  return {a, dot(u, v), NT(squared_length(u) - r2AA), NT(AA * (cyl.radius * cyl.radius * a - e * e)), dot(w, A), dot(d, A), AA};
}

template <class NT>
LineQuadric<NT> line_quadric(const Vec3<NT>& O, const Vec3<NT>& d, const EllipticCylinder<NT>& e) {
  const Vec3<NT> w = O - e.base;
  const Vec3<NT> R1 = cross(e.b, e.c), R2 = cross(e.c, e.a), R3 = cross(e.a, e.b);
  const NT D = dot(e.a, R1);
  const NT U1 = dot(R1, w), U2 = dot(R2, w), U3 = dot(R3, w);
  const NT V1 = dot(R1, d), V2 = dot(R2, d), V3 = dot(R3, d);
  const NT D2 = D * D;
  const NT a = V1 * V1 + V2 * V2;
  const NT cr = U1 * V2 - U2 * V1;
  return {a, NT(U1 * V1 + U2 * V2), NT(U1 * U1 + U2 * U2 - D2), NT(D2 * a - cr * cr), NT(D * U3), NT(D * V3), D2};
}

// The symbolic bounds of the parameter interval.
enum class BoundKind : unsigned char { tube_lo, tube_hi, cap0, cap1, range_lo, range_hi };

enum class TubeState : unsigned char { empty, point, interval, all_open, all_boundary };
enum class SlabState : unsigned char { empty, interval, all_open, plane0, plane1 };

// What the exact endpoints are built from: NT-free, so the interval filter can return it.
struct LineShape {
  Answer answer = Answer::separated;
  BoundKind in = BoundKind::range_lo, out = BoundKind::range_lo;
  LineFeature in_feature = LineFeature::none, in_surface = LineFeature::none;
  LineFeature out_feature = LineFeature::none, out_surface = LineFeature::none;
  TubeState tube = TubeState::empty;
  SlabState slab = SlabState::empty;
};

inline LineFeature combine_surface(bool wall, bool cap0, bool cap1) {
  if (wall) return cap0 ? LineFeature::rim0 : (cap1 ? LineFeature::rim1 : LineFeature::wall);
  return cap0 ? LineFeature::cap0 : (cap1 ? LineFeature::cap1 : LineFeature::none);
}

// The value of each bound as p + q sqrt(disc), compared by signs only.
template <class NT>
class BoundValues {
 public:
  BoundValues(const LineQuadric<NT>& q, TubeState tube, SlabState slab) : q_(q), tube_(tube) {
    if (tube == TubeState::point || tube == TubeState::interval) {
      centre_ = -q.b / q.a;
      half_ = nt::constant<NT>(1) / q.a;  // the roots are centre -/+ half * sqrt(disc)
    }
    if (slab == SlabState::interval) {
      cap0_ = -q.sw / q.sd;
      cap1_ = (q.H - q.sw) / q.sd;
    }
  }

  // Sign of value(x) - value(y).
  CGAL::Sign compare(BoundKind x, BoundKind y) const {
    if (x == y) return CGAL::ZERO;
    // Pairs whose difference is known symbolically (an interval does not know that
    // centre - centre = 0): the two roots differ by 2 half sqrt(disc), the caps by H / sd.
    if ((x == BoundKind::tube_lo && y == BoundKind::tube_hi) || (x == BoundKind::tube_hi && y == BoundKind::tube_lo)) {
      if (tube_ == TubeState::point) return CGAL::ZERO;
      return x == BoundKind::tube_lo ? CGAL::NEGATIVE : CGAL::POSITIVE;
    }
    if ((x == BoundKind::cap0 && y == BoundKind::cap1) || (x == BoundKind::cap1 && y == BoundKind::cap0)) {
      const CGAL::Sign s = nt::sign(q_.sd);  // cap1 - cap0 = H / sd, H > 0
      return x == BoundKind::cap1 ? s : CGAL::opposite(s);
    }
    const Parts vx = parts(x), vy = parts(y);
    return sign_of_root_form(NT(vx.p - vy.p), NT(vx.q - vy.q), q_.disc);
  }

 private:
  struct Parts {
    NT p, q;  // value = p + q sqrt(disc)
  };

  Parts parts(BoundKind k) const {
    const NT zero = nt::constant<NT>(0);
    switch (k) {
      case BoundKind::tube_lo: return {centre_, tube_ == TubeState::interval ? NT(-half_) : zero};
      case BoundKind::tube_hi: return {centre_, tube_ == TubeState::interval ? half_ : zero};
      case BoundKind::cap0: return {cap0_, zero};
      case BoundKind::cap1: return {cap1_, zero};
      case BoundKind::range_lo: return {zero, zero};
      case BoundKind::range_hi: return {nt::constant<NT>(1), zero};
    }
    return {zero, zero};
  }

  const LineQuadric<NT>& q_;
  TubeState tube_;
  NT centre_{}, half_{}, cap0_{}, cap1_{};
};

// The sign source of the skeleton for a quadric in a number type NT (Interval_nt, Gmpq): the
// signs of its coefficients, and BoundValues for the comparisons of bounds. The semi-static
// double stage (certified/detail/line_static_filter.hpp) offers the same interface.
template <class NT>
class QuadricSigns {
 public:
  explicit QuadricSigns(const LineQuadric<NT>& q) : q_(q) {}
  CGAL::Sign sign_a() const { return nt::sign(q_.a); }
  CGAL::Sign sign_c() const { return nt::sign(q_.c); }
  CGAL::Sign sign_disc() const { return nt::sign(q_.disc); }
  CGAL::Sign sign_sd() const { return nt::sign(q_.sd); }
  CGAL::Sign sign_sw() const { return nt::sign(q_.sw); }
  CGAL::Sign sign_H_minus_sw() const { return nt::sign(NT(q_.H - q_.sw)); }
  BoundValues<NT> bounds(TubeState tube, SlabState slab) const { return BoundValues<NT>(q_, tube, slab); }
  // NT either decides every sign or throws (intervals): it never leaves one undecided.
  static constexpr bool undecided() { return false; }

 private:
  const LineQuadric<NT>& q_;
};

// The skeleton over a sign source `s` (QuadricSigns<NT> or the static stage). A source that
// can give up (`undecided()`) makes the result meaningless; it is then stopped at the next
// step and the caller discards it.
template <class Signs>
LineShape line_shape_from(Signs& s, LineRange range) {
  LineShape shape;
  // Step 1: the tube's parameter set {a t^2 + 2 b t + c <= 0}.
  if (s.sign_a() == CGAL::ZERO) {
    // else: direction parallel to the axis; b = 0 and the set is all t or nothing.
    const CGAL::Sign sc = s.sign_c();
    shape.tube = sc == CGAL::POSITIVE ? TubeState::empty : (sc == CGAL::ZERO ? TubeState::all_boundary : TubeState::all_open);
  } else {
    const CGAL::Sign sd = s.sign_disc();
    shape.tube = sd == CGAL::NEGATIVE ? TubeState::empty : (sd == CGAL::ZERO ? TubeState::point : TubeState::interval);
  }
  if (shape.tube == TubeState::empty || s.undecided()) return shape;

  // Step 2: the slab's parameter set {0 <= sw + t sd <= H}.
  const CGAL::Sign s_sd = s.sign_sd();
  if (s_sd == CGAL::ZERO) {
    const CGAL::Sign below = s.sign_sw(), above = s.sign_H_minus_sw();
    if (below == CGAL::NEGATIVE || above == CGAL::NEGATIVE) return shape;
    shape.slab = below == CGAL::ZERO ? SlabState::plane0 : (above == CGAL::ZERO ? SlabState::plane1 : SlabState::all_open);
  } else {
    shape.slab = SlabState::interval;
  }
  if (s.undecided()) return shape;
  if (shape.tube != TubeState::point && shape.tube != TubeState::interval && shape.slab != SlabState::interval)
    throw std::logic_error("line_shape: zero direction");  // a = 0 and sd = 0 imply d = 0

  // Step 3: lower bound = max of the candidate lower bounds, upper = min of the upper ones.
  // Ties keep the earlier candidate: the range first (so a clipped end is reported as such).
  auto&& values = s.bounds(shape.tube, shape.slab);
  const bool has_tube = shape.tube == TubeState::point || shape.tube == TubeState::interval;
  const bool has_slab = shape.slab == SlabState::interval;
  const bool has_range_lo = range != LineRange::line, has_range_hi = range == LineRange::segment;
  const BoundKind slab_lo = s_sd == CGAL::POSITIVE ? BoundKind::cap0 : BoundKind::cap1;
  const BoundKind slab_hi = s_sd == CGAL::POSITIVE ? BoundKind::cap1 : BoundKind::cap0;

  BoundKind lower{}, upper{};
  bool have_lower = false, have_upper = false;
  auto take = [&](bool present, BoundKind k, BoundKind& best, bool& have, CGAL::Sign better) {
    if (!present) return;
    if (!have || values.compare(k, best) == better) best = k, have = true;
  };
  take(has_range_lo, BoundKind::range_lo, lower, have_lower, CGAL::POSITIVE);
  take(has_slab, slab_lo, lower, have_lower, CGAL::POSITIVE);
  take(has_tube, BoundKind::tube_lo, lower, have_lower, CGAL::POSITIVE);
  take(has_range_hi, BoundKind::range_hi, upper, have_upper, CGAL::NEGATIVE);
  take(has_slab, slab_hi, upper, have_upper, CGAL::NEGATIVE);
  take(has_tube, BoundKind::tube_hi, upper, have_upper, CGAL::NEGATIVE);
  if (s.undecided()) return shape;
  if (!have_upper) throw std::logic_error("line_shape: unbounded interval");  // a ray along the axis is bounded by the slab

  // Step 4: empty, a point or an interval.
  const CGAL::Sign width = values.compare(upper, lower);
  if (width == CGAL::NEGATIVE || s.undecided()) return shape;
  shape.in = lower;
  shape.out = upper;

  // Step 5: the features of each endpoint, by exact ties with the other bounds.
  auto describe = [&](BoundKind k, LineFeature& feature, LineFeature& surface) {
    auto equals = [&](BoundKind other) { return values.compare(k, other) == CGAL::ZERO; };
    const bool wall = shape.tube == TubeState::all_boundary || (has_tube && (equals(BoundKind::tube_lo) || equals(BoundKind::tube_hi)));
    const bool cap0 = shape.slab == SlabState::plane0 || (has_slab && equals(BoundKind::cap0));
    const bool cap1 = shape.slab == SlabState::plane1 || (has_slab && equals(BoundKind::cap1));
    surface = combine_surface(wall, cap0, cap1);
    if (has_range_lo && equals(BoundKind::range_lo))
      feature = LineFeature::origin;
    else if (has_range_hi && equals(BoundKind::range_hi))
      feature = LineFeature::end;
    else
      feature = surface;
  };
  describe(lower, shape.in_feature, shape.in_surface);
  describe(upper, shape.out_feature, shape.out_surface);

  // Step 6: overlapping iff the open sets meet: a proper interval, and neither the tube nor the
  // slab reduced to its boundary (the range's open part is never empty).
  const bool tube_open = shape.tube == TubeState::interval || shape.tube == TubeState::all_open;
  const bool slab_open = shape.slab == SlabState::interval || shape.slab == SlabState::all_open;
  shape.answer = (width == CGAL::POSITIVE && tube_open && slab_open) ? Answer::overlapping : Answer::touching;
  return shape;
}

template <class NT>
LineShape line_shape(const LineQuadric<NT>& q, LineRange range) {
  QuadricSigns<NT> s(q);
  return line_shape_from(s, range);
}

// The exact values of the bounds (q in Gmpq, the shape decided for it). The two tube roots
// share their normal form: it is made once, for the upper root, and negated for the lower.
class BoundValuesExact {
 public:
  BoundValuesExact(const LineQuadric<Rational>& q, TubeState tube) : q_(q), tube_(tube) {}

  QuadraticNumber operator()(BoundKind k) {
    switch (k) {
      case BoundKind::tube_lo:
      case BoundKind::tube_hi: {
        if (!root_) {
          centre_ = -q_.b / q_.a;
          root_ = tube_ == TubeState::point ? QuadraticNumber{centre_, 0, 0}
                                            : QuadraticNumber::make(centre_, Rational(1) / q_.a, q_.disc);
        }
        if (k == BoundKind::tube_hi || tube_ == TubeState::point) return *root_;
        // else: the lower root; a perfect-square radicand has made the upper one rational
        if (root_->is_rational()) return QuadraticNumber::make(centre_, Rational(-1) / q_.a, q_.disc);
        return {root_->alpha, Rational(-root_->beta), root_->gamma};
      }
      case BoundKind::cap0: return {Rational(-q_.sw / q_.sd), 0, 0};
      case BoundKind::cap1: return {Rational((q_.H - q_.sw) / q_.sd), 0, 0};
      case BoundKind::range_lo: return {0, 0, 0};
      case BoundKind::range_hi: return {1, 0, 0};
    }
    return {};
  }

 private:
  const LineQuadric<Rational>& q_;
  TubeState tube_;
  std::optional<QuadraticNumber> root_;  // the upper root
  Rational centre_;
};

inline QuadraticNumber bound_value(BoundKind k, const LineQuadric<Rational>& q, TubeState tube) {
  return BoundValuesExact(q, tube)(k);
}

}  // namespace certcyl::detail
