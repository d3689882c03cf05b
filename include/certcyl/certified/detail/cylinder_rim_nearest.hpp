// certcyl/certified/detail/cylinder_rim_nearest.hpp -- the points of a cylinder's rim circle
// nearest another cylinder's axis line: candidates for an overlap witness where a rim dips into
// the other cylinder by far less than an ulp of its coordinates (a cap disk tilted against a
// wall it touches at one rim point, a wall grazing a cap plane beside the rim).
//
// Semantics. The rim circle C = {E + r (cos t u + sin t v)} (u, v an orthonormal basis of the
// cap plane, normal A_i) and the line L = {p + s A_j}:
//   g(t) = |w(t)|^2,  w(t) = P(E - p) + r cos t P(u) + r sin t P(v),
// the squared distance of the rim point to L, P the projection orthogonal to A_j. The result is
// the rim points at the local minima of g below r_j^2 (the rim points nearest L that can lie in
// the cylinder of radius r_j about it), rounded to rationals: candidates only, each checked
// exactly by the caller (which pulls it into the open disk and pushes it into cylinder i), so
// nothing here needs an error bound; a missed minimum costs time, never an answer.
//
// Method. The local minima of 64 samples of g in double (coefficients computed at 64 bits and
// scaled to their largest binade) are refined in double, and those whose double value of g exceeds r_j^2 by more than
// the rounding of the samples (2^-40 of the largest coefficient squared) are dropped. The rest
// are refined at `precision` bits (Gmpfr; the coefficients computed again), with
//   w' = r (cos t P(v) - sin t P(u)),  w'' = P(E - p) - w,  w''' = -w',  w'''' = w - P(E - p),
//   g' = 2 w.w',  g'' = 2 (w'.w' + w.w''),  g''' = 2 (3 w'.w'' + w.w'''),
//   g'''' = 2 w.w'''' + 8 w'.w''' + 6 w''.w'',
// by Newton's method on g'. Where it creeps (a flat minimum: a rim tangent to the other
// cylinder at a point where g' has a near-triple root, opened far below an ulp), Newton's
// method on g''' finds the inflection x_c, and the real roots of the cubic model
// g'(x_c) + g''(x_c) y + g''''(x_c) y^3 / 6 (solved in double after scaling y to the binade
// where its terms balance) start Newton's method on g' again, now inside its quadratic basin.
// A step h rotates (c, s) to (c - h s, s + h c) / sqrt(1 + h^2), an angle of atan(h) = h +
// O(h^3). Newton stops on a step below 2^(8 - precision) or on steps that no longer shrink below
// 2^(-precision / 2) (the rounding noise), at most 24 steps; points with g'' > 0 are kept.
#pragma once

#include <CGAL/Gmpfr.h>
#include <mpfr.h>

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <numbers>
#include <vector>

#include "certcyl/certified/detail/cylinder_ellipsoid.hpp"
#include "certcyl/certified/detail/cylinder_ring_frame.hpp"
#include "certcyl/number_traits.hpp"
#include "certcyl/primitives.hpp"
#include "certcyl/vec3.hpp"

namespace certcyl::detail {

// g = |w|^2 and its first four derivatives (index k: the k-th) at the angle whose cosine and sine
// are c and s, for w = a0 + a1 c + a2 s (the formulas above), in double or Gmpfr.
template <class T>
std::array<T, 5> rim_distance_derivatives(const Vec3<T>& a0, const Vec3<T>& a1, const Vec3<T>& a2, const T& c, const T& s) {
  const T two = nt::constant<T>(2), three = nt::constant<T>(3), six = nt::constant<T>(6), eight = nt::constant<T>(8);
  const Vec3<T> w = a0 + a1 * c + a2 * s, w1 = a2 * c - a1 * s, w2 = a0 - w;
  const T ww1 = dot(w, w1), w1w1 = dot(w1, w1), ww2 = dot(w, w2), w2w2 = dot(w2, w2);
  return {dot(w, w), two * ww1, two * (w1w1 + ww2), two * (three * dot(w1, w2) - ww1), -two * ww2 - eight * w1w1 + six * w2w2};
}

// In an exact ring (Rational, or CGAL::Mpzf in a pair's ring frame).
template <class Ring>
std::vector<Point3<Ring>> rim_points_nearest_line(const Point3<Ring>& E, const Vec3<Ring>& Ai, const Ring& r, const Point3<Ring>& p, const Vec3<Ring>& Aj,
                                               const Ring& rj, long precision) {
  using F = CGAL::Gmpfr;
  std::vector<Point3<Ring>> out;
  const auto f = [](const Ring& q) { return ring_gmpfr(q); };
  const auto fv = [&f](const Vec3<Ring>& q) { return Vec3<F>{f(q.x), f(q.y), f(q.z)}; };
  // u: A_i x e_k for the axis e_k of A_i's smallest component; v = A_i x u; both normalised.
  const auto magnitude = [](const Ring& x) { return x < 0 ? Ring(-x) : x; };
  const Ring ax = magnitude(Ai.x), ay = magnitude(Ai.y), az = magnitude(Ai.z), zero(0), unit(1);
  const Vec3<Ring> e = ax <= ay && ax <= az ? Vec3<Ring>{unit, zero, zero} : ay <= az ? Vec3<Ring>{zero, unit, zero} : Vec3<Ring>{zero, zero, unit};
  const Vec3<Ring> U = cross(Ai, e), V = cross(Ai, U), EP = E - p;
  struct Frame {
    Vec3<F> u, v, a0, a1, a2;
    F r;
  };
  // The basis and the coefficients of w at the scope's precision.
  // E - p is exact before the projection: a line far from E would cancel every bit of E.
  const auto frame = [&]() {
    const Vec3<F> u = fv(U) / CGAL::sqrt(f(dot(U, U))), v = fv(V) / CGAL::sqrt(f(dot(V, V)));
    const Vec3<F> aj = fv(Aj);
    const F ajj = f(dot(Aj, Aj)), rf = f(r);
    const auto P = [&](const Vec3<F>& x) { return x - (dot(x, aj) / ajj) * aj; };
    return Frame{u, v, P(fv(EP)), P(u) * rf, P(v) * rf, rf};
  };
  // The samples and the filter need only 64 bits: the precision is paid for by the minima kept.
  const Frame low = [&] {
    GmpfrPrecision scope(64);
    return frame();
  }();
  const Vec3<F>&a0 = low.a0, &a1 = low.a1, &a2 = low.a2;

  // Double samples, scaled by 2^-ex (ex the largest coefficient's exponent).
  long ex = LONG_MIN;
  for (const Vec3<F>* a : {&a0, &a1, &a2})
    for (const F* c : {&a->x, &a->y, &a->z}) ex = std::max(ex, gmpfr_exponent(*c));
  if (ex == LONG_MIN) return out;
  const auto scaled = [ex](const Vec3<F>& a) {
    return Vec3<double>{gmpfr_scaled_double(a.x, ex), gmpfr_scaled_double(a.y, ex), gmpfr_scaled_double(a.z, ex)};
  };
  const Vec3<double> A0 = scaled(a0), A1 = scaled(a1), A2 = scaled(a2);
  const double R = [&] {
    GmpfrPrecision scope(64);
    return gmpfr_scaled_double(f(rj * rj), 2 * ex);
  }();
  // g and its derivatives at t, in double.
  const auto derivatives = [&](double t) { return rim_distance_derivatives(A0, A1, A2, std::cos(t), std::sin(t)); };
  constexpr int n = 64;
  double g[n];
  for (int k = 0; k < n; ++k) g[k] = derivatives(2 * std::numbers::pi * k / n)[0];
  std::vector<double> starts;
  for (int k = 0; k < n; ++k) {
    if (!(g[k] <= g[(k + n - 1) % n] && g[k] < g[(k + 1) % n])) continue;
    double t = 2 * std::numbers::pi * k / n;
    std::array<double, 5> d;
    for (int it = 0; it < 30; ++it) {
      d = derivatives(t);
      const double den = d[2] * d[2] - d[1] * d[3];
      if (!(den != 0) || !std::isfinite(den)) break;
      const double h = -d[1] * d[2] / den;
      t += std::clamp(h, -0.5, 0.5);
      if (std::abs(h) < 1e-15) break;
    }
    d = derivatives(t);
    if (!(d[0] <= R + 0x1p-40)) continue;
    if (std::any_of(starts.begin(), starts.end(), [t](double s) { return std::abs(std::remainder(s - t, 2 * std::numbers::pi)) < 1e-9; }))
      continue;
    starts.push_back(t);
  }

  if (starts.empty()) return out;
  GmpfrPrecision scope(precision);
  const Frame high = frame();
  const Vec3<F>&u = high.u, &v = high.v, &b0 = high.a0, &b1 = high.a1, &b2 = high.a2;
  const F& rf = high.r;
  const F one = nt::constant<F>(1), six = nt::constant<F>(6);
  struct Angle {
    F c, s;
  };
  const auto derivatives_at = [&](const Angle& a) { return rim_distance_derivatives(b0, b1, b2, a.c, a.s); };
  const auto rotate = [&one](Angle& a, const F& h) {
    const F norm = CGAL::sqrt(one + h * h);
    const F c = (a.c - h * a.s) / norm, s = (a.s + h * a.c) / norm;
    a = {c, s};
  };
  // Newton's method on g' (k = 1) or g''' (k = 3), at most 24 steps; true when the steps reach
  // the working precision or stop shrinking below half of it (the rounding noise).
  const auto newton = [&](Angle& a, int k) {
    long previous = LONG_MAX;
    for (int it = 0; it < 24; ++it) {
      const std::array<F, 5> d = derivatives_at(a);
      if (!(d[k + 1] != 0)) return false;
      const F h = -d[k] / d[k + 1];
      const long eh = gmpfr_exponent(h);
      if (eh > -2) return false;  // a step of a quarter radian or more: not near the root
      rotate(a, h);
      if (eh < 8 - precision || (eh < -precision / 2 && eh >= previous - 1)) return true;
      previous = eh;
    }
    return false;
  };
  const auto keep = [&](const Angle& a) {
    if (!(derivatives_at(a)[2] > 0)) return;
    const Vec3<F> x = (u * a.c + v * a.s) * rf;
    out.push_back(E + x.map([](const F& c) { return ring_exact<Ring>(c); }));
  };
  for (const double t0 : starts) {
    Angle start{F(std::cos(t0), precision), F(std::sin(t0), precision)};
    {
      const F norm = CGAL::sqrt(start.c * start.c + start.s * start.s);
      start = {start.c / norm, start.s / norm};
    }
    if (Angle a = start; newton(a, 1)) {
      keep(a);
      continue;
    }
    // A flat minimum (Newton creeps: g' has a near-triple root). The inflection x_c of g' (the
    // root of g''', simple there), then the roots of the cubic model at x_c,
    // g' + g'' y + g'''' y^3 / 6 (g''' = 0), solved in double after scaling y by 2^e, the
    // binade where its terms balance, and each polished by Newton's method on g'.
    Angle xc = start;
    if (!newton(xc, 3)) continue;
    const std::array<F, 5> d = derivatives_at(xc);
    if (!(d[4] != 0)) continue;
    const F p = six * d[2] / d[4], q = six * d[1] / d[4];
    const long ep = gmpfr_exponent(p), eq = gmpfr_exponent(q);
    long e = LONG_MIN;
    if (ep != LONG_MIN) e = (ep + 1) / 2 + 1;
    if (eq != LONG_MIN) e = std::max(e, eq / 3 + 1);
    if (e == LONG_MIN) continue;
    const double P = gmpfr_scaled_double(p, 2 * e), Q = gmpfr_scaled_double(q, 3 * e);  // z^3 + P z + Q = 0, y = 2^e z
    std::vector<double> zs;
    const double disc = Q * Q / 4 + P * P * P / 27;
    if (disc > 0) {
      const double root = std::sqrt(disc);
      zs.push_back(std::cbrt(-Q / 2 + root) + std::cbrt(-Q / 2 - root));
    } else {
      const double m = 2 * std::sqrt(-P / 3), phi = std::acos(std::clamp(3 * Q / (P * m), -1.0, 1.0)) / 3;
      for (int k = 0; k < 3; ++k) zs.push_back(m * std::cos(phi - 2 * std::numbers::pi * k / 3));
    }
    for (double z : zs) {
      for (int it = 0; it < 8; ++it) {
        const double slope = 3 * z * z + P;
        if (slope == 0) break;
        z -= (z * z * z + P * z + Q) / slope;
      }
      F y(z, precision);
      mpfr_mul_2si(y.fr(), y.fr(), e, MPFR_RNDN);
      Angle a = xc;
      rotate(a, y);
      if (newton(a, 1)) keep(a);
    }
  }
  return out;
}

}  // namespace certcyl::detail
