// certcyl/certified/detail/cylinder_corner_plane.hpp -- candidates for a cylinder pair whose
// operands or gap differ greatly in size: the best direction of one cylinder's rim wedge in the
// plane through its axis and a point of the other, and the other's deepest point in that wedge.
//
// Semantics. Let cylinder i have end p0, axis A, radius R, and let y be a point. With w the part
// of y - p0 orthogonal to A (any nonzero vector orthogonal to A when y is on the axis),
// e = w / |w|, E the end of i nearer to y along the axis (p1 when (y - p0).A >= A.A / 2, else
// p0), u = +-A / |A| pointing out of i at E and q = E + R e (the rim point of i in the
// half-plane of y), every direction D = a u + b e with a, b >= 0 has
//   h_i(D) = D.m_i + |D.A| / 2 + R |D x A| / |A| = a u.E + b (e.p0 + R) = D.q,
// the support of i in D attained at q, exactly. A cylinder j (ends E_0, E_1, axis A_j, radius
// r_j) has min over j of D.x = min_k D.E_k - r_j |D x A_j| / |A_j|, so D separates i from j iff
//   g(D) = min_k D.(E_k - q) - r_j |D x A_j| / |A_j| > 0.
// g (a minimum of linear functions minus a norm) is concave; on D(t) = (1 - t) u + t e it is
// concave in t in [0, 1], and best() finds its maximiser t* in closed form. Its inputs are reduced
// exactly to the scale of the contact, relative to j's ends (not its midpoint: a needle 2^1000
// long would cancel every bit):
//   (E_k - q).u = s ((E_k - p0).A - [E = p1] A.A) / |A|   (s = +-1, the sign of u),
//   (E_k - q).e = (rho^2 - R^2) / (rho + R),  rho = (E_k - p0).w / |w|, rho^2 rational,
// so a gap of 2^-1800 R survives: each term carries only the relative rounding of a square
// root. What is left is the cancellation between the terms of g near touching, which the caller
// meets by raising the precision.
//
// By the minimax theorem, when max g < 0 its negative is the depth of the deepest point of j in
// the wedge {x : u.(x - q) < 0, e.(x - q) < 0}, reached by the support points E_k + r_j nu of j in
// direction -D(t*) (a combination of the two on either side of t* where the support set is a
// face). Near the contact the wedge is i: it differs from i by the curvature of the rim and by
// i's other end, both far at the scale where this is used.
//
// Results: a rational direction D = a' s A + b' w (a', b' >= 0 rounded: it stays in the wedge, so
// h_i(D) = D.q whatever the rounding) and, when max g < 0, a rational point of j's interior: the
// support point moved towards a point c of j's axis near it (at distance min(r_j, |A_j| / 2)
// from the end) by a power of two eta small against the depth. They are candidates only: the
// caller checks each exactly.
//
// The exact ring R: Rational for any input, or CGAL::Mpzf for a pair in the ring frame
// (detail/cylinder_ring_frame.hpp; integer input, and every rounding above is dyadic, so every
// number here is a dyadic rational): the reductions' products then carry no gcds, which were
// most of a plane's cost on input spanning hundreds of binades.
#pragma once

#include <CGAL/Gmpfr.h>

#include <algorithm>
#include <array>
#include <optional>
#include <type_traits>

#include "certcyl/certified/detail/cylinder_ellipsoid.hpp"
#include "certcyl/certified/detail/cylinder_ring_frame.hpp"
#include "certcyl/number_traits.hpp"
#include "certcyl/primitives.hpp"
#include "certcyl/vec3.hpp"

namespace certcyl::detail {

template <class R>
class CornerPlane {
 public:
  using F = CGAL::Gmpfr;

  // A point of j: an end plus an offset of length r_j (rounded), and an interior point of j's
  // axis beside it; with its local coordinates (x - q).u and (x - q).e.
  struct Point {
    Point3<R> x, c;
    F xu, xe;
  };

  // The plane of cylinder i through y (any plane through the axis when y is on it), seen by
  // cylinder j. Call inside a GmpfrPrecision scope (it sets the precision of every number here).
  static CornerPlane make(const Cylinder<R>& ci, const Cylinder<R>& cj, const Point3<R>& y) {
    const Vec3<R> A = ci.axis(), Aj = cj.axis();
    // w is (A.A) times the part of y - p0 orthogonal to A: no division, so dyadic input keeps
    // dyadic numbers and only its direction matters below.
    const R AA = dot(A, A);
    const R along = dot(y - ci.p0, A);
    Vec3<R> w = AA * (y - ci.p0) - along * A;
    if (CGAL::is_zero(w.x) && CGAL::is_zero(w.y) && CGAL::is_zero(w.z)) {
      const R ax = CGAL::abs(A.x), ay = CGAL::abs(A.y), az = CGAL::abs(A.z);
      const R zero = nt::constant<R>(0), one = nt::constant<R>(1);
      const Vec3<R> k = ax <= ay && ax <= az ? Vec3<R>{one, zero, zero} : ay <= az ? Vec3<R>{zero, one, zero} : Vec3<R>{zero, zero, one};
      w = AA * k - dot(k, A) * A;
    }
    {
      // w rounded to 64 bits beyond the working precision and made exactly orthogonal to A again
      // (A.A r - (r.A) A): within 2^-(p+60) of the plane through y, and a few hundred bits long
      // where the exact w of a witness from the last plane has thousands.
      const long p = static_cast<long>(CGAL::Gmpfr::get_default_precision());
      Vec3<R> r;
      {
        GmpfrPrecision scope(p + 64);
        r = w.map([](const R& x) { return ring_exact<R>(f(x)); });
      }
      w = AA * r - dot(r, A) * A;
    }
    const R ww = dot(w, w);
    const bool far_end = nt::constant<R>(2) * along >= AA;
    CornerPlane c;
    c.p0_ = ci.p0;
    c.AA_ = AA;
    c.ww_ = ww;
    c.R_ = ci.radius;
    c.RRww_ = ci.radius * ci.radius * ww;
    c.far_end_ = far_end;
    c.axial_ = far_end ? A : Vec3<R>(-A);
    c.radial_ = w;
    c.inv_axial_ = k(1) / CGAL::sqrt(f(AA));
    c.inv_radial_ = k(1) / CGAL::sqrt(f(ww));
    c.Rf_ = f(ci.radius);
    c.E_ = {cj.p0, cj.p1};
    c.Aj_exact_ = Aj;
    c.AAj_ = dot(Aj, Aj);
    c.inv_AAj_ = ring_exact<R>(k(1) / f(c.AAj_));
    for (int e = 0; e < 2; ++e) c.local(c.E_[e], c.ca_[e], c.cr_[e]);
    c.jj_ = f(c.AAj_);
    c.rj_ = f(cj.radius);
    c.u_ = c.axial_.map(f) * c.inv_axial_;
    c.e_ = w.map(f) * c.inv_radial_;
    c.Aj_ = Aj.map(f);
    c.ux_ = cross(c.axial_, Aj).map(f) * c.inv_axial_;
    c.ex_ = cross(w, Aj).map(f) * c.inv_radial_;
    // The interior points of j's axis beside each end: at min(r_j, |A_j| / 2) from it (rounded
    // to a rational fraction lambda of the axis, 0 < lambda <= 1/2).
    R lambda = ring_two_power<R>(-1);
    const F ratio = c.rj_ / CGAL::sqrt(c.jj_);
    if (ratio < k(1) / k(2) && ratio > 0) lambda = ring_exact<R>(ratio);
    c.inner_ = {cj.p0 + lambda * Aj, cj.p1 - lambda * Aj};
    return c;
  }

  // g(D(t)); and the magnitude of its terms (the scale of its rounding error).
  F gain(const F& t) const {
    const F a = k(1) - t;
    const F lowest = std::min(a * ca_[0] + t * cr_[0], a * ca_[1] + t * cr_[1]);
    return lowest - rj_ * CGAL::sqrt(perp(t));
  }
  F scale(const F& t) const {
    const F a = k(1) - t;
    return CGAL::abs(a * ca_[0]) + CGAL::abs(t * cr_[0]) + CGAL::abs(a * ca_[1]) + CGAL::abs(t * cr_[1]) + rj_;
  }

  // The maximiser of gain on [0, 1], in closed form. gain is concave (a minimum of the linear
  // L_k(t) = (1 - t) ca_k + t cr_k less r_j sqrt(q(t)), q(t) = |u x A_j + t v|^2 / |A_j|^2 with
  // v = (e - u) x A_j, a norm of an affine function), so its maximum on [0, 1] is at an end, at
  // the crossing of L_0 and L_1, at the zero of q (where sqrt(q) has its kink), or at a
  // stationary point of one piece L_k - r_j sqrt(q): with slope m = cr_k - ca_k,
  // alpha = v.v, t0 = -(u x A_j).v / alpha (the minimiser of q) and
  // 4 alpha gamma - beta^2 = 4 |(u x A_j) x (e x A_j)|^2 (no cancellation),
  //   t = t0 + (m / alpha) |(u x A_j) x (e x A_j)| sqrt(|A_j|^2 / (r_j^2 alpha - m^2 |A_j|^2)),
  // which exists when m^2 |A_j|^2 < r_j^2 alpha. gain is evaluated at each of these points
  // inside [0, 1] and the best is kept (an end on a tie: the cap and wall normals, where a
  // maximum is exact).
  F best() const {
    std::array<F, 6> candidates;
    int n = 0;
    const auto add = [&](const F& t) {
      if (t > 0 && t < 1) candidates[n++] = t;
    };
    const F dc = ca_[0] - ca_[1], dr = cr_[0] - cr_[1];
    if (dc != dr) add(dc / (dc - dr));
    const Vec3<F> v = ex_ - ux_;
    const F alpha = dot(v, v);
    if (alpha > 0) {
      add(-dot(ux_, v) / alpha);
      const Vec3<F> w = cross(ux_, ex_);
      const F width = CGAL::sqrt(dot(w, w));
      const F t0 = -dot(ux_, v) / alpha;
      for (int e = 0; e < 2; ++e) {
        const F m = cr_[e] - ca_[e];
        const F room = rj_ * rj_ * alpha - m * m * jj_;
        if (room > 0) add(t0 + (m / alpha) * width * CGAL::sqrt(jj_ / room));
      }
    }
    F t = k(0), gt = gain(t);
    for (int i = 0; i < n; ++i) {
      const F g = gain(candidates[i]);
      if (g > gt) t = candidates[i], gt = g;
    }
    const F g1 = gain(k(1));
    if (g1 >= gt) t = k(1);
    return t;
  }

  // The rational direction a' s A + b' w with a' ~ (1 - t) / |A| and b' ~ t / |w|.
  Vec3<R> direction(const F& t) const {
    return ring_exact<R>((k(1) - t) * inv_axial_) * axial_ + ring_exact<R>(t * inv_radial_) * radial_;
  }

  // j's support point in direction -D(t): the lower end plus r_j times the unit part of -D
  // orthogonal to A_j (rounded to the working precision), and the interior point beside it.
  Point support(const F& t) const {
    const F a = k(1) - t;
    const int end = a * ca_[0] + t * cr_[0] <= a * ca_[1] + t * cr_[1] ? 0 : 1;
    const Vec3<F> D = u_ * a + e_ * t;
    const Vec3<F> p = D - Aj_ * (dot(D, Aj_) / jj_);
    const F pp = dot(p, p);
    Point s{E_[end], inner_[end], ca_[end], cr_[end]};
    if (pp > 0) {
      const Vec3<F> offset = p * (-rj_ / CGAL::sqrt(pp));
      // Exactly in the plane of the end disc (near a face, p is small and its rounding tilts it).
      // (A_j.A_j) o - (o.A_j) A_j is exactly orthogonal to A_j; times a dyadic 1 / A_j.A_j (its
      // length is rounded anyway) it stays so, without a division.
      const Vec3<R> o = offset.map([](const F& x) { return ring_exact<R>(x); });
      s.x = E_[end] + inv_AAj_ * (AAj_ * o - dot(o, Aj_exact_) * Aj_exact_);
      local(s.x, s.xu, s.xe);
    }
    return s;
  }

  // A candidate interior point of j deepest in the wedge, or nullopt when none is in the wedge
  // at the working precision or the inset would be below the rounding of the support points.
  // `spread`: the step either side of t where the support set of j may be a face.
  std::optional<Point3<R>> witness(const F& t, const F& spread, long precision) const {
    const F lo = t - spread < 0 ? k(0) : F(t - spread), hi = t + spread > 1 ? k(1) : F(t + spread);
    const Point m = support(lo), p = support(hi);
    const auto depth = [](const F& xu, const F& xe) { return -(xu > xe ? xu : xe); };
    // The combination lambda m + (1 - lambda) p whose two depths are equal.
    const R one = nt::constant<R>(1);
    R lambda = one;
    F best_depth = depth(m.xu, m.xe);
    if (depth(p.xu, p.xe) > best_depth) {
      lambda = nt::constant<R>(0);
      best_depth = depth(p.xu, p.xe);
    }
    const F den = (m.xu - p.xu) - (m.xe - p.xe);
    if (den != 0) {
      F l = (p.xe - p.xu) / den;
      if (l < 0) l = k(0);
      if (l > 1) l = k(1);
      const R lq = ring_exact<R>(l);
      const F lf = f(lq);
      const F d = depth(lf * m.xu + (k(1) - lf) * p.xu, lf * m.xe + (k(1) - lf) * p.xe);
      if (d > best_depth) {
        lambda = lq;
        best_depth = d;
      }
    }
    if (!(best_depth > 0)) return std::nullopt;
    const Point3<R> x = m.x + (one - lambda) * (p.x - m.x);
    const Point3<R> c = m.c + (one - lambda) * (p.c - m.c);
    // eta = 2^-shift with eta |x - c|_1 <= depth / 4: the inset costs at most a quarter of the
    // depth; and eta far above the rounding of the offsets (r_j 2^-precision against the
    // distance min(r_j, |A_j| / 2) of c from j's boundary).
    const Vec3<R> xc = x - c;
    const F size = f(CGAL::abs(xc.x) + CGAL::abs(xc.y) + CGAL::abs(xc.z));
    const long shift = std::max(1L, gmpfr_exponent(k(4) * size / best_depth) + 1);
    const long room = gmpfr_exponent(CGAL::sqrt(jj_) / rj_);
    if (shift + std::max(0L, -room) + 24 > precision) return std::nullopt;
    const R eta = ring_two_power<R>(-shift);
    return x + eta * (c - x);
  }

  // Precision needed to resolve a gain of g at t: its terms' scale over |g|, in bits.
  long bits_to_resolve(const F& t, const F& g) const {
    if (g == 0) return std::numeric_limits<long>::max();
    return gmpfr_exponent(scale(t) / CGAL::abs(g)) + 32;
  }

 private:
  static F f(const R& q) { return ring_gmpfr(q); }
  static F k(int n) { return nt::constant<F>(n); }

  // (x - q).u and (x - q).e for a rational x, reduced exactly (see the header).
  void local(const Point3<R>& x, F& xu, F& xe) const {
    const Vec3<R> v = x - p0_;
    const R along = dot(v, axial_);  // s (x - p0).A
    xu = f(far_end_ ? R(along - AA_) : along) * inv_axial_;
    const R rho_w = dot(v, radial_);  // rho |w|
    if (CGAL::sign(rho_w) == CGAL::POSITIVE) {
      const F rho = f(rho_w) * inv_radial_;
      xe = f(rho_w * rho_w - RRww_) / f(ww_) / (rho + Rf_);
    } else {
      xe = f(rho_w) * inv_radial_ - Rf_;
    }
  }

  // |D x A_j|^2 / |A_j|^2 for D(t), from the vector D x A_j = (1 - t) u x A_j + t e x A_j: near
  // D || A_j its components are accurate to the working precision, where |D|^2 - (D.A_j)^2 / A_j.A_j
  // would keep only half of it.
  F perp(const F& t) const {
    const Vec3<F> x = ux_ * (k(1) - t) + ex_ * t;
    return dot(x, x) / jj_;
  }

  Point3<R> p0_;
  R AA_, ww_, R_, RRww_, AAj_, inv_AAj_;  // RRww_: R^2 w.w; inv_AAj_: 1 / A_j.A_j rounded (dyadic)
  Vec3<R> Aj_exact_;
  bool far_end_ = false;
  Vec3<R> axial_, radial_;  // s A and w
  F inv_axial_, inv_radial_, Rf_;  // 1 / |A|, 1 / |w|, R
  std::array<Point3<R>, 2> E_, inner_;
  std::array<F, 2> ca_, cr_;  // (E_k - q).u, (E_k - q).e
  F jj_, rj_;                 // A_j.A_j, r_j
  Vec3<F> u_, e_, Aj_, ux_, ex_;  // u, e, A_j, u x A_j, e x A_j
};

}  // namespace certcyl::detail
