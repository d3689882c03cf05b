// An independent exact answer for triangle against cylinder, used to test the certified
// predicate. It shares no code with include/certcyl/certified/: instead of clipping the
// triangle and walking the clipped polygon, it parametrises the triangle barycentrically,
// X = v0 + a e1 + b e2, and minimises the convex quadratic q(a, b) = |(X - P) x A|^2 over the
// polygon {a >= 0, b >= 0, a + b <= 1, 0 <= s(a, b) <= A.A} by enumerating active sets:
//   every feasible intersection of two constraint lines (the polygon's vertices),
//   the minimiser of q along every constraint line (where q is not constant along it),
//   the unconstrained minimiser (where q's Hessian is definite).
// A convex function's minimum over a polygon is at one of these points (if q's set of
// minimisers is a line or the plane, it meets the polygon's boundary at a vertex or at a
// line minimiser). Then, with open = (max s_i > 0 and min s_i < A.A):
//   empty polygon: separated; open: m < R overlapping, m = R touching, m > R separated;
//   not open: m <= R touching, else separated.
#pragma once

#include <array>
#include <optional>

#include "certcyl/answer.hpp"
#include "certcyl/primitives.hpp"

namespace oracle {

using certcyl::Answer;
using certcyl::Rational;
using V3 = certcyl::Vec3<Rational>;

// a * alpha + b * beta + c >= 0
struct HalfPlane {
  Rational a, b, c;
};

inline Answer triangle_cylinder(const certcyl::Triangle<Rational>& T, const certcyl::Cylinder<Rational>& C) {
  const V3 A = C.p1 - C.p0;
  const Rational AA = certcyl::dot(A, A);
  const Rational R = C.radius * C.radius * AA;
  const V3 e1 = T.v[1] - T.v[0], e2 = T.v[2] - T.v[0], w0 = T.v[0] - C.p0;
  const Rational s0 = certcyl::dot(w0, A), s1 = certcyl::dot(T.v[1] - C.p0, A), s2 = certcyl::dot(T.v[2] - C.p0, A);
  const V3 u0 = certcyl::cross(w0, A), u1 = certcyl::cross(e1, A), u2 = certcyl::cross(e2, A);

  const std::array<HalfPlane, 5> H{{{1, 0, 0},
                                    {0, 1, 0},
                                    {-1, -1, 1},
                                    {s1 - s0, s2 - s0, s0},
                                    {s0 - s1, s0 - s2, AA - s0}}};
  const auto feasible = [&](const Rational& a, const Rational& b) {
    for (const HalfPlane& h : H)
      if (h.a * a + h.b * b + h.c < 0) return false;
    return true;
  };
  const auto q = [&](const Rational& a, const Rational& b) {
    const V3 u = u0 + a * u1 + b * u2;
    return certcyl::dot(u, u);
  };
  std::optional<Rational> best;
  const auto consider = [&](const Rational& a, const Rational& b) {
    if (!feasible(a, b)) return;
    const Rational v = q(a, b);
    if (!best || v < *best) best = v;
  };

  // Vertices: pairs of constraint lines.
  for (int i = 0; i < 5; ++i)
    for (int j = i + 1; j < 5; ++j) {
      const HalfPlane &h = H[i], &g = H[j];
      const Rational det = h.a * g.b - g.a * h.b;
      if (det == 0) continue;
      consider((g.c * h.b - h.c * g.b) / det, (g.a * h.c - h.a * g.c) / det);
    }
  // Minimisers along each constraint line.
  for (const HalfPlane& h : H) {
    if (h.a == 0 && h.b == 0) continue;
    const Rational pa = h.a != 0 ? Rational(-h.c / h.a) : Rational(0);
    const Rational pb = h.a != 0 ? Rational(0) : Rational(-h.c / h.b);
    const Rational da = -h.b, db = h.a;
    const V3 U0 = u0 + pa * u1 + pb * u2;
    const V3 Ud = da * u1 + db * u2;
    const Rational dd = certcyl::dot(Ud, Ud);
    if (dd == 0) continue;
    const Rational t = -certcyl::dot(U0, Ud) / dd;
    consider(pa + t * da, pb + t * db);
  }
  // Unconstrained minimiser: [g11 g12; g12 g22] (a, b) = -(u0.u1, u0.u2).
  const Rational g11 = certcyl::dot(u1, u1), g12 = certcyl::dot(u1, u2), g22 = certcyl::dot(u2, u2);
  const Rational det = g11 * g22 - g12 * g12;
  if (det != 0) {
    const Rational r1 = -certcyl::dot(u0, u1), r2 = -certcyl::dot(u0, u2);
    consider((r1 * g22 - g12 * r2) / det, (g11 * r2 - g12 * r1) / det);
  }

  if (!best) return Answer::separated;
  const Rational smax = std::max({s0, s1, s2}), smin = std::min({s0, s1, s2});
  const bool open = smax > 0 && smin < AA;
  if (open) return *best < R ? Answer::overlapping : (*best == R ? Answer::touching : Answer::separated);
  return *best <= R ? Answer::touching : Answer::separated;
}

}  // namespace oracle
