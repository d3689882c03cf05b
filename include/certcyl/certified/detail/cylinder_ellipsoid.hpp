// certcyl/certified/detail/cylinder_ellipsoid.hpp -- the complete stage of the certified
// cylinder-pair query: the two convex feasibility problems whose solutions are the overlapping
// and separated certificates, each solved by the central-cut ellipsoid method with exact
// rational cuts, so that the query decides every valid input.
//
// Semantics. Notation of cylinder_cylinder.hpp (phi, Delta = m1 - m0, T = 2 Delta). For a pair
// with Delta != 0, exactly one of the following holds:
//   P = int K0 n int K1 is not empty                       (overlapping; phi* > 1),
//   S = { D : D.Delta = 1, phi(D) < 1 } is not empty       (separated; phi* < 1),
//   the pair touches                                       (phi* = 1).
// P and S are open, convex and bounded. A rational point of P, or a rational D of S, is the
// certificate, and the caller checks it exactly (cylinder_certificates.hpp): nothing here can
// make an answer wrong. What this file adds is that the search for such a point provably ends
// when P or S is not empty; touching pairs are decided before, by the touching stage, which is
// complete (detail/cylinder_rim_contacts.hpp, Theorem 2 of the paper).
//
// Coordinates. The input is scaled to integers (IntegerPair), so that every exact evaluation is
// in Gmpz. Each problem is searched in coordinates u in which its target lies in the unit
// ball: points X = m + 2^k u (n = 3), m the midpoint of the smaller cylinder K by A.A/4 + r^2,
// with 2^k >= |A|/2 + r (P lies in K); directions
// D = D0 + 2^k (u1 E1 + u2 E2) (n = 2) with D0 = Delta / Delta.Delta, E1 = Delta x e_j,
// E2 = Delta x E1 (rational, orthogonal to Delta and to each other) and 2^(2k) min(E1.E1, E2.E2)
// >= 1 / mu^2, mu^2 = max(min(A0.A0 / 4, r0^2), min(A1.A1 / 4, r1^2)): phi(D) >= mu |D| (phi
// bounds each cylinder's term |D.A|/2 + r |D x A|/|A| >= min(|A|/2, r) |D|), so S lies in
// |D| < 1/mu, and |D - D0|^2 = 2^(2k) (u1^2 E1.E1 + u2^2 E2.E2).
//
// Cuts (the oracle). At a centre y that is not a certificate: c (an integer vector times a power
// of two) and gamma with c.u < gamma on the whole target; c.y >= gamma for point cuts, and for
// direction cuts once the minorant is accurate enough (below):
//   points      some constraint f > 0 of int K_i fails at X_y: f(X_y) <= 0, with f one of
//               (X - p0).A, A.A - (X - p0).A and r^2 A.A - |(X - p0) x A|^2 (decided exactly).
//               Each f is concave, so f(X) <= f(X_y) + grad f(X_y).(X - X_y), and on P:
//               c = -2^k grad f(X_y), gamma = c.y + f(X_y) (a deep cut, rational).
//   directions  phi(D) >= l(D) = V.D for every D, with V = sum_i e_i A_i / 2 + r_i A_i x w_i, any
//               e_i in [-1, 1] and rational w_i with |w_i|^2 A_i.A_i <= 1 (checked exactly):
//               w.(D x A) = D.(A x w) <= |w| |D x A| <= |D x A| / |A|. So S lies in V.D < 1:
//               c = 2^k (V.E1, V.E2), gamma = 1 - V.D0. With e_i = sign(D_y.A_i) and w_i the
//               rounding of (D_y x A_i) / (|D_y x A_i| |A_i|), l(D_y) -> phi(D_y) >= 1 as the
//               precision grows, so the centre is cut off (l(D_y) > 1 - eta) at some precision.
//
// Runs (EllipsoidRun). E(A, a) = { u : (u - a)^T A^-1 (u - a) <= 1 }, from the unit ball.
//   fast     MPFR at p bits, deep and shallow cuts, no rounding control, from the unit ball or
//            from a small ball around a warm start: a heuristic that usually ends in a few
//            hundred steps. It stops when a cut leaves no ellipsoid or the matrix stops being
//            positive definite (possible in floating point).
//   rounded  the central-cut ellipsoid method of Grotschel, Lovasz and Schrijver (Geometric
//            Algorithms and Combinatorial Optimization, 1988, (3.2.1)-(3.2.4)): N = p/8 steps,
//            a_{k+1} and A_{k+1} = (2n^2+3)/(2n^2) (A_k - 2/(n+1) b b^T), b = A_k c / sqrt(c^T A_k c),
//            rounded to p binary digits after the point. Their Theorem (3.2.1): every E_k
//            contains the target K (a closed convex set in the unit ball, given by a strong
//            separation oracle), and vol(E_{k+1}) < e^(-1/(5n)) vol(E_k); after
//            N >= 5 n |log2 eps| + 5 n^2 steps either a centre lies in K or vol(E_N) <= eps.
//            Obligation: each entry within 2^-p of the exact update. It is computed in MPFR at
//            W = 2p + 64 bits, then rounded to the nearest multiple of 2^-p (error <= 2^-(p+1)).
//            With ||A_k|| <= 2^k and ||A_k^-1|| <= 4^k (GLS, Section 3.2, for R = 1), k <= N = p/8,
//            each of the O(n^2) roundings at W bits (c included) moves b by at most
//            2^(-W) ||A_k|| ||A_k^-1||^(1/2) times a small constant, below 2^(-W + 3p/8 + 8)
//            <= 2^-(p+2) for p >= 128: the computed entries are within 2^-p.
//
// Termination (the completeness theorem of the paper, appendix "Completeness of the
// cylinder-pair query"). If P is not empty it holds a ball of radius rho > 0, and so does
// K_eta = { u : every constraint >= eta } for small eta > 0: every point cut is strict on K_eta
// (grad f(X_y).(X - X_y) >= f(X) - f(X_y) >= eta > 0), so the rounded point run with
// p/8 >= 5n |log2 vol(B_rho/2)| + 5n^2 ends at a centre in P. If S is not empty, phi is
// Lipschitz and S holds a ball of radius rho; the direction oracle of a rounded run at p refines
// its w_i until l(D_y) > 1 - eta_p, eta_p = 2^(-p/4) (this loop ends: l(D_y) -> phi(D_y) >= 1),
// so its cuts are strict on K'_p = { phi <= 1 - eta_p }, which holds a ball of radius rho/2 once
// eta_p is small; the run at such p ends at a centre in S. The stage runs p = 128, 256, ... until
// a certificate is checked, so it ends whenever the pair does not touch.
#pragma once

#include <CGAL/Gmpfr.h>
#include <CGAL/Gmpq.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <optional>

#include "certcyl/certified/detail/cylinder_certificates.hpp"
#include "certcyl/number_traits.hpp"
#include "certcyl/primitives.hpp"
#include "certcyl/vec3.hpp"

namespace certcyl::detail {

// The exact value of a Gmpfr number.
inline Rational to_rational(const CGAL::Gmpfr& x) {
  Rational q;
  mpfr_get_q(q.mpq(), x.fr());
  return q;
}

// A dyadic vector U 2^-s (U integer).
template <int n>
struct DyadicVector {
  std::array<CGAL::Gmpz, n> U;
  long s = 0;
};

// A cut for the ellipsoid: the target lies in { u : c.u < c.y - overshoot }, y the centre,
// c = C 2^e. No overshoot: a central cut (overshoot 0). The overshoot is used by fast runs only,
// and only its approximate value matters there.
template <int n>
struct EllipsoidCut {
  std::array<CGAL::Gmpz, n> C;
  long e = 0;
  std::optional<CGAL::Gmpfr> overshoot;
};

enum class EllipsoidMode { fast, rounded };

// x 2^k for an integer, exactly (k >= 0).
inline CGAL::Gmpz shifted(const CGAL::Gmpz& x, long k) {
  CGAL::Gmpz y;
  mpz_mul_2exp(y.mpz(), x.mpz(), static_cast<mp_bitcnt_t>(k));
  return y;
}

// One run of the ellipsoid method in dimension n (2 or 3) from the unit ball.
template <int n>
class EllipsoidRun {
 public:
  using Vec = std::array<CGAL::Gmpfr, n>;

  // From the unit ball; or, for a fast run, from the ball of radius 2^-j around `start` (a
  // warm start, which only helps when that ball holds part of the target).
  EllipsoidRun(EllipsoidMode mode, long p, const std::array<Rational, n>* start = nullptr, long j = 0)
      : mode_(mode), p_(p), bits_(mode == EllipsoidMode::rounded ? 2 * p + 64 : p) {
    GmpfrPrecision scope(bits_);
    const bool warm = start && mode == EllipsoidMode::fast;
    for (int i = 0; i < n; ++i) {
      a_[i] = warm ? nt::from_rational<CGAL::Gmpfr>((*start)[i]) : nt::constant<CGAL::Gmpfr>(0);
      for (int k = 0; k < n; ++k) {
        A_[i][k] = nt::constant<CGAL::Gmpfr>(i == k ? 1 : 0);
        if (warm && i == k) mpfr_mul_2si(A_[i][k].fr(), A_[i][k].fr(), -2 * j, MPFR_RNDN);
      }
    }
  }

  long bits() const { return bits_; }

  // The centre, exactly.
  DyadicVector<n> centre() const {
    DyadicVector<n> y;
    std::array<long, n> e{};
    long s = 0;
    for (int i = 0; i < n; ++i) {
      if (mpfr_zero_p(a_[i].fr())) continue;
      e[i] = mpfr_get_z_2exp(y.U[i].mpz(), a_[i].fr());
      s = std::max(s, -e[i]);
    }
    for (int i = 0; i < n; ++i)
      if (!mpfr_zero_p(a_[i].fr())) y.U[i] = shifted(y.U[i], e[i] + s);
    y.s = s;
    return y;
  }

  // Shrinks the ellipsoid to (an ellipsoid containing) its part in the cut's halfspace. False
  // when no ellipsoid is left or the arithmetic lost it (fast runs only).
  bool cut(const EllipsoidCut<n>& k) {
    GmpfrPrecision scope(bits_);
    using F = CGAL::Gmpfr;
    // c scaled by a power of two to a largest entry near 1 (the direction is all that counts).
    long top = std::numeric_limits<long>::min();
    for (const CGAL::Gmpz& ci : k.C)
      if (mpz_sgn(ci.mpz()) != 0) top = std::max(top, static_cast<long>(mpz_sizeinbase(ci.mpz(), 2)));
    if (top == std::numeric_limits<long>::min()) return false;  // c = 0: no cut
    Vec c;
    for (int i = 0; i < n; ++i) {
      c[i] = nt::constant<F>(0);
      mpfr_set_z_2exp(c[i].fr(), k.C[i].mpz(), -top, MPFR_RNDN);
    }
    Vec Ac;
    for (int i = 0; i < n; ++i) {
      Ac[i] = nt::constant<F>(0);
      for (int j = 0; j < n; ++j) Ac[i] = Ac[i] + A_[i][j] * c[j];
    }
    F cAc = nt::constant<F>(0);
    for (int i = 0; i < n; ++i) cAc = cAc + c[i] * Ac[i];
    if (!(cAc > 0)) return false;
    const F root = CGAL::sqrt(cAc);
    Vec b;
    for (int i = 0; i < n; ++i) b[i] = Ac[i] / root;
    // Depth alpha = overshoot / sqrt(c^T A c), with c and the overshoot in the same scale (0: central).
    F alpha = nt::constant<F>(0);
    if (mode_ == EllipsoidMode::fast && k.overshoot) {
      F o = nt::constant<F>(0);
      mpfr_mul_2si(o.fr(), k.overshoot->fr(), -top - k.e, MPFR_RNDN);
      alpha = o / root;
      if (!(alpha < 1)) return false;  // the halfspace misses the ellipsoid
      const F floor_alpha = nt::constant<F>(-1) / nt::constant<F>(2 * n);
      if (alpha < floor_alpha) alpha = floor_alpha;  // too shallow to shrink: a deeper cut (heuristic)
    }
    const F nn = nt::constant<F>(n), one = nt::constant<F>(1);
    const F step = (one + nn * alpha) / (nn + one);
    F scale, weight;
    if (mode_ == EllipsoidMode::rounded) {
      scale = nt::constant<F>(2 * n * n + 3) / nt::constant<F>(2 * n * n);
      weight = nt::constant<F>(2) / (nn + one);
    } else {
      scale = nn * nn * (one - alpha * alpha) / (nn * nn - one);
      weight = nt::constant<F>(2) * step / (one + alpha);
    }
    for (int i = 0; i < n; ++i) a_[i] = round(a_[i] - step * b[i]);
    for (int i = 0; i < n; ++i)
      for (int j = i; j < n; ++j) A_[i][j] = A_[j][i] = round(scale * (A_[i][j] - weight * b[i] * b[j]));
    for (int i = 0; i < n; ++i)
      if (!(A_[i][i] > 0)) return false;
    return true;
  }

 private:
  // Rounded runs: the nearest multiple of 2^-p (exact in W bits: the entries stay below 2^(p/8+2)).
  CGAL::Gmpfr round(const CGAL::Gmpfr& x) const {
    if (mode_ != EllipsoidMode::rounded) return x;
    CGAL::Gmpfr y(0, bits_);
    mpfr_mul_2si(y.fr(), x.fr(), p_, MPFR_RNDN);
    mpfr_rint(y.fr(), y.fr(), MPFR_RNDN);
    mpfr_div_2si(y.fr(), y.fr(), p_, MPFR_RNDN);
    return y;
  }

  EllipsoidMode mode_;
  long p_, bits_;
  Vec a_;
  std::array<Vec, n> A_;
};

// Runs the ellipsoid for at most `steps` steps: `oracle(y, bits)` checks the centre y exactly
// and returns nullopt when it is a certificate (the run ends: true), else a cut; `bits` is the
// run's working precision. `steps` counts the steps taken.
template <int n, class Oracle>
bool run_ellipsoid(EllipsoidMode mode, long p, long max_steps, std::uint32_t& steps, Oracle&& oracle,
                   const std::array<Rational, n>* start = nullptr, long j = 0) {
  EllipsoidRun<n> e(mode, p, start, j);
  for (long s = 0; s < max_steps; ++s) {
    ++steps;
    const std::optional<EllipsoidCut<n>> k = oracle(e.centre(), e.bits());
    if (!k) return true;
    if (!e.cut(*k)) return false;
  }
  return false;
}

// ---- the two problems ----------------------------------------------------------------------

// The pair scaled by L = 2 lcm(denominators of the input): integer endpoints, radii, axes,
// midpoints and Delta. Points scale with it; separating directions do not change.
struct IntegerPair {
  CylinderPair<CGAL::Gmpz> d;
  Point3<CGAL::Gmpz> m0;
  Vec3<CGAL::Gmpz> delta;  // m1 - m0
  CGAL::Gmpz L;

  explicit IntegerPair(const CylinderPair<Rational>& e) {
    L = *denominator_lcm(e.c0, e.c1) * 2;
    const auto to_z = [this](const Rational& q) { return nt::from_rational<CGAL::Gmpz>(q * Rational(L)); };
    d = CylinderPair<CGAL::Gmpz>::make(e.c0.map(to_z), e.c1.map(to_z));
    const auto half = [](const CGAL::Gmpz& x) {
      CGAL::Gmpz y;
      mpz_divexact_ui(y.mpz(), x.mpz(), 2);
      return y;
    };
    m0 = {half(d.c0.p0.x + d.c0.p1.x), half(d.c0.p0.y + d.c0.p1.y), half(d.c0.p0.z + d.c0.p1.z)};
    delta = {half(d.T.x), half(d.T.y), half(d.T.z)};
  }
};

// The smallest k with 4^k x >= y for rationals x, y > 0.
inline long two_power_covering(const Rational& x, const Rational& y) {
  const Rational ratio = y / x;
  long k = (static_cast<long>(mpz_sizeinbase(mpq_numref(ratio.mpq()), 2)) - static_cast<long>(mpz_sizeinbase(mpq_denref(ratio.mpq()), 2))) / 2 - 2;
  const auto pow4 = [](long j) {
    Rational r(1);
    if (j >= 0) mpq_mul_2exp(r.mpq(), r.mpq(), static_cast<mp_bitcnt_t>(2 * j));
    else mpq_div_2exp(r.mpq(), r.mpq(), static_cast<mp_bitcnt_t>(-2 * j));
    return r;
  };
  while (pow4(k) * x < y) ++k;
  return k;
}

// 2^sigma times the point or direction base + 2^k (U 2^-s) . basis, with sigma = max(0, s - k)
// so that the result is an integer vector.
template <int n>
Vec3<CGAL::Gmpz> dyadic_combination(const Vec3<CGAL::Gmpz>& base, long k, const DyadicVector<n>& y,
                                    const std::array<Vec3<CGAL::Gmpz>, n>& basis, long& sigma) {
  const long t = k - y.s;
  sigma = std::max(0L, -t);
  Vec3<CGAL::Gmpz> v{shifted(base.x, sigma), shifted(base.y, sigma), shifted(base.z, sigma)};
  for (int i = 0; i < n; ++i) {
    const CGAL::Gmpz ui = shifted(y.U[i], sigma + t);
    v = v + Vec3<CGAL::Gmpz>{ui * basis[i].x, ui * basis[i].y, ui * basis[i].z};
  }
  return v;
}

inline CGAL::Gmpfr gmpfr_of(const CGAL::Gmpz& x, long e = 0) {
  CGAL::Gmpfr y = nt::constant<CGAL::Gmpfr>(0);
  mpfr_set_z_2exp(y.fr(), x.mpz(), e, MPFR_RNDN);
  return y;
}

// Points: X(u) = m + 2^k u in the integer frame, m the midpoint of the smaller cylinder K (by
// A.A/4 + r^2), the target P = int K0 n int K1 (in K) in the unit ball.
class PointProblem {
 public:
  explicit PointProblem(const IntegerPair& z) : z_(z) {
    const auto size = [](const CGAL::Gmpz& AA, const CGAL::Gmpz& r) { return Rational(AA) / 4 + Rational(r) * Rational(r); };
    const Rational s0 = size(z.d.AA0, z.d.c0.radius), s1 = size(z.d.AA1, z.d.c1.radius);
    m_ = s1 < s0 ? z.m0 + z.delta : z.m0;
    // (|A|/2 + r)^2 <= 2 (A.A/4 + r^2) <= 4^k
    k_ = two_power_covering(Rational(1), 2 * std::min(s0, s1));
    const Vec3<CGAL::Gmpz> ex{1, 0, 0}, ey{0, 1, 0}, ez{0, 0, 1};
    basis_ = {ex, ey, ez};
  }

  // The coordinates u of an input-frame point X (X L = m + 2^k u in the integer frame).
  std::array<Rational, 3> coordinates(const Point3<Rational>& X) const {
    const Rational L(z_.L);
    const Rational scale = times_two_power(Rational(1), -k_);
    return {(X.x * L - Rational(m_.x)) * scale, (X.y * L - Rational(m_.y)) * scale, (X.z * L - Rational(m_.z)) * scale};
  }

  // The input-frame point of y.
  Point3<Rational> point(const DyadicVector<3>& y) const {
    long sigma = 0;
    const Vec3<CGAL::Gmpz> X = dyadic_combination<3>(m_ - Point3<CGAL::Gmpz>{0, 0, 0}, k_, y, basis_, sigma);
    const Rational scale = Rational(shifted(z_.L, sigma));
    return {Rational(X.x) / scale, Rational(X.y) / scale, Rational(X.z) / scale};
  }

  // nullopt when X(y) is strictly inside both (exactly); else a deep cut from a violated
  // constraint (grad f at X(y); its overshoot -f(X(y)) approximate, at `bits` bits).
  std::optional<EllipsoidCut<3>> cut(const DyadicVector<3>& y, long bits) const {
    long sigma = 0;
    const Vec3<CGAL::Gmpz> Xs = dyadic_combination<3>(m_ - Point3<CGAL::Gmpz>{0, 0, 0}, k_, y, basis_, sigma);
    for (int i = 0; i < 2; ++i) {
      const Cylinder<CGAL::Gmpz>& c = i == 0 ? z_.d.c0 : z_.d.c1;
      const Vec3<CGAL::Gmpz>& A = i == 0 ? z_.d.A0 : z_.d.A1;
      const CGAL::Gmpz& AA = i == 0 ? z_.d.AA0 : z_.d.AA1;
      // Everything times 2^sigma: w = 2^sigma (X - p0), s = w.A.
      const Vec3<CGAL::Gmpz> w{Xs.x - shifted(c.p0.x, sigma), Xs.y - shifted(c.p0.y, sigma), Xs.z - shifted(c.p0.z, sigma)};
      const CGAL::Gmpz s = dot(w, A);
      // f = (X - p0).A = s 2^-sigma, grad A.
      if (CGAL::sign(s) != CGAL::POSITIVE) return make_cut(A, 0, s, sigma, bits);
      const CGAL::Gmpz b = shifted(AA, sigma) - s;
      // f = A.A - (X - p0).A = b 2^-sigma, grad -A.
      if (CGAL::sign(b) != CGAL::POSITIVE) return make_cut(-A, 0, b, sigma, bits);
      const Vec3<CGAL::Gmpz> x = cross(w, A);
      const CGAL::Gmpz rs = shifted(c.radius, sigma);
      const CGAL::Gmpz q = rs * rs * AA - dot(x, x);
      // f = r^2 A.A - |(X - p0) x A|^2 = q 2^-2sigma, grad -2 (A.A (X - p0) - ((X - p0).A) A)
      //   = -(A.A w - s A) 2^(1 - sigma).
      if (CGAL::sign(q) != CGAL::POSITIVE) {
        const Vec3<CGAL::Gmpz> g = AA * w - s * A;
        return make_cut(-g, 1 - sigma, q, 2 * sigma, bits);
      }
    }
    return std::nullopt;
  }

 private:
  // f(X) <= f(X_y) + g.(X - X_y), X - X_y = 2^k (u - y): on the target (-2^k g).u < (-2^k g).y + f,
  // with g = G 2^ge and f = F 2^-fe: c = -G 2^(k + ge), overshoot -f.
  EllipsoidCut<3> make_cut(const Vec3<CGAL::Gmpz>& G, long ge, const CGAL::Gmpz& F, long fe, long bits) const {
    EllipsoidCut<3> k;
    k.C = {-G.x, -G.y, -G.z};
    k.e = k_ + ge;
    GmpfrPrecision scope(bits);
    k.overshoot = gmpfr_of(-F, -fe);
    return k;
  }

  const IntegerPair& z_;
  Point3<CGAL::Gmpz> m_;
  long k_ = 0;
  std::array<Vec3<CGAL::Gmpz>, 3> basis_;
};

// Directions: D(u) = D0 + 2^k (u1 E1 + u2 E2) on the plane D.Delta = 1 (integer frame), the
// target S = { phi(D) < 1 } in the unit ball. Requires Delta != 0.
class DirectionProblem {
 public:
  explicit DirectionProblem(const IntegerPair& z) : z_(z) {
    const Vec3<CGAL::Gmpz>& delta = z.delta;
    G_ = dot(delta, delta);
    int j = 0;
    for (int i = 1; i < 3; ++i)
      if (CGAL::abs(delta[i]) < CGAL::abs(delta[j])) j = i;
    Vec3<CGAL::Gmpz> ej{0, 0, 0};
    ej[j] = 1;
    E_[0] = cross(delta, ej);
    E_[1] = cross(delta, E_[0]);
    const auto q = [](const CGAL::Gmpz& x) { return Rational(x); };
    const Rational mu0 = std::min(q(z.d.AA0) / 4, q(z.d.c0.radius) * q(z.d.c0.radius));
    const Rational mu1 = std::min(q(z.d.AA1) / 4, q(z.d.c1.radius) * q(z.d.c1.radius));
    const Rational mu = std::max(mu0, mu1);  // mu^2
    // D - D0 = 2^k (u1 E1 + u2 E2), so |D - D0|^2 >= 4^k min(E1.E1, E2.E2) |u|^2.
    k_ = two_power_covering(std::min(q(dot(E_[0], E_[0])), q(dot(E_[1], E_[1]))), 1 / mu);
  }

  // The coordinates u of the direction D / (D.Delta) (nullopt when D.Delta = 0).
  std::optional<std::array<Rational, 2>> coordinates(const Vec3<Rational>& D) const {
    const auto q = [](const Vec3<CGAL::Gmpz>& v) { return v.map([](const CGAL::Gmpz& x) { return Rational(x); }); };
    const Vec3<Rational> delta = q(z_.delta);
    const Rational dd = dot(D, delta);
    if (dd == 0) return std::nullopt;
    const Vec3<Rational> v = D / dd - delta / Rational(G_);  // 2^k (u1 E1 + u2 E2)
    const Vec3<Rational> E1 = q(E_[0]), E2 = q(E_[1]);
    const Rational scale = times_two_power(Rational(1), -k_);
    return std::array<Rational, 2>{dot(v, E1) / dot(E1, E1) * scale, dot(v, E2) / dot(E2, E2) * scale};
  }

  // 2^sigma G D(y) (a positive multiple of D(y), integer), G = Delta.Delta.
  Vec3<CGAL::Gmpz> direction(const DyadicVector<2>& y, long& sigma) const {
    const std::array<Vec3<CGAL::Gmpz>, 2> basis{G_ * E_[0], G_ * E_[1]};
    return dyadic_combination<2>(z_.delta, k_, y, basis, sigma);
  }

  // The cut l(D) = V.D < 1 for w_i rounded from `bits`-bit values, at the direction Ds =
  // 2^sigma G D_y. With eta_exponent > 0, *cuts_off tells whether l(D_y) > 1 - 2^-eta_exponent
  // (exactly). The overshoot l(D_y) - 1 is approximate (fast runs).
  EllipsoidCut<2> minorant_cut(const Vec3<CGAL::Gmpz>& Ds, long sigma, long bits, long eta_exponent = 0, bool* cuts_off = nullptr) const {
    long h = 0;
    const Vec3<CGAL::Gmpz> Vz = minorant(Ds, bits, h);
    // l(D_y) = V.D_y = Vz.Ds 2^-(h + sigma) / G.
    const CGAL::Gmpz lD = dot(Vz, Ds), unit = shifted(G_, h + sigma);
    if (cuts_off) {
      // l(D_y) > 1 - 2^-eta  <=>  2^eta lD > (2^eta - 1) unit
      *cuts_off = shifted(lD, eta_exponent) > shifted(unit, eta_exponent) - unit;
    }
    EllipsoidCut<2> k;
    // l(D(u)) = V.D0 + 2^k (u1 V.E1 + u2 V.E2): c = (Vz.E1, Vz.E2) 2^(k - h).
    k.C = {dot(Vz, E_[0]), dot(Vz, E_[1])};
    k.e = k_ - h;
    GmpfrPrecision scope(bits);
    k.overshoot = (gmpfr_of(lD) - gmpfr_of(unit)) / gmpfr_of(unit);
    return k;
  }

  // The minorant's vector V = Vz 2^-h (integer frame) at the direction Ds: phi(D) >= V.D for
  // every D (Lemma in the header comment).
  Vec3<CGAL::Gmpz> minorant(const Vec3<CGAL::Gmpz>& Ds, long bits, long& h) const {
    // V = Vz 2^-h, h chosen below; collect each term as (integer vector, exponent).
    struct Term {
      Vec3<CGAL::Gmpz> v;
      long e;
    };
    std::array<Term, 4> terms;
    int used = 0;
    for (int i = 0; i < 2; ++i) {
      const Cylinder<CGAL::Gmpz>& c = i == 0 ? z_.d.c0 : z_.d.c1;
      const Vec3<CGAL::Gmpz>& A = i == 0 ? z_.d.A0 : z_.d.A1;
      const CGAL::Gmpz& AA = i == 0 ? z_.d.AA0 : z_.d.AA1;
      const int sg = CGAL::sign(dot(Ds, A));
      if (sg != 0) terms[used++] = {sg > 0 ? A : Vec3<CGAL::Gmpz>(-A), -1};
      const Vec3<CGAL::Gmpz> x = cross(Ds, A);
      const CGAL::Gmpz xx = dot(x, x);
      if (CGAL::sign(xx) == CGAL::ZERO) continue;
      // w = W 2^we, the rounding of x / (|x| |A|), shrunk until |w|^2 A.A <= 1 (exact).
      std::array<CGAL::Gmpz, 3> W;
      long we = 0;
      {
        GmpfrPrecision scope(bits);
        using F = CGAL::Gmpfr;
        const F inv = nt::constant<F>(1) / CGAL::sqrt(gmpfr_of(xx) * gmpfr_of(AA));
        const F wf[3] = {gmpfr_of(x.x) * inv, gmpfr_of(x.y) * inv, gmpfr_of(x.z) * inv};
        // A common exponent: w_k = W_k 2^we with |W_k| < 2^bits.
        long top = std::numeric_limits<long>::min();
        for (const F& f : wf)
          if (!mpfr_zero_p(f.fr())) top = std::max(top, static_cast<long>(mpfr_get_exp(f.fr())));
        we = top - bits;
        for (int k = 0; k < 3; ++k) {
          F t = nt::constant<F>(0);
          mpfr_mul_2si(t.fr(), wf[k].fr(), -we, MPFR_RNDN);
          mpfr_get_z(W[k].mpz(), t.fr(), MPFR_RNDZ);  // towards zero: |w| only shrinks
        }
      }
      for (;;) {
        // |W|^2 A.A 2^(2 we) <= 1
        const CGAL::Gmpz n2 = W[0] * W[0] + W[1] * W[1] + W[2] * W[2];
        const CGAL::Gmpz lhs = n2 * AA;
        const bool ok = 2 * we >= 0 ? lhs * shifted(CGAL::Gmpz(1), 2 * we) <= CGAL::Gmpz(1) : lhs <= shifted(CGAL::Gmpz(1), -2 * we);
        if (ok) break;
        // W (1 - 2^-(bits - 4)), truncated: |W| only shrinks.
        for (CGAL::Gmpz& Wk : W) {
          CGAL::Gmpz part;
          mpz_tdiv_q_2exp(part.mpz(), Wk.mpz(), static_cast<mp_bitcnt_t>(std::max(1L, bits - 4)));
          Wk = Wk - part;
        }
      }
      const Vec3<CGAL::Gmpz> Wv{W[0], W[1], W[2]};
      terms[used++] = {c.radius * cross(A, Wv), we};
    }
    // Common exponent h: V = sum_t v_t 2^(e_t) = Vz 2^(-h), h = -min e_t.
    h = 0;
    for (int t = 0; t < used; ++t) h = std::max(h, -terms[t].e);
    Vec3<CGAL::Gmpz> Vz{0, 0, 0};
    for (int t = 0; t < used; ++t) {
      const long sh = terms[t].e + h;
      Vz = Vz + Vec3<CGAL::Gmpz>{shifted(terms[t].v.x, sh), shifted(terms[t].v.y, sh), shifted(terms[t].v.z, sh)};
    }
    return Vz;
  }

 private:
  const IntegerPair& z_;
  CGAL::Gmpz G_;
  std::array<Vec3<CGAL::Gmpz>, 2> E_;
  long k_ = 0;
};

}  // namespace certcyl::detail
