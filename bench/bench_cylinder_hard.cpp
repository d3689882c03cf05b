// The certified cylinder-pair query on the hard inputs: pairs exactly touching and near touching,
// in every contact type, side by side in one run with the same query on random pairs and with
// FCL on the same pairs.
//
// Families: the seven touching configurations of tests/test_cylinder_cylinder_cases.hpp (cap-cap,
// cap-wall, wall-wall crossing, wall-wall parallel, rim-cap, rim-wall, rim-rim) in three frames:
//   axis-aligned  the configuration scaled to integer coordinates, plus an integer translation;
//   rotated       turned by a rational rotation (a random integer quaternion), scaled to integer
//                 coordinates again, plus a translation;
//   rounded       turned by a random double rotation and rounded to binary64: within about one
//                 ulp of touching, on either side.
// In the first two frames the pair touches exactly, and is moved apart (+) or into each other
// (-) along its contact normal by
//   1 ulp    a translation by 2 ulp(max |coordinate|) times the signs of the normal's coordinates;
//   2^-k     for k = 20, 40: 2^-k M times the integer normal, M the largest coordinate (binary64);
//   2^-k     for k = 60, 80: exactly 2^-k M times the unit normal, as Rational input (binary64
//            cannot move an integer configuration by that little).
// Every pair is binary64 except the 2^-60 and 2^-80 families. 16 instances per family.
//
// Per family: the time of one query (median of 3 calls on each instance), as mean, median, p99
// and max over the instances, each also as a ratio to the mean on the random pairs of
// bench_cylinder_cylinder measured right before and right after the family's instances (the
// mean of the two, `random_ns`: this machine's speed drifts by up to 1.7x between minutes, so a
// mean taken once at start-up, `BM_random_pairs`, is not side by side); the answers; the stage that
// decided most instances; and FCL's agreement with the certified answer (a collision reported
// for touching and overlapping pairs). The exit status is 1 when an answer contradicts the
// construction or is undecided. BM_hard_refine_off repeats the 2^-60 families with the
// refine stage off (the Gmpfr stage then decides), for the stage's effect in the same run.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "checked_main.hpp"
#include "../tests/test_cylinder_cylinder_cases.hpp"
#include "certcyl/certified/cylinder_cylinder.hpp"
#include "cylinder_pairs.hpp"

namespace {

using certcyl::Cylinder;
using certcyl::Point3;
using certcyl::Rational;
using certcyl::Vec3;
using namespace certcyl_bench;

// One instance: binary64 operands, or rational ones (the 2^-60 and 2^-80 families).
struct HardPair {
  bool binary64 = true;
  Cylinder<double> a, b;
  Cylinder<Rational> qa, qb;
};

struct Family {
  std::string name;  // "rim-wall, rotated, -2^-40"
  std::vector<HardPair> pairs;
  // The answer known by construction: touching; separated when moved apart along a contact
  // normal; overlapping when moved into each other and the contact has one normal (every type
  // but rim-rim). Unknown (undecided here) otherwise.
  certcyl::Answer expected = certcyl::Answer::undecided;
};

// Answers that contradict the construction, or undecided ones, over the run: the exit status.
int contradictions = 0;

double to_d(const Rational& q) {
  double d;
  if (!certcyl::detail::exact_double(q, d)) throw std::logic_error("bench_cylinder_hard: a coordinate is not binary64");
  return d;
}

Cylinder<Rational> scaled(const Cylinder<Rational>& c, const Rational& s, const Vec3<Rational>& t) {
  return {s * c.p0 + t, s * c.p1 + t, s * c.radius};
}

Rational largest(const Cylinder<Rational>& a, const Cylinder<Rational>& b) {
  Rational m = 0;
  for (const Cylinder<Rational>* c : {&a, &b})
    for (const Rational* q : {&c->p0.x, &c->p0.y, &c->p0.z, &c->p1.x, &c->p1.y, &c->p1.z})
      m = std::max(m, *q < 0 ? Rational(-*q) : *q);
  return m;
}

// The exactly touching pair of case c in an integer frame: rotated by the quaternion's rational
// rotation (none when it is null), scaled by the least common multiple of the denominators and
// translated by an integer vector; with its integer contact normal.
struct IntegerPair {
  Cylinder<Rational> a, b;
  Vec3<Rational> normal;  // integer, from a to b
  Rational length;        // |normal| (an integer)
};

IntegerPair integer_frame(const cctest::TouchingCase& c, const std::array<int, 4>* quaternion, std::mt19937_64& g) {
  std::uniform_int_distribution<int> shift(-50, 50);
  Cylinder<Rational> a = c.a, b = c.b;
  Vec3<Rational> n = c.normal;  // a unit vector
  if (quaternion) {
    const auto& q = *quaternion;
    const cctest::Rotation R = cctest::Rotation::from_quaternion(q[0], q[1], q[2], q[3]);
    a = cctest::move(a, R, {0, 0, 0});
    b = cctest::move(b, R, {0, 0, 0});
    n = R(n);
  }
  // The least common multiple of every denominator, times 2 (a unit of margin).
  CGAL::Gmpz l = 2;
  for (const Cylinder<Rational>* cy : {&a, &b})
    for (const Rational* x : {&cy->p0.x, &cy->p0.y, &cy->p0.z, &cy->p1.x, &cy->p1.y, &cy->p1.z, &cy->radius})
      mpz_lcm(l.mpz(), l.mpz(), mpq_denref(x->mpq()));
  for (const Rational* x : {&n.x, &n.y, &n.z}) mpz_lcm(l.mpz(), l.mpz(), mpq_denref(x->mpq()));
  const Rational scale(l);
  const Vec3<Rational> t{shift(g), shift(g), shift(g)};
  return {scaled(a, scale, t), scaled(b, scale, t), scale * n, scale};
}

Cylinder<double> binary64(const Cylinder<Rational>& c) { return c.map(to_d); }

Rational abs(const Rational& x) { return x < 0 ? Rational(-x) : x; }

// The integer vector v divided by the greatest common divisor of its entries.
Vec3<Rational> primitive(const Vec3<Rational>& v) {
  CGAL::Gmpz g = 0;
  for (const Rational* q : {&v.x, &v.y, &v.z}) mpz_gcd(g.mpz(), g.mpz(), mpq_numref(q->mpq()));
  return v / Rational(g);
}

Cylinder<Rational> translated(const Cylinder<Rational>& c, const Vec3<Rational>& v) { return {c.p0 + v, c.p1 + v, c.radius}; }

Rational two_power(int k) {
  Rational r = 1;
  for (int i = 0; i < std::abs(k); ++i) r = k > 0 ? r * 2 : r / 2;
  return r;
}

// The largest power of two <= x (x > 0).
Rational floor_two_power(const Rational& x) {
  Rational p = 1;
  while (p > x) p = p / 2;
  while (p * 2 <= x) p = p * 2;
  return p;
}

std::vector<Family> make_families() {
  std::vector<Family> out;
  std::mt19937_64 g(20261125);
  std::uniform_int_distribution<int> qd(-3, 3);
  std::normal_distribution<double> gauss;
  constexpr int kInstances = 16;
  const std::vector<cctest::TouchingCase> cases = cctest::base_touching_cases();
  const std::vector<std::string> distances = {"touching", "+1 ulp", "-1 ulp", "+2^-20", "-2^-20", "+2^-40", "-2^-40",
                                              "+2^-60", "-2^-60", "+2^-80", "-2^-80"};
  for (const cctest::TouchingCase& c : cases) {
    for (const bool rotated : {false, true}) {
      for (const std::string& distance : distances) {
        Family f{c.name + (rotated ? ", rotated, " : ", axis-aligned, ") + distance, {}, certcyl::Answer::undecided};
        if (distance == "touching") f.expected = certcyl::Answer::touching;
        else if (distance[0] == '+') f.expected = certcyl::Answer::separated;
        else if (c.type != "rim-rim") f.expected = certcyl::Answer::overlapping;
        for (int i = 0; i < kInstances; ++i) {
          std::array<int, 4> q{};
          do {
            q = {qd(g), qd(g), qd(g), qd(g)};
          } while (q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3] == 0);
          const IntegerPair p = integer_frame(c, rotated ? &q : nullptr, g);
          const Rational M = largest(p.a, p.b);
          const int sign = distance[0] == '-' ? -1 : 1;
          Cylinder<Rational> b = p.b;
          bool rational = false;
          if (distance == "touching") {
          } else if (distance.find("ulp") != std::string::npos) {
            // 2 ulp of the largest coordinate: a multiple of the ulp of every coordinate.
            const Rational u = floor_two_power(M) * two_power(-51);
            const auto sgn = [](const Rational& x) { return x > 0 ? 1 : x < 0 ? -1 : 0; };
            b = translated(b, Vec3<Rational>{sign * sgn(p.normal.x) * u, sign * sgn(p.normal.y) * u, sign * sgn(p.normal.z) * u});
          } else {
            const int k = std::stoi(distance.substr(4));  // "+2^-20" -> 20
            if (k <= 40) {
              // The normal's primitive integer multiple N (small entries), times a power of two
              // near 2^-k M / max |N_i|: exact in binary64.
              const Vec3<Rational> N = primitive(p.normal);
              const Rational big = std::max({abs(N.x), abs(N.y), abs(N.z)});
              b = translated(b, (sign * floor_two_power(M / big) * two_power(-k)) * N);
            } else {
              // p.normal is scale n with n a unit vector: its length is p.length.
              b = translated(b, (sign * M * two_power(-k) / p.length) * p.normal);
              rational = true;
            }
          }
          HardPair h;
          h.qa = p.a;
          h.qb = b;
          h.binary64 = !rational;
          if (!rational) {
            try {
              h.a = binary64(p.a);
              h.b = binary64(b);
            } catch (const std::logic_error& e) {
              throw std::logic_error(std::string(e.what()) + " in " + f.name);
            }
          }
          f.pairs.push_back(h);
        }
        out.push_back(std::move(f));
      }
    }
    // Rounded: a random double rotation, applied in double (the pair is then within about an
    // ulp of touching, on either side).
    Family f{c.name + ", rounded, ~1 ulp", {}, certcyl::Answer::undecided};
    for (int i = 0; i < kInstances; ++i) {
      const cctest::RoundedRotation R(g, gauss, 20);
      HardPair h;
      h.a = R.rounded(c.a);
      h.b = R.rounded(c.b);
      h.qa = h.a.map([](double x) { return Rational(x); });
      h.qb = h.b.map([](double x) { return Rational(x); });
      f.pairs.push_back(h);
    }
    out.push_back(std::move(f));
  }
  return out;
}

const std::vector<Family>& families() {
  static const std::vector<Family> f = make_families();
  return f;
}

certcyl::CylinderCylinderResult query(const HardPair& p, const certcyl::CylinderCylinderOptions& o) {
  return p.binary64 ? certcyl::certified_cylinder_cylinder(p.a, p.b, o) : certcyl::certified_cylinder_cylinder(p.qa, p.qb, o);
}

// Nanoseconds of one call of f: the median of 3 calls.
template <class F>
double call_ns(F f) {
  std::array<double, 3> t{};
  for (double& x : t) {
    const auto s = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(f());
    x = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - s).count();
  }
  std::sort(t.begin(), t.end());
  return t[1];
}

// The mean time of the query on the random pairs of bench_cylinder_cylinder (4,000 pairs, the
// default options, binary64 input): the best of 5 passes, measured now.
double random_mean_ns() {
  static const std::vector<std::pair<Cylinder<double>, Cylinder<double>>> ps = [] {
    std::mt19937_64 g(20240611);
    std::vector<std::pair<Cylinder<double>, Cylinder<double>>> v;
    for (int i = 0; i < 4000; ++i) {
      const Cylinder<double> a = random_cylinder(g);
      v.emplace_back(a, random_cylinder(g));
    }
    return v;
  }();
  double best = INFINITY;
  for (int rep = 0; rep < 5; ++rep) {
    const auto s = std::chrono::steady_clock::now();
    for (const auto& [a, b] : ps) benchmark::DoNotOptimize(certcyl::certified_cylinder_cylinder(a, b).answer);
    best = std::min(best, std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - s).count() / static_cast<double>(ps.size()));
  }
  return best;
}

// The random-pair mean once, at start-up (the families' ratios use their own, run_family).
void BM_random_pairs(benchmark::State& state) {
  double mean = 0;
  for (auto _ : state) mean = random_mean_ns();
  state.counters["mean_ns"] = mean;
}

void run_family(benchmark::State& state, const Family& f, bool refine) {
  certcyl::CylinderCylinderOptions o;
  o.refine = refine;
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(query(f.pairs[i], o).answer);
    if (++i == f.pairs.size()) i = 0;
  }
  const double random_before = random_mean_ns();
  std::vector<double> t;
  std::map<std::string, int> stages;
  std::array<int, 4> answers{};
  int fcl_agree = 0, fcl_run = 0;
  for (const HardPair& p : f.pairs) {
    t.push_back(call_ns([&] { return query(p, o).answer; }));
    const certcyl::CylinderCylinderResult r = query(p, o);
    ++stages[std::string(certcyl::to_string(r.stage))];
    ++answers[static_cast<std::size_t>(r.answer)];
    if (r.answer == certcyl::Answer::undecided || (f.expected != certcyl::Answer::undecided && r.answer != f.expected)) {
      ++contradictions;
      std::fprintf(stderr, "bench_cylinder_hard: %s: answer %s\n", f.name.c_str(), std::string(certcyl::to_string(r.answer)).c_str());
    }
#ifdef CERTCYL_HAVE_FCL
    if (p.binary64) {
      ++fcl_run;
      fcl_agree += fcl_collide(to_fcl(p.a, p.b)) == (r.answer != certcyl::Answer::separated);
    }
#endif
  }
  std::sort(t.begin(), t.end());
  double mean = 0;
  for (double x : t) mean += x;
  mean /= static_cast<double>(t.size());
  const double random = (random_before + random_mean_ns()) / 2;
  const auto at = [&t](double q) { return t[std::min(t.size() - 1, static_cast<std::size_t>(std::ceil(q * static_cast<double>(t.size())) - 1))]; };
  state.counters["mean_us"] = mean / 1e3;
  state.counters["p50_us"] = at(0.5) / 1e3;
  state.counters["p99_us"] = at(0.99) / 1e3;
  state.counters["max_us"] = t.back() / 1e3;
  state.counters["x_mean"] = mean / random;
  state.counters["x_p99"] = at(0.99) / random;
  state.counters["random_ns"] = random;
  state.counters["separated"] = answers[static_cast<std::size_t>(certcyl::Answer::separated)];
  state.counters["touching"] = answers[static_cast<std::size_t>(certcyl::Answer::touching)];
  state.counters["overlapping"] = answers[static_cast<std::size_t>(certcyl::Answer::overlapping)];
  state.counters["undecided"] = answers[static_cast<std::size_t>(certcyl::Answer::undecided)];
  if (fcl_run > 0) state.counters["fcl_agree"] = static_cast<double>(fcl_agree) / fcl_run;
  std::string label;
  for (const auto& [s, n] : stages) label += (label.empty() ? "" : " ") + s + ":" + std::to_string(n);
  state.SetLabel(label);
}

const bool registered = [] {
  benchmark::RegisterBenchmark("BM_random_pairs", BM_random_pairs)->Iterations(1);
  for (const Family& f : families())
    benchmark::RegisterBenchmark(("BM_hard/" + f.name).c_str(), [&f](benchmark::State& s) { run_family(s, f, true); })->Unit(benchmark::kMicrosecond);
  for (const Family& f : families())
    if (f.name.find("2^-60") != std::string::npos)
      benchmark::RegisterBenchmark(("BM_hard_refine_off/" + f.name).c_str(), [&f](benchmark::State& s) { run_family(s, f, false); })
          ->Unit(benchmark::kMicrosecond)
          ->Iterations(f.pairs.size());
  return true;
}();

}  // namespace

// Google Benchmark's main; exit status 1 when an answer failed its check (checked_main.hpp).
int main(int argc, char** argv) {
  return certcyl::bench::run_checked_benchmarks(argc, argv, contradictions, "bench_cylinder_hard: answers that contradict the construction or are undecided");
}

