// study/families.hpp -- the inputs of the robustness study: the hard-case families of
// design note section 6 for every query, and uniform random inputs.
//
// Every family places a configuration at a degeneracy and then moves one input coordinate (the
// line families: the radius, or a cap's position) by k ulps (k = 0 on the degeneracy, k of either sign and of every size up to 2^40 ulps). The
// "aligned" families build the input exactly in binary64 (dyadic coordinates with few bits,
// axes along coordinate axes), so the answer is known by construction for every k; their
// `expected` field is checked against the certified answer by the study. The "rotated"
// families put the same configuration in general position: the construction rounds, so only
// the certified query knows the answer (expected = unknown).
//
// Cylinder of an aligned family: centre c, axis e_a (a coordinate axis, either sign), radial
// directions e_1, e_2 (the two others), radius r, height h; p0 = c - (h/2) e_a, p1 = c + (h/2) e_a.
//
// Families (query: name -- configuration at k = 0; side for k > 0 / k < 0):
//   line, ray, segment:
//     tangent            line tangent to the wall, tilted toward the axis; outward separated
//     near_parallel      tangent line at angle 2^-j (j up to 50) to the axis
//     rim                line grazing a rim circle from outside (through the rim, leaving the solid)
//     on_wall            line on the wall, parallel to the axis
//     cap_plane          chord lying in a cap plane
//     far                tangent, translated by 2^20..2^40
//     extreme_scale      tangent, scaled by 2^-40..2^40, aspect ratio r / h down to 2^-20
//     ends_on_wall       (ray, segment) the range ends on the wall, coming from outside
//     tangent_rotated    tangent in general position (rounded)
//     rim_rotated        rim graze in general position (rounded)
//     uniform            random line and cylinder in [-2, 2]^3
//   line against elliptic cylinder (frames with shear, a, b not orthogonal, c oblique):
//     e_tangent, e_parallel_axis (inside, on and outside the wall: the seed's a = b = 0 case),
//     e_rim, e_cap_plane, e_tangent_oblique (rounded), uniform
//   triangle:
//     t_vertex_wall, t_edge_wall, t_face_cap, t_vertex_rim, t_axis_plane (the plane contains
//     the axis direction, away from the axis: separated for every k), t_edge_rotated (rounded),
//     uniform
//   cylinder pairs:
//     c_cap_cap, c_wall_parallel, c_wall_crossing, c_cap_wall, c_near_parallel (skew axes at
//     angle 2^-j, wall contact), c_rim_cap, c_rim_wall, c_rim_rim (a's rim against b's cap,
//     wall or rim; a's radius moved: larger overlaps, except rim-rim, which stays touching),
//     c_coaxial
//     (nested, overlapping), c_equal_midpoints, c_crossing_rotated (rounded), uniform
#pragma once

#include <cmath>
#include <cstdint>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "study/instance.hpp"

namespace certcyl::study {

// A reproducible generator (the raw 64-bit output of mt19937_64; no library distribution, so
// the same seed gives the same inputs with every standard library).
class Rng {
 public:
  explicit Rng(std::uint64_t seed) : engine_(seed) {}
  std::uint64_t next() { return engine_(); }
  // An integer in [lo, hi].
  long long integer(long long lo, long long hi) { return lo + static_cast<long long>(next() % static_cast<std::uint64_t>(hi - lo + 1)); }
  // A uniform double in [lo, hi) (53 random bits).
  double uniform(double lo, double hi) { return lo + (hi - lo) * (static_cast<double>(next() >> 11) * 0x1p-53); }
  // A dyadic number m / 2^bits with m in [lo 2^bits, hi 2^bits]: exact with few bits.
  double dyadic(double lo, double hi, int bits = 8) {
    const double s = std::ldexp(1.0, bits);
    return static_cast<double>(integer(static_cast<long long>(lo * s), static_cast<long long>(hi * s))) / s;
  }
  bool coin() { return (next() >> 63) != 0; }

 private:
  std::mt19937_64 engine_;
};

// An ulp displacement for instance number i of a family: 0, then +-1, +-2, ..., growing on a
// log scale up to 2^40, with random signs and sizes.
inline long long ulp_offset(Rng& rng, std::size_t i) {
  if (i % 8 == 0) return 0;
  const int e = static_cast<int>(rng.integer(0, 40));
  const long long mag = (1LL << e) + rng.integer(0, (1LL << e) / 2);
  return rng.coin() ? mag : -mag;
}

struct FamilyInput {
  std::vector<double> x;
  Expected expected = Expected::unknown;
};

struct Family {
  std::string name;
  std::vector<Query> queries;
  // Builds one input for the query with displacement k (ulps).
  std::function<FamilyInput(Rng&, Query, long long k)> make;
};

namespace detail {

using V = Vec3<double>;

inline V axis_unit(int i, double sign) {
  V v{0, 0, 0};
  (i == 0 ? v.x : (i == 1 ? v.y : v.z)) = sign;
  return v;
}
inline double& coord(V& v, int i) { return i == 0 ? v.x : (i == 1 ? v.y : v.z); }

// An aligned cylinder: centre, axis index and sign, radius, height, the radial axes.
struct Aligned {
  V c;
  int ia = 2, i1 = 0, i2 = 1;
  double sa = 1, s1 = 1;
  double r = 1, h = 2;
  V ea() const { return axis_unit(ia, sa); }
  V e1() const { return axis_unit(i1, s1); }
  V e2() const { return axis_unit(i2, 1); }
  V p0() const { return c - (h / 2) * ea(); }
  V p1() const { return c + (h / 2) * ea(); }
};

inline Aligned random_aligned(Rng& rng, double scale = 1, double translate = 0) {
  Aligned a;
  a.ia = static_cast<int>(rng.integer(0, 2));
  a.i1 = (a.ia + 1 + static_cast<int>(rng.integer(0, 1))) % 3;
  a.i2 = 3 - a.ia - a.i1;
  a.sa = rng.coin() ? 1 : -1;
  a.s1 = rng.coin() ? 1 : -1;
  a.c = {translate + scale * rng.dyadic(-4, 4), translate + scale * rng.dyadic(-4, 4), translate + scale * rng.dyadic(-4, 4)};
  a.r = scale * rng.dyadic(0.25, 2);
  a.h = scale * rng.dyadic(0.5, 4) * 2;
  return a;
}

// Moves coordinate i of v by k ulps; returns which answer k > 0 gives when moving coordinate i
// of a point along +e_i is "outward" (sign_out = +1) or "inward" (-1).
inline void nudge(V& v, int i, long long k) { coord(v, i) = ulp_step(coord(v, i), k); }

inline Expected side(long long k, double outward_sign, Expected outward, Expected inward) {
  if (k == 0) return Expected::touching;
  return (k > 0) == (outward_sign > 0) ? outward : inward;
}

// The line families move the radius by k ulps (the line stays exact in every range form):
// a larger radius (k > 0) overlaps.
inline Expected radius_side(long long k) {
  return k == 0 ? Expected::touching : (k > 0 ? Expected::overlapping : Expected::separated);
}

inline void push(std::vector<double>& x, const V& v) { x.insert(x.end(), {v.x, v.y, v.z}); }

inline void push_cylinder(std::vector<double>& x, const V& p0, const V& p1, double r) {
  push(x, p0);
  push(x, p1);
  x.push_back(r);
}

// A line (origin O, direction d) in the form of the query: a line as is, a ray starting 4d
// before O, a segment from O - 4d to O + 4d (exact for the aligned families: d is dyadic).
inline void push_line_like(std::vector<double>& x, Query q, const V& O, const V& d) {
  if (q == Query::line_cylinder || q == Query::line_elliptic_cylinder) {
    push(x, O), push(x, d);
  } else if (q == Query::ray_cylinder) {
    push(x, O - 4.0 * d), push(x, d);
  } else {
    push(x, O - 4.0 * d), push(x, O + 4.0 * d);
  }
}

inline V random_vec(Rng& rng, double lo, double hi) { return {rng.uniform(lo, hi), rng.uniform(lo, hi), rng.uniform(lo, hi)}; }

inline V normalized(const V& v) {
  const double n = std::sqrt(dot(v, v));
  return (1 / n) * v;
}

// A random cylinder in general position and a unit vector n perpendicular to its axis (both in
// double, rounded).
struct Rotated {
  V p0, p1, A, n, m;
  double r;
};
inline Rotated random_rotated(Rng& rng) {
  Rotated R;
  R.p0 = random_vec(rng, -2, 2);
  R.p1 = R.p0 + random_vec(rng, -2, 2);
  R.A = R.p1 - R.p0;
  R.n = normalized(cross(R.A, random_vec(rng, -1, 1)));
  R.m = normalized(cross(R.A, R.n));
  R.r = rng.uniform(0.2, 1.5);
  return R;
}

// The index of the largest |component|.
inline int major(const V& v) {
  const double a = std::fabs(v.x), b = std::fabs(v.y), c = std::fabs(v.z);
  return a >= b && a >= c ? 0 : (b >= c ? 1 : 2);
}

}  // namespace detail

// ---- The families -----------------------------------------------------------------------------

inline std::vector<Family> line_families() {
  using namespace detail;
  const std::vector<Query> lrs{Query::line_cylinder, Query::ray_cylinder, Query::segment_cylinder};
  const std::vector<Query> rs{Query::ray_cylinder, Query::segment_cylinder};
  std::vector<Family> f;
  // Tangent: O = c + r e1 + z ea, d = e2 + tilt ea; radial distance^2 = (r + delta)^2 + t^2.
  auto tangent = [](Rng& rng, Query q, long long k, double scale, double translate, int tilt_exp) {
    Aligned a = random_aligned(rng, scale, translate);
    if (tilt_exp > 0) a.h = a.r * std::ldexp(1.0, static_cast<int>(rng.integer(0, 20)));  // aspect r/h down to 2^-20
    const V O = a.c + a.r * a.e1() + (a.h * rng.dyadic(-0.4, 0.4)) * a.ea();
    const V d = tilt_exp > 0 ? V(scale * a.e2() + scale * std::ldexp(rng.dyadic(-1, 1), -tilt_exp) * a.ea())
                             : V(scale * a.e2() + (scale * rng.dyadic(-1, 1, 3)) * a.ea());
    FamilyInput in;
    push_line_like(in.x, q, O, d);
    push_cylinder(in.x, a.p0(), a.p1(), ulp_step(a.r, k));
    in.expected = radius_side(k);
    return in;
  };
  f.push_back({"tangent", lrs, [=](Rng& rng, Query q, long long k) { return tangent(rng, q, k, 1, 0, 0); }});
  f.push_back({"near_parallel", lrs, [=](Rng& rng, Query q, long long k) {
                 Aligned a = random_aligned(rng);
                 const V O = a.c + a.r * a.e1();
                 const V d = a.ea() + std::ldexp(rng.dyadic(0.5, 1), -static_cast<int>(rng.integer(10, 50))) * a.e2();
                 FamilyInput in;
                 push_line_like(in.x, q, O, d);
                 push_cylinder(in.x, a.p0(), a.p1(), ulp_step(a.r, k));
                 in.expected = radius_side(k);
                 return in;
               }});
  f.push_back({"far", lrs, [=](Rng& rng, Query q, long long k) {
                 return tangent(rng, q, k, 1, std::ldexp(1.0, static_cast<int>(rng.integer(20, 40))), 0);
               }});
  f.push_back({"extreme_scale", lrs, [=](Rng& rng, Query q, long long k) {
                 const double s = std::ldexp(1.0, static_cast<int>(rng.integer(-40, 40)));
                 return tangent(rng, q, k, s, 0, static_cast<int>(rng.integer(1, 30)));
               }});
  // Rim graze: O on the rim at p1, d = e1 - ea (+ a small e2 tilt): t > 0 outside the tube,
  // t < 0 above the cap. Outward: separated; inward: the line cuts the corner.
  f.push_back({"rim", lrs, [=](Rng& rng, Query q, long long k) {
                 Aligned a = random_aligned(rng);
                 const V O = a.p1() + a.r * a.e1();
                 const V d = a.e1() - a.ea() + rng.dyadic(-0.25, 0.25, 4) * a.e2();
                 FamilyInput in;
                 push_line_like(in.x, q, O, d);
                 push_cylinder(in.x, a.p0(), a.p1(), ulp_step(a.r, k));
                 in.expected = radius_side(k);
                 return in;
               }});
  f.push_back({"on_wall", lrs, [=](Rng& rng, Query q, long long k) {
                 Aligned a = random_aligned(rng);
                 const V O = a.c + a.r * a.e1() + (a.h * rng.dyadic(-0.4, 0.4)) * a.ea();
                 const V d = (a.h / 4) * a.ea();
                 FamilyInput in;
                 push_line_like(in.x, q, O, d);
                 push_cylinder(in.x, a.p0(), a.p1(), ulp_step(a.r, k));
                 in.expected = radius_side(k);
                 return in;
               }});
  f.push_back({"cap_plane", lrs, [=](Rng& rng, Query q, long long k) {
                 Aligned a = random_aligned(rng);
                 const V O = a.p1() + (a.r * rng.dyadic(-0.75, 0.75)) * a.e1();
                 const V d = a.e2() + rng.dyadic(-1, 1, 3) * a.e1();
                 V p1 = a.p1();
                 nudge(p1, a.ia, k);  // the cap moves: outward (overlapping) when k a_sign > 0
                 FamilyInput in;
                 push_line_like(in.x, q, O, d);
                 push_cylinder(in.x, a.p0(), p1, a.r);
                 in.expected = k == 0 ? Expected::touching : ((k > 0) == (a.sa > 0) ? Expected::overlapping : Expected::separated);
                 return in;
               }});
  // The range ends on the wall: the segment's p1 (the ray's origin, pointing outward) is a
  // wall point moved by k ulps radially; the rest of the range is outside.
  f.push_back({"ends_on_wall", rs, [=](Rng& rng, Query q, long long k) {
                 Aligned a = random_aligned(rng);
                 const V W = a.c + a.r * a.e1() + (a.h * rng.dyadic(-0.4, 0.4)) * a.ea();
                 const V out = a.e1() + rng.dyadic(-0.5, 0.5, 3) * a.e2() + rng.dyadic(-0.5, 0.5, 3) * a.ea();
                 FamilyInput in;
                 if (q == Query::ray_cylinder) {
                   push(in.x, W), push(in.x, out);
                 } else {
                   push(in.x, W + 2.0 * out), push(in.x, W);
                 }
                 push_cylinder(in.x, a.p0(), a.p1(), ulp_step(a.r, k));
                 in.expected = radius_side(k);
                 return in;
               }});
  f.push_back({"tangent_rotated", lrs, [=](Rng& rng, Query q, long long k) {
                 const Rotated R = random_rotated(rng);
                 const V O = R.p0 + rng.uniform(0.1, 0.9) * R.A + R.r * R.n;
                 const V d = R.m + rng.uniform(-0.5, 0.5) * normalized(R.A);
                 FamilyInput in;
                 push_line_like(in.x, q, O, d);
                 push_cylinder(in.x, R.p0, R.p1, ulp_step(R.r, k));
                 return in;
               }});
  f.push_back({"rim_rotated", lrs, [=](Rng& rng, Query q, long long k) {
                 const Rotated R = random_rotated(rng);
                 const V O = R.p1 + R.r * R.n;
                 const V d = R.n - normalized(R.A) + rng.uniform(-0.25, 0.25) * R.m;
                 FamilyInput in;
                 push_line_like(in.x, q, O, d);
                 push_cylinder(in.x, R.p0, R.p1, ulp_step(R.r, k));
                 return in;
               }});
  f.push_back({"uniform", lrs, [=](Rng& rng, Query q, long long) {
                 FamilyInput in;
                 const V O = random_vec(rng, -2, 2), d = random_vec(rng, -1, 1);
                 push_line_like(in.x, q, O, d);
                 push_cylinder(in.x, random_vec(rng, -2, 2), random_vec(rng, -2, 2), rng.uniform(0.05, 1));
                 return in;
               }});
  return f;
}

inline std::vector<Family> elliptic_families() {
  using namespace detail;
  const std::vector<Query> le{Query::line_elliptic_cylinder};
  // An aligned elliptic frame: a = alpha e_x, b = beta e_y, c = h e_z (exact), base random.
  struct Frame {
    V base, a, b, c;
  };
  auto aligned = [](Rng& rng) {
    return Frame{{rng.dyadic(-2, 2), rng.dyadic(-2, 2), rng.dyadic(-2, 2)},
                 {rng.dyadic(0.25, 2), 0, 0},
                 {0, rng.dyadic(0.25, 2), 0},
                 {0, 0, rng.dyadic(0.5, 4)}};
  };
  auto push_frame = [](std::vector<double>& x, const Frame& F) { push(x, F.base), push(x, F.a), push(x, F.b), push(x, F.c); };
  std::vector<Family> f;
  f.push_back({"e_tangent", le, [=](Rng& rng, Query q, long long k) {
                 const Frame F = aligned(rng);
                 V O = F.base + F.a + rng.dyadic(0.1, 0.9) * F.c;
                 nudge(O, 0, k);
                 const V d{0, 1, rng.dyadic(-1, 1, 3)};
                 FamilyInput in;
                 push_line_like(in.x, q, O, d);
                 push_frame(in.x, F);
                 in.expected = side(k, 1, Expected::separated, Expected::overlapping);
                 return in;
               }});
  // Parallel to c: inside (x' = 1/2), on the wall (x' = 1 + k ulps), outside (x' = 2).
  f.push_back({"e_parallel_axis", le, [=](Rng& rng, Query q, long long k) {
                 const Frame F = aligned(rng);
                 const long long where = rng.integer(0, 2);
                 V O = F.base + (where == 0 ? 0.5 : (where == 1 ? 1.0 : 2.0)) * F.a + 0.5 * F.c;
                 FamilyInput in;
                 if (where == 1) {
                   nudge(O, 0, k);
                   in.expected = side(k, 1, Expected::separated, Expected::overlapping);
                 } else {
                   in.expected = where == 0 ? Expected::overlapping : Expected::separated;
                 }
                 push_line_like(in.x, q, O, rng.dyadic(0.25, 2) * F.c);
                 push_frame(in.x, F);
                 return in;
               }});
  f.push_back({"e_rim", le, [=](Rng& rng, Query q, long long k) {
                 const Frame F = aligned(rng);
                 V O = F.base + F.a + F.c;
                 nudge(O, 0, k);
                 const V d = F.a - F.c;
                 FamilyInput in;
                 push_line_like(in.x, q, O, d);
                 push_frame(in.x, F);
                 in.expected = side(k, 1, Expected::separated, Expected::overlapping);
                 return in;
               }});
  f.push_back({"e_cap_plane", le, [=](Rng& rng, Query q, long long k) {
                 const Frame F = aligned(rng);
                 V O = F.base + F.c + rng.dyadic(-0.75, 0.75) * F.a;
                 nudge(O, 2, k);
                 const V d{rng.dyadic(-1, 1, 3), 1, 0};
                 FamilyInput in;
                 push_line_like(in.x, q, O, d);
                 push_frame(in.x, F);
                 in.expected = side(k, 1, Expected::separated, Expected::overlapping);
                 return in;
               }});
  // Sheared frame: b = (delta, beta, 0), c = (gamma, 0, h); the unit-space tangent line at
  // (1, 0, 1/2) with direction (0, 1, 1/10), mapped to world space in double.
  f.push_back({"e_tangent_oblique", le, [=](Rng& rng, Query q, long long k) {
                 Frame F = aligned(rng);
                 F.b.x = rng.uniform(-0.5, 0.5);
                 F.c.x = rng.uniform(-0.5, 0.5);
                 F.a.y = rng.uniform(-0.2, 0.2);
                 V O = F.base + F.a + 0.5 * F.c;
                 nudge(O, 0, k);
                 const V d = F.b + 0.1 * F.c;
                 FamilyInput in;
                 push_line_like(in.x, q, O, d);
                 push_frame(in.x, F);
                 return in;
               }});
  f.push_back({"uniform", le, [=](Rng& rng, Query q, long long) {
                 FamilyInput in;
                 push_line_like(in.x, q, random_vec(rng, -2, 2), random_vec(rng, -1, 1));
                 Frame F{random_vec(rng, -1, 1), random_vec(rng, -1, 1), random_vec(rng, -1, 1), random_vec(rng, -2, 2)};
                 push_frame(in.x, F);
                 return in;
               }});
  return f;
}

inline std::vector<Family> triangle_families() {
  using namespace detail;
  const std::vector<Query> tq{Query::triangle_cylinder};
  auto finish = [](const V& v0, const V& v1, const V& v2, const V& p0, const V& p1, double r, Expected e) {
    FamilyInput in;
    push(in.x, v0), push(in.x, v1), push(in.x, v2);
    push_cylinder(in.x, p0, p1, r);
    in.expected = e;
    return in;
  };
  std::vector<Family> f;
  f.push_back({"t_vertex_wall", tq, [=](Rng& rng, Query, long long k) {
                 const Aligned a = random_aligned(rng);
                 V v = a.c + a.r * a.e1() + (a.h * rng.dyadic(-0.4, 0.4)) * a.ea();
                 nudge(v, a.i1, k);
                 const double L = rng.dyadic(0.25, 2);
                 return finish(v, v + a.e1() + L * a.e2(), v + a.e1() - L * a.e2() + 0.5 * a.ea(), a.p0(), a.p1(), a.r,
                               side(k, a.s1, Expected::separated, Expected::overlapping));
               }});
  f.push_back({"t_edge_wall", tq, [=](Rng& rng, Query, long long k) {
                 const Aligned a = random_aligned(rng);
                 V v = a.c + a.r * a.e1() + (a.h * rng.dyadic(-0.3, 0.3)) * a.ea();
                 nudge(v, a.i1, k);
                 const double L = rng.dyadic(0.25, 2);
                 const V v0 = v - L * a.e2(), v1 = v + L * a.e2() + rng.dyadic(-0.1, 0.1, 6) * a.ea();
                 return finish(v0, v1, v + a.e1() + (a.h / 8) * a.ea(), a.p0(), a.p1(), a.r,
                               side(k, a.s1, Expected::separated, Expected::overlapping));
               }});
  f.push_back({"t_face_cap", tq, [=](Rng& rng, Query, long long k) {
                 const Aligned a = random_aligned(rng);
                 V v = a.p1() + (a.r * rng.dyadic(-0.5, 0.5)) * a.e1();
                 nudge(v, a.ia, k);
                 const double L = 2 * a.r;
                 return finish(v, v + L * a.e1() + L * a.e2(), v - L * a.e2(), a.p0(), a.p1(), a.r,
                               side(k, a.sa, Expected::separated, Expected::overlapping));
               }});
  // A vertex on the rim at p1, the triangle going outward and below the cap plane.
  f.push_back({"t_vertex_rim", tq, [=](Rng& rng, Query, long long k) {
                 const Aligned a = random_aligned(rng);
                 V v = a.p1() + a.r * a.e1();
                 nudge(v, a.i1, k);
                 const double L = rng.dyadic(0.25, 1);
                 return finish(v, v + a.e1() + L * a.e2() - L * a.ea(), v + a.e1() - L * a.e2() - 0.5 * a.ea(), a.p0(), a.p1(),
                               a.r, side(k, a.s1, Expected::separated, Expected::overlapping));
               }});
  // The plane contains the axis direction (x_1 = c_1 + k ulps), the triangle at radial
  // distance >= r + 1 along e2: separated for every k.
  f.push_back({"t_axis_plane", tq, [=](Rng& rng, Query, long long k) {
                 const Aligned a = random_aligned(rng);
                 V v = a.c + (a.r + 1) * a.e2();
                 nudge(v, a.i1, k);
                 const double L = rng.dyadic(0.25, 2);
                 FamilyInput in = finish(v - (a.h / 4) * a.ea(), v + L * a.e2() + (a.h / 4) * a.ea(), v + 2 * L * a.e2(),
                                         a.p0(), a.p1(), a.r, Expected::separated);
                 return in;
               }});
  f.push_back({"t_edge_rotated", tq, [=](Rng& rng, Query, long long k) {
                 const Rotated R = random_rotated(rng);
                 V v = R.p0 + rng.uniform(0.2, 0.8) * R.A + R.r * R.n;
                 nudge(v, major(R.n), k);
                 const double L = rng.uniform(0.2, 1);
                 return finish(v - L * R.m, v + L * R.m, v + R.n + 0.3 * R.A, R.p0, R.p1, R.r, Expected::unknown);
               }});
  f.push_back({"uniform", tq, [=](Rng& rng, Query, long long) {
                 return finish(random_vec(rng, -2, 2), random_vec(rng, -2, 2), random_vec(rng, -2, 2), random_vec(rng, -2, 2),
                               random_vec(rng, -2, 2), rng.uniform(0.05, 1), Expected::unknown);
               }});
  return f;
}

inline std::vector<Family> cylinder_families() {
  using namespace detail;
  const std::vector<Query> cq{Query::cylinder_cylinder};
  auto pair = [](const V& a0, const V& a1, double ra, const V& b0, const V& b1, double rb, Expected e) {
    FamilyInput in;
    push_cylinder(in.x, a0, a1, ra);
    push_cylinder(in.x, b0, b1, rb);
    in.expected = e;
    return in;
  };
  std::vector<Family> f;
  // B stacked on A's cap p1, its axis parallel, offset sideways by less than r_a + r_b.
  f.push_back({"c_cap_cap", cq, [=](Rng& rng, Query, long long k) {
                 const Aligned a = random_aligned(rng);
                 const double rb = rng.dyadic(0.25, 2), hb = rng.dyadic(0.5, 4);
                 V b0 = a.p1() + (a.r * rng.dyadic(0, 0.9)) * a.e1();
                 nudge(b0, a.ia, k);
                 return pair(a.p0(), a.p1(), a.r, b0, b0 + hb * a.ea(), rb, side(k, a.sa, Expected::separated, Expected::overlapping));
               }});
  f.push_back({"c_wall_parallel", cq, [=](Rng& rng, Query, long long k) {
                 const Aligned a = random_aligned(rng);
                 const double rb = rng.dyadic(0.25, 2);
                 V m = a.c + (a.r + rb) * a.e1() + (a.h * rng.dyadic(-0.4, 0.4)) * a.ea();
                 nudge(m, a.i1, k);
                 const double hb = rng.dyadic(0.5, 4);
                 return pair(a.p0(), a.p1(), a.r, m - hb * a.ea(), m + hb * a.ea(), rb,
                             side(k, a.s1, Expected::separated, Expected::overlapping));
               }});
  f.push_back({"c_wall_crossing", cq, [=](Rng& rng, Query, long long k) {
                 const Aligned a = random_aligned(rng);
                 const double rb = rng.dyadic(0.25, 2);
                 V m = a.c + (a.r + rb) * a.e1() + (a.h * rng.dyadic(-0.2, 0.2)) * a.ea();
                 nudge(m, a.i1, k);
                 const double hb = rng.dyadic(0.5, 4);
                 return pair(a.p0(), a.p1(), a.r, m - hb * a.e2(), m + hb * a.e2(), rb,
                             side(k, a.s1, Expected::separated, Expected::overlapping));
               }});
  // B lies on A's cap p1, its axis along e2, crossing the cap's centre region.
  f.push_back({"c_cap_wall", cq, [=](Rng& rng, Query, long long k) {
                 const Aligned a = random_aligned(rng);
                 const double rb = rng.dyadic(0.25, 2);
                 V m = a.p1() + rb * a.ea() + (a.r * rng.dyadic(-0.5, 0.5)) * a.e1();
                 nudge(m, a.ia, k);
                 const double hb = rng.dyadic(0.5, 4);
                 return pair(a.p0(), a.p1(), a.r, m - hb * a.e2(), m + hb * a.e2(), rb,
                             side(k, a.sa, Expected::separated, Expected::overlapping));
               }});
  // Skew axes at angle ~2^-j: B's axis through c + (r_a + r_b) e1 with direction ea + eps e2;
  // the common perpendicular joins the two midpoints, so the contact is wall against wall.
  f.push_back({"c_near_parallel", cq, [=](Rng& rng, Query, long long k) {
                 const Aligned a = random_aligned(rng);
                 const double rb = rng.dyadic(0.25, 2);
                 V m = a.c + (a.r + rb) * a.e1();
                 nudge(m, a.i1, k);
                 const V dir = (a.h / 2) * a.ea() + std::ldexp(rng.dyadic(0.5, 1), -static_cast<int>(rng.integer(4, 50))) * a.e2();
                 return pair(a.p0(), a.p1(), a.r, m - dir, m + dir, rb, side(k, a.s1, Expected::separated, Expected::overlapping));
               }});
  // Rim contacts: a's rim point P = p1 + r e1 touches b, and n = 3 e1 + 4 ea (length 5) is a
  // contact normal: a lies in {X.n <= P.n} with P its only point on that plane, b in
  // {X.n >= P.n}, so a and b meet at P alone. The radius of a is moved by k ulps (P and b stay):
  // smaller, a no longer reaches P (separated); larger, a's widened rim enters b near P
  // (overlapping), except for rim-rim (below).
  const auto rim_point = [](const Aligned& a) { return a.p1() + a.r * a.e1(); };
  const auto rim_normal = [](const Aligned& a) { return 3.0 * a.e1() + 4.0 * a.ea(); };
  // b's bottom cap lies in the plane {X.n = P.n}, P inside the cap disc: b0 = P + t e2, |t| < rb.
  f.push_back({"c_rim_cap", cq, [=](Rng& rng, Query, long long k) {
                 const Aligned a = random_aligned(rng);
                 const double rb = rng.dyadic(0.25, 2), t = rb * rng.dyadic(-0.5, 0.5), s = rng.dyadic(0.125, 0.75);
                 const V b0 = rim_point(a) + t * a.e2();
                 return pair(a.p0(), a.p1(), ulp_step(a.r, k), b0, b0 + s * rim_normal(a), rb,
                             side(k, 1, Expected::overlapping, Expected::separated));
               }});
  // b's axis at height rb above P along n (rb = 5 rho, so P + rho n is exact), direction
  // u = 4 e1 - 3 ea + lambda e2, orthogonal to n: b's wall passes through P.
  f.push_back({"c_rim_wall", cq, [=](Rng& rng, Query, long long k) {
                 const Aligned a = random_aligned(rng);
                 const double rho = rng.dyadic(0.0625, 0.4), lambda = rng.dyadic(-2, 2, 3), s = rng.dyadic(0.125, 0.75);
                 const V q = rim_point(a) + rho * rim_normal(a);
                 const V u = 4.0 * a.e1() - 3.0 * a.ea() + lambda * a.e2();
                 return pair(a.p0(), a.p1(), ulp_step(a.r, k), q - s * u, q + s * u, 5 * rho,
                             side(k, 1, Expected::overlapping, Expected::separated));
               }});
  // b's axis along m = 4 e1 + 3 ea (m.n = 24, so b's support point in direction -n is on its
  // bottom rim, at b0 + rb (3 e1 - 4 ea) / 5): b0 = P + rho (-3 e1 + 4 ea) with rb = 5 rho.
  // P is also b's only lowest point along ea (b0 + rb (3 e1 - 4 ea) / 5 again), so b lies on
  // a's top cap plane's far side: with a larger radius, P is inside a's top cap disc and b
  // rests on it (rim against cap): still touching.
  f.push_back({"c_rim_rim", cq, [=](Rng& rng, Query, long long k) {
                 const Aligned a = random_aligned(rng);
                 const double rho = rng.dyadic(0.0625, 0.4), s = rng.dyadic(0.125, 0.75);
                 const V b0 = rim_point(a) + rho * (-3.0 * a.e1() + 4.0 * a.ea());
                 return pair(a.p0(), a.p1(), ulp_step(a.r, k), b0, b0 + s * (4.0 * a.e1() + 3.0 * a.ea()), 5 * rho,
                             side(k, 1, Expected::touching, Expected::separated));
               }});
  f.push_back({"c_coaxial", cq, [=](Rng& rng, Query, long long) {
                 const Aligned a = random_aligned(rng);
                 return pair(a.p0(), a.p1(), a.r, a.c - (a.h / 4) * a.ea(), a.c + (a.h / 4) * a.ea(), a.r * rng.dyadic(0.1, 2),
                             Expected::overlapping);
               }});
  f.push_back({"c_equal_midpoints", cq, [=](Rng& rng, Query, long long) {
                 const V m = random_vec(rng, -2, 2);
                 const V da = {rng.dyadic(-1, 1), rng.dyadic(-1, 1), 1}, db = {1, rng.dyadic(-1, 1), rng.dyadic(-1, 1)};
                 return pair(m - da, m + da, rng.uniform(0.1, 1), m - db, m + db, rng.uniform(0.1, 1), Expected::overlapping);
               }});
  f.push_back({"c_crossing_rotated", cq, [=](Rng& rng, Query, long long k) {
                 const Rotated R = random_rotated(rng);
                 const double rb = rng.uniform(0.2, 1.5);
                 V m = R.p0 + 0.5 * R.A + (R.r + rb) * R.n;
                 nudge(m, major(R.n), k);
                 const V dir = R.m + rng.uniform(-0.5, 0.5) * normalized(R.A);
                 return pair(R.p0, R.p1, R.r, m - dir, m + dir, rb, Expected::unknown);
               }});
  f.push_back({"uniform", cq, [=](Rng& rng, Query, long long) {
                 const V a0 = random_vec(rng, -2, 2), b0 = random_vec(rng, -2, 2);
                 return pair(a0, a0 + random_vec(rng, -2, 2), rng.uniform(0.05, 1), b0, b0 + random_vec(rng, -2, 2),
                             rng.uniform(0.05, 1), Expected::unknown);
               }});
  return f;
}

inline std::vector<Family> all_families() {
  std::vector<Family> f = line_families();
  for (auto* more : {&elliptic_families, &triangle_families, &cylinder_families})
    for (Family& g : more()) f.push_back(std::move(g));
  return f;
}

}  // namespace certcyl::study
