// Shared constructions for the certified cylinder-cylinder tests: exactly touching pairs for each
// contact type, rational rigid motions, and an independent exact check of every certificate.
#pragma once

#include <CGAL/CORE_Expr.h>

#include <array>
#include <cmath>
#include <initializer_list>
#include <random>
#include <string>
#include <vector>

#include "certcyl/certified/cylinder_cylinder.hpp"

namespace cctest {

using certcyl::Cylinder;
using certcyl::Point3;
using certcyl::Vec3;
using Q = certcyl::Rational;

inline Cylinder<Q> cyl(Point3<Q> p0, Point3<Q> p1, Q r) { return {p0, p1, r}; }

// A random binary64 cylinder: midpoint uniform in [-1, 1]^3, axis direction uniform, length in
// [0.2, 2], radius in [0.05, 0.5] (the random pairs of the tests and the benchmarks).
inline Cylinder<double> random_cylinder(std::mt19937_64& g) {
  using D3 = Vec3<double>;
  std::uniform_real_distribution<double> u(-1, 1), len(0.2, 2), rad(0.05, 0.5);
  D3 w;
  double n2;
  do {
    w = {u(g), u(g), u(g)};
    n2 = dot(w, w);
  } while (n2 < 0.01 || n2 > 1);
  const double h = len(g) / (2 * std::sqrt(n2));
  const D3 c{u(g), u(g), u(g)};
  return {c - h * w, c + h * w, rad(g)};
}

// A rational rotation from the integer quaternion (a, b, c, d): the usual matrix divided by
// a^2 + b^2 + c^2 + d^2, exactly orthogonal.
struct Rotation {
  std::array<std::array<Q, 3>, 3> m;
  static Rotation from_quaternion(long a, long b, long c, long d) {
    const Q n(a * a + b * b + c * c + d * d);
    Rotation r;
    r.m = {{{Q(a * a + b * b - c * c - d * d) / n, Q(2 * (b * c - a * d)) / n, Q(2 * (b * d + a * c)) / n},
            {Q(2 * (b * c + a * d)) / n, Q(a * a - b * b + c * c - d * d) / n, Q(2 * (c * d - a * b)) / n},
            {Q(2 * (b * d - a * c)) / n, Q(2 * (c * d + a * b)) / n, Q(a * a - b * b - c * c + d * d) / n}}};
    return r;
  }
  Vec3<Q> operator()(const Vec3<Q>& v) const {
    return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
            m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
  }
};

// A random rotation computed in double (a normalised Gaussian quaternion), applied in double:
// rounded(c) is cylinder c times `scale`, turned and rounded to binary64, so a touching pair
// ends within about an ulp of touching, on either side (the "rounded" frame of the tests and of
// bench/bench_cylinder_hard.cpp).
struct RoundedRotation {
  double m[3][3];
  double scale = 1;
  RoundedRotation(std::mt19937_64& g, std::normal_distribution<double>& gauss, double s) : scale(s) {
    double w[4], norm = 0;
    for (double& x : w) x = gauss(g), norm += x * x;
    norm = std::sqrt(norm);
    for (double& x : w) x /= norm;
    const double a = w[0], b = w[1], c = w[2], d = w[3];
    const double r[3][3] = {{a * a + b * b - c * c - d * d, 2 * (b * c - a * d), 2 * (b * d + a * c)},
                            {2 * (b * c + a * d), a * a - b * b + c * c - d * d, 2 * (c * d - a * b)},
                            {2 * (b * d - a * c), 2 * (c * d + a * b), a * a - b * b - c * c + d * d}};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) m[i][j] = r[i][j];
  }
  Point3<double> operator()(const Point3<Q>& p) const {
    const double x = scale * CGAL::to_double(p.x), y = scale * CGAL::to_double(p.y), z = scale * CGAL::to_double(p.z);
    return {m[0][0] * x + m[0][1] * y + m[0][2] * z, m[1][0] * x + m[1][1] * y + m[1][2] * z, m[2][0] * x + m[2][1] * y + m[2][2] * z};
  }
  Cylinder<double> rounded(const Cylinder<Q>& c) const { return {(*this)(c.p0), (*this)(c.p1), scale * CGAL::to_double(c.radius)}; }
};

// X -> R X + t, applied to a cylinder (radius unchanged): the answer is unchanged exactly.
inline Cylinder<Q> move(const Cylinder<Q>& c, const Rotation& R, const Vec3<Q>& t) { return {R(c.p0) + t, R(c.p1) + t, c.radius}; }
inline Cylinder<Q> translate(const Cylinder<Q>& c, const Vec3<Q>& t) { return {c.p0 + t, c.p1 + t, c.radius}; }
inline Cylinder<Q> scale(const Cylinder<Q>& c, const Q& s) { return {s * c.p0, s * c.p1, s * c.radius}; }
inline Cylinder<Q> flip(const Cylinder<Q>& c) { return {c.p1, c.p0, c.radius}; }

// An exactly touching pair with its unit contact normal n (from a to b), the expected contact
// type, and the contact point when the contact is a single point.
struct TouchingCase {
  std::string name, type;
  Cylinder<Q> a, b;
  Vec3<Q> normal;
  bool point_contact;
  Point3<Q> contact;
};

// The seven base configurations (axis-aligned or with Pythagorean normals; pictures in the
// comments are side views in the xz-plane).
inline std::vector<TouchingCase> base_touching_cases() {
  std::vector<TouchingCase> cases;
  const Cylinder<Q> a{{0, 0, 0}, {0, 0, 2}, Q(1)};  // z in [0, 2], radius 1
  const Vec3<Q> ez{0, 0, 1}, ex{1, 0, 0};
  const Vec3<Q> n{Q(3, 5), 0, Q(4, 5)};  // unit, rational
  const Point3<Q> P{1, 0, 2};            // a's rim point with normal n: a's support point in direction n
  //  b on top of a, caps coplanar at z = 2, disks centred 1 apart.
  cases.push_back({"cap-cap", "cap-cap", a, cyl({1, 0, 2}, {1, 0, 5}, 1), ez, false, {}});
  //  b lies on a's top cap, axis along x at height 3.
  cases.push_back({"cap-wall", "cap-wall", a, cyl({-1, 0, 3}, {1, 0, 3}, 1), ez, false, {}});
  //  crossing axes (z and y) at distance 2, radii 1: contact at (1, 0, 0).
  cases.push_back(
      {"wall-wall crossing", "wall-wall", cyl({0, 0, -1}, {0, 0, 1}, 1), cyl({2, -1, 0}, {2, 1, 0}, 1), ex, true, {1, 0, 0}});
  //  parallel axes at distance 2, overlapping in z on [1, 2]: contact along a segment.
  cases.push_back({"wall-wall parallel", "wall-wall", a, cyl({2, 0, 1}, {2, 0, 3}, 1), ex, false, {}});
  //  b's bottom cap (normal n) rests on a's rim at P.
  cases.push_back({"rim-cap", "rim-cap", a, cyl(P + Vec3<Q>{0, Q(1, 2), 0}, P + Vec3<Q>{Q(6, 5), Q(1, 2), Q(8, 5)}, 1), n, true, P});
  //  b's wall (axis (4,5,-3), orthogonal to n, through P + n) touches a's rim at P.
  {
    const Point3<Q> q = P + n;
    const Vec3<Q> h{1, Q(5, 4), Q(-3, 4)};
    cases.push_back({"rim-wall", "rim-wall", a, cyl(q - h, q + h, 1), n, true, P});
  }
  //  b is a reflected through P, then turned a quarter about n: rim against rim at P.
  {
    auto quarter = [&](const Vec3<Q>& v) { return cross(n, v) + dot(n, v) * n; };  // rotation by 90 degrees about n
    cases.push_back({"rim-rim", "rim-rim", a, cyl(P + quarter(P - a.p0), P + quarter(P - a.p1), 1), n, true, P});
  }
  return cases;
}

inline TouchingCase moved(const TouchingCase& c, const Rotation& R, const Vec3<Q>& t) {
  return {c.name, c.type, move(c.a, R, t), move(c.b, R, t), R(c.normal), c.point_contact, R(c.contact) + t};
}

// ---- independent exact checks (written apart from the library's own) --------------------------

// X strictly inside (or in the closed) cylinder c, straight from the definition.
inline int position(const Point3<Q>& X, const Cylinder<Q>& c) {  // 1 inside, 0 boundary, -1 outside
  const Vec3<Q> A = c.p1 - c.p0, w = X - c.p0;
  const Q s = w.x * A.x + w.y * A.y + w.z * A.z;
  const Q AA = A.x * A.x + A.y * A.y + A.z * A.z;
  const Q ww = w.x * w.x + w.y * w.y + w.z * w.z;
  const Q radial = c.radius * c.radius * AA - (ww * AA - s * s);  // |w x A|^2 = |w|^2 |A|^2 - (w.A)^2
  if (s < 0 || s > AA || radial < 0) return -1;
  if (s == 0 || s == AA || radial == 0) return 0;
  return 1;
}

// x 2^-e with 2^e near the largest magnitude among xs (exact); 1 for all zero.
inline Q power_of_two_scale(std::initializer_list<Q> xs) {
  double m = 0;
  for (const Q& x : xs) m = std::max(m, std::abs(CGAL::to_double(x)));
  if (!(m > 0)) return Q(1);
  int e;
  std::frexp(m, &e);
  Q f(1);
  if (e > 0) mpq_div_2exp(f.mpq(), f.mpq(), static_cast<mp_bitcnt_t>(e));
  if (e < 0) mpq_mul_2exp(f.mpq(), f.mpq(), static_cast<mp_bitcnt_t>(-e));
  return f;
}

// sign(|D.Delta| - phi(D)) in CORE::Expr with square roots (not by squaring). The sign is
// homogeneous in the input and in D, so both are first scaled by powers of two to magnitudes
// near 1: CORE's floating filter misjudges signs of values near the subnormal range.
inline int separation_sign_core(const Cylinder<Q>& a0, const Cylinder<Q>& b0, const Vec3<Q>& D0) {
  const Q f = power_of_two_scale({a0.p0.x, a0.p0.y, a0.p0.z, a0.p1.x, a0.p1.y, a0.p1.z, a0.radius, b0.p0.x, b0.p0.y, b0.p0.z, b0.p1.x,
                                  b0.p1.y, b0.p1.z, b0.radius});
  const Cylinder<Q> a = scale(a0, f), b = scale(b0, f);
  const Vec3<Q> D = power_of_two_scale({D0.x, D0.y, D0.z}) * D0;
  using E = CORE::Expr;
  auto e = [](const Q& q) { return E(CORE::BigRat(q.mpq())); };
  const Vec3<Q> A0 = a.p1 - a.p0, A1 = b.p1 - b.p0;
  const Vec3<Q> delta = ((b.p0 + b.p1) - (a.p0 + a.p1)) / Q(2);
  auto absq = [](const Q& q) { return q < 0 ? Q(-q) : q; };
  const Vec3<Q> c0 = cross(D, A0), c1 = cross(D, A1);
  const E phi = e(absq(dot(D, A0)) / 2) + e(absq(dot(D, A1)) / 2) + e(a.radius) * CORE::sqrt(e(dot(c0, c0)) / e(dot(A0, A0))) +
                e(b.radius) * CORE::sqrt(e(dot(c1, c1)) / e(dot(A1, A1)));
  return CGAL::sign(e(absq(dot(D, delta))) - phi);
}

// Checks the certificate of r exactly and independently; returns "" or what is wrong.
inline std::string certificate_error(const Cylinder<Q>& a, const Cylinder<Q>& b, const certcyl::CylinderCylinderResult& r) {
  // The certificates as exact rationals, whichever field holds them.
  const auto direction = r.exact_direction();
  const auto witness = r.exact_witness();
  using certcyl::Answer;
  const certcyl::CylinderGap gap = r.gap();
  switch (r.answer) {
    case Answer::separated:
      if (!direction) return "separated without a direction";
      if (separation_sign_core(a, b, *direction) <= 0) return "direction does not separate";
      if (gap.known && !(gap.phi_lower < 1)) return "separated but phi_lower >= 1";
      return "";
    case Answer::overlapping:
      if (!witness) return "overlapping without a witness";
      if (position(*witness, a) != 1 || position(*witness, b) != 1) return "witness not interior to both";
      if (gap.known && !(gap.phi_upper > 1)) return "overlapping but phi_upper <= 1";
      return "";
    case Answer::touching:
      if (!direction || !witness || !r.contact) return "touching without a contact";
      if (separation_sign_core(a, b, *direction) != 0) return "contact normal does not support both";
      if (position(*witness, a) < 0 || position(*witness, b) < 0) return "contact point not in both";
      return "";
    case Answer::undecided:
      if (!gap.known || !(gap.phi_lower <= 1 && 1 <= gap.phi_upper)) return "undecided without a bound containing 1";
      return "";
  }
  return "unknown answer";
}

}  // namespace cctest
