// certcyl/seeds/detail/eberly_other_directions.hpp -- SeparatedByOtherDirections (seed
// sections 7 and 8), which the seed leaves empty.
//
// The hemisphere of directions D with D.Delta >= 0 is split into four octant triangles. With
// W = Delta/|Delta| and {U, V, W} right-handed orthonormal, triangle (su, sv) in {+1,-1}^2 is
//   D(s,t) = s (su U) + t (sv V) + (1-s-t) W,   s >= 0, t >= 0, s + t <= 1,
// and G(s,t) = f(D(s,t)) (equation (11)) with a_i = su U.W_i, b_i = sv V.W_i, c_i = W.W_i.
// On the hemisphere -|D.Delta| = -(1-s-t)|Delta| is linear, so G is convex on each triangle
// (a sum of norms of affine maps minus a linear function); it is not smooth on the lines
// L_i = D.W_i = 0 and at the points Q_i = |P_i D|^2 = 0 (D parallel to W_i).
//
// The minimiser (choices the seed leaves open, each a parameter or stated here):
// - start at the centroid (1/3, 1/3) of each triangle; G is tested there;
// - line direction: the negative gradient of G (seed GDer), projected onto the triangle's
//   tangent cone at the current point (components leaving an active edge removed);
// - line search on [0, r_max] (r_max where the line leaves the triangle), exactly as section 8
//   describes: test gamma(r_max); stop when gamma'(0) >= 0; take r_max when gamma'(r_max) <= 0;
//   otherwise bisect on the sign of gamma' (line_search_bisections steps), testing G at every
//   midpoint. The new point is the last midpoint (already tested), or r_max with the binding
//   coordinate set exactly to the edge;
// - stopping rule: max_line_searches, no progress (gamma'(0) >= 0), a vanishing projected
//   direction, or G_prev - G_new <= min_relative_decrease |G_new|.
// Variant differences:
// - as written, gamma' is d . GDer with the seed's Sign(0) = 0 and is undefined where
//   Q_i = 0 (GDer divides by sqrt(Q_i)); corrected, gamma' is the exact one-sided derivative
//   (right or left as the bisection needs), so the bisection is right at the kinks too, and a
//   midpoint whose right derivative is >= 0 and left derivative <= 0 is the minimum;
// - as written, a line search ending on an edge restricts the triangle to a search of that
//   edge, as section 8 says ("you need only search that boundary"). That advice is wrong: a
//   line of a convex function can reach its minimum on the boundary while the global minimum
//   is interior. The corrected variant keeps descending (projected direction);
// - corrected, Q_i is clamped at 0 (rounding can make |D|^2 - (D.W_i)^2 negative), and the
//   direction uses the least-norm subgradient (the term of a vanishing Q_i or L_i dropped).
#pragma once

#include <array>

#include "certcyl/number_traits.hpp"
#include "certcyl/seeds/detail/eberly_common.hpp"
#include "certcyl/vec3.hpp"

namespace certcyl::detail {

// The constants of G for one octant triangle (the seed's argument list of G and GDer).
template <class NT>
struct OctantFrame {
  NT r0, h0Div2, r1, h1Div2, a0, b0, c0, a1, b1, c1, lenDelta;
  Vec3<NT> U, V, W;  // su U, sv V, W
};

template <class NT>
struct GParts {
  NT omsmt, L0, L1, Q0, Q1;
};

template <class NT>
GParts<NT> g_parts(const NT& s, const NT& t, const OctantFrame<NT>& g, bool clamp) {
  const NT omsmt = nt::constant<NT>(1) - s - t;
  const NT temp = s * s + t * t + omsmt * omsmt;
  const NT L0 = g.a0 * s + g.b0 * t + g.c0 * omsmt;
  const NT L1 = g.a1 * s + g.b1 * t + g.c1 * omsmt;
  NT Q0 = temp - L0 * L0, Q1 = temp - L1 * L1;
  if (clamp) {
    if (!is_nan(Q0) && nt::is_negative(Q0)) Q0 = nt::constant<NT>(0);
    if (!is_nan(Q1) && nt::is_negative(Q1)) Q1 = nt::constant<NT>(0);
  }
  return {omsmt, L0, L1, Q0, Q1};
}

template <class NT>
NT eberly_G(const NT& s, const NT& t, const OctantFrame<NT>& g, bool clamp, EberlyCounters& k) {
  ++k.G;
  const GParts<NT> p = g_parts(s, t, g, clamp);
  return g.r0 * nt::sqrt(p.Q0) + g.r1 * nt::sqrt(p.Q1) + g.h0Div2 * nt::abs(p.L0) + g.h1Div2 * nt::abs(p.L1) -
         p.omsmt * g.lenDelta;
}

template <class NT>
NT sign_as_number(CGAL::Sign s) {
  return nt::constant<NT>(static_cast<long>(s));
}

// GDer of the seed. `least_norm`: where Q_i = 0 the term r_i sqrt(Q_i) contributes 0 (the
// least-norm element of its subdifferential) instead of dividing by zero; without it the
// gradient is undefined there.
template <class NT>
std::optional<std::array<NT, 2>> eberly_GDer(const NT& s, const NT& t, const OctantFrame<NT>& g, bool corrected,
                                             EberlyCounters& k) {
  ++k.G_gradient;
  const GParts<NT> p = g_parts(s, t, g, corrected);
  const NT diffS = s - p.omsmt, diffT = t - p.omsmt;
  const NT diffa0c0 = g.a0 - g.c0, diffa1c1 = g.a1 - g.c1, diffb0c0 = g.b0 - g.c0, diffb1c1 = g.b1 - g.c1;
  const NT halfQ0s = diffS - diffa0c0 * p.L0, halfQ1s = diffS - diffa1c1 * p.L1;
  const NT halfQ0t = diffT - diffb0c0 * p.L0, halfQ1t = diffT - diffb1c1 * p.L1;
  const NT root0 = nt::sqrt(p.Q0), root1 = nt::sqrt(p.Q1);
  if (is_nan(root0) || is_nan(root1)) return std::nullopt;
  const NT zero = nt::constant<NT>(0);
  NT factor0 = zero, factor1 = zero;
  if (nt::is_zero(root0)) {
    if (!corrected) return std::nullopt;
  } else {
    factor0 = g.r0 / root0;
  }
  if (nt::is_zero(root1)) {
    if (!corrected) return std::nullopt;
  } else {
    factor1 = g.r1 / root1;
  }
  const NT signL0 = sign_as_number<NT>(nt::sign(p.L0)), signL1 = sign_as_number<NT>(nt::sign(p.L1));
  std::array<NT, 2> gradient{halfQ0s * factor0 + halfQ1s * factor1 + g.h0Div2 * diffa0c0 * signL0 +
                                 g.h1Div2 * diffa1c1 * signL1 + g.lenDelta,
                             halfQ0t * factor0 + halfQ1t * factor1 + g.h0Div2 * diffb0c0 * signL0 +
                                 g.h1Div2 * diffb1c1 * signL1 + g.lenDelta};
  return gradient;
}

// The exact one-sided derivative of gamma(r) = G((s,t) + r d) at r = 0: from the right when
// side = +1, from the left when side = -1 (the derivative of gamma at 0 from the left, i.e.
// minus the right derivative along -d).
template <class NT>
NT one_sided_derivative(const NT& s, const NT& t, const NT& d0, const NT& d1, int side, const OctantFrame<NT>& g,
                        EberlyCounters& k) {
  ++k.G_gradient;
  const GParts<NT> p = g_parts(s, t, g, true);
  const NT sd = nt::constant<NT>(side);
  const NT dw = -(d0 + d1);                     // derivative of 1-s-t
  const NT dD2 = d0 * d0 + d1 * d1 + dw * dw;  // |dD|^2
  const NT dL0 = g.a0 * d0 + g.b0 * d1 + g.c0 * dw;
  const NT dL1 = g.a1 * d0 + g.b1 * d1 + g.c1 * dw;
  auto root_term = [&](const NT& r, const NT& Q, const NT& L, const NT& dL) -> NT {
    // r sqrt(|D|^2 - L^2): half its derivative is D.dD - L dL.
    if (nt::is_zero(Q)) {
      NT pd2 = dD2 - dL * dL;  // |P_i dD|^2
      if (nt::is_negative(pd2)) pd2 = nt::constant<NT>(0);
      return sd * r * nt::sqrt(pd2);
    }
    const NT half = s * d0 + t * d1 + p.omsmt * dw - L * dL;
    return r * half / nt::sqrt(Q);
  };
  auto abs_term = [&](const NT& hDiv2, const NT& L, const NT& dL) -> NT {
    const CGAL::Sign sl = nt::sign(L);
    if (sl == CGAL::ZERO) return sd * hDiv2 * nt::abs(dL);
    return sl == CGAL::POSITIVE ? NT(hDiv2 * dL) : NT(-(hDiv2 * dL));
  };
  return root_term(g.r0, p.Q0, p.L0, dL0) + root_term(g.r1, p.Q1, p.L1, dL1) + abs_term(g.h0Div2, p.L0, dL0) +
         abs_term(g.h1Div2, p.L1, dL1) - dw * g.lenDelta;
}

enum class Edge { none, s_zero, t_zero, hypotenuse };

template <class NT>
class OctantMinimiser {
  using P = EberlyParam<NT>;  // s, t, the line direction and r (see eberly_common.hpp)

 public:
  OctantMinimiser(EberlyRun<NT>& run, const OctantFrame<NT>& g) : run_(run), g_(g) {}

  // Returns true when a separating direction was found.
  bool minimise() {
    const P third = nt::constant<P>(1) / nt::constant<P>(3);
    s_ = third;
    t_ = third;
    G_ = G(s_, t_);
    if (judge(G_, s_, t_)) return true;
    for (int n = 0; n < run_.params.max_line_searches; ++n) {
      // The line direction: projected negative gradient.
      const auto grad = eberly_GDer(nt_(s_), nt_(t_), g_, run_.corrected(), k());
      if (!grad || is_nan((*grad)[0]) || is_nan((*grad)[1])) return false;  // as written: undefined gradient
      P d0 = nt_to_param(NT(-(*grad)[0])), d1 = nt_to_param(NT(-(*grad)[1]));
      project(d0, d1);
      if (nt::is_zero(d0) && nt::is_zero(d1)) return false;
      const NT G_prev = G_;
      Edge hit = Edge::none;
      const int outcome = line_search(s_, t_, d0, d1, hit);
      if (outcome > 0) return true;
      if (outcome < 0) return false;  // no progress along the line
      if (hit != Edge::none && !run_.corrected()) return search_edge(hit);
      const NT decrease = G_prev - G_;
      if (!greater_zero(NT(decrease - min_decrease_ * nt::abs(G_)))) return false;
    }
    return false;
  }

 private:
  bool clamp() const { return run_.corrected(); }
  EberlyCounters& k() { return run_.result.counters; }
  static NT nt_(const P& x) { return param_to_nt<NT>(x); }
  NT G(const P& s, const P& t) { return eberly_G(nt_(s), nt_(t), g_, clamp(), k()); }

  bool judge(const NT& value, const P& s, const P& t) {
    const OctantFrame<NT>& g = g_;
    return run_.judge(value, run_.params.other_direction_tests, EberlyTest::other_directions, [&g, s, t] {
      const NT sn = nt_(s), tn = nt_(t);
      return sn * g.U + tn * g.V + NT(nt::constant<NT>(1) - sn - tn) * g.W;
    });
  }

  // Removes the components of (d0, d1) that leave the triangle through an active edge.
  void project(P& d0, P& d1) const {
    const P zero = nt::constant<P>(0);
    const bool on_s = nt::is_zero(s_), on_t = nt::is_zero(t_);
    const bool on_h = nt::is_zero(P(nt::constant<P>(1) - s_ - t_));
    if (on_s && nt::is_negative(d0)) d0 = zero;
    if (on_t && nt::is_negative(d1)) d1 = zero;
    if (on_h && nt::is_positive(P(d0 + d1))) {
      const P m = (d0 + d1) / nt::constant<P>(2);
      d0 = d0 - m;
      d1 = d1 - m;
      if ((on_s && nt::is_negative(d0)) || (on_t && nt::is_negative(d1))) d0 = d1 = zero;
    }
  }

  // The sign of gamma' at (s, t) along d, as the variant computes it: side +1 from the right,
  // -1 from the left, 0 at a bisection midpoint (as written: d . GDer for all three, nullopt
  // when undefined). Corrected, at a midpoint: NEGATIVE when the right derivative is < 0 (the
  // minimum lies right), POSITIVE when the left derivative is > 0, ZERO otherwise (minimum).
  std::optional<NT> derivative_sign(const P& s, const P& t, const P& d0, const P& d1, int side) {
    const NT sn = nt_(s), tn = nt_(t), d0n = nt_(d0), d1n = nt_(d1);
    if (!run_.corrected()) {
      const auto grad = eberly_GDer(sn, tn, g_, false, k());
      if (!grad) return std::nullopt;
      const NT value = d0n * (*grad)[0] + d1n * (*grad)[1];
      const auto sg = sign_of(value);
      if (!sg) return std::nullopt;
      return sign_as_number<NT>(*sg);
    }
    if (side != 0) return sign_as_number<NT>(nt::sign(one_sided_derivative(sn, tn, d0n, d1n, side, g_, k())));
    if (nt::is_negative(one_sided_derivative(sn, tn, d0n, d1n, +1, g_, k()))) return sign_as_number<NT>(CGAL::NEGATIVE);
    if (nt::is_positive(one_sided_derivative(sn, tn, d0n, d1n, -1, g_, k()))) return sign_as_number<NT>(CGAL::POSITIVE);
    return sign_as_number<NT>(CGAL::ZERO);
  }

  // Minimises gamma(r) = G((s,t) + r d) on [0, r_max]. Returns +1 separated, -1 when
  // gamma'(0) >= 0 (no progress), 0 after moving to the line's minimum (s_, t_, G_ updated;
  // `hit` is the edge when the minimum is at r_max).
  int line_search(const P& s, const P& t, const P& d0, const P& d1, Edge& hit) {
    ++k().line_searches;
    const P zero = nt::constant<P>(0);
    const P omsmt = nt::constant<P>(1) - s - t;
    // r_max: where the line leaves the triangle, and through which edge.
    std::optional<P> rmax;
    Edge edge = Edge::none;
    auto consider = [&](const P& r, Edge e) {
      if (!rmax || nt::compare(r, *rmax) == CGAL::SMALLER) rmax = r, edge = e;
    };
    if (nt::is_negative(d0)) consider(P(-s / d0), Edge::s_zero);
    if (nt::is_negative(d1)) consider(P(-t / d1), Edge::t_zero);
    if (nt::is_positive(P(d0 + d1))) consider(P(omsmt / (d0 + d1)), Edge::hypotenuse);
    if (!rmax) return -1;  // unreachable for a nonzero d in the triangle
    auto point = [&](const P& r, P& ps, P& pt) {
      ps = s + r * d0;
      pt = t + r * d1;
    };
    P se, te;
    point(*rmax, se, te);
    // The end lies on the edge exactly.
    if (edge == Edge::s_zero) se = zero;
    if (edge == Edge::t_zero) te = zero;
    if (edge == Edge::hypotenuse) te = nt::constant<P>(1) - se;
    const NT Gend = G(se, te);
    if (judge(Gend, se, te)) return 1;
    if (greater_equal_zero(derivative_sign(s, t, d0, d1, +1))) return -1;
    if (less_equal_zero(derivative_sign(se, te, d0, d1, -1))) {
      s_ = se, t_ = te, G_ = Gend, hit = edge;
      return 0;
    }
    P r0 = zero, r1 = *rmax;
    const P two = nt::constant<P>(2);
    bool moved = false;
    for (int i = 0; i < run_.params.line_search_bisections; ++i) {
      const P rmid = (r0 + r1) / two;
      P sm, tm;
      point(rmid, sm, tm);
      const NT Gmid = G(sm, tm);
      if (judge(Gmid, sm, tm)) return 1;
      s_ = sm, t_ = tm, G_ = Gmid, moved = true;
      const auto dm = derivative_sign(sm, tm, d0, d1, 0);
      if (greater_zero(dm)) {
        r1 = rmid;
      } else if (less_zero(dm)) {
        r0 = rmid;
      } else {
        break;
      }
    }
    return moved ? 0 : -1;
  }

  // As written: one line search along the whole edge the last line search ended on.
  bool search_edge(Edge e) {
    const P zero = nt::constant<P>(0), one = nt::constant<P>(1);
    P s = zero, t = zero, d0 = zero, d1 = zero;
    switch (e) {
      case Edge::s_zero: d1 = one; break;                          // (0,0) -> (0,1)
      case Edge::t_zero: d0 = one; break;                          // (0,0) -> (1,0)
      case Edge::hypotenuse: s = one, d0 = -one, d1 = one; break;  // (1,0) -> (0,1)
      case Edge::none: return false;
    }
    if (judge(G(s, t), s, t)) return true;
    Edge hit = Edge::none;
    return line_search(s, t, d0, d1, hit) > 0;
  }

  EberlyRun<NT>& run_;
  const OctantFrame<NT>& g_;
  P s_, t_;
  NT G_;
  NT min_decrease_ = nt::from_rational<NT>(Rational(run_.params.min_relative_decrease));
};

// Gram-Schmidt-free orthonormal complement of a unit W (Geometric Tools'
// ComputeOrthogonalComplement). The branch only picks the better-conditioned of two valid
// frames, so it is taken on binary64 approximations and never throws for intervals.
template <class NT>
void orthonormal_complement(const Vec3<NT>& W, Vec3<NT>& U, Vec3<NT>& V) {
  const NT zero = nt::constant<NT>(0);
  if (std::abs(nt::to_double(W.x)) > std::abs(nt::to_double(W.y))) {
    const NT inv = nt::constant<NT>(1) / nt::sqrt(NT(W.x * W.x + W.z * W.z));
    U = {-W.z * inv, zero, W.x * inv};
  } else {
    const NT inv = nt::constant<NT>(1) / nt::sqrt(NT(W.y * W.y + W.z * W.z));
    U = {zero, W.z * inv, -W.y * inv};
  }
  V = cross(W, U);
}

// SeparatedByOtherDirections(W0,r0,h0,W1,r1,h1,Delta). Delta = 0 makes W undefined; it is
// answered before this call (corrected) or here (as written: no separating direction).
template <class NT>
bool separated_by_other_directions(EberlyRun<NT>& run, const Vec3<NT>& W0, const NT& r0, const NT& h0,
                                   const Vec3<NT>& W1, const NT& r1, const NT& h1, const Vec3<NT>& Delta) {
  const NT lenDelta = nt::sqrt(squared_length(Delta));
  if (is_nan(lenDelta) || nt::is_zero(lenDelta)) return false;
  const Vec3<NT> W = Delta / lenDelta;
  Vec3<NT> U, V;
  orthonormal_complement(W, U, V);
  const NT two = nt::constant<NT>(2);
  OctantFrame<NT> base{r0, h0 / two, r1, h1 / two, dot(U, W0), dot(V, W0), dot(W, W0), dot(U, W1), dot(V, W1), dot(W, W1), lenDelta, U, V, W};
  for (int su : {+1, -1}) {
    for (int sv : {+1, -1}) {
      OctantFrame<NT> g = base;
      if (su < 0) g.a0 = -g.a0, g.a1 = -g.a1, g.U = -g.U;
      if (sv < 0) g.b0 = -g.b0, g.b1 = -g.b1, g.V = -g.V;
      OctantMinimiser<NT> minimiser(run, g);
      if (minimiser.minimise()) return true;
    }
  }
  return false;
}

}  // namespace certcyl::detail
