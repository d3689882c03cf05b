// certcyl/certified/detail/cylinder_corner_plane.hpp -- candidates for a cylinder pair whose
// operands differ greatly in size: the best direction of one cylinder's rim wedge in the plane
// through its axis and a point of the other, and the other's deepest point against that wedge.
//
// Semantics. Let cylinder i have end p0, axis A, radius R, and let y be a point.
// With w the part of y - p0 orthogonal to A (or, for y on the axis, any nonzero w orthogonal to A), e = w / |w|, E the end of i nearer to y along the
// axis (p1 when (y - p0).A >= A.A / 2, else p0), u = +-A / |A| pointing out of i at E and
// q = E + R e (the rim point of i in the half-plane of y), every direction D = a u + b e with
// a, b >= 0 has
//   h_i(D) = D.m_i + |D.A| / 2 + R |D x A| / |A| = a u.E + b (e.p0 + R) = D.q,
// the support of i in D attained at q, exactly. So D separates i from a cylinder j (midpoint m_j,
// axis A_j, radius r_j) iff
//   g(D) = D.(m_j - q) - |D.A_j| / 2 - r_j |D x A_j| / |A_j| > 0,
// and g, a linear function minus a support function, is concave; on D(t) = (1 - t) u + t e it is
// concave in t in [0, 1] and golden-section search finds its maximiser t*. Its inputs are reduced
// to j's scale without cancellation:
//   (m_j - q).u = s ((m_j - p0).A - [E = p1] A.A) / |A|   (s = +-1, the sign of u),
//   (m_j - q).e = (rho^2 - R^2) / (rho + R),  rho = (m_j - p0).w / |w|, rho^2 rational,
// so a gap of 2^-1800 R survives: the square roots carry only relative rounding.
//
// By the minimax theorem, when max g < 0 its negative is the depth of the deepest point of j in
// the wedge {x : u.(x - q) < 0, e.(x - q) < 0}, reached by the support points of j in direction
// -D(t*) (a combination of the two on either side of t* where the support set is a face).
// Near y the wedge is i: it differs from i by the curvature of the rim, |x - y|^2 / R at most.
//
// Results: a rational direction D = a' s A + b' w (a', b' >= 0 rounded: it stays in the wedge, so
// h_i(D) = D.q whatever the rounding) and, when max g < 0, a rational point of j's interior
// moved from that support point towards m_j by a power of two eta small against the depth.
// They are candidates only: the caller checks each exactly.
#pragma once

#include <CGAL/Gmpfr.h>

#include <algorithm>
#include <optional>

#include "certcyl/certified/detail/cylinder_ellipsoid.hpp"
#include "certcyl/number_traits.hpp"
#include "certcyl/primitives.hpp"
#include "certcyl/vec3.hpp"

namespace certcyl::detail {

class CornerPlane {
 public:
  using F = CGAL::Gmpfr;

  // The plane of cylinder i through y (any plane through the axis when y is on it), seen by
  // cylinder j. Call inside a GmpfrPrecision scope (it sets the precision of every number here).
  static CornerPlane make(const Cylinder<Rational>& ci, const Cylinder<Rational>& cj, const Point3<Rational>& y) {
    const Vec3<Rational> A = ci.axis(), Aj = cj.axis();
    const Rational AA = dot(A, A);
    const Vec3<Rational> v = y - ci.p0;
    const Rational t = dot(v, A) / AA;
    Vec3<Rational> w = v - t * A;
    if (w == Vec3<Rational>{0, 0, 0}) {
      // y on the axis: every plane through the axis is alike; take the one through the
      // coordinate direction least aligned with A.
      const Rational ax = CGAL::abs(A.x), ay = CGAL::abs(A.y), az = CGAL::abs(A.z);
      const Vec3<Rational> k = ax <= ay && ax <= az ? Vec3<Rational>{1, 0, 0} : ay <= az ? Vec3<Rational>{0, 1, 0} : Vec3<Rational>{0, 0, 1};
      w = k - (dot(k, A) / AA) * A;
    }
    const Rational ww = dot(w, w);
    const bool far_end = 2 * t >= 1;
    CornerPlane c;
    c.axial_ = far_end ? A : Vec3<Rational>(-A);
    c.radial_ = w;
    c.inv_axial_ = k(1) / CGAL::sqrt(f(AA));
    c.inv_radial_ = k(1) / CGAL::sqrt(f(ww));
    const Point3<Rational> mj = cj.p0 + Aj / Rational(2);
    const Vec3<Rational> vm = mj - ci.p0;
    c.ca_ = f(far_end ? Rational(dot(vm, A) - AA) : Rational(-dot(vm, A))) * c.inv_axial_;
    const Rational rho_w = dot(vm, w);  // rho |w|
    const Rational R2 = ci.radius * ci.radius;
    if (rho_w > 0) {
      const F rho = f(rho_w) * c.inv_radial_;
      c.cr_ = f(rho_w * rho_w / ww - R2) / (rho + f(ci.radius));
    } else {
      c.cr_ = f(rho_w) * c.inv_radial_ - f(ci.radius);
    }
    c.ja_ = f(dot(c.axial_, Aj)) * c.inv_axial_;
    c.jr_ = f(dot(w, Aj)) * c.inv_radial_;
    c.jj_ = f(dot(Aj, Aj));
    c.rj_ = f(cj.radius);
    c.u_ = c.axial_.map(f) * c.inv_axial_;
    c.e_ = w.map(f) * c.inv_radial_;
    c.Aj_ = Aj.map(f);
    return c;
  }

  // g(D(t)).
  F gain(const F& t) const {
    const F a = k(1) - t;
    const F dA = a * ja_ + t * jr_;
    F perp = a * a + t * t - dA * dA / jj_;
    if (perp < 0) perp = k(0);
    return a * ca_ + t * cr_ - CGAL::abs(dA) / k(2) - rj_ * CGAL::sqrt(perp);
  }

  // The maximiser of gain on [0, 1], by golden-section search (gain is concave).
  F best(int iterations) const {
    const F ratio = (CGAL::sqrt(k(5)) - k(1)) / k(2);
    F lo = k(0), hi = k(1);
    F x1 = hi - ratio * (hi - lo), x2 = lo + ratio * (hi - lo);
    F g1 = gain(x1), g2 = gain(x2);
    for (int k = 0; k < iterations; ++k) {
      if (g1 < g2) {
        lo = x1;
        x1 = x2;
        g1 = g2;
        x2 = lo + ratio * (hi - lo);
        g2 = gain(x2);
      } else {
        hi = x2;
        x2 = x1;
        g2 = g1;
        x1 = hi - ratio * (hi - lo);
        g1 = gain(x1);
      }
    }
    F t = (lo + hi) / k(2);
    // The ends are the cap and wall normals; a maximum there is exact.
    for (const F& end : {k(0), k(1)})
      if (gain(end) >= gain(t)) t = end;
    return t;
  }

  // The rational direction a' s A + b' w with a' ~ (1 - t) / |A| and b' ~ t / |w|.
  Vec3<Rational> direction(const F& t) const {
    return to_rational((k(1) - t) * inv_axial_) * axial_ + to_rational(t * inv_radial_) * radial_;
  }

  // The offset from m_j of j's support point in direction -D(t) (rounded; on j's boundary to
  // the working precision).
  Vec3<F> support_offset(const F& t) const {
    const Vec3<F> D = u_ * (k(1) - t) + e_ * t;
    const F dA = dot(D, Aj_);
    const Vec3<F> perp = D - Aj_ * (dA / jj_);
    const F pp = dot(perp, perp);
    const F half = k(1) / k(2);
    Vec3<F> z = Aj_ * (dA > 0 ? -half : dA < 0 ? half : k(0));
    if (pp > 0) z = z - perp * (rj_ / CGAL::sqrt(pp));
    return z;
  }

  // Depth of m_j + z in the wedge: min(-u.(x - q), -e.(x - q)).
  F depth(const Vec3<F>& z) const {
    const F da = -(ca_ + dot(z, u_)), dr = -(cr_ + dot(z, e_));
    return da < dr ? da : dr;
  }

  // A candidate interior point of j deepest in the wedge, as the offset z from m_j (the caller
  // adds m_j), or nullopt when no point of j is in the wedge to the working precision. `spread`
  // is the step either side of t where the support set of j may be a face; eta the inset.
  std::optional<Vec3<Rational>> witness_offset(const F& t, const F& spread, long precision) const {
    const F lo = t - spread < 0 ? k(0) : F(t - spread), hi = t + spread > 1 ? k(1) : F(t + spread);
    const Vec3<F> zm = support_offset(lo), zp = support_offset(hi);
    // The combination of zm and zp whose axial and radial depths are equal.
    const F da_m = -(ca_ + dot(zm, u_)), dr_m = -(cr_ + dot(zm, e_));
    const F da_p = -(ca_ + dot(zp, u_)), dr_p = -(cr_ + dot(zp, e_));
    const F den = (da_m - da_p) - (dr_m - dr_p);
    Vec3<F> best = zm;
    F best_depth = depth(zm);
    const auto consider = [&](const Vec3<F>& z) {
      const F d = depth(z);
      if (d > best_depth) {
        best = z;
        best_depth = d;
      }
    };
    consider(zp);
    if (den != 0) {
      F lambda = (dr_p - da_p) / den;
      if (lambda < 0) lambda = k(0);
      if (lambda > 1) lambda = k(1);
      consider(zm * lambda + zp * (k(1) - lambda));
    }
    if (!(best_depth > 0)) return std::nullopt;
    // eta = 2^-k <= depth / (2 |z|_1): moving by eta z costs at most half the depth.
    const F size = CGAL::abs(best.x) + CGAL::abs(best.y) + CGAL::abs(best.z);
    if (!(size > 0)) return best.map([](const F& x) { return to_rational(x); });
    const long shift = std::max(1L, static_cast<long>(mpfr_get_exp(F(k(2) * size / best_depth).fr())) + 1);
    if (shift > precision - 20) return std::nullopt;  // the rounding of z would not be covered
    const Rational shrink = Rational(1) - times_two_power(Rational(1), -shift);
    return best.map([&shrink](const F& x) { return shrink * to_rational(x); });
  }

 private:
  static F f(const Rational& q) { return nt::from_rational<F>(q); }
  static F k(int n) { return nt::constant<F>(n); }

  Vec3<Rational> axial_, radial_;  // s A and w
  F inv_axial_, inv_radial_;       // 1 / |A|, 1 / |w|
  F ca_, cr_;                      // (m_j - q).u, (m_j - q).e
  F ja_, jr_, jj_, rj_;            // A_j.u, A_j.e, A_j.A_j, r_j
  Vec3<F> u_, e_, Aj_;
};

}  // namespace certcyl::detail
