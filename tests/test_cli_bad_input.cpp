// Bad input through the command: every line gets an answer or a clear error naming the field,
// the other lines are still answered, the exit status is 2, and nothing crashes.
#define BOOST_TEST_MODULE cli_bad_input
#include <boost/test/unit_test.hpp>

#include <array>
#include <sstream>
#include <vector>

#include "query.hpp"

using namespace certcyl;
using namespace certcyl::cli;

namespace {

struct Run {
  int status;
  std::vector<json> lines;
};

Run run(const std::string& input) {
  std::istringstream in(input);
  std::ostringstream out;
  Run r;
  r.status = run_query(in, out, QueryOptions{}, 1);
  std::istringstream produced(out.str());
  for (std::string line; std::getline(produced, line);) r.lines.push_back(json::parse(line));
  return r;
}

const std::string cyl5 = R"("cylinder": {"p0": [0,0,0], "p1": [0,0,2], "radius": 5})";

// A point query with the given x (JSON text), id `id`.
std::string point_with_x(int id, const std::string& x) {
  return R"({"id": )" + std::to_string(id) + R"(, "query": "point_cylinder", "point": [)" + x + ", 0, 1], " + cyl5 + "}";
}

// (3, 4, 1) is on the wall of cyl5: touching.
const std::string good = R"({"id": "good", "query": "point_cylinder", "point": [3, 4, 1], )" + cyl5 + "}";

std::string error_of(const json& line) { return line.contains("error") ? line["error"].get<std::string>() : std::string(); }

// Runs `bad` between two good lines: three output lines, the good ones answered "touching".
json sandwiched(const std::string& bad) {
  const Run r = run(good + "\n" + bad + "\n" + good + "\n");
  BOOST_TEST(r.status == 2);
  BOOST_REQUIRE(r.lines.size() == 3u);
  for (int i : {0, 2}) {
    BOOST_TEST(r.lines[i]["id"] == "good");
    BOOST_TEST(r.lines[i]["answer"] == "touching");
  }
  BOOST_TEST(r.lines[1].contains("error"));
  BOOST_TEST(!r.lines[1].contains("answer"));
  return r.lines[1];
}

}  // namespace

BOOST_AUTO_TEST_CASE(malformed_and_truncated_json) {
  BOOST_TEST(error_of(sandwiched(R"({"id": 1, "query": "point_cylinder", "point": [3, 4)")).find("malformed JSON") == 0u);
  BOOST_TEST(error_of(sandwiched(R"({"id": 1 "query": 2})")).find("malformed JSON") == 0u);
  BOOST_TEST(error_of(sandwiched(good.substr(0, good.size() / 2))).find("malformed JSON") == 0u);
  BOOST_TEST(error_of(sandwiched("{")).find("malformed JSON") == 0u);
  BOOST_TEST(error_of(sandwiched("[1, 2, 3]")).find("expected a JSON object") == 0u);
  BOOST_TEST(error_of(sandwiched("null")).find("expected a JSON object") == 0u);
  BOOST_TEST(error_of(sandwiched(R"("just a string")")).find("expected a JSON object") == 0u);
  // The id of a malformed line is recovered from its text when it shows one at the top level,
  // null otherwise; the error names the line's number in the input (the sandwich's second).
  BOOST_TEST(sandwiched(R"({"id": 7, "query": )")["id"] == 7);
  BOOST_TEST(sandwiched(R"({"id": "a\"b", "query": )")["id"] == "a\"b");
  BOOST_TEST(sandwiched(R"({"x": {"id": 7}, "query": )")["id"].is_null());
  BOOST_TEST(sandwiched(R"({"id": [7], "query": )")["id"].is_null());
  BOOST_TEST(sandwiched(R"({"id": 7 "query": 1})")["line"] == 2);
}

BOOST_AUTO_TEST_CASE(empty_input_and_blank_lines) {
  const Run empty = run("");
  BOOST_TEST(empty.status == 0);
  BOOST_TEST(empty.lines.empty());
  const Run blanks = run("\n   \n\t\n" + good + "\n\n");
  BOOST_TEST(blanks.status == 0);
  BOOST_REQUIRE(blanks.lines.size() == 1u);
  BOOST_TEST(blanks.lines[0]["answer"] == "touching");
  // A line with no newline at the end is still answered; a CR before the newline is dropped.
  const Run crlf = run(good + "\r\n" + good);
  BOOST_TEST(crlf.status == 0);
  BOOST_TEST(crlf.lines.size() == 2u);
}

BOOST_AUTO_TEST_CASE(huge_numbers) {
  // A JSON literal beyond binary64 (1e308 * 10) is not a finite double: the parser rejects it
  // or the reader does, naming the field.
  for (const char* x : {"1e309", "1e400", "-1e999", "1e99999999999"}) {
    const std::string e = error_of(sandwiched(point_with_x(1, x)));
    BOOST_TEST_INFO(x << ": " << e);
    BOOST_TEST((e.find("point[0]") == 0u || e.find("malformed JSON") == 0u));
  }
  // 1e308 is a finite double: answered (outside the cylinder of radius 5: separated).
  const Run big = run(point_with_x(1, "1e308") + "\n");
  BOOST_TEST(big.status == 0);
  BOOST_TEST(big.lines.at(0)["answer"] == "separated");
  // As strings these are exact rationals: "1e400" is valid (far outside); numbers of more than
  // kMaxExactBits bits (10^19000 has 63,117) and exponents beyond the parser's limit (10^100000)
  // are rejected with the field named.
  for (const char* x : {R"("1e308")", R"("1e400")", R"("-1e19000")", R"("0x1p65000")", R"("-0x1.8p65000")"}) {
    const Run r = run(point_with_x(2, x) + "\n");
    BOOST_TEST_INFO(x);
    BOOST_TEST(r.lines.at(0)["answer"] == "separated");
  }
  for (const char* x : {R"("1e100001")", R"("1e99999999999999999999")", R"("0x1p400001")", R"("1e-100001")"}) {
    const std::string e = error_of(sandwiched(point_with_x(3, x)));
    BOOST_TEST_INFO(x << ": " << e);
    BOOST_TEST(e.find("point[0]") == 0u);
  }
  for (const char* x : {R"("-1e100000")", R"("0x1p400000")", R"("1e19800")", R"("0x1p-65535")"}) {
    const std::string e = error_of(sandwiched(point_with_x(3, x)));
    BOOST_TEST_INFO(x << ": " << e);
    BOOST_TEST(e.find("point[0]: exact number of ") == 0u);
    BOOST_TEST(e.find("the limit is 65536") != std::string::npos);
  }
}

BOOST_AUTO_TEST_CASE(subnormals_are_valid) {
  // The smallest subnormal, as a JSON number and as hexfloat and decimal strings: x is tiny,
  // so (x, 0, 1) is strictly inside the cylinder of radius 5 (overlapping).
  for (const char* x : {"4.9406564584124654e-324", "5e-324", R"("0x1p-1074")", R"("0x0.0000000000001p-1022")",
                        R"("4.9406564584124654e-324")", "2.2250738585072009e-308", "-0.0"}) {
    const Run r = run(point_with_x(4, x) + "\n");
    BOOST_TEST_INFO(x);
    BOOST_TEST(r.status == 0);
    BOOST_TEST(r.lines.at(0)["answer"] == "overlapping");
  }
}

BOOST_AUTO_TEST_CASE(strings_that_are_not_numbers) {
  for (const char* x : {R"("abc")", R"("")", R"("1/0")", R"("0x")", R"("1e")", R"("--1")", R"("1.2.3")", R"("NaN")",
                        R"("inf")", R"(" 1")", R"("1/")", R"("0x1p")"}) {
    const std::string e = error_of(sandwiched(point_with_x(5, x)));
    BOOST_TEST_INFO(x << ": " << e);
    BOOST_TEST(e.find("point[0]") == 0u);
  }
  // Values of the wrong kind name the field too.
  for (const char* x : {"true", "null", "[1]", R"({"x": 1})"}) {
    const std::string e = error_of(sandwiched(point_with_x(6, x)));
    BOOST_TEST_INFO(x << ": " << e);
    BOOST_TEST(e.find("point[0]: expected a number") == 0u);
  }
}

BOOST_AUTO_TEST_CASE(deeply_nested_values) {
  // Nested as the whole line, and as a field's value: an error, no stack overflow.
  for (std::size_t depth : {1000u, 100000u, 1000000u}) {
    const std::string nest = std::string(depth, '[') + std::string(depth, ']');
    BOOST_TEST_INFO("depth " << depth);
    BOOST_TEST(!error_of(sandwiched(nest)).empty());
    const std::string in_field = point_with_x(7, nest);
    const std::string e = error_of(sandwiched(in_field));
    BOOST_TEST_INFO(e.substr(0, 200));
    if (in_field.size() > kMaxLineBytes)
      BOOST_TEST(e == "line longer than the limit of 1048576 bytes");
    else
      BOOST_TEST(e == "malformed JSON: nested deeper than 16 levels");
    const std::string objects = R"({"id": 8, "query": "point_cylinder", "extra": )" + [&] {
      std::string s;
      for (std::size_t i = 0; i < depth; ++i) s += R"({"a":)";
      return s + "1" + std::string(depth, '}');
    }() + "}";
    BOOST_TEST(!error_of(sandwiched(objects)).empty());
  }
  // Unclosed nesting (truncated) as well.
  BOOST_TEST(!error_of(sandwiched(std::string(100000, '['))).empty());
}

BOOST_AUTO_TEST_CASE(binary_garbage) {
  std::string garbage;
  for (int i = 0; i < 4096; ++i) garbage += static_cast<char>((i * 7919 + 13) % 256 == '\n' ? 0 : (i * 7919 + 13) % 256);
  BOOST_TEST(error_of(sandwiched(garbage)).find("malformed JSON") == 0u);
  BOOST_TEST(error_of(sandwiched(std::string("\0\0\0\x01\xff", 5))).find("malformed JSON") == 0u);
  // Invalid UTF-8 inside a string value: the error line is still valid JSON (run() parsed it).
  const std::string bad_utf8 = R"({"id": "\u00e9", "query": "no)" + std::string("\xff\xfe") + R"("})";
  BOOST_TEST(!error_of(sandwiched(bad_utf8)).empty());
  const std::string bad_key = R"({"id": 9, "query": "point_cylinder", "point": [3, 4, 1], "cylinder": {"p0": [0,0,0], "p1": [0,0,2], "radius": 5, ")" +
                              std::string("\xc3\x28") + R"(": 1}})";
  BOOST_TEST(!error_of(sandwiched(bad_key)).empty());
}

BOOST_AUTO_TEST_CASE(errors_name_the_field) {
  BOOST_TEST(error_of(sandwiched(R"({"id": 1, "query": "point_cylinder", "point": [3, 4], )" + cyl5 + "}")).find("point:") == 0u);
  BOOST_TEST(error_of(sandwiched(R"({"id": 1, "query": "point_cylinder", "point": [3, 4, 1]})")).find("cylinder: missing") == 0u);
  BOOST_TEST(error_of(sandwiched(R"({"id": 1, "query": "point_cylinder", "point": [3, 4, 1], "cylinder": {"p0": [0,0,0], "p1": [0,0,2], "radius": -1}})"))
                 .find("cylinder.radius") == 0u);
  BOOST_TEST(error_of(sandwiched(R"({"id": 1, "query": 5})")).find("query") == 0u);
  BOOST_TEST(error_of(sandwiched(R"({"id": 1})")).find("query: missing") == 0u);
  // Every error line echoes the id it could read; an id must be a string or a number.
  BOOST_TEST(sandwiched(R"({"id": 1.5, "query": "nope"})")["id"] == 1.5);
  const json array_id = sandwiched(R"({"id": [1, "x"], "query": "nope"})");
  BOOST_TEST(array_id["id"].is_null());
  BOOST_TEST(error_of(array_id) == "id: expected a string or a number, got array");
}

BOOST_AUTO_TEST_CASE(members_the_query_does_not_read) {
  // A misspelt or foreign member is an error naming it and listing the valid ones, never a
  // default silently used.
  const json typo = sandwiched(R"({"id": 1, "query": "point_cylinder", "point": [3, 4, 1], "parameter": {}, )" + cyl5 + "}");
  BOOST_TEST(typo["id"] == 1);
  BOOST_TEST(error_of(typo) == "parameter: unknown member of a point_cylinder line with --method certified "
                               "(expected: id, query, meta, point, cylinder)");
  // method and nt are options of the command, not of a line.
  for (const char* m : {"method", "nt"}) {
    const std::string e = error_of(sandwiched(R"({"id": 1, "query": "point_cylinder", ")" + std::string(m) +
                                              R"(": "x", "point": [3, 4, 1], )" + cyl5 + "}"));
    BOOST_TEST(e == std::string(m) + ": not a member of a line: the command's --" + m + " option sets it for every line");
  }
  // "parameters" belongs to the Eberly methods only.
  const std::string pair = R"({"id": 2, "query": "cylinder_cylinder", "a": {"p0": [0,0,0], "p1": [0,0,1], "radius": 1}, )"
                           R"("b": {"p0": [5,0,0], "p1": [5,0,1], "radius": 1}, "parameters": {"max_line_searches": 3}})";
  BOOST_TEST(error_of(sandwiched(pair)).find("parameters: unknown member of a cylinder_cylinder line with --method certified") == 0u);
  QueryOptions eberly;
  eberly.method = "eberly_corrected";
  BOOST_TEST(answer_line(pair, eberly, 1)["answer"] == "separated");
}

BOOST_AUTO_TEST_CASE(operand_members_list_the_valid_names) {
  // A misspelt member inside an operand object is refused with the names that operand takes,
  // for every operand kind (the cylinder lists the names of the form its other members chose).
  const std::string cyl = R"("cylinder": {"p0": [0,0,0], "p1": [0,0,2], "radius": 1})";
  const std::string ell = R"("elliptic_cylinder": {"base": [0,0,0], "a": [1,0,0], "b": [0,1,0], "c": [0,0,2]})";
  const std::string line = R"("line": {"origin": [5,0,1], "direction": [0,1,0]})";
  const std::string ray = R"("ray": {"origin": [5,0,1], "direction": [1,0,0]})";
  const std::string segment = R"("segment": {"p0": [5,0,1], "p1": [6,0,1]})";
  const auto error_for = [&](const std::string& query, const std::string& a, const std::string& b) {
    return error_of(sandwiched(R"({"id": 1, "query": ")" + query + R"(", )" + a + ", " + b + "}"));
  };
  BOOST_TEST(error_for("line_cylinder", R"("line": {"origin": [5,0,1], "dir": [1,0,0]})", cyl) ==
             "line.dir: unexpected member (expected: origin, direction)");
  BOOST_TEST(error_for("ray_cylinder", R"("ray": {"orign": [5,0,1], "direction": [1,0,0]})", cyl) ==
             "ray.orign: unexpected member (expected: origin, direction)");
  BOOST_TEST(error_for("segment_cylinder", R"("segment": {"p0": [5,0,1], "p1": [6,0,1], "p2": [7,0,1]})", cyl) ==
             "segment.p2: unexpected member (expected: p0, p1)");
  BOOST_TEST(error_for("line_elliptic_cylinder", line,
                       R"("elliptic_cylinder": {"base": [0,0,0], "a": [1,0,0], "b": [0,1,0], "c": [0,0,2], "d": 1})") ==
             "elliptic_cylinder.d: unexpected member (expected: base, a, b, c)");
  BOOST_TEST(error_for("ray_elliptic_cylinder", R"("ray": {"origin": [5,0,1], "direction": [1,0,0], "t": 0})", ell) ==
             "ray.t: unexpected member (expected: origin, direction)");
  BOOST_TEST(error_for("segment_elliptic_cylinder", R"("segment": {"p0": [5,0,1], "q1": [6,0,1]})", ell) ==
             "segment.q1: unexpected member (expected: p0, p1)");
  BOOST_TEST(error_for("line_cylinder", line, R"("cylinder": {"p0": [0,0,0], "p1": [0,0,2], "radius": 1, "height": 2})") ==
             "cylinder.height: unexpected member (endpoint form: p0, p1, radius)");
  // The good forms of the same operands are answered.
  for (const auto& [query, a, b] : std::vector<std::array<std::string, 3>>{{"line_cylinder", line, cyl},
                                                                           {"ray_elliptic_cylinder", ray, ell},
                                                                           {"segment_cylinder", segment, cyl}})
    BOOST_TEST(answer_line(R"({"id": 1, "query": ")" + query + R"(", )" + a + ", " + b + "}", QueryOptions{}, 1)["answer"] ==
               "separated");
  // An Eberly parameter that does not exist: the valid ones are listed.
  QueryOptions eberly;
  eberly.method = "eberly_corrected";
  const std::string pair = R"({"id": 2, "query": "cylinder_cylinder", "a": {"p0": [0,0,0], "p1": [0,0,1], "radius": 1}, )"
                           R"("b": {"p0": [5,0,0], "p1": [5,0,1], "radius": 1}, "parameters": {"max_linesearches": 3}})";
  BOOST_TEST(error_of(answer_line(pair, eberly, 1)) ==
             "parameters.max_linesearches: unknown parameter (expected: perpendicular_bisections, line_search_bisections, "
             "max_line_searches, axis_tests, perpendicular_tests, other_direction_tests, parallel_tests, parallel_threshold)");
}

BOOST_AUTO_TEST_CASE(meta_is_passed_through) {
  const std::string with_meta = R"({"id": "m", "query": "point_cylinder", "point": [3, 4, 1], )" + cyl5 +
                                R"(, "meta": {"family": "wall", "k": [3, "x"], "note": null}})";
  const Run r = run(with_meta + "\n");
  BOOST_TEST(r.status == 0);
  BOOST_REQUIRE(r.lines.size() == 1u);
  BOOST_TEST(r.lines[0]["answer"] == "touching");
  BOOST_TEST(r.lines[0]["meta"] == json::parse(R"({"family": "wall", "k": [3, "x"], "note": null})"));
}

BOOST_AUTO_TEST_CASE(duplicate_members) {
  // The same name twice in one object: JSON leaves the meaning open, so the line is refused
  // (a duplicated cylinder would otherwise silently replace the first).
  const std::string twice = R"({"id": 3, "query": "point_cylinder", "point": [0, 0, 1], )" + cyl5 +
                            R"(, "cylinder": {"p0": [9,0,0], "p1": [9,0,2], "radius": 1}})";
  const json e = sandwiched(twice);
  BOOST_TEST(e["id"] == 3);
  BOOST_TEST(error_of(e) == "malformed JSON: member \"cylinder\" appears twice in one object");
  const std::string nested = R"({"id": 4, "query": "point_cylinder", "point": [0, 0, 1], "cylinder": {"p0": [0,0,0], "p1": [0,0,2], "radius": 1, "radius": 5}})";
  BOOST_TEST(error_of(sandwiched(nested)) == "malformed JSON: member \"radius\" appears twice in one object");
  // The same name in different objects is fine.
  const Run ok = run(R"({"id": 5, "query": "cylinder_cylinder", "a": {"p0": [0,0,0], "p1": [0,0,1], "radius": 1}, "b": {"p0": [5,0,0], "p1": [5,0,1], "radius": 1}})" "\n");
  BOOST_TEST(ok.status == 0);
  BOOST_TEST(ok.lines.at(0)["answer"] == "separated");
}

BOOST_AUTO_TEST_CASE(floating_methods_that_overflow_answer_invalid) {
  // 1e300 squared overflows binary64: the floating methods' endpoints are not finite. The
  // answer is "invalid" with the value named, never a crash or a silent null.
  const std::string line = R"({"id": 1, "query": "line_cylinder", "line": {"origin": [0,0,0], "direction": [1e300,0,0]}, )"
                           R"("cylinder": {"p0": [0,0,0], "p1": [0,0,1], "radius": 1}})";
  for (const char* method : {"robust_double", "shene", "gullotti"}) {
    QueryOptions o;
    o.method = method;
    const ojson a = answer_line(line, o, 1);
    BOOST_TEST_INFO(method << ": " << a.dump());
    BOOST_TEST(!a.contains("error"));
    if (a["answer"] == "invalid") {
      BOOST_TEST(a["reason"].get<std::string>().find("non-finite value in interval[") == 0u);
      BOOST_TEST(a.contains("computed_answer"));
    } else {
      // A method that stays finite is compared with the certified answer.
      BOOST_TEST(a["answer"] == answer_line(line, QueryOptions{}, 1)["answer"]);
    }
  }
  QueryOptions robust;
  robust.method = "robust_double";
  BOOST_TEST(answer_line(line, robust, 1)["answer"] == "invalid");
  // The certified answer of the same line: it lies in the base plane and crosses the base disc
  // through the axis, so it meets the closed cylinder only on its boundary.
  BOOST_TEST(answer_line(line, QueryOptions{}, 1)["answer"] == "touching");
}
