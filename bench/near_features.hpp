// Shared by the benchmarks' near-feature families (bench_line_cylinder, bench_triangle_cylinder):
// the double vector helpers used to build a feature in an oriented frame before rounding, the
// nudge by a few ulps, and the per-instance timing.
#pragma once

#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <random>

#include "certcyl/vec3.hpp"

namespace certcyl::bench {

inline Vec3<double> vcross(const Vec3<double>& a, const Vec3<double>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

inline Vec3<double> unit(const Vec3<double>& v) {
  const double n = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
  return {v.x / n, v.y / n, v.z / n};
}

// x moved by k ulps (towards +infinity for k > 0).
inline double ulps_from(double x, int k) {
  for (; k > 0; --k) x = std::nextafter(x, INFINITY);
  for (; k < 0; ++k) x = std::nextafter(x, -INFINITY);
  return x;
}

// Moves a double, or each coordinate of a vector, by -3..3 ulps drawn from rng.
class UlpNudge {
 public:
  explicit UlpNudge(std::mt19937_64& rng) : rng_(rng) {}
  double operator()(double x) { return ulps_from(x, ulps_(rng_)); }
  Vec3<double> operator()(const Vec3<double>& v) { return {(*this)(v.x), (*this)(v.y), (*this)(v.z)}; }

 private:
  std::mt19937_64& rng_;
  std::uniform_int_distribution<int> ulps_{-3, 3};
};

// Nanoseconds of one call of f: the median of 3 batches of 4 consecutive calls (the clock's
// resolution is coarse next to a query of a few dozen nanoseconds).
template <class F>
double median_call_ns(F&& f) {
  std::array<double, 3> t{};
  for (double& x : t) {
    const auto s = std::chrono::steady_clock::now();
    for (int k = 0; k < 4; ++k) benchmark::DoNotOptimize(f());
    x = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - s).count() / 4;
  }
  std::sort(t.begin(), t.end());
  return t[1];
}

}  // namespace certcyl::bench
