// study/gap.hpp -- the certified answer of a study instance and its certified signed gap.
//
// THE SIGNED GAP, one definition per query (paper, section "The signed gap", and the appendix
// lemma "depth margin", which proves what follows).
//
// (1) Line, ray, segment, triangle, point against a circular or elliptic cylinder C: the DEPTH
// MARGIN
//     G(X, C) = max over x in X of d(x),   d(x) = min( 1 - q(x), s(x), 1 - s(x) ),
// X the query set (the line's allowed parameter range, the segment, the triangle, the point), in
// the cylinder's own coordinates: s(x) the axial coordinate (circular: (x-P).A / A.A; elliptic:
// z of M^-1 (x - base)) and q(x) the squared radial coordinate (circular: |(x-P) x A|^2 /
// (r^2 A.A); elliptic: x^2 + y^2). The maximum exists (d is continuous and tends to -infinity
// along an unbounded X) and G <= 1/2. G is dimensionless: one unit is a change of r^2 in the
// squared radius and of one height h = |A| in each cap position, at the same time:
//   d(x) >= delta  iff  x is in C_delta = { q <= 1 - delta, delta <= s <= 1 - delta },
// the cylinder offset by delta (radius r sqrt(1 - delta), each cap moved inward by delta h;
// delta < 0 grows it). Hence, exactly (lemma "depth margin"):
//   sign(G - delta) = the answer of X against C_delta (+1 overlapping, 0 touching, -1 separated)
// for every delta <= 1/2, so sign(G) is the answer for C itself, and |G| is the EXACT size of
// the smallest offset of the cylinder that changes the answer: every offset delta with
// |delta| < |G| (delta of either sign) leaves the answer as it is, and C_G touches X. It is
// not an upper or lower bound of that size but the size itself; the study reports a certified
// enclosure [lo, hi] of it, lo <= G <= hi, with lo = hi = G when G is found exactly.
// Euclidean consequence (the same lemma): with h = |A| and r the radius (circular cylinder),
// X is at Euclidean distance at least  min( r (sqrt(1 - G) - 1), -G h )  from C when G < 0,
// and contains a point at depth at least  min( r (1 - sqrt(1 - G)), G h )  inside C when G > 0;
// so no translation of X shorter than that changes the answer.
// For a point, G = d(x) exactly. Computing G: exact rational comparisons of G with dyadic or
// rational delta (compare_line_margin, compare_triangle_margin: the exact answer against
// C_delta, in Gmpq), seeded by exact values of d at rational points of X (lower bounds of G)
// and, for line-like sets, by interval enclosures of the crossings of 1 - q with s and with
// 1 - s (roots of quadratics with exact rational coefficients), each only a guess until two
// exact comparisons bracket G; otherwise bisection. No tolerance: every bound is proved by an
// exact comparison or by G <= 1/2.
//
// (2) Cylinder against cylinder: the LOG GROWTH FACTOR
//     G = log(phi*) = -log(sigma*),
// sigma* = 1/phi* the growth distance: both cylinders scaled about their own midpoints by
// sigma* just touch (design note section 4). A different quantity from (1), also
// dimensionless: |G| is the exact amount, in natural log units of a common scale factor, by
// which both cylinders must be scaled to change the answer; reported as the certified enclosure
// of certified_cylinder_cylinder (not tight). Equal midpoints: +infinity (null in JSON).
// Euclidean consequence: for G < 0 the cylinders are at distance at least
// 2 (sigma* - 1) min(r_i, h_i / 2), for G > 0 they share a point at depth at least
// (1 - sigma*) min(r_i, h_i / 2) in both.
//
// Panels, tables and pages that show a gap say which of the two it is: "depth margin G" for (1),
// "log(phi*)" for (2); the study never pools the two on one axis. Machine-readable output names
// them depth_margin and log_phi (study/gap_quantity.hpp).
//
// The study checks the gap's sign against the certified answer on every instance.
#pragma once

#include <CGAL/Interval_nt.h>
#include <gmp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

#include "certcyl/certified/cylinder_cylinder.hpp"
#include "certcyl/certified/line_cylinder.hpp"
#include "certcyl/certified/triangle_cylinder.hpp"
#include "study/contract.hpp"
#include "study/gap_quantity.hpp"
#include "study/instance.hpp"

namespace certcyl::study {

// A certified enclosure lo <= G <= hi of a depth margin G (exact: lo == hi).
struct MarginEnclosure {
  Rational lo, hi;
  bool exact() const { return lo == hi; }
};

namespace detail {

// min over t in [lo, hi] (either end may be open to infinity; lo <= hi) of a t^2 + b t + c, a >= 0.
inline Rational min_quadratic(const Rational& a, const Rational& b, const Rational& c, const std::optional<Rational>& lo,
                              const std::optional<Rational>& hi) {
  Rational t = 0;
  if (a == 0) {
    // b == 0 for a squared length with a == 0: q is constant.
    t = lo ? *lo : (hi ? *hi : Rational(0));
  } else {
    t = -b / (2 * a);
    if (lo && t < *lo) t = *lo;
    if (hi && t > *hi) t = *hi;
  }
  return (a * t + b) * t + c;
}

// 2^e as a rational.
inline Rational power_of_two(long e) {
  Rational r(1);
  mpq_t t;
  mpq_init(t);
  mpq_set_ui(t, 1, 1);
  if (e >= 0) mpq_mul_2exp(t, t, static_cast<mp_bitcnt_t>(e));
  else mpq_div_2exp(t, t, static_cast<mp_bitcnt_t>(-e));
  r = Rational(t);
  mpq_clear(t);
  return r;
}

// An integer e with 2^e >= x > 0.
inline long ceil_log2_bound(const Rational& x) {
  const mpq_srcptr q = x.mpq();
  return static_cast<long>(mpz_sizeinbase(mpq_numref(q), 2)) - static_cast<long>(mpz_sizeinbase(mpq_denref(q), 2)) + 1;
}
// An integer e with 2^e <= x (x > 0).
inline long floor_log2_bound(const Rational& x) {
  const mpq_srcptr q = x.mpq();
  return static_cast<long>(mpz_sizeinbase(mpq_numref(q), 2)) - static_cast<long>(mpz_sizeinbase(mpq_denref(q), 2)) - 1;
}

inline int sign_of(const Rational& x) { return x < 0 ? -1 : (x > 0 ? 1 : 0); }

// The enclosure of G from an exact three-valued comparison cmp(delta) = sign(G - delta)
// (delta <= 1/2; never called with delta >= 1/2 when G > 0), the exact sign of G, a certified
// lower bound `floor` <= G (the depth of a point of X) and guesses [l, u] (each is only tried:
// it is kept when cmp(l) >= 0 and cmp(u) <= 0). Then bisection (on the binary exponent of |G|
// while no bracket is known): from a guess's bracket to a width of 2^-54 of |G|'s binary order,
// so the double enclosure is at most two adjacent doubles wide; otherwise to 2^-24 of it.
template <class Cmp>
MarginEnclosure enclose_margin(const Cmp& cmp, int sign, const Rational& floor,
                               const std::vector<std::pair<Rational, Rational>>& guesses) {
  if (sign == 0) return {Rational(0), Rational(0)};
  const Rational half(1, 2);
  if (floor == half) return {half, half};  // floor <= G <= 1/2
  // sign(|G| - m) for m > 0.
  const auto rel = [&](const Rational& m) { return sign > 0 ? cmp(m) : -cmp(Rational(-m)); };
  // Certified bounds a <= |G| <= b (a = 0: none yet).
  Rational a(0), b(0);
  if (sign > 0) {
    b = half;
    if (floor > 0) a = floor;
  } else {
    b = -floor;  // floor <= G < 0
  }
  if (sign_of(floor) == sign) {
    const int c = cmp(floor);
    if (c == 0) return {floor, floor};
  }
  bool guessed = false;
  for (const auto& [l, u] : guesses) {
    if (sign_of(l) != sign || sign_of(u) != sign || u < l) continue;
    if (sign > 0 ? (u < a || l > b) : (-l < a || -u > b)) continue;
    if (sign > 0 && u >= half) continue;
    const int cl = cmp(l);
    if (cl == 0) return {l, l};
    if (cl < 0) continue;
    const int cu = cmp(u);
    if (cu == 0) return {u, u};
    if (cu > 0) continue;
    // l < G < u: a bracket of a few ulps, narrowed below.
    if (sign > 0) a = l, b = u;
    else a = -u, b = -l;
    guessed = true;
    break;
  }
  // Bracket |G| between powers of two: 2^elo <= |G| <= 2^ehi.
  // (G > 0: 2^-1 = 1/2 >= G is known and never compared, so cmp never sees delta >= 1/2.)
  long ehi = sign > 0 ? -1 : ceil_log2_bound(b);
  long elo = 0;
  if (a > 0) {
    elo = floor_log2_bound(a);
  } else {
    long step = 1;
    for (;;) {
      const long e = ehi - step;
      const int r = rel(power_of_two(e));
      if (r == 0) return sign > 0 ? MarginEnclosure{power_of_two(e), power_of_two(e)}
                                  : MarginEnclosure{-power_of_two(e), -power_of_two(e)};
      if (r > 0) {
        elo = e;
        break;
      }
      ehi = e, step *= 2;
    }
  }
  while (ehi - elo > 1) {
    const long e = elo + (ehi - elo) / 2;
    const int r = rel(power_of_two(e));
    if (r == 0) return sign > 0 ? MarginEnclosure{power_of_two(e), power_of_two(e)}
                                : MarginEnclosure{-power_of_two(e), -power_of_two(e)};
    (r > 0 ? elo : ehi) = e;
  }
  Rational lo = std::max(a, power_of_two(elo)), hi = std::min(b, power_of_two(ehi));
  // Narrowed to 2^-54 of |G|'s binary order (two adjacent doubles) when a guess bracketed G
  // within a few ulps (a few steps); by blind bisection only to 2^-24 (24 steps, not 54: the
  // study's bins and tables need far less, and each step is an exact comparison).
  const Rational width = power_of_two(elo - (guessed ? 54 : 24));
  while (hi - lo > width) {
    const Rational m = (lo + hi) / 2;
    const int r = rel(m);
    if (r == 0) {
      lo = hi = m;
      break;
    }
    (r > 0 ? lo : hi) = m;
  }
  return sign > 0 ? MarginEnclosure{lo, hi} : MarginEnclosure{-hi, -lo};
}

// A line-like query set x(t), t in the range (line: all t; ray: t >= 0; segment: 0 <= t <= 1),
// in the cylinder's coordinates: q(t) = qa t^2 + qb t + qc (qa >= 0), s(t) = s0 + s1 t.
struct LineMarginInput {
  Rational qa, qb, qc, s0, s1;
  LineRange range = LineRange::line;
  std::optional<Rational> lo() const { return range == LineRange::line ? std::nullopt : std::optional<Rational>(0); }
  std::optional<Rational> hi() const { return range == LineRange::segment ? std::optional<Rational>(1) : std::nullopt; }
  Rational q(const Rational& t) const { return (qa * t + qb) * t + qc; }
  Rational s(const Rational& t) const { return s0 + s1 * t; }
  Rational depth(const Rational& t) const {
    const Rational st = s(t);
    return std::min({Rational(1) - q(t), st, Rational(1) - st});
  }
};

// sign(G - delta): the exact answer of the line-like set against C_delta = { q <= 1 - delta,
// delta <= s <= 1 - delta } (empty for delta > 1/2).
inline int compare_line_margin(const LineMarginInput& L, const Rational& delta) {
  const Rational one(1), half(1, 2);
  if (delta > half) return -1;
  const std::optional<Rational> lo = L.lo(), hi = L.hi();
  std::optional<Rational> jlo = lo, jhi = hi;  // J = the range within the closed slab of C_delta
  bool open = false;                           // the range meets the open slab delta < s < 1 - delta
  if (L.s1 != 0) {
    Rational a = (delta - L.s0) / L.s1, b = (one - delta - L.s0) / L.s1;
    if (a > b) std::swap(a, b);
    if (!jlo || a > *jlo) jlo = a;
    if (!jhi || b < *jhi) jhi = b;
    if (*jlo > *jhi) return -1;
    open = a < b && (!hi || a < *hi) && (!lo || b > *lo);
  } else {
    if (L.s0 < delta || L.s0 > one - delta) return -1;
    open = delta < L.s0 && L.s0 < one - delta;
  }
  const Rational m = min_quadratic(L.qa, L.qb, L.qc, jlo, jhi);
  const Rational R = one - delta;
  if (m > R) return -1;
  return m < R && open ? 1 : 0;
}

inline std::pair<Rational, Rational> rational_interval(const CGAL::Interval_nt<>& v) {
  return {Rational(v.inf()), Rational(v.sup())};
}

// Guesses of G for a line-like set: the values v at the crossings of 1 - q with s (k = 0) and
// with 1 - s (k = 1). On the linear term g = al + be t, the crossing t = (v - al) / be solves
// q(t) + v - 1 = 0, so be^2 (q(t) + v - 1) = 0 is the quadratic
//   qa v^2 + (qb be + be^2 - 2 qa al) v + (qa al^2 - qb al be + (qc - 1) be^2) = 0
// in v, with exact coefficients; its roots are enclosed in interval arithmetic without
// cancellation (each root is formed from -b - sign(b) sqrt(disc) or from c over it).
inline void line_crossing_guesses(const LineMarginInput& L, std::vector<std::pair<Rational, Rational>>& out) {
  using I = CGAL::Interval_nt<>;
  if (L.s1 == 0) return;
  const auto iv = [](const Rational& x) {
    const auto p = CGAL::to_interval(x);
    return I(p.first, p.second);
  };
  for (int k = 0; k < 2; ++k) {
    const Rational al = k == 0 ? L.s0 : Rational(1) - L.s0, be = k == 0 ? L.s1 : -L.s1;
    const Rational a = L.qa, b = L.qb * be + be * be - 2 * L.qa * al, c = L.qa * al * al - L.qb * al * be + (L.qc - 1) * be * be;
    if (a == 0) {
      if (b != 0) out.push_back({-c / b, -c / b});
      continue;
    }
    const Rational disc = b * b - 4 * a * c;
    if (disc < 0) continue;
    const I sq = CGAL::sqrt(iv(disc)), ia = iv(a), ib = iv(b), ic = iv(c);
    if (!std::isfinite(sq.sup()) || !std::isfinite(ia.sup()) || !std::isfinite(ib.sup()) || !std::isfinite(ic.sup())) continue;
    if (b == 0) {
      const I v = sq / (2 * ia);
      out.push_back(rational_interval(v));
      out.push_back(rational_interval(-v));
      continue;
    }
    const I w = b > 0 ? -ib - sq : -ib + sq;  // no cancellation: both terms of one sign
    if (w.inf() <= 0 && w.sup() >= 0) continue;
    const I v1 = w / (2 * ia), v2 = (2 * ic) / w;
    for (const I& v : {v1, v2})
      if (std::isfinite(v.inf()) && std::isfinite(v.sup())) out.push_back(rational_interval(v));
  }
}

// The depth margin of a line-like set.
inline MarginEnclosure line_margin(const LineMarginInput& L) {
  const std::optional<Rational> lo = L.lo(), hi = L.hi();
  const auto clamp = [&](Rational t) {
    if (lo && t < *lo) t = *lo;
    if (hi && t > *hi) t = *hi;
    return t;
  };
  // d at rational points of the set: the ends, the point nearest the axis, the mid-height
  // crossing and the cap-plane crossings. Each is <= G; G is among them when its maximiser is.
  std::vector<Rational> ts{clamp(0)};
  if (lo) ts.push_back(*lo);
  if (hi) ts.push_back(*hi);
  if (L.qa != 0) ts.push_back(clamp(-L.qb / (2 * L.qa)));
  if (L.s1 != 0) {
    ts.push_back(clamp((Rational(1, 2) - L.s0) / L.s1));
    ts.push_back(clamp(-L.s0 / L.s1));
    ts.push_back(clamp((Rational(1) - L.s0) / L.s1));
  }
  Rational floor = L.depth(ts[0]);
  for (const Rational& t : ts) floor = std::max(floor, L.depth(t));
  std::vector<std::pair<Rational, Rational>> guesses;
  line_crossing_guesses(L, guesses);
  const auto cmp = [&](const Rational& delta) { return compare_line_margin(L, delta); };
  return enclose_margin(cmp, cmp(Rational(0)), floor, guesses);
}

inline std::pair<double, double> enclose_rational(const Rational& q) {
  const auto iv = CGAL::to_interval(q);
  return {iv.first, iv.second};
}

// The enclosure in doubles: [round down lo, round up hi].
inline std::pair<double, double> enclose_margin_doubles(const MarginEnclosure& g) {
  return {enclose_rational(g.lo).first, enclose_rational(g.hi).second};
}

template <class LineLike>
LineMarginInput circular_line_input(const LineLike& l, const Cylinder<Rational>& c, LineRange range) {
  const Vec3<Rational> A = c.axis();
  const Rational AA = squared_length(A);
  const Rational R = c.radius * c.radius * AA;
  const Vec3<Rational> w = l.origin - c.p0;
  const Vec3<Rational> u = cross(w, A), v = cross(l.direction, A);
  return {dot(v, v) / R, 2 * dot(u, v) / R, dot(u, u) / R, dot(w, A) / AA, dot(l.direction, A) / AA, range};
}

// LineLike: a line or ray (origin, direction) or a segment as Line{p0, p1 - p0} with its range.
template <class LineLike>
MarginEnclosure circular_line_gap(const LineLike& l, const Cylinder<Rational>& c, LineRange range) {
  return line_margin(circular_line_input(l, c, range));
}

// The unit frame of an elliptic cylinder: y = M^-1 v, M = [a b c] (M^-1's rows are the cross
// products over det); a point X maps to y(X - base).
struct EllipticFrame {
  explicit EllipticFrame(const EllipticCylinder<Rational>& e)
      : base(e.base), det(determinant(e.a, e.b, e.c)), r0(cross(e.b, e.c)), r1(cross(e.c, e.a)), r2(cross(e.a, e.b)) {}
  Vec3<Rational> operator()(const Vec3<Rational>& v) const { return {dot(r0, v) / det, dot(r1, v) / det, dot(r2, v) / det}; }
  Vec3<Rational> base;
  Rational det;
  Vec3<Rational> r0, r1, r2;
};

template <class LineLike>
LineMarginInput elliptic_line_input(const LineLike& l, const EllipticCylinder<Rational>& e, LineRange range) {
  const EllipticFrame unit(e);
  const Vec3<Rational> w = unit(l.origin - unit.base), v = unit(l.direction);
  return {v.x * v.x + v.y * v.y, 2 * (w.x * v.x + w.y * v.y), w.x * w.x + w.y * w.y, w.z, v.z, range};
}

template <class LineLike>
MarginEnclosure elliptic_line_gap(const LineLike& l, const EllipticCylinder<Rational>& e, LineRange range) {
  return line_margin(elliptic_line_input(l, e, range));
}

// The depth of one point from its squared radial coordinate q and axial coordinate s.
inline Rational point_depth(const Rational& q, const Rational& s) {
  const Rational one = 1;
  return std::min({one - q, s, one - s});
}

inline Rational circular_point_gap(const Point3<Rational>& X, const Cylinder<Rational>& c) {
  const Vec3<Rational> A = c.axis(), w = X - c.p0, u = cross(w, A);
  const Rational AA = squared_length(A);
  return point_depth(dot(u, u) / (c.radius * c.radius * AA), dot(w, A) / AA);
}

inline Rational elliptic_point_gap(const Point3<Rational>& X, const EllipticCylinder<Rational>& e) {
  const EllipticFrame unit(e);
  const Vec3<Rational> y = unit(X - unit.base);
  return point_depth(y.x * y.x + y.y * y.y, y.z);
}

// sign(G - delta) for a triangle, delta < 1/2: the exact construction of the certified query
// (triangle_cylinder.hpp, exact_certificate) against C_delta, the cylinder from P + delta A to
// P + (1 - delta) A with squared radius (1 - delta) r^2: clip T to its slab, take X*_delta, the
// point of the clipped polygon nearest the axis, and compare q(X*_delta) with 1 - delta. When
// `nearest` is given and T meets the slab, X*_delta is stored there.
inline int compare_triangle_margin(const Triangle<Rational>& T, const Cylinder<Rational>& C, const Rational& delta,
                                   std::optional<Point3<Rational>>* nearest = nullptr) {
  using namespace certcyl::detail;
  if (delta >= Rational(1, 2)) throw std::logic_error("study gap: triangle margin compared with delta >= 1/2");
  const Vec3<Rational> A = C.axis();
  const Cylinder<Rational> Cd{C.p0 + delta * A, C.p1 - delta * A, C.radius};
  const SlabInput<Rational> in = slab_input(T, Cd);
  const SlabAxial<Rational> ax = slab_axial_data(in, ExactSigns{});
  const SlabContact where = locate_in_slab(ax.lo, ax.hi);
  if (where == SlabContact::beyond_cap0 || where == SlabContact::beyond_cap1) return -1;
  const SlabPolygon<Rational> S = clip_to_slab(in, ax.s, ax.top, ax.lo, ax.hi);
  const Vec3<Rational> x = nearest_to_axis(S, in);
  if (nearest) *nearest = Cd.p0 + x;
  const Rational qx = squared_length(cross(x, in.A));
  const Rational R = (Rational(1) - delta) * C.radius * C.radius * ax.AA;
  if (qx > R) return -1;
  return qx < R && where == SlabContact::crosses_open_slab ? 1 : 0;
}

// The depth margin of a triangle. Lower bounds: d at the vertices, the centroid and X*_0; the
// guesses: the margins of the three edges (segments, each <= G; G is one of them when the
// maximiser lies on an edge).
inline MarginEnclosure triangle_margin(const Triangle<Rational>& T, const Cylinder<Rational>& C) {
  const Vec3<Rational> A = C.axis();
  const Rational AA = squared_length(A), RR = C.radius * C.radius * AA;
  const auto depth = [&](const Point3<Rational>& x) {
    const Vec3<Rational> w = x - C.p0;
    return point_depth(squared_length(cross(w, A)) / RR, dot(w, A) / AA);
  };
  std::optional<Point3<Rational>> nearest;
  const int sign = compare_triangle_margin(T, C, Rational(0), &nearest);
  Rational floor = depth(T.v[0]);
  for (int i = 1; i < 3; ++i) floor = std::max(floor, depth(T.v[i]));
  floor = std::max(floor, depth(Point3<Rational>(T.v[0] + Rational(1, 3) * (Vec3<Rational>(T.v[1] - T.v[0]) + Vec3<Rational>(T.v[2] - T.v[0])))));
  if (nearest) floor = std::max(floor, depth(*nearest));
  std::vector<std::pair<Rational, Rational>> guesses;
  for (int i = 0; i < 3; ++i) {
    const Line<Rational> edge{T.v[i], Vec3<Rational>(T.v[(i + 1) % 3] - T.v[i])};
    const MarginEnclosure e = circular_line_gap(edge, C, LineRange::segment);
    floor = std::max(floor, e.lo);  // e.lo <= the edge's margin <= G (the edge is a subset of T)
    if (!e.exact()) guesses.push_back({e.lo, e.hi});
  }
  std::sort(guesses.begin(), guesses.end(), [](const auto& x, const auto& y) { return x.second > y.second; });
  const auto cmp = [&](const Rational& delta) { return compare_triangle_margin(T, C, delta); };
  return enclose_margin(cmp, sign, floor, guesses);
}

inline Answer answer_of_sign(const Rational& g) {
  return g < 0 ? Answer::separated : (g > 0 ? Answer::overlapping : Answer::touching);
}
inline Answer answer_of_margin(const MarginEnclosure& g) {
  return g.hi < 0 ? Answer::separated : (g.lo > 0 ? Answer::overlapping : (g.exact() ? Answer::touching : Answer::undecided));
}

}  // namespace detail

// Computes inst.certified, its answers under the ray-cast contracts (study/contract.hpp), the gap
// enclosure, (line queries) t_in and (cylinder pairs) the stage,
// arithmetic and Gmpfr precision that decided. Sets certified_ok to false when the gap's sign
// and the certified answer differ (a defect the study reports): the depth margin's sign comes
// from its own exact comparison with 0 (compare_line_margin, compare_triangle_margin), not from
// the certified query.
// The cylinder pairs' gap enclosure comes from the ranked fast path (refine_gap).
inline CylinderCylinderOptions refined_gap_options() {
  CylinderCylinderOptions o;
  o.refine_gap = true;
  return o;
}

inline void certify(Instance& inst, const CylinderCylinderOptions& cyl_options = refined_gap_options()) {
  using namespace detail;
  const std::vector<double>& x = inst.x;
  auto finish_line = [&](const CertifiedLineResult& r, const MarginEnclosure& gap) {
    inst.certified = r.answer;
    inst.certified_entry = contract_answer(r, Contract::surface_entry);
    inst.certified_surface_hit = contract_answer(r, Contract::surface_hit);
    if (r.in) inst.t_in = r.in->nearest;
    std::tie(inst.gap_lo, inst.gap_hi) = enclose_margin_doubles(gap);
    inst.certified_ok = answer_of_margin(gap) == r.answer;
  };
  const std::vector<Rational> q = exact(x);
  switch (inst.query) {
    case Query::line_cylinder:
      finish_line(certified_line_cylinder(line_at(x), cylinder_at(x, 6)),
                  circular_line_gap(line_at(q), cylinder_at(q, 6), LineRange::line));
      return;
    case Query::ray_cylinder:
      finish_line(certified_line_cylinder(ray_at(x), cylinder_at(x, 6)),
                  circular_line_gap(ray_at(q), cylinder_at(q, 6), LineRange::ray));
      return;
    case Query::segment_cylinder: {
      const Segment<Rational> s = segment_at(q);
      finish_line(certified_line_cylinder(segment_at(x), cylinder_at(x, 6)),
                  circular_line_gap(Line<Rational>{s.p0, s.direction()}, cylinder_at(q, 6), LineRange::segment));
      return;
    }
    case Query::line_elliptic_cylinder:
      finish_line(certified_line_cylinder(line_at(x), elliptic_at(x, 6)),
                  elliptic_line_gap(line_at(q), elliptic_at(q, 6), LineRange::line));
      return;
    case Query::triangle_cylinder: {
      const Triangle<Rational> T = triangle_at(q);
      const Cylinder<Rational> C = cylinder_at(q, 9);
      const TriangleCylinderResult r = certified_triangle_cylinder(T, C);
      const MarginEnclosure gap = triangle_margin(T, C);
      inst.certified = inst.certified_entry = inst.certified_surface_hit = r.answer;
      std::tie(inst.gap_lo, inst.gap_hi) = enclose_margin_doubles(gap);
      inst.certified_ok = answer_of_margin(gap) == r.answer;
      return;
    }
    case Query::cylinder_cylinder: {
      const CylinderCylinderResult r = certified_cylinder_cylinder(cylinder_at(x, 0), cylinder_at(x, 7), cyl_options);
      inst.certified = inst.certified_entry = inst.certified_surface_hit = r.answer;
      inst.stage = to_string(r.stage);
      inst.certified_by = to_string(r.certified_by);
      inst.gmpfr_precision = r.gmpfr_precision;
      const CylinderGap gap = r.gap();
      if (gap.known) {
        inst.gap_lo = gap.log_lower();
        inst.gap_hi = gap.log_upper();
      } else {
        inst.gap_lo = inst.gap_hi = std::numeric_limits<double>::infinity();
      }
      // The enclosure must allow the answer's sign (touching: it contains 0).
      const Answer a = r.answer;
      inst.certified_ok = a == Answer::undecided || !gap.known ||
                          (a == Answer::separated && inst.gap_lo < 0) || (a == Answer::overlapping && inst.gap_hi > 0) ||
                          (a == Answer::touching && inst.gap_lo <= 0 && inst.gap_hi >= 0);
      return;
    }
  }
}

}  // namespace certcyl::study
