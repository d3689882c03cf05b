// The cost of the exchanges of `certcyl judge` with a judged method, on a trivial method (a
// cylinder-pair test of one comparison), so that the figures are the exchange's own:
//
//   BM_pair_direct              the method called directly (a call the compiler cannot inline)
//   BM_pair_dlsym               the same function from a shared library, through the pointer
//                               dlsym returned (what the judge's child process calls)
//   BM_judge_plugin/N           run_plugin (src/judge_plugin.cpp) on N cases: the child process
//                               forked, the library loaded, every case answered into the shared
//                               memory and read back by the parent; ns per case
//   BM_judge_exec/N             run_exec (src/judge_exec.cpp) on N cases with a trivial program
//                               (this executable run as `bench_judge_exchange --answer-separated`:
//                               it reads query lines and answers {"id": ..., "answer": "separated"}
//                               to each, in blocks): the query lines written, the program's lines
//                               read and parsed; queries per second
//
// The shared library is this file built with CERTCYL_BENCH_PLUGIN_ONLY (bench/CMakeLists.txt:
// bench_judge_exchange_plugin), so the direct and the dlsym calls run the same code. The cases
// are synthetic (ids "cylinder_cylinder/bench/<i>", random coordinates): no certification.
#include <cmath>

#include "certcyl/plugin.h"

namespace {
// The trivial method: the two radii against the distance of the first coordinates.
inline int trivial_pair(const double a[7], const double b[7]) {
  return a[6] + b[6] >= std::fabs(a[0] - b[0]) ? CERTCYL_INTERSECTING : CERTCYL_SEPARATED;
}
}  // namespace

#ifdef CERTCYL_BENCH_PLUGIN_ONLY

extern "C" {
const char* certcyl_plugin_name(void) { return "bench_trivial"; }
int certcyl_plugin_cylinder_cylinder(const double a[7], const double b[7]) { return trivial_pair(a, b); }
}

#else

#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstring>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <dlfcn.h>
#include <unistd.h>

#include "judge_internal.hpp"

using certcyl::cli::Case;
namespace judging = certcyl::cli::judging;

namespace {

[[gnu::noinline]] int direct_pair(const double a[7], const double b[7]) { return trivial_pair(a, b); }

std::vector<Case> make_bench_cases(std::size_t n) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> coordinate(-10, 10), radius(0.1, 2);
  std::vector<Case> cases(n);
  for (std::size_t i = 0; i < n; ++i) {
    Case& c = cases[i];
    c.id = "cylinder_cylinder/bench/" + std::to_string(i);
    c.query = certcyl::study::Query::cylinder_cylinder;
    c.family = "bench";
    c.k = static_cast<long long>(i);
    c.line = i + 1;
    c.x.resize(14);
    for (double& v : c.x) v = coordinate(rng);
    c.x[6] = radius(rng);
    c.x[13] = radius(rng);
  }
  return cases;
}

const std::vector<Case>& bench_cases(std::size_t n) {
  static std::vector<Case> cases;
  if (cases.size() < n) cases = make_bench_cases(n);
  static std::vector<Case> prefix;
  if (prefix.size() != n) prefix.assign(cases.begin(), cases.begin() + static_cast<std::ptrdiff_t>(n));
  return prefix;
}

using PairFn = int (*)(const double*, const double*);

PairFn plugin_pair() {
  static PairFn fn = [] {
    void* handle = ::dlopen(CERTCYL_BENCH_PLUGIN, RTLD_NOW | RTLD_LOCAL);
    if (!handle) throw std::runtime_error(std::string("dlopen: ") + ::dlerror());
    void* sym = ::dlsym(handle, "certcyl_plugin_cylinder_cylinder");
    if (!sym) throw std::runtime_error("dlsym: no certcyl_plugin_cylinder_cylinder");
    return reinterpret_cast<PairFn>(sym);
  }();
  return fn;
}

constexpr std::size_t kCallCases = 4096;

template <class Fn>
void run_calls(benchmark::State& state, Fn fn) {
  const std::vector<Case>& cases = bench_cases(kCallCases);
  long long meet = 0;
  for (auto _ : state) {
    for (const Case& c : cases) {
      const double* x = c.x.data();
      benchmark::DoNotOptimize(x);
      meet += fn(x, x + 7);
    }
  }
  benchmark::DoNotOptimize(meet);
  state.SetItemsProcessed(state.iterations() * static_cast<long long>(cases.size()));
  state.counters["ns_per_call"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * static_cast<double>(cases.size()),
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_pair_direct(benchmark::State& state) { run_calls(state, [](const double* a, const double* b) { return direct_pair(a, b); }); }

void BM_pair_dlsym(benchmark::State& state) {
  const PairFn fn = plugin_pair();
  benchmark::DoNotOptimize(fn);
  run_calls(state, [fn](const double* a, const double* b) { return fn(a, b); });
}

// Fails the benchmark when the exchange did not answer every case, or answered one wrongly.
void check(benchmark::State& state, const judging::Answers& answers, const std::vector<Case>& cases, bool trivial) {
  if (!answers.failure.empty()) return state.SkipWithError(answers.failure.c_str());
  for (std::size_t i = 0; i < cases.size(); ++i) {
    if (!answers.answers[i]) return state.SkipWithError("a case without an answer");
    const std::string expected = trivial ? (trivial_pair(cases[i].x.data(), cases[i].x.data() + 7) == CERTCYL_INTERSECTING ? "intersecting" : "separated")
                                         : "separated";
    if (answers.answers[i]->answer != expected) return state.SkipWithError("an answer differs from the method's");
  }
}

void BM_judge_plugin(benchmark::State& state) {
  const std::vector<Case>& cases = bench_cases(static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) {
    const judging::Answers answers = judging::run_plugin(CERTCYL_BENCH_PLUGIN, cases, judging::Timeout{60});
    state.PauseTiming();
    check(state, answers, cases, true);
    state.ResumeTiming();
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
  state.counters["ns_per_case"] = benchmark::Counter(static_cast<double>(state.iterations() * state.range(0)),
                                                     benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

std::string self_path() {
  char buf[4096];
  const ssize_t n = ::readlink("/proc/self/exe", buf, sizeof buf - 1);
  if (n <= 0) throw std::runtime_error("readlink /proc/self/exe failed");
  return std::string(buf, static_cast<std::size_t>(n));
}

void BM_judge_exec(benchmark::State& state) {
  const std::vector<Case>& cases = bench_cases(static_cast<std::size_t>(state.range(0)));
  std::string command = "'";  // appended piecewise: GCC 12's -Wrestrict misreads "'" + self_path()
  command += self_path();
  command += "' --answer-separated";
  for (auto _ : state) {
    const judging::Answers answers = judging::run_exec(command, cases, judging::Timeout{60});
    state.PauseTiming();
    check(state, answers, cases, false);
    state.ResumeTiming();
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
  state.counters["queries_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations() * state.range(0)), benchmark::Counter::kIsRate);
}

// The trivial program of BM_judge_exec: for each line {"id":"ID",...} it writes
// {"id":"ID","answer":"separated"}; it reads and writes in blocks, writing the answers to the
// lines of each block read before it waits for the next.
int answer_separated() {
  std::string in, out;
  char chunk[65536];
  for (;;) {
    const ssize_t n = ::read(0, chunk, sizeof chunk);
    if (n < 0) return 1;
    if (n == 0) break;
    in.append(chunk, static_cast<std::size_t>(n));
    std::size_t start = 0;
    for (std::size_t nl; (nl = in.find('\n', start)) != std::string::npos; start = nl + 1) {
      const std::size_t id = start + std::strlen("{\"id\":\"");
      const std::size_t end = in.find('"', id);
      if (in.compare(start, id - start, "{\"id\":\"") != 0 || end == std::string::npos || end > nl) return 2;
      out += "{\"id\":\"";
      out.append(in, id, end - id);
      out += "\",\"answer\":\"separated\"}\n";
    }
    in.erase(0, start);
    for (std::size_t done = 0; done < out.size();) {
      const ssize_t w = ::write(1, out.data() + done, out.size() - done);
      if (w <= 0) return 1;
      done += static_cast<std::size_t>(w);
    }
    out.clear();
  }
  return 0;
}

}  // namespace

BENCHMARK(BM_pair_direct);
BENCHMARK(BM_pair_dlsym);
BENCHMARK(BM_judge_plugin)->Arg(1 << 20)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_judge_exec)->Arg(1 << 18)->Unit(benchmark::kMillisecond)->UseRealTime();

int main(int argc, char** argv) {
  if (argc == 2 && std::strcmp(argv[1], "--answer-separated") == 0) return answer_separated();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

#endif
