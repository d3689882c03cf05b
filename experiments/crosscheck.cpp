// The cross-check driver: random and degenerate cases for every certified query, each answer
// re-checked exactly through an independent path (fuzz/recheck.hpp) and compared across exactly
// equivalent inputs (fuzz/crosscheck_cases.hpp has the cases and the invariances).
//
//   crosscheck [--cases N] [--first I] [--seed S] [--query line|triangle|cylinder|all]
//              [--threads T] [--shard K/M] [--progress SECONDS] [--profile]
// Checks cases I, ..., I + N - 1 of each query (default 0 and 1,000,000). Case i is generated
// from (seed, i) alone, so threads and shards check exactly the cases a single thread would:
// shard K of M (K = 0, ..., M - 1) takes the K-th of M consecutive blocks of the range, and
// `--first i --cases 1` reproduces case i. --progress prints counts to stderr every SECONDS
// (failures are printed there as they are found, with their exact input);
// --profile (cylinder pairs) prints where the time goes, per kind of case and per stage.
// Prints whether assertions are on, then cases, re-checked answers, wrong answers and crashes per
// query; exits 1 if any answer was wrong, any cylinder pair undecided or any query threw.
// scripts/crosscheck.sh builds it with CGAL's and the standard library's assertions on and runs
// it.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "../fuzz/crosscheck_cases.hpp"

namespace {

using certcyl::crosscheck::KindProfile;
using certcyl::crosscheck::Stats;

struct Options {
  std::uint64_t cases = 1000000, first = 0, seed = 1;
  std::string query = "all";
  unsigned threads = 1, shard = 0, shards = 1;
  double progress = 0;
  bool profile = false;
};

[[noreturn]] void usage() {
  std::cerr << "usage: crosscheck [--cases N] [--first I] [--seed S] [--query line|triangle|cylinder|all] [--threads T]\n"
               "                  [--shard K/M] [--progress SECONDS] [--profile]\n";
  std::exit(2);
}

Options parse(int argc, char** argv) {
  Options o;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      if (a == "--profile") {
        o.profile = true;
        continue;
      }
      if (i + 1 >= argc) usage();
      const std::string v = argv[++i];
      if (a == "--cases") o.cases = std::stoull(v);
      else if (a == "--first") o.first = std::stoull(v);
      else if (a == "--seed") o.seed = std::stoull(v);
      else if (a == "--query") o.query = v;
      else if (a == "--threads") o.threads = static_cast<unsigned>(std::stoul(v));
      else if (a == "--progress") o.progress = std::stod(v);
      else if (a == "--shard") {
        const auto slash = v.find('/');
        if (slash == std::string::npos) usage();
        o.shard = static_cast<unsigned>(std::stoul(v.substr(0, slash)));
        o.shards = static_cast<unsigned>(std::stoul(v.substr(slash + 1)));
      } else usage();
    }
  } catch (const std::exception&) {
    usage();
  }
  if (o.threads == 0 || o.shards == 0 || o.shard >= o.shards) usage();
  if (o.query != "all" && o.query != "line" && o.query != "triangle" && o.query != "cylinder") usage();
  return o;
}

// Cases [begin, end) over `threads` threads taking blocks of 16 from a shared counter; each
// thread keeps its own Stats, merged at the end.
template <class CheckCase>
Stats run_range(std::uint64_t begin, std::uint64_t end, unsigned threads, double progress, const std::string& name, CheckCase check_case) {
  constexpr std::uint64_t kBlock = 16;
  std::atomic<std::uint64_t> next{begin}, done{0}, evaluations{0}, wrong{0}, crashes{0};
  std::mutex report;  // failures are printed to stderr as they are found
  std::vector<Stats> parts(threads);
  const auto start = std::chrono::steady_clock::now();
  const auto worker = [&](Stats& st) {
    for (;;) {
      const std::uint64_t b = next.fetch_add(kBlock);
      if (b >= end) return;
      for (std::uint64_t i = b; i < std::min(end, b + kBlock); ++i) {
        const std::uint64_t w = st.wrong, c = st.crashes, e = st.evaluations;
        const std::size_t f = st.failures.size();
        check_case(i, st);
        wrong += st.wrong - w;
        crashes += st.crashes - c;
        evaluations += st.evaluations - e;
        ++done;
        if (st.failures.size() > f) {
          const std::lock_guard<std::mutex> lock(report);
          for (std::size_t k = f; k < st.failures.size(); ++k) std::cerr << "FAILURE " << st.failures[k].what << std::endl;
        }
      }
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 0; t < threads; ++t) pool.emplace_back(worker, std::ref(parts[t]));
  if (progress > 0) {
    // The progress line, every `progress` seconds until the workers finish.
    const std::uint64_t total = end - begin;
    while (done.load() < total) {
      for (double waited = 0; waited < progress && done.load() < total; waited += 0.25)
        std::this_thread::sleep_for(std::chrono::milliseconds(250));
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const std::uint64_t d = done.load();
      const double rate = d / s;
      std::cerr << name << ": " << d << "/" << total << " cases, " << std::fixed << std::setprecision(0) << s << " s, "
                << std::setprecision(1) << rate << " cases/s, ETA " << std::setprecision(0) << (total - d) / std::max(rate, 1e-9)
                << " s; " << evaluations.load() << " answers re-checked, wrong " << wrong.load() << ", crashes " << crashes.load() << std::defaultfloat << std::endl;
    }
  }
  for (std::thread& t : pool) t.join();
  Stats all;
  for (const Stats& p : parts) all.merge(p);
  return all;
}

// Where the time of the cylinder pairs goes: per kind of case, the share of all time, the time
// per case, the split into queries / re-checks / the rest, the queries' stage split, and which
// stage decided.
void print_profile(std::ostream& out, const Stats& s) {
  double total = 0;
  KindProfile all;
  for (const auto& [kind, p] : s.profile) total += p.case_seconds, all.merge(p);
  out << "profile (wall time measured in each thread, summed over the threads):\n"
      << "  kind | cases | share of time | ms per case | query / recheck / other % | query stages midpoints/fast/optimiser/refine/"
         "touching_exact/gmpfr/ellipsoid % | evaluations decided by midpoints/fast/optimiser/refine/touching_exact/gmpfr/ellipsoid/none | exact checks per evaluation\n";
  std::vector<std::pair<std::string, KindProfile>> rows(s.profile.begin(), s.profile.end());
  std::sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) { return a.second.case_seconds > b.second.case_seconds; });
  rows.emplace_back("all", all);
  out << std::fixed;
  for (const auto& [kind, p] : rows) {
    const double q = p.query_seconds > 0 ? p.query_seconds : 1;
    out << "  " << kind << " | " << p.cases << " | " << std::setprecision(1) << 100 * p.case_seconds / total << "% | "
        << std::setprecision(2) << 1e3 * p.case_seconds / std::max<std::uint64_t>(p.cases, 1) << " | " << std::setprecision(0)
        << 100 * p.query_seconds / p.case_seconds << " / " << 100 * p.recheck_seconds / p.case_seconds << " / "
        << 100 * (p.case_seconds - p.query_seconds - p.recheck_seconds) / p.case_seconds << " | ";
    for (std::size_t k = 0; k < p.stage_seconds.size(); ++k) out << (k ? "/" : "") << 100 * p.stage_seconds[k] / q;
    out << " | ";
    for (std::size_t k = 0; k < p.decided_by.size(); ++k) out << (k ? "/" : "") << p.decided_by[k];
    out << " | " << std::setprecision(1) << static_cast<double>(p.exact_checks) / std::max<std::uint64_t>(p.evaluations, 1) << "\n";
  }
  out << std::defaultfloat;
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  const std::uint64_t begin = o.first + o.cases * o.shard / o.shards, end = o.first + o.cases * (o.shard + 1) / o.shards;
  // Whether CGAL's assertions and preconditions (and assert) can fire in this build: a failing
  // one throws inside a query, which counts as a crash (scripts/crosscheck.sh builds with them).
#ifdef CGAL_NO_ASSERTIONS
  std::cout << "assertions: off (NDEBUG)\n";
#else
  std::cout << "assertions: on\n";
#endif
  bool bad = false;
  const auto run = [&](const std::string& name, std::uint64_t offset, auto check_case) {
    if (o.query != "all" && o.query != name) return;
    const std::uint64_t seed = o.seed + offset;
    const auto start = std::chrono::steady_clock::now();
    const std::clock_t cpu_start = std::clock();
    const Stats s = run_range(begin, end, o.threads, o.progress, name, [&](std::uint64_t i, Stats& st) { check_case(i, seed, st); });
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double cpu = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
    certcyl::crosscheck::print(std::cout, name, s);
    std::cout << "  seed " << seed << ", cases " << begin << " to " << end - 1 << ", " << o.threads << " thread(s), " << seconds
              << " s wall, " << cpu << " s CPU\n";
    if (o.profile && !s.profile.empty()) print_profile(std::cout, s);
    std::cout << std::flush;
    bad = bad || s.wrong != 0 || s.crashes != 0 || s.undecided != 0;
  };
  using namespace certcyl::crosscheck;
  run("line", 0, [](std::uint64_t i, std::uint64_t seed, Stats& st) { check_line_case(i, seed, st); });
  run("triangle", 1, [](std::uint64_t i, std::uint64_t seed, Stats& st) { check_triangle_case(i, seed, st); });
  run("cylinder", 2, [&](std::uint64_t i, std::uint64_t seed, Stats& st) { check_cylinder_pair_case(i, seed, st, o.profile); });
  return bad ? 1 : 0;
}
