// Triangle against cylinder: ns per query, the Eberly seed's method in double against the
// certified predicate, on the same binary64 inputs, side by side.
//   eberly_double           seeds/eberly_triangle_cylinder.hpp in double (not certified)
//   certified_answer        classify_triangle_cylinder on binary64 input: semi-static double
//                           filter, then Interval_nt, then Mpzf; the counters give the fraction
//                           of queries each stage decided (static, interval, exact)
//   certified_answer_gmpq   the same on Rational (Gmpq) input: binary64 values are detected
//                           and take the double path
//   certified_certificate   certified_triangle_cylinder: the answer plus its exact, checked
//                           certificate (witness point, features, separating plane)
// Inputs: "random" (coordinates uniform in [-2, 2], radius in [0.1, 1.5]) and "near" (contacts
// with the wall, a cap and a rim of the cylinder z in [0, 2], radius 1, moved by -2..2 ulps,
// and translated by random dyadic offsets).
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "certcyl/certified/triangle_cylinder.hpp"
#include "certcyl/seeds/eberly_triangle_cylinder.hpp"

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
    const auto step = [](double x, int k) {
      for (; k > 0; --k) x = std::nextafter(x, INFINITY);
      for (; k < 0; ++k) x = std::nextafter(x, -INFINITY);
      return x;
    };
    while (static_cast<int>(r.td.size()) < kInstances) {
      const double x = step(1.0, ulps(g)), z = step(2.0, ulps(g));
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

}  // namespace

BENCHMARK_CAPTURE(eberly_double, random, random_inputs());
BENCHMARK_CAPTURE(certified_answer, random, random_inputs());
BENCHMARK_CAPTURE(certified_answer_gmpq, random, random_inputs());
BENCHMARK_CAPTURE(certified_certificate, random, random_inputs());
BENCHMARK_CAPTURE(eberly_double, near, near_inputs());
BENCHMARK_CAPTURE(certified_answer, near, near_inputs());
BENCHMARK_CAPTURE(certified_answer_gmpq, near, near_inputs());
BENCHMARK_CAPTURE(certified_certificate, near, near_inputs());

BENCHMARK_MAIN();
