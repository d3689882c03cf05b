// fuzz/crosscheck_cases.hpp -- the cross-check: random and degenerate cases for every certified
// query, each answer re-checked exactly (fuzz/recheck.hpp) and compared with the answers on
// exactly equivalent inputs.
//
// Cases (a fixed mix per query, all exact rationals):
//   random       small dyadic coordinates (binary64 values, so the double filters run) and, one
//                case in four, rationals with odd denominators (the Gmpq paths);
//   degenerate   built in a local frame where the contact is known by construction (axis z,
//                radius 5, (3, 4) on the rim circle; Pythagorean normals), moved by 0 or by
//                +-2^-k along the contact normal, then rotated by a rational rotation and
//                translated by an integer vector.
// Invariances, each an exact identity of the answers (and, for lines, of the endpoints):
//   swapped      cylinder pair (a, b) -> (b, a); triangle vertices rotated; segment p0 <-> p1
//                (t -> 1 - t); line direction reversed (t -> -t);
//   flipped      a cylinder's p0 <-> p1 (cap0 <-> cap1);
//   translated   every point + an integer vector;
//   scaled       every coordinate (and radius, direction) times 2^k, k in [-40, 40];
//   permuted     the coordinates (x, y, z) -> (y, z, x) or (y, x, z).
// A mismatch or a failed re-check is a wrong answer; an exception is a crash (the certified
// queries throw only on their own defects); an undecided cylinder pair is a failure too (the
// query runs with its default options, which set no resource limit).
#pragma once

#include <array>
#include <cstdint>
#include <algorithm>
#include <chrono>
#include <functional>
#include <map>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "recheck.hpp"

namespace certcyl::crosscheck {

using Q = Rational;
using V = Vec3<Q>;

// Where a cylinder pair's time goes, per kind of case (the driver's --profile).
struct KindProfile {
  std::uint64_t cases = 0, evaluations = 0;
  double case_seconds = 0;     // everything: generation, transformations, queries, re-checks
  double query_seconds = 0;    // the certified queries
  double recheck_seconds = 0;  // the independent re-checks
  std::array<double, kCylinderStages> stage_seconds{};           // the queries' own stage clocks
  std::array<std::uint64_t, kCylinderStages + 1> decided_by{};  // evaluations per deciding stage (none last)
  std::uint64_t exact_checks = 0;                                 // Gmpq sign computations, summed

  void merge(const KindProfile& o) {
    cases += o.cases, evaluations += o.evaluations;
    case_seconds += o.case_seconds, query_seconds += o.query_seconds, recheck_seconds += o.recheck_seconds;
    for (std::size_t i = 0; i < stage_seconds.size(); ++i) stage_seconds[i] += o.stage_seconds[i];
    for (std::size_t i = 0; i < decided_by.size(); ++i) decided_by[i] += o.decided_by[i];
    exact_checks += o.exact_checks;
  }
};

struct Failure {
  std::uint64_t index;  // the case
  std::string what;
};

struct Stats {
  std::uint64_t cases = 0;        // generated inputs
  std::uint64_t evaluations = 0;  // certified queries run (cases times their variants)
  std::uint64_t wrong = 0;        // failed re-checks or broken invariances
  std::uint64_t crashes = 0;      // exceptions out of a certified query
  std::uint64_t undecided = 0;    // undecided answers (cylinder pairs only): failures
  std::array<std::uint64_t, 4> by_answer{};  // of the original cases
  std::vector<Failure> failures;             // the first few, for the report
  std::map<std::string, KindProfile> profile;  // cylinder pairs only

  static constexpr std::size_t kMaxFailures = 20;

  void fail(std::uint64_t& counter, std::uint64_t index, const std::string& what) {
    ++counter;
    if (failures.size() < kMaxFailures) failures.push_back({index, what});
  }

  // Adds another part of the same run (threads, shards); the failures stay ordered by case.
  void merge(const Stats& o) {
    cases += o.cases, evaluations += o.evaluations, wrong += o.wrong, crashes += o.crashes, undecided += o.undecided;
    for (std::size_t i = 0; i < by_answer.size(); ++i) by_answer[i] += o.by_answer[i];
    failures.insert(failures.end(), o.failures.begin(), o.failures.end());
    std::stable_sort(failures.begin(), failures.end(), [](const Failure& a, const Failure& b) { return a.index < b.index; });
    if (failures.size() > kMaxFailures) failures.resize(kMaxFailures);
    for (const auto& [kind, p] : o.profile) profile[kind].merge(p);
  }
};

// Case i of a run with seed s is generated from its own seed, so it does not depend on the
// cases before it: a run split over threads or shards checks the same cases, and one case is
// reproduced alone (crosscheck --first i --cases 1). splitmix64 of (s, i).
inline std::uint64_t case_seed(std::uint64_t seed, std::uint64_t i) {
  std::uint64_t z = seed * 0x9E3779B97F4A7C15ull + i + 0x632BE59BD9B4E019ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

inline std::string describe(const V& v) {
  return "(" + to_exact_string(v.x) + ", " + to_exact_string(v.y) + ", " + to_exact_string(v.z) + ")";
}
inline std::string describe(const Cylinder<Q>& c) {
  return "{p0 " + describe(c.p0) + ", p1 " + describe(c.p1) + ", r " + to_exact_string(c.radius) + "}";
}

// ---- exact transformations --------------------------------------------------------------------

// A rational rotation from the integer quaternion (a, b, c, e), divided by its squared norm.
struct Rotation {
  std::array<std::array<Q, 3>, 3> m;
  Rotation(long a, long b, long c, long e) {
    const Q n(a * a + b * b + c * c + e * e);
    const long r[3][3] = {{a * a + b * b - c * c - e * e, 2 * (b * c - a * e), 2 * (b * e + a * c)},
                          {2 * (b * c + a * e), a * a - b * b + c * c - e * e, 2 * (c * e - a * b)},
                          {2 * (b * e - a * c), 2 * (c * e + a * b), a * a - b * b - c * c + e * e}};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) m[i][j] = Q(r[i][j]) / n;
  }
  V operator()(const V& v) const {
    return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
            m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
  }
};

// One of the invariance maps on points (as_vector: the same map without the translation).
struct Transform {
  enum Kind { translate, scale, permute_cyclic, permute_swap } kind;
  V shift{0, 0, 0};
  Q factor{1};
  V point(const V& p) const {
    switch (kind) {
      case translate: return p + shift;
      case scale: return factor * p;
      case permute_cyclic: return {p.y, p.z, p.x};
      case permute_swap: return {p.y, p.x, p.z};
    }
    return p;
  }
  V vector(const V& v) const { return kind == translate ? v : point(v); }
  Q length(const Q& r) const { return kind == scale ? Q(factor * r) : r; }
  std::string name() const {
    switch (kind) {
      case translate: return "translated";
      case scale: return "scaled";
      case permute_cyclic: return "permuted (yzx)";
      case permute_swap: return "permuted (yxz)";
    }
    return "?";
  }
};

inline Cylinder<Q> apply(const Transform& t, const Cylinder<Q>& c) { return {t.point(c.p0), t.point(c.p1), t.length(c.radius)}; }
inline EllipticCylinder<Q> apply(const Transform& t, const EllipticCylinder<Q>& e) {
  return {t.point(e.base), t.vector(e.a), t.vector(e.b), t.vector(e.c)};
}
inline Triangle<Q> apply(const Transform& t, const Triangle<Q>& T) { return {{t.point(T.v[0]), t.point(T.v[1]), t.point(T.v[2])}}; }
inline Cylinder<Q> flip(const Cylinder<Q>& c) { return {c.p1, c.p0, c.radius}; }

class Generator {
 public:
  explicit Generator(std::uint64_t seed) : rng_(seed) {}

  int uniform(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }
  Q pow2(int k) { return k >= 0 ? recheck::pow2(static_cast<unsigned long>(k)) : Q(1) / recheck::pow2(static_cast<unsigned long>(-k)); }

  // A small coordinate: a dyadic (binary64) value, or one time in `odd` a rational with an odd denominator.
  Q coordinate(int range, int odd = 4) {
    if (uniform(1, odd) == 1) return Q(uniform(-range * 7, range * 7)) / Q(uniform(1, 3) * 2 + 1);
    return Q(uniform(-range * 8, range * 8)) / Q(8);
  }
  V point(int range, int odd = 4) { return {coordinate(range, odd), coordinate(range, odd), coordinate(range, odd)}; }
  V nonzero(int range, int odd = 4) {
    for (;;) {
      const V v = point(range, odd);
      if (!recheck::is_zero(v)) return v;
    }
  }
  Q radius(int odd = 4) { return Q(uniform(1, 24)) / Q(uniform(1, odd) == 1 ? 3 : 8); }

  Rotation rotation() {
    long q[4];
    do
      for (long& x : q) x = uniform(-3, 3);
    while (q[0] == 0 && q[1] == 0 && q[2] == 0 && q[3] == 0);
    return Rotation(q[0], q[1], q[2], q[3]);
  }
  V integer_shift(int range) { return {uniform(-range, range), uniform(-range, range), uniform(-range, range)}; }
  Q epsilon() { return pow2(-uniform(10, 60)); }

  // The four invariance maps, with random parameters.
  std::array<Transform, 4> transforms() {
    Transform t{Transform::translate, integer_shift(1 << 20)};
    Transform s{Transform::scale};
    s.factor = pow2(uniform(-40, 40));
    return {t, s, Transform{Transform::permute_cyclic}, Transform{Transform::permute_swap}};
  }

  std::mt19937_64& engine() { return rng_; }

 private:
  std::mt19937_64 rng_;
};

// ---- lines --------------------------------------------------------------------------------------

struct LineCase {
  V O, d;
  LineRange range = LineRange::line;
  bool elliptic = false;
  Cylinder<Q> cyl;
  EllipticCylinder<Q> ell;
};

inline CertifiedLineResult run_line(const LineCase& c) {
  const auto go = [&](const auto& solid) {
    switch (c.range) {
      case LineRange::line: return certified_line_cylinder(Line<Q>{c.O, c.d}, solid);
      case LineRange::ray: return certified_line_cylinder(Ray<Q>{c.O, c.d}, solid);
      case LineRange::segment: return certified_line_cylinder(Segment<Q>{c.O, c.O + c.d}, solid);
    }
    return CertifiedLineResult{};
  };
  return c.elliptic ? go(c.ell) : go(c.cyl);
}

inline std::string recheck_line(const LineCase& c, const CertifiedLineResult& r) {
  return c.elliptic ? recheck::check_line(c.O, c.d, c.range, c.ell, r) : recheck::check_line(c.O, c.d, c.range, c.cyl, r);
}

inline LineCase make_line_case(Generator& g) {
  LineCase c;
  c.range = static_cast<LineRange>(g.uniform(0, 2));
  const int kind = g.uniform(0, 9);
  if (kind < 3) {
    // Random circular.
    c.cyl.p0 = g.point(4);
    do c.cyl.p1 = g.point(4);
    while (c.cyl.p1 == c.cyl.p0);
    c.cyl.radius = g.radius();
    c.O = c.cyl.p0 + g.point(6);
    c.d = g.nonzero(4);
  } else if (kind < 5) {
    // Random elliptic.
    c.elliptic = true;
    do c.ell = {g.point(4), g.point(3), g.point(3), g.point(3)};
    while (determinant(c.ell.a, c.ell.b, c.ell.c) == 0);
    c.O = c.ell.base + g.point(6);
    c.d = g.nonzero(4);
  } else {
    // Degenerate by construction in the local frame: axis z, z in [0, 2], radius 5.
    const Q H = 2, eps = g.epsilon();
    const Q z = Q(g.uniform(1, 3)) / 2;
    const int s = g.uniform(-1, 1);  // 0 at the degeneracy, +1 outward, -1 inward
    const Q f = Q(1) + Q(s) * eps;
    V O, d;
    switch (g.uniform(0, 6)) {
      case 0: O = {3 * f, 4 * f, z}, d = {-4, 3, Q(g.uniform(-2, 2))}; break;     // tangent to the wall
      case 1: O = {3 * f, 4 * f, z}, d = {0, 0, 1}; break;                        // on the wall
      case 2: O = {3 * f, 4 * f, H}, d = {3, 4, -5}; break;                       // grazing rim 1
      case 3: O = {3 * f, 4 * f, 0}, d = {3, 4, 5}; break;                        // grazing rim 0
      case 4: O = {3 * f, 4 * f, 0}, d = {-4, 3, 0}; break;                       // tangent to rim 0 in the cap plane
      case 5: O = {-7, 1, H + Q(s) * eps}, d = {1, Q(g.uniform(-2, 2)), 0}; break;  // a chord in cap plane 1
      default: O = {3, 4, H}, d = {Q(g.uniform(-3, 3)), Q(g.uniform(-3, 3)), 1}; break;  // through a rim point
    }
    if (g.uniform(0, 3) == 0) {
      // In unit space of a random elliptic frame.
      c.elliptic = true;
      do c.ell = {g.point(4, 1000), g.point(3, 1000), g.point(3, 1000), g.point(3, 1000)};
      while (determinant(c.ell.a, c.ell.b, c.ell.c) == 0);
      const auto dir = [&](const V& y) { return V{y.x * c.ell.a + y.y * c.ell.b + (y.z / H) * c.ell.c}; };
      const Q k = Q(1) / 5;  // radius 5 -> 1
      c.O = c.ell.base + dir(V{k * O.x, k * O.y, O.z});
      c.d = dir(V{k * d.x, k * d.y, d.z});
    } else {
      const bool rotate = g.uniform(0, 1) == 0;
      const Rotation R = g.rotation();
      const V T = g.integer_shift(1000);
      const auto place = [&](const V& p) { return rotate ? V(R(p) + T) : V(p + T); };
      c.cyl = {place({0, 0, 0}), place({0, 0, H}), Q(5)};
      c.O = place(O);
      c.d = rotate ? R(d) : d;
    }
    if (c.range == LineRange::segment) c.d = Q(g.uniform(1, 4)) * c.d;  // segments of a few lengths
  }
  return c;
}

// Endpoint values of r, mapped by t -> sign t + shift, must equal those of base (swapped if sign < 0).
inline std::string same_interval(const CertifiedLineResult& base, const CertifiedLineResult& r, int sign, const Q& shift) {
  if (base.answer != r.answer) return "answer " + std::string(to_string(r.answer)) + " vs " + std::string(to_string(base.answer));
  if (base.answer == Answer::separated) return "";
  const auto mapped = [&](const CertifiedEndpoint& e) {
    recheck::Root x = recheck::to_root(e.value());
    return recheck::Root{Q(sign) * x.p + shift, Q(sign) * x.q, x.g};
  };
  const recheck::Root in = mapped(sign > 0 ? *r.in : *r.out), out = mapped(sign > 0 ? *r.out : *r.in);
  if (recheck::compare(in, recheck::to_root(base.in->value())) != CGAL::ZERO ||
      recheck::compare(out, recheck::to_root(base.out->value())) != CGAL::ZERO)
    return "endpoints differ";
  return "";
}

inline std::string describe(const LineCase& c) {
  const char* range = c.range == LineRange::line ? "line" : c.range == LineRange::ray ? "ray" : "segment";
  std::string solid = c.elliptic ? "elliptic {base " + describe(c.ell.base) + ", a " + describe(c.ell.a) + ", b " + describe(c.ell.b) +
                                       ", c " + describe(c.ell.c) + "}"
                                 : "cylinder " + describe(c.cyl);
  return std::string(range) + " O " + describe(c.O) + ", d " + describe(c.d) + "; " + solid;
}

// Case i of the line cross-check: the original and its reversed, flipped, translated, scaled
// and permuted variants, each re-checked, their intervals compared exactly.
inline void check_line_case(std::uint64_t i, std::uint64_t seed, Stats& st) {
  Generator g(case_seed(seed, i));
  const LineCase c = make_line_case(g);
  ++st.cases;
  const std::string id = "line case " + std::to_string(i) + " (seed " + std::to_string(seed) + ")";
  bool failed = false;
  const auto fail = [&](std::uint64_t& counter, const std::string& what) {
    st.fail(counter, i, id + " " + what + (failed ? "" : "; input: " + describe(c)));
    failed = true;
  };
  try {
    const auto eval = [&](const LineCase& x, const std::string& what) {
      ++st.evaluations;
      CertifiedLineResult r = run_line(x);
      if (const std::string e = recheck_line(x, r); !e.empty()) fail(st.wrong, what + ": " + e);
      return r;
    };
    const CertifiedLineResult base = eval(c, "original");
    ++st.by_answer[static_cast<int>(base.answer)];
    // Swapped / reversed.
    if (c.range != LineRange::ray) {
      LineCase s = c;
      if (c.range == LineRange::segment) s.O = c.O + c.d;
      s.d = V{} - c.d;
      const auto r = eval(s, "reversed");
      const Q shift = c.range == LineRange::segment ? Q(1) : Q(0);
      if (const std::string e = same_interval(base, r, -1, shift); !e.empty()) fail(st.wrong, "reversed: " + e);
    }
    // Flipped cylinder.
    if (!c.elliptic) {
      LineCase f = c;
      f.cyl = flip(c.cyl);
      if (const std::string e = same_interval(base, eval(f, "flipped"), 1, 0); !e.empty()) fail(st.wrong, "flipped: " + e);
    }
    for (const Transform& t : g.transforms()) {
      LineCase m = c;
      m.O = t.point(c.O);
      m.d = t.vector(c.d);
      m.cyl = apply(t, c.cyl);
      m.ell = apply(t, c.ell);
      if (const std::string e = same_interval(base, eval(m, t.name()), 1, 0); !e.empty()) fail(st.wrong, t.name() + ": " + e);
    }
  } catch (const std::exception& e) {
    fail(st.crashes, std::string("exception: ") + e.what());
  }
}

// Cases first, ..., first + n - 1.
inline void check_lines(std::uint64_t first, std::uint64_t n, std::uint64_t seed, Stats& st) {
  for (std::uint64_t i = first; i < first + n; ++i) check_line_case(i, seed, st);
}
inline void check_lines(std::uint64_t n, std::uint64_t seed, Stats& st) { check_lines(0, n, seed, st); }

// ---- triangles ----------------------------------------------------------------------------------

struct TriangleCase {
  Triangle<Q> T;
  Cylinder<Q> C;
};

inline TriangleCase make_triangle_case(Generator& g) {
  TriangleCase c;
  const int kind = g.uniform(0, 9);
  if (kind < 5) {
    c.C.p0 = g.point(4);
    do c.C.p1 = g.point(4);
    while (c.C.p1 == c.C.p0);
    c.C.radius = g.radius();
    const V centre = c.C.p0 + g.point(4);
    const int scale = g.uniform(1, 6);
    for (V& v : c.T.v) v = centre + g.point(scale);
    if (kind == 4) c.T.v[2] = g.uniform(0, 1) ? c.T.v[0] : c.T.v[0] + Q(g.uniform(-2, 2)) * V(c.T.v[1] - c.T.v[0]);  // degenerate
    return c;
  }
  // Local frame: axis z, z in [0, 2], radius 5; (3, 4) on the circle, normal (3, 4, 0) / 5.
  const Q H = 2, eps = g.epsilon();
  const int s = g.uniform(-1, 1);
  const Q f = Q(1) + Q(s) * eps;
  const Q z = Q(g.uniform(1, 3)) / 2;
  const V t{-4, 3, 0};  // tangent to the circle at (3, 4)
  Triangle<Q> T;
  switch (g.uniform(0, 6)) {
    case 0: T = {{V{3 * f, 4 * f, z}, V{9, 12, z + 1}, V{9, 12, z - 1}}}; break;                      // a vertex on the wall
    case 1: T = {{V{3 * f, 4 * f, 0} + t, V{3 * f, 4 * f, 0} - t, V{6, 8, 1}}}; break;                // an edge tangent to rim 0... in cap plane
    case 2: T = {{V{3 * f, 4 * f, z} + t, V{3 * f, 4 * f, z} - t, V{3 * f, 4 * f, z} + V{0, 0, 1}}}; break;  // in the tangent plane
    case 3: T = {{V{-1, 0, H + Q(s) * eps}, V{1, 1, H + Q(s) * eps}, V{0, -2, H + Q(s) * eps}}}; break;  // on cap 1
    case 4: T = {{V{3 * f, 4 * f, H}, V{6, 8, H + 1}, V{6, 8, H + 2}}}; break;                       // a vertex on rim 1
    case 5: T = {{V{3 * f, 4 * f, z}, V{3 * f, 4 * f, z}, V{6, 8, z}}}; break;                       // a segment from the wall
    default: T = {{V{3 * f, 4 * f, z}, V{3 * f, 4 * f, z}, V{3 * f, 4 * f, z}}}; break;              // a point on the wall
  }
  const bool rotate = g.uniform(0, 1) == 0;
  const Rotation R = g.rotation();
  const V shift = g.integer_shift(1000);
  const auto place = [&](const V& p) { return rotate ? V(R(p) + shift) : V(p + shift); };
  c.C = {place({0, 0, 0}), place({0, 0, H}), Q(5)};
  c.T = {{place(T.v[0]), place(T.v[1]), place(T.v[2])}};
  return c;
}

inline std::string describe(const TriangleCase& c) {
  return "triangle " + describe(c.T.v[0]) + ", " + describe(c.T.v[1]) + ", " + describe(c.T.v[2]) + "; cylinder " + describe(c.C);
}

// Case i of the triangle cross-check: the original, its vertices rotated, the cylinder flipped,
// translated, scaled and permuted, each re-checked, the answers compared.
inline void check_triangle_case(std::uint64_t i, std::uint64_t seed, Stats& st) {
  Generator g(case_seed(seed, i));
  const TriangleCase c = make_triangle_case(g);
  ++st.cases;
  const std::string id = "triangle case " + std::to_string(i) + " (seed " + std::to_string(seed) + ")";
  bool failed = false;
  const auto fail = [&](std::uint64_t& counter, const std::string& what) {
    st.fail(counter, i, id + " " + what + (failed ? "" : "; input: " + describe(c)));
    failed = true;
  };
  try {
    const auto eval = [&](const Triangle<Q>& T, const Cylinder<Q>& C, const std::string& what) {
      ++st.evaluations;
      const TriangleCylinderResult r = certified_triangle_cylinder(T, C);
      if (const std::string e = recheck::check_triangle(T, C, r); !e.empty()) fail(st.wrong, what + ": " + e);
      return r.answer;
    };
    const Answer base = eval(c.T, c.C, "original");
    ++st.by_answer[static_cast<int>(base)];
    const auto same = [&](Answer a, const std::string& what) {
      if (a != base) fail(st.wrong, what + ": " + std::string(to_string(a)) + " vs " + std::string(to_string(base)));
    };
    same(eval({{c.T.v[1], c.T.v[2], c.T.v[0]}}, c.C, "vertices rotated"), "vertices rotated");
    same(eval(c.T, flip(c.C), "flipped"), "flipped");
    for (const Transform& t : g.transforms()) same(eval(apply(t, c.T), apply(t, c.C), t.name()), t.name());
  } catch (const std::exception& e) {
    fail(st.crashes, std::string("exception: ") + e.what());
  }
}

inline void check_triangles(std::uint64_t first, std::uint64_t n, std::uint64_t seed, Stats& st) {
  for (std::uint64_t i = first; i < first + n; ++i) check_triangle_case(i, seed, st);
}
inline void check_triangles(std::uint64_t n, std::uint64_t seed, Stats& st) { check_triangles(0, n, seed, st); }

// ---- cylinder pairs -----------------------------------------------------------------------------

struct CylinderPairCase {
  Cylinder<Q> a, b;
  std::string kind;  // for the profile: "random", "random parallel", or the contact, the move and the placement
};

inline CylinderPairCase make_cylinder_pair_case(Generator& g) {
  CylinderPairCase c;
  const int kind = g.uniform(0, 9);
  if (kind < 5) {
    for (Cylinder<Q>* x : {&c.a, &c.b}) {
      x->p0 = g.point(4);
      do x->p1 = x->p0 + g.point(3);
      while (x->p1 == x->p0);
      x->radius = g.radius();
    }
    if (kind == 4) c.b.p1 = c.b.p0 + Q(g.uniform(1, 3)) * V(c.a.p1 - c.a.p0);  // parallel axes
    c.kind = kind == 4 ? "random parallel" : "random";
    return c;
  }
  // Touching by construction (a: axis z, z in [0, 2], radius 1), b moved by s eps along the
  // contact normal n.
  const Q eps = g.epsilon();
  const Q s(g.uniform(-1, 1));
  const Cylinder<Q> a{{0, 0, 0}, {0, 0, 2}, Q(1)};
  Cylinder<Q> b;
  V n;
  const Q off = Q(g.uniform(-8, 8)) / 8;
  const int contact = g.uniform(0, 5);
  switch (contact) {
    case 0: b = {{off, 0, 2}, {off, 0, 5}, Q(1)}, n = {0, 0, 1}; break;               // cap-cap
    case 1: b = {{-1, off, 3}, {1, off, 3}, Q(1)}, n = {0, 0, 1}; break;              // cap-wall
    case 2: b = {{2, -1, off}, {2, 1, off}, Q(1)}, n = {1, 0, 0}; break;              // wall-wall crossing
    case 3: b = {{2, 0, 1 + off}, {2, 0, 3 + off}, Q(1)}, n = {1, 0, 0}; break;       // wall-wall parallel
    case 4: {                                                                         // rim-cap
      const V P{1, 0, 2}, m{Q(3, 5), 0, Q(4, 5)};
      b = {P + V{0, Q(1, 2), 0}, P + V{0, Q(1, 2), 0} + Q(2) * m, Q(1)}, n = m;
      break;
    }
    default: {  // rim-wall
      const V P{1, 0, 2}, m{Q(3, 5), 0, Q(4, 5)}, q = P + m, h{1, Q(5, 4), Q(-3, 4)};
      b = {q - h, q + h, Q(1)}, n = m;
      break;
    }
  }
  b = {b.p0 + s * eps * n, b.p1 + s * eps * n, b.radius};
  const bool rotate = g.uniform(0, 1) == 0;
  const Rotation R = g.rotation();
  const V shift = g.integer_shift(1000);
  const auto place = [&](const Cylinder<Q>& x) {
    return rotate ? Cylinder<Q>{R(x.p0) + shift, R(x.p1) + shift, x.radius} : Cylinder<Q>{x.p0 + shift, x.p1 + shift, x.radius};
  };
  c.a = place(a);
  c.b = place(b);
  static const char* const contacts[] = {"cap-cap", "cap-wall", "wall-wall crossing", "wall-wall parallel", "rim-cap", "rim-wall"};
  c.kind = std::string(contacts[contact]) + (s < 0 ? ", -eps" : s > 0 ? ", +eps" : ", touching") + (rotate ? ", rotated" : ", shifted");
  return c;
}

inline std::string describe(const CylinderPairCase& c) { return "a " + describe(c.a) + ", b " + describe(c.b); }

// Case i of the cylinder-pair cross-check: the original, swapped, a flipped, translated, scaled
// and permuted, each re-checked, the decided answers compared. With `profile`, the time of each
// part is added to st.profile under the case's kind.
inline void check_cylinder_pair_case(std::uint64_t i, std::uint64_t seed, Stats& st, bool profile = false) {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point case_start = profile ? Clock::now() : Clock::time_point{};
  Generator g(case_seed(seed, i));
  const CylinderPairCase c = make_cylinder_pair_case(g);
  ++st.cases;
  KindProfile* kp = profile ? &st.profile[c.kind] : nullptr;
  if (kp) ++kp->cases;
  const std::string id = "cylinder pair case " + std::to_string(i) + " (seed " + std::to_string(seed) + ")";
  bool failed = false;
  const auto fail = [&](std::uint64_t& counter, const std::string& what) {
    st.fail(counter, i, id + " " + what + (failed ? "" : "; input: " + describe(c)));
    failed = true;
  };
  try {
    const auto eval = [&](const Cylinder<Q>& a, const Cylinder<Q>& b, const std::string& what) {
      ++st.evaluations;
      const Clock::time_point t0 = kp ? Clock::now() : Clock::time_point{};
      const CylinderCylinderResult r = certified_cylinder_cylinder(a, b);
      const Clock::time_point t1 = kp ? Clock::now() : Clock::time_point{};
      if (r.answer == Answer::undecided) fail(st.undecided, what + ": undecided without a resource limit");
      if (const std::string e = recheck::check_cylinder_pair(a, b, r); !e.empty()) fail(st.wrong, what + ": " + e);
      if (kp) {
        ++kp->evaluations;
        kp->query_seconds += std::chrono::duration<double>(t1 - t0).count();
        kp->recheck_seconds += std::chrono::duration<double>(Clock::now() - t1).count();
        for (std::size_t k = 0; k < kCylinderStages; ++k) kp->stage_seconds[k] += r.stage_seconds[k];
        ++kp->decided_by[static_cast<std::size_t>(r.stage)];
        kp->exact_checks += r.counters.exact_checks;
      }
      return r.answer;
    };
    const Answer base = eval(c.a, c.b, "original");
    ++st.by_answer[static_cast<int>(base)];
    // An undecided answer is already a failure (above); decided answers must agree.
    const auto same = [&](Answer x, const std::string& what) {
      if (x != base && x != Answer::undecided && base != Answer::undecided)
        fail(st.wrong, what + ": " + std::string(to_string(x)) + " vs " + std::string(to_string(base)));
    };
    same(eval(c.b, c.a, "swapped"), "swapped");
    same(eval(flip(c.a), c.b, "flipped"), "flipped");
    for (const Transform& t : g.transforms()) same(eval(apply(t, c.a), apply(t, c.b), t.name()), t.name());
  } catch (const std::exception& e) {
    fail(st.crashes, std::string("exception: ") + e.what());
  }
  if (kp) kp->case_seconds += std::chrono::duration<double>(Clock::now() - case_start).count();
}

inline void check_cylinder_pairs(std::uint64_t first, std::uint64_t n, std::uint64_t seed, Stats& st, bool profile = false) {
  for (std::uint64_t i = first; i < first + n; ++i) check_cylinder_pair_case(i, seed, st, profile);
}
inline void check_cylinder_pairs(std::uint64_t n, std::uint64_t seed, Stats& st) { check_cylinder_pairs(0, n, seed, st); }

inline void print(std::ostream& out, const std::string& query, const Stats& s) {
  out << query << ": " << s.cases << " cases, " << s.evaluations << " certified answers re-checked; separated/touching/overlapping "
      << s.by_answer[0] << "/" << s.by_answer[1] << "/" << s.by_answer[2] << "; undecided " << s.undecided << "; wrong "
      << s.wrong << "; crashes " << s.crashes << "\n";
  for (const Failure& f : s.failures) out << "  " << f.what << "\n";
}

}  // namespace certcyl::crosscheck
