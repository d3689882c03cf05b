// study/instance.hpp -- one input of the robustness study and its certified truth.
//
// An instance is a query kind and a flat vector of binary64 coordinates. Every method of the
// study reads exactly these values (a number type other than double converts them with
// nt::from_rational, correctly rounded at its precision), and the certified answer is the
// exact answer for the rationals these doubles denote. Keeping the input flat makes the
// failure maps and the failure hunting (perturb coordinate i by k ulps) independent of the
// query, and lets every input be written back as hexfloats and reproduced.
//
// Layout of `x`:
//   line_cylinder, ray_cylinder   origin[0..2] direction[3..5]  cylinder p0[6..8] p1[9..11] r[12]
//   segment_cylinder              p0[0..2] p1[3..5]              cylinder as above
//   line_elliptic_cylinder        origin[0..2] direction[3..5]  base[6..8] a[9..11] b[12..14] c[15..17]
//   triangle_cylinder             v0[0..2] v1[3..5] v2[6..8]     cylinder p0[9..11] p1[12..14] r[15]
//   cylinder_cylinder             a: p0[0..2] p1[3..5] r[6]      b: p0[7..9] p1[10..12] r[13]
//
// Certified signed gap (study/gap.hpp): a number whose sign is the certified answer's
// (negative separated, zero touching, positive overlapping) and whose size says how far the
// input is from a change of answer; enclosed by [gap_lo, gap_hi].
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "certcyl/answer.hpp"
#include "certcyl/primitives.hpp"

namespace certcyl::study {

enum class Query { line_cylinder, ray_cylinder, segment_cylinder, line_elliptic_cylinder, triangle_cylinder, cylinder_cylinder };

inline constexpr std::array<Query, 6> kQueries{Query::line_cylinder,          Query::ray_cylinder,
                                               Query::segment_cylinder,       Query::line_elliptic_cylinder,
                                               Query::triangle_cylinder,      Query::cylinder_cylinder};

inline constexpr std::string_view to_string(Query q) {
  switch (q) {
    case Query::line_cylinder: return "line_cylinder";
    case Query::ray_cylinder: return "ray_cylinder";
    case Query::segment_cylinder: return "segment_cylinder";
    case Query::line_elliptic_cylinder: return "line_elliptic_cylinder";
    case Query::triangle_cylinder: return "triangle_cylinder";
    case Query::cylinder_cylinder: return "cylinder_cylinder";
  }
  return "?";
}

inline constexpr std::size_t coordinate_count(Query q) {
  switch (q) {
    case Query::line_cylinder:
    case Query::ray_cylinder:
    case Query::segment_cylinder: return 13;
    case Query::line_elliptic_cylinder: return 18;
    case Query::triangle_cylinder: return 16;
    case Query::cylinder_cylinder: return 14;
  }
  return 0;
}

inline constexpr bool is_line_query(Query q) {
  return q == Query::line_cylinder || q == Query::ray_cylinder || q == Query::segment_cylinder ||
         q == Query::line_elliptic_cylinder;
}

// What the construction says the answer is, when the generator builds the input exactly
// (unknown when the construction rounds, for instance after a rotation).
enum class Expected { unknown, separated, touching, overlapping };

inline constexpr std::string_view to_string(Expected e) {
  switch (e) {
    case Expected::unknown: return "unknown";
    case Expected::separated: return "separated";
    case Expected::touching: return "touching";
    case Expected::overlapping: return "overlapping";
  }
  return "unknown";
}

// The construction's side of a degeneracy displaced by k ulps: k = 0 on it; `positive_is`
// names the answer on the side k > 0.
inline Expected expected_side(long k, Expected positive_is, Expected negative_is) {
  return k == 0 ? Expected::touching : (k > 0 ? positive_is : negative_is);
}

struct Instance {
  std::uint64_t id = 0;
  std::string family;
  Query query = Query::line_cylinder;
  std::vector<double> x;
  Expected expected = Expected::unknown;

  // Filled by certify() (study/gap.hpp).
  Answer certified = Answer::undecided;
  double gap_lo = 0, gap_hi = 0;                               // the certified signed gap
  double t_in = std::numeric_limits<double>::quiet_NaN();      // line queries: nearest double to the exact entry parameter
  bool certified_ok = false;
  // The certified answer under the ray-cast contracts (study/contract.hpp): surface entry and
  // surface hit; equal to `certified` for every query but rays and segments.
  Answer certified_entry = Answer::undecided, certified_surface_hit = Answer::undecided;
  // cylinder_cylinder only (certified/cylinder_cylinder.hpp): the stage that decided (result.stage),
  // the arithmetic of its deciding check (result.certified_by) and the highest precision of the
  // Gmpfr stage's rounds (result.gmpfr_precision, 0 if none ran); empty and 0 for the other
  // queries.
  std::string_view stage, certified_by;
  long gmpfr_precision = 0;
};

// ---- Reading the primitives out of the flat coordinates ---------------------------------------

template <class T>
Vec3<T> vec_at(const std::vector<T>& x, std::size_t i) {
  return {x[i], x[i + 1], x[i + 2]};
}
template <class T>
Cylinder<T> cylinder_at(const std::vector<T>& x, std::size_t i) {
  return {vec_at(x, i), vec_at(x, i + 3), x[i + 6]};
}
template <class T>
EllipticCylinder<T> elliptic_at(const std::vector<T>& x, std::size_t i) {
  return {vec_at(x, i), vec_at(x, i + 3), vec_at(x, i + 6), vec_at(x, i + 9)};
}
template <class T>
Line<T> line_at(const std::vector<T>& x) {
  return {vec_at(x, 0), vec_at(x, 3)};
}
template <class T>
Ray<T> ray_at(const std::vector<T>& x) {
  return {vec_at(x, 0), vec_at(x, 3)};
}
template <class T>
Segment<T> segment_at(const std::vector<T>& x) {
  return {vec_at(x, 0), vec_at(x, 3)};
}
template <class T>
Triangle<T> triangle_at(const std::vector<T>& x) {
  return {{vec_at(x, 0), vec_at(x, 3), vec_at(x, 6)}};
}

// The exact rationals the doubles denote.
inline std::vector<Rational> exact(const std::vector<double>& x) {
  std::vector<Rational> q;
  q.reserve(x.size());
  for (double d : x) q.emplace_back(d);
  return q;
}

// A double as a C99 hexfloat ("0x1.8p-3"), the exact and reproducible spelling.
inline std::string hexfloat(double d) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%a", d);
  return buf;
}

// The number of representable doubles between a and b (signed: b - a), through the ordered
// integer image of the binary64 encoding.
inline long long ulp_distance(double a, double b) {
  auto ordered = [](double d) {
    std::int64_t i;
    static_assert(sizeof i == sizeof d);
    std::memcpy(&i, &d, sizeof d);
    return i < 0 ? std::numeric_limits<std::int64_t>::min() - i : i;
  };
  const __int128 d = static_cast<__int128>(ordered(b)) - ordered(a);
  const __int128 cap = std::numeric_limits<long long>::max();
  return static_cast<long long>(d > cap ? cap : (d < -cap ? -cap : d));
}

// x moved by k representable doubles (k may be negative), through the same ordered image; the
// result stays finite (it saturates at the largest finite double).
inline double ulp_step(double x, long long k) {
  std::int64_t i;
  std::memcpy(&i, &x, sizeof x);
  __int128 o = i < 0 ? static_cast<__int128>(std::numeric_limits<std::int64_t>::min()) - i : i;
  o += k;
  const __int128 top = 0x7fefffffffffffffLL;  // the largest finite double's encoding
  if (o > top) o = top;
  if (o < -top) o = -top;
  const std::int64_t j = o < 0 ? static_cast<std::int64_t>(static_cast<__int128>(std::numeric_limits<std::int64_t>::min()) - o)
                               : static_cast<std::int64_t>(o);
  double y;
  std::memcpy(&y, &j, sizeof y);
  return y;
}

}  // namespace certcyl::study
