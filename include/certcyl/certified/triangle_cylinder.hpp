// certcyl/certified/triangle_cylinder.hpp -- certified test-intersection of a triangle and a
// closed solid cylinder, with no square root and no orthonormal frame.
//
// Semantics (design note, sections 1 and 3): the triangle is the closed convex hull of its
// three vertices (a degenerate triangle is a segment or a point); the cylinder is the closed
// solid {X : 0 <= s(X) <= A.A, q(X) <= R}, with P = p0, A = p1 - p0, R = r^2 A.A,
// s(X) = (X-P).A and q(X) = |(X-P) x A|^2. The answer is
//   overlapping  the triangle meets the open interior of the cylinder;
//   touching     it meets the cylinder but not its open interior;
//   separated    no common point.
// This is the Eberly seed's query ("Intersection of a Triangle and a Cylinder", section 2)
// reformulated without the U, V frame: the triangle is clipped to the slab 0 <= s <= A.A
// with rational clip points, and the minimum of q over the clipped polygon is compared with R
// by sign tests (detail/triangle_slab.hpp has the outline and the degrees).
//
// Two entry points:
//   classify_triangle_cylinder(T, C, counter)   the answer only, filtered in four stages:
//       a semi-static double filter (detail/triangle_static_filter.hpp: each sign decided in
//       double when it exceeds an error bound derived from its expression tree; binary64 input,
//       or Rational input whose numbers are all binary64) in which each sign the double bound
//       leaves undecided is evaluated again, that test alone, with proved bounds
//       (detail/triangle_double_double.hpp; binary64 input of magnitudes 0 or 2^-24 .. 2^60):
//       a test on a crossing with a cap plane through its form in the vertices' values (those
//       values in double, then in double-double where needed), any test in double-double on
//       its own tree; the whole decision in double-double where the double stage's range is
//       left), then Interval_nt, then exact arithmetic (Mpzf for
//       binary64 input, Gmpq otherwise). A TriangleFilterStages counter
//       records which stage decided; a FilterCounter counts the exact fall-backs.
//   certified_triangle_cylinder(T, C)           the answer (filtered, as above) and its
//       certificate, checked exactly before it is returned (check_triangle_cylinder_certificate):
//     overlapping  a rational point of the triangle strictly inside the cylinder (an interior
//                  vertex; or, for binary64 input, a point v0 + alpha e1 + beta e2 with dyadic
//                  alpha, beta >= 0, alpha + beta <= 1 guessed in double; or the exact
//                  construction from X* below);
//     touching     a rational point of the triangle on the cylinder's boundary (X*), the pair
//                  of features that meet there, and why no point is interior: the triangle lies
//                  on the outer side of a cap plane, or a normal n, n.A = 0, n != 0, with
//                  n.(Y - P) >= r |n| for every point Y of the clipped triangle (so the open
//                  tube is on the other side of the plane n.(Y - P) = r |n|);
//     separated    beyond a cap plane (all s_i < 0 or all s_i > A.A), or a normal n, n.A = 0,
//                  with n.(Y - P) > r |n| for every point Y of the clipped triangle. For binary64
//                  input n = g A.A - (g.A) A with g guessed in double; otherwise, and whenever
//                  the guess fails its check, n = X* - (foot of X* on the axis).
//   X* is the point of T ∩ slab nearest the axis line (rational: a vertex, a clip point, the
//   foot of a perpendicular on an edge, or the point where the axis pierces the triangle). It
//   is computed (fields closest, squared_distance) for touching answers and whenever a cheap
//   certificate is not available.
//
// Both entry points take Rational operands or double ones (each double taken as the exact
// rational it denotes). They validate their operands as the command does (primitives.hpp: the
// cylinder's radius > 0 and p0 != p1, finite doubles; any triangle is valid, degenerate ones
// included) and throw InvalidInput naming "triangle" or "cylinder".
//
// Degenerate cases handled: degenerate triangles (segment, point), triangles in a cap plane,
// edges parallel to the axis, triangles whose plane contains the axis, contact on a rim.
#pragma once

#include <CGAL/FPU.h>
#include <CGAL/Gmpq.h>
#include <CGAL/Interval_nt.h>
#include <CGAL/Mpzf.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

#include "certcyl/answer.hpp"
#include "certcyl/certified/detail/triangle_slab.hpp"
#include "certcyl/certified/detail/triangle_double_double.hpp"
#include "certcyl/certified/detail/triangle_static_filter.hpp"
#include "certcyl/filtered.hpp"
#include "certcyl/number_traits.hpp"
#include "certcyl/predicates/point_in_cylinder.hpp"
#include "certcyl/primitives.hpp"

namespace certcyl {

// Which stage of the filtered decision decided, per call.
struct TriangleFilterStages {
  std::uint64_t calls = 0;
  std::uint64_t semi_static = 0;    // the double filter with static error bounds
  std::uint64_t double_double = 0;  // the same decision in double-double, with its error bounds
  std::uint64_t interval = 0;       // Interval_nt
  std::uint64_t exact = 0;        // Mpzf or Gmpq

  TriangleFilterStages& operator+=(const TriangleFilterStages& o) {
    calls += o.calls;
    semi_static += o.semi_static;
    double_double += o.double_double;
    interval += o.interval;
    exact += o.exact;
    return *this;
  }
};

struct TriangleCylinderResult {
  // The smallest feature of the triangle containing the witness: vertex {i}, edge {i, j}, face.
  enum class TriangleFeature { vertex, edge, face };
  // The boundary feature of the cylinder at the witness: cap = the open disk in a cap plane,
  // rim = its boundary circle, wall = the lateral surface strictly between the cap planes.
  enum class CylinderFeature { wall, cap0, cap1, rim0, rim1 };
  enum class Separation { none, beyond_cap0, beyond_cap1, outside_tube };

  Answer answer = Answer::undecided;

  // overlapping: a point of T strictly inside; touching: a point of T on the boundary.
  std::optional<Point3<Rational>> witness;
  // touching: the features meeting at the witness.
  TriangleFeature triangle_feature = TriangleFeature::face;
  std::array<int, 2> triangle_indices{-1, -1};
  CylinderFeature cylinder_feature = CylinderFeature::wall;

  // separated: why.
  Separation separation = Separation::none;

  // X*, the point of T ∩ slab nearest the axis line, and its squared distance to the axis:
  // set for touching answers and where the exact construction ran (see the header comment).
  std::optional<Point3<Rational>> closest;
  Rational squared_distance;
  // separated outside_tube, touching through the wall or a rim: n with n.A = 0 and
  // n.(Y - P) >= r |n| (> for separated) on T ∩ slab. From X*: n = X* - (foot of X*).
  Vec3<Rational> normal{0, 0, 0};

  // The filtered decision: 1 call, and whether it needed exact arithmetic; and which stage.
  FilterCounter counter;
  TriangleFilterStages stages;
};

inline const char* to_string(TriangleCylinderResult::TriangleFeature f) {
  using F = TriangleCylinderResult::TriangleFeature;
  return f == F::vertex ? "vertex" : (f == F::edge ? "edge" : "face");
}
inline const char* to_string(TriangleCylinderResult::CylinderFeature f) {
  using F = TriangleCylinderResult::CylinderFeature;
  switch (f) {
    case F::wall: return "wall";
    case F::cap0: return "cap0";
    case F::cap1: return "cap1";
    case F::rim0: return "rim0";
    case F::rim1: return "rim1";
  }
  return "?";
}
inline const char* to_string(TriangleCylinderResult::Separation s) {
  using S = TriangleCylinderResult::Separation;
  switch (s) {
    case S::none: return "none";
    case S::beyond_cap0: return "beyond_cap0";
    case S::beyond_cap1: return "beyond_cap1";
    case S::outside_tube: return "outside_tube";
  }
  return "?";
}

namespace detail {

// ---- the filtered decision: static double stage, Interval_nt, exact --------------------------

// An exact input value in a certified number type: Interval_nt encloses, Gmpq and Mpzf are exact.
template <class NT, class In>
NT certified_image(const In& x) {
  if constexpr (std::is_same_v<NT, In>) {
    return x;
  } else if constexpr (std::is_same_v<In, double>) {
    return NT(x);  // binary64 is exact in Interval_nt, Gmpq and Mpzf
  } else {
    static_assert(std::is_same_v<NT, Interval>, "certified_image: Rational input goes to Interval or Gmpq");
    return NT(nt::to_interval(x));
  }
}

template <class NT, class In>
SlabDecision decide_in(const Triangle<In>& T, const Cylinder<In>& C) {
  const auto f = [](const In& x) { return certified_image<NT>(x); };
  return decide_slab(slab_input(T.map(f), C.map(f)), ExactSigns{});
}

// Interval_nt, then the exact type (Mpzf for binary64 input: the decision is division-free).
template <class Exact, class In>
SlabDecision decide_interval_then_exact(const Triangle<In>& T, const Cylinder<In>& C, TriangleFilterStages& stages) {
  {
    CGAL::Protect_FPU_rounding<true> upward;
    try {
      const SlabDecision d = decide_in<Interval>(T, C);
      ++stages.interval;
      return d;
    } catch (const CGAL::Uncertain_conversion_exception&) {
      // else: the intervals could not decide; fall through to exact arithmetic.
    }
  }
  ++stages.exact;
  return decide_in<Exact>(T, C);
}

inline SlabDecision decide_filtered(const Triangle<double>& T, const Cylinder<double>& C, TriangleFilterStages& stages) {
  ++stages.calls;
  // Double, with each sign it cannot decide evaluated again in double-double on its own.
  const EscalatedTriangleDecision e = escalating_decide_triangle_cylinder(T, C);
  if (e.decision) {
    ++(e.escalated ? stages.double_double : stages.semi_static);
    return *e.decision;
  }
  // Outside the static stage's range, the whole decision in double-double. (Inside it, the
  // whole double-double decision would stop at the same sign: same trees, same bounds.)
  if (!e.in_static_range)
    if (const std::optional<SlabDecision> d = double_double_decide_triangle_cylinder(T, C)) {
      ++stages.double_double;
      return *d;
    }
  return decide_interval_then_exact<CGAL::Mpzf>(T, C, stages);
}

// x as a binary64 value, if it is one (exact test on the GMP representation, no allocation).
inline std::optional<double> exact_binary64(const Rational& x) {
  const mpq_srcptr q = x.mpq();
  const mpz_srcptr num = mpq_numref(q), den = mpq_denref(q);
  if (num->_mp_size == 0) return 0.0;
  // Fast path, reading the limbs: |num| < 2^64, den = 2^k < 2^64 (every binary64 value of
  // magnitude in [2^-63, 2^64)). The value is num 2^-k, both factors exact in double when
  // num has at most 53 significant bits.
  if ((num->_mp_size == 1 || num->_mp_size == -1) && den->_mp_size == 1 && sizeof(mp_limb_t) == 8) {
    const auto n = static_cast<std::uint64_t>(num->_mp_d[0]);
    const auto d = static_cast<std::uint64_t>(den->_mp_d[0]);
    if ((d & (d - 1)) != 0) return std::nullopt;  // not a power of two
    if (64 - std::countl_zero(n) - std::countr_zero(n) > 53) return std::nullopt;
    const int k = std::countr_zero(d);
    const double scale = std::bit_cast<double>(static_cast<std::uint64_t>(1023 - k) << 52);  // 2^-k
    const double magnitude = static_cast<double>(n) * scale;
    return num->_mp_size < 0 ? -magnitude : magnitude;
  }
  // den = 2^k, and num's significant bits fit in 53 within binary64's exponent range.
  const auto k = static_cast<long>(mpz_scan1(den, 0));
  if (static_cast<long>(mpz_sizeinbase(den, 2)) != k + 1) return std::nullopt;
  const auto low = static_cast<long>(mpz_scan1(num, 0));
  const auto high = static_cast<long>(mpz_sizeinbase(num, 2)) - 1;
  if (high - low >= 53 || low - k < -1074 || high - k > 1023) return std::nullopt;
  // num fits in 53 significant bits, so mpz_get_d is exact, and so is the scaling by 2^-k
  // (the lowest bit of the value is 2^(low - k) >= 2^-1074). No division (mpq_get_d divides).
  return k == 0 ? mpz_get_d(num) : std::ldexp(mpz_get_d(num), static_cast<int>(-k));
}

// The type of a primitive's image in double. (A named function object, not a lambda in the
// return type: clang 14 crashes generating code for a lambda in an unevaluated operand here.)
struct AsDouble {
  double operator()(const Rational&) const { return 0.0; }
};

template <class Primitive>
std::optional<decltype(std::declval<Primitive>().map(AsDouble{}))> exact_binary64(const Primitive& p) {
  bool ok = true;
  const auto image = p.map([&ok](const Rational& x) {
    const std::optional<double> d = exact_binary64(x);
    ok &= d.has_value();
    return d.value_or(0.0);
  });
  if (!ok) return std::nullopt;
  return image;
}

inline SlabDecision decide_filtered(const Triangle<Rational>& T, const Cylinder<Rational>& C,
                                    TriangleFilterStages& stages) {
  const auto Td = exact_binary64(T);
  const auto Cd = exact_binary64(C);
  if (Td && Cd) return decide_filtered(*Td, *Cd, stages);
  ++stages.calls;
  return decide_interval_then_exact<Rational>(T, C, stages);
}

inline FilterCounter as_filter_counter(const TriangleFilterStages& s) { return {s.calls, s.exact}; }

// ---- field-generic constructions: run in double for a guess, in Gmpq exactly ----------------

template <class NT>
Vec3<NT> relative_point(const SlabPoint<NT>& p) {
  return p.X / p.w;
}

// X* - P: the point of S nearest the axis line (S not empty), by the same case split as the
// sign tests. In double this is only a guess.
template <class NT>
Vec3<NT> nearest_to_axis(const SlabPolygon<NT>& S, const SlabInput<NT>& in) {
  const Vec3<NT>& A = in.A;
  if (axis_pierces(S, A, ExactSigns{})) {
    // The axis line crosses the plane of S (its projection along A is not degenerate, so the
    // plane's normal N has N.A != 0) at t A, t = N.a0 / N.A.
    const Vec3<NT> N = cross(Vec3<NT>(in.a[1] - in.a[0]), Vec3<NT>(in.a[2] - in.a[0]));
    const NT NA = dot(N, A);
    if (nt::sign(NA) != CGAL::ZERO) return (dot(N, in.a[0]) / NA) * A;
    if constexpr (NumberTraits<NT>::is_exact) throw std::logic_error("triangle_cylinder: pierced polygon parallel to the axis");
    // else: a rounded guess went wrong; any point of S will do as a guess.
    return relative_point(S.p[0]);
  }
  const auto q = [&](const Vec3<NT>& x) { return squared_length(cross(x, A)); };
  Vec3<NT> best = relative_point(S.p[0]);
  NT best_q = q(best);
  const int edges = S.n == 1 ? 0 : (S.n == 2 ? 1 : S.n);
  for (int i = 0; i < edges; ++i) {
    const Vec3<NT> a = relative_point(S.p[i]);
    const Vec3<NT> b = relative_point(S.p[(i + 1) % S.n]);
    const Vec3<NT> u = cross(a, A), v = cross(Vec3<NT>(b - a), A);
    const NT uv = dot(u, v), vv = dot(v, v);
    Vec3<NT> x = a;
    if (nt::sign(uv) == CGAL::NEGATIVE) {
      // else: the minimum is at a (slope >= 0 there).
      if (nt::sign(NT(uv + vv)) != CGAL::POSITIVE) x = b;
      else x = a + (-uv / vv) * Vec3<NT>(b - a);
    }
    const NT qx = q(x);
    if (nt::compare(qx, best_q) == CGAL::SMALLER) best = x, best_q = qx;
  }
  return best;
}

// A point of T strictly inside the cylinder, from x in T ∩ slab (relative to P) with q(x) < R,
// when T crosses the open slab. c, the centroid of S's vertices, is in T and strictly between
// the cap planes; q is convex, so on y = x + lambda (c - x), q(y) <= q(x) + lambda (q(c) - q(x)),
// and lambda = (R - q(x)) / (2 (q(c) - q(x))) (or c itself if q(c) < R) gives q(y) < R, with y
// strictly inside the slab because lambda > 0. One construction, no search.
template <class NT>
Vec3<NT> interior_witness(const Vec3<NT>& x, const SlabPolygon<NT>& S, const SlabInput<NT>& in) {
  const Vec3<NT>& A = in.A;
  const NT AA = dot(A, A);
  const NT R = slab_radius_term(in.r, AA);
  const auto q = [&](const Vec3<NT>& y) { return squared_length(cross(y, A)); };
  const NT sx = dot(x, A);
  if (nt::sign(sx) == CGAL::POSITIVE && nt::compare(sx, AA) == CGAL::SMALLER &&
      nt::compare(q(x), R) == CGAL::SMALLER)
    return x;
  Vec3<NT> c = relative_point(S.p[0]);
  for (int i = 1; i < S.n; ++i) c += relative_point(S.p[i]);
  c = c / nt::constant<NT>(S.n);
  const NT qx = q(x), qc = q(c);
  if (nt::compare(qc, R) == CGAL::SMALLER) return c;
  const NT lambda = (R - qx) / (nt::constant<NT>(2) * (qc - qx));
  return x + lambda * Vec3<NT>(c - x);
}

// ---- ring-generic exact checks ------------------------------------------------------------

template <class NT>
bool on_segment(const Vec3<NT>& x, const Vec3<NT>& a, const Vec3<NT>& b) {
  const Vec3<NT> d = b - a, w = x - a;
  const Vec3<NT> c = cross(d, w);
  if (!nt::is_zero(c.x) || !nt::is_zero(c.y) || !nt::is_zero(c.z)) return false;
  const NT t = dot(w, d);
  return !nt::is_negative(t) && !nt::is_negative(NT(dot(d, d) - t));
}

template <class NT>
bool same_point(const Vec3<NT>& a, const Vec3<NT>& b) {
  return nt::is_zero(NT(a.x - b.x)) && nt::is_zero(NT(a.y - b.y)) && nt::is_zero(NT(a.z - b.z));
}

// The smallest feature of T containing x, or nothing if x is not in T. Exact for exact NT.
template <class NT>
std::optional<std::pair<TriangleCylinderResult::TriangleFeature, std::array<int, 2>>> locate_on_triangle(
    const Vec3<NT>& x, const Triangle<NT>& T) {
  using F = TriangleCylinderResult::TriangleFeature;
  for (int i = 0; i < 3; ++i)
    if (same_point(x, T.v[i])) return std::pair{F::vertex, std::array<int, 2>{i, -1}};
  for (auto [i, j] : {std::pair{0, 1}, std::pair{1, 2}, std::pair{0, 2}})
    if (!same_point(T.v[i], T.v[j]) && on_segment(x, T.v[i], T.v[j]))
      return std::pair{F::edge, std::array<int, 2>{i, j}};
  const Vec3<NT> N = cross(Vec3<NT>(T.v[1] - T.v[0]), Vec3<NT>(T.v[2] - T.v[0]));
  if (nt::is_zero(dot(N, N)) || !nt::is_zero(dot(N, Vec3<NT>(x - T.v[0])))) return std::nullopt;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    if (nt::is_negative(dot(N, cross(Vec3<NT>(T.v[j] - T.v[i]), Vec3<NT>(x - T.v[i]))))) return std::nullopt;
  }
  return std::pair{F::face, std::array<int, 2>{-1, -1}};
}

// The certificate's numbers in a ring NT.
template <class NT>
struct CertificateData {
  Triangle<NT> T;
  Cylinder<NT> C;
  std::optional<Vec3<NT>> witness;
  Vec3<NT> normal;
};

// The check of check_triangle_cylinder_certificate, in an exact ring NT.
template <class NT>
std::string check_certificate(const TriangleCylinderResult& res, const CertificateData<NT>& d) {
  using Sep = TriangleCylinderResult::Separation;
  using CF = TriangleCylinderResult::CylinderFeature;
  const SlabInput<NT> in = slab_input(d.T, d.C);
  const SlabAxial<NT> ax = slab_axial_data(in, ExactSigns{});

  // Every point Y of T ∩ slab has n.(Y - P) >= r |n| (> r |n| if strict), with n.A = 0 and
  // n != 0: the open tube (strict: the closed tube) lies on the other side. Checked on the
  // vertices of the clipped triangle, homogeneous: n.X >= 0 and (n.X)^2 >= r^2 n.n w^2.
  const auto plane_holds = [&](bool strict) -> std::string {
    const Vec3<NT>& n = d.normal;
    if (!nt::is_zero(dot(n, in.A))) return "normal not perpendicular to the axis";
    const NT nn = dot(n, n);
    if (!nt::is_positive(nn)) return "zero normal";
    const SlabPolygon<NT> S = clip_to_slab(in, ax.s, ax.top, ax.lo, ax.hi);
    if (S.n == 0) return "triangle misses the slab";
    const NT r2nn = (in.r * in.r) * nn;
    for (int i = 0; i < S.n; ++i) {
      const NT k = dot(n, S.p[i].X);
      const CGAL::Sign side = nt::sign(k);
      const CGAL::Sign gap = nt::sign(NT(k * k - r2nn * (S.p[i].w * S.p[i].w)));
      if (side == CGAL::NEGATIVE || (strict && side == CGAL::ZERO)) return "clipped triangle on the tube's side";
      if (gap == CGAL::NEGATIVE || (strict && gap == CGAL::ZERO)) return "plane within distance r of the axis";
    }
    return "";
  };
  const auto all = [&](const std::array<CGAL::Sign, 3>& sg, auto pred) {
    return pred(sg[0]) && pred(sg[1]) && pred(sg[2]);
  };
  const auto negative = [](CGAL::Sign x) { return x == CGAL::NEGATIVE; };
  const auto non_positive = [](CGAL::Sign x) { return x != CGAL::POSITIVE; };

  switch (res.answer) {
    case Answer::overlapping:
      if (!d.witness) return "no witness";
      if (!locate_on_triangle(*d.witness, d.T)) return "witness not in the triangle";
      if (classify_point(*d.witness, d.C) != Side::inside) return "witness not interior to the cylinder";
      return "";
    case Answer::touching: {
      if (!d.witness) return "no witness";
      const auto where = locate_on_triangle(*d.witness, d.T);
      if (!where) return "witness not in the triangle";
      if (where->first != res.triangle_feature || where->second != res.triangle_indices) return "wrong triangle feature";
      if (classify_point(*d.witness, d.C) != Side::boundary) return "witness not on the cylinder's boundary";
      // No point of T strictly between the cap planes: nothing interior.
      if (all(ax.lo, non_positive) || all(ax.hi, non_positive)) return "";
      if (res.cylinder_feature == CF::cap0 || res.cylinder_feature == CF::cap1)
        return "cap contact for a triangle crossing the slab";
      return plane_holds(false);
    }
    case Answer::separated:
      switch (res.separation) {
        case Sep::beyond_cap0: return all(ax.lo, negative) ? "" : "not beyond cap plane 0";
        case Sep::beyond_cap1: return all(ax.hi, negative) ? "" : "not beyond cap plane 1";
        case Sep::outside_tube: return plane_holds(true);
        case Sep::none: return "no separation reason";
      }
      return "bad separation reason";
    case Answer::undecided: return "undecided";
  }
  return "bad answer";
}

// An integer as an Mpzf. CGAL 5.5's Mpzf(const Gmpz&) copies the limbs of |z| (it drops the
// sign and mishandles zero), so the sign and zero are handled here.
inline CGAL::Mpzf mpz_to_mpzf(mpz_srcptr z) {
  if (mpz_sgn(z) == 0) return CGAL::Mpzf(0);
  CGAL::Gmpz magnitude;
  mpz_abs(magnitude.mpz(), z);
  const CGAL::Mpzf m(magnitude);
  return mpz_sgn(z) < 0 ? CGAL::Mpzf(-m) : m;
}

// x as an Mpzf if it is dyadic (denominator a power of two, at most 2^1074).
inline std::optional<CGAL::Mpzf> dyadic_to_mpzf(const Rational& x) {
  if (const std::optional<double> d = exact_binary64(x)) return CGAL::Mpzf(*d);
  const mpz_srcptr den = mpq_denref(x.mpq());
  const auto k = mpz_scan1(den, 0);
  if (mpz_sizeinbase(den, 2) != k + 1 || k > 1074) return std::nullopt;
  return mpz_to_mpzf(mpq_numref(x.mpq())) * CGAL::Mpzf(std::ldexp(1.0, -static_cast<int>(k)));
}

inline std::optional<CertificateData<CGAL::Mpzf>> dyadic_certificate_data(const TriangleCylinderResult& res,
                                                                          const Triangle<Rational>& T,
                                                                          const Cylinder<Rational>& C) {
  bool ok = true;
  const auto f = [&ok](const Rational& x) {
    std::optional<CGAL::Mpzf> m = ok ? dyadic_to_mpzf(x) : std::nullopt;
    ok &= m.has_value();
    return m ? *m : CGAL::Mpzf(0);
  };
  CertificateData<CGAL::Mpzf> d{T.map(f), C.map(f), std::nullopt, res.normal.map(f)};
  if (res.witness) d.witness = res.witness->map(f);
  if (!ok) return std::nullopt;
  return d;
}

}  // namespace detail

// The answer only, filtered: a semi-static double stage (binary64 input, or Rational input
// whose every number is binary64), then Interval_nt, then exact arithmetic (Mpzf for binary64
// input, Gmpq otherwise). `stages` counts the calls and the stage that decided each.
inline Answer classify_triangle_cylinder(const Triangle<Rational>& T, const Cylinder<Rational>& C,
                                         TriangleFilterStages& stages) {
  validate_operand(T, "triangle");
  validate_operand(C, "cylinder");
  return detail::decide_filtered(T, C, stages).answer;
}
inline Answer classify_triangle_cylinder(const Triangle<double>& T, const Cylinder<double>& C,
                                         TriangleFilterStages& stages) {
  validate_operand(T, "triangle");
  validate_operand(C, "cylinder");
  return detail::decide_filtered(T, C, stages).answer;
}

// The same, counting in a FilterCounter: `exact` counts the calls that needed exact arithmetic.
inline Answer classify_triangle_cylinder(const Triangle<Rational>& T, const Cylinder<Rational>& C,
                                         FilterCounter& counter) {
  TriangleFilterStages stages;
  const Answer a = classify_triangle_cylinder(T, C, stages);
  counter += detail::as_filter_counter(stages);
  return a;
}

// The same for input given as binary64 values, each meaning exactly the value it holds.
inline Answer classify_triangle_cylinder(const Triangle<double>& T, const Cylinder<double>& C, FilterCounter& counter) {
  TriangleFilterStages stages;
  const Answer a = classify_triangle_cylinder(T, C, stages);
  counter += detail::as_filter_counter(stages);
  return a;
}

// Checks a certificate in exact arithmetic, independently of how it was found (see the header
// comment for what each answer's certificate proves). Returns an empty string when it holds,
// otherwise what failed. Runs in Mpzf when every number involved is dyadic, else in Gmpq.
inline std::string check_triangle_cylinder_certificate(const TriangleCylinderResult& res, const Triangle<Rational>& T,
                                                       const Cylinder<Rational>& C) {
  if (const auto d = detail::dyadic_certificate_data(res, T, C)) return detail::check_certificate(res, *d);
  return detail::check_certificate(res, detail::CertificateData<Rational>{T, C, res.witness, res.normal});
}

namespace detail {

// The exact construction in Gmpq: X* and, from it, the certificate of any answer.
inline void exact_certificate(TriangleCylinderResult& res, const Triangle<Rational>& T, const Cylinder<Rational>& C) {
  using Res = TriangleCylinderResult;
  const SlabInput<Rational> in = slab_input(T, C);
  const SlabAxial<Rational> ax = slab_axial_data(in, ExactSigns{});
  const SlabContact where = locate_in_slab(ax.lo, ax.hi);
  const Rational& AA = ax.AA;
  const Rational R = slab_radius_term(in.r, AA);
  Answer exact = Answer::separated;
  if (where == SlabContact::beyond_cap0 || where == SlabContact::beyond_cap1) {
    res.separation = where == SlabContact::beyond_cap0 ? Res::Separation::beyond_cap0 : Res::Separation::beyond_cap1;
  } else {
    const SlabPolygon<Rational> S = clip_to_slab(in, ax.s, ax.top, ax.lo, ax.hi);
    const Vec3<Rational> x = nearest_to_axis(S, in);
    const Rational sx = dot(x, in.A);
    const Rational qx = squared_length(cross(x, in.A));
    res.closest = C.p0 + x;
    res.squared_distance = qx / AA;
    res.normal = x - (sx / AA) * in.A;
    const bool crosses = where == SlabContact::crosses_open_slab;
    if (qx > R) {
      res.separation = Res::Separation::outside_tube;
    } else if (crosses && qx < R) {
      exact = Answer::overlapping;
      res.witness = C.p0 + interior_witness(x, S, in);
    } else {
      exact = Answer::touching;
      res.witness = *res.closest;
      const auto feature = locate_on_triangle(*res.witness, T);
      if (!feature) throw std::logic_error("triangle_cylinder: nearest point not in the triangle");
      res.triangle_feature = feature->first;
      res.triangle_indices = feature->second;
      const bool on_wall = qx == R;
      if (sx == 0) res.cylinder_feature = on_wall ? Res::CylinderFeature::rim0 : Res::CylinderFeature::cap0;
      else if (sx == AA) res.cylinder_feature = on_wall ? Res::CylinderFeature::rim1 : Res::CylinderFeature::cap1;
      else res.cylinder_feature = Res::CylinderFeature::wall;
    }
  }
  if (exact != res.answer)
    throw std::logic_error("triangle_cylinder: filtered answer " + std::string(to_string(res.answer)) +
                           " but exact construction " + std::string(to_string(exact)));
}

// A certificate guessed in double and built exactly in Mpzf (binary64 input), for an
// overlapping answer without an interior vertex or an outside_tube separation. False if no
// guess could be made; otherwise the caller's exact check decides whether it holds.
inline bool guessed_certificate(TriangleCylinderResult& res, const Triangle<double>& Td, const Cylinder<double>& Cd,
                                SlabContact where) {
  using Res = TriangleCylinderResult;
  using M = CGAL::Mpzf;
  const SlabInput<double> in{{Vec3<double>(Td.v[0] - Cd.p0), Vec3<double>(Td.v[1] - Cd.p0), Vec3<double>(Td.v[2] - Cd.p0)},
                             Cd.axis(),
                             Cd.radius,
                             1.0};
  // The clipped polygon in double, with the decision's (exact) picture of where T lies: the
  // signs are recomputed in double, and a guess built on a wrong sign only fails the check.
  // Only where double cannot overflow or underflow badly (the static stage's range).
  double m = std::fabs(in.r);
  for (const Vec3<double>& v : {in.a[0], in.a[1], in.a[2], in.A})
    m = std::max({m, std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
  if (!static_scale(m)) return false;
  const SlabAxial<double> ax = slab_axial_data(in, ExactSigns{});
  const SlabPolygon<double> S = clip_to_slab(in, ax.s, ax.top, ax.lo, ax.hi);
  if (S.n == 0) return false;
  const Vec3<double> x = nearest_to_axis(S, in);
  // else below: a non-finite value (an axis so short that A.A underflows, e.g. subnormal) gives
  // no guess; Mpzf cannot hold it.
  const auto finite = [](const Vec3<double>& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
  if (!finite(x)) return false;
  const Vec3<M> Am = Vec3<M>(Cd.p1.map([](double v) { return M(v); }) - Cd.p0.map([](double v) { return M(v); }));

  if (res.answer == Answer::separated) {
    // n = g A.A - (g.A) A with g = X* - P in double: n.A = 0 exactly.
    const Vec3<M> g = x.map([](double v) { return M(v); });
    const Vec3<M> n = g * dot(Am, Am) - Am * dot(g, Am);
    res.separation = Res::Separation::outside_tube;
    res.normal = n.map([](const M& v) { return Rational(v); });
    return true;
  }
  // Overlapping: candidates strictly inside in double, expressed in barycentric coordinates
  // of T rounded to 2^-30, so the exact point v0 + alpha e1 + beta e2 is in T by construction.
  if (where != SlabContact::crosses_open_slab) return false;
  const Vec3<double> e1 = in.a[1] - in.a[0], e2 = in.a[2] - in.a[0];
  const double g11 = dot(e1, e1), g12 = dot(e1, e2), g22 = dot(e2, e2);
  const double det = g11 * g22 - g12 * g12;
  if (!(det > 1e-12 * g11 * g22)) return false;
  const Vec3<double> y = interior_witness(x, S, in);
  Vec3<double> c = relative_point(S.p[0]);
  for (int i = 1; i < S.n; ++i) c += relative_point(S.p[i]);
  c = c / static_cast<double>(S.n);
  const Triangle<M> Tm = Td.map([](double v) { return M(v); });
  const Cylinder<M> Cm = Cd.map([](double v) { return M(v); });
  for (const Vec3<double>& candidate : {y, c, Vec3<double>((x + c) * 0.5)}) {
    const Vec3<double> w = candidate - in.a[0];
    const double b1 = dot(e1, w), b2 = dot(e2, w);
    const auto grid = [](double t) { return std::ldexp(std::nearbyint(std::ldexp(std::clamp(t, 0.0, 1.0), 30)), -30); };
    const double alpha = grid((b1 * g22 - b2 * g12) / det);
    const double beta = std::min(grid((b2 * g11 - b1 * g12) / det), 1.0 - alpha);
    if (!std::isfinite(alpha) || !std::isfinite(beta)) continue;  // else: no candidate (NaN survives the clamp)
    const Vec3<M> p = Tm.v[0] + M(alpha) * Vec3<M>(Tm.v[1] - Tm.v[0]) + M(beta) * Vec3<M>(Tm.v[2] - Tm.v[0]);
    if (classify_point(p, Cm) == Side::inside) {
      res.witness = p.map([](const M& v) { return Rational(v); });
      return true;
    }
  }
  return false;
}

// The certified query on valid operands T, C; Td, Cd are the same operands as doubles when every
// number of them is a binary64 value.
inline TriangleCylinderResult certified_triangle(const Triangle<Rational>& T, const Cylinder<Rational>& C,
                                                 const std::optional<Triangle<double>>& Td,
                                                 const std::optional<Cylinder<double>>& Cd) {
  using Res = TriangleCylinderResult;
  Res res;
  const detail::SlabDecision decision =
      Td && Cd ? detail::decide_filtered(*Td, *Cd, res.stages) : detail::decide_filtered(T, C, res.stages);
  res.answer = decision.answer;
  res.counter = detail::as_filter_counter(res.stages);

  // The cheap certificates: beyond a cap plane, an interior vertex, a guess from double.
  bool built = false;
  if (decision.where == detail::SlabContact::beyond_cap0 || decision.where == detail::SlabContact::beyond_cap1) {
    res.separation = decision.where == detail::SlabContact::beyond_cap0 ? Res::Separation::beyond_cap0
                                                                         : Res::Separation::beyond_cap1;
    built = true;
  } else if (decision.inside_vertex >= 0) {
    res.witness = T.v[decision.inside_vertex];
    built = true;
  } else if (Td && Cd && res.answer != Answer::touching && detail::guessed_certificate(res, *Td, *Cd, decision.where)) {
    if (check_triangle_cylinder_certificate(res, T, C).empty()) return res;
    // else: the guess failed its exact check (near-degenerate input): construct exactly.
    res.witness.reset();
    res.normal = Vec3<Rational>{0, 0, 0};
    res.separation = Res::Separation::none;
  }
  if (!built) detail::exact_certificate(res, T, C);
  if (const std::string failure = check_triangle_cylinder_certificate(res, T, C); !failure.empty())
    throw std::logic_error("triangle_cylinder: certificate check failed: " + failure);
  return res;
}

}  // namespace detail

// The answer with its exact, checked certificate. Throws InvalidInput on an invalid cylinder, and
// std::logic_error if the filtered answer and the exact construction disagree or the certificate
// fails its check (either would be a defect of this code, never a property of the input).
inline TriangleCylinderResult certified_triangle_cylinder(const Triangle<Rational>& T, const Cylinder<Rational>& C) {
  validate_operand(T, "triangle");
  validate_operand(C, "cylinder");
  return detail::certified_triangle(T, C, detail::exact_binary64(T), detail::exact_binary64(C));
}

// The same for binary64 operands, each double taken as the exact rational it denotes; non-finite
// numbers are an InvalidInput.
inline TriangleCylinderResult certified_triangle_cylinder(const Triangle<double>& T, const Cylinder<double>& C) {
  validate_operand(T, "triangle");
  validate_operand(C, "cylinder");
  const auto exact = [](double x) { return Rational(x); };
  return detail::certified_triangle(T.map(exact), C.map(exact), T, C);
}

}  // namespace certcyl
