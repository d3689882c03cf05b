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

Cylinder<double> random_cylinder(std::mt19937_64& g) {
  std::uniform_real_distribution<double> u(-1, 1), len(0.2, 2), rad(0.05, 0.5);
  D3 w;
  double n2;
  do {
    w = {u(g), u(g), u(g)};
    n2 = dot(w, w);
  } while (n2 < 0.01 || n2 > 1);
  const double h = len(g) / (2 * std::sqrt(n2));
  const D3 c{u(g), u(g), u(g)};
  return {c - h * w, c + h * w, rad(g)};
}

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
      BOOST_TEST(to_string(certified_cylinder_cylinder(p.a, p.b).answer) == to_string(r.answer));
      BOOST_TEST(to_string(certified_cylinder_cylinder(b, a).answer) == to_string(r.answer));
      if (!r.gap_known) continue;
      const double rmin = brute_min_ratio(p, g), smin = brute_min_sigma(p, g);
      // No contradicting evidence (beyond rounding), ever.
      if (r.answer == Answer::separated) BOOST_TEST(smin > 1 - 1e-12);
      if (r.answer == Answer::overlapping) BOOST_TEST(rmin > 1 - 1e-12);
      // The enclosure contains what the brute force proves: phi* <= rmin and phi* >= 1/smin.
      BOOST_TEST(r.phi_lower <= rmin * (1 + 1e-12));
      BOOST_TEST(1 / smin <= r.phi_upper * (1 + 1e-12));
      // At clear margins the brute force finds supporting evidence.
      if (r.phi_upper < 0.99) {
        ++clear;
        BOOST_TEST(rmin < 1 - 1e-9);
      }
      if (r.phi_lower > 1.01) {
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
