// `certcyl cases` and `certcyl judge`: the cases are lines `certcyl query` answers with their
// certified answer and read back bit for bit; an answers file is scored with counts derived here
// from the cases' certified answers; bad answers files are errors naming the line; a co-process
// (`certcyl query --method shene --nt double`) gets the counts and entry-parameter errors of the
// study's shene/double method, computed here by the study's code; answers' intervals are scored
// against the certified entry parameter, and a cases file is certified again, never trusted;
// a program that stops, dies or writes garbage ends
// the run with what was judged kept; the example plugin's failures are named where they occur,
// and a plugin that crashes keeps the answers before the crash.
#define BOOST_TEST_MODULE judge
#include <boost/test/unit_test.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <cstring>
#include <map>
#include <set>
#include <sstream>

#include <sys/wait.h>
#include <unistd.h>

#include "cases.hpp"
#include "judge_test_support.hpp"
#include "study/families.hpp"
#include "study/gap.hpp"
#include "study_internal.hpp"
#include "study_methods.hpp"

using namespace certcyl;
using namespace judge_test;
using json = nlohmann::json;

namespace {

const std::string kCertcyl = CERTCYL_BIN;

// The records of a CSV text as RFC 4180 reads them: fields split at commas outside double
// quotes, "" a quote inside them, a line break inside quotes part of the field.
std::vector<std::vector<std::string>> csv_records(const std::string& text) {
  std::vector<std::vector<std::string>> records;
  std::vector<std::string> record;
  std::string field;
  bool quoted = false, any = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c != '"') {
        field += c;
      } else if (i + 1 < text.size() && text[i + 1] == '"') {
        field += '"', ++i;
      } else {
        quoted = false;
      }
    } else if (c == '"') {
      BOOST_REQUIRE_MESSAGE(field.empty(), "a quote inside an unquoted CSV field");
      quoted = any = true;
    } else if (c == ',') {
      record.push_back(field), field.clear();
      any = true;
    } else if (c == '\n') {
      if (any || !field.empty()) record.push_back(field), records.push_back(record);
      record.clear(), field.clear(), any = false;
    } else if (c != '\r') {
      field += c, any = true;
    }
  }
  BOOST_REQUIRE_MESSAGE(!quoted, "an unterminated quoted CSV field");
  if (any || !field.empty()) record.push_back(field), records.push_back(record);
  return records;
}

// families.csv as (query, family) -> column -> value.
std::map<std::pair<std::string, std::string>, std::map<std::string, std::string>> families_csv(const fs::path& p) {
  std::map<std::pair<std::string, std::string>, std::map<std::string, std::string>> out;
  const auto rows = csv_records(slurp(p));
  BOOST_REQUIRE(!rows.empty());
  const auto& header = rows[0];
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const auto& cells = rows[i];
    BOOST_REQUIRE(cells.size() == header.size());
    std::map<std::string, std::string> row;
    for (std::size_t j = 0; j < cells.size(); ++j) row[header[j]] = cells[j];
    out[{row["query"], row["family"]}] = row;
  }
  return out;
}

long count(const std::map<std::string, std::string>& row, const std::string& column) { return std::stol(row.at(column)); }

}  // namespace

BOOST_AUTO_TEST_CASE(cases_are_query_lines_with_their_certified_answers) {
  Scratch s;
  for (const study::Query query : study::kQueries) {
    const std::string q(study::to_string(query));
    const Run cases = s.run(kCertcyl + " cases --query " + q + " --size tiny > cases.jsonl");
    BOOST_TEST_REQUIRE(cases.status == 0, cases.err);
    const Run answers = s.run(kCertcyl + " query < cases.jsonl");
    BOOST_TEST_REQUIRE(answers.status == 0, answers.err);
    const auto in = lines_of(slurp(s / "cases.jsonl")), out = lines_of(answers.out);
    BOOST_TEST_REQUIRE(in.size() == out.size());
    std::set<std::string> families;
    for (std::size_t i = 0; i < in.size(); ++i) {
      const json c = json::parse(in[i]), a = json::parse(out[i]);
      BOOST_TEST(a["id"] == c["id"]);
      BOOST_TEST(a["meta"] == c["meta"]);  // passed through
      BOOST_TEST(a["answer"] == c["meta"]["certified"], in[i]);
      families.insert(c["meta"]["family"].get<std::string>());
      // The pair query reports the same certified gap (log phi*) as an enclosure of it.
      if (a.contains("gap") && a["gap"].is_array() && c["meta"]["gap"].is_array())
        BOOST_TEST((a["gap"][0].get<double>() <= c["meta"]["gap"][1].get<double>() &&
                    c["meta"]["gap"][0].get<double>() <= a["gap"][1].get<double>()));
    }
    // Every family of the query, 3 cases each at tiny size.
    std::size_t expected_families = 0;
    for (const study::Family& f : study::all_families())
      expected_families += std::count(f.queries.begin(), f.queries.end(), cli::parse_study_query(q));
    BOOST_TEST(families.size() == expected_families);
    BOOST_TEST(in.size() == 3 * expected_families);
    BOOST_TEST(families.count("uniform") == 1u);
  }
}

BOOST_AUTO_TEST_CASE(cases_read_back_bit_for_bit) {
  cli::CaseSpec spec;
  spec.query = "triangle_cylinder";
  spec.size = "tiny";
  spec.families = {"t_vertex_wall", "uniform"};
  const std::vector<cli::Case> made = cli::make_cases(spec);
  BOOST_TEST_REQUIRE(made.size() == 6u);
  std::stringstream file;
  for (const cli::Case& c : made) file << cli::case_line(c).dump() << '\n';
  const std::vector<cli::Case> back = cli::read_cases(file, "cases");
  BOOST_TEST_REQUIRE(back.size() == made.size());
  for (std::size_t i = 0; i < made.size(); ++i) {
    BOOST_TEST(back[i].id == made[i].id);
    BOOST_TEST(back[i].family == made[i].family);
    BOOST_TEST(back[i].k == made[i].k);
    BOOST_TEST((back[i].certified == made[i].certified));
    BOOST_TEST(back[i].line == i + 1);
    BOOST_TEST(std::memcmp(back[i].x.data(), made[i].x.data(), made[i].x.size() * sizeof(double)) == 0);
  }
  BOOST_CHECK_THROW(cli::make_cases({"triangle_cylinder", {"tangent"}, "tiny"}), std::invalid_argument);
  BOOST_CHECK_THROW(cli::make_cases({"sphere", {}, "tiny"}), std::invalid_argument);
}

BOOST_AUTO_TEST_CASE(answers_file_scored_per_family) {
  Scratch s;
  BOOST_TEST_REQUIRE(s.run(kCertcyl + " cases --query ray_cylinder --size tiny > cases.jsonl").status == 0);
  // A method that always says "separated": wrong exactly where the certified answer meets.
  std::map<std::string, std::map<std::string, long>> expected;  // family -> outcome -> count
  std::set<std::string> meeting_inputs;
  {
    std::ofstream answers(s / "always_separated.jsonl");
    for (const std::string& l : lines_of(slurp(s / "cases.jsonl"))) {
      const json c = json::parse(l);
      answers << json{{"id", c["id"]}, {"answer", "separated"}}.dump() << '\n';
      const std::string certified = c["meta"]["certified"];
      const std::string family = c["meta"]["family"];
      ++expected[family][certified == "separated" ? "agree" : certified == "undecided" ? "uncertified" : "false_negative"];
      if (certified == "touching" || certified == "overlapping") {
        json input = c;
        input.erase("id"), input.erase("meta");
        meeting_inputs.insert(input.dump());
      }
    }
  }
  const Run r = s.run(kCertcyl + " judge --cases cases.jsonl --answers always_separated.jsonl --out results --name mine");
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  const auto csv = families_csv(s.dir / "results/mine/families.csv");
  for (const auto& [family, outcomes] : expected) {
    const auto& row = csv.at({"ray_cylinder", family});
    BOOST_TEST(count(row, "cases") == 3);
    for (const char* o : {"agree", "false_negative", "uncertified"})
      BOOST_TEST(count(row, o) == (outcomes.count(o) ? outcomes.at(o) : 0), family << " " << o);
    BOOST_TEST(count(row, "false_positive") == 0);
    BOOST_TEST(count(row, "failures") == count(row, "false_negative"));
    BOOST_TEST(r.out.find("ray_cylinder             " + family) != std::string::npos, family);
  }
  // One counterexample per distinct meeting input, the smallest |gap| first, each a query line.
  const auto cx = lines_of(slurp(s.dir / "results/mine/counterexamples.jsonl"));
  BOOST_TEST(cx.size() == meeting_inputs.size());
  double last = 0;
  for (const std::string& l : cx) {
    const json c = json::parse(l);
    BOOST_TEST(c["meta"]["answer"] == "separated");
    BOOST_TEST(c["meta"]["outcome"] == "false_negative");
    BOOST_TEST(c["meta"]["certified"] != "separated");
    const double g = c["meta"]["gap"].is_null() ? INFINITY
                                                : std::fabs(0.5 * c["meta"]["gap"][0].get<double>() + 0.5 * c["meta"]["gap"][1].get<double>());
    BOOST_TEST(g >= last);
    last = g;
  }
  const Run again = s.run(kCertcyl + " query < results/mine/counterexamples.jsonl");
  BOOST_TEST(again.status == 0, again.err);
  // The Wilson interval of 0 failures in n starts at 0 and of n in n ends at 1.
  for (const auto& [key, row] : csv) {
    if (count(row, "failures") == 0 && !row.at("failure_rate_lo95").empty()) BOOST_TEST(std::stod(row.at("failure_rate_lo95")) == 0.0);
    if (count(row, "failures") == count(row, "cases") - count(row, "uncertified") && count(row, "failures") > 0)
      BOOST_TEST(std::stod(row.at("failure_rate_hi95")) == 1.0);
  }
}

// An answers file's intervals: each meeting line case answered with its certified answer and an
// entry parameter d ulps (of max(|t*|, 1)) from the certified one, d chosen per case; the
// median and largest error per family in families.csv are those of the d's, computed here in
// exact rationals from the numbers written. `certcyl query`'s endpoint objects are read too,
// and answers.jsonl carries the intervals back.
BOOST_AUTO_TEST_CASE(answer_intervals_are_scored_like_the_study) {
  Scratch s;
  BOOST_TEST_REQUIRE(
      s.run(kCertcyl + " cases --query segment_cylinder --size 4 --family tangent --family on_wall --family cap_plane > cases.jsonl").status == 0);
  std::map<std::string, std::vector<double>> expected;  // family -> errors in ulps
  const std::vector<long> offsets = {0, 3, -1000, 7};
  std::size_t n = 0;
  {
    std::ofstream answers(s / "mine.jsonl");
    for (const std::string& l : lines_of(slurp(s / "cases.jsonl"))) {
      const json c = json::parse(l);
      const std::string certified = c["meta"]["certified"];
      json a{{"id", c["id"]}, {"answer", certified}};
      if (c["meta"].contains("t_in")) {
        const double t = c["meta"]["t_in"].get<double>();
        const double scale = std::max(std::fabs(t), 1.0), ulp = std::nextafter(scale, INFINITY) - scale;
        const long d = offsets[n++ % offsets.size()];
        const double mine = t + static_cast<double>(d) * ulp;
        // The error as written, exactly: |mine - t| / ulp.
        const Rational e = (Rational(mine) - Rational(t)) / Rational(ulp);
        expected[c["meta"]["family"]].push_back(CGAL::to_double(e < 0 ? Rational(-e) : e));
        // Half the answers as numbers, half as `certcyl query` writes endpoints.
        if (n % 2) a["interval"] = json::array({mine, mine + 1});
        else a["interval"] = json::array({json{{"approx", mine}, {"feature", "wall"}}, json{{"approx", nullptr}}});
      } else {
        BOOST_TEST(!(certified == "touching" || certified == "overlapping"), l);  // a meeting case has t_in
      }
      answers << a.dump() << '\n';
    }
  }
  BOOST_TEST_REQUIRE(n >= 6u);
  const Run r = s.run(kCertcyl + " judge --cases cases.jsonl --answers mine.jsonl --name mine");
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  const auto csv = families_csv(s.dir / "results/mine/families.csv");
  for (auto& [family, errors] : expected) {
    const auto& row = csv.at({"segment_cylinder", family});
    std::sort(errors.begin(), errors.end());
    const std::size_t m = errors.size();
    const double median = m % 2 ? errors[m / 2] : 0.5 * errors[m / 2 - 1] + 0.5 * errors[m / 2];
    BOOST_TEST(count(row, "t_errors") == static_cast<long>(m), family);
    BOOST_TEST(std::stod(row.at("t_error_median_ulps")) == median, family);
    BOOST_TEST(std::stod(row.at("t_error_max_ulps")) == errors.back(), family);
    BOOST_TEST(r.out.find("entry parameter t, segment_cylinder " + family + ": " + std::to_string(m) + " intervals") != std::string::npos, r.out);
  }
  // answers.jsonl keeps the intervals: judged again, the same families.csv.
  const Run again = s.run(kCertcyl + " judge --cases cases.jsonl --answers results/mine/answers.jsonl --name again --label mine");
  BOOST_TEST_REQUIRE(again.status == 0, again.err);
  BOOST_TEST(slurp(s.dir / "results/again/families.csv") == slurp(s.dir / "results/mine/families.csv"));
}

// A cases file is certified again: a line whose meta.certified was changed is an error naming
// the line and both answers; a changed gap or t_in is replaced by the certified one.
BOOST_AUTO_TEST_CASE(a_cases_file_is_certified_again) {
  Scratch s;
  BOOST_TEST_REQUIRE(s.run(kCertcyl + " cases --query line_cylinder --family tangent --size 3 > cases.jsonl").status == 0);
  const auto lines = lines_of(slurp(s / "cases.jsonl"));
  BOOST_TEST_REQUIRE(lines.size() == 3u);
  json second = json::parse(lines[1]);
  const std::string certified = second["meta"]["certified"];
  {
    std::ofstream answers(s / "answers.jsonl");
    for (const std::string& l : lines) answers << json{{"id", json::parse(l)["id"]}, {"answer", "separated"}}.dump() << '\n';
  }
  json changed = second;
  changed["meta"]["certified"] = certified == "separated" ? "overlapping" : "separated";
  std::ofstream(s / "changed.jsonl") << lines[0] << '\n' << changed.dump() << '\n' << lines[2] << '\n';
  const Run r = s.run(kCertcyl + " judge --cases changed.jsonl --answers answers.jsonl");
  BOOST_TEST(r.status == 1);
  BOOST_TEST(r.err.find("changed.jsonl line 2: case '" + second["id"].get<std::string>() + "' says meta.certified " +
                        changed["meta"]["certified"].get<std::string>() + ", its certified answer is " + certified) != std::string::npos,
             r.err);
  // A gap named by another query's quantity is an error naming the field; without the name (a
  // file written before it) the case is read.
  json mislabelled = second;
  mislabelled["meta"]["gap_quantity"] = "log_phi";
  std::ofstream(s / "mislabelled.jsonl") << lines[0] << '\n' << mislabelled.dump() << '\n' << lines[2] << '\n';
  const Run ml = s.run(kCertcyl + " judge --cases mislabelled.jsonl --answers answers.jsonl");
  BOOST_TEST(ml.status == 1);
  BOOST_TEST(ml.err.find(R"(mislabelled.jsonl line 2: meta.gap_quantity: expected "depth_margin" for line_cylinder, got "log_phi")") !=
                 std::string::npos,
             ml.err);
  json unnamed = second;
  unnamed["meta"].erase("gap_quantity");
  std::ofstream(s / "unnamed.jsonl") << lines[0] << '\n' << unnamed.dump() << '\n' << lines[2] << '\n';
  BOOST_TEST(s.run(kCertcyl + " judge --cases unnamed.jsonl --answers answers.jsonl --name unnamed").status == 0);
  // Gap and t_in moved: the counterexamples carry the certified ones.
  json moved = second;
  moved["meta"]["gap"] = json::array({-5.0, -4.0});
  moved["meta"]["t_in"] = 123.0;
  std::ofstream(s / "moved.jsonl") << lines[0] << '\n' << moved.dump() << '\n' << lines[2] << '\n';
  const Run m = s.run(kCertcyl + " judge --cases moved.jsonl --answers answers.jsonl --name moved");
  BOOST_TEST_REQUIRE(m.status == 0, m.err);
  const Run o = s.run(kCertcyl + " judge --cases cases.jsonl --answers answers.jsonl --name original");
  BOOST_TEST_REQUIRE(o.status == 0, o.err);
  BOOST_TEST(slurp(s.dir / "results/moved/counterexamples.jsonl") == slurp(s.dir / "results/original/counterexamples.jsonl"));
  BOOST_TEST(slurp(s.dir / "results/moved/families.csv") == slurp(s.dir / "results/original/families.csv"));
}

BOOST_AUTO_TEST_CASE(report_page_is_self_contained_and_names_the_failures) {
  // index.html: a method always answering "separated" on the tangent lines, under a label with
  // markup in it. The label is shown as text, never as markup; the page loads nothing; every
  // family is a row, shaded exactly where a certified answer meets; one figure per distinct
  // meeting input up to five, each two inline SVG drawings.
  Scratch s;
  BOOST_TEST_REQUIRE(s.run(kCertcyl + " cases --query line_cylinder --family tangent --family uniform --size 4 > cases.jsonl").status == 0);
  std::set<std::string> meeting_inputs;
  std::map<std::string, bool> family_fails;
  {
    std::ofstream answers(s / "answers.jsonl");
    for (const std::string& l : lines_of(slurp(s / "cases.jsonl"))) {
      json c = json::parse(l);
      answers << json{{"id", c["id"]}, {"answer", "separated"}}.dump() << '\n';
      const std::string certified = c["meta"]["certified"];
      const bool meets = certified == "touching" || certified == "overlapping";
      family_fails[c["meta"]["family"]] |= meets;
      c.erase("id"), c.erase("meta");
      if (meets) meeting_inputs.insert(c.dump());
    }
  }
  BOOST_TEST_REQUIRE(family_fails.size() == 2u);
  BOOST_TEST_REQUIRE(family_fails.at("tangent"));
  const Run r = s.run(kCertcyl + " judge --cases cases.jsonl --answers answers.jsonl --name mine --label '<script>x</script> & co'");
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  const fs::path page_file = s.dir / "results/mine/index.html";
  BOOST_TEST(r.out.find("report: results/mine/index.html\n") != std::string::npos, r.out);
  const std::string page = slurp(page_file);
  BOOST_TEST(page.find("<script") == std::string::npos);
  BOOST_TEST(page.find("&lt;script&gt;x&lt;/script&gt; &amp; co") != std::string::npos);
  for (const char* loads : {"src=", "<img", "<link", "url(", "@import", "href=\"http"}) BOOST_TEST(page.find(loads) == std::string::npos, loads);
  for (const auto& [family, fails] : family_fails) {
    const std::string row = std::string(fails ? "<tr class=\"wrong\">" : "<tr>") + "<td>" + family + "</td>";
    BOOST_TEST(page.find(row) != std::string::npos, row);
  }
  const std::size_t figures = std::min<std::size_t>(5, meeting_inputs.size());
  BOOST_TEST(figures > 0u);
  BOOST_TEST(occurrences(page, "<figure class=\"counterexample\"") == figures);
  BOOST_TEST(occurrences(page, "<svg class=\"view\"") == 2 * figures);
  BOOST_TEST(occurrences(page, "<td class=\"answer\">separated</td>") == figures);
}

BOOST_AUTO_TEST_CASE(method_names_with_commas_and_quotes_are_quoted_in_the_csv) {
  // The method's name is free text: a label, or the command of --exec. families.csv quotes it
  // (RFC 4180) so that its columns stay in place.
  Scratch s;
  BOOST_TEST_REQUIRE(s.run(kCertcyl + " cases --query line_cylinder --size tiny > cases.jsonl").status == 0);
  const std::string command = kCertcyl + " query --method robust_double | sed \"s/,/,/\"";
  const std::string label = "mine, \"fast\" v2";
  const Run exec = s.run(kCertcyl + " judge --cases cases.jsonl --name exec --exec '" + command + "'");
  BOOST_TEST_REQUIRE(exec.status == 0, exec.err);
  const Run labelled = s.run(kCertcyl + " judge --cases cases.jsonl --name label --answers results/exec/answers.jsonl --label '" + label + "'");
  BOOST_TEST_REQUIRE(labelled.status == 0, labelled.err);
  for (const auto& [name, method] : {std::pair{"exec", command}, std::pair{"label", label}}) {
    const fs::path file = s.dir / "results" / name / "families.csv";
    const auto records = csv_records(slurp(file));
    BOOST_TEST_REQUIRE(records.size() > 2u);
    BOOST_TEST(records[0][0] == "method");
    for (std::size_t i = 1; i < records.size(); ++i) {
      BOOST_TEST(records[i].size() == records[0].size(), name << " record " << i);
      BOOST_TEST(records[i][0] == method);
      BOOST_TEST(records[i][1] == "line_cylinder");
    }
    const auto csv = families_csv(file);
    BOOST_TEST(count(csv.at({"line_cylinder", "all"}), "cases") == static_cast<long>(lines_of(slurp(s / "cases.jsonl")).size()));
  }
  // The same counts either way: only the method's name differs.
  auto exec_rows = families_csv(s.dir / "results/exec/families.csv"), label_rows = families_csv(s.dir / "results/label/families.csv");
  for (auto* rows : {&exec_rows, &label_rows})
    for (auto& [key, row] : *rows) row.erase("method");
  BOOST_TEST((exec_rows == label_rows));
}

BOOST_AUTO_TEST_CASE(method_names_with_control_characters_are_refused) {
  // A newline or a tab in the method's name would split or shift CSV records for a line-based
  // reader: refused before anything is judged, naming where the name came from.
  Scratch s;
  BOOST_TEST_REQUIRE(s.run(kCertcyl + " cases --query line_cylinder --size tiny > cases.jsonl").status == 0);
  const Run exec = s.run(kCertcyl + " judge --cases cases.jsonl --name exec --exec '" + kCertcyl + " query --method robust_double'");
  BOOST_TEST_REQUIRE(exec.status == 0, exec.err);
  const std::string answers = " --cases cases.jsonl --answers results/exec/answers.jsonl";
  const Run newline = s.run(kCertcyl + " judge" + answers + " --name nl --label \"$(printf 'two\\nlines')\"");
  BOOST_TEST(newline.status == 1);
  BOOST_TEST(newline.err.find("--label: the method's name 'two...' holds the control character 0x0a") != std::string::npos, newline.err);
  const Run tab = s.run(kCertcyl + " judge" + answers + " --name tab --label \"$(printf 'a\\tb')\"");
  BOOST_TEST(tab.status == 1);
  BOOST_TEST(tab.err.find("holds the control character 0x09") != std::string::npos, tab.err);
  fs::copy_file(s.dir / "results/exec/answers.jsonl", s.dir / "mine\tv2.jsonl");
  const Run stem = s.run(kCertcyl + " judge --cases cases.jsonl --name stem --answers \"$(printf 'mine\\tv2.jsonl')\"");
  BOOST_TEST(stem.status == 1);
  BOOST_TEST(stem.err.find("--answers: the method's name 'mine...' holds the control character 0x09 (name it with --label NAME)") !=
                 std::string::npos,
             stem.err);
  for (const char* name : {"nl", "tab", "stem"}) BOOST_TEST(!fs::exists(s.dir / "results" / name), name);
  // The same file judged under a clean label.
  BOOST_TEST(s.run(kCertcyl + " judge --cases cases.jsonl --name ok --label mine --answers \"$(printf 'mine\\tv2.jsonl')\"").status == 0);
}

BOOST_AUTO_TEST_CASE(bad_answers_files_name_the_line) {
  Scratch s;
  BOOST_TEST_REQUIRE(s.run(kCertcyl + " cases --query line_cylinder --family tangent --size 2 > cases.jsonl").status == 0);
  const std::string a = R"({"id":"line_cylinder/tangent/0","answer":"separated"})", b = R"({"id":"line_cylinder/tangent/1","answer":"touching"})";
  const std::vector<std::pair<std::string, std::string>> bad = {
      {a + "\n", "no answer for case 'line_cylinder/tangent/1' (cases line 2)"},
      {a + "\n" + a + "\n" + b + "\n", "answers.jsonl line 2: id 'line_cylinder/tangent/0' answered twice (first on line 1)"},
      {a + "\n" + R"({"id":"line_cylinder/tangent/1","answer":"maybe"})" + "\n", "answers.jsonl line 2: answer: expected separated"},
      {a + "\n" + b + "\n" + R"({"id":"x","answer":"separated"})" + "\n", "answers.jsonl line 3: id 'x' is not a case"},
      {a + "\n{\"id\": \n", "answers.jsonl line 2: not JSON"},
      {R"({"answer":"separated"})" "\n", "answers.jsonl line 1: id: expected"},
      {a + "\n" + R"({"id":"line_cylinder/tangent/1","answer":"touching","interval":[1]})" + "\n",
       "answers.jsonl line 2: interval: expected [t_in, t_out]"},
      {a + "\n" + R"({"id":"line_cylinder/tangent/1","answer":"touching","interval":["0.5",1]})" + "\n",
       "answers.jsonl line 2: interval: expected [t_in, t_out]"},
  };
  for (const auto& [text, message] : bad) {
    std::ofstream(s / "answers.jsonl") << text;
    const Run r = s.run(kCertcyl + " judge --cases cases.jsonl --answers answers.jsonl");
    BOOST_TEST(r.status == 1);
    BOOST_TEST(r.err.find(message) != std::string::npos, r.err);
  }
  std::ofstream(s / "answers.jsonl") << b << "\n" << a << "\n";
  BOOST_TEST(s.run(kCertcyl + " judge --cases cases.jsonl --answers answers.jsonl").status == 0);
  // A duplicate case id is an error of the cases file.
  std::ofstream(s / "twice.jsonl") << slurp(s / "cases.jsonl") << lines_of(slurp(s / "cases.jsonl"))[0] << "\n";
  const Run r = s.run(kCertcyl + " judge --cases twice.jsonl --answers answers.jsonl");
  BOOST_TEST(r.status == 1);
  BOOST_TEST(r.err.find("twice.jsonl line 3: duplicate id 'line_cylinder/tangent/0'") != std::string::npos, r.err);
}

BOOST_AUTO_TEST_CASE(coprocess_gets_the_study_counts) {
  // The study's shene/double method on the study's tiny line_cylinder instances, judged by the
  // study's own code.
  cli::StudyOptions o;
  o.size = "small";
  cli::detail::apply_size(o);
  std::vector<cli::detail::Planned> plan = cli::detail::plan_instances(o);
  std::erase_if(plan, [](const cli::detail::Planned& p) { return p.inst.query != study::Query::line_cylinder; });
  study::Registry registry;
  cli::register_line_methods(registry);
  const auto shene = std::find_if(registry.begin(), registry.end(), [](const study::Method& m) {
    return m.name() == "shene/double" && m.query == study::Query::line_cylinder;
  });
  BOOST_TEST_REQUIRE((shene != registry.end()));
  std::map<std::string, std::map<std::string, long>> study_counts;
  std::map<std::string, std::vector<double>> study_t_errors;  // instances.csv's t_error_ulps, per family
  long failures = 0;
  for (cli::detail::Planned& p : plan) {
    study::certify(p.inst);
    const study::MethodOutput out = cli::detail::run_quiet(*shene, p.inst.x);
    const std::string outcome = cli::detail::outcome_of(out, p.inst);
    ++study_counts[p.inst.family][outcome];
    failures += outcome == "false_positive" || outcome == "false_negative";
    if (!out.intersecting && intersects(out.answer) && intersects(p.inst.certified) && std::isfinite(out.t_in) && std::isfinite(p.inst.t_in))
      study_t_errors[p.inst.family].push_back(cli::detail::t_error_ulps(out.t_in, p.inst.t_in));
  }
  BOOST_TEST(failures > 0);  // the comparison is not only of zeros
  BOOST_TEST(study_t_errors.size() > 5u);

  Scratch s;
  const Run r = s.run(kCertcyl + " judge --exec \"" + kCertcyl + " query --method shene --nt double\" --query line_cylinder --size small");
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  const auto csv = families_csv(s.dir / "results/judge/families.csv");
  for (const auto& [family, outcomes] : study_counts)
    for (const char* o : {"agree", "false_positive", "false_negative", "class_mismatch", "undecided", "error", "invalid", "uncertified"})
      BOOST_TEST(count(csv.at({"line_cylinder", family}), o) == (outcomes.count(o) ? outcomes.at(o) : 0), family << " " << o);
  BOOST_TEST(csv.size() == study_counts.size() + 1);  // and the query's "all" row
  // The entry parameters `certcyl query` writes as "approx" are the study's: the same errors.
  for (const auto& [family, outcomes] : study_counts) {
    const auto& row = csv.at({"line_cylinder", family});
    std::vector<double> t = study_t_errors[family];
    BOOST_TEST(count(row, "t_errors") == static_cast<long>(t.size()), family);
    if (t.empty()) continue;
    std::sort(t.begin(), t.end());
    const double median = t.size() % 2 ? t[t.size() / 2] : 0.5 * t[t.size() / 2 - 1] + 0.5 * t[t.size() / 2];
    BOOST_TEST(std::stod(row.at("t_error_median_ulps")) == median, family);
    BOOST_TEST(std::stod(row.at("t_error_max_ulps")) == t.back(), family);
  }
}

BOOST_AUTO_TEST_CASE(coprocess_failures_keep_what_was_judged) {
  Scratch s;
  BOOST_TEST_REQUIRE(s.run(kCertcyl + " cases --query line_cylinder --size tiny > cases.jsonl").status == 0);
  const std::string answer = kCertcyl + " query --method robust_double";
  const auto judged = [&] {
    long n = 0;
    for (const auto& [key, row] : families_csv(s.dir / "results/judge/families.csv"))
      if (key.second != "all") n += count(row, "cases");
    return n;
  };
  Run r = s.run(kCertcyl + " judge --cases cases.jsonl --exec '" + answer + " | head -n 5'");
  BOOST_TEST(r.status == 1);
  BOOST_TEST(r.err.find("the program exited with status 0 after answering 5 of") != std::string::npos, r.err);
  BOOST_TEST(r.err.find("no answer to line 6") != std::string::npos, r.err);
  BOOST_TEST(judged() == 5);
  r = s.run(kCertcyl + " judge --cases cases.jsonl --exec '" + answer + " | { head -n 2; echo garbage; }'");
  BOOST_TEST(r.status == 1);
  BOOST_TEST(r.err.find("line 3 of the program's output") != std::string::npos, r.err);
  BOOST_TEST(r.err.find("garbage") != std::string::npos, r.err);
  BOOST_TEST(judged() == 2);
  r = s.run(kCertcyl + " judge --cases cases.jsonl --exec 'head -n 1 > /dev/null; kill -SEGV $$'");
  BOOST_TEST(r.status == 1);
  BOOST_TEST(r.err.find("killed by signal 11") != std::string::npos, r.err);
  BOOST_TEST(judged() == 0);
  // Answers in another order are not answers to the lines in turn.
  r = s.run(kCertcyl + " judge --cases cases.jsonl --exec '" + answer + " | tac'");
  BOOST_TEST(r.status == 1);
  BOOST_TEST(r.err.find("answers another case") != std::string::npos, r.err);
}

BOOST_AUTO_TEST_CASE(speed_csv_holds_the_mean_time_per_query) {
  // A program that sleeps 1 s before its first answers, then answers at once: the exchange's
  // time per query is a mean (the 1 s spread over the n cases, so at least 1e9 / n ns on every
  // row), never the median of the per-query times, which would be a few microseconds, and the
  // column says so.
  Scratch s;
  BOOST_TEST_REQUIRE(s.run(kCertcyl + " cases --query line_cylinder --size tiny > cases.jsonl").status == 0);
  const double n = static_cast<double>(lines_of(slurp(s / "cases.jsonl")).size());
  BOOST_TEST_REQUIRE(n > 2);
  // Only its first run sleeps (the program runs again for the failure maps and the hunt).
  const std::string program = "if [ ! -e slept ]; then touch slept; sleep 1; fi; exec " + kCertcyl + " query";
  const Run r = s.run(kCertcyl + " judge --cases cases.jsonl --exec '" + program + "'");
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  const auto rows = csv_records(slurp(s.dir / "results/judge/speed.csv"));
  BOOST_TEST_REQUIRE(rows.size() == 2u);  // the header and line_cylinder's row
  BOOST_TEST(rows[0].back() == "mean_ns");
  BOOST_TEST((std::find(rows[0].begin(), rows[0].end(), "median_ns") == rows[0].end()));
  BOOST_TEST(rows[1][0] == "line_cylinder");
  BOOST_TEST(rows[1][2] == "judged");
  BOOST_TEST(std::stod(rows[1].back()) >= 1e9 / n, rows[1].back());
}

BOOST_AUTO_TEST_CASE(example_plugin_fails_where_a_double_test_fails) {
  Scratch s;
  const Run r = s.run(kCertcyl + " judge --plugin " CERTCYL_PLUGIN_DOUBLE " --size tiny");
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  BOOST_TEST(r.out.find("certcyl judge: plugin_double") != std::string::npos, r.out);
  const auto csv = families_csv(s.dir / "results/judge/families.csv");
  std::set<std::string> queries;
  for (const auto& [key, row] : csv) queries.insert(key.first);
  // Every query it exports, and no other.
  BOOST_TEST((queries == std::set<std::string>{"cylinder_cylinder", "line_cylinder", "ray_cylinder", "segment_cylinder"}));
  // The naive line test fails on the near-tangent families, not far from any degeneracy.
  long near_tangent = 0;
  for (const char* q : {"line_cylinder", "ray_cylinder", "segment_cylinder"}) {
    for (const char* f : {"tangent", "tangent_rotated", "near_parallel", "rim", "rim_rotated"}) near_tangent += count(csv.at({q, f}), "failures");
    BOOST_TEST(count(csv.at({q, "uniform"}), "failures") == 0);
  }
  BOOST_TEST(near_tangent > 0);
  // Its t[2] is read: the double test's entry parameter is within an ulp of the certified one on
  // most meeting cases (on_wall: exactly; a t read from another case, or not at all, would not
  // be), though not near tangency.
  for (const char* q : {"line_cylinder", "ray_cylinder", "segment_cylinder"}) {
    const auto& all = csv.at({q, "all"});
    BOOST_TEST(count(all, "t_errors") >= 10, q);
    if (count(all, "t_errors") > 0) BOOST_TEST(std::stod(all.at("t_error_median_ulps")) <= 1.0, q);
    const auto& on_wall = csv.at({q, "on_wall"});
    if (count(on_wall, "t_errors") > 0) BOOST_TEST(std::stod(on_wall.at("t_error_max_ulps")) == 0.0, q);
  }
  // The capsule test meets the cylinders near the caps.
  BOOST_TEST(count(csv.at({"cylinder_cylinder", "c_cap_cap"}), "false_positive") + count(csv.at({"cylinder_cylinder", "c_rim_cap"}), "false_positive") > 0);
  // speed.csv: one row per query it exports in the study's summary.csv columns up to the timing,
  // kind judged, n its certified cases, and a per-call time that is positive and below 1 ms (a
  // double test of a few dozen operations), the same on every row.
  const auto speed = csv_records(slurp(s.dir / "results/judge/speed.csv"));
  BOOST_TEST_REQUIRE(speed.size() == 1u + queries.size());
  BOOST_TEST((speed[0] == std::vector<std::string>{"query", "method", "kind", "n", "false_positive", "false_negative", "class_mismatch",
                                                   "undecided", "error", "invalid", "disagreement_rate", "mean_ns"}));
  for (std::size_t i = 1; i < speed.size(); ++i) {
    const auto& row = speed[i];
    BOOST_TEST_REQUIRE(row.size() == speed[0].size());
    BOOST_TEST(queries.count(row[0]) == 1u, row[0]);
    BOOST_TEST(row[1] == "plugin_double");
    BOOST_TEST(row[2] == "judged");
    const auto& all = csv.at({row[0], "all"});
    BOOST_TEST(std::stol(row[3]) == count(all, "cases") - count(all, "uncertified"), row[0]);
    BOOST_TEST(std::stol(row[4]) == count(all, "false_positive"), row[0]);
    BOOST_TEST(std::stol(row[5]) == count(all, "false_negative"), row[0]);
    const double ns = std::stod(row.back());
    BOOST_TEST(ns > 0.0, row[0]);
    BOOST_TEST(ns < 1e6, row[0]);
    BOOST_TEST(row.back() == speed[1].back());
  }
  BOOST_TEST(r.out.find("speed: ") != std::string::npos, r.out);
  // Each counterexample's family is counted as failing, in the CSV and in the printed table.
  const auto cx = lines_of(slurp(s.dir / "results/judge/counterexamples.jsonl"));
  BOOST_TEST(!cx.empty());
  for (const std::string& l : cx) {
    const json c = json::parse(l);
    const auto& row = csv.at({c["query"].get<std::string>(), c["meta"]["family"].get<std::string>()});
    BOOST_TEST(count(row, "failures") > 0);
    const std::string query = c["query"], family = c["meta"]["family"];
    const auto table = lines_of(r.out);
    BOOST_TEST(std::any_of(table.begin(), table.end(), [&](const std::string& t) {
      return t.rfind(query + " ", 0) == 0 && t.find(" " + family + " ") != std::string::npos;
    }), query << " " << family);
  }
}

BOOST_AUTO_TEST_CASE(plugin_crash_keeps_earlier_answers) {
  Scratch s;
  const Run r = s.run(kCertcyl + " judge --plugin " CERTCYL_PLUGIN_CRASH " --query line_cylinder --size tiny");
  BOOST_TEST(r.status == 1);
  BOOST_TEST(r.err.find("plugin crashed on line 5 (signal 11") != std::string::npos, r.err);
  long judged = 0, errors = 0;
  for (const auto& [key, row] : families_csv(s.dir / "results/judge/families.csv"))
    if (key.second != "all") judged += count(row, "cases"), errors += count(row, "error");
  BOOST_TEST(judged == 4);
  BOOST_TEST(errors == 1);  // the negative return, counted
  BOOST_TEST(slurp(s.dir / "results/judge/summary.txt").find(", 4 of ") != std::string::npos);
  // A plugin exporting no query of the cases is an error.
  const Run none = s.run(kCertcyl + " judge --plugin " CERTCYL_PLUGIN_CRASH " --query cylinder_cylinder --size tiny");
  BOOST_TEST(none.status == 1);
  BOOST_TEST(none.err.find("exports none of the cases' queries") != std::string::npos, none.err);
  // Line numbers are those of the cases file when there is one.
  BOOST_TEST_REQUIRE(s.run(kCertcyl + " cases --query line_cylinder --family rim --size 6 > cases.jsonl").status == 0);
  std::ofstream(s / "cases.jsonl", std::ios::app) << "\n\n";
  const std::string rim = slurp(s / "cases.jsonl");
  std::ofstream(s / "spaced.jsonl") << "\n" << rim;
  const Run spaced = s.run(kCertcyl + " judge --plugin " CERTCYL_PLUGIN_CRASH " --cases spaced.jsonl");
  BOOST_TEST(spaced.err.find("plugin crashed on line 6 (signal 11") != std::string::npos, spaced.err);
  BOOST_TEST(spaced.err.find("case 'line_cylinder/rim/4'") != std::string::npos, spaced.err);
}

BOOST_AUTO_TEST_CASE(plugin_hang_and_bad_return_keep_earlier_answers) {
  // The answers are read from memory shared with the plugin's child: those given before a call
  // that hangs, or before a return value that is no answer, are kept.
  Scratch s;
  const auto start = std::chrono::steady_clock::now();
  const Run hung = s.run(kCertcyl + " judge --plugin " CERTCYL_PLUGIN_CRASH " --query ray_cylinder --size tiny --timeout 1 --name hung");
  BOOST_TEST(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < 30);
  BOOST_TEST(hung.status == 1);
  BOOST_TEST(hung.err.find("plugin hung on line 3, case 'ray_cylinder/") != std::string::npos, hung.err);
  BOOST_TEST(hung.err.find("gave no answer within 1 s (--timeout) and was killed") != std::string::npos, hung.err);
  BOOST_TEST(lines_of(slurp(s.dir / "results/hung/answers.jsonl")).size() == 2u);
  const Run bad = s.run(kCertcyl + " judge --plugin " CERTCYL_PLUGIN_CRASH " --query segment_cylinder --size tiny --name bad");
  BOOST_TEST(bad.status == 1);
  BOOST_TEST(bad.err.find("the plugin returned 7 on line 2, case 'segment_cylinder/") != std::string::npos, bad.err);
  BOOST_TEST(lines_of(slurp(s.dir / "results/bad/answers.jsonl")).size() == 1u);
}

BOOST_AUTO_TEST_CASE(coprocess_reads_the_cases_query_lines) {
  // What the program reads is each case's line without "meta", byte for byte as the cases file
  // writes it, for every query.
  Scratch s;
  for (const study::Query query : study::kQueries) {
    const std::string q(study::to_string(query));
    BOOST_TEST_REQUIRE(s.run(kCertcyl + " cases --query " + q + " --size tiny > cases.jsonl").status == 0);
    // The program runs again for the failure maps and the hunt: its first run reads the cases.
    std::filesystem::remove(s / "read.jsonl");
    const Run r = s.run(kCertcyl + " judge --cases cases.jsonl --exec 'tee -a read.jsonl | " + kCertcyl + " query'");
    BOOST_TEST_REQUIRE(r.status == 0, r.err);
    const auto cases = lines_of(slurp(s / "cases.jsonl")), read = lines_of(slurp(s / "read.jsonl"));
    BOOST_TEST_REQUIRE(read.size() >= cases.size());
    for (std::size_t i = 0; i < cases.size(); ++i) {
      nlohmann::ordered_json c = nlohmann::ordered_json::parse(cases[i]);
      c.erase("meta");
      BOOST_TEST(read[i] == c.dump(), q << " line " << i + 1);
    }
  }
}

BOOST_AUTO_TEST_CASE(shards_concatenated_judge_as_one_run) {
  // Two shards of one cases file: each holds the cases whose index is its own modulo 2, is
  // renamed into place when finished, and their answers.jsonl together, judged as an answers
  // file, give the unsharded run's families.csv.
  Scratch s;
  BOOST_TEST_REQUIRE(s.run(kCertcyl + " cases --query line_cylinder --size tiny > cases.jsonl").status == 0);
  const auto cases = lines_of(slurp(s / "cases.jsonl"));
  BOOST_TEST_REQUIRE(cases.size() > 4);
  const std::string method = " --exec '" + kCertcyl + " query --method shene --nt double' --label shene";
  BOOST_TEST_REQUIRE(s.run(kCertcyl + " judge --cases cases.jsonl" + method + " --name whole").status == 0);
  for (const char* k : {"0", "1"}) {
    const Run r = s.run(kCertcyl + " judge --cases cases.jsonl" + method + " --name sharded --shard " + k + "/2");
    BOOST_TEST_REQUIRE(r.status == 0, r.err);
    // The printed report is where the page is once the shard is complete (not its temporary name).
    const std::string page = "results/sharded/shard-" + std::string(k) + "-of-2/index.html";
    BOOST_TEST(r.out.find("report: " + page + "\n") != std::string::npos, r.out);
    BOOST_TEST(fs::exists(s.dir / page));
  }
  std::string merged;
  for (int k = 0; k < 2; ++k) {
    const fs::path shard = s.dir / "results/sharded" / ("shard-" + std::to_string(k) + "-of-2");
    BOOST_TEST(!fs::exists(fs::path(shard).concat(".partial")));
    const auto answers = lines_of(slurp(shard / "answers.jsonl"));
    BOOST_TEST(answers.size() == (cases.size() + 1 - static_cast<std::size_t>(k)) / 2);
    for (std::size_t i = 0; i < answers.size(); ++i)
      BOOST_TEST(json::parse(answers[i])["id"] == json::parse(cases[2 * i + static_cast<std::size_t>(k)])["id"]);
    merged += slurp(shard / "answers.jsonl");
  }
  std::ofstream(s / "merged.jsonl") << merged;
  const Run m = s.run(kCertcyl + " judge --cases cases.jsonl --answers merged.jsonl --label shene --name merged");
  BOOST_TEST_REQUIRE(m.status == 0, m.err);
  BOOST_TEST(slurp(s.dir / "results/merged/families.csv") == slurp(s.dir / "results/whole/families.csv"));
  BOOST_TEST(slurp(s.dir / "results/merged/summary.txt").rfind("certcyl judge: shene, ", 0) == 0);
  // A shard index outside the count is refused.
  const Run bad = s.run(kCertcyl + " judge --cases cases.jsonl" + method + " --shard 2/2");
  BOOST_TEST(bad.status == 1);
  BOOST_TEST(!bad.err.empty());
}

BOOST_AUTO_TEST_CASE(a_shard_whose_method_fails_stays_partial) {
  Scratch s;
  BOOST_TEST_REQUIRE(s.run(kCertcyl + " cases --query line_cylinder --size tiny > cases.jsonl").status == 0);
  const Run r = s.run(kCertcyl + " judge --cases cases.jsonl --exec '" + kCertcyl +
                      " query --method robust_double | head -n 3' --name sharded --shard 1/2");
  BOOST_TEST(r.status == 1);
  BOOST_TEST(r.err.find("the shard is not finished") != std::string::npos, r.err);
  BOOST_TEST(fs::exists(s.dir / "results/sharded/shard-1-of-2.partial/answers.jsonl"));
  BOOST_TEST(lines_of(slurp(s.dir / "results/sharded/shard-1-of-2.partial/answers.jsonl")).size() == 3u);
  BOOST_TEST(!fs::exists(s.dir / "results/sharded/shard-1-of-2"));
}

BOOST_AUTO_TEST_CASE(a_program_that_stops_answering_is_killed_after_the_timeout) {
  Scratch s;
  BOOST_TEST_REQUIRE(s.run(kCertcyl + " cases --query line_cylinder --size tiny > cases.jsonl").status == 0);
  // Answers two lines, then holds its output open without answering.
  const std::string program = kCertcyl + " query --method robust_double --line-buffered | { head -n 2; sleep 60; }";
  const auto start = std::chrono::steady_clock::now();
  const Run r = s.run(kCertcyl + " judge --cases cases.jsonl --timeout 1 --exec '" + program + "'");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  BOOST_TEST(r.status == 1);
  BOOST_TEST(r.err.find("gave no answer to line 3") != std::string::npos, r.err);
  BOOST_TEST(r.err.find("within 1 s (--timeout) and was killed, after answering 2 of") != std::string::npos, r.err);
  BOOST_TEST(seconds < 30);  // not the program's 60 s: its process group was killed
  BOOST_TEST(lines_of(slurp(s.dir / "results/judge/answers.jsonl")).size() == 2u);
}

BOOST_AUTO_TEST_CASE(query_answers_a_coprocess_line_by_line) {
  // A line written while the input stays open is answered before the next one comes.
  Scratch s;
  const std::string line =
      R"({"id":1,"query":"point_cylinder","point":[0,0,1],"cylinder":{"p0":[0,0,0],"p1":[0,0,2],"radius":1}})";
  const Run r = s.run("{ echo '" + line + "'; sleep 6; } | timeout 2 " + kCertcyl + " query --line-buffered --brief");
  BOOST_TEST(r.status == 124);  // ended by timeout, the input still open
  // The gap, the point's depth min(1 - q, s, 1 - s): q = 0 on the axis, s = 1/2 at half height.
  BOOST_TEST(r.out == "{\"id\":1,\"answer\":\"overlapping\",\"gap\":[0.5,0.5],\"gap_quantity\":\"depth_margin\"}\n");
}
