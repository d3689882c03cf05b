// Line against circular cylinder: ns per query for each method and number type, on random
// lines and on near-tangent lines (distance to the axis within a few ulps of the radius).
// The certified query is measured twice: the decision alone (answer and features, filtered:
// semi-static double stage, Interval_nt, Gmpq; the fraction each stage decided is reported as
// static / interval / exact) and the full result (exact endpoints and their correctly rounded
// doubles), with double and with Rational input (binary64 values, so the same path after a
// check). Run the three side by side (--benchmark_filter='robust|certified') and take the
// ratios from one run: the machine's load moves all figures together.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "certcyl/certified/line_cylinder.hpp"
#include "certcyl/robust/line_cylinder.hpp"
#include "certcyl/seeds/gullotti_line_elliptic_cylinder.hpp"
#include "certcyl/seeds/shene_line_cylinder.hpp"

using namespace certcyl;

namespace {

struct Instance {
  Line<double> line;
  Cylinder<double> cyl;
};

std::vector<Instance> make_instances(bool near_tangent) {
  std::mt19937_64 rng(near_tangent ? 2 : 1);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Instance> out;
  for (int i = 0; i < 1024; ++i) {
    const Vec3<double> p0{u(rng), u(rng), u(rng)};
    if (!near_tangent) {
      const Cylinder<double> c{p0, {u(rng), u(rng), u(rng)}, 0.25 + std::fabs(u(rng))};
      out.push_back({{{u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}}, c});
    } else {
      // Vertical axis; the line passes at x-offset r (rounded) plus -2..2 ulps.
      const double r = 0.25 + std::fabs(u(rng));
      const Cylinder<double> c{p0, {p0.x, p0.y, p0.z + 1}, r};
      double off = r;
      for (int k = 0; k < i % 5; ++k) off = std::nextafter(off, i % 2 ? 2.0 : 0.0);
      out.push_back({{{p0.x + off, p0.y, p0.z + 0.5}, {0, 1, 0.5 * u(rng)}}, c});
    }
  }
  return out;
}

const std::vector<Instance>& instances(bool near_tangent) {
  static const std::vector<Instance> random = make_instances(false), tangent = make_instances(true);
  return near_tangent ? tangent : random;
}

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

// Argument: 0 = random lines, 1 = near-tangent lines.
BENCHMARK(BM_robust_double)->Arg(0)->Arg(1);
BENCHMARK(BM_certified_decision)->Arg(0)->Arg(1);
BENCHMARK(BM_certified_decision_interval_first)->Arg(0)->Arg(1);
BENCHMARK(BM_certified_full)->Arg(0)->Arg(1);
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

BENCHMARK_MAIN();
