// The seeds' line/cylinder methods (Shene, Gullotti) and the robust double method: hand
// cases in every number type, the seeds' flaws as regression cases, and agreement of the
// exact (CORE::Expr) runs with the certified query on random input.
#define BOOST_TEST_MODULE line_seeds
#include <boost/mpl/list.hpp>
#include <boost/test/unit_test.hpp>

#include <iostream>
#include <optional>
#include <random>
#include <string>

#include "certcyl/certified/line_cylinder.hpp"
#include "certcyl/number_traits_core.hpp"
#include "certcyl/robust/line_cylinder.hpp"
#include "certcyl/seeds/gullotti_line_elliptic_cylinder.hpp"
#include "certcyl/seeds/shene_line_cylinder.hpp"

using namespace certcyl;
using Q = Rational;

namespace {

Q q(const char* s) { return parse_rational(s); }

const Cylinder<Q> unit{{0, 0, 0}, {0, 0, 1}, 1};
const EllipticCylinder<Q> ellipse{{0, 0, 0}, {2, 0, 0}, {0, 1, 0}, {0, 0, 1}};
const EllipticCylinder<Q> oblique{{0, 0, 0}, {2, 0, 0}, {0, 1, 0}, {1, 0, 1}};

struct Expect {
  Answer answer;
  Q in, out;
  LineFeature fin, fout;
};

// Number types: each runs inside what it needs (rounding mode, precision).
struct Gmpfr53 {};
struct Gmpfr200 {};
template <class Tag>
struct Scope {
  template <class F>
  static void run(F&& f) {
    f.template operator()<Tag>();
  }
};
template <>
struct Scope<Interval> {
  template <class F>
  static void run(F&& f) {
    with_interval_rounding([&] { f.template operator()<Interval>(); });
  }
};
template <>
struct Scope<Gmpfr53> {
  template <class F>
  static void run(F&& f) {
    GmpfrPrecision p(53);
    f.template operator()<CGAL::Gmpfr>();
  }
};
template <>
struct Scope<Gmpfr200> {
  template <class F>
  static void run(F&& f) {
    GmpfrPrecision p(200);
    f.template operator()<CGAL::Gmpfr>();
  }
};

using Types = boost::mpl::list<double, long double, Interval, Gmpfr53, Gmpfr200, CORE::Expr>;

// Every operation in these cases is exact in every type (unit directions, small integers), so
// the results are asserted for all types; an interval may still refuse (it never did here).
template <class NT>
void check(const LineInterval<NT>& r, const Expect& e, const std::string& what) {
  BOOST_TEST_CONTEXT(what << " in " << nt::name<NT>()) {
    BOOST_TEST(to_string(r.answer) == to_string(e.answer));
    if (e.answer == Answer::separated) return;
    BOOST_REQUIRE(r.in && r.out);
    BOOST_TEST(nt::compare(r.in->t, nt::from_rational<NT>(e.in)) == CGAL::EQUAL);
    BOOST_TEST(nt::compare(r.out->t, nt::from_rational<NT>(e.out)) == CGAL::EQUAL);
    BOOST_TEST(to_string(r.in->feature) == to_string(e.fin));
    BOOST_TEST(to_string(r.out->feature) == to_string(e.fout));
  }
}

const LineFeature W = LineFeature::wall, C0 = LineFeature::cap0, C1 = LineFeature::cap1;

}  // namespace

BOOST_AUTO_TEST_CASE_TEMPLATE(hand_cases_every_type, Tag, Types) {
  Scope<Tag>::run([]<class NT>() {
    const auto cyl = convert<NT>(unit);
    auto L = [](Vec3<Q> o, Vec3<Q> d) { return convert<NT>(Line<Q>{o, d}); };
    // Through the axis; tangent; missing; along the axis; through the caps at a slant.
    const std::pair<Line<Q>, Expect> cases[] = {
        {{{-2, 0, q("1/2")}, {1, 0, 0}}, {Answer::overlapping, 1, 3, W, W}},
        {{{-2, 1, q("1/2")}, {1, 0, 0}}, {Answer::touching, 2, 2, W, W}},
        {{{-2, 2, q("1/2")}, {1, 0, 0}}, {Answer::separated, 0, 0, W, W}},
        {{{0, 0, -1}, {0, 0, 1}}, {Answer::overlapping, 1, 2, C0, C1}},
        {{{q("1/2"), 0, -1}, {0, 0, 1}}, {Answer::overlapping, 1, 2, C0, C1}},
        {{{0, -3, q("1/2")}, {0, 1, 0}}, {Answer::overlapping, 2, 4, W, W}},
    };
    for (const auto& [line, e] : cases) {
      const auto l = L(line.origin, line.direction);
      check(shene_line_cylinder(l, cyl), e, "shene");
      check(detail::gullotti_solve(detail::gullotti_quadratic(l, cyl), GullottiVariant::corrected), e, "gullotti circular");
    }
    // Elliptic: y = 0 through x^2/4 + y^2 <= 1; the oblique cylinder along c.
    check(gullotti_line_elliptic_cylinder(L({-4, 0, q("1/2")}, {1, 0, 0}), convert<NT>(ellipse)),
          {Answer::overlapping, 2, 6, W, W}, "gullotti elliptic");
    check(gullotti_line_elliptic_cylinder(L({-4, 1, q("1/2")}, {1, 0, 0}), convert<NT>(ellipse)),
          {Answer::touching, 4, 4, W, W}, "gullotti elliptic tangent");
    check(gullotti_line_elliptic_cylinder(L({0, 0, -1}, {1, 0, 1}), convert<NT>(oblique)),
          {Answer::overlapping, 1, 2, C0, C1}, "gullotti oblique");
    check(gullotti_line_elliptic_cylinder(L({-3, 0, q("1/2")}, {1, 0, 0}), convert<NT>(oblique)),
          {Answer::overlapping, q("3/2"), q("11/2"), W, W}, "gullotti oblique wall");
    // Rays and segments by clipping.
    check(shene_line_cylinder(convert<NT>(Ray<Q>{{0, 0, q("1/2")}, {1, 0, 0}}), cyl),
          {Answer::overlapping, 0, 1, LineFeature::origin, W}, "shene ray");
    check(gullotti_line_elliptic_cylinder(convert<NT>(Segment<Q>{{-4, 0, q("1/2")}, {0, 0, q("1/2")}}), convert<NT>(ellipse)),
          {Answer::overlapping, q("1/2"), 1, W, LineFeature::end}, "gullotti segment");
  });
}

// Rational types without sqrt cannot run these methods; the implicit quadratic's coefficients
// need none, and are checked in Gmpq against the cancellation-free discriminant.
BOOST_AUTO_TEST_CASE(implicit_discriminant_identity_in_gmpq) {
  std::mt19937_64 rng(3);
  std::uniform_int_distribution<int> u(-9, 9);
  for (int i = 0; i < 500; ++i) {
    const Cylinder<Q> c{{u(rng), u(rng), u(rng)}, {u(rng), u(rng), Q(u(rng)) + 20}, Q(1 + i % 5, 3)};
    const Line<Q> l{{u(rng), u(rng), u(rng)}, {u(rng), u(rng), Q(u(rng)) + Q(1, 7)}};
    const auto g = detail::gullotti_quadratic(l, c);
    const auto k = detail::line_quadric(l.origin, l.direction, c);
    // b_gullotti = 2 b, so b_g^2 - 4 a c = 4 (b^2 - a c) = 4 disc.
    BOOST_TEST(g.b * g.b - Q(4) * g.a * g.c == Q(4) * k.disc);
  }
}

// Gullotti's "|v^.h^| = 1: the line lies on the surface" holds for every line parallel to
// the axis, since then a = b = 0 and b^2 - 4ac = 0: as written it reports a line through the
// middle and a line far outside as lying on the wall.
BOOST_AUTO_TEST_CASE(gullotti_parallel_line_flaw) {
  using E = CORE::Expr;
  const auto e = convert<E>(ellipse);
  const auto inside = convert<E>(Line<Q>{{0, 0, 5}, {0, 0, -1}});
  const auto outside = convert<E>(Line<Q>{{5, 0, 5}, {0, 0, -1}});
  const auto on = convert<E>(Line<Q>{{2, 0, 5}, {0, 0, -1}});
  BOOST_TEST(to_string(gullotti_line_elliptic_cylinder(inside, e, GullottiVariant::as_written).answer) == "touching");
  BOOST_TEST(to_string(gullotti_line_elliptic_cylinder(outside, e, GullottiVariant::as_written).answer) == "touching");
  BOOST_TEST(to_string(gullotti_line_elliptic_cylinder(inside, e).answer) == "overlapping");
  BOOST_TEST(to_string(gullotti_line_elliptic_cylinder(outside, e).answer) == "separated");
  const auto r = gullotti_line_elliptic_cylinder(on, e);
  BOOST_TEST(to_string(r.answer) == "touching");
  BOOST_TEST(to_string(r.in->feature) == "rim1");  // z = 5 - t reaches z = 1 first, at t = 4
  BOOST_TEST((r.in->t == E(4)));
}

// Shene's text: "If r < |d|, two points". With the condition as printed, a line through the
// axis (d = 0 < r) would be reported as missing; the corrected r > |d| gives two points.
BOOST_AUTO_TEST_CASE(shene_condition_slip) {
  using E = CORE::Expr;
  const auto r = shene_line_cylinder(convert<E>(Line<Q>{{-2, 0, q("1/2")}, {1, 0, 0}}), convert<E>(unit));
  BOOST_TEST(to_string(r.answer) == "overlapping");
  const auto miss = shene_line_cylinder(convert<E>(Line<Q>{{-2, 3, q("1/2")}, {1, 0, 0}}), convert<E>(unit));
  BOOST_TEST(to_string(miss.answer) == "separated");
}

// The same text read as printed (SheneVariant::as_written), on the unit cylinder (axis z,
// z in [0, 1], r = 1) with lines along x at height 1/2. By hand, for the line through
// (-2, y0, 1/2): u = (1, 0, 0), v = (0, 0, 1), w = u x v = (0, -1, 0), B - A = (2, -y0, -1/2),
// d = (B - A).w = y0, P = (0, y0, 1/2) at s = 2, 1 - (u.v)^2 = 1, so x^2 = r^2 - d^2 = 1 - y0^2.
//   y0 = 0: r > |d|. Corrected: two points t = 2 -+ 1 = 1, 3. As written ("otherwise"): none.
//   y0 = 3: r < |d|. Corrected: none. As written: "two points" with x^2 = -8, not real.
//   y0 = 1: r = |d|. Both: tangent at P, t = 2.
template <class NT>
void shene_variants_in() {
  const auto line = [](int y0) { return convert<NT>(Line<Q>{{-2, y0, q("1/2")}, {1, 0, 0}}); };
  const auto cyl = convert<NT>(unit);
  const auto through = shene_line_cylinder(line(0), cyl, SheneVariant::as_written);
  BOOST_TEST(to_string(through.answer) == "separated");
  BOOST_TEST(!through.in);
  const auto through_c = shene_line_cylinder(line(0), cyl, SheneVariant::corrected);
  BOOST_TEST(to_string(through_c.answer) == "overlapping");
  BOOST_TEST_REQUIRE(through_c.in.has_value());
  BOOST_TEST(nt::to_double(through_c.in->t) == 1.0);
  BOOST_TEST(nt::to_double(through_c.out->t) == 3.0);
  const auto miss = shene_line_cylinder(line(3), cyl, SheneVariant::as_written);
  BOOST_TEST(to_string(miss.answer) == "overlapping");
  BOOST_TEST(!miss.in);  // no real points
  BOOST_TEST(to_string(shene_line_cylinder(line(3), cyl, SheneVariant::corrected).answer) == "separated");
  for (SheneVariant v : {SheneVariant::as_written, SheneVariant::corrected}) {
    const auto tangent = shene_line_cylinder(line(1), cyl, v);
    BOOST_TEST(to_string(tangent.answer) == "touching");
    BOOST_TEST_REQUIRE(tangent.in.has_value());
    BOOST_TEST(nt::to_double(tangent.in->t) == 2.0);
    BOOST_TEST(to_string(tangent.in->feature) == "wall");
  }
  // A ray from (-2, 3, 1/2) along x: as written the line's "two points" have nothing to clip,
  // so the ray is reported as the line; a ray from (2, 0, 1/2) pointing away from the
  // cylinder, through the axis line behind it: corrected the line's [-3, -1] is clipped away,
  // as written the line is already missing.
  const auto ray_miss = shene_line_cylinder(convert<NT>(Ray<Q>{{-2, 3, q("1/2")}, {1, 0, 0}}), cyl, SheneVariant::as_written);
  BOOST_TEST(to_string(ray_miss.answer) == "overlapping");
  const Ray<Q> away{{2, 0, q("1/2")}, {1, 0, 0}};
  BOOST_TEST(to_string(shene_line_cylinder(convert<NT>(away), cyl, SheneVariant::corrected).answer) == "separated");
  BOOST_TEST(to_string(shene_line_cylinder(convert<NT>(away), cyl, SheneVariant::as_written).answer) == "separated");
  // A segment from (-2, 0, 1/2) to (0, 0, 1/2), through the wall at t = 1/2: corrected
  // overlapping [1/2, 1], as written separated.
  const Segment<Q> seg{{-2, 0, q("1/2")}, {0, 0, q("1/2")}};
  const auto seg_c = shene_line_cylinder(convert<NT>(seg), cyl, SheneVariant::corrected);
  BOOST_TEST(to_string(seg_c.answer) == "overlapping");
  BOOST_TEST_REQUIRE(seg_c.in.has_value());
  BOOST_TEST(nt::to_double(seg_c.in->t) == 0.5);
  BOOST_TEST(to_string(shene_line_cylinder(convert<NT>(seg), cyl, SheneVariant::as_written).answer) == "separated");
}

BOOST_AUTO_TEST_CASE(shene_as_written_swaps_crossing_and_missing) {
  shene_variants_in<CORE::Expr>();
  shene_variants_in<double>();
  GmpfrPrecision p(53);
  shene_variants_in<CGAL::Gmpfr>();
}

// A line at angle ~2^-300 to the axis, inside the tube: it crosses cap1 at t = 1 / 0.890625 and
// cap0 at t = 2 / 0.890625. CORE::Expr (CGAL 5.5.1) finds 1 - (u.v)^2 zero here although it is
// ~2^-600; the seed must not divide by it (CORE aborts the process on such a division).
BOOST_AUTO_TEST_CASE(shene_tiny_angle_in_core_expr) {
  using E = CORE::Expr;
  const Line<Q> l{{q("1/2"), 0, 2}, {Q(0x1p-300), 0, Q(-0x1.c8p-1)}};
  const auto r = shene_line_cylinder(convert<E>(l), convert<E>(unit));
  BOOST_TEST(to_string(r.answer) == "overlapping");
  BOOST_TEST_REQUIRE(r.in.has_value());
  BOOST_TEST((r.in->t * E(0x1.c8p-1) == E(1)));
  BOOST_TEST((r.out->t * E(0x1.c8p-1) == E(2)));
  BOOST_TEST(to_string(certified_line_cylinder(l, unit).answer) == "overlapping");
  // As written: overlapping from the parallel branch where CORE finds 1 - (u.v)^2 zero,
  // separated where it does not (r > |d| is the printed "otherwise"); it must return.
  const auto w = shene_line_cylinder(convert<E>(l), convert<E>(unit), SheneVariant::as_written);
  BOOST_TEST((w.answer == Answer::overlapping || w.answer == Answer::separated));
}

// A chord in a cap plane: the seeds see two wall hits on the rim and say overlapping; the
// exact answer is touching (the line meets only the boundary).
BOOST_AUTO_TEST_CASE(seeds_cannot_see_a_cap_plane_chord) {
  using E = CORE::Expr;
  const Line<Q> chord{{-2, 0, 1}, {1, 0, 0}};
  BOOST_TEST(to_string(shene_line_cylinder(convert<E>(chord), convert<E>(unit)).answer) == "overlapping");
  BOOST_TEST(to_string(certified_line_cylinder(chord, unit).answer) == "touching");
}

// The exact runs of the seeds agree with the certified query on random rational input,
// endpoint for endpoint, wherever the certified answer is not touching.
BOOST_AUTO_TEST_CASE(seeds_in_core_expr_agree_with_certified) {
  using E = CORE::Expr;
  std::mt19937_64 rng(11);
  std::cout << "seeds_in_core_expr_agree_with_certified: seed 11\n";
  std::uniform_int_distribution<int> u(-4, 4);
  long compared = 0, overlapping = 0;
  auto same = [](const E& t, const QuadraticNumber& x) {
    const E ex = x.is_rational() ? E(CORE::BigRat(x.alpha.mpq()))
                                 : E(CORE::BigRat(x.alpha.mpq())) + E(CORE::BigRat(x.beta.mpq())) * CORE::sqrt(E(CORE::BigInt(x.gamma.mpz())));
    return t == ex;
  };
  for (int i = 0; i < 400; ++i) {
    Vec3<Q> p0{u(rng), u(rng), u(rng)}, p1{u(rng), u(rng), u(rng)};
    if (p0 == p1) p1.z += 2;
    const Cylinder<Q> c{p0, p1, Q(1 + i % 3)};
    Vec3<Q> d{u(rng), u(rng), u(rng)};
    if (d == Vec3<Q>{0, 0, 0}) d.x = 1;
    const Line<Q> l{p0 + Q(1, 2) * Vec3<Q>{u(rng), u(rng), u(rng)}, d};
    const auto cert = certified_line_cylinder(l, c);
    if (cert.answer == Answer::touching) continue;
    ++compared;
    const auto sh = shene_line_cylinder(convert<E>(l), convert<E>(c));
    const auto gu = gullotti_line_cylinder(convert<E>(l), convert<E>(c));
    BOOST_TEST_CONTEXT("case " << i) {
      BOOST_TEST(to_string(sh.answer) == to_string(cert.answer));
      BOOST_TEST(to_string(gu.answer) == to_string(cert.answer));
      if (cert.answer == Answer::overlapping && sh.in && gu.in) {
        ++overlapping;
        BOOST_TEST(same(sh.in->t, cert.in->value()));
        BOOST_TEST(same(sh.out->t, cert.out->value()));
        BOOST_TEST(same(gu.in->t, cert.in->value()));
        BOOST_TEST(same(gu.out->t, cert.out->value()));
        BOOST_TEST(to_string(sh.in->feature) == to_string(cert.in->feature));
        BOOST_TEST(to_string(gu.out->feature) == to_string(cert.out->feature));
      }
    }
  }
  std::cout << "  compared " << compared << ", overlapping " << overlapping << "\n";
  BOOST_TEST(overlapping > 50);
}

// The robust double method: the hand cases, and agreement with the certified query on random
// binary64 input (disagreements on random input are counted and printed, not expected).
BOOST_AUTO_TEST_CASE(robust_double) {
  const auto cyl = convert<double>(unit);
  const auto r1 = robust_line_cylinder(Line<double>{{-2, 0, 0.5}, {1, 0, 0}}, cyl);
  BOOST_TEST(to_string(r1.answer) == "overlapping");
  BOOST_TEST(r1.in->t == 1.0);
  BOOST_TEST(r1.out->t == 3.0);
  BOOST_TEST(to_string(robust_line_cylinder(Line<double>{{-2, 1, 0.5}, {1, 0, 0}}, cyl).answer) == "touching");
  BOOST_TEST(to_string(robust_line_cylinder(Line<double>{{1, 0, 5}, {0, 0, 2}}, cyl).answer) == "touching");
  BOOST_TEST(to_string(robust_line_cylinder(Line<double>{{-2, 0, 0}, {1, 0, 0}}, cyl).answer) == "touching");
  const auto ax = robust_line_cylinder(Line<double>{{0, 0, -1}, {0, 0, 1}}, cyl);
  BOOST_TEST(to_string(ax.in->feature) == "cap0");
  BOOST_TEST(to_string(ax.out->feature) == "cap1");
  const auto ray = robust_line_cylinder(Ray<double>{{0, 0, 0.5}, {1, 0, 0}}, cyl);
  BOOST_TEST(to_string(ray.in->feature) == "origin");
  const auto ell = robust_line_cylinder(Line<double>{{-4, 0.5, 0.5}, {1, 0, 0}}, convert<double>(ellipse));
  BOOST_TEST(to_string(ell.answer) == "overlapping");
  BOOST_TEST(std::fabs(ell.in->t - (4 - std::sqrt(3.0))) < 1e-15);

  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> u(-2, 2);
  long answers_differ = 0, ulps_max = 0;
  for (int i = 0; i < 2000; ++i) {
    const Cylinder<double> c{{u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}, 0.5 + std::fabs(u(rng))};
    const Line<double> l{{u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}};
    const auto cert = certified_line_cylinder(l, c);
    const auto rob = robust_line_cylinder(l, c);
    if (cert.answer != rob.answer) {
      ++answers_differ;
      continue;
    }
    if (cert.in) {
      const double diff = std::fabs(rob.in->t - cert.in->nearest) / std::fabs(std::nextafter(cert.in->nearest, INFINITY) - cert.in->nearest);
      ulps_max = std::max(ulps_max, static_cast<long>(diff));
    }
  }
  std::cout << "robust_double vs certified, 2000 random lines: answers differ " << answers_differ
            << ", max endpoint error " << ulps_max << " ulp\n";
  BOOST_TEST(answers_differ <= 20);
}
