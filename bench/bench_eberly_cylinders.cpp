// Eberly's cylinder-cylinder test: ns per query and evaluations per query, for each variant
// and number type, on random pairs (seeded), separated and overlapping pairs apart (an
// overlapping pair pays for every test). Pairs are classified by the corrected variant in
// CORE::Expr. Interval runs that throw (undecided) are counted in `undecided/query`.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "certcyl/number_traits.hpp"
#include "certcyl/number_traits_core.hpp"
#include "certcyl/primitives.hpp"
#include "certcyl/seeds/eberly_cylinders.hpp"

using namespace certcyl;

namespace {

struct Pair {
  Cylinder<Rational> c0, c1;
};

Rational random_rational(std::mt19937_64& rng, int lo, int hi, int den) {
  std::uniform_int_distribution<int> d(lo * den, hi * den);
  return Rational(d(rng), den);
}

Cylinder<Rational> random_cylinder(std::mt19937_64& rng) {
  for (;;) {
    Vec3<Rational> p0{random_rational(rng, -2, 2, 64), random_rational(rng, -2, 2, 64), random_rational(rng, -2, 2, 64)};
    Vec3<Rational> p1{random_rational(rng, -2, 2, 64), random_rational(rng, -2, 2, 64), random_rational(rng, -2, 2, 64)};
    std::uniform_int_distribution<int> r(4, 40);
    if (!(p0 == p1)) return {p0, p1, Rational(r(rng), 64)};
  }
}

// 200 pairs of each kind, classified by the corrected variant in CORE::Expr.
const std::vector<Pair>& pairs(bool separated) {
  static const auto sets = [] {
    std::mt19937_64 rng(20240605);
    std::vector<Pair> sep, ovl;
    while (sep.size() < 200 || ovl.size() < 200) {
      Pair p{random_cylinder(rng), random_cylinder(rng)};
      const auto r = eberly_separated(convert<CORE::Expr>(p.c0), convert<CORE::Expr>(p.c1), EberlyParameters::corrected());
      auto& set = r.separated ? sep : ovl;
      if (set.size() < 200) set.push_back(p);
    }
    return std::pair{sep, ovl};
  }();
  return separated ? sets.first : sets.second;
}

template <class NT>
void run_queries(benchmark::State& state, EberlyVariant variant, bool separated, long bits) {
  NumberScope<NT> scope(bits);
  std::vector<std::pair<Cylinder<NT>, Cylinder<NT>>> input;
  for (const Pair& p : pairs(separated)) input.emplace_back(convert<NT>(p.c0), convert<NT>(p.c1));
  const EberlyParameters params = EberlyParameters::of(variant);
  EberlyCounters total;
  std::uint64_t undecided = 0, said_separated = 0;
  std::size_t i = 0;
  for (auto _ : state) {
    const auto& [a, b] = input[i++ % input.size()];
    try {
      const auto r = eberly_separated(a, b, params);
      total += r.counters;
      said_separated += r.separated ? 1 : 0;
      benchmark::DoNotOptimize(r.separated);
    } catch (const CGAL::Uncertain_conversion_exception&) {
      ++undecided;
    }
  }
  using C = benchmark::Counter;
  state.counters["evals/query"] = C(static_cast<double>(total.evaluations()), C::kAvgIterations);
  state.counters["F/query"] = C(static_cast<double>(total.F + total.F_derivative), C::kAvgIterations);
  state.counters["G/query"] = C(static_cast<double>(total.G + total.G_gradient), C::kAvgIterations);
  state.counters["undecided/query"] = C(static_cast<double>(undecided), C::kAvgIterations);
  state.counters["separated/query"] = C(static_cast<double>(said_separated), C::kAvgIterations);
}

template <class NT>
void register_type(const std::string& name, long bits = 53) {
  for (EberlyVariant v : {EberlyVariant::as_written, EberlyVariant::corrected}) {
    for (bool separated : {true, false}) {
      const std::string label = "eberly/" + std::string(to_string(v)) + "/" + name + "/" +
                                (separated ? "separated" : "overlapping");
      benchmark::RegisterBenchmark(label.c_str(), [v, separated, bits](benchmark::State& s) {
        run_queries<NT>(s, v, separated, bits);
      })->Unit(benchmark::kNanosecond);
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  register_type<double>("double");
  register_type<long double>("long_double");
  register_type<Interval>("interval");
  register_type<CGAL::Gmpfr>("gmpfr<113>", 113);
  register_type<CGAL::Gmpfr>("gmpfr<256>", 256);
  register_type<CORE::Expr>("core_expr");
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
