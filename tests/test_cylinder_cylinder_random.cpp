// Certified cylinder-cylinder query on random pairs, checked three independent ways:
//  - every certificate is rechecked exactly by code written apart from the library's
//    (tests/test_cylinder_cylinder_cases.hpp: CORE::Expr square roots, the point test from its
//    definition);
//  - brute force in double looks for evidence of the opposite answer: a separating direction
//    (dense sampling of the sphere, then a compass search on phi(D)/|D.Delta|) or a point inside
//    both (compass search on the scale sigma(X), a convex function); at clear margins (1%) its
//    evidence is far beyond its rounding errors (about 1e-15), so it must agree;
//  - the certified enclosure of phi* must contain the brute-force bounds.
// Plus random rigid motions of the exactly touching constructions, and the double overload.
#define BOOST_TEST_MODULE certified_cylinder_cylinder_random
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include "test_cylinder_cylinder_cases.hpp"

using namespace cctest;
using certcyl::Answer;
using certcyl::certified_cylinder_cylinder;
using D3 = Vec3<double>;

namespace {

constexpr unsigned long kSeed = 20240611;

struct Pair {
  Cylinder<double> a, b;
};

Cylinder<Q> exact(const Cylinder<double>& c) {
  return c.map([](double x) { return Q(x); });
}

// phi(D) / |D.Delta| in double (the brute force's own formula).
double ratio(const Pair& p, const D3& D) {
  const D3 A0 = p.a.p1 - p.a.p0, A1 = p.b.p1 - p.b.p0;
  const D3 delta = 0.5 * ((p.b.p0 + p.b.p1) - (p.a.p0 + p.a.p1));
  const D3 c0 = cross(D, A0), c1 = cross(D, A1);
  const double phi = std::abs(dot(D, A0)) / 2 + std::abs(dot(D, A1)) / 2 + p.a.radius * std::sqrt(dot(c0, c0) / dot(A0, A0)) +
                     p.b.radius * std::sqrt(dot(c1, c1) / dot(A1, A1));
  return phi / std::abs(dot(D, delta));
}

// The scale sigma(X) about the midpoints at which X lies in both cylinders.
double sigma(const Pair& p, const D3& X) {
  auto one = [&](const Cylinder<double>& c) {
    const D3 A = c.p1 - c.p0, m = 0.5 * (c.p0 + c.p1), w = X - m;
    const D3 x = cross(w, A);
    return std::max(2 * std::abs(dot(w, A)) / dot(A, A), std::sqrt(dot(x, x) / dot(A, A)) / c.radius);
  };
  return std::max(one(p.a), one(p.b));
}

// Compass search with random directions, minimising f from x0 with initial step h.
template <class F>
std::pair<D3, double> compass(F f, D3 x, double h, std::mt19937_64& g) {
  std::normal_distribution<double> n;
  double fx = f(x);
  for (int it = 0; it < 400 && h > 1e-13; ++it) {
    bool improved = false;
    for (int k = 0; k < 12; ++k) {
      D3 d = k < 6 ? D3{double(k == 0) - double(k == 1), double(k == 2) - double(k == 3), double(k == 4) - double(k == 5)}
                   : D3{n(g), n(g), n(g)};
      d = d / std::sqrt(dot(d, d));
      const D3 y = x + h * d;
      const double fy = f(y);
      if (fy < fx) x = y, fx = fy, improved = true;
    }
    if (!improved) h /= 2;
  }
  return {x, fx};
}

// Smallest phi(D)/|D.Delta| found: a Fibonacci half-sphere of directions, then compass search
// on the unit sphere (f normalises).
double brute_min_ratio(const Pair& p, std::mt19937_64& g) {
  const int n = 3000;
  double best = INFINITY;
  D3 bestD{0, 0, 1};
  for (int i = 0; i < n; ++i) {
    const double z = 1 - (i + 0.5) / n, rxy = std::sqrt(1 - z * z), t = 2.399963229728653 * i;
    const D3 D{rxy * std::cos(t), rxy * std::sin(t), z};
    const double r = ratio(p, D);
    if (r < best) best = r, bestD = D;
  }
  auto f = [&](const D3& D) { return dot(D, D) > 0 ? ratio(p, D) : INFINITY; };
  return std::min(best, compass(f, bestD, 0.05, g).second);
}

// Nearest point of the cylinder c scaled by s about its midpoint: the solid is an interval times
// a disk in its own frame, so the projection clamps the axial and the radial part separately.
D3 project(const Cylinder<double>& c, double s, const D3& X) {
  const D3 A = c.p1 - c.p0, m = 0.5 * (c.p0 + c.p1), w = X - m;
  const double AA = dot(A, A);
  const double t = std::clamp(dot(w, A) / AA, -s / 2, s / 2);
  D3 radial = w - (dot(w, A) / AA) * A;
  const double rl = std::sqrt(dot(radial, radial));
  if (rl > s * c.radius) radial = (s * c.radius / rl) * radial;
  return m + t * A + radial;
}

// Smallest sigma(X) found: compass search from a few starts, and alternating projections onto
// both cylinders scaled by 0.995 (which converge to a common point when there is one).
double brute_min_sigma(const Pair& p, std::mt19937_64& g) {
  const D3 m0 = 0.5 * (p.a.p0 + p.a.p1), m1 = 0.5 * (p.b.p0 + p.b.p1);
  double best = INFINITY;
  for (const D3& s : {m0, m1, 0.5 * (m0 + m1)}) {
    auto f = [&](const D3& X) { return sigma(p, X); };
    best = std::min(best, compass(f, s, 0.25, g).second);
  }
  D3 X = 0.5 * (m0 + m1);
  for (int i = 0; i < 3000; ++i) X = project(p.a, 0.995, project(p.b, 0.995, X));
  return std::min(best, sigma(p, X));
}

}  // namespace

BOOST_AUTO_TEST_CASE(random_pairs_against_independent_checks) {
  BOOST_TEST_MESSAGE("seed " << kSeed);
  std::mt19937_64 g(kSeed);
  int counts[4] = {0, 0, 0, 0}, clear = 0, escalated = 0;
  const int N = 1500;
  for (int i = 0; i < N; ++i) {
    const Pair p{random_cylinder(g), random_cylinder(g)};
    const Cylinder<Q> a = exact(p.a), b = exact(p.b);
    const certcyl::CylinderCylinderResult r = certified_cylinder_cylinder(a, b);
    ++counts[static_cast<int>(r.answer)];
    if (r.stage != certcyl::CylinderStage::fast_path && r.stage != certcyl::CylinderStage::midpoints) ++escalated;
    BOOST_TEST_CONTEXT("pair " << i << " seed " << kSeed) {
      BOOST_TEST(certificate_error(a, b, r) == "");
      BOOST_TEST(to_string(r.answer) != "undecided");
      const certcyl::CylinderGap gap = r.gap();
      BOOST_TEST(gap.known);
      // The enclosure computed in the query is the one gap() computes on access; off, none.
      certcyl::CylinderCylinderOptions in_query, off;
      in_query.gap_enclosure = certcyl::GapEnclosure::in_query;
      off.gap_enclosure = certcyl::GapEnclosure::off;
      const certcyl::CylinderGap eager = certified_cylinder_cylinder(p.a, p.b, in_query).gap();
      BOOST_TEST((eager.known == gap.known && eager.phi_lower == gap.phi_lower && eager.phi_upper == gap.phi_upper));
      BOOST_TEST(!certified_cylinder_cylinder(p.a, p.b, off).gap().known);
      BOOST_TEST(to_string(certified_cylinder_cylinder(p.a, p.b).answer) == to_string(r.answer));
      BOOST_TEST(to_string(certified_cylinder_cylinder(b, a).answer) == to_string(r.answer));
      if (!gap.known) continue;
      const double rmin = brute_min_ratio(p, g), smin = brute_min_sigma(p, g);
      // No contradicting evidence (beyond rounding), ever.
      if (r.answer == Answer::separated) BOOST_TEST(smin > 1 - 1e-12);
      if (r.answer == Answer::overlapping) BOOST_TEST(rmin > 1 - 1e-12);
      // The enclosure contains what the brute force proves: phi* <= rmin and phi* >= 1/smin.
      BOOST_TEST(gap.phi_lower <= rmin * (1 + 1e-12));
      BOOST_TEST(1 / smin <= gap.phi_upper * (1 + 1e-12));
      // At clear margins the brute force finds supporting evidence.
      if (gap.phi_upper < 0.99) {
        ++clear;
        BOOST_TEST(rmin < 1 - 1e-9);
      }
      if (gap.phi_lower > 1.01) {
        ++clear;
        BOOST_TEST(smin < 1 - 1e-9);
      }
    }
  }
  BOOST_TEST_MESSAGE("separated " << counts[0] << ", touching " << counts[1] << ", overlapping " << counts[2] << ", undecided "
                                  << counts[3] << ", clear margins " << clear << ", beyond the fast path " << escalated);
  BOOST_TEST(counts[0] > N / 10);
  BOOST_TEST(counts[2] > N / 10);
  BOOST_TEST(clear > N / 2);
}

// Random rigid motions (rational rotations from random integer quaternions, rational
// translations, power-of-two scales) of the exactly touching constructions.
BOOST_AUTO_TEST_CASE(random_motions_of_touching_pairs) {
  BOOST_TEST_MESSAGE("seed " << kSeed + 1);
  std::mt19937_64 g(kSeed + 1);
  std::uniform_int_distribution<long> qd(-9, 9), num(-1000, 1000), den(1, 64), ex(-12, 12);
  const std::vector<TouchingCase> bases = base_touching_cases();
  for (int i = 0; i < 60; ++i) {
    long qa, qb, qc, qdd;
    do {
      qa = qd(g), qb = qd(g), qc = qd(g), qdd = qd(g);
    } while (qa == 0 && qb == 0 && qc == 0 && qdd == 0);
    const Rotation R = Rotation::from_quaternion(qa, qb, qc, qdd);
    const Vec3<Q> t{Q(num(g)) / Q(den(g)), Q(num(g)) / Q(den(g)), Q(num(g)) / Q(den(g))};
    const long e = ex(g);
    const Q s = e >= 0 ? Q(1L << e) : Q(1) / Q(1L << -e);
    TouchingCase c = moved(bases[i % bases.size()], R, t);
    c.a = scale(c.a, s);
    c.b = scale(c.b, s);
    BOOST_TEST_CONTEXT(c.name << " quaternion " << qa << " " << qb << " " << qc << " " << qdd << " scale 2^" << e) {
      const auto r = certified_cylinder_cylinder(c.a, c.b);
      BOOST_TEST(certificate_error(c.a, c.b, r) == "");
      BOOST_TEST(to_string(r.answer) == "touching");
      if (r.contact) BOOST_TEST(r.contact->type() == c.type);
      const Q eps = s / Q(1LL << 40);
      BOOST_TEST(to_string(certified_cylinder_cylinder(c.a, translate(c.b, eps * c.normal)).answer) == "separated");
      BOOST_TEST(to_string(certified_cylinder_cylinder(c.a, translate(c.b, -eps * c.normal)).answer) == "overlapping");
    }
  }
}

// ---- the static filter against Gmpq on the same certificate ----------------------------------
namespace {

namespace cd = certcyl::detail;
using certcyl::detail::StaticSign;

// A pair moved to the world frame the way the solver does it (|x| < 2, exact power of two).
struct World {
  Cylinder<double> a, b;
  cd::StaticPair s;
  cd::CylinderPair<Q> q;
};

// The largest magnitude of the fourteen numbers of a pair.
double largest_magnitude(const Pair& p) {
  double m = 0;
  for (const Cylinder<double>* c : {&p.a, &p.b})
    for (double x : {c->p0.x, c->p0.y, c->p0.z, c->p1.x, c->p1.y, c->p1.z, c->radius}) m = std::max(m, std::abs(x));
  return m;
}

World world(const Pair& p) {
  const double k = cd::power_of_two_normaliser(largest_magnitude(p));
  const auto sc = [k](double x) { return x * k; };
  World w{p.a.map(sc), p.b.map(sc), {}, {}};
  w.s = cd::StaticPair::make(w.a, w.b);
  w.q = cd::CylinderPair<Q>::make(exact(w.a), exact(w.b));
  return w;
}

// D scaled by a power of two to |D_i| < 2 (what the solver certifies).
D3 normalised(const D3& D) {
  const double k = cd::power_of_two_normaliser(std::max({std::abs(D.x), std::abs(D.y), std::abs(D.z)}));
  return k * D;
}

Vec3<Q> exact(const D3& v) {
  return v.map([](double x) { return Q(x); });
}

struct FilterTally {
  int decided = 0, unknown = 0, zero = 0;
};

// The filter's sign must equal the exact sign whenever it decides; its ratio bound must be an
// upper bound, exactly: U |D.T| - |D.A0| - |D.A1| - sqrt(p) - sqrt(q) >= 0.
void check_direction_filter(const World& w, const D3& D0, FilterTally& t) {
  const D3 D = normalised(D0);
  if (!(dot(D, D) > 0)) return;
  const cd::StaticDirection sd = cd::static_direction(w.s, D);
  const StaticSign g = cd::static_separation_sign(sd);
  const Vec3<Q> E = exact(D);
  const CGAL::Sign truth = cd::separation_sign_exact(w.q, E);
  if (truth == CGAL::ZERO) ++t.zero;
  if (g == StaticSign::unknown) {
    ++t.unknown;
  } else {
    ++t.decided;
    BOOST_TEST((g == StaticSign::positive ? CGAL::POSITIVE : CGAL::NEGATIVE) == truth);
  }
  const double U = cd::static_ratio_upper(sd);
  if (std::isfinite(U)) {
    const cd::SeparationTerms<Q> x = cd::separation_terms(w.q, E);
    const Q dT = dot(E, w.q.T) < 0 ? Q(-dot(E, w.q.T)) : dot(E, w.q.T);
    // c' = U |D.T| - |D.A0| - |D.A1| = c + (U - 1) |D.T|.
    BOOST_TEST(cd::sign_c_minus_roots(Q(x.c + (Q(U) - 1) * dT), x.p, x.q) != CGAL::NEGATIVE);
  }
}

// A claimed upper bound sigma of sigma(X) (finite: a bound), exactly: sigma AA >= |2s - AA| and
// sigma^2 r^2 AA >= |w x A|^2 for both cylinders.
void check_sigma_bound(const cd::CylinderPair<Q>& q, const Point3<Q>& X, double sigma) {
  if (!std::isfinite(sigma)) return;
  const Q S(sigma);
  for (const Cylinder<Q>* c : {&q.c0, &q.c1}) {
    const Vec3<Q> A = c->p1 - c->p0, v = X - c->p0;
    const Q AA = dot(A, A), two_s = 2 * dot(v, A) - AA;
    BOOST_TEST(S * AA >= (two_s < 0 ? Q(-two_s) : two_s));
    const Vec3<Q> x = cross(v, A);
    BOOST_TEST(S * S * c->radius * c->radius * AA >= dot(x, x));
  }
}

// Same for points: inside-both decisions and the sigma bound.
void check_point_filter(const World& w, const D3& X, FilterTally& t) {
  const cd::StaticPoint sp = cd::static_point(w.s, X);
  const StaticSign g = cd::static_inside_both(sp);
  const Point3<Q> E = exact(X);
  const bool truth = cd::strictly_inside_both(w.q, E);
  if (g == StaticSign::unknown) {
    ++t.unknown;
  } else {
    ++t.decided;
    BOOST_TEST((g == StaticSign::positive) == truth);
  }
  check_sigma_bound(w.q, E, cd::static_sigma_upper(w.s, sp));
}

}  // namespace

// Thousands of random pairs: random directions and points, the solver's candidates, and
// near-degenerate ones (the second cylinder moved along D until |D.T| = phi2(D)(1 +- 2^-j) in
// double, j from 10 to 55, then rounded: the exact sign is from 2^-10 relative down to a few ulps
// from zero; points on a cylinder's surface, rounded). The filter may say unknown, never the wrong sign.
BOOST_AUTO_TEST_CASE(static_filter_never_contradicts_gmpq) {
  BOOST_TEST_MESSAGE("seed " << kSeed + 2);
  std::mt19937_64 g(kSeed + 2);
  std::uniform_real_distribution<double> u(-1, 1), unit(0, 1);
  FilterTally dir, near_dir, pt, near_pt;
  for (int i = 0; i < 2000; ++i) {
    const Pair p0{random_cylinder(g), random_cylinder(g)};
    const World w = world(p0);
    if (!w.s.usable) continue;
    const D3 A0 = w.a.p1 - w.a.p0, A1 = w.b.p1 - w.b.p0, T = (w.b.p0 + w.b.p1) - (w.a.p0 + w.a.p1);
    for (const D3& D : {T, cross(A0, A1), A0, A1, D3{u(g), u(g), u(g)}, D3{u(g), u(g), u(g)}}) check_direction_filter(w, D, dir);
    for (int k = 0; k < 3; ++k) check_point_filter(w, D3{2 * u(g), 2 * u(g), 2 * u(g)}, pt);
    // Near-degenerate direction: translate b along D so that D.T = phi2(D) (double), rounded.
    {
      const D3 D = normalised(D3{u(g), u(g), u(g)});
      const double n = dot(D, D);
      if (n > 1e-3) {
        const double ratio_now = ratio(Pair{w.a, w.b}, D);  // phi(D) / |D.Delta| = phi2(D) / |D.T|
        const double dT = dot(D, T), phi2 = ratio_now * std::abs(dT);
        // T + 2 t D has D.T = +-phi2 (1 + delta), delta = +-2^-j: from a few ulps to 2^-10.
        const double delta = (unit(g) < 0.5 ? -1 : 1) * std::ldexp(1.0, -static_cast<int>(10 + 46 * unit(g)));
        const double target = phi2 * (1 + delta);
        const double t = ((dT >= 0 ? target : -target) - dT) / (2 * n);
        const Cylinder<double> b{w.b.p0 + t * D, w.b.p1 + t * D, w.b.radius};
        const World v = world(Pair{w.a, b});
        if (v.s.usable) check_direction_filter(v, D, near_dir);
      }
    }
    // Near-degenerate points: on cylinder a's wall, its rim, its cap disk (rounded), b's endpoint.
    {
      const D3 A = A0;
      D3 e = cross(A, D3{u(g), u(g), u(g)});
      const double el = std::sqrt(dot(e, e));
      if (el > 1e-6) {
        e = (w.a.radius / el) * e;
        const double s = unit(g), f = unit(g);
        check_point_filter(w, w.a.p0 + s * A + e, near_pt);
        check_point_filter(w, w.a.p1 + e, near_pt);
        check_point_filter(w, w.a.p0 + f * e, near_pt);
        check_point_filter(w, w.b.p1, near_pt);  // exactly on b's cap: never strictly inside
      }
    }
  }
  BOOST_TEST_MESSAGE("directions: decided " << dir.decided << ", unknown " << dir.unknown << "; near-degenerate: decided "
                                            << near_dir.decided << ", unknown " << near_dir.unknown << ", exactly zero "
                                            << near_dir.zero);
  BOOST_TEST_MESSAGE("points: decided " << pt.decided << ", unknown " << pt.unknown << "; near-degenerate: decided " << near_pt.decided
                                        << ", unknown " << near_pt.unknown);
  // The filter is useful: it decides nearly every clear case ...
  BOOST_TEST(dir.decided > 0.99 * (dir.decided + dir.unknown));
  BOOST_TEST(pt.decided > 0.99 * (pt.decided + pt.unknown));
  // ... and the near-degenerate sets really are near-degenerate (many left undecided).
  BOOST_TEST(near_dir.unknown > 100);
  BOOST_TEST(near_dir.decided > 100);
  BOOST_TEST(near_pt.unknown > 100);
}

// Which arithmetic proved the answers of random pairs (double input): the filter should carry
// nearly all of them, and the exact stages almost none.
BOOST_AUTO_TEST_CASE(random_pairs_stage_rates) {
  BOOST_TEST_MESSAGE("seed " << kSeed + 3);
  std::mt19937_64 g(kSeed + 3);
  int by[4] = {0, 0, 0, 0}, beyond_fast = 0;
  const int N = 4000;
  for (int i = 0; i < N; ++i) {
    const Pair p{random_cylinder(g), random_cylinder(g)};
    const certcyl::CylinderCylinderResult r = certified_cylinder_cylinder(p.a, p.b);
    ++by[static_cast<int>(r.certified_by)];
    if (r.stage != certcyl::CylinderStage::fast_path && r.stage != certcyl::CylinderStage::midpoints) ++beyond_fast;
  }
  BOOST_TEST_MESSAGE("certified by: static " << by[0] << ", interval " << by[1] << ", exact " << by[2] << ", none " << by[3]
                                             << " of " << N << "; beyond the fast path " << beyond_fast);
  BOOST_TEST(by[0] > 0.99 * N);
  BOOST_TEST(by[3] == 0);
}

// ---- the quick filters (detail/cylinder_quick_filter.hpp) against Gmpq -------------------------
namespace {

// A pair multiplied by 2^k (exact for the magnitudes used here).
Pair scaled(const Pair& p, int k) {
  const auto sc = [k](double x) { return std::ldexp(x, k); };
  return {p.a.map(sc), p.b.map(sc)};
}

// The quick path's frame (cd::quick_frame), checked against its definition: w = 2^j with
// max |x| / w in [1, 2) over the fourteen numbers.
double quick_frame(const Pair& p) {
  int e = 0;
  std::frexp(largest_magnitude(p), &e);  // m = f 2^e, f in [1/2, 1)
  const double w = std::ldexp(1.0, e - 1);
  BOOST_TEST(cd::quick_frame(p.a, p.b) == w);
  return w;
}

struct QuickTally {
  int separated = 0, by_radius_sum = 0, not_separated = 0, inside = 0, not_inside = 0, lower_bounds = 0;
};

// quick_separation: when it says separated, D separates exactly; its phi bound is an upper bound
// of phi2(D) / |D.T| exactly; its lower bound L satisfies L <= 1 / sigma(X_t) exactly at the point
// X_t = m0 + t (m1 - m0), t = s1 / (s0 + s1) from independent double estimates of the scales at
// the midpoints (which makes 1 / sigma(X_t) = 1/s0 + 1/s1 up to rounding in t).
void check_quick_direction(const Pair& p, QuickTally& t) {
  const double w = quick_frame(p);
  const cd::CylinderPair<Q> q = cd::CylinderPair<Q>::make(exact(p.a), exact(p.b));
  cd::QuickSeparation s;
  const bool separated = cd::quick_separation(p.a, p.b, w, true, s);
  cd::QuickSeparation s2;
  BOOST_TEST(cd::quick_separation(p.a, p.b, w, false, s2) == separated);  // the bounds change nothing
  const Vec3<Q> D = exact(s.direction);
  BOOST_TEST(s2.by_radius_sum == s.by_radius_sum);
  BOOST_TEST((!s.by_radius_sum || separated));
  if (s.by_radius_sum) {
    // The sufficient test's own claim, exactly: c* = |D.T*| - |D.A0| - |D.A1| > 0 and
    // c*^2 > 4 (r0 + r1)^2 D.D.
    ++t.by_radius_sum;
    const auto abs_q = [](const Q& x) { return x < 0 ? Q(-x) : x; };
    const Q c = abs_q(dot(D, q.T)) - abs_q(dot(D, q.A0)) - abs_q(dot(D, q.A1));
    const Q rs = q.c0.radius + q.c1.radius;
    BOOST_TEST(c > 0);
    BOOST_TEST(c * c > 4 * rs * rs * dot(D, D));
  }
  if (separated) {
    ++t.separated;
    BOOST_TEST(cd::separation_sign(q, D) == CGAL::POSITIVE);
  } else {
    ++t.not_separated;
  }
  if (std::isfinite(s.phi_upper) && !(D.x == 0 && D.y == 0 && D.z == 0)) {
    const cd::SeparationTerms<Q> x = cd::separation_terms(q, D);
    const Q dT = dot(D, q.T) < 0 ? Q(-dot(D, q.T)) : dot(D, q.T);
    BOOST_TEST(cd::sign_c_minus_roots(Q(x.c + (Q(s.phi_upper) - 1) * dT), x.p, x.q) != CGAL::NEGATIVE);
  }
  const double L = s.phi_lower;
  BOOST_TEST(L >= 0);
  if (L > 0) {
    ++t.lower_bounds;
    const D3 m0 = 0.5 * (p.a.p0 + p.a.p1), m1 = 0.5 * (p.b.p0 + p.b.p1);
    const double s0 = sigma(Pair{p.a, p.a}, m1), s1 = sigma(Pair{p.b, p.b}, m0);
    const Q tq(s1 / (s0 + s1));
    const Point3<Q> X = (exact(m0) + tq * (exact(m1) - exact(m0)));
    const Q Lq(L);
    for (const Cylinder<Q>* c : {&q.c0, &q.c1}) {
      const Vec3<Q> A = c->p1 - c->p0, v = X - c->p0;
      const Q AA = dot(A, A), two_s = 2 * dot(v, A) - AA;
      // sigma(X) <= 1 / L:  L |2s - AA| <= AA  and  L^2 |v x A|^2 <= r^2 AA.
      BOOST_TEST(Lq * (two_s < 0 ? Q(-two_s) : two_s) <= AA);
      const Vec3<Q> cr = cross(v, A);
      BOOST_TEST(Lq * Lq * dot(cr, cr) <= c->radius * c->radius * AA);
    }
  }
}

// quick_point: an "inside" answer is right exactly; the sigma bound is an upper bound exactly.
void check_quick_point(const Pair& p, const D3& X, QuickTally& t) {
  const double w = quick_frame(p);
  const cd::CylinderPair<Q> q = cd::CylinderPair<Q>::make(exact(p.a), exact(p.b));
  const cd::QuickPoint r = cd::quick_point(p.a, p.b, w, X);
  const Point3<Q> E = exact(X);
  if (r.inside) {
    ++t.inside;
    BOOST_TEST(cd::strictly_inside_both(q, E));
  } else {
    ++t.not_inside;
  }
  check_sigma_bound(q, E, r.sigma_upper);
}

}  // namespace

// Random pairs at scales 2^-90 ... 2^90, and pairs moved so that Delta is within 2^-10 ... a few
// ulps of separating or not (b translated along Delta until |T.T| = phi2(T)(1 +- 2^-j), rounded);
// points near the closest points of the axes and on the surfaces. The quick filters may decline,
// never be wrong.
BOOST_AUTO_TEST_CASE(quick_filters_never_contradict_gmpq) {
  BOOST_TEST_MESSAGE("seed " << kSeed + 4);
  std::mt19937_64 g(kSeed + 4);
  std::uniform_real_distribution<double> u(-1, 1), unit(0, 1);
  QuickTally clear, near, near_radius_sum, points, near_points;
  for (int i = 0; i < 1500; ++i) {
    const int k = std::array<int, 5>{-90, -40, 0, 40, 90}[i % 5];
    const Pair p = scaled(Pair{random_cylinder(g), random_cylinder(g)}, k);
    check_quick_direction(p, clear);
    // Near-degenerate: T' = T + 2 t T (b moved along T) with |T'|^2 = phi2(T')(1 + delta); phi2 is
    // linear in the direction, so solve (1 + 2t)^2 |T|^2 = (1 + 2t) phi2(T)(1 + delta).
    {
      const D3 T = (p.b.p0 + p.b.p1) - (p.a.p0 + p.a.p1);
      const double TT = dot(T, T);
      if (TT > 0) {
        const double phi2 = ratio(p, T) * TT;  // phi2(T) = ratio * |T.T|
        const double delta = (unit(g) < 0.5 ? -1 : 1) * std::ldexp(1.0, -static_cast<int>(10 + 46 * unit(g)));
        const double f = phi2 * (1 + delta) / TT;  // 1 + 2t
        const double t = (f - 1) / 2;
        const Pair m{p.a, {p.b.p0 + t * T, p.b.p1 + t * T, p.b.radius}};
        check_quick_direction(m, near);
        // The same at the threshold of the sufficient test, c* = 2 (r0 + r1) |T'| (1 + delta):
        // (1 + 2t) |T|^2 = (|T.A0| + |T.A1| + 2 (r0 + r1) |T|)(1 + delta).
        const D3 A0 = p.a.p1 - p.a.p0, A1 = p.b.p1 - p.b.p0;
        const double bound = std::abs(dot(T, A0)) + std::abs(dot(T, A1)) + 2 * (p.a.radius + p.b.radius) * std::sqrt(TT);
        const double t2 = (bound * (1 + delta) / TT - 1) / 2;
        check_quick_direction(Pair{p.a, {p.b.p0 + t2 * T, p.b.p1 + t2 * T, p.b.radius}}, near_radius_sum);
      }
    }
    // Points: the inset closest points' division point and midpoint, random points, points on
    // a's wall and cap, b's endpoint (on its cap: never strictly inside).
    const D3 A0 = p.a.p1 - p.a.p0, A1 = p.b.p1 - p.b.p0;
    const auto [c0, c1] = cd::closest_segment_points(p.a.p0, A0, p.b.p0, A1, 0.1, 0.1);
    const double scale = std::ldexp(1.0, k);
    for (const D3& X : {c0 + (p.a.radius / (p.a.radius + p.b.radius)) * (c1 - c0), 0.5 * (c0 + c1),
                        D3{scale * u(g), scale * u(g), scale * u(g)}})
      check_quick_point(p, X, points);
    D3 e = cross(A0, D3{u(g), u(g), u(g)});
    const double el = std::sqrt(dot(e, e));
    if (el > 0) {
      e = (p.a.radius / el) * e;
      for (const D3& X : {p.a.p0 + unit(g) * A0 + e, p.a.p1 + e, p.a.p0 + unit(g) * e, p.b.p1})
        check_quick_point(p, X, near_points);
    }
  }
  BOOST_TEST_MESSAGE("clear: separated " << clear.separated << " (by the radius sum " << clear.by_radius_sum << "), not "
                                         << clear.not_separated << ", lower bounds " << clear.lower_bounds << "; near: separated "
                                         << near.separated << ", not " << near.not_separated << "; near the radius-sum test: by it "
                                         << near_radius_sum.by_radius_sum << ", not " << near_radius_sum.separated - near_radius_sum.by_radius_sum
                                         << " + " << near_radius_sum.not_separated);
  BOOST_TEST_MESSAGE("points: inside " << points.inside << ", not " << points.not_inside << "; near: inside "
                                       << near_points.inside << ", not " << near_points.not_inside);
  // The sets exercise both outcomes (the filters are not vacuous).
  BOOST_TEST(clear.separated > 500);
  BOOST_TEST(near.separated > 100);
  BOOST_TEST(near.not_separated > 100);
  BOOST_TEST(clear.by_radius_sum > 300);
  BOOST_TEST(near_radius_sum.by_radius_sum > 100);
  BOOST_TEST(near_radius_sum.separated - near_radius_sum.by_radius_sum > 100);  // declined, decided by the test itself
  BOOST_TEST(near_radius_sum.lower_bounds > 100);
  BOOST_TEST(points.inside > 100);
  BOOST_TEST(clear.lower_bounds > 1000);
}
