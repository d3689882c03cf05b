// fuzz/recheck.hpp -- an independent exact re-check of every certified answer.
//
// Used by the fuzz harnesses, the cross-check driver (experiments/crosscheck.cpp) and its test.
// It shares nothing with include/certcyl/certified/ but the primitives and Vec3's dot and
// cross: every quantity is rebuilt here from the textbook formulas, in Gmpq, and every
// comparison is an exact sign.
//
//   line, ray, segment   The exact parameter interval is recomputed from scratch: the slab
//                        0 <= S(t) <= H (linear in t) and the tube E(t) <= 0 (quadratic in t,
//                        roots p +- q sqrt(g)) are intersected with the range; the open
//                        interior likewise with open intervals. The certified endpoints are
//                        compared with these numbers exactly (numbers of Q(sqrt g) with
//                        different radicands are compared by repeated squaring); each
//                        endpoint is substituted into the exact equations of its surface and
//                        the point there is classified (wall, cap, rim, interior); rational
//                        parameters just outside the interval (within 2^-64 relative) give
//                        points outside the solid or the range, and parameters just inside give
//                        points in the solid (in its open interior if the answer is overlapping).
//   triangle             The certificate is re-checked: an overlapping witness lies in the
//                        triangle (barycentric signs) and strictly inside the cylinder; a
//                        touching witness lies in the triangle on the claimed feature and on the
//                        cylinder's boundary, with a proof that no point is interior (all
//                        vertices on the outer side of one cap plane, or a plane n.(Y-P) = r|n|,
//                        n.A = 0, with every vertex of the triangle clipped to the slab on its
//                        far side); a separation beyond a cap plane or by such a plane, strictly.
//   cylinder pair        A separating direction D is re-evaluated: phi(D) < D.Delta, i.e.
//                        c > sqrt(p) + sqrt(q), decided by the squaring rule; a touching normal
//                        gives equality there, and its point lies on both boundaries on the
//                        claimed features; an overlapping witness is strictly inside both. The
//                        gap enclosure is checked against the answer and the certificates
//                        (check_cylinder_gap).
// Each check returns an empty string when it holds, otherwise what failed.
#pragma once

#include <CGAL/Gmpq.h>
#include <CGAL/Gmpz.h>

#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "certcyl/answer.hpp"
#include "certcyl/certified/cylinder_cylinder.hpp"
#include "certcyl/certified/line_cylinder.hpp"
#include "certcyl/certified/triangle_cylinder.hpp"
#include "certcyl/primitives.hpp"
#include "certcyl/rational.hpp"
#include "certcyl/vec3.hpp"

namespace certcyl::recheck {

using Q = Rational;
using V = Vec3<Q>;

inline CGAL::Sign sign(const Q& x) { return static_cast<CGAL::Sign>(mpq_sgn(x.mpq())); }
inline bool is_zero(const V& v) { return sign(v.x) == CGAL::ZERO && sign(v.y) == CGAL::ZERO && sign(v.z) == CGAL::ZERO; }

// ---- numbers p + q sqrt(g), g >= 0 rational (no normal form needed) ----------------------------

struct Root {
  Q p{0}, q{0}, g{0};
};

inline Root rational_root(const Q& x) { return {x, Q(0), Q(0)}; }

// Sign of p + q sqrt(g).
inline CGAL::Sign sign_of(const Q& p, const Q& q, const Q& g) {
  const CGAL::Sign sp = sign(p);
  const CGAL::Sign sq = sign(g) == CGAL::ZERO ? CGAL::ZERO : sign(q);
  if (sq == CGAL::ZERO) return sp;
  if (sp == CGAL::ZERO || sp == sq) return sq;
  // else: opposite signs: |p| against |q| sqrt(g), by squaring.
  const CGAL::Sign s = sign(Q(p * p - q * q * g));
  return sp == CGAL::POSITIVE ? s : CGAL::opposite(s);
}
inline CGAL::Sign sign_of(const Root& x) { return sign_of(x.p, x.q, x.g); }

// Sign of a - b, for any two radicands.
inline CGAL::Sign compare(const Root& a, const Root& b) {
  const Q x = a.p - b.p;
  // a - b = (x + a.q sqrt(a.g)) + (-b.q sqrt(b.g)) = U + W.
  const CGAL::Sign su = sign_of(x, a.q, a.g);
  const CGAL::Sign sw = sign(b.g) == CGAL::ZERO ? CGAL::ZERO : CGAL::opposite(sign(b.q));
  if (sw == CGAL::ZERO) return su;
  if (su == CGAL::ZERO || su == sw) return sw;
  // else: opposite signs; sign(|U| - |W|) = sign(U^2 - W^2), U^2 - W^2 = (x^2 + a.q^2 a.g - b.q^2 b.g) + 2 x a.q sqrt(a.g).
  const CGAL::Sign m = sign_of(Q(x * x + a.q * a.q * a.g - b.q * b.q * b.g), Q(2 * x * a.q), a.g);
  if (m == CGAL::ZERO) return CGAL::ZERO;
  return m == CGAL::POSITIVE ? su : sw;
}

// 2^k as an exact rational.
inline Q pow2(unsigned long k) {
  CGAL::Gmpz z(1);
  mpz_mul_2exp(z.mpz(), z.mpz(), k);
  return Q(z);
}

inline Root to_root(const certcyl::detail::QuadraticNumber& x) { return {x.alpha, x.beta, Q(x.gamma)}; }

// Rational lo <= x <= hi with hi - lo <= |q| 2^-bits (after sqrt(g) = sqrt(n m) / m).
inline std::pair<Q, Q> rational_bounds(const Root& x, unsigned long bits) {
  if (sign(x.q) == CGAL::ZERO || sign(x.g) == CGAL::ZERO) return {x.p, x.p};
  const CGAL::Gmpz n = x.g.numerator(), m = x.g.denominator();
  CGAL::Gmpz scaled = n * m, s;
  mpz_mul_2exp(scaled.mpz(), scaled.mpz(), 2 * bits);
  mpz_sqrt(s.mpz(), scaled.mpz());
  CGAL::Gmpz den = m;
  mpz_mul_2exp(den.mpz(), den.mpz(), bits);
  const Q lo_root(s, den), hi_root(CGAL::Gmpz(s + 1), den);  // lo_root <= sqrt(g) < hi_root
  if (x.q > 0) return {x.p + x.q * lo_root, x.p + x.q * hi_root};
  return {x.p + x.q * hi_root, x.p + x.q * lo_root};
}

// ---- the line query -----------------------------------------------------------------------------

// Along X(t) = O + t d: the slab S(t) = s0 + s1 t in [0, H] and the radial excess
// E(t) = ea t^2 + eb t + ec <= 0, from the textbook formulas.
struct LineEquations {
  Q s0, s1, H, ea, eb, ec;
};

// Circular: S = (X - P).A, H = A.A, E = |(X - P) x A|^2 - r^2 A.A.
inline LineEquations line_equations(const V& O, const V& d, const Cylinder<Q>& c) {
  const V A = c.p1 - c.p0, w = O - c.p0;
  const V u0 = cross(w, A), u1 = cross(d, A);
  return {dot(w, A), dot(d, A), dot(A, A), dot(u1, u1), Q(2) * dot(u0, u1), dot(u0, u0) - c.radius * c.radius * dot(A, A)};
}

// Elliptic: M = [a b c], M^-1 has rows (b x c, c x a, a x b) / det. y = M^-1 (X - C):
// E = (det y1)^2 + (det y2)^2 - det^2, S = det y3 in [0, det] (signs flipped when det < 0).
inline LineEquations line_equations(const V& O, const V& d, const EllipticCylinder<Q>& e) {
  const V r1 = cross(e.b, e.c), r2 = cross(e.c, e.a), r3 = cross(e.a, e.b);
  const Q det = dot(e.a, r1);
  const V w = O - e.base;
  const Q a0 = dot(r1, w), a1 = dot(r1, d), b0 = dot(r2, w), b1 = dot(r2, d);
  const Q flip = det > 0 ? Q(1) : Q(-1);
  return {flip * dot(r3, w), flip * dot(r3, d), flip * det, a1 * a1 + b1 * b1, Q(2) * (a0 * a1 + b0 * b1),
          a0 * a0 + b0 * b0 - det * det};
}

struct ParamInterval {
  bool empty = false;
  std::optional<Root> lo, hi;  // nullopt: unbounded
};

inline void meet(ParamInterval& s, const std::optional<Root>& lo, const std::optional<Root>& hi) {
  if (lo && (!s.lo || compare(*lo, *s.lo) == CGAL::LARGER)) s.lo = lo;
  if (hi && (!s.hi || compare(*hi, *s.hi) == CGAL::SMALLER)) s.hi = hi;
}

// The closed (open = false) or open (open = true) set of t with X(t) in the solid and t in range.
inline ParamInterval line_parameters(const LineEquations& q, LineRange range, bool open) {
  ParamInterval s;
  const auto strictly = [&](CGAL::Sign x) { return open ? x == CGAL::POSITIVE : x != CGAL::NEGATIVE; };
  // Range.
  if (range != LineRange::line) meet(s, rational_root(Q(0)), std::nullopt);
  if (range == LineRange::segment) meet(s, std::nullopt, rational_root(Q(1)));
  // Slab.
  if (sign(q.s1) == CGAL::ZERO) {
    if (!strictly(sign(q.s0)) || !strictly(sign(Q(q.H - q.s0)))) s.empty = true;
  } else {
    Q t0 = -q.s0 / q.s1, t1 = (q.H - q.s0) / q.s1;
    if (t1 < t0) std::swap(t0, t1);
    meet(s, rational_root(t0), rational_root(t1));
  }
  // Tube.
  if (sign(q.ea) == CGAL::ZERO) {
    // d is parallel to the axis (then eb = 0): E is constant.
    if (sign(q.eb) != CGAL::ZERO) throw std::logic_error("recheck: linear radial excess");
    if (!strictly(CGAL::opposite(sign(q.ec)))) s.empty = true;
  } else {
    const Q disc = q.eb * q.eb - Q(4) * q.ea * q.ec;
    if (!strictly(sign(disc))) {
      s.empty = true;
    } else {
      const Q p = -q.eb / (Q(2) * q.ea), r = Q(1) / (Q(2) * q.ea);
      meet(s, Root{p, -r, disc}, Root{p, r, disc});
    }
  }
  if (!s.empty && s.lo && s.hi) {
    const CGAL::Sign w = compare(*s.hi, *s.lo);
    if (w == CGAL::NEGATIVE || (open && w == CGAL::ZERO)) s.empty = true;
  }
  return s;
}

// S and E at the exact parameter t.
inline Root slab_at(const LineEquations& q, const Root& t) { return {q.s0 + q.s1 * t.p, q.s1 * t.q, t.g}; }
inline Root excess_at(const LineEquations& q, const Root& t) {
  // t^2 = (p^2 + q^2 g) + 2 p q sqrt(g).
  return {q.ea * (t.p * t.p + t.q * t.q * t.g) + q.eb * t.p + q.ec, Q(2) * q.ea * t.p * t.q + q.eb * t.q, t.g};
}

enum class Where { outside, interior, boundary };

// Where X(t) lies, and the surface feature when it is on the boundary.
inline std::pair<Where, LineFeature> locate(const LineEquations& q, const Root& t) {
  const CGAL::Sign s = sign_of(slab_at(q, t));
  const Root top = slab_at(q, t);
  const CGAL::Sign u = compare(rational_root(q.H), top);  // H - S
  const CGAL::Sign e = sign_of(excess_at(q, t));
  if (s == CGAL::NEGATIVE || u == CGAL::NEGATIVE || e == CGAL::POSITIVE) return {Where::outside, LineFeature::none};
  if (s == CGAL::POSITIVE && u == CGAL::POSITIVE && e == CGAL::NEGATIVE) return {Where::interior, LineFeature::none};
  if (s == CGAL::ZERO) return {Where::boundary, e == CGAL::ZERO ? LineFeature::rim0 : LineFeature::cap0};
  if (u == CGAL::ZERO) return {Where::boundary, e == CGAL::ZERO ? LineFeature::rim1 : LineFeature::cap1};
  return {Where::boundary, LineFeature::wall};
}

inline bool in_range(const Q& t, LineRange range) {
  if (range == LineRange::line) return true;
  if (t < 0) return false;
  return range == LineRange::ray || t <= 1;
}

inline std::string describe(const Root& x) {
  return to_exact_string(x.p) + " + " + to_exact_string(x.q) + "*sqrt(" + to_exact_string(x.g) + ")";
}

// The line query's re-check. `line` is origin + t direction with t restricted by `range`.
template <class Solid>
std::string check_line(const V& O, const V& d, LineRange range, const Solid& solid, const CertifiedLineResult& r) {
  const LineEquations q = line_equations(O, d, solid);
  const ParamInterval closed = line_parameters(q, range, false);
  const ParamInterval open = line_parameters(q, range, true);
  const Answer expected = closed.empty ? Answer::separated : (open.empty ? Answer::touching : Answer::overlapping);
  if (r.answer != expected)
    return "answer " + std::string(to_string(r.answer)) + ", recomputed " + std::string(to_string(expected));
  if (r.range != range) return "wrong range";
  if (expected == Answer::separated) return (r.in || r.out) ? "endpoints on a separated answer" : "";
  if (!r.in || !r.out) return "missing endpoint";
  if (!closed.lo || !closed.hi) return "recomputed interval unbounded";  // cannot happen for valid input
  const Root in = to_root(r.in->value()), out = to_root(r.out->value());
  if (compare(in, *closed.lo) != CGAL::ZERO) return "entry " + r.in->exact() + " differs from " + describe(*closed.lo);
  if (compare(out, *closed.hi) != CGAL::ZERO) return "exit " + r.out->exact() + " differs from " + describe(*closed.hi);

  // Each endpoint substituted into the equations: its surface and feature.
  for (const CertifiedEndpoint* e : {&*r.in, &*r.out}) {
    const Root t = to_root(e->value());
    const auto [where, surface] = locate(q, t);
    if (where == Where::outside) return "endpoint " + e->exact() + " outside the solid";
    if (e->surface != surface)
      return "endpoint " + e->exact() + " surface " + std::string(to_string(e->surface)) + ", recomputed " +
             std::string(to_string(surface));
    const bool at0 = compare(t, rational_root(Q(0))) == CGAL::ZERO, at1 = compare(t, rational_root(Q(1))) == CGAL::ZERO;
    const bool ok = e->feature == surface || (e->feature == LineFeature::origin && at0 && range != LineRange::line) ||
                    (e->feature == LineFeature::end && at1 && range == LineRange::segment);
    if (!ok || e->feature == LineFeature::none)
      return "endpoint " + e->exact() + " feature " + std::string(to_string(e->feature)) + " does not hold";
    if (e->surface == LineFeature::wall || e->surface == LineFeature::rim0 || e->surface == LineFeature::rim1)
      if (sign_of(excess_at(q, t)) != CGAL::ZERO) return "wall endpoint not a root of the tube equation";
  }
  if (expected == Answer::touching)
    for (const CertifiedEndpoint* e : {&*r.in, &*r.out})
      if (e->surface == LineFeature::none) return "touching answer with an interior endpoint";

  // Rational parameters just outside [in, out] give points outside the solid or the range, and
  // parameters just inside give points in it (interior when overlapping).
  const auto point_where = [&](const Q& t) { return locate(q, rational_root(t)).first; };
  const unsigned long bits = 64;
  const Q in_lo = rational_bounds(in, bits).first;
  const Q out_hi = rational_bounds(out, bits).second;
  const Q eps_in = (Q(1) + (in_lo < 0 ? Q(-in_lo) : in_lo)) / pow2(64);
  const Q eps_out = (Q(1) + (out_hi < 0 ? Q(-out_hi) : out_hi)) / pow2(64);
  for (const Q& t : {Q(in_lo - eps_in), Q(out_hi + eps_out)})
    if (in_range(t, range) && point_where(t) != Where::outside)
      return "a parameter just outside the interval (" + to_exact_string(t) + ") is in the solid";
  const CGAL::Sign width = compare(out, in);
  if (width == CGAL::NEGATIVE) return "entry after exit";
  if (width == CGAL::POSITIVE) {
    // The rational bounds tighten until they separate in from out.
    std::optional<std::pair<Q, Q>> inside;
    for (unsigned long b = bits; b <= 4096 && !inside; b *= 2) {
      const auto [a_lo, a_hi] = rational_bounds(in, b);
      const auto [b_lo, b_hi] = rational_bounds(out, b);
      if (a_hi < b_lo) {
        const Q step = (b_lo - a_hi) / pow2(20);
        inside = std::pair{Q(a_hi + step), Q(b_lo - step)};
      }
    }
    if (!inside) return "";  // in < out closer than 2^-4096 relative: no rational probe taken
    const auto& [just_in, just_out] = *inside;
    for (const Q& t : {just_in, just_out, Q((just_in + just_out) / Q(2))}) {
      if (!in_range(t, range)) return "a parameter inside the interval is out of range";
      const Where w = point_where(t);
      if (w == Where::outside) return "a parameter just inside the interval (" + to_exact_string(t) + ") is outside";
      if (expected == Answer::overlapping && w != Where::interior) return "an overlapping interval with a boundary point inside";
      if (expected == Answer::touching && w != Where::boundary) return "a touching interval with an interior point";
    }
  }
  return "";
}

// ---- point classification (circular cylinder) ---------------------------------------------------

struct CylinderFrame {
  V P, A;
  Q AA, R;  // R = r^2 A.A
  explicit CylinderFrame(const Cylinder<Q>& c) : P(c.p0), A(c.p1 - c.p0), AA(dot(A, A)), R(c.radius * c.radius * AA) {}
  Q axial(const V& X) const { return dot(V(X - P), A); }
  Q radial(const V& X) const {
    const V u = cross(V(X - P), A);
    return dot(u, u);
  }
  Where where(const V& X) const {
    const Q s = axial(X), q = radial(X);
    if (s < 0 || s > AA || q > R) return Where::outside;
    if (s > 0 && s < AA && q < R) return Where::interior;
    return Where::boundary;
  }
};

// ---- the triangle query -------------------------------------------------------------------------

inline bool on_segment(const V& x, const V& a, const V& b) {
  const V ab = b - a, ax = x - a;
  if (!is_zero(cross(ab, ax))) return false;
  const Q t = dot(ax, ab);
  return t >= 0 && t <= dot(ab, ab);
}

// Whether x lies in the closed triangle (a degenerate one is its longest edge or a point).
inline bool in_triangle(const V& x, const Triangle<Q>& T) {
  const V n = cross(V(T.v[1] - T.v[0]), V(T.v[2] - T.v[0]));
  if (is_zero(n)) {
    // Collinear: the hull is the longest of the three edges.
    int best = 0;
    Q longest = -1;
    for (int i = 0; i < 3; ++i) {
      const V e = T.v[(i + 1) % 3] - T.v[i];
      if (dot(e, e) > longest) longest = dot(e, e), best = i;
    }
    return on_segment(x, T.v[best], T.v[(best + 1) % 3]);
  }
  if (sign(dot(n, V(x - T.v[0]))) != CGAL::ZERO) return false;
  for (int i = 0; i < 3; ++i)
    if (sign(dot(n, cross(V(T.v[(i + 1) % 3] - T.v[i]), V(x - T.v[i])))) == CGAL::NEGATIVE) return false;
  return true;
}

// The vertices of T clipped to the slab 0 <= s <= A.A: the vertices inside it and the points
// where the edges cross its two planes (the clipped polygon is their convex hull).
inline std::vector<V> clipped_vertices(const Triangle<Q>& T, const CylinderFrame& f) {
  std::vector<V> out;
  std::array<Q, 3> s;
  for (int i = 0; i < 3; ++i) s[i] = f.axial(T.v[i]);
  for (int i = 0; i < 3; ++i)
    if (s[i] >= 0 && s[i] <= f.AA) out.push_back(T.v[i]);
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    for (const Q& level : {Q(0), f.AA}) {
      const Q a = s[i] - level, b = s[j] - level;
      if ((a < 0 && b > 0) || (a > 0 && b < 0)) {
        const Q lambda = a / (a - b);
        out.push_back(T.v[i] + lambda * V(T.v[j] - T.v[i]));
      }
    }
  }
  return out;
}

// Every point of T ∩ slab satisfies n.(Y - P) >= r |n| (> if strict); n.A = 0, n != 0.
inline std::string plane_holds(const V& n, const Triangle<Q>& T, const Cylinder<Q>& C, const CylinderFrame& f, bool strict) {
  if (sign(dot(n, f.A)) != CGAL::ZERO) return "normal not perpendicular to the axis";
  if (is_zero(n)) return "zero normal";
  const std::vector<V> pts = clipped_vertices(T, f);
  if (pts.empty()) return "triangle misses the slab";
  const Q r2nn = C.radius * C.radius * dot(n, n);
  for (const V& Y : pts) {
    const Q k = dot(n, V(Y - f.P));
    if (k < 0 || (strict && k == 0)) return "a clipped vertex on the tube's side of the plane";
    const Q gap = k * k - r2nn;
    if (gap < 0 || (strict && gap == 0)) return "a clipped vertex within distance r of the axis";
  }
  return "";
}

inline std::string check_triangle(const Triangle<Q>& T, const Cylinder<Q>& C, const TriangleCylinderResult& r) {
  using Res = TriangleCylinderResult;
  const CylinderFrame f(C);
  std::array<Q, 3> s;
  for (int i = 0; i < 3; ++i) s[i] = f.axial(T.v[i]);
  switch (r.answer) {
    case Answer::overlapping:
      if (!r.witness) return "overlapping without a witness";
      if (!in_triangle(*r.witness, T)) return "witness not in the triangle";
      if (f.where(*r.witness) != Where::interior) return "witness not interior to the cylinder";
      return "";
    case Answer::touching: {
      if (!r.witness) return "touching without a witness";
      const V& x = *r.witness;
      if (!in_triangle(x, T)) return "witness not in the triangle";
      if (f.where(x) != Where::boundary) return "witness not on the cylinder's boundary";
      // The claimed triangle feature.
      const auto [i, j] = r.triangle_indices;
      switch (r.triangle_feature) {
        case Res::TriangleFeature::vertex:
          if (i < 0 || i > 2 || !is_zero(V(x - T.v[i]))) return "witness is not the claimed vertex";
          break;
        case Res::TriangleFeature::edge:
          if (i < 0 || i > 2 || j < 0 || j > 2 || i == j || !on_segment(x, T.v[i], T.v[j])) return "witness not on the claimed edge";
          for (const V& v : T.v)
            if (is_zero(V(x - v))) return "witness is a vertex, claimed an edge";
          break;
        case Res::TriangleFeature::face:
          for (int k = 0; k < 3; ++k)
            if (on_segment(x, T.v[k], T.v[(k + 1) % 3])) return "witness on an edge, claimed the face";
          break;
      }
      // The claimed cylinder feature.
      const Q sx = f.axial(x);
      const bool on_tube = f.radial(x) == f.R;
      using CF = Res::CylinderFeature;
      const CF feature = sx == 0 ? (on_tube ? CF::rim0 : CF::cap0) : (sx == f.AA ? (on_tube ? CF::rim1 : CF::cap1) : CF::wall);
      if (feature != r.cylinder_feature) return "claimed cylinder feature does not hold at the witness";
      // Nothing interior: all of T on the outer side of a cap plane, or the plane certificate.
      const bool below = s[0] <= 0 && s[1] <= 0 && s[2] <= 0;
      const bool above = s[0] >= f.AA && s[1] >= f.AA && s[2] >= f.AA;
      if (below || above) return "";
      return plane_holds(r.normal, T, C, f, false);
    }
    case Answer::separated:
      switch (r.separation) {
        case Res::Separation::beyond_cap0: return (s[0] < 0 && s[1] < 0 && s[2] < 0) ? "" : "not beyond cap plane 0";
        case Res::Separation::beyond_cap1:
          return (s[0] > f.AA && s[1] > f.AA && s[2] > f.AA) ? "" : "not beyond cap plane 1";
        case Res::Separation::outside_tube: return plane_holds(r.normal, T, C, f, true);
        case Res::Separation::none: return "separated without a reason";
      }
      return "bad separation reason";
    case Answer::undecided: return "undecided";
  }
  return "bad answer";
}

// ---- the cylinder pair ---------------------------------------------------------------------------

// Sign of |D.Delta| - phi(D) (positive: D or -D separates; phi is even), with Delta = m1 - m0 and
// phi(D) = |D.A0|/2 + |D.A1|/2 + r0 |D x A0| / |A0| + r1 |D x A1| / |A1|: the sign of
// c - sqrt(p) - sqrt(q) with c = |D.Delta| - |D.A0|/2 - |D.A1|/2, p = r0^2 |D x A0|^2 / A0.A0, q
// likewise, by the squaring rule: c < 0 gives negative; otherwise compare c^2 - p - q with
// 2 sqrt(pq), i.e. its sign and then (c^2 - p - q)^2 with 4 p q.
// With a factor k: the sign of k |D.Delta| - phi(D) (c = k |D.Delta| - ...).
inline CGAL::Sign separation_margin(const Cylinder<Q>& a, const Cylinder<Q>& b, const V& D, const Q& k = Q(1)) {
  const V A0 = a.p1 - a.p0, A1 = b.p1 - b.p0;
  const V Delta = (b.p0 + b.p1 - a.p0 - a.p1) / Q(2);
  const auto absq = [](const Q& x) { return x < 0 ? Q(-x) : x; };
  const Q c = k * absq(dot(D, Delta)) - absq(dot(D, A0)) / Q(2) - absq(dot(D, A1)) / Q(2);
  const V x0 = cross(D, A0), x1 = cross(D, A1);
  const Q p = a.radius * a.radius * dot(x0, x0) / dot(A0, A0);
  const Q q = b.radius * b.radius * dot(x1, x1) / dot(A1, A1);
  if (c < 0) return CGAL::NEGATIVE;
  const Q m = c * c - p - q;  // sign(c - sqrt p - sqrt q) = sign(c^2 - (sqrt p + sqrt q)^2) for c >= 0
  if (m < 0) return CGAL::NEGATIVE;
  return sign(Q(m * m - Q(4) * p * q));
}

inline std::string check_feature(const CylinderFrame& f, const V& X, CylinderFeature feature) {
  const Q s = f.axial(X);
  const bool on_cap_plane = s == 0 || s == f.AA;
  const bool on_tube = f.radial(X) == f.R;
  switch (feature) {
    case CylinderFeature::cap: return on_cap_plane ? "" : "contact point not in a cap plane";
    case CylinderFeature::wall: return on_tube ? "" : "contact point not on the wall";
    case CylinderFeature::rim: return on_cap_plane && on_tube ? "" : "contact point not on a rim";
  }
  return "bad feature";
}

inline std::string check_cylinder_certificate(const Cylinder<Q>& a, const Cylinder<Q>& b, const CylinderCylinderResult& r) {
  // The certificates as exact rationals, whichever field holds them.
  const std::optional<Vec3<Q>> direction = r.exact_direction();
  const std::optional<Point3<Q>> witness = r.exact_witness();
  const CylinderFrame fa(a), fb(b);
  switch (r.answer) {
    case Answer::separated:
      if (!direction) return "separated without a direction";
      if (separation_margin(a, b, *direction) != CGAL::POSITIVE) return "direction does not separate";
      return "";
    case Answer::overlapping:
      if (!witness) return "overlapping without a witness";
      if (fa.where(*witness) != Where::interior || fb.where(*witness) != Where::interior) return "witness not interior to both";
      return "";
    case Answer::touching: {
      if (!direction || !witness || !r.contact) return "touching without a normal, a point or features";
      if (is_zero(*direction)) return "zero contact normal";
      if (separation_margin(a, b, *direction) != CGAL::ZERO) return "contact normal does not give phi(D) = D.Delta";
      const V& X = *witness;
      if (fa.where(X) != Where::boundary || fb.where(X) != Where::boundary) return "contact point not on both boundaries";
      if (!is_zero(V(r.contact->point - X)) || !is_zero(V(r.contact->normal - *direction))) return "contact differs from the certificate";
      if (auto e = check_feature(fa, X, r.contact->feature0); !e.empty()) return "a: " + e;
      if (auto e = check_feature(fb, X, r.contact->feature1); !e.empty()) return "b: " + e;
      return "";
    }
    case Answer::undecided: return "";  // no claim; counted by the callers
  }
  return "bad answer";
}

// The gap enclosure phi_lower <= phi* <= phi_upper (r.gap(), when known) against the answer and
// its certificates, exactly. phi* = min phi(D) / |D.Delta| over directions D, and 1 / phi* =
// min sigma(X) over points X (the factor by which both cylinders, scaled about their midpoints,
// reach X), so: phi_lower <= phi_upper; a certificate direction D gives phi_lower |D.Delta| <=
// phi(D); a certificate point X gives phi_upper sigma(X) >= 1, i.e. for some cylinder
// phi_upper |2 X.A - ...| >= A.A axially or phi_upper^2 |v x A|^2 >= r^2 A.A radially; and the
// answer's side of 1: separated phi_lower < 1, overlapping phi_upper > 1, touching and
// undecided phi_lower <= 1 <= phi_upper. Necessary conditions: they catch a wrong bound, they
// cannot prove a right one.
inline std::string check_cylinder_gap(const Cylinder<Q>& a, const Cylinder<Q>& b, const CylinderCylinderResult& r) {
  const CylinderGap g = r.gap();
  if (!g.known) return "";
  if (!std::isfinite(g.phi_lower) || !std::isfinite(g.phi_upper)) return "gap enclosure not finite";
  const Q lo(g.phi_lower), hi(g.phi_upper);
  if (!(lo <= hi)) return "gap enclosure empty";
  switch (r.answer) {
    case Answer::separated: if (!(lo < 1)) return "separated but phi_lower >= 1"; break;
    case Answer::overlapping: if (!(hi > 1)) return "overlapping but phi_upper <= 1"; break;
    case Answer::touching:
    case Answer::undecided: if (!(lo <= 1 && 1 <= hi)) return "enclosure does not contain 1"; break;
  }
  if (const std::optional<Vec3<Q>> D = r.exact_direction(); D && !is_zero(*D))
    if (separation_margin(a, b, *D, lo) == CGAL::POSITIVE) return "phi_lower above the certificate direction's ratio";
  if (const std::optional<Point3<Q>> X = r.exact_witness()) {
    bool reached = false;
    for (const Cylinder<Q>* c : {&a, &b}) {
      const CylinderFrame f(*c);
      const Q two_s = 2 * f.axial(*X) - f.AA;
      reached = reached || hi * (two_s < 0 ? Q(-two_s) : two_s) >= f.AA || hi * hi * f.radial(*X) >= f.R;
    }
    if (!reached) return "phi_upper below 1 / sigma of the certificate point";
  }
  return "";
}

inline std::string check_cylinder_pair(const Cylinder<Q>& a, const Cylinder<Q>& b, const CylinderCylinderResult& r) {
  const std::string e = check_cylinder_certificate(a, b, r);
  return e.empty() ? check_cylinder_gap(a, b, r) : e;
}

}  // namespace certcyl::recheck
