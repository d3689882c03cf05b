// An independent oracle for the study's families in general position (study/families.hpp), whose
// construction rounds, so that only the certified query knows their answer: a sample of each is
// decided again in Gmpq by checks written here from the definitions of the solids
// (certcyl/primitives.hpp), sharing no code with the certified queries or with the study's gap.
//
//  - Lines, rays and segments against a circular or elliptic cylinder (tangent_rotated,
//    rim_rotated, e_tangent_oblique, and the uniform family of each). With X(t) the range's points, the closed solid holds X(t)
//    iff an affine slab coordinate g(t) lies in [g_lo, g_hi] and a convex quadratic q(t) <= 0:
//      circular  g = (X - p0).A in [0, A.A],  q = |(X - p0) x A|^2 - r^2 A.A;
//      elliptic  (x, y, z) = M^-1 (X - base) (affine in t, Cramer's rule), g = z in [0, 1],
//                q = x^2 + y^2 - 1.
//    With I the range's parameters whose g is in the slab (a closed interval), the range meets
//    the closed solid iff min_I q <= 0, and its interior iff I has interior points (the slab
//    strictly, the range's interior) and min_I q < 0 (q is continuous). min_I q of a convex
//    quadratic is at the vertex -b / 2a when it lies in I, else at an end of I: rational.
//  - Cylinder pairs (c_crossing_rotated: walls crossing at distance ra + rb, moved by k ulps).
//    With axes not parallel (N = A x B != 0) and the closest points of the axis lines inside both
//    segments (parameters in (0, 1)), the pair's answer is that of the two infinite cylinders:
//    the sign of (ra + rb)^2 N.N - ((p0b - p0a).N)^2 (positive: overlapping, at the point between
//    the closest points at ratio ra : rb, which lies inside both slabs; zero: touching at that one
//    point; negative: separated, as the finite cylinders lie in the infinite ones). Instances where
//    the closest points fall outside are counted and left to the other checks.
// Each instance is certified as the study does (study/gap.hpp, certify) and its certified
// answer must equal the oracle's, at k = 0 and k of either sign up to 2^40 ulps.
#define BOOST_TEST_MODULE study_oracle
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "study/families.hpp"
#include "study/gap.hpp"

using namespace certcyl;
using namespace certcyl::study;
using Q = Rational;

namespace {

Vec3<Q> vq(const std::vector<Q>& x, std::size_t i) { return {x[i], x[i + 1], x[i + 2]}; }
Q dotq(const Vec3<Q>& u, const Vec3<Q>& v) { return u.x * v.x + u.y * v.y + u.z * v.z; }
Vec3<Q> crossq(const Vec3<Q>& u, const Vec3<Q>& v) { return {u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x}; }
Vec3<Q> sub(const Vec3<Q>& u, const Vec3<Q>& v) { return {u.x - v.x, u.y - v.y, u.z - v.z}; }
Q det3(const Vec3<Q>& a, const Vec3<Q>& b, const Vec3<Q>& c) { return dotq(a, crossq(b, c)); }

// An affine function of t: v0 + v1 t.
struct Affine {
  Q v0, v1;
};
// A quadratic a t^2 + b t + c.
struct Quadratic {
  Q a, b, c;
  Q at(const Q& t) const { return (a * t + b) * t + c; }
};
Quadratic square(const Affine& f) { return {f.v1 * f.v1, 2 * f.v0 * f.v1, f.v0 * f.v0}; }
Quadratic plus(const Quadratic& p, const Quadratic& q) { return {p.a + q.a, p.b + q.b, p.c + q.c}; }

// The answer for the range [lo, hi] of t (absent: unbounded), slab g in [g_lo, g_hi], tube q <= 0.
Answer decide(std::optional<Q> lo, std::optional<Q> hi, const Affine& g, const Q& g_lo, const Q& g_hi, const Quadratic& q) {
  bool strict_slab = true;  // the slab holds strictly somewhere on I's interior
  if (g.v1 == 0) {
    if (g.v0 < g_lo || g.v0 > g_hi) return Answer::separated;
    strict_slab = g.v0 > g_lo && g.v0 < g_hi;
  } else {
    Q s0 = (g_lo - g.v0) / g.v1, s1 = (g_hi - g.v0) / g.v1;
    if (s1 < s0) std::swap(s0, s1);
    if (!lo || *lo < s0) lo = s0;
    if (!hi || *hi > s1) hi = s1;
  }
  if (lo && hi && *hi < *lo) return Answer::separated;
  const bool has_interior = strict_slab && (!lo || !hi || *lo < *hi);
  // min over I of q (nullopt: unbounded below).
  std::optional<Q> m;
  const auto consider = [&m](const Q& v) {
    if (!m || v < *m) m = v;
  };
  bool unbounded_below = false;
  if (q.a > 0) {
    const Q v = -q.b / (2 * q.a);
    if ((!lo || *lo <= v) && (!hi || v <= *hi)) consider(q.at(v));
  } else if (q.b != 0 && ((q.b > 0 && !lo) || (q.b < 0 && !hi))) {
    unbounded_below = true;  // q linear and decreasing towards an open end
  } else if (q.b == 0 && !lo && !hi) {
    consider(q.c);
  }
  if (lo) consider(q.at(*lo));
  if (hi) consider(q.at(*hi));
  const bool closed = unbounded_below || (m && *m <= 0);
  const bool interior = has_interior && (unbounded_below || (m && *m < 0));
  return interior ? Answer::overlapping : (closed ? Answer::touching : Answer::separated);
}

// The range of a line-like query: its points O + t d and the bounds of t.
struct Range {
  Vec3<Q> O, d;
  std::optional<Q> lo, hi;
};
Range range_of(Query query, const std::vector<Q>& x) {
  if (query == Query::segment_cylinder) return {vq(x, 0), sub(vq(x, 3), vq(x, 0)), Q(0), Q(1)};
  if (query == Query::ray_cylinder) return {vq(x, 0), vq(x, 3), Q(0), std::nullopt};
  return {vq(x, 0), vq(x, 3), std::nullopt, std::nullopt};
}

Answer oracle_circular(Query query, const std::vector<Q>& x) {
  const Range R = range_of(query, x);
  const Vec3<Q> p0 = vq(x, 6), A = sub(vq(x, 9), p0);
  const Q r = x[12], AA = dotq(A, A);
  const Vec3<Q> w0 = sub(R.O, p0);  // X - p0 = w0 + t d
  const Vec3<Q> c0 = crossq(w0, A), c1 = crossq(R.d, A);
  Quadratic q{0, 0, -r * r * AA};
  for (const auto& [u, v] : {std::pair{c0.x, c1.x}, std::pair{c0.y, c1.y}, std::pair{c0.z, c1.z}}) q = plus(q, square({u, v}));
  return decide(R.lo, R.hi, {dotq(w0, A), dotq(R.d, A)}, Q(0), AA, q);
}

Answer oracle_elliptic(const std::vector<Q>& x) {
  const Range R = range_of(Query::line_elliptic_cylinder, x);
  const Vec3<Q> base = vq(x, 6), a = vq(x, 9), b = vq(x, 12), c = vq(x, 15);
  const Q D = det3(a, b, c);
  BOOST_REQUIRE(D != 0);
  const Vec3<Q> w0 = sub(R.O, base);
  // Cramer: x = det(v, b, c) / D, y = det(a, v, c) / D, z = det(a, b, v) / D for v = w0 + t d.
  const Affine fx{det3(w0, b, c) / D, det3(R.d, b, c) / D}, fy{det3(a, w0, c) / D, det3(a, R.d, c) / D},
      fz{det3(a, b, w0) / D, det3(a, b, R.d) / D};
  const Quadratic q = plus(plus(square(fx), square(fy)), Quadratic{0, 0, -1});
  return decide(R.lo, R.hi, fz, Q(0), Q(1), q);
}

// nullopt when the closest points of the axis lines are not inside both segments.
std::optional<Answer> oracle_crossing(const std::vector<Q>& x) {
  const Vec3<Q> pa = vq(x, 0), A = sub(vq(x, 3), pa), pb = vq(x, 7), B = sub(vq(x, 10), pb);
  const Q ra = x[6], rb = x[13];
  const Vec3<Q> N = crossq(A, B), w = sub(pb, pa);
  const Q NN = dotq(N, N);
  if (NN == 0) return std::nullopt;
  // pa + s A - (pb + t B) is orthogonal to A and B: s = (w x B).N / N.N, t = (w x A).N / N.N.
  const Q s = dotq(crossq(w, B), N) / NN, t = dotq(crossq(w, A), N) / NN;
  if (!(s > 0 && s < 1 && t > 0 && t < 1)) return std::nullopt;
  const Q wn = dotq(w, N), reach = (ra + rb) * (ra + rb) * NN - wn * wn;
  return reach > 0 ? Answer::overlapping : (reach == 0 ? Answer::touching : Answer::separated);
}

const Family& family(const std::vector<Family>& all, const std::string& name, Query q) {
  for (const Family& f : all)
    if (f.name == name && std::find(f.queries.begin(), f.queries.end(), q) != f.queries.end()) return f;
  BOOST_FAIL("no family " + name);
  return all.front();
}

std::string name(Answer a) { return std::string(to_string(a)); }

const std::vector<long long> kDisplacements{0, 1, -1, 3, -3, 1LL << 10, -(1LL << 10), 1LL << 30, -(1LL << 30), 1LL << 40, -(1LL << 40)};

struct Tally {
  int checked = 0, skipped = 0;
  int answers[3] = {0, 0, 0};  // separated, touching, overlapping
};

void count(Tally& t, Answer a) {
  ++t.checked;
  if (a == Answer::separated) ++t.answers[0];
  if (a == Answer::touching) ++t.answers[1];
  if (a == Answer::overlapping) ++t.answers[2];
}

}  // namespace

BOOST_AUTO_TEST_CASE(oracle_decides_hand_made_ranges) {
  // The oracle itself on answers known by construction: the unit cylinder along z, height 2.
  const std::vector<Q> cyl{0, 0, 0, 0, 0, 2, 1};
  const auto line = [&](Query q, std::vector<Q> range) {
    range.insert(range.end(), cyl.begin(), cyl.end());
    return oracle_circular(q, range);
  };
  BOOST_TEST(name(line(Query::line_cylinder, {1, 0, 1, 0, 1, 0})) == "touching");         // tangent to the wall
  BOOST_TEST(name(line(Query::line_cylinder, {Q(1, 2), 0, 1, 0, 1, 0})) == "overlapping");  // a chord
  BOOST_TEST(name(line(Query::line_cylinder, {2, 0, 1, 0, 1, 0})) == "separated");
  BOOST_TEST(name(line(Query::line_cylinder, {0, 0, 2, 1, 0, 0})) == "touching");  // in the cap plane
  BOOST_TEST(name(line(Query::line_cylinder, {1, 0, 0, 0, 0, 1})) == "touching");  // on the wall, along the axis
  BOOST_TEST(name(line(Query::line_cylinder, {0, 0, 5, 0, 0, 1})) == "overlapping");  // the axis
  BOOST_TEST(name(line(Query::ray_cylinder, {0, 0, 3, 0, 0, 1})) == "separated");     // pointing away
  BOOST_TEST(name(line(Query::ray_cylinder, {0, 0, 2, 0, 0, 1})) == "touching");      // from the cap's centre, away
  BOOST_TEST(name(line(Query::ray_cylinder, {0, 0, 1, 0, 0, 1})) == "overlapping");   // from inside
  BOOST_TEST(name(line(Query::segment_cylinder, {2, 0, 1, 3, 0, 1})) == "separated");
  BOOST_TEST(name(line(Query::segment_cylinder, {2, 0, 1, 1, 0, 1})) == "touching");  // ends on the wall
  BOOST_TEST(name(line(Query::segment_cylinder, {2, 0, 1, Q(99, 100), 0, 1})) == "overlapping");
  // Elliptic: x^2 + y^2 <= 1 in the frame a = (2, 0, 0), b = (0, 1, 0), c = (0, 0, 1).
  std::vector<Q> e{2, 0, Q(1, 2), 0, 1, 0, 0, 0, 0, 2, 0, 0, 0, 1, 0, 0, 0, 1};
  BOOST_TEST(name(oracle_elliptic(e)) == "touching");  // x = 1 in the frame: tangent
  e[0] = Q(199, 100);
  BOOST_TEST(name(oracle_elliptic(e)) == "overlapping");
  e[0] = Q(201, 100);
  BOOST_TEST(name(oracle_elliptic(e)) == "separated");
  // Crossing pairs: unit-radius axes along x and y, 2 + s apart along z.
  for (const auto& [dz, expected] : {std::pair{Q(0), Answer::touching}, std::pair{Q(1, 1000), Answer::separated},
                                     std::pair{Q(-1, 1000), Answer::overlapping}}) {
    const std::vector<Q> pair{-2, 0, 0, 2, 0, 0, 1, 0, -2, 2 + dz, 0, 2, 2 + dz, 1};
    const std::optional<Answer> got = oracle_crossing(pair);
    BOOST_TEST_REQUIRE(got.has_value());
    BOOST_TEST(name(*got) == name(expected));
  }
}

BOOST_AUTO_TEST_CASE(rotated_families_agree_with_the_oracle) {
  const std::vector<Family> all = all_families();
  struct Case {
    std::string family;
    Query query;
  };
  const std::vector<Case> cases{
      {"tangent_rotated", Query::line_cylinder},      {"tangent_rotated", Query::ray_cylinder},
      {"tangent_rotated", Query::segment_cylinder},   {"rim_rotated", Query::line_cylinder},
      {"rim_rotated", Query::ray_cylinder},           {"rim_rotated", Query::segment_cylinder},
      {"e_tangent_oblique", Query::line_elliptic_cylinder}, {"c_crossing_rotated", Query::cylinder_cylinder},
      {"uniform", Query::line_cylinder},              {"uniform", Query::ray_cylinder},
      {"uniform", Query::segment_cylinder},           {"uniform", Query::line_elliptic_cylinder},
  };
  for (const Case& c : cases) {
    const Family& f = family(all, c.family, c.query);
    Rng rng(20261128);
    Tally t;
    for (int sample = 0; sample < 40; ++sample) {
      for (const long long k : kDisplacements) {
        Instance inst;
        inst.family = f.name;
        inst.query = c.query;
        inst.x = f.make(rng, c.query, k).x;
        certify(inst);
        const std::vector<Q> x = exact(inst.x);
        std::optional<Answer> expected;
        if (c.query == Query::cylinder_cylinder) {
          expected = oracle_crossing(x);
        } else if (c.query == Query::line_elliptic_cylinder) {
          expected = oracle_elliptic(x);
        } else {
          expected = oracle_circular(c.query, x);
        }
        if (!expected) {
          ++t.skipped;
          continue;
        }
        BOOST_TEST_CONTEXT(c.family << " " << to_string(c.query) << " sample " << sample << " k " << k) {
          BOOST_TEST(name(inst.certified) == name(*expected));
        }
        count(t, *expected);
      }
    }
    BOOST_TEST_MESSAGE(c.family << " " << to_string(c.query) << ": " << t.checked << " checked (" << t.answers[0] << " separated, "
                                << t.answers[1] << " touching, " << t.answers[2] << " overlapping), " << t.skipped << " skipped");
    // Most instances are checked, and both sides of the degeneracy occur.
    BOOST_TEST(t.checked >= 400);
    BOOST_TEST(t.answers[0] > 0);
    BOOST_TEST(t.answers[2] > 0);
  }
}
