// certcyl/certified/detail/cylinder_optimiser.hpp -- approximate minimiser of phi2 on the plane
// D.T = 1 (notation of cylinder_certificates.hpp), in double or in Gmpfr.
//
// Nothing here is a certificate: the optimiser proposes a direction D and a point X, and the
// caller checks them exactly. It only has to be fast and robust.
//
// Method: phi2 restricted to the plane, D = D0 + u U + v V (D0 = T / T.T, U, V orthogonal to T
// with |U| = |V| = 1/|T|), is a sum of four norms of affine maps of (u, v):
//   |a_i(u,v)|  with a_i = D.A_i                         (two axial terms)
//   |w_i(u,v)|  with w_i = (2 r_i / |A_i|) D x A_i        (two radial terms).
// The radial terms (and the gauges of scale_at) depend on A_i only up to a positive scale: in
// double they use A_i times a power of two (unit_binade), so that an axis 2^-600 long (a disc
// far thinner than it is wide) does not make A_i.A_i underflow to 0.
// It is convex but not smooth on the kink set where a term vanishes, and the minimiser often
// lies there (design note, section 4). Each norm |y| is replaced by sqrt(|y|^2 + mu^2), which is
// smooth and strictly convex and overestimates phi2 by at most 4 mu; damped Newton minimises it
// for mu decreasing geometrically (a smoothing path: each level starts from the previous
// minimiser, where Newton converges in a few steps).
//
// Dual point. At a minimiser of the smoothed function, with y_k the gradients of the smoothed
// norms (|y_k| < 1), sum_k B_k^T y_k = lambda T, where B_k is the linear part of term k:
//   Z0 = y_a0 A0 + k0 A0 x y_w0  lies in 2 (K0 - m0),   Z1 likewise in 2 (K1 - m1),
//   Z0 + Z1 = lambda T = 2 lambda Delta.
// So X = m0 + Z0 / (2 lambda) = m1 - Z1 / (2 lambda) lies in both cylinders scaled by 1/lambda
// about their midpoints, and lambda >= F_mu(D) - 4 mu >= phi* - 4 mu. When phi* > 1 this X is
// interior to both: the witness point. The two expressions are averaged, which halves the effect
// of a residual in the stationarity condition.
#pragma once

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <utility>

#include "certcyl/certified/detail/cylinder_certificates.hpp"
#include "certcyl/number_traits.hpp"
#include "certcyl/vec3.hpp"

namespace certcyl::detail {

template <class NT>
struct PlaneMinimum {
  Vec3<NT> direction;  // D with D.T = 1 (up to rounding)
  Point3<NT> point;    // the dual point X
  NT value;            // phi2(D), unsmoothed
  NT dual;             // lambda: X lies in both cylinders scaled by 1/lambda
  int iterations = 0;  // Newton steps taken
};

template <class NT>
class PlaneProblem {
 public:
  // mu_exponent: the smoothing stops at mu = phi2(D0) * 2^-mu_exponent.
  PlaneProblem(const CylinderPair<NT>& d, int mu_exponent) : d_(d) {
    const NT zero = nt::constant<NT>(0), one = nt::constant<NT>(1), two = nt::constant<NT>(2);
    const NT TT = dot(d.T, d.T);
    const NT norm_T = nt::sqrt(TT);
    // Basis of the plane: U orthogonal to T and to the coordinate axis T is least aligned with.
    std::size_t k = 0;
    for (std::size_t i = 1; i < 3; ++i)
      if (nt::compare(abs_enclosure(d.T[i]), abs_enclosure(d.T[k])) == CGAL::SMALLER) k = i;
    Vec3<NT> e{zero, zero, zero};
    e[k] = one;
    const Vec3<NT> Tx = cross(d.T, e);
    U_ = Tx / (nt::sqrt(dot(Tx, Tx)) * norm_T);
    V_ = cross(d.T, U_) / norm_T;
    D0_ = d.T / TT;
    const Vec3<NT>* A[2] = {&d.A0, &d.A1};
    const Cylinder<NT>* c[2] = {&d.c0, &d.c1};
    for (int i = 0; i < 2; ++i) {
      Ahat_[i] = unit_binade(*A[i]);
      AhatA_[i] = dot(Ahat_[i], *A[i]);
      k_[i] = two * c[i]->radius / nt::sqrt(dot(Ahat_[i], Ahat_[i]));
      axial_[i] = {dot(D0_, *A[i]), dot(U_, *A[i]), dot(V_, *A[i])};
      radial_[i] = {k_[i] * cross(D0_, Ahat_[i]), k_[i] * cross(U_, Ahat_[i]), k_[i] * cross(V_, Ahat_[i])};
    }
    scale_ = value_at(zero, zero);
    mu_final_ = scale_;
    for (int i = 0; i < mu_exponent; ++i) mu_final_ = mu_final_ / two;
  }

  // Runs the smoothing path. With stop_early, stops at the end of a smoothing level once the
  // unsmoothed value drops below 1 by more than the relative margin 2^-stop_exponent (a
  // separating direction in sight) or the dual point's scale sigma(X) does (an interior point
  // in sight). Both are measured at the returned D and X, not inferred from the smoothed problem
  // (the dual value lambda is only a bound once the level has converged).
  // stop() is asked before each Newton step; true returns the current iterate at once.
  template <class Stop = NeverStop>
  PlaneMinimum<NT> minimise(bool stop_early, int stop_exponent, Stop&& stop = Stop{}) {
    const NT zero = nt::constant<NT>(0), one = nt::constant<NT>(1);
    NT margin = one;
    for (int i = 0; i < stop_exponent; ++i) margin = margin / nt::constant<NT>(2);
    NT u = zero, v = zero;
    NT mu = scale_ / nt::constant<NT>(4);
    int iterations = 0;
    for (;;) {
      const bool last = nt::compare(mu, mu_final_) != CGAL::LARGER;
      const NT mu2 = mu * mu;
      const NT tolerance = last ? NT(mu_final_ * margin) : NT(mu / nt::constant<NT>(16));
      for (int it = 0; it < 60; ++it) {
        if (stop()) {
          PlaneMinimum<NT> m = result(u, v, mu2);
          m.iterations = iterations;
          return m;
        }
        Local l = local(u, v, mu2);
        // Newton step: H s = -g, with H symmetric positive definite (2 x 2, by Cramer's rule).
        const NT det = l.h00 * l.h11 - l.h01 * l.h01;
        if (!sign_is(det, CGAL::POSITIVE)) break;
        const NT su = (l.h01 * l.g1 - l.h11 * l.g0) / det;
        const NT sv = (l.h01 * l.g0 - l.h00 * l.g1) / det;
        const NT decrement = -(l.g0 * su + l.g1 * sv);
        ++iterations;
        if (nt::compare(decrement, tolerance) != CGAL::LARGER) break;
        // Backtracking line search on the smoothed objective.
        NT t = one;
        bool moved = false;
        for (int ls = 0; ls < 40; ++ls) {
          const NT un = u + t * su, vn = v + t * sv;
          const NT fn = smoothed_at(un, vn, mu2);
          if (nt::compare(fn, NT(l.f - t * decrement / nt::constant<NT>(4))) != CGAL::LARGER) {
            u = un;
            v = vn;
            moved = true;
            break;
          }
          t = t / nt::constant<NT>(2);
        }
        if (!moved) break;
      }
      if (stop_early || last) {
        PlaneMinimum<NT> m = result(u, v, mu2);
        m.iterations = iterations;
        if (last) return m;
        if (nt::compare(m.value, NT(one - margin)) == CGAL::SMALLER) return m;
        if (nt::compare(scale_at(m.point), NT(one - margin)) == CGAL::SMALLER) return m;
      }
      mu = mu / nt::constant<NT>(8);
      if (nt::compare(mu, mu_final_) == CGAL::SMALLER) mu = mu_final_;
    }
  }

 private:
  struct Affine1 {
    NT c, cu, cv;
    NT at(const NT& u, const NT& v) const { return c + u * cu + v * cv; }
  };
  struct Affine3 {
    Vec3<NT> c, cu, cv;
    Vec3<NT> at(const NT& u, const NT& v) const { return c + u * cu + v * cv; }
  };
  struct Local {
    NT f, g0, g1, h00, h01, h11;
  };

  // sigma(X): X lies in both cylinders scaled by sigma(X) about their midpoints.
  NT scale_at(const Point3<NT>& X) const {
    const NT two = nt::constant<NT>(2);
    NT sigma = nt::constant<NT>(0);
    const Cylinder<NT>* c[2] = {&d_.c0, &d_.c1};
    for (int i = 0; i < 2; ++i) {
      const NT axial = abs_enclosure(dot(two * X - c[i]->p0 - c[i]->p1, Ahat_[i])) / AhatA_[i];
      const Vec3<NT> w = cross(X - c[i]->p0, Ahat_[i]);
      const NT radial = nt::sqrt(dot(w, w) / (c[i]->radius * c[i]->radius * dot(Ahat_[i], Ahat_[i])));
      if (nt::compare(axial, sigma) == CGAL::LARGER) sigma = axial;
      if (nt::compare(radial, sigma) == CGAL::LARGER) sigma = radial;
    }
    return sigma;
  }

  Vec3<NT> direction_at(const NT& u, const NT& v) const { return D0_ + u * U_ + v * V_; }

  NT value_at(const NT& u, const NT& v) const {
    NT f = nt::constant<NT>(0);
    for (int i = 0; i < 2; ++i) {
      f = f + abs_enclosure(axial_[i].at(u, v));
      const Vec3<NT> w = radial_[i].at(u, v);
      f = f + nt::sqrt(dot(w, w));
    }
    return f;
  }

  NT smoothed_at(const NT& u, const NT& v, const NT& mu2) const {
    NT f = nt::constant<NT>(0);
    for (int i = 0; i < 2; ++i) {
      const NT a = axial_[i].at(u, v);
      f = f + nt::sqrt(a * a + mu2);
      const Vec3<NT> w = radial_[i].at(u, v);
      f = f + nt::sqrt(dot(w, w) + mu2);
    }
    return f;
  }

  // Value, gradient and Hessian of the smoothed objective at (u, v).
  Local local(const NT& u, const NT& v, const NT& mu2) const {
    const NT zero = nt::constant<NT>(0);
    Local l{zero, zero, zero, zero, zero, zero};
    for (int i = 0; i < 2; ++i) {
      // Axial term sqrt(a^2 + mu^2): gradient (a/t) grad a, Hessian (mu^2 / t^3) grad a grad a^T.
      const Affine1& ax = axial_[i];
      const NT a = ax.at(u, v);
      const NT t = nt::sqrt(a * a + mu2);
      l.f = l.f + t;
      l.g0 = l.g0 + a / t * ax.cu;
      l.g1 = l.g1 + a / t * ax.cv;
      const NT c = mu2 / (t * t * t);
      l.h00 = l.h00 + c * ax.cu * ax.cu;
      l.h01 = l.h01 + c * ax.cu * ax.cv;
      l.h11 = l.h11 + c * ax.cv * ax.cv;
      // Radial term sqrt(|w|^2 + mu^2): gradient J^T w / s, Hessian J^T J / s - (J^T w)(J^T w)^T / s^3.
      const Affine3& rd = radial_[i];
      const Vec3<NT> w = rd.at(u, v);
      const NT s = nt::sqrt(dot(w, w) + mu2);
      l.f = l.f + s;
      const NT jw0 = dot(rd.cu, w), jw1 = dot(rd.cv, w);
      l.g0 = l.g0 + jw0 / s;
      l.g1 = l.g1 + jw1 / s;
      const NT s3 = s * s * s;
      l.h00 = l.h00 + dot(rd.cu, rd.cu) / s - jw0 * jw0 / s3;
      l.h01 = l.h01 + dot(rd.cu, rd.cv) / s - jw0 * jw1 / s3;
      l.h11 = l.h11 + dot(rd.cv, rd.cv) / s - jw1 * jw1 / s3;
    }
    return l;
  }

  PlaneMinimum<NT> result(const NT& u, const NT& v, const NT& mu2) const {
    const NT two = nt::constant<NT>(2);
    const Vec3<NT>* A[2] = {&d_.A0, &d_.A1};
    Vec3<NT> Z[2];
    for (int i = 0; i < 2; ++i) {
      const NT a = axial_[i].at(u, v);
      const Vec3<NT> w = radial_[i].at(u, v);
      const NT ya = a / nt::sqrt(a * a + mu2);
      const Vec3<NT> yw = w / nt::sqrt(dot(w, w) + mu2);
      Z[i] = ya * *A[i] + k_[i] * cross(Ahat_[i], yw);
    }
    const NT lambda = dot(Z[0] + Z[1], d_.T) / dot(d_.T, d_.T);
    const Point3<NT> m0 = (d_.c0.p0 + d_.c0.p1) / two;
    const Point3<NT> m1 = (d_.c1.p0 + d_.c1.p1) / two;
    const NT twice_lambda = two * lambda;
    const Point3<NT> X = ((m0 + Z[0] / twice_lambda) + (m1 - Z[1] / twice_lambda)) / two;
    return {direction_at(u, v), X, value_at(u, v), lambda, 0};
  }

  // v times the power of two that brings its largest coordinate into [1, 2) in double, whose
  // exponent range the squared length of an axis 2^-600 long underflows (the radial terms and
  // the gauges below depend on the axis only up to a positive scale); v itself when it is zero or
  // not finite, and in the other types. (In double-double, the refine stage, the same scaling
  // made 3,000 random wide queries 7% slower in all: the pairs it let that stage decide are
  // decided about as fast by the exact candidates after it.)
  static Vec3<NT> unit_binade(const Vec3<NT>& v) {
    if constexpr (std::is_same_v<NT, double>) {
      const double m = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
      if (!(m > 0) || !std::isfinite(m)) return v;
      const int e = std::ilogb(m);
      return v.map([e](double x) { return std::ldexp(x, -e); });
    } else {
      return v;
    }
  }

  const CylinderPair<NT>& d_;
  Vec3<NT> U_, V_, D0_;
  Vec3<NT> Ahat_[2];  // the axes scaled by powers of two (unit_binade)
  NT AhatA_[2];       // Ahat_i.A_i
  NT k_[2];           // 2 r_i / |Ahat_i|
  Affine1 axial_[2];
  Affine3 radial_[2];
  NT scale_, mu_final_;
};

}  // namespace certcyl::detail
