// `certcyl judge` under a method's contract (study/contract.hpp; --contract, or a plugin's
// certcyl_plugin_contract): hand-made rays and segments against the unit cylinder from (0,0,0) to
// (0,0,1), each certified answer under each contract worked out below, and one set of answers
// (a ray cast reporting entries only) whose failures under each contract are counted here by
// hand: none under surface_entry, the starts inside under solid, the exits under surface_hit.
// Then a plugin declaring its contract, and the errors of a bad or conflicting contract.
#define BOOST_TEST_MODULE judge_contract
#include <boost/test/unit_test.hpp>

#include <nlohmann/json.hpp>

#include <fstream>
#include <map>
#include <set>
#include <string>

#include "judge_test_support.hpp"

using namespace judge_test;
using json = nlohmann::json;

namespace {

const std::string kCertcyl = CERTCYL_BIN;
const std::string kPlugin = CERTCYL_PLUGIN_CONTRACT;

const std::string kCylinder = R"("cylinder": {"p0": [0,0,0], "p1": [0,0,1], "radius": 1})";

// A case by hand: id, its operand, the certified solid answer (the file's meta.certified, checked
// by the judge), and the answer of a ray cast that reports entering from outside only.
struct HandCase {
  std::string id, operand, solid, entry_answer;
};

// Certified answers, solid / surface_entry / surface_hit:
//   ray_inside     from the centre outwards: overlapping / miss (starts in C) / hit (the exit).
//   ray_towards    from (-3,0,1/2) towards the axis: overlapping under all three.
//   ray_away       from (3,0,1/2) away: separated under all three.
//   ray_wall_out   from the wall point (1,0,1/2) outwards: touching at t = 0 only / miss / miss
//                  (no surface point at t > 0).
//   segment_inside from (0,0,1/4) to (0,0,3/4): overlapping / miss / miss (its end is interior).
//   segment_enter  from (-3,0,1/2) to the centre: overlapping under all three.
//   segment_exit   from the centre to (3,0,1/2): overlapping / miss / hit (the wall at t = 1/3).
const std::vector<HandCase> kCases = {
    {"ray_inside", R"("ray": {"origin": [0,0,0.5], "direction": [1,0,0]})", "overlapping", "separated"},
    {"ray_towards", R"("ray": {"origin": [-3,0,0.5], "direction": [1,0,0]})", "overlapping", "overlapping"},
    {"ray_away", R"("ray": {"origin": [3,0,0.5], "direction": [1,0,0]})", "separated", "separated"},
    {"ray_wall_out", R"("ray": {"origin": [1,0,0.5], "direction": [1,0,0]})", "touching", "separated"},
    {"segment_inside", R"("segment": {"p0": [0,0,0.25], "p1": [0,0,0.75]})", "overlapping", "separated"},
    {"segment_enter", R"("segment": {"p0": [-3,0,0.5], "p1": [0,0,0.5]})", "overlapping", "overlapping"},
    {"segment_exit", R"("segment": {"p0": [0,0,0.5], "p1": [3,0,0.5]})", "overlapping", "separated"},
};

std::string query_of(const HandCase& c) { return c.id.rfind("ray", 0) == 0 ? "ray_cylinder" : "segment_cylinder"; }

// The cases file (meta.gap is computed again by the judge; any enclosure is read) and the
// entry-only answers.
void write_files(const Scratch& s) {
  std::ofstream cases(s / "cases.jsonl"), answers(s / "entry.jsonl");
  for (const HandCase& c : kCases) {
    cases << R"({"id": ")" << c.id << R"(", "query": ")" << query_of(c) << R"(", )" << c.operand << ", " << kCylinder
          << R"(, "meta": {"family": "hand", "k": 0, "certified": ")" << c.solid << R"(", "gap": [0, 0]}})" << '\n';
    answers << json{{"id", c.id}, {"answer", c.entry_answer}}.dump() << '\n';
  }
}

// families.csv's false negatives and false positives of the family "hand", per query (the
// method's name, given by --label, holds no comma).
std::map<std::string, std::pair<long, long>> hand_failures(const fs::path& file) {
  std::map<std::string, std::pair<long, long>> out;
  const std::vector<std::string> lines = lines_of(slurp(file));
  BOOST_REQUIRE(!lines.empty());
  std::vector<std::string> header;
  std::map<std::string, std::size_t> at;
  auto split = [](const std::string& l) {
    std::vector<std::string> f(1);
    for (char ch : l) {
      if (ch == ',') f.emplace_back();
      else f.back().push_back(ch);
    }
    return f;
  };
  header = split(lines[0]);
  for (std::size_t i = 0; i < header.size(); ++i) at[header[i]] = i;
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const auto f = split(lines[i]);
    BOOST_REQUIRE(f.size() == header.size());
    if (f[at["family"]] == "hand") out[f[at["query"]]] = {std::stol(f[at["false_negative"]]), std::stol(f[at["false_positive"]])};
  }
  return out;
}

// The family "hand" of `query` has these false negatives and false positives.
void check_failures(std::map<std::string, std::pair<long, long>>& f, const std::string& query, long false_negatives,
                    long false_positives) {
  BOOST_TEST_REQUIRE(f.count(query) == 1u, query);
  BOOST_TEST(f[query].first == false_negatives, query);
  BOOST_TEST(f[query].second == false_positives, query);
}

}  // namespace

BOOST_AUTO_TEST_CASE(an_answers_file_is_judged_under_the_contract_given) {
  Scratch s;
  write_files(s);
  const std::string judge = kCertcyl + " judge --cases cases.jsonl --answers entry.jsonl --label entry";
  // Under surface_entry every answer is right.
  const Run entry = s.run(judge + " --contract surface_entry --name entry");
  BOOST_TEST_REQUIRE(entry.status == 0, entry.err);
  BOOST_TEST(entry.out.find("rays and segments under the contract surface_entry") != std::string::npos, entry.out);
  auto f = hand_failures(s.dir / "results/entry/families.csv");
  check_failures(f, "ray_cylinder", 0, 0);
  check_failures(f, "segment_cylinder", 0, 0);
  BOOST_TEST(slurp(s.dir / "results/entry/counterexamples.jsonl").empty());
  // Solid (the default): the misses from inside and from the wall are false negatives
  // (ray_inside, ray_wall_out; segment_inside, segment_exit).
  const Run solid = s.run(judge + " --name solid");
  BOOST_TEST_REQUIRE(solid.status == 0, solid.err);
  BOOST_TEST(solid.out.find("under the contract") == std::string::npos, solid.out);
  f = hand_failures(s.dir / "results/solid/families.csv");
  check_failures(f, "ray_cylinder", 2, 0);
  check_failures(f, "segment_cylinder", 2, 0);
  for (const std::string& l : lines_of(slurp(s.dir / "results/solid/counterexamples.jsonl")))
    BOOST_TEST(!json::parse(l)["meta"].contains("contract"), l);
  // Surface hit: the exits are hits, so ray_inside and segment_exit are false negatives.
  const Run hit = s.run(judge + " --contract surface_hit --name hit");
  BOOST_TEST_REQUIRE(hit.status == 0, hit.err);
  f = hand_failures(s.dir / "results/hit/families.csv");
  check_failures(f, "ray_cylinder", 1, 0);
  check_failures(f, "segment_cylinder", 1, 0);
  std::set<std::string> ids;
  for (const std::string& l : lines_of(slurp(s.dir / "results/hit/counterexamples.jsonl"))) {
    const json c = json::parse(l);
    ids.insert(c["id"].get<std::string>());
    BOOST_TEST(c["meta"]["contract"] == "surface_hit", l);
    BOOST_TEST(c["meta"]["contract_answer"] == "overlapping", l);
    BOOST_TEST(c["meta"]["certified"] == "overlapping", l);
  }
  BOOST_TEST((ids == std::set<std::string>{"ray_inside", "segment_exit"}));
  BOOST_TEST(slurp(s.dir / "results/hit/index.html").find("Contract: <b>surface_hit</b>") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(a_plugin_declares_its_contract) {
  Scratch s;
  write_files(s);
  const std::string judge = kCertcyl + " judge --cases cases.jsonl --plugin " + kPlugin + " --size tiny --hunt-evaluations 4";
  // certcyl_plugin_contract says surface_entry: no failure.
  const Run declared = s.run(judge + " --name declared");
  BOOST_TEST_REQUIRE(declared.status == 0, declared.err);
  BOOST_TEST(declared.out.find("contract_test_plugin, 7 of 7 cases judged, rays and segments under the contract surface_entry") !=
                 std::string::npos,
             declared.out);
  auto f = hand_failures(s.dir / "results/declared/families.csv");
  check_failures(f, "ray_cylinder", 0, 0);
  check_failures(f, "segment_cylinder", 0, 0);
  // The same answers declared solid: the starts inside are false negatives.
  const Run solid = s.run("CERTCYL_TEST_CONTRACT=solid " + judge + " --name solid");
  BOOST_TEST_REQUIRE(solid.status == 0, solid.err);
  f = hand_failures(s.dir / "results/solid/families.csv");
  check_failures(f, "ray_cylinder", 2, 0);
  check_failures(f, "segment_cylinder", 2, 0);
  // --contract agreeing with the plugin is accepted; disagreeing, an error naming both.
  BOOST_TEST(s.run(judge + " --name agreed --contract surface_entry").status == 0);
  const Run conflict = s.run(judge + " --name conflict --contract solid");
  BOOST_TEST(conflict.status == 1);
  BOOST_TEST(conflict.err.find("--contract solid: the plugin contract_test_plugin declares surface_entry (certcyl_plugin_contract)") !=
                 std::string::npos,
             conflict.err);
  // A name the plugin returns that is no contract.
  const Run bad = s.run("CERTCYL_TEST_CONTRACT=entry " + judge + " --name bad");
  BOOST_TEST(bad.status == 1);
  BOOST_TEST(bad.err.find("certcyl_plugin_contract(): unknown contract 'entry' (expected solid, surface_entry or surface_hit)") !=
                 std::string::npos,
             bad.err);
}

BOOST_AUTO_TEST_CASE(a_bad_contract_is_an_error_naming_the_option) {
  Scratch s;
  write_files(s);
  const Run unknown = s.run(kCertcyl + " judge --cases cases.jsonl --answers entry.jsonl --contract surface-entry");
  BOOST_TEST(unknown.status == 1);
  BOOST_TEST(unknown.err.find("--contract: unknown contract 'surface-entry' (expected solid, surface_entry or surface_hit)") !=
                 std::string::npos,
             unknown.err);
  // Lines have only the solid contract.
  const Run lines = s.run(kCertcyl + " judge --query line_cylinder --size tiny --answers entry.jsonl --contract surface_hit");
  BOOST_TEST(lines.status == 1);
  BOOST_TEST(lines.err.find("--contract surface_hit: defined for ray_cylinder and segment_cylinder only, and no case is one of them") !=
                 std::string::npos,
             lines.err);
  BOOST_TEST(!fs::exists(s.dir / "results"));
}
