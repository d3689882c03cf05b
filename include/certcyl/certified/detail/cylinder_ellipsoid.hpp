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
#include <vector>

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
// run's working precision. `steps` counts the steps taken. `stop()` is asked before each step;
// true ends the run unfinished (false), so a caller's time limit is checked once a step.
template <int n, class Oracle, class Stop = NeverStop>
bool run_ellipsoid(EllipsoidMode mode, long p, long max_steps, std::uint32_t& steps, Oracle&& oracle,
                   const std::array<Rational, n>* start = nullptr, long j = 0, Stop&& stop = Stop{}) {
  EllipsoidRun<n> e(mode, p, start, j);
  for (long s = 0; s < max_steps; ++s) {
    if (stop()) return false;
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

// The smallest k with 4^k x >= y for integers x, y > 0 (no rational arithmetic: the frames
// below compare numbers of thousands of bits, where gcds would dominate).
inline long two_power_covering(const CGAL::Gmpz& x, const CGAL::Gmpz& y) {
  long k = (static_cast<long>(mpz_sizeinbase(y.mpz(), 2)) - static_cast<long>(mpz_sizeinbase(x.mpz(), 2))) / 2 - 2;
  const auto covers = [&](long j) { return j >= 0 ? shifted(x, 2 * j) >= y : x >= shifted(y, -2 * j); };
  while (!covers(k)) ++k;
  return k;
}

// The same for rationals x, y > 0: 4^k x >= y iff 4^k num(x) den(y) >= num(y) den(x).
inline long two_power_covering(const Rational& x, const Rational& y) {
  return two_power_covering(x.numerator() * y.denominator(), y.numerator() * x.denominator());
}

// v x e_j, e_j the unit vector of v's smallest coordinate: orthogonal to v, and nonzero when v is.
inline Vec3<CGAL::Gmpz> cross_with_least_axis(const Vec3<CGAL::Gmpz>& v) {
  int j = 0;
  for (int i = 1; i < 3; ++i)
    if (CGAL::abs(v[i]) < CGAL::abs(v[j])) j = i;
  Vec3<CGAL::Gmpz> e{0, 0, 0};
  e[j] = 1;
  return cross(v, e);
}

// 2^sigma times the point or direction base + sum_i 2^k_i (U_i 2^-s) basis_i, with
// sigma = max(0, max_i (s - k_i)) so that the result is an integer vector.
template <int n>
Vec3<CGAL::Gmpz> dyadic_combination(const Vec3<CGAL::Gmpz>& base, const std::array<long, n>& k, const DyadicVector<n>& y,
                                    const std::array<Vec3<CGAL::Gmpz>, n>& basis, long& sigma) {
  sigma = 0;
  for (int i = 0; i < n; ++i) sigma = std::max(sigma, y.s - k[i]);
  Vec3<CGAL::Gmpz> v{shifted(base.x, sigma), shifted(base.y, sigma), shifted(base.z, sigma)};
  for (int i = 0; i < n; ++i) {
    const CGAL::Gmpz ui = shifted(y.U[i], sigma + k[i] - y.s);
    v = v + Vec3<CGAL::Gmpz>{ui * basis[i].x, ui * basis[i].y, ui * basis[i].z};
  }
  return v;
}

inline CGAL::Gmpfr gmpfr_of(const CGAL::Gmpz& x, long e = 0) {
  CGAL::Gmpfr y = nt::constant<CGAL::Gmpfr>(0);
  mpfr_set_z_2exp(y.fr(), x.mpz(), e, MPFR_RNDN);
  return y;
}

// Points: X(u) = m + sum_i 2^k_i u_i B_i in the integer frame (integer m, integer basis B),
// chosen so that the target P = int K0 n int K1 lies in the unit ball: the ball frame, or the
// parallelepiped frame of least volume when the caller asks for it (input spanning over 256
// binades) and it is smaller by a factor of 2^128 or more. (Its basis of cross products makes
// each step dearer: on pairs of ordinary span 10^-400 off touching, the runs took up to twice as
// long in it, so ordinary input keeps the ball frame.)
//   ball            m the midpoint of the smaller cylinder K (by A.A/4 + r^2), B the unit
//                   vectors, 4^k >= 2 (A.A/4 + r^2) >= (|A|/2 + r)^2 (P lies in K).
//   parallelepiped  three independent functionals F_i from the bounds that hold on P:
//                     slab of K_j   |F.(X - m_j)| <= beta = A_j.A_j / 2 for F = A_j;
//                     tube of K_j   |F.(X - p_j)| <= beta = r_j |F| for F orthogonal to A_j
//                                   (X - p_j = t A_j + w, |w| < r_j);
//                   with F among A_0, A_1, N = A_0 x A_1 (either tube), N x A_0, N x A_1 (or,
//                   for parallel axes, two vectors orthogonal to both axes). B is the dual basis
//                   B_1 = F_2 x F_3, B_2 = F_3 x F_1, B_3 = F_1 x F_2 (F_i.B_j = det delta_ij,
//                   det = F_1.(F_2 x F_3)), m the integer point below (coordinates rounded down)
//                   the point where every F_i takes its bound's centre, so
//                   |F_i.(X - m)| <= beta_i + sqrt(3) |F_i| on P, and u_i = F_i.(X - m) / (2^k_i det)
//                   with 4^k_i det^2 >= 4 Q_i, Q_i = 2 beta_i^2 + 6 F_i.F_i, gives u_i^2 <= 1/4.
//                   Its volume is 2^(k_1 + k_2 + k_3) det^2 (up to 4 pi / 3).
// A needle crossing a pancake, or two pancakes crossing (a common interior a few units thick at
// coordinates of 2^100 and more), is thin in the ball frame, so the runs would need hundreds of
// bits and thousands of steps; in the frame of its slab and tube bounds it fills a fixed part
// of the ball.
class PointProblem {
 public:
  // `fitted`: also consider the parallelepiped frames.
  PointProblem(const IntegerPair& z, bool fitted) : z_(z) {
    const auto q = [](const CGAL::Gmpz& x) { return Rational(x); };
    const auto size = [&](int i) { return q(AA(i)) / 4 + q(radius(i)) * q(radius(i)); };
    const int smaller = size(1) < size(0) ? 1 : 0;
    // The ball frame.
    m_ = midpoint(smaller);
    const long k = two_power_covering(Rational(1), 2 * size(smaller));
    k_ = {k, k, k};
    F_ = basis_ = {Vec3<CGAL::Gmpz>{1, 0, 0}, Vec3<CGAL::Gmpz>{0, 1, 0}, Vec3<CGAL::Gmpz>{0, 0, 1}};
    det_ = 1;
    if (!fitted) return;
    double best = 3.0 * static_cast<double>(k) - 128;  // log2 of the volume to beat
    // The bounds on P.
    std::vector<Bound> bounds;
    for (int j = 0; j < 2; ++j) bounds.push_back(bound(axis(j), dot(axis(j), midpoint(j) - Point3<CGAL::Gmpz>{0, 0, 0}), AA(j) * AA(j)));
    const auto tube = [&](int j, const Vec3<CGAL::Gmpz>& F) {
      const Point3<CGAL::Gmpz>& pj = j == 0 ? z.d.c0.p0 : z.d.c1.p0;
      bounds.push_back(bound(F, dot(F, pj - Point3<CGAL::Gmpz>{0, 0, 0}), 4 * radius(j) * radius(j) * dot(F, F)));
    };
    const Vec3<CGAL::Gmpz> N = cross(axis(0), axis(1));
    if (!(N.x == 0 && N.y == 0 && N.z == 0)) {
      tube(0, N);
      tube(1, N);
      tube(0, cross(N, axis(0)));
      tube(1, cross(N, axis(1)));
    } else {
      const Vec3<CGAL::Gmpz> w1 = cross_with_least_axis(axis(0)), w2 = cross(axis(0), w1);
      for (int c = 0; c < 2; ++c) {
        tube(c, w1);
        tube(c, w2);
      }
    }
    const std::size_t nb = bounds.size();
    for (std::size_t i1 = 0; i1 < nb; ++i1)
      for (std::size_t i2 = i1 + 1; i2 < nb; ++i2)
        for (std::size_t i3 = i2 + 1; i3 < nb; ++i3) consider({&bounds[i1], &bounds[i2], &bounds[i3]}, best);
  }

  // The coordinates u of an input-frame point X: u_i = F_i.(X L - m) / (2^k_i det).
  std::array<Rational, 3> coordinates(const Point3<Rational>& X) const {
    const Rational L(z_.L);
    const Vec3<Rational> v{X.x * L - Rational(m_.x), X.y * L - Rational(m_.y), X.z * L - Rational(m_.z)};
    std::array<Rational, 3> u;
    for (int i = 0; i < 3; ++i) {
      const Vec3<Rational> F = F_[i].map([](const CGAL::Gmpz& x) { return Rational(x); });
      u[i] = dot(v, F) / Rational(det_) * times_two_power(Rational(1), -k_[i]);
    }
    return u;
  }

  // Whether a parallelepiped frame was taken (else the ball frame).
  bool fitted() const { return fitted_; }

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
  // f(X) <= f(X_y) + g.(X - X_y), X - X_y = sum_i 2^k_i (u_i - y_i) B_i: on the target c.u < c.y + f
  // with c_i = -2^k_i g.B_i; g = G 2^ge and f = F 2^-fe: c_i = -(G.B_i) 2^(k_i - kmin) 2^(kmin + ge),
  // overshoot -f.
  EllipsoidCut<3> make_cut(const Vec3<CGAL::Gmpz>& G, long ge, const CGAL::Gmpz& F, long fe, long bits) const {
    EllipsoidCut<3> k;
    const long kmin = std::min({k_[0], k_[1], k_[2]});
    for (int i = 0; i < 3; ++i) k.C[i] = -shifted(dot(G, basis_[i]), k_[i] - kmin);
    k.e = kmin + ge;
    GmpfrPrecision scope(bits);
    k.overshoot = gmpfr_of(-F, -fe);
    return k;
  }

  // |F.X - centre| <= beta on P, given by beta4 = 4 beta^2; the frame reads only 4 Q = 2 beta4 + 24 F.F.
  struct Bound {
    Vec3<CGAL::Gmpz> F;
    CGAL::Gmpz centre;
    CGAL::Gmpz Q4;
  };
  static Bound bound(const Vec3<CGAL::Gmpz>& F, const CGAL::Gmpz& centre, const CGAL::Gmpz& beta4) {
    return {F, centre, 2 * beta4 + 24 * dot(F, F)};
  }

  const CGAL::Gmpz& radius(int i) const { return i == 0 ? z_.d.c0.radius : z_.d.c1.radius; }
  const CGAL::Gmpz& AA(int i) const { return i == 0 ? z_.d.AA0 : z_.d.AA1; }
  const Vec3<CGAL::Gmpz>& axis(int i) const { return i == 0 ? z_.d.A0 : z_.d.A1; }
  Point3<CGAL::Gmpz> midpoint(int i) const { return i == 0 ? z_.m0 : z_.m0 + z_.delta; }

  // Takes the parallelepiped frame of three bounds when it is independent and its volume,
  // sum_i k_i + 2 log2 |det|, is below `best`. A triple is first judged by det alone: with
  // 2^(d-1) <= |det| < 2^d, each k_i (the least k with 4^k det^2 >= 4 Q_i) is at least
  // floor((bits(4 Q_i) - 1 - 2d) / 2) + 1, and a triple whose volume is not below `best` even
  // then is rejected before the rest of the frame is computed (the same choice, at a quarter of
  // the cost on integers of thousands of bits).
  void consider(const std::array<const Bound*, 3>& b, double& best) {
    const Vec3<CGAL::Gmpz> B0 = cross(b[1]->F, b[2]->F);
    const CGAL::Gmpz det = dot(b[0]->F, B0);
    if (det == 0) return;
    const long d = static_cast<long>(mpz_sizeinbase(det.mpz(), 2));
    double least = 2.0 * static_cast<double>(d);
    for (int i = 0; i < 3; ++i) {
      const long x = static_cast<long>(mpz_sizeinbase(b[i]->Q4.mpz(), 2)) - 1 - 2 * d;
      least += static_cast<double>((x >= 0 ? x / 2 : -((-x + 1) / 2)) + 1);  // floor(x / 2) + 1
    }
    if (!(least < best)) return;
    const std::array<Vec3<CGAL::Gmpz>, 3> B{B0, cross(b[2]->F, b[0]->F), cross(b[0]->F, b[1]->F)};
    const CGAL::Gmpz det2 = det * det;
    std::array<long, 3> ks{};
    double volume = 2.0 * static_cast<double>(d);
    for (int i = 0; i < 3; ++i) {
      ks[i] = two_power_covering(det2, b[i]->Q4);
      volume += static_cast<double>(ks[i]);
    }
    if (!(volume < best)) return;
    // m: F_i.m = centre_i, that is m = sum_i centre_i B_i / det, rounded down.
    Vec3<CGAL::Gmpz> num{0, 0, 0};
    for (int i = 0; i < 3; ++i) num = num + Vec3<CGAL::Gmpz>{b[i]->centre * B[i].x, b[i]->centre * B[i].y, b[i]->centre * B[i].z};
    const auto floor_div = [&det](const CGAL::Gmpz& x) {
      CGAL::Gmpz r;
      mpz_fdiv_q(r.mpz(), x.mpz(), det.mpz());
      return r;
    };
    best = volume;
    m_ = {floor_div(num.x), floor_div(num.y), floor_div(num.z)};
    F_ = {b[0]->F, b[1]->F, b[2]->F};
    basis_ = B;
    det_ = det;
    k_ = ks;
    fitted_ = true;
  }

  const IntegerPair& z_;
  Point3<CGAL::Gmpz> m_;
  std::array<long, 3> k_{};
  bool fitted_ = false;
  std::array<Vec3<CGAL::Gmpz>, 3> F_, basis_;  // X - m = sum_i 2^k_i u_i B_i, F_i.B_j = det delta_ij
  CGAL::Gmpz det_;
};

// Directions: D(u) = Dc + 2^k_1 u_1 E_1 + 2^k_2 u_2 E_2 on the plane D.Delta = 1 (integer frame,
// E_i orthogonal to Delta), the target S = { phi(D) < 1 } in the unit ball: the disc frame, or
// the parallelogram frame of least area when the caller asks for it and it is smaller by a factor
// of 2^128 or more.
// Requires Delta != 0.
//   disc           Dc = D0 = Delta / Delta.Delta, E_1 = Delta x e_j, E_2 = Delta x E_1 (orthogonal),
//                  4^k_i E_i.E_i >= 1 / mu^2 (S lies in |D| < 1 / mu, and
//                  |D - D0|^2 = sum_i 4^k_i u_i^2 E_i.E_i >= |u|^2 / mu^2). (One power of two for
//                  both axes made the second |Delta| times longer than needed: on pairs 10^-400
//                  off touching the direction runs took about a third more steps.)
//   parallelogram  two functionals F_1, F_2 from the bounds that hold on S (phi(D) < 1 and phi
//                  bounds each of its terms): |A_j.D| < 2, and |F.D| < |F| / r_j for F orthogonal
//                  to A_j (F.D = F.(D across A_j), and r_j |D x A_j| / |A_j| < 1), with F among
//                  A_0, A_1, N = A_0 x A_1, N x A_j, Delta x A_j. E_1 = Delta x F_2,
//                  E_2 = F_1 x Delta (F_i.E_j = d delta_ij, d = F_1.(Delta x F_2)), Dc = (F_1 x F_2) / s,
//                  s = (F_1 x F_2).Delta = -d (F_i.Dc = 0, Dc.Delta = 1); on S,
//                  |u_i| = |F_i.D| / (2^k_i |d|) < beta_i / (2^k_i |d|), and 4^k_i d^2 >= 2 beta_i^2
//                  gives u_i^2 < 1/2. Its area is 2^(k_1 + k_2) |d| |Delta| (up to pi).
// A needle's separating directions lie within about 1/|A| of the plane orthogonal to its axis:
// thin in the disc frame, fat in the frame of the needle's slab bound.
class DirectionProblem {
 public:
  // `fitted`: also consider the parallelogram frames.
  DirectionProblem(const IntegerPair& z, bool fitted) : z_(z) {
    const Vec3<CGAL::Gmpz>& delta = z.delta;
    const auto q = [](const CGAL::Gmpz& x) { return Rational(x); };
    const auto log2 = [](const CGAL::Gmpz& x2) { return 0.5 * static_cast<double>(mpz_sizeinbase(x2.mpz(), 2)); };  // of sqrt(x2)
    // The disc frame.
    scale_ = dot(delta, delta);
    base_ = delta;
    E_[0] = cross_with_least_axis(delta);
    E_[1] = cross(delta, E_[0]);
    F_ = E_;
    d_ = {dot(E_[0], E_[0]), dot(E_[1], E_[1])};
    const Rational mu0 = std::min(q(z.d.AA0) / 4, q(z.d.c0.radius) * q(z.d.c0.radius));
    const Rational mu1 = std::min(q(z.d.AA1) / 4, q(z.d.c1.radius) * q(z.d.c1.radius));
    const Rational mu = std::max(mu0, mu1);  // mu^2
    // D - D0 = 2^k_1 u1 E1 + 2^k_2 u2 E2 (E1, E2 orthogonal) with 4^k_i E_i.E_i >= 1 / mu^2, so
    // |D - D0|^2 >= |u|^2 / mu^2.
    k_ = {two_power_covering(q(d_[0]), 1 / mu), two_power_covering(q(d_[1]), 1 / mu)};
    if (!fitted) return;
    double best = static_cast<double>(k_[0] + k_[1]) + log2(d_[0]) + log2(d_[1]) - 128;  // log2 of the area to beat
    // The bounds on S: |F.D| < beta, beta^2 = num / den.
    struct Bound {
      Vec3<CGAL::Gmpz> F;
      CGAL::Gmpz num, den;
    };
    std::vector<Bound> bounds;
    const auto tube = [&](int i, const Vec3<CGAL::Gmpz>& F) {
      if (F.x == 0 && F.y == 0 && F.z == 0) return;
      const CGAL::Gmpz& r = i == 0 ? z.d.c0.radius : z.d.c1.radius;
      bounds.push_back({F, dot(F, F), r * r});
    };
    const Vec3<CGAL::Gmpz> N = cross(z.d.A0, z.d.A1);
    for (int i = 0; i < 2; ++i) {
      const Vec3<CGAL::Gmpz>& A = i == 0 ? z.d.A0 : z.d.A1;
      bounds.push_back({A, CGAL::Gmpz(4), CGAL::Gmpz(1)});
      tube(i, N);
      tube(i, cross(N, A));
      tube(i, cross(delta, A));
    }
    const double delta_size = log2(scale_);
    for (std::size_t i1 = 0; i1 < bounds.size(); ++i1)
      for (std::size_t i2 = i1 + 1; i2 < bounds.size(); ++i2) {
        const Bound& b1 = bounds[i1];
        const Bound& b2 = bounds[i2];
        const std::array<Vec3<CGAL::Gmpz>, 2> E{cross(delta, b2.F), cross(b1.F, delta)};
        const CGAL::Gmpz d = dot(b1.F, E[0]);
        if (d == 0) continue;
        const CGAL::Gmpz d2 = d * d;  // 4^k d^2 den >= 2 num
        const std::array<long, 2> ks{two_power_covering(d2 * b1.den, 2 * b1.num), two_power_covering(d2 * b2.den, 2 * b2.num)};
        const double area = static_cast<double>(ks[0] + ks[1]) + log2(d2) + delta_size;
        if (!(area < best)) continue;
        best = area;
        // Dc = (F_1 x F_2) / s with s = -d: base (F_1 x F_2) sign(s), scale |s|.
        const Vec3<CGAL::Gmpz> c = cross(b1.F, b2.F);
        base_ = d > 0 ? Vec3<CGAL::Gmpz>(-c) : c;
        scale_ = CGAL::abs(d);
        E_ = E;
        F_ = {b1.F, b2.F};
        d_ = {d, d};
        k_ = ks;
        fitted_ = true;
      }
  }

  // The coordinates u of the direction D / (D.Delta) (nullopt when D.Delta = 0):
  // u_i = F_i.(D / D.Delta - Dc) / (2^k_i d_i).
  std::optional<std::array<Rational, 2>> coordinates(const Vec3<Rational>& D) const {
    const auto q = [](const Vec3<CGAL::Gmpz>& v) { return v.map([](const CGAL::Gmpz& x) { return Rational(x); }); };
    const Rational dd = dot(D, q(z_.delta));
    if (dd == 0) return std::nullopt;
    const Vec3<Rational> v = D / dd - q(base_) / Rational(scale_);
    std::array<Rational, 2> u;
    for (int i = 0; i < 2; ++i) u[i] = dot(v, q(F_[i])) / Rational(d_[i]) * times_two_power(Rational(1), -k_[i]);
    return u;
  }

  // Whether a parallelogram frame was taken (else the disc frame).
  bool fitted() const { return fitted_; }

  // 2^sigma s D(y) (a positive multiple of D(y), integer), s = scale_ (Dc = base_ / s).
  Vec3<CGAL::Gmpz> direction(const DyadicVector<2>& y, long& sigma) const {
    const std::array<Vec3<CGAL::Gmpz>, 2> basis{scale_ * E_[0], scale_ * E_[1]};
    return dyadic_combination<2>(base_, k_, y, basis, sigma);
  }

  // The cut l(D) = V.D < 1 for w_i rounded from `bits`-bit values, at the direction Ds =
  // 2^sigma s D_y (s = scale_). With eta_exponent > 0, *cuts_off tells whether l(D_y) > 1 - 2^-eta_exponent
  // (exactly). The overshoot l(D_y) - 1 is approximate (fast runs).
  EllipsoidCut<2> minorant_cut(const Vec3<CGAL::Gmpz>& Ds, long sigma, long bits, long eta_exponent = 0, bool* cuts_off = nullptr) const {
    long h = 0;
    const Vec3<CGAL::Gmpz> Vz = minorant(Ds, bits, h);
    // l(D_y) = V.D_y = Vz.Ds 2^-(h + sigma) / G.
    const CGAL::Gmpz lD = dot(Vz, Ds), unit = shifted(scale_, h + sigma);
    if (cuts_off) {
      // l(D_y) > 1 - 2^-eta  <=>  2^eta lD > (2^eta - 1) unit
      *cuts_off = shifted(lD, eta_exponent) > shifted(unit, eta_exponent) - unit;
    }
    EllipsoidCut<2> k;
    // l(D(u)) = V.Dc + sum_i 2^k_i u_i V.E_i: c_i = (Vz.E_i) 2^(k_i - h).
    const long kmin = std::min(k_[0], k_[1]);
    k.C = {shifted(dot(Vz, E_[0]), k_[0] - kmin), shifted(dot(Vz, E_[1]), k_[1] - kmin)};
    k.e = kmin - h;
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
        for (const F& f : wf) top = std::max(top, gmpfr_exponent(f));
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
  Vec3<CGAL::Gmpz> base_;
  CGAL::Gmpz scale_;                        // Dc = base_ / scale_, scale_ > 0
  std::array<Vec3<CGAL::Gmpz>, 2> E_, F_;  // D - Dc = sum_i 2^k_i u_i E_i, F_i.E_j = d_i delta_ij
  std::array<CGAL::Gmpz, 2> d_;
  std::array<long, 2> k_{};
  bool fitted_ = false;
};

}  // namespace certcyl::detail
