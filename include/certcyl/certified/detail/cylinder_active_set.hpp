// certcyl/certified/detail/cylinder_active_set.hpp -- the minimiser of sigma(X) to the working
// precision of NT (double-double in the solver's refine stage), by Newton's method on its
// optimality conditions from a nearby point X0.
//
// Problem (notation of cylinder_certificates.hpp): phi* = min over X of sigma(X), the largest of
// the four gauges of X about the midpoints m_i,
//   axial_i(X)  = s_i 2 (X - m_i).A_i / A_i.A_i   (s_i = +-1: the cap on X's side),
//   radial_i(X) = |(X - m_i) x A_i| / (r_i |A_i|).
// Near the minimiser, the gauges that attain the maximum (the active set S: the caps, walls or
// rims that meet at the contact) are smooth, and the minimiser of the proximal problem
//   sigma(X) + (rho / 2) |X - X0|^2,   rho = 1 / L^2 (L the largest radius or axis length),
// solves the smooth system in (X, phi, lambda)
//   rho (X - X0) + sum_{k in S} lambda_k grad p_k(X) = 0,   sum_k lambda_k = 1,
//   p_k(X) = phi  (k in S),
// whose Jacobian is nonsingular when the augmented gradients (grad p_k, -1) are independent. The
// proximal term makes it so where the minimisers form a segment or a disc (parallel walls, a
// cap on a wall, a cap on a cap), and costs at most (rho / 2) |X* - X0|^2 in value (X* the
// minimiser nearest X0): about 2^-104 when X0 is a double optimum, below what the stage needs.
// Newton's method converges quadratically from there; S is read off the gauges at X0 and
// corrected (a piece with a negative multiplier leaves S, a piece above phi at the end joins).
//
// Outputs: X, sigma(X) computed in NT, and the direction D = sum over the pieces of cylinder 0
// in S of lambda_k grad p_k(X): the normal of the plane that supports both cylinders scaled by
// sigma(X) at X (it separates the cylinders when phi* > 1; it is the contact normal when they
// touch). Nothing here is a certificate: the caller checks X and D exactly.
#pragma once

#include <Eigen/Dense>

#include <array>
#include <cmath>
#include <optional>
#include <type_traits>

#include "certcyl/certified/detail/cylinder_certificates.hpp"
#include "certcyl/number_traits.hpp"
#include "certcyl/vec3.hpp"

namespace certcyl::detail {

template <class NT>
struct ActiveSetOptimum {
  Point3<NT> point;   // X, the minimiser of the proximal problem
  NT value;           // sigma(X)
  Vec3<NT> direction; // D (zero when no piece of cylinder 0 is active)
  unsigned pieces = 0;  // S as bits: 1 axial_0, 2 radial_0, 4 axial_1, 8 radial_1
  int iterations = 0;   // Newton steps taken, over all active sets tried
};

template <class NT>
class ActiveSetProblem {
 public:
  // b: Newton's method has converged when its relative step is below epsilon = 2^-b (96 for
  // dd_real, 48 for double, a little under the precision for Gmpfr). The other thresholds scale
  // with b: rho = 2^(-5b/6) / L^2 (2^-80 for dd_real: the system's conditioning, 2^(5b/6),
  // stays well inside the precision), the multiplier and joining tolerances 2^(-5b/6), a stalled
  // phi step 2^(-2b/3).
  //
  // stop_when_decided: Newton's method also ends as soon as its point X has sigma(X) < 1 - 2^(-5b/6)
  // or its direction D (the multipliers' combination) separates with ratio |D.T| / phi2(D) above
  // 1 + 2^(-5b/6), both evaluated in NT: the caller's exact check then decides, without the steps
  // that would only sharpen phi beyond what the decision needs. The answer to "is phi* below or
  // above 1" is all the refine stage asks; near touching, the full convergence runs as before.
  ActiveSetProblem(const CylinderPair<NT>& d, int b, bool stop_when_decided = false) : d_(d), stop_when_decided_(stop_when_decided) {
    const auto two_power = [](long e) {
      Rational r(1);
      mpq_div_2exp(r.mpq(), r.mpq(), static_cast<mp_bitcnt_t>(-e));
      return nt::from_rational<NT>(r);
    };
    epsilon_ = two_power(-b);
    fine_ = two_power(-(5 * b) / 6);
    stall_ = two_power(-(2 * b) / 3);
    const NT two = nt::constant<NT>(2);
    m_[0] = (d.c0.p0 + d.c0.p1) / two;
    m_[1] = (d.c1.p0 + d.c1.p1) / two;
    A_[0] = &d.A0;
    A_[1] = &d.A1;
    AA_[0] = d.AA0;
    AA_[1] = d.AA1;
    const NT* r[2] = {&d.c0.radius, &d.c1.radius};
    NT L2 = nt::max(d.AA0, d.AA1);
    for (int i = 0; i < 2; ++i) {
      c_[i] = nt::constant<NT>(1) / (*r[i] * nt::sqrt(AA_[i]));
      L2 = nt::max(L2, NT(two * two * *r[i] * *r[i]));
    }
    rho_ = fine_ / L2;
  }

  std::optional<ActiveSetOptimum<NT>> solve(const Point3<NT>& X0, unsigned first = 0, int max_steps = 24) {
    // The caps on X0's side, and the starting active set: the pieces within 2^-6 of the largest
    // (a piece that is not active gets a negative multiplier and leaves). When Newton's method
    // fails from there, it starts again from the pieces within 2^-2, then from all four.
    // first: instead, a single attempt from the active set `first`, no correction of its set.
    // max_steps: Newton steps per attempt.
    for (int i = 0; i < 2; ++i) side_[i] = sign_is(dot(X0 - m_[i], *A_[i]), CGAL::NEGATIVE) ? -1 : 1;
    std::array<NT, 4> p = values(X0);
    const NT top = nt::max(nt::max(p[0], p[1]), nt::max(p[2], p[3]));
    const auto within = [&](long divisor) {
      const NT near = top - top / nt::constant<NT>(divisor);
      unsigned S = 0;
      for (unsigned k = 0; k < 4; ++k)
        if (nt::compare(p[k], near) != CGAL::SMALLER) S |= 1u << k;
      return S;
    };
    int iterations = 0;
    if (first) return from(X0, top, first, iterations, max_steps, 1);
    const std::array<unsigned, 3> starts = {within(64), within(4), 15u};
    for (std::size_t start = 0; start < starts.size(); ++start) {
      if (start > 0 && starts[start] == starts[start - 1]) continue;
      std::optional<ActiveSetOptimum<NT>> o = from(X0, top, starts[start], iterations, max_steps);
      if (o) return o;
    }
    return std::nullopt;
  }

 private:
  // Newton's method from S, then corrections of S: a piece with a multiplier below -fine leaves,
  // a piece above phi by more than fine phi joins; an active set already tried ends the
  // corrections (each attempt starts from X0, so it would repeat itself). At most `attempts`
  // attempts. The point with the least sigma over the attempts is returned (the checks are
  // exact: any point is a fair candidate), or the point of an attempt that stop_when_decided
  // ended.
  std::optional<ActiveSetOptimum<NT>> from(const Point3<NT>& X0, const NT& top, unsigned S, int& iterations, int max_steps,
                                           int attempts = 4) {
    std::optional<ActiveSetOptimum<NT>> best;
    const NT& tol = fine_;
    unsigned tried = 0;  // bit S: active set S tried
    for (int attempt = 0; attempt < attempts; ++attempt) {
      if (tried >> S & 1u) break;
      tried |= 1u << S;
      std::optional<Newton> n = newton(X0, top, S, max_steps);
      const bool early = n && n->decided;
      if (!n) break;
      S = n->S;
      tried |= 1u << S;
      iterations += n->iterations;
      const std::array<NT, 4> p = values(n->X);
      ActiveSetOptimum<NT> o;
      o.point = n->X;
      o.value = nt::max(nt::max(p[0], p[1]), nt::max(p[2], p[3]));
      o.direction = Vec3<NT>{nt::constant<NT>(0), nt::constant<NT>(0), nt::constant<NT>(0)};
      for (unsigned k = 0; k < 2; ++k)
        if (S >> k & 1u) o.direction = o.direction + n->lambda[k] * gradient(k, n->X);
      o.pieces = S;
      if (!best || nt::compare(o.value, best->value) == CGAL::SMALLER || early) best = o;
      if (early) break;
      int worst = -1;
      for (unsigned k = 0; k < 4; ++k)
        if ((S >> k & 1u) && nt::compare(n->lambda[k], NT(-tol)) == CGAL::SMALLER && (worst < 0 || n->lambda[k] < n->lambda[worst]))
          worst = static_cast<int>(k);
      if (worst >= 0) {
        S &= ~(1u << worst);
        continue;
      }
      unsigned joined = 0;
      for (unsigned k = 0; k < 4; ++k)
        if (!(S >> k & 1u) && nt::compare(p[k], NT(n->phi + tol * n->phi)) == CGAL::LARGER) joined |= 1u << k;
      if (!joined) break;
      S |= joined;
    }
    if (best) best->iterations = iterations;
    return best;
  }

  struct Newton {
    Point3<NT> X;
    NT phi;
    std::array<NT, 4> lambda;
    int iterations;
    unsigned S;             // the active set it ended with
    bool decided = false;   // ended by stop_when_decided
  };

  static int cylinder(unsigned k) { return static_cast<int>(k / 2); }
  static bool axial(unsigned k) { return k % 2 == 0; }

  std::array<NT, 4> values(const Point3<NT>& X) const {
    std::array<NT, 4> p;
    for (unsigned k = 0; k < 4; ++k) p[k] = value(k, X);
    return p;
  }

  NT value(unsigned k, const Point3<NT>& X) const {
    const int i = cylinder(k);
    const Vec3<NT> v = X - m_[i];
    if (axial(k)) return abs_enclosure(nt::constant<NT>(2) * dot(v, *A_[i]) / AA_[i]);
    const Vec3<NT> w = cross(v, *A_[i]);
    return c_[i] * nt::sqrt(dot(w, w));
  }

  // grad p_k: 2 s A / A.A (axial), c A x w / |w| with w = (X - m) x A (radial).
  Vec3<NT> gradient(unsigned k, const Point3<NT>& X) const {
    const int i = cylinder(k);
    const Vec3<NT>& A = *A_[i];
    if (axial(k)) return (nt::constant<NT>(2 * side_[i]) / AA_[i]) * A;
    const Vec3<NT> w = cross(X - m_[i], A);
    return (c_[i] / nt::sqrt(dot(w, w))) * cross(A, w);
  }

  // Whether X is clearly inside both (sigma(X) < 1 - fine) or the direction of the multipliers
  // clearly separates (|D.T| > (1 + fine) phi2(D), phi2(D) = |D.A0| + |D.A1| + 2 r0 |D x A0| / |A0|
  // + 2 r1 |D x A1| / |A1|), in NT: a guess for stop_when_decided, checked exactly by the caller.
  bool decided(const Newton& s) const {
    const std::array<NT, 4> p = values(s.X);
    const NT top = nt::max(nt::max(p[0], p[1]), nt::max(p[2], p[3]));
    const NT one = nt::constant<NT>(1);
    if (nt::compare(top, NT(one - fine_)) == CGAL::SMALLER) return true;
    if (nt::compare(top, NT(one + fine_)) != CGAL::LARGER) return false;
    Vec3<NT> D{nt::constant<NT>(0), nt::constant<NT>(0), nt::constant<NT>(0)};
    for (unsigned k = 0; k < 2; ++k)
      if (s.S >> k & 1u) D = D + s.lambda[k] * gradient(k, s.X);
    // separation_terms (cylinder_certificates.hpp): c = |D.T| - |D.A0| - |D.A1|, and the radial
    // terms of phi2 are sqrt(p) and sqrt(q).
    const SeparationTerms<NT> t = separation_terms(d_, D);
    const NT DT = abs_enclosure(dot(D, d_.T));
    const NT phi2 = DT - t.c + nt::sqrt(t.p) + nt::sqrt(t.q);
    return nt::compare(DT, NT((one + fine_) * phi2)) == CGAL::LARGER;
  }

  // J step = -F by Eigen's partial-pivoting LU on a matrix of the fixed size n (5 to 8): the
  // dynamic-size LU's loops cost about as much as the arithmetic at this size.
  template <class Matrix, class Vector>
  static Vector solve_fixed(const Matrix& J, const Vector& F, int n) {
    Vector step(n);
    const auto fixed = [&](auto size) {
      constexpr int N = decltype(size)::value;
      using M = Eigen::Matrix<NT, N, N>;
      using V = Eigen::Matrix<NT, N, 1>;
      const Eigen::PartialPivLU<M> lu(M(J.template topLeftCorner<N, N>()));
      step = lu.solve(V(-F.template head<N>()));
    };
    switch (n) {
      case 5: fixed(std::integral_constant<int, 5>{}); break;
      case 6: fixed(std::integral_constant<int, 6>{}); break;
      case 7: fixed(std::integral_constant<int, 7>{}); break;
      default: fixed(std::integral_constant<int, 8>{}); break;
    }
    return step;
  }

  // Newton's method on the system of S from X0, at most max_steps steps; a piece that rises above
  // phi on the way joins S (with multiplier 0), and a step longer than a quarter of the size is
  // shortened to it.
  std::optional<Newton> newton(const Point3<NT>& X0, const NT& phi0, unsigned S, int max_steps) const {
    using Matrix = Eigen::Matrix<NT, Eigen::Dynamic, Eigen::Dynamic, 0, 8, 8>;
    using Vector = Eigen::Matrix<NT, Eigen::Dynamic, 1, 0, 8, 1>;
    const NT zero = nt::constant<NT>(0);
    Newton s{X0, phi0, {zero, zero, zero, zero}, 0, S};
    int m0 = 0;
    for (unsigned k = 0; k < 4; ++k) m0 += (S >> k) & 1u;
    if (m0 == 0) return std::nullopt;
    for (unsigned k = 0; k < 4; ++k)
      if (S >> k & 1u) s.lambda[k] = nt::constant<NT>(1) / nt::constant<NT>(m0);
    const NT size = nt::sqrt(nt::max(AA_[0], AA_[1]));
    const NT reach = size / nt::constant<NT>(4);
    NT last_phi_step = nt::constant<NT>(1);
    for (int it = 0; it < max_steps; ++it) {
      std::array<unsigned, 4> index{};
      int m = 0;
      for (unsigned k = 0; k < 4; ++k)
        if (s.S >> k & 1u) index[static_cast<std::size_t>(m++)] = k;
      const int n = 4 + m;
      Matrix J = Matrix::Zero(n, n);
      Vector F = Vector::Zero(n);
      for (int r = 0; r < 3; ++r) J(r, r) = rho_;
      F(3) = -nt::constant<NT>(1);
      for (int j = 0; j < m; ++j) {
        const unsigned k = index[static_cast<std::size_t>(j)];
        const NT& l = s.lambda[k];
        const Vec3<NT> g = gradient(k, s.X);
        for (int r = 0; r < 3; ++r) {
          const NT& gr = g[static_cast<std::size_t>(r)];
          F(r) += l * gr;
          J(r, 4 + j) = gr;
          J(4 + j, r) = gr;
        }
        F(3) += l;
        J(3, 4 + j) = nt::constant<NT>(1);
        J(4 + j, 3) = -nt::constant<NT>(1);
        F(4 + j) = value(k, s.X) - s.phi;
        if (!axial(k)) {
          // Hessian of c |w|: c (|A|^2 I - A A^T - h h^T) / |w| with h = A x w / |w|.
          const int i = cylinder(k);
          const Vec3<NT>& A = *A_[i];
          const Vec3<NT> w = cross(s.X - m_[i], A);
          const NT norm_w = nt::sqrt(dot(w, w));
          const Vec3<NT> h = cross(A, w) / norm_w;
          const NT f = l * c_[i] / norm_w;
          for (int r = 0; r < 3; ++r)
            for (int q = 0; q < 3; ++q) {
              const std::size_t ur = static_cast<std::size_t>(r), uq = static_cast<std::size_t>(q);
              NT e = -(A[ur] * A[uq]) - h[ur] * h[uq];
              if (r == q) e += AA_[i];
              J(r, q) += f * e;
            }
        }
      }
      Vector step = solve_fixed(J, F, n);
      for (int r = 0; r < n; ++r)
        if (!std::isfinite(nt::to_double(step(r)))) return std::nullopt;
      Vec3<NT> dX{step(0), step(1), step(2)};
      const NT big = nt::max(nt::max(abs_enclosure(dX.x), abs_enclosure(dX.y)), abs_enclosure(dX.z));
      if (nt::compare(big, reach) == CGAL::LARGER) {
        const NT t = reach / big;
        for (int r = 0; r < n; ++r) step(r) *= t;
        dX = Vec3<NT>{step(0), step(1), step(2)};
      }
      s.X = s.X + dX;
      s.phi += step(3);
      for (int j = 0; j < m; ++j) s.lambda[index[static_cast<std::size_t>(j)]] += step(4 + j);
      ++s.iterations;
      // Pieces above phi join.
      unsigned joined = 0;
      const NT above = s.phi + s.phi * fine_;
      for (unsigned k = 0; k < 4; ++k)
        if (!(s.S >> k & 1u) && nt::compare(value(k, s.X), above) == CGAL::LARGER) joined |= 1u << k;
      if (joined) {
        s.S |= joined;
        continue;
      }
      if (stop_when_decided_ && decided(s)) {
        s.decided = true;
        return s;
      }
      // Converged: phi to epsilon, X to 2^-20 of the size (along a segment or disc of minimisers
      // the steps are rounding noise divided by rho, and do not matter).
      if (nt::compare(abs_enclosure(step(3)), epsilon_) != CGAL::LARGER && nt::compare(big, NT(size / nt::constant<NT>(1L << 20))) != CGAL::LARGER) return s;
      // Gone far from X0 (it starts near the optimum): a wrong active set.
      const Vec3<NT> moved = s.X - X0;
      if (nt::compare(dot(moved, moved), NT(nt::constant<NT>(4) * size * size)) == CGAL::LARGER) return std::nullopt;
      // Stalled: a phi step below 2^(-2b/3) that no longer halves is the noise of an ill-conditioned
      // system; more steps do not help (see below).
      const NT phi_step = abs_enclosure(step(3));
      if (nt::compare(phi_step, stall_) != CGAL::LARGER && nt::compare(NT(phi_step + phi_step), last_phi_step) != CGAL::SMALLER) return s;
      last_phi_step = phi_step;
    }
    // Not converged to epsilon: where the pieces meet almost tangentially the system is
    // ill-conditioned, and X and phi stall at the noise of NT amplified. A phi that stalled below
    // 2^(-2b/3) is still worth checking (the checks are exact).
    if (nt::compare(last_phi_step, stall_) != CGAL::LARGER) return s;
    return std::nullopt;
  }

  const CylinderPair<NT>& d_;
  bool stop_when_decided_ = false;
  NT epsilon_;
  Point3<NT> m_[2];
  const Vec3<NT>* A_[2];
  NT AA_[2], c_[2], rho_;
  NT fine_, stall_;
  int side_[2] = {1, 1};
};

}  // namespace certcyl::detail
