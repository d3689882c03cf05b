// The semi-static double stage of the certified line/cylinder decision
// (certified/detail/line_static_filter.hpp):
//   - its error bound holds: for every decision polynomial, |double value - exact value| is
//     below the bound, on random and near-degenerate binary64 inputs (exact values in Gmpq
//     from the exact differences);
//   - at exact degeneracies (tangent, on the wall, rim graze, cap-plane chord, ends on the
//     boundary, direction parallel to the axis or to the caps) it never decides: the exact
//     zero goes to the next stage, and the filtered answer is the hand-derived one;
//   - huge (2^1000), tiny (2^-1000) and subnormal scales: power-of-two scaling of a
//     configuration with a known answer keeps the answer; outside its window the stage is
//     skipped;
//   - thousands of random, near-tangent, near-parallel, near-cap and far-translated inputs:
//     the filtered decision equals the pure Gmpq skeleton field by field; the rates of the
//     three stages are printed.
#define BOOST_TEST_MODULE line_static_filter
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <iostream>
#include <random>
#include <string>

#include "certcyl/certified/line_cylinder.hpp"

using namespace certcyl;
using namespace certcyl::detail;
using Q = Rational;

namespace {

struct Query {
  Vec3<double> origin, second;
  bool segment = false;
  LineRange range = LineRange::line;
  Cylinder<double> cyl;
};

LineInput<double> input(const Query& x) { return {x.origin, x.second, x.segment, x.range}; }

// The decision of the skeleton in Gmpq alone (no filter).
LineShape exact_shape(const Query& x) { return line_shape(line_quadric_in<Q>(input(x), x.cyl), x.range); }

bool same(const LineShape& a, const LineShape& b) {
  return a.answer == b.answer && a.tube == b.tube && a.slab == b.slab &&
         (a.answer == Answer::separated ||
          (a.in == b.in && a.out == b.out && a.in_feature == b.in_feature && a.out_feature == b.out_feature &&
           a.in_surface == b.in_surface && a.out_surface == b.out_surface));
}

// The static stage alone: decided (and its shape) or not.
struct StaticRun {
  bool usable = false, decided = false;
  LineShape shape;
};
StaticRun run_static(const Query& x) {
  StaticCircularSigns s(x.origin, x.second, x.segment, x.cyl);
  StaticRun r;
  r.usable = s.usable();
  if (!r.usable) return r;
  r.shape = line_shape_from(s, x.range);
  r.decided = !s.undecided();
  return r;
}

LineShape filtered(const Query& x, LineStageCounter& counter) {
  switch (x.range) {
    case LineRange::line: return certified_line_cylinder_shape(Line<double>{x.origin, x.second}, x.cyl, counter);
    case LineRange::ray: return certified_line_cylinder_shape(Ray<double>{x.origin, x.second}, x.cyl, counter);
    case LineRange::segment: return certified_line_cylinder_shape(Segment<double>{x.origin, x.second}, x.cyl, counter);
  }
  return {};
}

SV3<double> sv(const Vec3<double>& v) { return {v.x, v.y, v.z}; }
SV3<Q> svq(const Vec3<double>& v) { return {Q(v.x), Q(v.y), Q(v.z)}; }
SV3<double> dd(const Vec3<double>& p, const Vec3<double>& q) { return {p.x - q.x, p.y - q.y, p.z - q.z}; }
SV3<Q> dq(const Vec3<double>& p, const Vec3<double>& q) { return {Q(p.x) - Q(q.x), Q(p.y) - Q(q.y), Q(p.z) - Q(q.z)}; }

// Largest |double - exact| / bound over the decision polynomials of one query (< 1 required).
double worst_error_ratio(const Query& x) {
  StaticCircularSigns s(x.origin, x.second, x.segment, x.cyl);
  if (!s.usable()) return 0;
  using PD = CircularPolynomials<double>;
  using PQ = CircularPolynomials<Q>;
  const SV3<double> A = dd(x.cyl.p1, x.cyl.p0), w = dd(x.origin, x.cyl.p0), w1 = dd(x.origin, x.cyl.p1);
  const SV3<Q> Aq = dq(x.cyl.p1, x.cyl.p0), wq = dq(x.origin, x.cyl.p0), w1q = dq(x.origin, x.cyl.p1);
  const SV3<double> d = x.segment ? dd(x.second, x.origin) : sv(x.second);
  const SV3<Q> d_q = x.segment ? dq(x.second, x.origin) : svq(x.second);
  const double r = x.cyl.radius;
  const Q rq(r);
  double worst = 0;
  auto check = [&](double v, const Q& exact, const StaticBound& b) {
    const double bound = s.bound(b);
    const Q err = Q(v) - exact;
    const double ratio = CGAL::to_double((err < 0 ? Q(-err) : err) / Q(bound));
    worst = std::max(worst, ratio);
  };
  namespace sb = line_static_bounds;
  check(PD::a(A, d), PQ::a(Aq, d_q), sb::a);
  check(PD::disc(A, w, d, r), PQ::disc(Aq, wq, d_q, rq), sb::disc);
  check(PD::excess(A, w, r), PQ::excess(Aq, wq, rq), sb::excess);
  check(PD::dot(d, A), PQ::dot(d_q, Aq), sb::dot_ld);
  check(PD::dot(w, A), PQ::dot(wq, Aq), sb::dot_ll);
  check(PD::dot(w1, A), PQ::dot(w1q, Aq), sb::dot_ll);
  check(PD::b(A, w, d), PQ::b(Aq, wq, d_q), sb::b);
  check(PD::cap_excess(A, w, d, r), PQ::cap_excess(Aq, wq, d_q, rq), sb::cap_excess);
  check(PD::cap_excess(A, w1, d, r), PQ::cap_excess(Aq, w1q, d_q, rq), sb::cap_excess);
  check(PD::cap_side(A, w, d), PQ::cap_side(Aq, wq, d_q), sb::cap_side);
  check(PD::cap_side(A, w1, d), PQ::cap_side(Aq, w1q, d_q), sb::cap_side);
  if (x.segment) {
    const SV3<double> e0 = dd(x.second, x.cyl.p0), e1 = dd(x.second, x.cyl.p1);
    const SV3<Q> e0q = dq(x.second, x.cyl.p0), e1q = dq(x.second, x.cyl.p1);
    check(PD::excess(A, e0, r), PQ::excess(Aq, e0q, rq), sb::excess);
    check(PD::b(A, e0, d), PQ::b(Aq, e0q, d_q), sb::b);
    check(PD::dot(e0, A), PQ::dot(e0q, Aq), sb::dot_ll);
    check(PD::dot(e1, A), PQ::dot(e1q, Aq), sb::dot_ll);
  }
  return worst;
}

// Generators. `kind`: 0 random, 1 near-tangent, 2 nearly parallel to the axis, 3 segment
// ending near a cap plane, 4 far translation, 5 nearly parallel to the caps.
Query make_query(std::mt19937_64& rng, int kind) {
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_int_distribution<int> ulps(-3, 3), rsel(0, 2);
  auto nudge = [&](double x) {
    const int k = ulps(rng);
    for (int i = 0; i < std::abs(k); ++i) x = std::nextafter(x, k > 0 ? INFINITY : -INFINITY);
    return x;
  };
  auto rv = [&] { return Vec3<double>{u(rng), u(rng), u(rng)}; };
  Query x;
  x.range = static_cast<LineRange>(rsel(rng));
  const Vec3<double> p0 = rv();
  switch (kind) {
    case 0: {
      x.cyl = {p0, rv(), 0.1 + std::fabs(u(rng))};
      x.origin = rv();
      x.second = rv();
      break;
    }
    case 1: {  // vertical axis, the line at distance r (rounded) plus a few ulps
      const double r = 0.25 + std::fabs(u(rng));
      x.cyl = {p0, {p0.x, p0.y, p0.z + 1 + std::fabs(u(rng))}, r};
      x.origin = {nudge(p0.x + r), p0.y + u(rng), p0.z + 0.5};
      x.second = {0, 1, 0.5 * u(rng)};
      break;
    }
    case 2: {  // direction = axis plus a few ulps
      x.cyl = {p0, {p0.x + u(rng), p0.y + u(rng), p0.z + 1}, 0.5};
      const Vec3<double> A = x.cyl.axis();
      x.origin = {p0.x + u(rng), p0.y + u(rng), p0.z + u(rng)};
      x.second = {nudge(A.x), nudge(A.y), nudge(A.z)};
      break;
    }
    case 3: {  // a segment from inside to a point within ulps of the top cap plane z = p1.z
      x.cyl = {p0, {p0.x, p0.y, p0.z + 1}, 0.75};
      x.segment = true;
      x.range = LineRange::segment;
      x.origin = {p0.x + 0.1 * u(rng), p0.y + 0.1 * u(rng), p0.z + 0.5};
      x.second = {p0.x + u(rng), p0.y + u(rng), nudge(p0.z + 1)};
      break;
    }
    case 4: {  // far from the origin
      const Vec3<double> T{1e6 * u(rng), 1e6 * u(rng), 1e6 * u(rng)};
      x.cyl = {p0 + T, rv() + T, 0.1 + std::fabs(u(rng))};
      x.origin = rv() + T;
      x.second = rv();
      break;
    }
    default: {  // direction within ulps of the cap planes (vertical axis)
      x.cyl = {p0, {p0.x, p0.y, p0.z + 1}, 0.5};
      x.origin = {p0.x + u(rng), p0.y + u(rng), p0.z + u(rng)};
      x.second = {u(rng), u(rng), nudge(0.0)};
      break;
    }
  }
  if (x.range == LineRange::segment && !x.segment) {
    x.segment = true;
    x.second = x.origin + x.second;
  }
  return x;
}

}  // namespace

// The bound of every polynomial holds on 6000 inputs, near-degenerate ones included.
BOOST_AUTO_TEST_CASE(error_bounds_hold) {
  const unsigned seed = 4242;
  std::cout << "error_bounds_hold: seed " << seed << "\n";
  std::mt19937_64 rng(seed);
  double worst = 0;
  for (int i = 0; i < 6000; ++i) {
    const Query x = make_query(rng, i % 6);
    const double ratio = worst_error_ratio(x);
    BOOST_TEST_CONTEXT("kind " << i % 6 << " #" << i) { BOOST_TEST(ratio < 1.0); }
    worst = std::max(worst, ratio);
  }
  std::cout << "  largest |error| / bound: " << worst << "\n";
}

// Exact degeneracies on the unit cylinder (axis z, radius 1, z in [0, 1]), binary64 input:
// the static stage must not decide, and the filtered answer is the hand-derived one.
//
//        cap1 z=1  ______
//                 |      |   tangent: x = 1 (touching at one point)
//                 |  .   |   on_wall: direction (0,0,1) at x = 1
//        cap0 z=0 |______|   chord in z = 1, rim grazes, segment ending on the wall
BOOST_AUTO_TEST_CASE(degeneracies_are_left_to_the_exact_stages) {
  const Cylinder<double> unit{{0, 0, 0}, {0, 0, 1}, 1};
  struct Case {
    const char* name;
    Query q;
    Answer expected;
  };
  auto line = [&](Vec3<double> o, Vec3<double> d) { return Query{o, d, false, LineRange::line, unit}; };
  auto ray = [&](Vec3<double> o, Vec3<double> d) { return Query{o, d, false, LineRange::ray, unit}; };
  auto seg = [&](Vec3<double> a, Vec3<double> b) { return Query{a, b, true, LineRange::segment, unit}; };
  const Case cases[] = {
      {"tangent", line({1, -3, 0.5}, {0, 1, 0}), Answer::touching},
      {"tangent_oblique", line({1, -3, 0.25}, {0, 2, 0.25}), Answer::touching},
      {"on_wall", line({1, 0, 0.5}, {0, 0, 1}), Answer::touching},
      {"axis_parallel_inside", line({0.5, 0, 3}, {0, 0, -1}), Answer::overlapping},
      {"chord_in_cap1", line({-2, 0.5, 1}, {1, 0, 0}), Answer::touching},
      {"chord_in_cap0", line({-2, 0, 0}, {1, 0, 0}), Answer::touching},
      {"enter_through_rim1", line({2, 0, 2}, {-1, 0, -1}), Answer::overlapping},  // (1,0,1) then inside
      {"graze_rim1", line({0, 0, 2}, {1, 0, -1}), Answer::touching},  // (t, 0, 2 - t): only (1,0,1)
      {"segment_ends_on_wall", seg({3, 0, 0.5}, {1, 0, 0.5}), Answer::touching},
      {"segment_ends_on_cap1", seg({0, 0, 3}, {0.5, 0, 1}), Answer::touching},
      {"ray_starts_on_wall_outward", ray({1, 0, 0.5}, {1, 0, 0}), Answer::touching},
      {"ray_starts_on_cap0_inward", ray({0.5, 0, 0}, {0, 0, 1}), Answer::overlapping},
      {"segment_starts_on_rim", seg({1, 0, 1}, {2, 0, 2}), Answer::touching},
  };
  for (const Case& c : cases) {
    BOOST_TEST_CONTEXT(c.name) {
      const StaticRun s = run_static(c.q);
      BOOST_TEST(s.usable);
      BOOST_TEST(!s.decided);
      LineStageCounter counter;
      const LineShape shape = filtered(c.q, counter);
      BOOST_TEST(to_string(shape.answer) == to_string(c.expected));
      BOOST_TEST(counter.semi_static == 0u);
      BOOST_TEST(same(shape, exact_shape(c.q)));
    }
  }
  // One ulp off the tangent either side is decided by some stage, and correctly.
  for (double y : {std::nextafter(1.0, 2.0), std::nextafter(1.0, 0.0)}) {
    const Query q = line({-3, y, 0.5}, {1, 0, 0});
    LineStageCounter counter;
    const LineShape shape = filtered(q, counter);
    BOOST_TEST(to_string(shape.answer) == (y > 1 ? "separated" : "overlapping"));
    BOOST_TEST(same(shape, exact_shape(q)));
  }
}

// A configuration with known answers scaled by 2^k (exact in binary64 for these values):
// the answers stay, and the static stage runs only inside its window [2^-150, 2^150].
BOOST_AUTO_TEST_CASE(huge_tiny_and_subnormal_scales) {
  // Radius 3 around the z axis, z in [0, 4]: a chord (overlapping), a tangent (touching), a
  // miss (separated), as lines; the scaled copies must keep them.
  struct Base {
    Vec3<double> o, d;
    Answer answer;
  };
  const Base bases[] = {{{-5, 1, 2}, {1, 0, 0}, Answer::overlapping},
                        {{-5, 3, 2}, {1, 0, 0}, Answer::touching},
                        {{-5, 4, 2}, {1, 0, 0}, Answer::separated},
                        {{-5, 1, 5}, {1, 0, -1}, Answer::overlapping}};  // z = 5 - t, |x| <= 2 sqrt 2
  long static_decided = 0, static_skipped = 0;
  for (int k : {-1070, -1060, -1000, -997, -300, -151, -150, -100, 0, 100, 149, 150, 151, 300, 900, 1000, 1015}) {
    const double s = std::ldexp(1.0, k);
    const Cylinder<double> cyl{{0, 0, 0}, {0, 0, 4 * s}, 3 * s};
    for (const Base& b : bases) {
      // Directions are scaled too (all lengths): t is unchanged.
      const Query q{b.o * s, b.d * s, false, LineRange::line, cyl};
      BOOST_TEST_CONTEXT("2^" << k << " " << to_string(b.answer)) {
        BOOST_REQUIRE(std::isfinite(q.origin.x) && q.origin.x == -5 * s);  // the scaling is exact
        LineStageCounter counter;
        const LineShape shape = filtered(q, counter);
        BOOST_TEST(to_string(shape.answer) == to_string(b.answer));
        const StaticRun st = run_static(q);
        // 4 s and 5 s are the largest length magnitudes (5 s for the origin; 4 s the axis).
        const bool inside_window = k >= -150 && k + 3 <= 150;
        BOOST_TEST(st.usable == inside_window);
        if (st.decided) {
          ++static_decided;
          BOOST_TEST(same(st.shape, exact_shape(q)));
        }
        if (!st.usable) ++static_skipped;
        // Also as Rational input: binary64 values take the same path.
        const auto rq = certified_line_cylinder(Line<Q>{q.origin.map([](double v) { return Q(v); }), q.second.map([](double v) { return Q(v); })},
                                                cyl.map([](double v) { return Q(v); }));
        BOOST_TEST(to_string(rq.answer) == to_string(b.answer));
      }
    }
  }
  std::cout << "huge_tiny_and_subnormal_scales: static decided " << static_decided << ", skipped " << static_skipped << "\n";
  BOOST_TEST(static_decided > 0);
  BOOST_TEST(static_skipped > 0);
  // Mixed magnitudes: a subnormal radius with unit coordinates (window holds: the largest
  // length is 1), and a line far out at 2^1000 with a unit cylinder (outside the window).
  const Cylinder<double> thin{{0, 0, 0}, {0, 0, 1}, 0x1p-1074};
  const Query through{{-1, 0, 0.5}, {1, 0, 0}, false, LineRange::line, thin};
  const Query beside{{-1, 0x1p-1073, 0.5}, {1, 0, 0}, false, LineRange::line, thin};
  LineStageCounter counter;
  BOOST_TEST(to_string(filtered(through, counter).answer) == "overlapping");
  BOOST_TEST(to_string(filtered(beside, counter).answer) == "separated");
  BOOST_TEST(same(filtered(through, counter), exact_shape(through)));
  const Query far{{-0x1p1000, 0.5, 0.5}, {1, 0, 0}, false, LineRange::line, Cylinder<double>{{0, 0, 0}, {0, 0, 1}, 1}};
  BOOST_TEST(!run_static(far).usable);
  BOOST_TEST(to_string(filtered(far, counter).answer) == "overlapping");
}

// The filtered decision equals the Gmpq skeleton on 12000 inputs of six families.
BOOST_AUTO_TEST_CASE(filtered_equals_exact_on_random_and_near_degenerate) {
  const unsigned seed = 99;
  std::cout << "filtered_equals_exact: seed " << seed << "\n";
  std::mt19937_64 rng(seed);
  const char* names[] = {"random", "near-tangent", "near-parallel", "segment near cap", "far translation", "near cap-parallel"};
  LineStageCounter by_kind[6];
  long static_checked = 0;
  for (int i = 0; i < 12000; ++i) {
    const int kind = i % 6;
    const Query x = make_query(rng, kind);
    const LineShape exact = exact_shape(x);
    BOOST_TEST_CONTEXT(names[kind] << " #" << i) {
      BOOST_TEST(same(filtered(x, by_kind[kind]), exact));
      const StaticRun st = run_static(x);
      if (st.decided) {
        ++static_checked;
        BOOST_TEST(same(st.shape, exact));
      }
    }
  }
  for (int k = 0; k < 6; ++k) {
    const LineStageCounter& c = by_kind[k];
    std::cout << "  " << names[k] << ": " << c.calls << " queries, static " << c.semi_static << ", interval " << c.interval
              << ", exact " << c.exact << "\n";
  }
  // The stage must carry the plain random inputs (a filter that never decides is no filter).
  BOOST_TEST(by_kind[0].semi_static > by_kind[0].calls * 9 / 10);
  BOOST_TEST(static_checked > 4000);
}

// Rational input is recognised as binary64 exactly when it is one (then the double path runs).
BOOST_AUTO_TEST_CASE(binary64_recognition) {
  double x = 0;
  const Q two(2);
  auto pow2 = [&](int k) {
    Q p(1);
    for (int i = 0; i < std::abs(k); ++i) p = k > 0 ? Q(p * two) : Q(p / two);
    return p;
  };
  BOOST_TEST(binary64_value(Q(0), x));
  BOOST_TEST(x == 0.0);
  BOOST_TEST((binary64_value(pow2(-1074), x) && x == 0x1p-1074));            // smallest subnormal
  BOOST_TEST((binary64_value(Q(-3) * pow2(-1074), x) && x == -0x3p-1074));   // negative subnormal
  BOOST_TEST(!binary64_value(pow2(-1075), x));                               // half of it
  BOOST_TEST((binary64_value(pow2(53) - Q(1), x) && x == 0x1.fffffffffffffp+52));
  BOOST_TEST(!binary64_value(pow2(53) + Q(1), x));                           // 54 significant bits
  BOOST_TEST((binary64_value((pow2(53) - Q(1)) * pow2(971), x) && x == 0x1.fffffffffffffp+1023));  // DBL_MAX
  BOOST_TEST(!binary64_value(pow2(1024), x));
  BOOST_TEST(!binary64_value(parse_rational("0.1"), x));
  BOOST_TEST(!binary64_value(Q(1) / Q(3), x));
  BOOST_TEST((binary64_value(parse_rational("-2.5"), x) && x == -2.5));
}
