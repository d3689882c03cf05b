// certcyl/certified/detail/cylinder_rim_contacts.hpp -- the exact contact normals of rim-wall and
// rim-rim contacts between two cylinders with rational data.
//
// Notation of detail/cylinder_certificates.hpp: cylinder i has axis A_i, radius r_i, ends p0_i,
// p1_i; T = 2 Delta; phi2(D) = |D.A0| + |D.A1| + sqrt(p_0(D)) + sqrt(p_1(D)) with
// p_i(D) = 4 r_i^2 |D x A_i|^2 / A_i.A_i; touching with normal D means phi2(D) = D.T > 0 plus a
// common point (detail/cylinder_touching.hpp proves both exactly for a rational D).
//
// Theorem (paper, Theorem 2; complete proof in its appendix "Touching pairs: complete proofs").
// If two cylinders with rational data touch, one of these candidates is a contact normal:
//   (i) A0 or A1; (ii) A0 x A1, or for parallel axes the part of T orthogonal to them;
//   (iii) a rim-wall normal P + t W with t a rational double root of F_sigma (below);
//   (iv) for a rational common point X of a rim of each (on the line where the cap planes meet),
//        (A0 x u0) x (A1 x u1) when nonzero, else u0 or -u1 (u_i = X - e_i, e_i the rim's centre).
// Proof outline. The contact normals are the nonzero vectors of N0(X) n -N1(X) for any one
// contact point X (N_i the normal cone of cylinder i): every contact point lies in every contact
// plane. Classify X: in the relative interior of a cap (normal +-A_i: (i)); on both walls
// (normal orthogonal to both axes: (ii), with Cauchy-Schwarz for parallel axes); on a rim of i
// and the wall of j (normal -n_j(X), radial; rational because X is: a conjugate X' != X would be
// a second double zero of Q_j on rim circle i; Q_j restricted to the circle has four zeros
// with multiplicity (unless it vanishes on the whole circle, which makes the cap disk a cross-
// section of the tube: overlap), so Q_j = lambda l^2 on the circle, l the chord line XX', and
// both signs of lambda give an interior common point or the cap normal +-A_i; conjugates of
// degree 3 or 4 cannot occur, since X and X' already use the four zeros, and a non-real X'
// would bring its complex conjugate as a third); on a rim of each (X is rational: an
// irrational root on the line of the cap planes has a conjugate that is a second contact
// point, and the chord between them would make both cap planes the contact plane; the normal
// lies on the line pi0 n pi1, pi_i = span(A_i, u_i), or, when pi0 = pi1, the extreme rays of
// the intersection of two plane cones are generators: +-A_i, u0, -u1). The touching stage
// tries every candidate, so it decides every touching pair.
//
// So no algebraic numbers are needed: the design note's "roots of univariate polynomials of
// degree up to 4 and 8" are, for rational input, always rational roots, and an irrational
// root proves that no contact of that type exists. This file finds the rational candidates
// exactly; the caller proves or rejects each one (prove_touching).
//
// Rim-wall candidates, without a frame of the cap plane: a rim-wall normal D (wall of j) lies
// on the line { D : D.A_j = 0, D.T = 1 } = { P + t W }, W = A_j x T, and there
//   g(t) = phi2(P + t W) = sigma l(t) + sqrt(p_i(t)) + sqrt(p_j(t)),   l(t) = (P + t W).A_i,
// with sigma = sign(D.A_i) = +-1 (which rim of i) and p_i, p_j quadratics in t. At the contact
// g has a minimum equal to 1 and is smooth there (D x A_i != 0 for a rim, D x A_j != 0 for a
// wall), so t* is a double root of 1 - g, hence of the rational quartic
//   F_sigma(t) = ((1 - sigma l)^2 - p_i - p_j)^2 - 4 p_i p_j
//              = product over the four sign choices of (1 - sigma l +- sqrt(p_i) +- sqrt(p_j)).
// F_sigma is the zero polynomial exactly when sigma l = 1 and p_i = p_j identically (p_j(t) =
// 4 r_j^2 |P + t W|^2 has two simple non-real roots, since P.T = 1 and W.T = 0 make P, W
// independent; F = 0 makes p_i p_j a square, so p_i = c p_j, and then (1 - sigma l)^2 =
// (1 +- sqrt c)^2 p_j forces c = 1 and sigma l = 1); there g = 1 + 2 sqrt(p_j) > 1 on the line,
// so that sigma has no contact and is skipped. Otherwise a contact normal on the line is a
// double root (g >= 1 with equality there, g analytic near it), so a root of
// S = squarefree(gcd(F, F')), of degree at most 2 (a quartic has at most two multiple roots);
// only rational roots can be contacts (theorem), and they give the candidates P + t* W. Degree:
// the coefficients of F are of degree 8 in P, W and 4 in the squared radii over A.A; all in Gmpq.
// Euclid's algorithm on such coefficients grows them quickly (seconds for operands of thousands
// of digits), so F is first reduced modulo a prime p: when F mod p and its derivative are coprime,
// F has no multiple root (squarefree_mod_p) and the exact gcd is skipped.
#pragma once

#include <CGAL/Gmpq.h>
#include <CGAL/Gmpz.h>
#include <gmp.h>

#include <algorithm>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "certcyl/certified/detail/cylinder_certificates.hpp"

namespace certcyl::detail {

// The square root of q when q is the square of a rational.
inline std::optional<Rational> rational_sqrt(const Rational& q) {
  if (q < 0) return std::nullopt;
  mpz_srcptr n = mpq_numref(q.mpq());
  mpz_srcptr d = mpq_denref(q.mpq());
  if (!mpz_perfect_square_p(n) || !mpz_perfect_square_p(d)) return std::nullopt;
  CGAL::Gmpz rn, rd;
  mpz_sqrt(rn.mpz(), n);
  mpz_sqrt(rd.mpz(), d);
  return Rational(rn, rd);
}

// ---- univariate polynomials over Q: coefficients from degree 0 up, no trailing zero ------------
using RationalPolynomial = std::vector<Rational>;

inline RationalPolynomial trimmed(RationalPolynomial f) {
  while (!f.empty() && f.back() == 0) f.pop_back();
  return f;
}

inline RationalPolynomial operator+(const RationalPolynomial& f, const RationalPolynomial& g) {
  RationalPolynomial h(std::max(f.size(), g.size()), Rational(0));
  for (std::size_t i = 0; i < f.size(); ++i) h[i] += f[i];
  for (std::size_t i = 0; i < g.size(); ++i) h[i] += g[i];
  return trimmed(std::move(h));
}

inline RationalPolynomial operator*(const Rational& c, const RationalPolynomial& f) {
  RationalPolynomial h(f);
  for (Rational& x : h) x *= c;
  return trimmed(std::move(h));
}

inline RationalPolynomial operator-(const RationalPolynomial& f, const RationalPolynomial& g) { return f + Rational(-1) * g; }

inline RationalPolynomial operator*(const RationalPolynomial& f, const RationalPolynomial& g) {
  if (f.empty() || g.empty()) return {};
  RationalPolynomial h(f.size() + g.size() - 1, Rational(0));
  for (std::size_t i = 0; i < f.size(); ++i)
    for (std::size_t j = 0; j < g.size(); ++j) h[i + j] += f[i] * g[j];
  return trimmed(std::move(h));
}

inline RationalPolynomial derivative(const RationalPolynomial& f) {
  RationalPolynomial h;
  for (std::size_t i = 1; i < f.size(); ++i) h.push_back(Rational(static_cast<long>(i)) * f[i]);
  return trimmed(std::move(h));
}

// Quotient and remainder of f by g != 0.
inline std::pair<RationalPolynomial, RationalPolynomial> divide(RationalPolynomial f, const RationalPolynomial& g) {
  RationalPolynomial q(f.size() >= g.size() ? f.size() - g.size() + 1 : 0, Rational(0));
  while (f.size() >= g.size() && !f.empty()) {
    const std::size_t shift = f.size() - g.size();
    const Rational c = f.back() / g.back();
    q[shift] = c;
    for (std::size_t i = 0; i < g.size(); ++i) f[shift + i] -= c * g[i];
    f.pop_back();  // the leading coefficient cancels exactly
    f = trimmed(std::move(f));
  }
  return {trimmed(std::move(q)), std::move(f)};
}

// True when f is proved squarefree (no multiple root, over the complex numbers) by reduction
// modulo the prime p = 2^32 - 5: each coefficient n/d with p not dividing d maps to n d^-1 mod p
// (a ring homomorphism from the rationals with such denominators onto Z/p). If p divides no
// denominator nor the leading coefficient, and gcd(f mod p, (f mod p)') is a constant, then f is
// squarefree: a factor h of f and f' of degree >= 1, taken primitive over the p-adic integers
// (Gauss's lemma), has a leading coefficient dividing lc(f), so h mod p keeps its degree and
// divides both reductions. False proves nothing (the exact gcd decides).
inline bool squarefree_mod_p(const RationalPolynomial& f) {
  constexpr std::uint64_t p = 4294967291u;
  if (f.size() < 2) return f.size() == 1;
  const auto power = [&](std::uint64_t b, std::uint64_t e) {
    std::uint64_t r = 1;
    for (b %= p; e; e >>= 1, b = b * b % p)
      if (e & 1) r = r * b % p;
    return r;
  };
  std::vector<std::uint64_t> g;  // f mod p, lowest degree first
  for (const Rational& c : f) {
    const std::uint64_t d = mpz_fdiv_ui(mpq_denref(c.mpq()), p);
    if (d == 0) return false;
    g.push_back(mpz_fdiv_ui(mpq_numref(c.mpq()), p) * power(d, p - 2) % p);
  }
  if (g.back() == 0) return false;
  std::vector<std::uint64_t> h;  // the derivative
  for (std::size_t i = 1; i < g.size(); ++i) h.push_back(g[i] * i % p);
  const auto trim = [](std::vector<std::uint64_t>& v) {
    while (!v.empty() && v.back() == 0) v.pop_back();
  };
  trim(h);
  // Euclid over Z/p: a remainder sequence ending in a nonzero constant means coprime.
  while (!h.empty()) {
    const std::uint64_t inv = power(h.back(), p - 2);
    while (g.size() >= h.size()) {
      const std::uint64_t c = g.back() * inv % p;
      const std::size_t shift = g.size() - h.size();
      for (std::size_t i = 0; i < h.size(); ++i) g[shift + i] = (g[shift + i] + (p - c) * h[i]) % p;
      g.pop_back();
      trim(g);
      if (g.empty()) break;
    }
    std::swap(g, h);
  }
  return g.size() == 1;
}

// The monic greatest common divisor (Euclid's algorithm, exact); empty when f = g = 0.
inline RationalPolynomial gcd(RationalPolynomial f, RationalPolynomial g) {
  while (!g.empty()) {
    RationalPolynomial r = divide(f, g).second;
    f = std::move(g);
    g = std::move(r);
  }
  if (f.empty()) return f;
  return (Rational(1) / f.back()) * f;
}

// The distinct rational roots of f != 0 when f has degree at most 2; an irrational or complex
// pair gives none.
inline std::vector<Rational> rational_roots_up_to_quadratic(const RationalPolynomial& f) {
  if (f.size() == 2) return {-f[0] / f[1]};
  if (f.size() != 3) return {};
  const Rational b = f[1] / (2 * f[2]), c = f[0] / f[2];  // t^2 + 2 b t + c
  const std::optional<Rational> root = rational_sqrt(b * b - c);
  if (!root) return {};
  if (*root == 0) return {-b};
  return {-b - *root, -b + *root};
}

// |U + t V|^2 as a polynomial in t.
inline RationalPolynomial squared_norm_along(const Vec3<Rational>& U, const Vec3<Rational>& V) {
  return trimmed({dot(U, U), 2 * dot(U, V), dot(V, V)});
}

// ---- rim-wall candidates (header comment) --------------------------------------------------------
// Normals of every rim-wall contact of the pair (rim of one cylinder, wall of the other): for
// each wall cylinder j and each sign sigma, the rational double roots of F_sigma.
inline void rim_wall_normals(const CylinderPair<Rational>& d, std::vector<Vec3<Rational>>& out) {
  for (int j = 0; j < 2; ++j) {
    const Cylinder<Rational>& ci = j == 0 ? d.c1 : d.c0;  // the rim
    const Cylinder<Rational>& cj = j == 0 ? d.c0 : d.c1;  // the wall
    const Vec3<Rational>& Ai = j == 0 ? d.A1 : d.A0;
    const Vec3<Rational>& Aj = j == 0 ? d.A0 : d.A1;
    const Rational& AAi = j == 0 ? d.AA1 : d.AA0;
    const Rational& AAj = j == 0 ? d.AA0 : d.AA1;
    const Vec3<Rational> W = cross(Aj, d.T);
    if (W.x == 0 && W.y == 0 && W.z == 0) continue;  // A_j parallel to T: no normal with D.A_j = 0 < D.T
    // P: D.A_j = 0 and D.T = 1 (the part of T orthogonal to A_j, scaled; P.T = |W|^2 / AAj > 0).
    const Vec3<Rational> Tj = AAj * d.T - dot(d.T, Aj) * Aj;
    const Vec3<Rational> P = Tj / dot(Tj, d.T);
    const RationalPolynomial l = trimmed({dot(P, Ai), dot(W, Ai)});
    const RationalPolynomial pi = (4 * ci.radius * ci.radius / AAi) * squared_norm_along(cross(P, Ai), cross(W, Ai));
    const RationalPolynomial pj = (4 * cj.radius * cj.radius / AAj) * squared_norm_along(cross(P, Aj), cross(W, Aj));
    const RationalPolynomial four_pi_pj = Rational(4) * (pi * pj);
    for (const int sigma : {1, -1}) {
      const RationalPolynomial m = RationalPolynomial{Rational(1)} - Rational(sigma) * l;  // 1 - sigma l
      const RationalPolynomial e = m * m - pi - pj;
      const RationalPolynomial F = e * e - four_pi_pj;
      if (F.empty()) continue;  // sigma l = 1 and p_i = p_j: no contact for this sigma (header comment)
      if (squarefree_mod_p(F)) continue;  // no double root
      const RationalPolynomial H = gcd(F, derivative(F));
      if (H.size() < 2) continue;  // no double root
      const RationalPolynomial S = divide(H, gcd(H, derivative(H))).first;
      for (const Rational& t : rational_roots_up_to_quadratic(S)) {
        // The rim is the end sigma: sign(D.A_i) = sigma, else this root belongs to another factor.
        const Rational li = dot(P, Ai) + t * dot(W, Ai);
        if ((sigma > 0 && li > 0) || (sigma < 0 && li < 0)) out.push_back(P + t * W);
      }
    }
  }
}

// ---- rim-rim candidates (header comment) ----------------------------------------------------------
inline void rim_rim_normals(const CylinderPair<Rational>& d, std::vector<Vec3<Rational>>& out) {
  const Vec3<Rational> L = cross(d.A0, d.A1);
  if (L.x == 0 && L.y == 0 && L.z == 0) return;  // parallel cap planes: rims meet only in a cap-cap contact
  const Rational LL = dot(L, L), A01 = dot(d.A0, d.A1);
  const Rational r0r0 = d.c0.radius * d.c0.radius, r1r1 = d.c1.radius * d.c1.radius;
  for (const Point3<Rational>* e0 : {&d.c0.p0, &d.c0.p1}) {
    for (const Point3<Rational>* e1 : {&d.c1.p0, &d.c1.p1}) {
      // X0: the point of the line {A0.X = h0} n {A1.X = h1} in span(A0, A1).
      const Rational h0 = dot(d.A0, *e0), h1 = dot(d.A1, *e1);
      const Point3<Rational> X0 = ((h0 * d.AA1 - h1 * A01) / LL) * d.A0 + ((h1 * d.AA0 - h0 * A01) / LL) * d.A1;
      // |X0 + s L - e0|^2 = r0^2:  LL s^2 + 2 b s + c = 0.
      const Vec3<Rational> w = X0 - *e0;
      const Rational b = dot(L, w), c = dot(w, w) - r0r0;
      const std::optional<Rational> root = rational_sqrt(b * b - LL * c);
      if (!root) continue;  // no common point, or an irrational one: no rim-rim contact (theorem)
      for (const Rational& s : {(-b + *root) / LL, (-b - *root) / LL}) {
        const Point3<Rational> X = X0 + s * L;
        const Vec3<Rational> u0 = X - *e0, u1 = X - *e1;
        if (dot(u1, u1) != r1r1) continue;
        const Vec3<Rational> D = cross(cross(d.A0, u0), cross(d.A1, u1));
        if (D.x == 0 && D.y == 0 && D.z == 0) {
          // else-branch of the header: the two normal planes coincide; the boundary rays.
          out.push_back(u0);
          out.push_back(-u1);
        } else {
          out.push_back(D);
        }
        if (*root == 0) break;  // a double root: one point
      }
    }
  }
}

// Every candidate normal of a rim-wall or rim-rim contact (orientation left to the proof, which
// turns D so that D.T > 0). If the pair touches by such a contact, its normal is among them.
inline std::vector<Vec3<Rational>> rim_contact_normals(const CylinderPair<Rational>& d) {
  std::vector<Vec3<Rational>> out;
  rim_wall_normals(d, out);
  rim_rim_normals(d, out);
  return out;
}

}  // namespace certcyl::detail
