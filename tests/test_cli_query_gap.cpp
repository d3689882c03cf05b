// `certcyl query`'s "gap", the certified signed gap, for every query kind: hand-derived values
// of the depth margin G = max over the set of min(1 - q, s, 1 - s) (src/study/gap.hpp) worked
// out in comments, irrational ones checked exactly against their closed form, and, over the study's tiny
// cases of every query, the gap's sign against the certified answer and the gap of `certcyl
// cases` on the same line; every gap named by its quantity (depth_margin, or log_phi for pairs).
#define BOOST_TEST_MODULE cli_query_gap
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <sstream>

#include "cases.hpp"
#include "certcyl/rational.hpp"
#include "query.hpp"
#include "study/instance.hpp"

using namespace certcyl;
using namespace certcyl::cli;

namespace {

std::vector<json> run(const std::string& input, const std::string& method = "certified") {
  QueryOptions o;
  o.method = method;
  std::istringstream in(input);
  std::ostringstream out;
  BOOST_TEST_REQUIRE(run_query(in, out, o, 1) == 0);
  std::vector<json> lines;
  std::istringstream produced(out.str());
  for (std::string line; std::getline(produced, line);) lines.push_back(json::parse(line));
  return lines;
}

json answer_of(const std::string& line, const std::string& method = "certified") {
  const std::vector<json> r = run(line + "\n", method);
  BOOST_TEST_REQUIRE(r.size() == 1u);
  BOOST_TEST_REQUIRE(!r[0].contains("error"), r[0].dump());
  return r[0];
}

// The radius-1 cylinder from (0,0,0) to (0,0,1): s(X) = z, q(X) = x^2 + y^2.
const std::string unit = R"("cylinder": {"p0": [0,0,0], "p1": [0,0,1], "radius": 1})";
// The elliptic cylinder base 0, a = (2,0,0), b = (0,1,0), c = (0,0,1): unit coordinates
// (x/2, y, z), so s = z and q = x^2/4 + y^2.
const std::string ellipse = R"("elliptic_cylinder": {"base": [0,0,0], "a": [2,0,0], "b": [0,1,0], "c": [0,0,1]})";

std::string line_query(const std::string& query, const std::string& operand, const std::string& solid) {
  return R"({"query": ")" + query + R"(", )" + operand + ", " + solid + "}";
}

// Every certified answer but a cylinder pair's names its gap the depth margin.
void check_depth_margin(const json& a) { BOOST_TEST(a["gap_quantity"] == "depth_margin", a.dump()); }

// Asserts that the answer's gap is [v, v] (v a double) and its answer the one given.
void check_exact_gap(const json& a, double v, const std::string& answer) {
  check_depth_margin(a);
  BOOST_TEST(a["answer"] == answer, a.dump());
  BOOST_TEST_REQUIRE(a["gap"].is_array(), a.dump());
  BOOST_TEST(a["gap"][0].get<double>() == v, a.dump());
  BOOST_TEST(a["gap"][1].get<double>() == v, a.dump());
}

// Asserts that the gap encloses the rational num/den (not a double) between adjacent doubles.
void check_enclosed_gap(const json& a, int num, int den, const std::string& answer) {
  check_depth_margin(a);
  BOOST_TEST(a["answer"] == answer, a.dump());
  BOOST_TEST_REQUIRE(a["gap"].is_array(), a.dump());
  const double lo = a["gap"][0].get<double>(), hi = a["gap"][1].get<double>();
  const Rational exact(num, den);
  BOOST_TEST((Rational(lo) < exact && exact < Rational(hi)), a.dump());
  BOOST_TEST(hi == std::nextafter(lo, 2.0), a.dump());
}

// Asserts that the gap encloses (p + sqrt(n)) / den (irrational), checked exactly, between
// adjacent doubles.
void check_root_gap(const json& a, int p, int n, int den, const std::string& answer) {
  check_depth_margin(a);
  BOOST_TEST(a["answer"] == answer, a.dump());
  BOOST_TEST_REQUIRE(a["gap"].is_array(), a.dump());
  const double lo = a["gap"][0].get<double>(), hi = a["gap"][1].get<double>();
  const Rational x = Rational(lo) * den - p, y = Rational(hi) * den - p;
  BOOST_TEST((x <= 0 || x * x < Rational(n)), a.dump());
  BOOST_TEST((y >= 0 && Rational(n) < y * y), a.dump());
  BOOST_TEST(hi == std::nextafter(lo, 2.0), a.dump());
}

}  // namespace

BOOST_AUTO_TEST_CASE(lines_worked_out_by_hand) {
  // gap = max over t of d(t) = min(1 - q(t), s(t), 1 - s(t)) along X = origin + t direction.
  // Through (0,0,1/2) along x: s = 1/2, q = t^2: d = min(1 - t^2, 1/2), largest at t = 0: 1/2.
  check_exact_gap(answer_of(line_query("line_cylinder", R"("line": {"origin": [0,0,0.5], "direction": [1,0,0]})", unit)),
                  0.5, "overlapping");
  // Through (2,0,1/2) along y, 2 from the axis: q = 4 + t^2: d = min(-3 - t^2, 1/2): -3 at t = 0.
  check_exact_gap(answer_of(line_query("line_cylinder", R"("line": {"origin": [2,0,0.5], "direction": [0,1,0]})", unit)),
                  -3.0, "separated");
  // Tangent: through (1,0,1/2) along y, q = 1 + t^2: d = min(-t^2, 1/2), 0 at t = 0.
  check_exact_gap(answer_of(line_query("line_cylinder", R"("line": {"origin": [1,0,0.5], "direction": [0,1,0]})", unit)),
                  0.0, "touching");
  // Parallel to the axis at x = 1/2: q = 1/4, s = t: d = min(3/4, t, 1 - t), at most
  // min(s, 1 - s) <= 1/2, which t = 1/2 attains. gap = 1/2.
  check_exact_gap(answer_of(line_query("line_cylinder", R"("line": {"origin": [0.5,0,0], "direction": [0,0,1]})", unit)),
                  0.5, "overlapping");
  // A third of the height: through (0,0,"1/3") along x, s = 1/3: d = min(1 - t^2, 1/3, 2/3),
  // 1/3 at t = 0, not a double: enclosed by adjacent doubles.
  check_enclosed_gap(answer_of(line_query("line_cylinder", R"("line": {"origin": [0,0,"1/3"], "direction": [1,0,0]})", unit)),
                     1, 3, "overlapping");
}

BOOST_AUTO_TEST_CASE(rays_and_segments_are_clipped_to_their_range) {
  // The ray from (2,0,1/2) along +x: t >= 0, q = (2 + t)^2 >= 4 (its line through the axis
  // would have gap 1/2): d = min(1 - (2 + t)^2, 1/2), largest at t = 0: -3.
  check_exact_gap(answer_of(line_query("ray_cylinder", R"("ray": {"origin": [2,0,0.5], "direction": [1,0,0]})", unit)),
                  -3.0, "separated");
  // The ray up the axis from z = 3/4: s = 3/4 + t, t >= 0, q = 0: d = min(1, s, 1 - s) = 1 - s
  // (s >= 3/4), largest at t = 0: 1/4. Its line reaches s = 1/2: gap 1/2.
  check_exact_gap(answer_of(line_query("ray_cylinder", R"("ray": {"origin": [0,0,0.75], "direction": [0,0,1]})", unit)),
                  0.25, "overlapping");
  check_exact_gap(answer_of(line_query("line_cylinder", R"("line": {"origin": [0,0,0.75], "direction": [0,0,1]})", unit)),
                  0.5, "overlapping");
  // The segment on the axis from z = 1/4 to z = 1/2: s = 1/4 + t/4, t in [0, 1], q = 0:
  // d = min(s, 1 - s) = s, 1/2 at t = 1.
  check_exact_gap(answer_of(line_query("segment_cylinder", R"("segment": {"p0": [0,0,0.25], "p1": [0,0,0.5]})", unit)),
                  0.5, "overlapping");
  // The segment from z = 2 to z = 3 on the axis: d = min(1, s, 1 - s) = 1 - s, s in [2, 3]:
  // -1 at t = 0.
  check_exact_gap(answer_of(line_query("segment_cylinder", R"("segment": {"p0": [0,0,2], "p1": [0,0,3]})", unit)),
                  -1.0, "separated");
  // Segments along x at z = 1/2 (s = 1/2, d = min(1 - q, 1/2)). From (0,0,1/2) to (1,0,1/2):
  // q = t^2: gap 1/2 at t = 0. From (1,0,1/2) to (3,0,1/2): q = (1 + 2t)^2 >= 1, 1 at t = 0:
  // gap 0, touching at p0.
  check_exact_gap(answer_of(line_query("segment_cylinder", R"("segment": {"p0": [0,0,0.5], "p1": [1,0,0.5]})", unit)),
                  0.5, "overlapping");
  check_exact_gap(answer_of(line_query("segment_cylinder", R"("segment": {"p0": [1,0,0.5], "p1": [3,0,0.5]})", unit)),
                  0.0, "touching");
}

BOOST_AUTO_TEST_CASE(elliptic_lines_rays_and_segments) {
  // In unit coordinates (x/2, y, z). The line through (0,1,1/2) along x: q = t^2/4 + 1, s = 1/2:
  // d = min(-t^2/4, 1/2), 0 at t = 0, tangent.
  check_exact_gap(
      answer_of(line_query("line_elliptic_cylinder", R"("line": {"origin": [0,1,0.5], "direction": [1,0,0]})", ellipse)), 0.0,
      "touching");
  // The line through (1,0,1/2) along x: q = (1 + t)^2/4, s = 1/2: d = 1/2 at t = -1.
  check_exact_gap(
      answer_of(line_query("line_elliptic_cylinder", R"("line": {"origin": [1,0,0.5], "direction": [1,0,0]})", ellipse)), 0.5,
      "overlapping");
  // The segment from (3,0,1/2) to (5,0,1/2): q = (3/2 + t)^2, t in [0, 1], least 9/4 at t = 0:
  // d = min(1 - 9/4, 1/2) = -5/4 (its line's gap is 1/2).
  check_exact_gap(
      answer_of(line_query("segment_elliptic_cylinder", R"("segment": {"p0": [3,0,0.5], "p1": [5,0,0.5]})", ellipse)), -1.25,
      "separated");
  // The ray up the axis from z = 3/4, direction (0,0,2): s = 3/4 + 2t, t >= 0, q = 0:
  // d = 1 - s, 1/4 at t = 0.
  check_exact_gap(
      answer_of(line_query("ray_elliptic_cylinder", R"("ray": {"origin": [0,0,0.75], "direction": [0,0,2]})", ellipse)), 0.25,
      "overlapping");
}

BOOST_AUTO_TEST_CASE(triangles_worked_out_by_hand) {
  // gap = max over the triangle of d = min(1 - q, s, 1 - s).
  // Vertices v0 = (3/4,0,1/4), v1 = (3/4,1/2,3/4), v2 = (1,0,3/4): the points v0 + a (v1 - v0)
  // + b (v2 - v0) have x = 3/4 + b/4, y = a/2, s = 1/4 + (a + b)/2, so at equal s a point with
  // b > 0 has the larger x and the larger q than the point with b = 0 (y then larger by b/2, q
  // up by less: d/db of x^2 >= 3/8 > (a/2)(1/2) = d/db of y^2 along a + b = const while a <= 1):
  // the maximum lies on the edge b = 0, where 1 - q = 7/16 - a^2/4 falls and s = 1/4 + a/2 rises;
  // they meet at 4a^2 + 8a - 3 = 0, a = (sqrt(7) - 2)/2 (s ~ 0.41 < 1/2, so 1 - s is not active):
  // gap = s = (sqrt(7) - 1)/4, irrational.
  check_root_gap(answer_of(R"({"query": "triangle_cylinder", "triangle": [[0.75,0,0.25],[0.75,0.5,0.75],[1,0,0.75]], )" +
                           unit + "}"),
                 -1, 7, 4, "overlapping");
  // The same with x from 0.6 (vertices (0.6,0,0.2), (0.6,0.5,0.7), (0.8,0,0.7), read exactly):
  // on the edge b = 0 at a = 3/5, the point (3/5, 3/10, 1/2) has q = 9/25 + 9/100 = 9/20 and
  // s = 1/2: d = min(11/20, 1/2, 1/2) = 1/2, the largest any point can have. gap = 1/2.
  check_exact_gap(answer_of(R"({"query": "triangle_cylinder", "triangle": [["0.6",0,"0.2"],["0.6","0.5","0.7"],["0.8",0,"0.7"]], )" +
                            unit + "}"),
                  0.5, "overlapping");
  // Lifted to z in [2, 3]: d <= 1 - s <= -1, and d(0,0,2) = min(1, 2, -1) = -1. gap = -1.
  check_exact_gap(answer_of(R"({"query": "triangle_cylinder", "triangle": [[0,0,2],[1,0,3],[0,1,3]], )" + unit + "}"), -1.0,
                  "separated");
  // In the cap plane z = 1: 1 - s = 0 everywhere, and 1 - q > 0 at (0,0,1). gap = 0.
  check_exact_gap(
      answer_of(R"({"query": "triangle_cylinder", "triangle": [[-0.5,0,1],[0.5,0,1],[0,0.5,1]], )" + unit + "}"), 0.0,
      "touching");
}

BOOST_AUTO_TEST_CASE(points_worked_out_by_hand) {
  // gap = min(1 - q, s, 1 - s) at the point.
  auto point = [&](const std::string& p) { return answer_of(R"({"query": "point_cylinder", "point": )" + p + ", " + unit + "}"); };
  check_exact_gap(point("[0.5,0,0.25]"), 0.25, "overlapping");  // min(3/4, 1/4, 3/4)
  check_exact_gap(point("[3,4,0.5]"), -24.0, "separated");      // q = 25: min(-24, 1/2, 1/2)
  check_exact_gap(point("[0,0,1.5]"), -0.5, "separated");       // above the top: min(1, 3/2, -1/2)
  check_exact_gap(point(R"(["0.6","0.8",0.5])"), 0.0, "touching");  // q = 9/25 + 16/25 = 1
  check_enclosed_gap(point(R"([0,0,"0.1"])"), 1, 10, "overlapping");  // min(1, 1/10, 9/10)
  // Elliptic, unit coordinates (x/2, y, z): (1,0,1/2) has q = 1/4: min(3/4, 1/2, 1/2) = 1/2;
  // (2,0,1/2) is on the wall.
  auto elliptic = [&](const std::string& p) {
    return answer_of(R"({"query": "point_elliptic_cylinder", "point": )" + p + ", " + ellipse + "}");
  };
  check_exact_gap(elliptic("[1,0,0.5]"), 0.5, "overlapping");
  check_exact_gap(elliptic("[2,0,0.5]"), 0.0, "touching");
  check_exact_gap(elliptic("[0,0,-2]"), -2.0, "separated");  // min(1, -2, 3)
  // 10^200 radii from the axis: gap = 1 - 10^400, beyond the doubles: null, the answer stands.
  const json far = point("[1e200,0,0.5]");
  BOOST_TEST(far["answer"] == "separated");
  BOOST_TEST_REQUIRE(far.contains("gap"));
  BOOST_TEST(far["gap"].is_null());
  check_depth_margin(far);
}

BOOST_AUTO_TEST_CASE(gap_follows_the_common_fields_as_for_pairs) {
  // The member order of an answer: answer, certified, method, nt, gap, gap_quantity, then the
  // query's own.
  QueryOptions o;
  std::istringstream in(line_query("line_cylinder", R"("line": {"origin": [0,0,0.5], "direction": [1,0,0]})", unit) + "\n" +
                        R"({"query": "point_cylinder", "point": [0,0,0.5], )" + unit + "}\n");
  std::ostringstream out;
  BOOST_TEST_REQUIRE(run_query(in, out, o, 1) == 0);
  std::istringstream produced(out.str());
  std::string line;
  std::getline(produced, line);
  BOOST_TEST(line.find(R"("nt":"exact","gap":[0.5,0.5],"gap_quantity":"depth_margin","interval":)") != std::string::npos, line);
  std::getline(produced, line);
  BOOST_TEST(line.find(R"("nt":"interval","gap":[0.5,0.5],"gap_quantity":"depth_margin","certificate":)") != std::string::npos,
             line);
}

BOOST_AUTO_TEST_CASE(a_pair_names_its_gap_log_phi) {
  // Two unit cylinders side by side, axes 3 apart: separated, log(phi*) < 0; equal midpoints:
  // no gap, but its quantity is still named.
  const std::string a = R"("a": {"p0": [0,0,0], "p1": [0,0,1], "radius": 1})";
  const json apart = answer_of(R"({"query": "cylinder_cylinder", )" + a + R"(, "b": {"p0": [3,0,0], "p1": [3,0,1], "radius": 1}})");
  BOOST_TEST(apart["answer"] == "separated");
  BOOST_TEST(apart["gap_quantity"] == "log_phi", apart.dump());
  BOOST_TEST(apart["gap"][1].get<double>() < 0);
  const json same = answer_of(R"({"query": "cylinder_cylinder", )" + a + R"(, "b": {"p0": [0,0,0], "p1": [0,0,1], "radius": 1}})");
  BOOST_TEST(same["gap"].is_null());
  BOOST_TEST(same["gap_quantity"] == "log_phi", same.dump());
  // --brief keeps both.
  QueryOptions o;
  o.brief = true;
  std::istringstream in(R"({"id": 7, "query": "cylinder_cylinder", )" + a + R"(, "b": {"p0": [3,0,0], "p1": [3,0,1], "radius": 1}})" + "\n");
  std::ostringstream out;
  BOOST_TEST_REQUIRE(run_query(in, out, o, 1) == 0);
  const json b = json::parse(out.str());
  BOOST_TEST(b["gap_quantity"] == "log_phi", b.dump());
  BOOST_TEST(b["gap"] == apart["gap"]);
}

BOOST_AUTO_TEST_CASE(other_methods_report_no_gap) {
  const std::string l = line_query("line_cylinder", R"("line": {"origin": [0,0,0.5], "direction": [1,0,0]})", unit);
  for (const char* m : {"robust_double", "shene", "gullotti"}) {
    BOOST_TEST(!answer_of(l, m).contains("gap"), m);
    BOOST_TEST(!answer_of(l, m).contains("gap_quantity"), m);
  }
  BOOST_TEST(!answer_of(R"({"query": "point_cylinder", "point": [0,0,0.5], )" + unit + "}", "polynomial").contains("gap"));
  BOOST_TEST(!answer_of(R"({"query": "triangle_cylinder", "triangle": [[0,0,2],[1,0,3],[0,1,3]], )" + unit + "}", "eberly")
                  .contains("gap"));
}

BOOST_AUTO_TEST_CASE(the_gap_of_every_tiny_case_has_the_answers_sign_and_is_that_of_cases) {
  for (const study::Query q : study::kQueries) {
    CaseSpec spec;
    spec.query = std::string(study::to_string(q));
    spec.size = "tiny";
    std::ostringstream cases;
    BOOST_TEST_REQUIRE(run_cases(spec, cases) == 0);
    const std::vector<json> answers = run(cases.str());
    std::istringstream in(cases.str());
    std::size_t i = 0, signed_gaps = 0;
    for (std::string text; std::getline(in, text); ++i) {
      BOOST_TEST_REQUIRE(i < answers.size());
      const json c = json::parse(text), &a = answers[i];
      const std::string where = c["id"].get<std::string>();
      BOOST_TEST(a["answer"] == c["meta"]["certified"], where);
      BOOST_TEST_REQUIRE(a.contains("gap"), where);
      BOOST_TEST(a["gap"] == c["meta"]["gap"], where);
      const std::string quantity = q == study::Query::cylinder_cylinder ? "log_phi" : "depth_margin";
      BOOST_TEST(a["gap_quantity"] == quantity, where);
      BOOST_TEST(c["meta"]["gap_quantity"] == quantity, where);
      if (a["gap"].is_null()) continue;
      ++signed_gaps;
      const double lo = a["gap"][0].get<double>(), hi = a["gap"][1].get<double>();
      BOOST_TEST(lo <= hi, where);
      const std::string answer = a["answer"];
      if (q == study::Query::cylinder_cylinder) {
        // log(phi*) is an enclosure that allows the answer's sign (as study::certify checks).
        if (answer == "separated") BOOST_TEST(lo < 0, where);
        else if (answer == "overlapping") BOOST_TEST(hi > 0, where);
        else BOOST_TEST((answer == "touching" && lo <= 0 && 0 <= hi), where);
      } else {
        // A depth margin is an exact rational: its enclosure has its sign.
        if (answer == "separated") BOOST_TEST(hi < 0, where);
        else if (answer == "overlapping") BOOST_TEST(lo > 0, where);
        else BOOST_TEST((answer == "touching" && lo == 0 && hi == 0), where);
      }
    }
    BOOST_TEST(i == answers.size());
    BOOST_TEST(signed_gaps > 10u, spec.query);
  }
}
