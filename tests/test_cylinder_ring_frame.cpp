// The ring frame of detail/cylinder_ring_frame.hpp and the touching proof in it
// (prove_touching_ring, detail/cylinder_touching.hpp): every decision checked against the same
// decision in Gmpq on constructed near-degenerate inputs.
//  - conversions: integers of either sign and zero, dyadic rationals, directions;
//  - separation_sign and strictly_inside_both in the ring frame against Gmpq in the input frame,
//    for rational input (times the lcm of its denominators) and binary64 input (times a power
//    of two), at directions and points within 2^-60 of a contact normal and a contact point;
//  - prove_touching_ring against prove_touching for the seven touching configurations turned by
//    rational rotations, exactly touching and moved by 2^-60 or one binary64 ulp either way,
//    at the structural candidates and the contact normal (same decision, same features, same
//    point, normal parallel), each proved contact rechecked from the definition.
#define BOOST_TEST_MODULE cylinder_ring_frame
#include <boost/test/unit_test.hpp>

#include <random>

#include "test_cylinder_cylinder_cases.hpp"

using namespace cctest;
using certcyl::detail::CylinderPair;
using certcyl::detail::RingFrame;
using M = CGAL::Mpzf;

namespace {

Q to_q(const M& x) { return Q(static_cast<CGAL::Gmpq>(x)); }

bool parallel(const Vec3<Q>& u, const Vec3<Q>& v) { return cross(u, v) == Vec3<Q>{0, 0, 0}; }

// The rotations the pairs are turned by (identity first).
std::vector<Rotation> rotations() {
  std::vector<Rotation> out = {Rotation::from_quaternion(1, 0, 0, 0)};
  std::mt19937_64 g(20261126);
  std::uniform_int_distribution<long> q(-9, 9);
  for (int i = 0; i < 6; ++i) {
    long a, b, c, d;
    do {
      a = q(g), b = q(g), c = q(g), d = q(g);
    } while (a * a + b * b + c * c + d * d == 0);
    out.push_back(Rotation::from_quaternion(a, b, c, d));
  }
  return out;
}

// The binary64 pair nearest (a, b) when each coordinate is a double, else nullopt.
std::optional<std::pair<Cylinder<double>, Cylinder<double>>> as_binary64(const Cylinder<Q>& a, const Cylinder<Q>& b) {
  bool ok = true;
  const auto d = [&ok](const Q& q) {
    double x = 0;
    if (!certcyl::detail::exact_double(q, x)) ok = false;
    return x;
  };
  auto p = std::make_pair(a.map(d), b.map(d));
  if (!ok) return std::nullopt;
  return p;
}

// The world frame of a binary64 pair: times 2^k so that the largest magnitude is in [1, 2).
RingFrame world_ring(const Cylinder<double>& a, const Cylinder<double>& b) {
  double m = 0;
  for (const Cylinder<double>* c : {&a, &b})
    for (double x : {c->p0.x, c->p0.y, c->p0.z, c->p1.x, c->p1.y, c->p1.z, c->radius}) m = std::max(m, std::abs(x));
  int e = 0;
  std::frexp(m, &e);
  const int k = 1 - e;
  const auto s = [k](double x) { return std::ldexp(x, k); };
  return RingFrame::from_world(a.map(s), b.map(s), k);
}

// The pairs: each configuration turned, exactly touching and moved along the normal by +-2^-60;
// and scaled to integers then moved by one ulp of the largest coordinate (binary64).
struct Pair {
  std::string name;
  Cylinder<Q> a, b;
  Vec3<Q> normal;
  Point3<Q> contact;
};

std::vector<Pair> pairs() {
  std::vector<Pair> out;
  const Q tiny = Q(1) / Q(CGAL::Gmpz(1) << 60);
  int r = 0;
  for (const Rotation& R : rotations()) {
    for (const TouchingCase& base : base_touching_cases()) {
      const TouchingCase c = moved(base, R, {Q(r, 7), Q(-3), Q(1, 3)});
      const std::string name = base.name + " rotation " + std::to_string(r);
      out.push_back({name + " touching", c.a, c.b, c.normal, c.contact});
      out.push_back({name + " +2^-60", c.a, translate(c.b, tiny * c.normal), c.normal, c.contact});
      out.push_back({name + " -2^-60", c.a, translate(c.b, -tiny * c.normal), c.normal, c.contact});
      if (r == 0) {
        // Integer, binary64: scaled by 2^20, moved by 2 ulp of 2^21 along the signs of the normal.
        const Q s(1 << 20);
        const Cylinder<Q> a = scale(c.a, s), b = scale(c.b, s);
        const Q u = Q(1) / Q(CGAL::Gmpz(1) << 31);
        const auto sg = [](const Q& x) { return Q(x > 0 ? 1 : (x < 0 ? -1 : 0)); };
        const Vec3<Q> step{u * sg(c.normal.x), u * sg(c.normal.y), u * sg(c.normal.z)};
        out.push_back({name + " binary64 touching", a, b, c.normal, s * c.contact});
        out.push_back({name + " binary64 +1 ulp", a, translate(b, step), c.normal, s * c.contact});
        out.push_back({name + " binary64 -1 ulp", a, translate(b, -step), c.normal, s * c.contact});
      }
    }
    ++r;
  }
  return out;
}

// The ring frames of a pair: from its rational form always, and from its binary64 form when
// every number is a double.
std::vector<RingFrame> frames(const Pair& p) {
  std::vector<RingFrame> out;
  const std::optional<RingFrame> q = RingFrame::from_rational(p.a, p.b);
  BOOST_REQUIRE(q.has_value());
  out.push_back(*q);
  if (const auto d = as_binary64(p.a, p.b)) out.push_back(world_ring(d->first, d->second));
  return out;
}

// The ring frame's numbers are the input's times s: check it.
void check_frame(const Pair& p, const RingFrame& f) {
  const Q s = Q(f.L) * (f.e >= 0 ? Q(CGAL::Gmpz(1) << f.e) : Q(1) / Q(CGAL::Gmpz(1) << -f.e));
  BOOST_TEST((to_q(f.pair.c0.p0.x) == s * p.a.p0.x && to_q(f.pair.c0.p1.z) == s * p.a.p1.z && to_q(f.pair.c1.radius) == s * p.b.radius &&
              to_q(f.pair.c1.p1.y) == s * p.b.p1.y));
  BOOST_TEST((f.to_input(f.pair.c1.p0.x, M(1)) == p.b.p0.x));
  BOOST_TEST((f.to_input(M(3) * f.pair.c0.p1.y, M(3)) == p.a.p1.y));
  // Any dyadic n and w != 0, either sign: n / (w s), in lowest terms (== compares canonical Gmpq).
  for (const M& w : {M(1), M(3), M(-5), M(0.375), M(std::ldexp(-3.0, -70)), M(std::ldexp(7.0, 80))})
    for (const M& n : {f.pair.c0.p0.x, f.pair.c1.p1.z + M(0.25), M(0), M(-std::ldexp(1.0, -200))}) {
      const Q expected = to_q(n) / (to_q(w) * s);
      const Q got = f.to_input(n, w);
      BOOST_TEST((got == expected));
      BOOST_TEST(mpz_sgn(mpq_denref(got.mpq())) > 0);
      CGAL::Gmpz g;
      mpz_gcd(g.mpz(), mpq_numref(got.mpq()), mpq_denref(got.mpq()));
      BOOST_TEST((g == 1));
    }
}

}  // namespace

BOOST_AUTO_TEST_CASE(conversions_are_exact) {
  for (const char* text : {"0", "1", "-1", "18446744073709551616", "-18446744073709551617", "-340282366920938463463374607431768211456",
                           "123456789012345678901234567890"}) {
    const CGAL::Gmpz n(text);
    BOOST_TEST_CONTEXT(text) {
      const M m = certcyl::detail::mpzf_from_integer(n);
      BOOST_TEST((to_q(m) == Q(n)));
      BOOST_TEST((to_q(m * M(2)) == Q(2) * Q(n)));
      BOOST_TEST(CGAL::sign(m) == CGAL::sign(Q(n)));
    }
  }
  for (const Q& q : {Q(0), Q(3, 8), Q(-5, 1024), Q(CGAL::Gmpz(7), CGAL::Gmpz(1) << 700), Q(-(CGAL::Gmpz(1) << 900) + 1)}) {
    const std::optional<M> m = certcyl::detail::mpzf_from_dyadic(q);
    BOOST_TEST_REQUIRE(m.has_value());
    BOOST_TEST((to_q(*m) == q));
  }
  BOOST_TEST(!certcyl::detail::mpzf_from_dyadic(Q(1, 3)).has_value());
  const Vec3<Q> D{Q(1, 3), Q(-5, 6), Q(7)};
  const Vec3<Q> R = certcyl::detail::mpzf_to_rational(certcyl::detail::ring_direction(D));
  BOOST_TEST(parallel(R, D));
  BOOST_TEST(dot(R, D) > 0);
  BOOST_TEST((R == Vec3<Q>{2, -5, 42}));
}

BOOST_AUTO_TEST_CASE(ring_checks_agree_with_gmpq) {
  std::mt19937_64 g(7);
  std::uniform_int_distribution<int> small(-3, 3);
  const Q tiny = Q(1) / Q(CGAL::Gmpz(1) << 60);
  int decided = 0;
  for (const Pair& p : pairs()) {
    const CylinderPair<Q> e = CylinderPair<Q>::make(p.a, p.b);
    for (const RingFrame& f : frames(p)) {
      BOOST_TEST_CONTEXT(p.name << " L " << f.L << " e " << f.e) {
        check_frame(p, f);
        // Directions at and within 2^-60 of the contact normal (dyadic perturbations).
        for (int k = 0; k < 6; ++k) {
          const Vec3<Q> D = p.normal + (k == 0 ? Q(0) : tiny) * Vec3<Q>{Q(small(g)), Q(small(g)), Q(small(g))};
          if (D == Vec3<Q>{0, 0, 0}) continue;
          const CGAL::Sign exact = certcyl::detail::separation_sign(e, D);
          BOOST_TEST(certcyl::detail::separation_sign(f.pair, certcyl::detail::ring_direction(D)) == exact);
          decided += exact == CGAL::POSITIVE;
        }
        // Points at and within 2^-60 of the contact point, as the ring frame sees them.
        for (int k = 0; k < 6; ++k) {
          const Point3<Q> X = p.contact + (k == 0 ? Q(0) : tiny) * Vec3<Q>{Q(small(g)), Q(small(g)), Q(small(g))};
          const bool inside = certcyl::detail::strictly_inside_both(e, X);
          const bool closed = certcyl::detail::in_both_closed(e, X);
          // X in the ring frame: X s as n / w with w = 1 when X s is dyadic; else n = X s w.
          const Q s = Q(f.L) * (f.e >= 0 ? Q(CGAL::Gmpz(1) << f.e) : Q(1) / Q(CGAL::Gmpz(1) << -f.e));
          const Point3<Q> Y = s * X;
          CGAL::Gmpz l = 1;
          for (std::size_t i = 0; i < 3; ++i) mpz_lcm(l.mpz(), l.mpz(), mpq_denref(Y[i].mpq()));
          const Point3<M> n = Y.map([&l](const Q& y) { return *certcyl::detail::mpzf_from_dyadic(y * Q(l)); });
          const M w = certcyl::detail::mpzf_from_integer(l);
          const auto scaled = [&w](const Cylinder<M>& c) { return Cylinder<M>{w * c.p0, w * c.p1, w * c.radius}; };
          const CylinderPair<M> pw = CylinderPair<M>::make(scaled(f.pair.c0), scaled(f.pair.c1));
          BOOST_TEST(certcyl::detail::strictly_inside_both(pw, n) == inside);
          BOOST_TEST(certcyl::detail::in_both_closed(pw, n) == closed);
        }
      }
    }
  }
  BOOST_TEST(decided > 0);
}

BOOST_AUTO_TEST_CASE(ring_touching_proof_agrees_with_gmpq) {
  int proved = 0;
  for (const Pair& p : pairs()) {
    const CylinderPair<Q> e = CylinderPair<Q>::make(p.a, p.b);
    std::vector<Vec3<Q>> candidates = {p.normal, e.A0, e.A1, cross(e.A0, e.A1), e.AA0 * e.T - dot(e.A0, e.T) * e.A0,
                                       e.AA1 * e.T - dot(e.A1, e.T) * e.A1, -p.normal};
    for (const Vec3<Q>& D : certcyl::detail::rim_contact_normals(e)) candidates.push_back(D);
    for (const RingFrame& f : frames(p)) {
      for (const Vec3<Q>& D : candidates) {
        if (D == Vec3<Q>{0, 0, 0}) continue;
        BOOST_TEST_CONTEXT(p.name << " L " << f.L << " e " << f.e << " D " << D.x << " " << D.y << " " << D.z) {
          const auto exact = certcyl::detail::prove_touching(e, D);
          const auto ring = certcyl::detail::prove_touching_ring(f.pair, certcyl::detail::ring_direction(D));
          BOOST_TEST_REQUIRE(exact.has_value() == ring.has_value());
          if (!exact) continue;
          ++proved;
          BOOST_TEST((ring->feature0 == exact->feature0 && ring->feature1 == exact->feature1));
          const Vec3<Q> normal = certcyl::detail::mpzf_to_rational(ring->normal);
          BOOST_TEST(parallel(normal, exact->normal));
          BOOST_TEST(dot(normal, exact->normal) > 0);
          const Point3<Q> X = ring->point.n.map([&f, &ring](const M& x) { return f.to_input(x, ring->point.w); });
          BOOST_TEST((X == exact->point));
          BOOST_TEST(CGAL::sign(ring->point.w) == CGAL::POSITIVE);
          // From the definition: X in both closed cylinders, and D supports both there.
          BOOST_TEST(position(X, p.a) >= 0);
          BOOST_TEST(position(X, p.b) >= 0);
          BOOST_TEST(separation_sign_core(p.a, p.b, normal) == 0);
        }
      }
    }
  }
  BOOST_TEST(proved > 0);
}

// simplest_convergent (integer continued fractions) against the same definition in Gmpq: the
// first convergent within the tolerance, on fractions near small-height ones and on random ones.
namespace {
Q convergent_reference(const Q& x, const Q& tolerance) {
  CGAL::Gmpz h_prev(1), h_prev2(0), k_prev(0), k_prev2(1);
  Q y = x;
  for (int i = 0; i < 400; ++i) {
    CGAL::Gmpz a;
    mpz_fdiv_q(a.mpz(), mpq_numref(y.mpq()), mpq_denref(y.mpq()));
    const CGAL::Gmpz h = a * h_prev + h_prev2, k = a * k_prev + k_prev2;
    const Q approx(h, k);
    const Q error = x - approx;
    if ((error < 0 ? Q(-error) : error) <= tolerance) return approx;
    const Q frac = y - Q(a);
    if (frac == 0) return approx;
    y = 1 / frac;
    h_prev2 = h_prev, h_prev = h, k_prev2 = k_prev, k_prev = k;
  }
  return x;
}
}  // namespace

BOOST_AUTO_TEST_CASE(reconstruction_agrees_with_gmpq) {
  std::mt19937_64 g(11);
  std::uniform_int_distribution<long> num(-1000000, 1000000), den(1, 1000000);
  const Q tiny = Q(1) / Q(CGAL::Gmpz(1) << 100);
  for (int i = 0; i < 2000; ++i) {
    const Q base(num(g), den(g));
    const Q x = i % 3 == 0 ? base : base + Q(num(g) % 7) * tiny;
    for (const Q& tol : {Q(0), Q(1) / Q(CGAL::Gmpz(1) << 20), Q(1) / Q(CGAL::Gmpz(1) << 50), Q(1, 3)}) {
      BOOST_TEST_CONTEXT(x << " tolerance " << tol) { BOOST_TEST((certcyl::detail::simplest_convergent(x, tol) == convergent_reference(x, tol))); }
    }
  }
  // reconstruct_direction (unreduced quotients over the coordinate largest in magnitude, the
  // first one on ties) against its definition in Gmpq, on directions near integer ones given as
  // dyadic numbers (as the refine stage's double-double directions are), with ties and zeros.
  std::uniform_int_distribution<long> small(-40, 40);
  for (int i = 0; i < 3000; ++i) {
    Vec3<Q> D{Q(small(g)), Q(small(g)), Q(small(g))};
    if (i % 5 == 0) D.y = i % 2 ? D.x : Q(-D.x);  // a tie in magnitude
    if (D == Vec3<Q>{0, 0, 0}) continue;
    const Q s = Q(den(g)) / Q(CGAL::Gmpz(1) << (i % 60));
    for (std::size_t j = 0; j < 3; ++j)
      if (D[j] != 0 && i % 4 != 1) D[j] = s * D[j] + Q(num(g) % 9) * tiny;
    for (const Q& tol : {Q(1) / Q(CGAL::Gmpz(1) << 50), Q(1) / Q(CGAL::Gmpz(1) << 20)}) {
      std::size_t k = 0;
      for (std::size_t j = 1; j < 3; ++j)
        if (CGAL::abs(D[j]) > CGAL::abs(D[k])) k = j;
      Vec3<Q> expected;
      for (std::size_t j = 0; j < 3; ++j) expected[j] = j == k ? Q(1) : convergent_reference(D[j] / D[k], tol);
      BOOST_TEST_CONTEXT(D.x << " " << D.y << " " << D.z << " tolerance " << tol) { BOOST_TEST((certcyl::detail::reconstruct_direction(D, tol) == expected)); }
    }
  }
}

// The span in binades read off a binary64 pair's world frame in Mpzf (the solver's
// input_span_bits for such input) equals the span of the same pair in Gmpq, on random pairs
// over the whole exponent range and on pairs built so that an axis or T is just below or above
// a power of two, or cancels to a few ulps, or is subnormal in the world frame (where CGAL's
// double enclosure of an Mpzf widens to 0 and the binade is read in Gmpq).
BOOST_AUTO_TEST_CASE(span_from_the_world_frame_equals_span_in_gmpq) {
  using certcyl::detail::cylinder_pair_span_bits;
  std::mt19937_64 g(20261127);
  std::uniform_int_distribution<int> exponent(-1074, 1023);
  std::uniform_real_distribution<double> unit(1, 2);
  std::bernoulli_distribution coin(0.5);
  const auto number = [&](int span_lo, int span_hi) {
    const double x = std::ldexp(unit(g), std::uniform_int_distribution<int>(span_lo, span_hi)(g));
    return coin(g) ? -x : x;
  };
  long compared = 0;
  const auto check = [&](const Cylinder<double>& a, const Cylinder<double>& b) {
    double m = 0;
    for (const Cylinder<double>* c : {&a, &b})
      for (double x : {c->p0.x, c->p0.y, c->p0.z, c->p1.x, c->p1.y, c->p1.z, c->radius}) m = std::max(m, std::abs(x));
    int e = 0;
    std::frexp(m, &e);
    bool exact = true;  // the solver uses the world frame only when the scaling is exact
    const auto s = [&](double x) {
      const double y = std::ldexp(x, 1 - e);
      exact = exact && std::ldexp(y, e - 1) == x;
      return y;
    };
    const RingFrame f = RingFrame::from_world(a.map(s), b.map(s), 1 - e);
    if (!exact) return;
    const auto q = [](double x) { return Q(x); };
    ++compared;
    BOOST_TEST(cylinder_pair_span_bits(f.pair) == cylinder_pair_span_bits(CylinderPair<Q>::make(a.map(q), b.map(q))));
  };
  for (int i = 0; i < 4000; ++i) {
    // Every number in one random window of 60 to 2,000 binades.
    const int lo = exponent(g), width = std::uniform_int_distribution<int>(60, 2000)(g), hi = std::min(1023, lo + width);
    const auto n = [&] { return number(lo, hi); };
    const Cylinder<double> a{{n(), n(), n()}, {n(), n(), n()}, std::abs(n())}, b{{n(), n(), n()}, {n(), n(), n()}, std::abs(n())};
    check(a, b);
  }
  BOOST_TEST(compared > 3000);
  for (int k = -1000; k <= 1000; k += 37) {
    const double p = std::ldexp(1.0, k);
    for (int j : {1, 30, 52, 53, 54, 60, 200}) {
      const double t = std::ldexp(1.0, k - j);
      // An axis of 2^k - 2^(k-j) or 2^k + 2^(k-j), and T of a few ulps after cancelling.
      const Cylinder<double> a{{t, 0, 1}, {p, 0, 1}, 1}, b{{-t, 3, 1}, {p, 5, 1}, 0.5};
      const Cylinder<double> c{{-t, 0, p}, {p, 1, p}, p}, d{{t, 0, -p}, {-p, -1, std::nextafter(-p, 0.0)}, p};
      const Cylinder<double> all_ones{{0, 0, 0}, {std::nextafter(2 * p, 0.0), 0, 0}, p};
      check(a, b);
      check(c, d);
      check(b, c);
      check(all_ones, a);
    }
  }
  BOOST_TEST(compared > 3500);
}

// separation_sign_bounds (c exact, then 128-bit MPFR bounds rounded outwards) against the exact
// squaring, in Q, in the ring frame (Mpzf) and in the integer frame (Gmpz), at each touching
// configuration's contact normal with the second cylinder moved along it by 2^-k either way
// (k = 4 ... 400; one way separates, the other overlaps): whenever the bounds decide, the sign is
// the exact one; they decide every move up to 2^-60 and leave every move from 2^-140 on (and
// the exact zeros at k = 0) to the squaring, unless both roots vanish (then they are exact).
BOOST_AUTO_TEST_CASE(separation_bounds_agree_with_the_exact_sign) {
  namespace cd = certcyl::detail;
  int decided = 0, positive = 0, open = 0;
  for (const TouchingCase& base : base_touching_cases()) {
    const TouchingCase c = moved(base, rotations()[1], {Q(2, 7), Q(-3), Q(1, 3)});
    for (const int k : {0, 4, 20, 60, 100, 110, 118, 126, 140, 200, 400}) {
      for (const int side : {1, -1}) {
        const Q t = k == 0 ? Q(0) : Q(side) / Q(CGAL::Gmpz(1) << k);
        const Cylinder<Q> b = translate(c.b, t * c.normal);
        BOOST_TEST_CONTEXT(base.name << " moved by " << side << " 2^-" << k) {
          const CylinderPair<Q> e = CylinderPair<Q>::make(c.a, b);
          const CGAL::Sign exact = cd::separation_sign_exact(e, c.normal);
          if (k == 0) BOOST_TEST(exact == CGAL::ZERO);
          const std::optional<CGAL::Sign> q = cd::separation_sign_bounds(e, c.normal);
          const std::optional<RingFrame> f = RingFrame::from_rational(c.a, b);
          BOOST_TEST_REQUIRE(f.has_value());
          const Vec3<M> Dm = cd::ring_direction(c.normal);
          const std::optional<CGAL::Sign> m = cd::separation_sign_bounds(f->pair, Dm);
          BOOST_TEST(cd::separation_sign_exact(f->pair, Dm) == exact);
          const cd::IntegerPair z(e);
          const Vec3<CGAL::Gmpz> Dz = Dm.map([](const M& x) { return CGAL::Gmpz(mpq_numref(static_cast<CGAL::Gmpq>(x).mpq())); });
          const std::optional<CGAL::Sign> g = cd::separation_sign_bounds(z.d, Dz);
          BOOST_TEST(cd::separation_sign_exact(z.d, Dz) == exact);
          for (const std::optional<CGAL::Sign>& s : {q, m, g}) {
            if (s) {
              BOOST_TEST(*s == exact);
              ++decided;
              positive += *s == CGAL::POSITIVE;
            } else {
              ++open;
            }
          }
          // With D x A0 = D x A1 = 0 (a cap-cap contact's axis normal) both roots are zero and
          // the bounds are exact: they decide at every k.
          const Vec3<Q> zero{0, 0, 0};
          const bool roots_vanish = cross(c.normal, e.A0) == zero && cross(c.normal, e.A1) == zero;
          if (roots_vanish || (k > 0 && k <= 60)) BOOST_TEST((q && m && g));
          if (!roots_vanish && k >= 140) BOOST_TEST((!q && !m && !g));
        }
      }
    }
  }
  BOOST_TEST(positive > 0);
  BOOST_TEST(open > 0);
  BOOST_TEST(decided > open);
}
