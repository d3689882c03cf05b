// The signed gap of src/study/gap.hpp, the depth margin G = max over the query set X of
// d(x) = min(1 - q(x), s(x), 1 - s(x)), against values worked out by hand (in the comments, each
// from the geometry, not from the code), including irrational ones, checked exactly: the
// enclosure [lo, hi] must contain the hand value (compared in exact arithmetic) and be at most a
// few ulps wide. Then the lemma's content: sign(G - delta) is the answer of X against the offset
// cylinder C_delta (radius r sqrt(1 - delta), caps moved in by delta heights), checked with the
// certified queries on explicitly built offset cylinders (radii chosen rational); sign families
// across touching; and the Euclidean clearance that a separated or overlapping margin implies.
#define BOOST_TEST_MODULE study_gap
#include <boost/test/unit_test.hpp>

#include <cmath>

#include "certcyl/certified/line_cylinder.hpp"
#include "certcyl/certified/triangle_cylinder.hpp"
#include "study/gap.hpp"

using namespace certcyl;
using namespace certcyl::study;
using namespace certcyl::study::detail;

namespace {

// The unit cylinder from (0,0,0) to (0,0,1), radius 1: s(x) = z, q(x) = x^2 + y^2.
Cylinder<Rational> unit_cylinder() { return {{0, 0, 0}, {0, 0, 1}, Rational(1)}; }

Rational R(long p, long q = 1) { return Rational(p) / Rational(q); }

Triangle<Rational> tri(const Point3<Rational>& a, const Point3<Rational>& b, const Point3<Rational>& c) {
  Triangle<Rational> t;
  t.v = {a, b, c};
  return t;
}

Line<Rational> line(Rational ox, Rational oy, Rational oz, Rational dx, Rational dy, Rational dz) {
  return {{ox, oy, oz}, {dx, dy, dz}};
}

// lo <= (p + sqrt(N)) / den <= hi, decided exactly (den > 0).
bool encloses_root(const MarginEnclosure& g, const Rational& p, const Rational& N, const Rational& den) {
  const Rational x = g.lo * den - p, y = g.hi * den - p;
  const bool lo_ok = x <= 0 || x * x <= N;
  const bool hi_ok = y >= 0 && N <= y * y;
  return lo_ok && hi_ok;
}

// The enclosure is at most `ulps` doubles wide around its value (it is written as doubles).
bool tight(const MarginEnclosure& g, int ulps = 2) {
  const auto [lo, hi] = enclose_margin_doubles(g);
  double x = lo;
  for (int i = 0; i < ulps; ++i) x = std::nextafter(x, HUGE_VAL);
  return hi <= x;
}

int sign_of_answer(Answer a) { return a == Answer::overlapping ? 1 : (a == Answer::touching ? 0 : -1); }

}  // namespace

BOOST_AUTO_TEST_CASE(exact_rational_margins) {
  const Cylinder<Rational> C = unit_cylinder();
  // Along y through (D, 0, 1/2): q = D^2 + t^2, s = 1/2, so d(t) = min(1 - D^2 - t^2, 1/2), largest
  // at t = 0: G = min(1 - D^2, 1/2).
  struct Case {
    Rational D, G;
  } cases[] = {{R(2), R(-3)}, {R(1), R(0)}, {R(3, 4), R(7, 16)}, {R(1, 2), R(1, 2)}, {R(0), R(1, 2)}, {R(5, 4), R(-9, 16)}};
  for (const Case& c : cases) {
    const MarginEnclosure g = circular_line_gap(line(c.D, 0, R(1, 2), 0, 1, 0), C, LineRange::line);
    BOOST_TEST((g.lo == c.G && g.hi == c.G), "D = " << c.D << ": [" << g.lo << ", " << g.hi << "], expected " << c.G);
  }
  // Parallel to the axis at distance D = 3/2: q = 9/4, s = t, d = min(-5/4, t, 1 - t): G = -5/4
  // (any t in [0, 1]); a ray starting at z = 3 pointing up (s >= 3): d = min(-5/4, 1 - s) <= -2,
  // G = -2 at its origin; the segment from z = -1/2 to z = -1/4: G = min(-5/4, -1/4) = -5/4.
  const auto g1 = circular_line_gap(line(R(3, 2), 0, 0, 0, 0, 1), C, LineRange::line);
  BOOST_TEST((g1.lo == R(-5, 4) && g1.hi == R(-5, 4)));
  const auto g2 = circular_line_gap(line(R(3, 2), 0, 3, 0, 0, 1), C, LineRange::ray);
  BOOST_TEST((g2.lo == R(-2) && g2.hi == R(-2)));
  const auto g3 = circular_line_gap(line(0, 0, R(-1, 2), 0, 0, R(1, 4)), C, LineRange::segment);
  // On the axis (q = 0): d = min(1, s, 1 - s) = s in [-1/2, -1/4]: G = -1/4.
  BOOST_TEST((g3.lo == R(-1, 4) && g3.hi == R(-1, 4)));
  // A point: (0, 0, 1/4) has d = min(1, 1/4, 3/4) = 1/4.
  BOOST_TEST(circular_point_gap({0, 0, R(1, 4)}, C) == R(1, 4));
}

BOOST_AUTO_TEST_CASE(irrational_margins) {
  const Cylinder<Rational> C = unit_cylinder();
  // X(t) = (t, 3/5, t): q = t^2 + 9/25, s = t, d = min(16/25 - t^2, t, 1 - t). s increases and
  // 1 - q decreases for t > 0; they cross where t^2 + t - 16/25 = 0, t = (sqrt(89) - 5)/10
  // ~ 0.4434 < 1/2 (so 1 - s > s there): G = (sqrt(89) - 5) / 10, overlapping.
  const auto g = circular_line_gap(line(0, R(3, 5), 0, 1, 0, 1), C, LineRange::line);
  BOOST_TEST(encloses_root(g, R(-5), R(89), R(10)), "[" << g.lo << ", " << g.hi << "]");
  BOOST_TEST(tight(g));
  BOOST_TEST(g.lo > 0);
  // The ray from t = 0 has the same maximiser: same G. The ray from t = 1/2 (origin
  // (1/2, 3/5, 1/2)): d decreases along it, G = d(1/2) = min(16/25 - 1/4, 1/2, 1/2) = 39/100.
  BOOST_TEST(encloses_root(circular_line_gap(line(0, R(3, 5), 0, 1, 0, 1), C, LineRange::ray), R(-5), R(89), R(10)));
  const auto g_ray = circular_line_gap(line(R(1, 2), R(3, 5), R(1, 2), 1, 0, 1), C, LineRange::ray);
  BOOST_TEST((g_ray.lo == R(39, 100) && g_ray.hi == R(39, 100)));
  // The segment t in [0, 1/4]: d increasing, G = d(1/4) = min(16/25 - 1/16, 1/4, 3/4) = 1/4.
  const auto g_seg = circular_line_gap(line(0, R(3, 5), 0, R(1, 4), 0, R(1, 4)), C, LineRange::segment);
  BOOST_TEST((g_seg.lo == R(1, 4) && g_seg.hi == R(1, 4)));

  // Separated, below the bottom cap: X(t) = (t, 0, t - 2), q = t^2, s = t - 2,
  // d = min(1 - t^2, t - 2, 3 - t). s and 1 - q cross at t^2 + t - 3 = 0, t = (sqrt(13) - 1)/2
  // ~ 1.30; left of it d = s rises, right of it d = 1 - q falls: G = t - 2 = (sqrt(13) - 5)/2
  // ~ -0.697. (The largest depth at the points t = 0, the nearest to the axis, and the
  // cap-plane crossings t = 2, 3 is -2: far from G.)
  const auto s = circular_line_gap(line(0, 0, -2, 1, 0, 1), C, LineRange::line);
  BOOST_TEST(encloses_root(s, R(-5), R(13), R(2)), "[" << s.lo << ", " << s.hi << "]");
  BOOST_TEST(tight(s));
  BOOST_TEST(s.hi < R(-69, 100));
  BOOST_TEST(s.lo > R(-70, 100));

  // A triangle in the plane x = z with the edge X(t) = (t, 3/5, t), t in [0, 1], and the vertex
  // (1/2, 2, 1/2): every point has y >= 3/5, so d(x, y, x) <= min(16/25 - x^2, x, 1 - x) with
  // equality on the edge: G = (sqrt(89) - 5)/10, the edge's.
  const Triangle<Rational> T = tri({0, R(3, 5), 0}, {1, R(3, 5), 1}, {R(1, 2), 2, R(1, 2)});
  const auto gt = triangle_margin(T, C);
  BOOST_TEST(encloses_root(gt, R(-5), R(89), R(10)), "[" << gt.lo << ", " << gt.hi << "]");
  BOOST_TEST(tight(gt));
}

BOOST_AUTO_TEST_CASE(triangles_and_elliptic) {
  const Cylinder<Rational> C = unit_cylinder();
  // In the plane z = 1/2 around the axis point (0, 0, 1/2): d = min(1, 1/2, 1/2) = 1/2 = G (G never exceeds 1/2).
  const Triangle<Rational> across = tri({R(-1, 4), R(-1, 4), R(1, 2)}, {R(1, 2), 0, R(1, 2)}, {0, R(1, 2), R(1, 2)});
  const auto a = triangle_margin(across, C);
  BOOST_TEST((a.lo == R(1, 2) && a.hi == R(1, 2)));
  // In the plane x = 2, spanning z in [0, 1] over y = 0: q = 4 + y^2, d <= 1 - 4 = -3, attained at
  // (2, 0, z), z in [0, 1]: G = -3.
  const Triangle<Rational> wall = tri({2, -1, 0}, {2, 1, 0}, {2, 0, 1});
  const auto w = triangle_margin(wall, C);
  BOOST_TEST((w.lo == R(-3) && w.hi == R(-3)));
  // The same pushed to x = 1: tangent to the wall, G = 0.
  const Triangle<Rational> tangent = tri({1, -1, 0}, {1, 1, 0}, {1, 0, 1});
  const auto t = triangle_margin(tangent, C);
  BOOST_TEST((t.lo == 0 && t.hi == 0));
  // Above the top cap, horizontal at z = 5/4 over the axis: d = min(1 - q, 5/4, -1/4) = -1/4 at any
  // point with q <= 5/4: G = -1/4.
  const Triangle<Rational> above = tri({-1, -1, R(5, 4)}, {1, 0, R(5, 4)}, {0, 1, R(5, 4)});
  const auto b = triangle_margin(above, C);
  BOOST_TEST((b.lo == R(-1, 4) && b.hi == R(-1, 4)));

  // The elliptic cylinder base 0, a = (2,0,0), b = (0,1,0), c = (0,0,1): unit coordinates
  // (x/2, y, z). Along y through (3, 0, 1/2): q = 9/4 + t^2, s = 1/2: G = 1 - 9/4 = -5/4.
  const EllipticCylinder<Rational> E{{0, 0, 0}, {2, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const auto e = elliptic_line_gap(line(3, 0, R(1, 2), 0, 1, 0), E, LineRange::line);
  BOOST_TEST((e.lo == R(-5, 4) && e.hi == R(-5, 4)));
  // Through (1, 0, 1/2) along y: q = 1/4 + t^2: G = min(3/4, 1/2) = 1/2.
  const auto e2 = elliptic_line_gap(line(1, 0, R(1, 2), 0, 1, 0), E, LineRange::line);
  BOOST_TEST((e2.lo == R(1, 2) && e2.hi == R(1, 2)));
  BOOST_TEST(elliptic_point_gap({1, 0, R(1, 4)}, E) == R(1, 4));  // min(3/4, 1/4, 3/4)
}

// Lines along y through (1 + e, 0, 1/2), e = k 2^-40: G = 1 - (1 + e)^2 = -2e - e^2, exactly;
// separated for k > 0, touching at k = 0, overlapping for k < 0. The enclosure has the answer's
// sign and contains the value.
BOOST_AUTO_TEST_CASE(sign_across_touching) {
  const Cylinder<Rational> C = unit_cylinder();
  const Rational ulp = power_of_two(-40);
  for (int k = -3; k <= 3; ++k) {
    const Rational e = Rational(k) * ulp, G = -2 * e - e * e;
    const Line<Rational> l = line(1 + e, 0, R(1, 2), 0, 1, 0);
    const auto g = circular_line_gap(l, C, LineRange::line);
    BOOST_TEST((g.lo <= G && G <= g.hi), "k = " << k);
    BOOST_TEST(sign_of(g.lo) == sign_of(G));
    BOOST_TEST(sign_of(g.hi) == sign_of(G));
    BOOST_TEST(sign_of_answer(certified_line_cylinder(l, C).answer) == sign_of(G), "k = " << k);
  }
  // Tilted family through the bottom cap's rim circle: X(t) = (t, b, t) (direction (1,0,1)),
  // q = t^2 + b^2, s = t, d = min(c - t^2, t, 1 - t) with c = 1 - b^2. For b = 1 + e (c < 0):
  // d(0) = min(c, 0) = c, and d(t) <= c - t^2 < c for every t != 0: G = c = -(2e + e^2), exactly.
  // For b = 1 - e (c > 0): d(0) = 0 and d rises as s = t until it meets 1 - q at
  // t^2 + t - c = 0, t = (-1 + sqrt(1 + 4c))/2 (< 1/2 for small c): G = t, irrational.
  for (int k = 1; k <= 3; ++k) {
    const Rational e = Rational(k) * ulp;
    const Rational c_out = 1 - (1 + e) * (1 + e), c_in = 1 - (1 - e) * (1 - e);
    const auto g_out = circular_line_gap(line(0, 1 + e, 0, 1, 0, 1), C, LineRange::line);
    BOOST_TEST((g_out.lo == c_out && g_out.hi == c_out), "k = " << k);
    const auto g_in = circular_line_gap(line(0, 1 - e, 0, 1, 0, 1), C, LineRange::line);
    BOOST_TEST(encloses_root(g_in, R(-1), 1 + 4 * c_in, R(2)), "k = " << k);
    BOOST_TEST(g_in.lo > 0);
    BOOST_TEST(tight(g_in));
  }
}

// The lemma: sign(G - delta) is the answer of X against C_delta, checked by the certified query
// on C_delta built explicitly, for offsets delta = 1 - m^2 with m rational (so the radius m is
// rational): caps at delta and 1 - delta, radius m.
BOOST_AUTO_TEST_CASE(margin_is_the_offset_that_changes_the_answer) {
  const Cylinder<Rational> C = unit_cylinder();
  const auto offset = [](const Rational& m) {
    const Rational delta = 1 - m * m;
    return Cylinder<Rational>{{0, 0, delta}, {0, 0, 1 - delta}, m};
  };
  // The separated line (t, 0, t - 2) of irrational_margins, G ~ -0.6972: growing the cylinder
  // by delta = 1 - 1.3^2 = -0.69 (|delta| < |G|) leaves it separated; by delta = 1 - 1.32^2
  // = -0.7424 (|delta| > |G|) it overlaps. (A size of 2, as the largest sample depth had it,
  // would wrongly promise that the second stays separated.)
  const Line<Rational> below = line(0, 0, -2, 1, 0, 1);
  const auto g = circular_line_gap(below, C, LineRange::line);
  for (const Rational& m : {R(13, 10), R(132, 100), R(131, 100), R(1395, 1000), R(1303, 1000), R(1302, 1000)}) {
    const Rational delta = 1 - m * m;
    const Answer a = certified_line_cylinder(below, offset(m)).answer;
    if (delta > g.hi) BOOST_TEST((a == Answer::separated), "m = " << m);
    if (delta < g.lo) BOOST_TEST((a == Answer::overlapping), "m = " << m);
  }
  // The overlapping line (t, 3/5, t), G ~ 0.4434: shrinking by delta = 1 - m^2 < G keeps it
  // overlapping, beyond G it misses.
  const Line<Rational> inside = line(0, R(3, 5), 0, 1, 0, 1);
  const auto h = circular_line_gap(inside, C, LineRange::line);
  for (const Rational& m : {R(3, 4), R(76, 100), R(745, 1000), R(748, 1000), R(8, 10), R(7, 10)}) {
    const Rational delta = 1 - m * m;
    const Answer a = certified_line_cylinder(inside, offset(m)).answer;
    if (delta > h.hi) BOOST_TEST((a == Answer::separated), "m = " << m);
    if (delta < h.lo) BOOST_TEST((a == Answer::overlapping), "m = " << m);
  }
  // The same for the triangle with that edge, through the certified triangle query.
  const Triangle<Rational> T = tri({0, R(3, 5), 0}, {1, R(3, 5), 1}, {R(1, 2), 2, R(1, 2)});
  const auto gt = triangle_margin(T, C);
  for (const Rational& m : {R(3, 4), R(76, 100), R(745, 1000), R(748, 1000)}) {
    const Rational delta = 1 - m * m;
    const Answer a = certified_triangle_cylinder(T, offset(m)).answer;
    if (delta > gt.hi) BOOST_TEST((a == Answer::separated), "m = " << m);
    if (delta < gt.lo) BOOST_TEST((a == Answer::overlapping), "m = " << m);
  }
  // Exactly at G = 7/16 (line along y through (3/4, 0, 1/2), m = 3/4): touching.
  BOOST_TEST((certified_line_cylinder(line(R(3, 4), 0, R(1, 2), 0, 1, 0), offset(R(3, 4))).answer == Answer::touching));
}

// The Euclidean consequence: with G < 0, X is at distance >= min(r (sqrt(1 - G) - 1), -G h) from
// C. For the line (t, 0, t - 2), G ~ -0.6972, r = h = 1: sqrt(1.6972) - 1 ~ 0.3028; its true
// distance to the cylinder is the distance from the rim point (1, 0, 0) to the line, |(1, 0, 2)
// x (1, 0, 1)| / sqrt(2) = 1/sqrt(2) ~ 0.707, indeed at least the bound. For G > 0 a point of
// X has depth >= min(r (1 - sqrt(1 - G)), G h): for (t, 3/5, t), G ~ 0.4434, the bound is
// 1 - sqrt(0.5566) ~ 0.254; the point t = 0.4434 is 1 - sqrt(0.4434^2 + 0.36) ~ 0.254 from the
// wall and 0.4434 from the bottom cap.
BOOST_AUTO_TEST_CASE(euclidean_clearance) {
  const Cylinder<Rational> C = unit_cylinder();
  const auto g = circular_line_gap(line(0, 0, -2, 1, 0, 1), C, LineRange::line);
  const double G = CGAL::to_double(g.hi);
  const double bound = std::min(std::sqrt(1 - G) - 1, -G);
  BOOST_TEST(bound > 0.30);
  BOOST_TEST(bound <= 1 / std::sqrt(2.0));
  const auto h = circular_line_gap(line(0, R(3, 5), 0, 1, 0, 1), C, LineRange::line);
  const double H = CGAL::to_double(h.lo);
  BOOST_TEST(std::min(1 - std::sqrt(1 - H), H) > 0.25);
}

// The bisection without a guess, on a comparison known in closed form: G = c (sqrt(2) - 1) for
// scales c of either sign and sizes from 2^-300 to 2^40 (sign(G - delta) decided exactly by
// squaring). The enclosure must contain G (checked exactly) and have a relative width of at
// most 2^-23; a guess that does not bracket G must be rejected.
BOOST_AUTO_TEST_CASE(bisection_without_a_guess) {
  for (const long e : {-300L, -40L, -2L, 0L, 40L}) {
    for (const int sign : {1, -1}) {
      const Rational c = sign * power_of_two(e);
      if (sign > 0 && e > -2) continue;  // G <= 1/2
      // sign(c (sqrt(2) - 1) - delta) = sign(c) sign(sqrt(2) - (1 + delta / c)).
      const auto cmp = [&](const Rational& delta) {
        const Rational y = 1 + delta / c;
        const int s = y < 0 ? 1 : (y * y < 2 ? 1 : (y * y > 2 ? -1 : 0));
        return sign * s;
      };
      const Rational floor = sign > 0 ? Rational(0) : Rational(-1) * power_of_two(e + 1);  // a lower bound of G
      const std::vector<std::pair<Rational, Rational>> wrong_guess{{c / 2, c / 3}, {c * 2, c * 3}};
      const MarginEnclosure g = enclose_margin(cmp, sign, floor, wrong_guess);
      // lo <= c (sqrt(2) - 1) <= hi, i.e. (for c > 0) lo / c + 1 <= sqrt(2) <= hi / c + 1.
      const Rational a = (sign > 0 ? g.lo : g.hi) / c + 1, b = (sign > 0 ? g.hi : g.lo) / c + 1;
      BOOST_TEST((a * a <= 2 && 2 <= b * b), "e = " << e << " sign " << sign);
      BOOST_TEST(((g.hi - g.lo) * power_of_two(23) <= (sign > 0 ? g.lo : -g.hi)), "e = " << e << " sign " << sign);
    }
  }
}
