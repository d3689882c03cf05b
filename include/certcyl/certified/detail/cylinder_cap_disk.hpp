// certcyl/certified/detail/cylinder_cap_disk.hpp -- candidate points beside a cap disk of one
// cylinder of a pair, for an overlap witness, and an estimate of a point's depth in a cylinder;
// in homogeneous coordinates over an exact ring R (Rational, or CGAL::Mpzf in the pair's ring
// frame, detail/cylinder_ring_frame.hpp).
//
// Semantics. HomogeneousPoint{n, w} is the point n / w, w > 0. For the cap plane through the end
// E of cylinder i (normal A_i) the candidates are (all candidates only: the caller checks each
// exactly, so a poor one costs time, never an answer):
//   without `rim`: Y0, where j's axis line crosses the cap plane (A_j.A_i != 0); Y1, the point
//     nearest E of the line where the cap plane meets j's mid-plane; Y2, the point nearest E of
//     j's axis line projected orthogonally onto the cap plane (both when A_i x A_j != 0);
//   with `rim`: the points of i's rim deepest into the half-space of each cap of j,
//     E + r_i u / s (u the part in the cap plane of that cap's inward normal, s >= |u| at
//     span + 128 bits raised by 2^(2 - q)), and the rim points nearest j's axis line
//     (detail/cylinder_rim_nearest.hpp) at twice the span plus 128 bits;
//   and, for a candidate in the open disk that lies on j's boundary (j's wall tangent to the cap
//   plane, or a rim of j meeting it), the candidate moved toward j's axis within the cap plane
//   (cap_disk_toward_axis).
// interior_slacks(Y, c) are the signs of classify_point(Y, c) without a division, so the exact
// check of a candidate; depth_binade(Y, c) is floor(log2) (within a few) of a lower bound on Y's distance from the
// boundary of c when Y is strictly inside c, nullopt otherwise: the least of the distances to
// the cap planes, m / |A| with m = min(u, A.A - u), u = (Y - p0).A, and to the wall,
// r - |x| / |A| >= (r^2 A.A - |x|^2) / (2 r A.A), x = (Y - p0) x A.
//
// Method. No division: each candidate is written over one positive denominator (for Y0,
// (a p_j + b A_j) / a with a = A_j.A_i; Y1 and Y2 over 2 |L|^4 and A_i.A_i |P|^2), and the depth
// over w and w^2: with V = n - w p0, u w = V.A, (A.A - u) w = w A.A - V.A and
// (r^2 A.A - |x|^2) w^2 = r^2 w^2 A.A - |V x A|^2. In Mpzf (every binary64 pair, and rational
// input with a ring frame) no product needs a gcd, which made these candidates, computed in Gmpq
// on non-dyadic points, the larger part of the cost of the slowest binary64 pairs.
#pragma once

#include <CGAL/Gmpfr.h>

#include <algorithm>
#include <array>
#include <optional>
#include <utility>
#include <vector>

#include "certcyl/certified/detail/cylinder_rim_nearest.hpp"
#include "certcyl/certified/detail/cylinder_ring_frame.hpp"
#include "certcyl/number_traits.hpp"
#include "certcyl/primitives.hpp"
#include "certcyl/vec3.hpp"

namespace certcyl::detail {

// Cylinder j of a pair and the other one, i, with their axes and squared lengths.
template <class R>
struct PairRoles {
  const Cylinder<R>& cj;
  const Cylinder<R>& ci;
  const Vec3<R>& Aj;
  const Vec3<R>& Ai;
  const R& AAj;
  const R& AAi;
};
template <class R>
PairRoles<R> pair_roles(const CylinderPair<R>& e, int j) {
  return j == 0 ? PairRoles<R>{e.c0, e.c1, e.A0, e.A1, e.AA0, e.AA1} : PairRoles<R>{e.c1, e.c0, e.A1, e.A0, e.AA1, e.AA0};
}

template <class R>
struct HomogeneousPoint {
  Point3<R> n;
  R w;  // > 0
};

// The slacks of classify_point for Y = n / w against c (axis A, A.A = AA), times w, w and w^2
// (> 0: the same signs): w (Y - p0).A, w (A.A - (Y - p0).A) and w^2 (r^2 A.A - |(Y - p0) x A|^2),
// with V = n - w p0; nullopt as soon as one is not positive (Y is not strictly inside c).
template <class R>
std::optional<std::array<R, 3>> interior_slacks(const HomogeneousPoint<R>& Y, const Cylinder<R>& c, const Vec3<R>& A, const R& AA) {
  const Vec3<R> V = Y.n - Y.w * c.p0;
  R u = dot(V, A);
  if (!(u > 0)) return std::nullopt;
  R rest = Y.w * AA - u;
  if (!(rest > 0)) return std::nullopt;
  const Vec3<R> X = cross(V, A);
  R tube = c.radius * c.radius * Y.w * Y.w * AA - dot(X, X);
  if (!(tube > 0)) return std::nullopt;
  return std::array<R, 3>{std::move(u), std::move(rest), std::move(tube)};
}

template <class R>
std::optional<long> depth_binade(const HomogeneousPoint<R>& Y, const Cylinder<R>& c, const Vec3<R>& A, const R& AA) {
  const std::optional<std::array<R, 3>> slack = interior_slacks(Y, c, A, AA);
  if (!slack) return std::nullopt;
  const auto& [u, rest, tube] = *slack;
  const long bw = binade(Y.w);
  return std::min(binade(std::min(u, rest)) - bw - binade(AA) / 2, binade(tube) - 2 * bw - binade(AA) - binade(c.radius) - 1);
}

// w^2 (r^2 - |Y - E|^2) for Y = n / w: positive iff Y is in the open disk of radius r about E
// (in its plane), and w^2 times Y's room in it.
template <class R>
R disk_room(const HomogeneousPoint<R>& Y, const Point3<R>& E, const R& r) {
  const Vec3<R> radial = Y.n - Y.w * E;
  return r * r * Y.w * Y.w - dot(radial, radial);
}

// max_k |v_k|.
template <class R>
R largest_coordinate(const Vec3<R>& v) {
  R m(0);
  for (const R* q : {&v.x, &v.y, &v.z})
    if (const R a = *q < 0 ? R(-*q) : *q; a > m) m = a;
  return m;
}

// A candidate Y = n / w in the open disk of i's cap (centre E, radius r_i, normal A_i) that is
// not strictly inside j (it lies on j's wall where the wall is tangent to the cap plane, or where
// a rim of j meets it): Y + s P with P the part in the cap plane of the direction from Y toward
// j's axis, |s P| about 2^-2 sqrt(r_i^2 - |Y - E|^2) (Y's room in the disk: moved across a
// tangent wall by d, a point leaves the disk by about d^2 / r_i); nullopt when Y is not in the
// open disk or P = 0. With V = n - w p_j: the part of Y - p_j orthogonal to A_j is
// Q / (w A_j.A_j), Q = A_j.A_j V - (V.A_j) A_j, and P = (Q.A_i) A_i - A_i.A_i Q.
template <class R>
std::optional<HomogeneousPoint<R>> cap_disk_toward_axis(const HomogeneousPoint<R>& Y, const Point3<R>& E, const R& ri, const Vec3<R>& Ai,
                                                        const R& AAi, const Cylinder<R>& cj, const Vec3<R>& Aj, const R& AAj) {
  const R room = disk_room(Y, E, ri);
  if (!(room > 0)) return std::nullopt;
  const Vec3<R> V = Y.n - Y.w * cj.p0;
  const Vec3<R> Q = AAj * V - dot(V, Aj) * Aj;
  const Vec3<R> P = dot(Q, Ai) * Ai - AAi * Q;
  const R largest = largest_coordinate(P);
  if (CGAL::is_zero(largest)) return std::nullopt;
  const long bw = binade(Y.w), room_binade = binade(room) - 2 * bw;
  const long target = (room_binade - (room_binade < 0 ? 1 : 0)) / 2 - 2;  // about log2 of the room's square root, less 2
  const long k = binade(largest) - bw - target;                        // |2^-k P / w| about 2^target
  return HomogeneousPoint<R>{Y.n + ring_two_power<R>(-k) * P, Y.w};
}

// The candidates on the cap plane through i's end p1 (far_end) or p0; span_bits the input's
// span (CylinderCylinderSolver::input_span_bits).
template <class R>
std::vector<HomogeneousPoint<R>> cap_disk_points(const CylinderPair<R>& e, int i, bool far_end, bool rim, long span_bits) {
  const auto [cj, ci, Aj, Ai, AAj, AAi] = pair_roles(e, 1 - i);
  const Point3<R>& E = far_end ? ci.p1 : ci.p0;
  const R zero(0), one(1), two(2);
  std::vector<HomogeneousPoint<R>> out;
  const R a = dot(Aj, Ai);
  if (!rim) {
    if (a != 0) {  // p_j + (b / a) A_j, b = (E - p_j).A_i
      const R b = dot(E - cj.p0, Ai);
      const Point3<R> n = a * cj.p0 + b * Aj;
      out.push_back(a > 0 ? HomogeneousPoint<R>{n, a} : HomogeneousPoint<R>{-n, -a});
    }
    const Vec3<R> L = cross(Ai, Aj);
    if (!(L.x == zero && L.y == zero && L.z == zero)) {
      const R LL = dot(L, L);
      // A point X0 = N0 / (2 LL) of the line {(X - E).A_i = 0} n {(X - m_j).A_j = 0}, m_j = p_j + A_j / 2
      // (h = A_i.E and 2 k = 2 A_j.p_j + A_j.A_j its planes' offsets), then the point nearest E:
      // X0 + ((E - X0).L / LL) L = (LL N0 + (2 LL E - N0).L L) / (2 LL^2).
      const R h2 = two * dot(Ai, E), k2 = two * dot(Aj, cj.p0) + AAj;
      const Vec3<R> N0 = (h2 * AAj - k2 * a) * Ai + (k2 * AAi - h2 * a) * Aj;
      const R W0 = two * LL;
      out.push_back({LL * N0 + dot(W0 * E - N0, L) * L, W0 * LL});
      // j's axis projected onto the cap plane: through Q0 = Nq / A_i.A_i along P = A_i.A_i A_j - a A_i
      // (not zero), and its point nearest E: (|P|^2 Nq + (A_i.A_i E - Nq).P P) / (A_i.A_i |P|^2).
      const Vec3<R> P = AAi * Aj - a * Ai;
      const Vec3<R> Nq = AAi * cj.p0 - dot(cj.p0 - E, Ai) * Ai;
      const R PP = dot(P, P);
      out.push_back({PP * Nq + dot(AAi * E - Nq, P) * P, AAi * PP});
    }
    return out;
  }
  const long q = span_bits + 128;
  for (const bool j_far : {false, true}) {
    // u = m - (m.A_i / A_i.A_i) A_i for the inward normal m of j's cap, as U = A_i.A_i u.
    const Vec3<R> m = j_far ? Vec3<R>(-Aj) : Aj;
    const Vec3<R> U = AAi * m - dot(m, Ai) * Ai;
    const R UU = dot(U, U);
    if (UU == zero) continue;
    R s;
    {
      GmpfrPrecision scope(q);
      s = ring_exact<R>(CGAL::sqrt(ring_gmpfr(UU)));
    }
    s = s + s * ring_two_power<R>(2 - q);  // s >= |U|: E + r_i U / s
    out.push_back({s * E + ci.radius * U, s});
  }
  for (Point3<R>& y : rim_points_nearest_line(E, Ai, ci.radius, cj.p0, Aj, cj.radius, 2 * span_bits + 128)) out.push_back({std::move(y), one});
  return out;
}

}  // namespace certcyl::detail
