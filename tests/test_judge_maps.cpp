// The failure maps and the hunt of `certcyl judge` (src/judge_maps.cpp, the study's grids of
// src/study_maps.cpp): the example plugin's maps are written as the study writes its maps, one
// cell per input, record its failures near tangency where the CSV's certified column says its
// answer is wrong, and are drawn on the page cell for cell; a method that gives the certified
// answer has no failed cell and the same codes; a method that fails on the way keeps the cells
// answered before and after the failure, and a real plugin that crashes inside a map keeps the
// map; the hunt finds an input where the example plugin's answer (called here) is not the
// certified one (`certcyl query`'s); --map-cells, --map-step and --hunt-evaluations size them and
// are checked; an answers file says the maps need a plugin or a program.
#define BOOST_TEST_MODULE judge_maps
#include <boost/test/unit_test.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include <dlfcn.h>

#include <sys/wait.h>
#include <unistd.h>

#include "judge_internal.hpp"
#include "judge_test_support.hpp"
#include "study_internal.hpp"

using namespace certcyl;
using namespace certcyl::cli::judging;
using namespace judge_test;
using json = nlohmann::json;

namespace {

std::vector<std::string> fields(const std::string& line) { return cli::detail::split_csv(line); }

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

// The fills of an <svg>'s rects, in order.
std::vector<std::string> fills(const std::string& svg) {
  std::vector<std::string> v;
  const std::regex fill("<rect [^>]*fill=\"([^\"]*)\"");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), fill); it != std::sregex_iterator(); ++it) v.push_back((*it)[1]);
  return v;
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
  // The page draws each map of failure_maps.csv as two inline SVG panels of 16 x 16 cells (and
  // the centre cell's outline), cell (i, j) the CSV's row 16 i + j: on the left in the colour its
  // key gives the certified answer, on the right the method's answer's, or magenta where wrong.
  const std::string page = slurp(folder / "index.html");
  BOOST_TEST(occurrences(page, "<figure class=\"failure-map\"") == expected.size());
  std::map<char, std::string> colour;  // answer code -> the colour the maps' key gives it
  const std::size_t maps_at = page.find("<h2 id=\"maps\">");
  BOOST_TEST_REQUIRE(maps_at != std::string::npos);
  const std::string legend = page.substr(maps_at, page.find("<figure class=\"failure-map\"", maps_at) - maps_at);
  const std::regex key("<span class=\"key\" style=\"background:([^\"]*)\"></span> ([a-z ()]+?)[,.]");
  for (auto it = std::sregex_iterator(legend.begin(), legend.end(), key); it != std::sregex_iterator(); ++it) {
    const std::string word = (*it)[2];
    colour[word.rfind("wrong", 0) == 0 ? 'w' : word.at(0)] = (*it)[1];
  }
  for (const char c : {'s', 't', 'o', 'i', 'u', 'e', 'w'}) BOOST_TEST_REQUIRE(colour.count(c) == 1u, c);
  for (const auto& [name, n] : wrong) {
    const std::size_t at = page.find("<figure class=\"failure-map\" id=\"map-" + name + "\">");
    BOOST_TEST_REQUIRE(at != std::string::npos, name);
    const std::string figure = page.substr(at, page.find("</figure>", at) - at);
    BOOST_TEST_REQUIRE(occurrences(figure, "<svg ") == 2u, name);
    const std::size_t second = figure.find("<svg ", figure.find("<svg ") + 1);
    const std::vector<std::string> left = fills(figure.substr(0, second)), right = fills(figure.substr(second));
    BOOST_TEST_REQUIRE(left.size() == 16u * 16 + 1, name);
    BOOST_TEST_REQUIRE(right.size() == 16u * 16 + 1, name);
    BOOST_TEST(left.back() == "none");  // the centre's outline
    const auto csv = lines_of(slurp(folder / "failure_maps" / (name + ".csv")));
    std::size_t magenta = 0;
    for (std::size_t r = 1; r < csv.size(); ++r) {
      const auto f = fields(csv[r]);
      const std::size_t cell = std::stoul(f.at(0)) * 16 + std::stoul(f.at(1));
      BOOST_TEST_REQUIRE(cell == r - 1, name);
      const char certified = f.at(4).at(0), method = f.at(7).at(0);
      BOOST_TEST(left[cell] == colour[certified], name << " cell " << cell);
      const bool is_wrong = certified != 'u' && method != 'u' && method != 'e' && meets(certified) != meets(method);
      BOOST_TEST(right[cell] == (is_wrong ? colour['w'] : colour[method]), name << " cell " << cell);
      magenta += right[cell] == colour['w'];
    }
    BOOST_TEST(magenta == n, name);
    BOOST_TEST(figure.find("<b>" + std::to_string(n) + " wrong</b> of 256 cells evaluated") != std::string::npos, name);
  }
  BOOST_TEST(slurp(s.dir / "out.txt").find("failure map tangent_line (line_cylinder): ") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(example_plugin_hunt_finds_a_wrong_answer) {
  // hunt.csv: the study's columns (experiments/STUDY_FILES.md), one row for the one query
  // judged, a wrong answer found near tangency by the textbook discriminant. The row is checked
  // against the plugin itself, called here on the row's input, and against `certcyl query`'s
  // certified answer and gap on the same input.
  Scratch s;
  const Run r = s.run(std::string(CERTCYL_BIN) + " judge --plugin " CERTCYL_PLUGIN_DOUBLE " --query line_cylinder --size small");
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  const auto hunt = lines_of(slurp(s.dir / "results/judge/hunt.csv"));
  BOOST_TEST_REQUIRE(hunt.size() == 2u);
  BOOST_TEST(hunt[0] == "method,query,start_family,evaluations,found,answer,certified_answer,outcome,gap_lo,gap_hi,input_hex");
  const auto f = fields(hunt[1]);
  BOOST_TEST_REQUIRE(f.size() == 11u);
  BOOST_TEST(f[0] == "plugin_double");
  BOOST_TEST(f[1] == "line_cylinder");
  BOOST_TEST(std::stol(f[3]) > 0);
  BOOST_TEST(std::stol(f[3]) <= 150);  // --size small's budget
  BOOST_TEST_REQUIRE(f[4] == "1");
  BOOST_TEST(f[5] != f[6]);
  BOOST_TEST((f[7] == "false_positive" || f[7] == "false_negative"));
  BOOST_TEST((f[7] == "false_positive") == (f[6] == "separated"));
  // The input: origin, direction, p0, p1, radius (src/study/instance.hpp).
  std::vector<double> x;
  std::vector<std::string> hex;
  std::istringstream in(f[10]);
  for (std::string v; in >> v;) hex.push_back(v), x.push_back(std::strtod(v.c_str(), nullptr));
  BOOST_TEST_REQUIRE(x.size() == 13u);
  // The plugin's answer there, by a direct call.
  void* so = ::dlopen(CERTCYL_PLUGIN_DOUBLE, RTLD_NOW | RTLD_LOCAL);
  BOOST_TEST_REQUIRE((so != nullptr));
  using LineFn = int (*)(const double*, const double*, const double*, double*);
  const auto line = reinterpret_cast<LineFn>(::dlsym(so, "certcyl_plugin_line_cylinder"));
  BOOST_TEST_REQUIRE((line != nullptr));
  double t[2] = {0, 0};
  const int code = line(x.data(), x.data() + 3, x.data() + 6, t);
  ::dlclose(so);
  const char* const words[] = {"separated", "touching", "overlapping", "intersecting", "undecided"};
  BOOST_TEST_REQUIRE((code >= 0 && code <= 4));
  BOOST_TEST(f[5] == words[code]);
  // The certified answer and gap there, the hexfloats read exactly.
  auto point = [&](std::size_t k) { return json::array({hex[k], hex[k + 1], hex[k + 2]}); };
  const json query{{"id", 1},
                   {"query", "line_cylinder"},
                   {"line", {{"origin", point(0)}, {"direction", point(3)}}},
                   {"cylinder", {{"p0", point(6)}, {"p1", point(9)}, {"radius", hex[12]}}}};
  std::ofstream(s / "worst.jsonl") << query.dump() << '\n';
  const Run certified = s.run(std::string(CERTCYL_BIN) + " query --brief < worst.jsonl");
  BOOST_TEST_REQUIRE(certified.status == 0, certified.err);
  const json a = json::parse(certified.out);
  BOOST_TEST(a["answer"] == f[6]);
  BOOST_TEST_REQUIRE(a["gap"].is_array());
  BOOST_TEST(a["gap"][0].get<double>() <= std::stod(f[9]));
  BOOST_TEST(std::stod(f[8]) <= a["gap"][1].get<double>());
  // The table and the page say it.
  BOOST_TEST(r.out.find("hunt: line_cylinder: " + f[5] + " where the certified answer is " + f[6]) != std::string::npos, r.out);
  BOOST_TEST(occurrences(slurp(s.dir / "results/judge/index.html"), "<li class=\"hunt\">") == 1u);
}

BOOST_AUTO_TEST_CASE(a_label_with_commas_and_quotes_stays_one_csv_field) {
  // A judged method's name is free text: hunt.csv, speed.csv and families.csv quote it as
  // RFC 4180 does, so every row keeps its columns (an unquoted comma shifted hunt.csv's by one).
  Scratch s;
  const std::string label = "engine, \"fast\" path";
  const Run r = s.run(std::string(CERTCYL_BIN) + " judge --plugin " CERTCYL_PLUGIN_DOUBLE " --query line_cylinder --size small --label '" +
                      label + "'");
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  const auto hunt = lines_of(slurp(s.dir / "results/judge/hunt.csv"));
  BOOST_TEST_REQUIRE(hunt.size() == 2u);
  BOOST_TEST(hunt[1].rfind("\"engine, \"\"fast\"\" path\",line_cylinder,", 0) == 0u, hunt[1]);
  const auto f = fields(hunt[1]);
  BOOST_TEST_REQUIRE(f.size() == 11u);
  BOOST_TEST(f[0] == label);
  BOOST_TEST(f[1] == "line_cylinder");
  BOOST_TEST(f[4] == "1");
  BOOST_TEST(r.out.find("hunt: line_cylinder: " + f[5] + " where the certified answer is " + f[6]) != std::string::npos, r.out);
  for (const char* file : {"speed.csv", "families.csv"}) {
    const auto csv = lines_of(slurp(s.dir / "results/judge" / file));
    BOOST_TEST_REQUIRE(csv.size() >= 2u, file);
    const std::size_t columns = fields(csv[0]).size();
    for (std::size_t k = 1; k < csv.size(); ++k) {
      const auto row = fields(csv[k]);
      BOOST_TEST(row.size() == columns, file << ": " << csv[k]);
      BOOST_TEST((std::find(row.begin(), row.end(), label) != row.end()), file << ": " << csv[k]);
    }
  }
}

BOOST_AUTO_TEST_CASE(a_plugin_crashing_inside_a_map_keeps_the_map) {
  // The test plugin answers triangle queries "separated" and abort()s on the 100th call of each
  // of its processes: the 3 cases of one family pass, then the triangle map's 256 cells are
  // answered by three processes: cells 0 to 98, the crash on cell 99 (line 100 of the map's
  // cells, cell (6, 3)), cells 100 to 198, the crash on cell 199 (line 200, cell (12, 7)), cells
  // 200 to 255. Every cell is kept, the two it crashed on are errors, the crashes are named, and
  // the exit status is 0: every case was judged.
  Scratch s;
  const Run r = s.run(std::string(CERTCYL_BIN) + " judge --plugin " CERTCYL_PLUGIN_CRASH
                                                 " --query triangle_cylinder --family t_vertex_wall --size tiny");
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  const fs::path folder = s.dir / "results/judge";
  const auto summary = lines_of(slurp(folder / "failure_maps.csv"));
  BOOST_TEST_REQUIRE(summary.size() == 2u);
  const auto row = fields(summary[1]);
  BOOST_TEST(row.at(0) == "triangle_edge_wall");
  BOOST_TEST(row.at(2) == "256");
  BOOST_TEST(row.at(3) == "256");  // evaluated: none lost
  const auto csv = lines_of(slurp(folder / "failure_maps/triangle_edge_wall.csv"));
  BOOST_TEST_REQUIRE(csv.size() == 257u);
  BOOST_TEST(csv[0] == "i,j,d0_ulps,d1_ulps,certified,gap_lo,gap_hi,faulty_test_plugin");
  for (std::size_t cell = 0; cell < 256; ++cell) {
    const auto f = fields(csv[cell + 1]);
    BOOST_TEST(f.at(7) == (cell == 99 || cell == 199 ? "e" : "s"), "cell " << cell);
  }
  for (const std::string& crash : {std::string("plugin crashed on line 100 (signal 6"), std::string("case 'failure_map/triangle_edge_wall/6/3'"),
                                   std::string("plugin crashed on line 200 (signal 6"), std::string("case 'failure_map/triangle_edge_wall/12/7'")}) {
    BOOST_TEST(r.out.find(crash) != std::string::npos, crash << "\n" << r.out);
    BOOST_TEST(slurp(folder / "index.html").find(crash) != std::string::npos, crash);
  }
  BOOST_TEST(r.out.find("failure map triangle_edge_wall (triangle_cylinder): ") != std::string::npos, r.out);
  BOOST_TEST(slurp(folder / "index.html").find("The method failed on the way:") != std::string::npos);
  // The cases were all judged before the maps.
  BOOST_TEST(lines_of(slurp(folder / "answers.jsonl")).size() == 3u);
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

BOOST_AUTO_TEST_CASE(an_answers_file_gives_the_maps_when_the_cases_hold_their_cells) {
  Scratch s;
  const std::string certcyl = CERTCYL_BIN, method = " query --method shene --nt double";
  // Without the maps' cells in the cases file: no maps, and the summary says how to get them.
  BOOST_TEST_REQUIRE(s.run(certcyl + " cases --query line_cylinder --size tiny > cases.jsonl").status == 0);
  BOOST_TEST_REQUIRE(s.run(certcyl + method + " < cases.jsonl > answers.jsonl").status == 0);
  BOOST_TEST_REQUIRE(s.run(certcyl + " judge --answers answers.jsonl --cases cases.jsonl --name plain").status == 0);
  BOOST_TEST(!fs::exists(s.dir / "results/plain/failure_maps"));
  BOOST_TEST(slurp(s.dir / "out.txt").find("failure maps: an answers file gives them when the cases file holds the maps' cells") !=
                 std::string::npos,
             slurp(s.dir / "out.txt"));
  // With them (certcyl cases --map-cells 16): the same maps as the program judged through --exec
  // at 16 x 16 cells, byte for byte, and the same families (the cells are not a family's cases).
  BOOST_TEST_REQUIRE(s.run(certcyl + " cases --query line_cylinder --size tiny --map-cells 16 > cells.jsonl").status == 0);
  const std::vector<std::string> lines = lines_of(slurp(s / "cells.jsonl"));
  BOOST_TEST_REQUIRE(lines.size() == lines_of(slurp(s / "cases.jsonl")).size() + 2 * 16 * 16);
  BOOST_TEST(lines.back().find(R"("id":"failure_map/rim_line/15/15")") != std::string::npos, lines.back());
  BOOST_TEST(lines.back().find(R"("map":{"cells":16,"step":1,"seed":1})") != std::string::npos, lines.back());
  BOOST_TEST_REQUIRE(s.run(certcyl + method + " < cells.jsonl > cell_answers.jsonl").status == 0);
  const Run answered = s.run(certcyl + " judge --answers cell_answers.jsonl --cases cells.jsonl --name answered --label shene");
  BOOST_TEST_REQUIRE(answered.status == 0, answered.err);
  const Run exec = s.run(certcyl + " judge --exec '" + certcyl + method + "' --cases cases.jsonl --name exec --label shene --map-cells 16");
  BOOST_TEST_REQUIRE(exec.status == 0, exec.err);
  for (const char* file : {"families.csv", "failure_maps.csv", "failure_maps/tangent_line.csv", "failure_maps/rim_line.csv",
                           "failure_maps/tangent_line.json", "failure_maps/rim_line.json", "counterexamples.jsonl"})
    BOOST_TEST(slurp(s.dir / "results/answered" / file) == slurp(s.dir / "results/exec" / file), file);
  BOOST_TEST(lines_of(slurp(s.dir / "results/answered/failure_maps.csv")).size() == 3u);
  BOOST_TEST(lines_of(slurp(s.dir / "results/answered/answers.jsonl")).size() == lines_of(slurp(s / "cases.jsonl")).size());

  // Errors, each naming what is wrong: a cell left unanswered, a cell whose input was changed,
  // another map size asked for, a file of cells alone, a cell without its maps' parameters.
  {
    std::vector<std::string> a = lines_of(slurp(s / "cell_answers.jsonl"));
    a.pop_back();
    std::ofstream out(s / "short.jsonl");
    for (const std::string& l : a) out << l << "\n";
  }
  Run r = s.run(certcyl + " judge --answers short.jsonl --cases cells.jsonl --name short");
  BOOST_TEST(r.status == 1);
  BOOST_TEST(r.err.find("no answer for case 'failure_map/rim_line/15/15'") != std::string::npos, r.err);
  {
    std::string text = slurp(s / "cells.jsonl");
    const std::size_t at = text.find(R"({"id":"failure_map/tangent_line/0/0")");
    BOOST_TEST_REQUIRE(at != std::string::npos);
    const std::size_t digit = text.find_first_of("123456789", text.find("\"origin\":[", at));
    text[digit] = text[digit] == '9' ? '8' : static_cast<char>(text[digit] + 1);
    std::ofstream(s / "edited.jsonl") << text;
  }
  r = s.run(certcyl + " judge --answers cell_answers.jsonl --cases edited.jsonl --name edited");
  BOOST_TEST(r.status == 0, r.err);
  BOOST_TEST(slurp(s.dir / "out.txt").find("failure_map/tangent_line/0/0 (line ") != std::string::npos, slurp(s.dir / "out.txt"));
  BOOST_TEST(slurp(s.dir / "out.txt").find("has another input than the map's") != std::string::npos, slurp(s.dir / "out.txt"));
  r = s.run(certcyl + " judge --answers cell_answers.jsonl --cases cells.jsonl --name other --map-cells 8");
  BOOST_TEST(r.status == 1);
  BOOST_TEST(r.err.find("--map-cells 8: the cases file's maps have 16 x 16 cells") != std::string::npos, r.err);
  BOOST_TEST(!fs::exists(s.dir / "results/other"));  // refused before anything is judged
  {
    std::ofstream out(s / "only.jsonl");
    for (const std::string& l : lines)
      if (l.find("failure_map/") != std::string::npos) out << l << "\n";
  }
  r = s.run(certcyl + " judge --answers cell_answers.jsonl --cases only.jsonl --name only");
  BOOST_TEST(r.status == 1);
  BOOST_TEST(r.err.find("--cases: only failure-map cells, no case to judge") != std::string::npos, r.err);
  {
    std::string text = slurp(s / "cells.jsonl");
    const std::size_t at = text.find(R"(,"map":{"cells":16,"step":1,"seed":1})");
    text.erase(at, std::string(R"(,"map":{"cells":16,"step":1,"seed":1})").size());
    std::ofstream(s / "nomap.jsonl") << text;
  }
  r = s.run(certcyl + " judge --answers cell_answers.jsonl --cases nomap.jsonl --name nomap");
  BOOST_TEST(r.status == 1);
  BOOST_TEST(r.err.find("meta.map: missing on a failure map's cell") != std::string::npos, r.err);
}

BOOST_AUTO_TEST_CASE(map_and_hunt_sizes_from_the_command_line) {
  // --map-cells 5 --map-step 3: each line map 5 x 5 cells, rows and columns 3 ulps apart around
  // the centre (-6, -3, 0, 3, 6); --hunt-evaluations 7: at most 7 inputs hunted, each one run of
  // the program (its query line's id "hunt/...").
  Scratch s;
  const std::string program = "tee -a read.jsonl | " + std::string(CERTCYL_BIN) + " query --method robust_double";
  const Run r = s.run(std::string(CERTCYL_BIN) + " judge --exec '" + program +
                      "' --query line_cylinder --size tiny --map-cells 5 --map-step 3 --hunt-evaluations 7");
  BOOST_TEST_REQUIRE(r.status == 0, r.err);
  const fs::path folder = s.dir / "results/judge";
  const auto summary = lines_of(slurp(folder / "failure_maps.csv"));
  BOOST_TEST_REQUIRE(summary.size() == 3u);  // tangent_line and rim_line
  for (std::size_t m = 1; m < summary.size(); ++m) {
    const auto f = fields(summary[m]);
    BOOST_TEST(f.at(2) == "25");
    BOOST_TEST(f.at(3) == "25");
    const auto csv = lines_of(slurp(folder / "failure_maps" / (f.at(0) + ".csv")));
    BOOST_TEST_REQUIRE(csv.size() == 26u);
    std::set<std::string> d0, d1;
    for (std::size_t k = 1; k < csv.size(); ++k) d0.insert(fields(csv[k]).at(2)), d1.insert(fields(csv[k]).at(3));
    const std::set<std::string> expected{"-6", "-3", "0", "3", "6"};
    BOOST_TEST((d0 == expected));
    BOOST_TEST((d1 == expected));
    const json meta = json::parse(slurp(folder / "failure_maps" / (f.at(0) + ".json")));
    BOOST_TEST(meta["cells"] == 5);
    BOOST_TEST(meta["ulps_per_cell"] == 3);
  }
  const auto hunt = lines_of(slurp(folder / "hunt.csv"));
  BOOST_TEST_REQUIRE(hunt.size() == 2u);
  const long evaluations = std::stol(fields(hunt[1]).at(3));
  BOOST_TEST(evaluations >= 1);
  BOOST_TEST(evaluations <= 7);
  std::size_t hunted = 0;
  for (const std::string& l : lines_of(slurp(s / "read.jsonl"))) hunted += json::parse(l)["id"].get<std::string>().rfind("hunt/", 0) == 0;
  BOOST_TEST(hunted >= 1u);
  BOOST_TEST(hunted <= static_cast<std::size_t>(evaluations));  // inputs left undecided by the certified query are not asked
}

BOOST_AUTO_TEST_CASE(bad_map_and_hunt_sizes_are_errors_naming_the_option) {
  Scratch s;
  const std::string judge = std::string(CERTCYL_BIN) + " judge --plugin " CERTCYL_PLUGIN_DOUBLE " --query line_cylinder --size tiny";
  const std::vector<std::tuple<std::string, std::string, std::string>> bad = {
      {"--map-cells", "0", "[2, 1024]"},         {"--map-cells", "1", "[2, 1024]"},     {"--map-cells", "-4", "[2, 1024]"},
      {"--map-cells", "sixteen", "[2, 1024]"},   {"--map-cells", "2.5", "[2, 1024]"},   {"--map-cells", "1025", "[2, 1024]"},
      {"--map-step", "0", "[1, 1000000000]"},    {"--map-step", "-1", "[1, 1000000000]"},
      {"--hunt-evaluations", "0", "[1, 100000000]"}, {"--hunt-evaluations", "-20", "[1, 100000000]"},
      {"--hunt-evaluations", "1e3", "[1, 100000000]"}};
  for (const auto& [option, value, range] : bad) {
    const Run r = s.run(judge + " " + option + "=" + value);
    BOOST_TEST(r.status == 1, option << " " << value);
    BOOST_TEST(r.err.find(option) != std::string::npos, r.err);
    BOOST_TEST(r.err.find("expected an integer in " + range + ", got '" + value + "'") != std::string::npos, r.err);
    BOOST_TEST(!fs::exists(s.dir / "results"), option << " " << value);
  }
  // The help names them.
  const Run help = s.run(std::string(CERTCYL_BIN) + " judge --help");
  BOOST_TEST(help.status == 0);
  for (const char* option : {"--map-cells", "--map-step", "--hunt-evaluations"}) BOOST_TEST(help.out.find(option) != std::string::npos, option);
}
