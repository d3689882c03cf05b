// Certified line/ray/segment against cylinder: named cases with the truth derived by hand,
// the hard-case families of design note section 6 at the degeneracy and one ulp either side,
// and invariance under reversal, integer translation and power-of-two scaling.
#define BOOST_TEST_MODULE line_certified
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <string>

#include "certcyl/certified/line_cylinder.hpp"

using namespace certcyl;
using Q = Rational;

namespace {

Q q(const char* s) { return parse_rational(s); }

// The unit cylinder: radius 1 around the z axis, z in [0, 1].
const Cylinder<Q> unit{{0, 0, 0}, {0, 0, 1}, 1};
// x^2/4 + y^2 <= 1, 0 <= z <= 1, and its sheared copy with c = (1, 0, 1).
const EllipticCylinder<Q> ellipse{{0, 0, 0}, {2, 0, 0}, {0, 1, 0}, {0, 0, 1}};
const EllipticCylinder<Q> oblique{{0, 0, 0}, {2, 0, 0}, {0, 1, 0}, {1, 0, 1}};

struct Expect {
  Answer answer;
  std::string in, out;  // exact text
  LineFeature in_feature, out_feature;
};

void check(const CertifiedLineResult& r, const Expect& e) {
  BOOST_TEST(to_string(r.answer) == to_string(e.answer));
  if (e.answer == Answer::separated) {
    BOOST_TEST(!r.in.has_value());
    return;
  }
  BOOST_REQUIRE(r.in.has_value());
  BOOST_REQUIRE(r.out.has_value());
  BOOST_TEST(r.in->exact() == e.in);
  BOOST_TEST(r.out->exact() == e.out);
  BOOST_TEST(to_string(r.in->feature) == to_string(e.in_feature));
  BOOST_TEST(to_string(r.out->feature) == to_string(e.out_feature));
  BOOST_TEST(r.counter.calls == 1u);
}

}  // namespace

// ---- circular, lines -------------------------------------------------------------------------

//   y
//   |   .-.
//   |  (   )      the line y = 0, z = 1/2 through the axis: wall to wall, t in [1, 3]
// --o--------x->
BOOST_AUTO_TEST_CASE(line_through_axis) {
  check(certified_line_cylinder(Line<Q>{{-2, 0, q("1/2")}, {1, 0, 0}}, unit),
        {Answer::overlapping, "1", "3", LineFeature::wall, LineFeature::wall});
}

// y = 1/2: x = +-sqrt(3)/2, t = 2 -+ sqrt(3)/2.
BOOST_AUTO_TEST_CASE(line_irrational_endpoints) {
  const auto r = certified_line_cylinder(Line<Q>{{-2, q("1/2"), q("1/2")}, {1, 0, 0}}, unit);
  check(r, {Answer::overlapping, "2 - 1/2*sqrt(3)", "2 + 1/2*sqrt(3)", LineFeature::wall, LineFeature::wall});
  // 2 -+ sqrt(3)/2 = 1.1339745962155614..., 2.8660254037844386...; hexfloat of the nearest doubles.
  BOOST_TEST(r.in->nearest == 0x1.224c28bd3d9abp+0);
  BOOST_TEST(r.out->nearest == 0x1.6ed9eba16132bp+1);
}

// Tangent at (0, 1, 1/2): a point, touching; one ulp of y either side.
BOOST_AUTO_TEST_CASE(tangent_line_and_one_ulp_either_side) {
  check(certified_line_cylinder(Line<Q>{{-2, 1, q("1/2")}, {1, 0, 0}}, unit),
        {Answer::touching, "2", "2", LineFeature::wall, LineFeature::wall});
  const double above = std::nextafter(1.0, 2.0), below = std::nextafter(1.0, 0.0);
  check(certified_line_cylinder(Line<Q>{{-2, Q(above), q("1/2")}, {1, 0, 0}}, unit), {Answer::separated, "", "", {}, {}});
  const auto r = certified_line_cylinder(Line<Q>{{-2, Q(below), q("1/2")}, {1, 0, 0}}, unit);
  BOOST_TEST(to_string(r.answer) == "overlapping");
  // x^2 = 1 - (1 - 2^-53)^2 = 2^-52 - 2^-106: t = 2 -+ sqrt(2^-52 - 2^-106), about 2 -+ 2^-26.
  BOOST_TEST(r.in->nearest < 2.0);
  BOOST_TEST(r.out->nearest > 2.0);
  BOOST_TEST(std::fabs(r.out->nearest - 2.0 - 0x1p-26) < 0x1p-70);
  // The same in double input: disc = 0 exactly, which no error bound decides, so its sign is
  // taken exactly (Mpzf) and the endpoints are the exact tangent point.
  const auto rd = certified_line_cylinder(Line<double>{{-2, 1, 0.5}, {1, 0, 0}}, Cylinder<double>{{0, 0, 0}, {0, 0, 1}, 1});
  BOOST_TEST(to_string(rd.answer) == "touching");
  BOOST_TEST(rd.in->exact() == "2");
  BOOST_TEST(to_string(rd.stage) == "exact");
  BOOST_TEST(rd.counter.exact == 1u);
  // Radius and offset the binary64 0.1: the same tangency with inexact squares.
  const auto rt = certified_line_cylinder(Line<double>{{-2, 0.1, 0.5}, {1, 0, 0}}, Cylinder<double>{{0, 0, 0}, {0, 0, 1}, 0.1});
  BOOST_TEST(to_string(rt.answer) == "touching");
  BOOST_TEST(rt.in->exact() == "2");
  BOOST_TEST(rt.counter.exact == 1u);
  // One ulp of 0.1 either side of that tangency (the side by construction): no exact zero,
  // so the double-double escalation decides, without exact arithmetic.
  for (const double y : {std::nextafter(0.1, 1.0), std::nextafter(0.1, 0.0)}) {
    // Not parallel to the caps (d.A = 0 would be an exact zero): z = 0.25 + t / 8, 0.5 at x = 0.
    const auto ru = certified_line_cylinder(Line<double>{{-2, y, 0.25}, {1, 0, 0.125}}, Cylinder<double>{{0, 0, 0}, {0, 0, 1}, 0.1});
    BOOST_TEST(to_string(ru.answer) == (y > 0.1 ? "separated" : "overlapping"));
    BOOST_TEST(to_string(ru.stage) == "double_double");
    BOOST_TEST(ru.counter.exact == 0u);
  }
}

// Along the axis: cap0 at t = 1, cap1 at t = 2.
BOOST_AUTO_TEST_CASE(line_along_axis) {
  check(certified_line_cylinder(Line<Q>{{0, 0, -1}, {0, 0, 1}}, unit),
        {Answer::overlapping, "1", "2", LineFeature::cap0, LineFeature::cap1});
  // Reversed and with a longer direction: t in [-5/4, -3/4] ... cap1 first.
  check(certified_line_cylinder(Line<Q>{{0, 0, q("-3/2")}, {0, 0, -2}}, unit),
        {Answer::overlapping, "-5/4", "-3/4", LineFeature::cap1, LineFeature::cap0});
}

// x = 1 on the wall, parallel to the axis: touching along [-5/2, -2], rim to rim.
BOOST_AUTO_TEST_CASE(line_on_the_wall) {
  check(certified_line_cylinder(Line<Q>{{1, 0, 5}, {0, 0, 2}}, unit),
        {Answer::touching, "-5/2", "-2", LineFeature::rim0, LineFeature::rim1});
  // (3/5, 4/5) is on the unit circle too.
  check(certified_line_cylinder(Line<Q>{{q("3/5"), q("4/5"), 0}, {0, 0, 1}}, unit),
        {Answer::touching, "0", "1", LineFeature::rim0, LineFeature::rim1});
  // One ulp outside and inside the wall.
  check(certified_line_cylinder(Line<Q>{{Q(std::nextafter(1.0, 2.0)), 0, 0}, {0, 0, 1}}, unit),
        {Answer::separated, "", "", {}, {}});
  check(certified_line_cylinder(Line<Q>{{Q(std::nextafter(1.0, 0.0)), 0, 0}, {0, 0, 1}}, unit),
        {Answer::overlapping, "0", "1", LineFeature::cap0, LineFeature::cap1});
}

// In the plane z = 0 of cap0 (and z = 1 of cap1): a chord of the rim, touching.
BOOST_AUTO_TEST_CASE(chord_in_a_cap_plane) {
  check(certified_line_cylinder(Line<Q>{{-2, 0, 0}, {1, 0, 0}}, unit),
        {Answer::touching, "1", "3", LineFeature::rim0, LineFeature::rim0});
  check(certified_line_cylinder(Line<Q>{{-2, 0, 1}, {1, 0, 0}}, unit),
        {Answer::touching, "1", "3", LineFeature::rim1, LineFeature::rim1});
  // Tangent to the rim circle in the cap plane: one point.
  check(certified_line_cylinder(Line<Q>{{-2, 1, 0}, {1, 0, 0}}, unit),
        {Answer::touching, "2", "2", LineFeature::rim0, LineFeature::rim0});
  // One ulp of z above cap1 / inside below it.
  check(certified_line_cylinder(Line<Q>{{-2, 0, Q(std::nextafter(1.0, 2.0))}, {1, 0, 0}}, unit),
        {Answer::separated, "", "", {}, {}});
  check(certified_line_cylinder(Line<Q>{{-2, 0, Q(std::nextafter(1.0, 0.0))}, {1, 0, 0}}, unit),
        {Answer::overlapping, "1", "3", LineFeature::wall, LineFeature::wall});
}

//   z
//   1 +----*        the line (t, 0, 2 - t) meets the solid only at the rim point (1, 0, 1)
//     |    |\       .
//   0 +----+ \      .
BOOST_AUTO_TEST_CASE(graze_of_a_rim) {
  check(certified_line_cylinder(Line<Q>{{0, 0, 2}, {1, 0, -1}}, unit),
        {Answer::touching, "1", "1", LineFeature::rim1, LineFeature::rim1});
  // Shifted down by one ulp of 2 the line cuts the corner: a short chord cap1 -> wall.
  const auto r = certified_line_cylinder(Line<Q>{{0, 0, Q(std::nextafter(2.0, 0.0))}, {1, 0, -1}}, unit);
  BOOST_TEST(to_string(r.answer) == "overlapping");
  BOOST_TEST(to_string(r.in->feature) == "cap1");
  BOOST_TEST(to_string(r.out->feature) == "wall");
  // Shifted up: separated.
  check(certified_line_cylinder(Line<Q>{{0, 0, Q(std::nextafter(2.0, 4.0))}, {1, 0, -1}}, unit),
        {Answer::separated, "", "", {}, {}});
}

// Through both rims: (−1, 0, 0) and (1, 0, 1): in at rim0, out at rim1, overlapping.
BOOST_AUTO_TEST_CASE(line_through_two_rims) {
  check(certified_line_cylinder(Line<Q>{{-1, 0, 0}, {2, 0, 1}}, unit),
        {Answer::overlapping, "0", "1", LineFeature::rim0, LineFeature::rim1});
}

// ---- circular, rays and segments ---------------------------------------------------------------

BOOST_AUTO_TEST_CASE(rays) {
  // From inside: clipped at the origin.
  const auto r = certified_line_cylinder(Ray<Q>{{0, 0, q("1/2")}, {1, 0, 0}}, unit);
  check(r, {Answer::overlapping, "0", "1", LineFeature::origin, LineFeature::wall});
  BOOST_TEST(to_string(r.in->surface) == "none");
  // From the wall outward: the single point t = 0, on the wall.
  const auto w = certified_line_cylinder(Ray<Q>{{1, 0, q("1/2")}, {1, 0, 0}}, unit);
  check(w, {Answer::touching, "0", "0", LineFeature::origin, LineFeature::origin});
  BOOST_TEST(to_string(w.in->surface) == "wall");
  // From the wall inward: the whole chord, the origin on the wall.
  const auto i = certified_line_cylinder(Ray<Q>{{1, 0, q("1/2")}, {-1, 0, 0}}, unit);
  check(i, {Answer::overlapping, "0", "2", LineFeature::origin, LineFeature::wall});
  BOOST_TEST(to_string(i.in->surface) == "wall");
  // Pointing away.
  check(certified_line_cylinder(Ray<Q>{{2, 0, q("1/2")}, {1, 0, 0}}, unit), {Answer::separated, "", "", {}, {}});
  // From the rim1 point, grazing outward: touching at the origin, surface rim1.
  const auto g = certified_line_cylinder(Ray<Q>{{1, 0, 1}, {1, 0, -1}}, unit);
  check(g, {Answer::touching, "0", "0", LineFeature::origin, LineFeature::origin});
  BOOST_TEST(to_string(g.in->surface) == "rim1");
  // In the cap0 plane from the centre: touching along [0, 1].
  check(certified_line_cylinder(Ray<Q>{{0, 0, 0}, {1, 0, 0}}, unit),
        {Answer::touching, "0", "1", LineFeature::origin, LineFeature::rim0});
}

BOOST_AUTO_TEST_CASE(segments) {
  // Ends on the wall from outside: touching at t = 1.
  const auto e = certified_line_cylinder(Segment<Q>{{3, 0, q("1/2")}, {1, 0, q("1/2")}}, unit);
  check(e, {Answer::touching, "1", "1", LineFeature::end, LineFeature::end});
  BOOST_TEST(to_string(e.in->surface) == "wall");
  // Inside: both ends clipped.
  const auto i = certified_line_cylinder(Segment<Q>{{0, 0, q("1/4")}, {q("1/2"), 0, q("1/2")}}, unit);
  check(i, {Answer::overlapping, "0", "1", LineFeature::origin, LineFeature::end});
  BOOST_TEST(to_string(i.out->surface) == "none");
  // Crossing: from (-2, 0, 1/2) to (0, 0, 1/2): wall at t = 1/2, end inside.
  check(certified_line_cylinder(Segment<Q>{{-2, 0, q("1/2")}, {0, 0, q("1/2")}}, unit),
        {Answer::overlapping, "1/2", "1", LineFeature::wall, LineFeature::end});
  // Stops one ulp short of the wall: separated; reaches one ulp in: overlapping.
  check(certified_line_cylinder(Segment<Q>{{-2, 0, q("1/2")}, {Q(std::nextafter(-1.0, -2.0)), 0, q("1/2")}}, unit),
        {Answer::separated, "", "", {}, {}});
  const auto in = certified_line_cylinder(Segment<Q>{{-2, 0, q("1/2")}, {Q(std::nextafter(-1.0, 0.0)), 0, q("1/2")}}, unit);
  BOOST_TEST(to_string(in.answer) == "overlapping");
  BOOST_TEST(to_string(in.out->feature) == "end");
  // Lying on the wall, inside the slab: touching, both ends clipped, on the wall.
  const auto w = certified_line_cylinder(Segment<Q>{{0, 1, q("1/4")}, {0, 1, q("3/4")}}, unit);
  check(w, {Answer::touching, "0", "1", LineFeature::origin, LineFeature::end});
  BOOST_TEST(to_string(w.in->surface) == "wall");
}

// ---- elliptic ----------------------------------------------------------------------------------

BOOST_AUTO_TEST_CASE(elliptic_cases) {
  // x^2/4 + y^2 = 1 on y = 0: x = +-2, t in [2, 6].
  check(certified_line_cylinder(Line<Q>{{-4, 0, q("1/2")}, {1, 0, 0}}, ellipse),
        {Answer::overlapping, "2", "6", LineFeature::wall, LineFeature::wall});
  // Tangent at (0, 1): touching.
  check(certified_line_cylinder(Line<Q>{{-4, 1, q("1/2")}, {1, 0, 0}}, ellipse),
        {Answer::touching, "4", "4", LineFeature::wall, LineFeature::wall});
  // y = 1/2: x^2 = 3, t = 4 -+ sqrt(3).
  check(certified_line_cylinder(Line<Q>{{-4, q("1/2"), q("1/2")}, {1, 0, 0}}, ellipse),
        {Answer::overlapping, "4 - sqrt(3)", "4 + sqrt(3)", LineFeature::wall, LineFeature::wall});
  // Oblique: along c from below the base, unit-space x = 1/2: cap0 at t = 1, cap1 at t = 2.
  check(certified_line_cylinder(Line<Q>{{0, 0, -1}, {1, 0, 1}}, oblique),
        {Answer::overlapping, "1", "2", LineFeature::cap0, LineFeature::cap1});
  // Oblique: graze of rim1 at C + a + c = (3, 0, 1), unit direction (1, 0, -1) = world a - c.
  check(certified_line_cylinder(Line<Q>{{2, 0, 2}, {1, 0, -1}}, oblique),
        {Answer::touching, "1", "1", LineFeature::rim1, LineFeature::rim1});
  // Oblique: on the wall, along c through C + b = (0, 1, 0).
  check(certified_line_cylinder(Line<Q>{{0, 1, 0}, {1, 0, 1}}, oblique),
        {Answer::touching, "0", "1", LineFeature::rim0, LineFeature::rim1});
  // Oblique: the chord y = 0 in the cap1 plane z = 1 spans world x in [-1, 3].
  check(certified_line_cylinder(Ray<Q>{{-3, 0, 1}, {2, 0, 0}}, oblique),
        {Answer::touching, "1", "3", LineFeature::rim1, LineFeature::rim1});
  // Segment stopping inside the oblique cylinder.
  check(certified_line_cylinder(Segment<Q>{{-3, 0, q("1/2")}, {q("1/2"), 0, q("1/2")}}, oblique),
        {Answer::overlapping, "3/7", "1", LineFeature::wall, LineFeature::end});
}

// ---- invariance ------------------------------------------------------------------------------

namespace {
// A tilted cylinder (axis (2, 3, 6), length 7) and lines about it,
// all with rational coordinates.
Cylinder<Q> tilted() { return {{q("1/3"), -2, 5}, {q("7/3"), 1, 11}, q("3/2")}; }
}  // namespace

BOOST_AUTO_TEST_CASE(reversal_translation_scaling) {
  const Cylinder<Q> cyl = tilted();
  const Line<Q> lines[] = {{{-3, 1, 4}, {1, q("1/5"), 2}}, {{q("1/3"), q("-1/2"), 5}, {2, 3, 6}}, {{-5, -5, 9}, {1, 1, 0}}};
  for (const auto& line : lines) {
    const auto r = certified_line_cylinder(line, cyl);
    // Reversal: t -> -t, in and out swap.
    const auto rev = certified_line_cylinder(Line<Q>{line.origin, -line.direction}, cyl);
    BOOST_TEST(to_string(rev.answer) == to_string(r.answer));
    if (r.in) {
      BOOST_TEST(detail::compare_with(rev.in->value(), 0) == CGAL::opposite(detail::compare_with(r.out->value(), 0)));
      BOOST_TEST(rev.in->nearest == -r.out->nearest);
      BOOST_TEST(rev.out->nearest == -r.in->nearest);
      BOOST_TEST(to_string(rev.in->feature) == to_string(r.out->feature));
    }
    // Integer translation of everything: the same exact interval.
    const Vec3<Q> shift{1000, -77, 1 << 20};
    const auto tr = certified_line_cylinder(Line<Q>{line.origin + shift, line.direction},
                                            Cylinder<Q>{cyl.p0 + shift, cyl.p1 + shift, cyl.radius});
    BOOST_TEST(to_string(tr.answer) == to_string(r.answer));
    if (r.in) {
      BOOST_TEST(tr.in->exact() == r.in->exact());
      BOOST_TEST(tr.out->exact() == r.out->exact());
    }
    // Power-of-two scaling of everything: the same t; of the direction alone: t / 2^k.
    const Q s = q("0x1p-40");
    const auto sc = certified_line_cylinder(Line<Q>{s * line.origin, s * line.direction},
                                            Cylinder<Q>{s * cyl.p0, s * cyl.p1, s * cyl.radius});
    const auto sd = certified_line_cylinder(Line<Q>{line.origin, Q(8) * line.direction}, cyl);
    BOOST_TEST(to_string(sc.answer) == to_string(r.answer));
    if (r.in) {
      BOOST_TEST(sc.in->exact() == r.in->exact());
      BOOST_TEST(sd.in->nearest == r.in->nearest / 8);
      BOOST_TEST(sd.out->nearest == r.out->nearest / 8);
    }
  }
}
