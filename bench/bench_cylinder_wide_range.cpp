// The certified cylinder-pair query on pairs spanning many binades: the wide-range pairs of
// tests/test_cylinder_wide_range_cases.hpp (operands scaled independently by powers of two from
// 2^-1040 to 2^1000, subnormal radii, needles stretched 2^1000 along their axis; every contact
// type; exactly touching and moved 2^-2, 2^-20, 2^-45, 2^-80 of the smaller scale either side
// along the contact normal).
//
// One family per base configuration and pair of scales: its binary64 pairs (BM_wide/...) or its
// rational pairs (BM_wide_rational/...: turned by a rational rotation, translated by 2^900 + 1/3
// and divided by 10^500 + 1), each query in both orders. BM_deep/<contact> k=<k>: each base
// contact type turned by the rational rotation of quaternion (1, 2, 3, 4), translated by
// (10^60 + 7) / (3 10^59 + 1) and 1/3, and moved 2^-k apart and 2^-k into overlap along its
// contact normal, k = 100, 1000, 5000, 10000 (rim-rim k = 5000 took minutes before the corner
// planes could go on between the rounds). BM_fuzz_found/<pair>: the slowest pairs the pair fuzz
// harness found (binary64; their answers worked out by hand, below). BM_random_wide/<n>: n random
// binary64 pairs in the pair fuzz harness's input format (fuzz/fuzz_input.hpp: each number a random
// bit pattern or a small dyadic; seed 1; pairs with a non-finite number or failing validation
// skipped), whose exponents spread over the whole range; no answer is known by construction, so an
// answer is checked only for being decided and the same in both orders. Per family: the time of
// one call on each pair (one call: the slowest pairs took seconds before the corner candidates),
// as mean, median, p99 and max, the calls above the 10 ms target (over_10ms), the slowest pair,
// the answers and the stages that decided. The exit status is 1 when
// an answer contradicts the construction or is undecided.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "../fuzz/fuzz_input.hpp"
#include "../tests/test_cylinder_wide_range_cases.hpp"
#include "checked_main.hpp"
#include "certcyl/certified/cylinder_cylinder.hpp"

namespace {

using cctest::WideCase;

int contradictions = 0;

struct Family {
  std::string name;
  std::vector<const WideCase*> cases;
};

const std::vector<WideCase>& all_cases() {
  static const std::vector<WideCase> cases = cctest::wide_range_cases();
  return cases;
}

// The family of a case: its name without the move (" d=...") and the " turned" suffix.
std::string family_name(const WideCase& c) { return c.name.substr(0, c.name.find(" d=")); }

std::vector<Family> families(bool binary64) {
  std::vector<Family> out;
  std::map<std::string, std::size_t> index;
  for (const WideCase& c : all_cases()) {
    if (c.binary64 != binary64 || (!binary64 && c.name.find(" turned") == std::string::npos)) continue;
    const std::string name = family_name(c);
    const auto [it, inserted] = index.emplace(name, out.size());
    if (inserted) out.push_back({name, {}});
    out[it->second].cases.push_back(&c);
  }
  return out;
}

// The deep families (header comment): one per contact type and k, each pair's answer known by
// construction (apart: separated; into each other: overlapping).
std::vector<Family> deep_families() {
  static std::vector<WideCase> cases;
  const cctest::Rotation R = cctest::Rotation::from_quaternion(1, 2, 3, 4);
  const cctest::Q shift(CGAL::Gmpz(std::string("1") + std::string(60, '0')) + 7, CGAL::Gmpz(std::string("3") + std::string(59, '0')) + 1);
  const cctest::Vec3<cctest::Q> t{shift, cctest::Q(1, 3), 0};
  const long ks[] = {100, 1000, 5000, 10000};
  for (const cctest::TouchingCase& base : cctest::base_touching_cases())
    for (const long k : ks)
      for (const int side : {1, -1}) {
        const cctest::Q eps = cctest::two_power(-k);
        cases.push_back({base.name + " k=" + std::to_string(k) + (side > 0 ? " d=+" : " d=-"), cctest::move(base.a, R, t),
                         cctest::move(cctest::translate(base.b, (cctest::Q(side) * eps) * base.normal), R, t),
                         side > 0 ? certcyl::Answer::separated : certcyl::Answer::overlapping, false});
      }
  std::vector<Family> out;
  for (const WideCase& c : cases) {
    if (out.empty() || out.back().name != family_name(c)) out.push_back({family_name(c), {}});
    out.back().cases.push_back(&c);
  }
  return out;
}

// The fuzz harness's slowest pairs (seconds each): contacts that are degenerate twice over (a
// line of one boundary tangent to the other's rim circle in a common plane, or a wall lying in a
// cap plane), opened into overlaps 2^-600 .. 2^-1035 thin by tilts far below an ulp of the
// contact's coordinates. The overlaps, by hand (r = 0x1.38p-2):
//  rim_line_tangent_400: a's cap plane y ~ 0 (tilt 2 / 2^401 in x) against b's wall, tangent to
//    it along x = r, y = 0 (b tilted 2^-411 toward y < 0), meeting a's rim at (r, 0, 99): the
//    cap plane lies about 2^-400 above b's lowest line there.
//  rim_line_tangent_600: a's tube top line x = 0, z = r against b's cap plane z = r, tangent to
//    b's rim at (0, r, r); a's axis sits 2^-394 toward b, b's cap plane tilts about 2^-410 in y: both
//    hold points 2^-198 before the tangent point and about 2^-608 below z = r.
//  pancake_rim_cap: a disk 2^-828 thick whose rim reaches b's cap plane at (0, 3/4, 0): its
//    upper face's rim point crosses the plane by about 2^-829.
//  wall_on_tilted_cap: b's lowest line lies in z = 2 and crosses a's unit cap disk near (1, 0);
//    a's axis is tilted by about 2^-1035, which lifts its cap plane by about 2^-1035 at x ~ 1.
//  needles_cap_on_wall: a along y (2^422 long, radius 45/2); b's cap disk at (45/2, 45/2, 45/2)
//    touches a's wall at (45/2, 45/2, 0) and is tilted about 2^-422 into it: the common interior
//    is about 2^-560 deep, 2^-140 from the touching point (test_cylinder_wide_range.cpp).
//  rim_line_quarter: rim_line_tangent_400 with b's end at x = -1/4, where b's lowest line crosses
//    a's rim inside its cap disk.
std::vector<Family> fuzz_found_families() {
  static std::vector<WideCase> cases;
  using cctest::Q;
  const auto cyl = [](double x0, double y0, double z0, double x1, double y1, double z1, double r) {
    return cctest::Cylinder<Q>{{Q(x0), Q(y0), Q(z0)}, {Q(x1), Q(y1), Q(z1)}, Q(r)};
  };
  const double r = 0x1.38p-2;
  const auto add = [&](const std::string& name, const cctest::Cylinder<Q>& a, const cctest::Cylinder<Q>& b) {
    cases.push_back({name, a, b, certcyl::Answer::overlapping, true});
  };
  add("rim_line_tangent_400", cyl(0, 0, 0x1.8cp+6, 2, -0x1.01414fb0000fap+401, 0x1.72727275a27d5p-397, r),
      cyl(r, 0, 0x1.00002p+417, r, r, r, r));
  add("rim_line_tangent_600", cyl(0, 2, 0, 0x1.8cp+6, -0x1.01414fbp+401, 0x1.72727275a27d5p-397, r),
      cyl(r, -0x1.8cp+6, 0x1.0000224p+417, r, r, r, r));
  add("pancake_rim_cap", cyl(0, 0, 0, 0, 0, 0x1.fp-829, 0x1.8p-1), cyl(0x1.8p-1, 0x1.7p+0, 0x1.8p-1, 0x1.8p-1, 0x1.8p-1, 0, 0x1.2p+3));
  add("needles_cap_on_wall", cyl(0, 0, 0, 0, 0x1p+422, 0, 22.5), cyl(0x1p+422, 8.75, 22.5, 22.5, 22.5, 22.5, 22.5));
  add("rim_line_quarter", cyl(0, 0, 0x1.8cp+6, 2, -0x1.01414fb0000fap+401, 0x1.72727275a27d5p-397, r),
      cyl(r, 0, 0x1.00002p+417, -0.25, r, r, r));
  add("wall_on_tilted_cap", cyl(0x0.000fffb0008p-1022, 0, 0, 0, 0, 2, 1), cyl(-1, 0x1.8p+6, 0x1.8p+1, 1, 0, 0x1.8p+1, 1));
  // A pancake whose rim meets a wall and a cap edge of the other at one point (the witness:
  // tests/test_cylinder_wide_range.cpp, pancake_on_a_rim_wall_and_cap_edge_is_overlapping).
  const double s = 0x1.1cp-1;
  add("pancake_rim_wall_cap_edge", cyl(0, 0, 0, 0, 0, 0x1.8000001ffff2bp-425, s), cyl(0, s, s, s, 0x1.f8p-1, s, s));
  std::vector<Family> out;
  for (const WideCase& c : cases) out.push_back({c.name, {&c}});
  return out;
}

// A family's counters (the times t of its calls in us: mean, median, p99, max, the number over the
// 10 ms target) and its label (the slowest call and the stages that decided).
void report(benchmark::State& state, std::vector<double>& t, const std::map<std::string, int>& stages, const std::string& slowest) {
  const double over = static_cast<double>(std::count_if(t.begin(), t.end(), [](double us) { return us > 10000; }));
  std::sort(t.begin(), t.end());
  double mean = 0;
  for (double x : t) mean += x;
  mean /= static_cast<double>(t.size());
  state.counters["pairs"] = static_cast<double>(t.size());
  state.counters["mean_us"] = mean;
  state.counters["p50_us"] = t[t.size() / 2];
  state.counters["p99_us"] = t[t.size() * 99 / 100];
  state.counters["max_us"] = t.back();
  state.counters["over_10ms"] = over;
  std::string label = "slowest " + slowest + ";";
  for (const auto& [s, n] : stages) label += " " + s + ":" + std::to_string(n);
  state.SetLabel(label);
}

void run_family(benchmark::State& state, const Family& f) {
  std::vector<double> t;
  std::map<std::string, int> stages;
  std::string slowest;
  double slowest_time = -1;
  for (auto _ : state) {
    for (const WideCase* c : f.cases)
      for (const bool swap : {false, true}) {
        const cctest::Cylinder<cctest::Q>& a = swap ? c->b : c->a;
        const cctest::Cylinder<cctest::Q>& b = swap ? c->a : c->b;
        const auto start = std::chrono::steady_clock::now();
        const certcyl::CylinderCylinderResult r = certcyl::certified_cylinder_cylinder(a, b);
        const double us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
        t.push_back(us);
        ++stages[std::string(certcyl::to_string(r.stage))];
        const std::string label = c->name.substr(c->name.find(" d=") + 1) + (swap ? " swapped" : "");
        if (us > slowest_time) {
          slowest_time = us;
          slowest = label;
        }
        if (r.answer != c->expected) {
          ++contradictions;
          std::fprintf(stderr, "bench_cylinder_wide_range: %s%s: answer %s\n", c->name.c_str(), swap ? " swapped" : "",
                       std::string(certcyl::to_string(r.answer)).c_str());
        }
      }
  }
  report(state, t, stages, slowest);
}

// The random wide pairs (header comment), both orders each.
void run_random_wide(benchmark::State& state, int n) {
  std::vector<std::pair<certcyl::Cylinder<certcyl::Rational>, certcyl::Cylinder<certcyl::Rational>>> pairs;
  std::mt19937_64 rng(1);
  while (static_cast<int>(pairs.size()) < n) {
    std::uint8_t bytes[126];
    for (std::uint8_t& b : bytes) b = static_cast<std::uint8_t>(rng() & 0xff);
    certcyl::fuzz::ByteReader in(bytes, sizeof bytes);
    const certcyl::Cylinder<certcyl::Rational> a = in.cylinder(), b = in.cylinder();
    if (!in.finite()) continue;
    try {
      certcyl::validate(a, "a");
      certcyl::validate(b, "b");
    } catch (const certcyl::InvalidInput&) {
      continue;
    }
    pairs.emplace_back(a, b);
  }
  std::vector<double> t;
  std::map<std::string, int> stages;
  int slowest = -1;
  double slowest_us = -1;
  for (auto _ : state) {
    for (int i = 0; i < n; ++i) {
      certcyl::Answer answers[2];
      for (const int swap : {0, 1}) {
        const auto& a = swap ? pairs[i].second : pairs[i].first;
        const auto& b = swap ? pairs[i].first : pairs[i].second;
        const auto start = std::chrono::steady_clock::now();
        const certcyl::CylinderCylinderResult r = certcyl::certified_cylinder_cylinder(a, b);
        const double us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
        if (us > slowest_us) slowest_us = us, slowest = i;
        t.push_back(us);
        ++stages[std::string(certcyl::to_string(r.stage))];
        answers[swap] = r.answer;
      }
      if (answers[0] == certcyl::Answer::undecided || answers[0] != answers[1]) {
        ++contradictions;
        std::fprintf(stderr, "bench_cylinder_wide_range: random wide pair %d: answers %s and %s\n", i,
                     std::string(certcyl::to_string(answers[0])).c_str(), std::string(certcyl::to_string(answers[1])).c_str());
      }
    }
  }
  report(state, t, stages, "pair " + std::to_string(slowest));
}

const bool registered = [] {
  for (const bool binary64 : {true, false}) {
    static std::vector<Family> store[2];
    store[binary64] = families(binary64);
    for (const Family& f : store[binary64])
      benchmark::RegisterBenchmark(((binary64 ? "BM_wide/" : "BM_wide_rational/") + f.name).c_str(),
                                   [&f](benchmark::State& s) { run_family(s, f); })
          ->Unit(benchmark::kMillisecond)
          ->Iterations(1);
  }
  static const std::vector<Family> deep = deep_families();
  for (const Family& f : deep)
    benchmark::RegisterBenchmark(("BM_deep/" + f.name).c_str(), [&f](benchmark::State& s) { run_family(s, f); })
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1);
  benchmark::RegisterBenchmark("BM_random_wide/1500", [](benchmark::State& s) { run_random_wide(s, 1500); })
      ->Unit(benchmark::kMillisecond)
      ->Iterations(1);
  static const std::vector<Family> fuzz_found = fuzz_found_families();
  for (const Family& f : fuzz_found)
    benchmark::RegisterBenchmark(("BM_fuzz_found/" + f.name).c_str(), [&f](benchmark::State& s) { run_family(s, f); })
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1);
  return true;
}();

}  // namespace

// Google Benchmark's main; exit status 1 when an answer failed its check (checked_main.hpp).
int main(int argc, char** argv) {
  return certcyl::bench::run_checked_benchmarks(argc, argv, contradictions, "bench_cylinder_wide_range: answers that contradict the construction or are undecided");
}

