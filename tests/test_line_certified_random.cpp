// Certified line/ray/segment against cylinder, checked against an independent exact
// reference on thousands of random and constructed degenerate inputs.
//
// The reference (written here, sharing nothing with the library but the primitives):
//   S = range ∩ slab, a rational interval; m = min over S of the radial excess
//   q(t) = |(O - P + t d) x A|^2 - r^2 A.A (textbook coefficients, Gmpq; the minimum of a
//   convex quadratic over an interval: the clamped vertex). Then separated iff S is empty or
//   m > 0, overlapping iff S has positive length and m < 0, touching otherwise.
// Each endpoint is rebuilt as a CORE::Expr alpha + beta sqrt(gamma) and the point there is
// classified exactly (its surface must match); rational parameters just outside the interval
// must give points outside the solid (Gmpq), the midpoint a point inside (overlapping) or on
// the boundary (touching); the nearest double must be within half a gap of the exact value.
#define BOOST_TEST_MODULE line_certified_random
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <iostream>
#include <optional>
#include <random>

#include "certcyl/certified/line_cylinder.hpp"
#include "certcyl/number_traits_core.hpp"
#include "certcyl/predicates/point_in_cylinder.hpp"

using namespace certcyl;
using Q = Rational;
using E = CORE::Expr;

namespace {

struct Reference {
  Answer answer;
};

struct ParamSet {
  std::optional<Q> lo, hi;  // unbounded when absent
  bool empty = false;
};

void clip(ParamSet& s, const std::optional<Q>& lo, const std::optional<Q>& hi) {
  if (lo && (!s.lo || *lo > *s.lo)) s.lo = lo;
  if (hi && (!s.hi || *hi < *s.hi)) s.hi = hi;
  if (s.lo && s.hi && *s.lo > *s.hi) s.empty = true;
}

// Axial slab sw + t sd in [0, H] and radial excess qa t^2 + qb t + qc, in exact rationals.
struct Constraints {
  Q sw, sd, H, qa, qb, qc;
};

Constraints constraints(const Vec3<Q>& O, const Vec3<Q>& d, const Cylinder<Q>& c) {
  const Vec3<Q> A = c.p1 - c.p0, w = O - c.p0;
  const Vec3<Q> wa = cross(w, A), da = cross(d, A);
  const Q AA = dot(A, A);
  return {dot(w, A), dot(d, A), AA, dot(da, da), Q(2) * dot(wa, da), dot(wa, wa) - c.radius * c.radius * AA};
}

Constraints constraints(const Vec3<Q>& O, const Vec3<Q>& d, const EllipticCylinder<Q>& e) {
  // Unit-space coordinates y = M^-1 (X - C), by Cramer's rule.
  const Q D = determinant(e.a, e.b, e.c);
  auto solve = [&](const Vec3<Q>& x) {
    return Vec3<Q>{determinant(x, e.b, e.c) / D, determinant(e.a, x, e.c) / D, determinant(e.a, e.b, x) / D};
  };
  const Vec3<Q> y0 = solve(O - e.base), y1 = solve(d);
  return {y0.z, y1.z, 1, y1.x * y1.x + y1.y * y1.y, Q(2) * (y0.x * y1.x + y0.y * y1.y), y0.x * y0.x + y0.y * y0.y - 1};
}

template <class Solid>
Answer reference_answer(const Vec3<Q>& O, const Vec3<Q>& d, LineRange range, const Solid& solid) {
  const Constraints k = constraints(O, d, solid);
  ParamSet S;
  if (range != LineRange::line) clip(S, Q(0), std::nullopt);
  if (range == LineRange::segment) clip(S, std::nullopt, Q(1));
  if (k.sd == 0) {
    if (k.sw < 0 || k.sw > k.H) return Answer::separated;
  } else {
    Q t0 = -k.sw / k.sd, t1 = (k.H - k.sw) / k.sd;
    if (t0 > t1) std::swap(t0, t1);
    clip(S, t0, t1);
  }
  if (S.empty) return Answer::separated;
  auto q = [&](const Q& t) { return (k.qa * t + k.qb) * t + k.qc; };
  std::optional<Q> m;
  auto consider = [&](const Q& t) {
    const Q v = q(t);
    if (!m || v < *m) m = v;
  };
  if (S.lo) consider(*S.lo);
  if (S.hi) consider(*S.hi);
  if (k.qa > 0) {
    const Q vertex = -k.qb / (Q(2) * k.qa);
    if ((!S.lo || vertex >= *S.lo) && (!S.hi || vertex <= *S.hi)) consider(vertex);
  } else {
    consider(Q(0));  // qa = 0 means qb = 0: q is the constant qc
  }
  if (*m > 0) return Answer::separated;
  // The open slab is empty for a line in a cap plane.
  const bool slab_open = k.sd != 0 || (k.sw > 0 && k.sw < k.H);
  const bool proper = slab_open && (!S.lo || !S.hi || *S.lo < *S.hi);
  return (proper && *m < 0) ? Answer::overlapping : Answer::touching;
}

E to_expr(const Q& q) { return E(CORE::BigRat(q.mpq())); }
E to_expr(const QuadraticNumber& x) {
  if (x.is_rational()) return to_expr(x.alpha);
  return to_expr(x.alpha) + to_expr(x.beta) * CORE::sqrt(E(CORE::BigInt(x.gamma.mpz())));
}

// The surface feature of the exact point X(t) (t a CORE::Expr).
template <class Solid>
LineFeature surface_at(const Vec3<Q>& O, const Vec3<Q>& d, const E& t, const Solid& solid) {
  const Constraints k = constraints(O, d, solid);
  const E s = to_expr(k.sw) + t * to_expr(k.sd);
  const E qv = (to_expr(k.qa) * t + to_expr(k.qb)) * t + to_expr(k.qc);
  const bool wall = qv == 0, cap0 = s == 0, cap1 = s == to_expr(k.H);
  if (wall) return cap0 ? LineFeature::rim0 : (cap1 ? LineFeature::rim1 : LineFeature::wall);
  return cap0 ? LineFeature::cap0 : (cap1 ? LineFeature::cap1 : LineFeature::none);
}

struct Stats {
  long cases = 0, exact = 0, midpoints = 0, by_answer[3] = {0, 0, 0};
};

bool in_range(const Q& t, LineRange range) {
  return range == LineRange::line || (t >= 0 && (range == LineRange::ray || t <= 1));
}

// Checks a certified result against the reference; `expected` when known by construction.
template <class Solid>
void verify(const Vec3<Q>& O, const Vec3<Q>& d, LineRange range, const Solid& solid, const CertifiedLineResult& r,
            std::optional<Answer> expected, Stats& stats, const std::string& id) {
  BOOST_TEST_CONTEXT(id) {
    ++stats.cases;
    stats.exact += static_cast<long>(r.counter.exact);
    const Answer ref = reference_answer(O, d, range, solid);
    BOOST_TEST(to_string(r.answer) == to_string(ref));
    if (expected) BOOST_TEST(to_string(r.answer) == to_string(*expected));
    ++stats.by_answer[static_cast<int>(ref)];
    if (r.answer == Answer::separated) {
      BOOST_TEST(!r.in.has_value());
      return;
    }
    BOOST_REQUIRE(r.in && r.out);
    const E tin = to_expr(r.in->value()), tout = to_expr(r.out->value());
    BOOST_TEST((r.answer == Answer::touching ? tin <= tout : tin < tout));
    auto point = [&](const Q& t) { return Vec3<Q>{O + t * d}; };
    for (const CertifiedEndpoint* e : {&*r.in, &*r.out}) {
      const E t = to_expr(e->value());
      BOOST_TEST(to_string(e->surface) == to_string(surface_at(O, d, t, solid)));
      if (e->feature == LineFeature::origin)
        BOOST_TEST((t == 0));
      else if (e->feature == LineFeature::end)
        BOOST_TEST((t == 1));
      else
        BOOST_TEST((e->feature == e->surface && e->surface != LineFeature::none));
      // Correct rounding: within half the gap to each neighbour.
      const double n = e->nearest, up = std::nextafter(n, INFINITY), down = std::nextafter(n, -INFINITY);
      BOOST_TEST((E(2) * (t - E(n)) <= E(up) - E(n)));
      BOOST_TEST((E(2) * (E(n) - t) <= E(n) - E(down)));
    }
    // Just outside the interval: outside the solid (when the range allows the parameter).
    for (int side : {-1, 1}) {
      const CertifiedEndpoint& e = side < 0 ? *r.in : *r.out;
      const Q n(e.nearest);
      const Q step = Q(std::fabs(e.nearest)) * Q(std::ldexp(1.0, -40)) + Q(std::ldexp(1.0, -80));
      const Q t = side < 0 ? Q(n - step) : Q(n + step);
      BOOST_TEST((side < 0 ? to_expr(t) < to_expr(e.value()) : to_expr(t) > to_expr(e.value())));
      if (in_range(t, range)) BOOST_TEST(to_string(classify_point(point(t), solid)) == "outside");
    }
    // The midpoint, when a rational one is provably inside the interval.
    const Q mid = (Q(r.in->nearest) + Q(r.out->nearest)) / 2;
    if (tin < to_expr(mid) && to_expr(mid) < tout) {
      ++stats.midpoints;
      BOOST_TEST(to_string(classify_point(point(mid), solid)) == (r.answer == Answer::overlapping ? "inside" : "boundary"));
    }
  }
}

template <class Solid>
CertifiedLineResult run(const Vec3<Q>& O, const Vec3<Q>& d, LineRange range, const Solid& solid) {
  switch (range) {
    case LineRange::line: return certified_line_cylinder(Line<Q>{O, d}, solid);
    case LineRange::ray: return certified_line_cylinder(Ray<Q>{O, d}, solid);
    case LineRange::segment: return certified_line_cylinder(Segment<Q>{O, O + d}, solid);
  }
  return {};
}

// A rational rotation from the quaternion (a, b, c, e), divided by its squared norm.
struct Rotation {
  Q m[3][3];
  Rotation(long a, long b, long c, long e) {
    const Q n(a * a + b * b + c * c + e * e);
    const long r[3][3] = {{a * a + b * b - c * c - e * e, 2 * (b * c - a * e), 2 * (b * e + a * c)},
                          {2 * (b * c + a * e), a * a - b * b + c * c - e * e, 2 * (c * e - a * b)},
                          {2 * (b * e - a * c), 2 * (c * e + a * b), a * a - b * b - c * c + e * e}};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) m[i][j] = Q(r[i][j]) / n;
  }
  Vec3<Q> operator()(const Vec3<Q>& v) const {
    return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
            m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
  }
};

}  // namespace

BOOST_AUTO_TEST_CASE(random_circular_and_elliptic) {
  const unsigned seed = 20240611;
  std::cout << "random_circular_and_elliptic: seed " << seed << "\n";
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> coord(-6, 6), small(-3, 3), kind(0, 2);
  auto rv = [&](std::uniform_int_distribution<int>& dist) { return Vec3<Q>{dist(rng), dist(rng), dist(rng)}; };
  Stats circ, ell;
  for (int i = 0; i < 2000; ++i) {
    Vec3<Q> p0 = rv(small), p1 = rv(small);
    if (p0 == p1) p1.z += 1;
    const Cylinder<Q> cyl{p0, p1, Q(1 + (i % 4)) / 2};
    Vec3<Q> O = p0 + Q(1, 2) * rv(coord), d = rv(small);
    if (d == Vec3<Q>{0, 0, 0}) d.x = 1;
    const auto range = static_cast<LineRange>(kind(rng));
    verify(O, d, range, cyl, run(O, d, range, cyl), std::nullopt, circ, "circular #" + std::to_string(i));
  }
  for (int i = 0; i < 1500; ++i) {
    EllipticCylinder<Q> e{rv(small), rv(small), rv(small), rv(small)};
    if (determinant(e.a, e.b, e.c) == 0) continue;
    Vec3<Q> O = e.base + Q(1, 2) * rv(coord), d = rv(small);
    if (d == Vec3<Q>{0, 0, 0}) d.y = 1;
    const auto range = static_cast<LineRange>(kind(rng));
    verify(O, d, range, e, run(O, d, range, e), std::nullopt, ell, "elliptic #" + std::to_string(i));
  }
  std::cout << "  circular: " << circ.cases << " cases (sep/touch/overlap " << circ.by_answer[0] << "/" << circ.by_answer[1]
            << "/" << circ.by_answer[2] << "), exact fall-backs " << circ.exact << ", midpoints " << circ.midpoints << "\n";
  std::cout << "  elliptic: " << ell.cases << " cases (sep/touch/overlap " << ell.by_answer[0] << "/" << ell.by_answer[1]
            << "/" << ell.by_answer[2] << "), exact fall-backs " << ell.exact << ", midpoints " << ell.midpoints << "\n";
  BOOST_TEST(circ.by_answer[0] > 100);
  BOOST_TEST(circ.by_answer[2] > 100);
}

// Degenerate families built in a local frame (axis z, radius 5, z in [0, 2]) where the truth is
// known, then rotated by a rational rotation and translated by an integer vector; the
// perturbed versions move the contact point by a relative 2^-k along the contact normal.
BOOST_AUTO_TEST_CASE(constructed_degenerate_families) {
  const unsigned seed = 77;
  std::cout << "constructed_degenerate_families: seed " << seed << "\n";
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> qd(-3, 3), shift(-1000, 1000), zsel(1, 3), ksel(20, 60);
  Stats stats;
  const Q H = 2, R = 5;
  for (int i = 0; i < 250; ++i) {
    long a = qd(rng), b = qd(rng), c = qd(rng), e = qd(rng);
    if (a == 0 && b == 0 && c == 0 && e == 0) a = 1;
    const Rotation rot(a, b, c, e);
    const Vec3<Q> T{shift(rng), shift(rng), shift(rng)};
    auto place = [&](const Vec3<Q>& p) { return Vec3<Q>{rot(p) + T}; };
    const Cylinder<Q> cyl{place({0, 0, 0}), place({0, 0, H}), R};
    const Q eps = Q(std::ldexp(1.0, -ksel(rng)));
    const Q z = Q(zsel(rng)) / 2;  // 1/2, 1, 3/2: strictly between the caps
    // (3, 4) is on the circle of radius 5; scaled by (1 + s eps) it moves outward (s = 1).
    struct Case {
      const char* name;
      Vec3<Q> O, d;
      Answer at, out, in;  // at the degeneracy, moved outward, moved inward
    };
    const Case cases[] = {
        {"tangent", {3, 4, z}, {-4, 3, 1}, Answer::touching, Answer::separated, Answer::overlapping},
        {"on_wall", {3, 4, z}, {0, 0, 1}, Answer::touching, Answer::separated, Answer::overlapping},
        {"graze_rim1", {3, 4, H}, {3, 4, -5}, Answer::touching, Answer::separated, Answer::overlapping},
        {"graze_rim0", {3, 4, 0}, {3, 4, 5}, Answer::touching, Answer::separated, Answer::overlapping},
        {"rim_tangent_in_cap", {3, 4, 0}, {-4, 3, 0}, Answer::touching, Answer::separated, Answer::touching},
    };
    for (const Case& k : cases) {
      for (int s : {0, 1, -1}) {
        Vec3<Q> O = k.O;
        if (s != 0) {
          const Q f = Q(1) + Q(s) * eps;
          O = Vec3<Q>{O.x * f, O.y * f, O.z};
        }
        const Answer expected = s == 0 ? k.at : (s > 0 ? k.out : k.in);
        const Vec3<Q> Ow = place(O), dw = rot(k.d);
        const std::string id = std::string(k.name) + " s=" + std::to_string(s) + " #" + std::to_string(i);
        verify(Ow, dw, LineRange::line, cyl, run(Ow, dw, LineRange::line, cyl), expected, stats, id);
        // As a ray from the contact point outward along the normal direction: the same sets
        // pass through it; only the answer for the exact contact is known (touching).
        verify(Ow, dw, LineRange::ray, cyl, run(Ow, dw, LineRange::ray, cyl), std::nullopt, stats, id + " ray");
      }
    }
    // The cap-plane chord: in the plane of cap1, moved up (separated) and down (overlapping).
    for (int s : {0, 1, -1}) {
      const Q zc = H + Q(s) * eps;
      const Vec3<Q> Ow = place({-7, 1, zc}), dw = rot({1, 0, 0});
      const Answer expected = s == 0 ? Answer::touching : (s > 0 ? Answer::separated : Answer::overlapping);
      verify(Ow, dw, LineRange::line, cyl, run(Ow, dw, LineRange::line, cyl), expected, stats, "cap1 chord s=" + std::to_string(s));
    }
  }
  // Elliptic: the same constructions in unit space mapped by random frames.
  std::uniform_int_distribution<int> fr(-4, 4);
  for (int i = 0; i < 250; ++i) {
    const EllipticCylinder<Q> e{{fr(rng), fr(rng), fr(rng)}, {fr(rng), fr(rng), fr(rng)}, {fr(rng), fr(rng), fr(rng)}, {fr(rng), fr(rng), fr(rng)}};
    if (determinant(e.a, e.b, e.c) == 0) continue;
    auto map_dir = [&](const Vec3<Q>& y) { return Vec3<Q>{y.x * e.a + y.y * e.b + y.z * e.c}; };
    auto map_pt = [&](const Vec3<Q>& y) { return Vec3<Q>{e.base + map_dir(y)}; };
    const Q eps = Q(std::ldexp(1.0, -ksel(rng)));
    const Q h = Q(1) / 2, c3 = Q(3) / 5, c4 = Q(4) / 5;
    struct Case {
      const char* name;
      Vec3<Q> O, d;
      Answer at, out, in;
    };
    const Case cases[] = {
        {"e_tangent", {c3, c4, h}, {-c4, c3, 1}, Answer::touching, Answer::separated, Answer::overlapping},
        {"e_on_wall", {c3, c4, h}, {0, 0, 1}, Answer::touching, Answer::separated, Answer::overlapping},
        {"e_graze_rim1", {c3, c4, 1}, {c3, c4, -1}, Answer::touching, Answer::separated, Answer::overlapping},
    };
    for (const Case& k : cases)
      for (int s : {0, 1, -1}) {
        Vec3<Q> O = k.O;
        if (s != 0) {
          const Q f = Q(1) + Q(s) * eps;
          O = Vec3<Q>{O.x * f, O.y * f, O.z};
        }
        const Answer expected = s == 0 ? k.at : (s > 0 ? k.out : k.in);
        const Vec3<Q> Ow = map_pt(O), dw = map_dir(k.d);
        const std::string id = std::string(k.name) + " s=" + std::to_string(s) + " #" + std::to_string(i);
        verify(Ow, dw, LineRange::line, e, run(Ow, dw, LineRange::line, e), expected, stats, id);
        verify(Ow, dw, LineRange::segment, e, run(Ow, dw, LineRange::segment, e), std::nullopt, stats, id + " segment");
      }
  }
  std::cout << "  " << stats.cases << " cases (sep/touch/overlap " << stats.by_answer[0] << "/" << stats.by_answer[1] << "/"
            << stats.by_answer[2] << "), exact fall-backs " << stats.exact << ", midpoints " << stats.midpoints << "\n";
  BOOST_TEST(stats.by_answer[1] > 500);
}

// The double-input API on binary64 near-tangent lines agrees with the Rational API on the
// same values.
BOOST_AUTO_TEST_CASE(double_input_agrees_with_rational_input) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  long agree = 0;
  for (int i = 0; i < 1000; ++i) {
    const double r = 0.1 + std::fabs(u(rng));
    const Vec3<double> p0{u(rng), u(rng), u(rng)};
    const Cylinder<double> cd{p0, {p0.x, p0.y, p0.z + 1.5 + u(rng)}, r};
    // A near-tangent line: offset about r along x from the vertical axis (p0.x + off rounds),
    // direction with no x component, the offset moved by 0, 1 or 2 ulps.
    const double z = p0.z + 0.5;
    double off = r;
    for (int k = 0; k < i % 3; ++k) off = std::nextafter(off, i % 2 ? 10.0 : 0.0);
    const Line<double> ld{{cd.p0.x + off, cd.p0.y, z}, {0, 1, 0.5 * u(rng)}};
    const auto to_q = [](double x) { return Q(x); };
    const auto rd = certified_line_cylinder(ld, cd);
    const auto rq = certified_line_cylinder(ld.map(to_q), cd.map(to_q));
    BOOST_TEST(to_string(rd.answer) == to_string(rq.answer));
    if (rd.in && rq.in) {
      BOOST_TEST(rd.in->exact() == rq.in->exact());
      BOOST_TEST(rd.out->nearest == rq.out->nearest);
    }
    agree += rd.answer == rq.answer;
  }
  BOOST_TEST(agree == 1000);
}
