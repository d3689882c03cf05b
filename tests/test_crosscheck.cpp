// The cross-check on a 10,000-case subset per query (2,000 cylinder pairs) (the full run is experiments/crosscheck):
// random and degenerate cases, every certified answer re-checked exactly by fuzz/recheck.hpp
// and compared across swapped, reversed, flipped, translated, scaled and permuted inputs.
// Also checks that the re-check itself rejects wrong answers.
#define BOOST_TEST_MODULE crosscheck
#include <boost/test/unit_test.hpp>

#include "../fuzz/crosscheck_cases.hpp"

using namespace certcyl;
using crosscheck::Stats;
using Q = Rational;
using V = Vec3<Q>;

namespace {

constexpr std::uint64_t kCases = 10000;
// Cylinder pairs cost about 8 ms per case with its six variants (the touching constructions
// go through the exact stages), so the test runs 2,000 of them; experiments/crosscheck runs more.
constexpr std::uint64_t kCylinderPairCases = 2000;

void report(const std::string& query, const Stats& s, std::uint64_t cases = kCases) {
  crosscheck::print(std::cout, query, s);
  BOOST_TEST(s.cases == cases);
  BOOST_TEST(s.wrong == 0u);
  BOOST_TEST(s.crashes == 0u);
  // The mix reaches every answer.
  BOOST_TEST(s.by_answer[0] > cases / 20);
  BOOST_TEST(s.by_answer[1] > cases / 20);
  BOOST_TEST(s.by_answer[2] > cases / 20);
}

}  // namespace

BOOST_AUTO_TEST_CASE(lines) {
  Stats s;
  crosscheck::check_lines(kCases, 1, s);
  report("line/ray/segment", s);
}

BOOST_AUTO_TEST_CASE(triangles) {
  Stats s;
  crosscheck::check_triangles(kCases, 2, s);
  report("triangle", s);
}

BOOST_AUTO_TEST_CASE(cylinder_pairs) {
  Stats s;
  crosscheck::check_cylinder_pairs(kCylinderPairCases, 3, s);
  report("cylinder pair", s, kCylinderPairCases);
  BOOST_TEST(s.undecided == 0u);
}

// The re-check can fail: wrong answers, endpoints and certificates built by hand are rejected.
BOOST_AUTO_TEST_CASE(recheck_rejects_wrong_answers) {
  // Line x = 3/5... : the line {(t, 0, 1)} crosses the cylinder axis z in [0, 2], radius 1: t in [-1, 1].
  const Cylinder<Q> C{{0, 0, 0}, {0, 0, 2}, Q(1)};
  const V O{0, 0, 1}, d{1, 0, 0};
  CertifiedLineResult r = certified_line_cylinder(Line<Q>{O, d}, C);
  BOOST_TEST(recheck::check_line(O, d, LineRange::line, C, r) == "");
  CertifiedLineResult bad = r;
  bad.out = CertifiedEndpoint(detail::QuadraticNumber{Q(2), 0, 0}, 2.0, r.out->feature, r.out->surface);  // exit at t = 2 instead of 1
  BOOST_TEST(recheck::check_line(O, d, LineRange::line, C, bad) != "");
  bad = r;
  bad.answer = Answer::touching;
  BOOST_TEST(recheck::check_line(O, d, LineRange::line, C, bad) != "");
  bad = r;
  bad.in->surface = LineFeature::cap0;
  BOOST_TEST(recheck::check_line(O, d, LineRange::line, C, bad) != "");
  // Tangent line y = 1 at z = 1: touching at t = 0; as a ray from x = 1/1024 it misses.
  const V Ot{0, 1, 1};
  BOOST_TEST(recheck::check_line(Ot, d, LineRange::line, C, certified_line_cylinder(Line<Q>{Ot, d}, C)) == "");
  const V Or{Q(1, 1024), 1, 1};
  CertifiedLineResult touch = certified_line_cylinder(Line<Q>{Ot, d}, C);
  BOOST_TEST(recheck::check_line(Or, d, LineRange::ray, C, touch) != "");

  // Triangle: a separated answer whose plane certificate is not separating.
  const Triangle<Q> T{{V{2, 0, 1}, V{3, 1, 1}, V{3, -1, 1}}};
  TriangleCylinderResult tr = certified_triangle_cylinder(T, C);
  BOOST_TEST(to_string(tr.answer) == "separated");
  BOOST_TEST(recheck::check_triangle(T, C, tr) == "");
  TriangleCylinderResult tbad = tr;
  tbad.separation = TriangleCylinderResult::Separation::outside_tube;
  tbad.normal = V{0, 1, 0};
  BOOST_TEST(recheck::check_triangle(T, C, tbad) != "");
  tbad.answer = Answer::overlapping;
  tbad.witness = V{2, 0, 1};
  BOOST_TEST(recheck::check_triangle(T, C, tbad) != "");
  // Moved to x = 1 the vertex touches the wall: a touching certificate with the plane x = 1.
  const Triangle<Q> Tt{{V{1, 0, 1}, V{3, 1, 1}, V{3, -1, 1}}};
  const TriangleCylinderResult tt = certified_triangle_cylinder(Tt, C);
  BOOST_TEST(to_string(tt.answer) == "touching");
  BOOST_TEST(recheck::check_triangle(Tt, C, tt) == "");
  BOOST_TEST(recheck::check_triangle(T, C, tt) != "");  // the witness is not in T

  // Cylinder pair: axes z and y at distance 3 (radii 1): separated by D = (1, 0, 0); the
  // direction (0, 0, 1) does not separate; at distance 2 they touch with D = (1, 0, 0).
  const Cylinder<Q> b{{3, -1, 1}, {3, 1, 1}, Q(1)};
  CylinderCylinderResult cr = certified_cylinder_cylinder(C, b);
  BOOST_TEST(to_string(cr.answer) == "separated");
  BOOST_TEST(recheck::check_cylinder_pair(C, b, cr) == "");
  BOOST_TEST(recheck::separation_margin(C, b, V{1, 0, 0}) == CGAL::POSITIVE);
  BOOST_TEST(recheck::separation_margin(C, b, V{0, 0, 1}) == CGAL::NEGATIVE);
  cr.direction = V{0, 0, 1};
  BOOST_TEST(recheck::check_cylinder_pair(C, b, cr) != "");
  const Cylinder<Q> bt{{2, -1, 1}, {2, 1, 1}, Q(1)};
  const CylinderCylinderResult ct = certified_cylinder_cylinder(C, bt);
  BOOST_TEST(to_string(ct.answer) == "touching");
  BOOST_TEST(recheck::check_cylinder_pair(C, bt, ct) == "");
  BOOST_TEST(recheck::separation_margin(C, bt, V{1, 0, 0}) == CGAL::ZERO);
  BOOST_TEST(recheck::check_cylinder_pair(C, b, ct) != "");  // the contact point is not on b

  // The gap enclosure of (C, b), around phi* = 2/3, checked against b moved to x = 30: the
  // direction still separates, but phi(D) / |D.Delta| = 1/15 there, below phi_lower.
  const Cylinder<Q> b_far{{30, -1, 1}, {30, 1, 1}, Q(1)};
  const CylinderCylinderResult cs = certified_cylinder_cylinder(C, b);
  BOOST_TEST(recheck::check_cylinder_certificate(C, b_far, cs) == "");
  BOOST_TEST(recheck::check_cylinder_pair(C, b_far, cs) == "phi_lower above the certificate direction's ratio");
  // An overlapping pair (axis of b at x = 1, phi* = 2) against both cylinders grown 4 times
  // about their midpoints: the witness stays inside both, at a quarter of its scale, and
  // phi_upper no longer reaches 1 / sigma of it.
  const Cylinder<Q> bo{{1, -1, 1}, {1, 1, 1}, Q(1)};
  const CylinderCylinderResult co = certified_cylinder_cylinder(C, bo);
  BOOST_TEST(to_string(co.answer) == "overlapping");
  BOOST_TEST(recheck::check_cylinder_pair(C, bo, co) == "");
  const Cylinder<Q> C4{{0, 0, -3}, {0, 0, 5}, Q(4)}, bo4{{1, -4, 1}, {1, 4, 1}, Q(4)};
  BOOST_TEST(recheck::check_cylinder_certificate(C4, bo4, co) == "");
  BOOST_TEST(recheck::check_cylinder_pair(C4, bo4, co) == "phi_upper below 1 / sigma of the certificate point");
}

// Regression (found by the cross-check): the interval stage of the cylinder-pair separation
// check called CGAL::magnitude(Interval_nt) through ADL (a double, max |x|) instead of an
// enclosure of |x|, and accepted this direction although phi(D) - |D.Delta| = +4.3e-15.
BOOST_AUTO_TEST_CASE(regression_interval_magnitude) {
  const Cylinder<Q> a{{-170, 465, -646}, {Q(-1194, 7), Q(3249, 7), Q(-4510, 7)}, Q(1)};
  const Cylinder<Q> b{{Q("-53655885960492089361/315251973915934720"), Q("73193627043932143619/157625986957967360"),
                       Q("-20247058024750907389/31525197391593472")},
                      {Q("-54466533893418778641/315251973915934720"), Q("73452584022505947139/157625986957967360"),
                       Q("-20303353020093038589/31525197391593472")},
                      Q(1)};
  const V D{Q(-7291542253838013, 72057594037927936), Q(2573485501354753, 72057594037927936),
            Q(3216856876693191, 18014398509481984)};
  BOOST_TEST(recheck::separation_margin(a, b, D) == CGAL::NEGATIVE);
  const CylinderCylinderResult r = certified_cylinder_cylinder(a, b);
  BOOST_TEST(recheck::check_cylinder_pair(a, b, r) == "");
  BOOST_TEST(recheck::check_cylinder_pair(b, a, certified_cylinder_cylinder(b, a)) == "");
}
