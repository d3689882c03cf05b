// Line against circular cylinder: ns per query for each method and number type, on random
// lines and on the hard families (within a few ulps of a tangency, a rim or a cap plane, axis-
// aligned or in any orientation; lines, rays and segments).
// The certified query is measured twice: the decision alone (answer and features: adaptive
// polynomial signs in double, double-double, Mpzf; the fraction decided at each depth is
// reported as static / dd / interval / exact) and the full result (the endpoints' correctly
// rounded doubles, their exact values left to be built on request; BM_certified_full_exact
// also prints both exact values), with double and with Rational input (binary64 values, so the
// same path after a check). Run side by side (--benchmark_filter='robust|certified') and take
// the ratios from one run: the machine's load moves all figures together.
// BM_family/<k> reports, per family, Google Benchmark's mean (cycling through the instances)
// and, per instance, the median of 3 batches of 4 consecutive calls (the clock's resolution is
// coarse next to a 40 ns query), as median_ns, p99_ns and max_ns over the instances, and the
// family's mean is read against BM_family/0 (random lines) of the same run. Every answer is compared
// with the Gmpq skeleton; a disagreement makes the run exit non-zero.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "checked_main.hpp"
#include "certcyl/certified/line_cylinder.hpp"
#include "certcyl/number_traits_core.hpp"
#include "certcyl/robust/line_cylinder.hpp"
#include "certcyl/seeds/gullotti_line_elliptic_cylinder.hpp"
#include "certcyl/seeds/shene_line_cylinder.hpp"
#include "near_features.hpp"

using namespace certcyl;

namespace {

struct Instance {
  Line<double> line;
  Cylinder<double> cyl;
};

// The hard families. Every instance is binary64; for the oriented families the feature is
// computed in double and rounded, then coordinates are moved by 0..3 ulps, so each instance is
// within a few ulps of the feature (its side is whatever the rounding gives: the Gmpq skeleton
// says which).
enum Family : int {
  kRandom,
  kTangentAxis,      // vertical axis, x-offset r (rounded) -+ 0..4 ulps (the original family)
  kTangentOriented,  // any axis, a tangent line (rounded), moved a few ulps
  kRimOriented,      // any axis, through a rim point, grazing (rounded), moved a few ulps
  kCapPlaneOriented, // any axis, in a cap plane across the disk (rounded), moved a few ulps
  kSegmentCapEnd,    // any axis, a segment from inside to a point of a cap plane (rounded)
  kSegmentWallEnd,   // any axis, a segment from outside to a point of the wall (rounded)
  kFamilies
};
const char* const family_names[kFamilies] = {"random",           "tangent_axis_aligned", "tangent_oriented", "rim_oriented",
                                              "cap_plane_oriented", "segment_cap_end",   "segment_wall_end"};

// A line-like query of one of the three ranges.
struct Query {
  Vec3<double> origin, second;
  LineRange range = LineRange::line;
  Cylinder<double> cyl;
};

detail::LineShape decide(const Query& q, LineStageCounter& c) {
  switch (q.range) {
    case LineRange::ray: return certified_line_cylinder_shape(Ray<double>{q.origin, q.second}, q.cyl, c);
    case LineRange::segment: return certified_line_cylinder_shape(Segment<double>{q.origin, q.second}, q.cyl, c);
    case LineRange::line: break;
  }
  return certified_line_cylinder_shape(Line<double>{q.origin, q.second}, q.cyl, c);
}

using bench::unit;
using bench::vcross;

std::vector<Query> make_family(int family) {
  std::mt19937_64 rng(100 + family);
  std::uniform_real_distribution<double> u(-1, 1);
  auto rv = [&] { return Vec3<double>{u(rng), u(rng), u(rng)}; };
  bench::UlpNudge nudge3(rng);
  std::vector<Query> out;
  for (int i = 0; i < 1024; ++i) {
    Query q;
    const Vec3<double> p0 = rv();
    if (family == kRandom) {
      q.cyl = {p0, rv(), 0.25 + std::fabs(u(rng))};
      q.origin = rv();
      q.second = rv();
      out.push_back(q);
      continue;
    }
    if (family == kTangentAxis) {
      const double r = 0.25 + std::fabs(u(rng));
      q.cyl = {p0, {p0.x, p0.y, p0.z + 1}, r};
      double off = r;
      for (int k = 0; k < i % 5; ++k) off = std::nextafter(off, i % 2 ? 2.0 : 0.0);
      q.origin = {p0.x + off, p0.y, p0.z + 0.5};
      q.second = {0, 1, 0.5 * u(rng)};
      out.push_back(q);
      continue;
    }
    // An oriented cylinder and a frame (n, m) perpendicular to its axis, rounded.
    const Vec3<double> p1 = p0 + rv() * 2.0;
    const double r = 0.25 + std::fabs(u(rng));
    q.cyl = {p0, p1, r};
    const Vec3<double> A = p1 - p0;
    const Vec3<double> n = unit(vcross(A, rv())), m = unit(vcross(A, n));
    q.range = static_cast<LineRange>(i % 3);
    Vec3<double> X, d;
    switch (family) {
      case kTangentOriented:  // X on the wall mid-height, d in the tangent plane
        X = p0 + A * (0.25 + 0.5 * std::fabs(u(rng))) + n * r;
        d = m + A * (0.5 * u(rng));
        break;
      case kRimOriented:  // X on the rim of cap1; d grazes it (outward and towards cap0), or
                          // (odd i) enters the solid through it
        X = p1 + n * r;
        d = n + unit(A) * ((i % 2 ? 1 : -1) * (0.5 + std::fabs(u(rng))));
        break;
      case kCapPlaneOriented:  // X in the disk of cap0, d in the cap plane
        X = p0 + n * (r * u(rng));
        d = m + n * (0.5 * u(rng));
        break;
      case kSegmentCapEnd: {  // from inside to the cap1 plane, inside or outside the disk
        q.range = LineRange::segment;
        const Vec3<double> S0 = p0 + A * 0.5 + n * (0.5 * r * u(rng));
        const Vec3<double> S1 = p1 + m * (2 * r * u(rng));
        q.origin = S0;
        q.second = nudge3(S1);
        q.cyl = {nudge3(p0), p1, r};
        out.push_back(q);
        continue;
      }
      default: {  // kSegmentWallEnd: from outside to a point of the wall
        q.range = LineRange::segment;
        const Vec3<double> S1 = p0 + A * (0.25 + 0.5 * std::fabs(u(rng))) + n * r;
        q.origin = S1 + n * (1 + std::fabs(u(rng))) + m * u(rng);
        q.second = nudge3(S1);
        out.push_back(q);
        continue;
      }
    }
    const Vec3<double> O = nudge3(X - d * (1 + std::fabs(u(rng))));
    q.origin = O;
    q.second = q.range == LineRange::segment ? nudge3(X + d * (1 + std::fabs(u(rng)))) : nudge3(d);
    out.push_back(q);
  }
  return out;
}

const std::vector<Query>& family(int k) {
  static const std::array<std::vector<Query>, kFamilies> all = [] {
    std::array<std::vector<Query>, kFamilies> a;
    for (int f = 0; f < kFamilies; ++f) a[f] = make_family(f);
    return a;
  }();
  return all[k];
}

// The lines of the random and axis-aligned tangent families, for the methods that take lines.
std::vector<Instance> make_instances(bool near_tangent) {
  std::vector<Instance> out;
  for (const Query& q : family(near_tangent ? kTangentAxis : kRandom)) out.push_back({{q.origin, q.second}, q.cyl});
  return out;
}

const std::vector<Instance>& instances(bool near_tangent) {
  static const std::vector<Instance> random = make_instances(false), tangent = make_instances(true);
  return near_tangent ? tangent : random;
}

int disagreements = 0;

void BM_robust_double(benchmark::State& state) {
  const auto& in = instances(state.range(0) != 0);
  std::size_t i = 0;
  for (auto _ : state) {
    const auto& x = in[i++ & 1023];
    benchmark::DoNotOptimize(robust_line_cylinder(x.line, x.cyl));
  }
}

void report_stages(benchmark::State& state, const LineStageCounter& c) {
  const double n = static_cast<double>(c.calls);
  state.counters["static"] = static_cast<double>(c.semi_static) / n;
  state.counters["dd"] = static_cast<double>(c.double_double) / n;
  state.counters["interval"] = static_cast<double>(c.interval) / n;
  state.counters["exact"] = static_cast<double>(c.exact) / n;
}

void BM_certified_decision(benchmark::State& state) {
  const auto& in = instances(state.range(0) != 0);
  std::size_t i = 0;
  LineStageCounter counter;
  for (auto _ : state) {
    const auto& x = in[i++ & 1023];
    benchmark::DoNotOptimize(certified_line_cylinder_shape(x.line, x.cyl, counter));
  }
  report_stages(state, counter);
}

// The decision with Interval_nt as the first stage (the static stage left out): the filter
// as it was before the semi-static stage, for comparison.
void BM_certified_decision_interval_first(benchmark::State& state) {
  const auto& in = instances(state.range(0) != 0);
  std::size_t i = 0;
  FilterCounter counter;
  for (auto _ : state) {
    const auto& x = in[i++ & 1023];
    const detail::LineInput<double> li = detail::line_input(x.line);
    benchmark::DoNotOptimize(filtered_call(
        [&]<class NT>() { return detail::line_shape(detail::line_quadric_in<NT>(li, x.cyl), li.range); }, counter));
  }
  state.counters["exact"] = static_cast<double>(counter.exact) / static_cast<double>(counter.calls);
}

// The decision as it was before the double-double stage: the static double stage alone, then
// the skeleton in Interval_nt and Gmpq for whatever it leaves undecided; side by side with
// BM_family in one run (argument: the family).
void BM_decision_before_double_double(benchmark::State& state) {
  const std::vector<Query>& f = family(static_cast<int>(state.range(0)));
  std::size_t i = 0;
  FilterCounter counter;
  for (auto _ : state) {
    const Query& q = f[i];
    if (++i == f.size()) i = 0;
    const detail::LineInput<double> li{q.origin, q.second, q.range == LineRange::segment, q.range};
    detail::StaticCircularSigns s(q.origin, q.second, li.second_is_point, q.cyl);
    if (s.usable()) {
      const detail::LineShape shape = detail::line_shape_from(s, q.range);
      if (!s.undecided()) {
        benchmark::DoNotOptimize(shape);
        continue;
      }
    }
    benchmark::DoNotOptimize(
        filtered_call([&]<class NT>() { return detail::line_shape(detail::line_quadric_in<NT>(li, q.cyl), li.range); }, counter));
  }
  state.SetLabel(family_names[state.range(0)]);
}

void BM_certified_full(benchmark::State& state) {
  const auto& in = instances(state.range(0) != 0);
  std::size_t i = 0;
  LineStageCounter counter;
  for (auto _ : state) {
    const auto& x = in[i++ & 1023];
    const auto r = certified_line_cylinder(x.line, x.cyl);
    counter.count(r.stage);
    benchmark::DoNotOptimize(r);
  }
  report_stages(state, counter);
}

// The full answer with the exact values of both endpoints materialised as strings (they are
// built on request: BM_certified_full leaves them unbuilt).
void BM_certified_full_exact(benchmark::State& state) {
  const auto& in = instances(state.range(0) != 0);
  std::size_t i = 0;
  LineStageCounter counter;
  for (auto _ : state) {
    const auto& x = in[i++ & 1023];
    const auto r = certified_line_cylinder(x.line, x.cyl);
    counter.count(r.stage);
    if (r.in) {
      const auto [in_value, out_value] = r.exact_values();
      const std::string in_exact = in_value.to_string(), out_exact = out_value.to_string();
      benchmark::DoNotOptimize(in_exact.data());
      benchmark::DoNotOptimize(out_exact.data());
    }
    benchmark::DoNotOptimize(r);
  }
  report_stages(state, counter);
}

void BM_certified_full_rational_input(benchmark::State& state) {
  const auto& in = instances(state.range(0) != 0);
  std::vector<std::pair<Line<Rational>, Cylinder<Rational>>> conv;
  for (const auto& x : in) {
    auto f = [](double v) { return Rational(v); };
    conv.push_back({x.line.map(f), x.cyl.map(f)});
  }
  std::size_t i = 0;
  LineStageCounter counter;
  for (auto _ : state) {
    const auto& x = conv[i++ & 1023];
    const auto r = certified_line_cylinder(x.first, x.second);
    counter.count(r.stage);
    benchmark::DoNotOptimize(r);
  }
  report_stages(state, counter);
}

// Nanoseconds of one decision on q: the median of 3 batches of 4 calls.
double call_ns(const Query& q) {
  LineStageCounter c;
  return bench::median_call_ns([&] { return decide(q, c); });
}

// One family: Google Benchmark's mean cycling through the instances, and the distribution
// over instances; the answers checked against the Gmpq skeleton.
void BM_family(benchmark::State& state) {
  const std::vector<Query>& f = family(static_cast<int>(state.range(0)));
  std::size_t i = 0;
  LineStageCounter counter;
  for (auto _ : state) {
    benchmark::DoNotOptimize(decide(f[i], counter));
    if (++i == f.size()) i = 0;
  }
  std::vector<double> t;
  LineStageCounter once;
  for (const Query& q : f) {
    t.push_back(call_ns(q));
    const detail::LineShape s = decide(q, once);
    const detail::LineInput<double> li{q.origin, q.second, q.range == LineRange::segment, q.range};
    const detail::LineShape e = detail::line_shape(detail::line_quadric_in<Rational>(li, q.cyl), q.range);
    if (s.answer != e.answer || s.in != e.in || s.out != e.out) ++disagreements;
  }
  std::sort(t.begin(), t.end());
  state.counters["median_ns"] = t[t.size() / 2];
  state.counters["p99_ns"] = t[t.size() * 99 / 100];
  state.counters["max_ns"] = t.back();
  report_stages(state, once);
  std::array<int, 4> answers{};
  for (const Query& q : f) ++answers[static_cast<int>(decide(q, once).answer)];
  state.counters["separated"] = answers[0], state.counters["touching"] = answers[1], state.counters["overlapping"] = answers[2];
  state.SetLabel(family_names[state.range(0)]);
}

template <class NT>
void seed_loop(benchmark::State& state, bool shene) {
  const auto& in = instances(state.range(0) != 0);
  std::vector<std::pair<Line<NT>, Cylinder<NT>>> conv;
  for (const auto& x : in) {
    auto f = [](double v) { return nt::from_rational<NT>(Rational(v)); };
    conv.push_back({x.line.map(f), x.cyl.map(f)});
  }
  std::size_t i = 0;
  long undecided = 0;
  for (auto _ : state) {
    const auto& x = conv[i++ & 1023];
    try {
      if (shene)
        benchmark::DoNotOptimize(shene_line_cylinder(x.first, x.second));
      else
        benchmark::DoNotOptimize(gullotti_line_cylinder(x.first, x.second));
    } catch (const CGAL::Uncertain_conversion_exception&) {
      ++undecided;
    }
  }
  state.counters["undecided"] = static_cast<double>(undecided) / static_cast<double>(state.iterations());
}

template <class NT>
void BM_shene(benchmark::State& state) {
  seed_loop<NT>(state, true);
}
template <class NT>
void BM_gullotti(benchmark::State& state) {
  seed_loop<NT>(state, false);
}
void BM_shene_interval(benchmark::State& state) {
  CGAL::Protect_FPU_rounding<true> upward;
  seed_loop<Interval>(state, true);
}
void BM_gullotti_interval(benchmark::State& state) {
  CGAL::Protect_FPU_rounding<true> upward;
  seed_loop<Interval>(state, false);
}
void BM_shene_gmpfr113(benchmark::State& state) {
  GmpfrPrecision p(113);
  seed_loop<CGAL::Gmpfr>(state, true);
}
void BM_gullotti_gmpfr113(benchmark::State& state) {
  GmpfrPrecision p(113);
  seed_loop<CGAL::Gmpfr>(state, false);
}

}  // namespace

// Argument: 0 = random lines, 1 = near-tangent lines (axis-aligned); BM_family: every family.
BENCHMARK(BM_family)->DenseRange(0, kFamilies - 1);
BENCHMARK(BM_decision_before_double_double)->DenseRange(0, kFamilies - 1);
BENCHMARK(BM_robust_double)->Arg(0)->Arg(1);
BENCHMARK(BM_certified_decision)->Arg(0)->Arg(1);
BENCHMARK(BM_certified_decision_interval_first)->Arg(0)->Arg(1);
BENCHMARK(BM_certified_full)->Arg(0)->Arg(1);
BENCHMARK(BM_certified_full_exact)->Arg(0)->Arg(1);
BENCHMARK(BM_certified_full_rational_input)->Arg(0)->Arg(1);
BENCHMARK(BM_shene<double>)->Arg(0)->Arg(1);
BENCHMARK(BM_gullotti<double>)->Arg(0)->Arg(1);
BENCHMARK(BM_shene<long double>)->Arg(0)->Arg(1);
BENCHMARK(BM_gullotti<long double>)->Arg(0)->Arg(1);
BENCHMARK(BM_shene_interval)->Arg(0)->Arg(1);
BENCHMARK(BM_gullotti_interval)->Arg(0)->Arg(1);
BENCHMARK(BM_shene_gmpfr113)->Arg(0)->Arg(1);
BENCHMARK(BM_gullotti_gmpfr113)->Arg(0)->Arg(1);
BENCHMARK(BM_shene<CORE::Expr>)->Arg(0)->Arg(1);
BENCHMARK(BM_gullotti<CORE::Expr>)->Arg(0)->Arg(1);

// Google Benchmark's main; exit status 1 when an answer failed its check (checked_main.hpp).
int main(int argc, char** argv) {
  return certcyl::bench::run_checked_benchmarks(argc, argv, disagreements, "bench_line_cylinder: decisions that disagree with the Gmpq skeleton");
}

