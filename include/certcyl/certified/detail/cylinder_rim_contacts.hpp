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
// F has no multiple root (squarefree_mod_p) and the exact gcd is skipped. F mod p is computed
// from the residues of the integer inputs, so F itself (coefficients of degree 8 in numbers of
// thousands of bits, on wide-range input) is formed only when that test fails.
#pragma once

#include <CGAL/Gmpq.h>
#include <CGAL/Gmpz.h>
#include <gmp.h>

#include <algorithm>
#include <array>
#include <concepts>
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

inline constexpr std::uint64_t kSquarefreePrime = 4294967291u;  // 2^32 - 5

// An integer's residue modulo kSquarefreePrime: the ring homomorphism Z -> Z/p, so that a
// polynomial's reduction can be computed without the polynomial (the same operations on the
// residues of its integer inputs).
struct ResidueModP {
  static constexpr std::uint64_t p = kSquarefreePrime;
  std::uint64_t v = 0;  // in [0, p)
  ResidueModP() = default;
  explicit ResidueModP(long x) : v(x >= 0 ? static_cast<std::uint64_t>(x) % p : (p - static_cast<std::uint64_t>(-(x + 1)) % p - 1) % p) {}
  explicit ResidueModP(const CGAL::Gmpz& z) : v(mpz_fdiv_ui(z.mpz(), p)) {}
  friend ResidueModP operator+(ResidueModP a, ResidueModP b) { return from((a.v + b.v) % p); }
  friend ResidueModP operator-(ResidueModP a, ResidueModP b) { return from((a.v + p - b.v) % p); }
  friend ResidueModP operator-(ResidueModP a) { return from((p - a.v) % p); }
  friend ResidueModP operator*(ResidueModP a, ResidueModP b) { return from(a.v * b.v % p); }
  ResidueModP& operator+=(ResidueModP b) { return *this = *this + b; }
  ResidueModP& operator-=(ResidueModP b) { return *this = *this - b; }
  ResidueModP& operator*=(ResidueModP b) { return *this = *this * b; }
  friend bool operator==(ResidueModP a, int b) { return a.v == ResidueModP(static_cast<long>(b)).v; }

 private:
  static ResidueModP from(std::uint64_t v) {
    ResidueModP r;
    r.v = v;
    return r;
  }
};

// ---- univariate polynomials over Q, Z or Z/p: coefficients from degree 0 up, no trailing zero --
template <class C>
concept PolynomialCoefficient = std::same_as<C, Rational> || std::same_as<C, CGAL::Gmpz> || std::same_as<C, ResidueModP>;
using RationalPolynomial = std::vector<Rational>;
using IntegerPolynomial = std::vector<CGAL::Gmpz>;

template <PolynomialCoefficient C>
std::vector<C> trimmed(std::vector<C> f) {
  while (!f.empty() && f.back() == 0) f.pop_back();
  return f;
}

template <PolynomialCoefficient C>
std::vector<C> operator+(const std::vector<C>& f, const std::vector<C>& g) {
  std::vector<C> h(std::max(f.size(), g.size()), C(0));
  for (std::size_t i = 0; i < f.size(); ++i) h[i] += f[i];
  for (std::size_t i = 0; i < g.size(); ++i) h[i] += g[i];
  return trimmed(std::move(h));
}

template <PolynomialCoefficient C>
std::vector<C> operator*(const C& c, const std::vector<C>& f) {
  std::vector<C> h(f);
  for (C& x : h) x *= c;
  return trimmed(std::move(h));
}

template <PolynomialCoefficient C>
std::vector<C> operator-(const std::vector<C>& f, const std::vector<C>& g) {
  return f + C(-1) * g;
}

template <PolynomialCoefficient C>
std::vector<C> operator*(const std::vector<C>& f, const std::vector<C>& g) {
  if (f.empty() || g.empty()) return {};
  std::vector<C> h(f.size() + g.size() - 1, C(0));
  for (std::size_t i = 0; i < f.size(); ++i)
    for (std::size_t j = 0; j < g.size(); ++j) h[i + j] += f[i] * g[j];
  return trimmed(std::move(h));
}

template <PolynomialCoefficient C>
std::vector<C> derivative(const std::vector<C>& f) {
  std::vector<C> h;
  for (std::size_t i = 1; i < f.size(); ++i) h.push_back(C(static_cast<long>(i)) * f[i]);
  return trimmed(std::move(h));
}

// Quotient and remainder of f by g != 0 over Q.
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

// f over Z divided by the gcd of its coefficients, with a positive leading coefficient.
inline IntegerPolynomial primitive_part(IntegerPolynomial f) {
  CGAL::Gmpz g(0);
  for (const CGAL::Gmpz& c : f) mpz_gcd(g.mpz(), g.mpz(), c.mpz());
  if (mpz_sgn(g.mpz()) == 0) return {};
  if (mpz_sgn(f.back().mpz()) < 0) mpz_neg(g.mpz(), g.mpz());
  for (CGAL::Gmpz& c : f) mpz_divexact(c.mpz(), c.mpz(), g.mpz());
  return f;
}

// A remainder of f by g != 0 over Z: lc(g)^k f - q g of degree below g's, for some k >= 0 and an
// integer polynomial q (each step scales f by lc(g) so that its leading term cancels in
// integers). Over Q it is a nonzero constant times f mod g, so gcd(g, it) = gcd(f, g).
inline IntegerPolynomial pseudo_remainder(IntegerPolynomial f, const IntegerPolynomial& g) {
  const CGAL::Gmpz& lead = g.back();
  while (f.size() >= g.size() && !f.empty()) {
    const std::size_t shift = f.size() - g.size();
    const CGAL::Gmpz c = f.back();
    for (CGAL::Gmpz& x : f) x *= lead;
    for (std::size_t i = 0; i < g.size(); ++i) f[shift + i] -= c * g[i];
    f.pop_back();  // the leading coefficient cancels exactly
    f = trimmed(std::move(f));
  }
  return f;
}

// A greatest common divisor over Q, as a primitive integer polynomial (the primitive remainder
// sequence: Euclid's algorithm with pseudo-remainders, each made primitive so that the
// coefficients do not grow); empty when f = g = 0.
inline IntegerPolynomial primitive_gcd(IntegerPolynomial f, IntegerPolynomial g) {
  f = primitive_part(std::move(f));
  g = primitive_part(std::move(g));
  while (!g.empty()) {
    IntegerPolynomial r = primitive_part(pseudo_remainder(f, g));
    f = std::move(g);
    g = std::move(r);
  }
  return f;
}

inline std::uint64_t power_mod_p(std::uint64_t b, std::uint64_t e) {
  constexpr std::uint64_t p = kSquarefreePrime;
  std::uint64_t r = 1;
  for (b %= p; e; e >>= 1, b = b * b % p)
    if (e & 1) r = r * b % p;
  return r;
}

// True when f is proved squarefree (no multiple root, over the complex numbers) by reduction
// modulo the prime p = 2^32 - 5: each coefficient n/d with p not dividing d maps to n d^-1 mod p
// (a ring homomorphism from the rationals with such denominators onto Z/p). If p divides no
// denominator nor the leading coefficient, and gcd(f mod p, (f mod p)') is a constant, then f is
// squarefree: a factor h of f and f' of degree >= 1, taken primitive over the p-adic integers
// (Gauss's lemma), has a leading coefficient dividing lc(f), so h mod p keeps its degree and
// divides both reductions. False proves nothing (the exact gcd decides).
// Here on g = f mod p, lowest degree first, when f's reduction is computed without f (so g.back()
// must be the reduction of f's leading coefficient: nonzero, g has f's degree).
inline bool squarefree_reduced_mod_p(std::vector<std::uint64_t> g) {
  constexpr std::uint64_t p = kSquarefreePrime;
  if (g.size() < 2) return g.size() == 1;
  if (g.back() == 0) return false;
  std::vector<std::uint64_t> h;  // the derivative
  for (std::size_t i = 1; i < g.size(); ++i) h.push_back(g[i] * i % p);
  const auto trim = [](std::vector<std::uint64_t>& v) {
    while (!v.empty() && v.back() == 0) v.pop_back();
  };
  trim(h);
  // Euclid over Z/p: a remainder sequence ending in a nonzero constant means coprime.
  while (!h.empty()) {
    const std::uint64_t inv = power_mod_p(h.back(), p - 2);
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

// The same test on f itself.
template <PolynomialCoefficient C>
bool squarefree_mod_p(const std::vector<C>& f) {
  constexpr std::uint64_t p = kSquarefreePrime;
  if (f.size() < 2) return f.size() == 1;
  std::vector<std::uint64_t> g;  // f mod p, lowest degree first
  for (const C& c : f) {
    if constexpr (std::same_as<C, CGAL::Gmpz>) {
      g.push_back(mpz_fdiv_ui(c.mpz(), p));
    } else {
      const std::uint64_t d = mpz_fdiv_ui(mpq_denref(c.mpq()), p);
      if (d == 0) return false;
      g.push_back(mpz_fdiv_ui(mpq_numref(c.mpq()), p) * power_mod_p(d, p - 2) % p);
    }
  }
  return squarefree_reduced_mod_p(std::move(g));
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
template <PolynomialCoefficient C>
std::vector<C> squared_norm_along(const Vec3<C>& U, const Vec3<C>& V) {
  return trimmed(std::vector<C>{dot(U, U), C(2) * dot(U, V), dot(V, V)});
}

// The pair times the least common multiple of its denominators: integers, and the same
// directions (a positive scale), for the candidates below.
struct IntegerScaledPair {
  std::array<std::array<Vec3<CGAL::Gmpz>, 2>, 2> ends;  // ends[i] = {p0_i, p1_i}
  std::array<Vec3<CGAL::Gmpz>, 2> A;
  std::array<CGAL::Gmpz, 2> r, AA;
  Vec3<CGAL::Gmpz> T;

  static IntegerScaledPair make(const CylinderPair<Rational>& d) {
    using Z = CGAL::Gmpz;
    const Z L = *denominator_lcm(d.c0, d.c1);
    const auto integer = [&L](const Rational& q) { return scaled_integer(q, L); };
    IntegerScaledPair z;
    const auto point = [&integer](const Point3<Rational>& p) { return Vec3<Z>{integer(p.x), integer(p.y), integer(p.z)}; };
    z.ends = {{{point(d.c0.p0), point(d.c0.p1)}, {point(d.c1.p0), point(d.c1.p1)}}};
    z.A = {d.A0.map(integer), d.A1.map(integer)};
    z.r = {integer(d.c0.radius), integer(d.c1.radius)};
    z.AA = {dot(z.A[0], z.A[0]), dot(z.A[1], z.A[1])};
    z.T = d.T.map(integer);
    return z;
  }
};

inline Vec3<Rational> to_rational_vector(const Vec3<CGAL::Gmpz>& v) {
  return v.map([](const CGAL::Gmpz& x) { return Rational(x); });
}

// ---- rim-wall candidates (header comment) --------------------------------------------------------
// Normals of every rim-wall contact of the pair (rim of one cylinder, wall of the other): for
// each wall cylinder j and each sign sigma, the rational double roots of F_sigma. In integers:
// the pair times the least common multiple of its denominators (the same directions), the line
// as D = T_j + t W with T_j = a_j T - (T.A_j) A_j (so D.T = k = T_j.T > 0 instead of 1), and
// F_sigma times k^4 (a_i a_j)^2, a_i = A_i.A_i:
//   E = a_i a_j (k - sigma l)^2 - P_i - P_j,  G = E^2 - 4 P_i P_j,
//   P_i = 4 r_i^2 a_j |D x A_i|^2,  P_j = 4 r_j^2 a_i |D x A_j|^2,  l = D.A_i,
// whose roots are those of F_sigma. No gcd of rationals is formed on the way (they were most of
// the cost for input of thousands of bits), and the double roots come from a primitive
// remainder sequence over Z.
// The polynomials above for wall j and rim i on the line D = T_j + t W, over Z (exactly) or Z/p
// (the same operations on the residues of the integer inputs: G's reduction without G).
template <PolynomialCoefficient C>
struct RimWallLine {
  std::vector<C> l, Pi, Pj, four_pi_pj;
  C k, aa;  // k and a_i a_j

  RimWallLine(const Vec3<C>& Tj, const Vec3<C>& W, const Vec3<C>& Ai, const Vec3<C>& Aj, const C& k_, const C& ri, const C& rj,
              const C& AAi, const C& AAj)
      : k(k_), aa(AAi * AAj) {
    const C four(4L);
    l = trimmed(std::vector<C>{dot(Tj, Ai), dot(W, Ai)});
    Pi = (four * ri * ri * AAj) * squared_norm_along(cross(Tj, Ai), cross(W, Ai));
    Pj = (four * rj * rj * AAi) * squared_norm_along(cross(Tj, Aj), cross(W, Aj));
    four_pi_pj = four * (Pi * Pj);
  }
  std::vector<C> G(int sigma) const {
    const std::vector<C> m = std::vector<C>{k} - C(static_cast<long>(sigma)) * l;  // k - sigma l
    const std::vector<C> E = aa * (m * m) - Pi - Pj;
    return E * E - four_pi_pj;
  }
};

inline void rim_wall_normals(const CylinderPair<Rational>& d, std::vector<Vec3<Rational>>& out) {
  using Z = CGAL::Gmpz;
  using P = ResidueModP;
  const IntegerScaledPair z = IntegerScaledPair::make(d);
  const Vec3<Z>& T = z.T;
  const std::array<Vec3<Z>, 2>& A = z.A;
  const std::array<Z, 2>&r = z.r, &AA = z.AA;
  const auto residue = [](const Z& x) { return P(x); };
  for (int j = 0; j < 2; ++j) {
    const int i = 1 - j;  // the rim's cylinder; j is the wall's
    const Vec3<Z> W = cross(A[j], T);
    if (W.x == 0 && W.y == 0 && W.z == 0) continue;  // A_j parallel to T: no normal with D.A_j = 0 < D.T
    const Vec3<Z> Tj = AA[j] * T - dot(T, A[j]) * A[j];
    const Z k = dot(Tj, T);  // = |W|^2 > 0
    // G modulo p first: when its degree-4 coefficient survives the reduction (so G has degree 4)
    // and the reduction is squarefree, G has no double root and is never formed (its
    // coefficients are of degree 8 in numbers of thousands of bits on wide-range input).
    const RimWallLine<P> reduced(Tj.map(residue), W.map(residue), A[i].map(residue), A[j].map(residue), P(k), P(r[i]), P(r[j]),
                                 P(AA[i]), P(AA[j]));
    std::optional<RimWallLine<Z>> line;
    for (const int sigma : {1, -1}) {
      if (const std::vector<P> Gp = reduced.G(sigma); Gp.size() == 5) {
        std::vector<std::uint64_t> g;
        for (const P& c : Gp) g.push_back(c.v);
        if (squarefree_reduced_mod_p(std::move(g))) continue;  // no double root
      }
      if (!line) line.emplace(Tj, W, A[i], A[j], k, r[i], r[j], AA[i], AA[j]);
      const IntegerPolynomial& l = line->l;
      const IntegerPolynomial G = line->G(sigma);
      if (G.empty()) continue;  // sigma l = k and p_i = p_j: no contact for this sigma (header comment)
      if (squarefree_mod_p(G)) continue;  // no double root
      const IntegerPolynomial H = primitive_gcd(G, derivative(G));
      if (H.size() < 2) continue;  // no double root
      RationalPolynomial Hq;
      for (const Z& c : H) Hq.push_back(Rational(c));
      const RationalPolynomial S = divide(Hq, gcd(Hq, derivative(Hq))).first;
      for (const Rational& t : rational_roots_up_to_quadratic(S)) {
        // The rim is the end sigma: sign(D.A_i) = sigma, else this root belongs to another factor.
        const Rational li = Rational(l.empty() ? Z(0) : l[0]) + t * Rational(l.size() > 1 ? l[1] : Z(0));
        if ((sigma > 0 && li > 0) || (sigma < 0 && li < 0)) out.push_back(to_rational_vector(Tj) + t * to_rational_vector(W));
      }
    }
  }
}

// ---- rim-rim candidates (header comment) ----------------------------------------------------------
// In integers (IntegerScaledPair): with L = A0 x A1 and Lq = L.L, the line where the cap planes
// A0.X = h0 and A1.X = h1 meet is X = (X0 + s L) / Lq, X0 = (h0 a1 - h1 A01) A0 + (h1 a0 - h0 A01) A1
// (a_i = A_i.A_i, A01 = A0.A1); on rim circle 0, with w = X0 - Lq e0,
//   Lq s^2 + 2 b s + c = 0,  b = L.w,  c = |w|^2 - r0^2 Lq^2,
// so s = (-b +- root) / Lq with root^2 = b^2 - Lq c, and U_i = Lq^2 (X - e_i) are integer vectors:
// U_0 = Lq w + (-b +- root) L, U_1 = U_0 + Lq^2 (e0 - e1); X is on rim 1 when |U_1|^2 = r1^2 Lq^4.
inline void rim_rim_normals(const CylinderPair<Rational>& d, std::vector<Vec3<Rational>>& out) {
  using Z = CGAL::Gmpz;
  const IntegerScaledPair z = IntegerScaledPair::make(d);
  const Vec3<Z> L = cross(z.A[0], z.A[1]);
  if (L.x == 0 && L.y == 0 && L.z == 0) return;  // parallel cap planes: rims meet only in a cap-cap contact
  const Z Lq = dot(L, L), A01 = dot(z.A[0], z.A[1]), Lq2 = Lq * Lq;
  const Z r1_Lq2_squared = z.r[1] * z.r[1] * Lq2 * Lq2;
  for (const Vec3<Z>& e0 : z.ends[0]) {
    for (const Vec3<Z>& e1 : z.ends[1]) {
      const Z h0 = dot(z.A[0], e0), h1 = dot(z.A[1], e1);
      const Vec3<Z> X0 = (h0 * z.AA[1] - h1 * A01) * z.A[0] + (h1 * z.AA[0] - h0 * A01) * z.A[1];
      const Vec3<Z> w = X0 - Lq * e0;
      const Z b = dot(L, w), c = dot(w, w) - z.r[0] * z.r[0] * Lq2;
      const Z disc = b * b - Lq * c;
      if (mpz_sgn(disc.mpz()) < 0 || !mpz_perfect_square_p(disc.mpz())) continue;  // no common point, or an irrational one (theorem)
      Z root;
      mpz_sqrt(root.mpz(), disc.mpz());
      for (const Z& shift : {Z(root - b), Z(-root - b)}) {
        const Vec3<Z> U0 = Lq * w + shift * L;
        const Vec3<Z> U1 = U0 + Lq2 * (e0 - e1);
        if (dot(U1, U1) != r1_Lq2_squared) continue;
        const Vec3<Z> D = cross(cross(z.A[0], U0), cross(z.A[1], U1));
        if (D.x == 0 && D.y == 0 && D.z == 0) {
          // else-branch of the header: the two normal planes coincide; the boundary rays.
          out.push_back(to_rational_vector(U0));
          out.push_back(to_rational_vector(-U1));
        } else {
          out.push_back(to_rational_vector(D));
        }
        if (root == 0) break;  // a double root: one point
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
