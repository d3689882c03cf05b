// Cylinder against cylinder, side by side on the same random pairs: the certified query (exact
// rational input, and binary64 input taken exactly, with several options), Eberly's separating-axis test in double (corrected variant, not certified), and
// FCL's fcl::collide on two fcl::Cylinderd with its default GJK solver (libccd), when FCL is
// installed.
//
// Options: the defaults (certificate as binary64 vectors, gap enclosure on access, no stage
// clock), the defaults with the enclosure read (gap()), the enclosure computed in the query and
// read (GapEnclosure::in_query), without the gap enclosure, with the ranked candidates' tighter
// enclosure (refine_gap, as the command runs it), and with everything on (refine_gap, Rational
// certificate fields, stage clock).
//
// Pairs: midpoints uniform in [-1, 1]^3, axis directions uniform, lengths in [0.2, 2], radii in
// [0.05, 0.5] (binary64 values); split by the certified answer into separated and overlapping
// sets, timed apart. Each benchmark reports the mean time per query (Google Benchmark's figure)
// and, as counters, the median over pairs of the per-pair time (pair_ns: best of 5 batches of 32 calls).
// BM_certified_stages reports, over all pairs (binary64 input, default options), the fraction
// each stage decided, the fraction each arithmetic proved (static filter, intervals, Gmpq), the
// fraction that needed any Gmpq check, and the mean time spent in each stage per query.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <vector>

#include "certcyl/certified/cylinder_cylinder.hpp"
#include "certcyl/seeds/eberly_cylinders.hpp"

#include "cylinder_pairs.hpp"

namespace {

using certcyl::Cylinder;
using certcyl::Rational;
using namespace certcyl_bench;

struct Pair {
  Cylinder<double> a, b;
  Cylinder<Rational> qa, qb;
};

struct Pairs {
  std::vector<Pair> separated, overlapping, all;
};

const Pairs& pairs() {
  static const Pairs p = [] {
    Pairs r;
    std::mt19937_64 g(20240611);
    const auto q = [](double x) { return Rational(x); };
    for (int i = 0; i < 4000; ++i) {
      Pair p{random_cylinder(g), random_cylinder(g), {}, {}};
      p.qa = p.a.map(q);
      p.qb = p.b.map(q);
      const auto res = certcyl::certified_cylinder_cylinder(p.qa, p.qb);
      if (res.answer == certcyl::Answer::separated) r.separated.push_back(p);
      if (res.answer == certcyl::Answer::overlapping) r.overlapping.push_back(p);
      r.all.push_back(p);
    }
    return r;
  }();
  return p;
}

const std::vector<Pair>& set(int which) { return which == 0 ? pairs().separated : pairs().overlapping; }

// Per-pair time of f in nanoseconds: the best of 5 batches of kBatch consecutive calls on the
// pair, divided by kBatch. The clock of the build machine ticks in steps of about 10 ns and one
// reading costs 20 to 30 ns, as much as a quick query: a batch makes both negligible. Repeating
// one pair lets the branch predictor learn its path, alike for every method.
constexpr int kBatch = 32;

template <class F>
double pair_ns(const Pair& p, F f) {
  double best = INFINITY;
  for (int k = 0; k < 5; ++k) {
    const auto s = std::chrono::steady_clock::now();
    for (int j = 0; j < kBatch; ++j) benchmark::DoNotOptimize(f(p));
    best = std::min(best, std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - s).count());
  }
  return best / kBatch;
}

// Median over pairs of pair_ns.
template <class F>
double median_ns(const std::vector<Pair>& ps, F f) {
  std::vector<double> t;
  t.reserve(ps.size());
  for (const Pair& p : ps) t.push_back(pair_ns(p, f));
  std::nth_element(t.begin(), t.begin() + t.size() / 2, t.end());
  return t[t.size() / 2];
}

template <class F>
void run(benchmark::State& state, F f) {
  const std::vector<Pair>& ps = set(static_cast<int>(state.range(0)));
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(f(ps[i]));
    if (++i == ps.size()) i = 0;
  }
  state.counters["median_ns"] = median_ns(ps, f);
  state.counters["pairs"] = static_cast<double>(ps.size());
  state.SetLabel(state.range(0) == 0 ? "separated" : "overlapping");
}

void BM_certified_rational(benchmark::State& state) {
  run(state, [](const Pair& p) { return certcyl::certified_cylinder_cylinder(p.qa, p.qb).answer; });
}

void BM_certified_double(benchmark::State& state) {
  run(state, [](const Pair& p) { return certcyl::certified_cylinder_cylinder(p.a, p.b).answer; });
}

// Default options but the refine stage off (the query as it was before that stage): the stage
// must cost random pairs nothing, side by side in one run.
void BM_certified_double_refine_off(benchmark::State& state) {
  certcyl::CylinderCylinderOptions o;
  o.refine = false;
  run(state, [o](const Pair& p) { return certcyl::certified_cylinder_cylinder(p.a, p.b, o).answer; });
}

// The query and its gap enclosure read at once (an answer of the quick path computes the
// enclosure in gap(); the other stages record it during the query).
void BM_certified_double_read_gap(benchmark::State& state) {
  run(state, [](const Pair& p) { return certcyl::certified_cylinder_cylinder(p.a, p.b).gap().phi_lower; });
}

// The enclosure computed in the query (GapEnclosure::in_query) and read.
void BM_certified_double_gap_in_query(benchmark::State& state) {
  certcyl::CylinderCylinderOptions o;
  o.gap_enclosure = certcyl::GapEnclosure::in_query;
  run(state, [o](const Pair& p) { return certcyl::certified_cylinder_cylinder(p.a, p.b, o).gap().phi_lower; });
}

void BM_certified_double_no_gap(benchmark::State& state) {
  certcyl::CylinderCylinderOptions o;
  o.gap_enclosure = certcyl::GapEnclosure::off;
  run(state, [o](const Pair& p) { return certcyl::certified_cylinder_cylinder(p.a, p.b, o).answer; });
}

// The ranked fast path's tighter gap enclosure (what the command reports).
void BM_certified_double_refined_gap(benchmark::State& state) {
  certcyl::CylinderCylinderOptions o;
  o.refine_gap = true;
  run(state, [o](const Pair& p) { return certcyl::certified_cylinder_cylinder(p.a, p.b, o).answer; });
}

// Everything on: ranked candidates, Rational certificate fields filled, stage clock.
void BM_certified_double_everything(benchmark::State& state) {
  certcyl::CylinderCylinderOptions o;
  o.refine_gap = true;
  o.rational_certificates = true;
  o.time_stages = true;
  run(state, [o](const Pair& p) { return certcyl::certified_cylinder_cylinder(p.a, p.b, o).answer; });
}

// Eberly's test in double, corrected variant (not certified); "disagree" counts pairs where its
// boolean differs from the certified answer.
void BM_eberly_double(benchmark::State& state) {
  const std::vector<Pair>& ps = set(static_cast<int>(state.range(0)));
  const certcyl::EberlyParameters params = certcyl::EberlyParameters::corrected();
  const auto f = [&params](const Pair& p) { return certcyl::eberly_separated(p.a, p.b, params).separated; };
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(f(ps[i]));
    if (++i == ps.size()) i = 0;
  }
  double wrong = 0;
  for (const Pair& p : ps) wrong += f(p) != (state.range(0) == 0);
  state.counters["median_ns"] = median_ns(ps, f);
  state.counters["pairs"] = static_cast<double>(ps.size());
  state.counters["disagree"] = wrong;
  state.SetLabel(state.range(0) == 0 ? "separated" : "overlapping");
}
BENCHMARK(BM_eberly_double)->Arg(0)->Arg(1);

#ifdef CERTCYL_HAVE_FCL
FclPair to_fcl(const Pair& p) { return certcyl_bench::to_fcl(p.a, p.b); }

void BM_fcl(benchmark::State& state) {
  const std::vector<Pair>& ps = set(static_cast<int>(state.range(0)));
  std::vector<FclPair> fs;
  for (const Pair& p : ps) fs.push_back(to_fcl(p));
  std::size_t i = 0, wrong = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(fcl_collide(fs[i]));
    if (++i == fs.size()) i = 0;
  }
  // Median per pair (pair_ns), and how often FCL disagrees with the certified answer.
  std::vector<double> t;
  for (std::size_t k = 0; k < fs.size(); ++k) {
    t.push_back(pair_ns(ps[k], [&fs, k](const Pair&) { return fcl_collide(fs[k]); }));
    if (fcl_collide(fs[k]) != (state.range(0) == 1)) ++wrong;
  }
  std::nth_element(t.begin(), t.begin() + t.size() / 2, t.end());
  state.counters["median_ns"] = t[t.size() / 2];
  state.counters["pairs"] = static_cast<double>(fs.size());
  state.counters["disagree"] = static_cast<double>(wrong);
  state.SetLabel(state.range(0) == 0 ? "separated" : "overlapping");
}
BENCHMARK(BM_fcl)->Arg(0)->Arg(1);
#endif

// Which stage and which arithmetic decided, and the time spent per stage, over all pairs (one
// pass per iteration).
void BM_certified_stages(benchmark::State& state) {
  const std::vector<Pair>& ps = pairs().all;
  std::array<double, certcyl::kCylinderStages + 1> decided{};
  std::array<double, 4> by{};
  std::array<double, certcyl::kCylinderStages> seconds{};
  double runs = 0, any_exact = 0;
  for (auto _ : state) {
    certcyl::CylinderCylinderOptions o;
    o.time_stages = true;
    for (const Pair& p : ps) {
      const auto r = certcyl::certified_cylinder_cylinder(p.a, p.b, o);
      decided[static_cast<std::size_t>(r.stage)] += 1;
      by[static_cast<std::size_t>(r.certified_by)] += 1;
      if (r.counters.exact_checks > 0 || r.gmpfr_precision > 0) any_exact += 1;
      for (std::size_t s = 0; s < seconds.size(); ++s) seconds[s] += r.stage_seconds[s];
      runs += 1;
    }
  }
  for (std::size_t s = 0; s <= certcyl::kCylinderStages; ++s) {
    const std::string name(certcyl::to_string(static_cast<certcyl::CylinderStage>(s)));
    state.counters["decided_" + name] = decided[s] / runs;
    if (s < seconds.size()) state.counters["ns_" + name] = 1e9 * seconds[s] / runs;
  }
  for (std::size_t a = 0; a < by.size(); ++a)
    state.counters["by_" + std::string(certcyl::to_string(static_cast<certcyl::CylinderArithmetic>(a)))] = by[a] / runs;
  state.counters["beyond_fast_path"] = 1 - (decided[0] + decided[1]) / runs;
  state.counters["beyond_double"] = (decided[3] + decided[4] + decided[5] + decided[6]) / runs;
  state.counters["any_gmpq_check"] = any_exact / runs;
}
BENCHMARK(BM_certified_stages)->Iterations(1)->Unit(benchmark::kMillisecond);

BENCHMARK(BM_certified_rational)->Arg(0)->Arg(1);
BENCHMARK(BM_certified_double)->Arg(0)->Arg(1);
BENCHMARK(BM_certified_double_refine_off)->Arg(0)->Arg(1);
BENCHMARK(BM_certified_double_read_gap)->Arg(0)->Arg(1);
BENCHMARK(BM_certified_double_gap_in_query)->Arg(0)->Arg(1);
BENCHMARK(BM_certified_double_no_gap)->Arg(0)->Arg(1);
BENCHMARK(BM_certified_double_refined_gap)->Arg(0)->Arg(1);
BENCHMARK(BM_certified_double_everything)->Arg(0)->Arg(1);

}  // namespace

BENCHMARK_MAIN();
