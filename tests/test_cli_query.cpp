// The `certcyl query` contract: one answer line per input line, in order, ids echoed, errors
// naming the field, exit status 0 / 2. Expected answers are worked out by hand in comments.
#define BOOST_TEST_MODULE cli_query
#include <boost/test/unit_test.hpp>

#include <sstream>

#include "query.hpp"

using namespace certcyl;
using namespace certcyl::cli;

namespace {

struct Run {
  int status;
  std::vector<json> lines;
};

Run run(const std::string& input, const QueryOptions& options = {}, unsigned threads = 1) {
  std::istringstream in(input);
  std::ostringstream out;
  Run r;
  r.status = run_query(in, out, options, threads);
  std::istringstream produced(out.str());
  for (std::string line; std::getline(produced, line);) r.lines.push_back(json::parse(line));
  return r;
}

// Cylinder of radius 5 around the z axis from z = 0 to z = 2.
const std::string cyl5 = R"("cylinder": {"p0": [0,0,0], "p1": [0,0,2], "radius": 5})";

std::string point_line(const std::string& id, const std::string& point) {
  return R"({"id": )" + id + R"(, "query": "point_cylinder", "point": )" + point + ", " + cyl5 + "}\n";
}

}  // namespace

BOOST_AUTO_TEST_CASE(point_answers_worked_out_by_hand) {
  // (3,4,1): |(3,4)| = 5 = r, 0 < z < 2: on the wall -> touching.
  // (1,1,1): inside -> overlapping.  (3,4,3): above the top cap -> separated.
  // ("3.0000001", 4, 1): x^2 + y^2 = 25.00000060000001 > 25 -> separated.
  const Run r = run(point_line("1", "[3,4,1]") + point_line("2", "[1,1,1]") + point_line("3", "[3,4,3]") +
                    point_line("4", R"(["3.0000001", 4, 1])"));
  BOOST_TEST(r.status == 0);
  BOOST_TEST_REQUIRE(r.lines.size() == 4u);
  const char* expected[] = {"touching", "overlapping", "separated", "separated"};
  for (int i = 0; i < 4; ++i) {
    BOOST_TEST(r.lines[i]["id"] == i + 1);
    BOOST_TEST(r.lines[i]["answer"] == expected[i]);
    BOOST_TEST(r.lines[i]["certified"] == true);
    BOOST_TEST(r.lines[i]["method"] == "certified");
  }
  // Exact string input comes back exact.
  BOOST_TEST(r.lines[3]["certificate"]["point"][0] == "30000001/10000000");
}

BOOST_AUTO_TEST_CASE(floating_methods_say_when_input_was_rounded) {
  QueryOptions o;
  o.method = "polynomial";
  o.nt = parse_number_type("double");
  // "0.1" is not a binary64: the double kernel saw it rounded.
  const Run r = run(point_line("1", R"(["0.1", 0, 1])") + point_line("2", "[0.5, 0, 1]"), o);
  BOOST_TEST_REQUIRE(r.lines.size() == 2u);
  BOOST_TEST(r.lines[0]["input_rounded"] == true);
  BOOST_TEST(!r.lines[1].contains("input_rounded"));
  BOOST_TEST(r.lines[0]["certified"] == false);
  BOOST_TEST(r.lines[0]["nt"] == "double");
  // An interval that cannot decide says undecided, never guesses: (0.6, 0.8) on radius 1.
  o.nt = parse_number_type("interval");
  const Run u = run(R"({"id": 7, "query": "point_cylinder", "point": ["0.6", "0.8", 1], "cylinder": {"p0": [0,0,0], "p1": [0,0,2], "radius": 1}})"
                    "\n",
                    o);
  BOOST_TEST(u.lines[0]["answer"] == "undecided");
  BOOST_TEST(u.lines[0]["certified"] == false);
}

BOOST_AUTO_TEST_CASE(each_bad_line_gets_an_error_and_the_rest_are_answered) {
  const std::string good = point_line("0", "[1,1,1]");
  struct Bad {
    std::string line;
    std::string must_mention;
  };
  const std::vector<Bad> bad{
      {"{\"id\": 1, \"query\": \"point_cylinder\", \"point\": [1,1,", "malformed JSON"},  // truncated
      {"not json at all", "malformed JSON"},
      {std::string("\x01\xff\xfe garbage \x00 bytes", 22), "malformed JSON"},
      {R"({"id": 3, "query": "no_such_query"})", "query: unknown query"},
      {R"({"id": 4, "point": [1,1,1]})", "query: missing"},
      {R"({"id": 5, "query": "point_cylinder", "cylinder": {"p0": [0,0,0], "p1": [0,0,2], "radius": 5}})", "point: missing"},
      {R"({"id": 6, "query": "point_cylinder", "point": [1,1,1e999], )" + cyl5 + "}", "malformed JSON"},  // non-finite
      {R"({"id": 7, "query": "point_cylinder", "point": [1,1,"inf"], )" + cyl5 + "}", "point[2]"},
      {R"({"id": 8, "query": "point_cylinder", "point": [1,1,1], "cylinder": {"p0": [0,0,1], "p1": [0,0,1], "radius": 5}})",
       "cylinder: zero-length axis"},
      {R"({"id": 9, "query": "point_cylinder", "point": [1,1,1], "cylinder": {"p0": [0,0,0], "p1": [0,0,1], "radius": -2}})",
       "cylinder.radius"},
      {R"({"id": 10, "query": "point_cylinder", "point": [1,1], )" + cyl5 + "}", "point: expected an array of 3"},
      {R"([1, 2, 3])", "expected a JSON object"},
      {std::string(200, '[') + std::string(200, ']'), "nested deeper than 16 levels"},
  };
  std::string input;
  for (const auto& b : bad) input += good + b.line + "\n";
  input += good;
  const Run r = run(input);
  BOOST_TEST(r.status == 2);
  BOOST_TEST_REQUIRE(r.lines.size() == 2 * bad.size() + 1);
  for (std::size_t i = 0; i < bad.size(); ++i) {
    BOOST_TEST(r.lines[2 * i]["answer"] == "overlapping");
    const json& e = r.lines[2 * i + 1];
    BOOST_TEST_REQUIRE(e.contains("error"), bad[i].line);
    const std::string message = e["error"];
    BOOST_TEST(message.find(bad[i].must_mention) != std::string::npos, message);
  }
  BOOST_TEST(r.lines.back()["answer"] == "overlapping");
}

BOOST_AUTO_TEST_CASE(empty_input_is_answered_by_nothing) {
  const Run r = run("");
  BOOST_TEST(r.status == 0);
  BOOST_TEST(r.lines.empty());
  const Run blank = run("\n  \n\t\n");
  BOOST_TEST(blank.status == 0);
  BOOST_TEST(blank.lines.empty());
}

BOOST_AUTO_TEST_CASE(threads_keep_order_and_ids) {
  // 3000 lines: every fifth is bad; the answer pattern is known per index.
  std::string input;
  for (int i = 0; i < 3000; ++i) {
    if (i % 5 == 4)
      input += R"({"id": ")" + std::to_string(i) + R"(", "query": "nope"})" "\n";
    else
      input += point_line(std::to_string(i), i % 2 ? "[3,4,1]" : "[0,0,5]");
  }
  const Run r = run(input, {}, 4);
  BOOST_TEST(r.status == 2);
  BOOST_TEST_REQUIRE(r.lines.size() == 3000u);
  for (int i = 0; i < 3000; ++i) {
    if (i % 5 == 4) {
      BOOST_TEST_REQUIRE(r.lines[i]["id"] == std::to_string(i));
      BOOST_TEST_REQUIRE(r.lines[i].contains("error"));
    } else {
      BOOST_TEST_REQUIRE(r.lines[i]["id"] == i);
      BOOST_TEST_REQUIRE(r.lines[i]["answer"] == (i % 2 ? "touching" : "separated"));
    }
  }
}

BOOST_AUTO_TEST_CASE(a_method_that_does_not_answer_the_query_is_an_error) {
  QueryOptions o;
  o.method = "no_such_method";
  const Run r = run(point_line("1", "[1,1,1]"), o);
  BOOST_TEST(r.status == 2);
  BOOST_TEST(std::string(r.lines[0]["error"]).find("method") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(brief_answers) {
  QueryOptions o;
  o.brief = true;
  // The line x = 1/2 + t, y = 0, z = 1 crosses the wall of the unit cylinder at x = -1 and x = 1:
  // t in [-3/2, 1/2], both exact doubles. Its gap (the depth margin, src/study/gap.hpp): s = 1/2
  // (z = 1 of a height 2), so max s = max (1 - s) = 1/2, and the line crosses the axis: 1/2.
  const Run line = run(R"({"id": "l", "query": "line_cylinder", "line": {"origin": [0.5, 0, 1], "direction": [1, 0, 0]}, )"
                       R"("cylinder": {"p0": [0,0,0], "p1": [0,0,2], "radius": 1}, "meta": {"k": 1}})"
                       "\n",
                       o);
  BOOST_TEST(line.lines.at(0) == json::parse(R"({"id": "l", "meta": {"k": 1}, "answer": "overlapping", "interval": [-1.5, 0.5], "gap": [0.5, 0.5], "gap_quantity": "depth_margin"})"));
  // Two unit cylinders with parallel axes 3 apart: separated; the gap is an enclosure of log(phi*) < 0.
  const Run pair = run(R"({"id": 2, "query": "cylinder_cylinder", "a": {"p0": [0,0,0], "p1": [0,0,1], "radius": 1}, )"
                       R"("b": {"p0": [3,0,0], "p1": [3,0,1], "radius": 1}})"
                       "\n",
                       o);
  const json& p = pair.lines.at(0);
  BOOST_TEST(p["answer"] == "separated");
  BOOST_TEST(p.size() == 4u);  // id, answer, gap, gap_quantity
  BOOST_TEST(p["gap_quantity"] == "log_phi");
  BOOST_TEST(p["gap"][1].get<double>() < 0);
  BOOST_TEST(p["gap"][0].get<double>() <= p["gap"][1].get<double>());
}

// --time-limit (QueryOptions::time_limit_seconds): the needles of test_cylinder_wide_range's
// time-limit case (a along y, 2^422 long; b's cap disk tilted into a's wall) overlap and are
// decided only after the optimiser. With a limit that has run out before the first check the line
// is answered undecided with a reason, and the run still exits 0 (every line was answered);
// without a limit the answer is overlapping, with no reason.
BOOST_AUTO_TEST_CASE(a_time_limit_that_runs_out_is_answered_undecided_with_a_reason) {
  CGAL::Gmpz two_422;
  mpz_ui_pow_ui(two_422.mpz(), 2, 422);
  std::ostringstream digits;
  digits << two_422;
  const std::string far = "\"" + digits.str() + "\"";
  const std::string line = R"({"id": 1, "query": "cylinder_cylinder", "a": {"p0": [0,0,0], "p1": [0,)" + far +
                           R"(,0], "radius": 22.5}, "b": {"p0": [)" + far + R"(, 8.75, 22.5], "p1": [22.5, 22.5, 22.5], "radius": 22.5}})" + "\n";
  QueryOptions limited;
  limited.time_limit_seconds = 1e-9;
  const Run stopped = run(line, limited);
  BOOST_TEST(stopped.status == 0);
  BOOST_TEST_REQUIRE(stopped.lines.size() == 1u);
  BOOST_TEST(stopped.lines[0]["answer"] == "undecided");
  BOOST_TEST(stopped.lines[0]["reason"] == "time limit reached (--time-limit)");
  limited.brief = true;
  BOOST_TEST(run(line, limited).lines.at(0)["reason"] == "time limit reached (--time-limit)");
  const Run decided = run(line);
  BOOST_TEST(decided.status == 0);
  BOOST_TEST_REQUIRE(decided.lines.size() == 1u);
  BOOST_TEST(decided.lines[0]["answer"] == "overlapping");
  BOOST_TEST(!decided.lines[0].contains("reason"));
}
