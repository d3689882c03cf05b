// certcyl/certified/detail/cylinder_touching.hpp -- exact proof that two cylinders touch, from a
// rational candidate normal D.
//
// Touching needs two facts (design note, section 4):
//   (a) phi(D) = |D.Delta| exactly for some D: then phi* <= 1, so the interiors are disjoint;
//   (b) a point in both closed cylinders: then they are not separated.
// (a) is separation_sign(D) == ZERO in Gmpq. For (b) we take D with D.T > 0 and build the
// support sets F0 of cylinder 0 in direction D and F1 of cylinder 1 in direction -D; by (a) both
// lie in one plane, and the cylinders' common points are exactly F0 n F1.
//
// Support set of cylinder (p0, p1, r) in direction E (A = p1 - p0):
//   axial part   the end p1 if E.A > 0, p0 if E.A < 0, the whole axis segment if E.A = 0;
//   radial part  the offset o = r P E / |P E| (P the projection orthogonal to A) if E x A != 0,
//                the whole disk of radius r if E x A = 0 (E parallel to A).
// So F is a rim point (end + o), a wall segment [p0 + o, p1 + o], or a cap disk (end, r).
// |P E| = |E x A| / |A| = sqrt(p) / (2 r) with p the term of separation_terms. Under (a),
// c = sqrt(p) + sqrt(q) with c, p, q rational, and this forces sqrt(p) and sqrt(q) to be rational
// (if c > 0: sqrt(q) = c - sqrt(p) squares to sqrt(p) = (c^2 + p - q) / (2c); if c = 0 then
// p = q = 0). So for a rational D every support set, and every contact point built below, is
// rational: the design note's Q(sqrt) for rim-cap contacts is not needed once (a) holds.
//
// Contact types by the support sets: cap-cap, cap-wall, wall-wall, rim-cap, rim-wall, rim-rim.
// With rational data every touching pair has a rational normal (the theorem of
// detail/cylinder_rim_contacts.hpp), so proving from rational candidates loses nothing; the
// rim-wall and rim-rim candidates are computed exactly there (rim_contact_normals).
//
// Two forms of the proof: prove_touching in Gmpq on the input, and prove_touching_ring in Mpzf
// on the ring frame of detail/cylinder_ring_frame.hpp (the same facts, the same contact point,
// without division or gcds; the solver uses it whenever the ring frame exists).
#pragma once

#include <CGAL/Gmpq.h>
#include <CGAL/Gmpz.h>
#include <gmp.h>

#include <optional>
#include <string>

#include "certcyl/certified/detail/cylinder_certificates.hpp"
#include "certcyl/certified/detail/cylinder_rim_contacts.hpp"
#include "certcyl/certified/detail/cylinder_ring_frame.hpp"

namespace certcyl {

// Which part of a cylinder's boundary a contact uses.
enum class CylinderFeature { cap, wall, rim };

inline constexpr const char* to_string(CylinderFeature f) {
  return f == CylinderFeature::cap ? "cap" : (f == CylinderFeature::wall ? "wall" : "rim");
}

// A proved contact: the features of cylinder 0 and 1 that meet, the common normal (exact,
// D.Delta > 0, phi(D) = D.Delta) and one common point (exact).
struct CylinderContact {
  CylinderFeature feature0 = CylinderFeature::wall, feature1 = CylinderFeature::wall;
  Vec3<Rational> normal;
  Point3<Rational> point;

  // "cap-wall" and so on; cylinder 0's feature first.
  std::string type() const { return std::string(to_string(feature0)) + "-" + to_string(feature1); }
};

namespace detail {

struct SupportSet {
  CylinderFeature feature;
  Point3<Rational> a, b;  // rim: a; wall: segment [a, b]; cap: centre a
  Rational radius;        // cap only
};

// Support set of cylinder c in direction E, given root = sqrt(4 r^2 |E x A|^2 / A.A) (rational).
inline SupportSet support_set(const Cylinder<Rational>& c, const Vec3<Rational>& E, const Rational& root) {
  const Vec3<Rational> A = c.axis();
  const Rational EA = dot(E, A);
  const Rational AA = dot(A, A);
  if (root == 0) {
    // E is parallel to A: a cap disk.
    return {CylinderFeature::cap, EA > 0 ? c.p1 : c.p0, {}, c.radius};
  }
  // o = r P E / |P E| with P E = E - (E.A / A.A) A and |P E| = root / (2 r).
  const Vec3<Rational> PE = E - (EA / AA) * A;
  const Vec3<Rational> o = (Rational(2) * c.radius * c.radius / root) * PE;
  if (EA == 0) return {CylinderFeature::wall, c.p0 + o, c.p1 + o, Rational(0)};
  return {CylinderFeature::rim, (EA > 0 ? c.p1 : c.p0) + o, {}, Rational(0)};
}

// Closest point of segment [a, b] to x (rational).
inline Point3<Rational> closest_on_segment(const Point3<Rational>& a, const Point3<Rational>& b, const Point3<Rational>& x) {
  const Vec3<Rational> ab = b - a;
  Rational t = dot(x - a, ab) / dot(ab, ab);
  if (t < 0) t = 0;
  if (t > 1) t = 1;
  return a + t * ab;
}

// A candidate common point of two support sets lying in one plane; the caller checks it.
inline Point3<Rational> common_point_candidate(const SupportSet& f0, const SupportSet& f1) {
  using F = CylinderFeature;
  if (f0.feature == F::rim) return f0.a;
  if (f1.feature == F::rim) return f1.a;
  if (f0.feature == F::cap && f1.feature == F::cap) {
    // Two coplanar disks meet iff |c1 - c0| <= r0 + r1, and then at c0 + r0/(r0+r1) (c1 - c0).
    return f0.a + (f0.radius / (f0.radius + f1.radius)) * (f1.a - f0.a);
  }
  if (f0.feature == F::cap) return closest_on_segment(f1.a, f1.b, f0.a);
  if (f1.feature == F::cap) return closest_on_segment(f0.a, f0.b, f1.a);
  // Two coplanar segments. Crossing: intersect the lines a0 + s e0 and a1 + t e1 (the normal
  // equations of the closest points, exact). Parallel: the middle of the overlap of their
  // projections on the common direction.
  const Vec3<Rational> e0 = f0.b - f0.a, e1 = f1.b - f1.a, w = f0.a - f1.a;
  const Rational a = dot(e0, e0), b = dot(e0, e1), c = dot(e1, e1), d = dot(e0, w), e = dot(e1, w);
  const Rational den = a * c - b * b;
  if (den != 0) {
    const Rational s = (b * e - c * d) / den;
    return f0.a + s * e0;
  }
  // else: parallel segments; parameters of f1's ends along f0.
  Rational t0 = dot(f1.a - f0.a, e0) / a, t1 = dot(f1.b - f0.a, e0) / a;
  if (t1 < t0) std::swap(t0, t1);
  const Rational lo = t0 > 0 ? t0 : Rational(0);
  const Rational hi = t1 < 1 ? t1 : Rational(1);
  return f0.a + ((lo + hi) / 2) * e0;
}

// Proves that the cylinders touch with normal D (any rational D != 0), or returns nullopt.
// Every fact used is checked exactly in Gmpq.
inline std::optional<CylinderContact> prove_touching(const CylinderPair<Rational>& d, Vec3<Rational> D) {
  if (D.x == 0 && D.y == 0 && D.z == 0) return std::nullopt;
  const Rational DT = dot(D, d.T);
  if (DT == 0) return std::nullopt;
  if (DT < 0) D = -D;
  const SeparationTerms<Rational> t = separation_terms(d, D);
  if (sign_c_minus_roots(t.c, t.p, t.q) != CGAL::ZERO) return std::nullopt;
  // (a) holds: phi(D) = D.Delta. The roots are rational (header comment).
  const std::optional<Rational> root0 = rational_sqrt(t.p), root1 = rational_sqrt(t.q);
  if (!root0 || !root1) return std::nullopt;  // unreachable when (a) holds; kept as a guard
  const SupportSet f0 = support_set(d.c0, D, *root0);
  const SupportSet f1 = support_set(d.c1, -D, *root1);
  const Point3<Rational> X = common_point_candidate(f0, f1);
  if (!in_both_closed(d, X)) return std::nullopt;
  // (b) holds.
  return CylinderContact{f0.feature, f1.feature, D, X};
}

// ---- the same proof in the ring frame (detail/cylinder_ring_frame.hpp) --------------------------
// prove_touching for a pair of dyadic numbers (Mpzf) and a dyadic direction D, without division:
// every quantity that prove_touching divides is kept as a numerator over a positive denominator,
// and every sign is taken of the numerator. The facts proved are the same:
//   (a) separation_sign(D) == ZERO, on the ring form of separation_terms (c k, p k^2, q k^2 with
//       k = A0.A0 A1.A1 > 0; the sign is unchanged);
//   (b) a candidate point X = n / w (w > 0) in both closed cylinders: classify_point(n, c w) for
//       the cylinder c scaled by w (each slack of the point test is homogeneous in the lengths,
//       so its sign at (n, c w) is its sign at (n / w, c)).
// Support sets as in prove_touching, with R_i = |D x A_i| |A_i| = sqrt(|D x A_i|^2 A_i.A_i)
// (dyadic under (a): sqrt(p) = 2 r0 R0 / A0.A0 is rational, and the square root of a dyadic
// number that is rational is dyadic): P E = V / A.A with V = (A.A) E - (E.A) A and |P E| = R / A.A,
// so the offset is o = r V / R, and a wall is the segment [a, a + A] with a = p0 + o (o.A = 0).
// The candidate point is the one prove_touching takes, in homogeneous form:
//   cap-cap    (r1 c0 + r0 c1) / (r0 + r1);
//   cap-wall   a + t A with t = (c - p0).A / A.A clamped to [0, 1] (c the cap's centre);
//   wall-wall  crossing: a0 + s A0, s = (b e - c d) / (a c - b^2) (the closest points of the
//              lines); parallel: a0 + t A0, t the middle of the overlap of the parameter ranges;
//   rim        the rim point.

// A point with homogeneous coordinates: n / w, w > 0.
struct RingPoint {
  Point3<CGAL::Mpzf> n;
  CGAL::Mpzf w;
};

struct RingContact {
  CylinderFeature feature0 = CylinderFeature::wall, feature1 = CylinderFeature::wall;
  Vec3<CGAL::Mpzf> normal;  // D.T > 0
  RingPoint point;
};

struct RingSupport {
  CylinderFeature feature;
  RingPoint a;  // rim: the point; wall: the start of the segment [a, a + A]; cap: the centre
};

// sqrt(x) for a dyadic x >= 0 when it is rational (then dyadic), else nullopt.
inline std::optional<CGAL::Mpzf> mpzf_rational_sqrt(const CGAL::Mpzf& x) {
  const std::optional<Rational> r = rational_sqrt(Rational(static_cast<CGAL::Gmpq>(x)));
  if (!r) return std::nullopt;
  return mpzf_from_dyadic(*r);
}

// Support set of cylinder c (axis A, AA = A.A) in direction E, R = |E x A| |A| (0: E parallel
// to A).
inline RingSupport ring_support_set(const Cylinder<CGAL::Mpzf>& c, const Vec3<CGAL::Mpzf>& A, const CGAL::Mpzf& AA,
                                    const Vec3<CGAL::Mpzf>& E, const CGAL::Mpzf& R) {
  const CGAL::Mpzf EA = dot(E, A);
  const CGAL::Sign s = CGAL::sign(EA);
  const Point3<CGAL::Mpzf>& end = s == CGAL::POSITIVE ? c.p1 : c.p0;
  if (CGAL::sign(R) == CGAL::ZERO) return {CylinderFeature::cap, {end, CGAL::Mpzf(1)}};
  const Vec3<CGAL::Mpzf> V = AA * E - EA * A;
  const Point3<CGAL::Mpzf> base = s == CGAL::ZERO ? c.p0 : end;
  return {s == CGAL::ZERO ? CylinderFeature::wall : CylinderFeature::rim, {R * base + c.radius * V, R}};
}

inline RingPoint ring_common_point_candidate(const CylinderPair<CGAL::Mpzf>& d, const RingSupport& f0, const RingSupport& f1) {
  using F = CylinderFeature;
  using M = CGAL::Mpzf;
  if (f0.feature == F::rim) return f0.a;
  if (f1.feature == F::rim) return f1.a;
  const M &r0 = d.c0.radius, &r1 = d.c1.radius;
  if (f0.feature == F::cap && f1.feature == F::cap) return {r1 * f0.a.n + r0 * f1.a.n, r0 + r1};
  if (f0.feature == F::cap || f1.feature == F::cap) {
    const bool cap0 = f0.feature == F::cap;
    const Point3<M>& centre = cap0 ? f0.a.n : f1.a.n;  // w = 1
    const RingPoint& a = cap0 ? f1.a : f0.a;
    const Cylinder<M>& wall = cap0 ? d.c1 : d.c0;
    const Vec3<M>& A = cap0 ? d.A1 : d.A0;
    const M& AA = cap0 ? d.AA1 : d.AA0;
    M t = dot(centre - wall.p0, A);  // t A.A
    if (CGAL::sign(t) == CGAL::NEGATIVE) t = M(0);
    if (t > AA) t = AA;
    return {AA * a.n + (a.w * t) * A, a.w * AA};
  }
  // Two walls: a0 = P0 / R0, a1 = P1 / R1, a0 - a1 = W / (R0 R1).
  const Vec3<M> W = f1.a.w * f0.a.n - f0.a.w * f1.a.n;
  const M Rw = f0.a.w * f1.a.w;
  const M a = d.AA0, b = dot(d.A0, d.A1), c = d.AA1, dW = dot(d.A0, W), eW = dot(d.A1, W);
  const M den = a * c - b * b;
  if (CGAL::sign(den) != CGAL::ZERO) return {(f1.a.w * den) * f0.a.n + (b * eW - c * dW) * d.A0, Rw * den};
  // else: parallel walls; the parameters along A0 of f1's ends over Q = R0 R1 a.
  const M Q = Rw * a;
  M u0 = -dW, u1 = u0 + Rw * b;
  if (u1 < u0) std::swap(u0, u1);
  const M lo = CGAL::sign(u0) == CGAL::POSITIVE ? u0 : M(0);
  const M hi = u1 < Q ? u1 : Q;
  return {(M(2) * a * f1.a.w) * f0.a.n + (lo + hi) * d.A0, M(2) * Q};
}

// prove_touching in the ring frame (above): a contact with normal D, or nullopt.
inline std::optional<RingContact> prove_touching_ring(const CylinderPair<CGAL::Mpzf>& d, Vec3<CGAL::Mpzf> D) {
  using M = CGAL::Mpzf;
  if (CGAL::sign(D.x) == CGAL::ZERO && CGAL::sign(D.y) == CGAL::ZERO && CGAL::sign(D.z) == CGAL::ZERO) return std::nullopt;
  const CGAL::Sign DT = CGAL::sign(dot(D, d.T));
  if (DT == CGAL::ZERO) return std::nullopt;
  if (DT == CGAL::NEGATIVE) D = -D;
  const SeparationTerms<M> t = separation_terms(d, D);
  if (sign_c_minus_roots(t.c, t.p, t.q) != CGAL::ZERO) return std::nullopt;
  // (a) holds; R_i = sqrt(|D x A_i|^2 A_i.A_i) are dyadic (comment above).
  const std::optional<M> R0 = mpzf_rational_sqrt(squared_norm(cross(D, d.A0)) * d.AA0);
  const std::optional<M> R1 = mpzf_rational_sqrt(squared_norm(cross(D, d.A1)) * d.AA1);
  if (!R0 || !R1) return std::nullopt;  // unreachable when (a) holds; kept as a guard
  const RingSupport f0 = ring_support_set(d.c0, d.A0, d.AA0, D, *R0);
  const RingSupport f1 = ring_support_set(d.c1, d.A1, d.AA1, Vec3<M>(-D), *R1);
  const RingPoint X = ring_common_point_candidate(d, f0, f1);
  const auto scaled = [&X](const Cylinder<M>& c) { return Cylinder<M>{X.w * c.p0, X.w * c.p1, X.w * c.radius}; };
  if (classify_point(X.n, scaled(d.c0)) == Side::outside || classify_point(X.n, scaled(d.c1)) == Side::outside) return std::nullopt;
  // (b) holds.
  return RingContact{f0.feature, f1.feature, D, X};
}

// Continued-fraction reconstruction: the first convergent p/q of x = n0 / d0 (d0 > 0, the
// fraction need not be in lowest terms: Euclid's algorithm on (n0, d0) gives the same partial
// quotients as on the reduced fraction) with |x - p/q| <= tolerance (tolerance >= 0). In
// integers: with the remainders (n, d) of Euclid's algorithm, each partial quotient
// a = floor(n / d) extends the convergents h / k, and the test is
// |n0 k - h d0| tol_den <= tol_num d0 k (k > 0), homogeneous in (n0, d0), without a gcd.
inline Rational simplest_convergent(mpz_srcptr n0, mpz_srcptr d0, const Rational& tolerance) {
  mpz_srcptr tn = mpq_numref(tolerance.mpq()), td = mpq_denref(tolerance.mpq());
  CGAL::Gmpz n(n0), d(d0), a, r, h, k, h_prev(1), h_prev2(0), k_prev(0), k_prev2(1), lhs, rhs;
  for (int i = 0; i < 400; ++i) {
    mpz_fdiv_qr(a.mpz(), r.mpz(), n.mpz(), d.mpz());
    mpz_mul(h.mpz(), a.mpz(), h_prev.mpz());
    mpz_add(h.mpz(), h.mpz(), h_prev2.mpz());
    mpz_mul(k.mpz(), a.mpz(), k_prev.mpz());
    mpz_add(k.mpz(), k.mpz(), k_prev2.mpz());
    mpz_mul(lhs.mpz(), n0, k.mpz());
    mpz_submul(lhs.mpz(), h.mpz(), d0);
    mpz_abs(lhs.mpz(), lhs.mpz());
    mpz_mul(lhs.mpz(), lhs.mpz(), td);
    mpz_mul(rhs.mpz(), tn, d0);
    mpz_mul(rhs.mpz(), rhs.mpz(), k.mpz());
    if (mpz_cmp(lhs.mpz(), rhs.mpz()) <= 0 || mpz_sgn(r.mpz()) == 0) return Rational(h, k);
    mpz_swap(n.mpz(), d.mpz());  // y = 1 / (y - a) = d / r
    mpz_swap(d.mpz(), r.mpz());
    mpz_swap(h_prev2.mpz(), h_prev.mpz());
    mpz_swap(h_prev.mpz(), h.mpz());
    mpz_swap(k_prev2.mpz(), k_prev.mpz());
    mpz_swap(k_prev.mpz(), k.mpz());
  }
  return Rational(CGAL::Gmpz(n0), CGAL::Gmpz(d0));
}

inline Rational simplest_convergent(const Rational& x, const Rational& tolerance) {
  return simplest_convergent(mpq_numref(x.mpq()), mpq_denref(x.mpq()), tolerance);
}

// A rational direction with small numbers near D: each coordinate divided by the largest one
// in magnitude, then reconstructed within the tolerance. The quotients D[i] / D[k] are passed
// as the products num_i den_k / (den_i num_k), not reduced (simplest_convergent needs no gcd).
inline Vec3<Rational> reconstruct_direction(const Vec3<Rational>& D, const Rational& tolerance) {
  std::size_t k = 0;
  CGAL::Gmpz n, d;
  for (std::size_t i = 1; i < 3; ++i) {
    // |D[i]| > |D[k]|, cross-multiplied (denominators are positive).
    mpz_mul(n.mpz(), mpq_numref(D[i].mpq()), mpq_denref(D[k].mpq()));
    mpz_mul(d.mpz(), mpq_numref(D[k].mpq()), mpq_denref(D[i].mpq()));
    if (mpz_cmpabs(n.mpz(), d.mpz()) > 0) k = i;
  }
  Vec3<Rational> R;
  mpz_srcptr nk = mpq_numref(D[k].mpq()), dk = mpq_denref(D[k].mpq());
  for (std::size_t i = 0; i < 3; ++i) {
    if (i == k) {
      R[i] = Rational(1);
      continue;
    }
    mpz_mul(n.mpz(), mpq_numref(D[i].mpq()), dk);
    mpz_mul(d.mpz(), mpq_denref(D[i].mpq()), nk);
    if (mpz_sgn(d.mpz()) < 0) {
      mpz_neg(n.mpz(), n.mpz());
      mpz_neg(d.mpz(), d.mpz());
    }
    R[i] = simplest_convergent(n.mpz(), d.mpz(), tolerance);
  }
  return R;
}

}  // namespace detail
}  // namespace certcyl
