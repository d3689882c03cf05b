// Triangle against cylinder: ns per query, the Eberly seed's method in double against the
// certified predicate, on the same binary64 inputs, side by side.
//   eberly_double           seeds/eberly_triangle_cylinder.hpp in double (not certified)
//   certified_answer        classify_triangle_cylinder on binary64 input: semi-static double
//                           filter, double-double, then Interval_nt, then Mpzf; the counters
//                           give the fraction of queries each stage decided (static, dd,
//                           interval, exact)
//   certified_answer_gmpq   the same on Rational (Gmpq) input: binary64 values are detected
//                           and take the double path
//   certified_certificate   certified_triangle_cylinder: the answer plus its exact, checked
//                           certificate (witness point, features, separating plane)
// Inputs: "random" (coordinates uniform in [-2, 2], radius in [0.1, 1.5]) and "near" (contacts
// with the wall, a cap and a rim of the cylinder z in [0, 2], radius 1, moved by -2..2 ulps,
// and translated by random dyadic offsets).
// BM_family/<k>: the hard families in any orientation, one boundary feature each (a vertex,
// an edge or the face of the triangle on the wall, in a cap plane, on a rim), built in double
// in the cylinder's frame, rounded and moved by -3..3 ulps per coordinate, so each instance is
// within a few ulps of the contact (its side is whatever the rounding gives). Per family: Google
// Benchmark's mean of classify_triangle_cylinder cycling through the 1,024 instances, and per
// instance the median of 3 batches of 4 calls (median_ns, p99_ns, max_ns over the instances);
// read each mean against BM_family/0 (random triangles) of the same run. Every answer is
// compared with the decision in Gmpq (detail::decide_in<Rational>); a disagreement makes the
// run exit non-zero.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "checked_main.hpp"
#include "certcyl/certified/triangle_cylinder.hpp"
#include "certcyl/seeds/eberly_triangle_cylinder.hpp"
#include "near_features.hpp"

using namespace certcyl;

namespace {

struct Inputs {
  std::vector<Triangle<double>> td;
  std::vector<Cylinder<double>> cd;
  std::vector<Triangle<Rational>> tq;
  std::vector<Cylinder<Rational>> cq;

  void add(const Triangle<double>& t, const Cylinder<double>& c) {
    td.push_back(t);
    cd.push_back(c);
    const auto q = [](double x) { return Rational(x); };
    tq.push_back(t.map(q));
    cq.push_back(c.map(q));
  }
};

constexpr int kInstances = 1024;

const Inputs& random_inputs() {
  static const Inputs in = [] {
    Inputs r;
    std::mt19937_64 g(12345);
    std::uniform_real_distribution<double> u(-2, 2), rad(0.1, 1.5);
    while (static_cast<int>(r.td.size()) < kInstances) {
      const Cylinder<double> c{{u(g), u(g), u(g)}, {u(g), u(g), u(g)}, rad(g)};
      const Triangle<double> t{{Point3<double>{u(g), u(g), u(g)}, {u(g), u(g), u(g)}, {u(g), u(g), u(g)}}};
      r.add(t, c);
    }
    return r;
  }();
  return in;
}

const Inputs& near_inputs() {
  static const Inputs in = [] {
    Inputs r;
    std::mt19937_64 g(54321);
    std::uniform_int_distribution<int> ulps(-2, 2), kind(0, 4), offset(-1000, 1000);
    while (static_cast<int>(r.td.size()) < kInstances) {
      const double x = bench::ulps_from(1.0, ulps(g)), z = bench::ulps_from(2.0, ulps(g));
      Triangle<double> t;
      switch (kind(g)) {
        case 0: t = {{Point3<double>{x, 0, 1}, {3, 0, 1}, {3, 1, 1}}}; break;       // vertex on the wall
        case 1: t = {{Point3<double>{x, -1, 1}, {x, 1, 1}, {2, 0, 1}}}; break;      // edge on the wall
        case 2: t = {{Point3<double>{-1, -1, z}, {2, -1, z}, {-1, 2, z}}}; break;   // face in a cap plane
        case 3: t = {{Point3<double>{x, 0, z}, {2, 0, 3}, {2, 1, 3}}}; break;       // vertex on a rim
        default: t = {{Point3<double>{x, -1, z}, {x, 1, z}, {2, 0, 3}}}; break;     // edge on a rim
      }
      // A dyadic translation keeps every coordinate exact in binary64.
      const Vec3<double> d{offset(g) / 64.0, offset(g) / 64.0, offset(g) / 64.0};
      for (auto& v : t.v) v = v + d;
      r.add(t, Cylinder<double>{Point3<double>{0, 0, 0} + d, Point3<double>{0, 0, 2} + d, 1.0});
    }
    return r;
  }();
  return in;
}

void eberly_double(benchmark::State& state, const Inputs& in) {
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(eberly_triangle_cylinder(in.td[i], in.cd[i]));
    i = (i + 1) % in.td.size();
  }
  state.SetItemsProcessed(state.iterations());
}

void stage_counters(benchmark::State& state, const TriangleFilterStages& st) {
  const auto calls = static_cast<double>(st.calls);
  state.counters["static"] = static_cast<double>(st.semi_static) / calls;
  state.counters["dd"] = static_cast<double>(st.double_double) / calls;
  state.counters["interval"] = static_cast<double>(st.interval) / calls;
  state.counters["exact"] = static_cast<double>(st.exact) / calls;
}

void certified_answer(benchmark::State& state, const Inputs& in) {
  std::size_t i = 0;
  TriangleFilterStages st;
  for (auto _ : state) {
    benchmark::DoNotOptimize(classify_triangle_cylinder(in.td[i], in.cd[i], st));
    i = (i + 1) % in.td.size();
  }
  stage_counters(state, st);
  state.SetItemsProcessed(state.iterations());
}

void certified_answer_gmpq(benchmark::State& state, const Inputs& in) {
  std::size_t i = 0;
  TriangleFilterStages st;
  for (auto _ : state) {
    benchmark::DoNotOptimize(classify_triangle_cylinder(in.tq[i], in.cq[i], st));
    i = (i + 1) % in.tq.size();
  }
  stage_counters(state, st);
  state.SetItemsProcessed(state.iterations());
}

void certified_certificate(benchmark::State& state, const Inputs& in) {
  std::size_t i = 0;
  TriangleFilterStages st;
  for (auto _ : state) {
    const TriangleCylinderResult r = certified_triangle_cylinder(in.tq[i], in.cq[i]);
    st += r.stages;
    benchmark::DoNotOptimize(r);
    i = (i + 1) % in.tq.size();
  }
  stage_counters(state, st);
  state.SetItemsProcessed(state.iterations());
}

// ---- the near-feature families in any orientation -------------------------------------------

enum Family : int {
  kRandom,
  kVertexOnWall,   // one vertex on the wall at mid-height, the triangle outside
  kEdgeOnWall,     // an edge tangent to the wall (in the tangent plane), the third vertex outside
  kFaceOnWall,     // the triangle in a tangent plane of the wall
  kFaceInCap,      // the triangle in a cap plane, across the cap's disk
  kVertexOnRim,    // one vertex on a rim, the triangle outside
  kEdgeOnRim,      // an edge tangent to a rim circle (in the cap plane), the third vertex outside
  kVertexInCap,    // one vertex inside a cap's disk, the triangle beyond the cap
  kFamilies
};
const char* const family_names[kFamilies] = {"random",      "vertex_on_wall", "edge_on_wall",  "face_on_wall",
                                             "face_in_cap", "vertex_on_rim",  "edge_on_rim",   "vertex_in_cap"};

struct TriangleQuery {
  Triangle<double> t;
  Cylinder<double> c;
};

std::vector<TriangleQuery> make_family(int family) {
  using bench::unit;
  using bench::vcross;
  std::vector<TriangleQuery> out;
  if (family == kRandom) {
    const Inputs& r = random_inputs();
    for (std::size_t i = 0; i < r.td.size(); ++i) out.push_back({r.td[i], r.cd[i]});
    return out;
  }
  std::mt19937_64 rng(200 + family);
  std::uniform_real_distribution<double> u(-1, 1);
  const auto rv = [&] { return Vec3<double>{u(rng), u(rng), u(rng)}; };
  bench::UlpNudge nudge3(rng);
  const auto pos = [&] { return 0.25 + std::fabs(u(rng)); };
  while (static_cast<int>(out.size()) < kInstances) {
    const Vec3<double> p0 = rv(), p1 = p0 + rv() * 2.0;
    const double r = 0.25 + std::fabs(u(rng));
    const Vec3<double> A = p1 - p0, a = unit(A);
    const Vec3<double> n = unit(vcross(A, rv())), m = unit(vcross(a, n));
    const Vec3<double> W = p0 + A * (0.25 + 0.5 * std::fabs(u(rng))) + n * r;  // a wall point, normal n
    const Vec3<double> P = p1 + n * r;                                         // a rim point of cap 1
    Vec3<double> v0, v1, v2;
    switch (family) {
      case kVertexOnWall: v0 = W, v1 = W + n * pos() + m * u(rng), v2 = W + n * pos() + a * u(rng); break;
      case kEdgeOnWall: {
        const Vec3<double> d = m + a * (0.5 * u(rng));
        v0 = W - d * pos(), v1 = W + d * pos(), v2 = W + n * pos() + m * u(rng);
        break;
      }
      case kFaceOnWall: v0 = W - m * pos(), v1 = W + m * pos() + a * (0.5 * pos()), v2 = W + m * u(rng) - a * (0.5 * pos()); break;
      case kFaceInCap: v0 = p1 + n * (2 * r * u(rng)) + m * (2 * r), v1 = p1 + n * (2 * r * u(rng)) - m * (2 * r), v2 = p1 + n * (2 * r) + m * u(rng); break;
      case kVertexOnRim: v0 = P, v1 = P + n * pos() + a * u(rng), v2 = P + a * pos() + m * u(rng); break;
      case kEdgeOnRim: v0 = P - m * pos(), v1 = P + m * pos(), v2 = P + n * pos() + a * pos(); break;
      default: {  // kVertexInCap
        const Vec3<double> V = p1 + n * (r * 0.9 * u(rng)) + m * (r * 0.4 * u(rng));
        v0 = V, v1 = V + a * pos() + n * u(rng), v2 = V + a * pos() + m * u(rng);
        break;
      }
    }
    out.push_back({Triangle<double>{{nudge3(v0), nudge3(v1), nudge3(v2)}}, Cylinder<double>{nudge3(p0), nudge3(p1), r}});
  }
  return out;
}

const std::vector<TriangleQuery>& family(int k) {
  static const std::array<std::vector<TriangleQuery>, kFamilies> all = [] {
    std::array<std::vector<TriangleQuery>, kFamilies> f;
    for (int i = 0; i < kFamilies; ++i) f[i] = make_family(i);
    return f;
  }();
  return all[k];
}

int disagreements = 0;

// Nanoseconds of one decision: the median of 3 batches of 4 calls.
double call_ns(const TriangleQuery& q) {
  TriangleFilterStages st;
  return bench::median_call_ns([&] { return classify_triangle_cylinder(q.t, q.c, st); });
}

void BM_family(benchmark::State& state) {
  const std::vector<TriangleQuery>& f = family(static_cast<int>(state.range(0)));
  std::size_t i = 0;
  TriangleFilterStages st;
  for (auto _ : state) {
    benchmark::DoNotOptimize(classify_triangle_cylinder(f[i].t, f[i].c, st));
    if (++i == f.size()) i = 0;
  }
  std::vector<double> t;
  TriangleFilterStages once;
  std::array<int, 4> answers{};
  for (const TriangleQuery& q : f) {
    t.push_back(call_ns(q));
    const Answer a = classify_triangle_cylinder(q.t, q.c, once);
    ++answers[static_cast<std::size_t>(a)];
    if (a != detail::decide_in<Rational>(q.t, q.c).answer) ++disagreements;
  }
  std::sort(t.begin(), t.end());
  state.counters["median_ns"] = t[t.size() / 2];
  state.counters["p99_ns"] = t[t.size() * 99 / 100];
  state.counters["max_ns"] = t.back();
  stage_counters(state, once);
  state.counters["separated"] = answers[static_cast<std::size_t>(Answer::separated)];
  state.counters["touching"] = answers[static_cast<std::size_t>(Answer::touching)];
  state.counters["overlapping"] = answers[static_cast<std::size_t>(Answer::overlapping)];
  state.SetLabel(family_names[state.range(0)]);
}

}  // namespace

BENCHMARK_CAPTURE(eberly_double, random, random_inputs());
BENCHMARK_CAPTURE(certified_answer, random, random_inputs());
BENCHMARK_CAPTURE(certified_answer_gmpq, random, random_inputs());
BENCHMARK_CAPTURE(certified_certificate, random, random_inputs());
BENCHMARK_CAPTURE(eberly_double, near, near_inputs());
BENCHMARK_CAPTURE(certified_answer, near, near_inputs());
BENCHMARK_CAPTURE(certified_answer_gmpq, near, near_inputs());
BENCHMARK_CAPTURE(certified_certificate, near, near_inputs());

BENCHMARK(BM_family)->DenseRange(0, kFamilies - 1);

// Google Benchmark's main; exit status 1 when an answer failed its check (checked_main.hpp).
int main(int argc, char** argv) {
  return certcyl::bench::run_checked_benchmarks(argc, argv, disagreements, "bench_triangle_cylinder: answers that disagree with the decision in Gmpq");
}

