// `certcyl query` on every query kind, and `certcyl scene`: answers worked out by hand.
#define BOOST_TEST_MODULE cli_queries
#include <boost/test/unit_test.hpp>

#include <array>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>

#include "query.hpp"
#include "scene.hpp"

using namespace certcyl;
using namespace certcyl::cli;

namespace {

std::vector<json> run(const std::string& input, const std::string& method = "certified", const std::string& nt = "double") {
  QueryOptions o;
  o.method = method;
  o.nt = parse_number_type(nt);
  std::istringstream in(input);
  std::ostringstream out;
  run_query(in, out, o, 1);
  std::vector<json> lines;
  std::istringstream produced(out.str());
  for (std::string line; std::getline(produced, line);) lines.push_back(json::parse(line));
  return lines;
}

// Radius 1 around the z axis, z in [0, 2].
const std::string unit = R"({"p0": [0,0,0], "p1": [0,0,2], "radius": 1})";

}  // namespace

BOOST_AUTO_TEST_CASE(line_through_the_wall) {
  // X = (-5, 0, 1) + t (1, 0, 0) crosses the wall at x = -1 and x = 1: t = 4 and 6.
  const auto r = run(R"({"id": 1, "query": "line_cylinder", "line": {"origin": [-5,0,1], "direction": [1,0,0]}, "cylinder": )" +
                     unit + "}\n");
  BOOST_TEST(r[0]["answer"] == "overlapping");
  BOOST_TEST(r[0]["certified"] == true);
  BOOST_TEST(r[0]["interval"][0]["exact"] == "4");
  BOOST_TEST(r[0]["interval"][1]["exact"] == "6");
  BOOST_TEST(r[0]["interval"][0]["feature"] == "wall");
  BOOST_TEST(r[0]["interval"][1]["approx"] == 6.0);
}

BOOST_AUTO_TEST_CASE(tangent_line_touches_at_one_point) {
  // y = 1 is tangent to the unit circle at (0, 1): t = 5 twice.
  const auto r = run(R"({"id": 2, "query": "line_cylinder", "line": {"origin": [-5,1,1], "direction": [1,0,0]}, "cylinder": )" +
                     unit + "}\n");
  BOOST_TEST(r[0]["answer"] == "touching");
  BOOST_TEST(r[0]["interval"][0]["exact"] == "5");
  BOOST_TEST(r[0]["interval"][1]["exact"] == "5");
}

BOOST_AUTO_TEST_CASE(segment_with_an_irrational_endpoint) {
  // X = (-5, 1/2, 1) + t (5, 0, 0), t in [0, 1]: the wall at x = -sqrt(3)/2, so
  // t = (5 - sqrt(3)/2) / 5 = 1 - sqrt(3)/10; the segment ends at t = 1 (x = 0) inside.
  const auto r = run(R"({"id": 3, "query": "segment_cylinder", "segment": {"p0": [-5,"1/2",1], "p1": [0,"1/2",1]}, "cylinder": )" +
                     unit + "}\n");
  BOOST_TEST(r[0]["answer"] == "overlapping");
  BOOST_TEST(r[0]["interval"][0]["exact"] == "1 - 1/10*sqrt(3)");
  // 1 - sqrt(3)/10 = 0.82679491924311227064725536584941...; its binary64 neighbours are
  // 0x1.a751a9e54bd77p-1 and 0x1.a751a9e54bd78p-1 (worked out to 60 digits), and it is nearer
  // the second.
  BOOST_TEST(r[0]["interval"][0]["approx"] == 0x1.a751a9e54bd78p-1);
  BOOST_TEST(r[0]["interval"][1]["feature"] == "end");
  BOOST_TEST(r[0]["interval"][1]["surface"] == "none");
}

BOOST_AUTO_TEST_CASE(ray_along_an_oblique_elliptic_axis) {
  // Base 0, a = (2,0,0), b = (0,1,0), c = (1,0,1): the ray (0,0,-1) + t (0,0,1) meets z = 0
  // (cap0) at t = 1; at height z the section is centred at (z, 0) with semi-axis 2 along x,
  // so (0,0,z) stays inside up to z = 1 (cap1) at t = 2.
  const auto r = run(
      R"({"id": 4, "query": "ray_elliptic_cylinder", "ray": {"origin": [0,0,-1], "direction": [0,0,1]}, "elliptic_cylinder": {"base": [0,0,0], "a": [2,0,0], "b": [0,1,0], "c": [1,0,1]}})"
      "\n");
  BOOST_TEST(r[0]["answer"] == "overlapping");
  BOOST_TEST(r[0]["interval"][0]["exact"] == "1");
  BOOST_TEST(r[0]["interval"][0]["feature"] == "cap0");
  BOOST_TEST(r[0]["interval"][1]["exact"] == "2");
  BOOST_TEST(r[0]["interval"][1]["feature"] == "cap1");
}

BOOST_AUTO_TEST_CASE(seed_methods_answer_in_the_requested_type) {
  const std::string line = R"({"id": 5, "query": "line_cylinder", "line": {"origin": [-5,0,1], "direction": [1,0,0]}, "cylinder": )" +
                           unit + "}\n";
  for (const char* m : {"shene", "gullotti", "gullotti_as_written", "robust_double"}) {
    const auto r = run(line, m, "core_expr");
    BOOST_TEST(r[0]["answer"] == "overlapping", m);
    BOOST_TEST(r[0]["certified"] == false, m);  // a seed is not a certified method
    BOOST_TEST(r[0]["method"] == m);
  }
  // Without a square root the seeds cannot run: a clear error naming --nt.
  const auto g = run(line, "shene", "gmpq");
  BOOST_TEST(std::string(g[0]["error"]).rfind("nt:", 0) == 0);
}

BOOST_AUTO_TEST_CASE(shene_as_written_follows_the_printed_condition) {
  // Lines along x at height 1 through (-5, y0, 1); the cylinder has radius 1 around the z axis.
  // The distance between the line and the axis is |d| = |y0|. y0 = 0: r > |d|, the line crosses
  // the wall at t = 4 and 6, but the printed "if r < |d|, two points" falls to "otherwise: no
  // intersection". y0 = 3: r < |d|, the line misses, but the text claims two points, with
  // x^2 = r^2 - d^2 = -8: overlapping without endpoints.
  const std::string cyl = R"(, "cylinder": )" + unit + "}\n";
  const std::string input = R"({"id": "through", "query": "line_cylinder", "line": {"origin": [-5,0,1], "direction": [1,0,0]})" + cyl +
                            R"({"id": "miss", "query": "line_cylinder", "line": {"origin": [-5,3,1], "direction": [1,0,0]})" + cyl;
  for (const char* nt : {"double", "core_expr"}) {
    const auto w = run(input, "shene_as_written", nt);
    BOOST_TEST_REQUIRE(w.size() == 2u);
    BOOST_TEST(w[0]["id"] == "through");
    BOOST_TEST(w[0]["answer"] == "separated");
    BOOST_TEST(w[0]["interval"].empty());
    BOOST_TEST(w[1]["answer"] == "overlapping");
    BOOST_TEST(w[1]["interval"].empty());
    BOOST_TEST(w[1].contains("note"));
    BOOST_TEST(w[1]["method"] == "shene_as_written");
    const auto c = run(input, "shene", nt);
    BOOST_TEST(c[0]["answer"] == "overlapping");
    BOOST_TEST(c[0]["interval"][0]["approx"] == 4.0);
    BOOST_TEST(c[0]["interval"][1]["approx"] == 6.0);
    BOOST_TEST(c[1]["answer"] == "separated");
  }
}

BOOST_AUTO_TEST_CASE(triangle_in_a_cap_plane_touches) {
  // The triangle lies in the plane z = 2 of cap1 and covers the cap's centre: it meets the
  // cylinder only on its boundary.
  const auto r = run(R"({"id": 6, "query": "triangle_cylinder", "triangle": [[0,0,2],[5,0,2],[0,5,2]], "cylinder": )" + unit +
                     "}\n" +
                     R"({"id": 7, "query": "triangle_cylinder", "triangle": [[0,0,1],[5,0,1],[0,5,1]], "cylinder": )" + unit +
                     "}\n" +
                     R"({"id": 8, "query": "triangle_cylinder", "triangle": [[2,0,1],[5,0,1],[2,5,1]], "cylinder": )" + unit +
                     "}\n");
  BOOST_TEST(r[0]["answer"] == "touching");
  BOOST_TEST(r[0]["certificate"]["cylinder_feature"] == "cap1");
  BOOST_TEST(r[1]["answer"] == "overlapping");  // the same triangle at mid-height
  BOOST_TEST(r[2]["answer"] == "separated");    // x >= 2 everywhere: outside the tube
  BOOST_TEST(r[2]["certificate"]["separation"] == "outside_tube");
  const auto e = run(R"({"id": 9, "query": "triangle_cylinder", "triangle": [[2,0,1],[5,0,1],[2,5,1]], "cylinder": )" + unit + "}\n",
                     "eberly", "double");
  BOOST_TEST(e[0]["answer"] == "separated");
  BOOST_TEST(e[0]["certified"] == false);
}

BOOST_AUTO_TEST_CASE(cylinders_by_hand) {
  // Two unit cylinders with parallel axes 2 apart touch along the wall line x = 1.
  // Axes 3 apart are separated; 1 apart overlap. A cross of two cylinders through a common
  // midpoint overlaps there.
  auto pair = [](const std::string& id, const std::string& x) {
    return R"({"id": )" + id + R"(, "query": "cylinder_cylinder", "a": )" + unit + R"(, "b": {"p0": [)" + x + R"(,0,0], "p1": [)" + x +
           R"(,0,2], "radius": 1}})" "\n";
  };
  const auto r = run(pair("1", "2") + pair("2", "3") + pair("3", "1") +
                     R"({"id": 4, "query": "cylinder_cylinder", "a": )" + unit +
                     R"(, "b": {"center": [0,0,1], "axis": [1,0,0], "radius": "1/2", "height": 4}})" "\n");
  BOOST_TEST(r[0]["answer"] == "touching");
  BOOST_TEST(r[0]["certificate"]["contact"]["type"] == "wall-wall");
  BOOST_TEST(r[0]["gap"][0] == 0.0);
  BOOST_TEST(r[0]["gap"][1] == 0.0);
  BOOST_TEST(r[1]["answer"] == "separated");
  BOOST_TEST(r[1]["gap"][1].get<double>() < 0.0);  // log(phi*) < 0 when separated
  BOOST_TEST(r[2]["answer"] == "overlapping");
  BOOST_TEST(r[2]["gap"][0].get<double>() > 0.0);
  BOOST_TEST(r[3]["answer"] == "overlapping");
  BOOST_TEST(r[3]["gap"].is_null());  // common midpoint: phi* undefined
  for (const auto& l : r) BOOST_TEST(l["certified"] == true);
}

BOOST_AUTO_TEST_CASE(scene_reports_every_meeting_pair) {
  const std::string path = "test_cli_queries_scene.json";
  {
    std::ofstream f(path);
    f << R"({"cylinders": [
      {"name": "a", "p0": [0,0,0], "p1": [0,0,2], "radius": 1},
      {"name": "b", "p0": [2,0,0], "p1": [2,0,2], "radius": 1},
      {"name": "far", "p0": [10,0,0], "p1": [10,0,2], "radius": 1},
      {"center": [0,0,1], "axis": [1,0,0], "radius": "1/2", "height": 4}],
      "triangles": [{"name": "t", "vertices": [[0,0,2],[5,0,2],[0,5,2]]}]})";
  }
  std::ostringstream out;
  BOOST_TEST(run_scene(path, out, 2, false) == 0);
  std::vector<json> lines;
  std::istringstream produced(out.str());
  for (std::string line; std::getline(produced, line);) lines.push_back(json::parse(line));
  // By hand: a-b touch (walls), a and b overlap the crossing cylinder "cylinders[3]" (it spans
  // x in [-2, 2] at z = 1 with radius 1/2), a and b touch the triangle in their top cap plane;
  // "far" meets nothing; the crossing cylinder (z <= 3/2) misses the triangle at z = 2.
  // The lines come in the broad phase's order; as a set they are these.
  std::set<std::array<std::string, 3>> found;
  for (const json& l : lines) found.insert({l["a"].get<std::string>(), l["b"].get<std::string>(), l["answer"].get<std::string>()});
  const std::set<std::array<std::string, 3>> expected{{"a", "b", "touching"},
                                                      {"a", "cylinders[3]", "overlapping"},
                                                      {"a", "t", "touching"},
                                                      {"b", "cylinders[3]", "overlapping"},
                                                      {"b", "t", "touching"}};
  BOOST_TEST(lines.size() == 5u);
  BOOST_TEST((found == expected));
  // An invalid scene names the field.
  {
    std::ofstream f(path);
    f << R"({"cylinders": [{"name": "a", "p0": [0,0,0], "p1": [0,0,2], "radius": 0}]})";
  }
  std::ostringstream none;
  BOOST_TEST(run_scene(path, none, 1, false) == 2);
  BOOST_TEST(run_scene("no/such/file.json", none, 1, false) == 1);
  std::remove(path.c_str());
}
