// Eberly's cylinder-cylinder test against an independent truth on random pairs at clear
// margins. The truth never uses the algorithm: a pair is "clearly separated" when a direction
// from a dense sampling of the sphere has a support gap below -margin and that direction,
// taken as a rational vector, separates by an exact CORE::Expr evaluation of the support
// function; "clearly overlapping" when a rational point lies strictly inside both cylinders
// shrunk by 10% (radius and both ends of the axis), decided by the exact point predicate.
// Pairs that are neither are skipped.
#define BOOST_TEST_MODULE eberly_independent
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "certcyl/number_traits_core.hpp"
#include "certcyl/predicates/point_in_cylinder.hpp"
#include "eberly_test_support.hpp"

using namespace certcyl;
using namespace eberly_test;

namespace {

constexpr std::uint64_t kSeed = 20240605;
constexpr double kMargin = 0.05;

struct Pair {
  Cylinder<Rational> c0, c1;
  Answer truth;
};

Rational random_rational(std::mt19937_64& rng, int lo, int hi, int den) {
  std::uniform_int_distribution<int> d(lo * den, hi * den);
  return Rational(d(rng), den);
}

Cylinder<Rational> random_cylinder(std::mt19937_64& rng) {
  for (;;) {
    Vec3<Rational> p0{random_rational(rng, -2, 2, 8), random_rational(rng, -2, 2, 8), random_rational(rng, -2, 2, 8)};
    Vec3<Rational> p1{random_rational(rng, -2, 2, 8), random_rational(rng, -2, 2, 8), random_rational(rng, -2, 2, 8)};
    std::uniform_int_distribution<int> r(1, 6);
    if (!(p0 == p1)) return {p0, p1, Rational(r(rng), 8)};
  }
}

std::vector<Vec3<double>> sphere_directions(int n) {
  // Fibonacci points on the unit sphere.
  std::vector<Vec3<double>> ds;
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - (i + 0.5) * 2.0 / n, rho = std::sqrt(1.0 - z * z), th = golden * i;
    ds.push_back({rho * std::cos(th), rho * std::sin(th), z});
  }
  return ds;
}

bool clearly_separated(const Pair& p, const std::vector<Vec3<double>>& directions) {
  const Cylinder<double> a = convert<double>(p.c0), b = convert<double>(p.c1);
  double best = 1e300;
  Vec3<double> best_d{0, 0, 0};
  for (const auto& d : directions) {
    const double g = support_gap(a, b, d);
    if (g < best) best = g, best_d = d;
  }
  if (best >= -kMargin) return false;
  const Vec3<CORE::Expr> D{CORE::Expr(best_d.x), CORE::Expr(best_d.y), CORE::Expr(best_d.z)};
  return nt::sign(support_gap(convert<CORE::Expr>(p.c0), convert<CORE::Expr>(p.c1), D)) == CGAL::NEGATIVE;
}

Cylinder<Rational> shrunk(const Cylinder<Rational>& c) {
  const Vec3<Rational> A = c.axis();
  return {c.p0 + Rational(1, 10) * A, c.p1 - Rational(1, 10) * A, Rational(9, 10) * c.radius};
}

bool clearly_overlapping(const Pair& p) {
  const Cylinder<Rational> a = shrunk(p.c0), b = shrunk(p.c1);
  // Candidates: points on the segment between the axes' closest points, and between centres.
  const Cylinder<double> da = convert<double>(p.c0), db = convert<double>(p.c1);
  const Vec3<double> u = da.axis(), w = db.axis(), r = da.p0 - db.p0;
  const double A = dot(u, u), B = dot(u, w), C = dot(w, w), Dd = dot(u, r), E = dot(w, r);
  const double den = A * C - B * B;
  double s = den > 1e-12 ? (B * E - C * Dd) / den : 0.5, t = den > 1e-12 ? (A * E - B * Dd) / den : 0.5;
  s = std::min(1.0, std::max(0.0, s));
  t = std::min(1.0, std::max(0.0, t));
  const Vec3<double> x0 = da.p0 + s * u, x1 = db.p0 + t * w;
  const Vec3<double> m0 = (da.p0 + da.p1) * 0.5, m1 = (db.p0 + db.p1) * 0.5;
  for (int k = 0; k <= 16; ++k) {
    const double l = k / 16.0;
    for (const Vec3<double>& x : {x0 + l * (x1 - x0), m0 + l * (m1 - m0)}) {
      const Vec3<Rational> X{Rational(x.x), Rational(x.y), Rational(x.z)};
      if (classify_point(X, a) == Side::inside && classify_point(X, b) == Side::inside) return true;
    }
  }
  return false;
}

const std::vector<Pair>& clear_pairs() {
  static const std::vector<Pair> pairs = [] {
    std::mt19937_64 rng(kSeed);
    const auto directions = sphere_directions(6000);
    std::vector<Pair> out;
    for (int i = 0; i < 400; ++i) {
      Pair p{random_cylinder(rng), random_cylinder(rng), Answer::undecided};
      if (clearly_overlapping(p)) {
        p.truth = Answer::overlapping;
      } else if (clearly_separated(p, directions)) {
        p.truth = Answer::separated;
      } else {
        continue;
      }
      out.push_back(p);
    }
    return out;
  }();
  return pairs;
}

}  // namespace

BOOST_AUTO_TEST_CASE(enough_clear_pairs_of_each_kind) {
  BOOST_TEST_MESSAGE("seed " << kSeed << ": " << clear_pairs().size() << " clear pairs of 400");
  int separated = 0, overlapping = 0;
  for (const Pair& p : clear_pairs()) (p.truth == Answer::separated ? separated : overlapping) += 1;
  BOOST_TEST(separated >= 50);
  BOOST_TEST(overlapping >= 50);
}

BOOST_AUTO_TEST_CASE(corrected_double_agrees_with_the_independent_truth) {
  int as_written_disagreements = 0;
  for (std::size_t i = 0; i < clear_pairs().size(); ++i) {
    const Pair& p = clear_pairs()[i];
    BOOST_TEST_CONTEXT("pair " << i << " (seed " << kSeed << "), truth " << to_string(p.truth)) {
      const auto r = eberly_separated(convert<double>(p.c0), convert<double>(p.c1), EberlyParameters::corrected());
      BOOST_TEST(to_string(r.answer) == to_string(p.truth));
      const auto w = eberly_separated(convert<double>(p.c0), convert<double>(p.c1), EberlyParameters::as_written());
      if (w.answer != p.truth) ++as_written_disagreements;
    }
  }
  BOOST_TEST_MESSAGE("as written, double: " << as_written_disagreements << " disagreements at clear margins");
}

BOOST_AUTO_TEST_CASE(corrected_core_expr_agrees_with_the_independent_truth_and_intervals_never_contradict) {
  // 25 pairs of each kind in CORE::Expr, and the same in intervals.
  int separated = 0, overlapping = 0, interval_decided = 0;
  const EberlyParameters p = EberlyParameters::corrected();  // default parameters
  for (std::size_t i = 0; i < clear_pairs().size() && (separated < 25 || overlapping < 25); ++i) {
    const Pair& pr = clear_pairs()[i];
    int& count = pr.truth == Answer::separated ? separated : overlapping;
    if (count >= 25) continue;
    ++count;
    BOOST_TEST_CONTEXT("pair " << i << " (seed " << kSeed << "), truth " << to_string(pr.truth)) {
      const Cylinder<CORE::Expr> a = convert<CORE::Expr>(pr.c0), b = convert<CORE::Expr>(pr.c1);
      const auto r = eberly_separated(a, b, p);
      BOOST_TEST(to_string(r.answer) == to_string(pr.truth));
      if (r.separated) BOOST_TEST(nt::sign(support_gap(a, b, r.direction)) == CGAL::NEGATIVE);
      CGAL::Protect_FPU_rounding<true> upward;
      try {
        const auto ri = eberly_separated(convert<Interval>(pr.c0), convert<Interval>(pr.c1), p);
        ++interval_decided;
        BOOST_TEST(to_string(ri.answer) == to_string(r.answer));
        BOOST_TEST(to_string(ri.test) == to_string(r.test));
      } catch (const CGAL::Uncertain_conversion_exception&) {
        // else: undecided in intervals, which is allowed
      }
    }
  }
  BOOST_TEST(separated == 25);
  BOOST_TEST(overlapping == 25);
  BOOST_TEST_MESSAGE("intervals decided " << interval_decided << " of 50");
}
