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
//     three stages are printed;
//   - the endpoints' nearest doubles (certified/detail/line_nearest.hpp) on the same kinds and
//     on rotated tangencies, rims and cap planes: each is the nearest (checked exactly here),
//     equals the MPFR rounding of the exact value, and the exact value satisfies its feature;
//     an endpoint on a midpoint falls back and ties to even; random input takes the fast proof.
#define BOOST_TEST_MODULE line_static_filter
#include <boost/test/unit_test.hpp>

#include <bit>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <optional>
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
    std::cout << "  " << names[k] << ": " << c.calls << " queries, static " << c.semi_static << ", double-double " << c.double_double
              << ", interval " << c.interval << ", exact " << c.exact << "\n";
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

// ---- The double-double escalation ------------------------------------------------------------

namespace {

// The exact value of a double-double (hi + lo) as a rational.
Q exact_dd(const DD& v) { return Q(v.v.x[0]) + Q(v.v.x[1]); }

SV3<DD> ddv(const Vec3<double>& v) { return {DD(v.x), DD(v.y), DD(v.z)}; }
SV3<DD> ddd(const Vec3<double>& p, const Vec3<double>& q) {
  return {dd_difference(p.x, q.x), dd_difference(p.y, q.y), dd_difference(p.z, q.z)};
}

// Largest |double-double - exact| / bound over the decision polynomials of one query, with
// the bound recomputed here from its definition (line_double_double.hpp: C mlen^i mdir^j,
// mlen and mdir the largest high parts, at least 2^-120).
double worst_dd_error_ratio(const Query& x) {
  using PD = CircularPolynomials<DD>;
  using PQ = CircularPolynomials<Q>;
  const SV3<DD> A = ddd(x.cyl.p1, x.cyl.p0), w = ddd(x.origin, x.cyl.p0), w1 = ddd(x.origin, x.cyl.p1);
  const SV3<Q> Aq = dq(x.cyl.p1, x.cyl.p0), wq = dq(x.origin, x.cyl.p0), w1q = dq(x.origin, x.cyl.p1);
  const SV3<DD> d = x.segment ? ddd(x.second, x.origin) : ddv(x.second);
  const SV3<Q> d_q = x.segment ? dq(x.second, x.origin) : svq(x.second);
  const SV3<DD> e0 = x.segment ? ddd(x.second, x.cyl.p0) : ddv({0, 0, 0}), e1 = x.segment ? ddd(x.second, x.cyl.p1) : ddv({0, 0, 0});
  const SV3<Q> e0q = x.segment ? dq(x.second, x.cyl.p0) : svq({0, 0, 0}), e1q = x.segment ? dq(x.second, x.cyl.p1) : svq({0, 0, 0});
  const DD r(x.cyl.radius);
  const Q rq(x.cyl.radius);
  auto hmax = [](const SV3<DD>& v) { return std::max({std::fabs(v.x.hi()), std::fabs(v.y.hi()), std::fabs(v.z.hi())}); };
  const double ml = std::max({0x1p-120, std::fabs(x.cyl.radius), hmax(A), hmax(w), hmax(w1), hmax(e0), hmax(e1)});
  const double md = std::max(0x1p-120, hmax(d));
  double worst = 0;
  auto check = [&](const DD& v, const Q& exact, const StaticBound& b) {
    const double bound = b.C * std::pow(ml, b.deg_len) * std::pow(md, b.deg_dir);
    const Q err = exact_dd(v) - exact;
    worst = std::max(worst, CGAL::to_double((err < 0 ? Q(-err) : err) / Q(bound)));
    // The sign rule of the stage: |hi| > bound decides, and decides right.
    if (std::fabs(v.hi()) > bound) BOOST_TEST(CGAL::sign(exact) == (v.hi() > 0 ? CGAL::POSITIVE : CGAL::NEGATIVE));
  };
  namespace db = line_dd_bounds;
  check(PD::a(A, d), PQ::a(Aq, d_q), db::a);
  check(PD::disc(A, w, d, r), PQ::disc(Aq, wq, d_q, rq), db::disc);
  check(PD::excess(A, w, r), PQ::excess(Aq, wq, rq), db::excess);
  check(PD::dot(d, A), PQ::dot(d_q, Aq), db::dot_ld);
  check(PD::dot(w, A), PQ::dot(wq, Aq), db::dot_ll);
  check(PD::dot(w1, A), PQ::dot(w1q, Aq), db::dot_ll);
  check(PD::b(A, w, d), PQ::b(Aq, wq, d_q), db::b);
  check(PD::cap_excess(A, w, d, r), PQ::cap_excess(Aq, wq, d_q, rq), db::cap_excess);
  check(PD::cap_excess(A, w1, d, r), PQ::cap_excess(Aq, w1q, d_q, rq), db::cap_excess);
  check(PD::cap_side(A, w, d), PQ::cap_side(Aq, wq, d_q), db::cap_side);
  check(PD::cap_side(A, w1, d), PQ::cap_side(Aq, w1q, d_q), db::cap_side);
  check(PD::excess(A, e0, r), PQ::excess(Aq, e0q, rq), db::excess);
  check(PD::b(A, e0, d), PQ::b(Aq, e0q, d_q), db::b);
  check(PD::dot(e0, A), PQ::dot(e0q, Aq), db::dot_ll);
  check(PD::dot(e1, A), PQ::dot(e1q, Aq), db::dot_ll);
  return worst;
}

// An integer frame: M = N R for the rotation R of the quaternion (a, b, c, d), N = a^2 + b^2 +
// c^2 + d^2, so M^T M = N^2 I. Mapping every point by X -> M X + T and the radius by r -> N r
// keeps every incidence, tangency and side exactly (all lengths scale by N), and keeps small
// dyadic coordinates exact in binary64.
struct Frame {
  long m[3][3];
  long N;
  Vec3<double> T;
};
Frame frame(long a, long b, long c, long d, Vec3<double> T) {
  Frame f{{{a * a + b * b - c * c - d * d, 2 * (b * c - a * d), 2 * (b * d + a * c)},
           {2 * (b * c + a * d), a * a - b * b + c * c - d * d, 2 * (c * d - a * b)},
           {2 * (b * d - a * c), 2 * (c * d + a * b), a * a - b * b - c * c + d * d}},
          a * a + b * b + c * c + d * d,
          T};
  return f;
}
Vec3<double> apply_linear(const Frame& f, const Vec3<double>& v) {
  const double x[3] = {v.x, v.y, v.z};
  double y[3];
  for (int i = 0; i < 3; ++i) y[i] = f.m[i][0] * x[0] + f.m[i][1] * x[1] + f.m[i][2] * x[2];  // small dyadics: exact
  return {y[0], y[1], y[2]};
}
Vec3<double> apply_point(const Frame& f, const Vec3<double>& p) { return apply_linear(f, p) + f.T; }

const Frame frames[] = {frame(1, 0, 0, 0, {0, 0, 0}), frame(1, 2, 3, 4, {0.5, -3, 7}), frame(3, 1, -2, 5, {-11, 0.25, 2}),
                        frame(2, -1, 1, 1, {100, 100, -100})};

// A base configuration around the cylinder of axis z, z in [0, 4], radius 2 (before scaling),
// with its answer; `grow` is the answer when the radius grows by a few ulps, `shrink` when it
// shrinks.
struct Base {
  const char* name;
  Vec3<double> o, second;
  LineRange range;
  Answer exact, grow, shrink;
};
//   tangent      x = 2, through (2, 0, 2): touching; inside when r grows, apart when it shrinks
//   rim graze    (2 + t, 0, 4 - t): only the rim point (2, 0, 4)
//   cap tangent  in the cap plane z = 4, tangent to the rim circle at (0, 2, 4): the cap plane
//                is boundary, so touching when r grows too
const Base bases[] = {
    {"tangent_line", {2, -3, 0.5}, {0, 2, 1}, LineRange::line, Answer::touching, Answer::overlapping, Answer::separated},
    {"tangent_ray", {2, -3, 0.5}, {0, 2, 1}, LineRange::ray, Answer::touching, Answer::overlapping, Answer::separated},
    {"tangent_segment", {2, -3, 0.5}, {2, 3, 3.5}, LineRange::segment, Answer::touching, Answer::overlapping, Answer::separated},
    {"rim_graze", {1, 0, 5}, {1, 0, -1}, LineRange::line, Answer::touching, Answer::overlapping, Answer::separated},
    {"rim_graze_segment", {1, 0, 5}, {3, 0, 3}, LineRange::segment, Answer::touching, Answer::overlapping, Answer::separated},
    {"cap_plane_rim_tangent", {-3, 2, 4}, {1, 0, 0}, LineRange::line, Answer::touching, Answer::touching, Answer::separated},
};

// Whether one of the decision polynomials of the stage is exactly zero (Gmpq).
bool some_polynomial_is_zero(const Query& x) {
  using PQ = CircularPolynomials<Q>;
  const SV3<Q> A = dq(x.cyl.p1, x.cyl.p0), w = dq(x.origin, x.cyl.p0), w1 = dq(x.origin, x.cyl.p1);
  const SV3<Q> d = x.segment ? dq(x.second, x.origin) : svq(x.second);
  const Q r(x.cyl.radius);
  Q v[] = {PQ::a(A, d), PQ::disc(A, w, d, r), PQ::excess(A, w, r), PQ::dot(d, A), PQ::dot(w, A), PQ::dot(w1, A),
           PQ::b(A, w, d), PQ::cap_excess(A, w, d, r), PQ::cap_excess(A, w1, d, r), PQ::cap_side(A, w, d), PQ::cap_side(A, w1, d)};
  bool zero = false;
  for (const Q& q : v) zero = zero || CGAL::sign(q) == CGAL::ZERO;
  if (x.segment) {
    const SV3<Q> e0 = dq(x.second, x.cyl.p0), e1 = dq(x.second, x.cyl.p1);
    Q s[] = {PQ::excess(A, e0, r), PQ::b(A, e0, d), PQ::dot(e0, A), PQ::dot(e1, A)};
    for (const Q& q : s) zero = zero || CGAL::sign(q) == CGAL::ZERO;
  }
  return zero;
}

Query in_frame(const Frame& f, const Base& b, double radius) {
  Query x;
  x.range = b.range;
  x.segment = b.range == LineRange::segment;
  x.origin = apply_point(f, b.o);
  x.second = x.segment ? apply_point(f, b.second) : apply_linear(f, b.second);
  x.cyl = {apply_point(f, {0, 0, 0}), apply_point(f, {0, 0, 4}), radius};
  return x;
}

}  // namespace

// The double-double bound holds (|computed - exact| < bound) on near-degenerate inputs, where
// the values are small and the test is sharp; and where |hi| > bound the sign is right.
BOOST_AUTO_TEST_CASE(double_double_error_bounds_hold) {
  const unsigned seed = 777;
  std::cout << "double_double_error_bounds_hold: seed " << seed << "\n";
  std::mt19937_64 rng(seed);
  double worst = 0;
  for (int i = 0; i < 3000; ++i) {
    const Query x = make_query(rng, i % 6);
    const double ratio = worst_dd_error_ratio(x);
    BOOST_TEST_CONTEXT("kind " << i % 6 << " #" << i) { BOOST_TEST(ratio < 1.0); }
    worst = std::max(worst, ratio);
  }
  std::cout << "  largest |error| / bound: " << worst << "\n";
  // The constants derived by hand (line_dd_bounds): C = 2 (k + 1) N 2^-100.
  BOOST_TEST(line_dd_bounds::excess.C == 2 * 9 * 15 * 0x1p-100);  // |x x A|^2 k 7, N 12; (r r)(A.A) k 5, N 3
}

// Exact constructions in rotated integer frames: the exact configuration is touching (an exact
// zero, decided exactly), and the radius moved 1, 2 or 3 ulps gives the answer known by
// construction, decided by the double or double-double stage, never by exact arithmetic; the
// shape equals the Gmpq skeleton's.
BOOST_AUTO_TEST_CASE(rotated_exact_tangencies_moved_by_ulps) {
  for (const Frame& f : frames) {
    for (const Base& b : bases) {
      const double R = 2.0 * static_cast<double>(f.N);
      BOOST_TEST_CONTEXT(b.name << " in frame N = " << f.N) {
        {
          const Query x = in_frame(f, b, R);
          LineStageCounter c;
          const LineShape s = filtered(x, c);
          BOOST_TEST(to_string(s.answer) == to_string(b.exact));
          BOOST_TEST(same(s, exact_shape(x)));
          BOOST_TEST(c.exact == 1u);  // the exact zero
        }
        for (int k = 1; k <= 3; ++k) {
          for (const bool grow : {true, false}) {
            double r = R;
            for (int i = 0; i < k; ++i) r = std::nextafter(r, grow ? INFINITY : 0.0);
            const Query x = in_frame(f, b, r);
            LineStageCounter c;
            const LineShape s = filtered(x, c);
            BOOST_TEST_CONTEXT((grow ? "+" : "-") << k << " ulps") {
              BOOST_TEST(to_string(s.answer) == to_string(grow ? b.grow : b.shrink));
              BOOST_TEST(same(s, exact_shape(x)));
              // Only an exact zero takes exact arithmetic. The cap-plane line keeps its zeros (it
              // lies in the cap plane: d.A = 0, w1.A = 0); the others have none.
              if (!some_polynomial_is_zero(x)) BOOST_TEST(c.exact == 0u);
              if (std::string(b.name) != "cap_plane_rim_tangent") BOOST_TEST(!some_polynomial_is_zero(x));
              BOOST_TEST(c.interval == 0u);
            }
          }
        }
      }
    }
  }
}

// Tangent, rim and cap-plane lines in rotated frames with one coordinate of the line moved by
// 1..3 ulps: the expected shape is the Gmpq skeleton's (an independent exact evaluation of
// other polynomials); exact arithmetic is needed only for exact zeros, subnormal inputs and
// second-order contacts.
BOOST_AUTO_TEST_CASE(rotated_lines_moved_by_ulps_agree_with_gmpq) {
  const unsigned seed = 31;
  std::cout << "rotated_lines_moved_by_ulps: seed " << seed << "\n";
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> coord(0, 5), ulps(1, 3), sign(0, 1);
  LineStageCounter total;
  int outside_window = 0, nonzero = 0, nonzero_exact = 0;
  for (int i = 0; i < 2000; ++i) {
    const Frame& f = frames[i % 4];
    const Base& b = bases[(i / 4) % 6];
    Query x = in_frame(f, b, 2.0 * static_cast<double>(f.N));
    const int c = coord(rng), k = ulps(rng);
    double* slot[6] = {&x.origin.x, &x.origin.y, &x.origin.z, &x.second.x, &x.second.y, &x.second.z};
    for (int j = 0; j < k; ++j) *slot[c] = std::nextafter(*slot[c], sign(rng) ? INFINITY : -INFINITY);
    // A coordinate 0 moved by ulps is subnormal: outside the double-double window (every nonzero
    // input in [2^-120, 2^100]), so such inputs may take exact arithmetic too.
    const bool exact_zero = some_polynomial_is_zero(x);
    const double* v[] = {&x.origin.x, &x.origin.y, &x.origin.z, &x.second.x, &x.second.y, &x.second.z};
    bool window = true;
    for (const double* p : v) window = window && (*p == 0 || std::fabs(*p) >= 0x1p-120);
    if (!window) ++outside_window;
    LineStageCounter cnt;
    BOOST_TEST_CONTEXT(b.name << " frame " << f.N << " coordinate " << c << " moved " << k << " ulps") {
      BOOST_TEST(same(filtered(x, cnt), exact_shape(x)));
      BOOST_TEST(cnt.interval == 0u);
    }
    total += cnt;
    if (!exact_zero && window) {
      ++nonzero;
      if (cnt.exact != 0) ++nonzero_exact;
    }
  }
  std::cout << "  static " << total.semi_static << ", double-double " << total.double_double << ", exact " << total.exact
            << "; inputs with a subnormal coordinate " << outside_window << "; no exact zero, in the window: " << nonzero
            << ", of which exact " << nonzero_exact << "\n";
  BOOST_TEST(total.double_double > 1000u);
  // Without an exact zero, exact arithmetic is the exception: a value below the double-double
  // bound (about 2^-92 of the magnitudes) is a second-order contact, such as a rim approached
  // tangentially, where one ulp moves the cap point along the rim circle.
  BOOST_TEST(nonzero_exact * 10 < nonzero);
}

// Lines in a cap plane of an oriented cylinder, computed in double and rounded, then moved
// 0..3 ulps per coordinate: d.A and w.A are about 2^-53 of their magnitudes, so the cap
// polynomial |A x (w x d)|^2 - r^2 (d.A)^2 is about 2^-106 of them, below the double-double
// bound. Its factored form (line_static_filter.hpp, "A line in or near a cap plane") decides
// it: exact arithmetic only for exact zeros and inputs outside the double-double window; every
// shape equals the Gmpq skeleton's.
BOOST_AUTO_TEST_CASE(oriented_lines_in_a_cap_plane_are_decided_without_exact_arithmetic) {
  const unsigned seed = 4242;
  std::cout << "oriented_lines_in_a_cap_plane: seed " << seed << "\n";
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_int_distribution<int> ulps(-3, 3);
  auto rv = [&] { return Vec3<double>{u(rng), u(rng), u(rng)}; };
  auto unit = [](const Vec3<double>& v) { return v * (1 / std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z)); };
  auto cross = [](const Vec3<double>& a, const Vec3<double>& b) {
    return Vec3<double>{a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
  };
  auto nudge = [&](double v) {
    const int k = ulps(rng);
    for (int i = 0; i < std::abs(k); ++i) v = std::nextafter(v, k > 0 ? INFINITY : -INFINITY);
    return v;
  };
  LineStageCounter total;
  int cases = 0, small_cap_dots = 0, nonzero = 0, nonzero_exact = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec3<double> p0 = rv() * 10.0, p1 = p0 + rv() * 2.0;
    const double r = 0.25 + std::fabs(u(rng));
    const Vec3<double> A = p1 - p0, n = unit(cross(A, rv())), m = unit(cross(A, n));
    // In the plane of cap0 (even i) or cap1 (odd i), through the disk or beside it.
    const Vec3<double> P = i % 2 ? p1 : p0;
    Query x;
    x.range = static_cast<LineRange>(i % 3);
    x.segment = x.range == LineRange::segment;
    x.origin = P + n * (1.5 * r * u(rng));
    x.second = m + n * (0.5 * u(rng));
    if (x.range == LineRange::ray && i % 4 == 1) x.second = x.second * -1.0;
    if (x.segment) x.origin = x.origin - x.second * (2 * r), x.second = x.origin + x.second * (4 * r);  // a chord's ends
    for (double* c : {&x.origin.x, &x.origin.y, &x.origin.z, &x.second.x, &x.second.y, &x.second.z}) *c = nudge(*c);
    x.cyl = {p0, p1, r};
    ++cases;
    // The construction puts the line in the cap plane to rounding: |d.A| well below |d||A|.
    const Vec3<double> d = x.segment ? x.second - x.origin : x.second;
    const double dA = d.x * A.x + d.y * A.y + d.z * A.z;
    if (std::fabs(dA) < 0x1p-40 * std::sqrt(A.x * A.x + A.y * A.y + A.z * A.z)) ++small_cap_dots;
    LineStageCounter cnt;
    BOOST_TEST_CONTEXT("case " << i) { BOOST_TEST(same(filtered(x, cnt), exact_shape(x))); }
    total += cnt;
    if (!some_polynomial_is_zero(x)) {
      ++nonzero;
      if (cnt.exact != 0) ++nonzero_exact;
    }
  }
  std::cout << "  static " << total.semi_static << ", double-double " << total.double_double << ", exact " << total.exact
            << "; no exact zero: " << nonzero << ", of which exact " << nonzero_exact << "\n";
  BOOST_TEST(small_cap_dots == cases);
  BOOST_TEST(nonzero > 1900);
  // Before the factored form every one of these took exact arithmetic.
  BOOST_TEST(nonzero_exact * 100 < nonzero);
}

// ---- The endpoints' nearest doubles (certified/detail/line_nearest.hpp) ---------------------

namespace {

// Sign of alpha + beta sqrt(gamma) (gamma >= 0), by squaring: written here, not the library's.
int sign_root(const Q& alpha, const Q& beta, const Q& gamma) {
  const int sa = CGAL::sign(alpha), sb = gamma == 0 ? 0 : CGAL::sign(beta);
  if (sb == 0) return sa;
  if (sa == 0 || sa == sb) return sb;
  const int s = CGAL::sign(Q(alpha * alpha - beta * beta * gamma));
  return sa > 0 ? s : -s;
}

// The double nearest to x = alpha + beta sqrt(gamma), checked exactly: x lies between the
// midpoints to n's neighbours, and on one of them only if n is even (ties to even).
bool is_nearest(double n, const QuadraticNumber& x) {
  const Q alpha = x.alpha, beta = x.beta, gamma(x.gamma);
  const Q lo = (Q(std::nextafter(n, -INFINITY)) + Q(n)) / 2, hi = (Q(n) + Q(std::nextafter(n, INFINITY))) / 2;
  const int below = sign_root(Q(alpha - lo), beta, gamma), above = sign_root(Q(alpha - hi), beta, gamma);
  if (below < 0 || above > 0) return false;
  if (below == 0 || above == 0) {
    int e = 0;
    const double m = std::frexp(n, &e);  // n = m 2^e, 2^53 m an integer
    return std::fmod(std::ldexp(m, 53), 2.0) == 0;
  }
  return true;
}

// The endpoint satisfies its feature exactly: a root of the tube quadratic (textbook
// coefficients, in Q(sqrt gamma)), the cap plane's equation, 0 or 1.
bool satisfies_feature(const Query& x, const CertifiedEndpoint& e) {
  const Vec3<Q> P0{Q(x.cyl.p0.x), Q(x.cyl.p0.y), Q(x.cyl.p0.z)}, P1{Q(x.cyl.p1.x), Q(x.cyl.p1.y), Q(x.cyl.p1.z)};
  const Vec3<Q> O{Q(x.origin.x), Q(x.origin.y), Q(x.origin.z)}, S{Q(x.second.x), Q(x.second.y), Q(x.second.z)};
  const Vec3<Q> A = P1 - P0, w = O - P0, d = x.segment ? Vec3<Q>(S - O) : S;
  const Vec3<Q> wa = cross(w, A), da = cross(d, A);
  const Q AA = dot(A, A), r(x.cyl.radius);
  const Q qa = dot(da, da), qb = Q(2) * dot(wa, da), qc = dot(wa, wa) - r * r * AA, sw = dot(w, A), sd = dot(d, A);
  const QuadraticNumber t = e.value();
  const Q g(t.gamma), a = t.alpha, b = t.beta;
  // q(t) = qa t^2 + qb t + qc = P + R sqrt(g) with t^2 = a^2 + b^2 g + 2 a b sqrt(g).
  const Q P = qa * (a * a + b * b * g) + qb * a + qc, R = qa * Q(2) * a * b + qb * b;
  const bool on_wall = P == 0 && (R == 0 || g == 0);
  auto on_plane = [&](const Q& level) { return sw + a * sd == level && (b * sd == 0 || g == 0); };  // sw + t sd = level
  switch (e.feature) {
    case LineFeature::wall: return on_wall;
    case LineFeature::cap0: return on_plane(0);
    case LineFeature::cap1: return on_plane(AA);
    case LineFeature::rim0: return on_wall && on_plane(0);
    case LineFeature::rim1: return on_wall && on_plane(AA);
    case LineFeature::origin: return b == 0 && a == 0;
    case LineFeature::end: return b == 0 && a == 1;
    case LineFeature::none: break;
  }
  return false;
}

CertifiedLineResult certified(const Query& x) {
  switch (x.range) {
    case LineRange::ray: return certified_line_cylinder(Ray<double>{x.origin, x.second}, x.cyl);
    case LineRange::segment: return certified_line_cylinder(Segment<double>{x.origin, x.second}, x.cyl);
    case LineRange::line: break;
  }
  return certified_line_cylinder(Line<double>{x.origin, x.second}, x.cyl);
}

struct NearestStats {
  long endpoints = 0, range_bounds = 0, fast = 0, exact_rational = 0, mpfr = 0;
};

// Every endpoint: its exact value satisfies its feature; its nearest double is the nearest
// (exact check) and equals the MPFR rounding of the exact value (the computation used before).
void check_endpoints(const Query& x, NearestStats& st) {
  const CertifiedLineResult r = certified(x);
  BOOST_TEST(to_string(r.answer) == to_string(exact_shape(x).answer));
  if (r.answer == Answer::separated) return;
  BOOST_REQUIRE(r.in && r.out);
  for (const CertifiedEndpoint* e : {&*r.in, &*r.out}) {
    ++st.endpoints;
    const QuadraticNumber v = e->value();
    BOOST_TEST(satisfies_feature(x, *e));
    BOOST_TEST(is_nearest(e->nearest, v));
    BOOST_TEST(e->nearest == nearest_double(v));
    if (e->feature == LineFeature::origin || e->feature == LineFeature::end) ++st.range_bounds;
    switch (e->rounding) {
      case EndpointRounding::double_double: ++st.fast; break;
      case EndpointRounding::exact_rational: ++st.exact_rational; break;
      case EndpointRounding::mpfr: ++st.mpfr; break;
    }
  }
  // Both values from one exact quadric: the same numbers as each endpoint's own.
  const auto [in, out] = r.exact_values();
  BOOST_TEST(in.to_string() == r.in->value().to_string());
  BOOST_TEST(out.to_string() == r.out->value().to_string());
}

void print(const char* what, const NearestStats& st) {
  std::cout << "  " << what << ": " << st.endpoints << " endpoints (0 or 1: " << st.range_bounds << "), double-double "
            << st.fast << ", rational " << st.exact_rational << ", mpfr " << st.mpfr << "\n";
}

}  // namespace

// Random lines, rays and segments and the near-degenerate kinds of make_query (near-tangent,
// nearly parallel to the axis, a segment ending near a cap plane, far translations, nearly
// parallel to the caps): every endpoint as above. On random input the double-double proof
// must round nearly every endpoint (the test fails if it silently always fell back).
BOOST_AUTO_TEST_CASE(endpoint_nearest_doubles_on_random_and_near_degenerate_input) {
  const unsigned seed = 2611;
  std::cout << "endpoint_nearest_doubles: seed " << seed << "\n";
  std::mt19937_64 rng(seed);
  NearestStats by_kind[6];
  for (int i = 0; i < 6000; ++i) {
    const int kind = i % 6;
    const Query x = make_query(rng, kind);
    BOOST_TEST_CONTEXT("kind " << kind << " #" << i) { check_endpoints(x, by_kind[kind]); }
  }
  const char* names[6] = {"random", "near-tangent", "near-axis direction", "segment end near a cap plane", "far translation",
                          "near-cap direction"};
  for (int k = 0; k < 6; ++k) print(names[k], by_kind[k]);
  const NearestStats& random = by_kind[0];
  BOOST_TEST(random.endpoints > 500);
  // Every random endpoint other than 0 and 1 is rounded in double-double.
  BOOST_TEST(random.fast == random.endpoints - random.range_bounds);
  BOOST_TEST(by_kind[4].fast * 10 > (by_kind[4].endpoints - by_kind[4].range_bounds) * 9);
}

// Tangent, rim and cap-plane configurations in rotated frames, exact and moved by 1..3 ulps,
// and lines in an oriented cap plane: every endpoint as above (here many endpoints are exact
// tangent points, rims and cap chords, rounded through the rational or MPFR).
BOOST_AUTO_TEST_CASE(endpoint_nearest_doubles_near_tangencies_rims_and_caps) {
  std::mt19937_64 rng(97);
  std::uniform_int_distribution<int> coord(0, 5), ulps(0, 3), sign(0, 1);
  NearestStats st;
  for (int i = 0; i < 1200; ++i) {
    const Frame& f = frames[i % 4];
    const Base& b = bases[(i / 4) % 6];
    Query x = in_frame(f, b, 2.0 * static_cast<double>(f.N));
    const int c = coord(rng), k = ulps(rng);
    double* slot[6] = {&x.origin.x, &x.origin.y, &x.origin.z, &x.second.x, &x.second.y, &x.second.z};
    for (int j = 0; j < k; ++j) *slot[c] = std::nextafter(*slot[c], sign(rng) ? INFINITY : -INFINITY);
    BOOST_TEST_CONTEXT(b.name << " frame " << f.N << " coordinate " << c << " moved " << k << " ulps") { check_endpoints(x, st); }
  }
  print("rotated tangencies, rims, cap planes", st);
  BOOST_TEST(st.endpoints > 1000);
  BOOST_TEST(st.fast > 0);
}

// Cap parameters placed on and near a midpoint between two doubles. The line (-1 + t, -y, -z)
// against the cylinder from the origin to (1, 1, 1) (or (1, 1, 0)) enters through cap0 at
// t = 1 + y + z: on the midpoint 1 + 2^-53 the proof must fail (the polynomial is zero there)
// and the tie goes to the even 1; 2^-110 above it is below the double-double bound (it
// fails too, and the rational rounds up); 2^-80 above it the proof rounds up by itself.
BOOST_AUTO_TEST_CASE(endpoint_on_and_near_a_midpoint) {
  struct Case {
    double y, z;
    Vec3<double> p1;
    double nearest;
    EndpointRounding rounding;
    const char* exact;
  };
  const Case cases[] = {
      {0x1p-53, 0, {1, 1, 0}, 1.0, EndpointRounding::exact_rational, "9007199254740993/9007199254740992"},
      {0x1p-53, 0x1p-110, {1, 1, 1}, 1 + 0x1p-52, EndpointRounding::exact_rational,
       "1298074214633707051247812158160897/1298074214633706907132624082305024"},
      {0x1p-53, 0x1p-80, {1, 1, 1}, 1 + 0x1p-52, EndpointRounding::double_double,
       "1208925819614629308923905/1208925819614629174706176"},
  };
  for (const Case& k : cases) {
    BOOST_TEST_CONTEXT("z = " << k.z) {
      Query x;
      x.origin = {-1, -k.y, -k.z};
      x.second = {1, 0, 0};
      x.cyl = {{0, 0, 0}, k.p1, 1.0};
      const CertifiedLineResult r = certified(x);
      BOOST_REQUIRE(r.in.has_value());
      BOOST_TEST(to_string(r.in->feature) == "cap0");
      BOOST_TEST(r.in->exact() == k.exact);
      BOOST_TEST(r.in->nearest == k.nearest);
      BOOST_TEST(to_string(r.in->rounding) == to_string(k.rounding));
      BOOST_TEST(is_nearest(r.in->nearest, r.in->value()));
      NearestStats st;
      check_endpoints(x, st);
    }
  }
}

// Lines tangent to an axis-aligned cylinder at their own origin, and moved off it by 1..4 ulps
// of the offset (the benchmark's near-tangent family): the origin is the foot of the
// perpendicular, so b = 0 and the roots are 0 (tangent) or about +-2^-25 (a chord of a few
// ulps' depth), where |p| at the midpoints (about 2^-100) is below the double-double bound.
//   x = p0.x + r (+- ulps), y = p0.y + t, z = p0.z + 1/2 + t dz;  axis p0 + (0, 0, s)
// b = 0 exactly ((w x A).(d x A) with w x A along y, d x A along x). Every endpoint as
// above; a tangent point (touching: t = 0) is proved by the sign of b alone: it
// keeps its source (rounded without the exact value) and is rounded exactly.
BOOST_AUTO_TEST_CASE(endpoint_nearest_doubles_tangent_at_the_foot_point) {
  std::mt19937_64 rng(101);
  std::uniform_real_distribution<double> u(-1, 1);
  auto rv = [&] { return Vec3<double>{u(rng), u(rng), u(rng)}; };
  NearestStats st;
  long tangent_points = 0;
  for (int i = 0; i < 400; ++i) {
    const Vec3<double> p0 = rv();
    const double r = 0.25 + std::fabs(u(rng));
    double off = r;
    for (int k = 0; k < i % 5; ++k) off = std::nextafter(off, i % 2 ? 2.0 : 0.0);
    Query x;
    x.cyl = {p0, {p0.x, p0.y, p0.z + 1}, r};
    x.origin = {p0.x + off, p0.y, p0.z + 0.5};
    x.second = {0, 1, 0.5 * u(rng)};
    BOOST_TEST_CONTEXT("#" << i << " moved " << i % 5 << " ulps") {
      check_endpoints(x, st);
      const CertifiedLineResult r = certified(x);
      if (r.answer == Answer::touching) {  // tangent (the origin's x is rounded: not every i % 5 = 0)
        BOOST_REQUIRE(r.in && r.out);
        for (const CertifiedEndpoint* e : {&*r.in, &*r.out}) {
          ++tangent_points;
          BOOST_TEST(e->nearest == 0.0);
          BOOST_TEST(e->value().to_string() == "0");
          BOOST_TEST(to_string(e->rounding) == "exact_rational");
          BOOST_TEST(e->source() != nullptr);  // not through the exact quadric
        }
      }
    }
  }
  print("tangent at the foot point", st);
  std::cout << "  tangent points: " << tangent_points << "\n";
  BOOST_TEST(tangent_points > 40);
}

// The fused product (DDFused: the exact error of a product by one fused multiply-add) gives the
// Dekker product's results bit for bit, so the proof of line_double_double.hpp covers both: every
// endpoint proof of the queries above, run with each product, proves the same double or fails
// alike. On a processor without FMA only the Dekker proofs run (the count says so).
BOOST_AUTO_TEST_CASE(fused_and_dekker_products_prove_the_same_endpoints) {
  std::mt19937_64 rng(4099);
  long compared = 0, proved = 0;
  for (int i = 0; i < 6000; ++i) {
    const Query x = make_query(rng, i % 6);
    StaticCircularSigns s(x.origin, x.second, x.segment, x.cyl, /*escalate=*/true);
    if (!s.usable()) continue;
    const LineShape shape = line_shape_from(s, x.range);
    if (shape.answer == Answer::separated || s.double_double_leaves() == nullptr) continue;
    for (const BoundKind k : {shape.in, shape.out}) {
      if (k == BoundKind::range_lo || k == BoundKind::range_hi) continue;
      LineNearest n(s);
      const std::optional<ProvedNearest> dekker = n.with_product(k, shape.tube, false);
      if (dekker) ++proved;
      if (!has_fused_multiply_add()) continue;
      const std::optional<ProvedNearest> fused = n.with_product(k, shape.tube, true);
      ++compared;
      BOOST_TEST_CONTEXT("kind " << i % 6 << " #" << i) {
        BOOST_TEST(fused.has_value() == dekker.has_value());
        if (fused && dekker) BOOST_TEST(std::bit_cast<std::uint64_t>(fused->nearest) == std::bit_cast<std::uint64_t>(dekker->nearest));
      }
    }
  }
  std::cout << "fused and Dekker products: " << compared << " endpoint proofs compared (FMA "
            << (has_fused_multiply_add() ? "present" : "absent") << "), " << proved << " proved\n";
  BOOST_TEST(proved > 2000);
  if (has_fused_multiply_add()) BOOST_TEST(compared > 2000);
}

namespace {
// One product in each form, each compiled where FMA is used (the same dispatch as the proofs).
#if CERTCYL_FUSED_DISPATCH
[[gnu::target("fma"), gnu::flatten]] DD fused_product(const DD& x, const DD& y) { return DD(DDFused(x) * DDFused(y)); }
#endif
}  // namespace

// Products over the whole window of line_double_double.hpp (magnitudes 2^-120 .. 2^100, low
// parts up to half an ulp, every sign): the fused product equals Dekker's bit for bit.
BOOST_AUTO_TEST_CASE(fused_product_equals_dekker_product_bit_for_bit) {
  if (!has_fused_multiply_add()) {
    BOOST_TEST_MESSAGE("no FMA on this processor: the Dekker product alone is used");
    return;
  }
#if CERTCYL_FUSED_DISPATCH
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> mant(1, 2), half(-0.5, 0.5);
  std::uniform_int_distribution<int> ex(-60, 50), sign(0, 1);
  auto value = [&] {
    const double hi = std::ldexp(mant(rng), ex(rng)) * (sign(rng) ? -1 : 1);
    const double lo = half(rng) * std::ldexp(1.0, std::ilogb(hi) - 52);
    const double s = hi + lo;  // a double-word value: |lo'| <= ulp(s) / 2
    return DD(dd_real(s, lo - (s - hi)));
  };
  long differ = 0;
  for (int i = 0; i < 1000000; ++i) {
    const DD x = value(), y = value();
    const DD a = x * y, b = fused_product(x, y);
    if (std::bit_cast<std::uint64_t>(a.v.x[0]) != std::bit_cast<std::uint64_t>(b.v.x[0]) ||
        std::bit_cast<std::uint64_t>(a.v.x[1]) != std::bit_cast<std::uint64_t>(b.v.x[1]))
      ++differ;
  }
  BOOST_TEST(differ == 0);
#endif
}
