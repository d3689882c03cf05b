// Shared by the benchmarks' near-feature families (bench_line_cylinder, bench_triangle_cylinder):
// the double vector helpers used to build a feature in an oriented frame before rounding.
#pragma once

#include <cmath>

#include "certcyl/vec3.hpp"

namespace certcyl::bench {

inline Vec3<double> vcross(const Vec3<double>& a, const Vec3<double>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

inline Vec3<double> unit(const Vec3<double>& v) {
  const double n = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
  return {v.x / n, v.y / n, v.z / n};
}

}  // namespace certcyl::bench
