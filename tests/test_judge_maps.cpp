// The failure maps of `certcyl judge` (src/judge_maps.cpp, the study's grids of
// src/study_maps.cpp): the example plugin's maps are written as the study writes its maps, one
// cell per input, and record its failures near tangency where the CSV's certified column says
// its answer is wrong; a method that gives the certified answer has no failed cell and the same
// codes; a method that fails on the way keeps the cells answered before and after the failure;
// an answers file says the maps need a plugin or a program.
#define BOOST_TEST_MODULE judge_maps
#include <boost/test/unit_test.hpp>

#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <sys/wait.h>
#include <unistd.h>

#include "judge_internal.hpp"
#include "judge_test_support.hpp"
#include "study_internal.hpp"

using namespace certcyl;
using namespace certcyl::cli::judging;
using json = nlohmann::json;
namespace fs = std::filesystem;
using judge_test::lines_of;
using judge_test::Run;
using judge_test::Scratch;
using judge_test::slurp;

namespace {

std::vector<std::string> fields(const std::string& line) { return cli::detail::split(line, ','); }

bool meets(char code) { return code == 't' || code == 'o' || code == 'i'; }

// The wrong cells of a map's CSV counted from its columns: the method's code against the
// certified one, where the certified answer is decided.
std::size_t wrong_cells(const std::vector<std::string>& csv) {
  std::size_t wrong = 0;
  for (std::size_t r = 1; r < csv.size(); ++r) {
    const auto f = fields(csv[r]);
    const char certified = f.at(4).at(0), method = f.at(7).at(0);
    if (certified == 'u' || method == '.' || method == 'u' || method == 'e') continue;
    wrong += meets(certified) != meets(method);
  }
  return wrong;
}

// A source answering every case with its certified answer, or with `fixed`.
AnswerSource answering(const std::string& fixed = "") {
  return [fixed](const std::vector<cli::Case>& cases) {
    Answers a;
    for (const cli::Case& c : cases) a.answers.push_back(answered(fixed.empty() ? std::string(to_string(c.certified)) : fixed));
    return a;
  };
}

}  // namespace

BOOST_AUTO_TEST_CASE(example_plugin_maps_record_its_failures_near_tangency) {
  Scratch s;
  const Run r = s.run(std::string(CERTCYL_BIN) + " judge --plugin " CERTCYL_PLUGIN_DOUBLE " --size tiny");
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  const fs::path folder = s.dir / "results/judge";
  // One map per degeneracy of the queries it exports (no triangle, no elliptic cylinder).
  const std::set<std::string> expected{"tangent_line", "rim_line", "ray_ends_on_wall", "segment_ends_on_wall", "touching_cylinders"};
  std::set<std::string> written;
  for (const auto& e : fs::directory_iterator(folder / "failure_maps"))
    if (e.path().extension() == ".csv") written.insert(e.path().stem().string());
  BOOST_TEST((written == expected));
  const auto summary = lines_of(slurp(folder / "failure_maps.csv"));
  BOOST_TEST_REQUIRE(summary.size() == expected.size() + 1);
  BOOST_TEST(summary[0] == "map,query,cells,evaluated,certified,false_positive,false_negative,wrong");
  std::map<std::string, std::size_t> wrong;
  for (std::size_t r = 1; r < summary.size(); ++r) {
    const auto f = fields(summary[r]);
    const std::string name = f.at(0);
    const auto csv = lines_of(slurp(folder / "failure_maps" / (name + ".csv")));
    // 16 x 16 cells at --size tiny, every one answered, the study's columns then the method's.
    BOOST_TEST(csv.size() == 1u + 16 * 16, name);
    BOOST_TEST(csv.at(0) == "i,j,d0_ulps,d1_ulps,certified,gap_lo,gap_hi,plugin_double", name);
    BOOST_TEST(f.at(2) == "256");
    BOOST_TEST(f.at(3) == "256");
    // The counts are those of the cells.
    BOOST_TEST(std::stoul(f.at(7)) == wrong_cells(csv), name);
    wrong[name] = std::stoul(f.at(7));
    const json meta = json::parse(slurp(folder / "failure_maps" / (name + ".json")));
    BOOST_TEST(meta["cells"] == 16);
    BOOST_TEST(meta["name"] == name);
  }
  // The textbook discriminant is wrong around the tangent line, and the capsule test around
  // cylinders touching wall to wall says "intersecting" where they only touch (not wrong) but
  // the line maps have false answers.
  BOOST_TEST(wrong["tangent_line"] + wrong["rim_line"] + wrong["ray_ends_on_wall"] + wrong["segment_ends_on_wall"] > 0u);
  // The page shows each map.
  const std::string page = slurp(folder / "index.html");
  std::size_t figures = 0;
  for (std::size_t p = 0; (p = page.find("<figure class=\"failure-map\"", p)) != std::string::npos; ++p) ++figures;
  BOOST_TEST(figures == expected.size());
  BOOST_TEST(slurp(s.dir / "out.txt").find("failure map tangent_line (line_cylinder): ") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(a_method_giving_the_certified_answer_fails_on_no_cell) {
  Scratch s;
  const std::vector<study::Query> queries{study::Query::line_cylinder, study::Query::cylinder_cylinder};
  const MapsResult right = judge_failure_maps(s.dir / "right", "exact", queries, answering(), 9, 1, 1, 2);
  BOOST_TEST_REQUIRE(right.maps.size() == 3u);  // tangent_line, rim_line, touching_cylinders
  for (const MapJudgement& m : right.maps) {
    BOOST_TEST(m.false_positive + m.false_negative == 0u, m.name);
    BOOST_TEST(m.evaluated == 81u);
    BOOST_TEST(m.codes == m.certified, m.name);
    const auto csv = lines_of(slurp(s.dir / "right/failure_maps" / (m.name + ".csv")));
    BOOST_TEST_REQUIRE(csv.size() == 82u);
    for (std::size_t r = 1; r < csv.size(); ++r) BOOST_TEST(fields(csv[r]).at(7) == fields(csv[r]).at(4));
  }
  // A method that always says separated fails on every cell certified to meet.
  const MapsResult wrong = judge_failure_maps(s.dir / "wrong", "never", queries, answering("separated"), 9, 1, 1, 2);
  std::size_t meeting = 0, failures = 0;
  for (std::size_t k = 0; k < wrong.maps.size(); ++k) {
    for (char c : right.maps[k].certified) meeting += meets(c);
    failures += wrong.maps[k].false_negative;
    BOOST_TEST(wrong.maps[k].false_positive == 0u);
  }
  BOOST_TEST(meeting > 0u);
  BOOST_TEST(failures == meeting);
}

BOOST_AUTO_TEST_CASE(a_failure_on_the_way_keeps_the_other_cells) {
  Scratch s;
  // Answers the first 10 cases it is given, then fails (as a crashed plugin's run ends).
  int calls = 0;
  const AnswerSource crashing = [&](const std::vector<cli::Case>& cases) {
    ++calls;
    Answers a;
    a.answers.resize(cases.size());
    for (std::size_t i = 0; i < cases.size() && i < 10; ++i) a.answers[i] = answered(std::string(to_string(cases[i].certified)));
    if (cases.size() > 10) a.failure = "plugin crashed on " + cases[10].id;
    return a;
  };
  const MapsResult r = judge_failure_maps(s.dir, "crashing", {study::Query::line_cylinder}, crashing, 9, 1, 1, 2);
  BOOST_TEST_REQUIRE(r.maps.size() == 2u);
  // Four runs of 10 answers, each followed by the cell it failed on (an error), then no more.
  BOOST_TEST(calls == 4);
  BOOST_TEST(r.failed_cells == 4u);
  const std::string codes = r.maps[0].codes + r.maps[1].codes;
  BOOST_TEST(codes.substr(0, 10) == (r.maps[0].certified + r.maps[1].certified).substr(0, 10));
  for (std::size_t k : {10u, 21u, 32u, 43u}) BOOST_TEST(codes[k] == 'e', k);
  BOOST_TEST(codes.find_first_not_of('.', 44) == std::string::npos);
  BOOST_TEST(r.maps[0].evaluated + r.maps[1].evaluated == 44u);
  BOOST_TEST(r.failure.find("not evaluated") != std::string::npos, r.failure);
  // The maps are written with what was gathered.
  BOOST_TEST(lines_of(slurp(s.dir / "failure_maps/tangent_line.csv")).size() == 82u);
}

BOOST_AUTO_TEST_CASE(an_answers_file_has_no_maps) {
  Scratch s;
  BOOST_TEST_REQUIRE(s.run(std::string(CERTCYL_BIN) + " cases --query line_cylinder --size tiny > cases.jsonl").status == 0);
  BOOST_TEST_REQUIRE(s.run(std::string(CERTCYL_BIN) + " query < cases.jsonl > answers.jsonl").status == 0);
  BOOST_TEST_REQUIRE(s.run(std::string(CERTCYL_BIN) + " judge --answers answers.jsonl --cases cases.jsonl").status == 0);
  BOOST_TEST(!fs::exists(s.dir / "results/judge/failure_maps"));
  BOOST_TEST(slurp(s.dir / "out.txt").find("failure maps: they need --plugin or --exec") != std::string::npos, slurp(s.dir / "out.txt"));
}
