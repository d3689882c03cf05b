// The robustness study: its families against their construction, the certified signed gap on
// hand-derived cases, the judgement of answers, ulp arithmetic, the peer adapters on clear
// cases, and a tiny study end to end (CSV schema, summary, machine facts, failure maps,
// hunting, the stages that decided the cylinder pairs, shards merged into the unsharded result,
// figures when matplotlib is installed).
#define BOOST_TEST_MODULE study
#include <boost/test/unit_test.hpp>

#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "study/families.hpp"
#include "study/gap.hpp"
#include "study/methods.hpp"
#include "study.hpp"
#include "study_methods.hpp"

using namespace certcyl;
using namespace certcyl::study;
namespace fs = std::filesystem;

BOOST_AUTO_TEST_CASE(ulp_arithmetic) {
  BOOST_TEST(ulp_step(1.0, 1) == 1.0 + 0x1p-52);
  BOOST_TEST(ulp_step(1.0, -1) == 1.0 - 0x1p-53);
  BOOST_TEST(ulp_step(0.0, -1) == -std::numeric_limits<double>::denorm_min());
  BOOST_TEST(ulp_step(-std::numeric_limits<double>::denorm_min(), 2) == std::numeric_limits<double>::denorm_min());
  BOOST_TEST(ulp_step(2.0, 1LL << 52) == 4.0);  // 2^52 doubles in [2, 4)
  BOOST_TEST(ulp_distance(1.0, 1.0 + 0x1p-52) == 1);
  BOOST_TEST(ulp_distance(-std::numeric_limits<double>::denorm_min(), std::numeric_limits<double>::denorm_min()) == 2);
  BOOST_TEST(ulp_distance(4.0, 2.0) == -(1LL << 52));
  BOOST_TEST(hexfloat(0.375) == "0x1.8p-2");
}

BOOST_AUTO_TEST_CASE(judgement) {
  BOOST_TEST(judge(boolean_answer(true), Answer::separated) == Outcome::false_positive);
  BOOST_TEST(judge(boolean_answer(false), Answer::touching) == Outcome::false_negative);
  BOOST_TEST(judge(boolean_answer(true), Answer::touching) == Outcome::agree);
  BOOST_TEST(judge(three_valued(Answer::overlapping), Answer::touching) == Outcome::class_mismatch);
  BOOST_TEST(judge(three_valued(Answer::separated), Answer::touching) == Outcome::false_negative);
  BOOST_TEST(judge(three_valued(Answer::undecided), Answer::separated) == Outcome::undecided);
  MethodOutput e;
  e.error = true;
  BOOST_TEST(judge(e, Answer::separated) == Outcome::error);
  BOOST_TEST(disagrees(Outcome::false_positive));
  BOOST_TEST(!disagrees(Outcome::class_mismatch));
}

namespace {

// Cylinder p0 = (0,0,0), p1 = (0,0,2), r = 1, after the 6 coordinates of a line-like input.
std::vector<double> with_unit_cylinder(std::vector<double> x) {
  x.insert(x.end(), {0, 0, 0, 0, 0, 2, 1});
  return x;
}

Instance certified(Query q, std::vector<double> x) {
  Instance inst;
  inst.query = q;
  inst.x = std::move(x);
  certify(inst);
  return inst;
}

}  // namespace

// Hand-derived gaps (study/gap.hpp): the depth margin, the largest min(1 - q, s, 1 - s) over the
// set, s and q in units of the height and of r^2 (tests/test_study_gap.cpp has more).
BOOST_AUTO_TEST_CASE(gap_by_hand) {
  // Line through (1/2, 0, 1) along y: s = 1/2 everywhere, q = 1/4 + t^2: min(3/4 - t^2, 1/2),
  // gap 1/2 at t = 0, overlapping.
  Instance a = certified(Query::line_cylinder, with_unit_cylinder({0.5, 0, 1, 0, 1, 0}));
  BOOST_TEST(a.gap_lo == 0.5);
  BOOST_TEST(a.gap_hi == 0.5);
  BOOST_TEST(a.certified == Answer::overlapping);
  // Segment from (3,0,1) to (2,0,1): nearest point (2,0,1), q = 4: gap 1 - 4 = -3.
  Instance b = certified(Query::segment_cylinder, with_unit_cylinder({3, 0, 1, 2, 0, 1}));
  BOOST_TEST(b.gap_lo == -3.0);
  BOOST_TEST(b.certified == Answer::separated);
  // Tangent line x = 1 along y: gap 0, touching.
  Instance c = certified(Query::line_cylinder, with_unit_cylinder({1, 0, 1, 0, 1, 0}));
  BOOST_TEST(c.gap_lo == 0.0);
  BOOST_TEST(c.gap_hi == 0.0);
  BOOST_TEST(c.certified == Answer::touching);
  // Ray from (0,0,3) upward along the axis: above the cap, s from 3/2 up: 1 - s <= -1/2, gap -1/2.
  Instance d = certified(Query::ray_cylinder, with_unit_cylinder({0, 0, 3, 0, 0, 1}));
  BOOST_TEST(d.gap_hi == -0.5);
  // Triangle in the plane z = 1 with a vertex at distance 1/4 from the axis, others outside:
  // at (1/4, 0, 1), q = 1/16 and s = 1/2: min(15/16, 1/2, 1/2) = 1/2, the most any point has: gap 1/2.
  Instance t = certified(Query::triangle_cylinder, {0.25, 0, 1, 5, 1, 1, 5, -1, 1, 0, 0, 0, 0, 0, 2, 1});
  BOOST_TEST(t.gap_lo == 0.5);
  BOOST_TEST(t.certified == Answer::overlapping);
  // Elliptic cylinder a = (2,0,0), b = (0,1,0), c = (0,0,1) at the origin; the line x = 1 along y,
  // z = 1/2: unit x = 1/2, q = 1/4 + t^2, s = 1/2: min(3/4 - t^2, 1/2), gap 1/2.
  Instance e = certified(Query::line_elliptic_cylinder, {1, 0, 0.5, 0, 1, 0, 0, 0, 0, 2, 0, 0, 0, 1, 0, 0, 0, 1});
  BOOST_TEST(e.gap_lo == 0.5);
  // Cylinders side by side at distance 3 > 1 + 1: log(phi*) < 0; coaxial nested: > 0.
  Instance s = certified(Query::cylinder_cylinder, {0, 0, 0, 0, 0, 2, 1, 3, 0, 0, 3, 0, 2, 1});
  BOOST_TEST(s.certified == Answer::separated);
  BOOST_TEST(s.gap_hi < 0);
  Instance o = certified(Query::cylinder_cylinder, {0, 0, 0, 0, 0, 2, 1, 0, 0, 0.5, 0, 0, 1.5, 0.5});
  BOOST_TEST(o.certified == Answer::overlapping);
  BOOST_TEST(o.gap_lo > 0);
}

// Every family, at the degeneracy and k ulps off it: the certified answer agrees with the
// construction wherever the construction is exact, and the gap's sign with the answer.
BOOST_AUTO_TEST_CASE(families_match_their_construction) {
  long checked = 0, known = 0;
  for (const Family& f : all_families()) {
    for (Query q : f.queries) {
      Rng rng(42);
      for (long long k : {0LL, 1LL, -1LL, 3LL, -1000LL, 1LL << 30}) {
        FamilyInput in = f.make(rng, q, k);
        BOOST_TEST_REQUIRE(in.x.size() == coordinate_count(q));
        Instance inst;
        inst.query = q;
        inst.x = in.x;
        certify(inst);
        BOOST_TEST(inst.certified_ok, f.name << " " << to_string(q) << " k=" << k << ": gap sign differs from the answer");
        if (in.expected != Expected::unknown) {
          ++known;
          BOOST_TEST(to_string(inst.certified) == to_string(in.expected),
                     f.name << " " << to_string(q) << " k=" << k << ": certified " << to_string(inst.certified) << ", built "
                            << to_string(in.expected));
        }
        ++checked;
      }
    }
  }
  BOOST_TEST(checked > 200);
  BOOST_TEST(known > 150);
}

// The peer adapters on clear cases: far apart and deeply overlapping.
BOOST_AUTO_TEST_CASE(peer_adapters_on_clear_cases) {
  Registry r;
  const std::vector<std::string> peers = cli::register_peer_methods(r);
  BOOST_TEST_MESSAGE("peers: " << peers.size());
  const std::map<Query, std::pair<std::vector<double>, std::vector<double>>> cases{
      {Query::cylinder_cylinder, {{0, 0, 0, 0, 0, 2, 1, 5, 0, 0, 5, 1, 2, 1}, {0, 0, 0, 0, 0, 2, 1, 0.5, 0, 0, 0.5, 0.2, 2, 0.7}}},
      {Query::ray_cylinder, {with_unit_cylinder({3, 0, 1, 0, 1, 0.1}), with_unit_cylinder({3, 0, 1, -1, 0.1, 0})}},
      {Query::segment_cylinder, {with_unit_cylinder({3, 0, 1, 5, 1, 1.5}), with_unit_cylinder({3, 0, 1, -3, 0.2, 1.1})}},
      {Query::triangle_cylinder,
       {{3, 0, 1, 4, 1, 1, 4, -1, 1.5, 0, 0, 0, 0, 0, 2, 1}, {-3, -1, 1, 3, -1, 1.2, 0, 3, 0.8, 0, 0, 0, 0, 0, 2, 1}}}};
  int tested = 0;
  for (const Method& m : r) {
    const auto& [apart, overlapping] = cases.at(m.query);
    BOOST_TEST(judge(m.run(apart), Answer::separated) == Outcome::agree, m.name() << " on a clearly separated input");
    BOOST_TEST(judge(m.run(overlapping), Answer::overlapping) == Outcome::agree, m.name() << " on a clearly overlapping input");
    ++tested;
  }
  BOOST_TEST(tested == static_cast<int>(r.size()));
}

namespace {

std::vector<std::string> lines_of(const fs::path& p) {
  std::ifstream in(p);
  std::vector<std::string> out;
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

// A row of instances.csv without its timing column (field 15, ns).
std::string without_ns(const std::string& row) {
  std::vector<std::string> f;
  std::stringstream ss(row);
  for (std::string x; std::getline(ss, x, ',');) f.push_back(x);
  if (row.back() == ',') f.push_back("");
  std::string out;
  for (std::size_t i = 0; i < f.size(); ++i)
    if (i != 14) out += f[i] + ",";
  return out;
}

cli::StudyOptions tiny(const fs::path& root, const std::string& name) {
  cli::StudyOptions o;
  o.out_root = root.string();
  o.name = name;
  o.size = "tiny";
  o.threads = 2;
  o.progress = false;
  o.plots = false;
  return o;
}

}  // namespace

BOOST_AUTO_TEST_CASE(tiny_study_end_to_end) {
  const fs::path root = fs::temp_directory_path() / ("certcyl_study_test_" + std::to_string(::getpid()));
  fs::remove_all(root);
  std::ostringstream out;
  BOOST_TEST_REQUIRE(cli::run_study(tiny(root, "t"), out) == 0);
  const fs::path dir = root / "t";
  BOOST_TEST(out.str().find("0 gap-sign mismatches, 0 disagreements between construction and certified answer") != std::string::npos,
             out.str());

  // instances.csv: the schema, one row per instance and applicable method, valid outcomes.
  const auto rows = lines_of(dir / "instances.csv");
  BOOST_TEST_REQUIRE(rows.size() > 1000u);
  BOOST_TEST(rows[0] ==
             "family,query,instance,k_ulps,expected,method,base,nt,kind,answer,certified_answer,outcome,gap_lo,gap_hi,ns,t_error_ulps,"
             "contract,contract_answer,received_answer,cause");
  std::set<std::string> outcomes, queries;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    std::vector<std::string> f;
    std::stringstream ss(rows[i]);
    for (std::string x; std::getline(ss, x, ',');) f.push_back(x);
    BOOST_TEST_REQUIRE(f.size() >= 15u);
    outcomes.insert(f[11]);
    queries.insert(f[1]);
    if (f[8] == "certified") BOOST_TEST(f[11] == "agree", rows[i]);
    // A value the method reported left the finite doubles: counted apart, whatever it answered.
    if (f[11] == "invalid") BOOST_TEST(f[9] == "invalid", rows[i]);
  }
  for (const auto& o : outcomes)
    BOOST_TEST((o == "agree" || o == "false_positive" || o == "false_negative" || o == "class_mismatch" || o == "undecided" ||
                o == "error" || o == "invalid" || o == "uncertified"));
  BOOST_TEST(queries.size() == kQueries.size());
  BOOST_TEST(lines_of(dir / "inputs.csv").size() > 100u);
  BOOST_TEST(lines_of(dir / "summary.csv").size() > 20u);
  BOOST_TEST(fs::exists(dir / "summary.txt"));
  const auto machine = nlohmann::json::parse(std::ifstream(dir / "machine.json"));
  for (const char* key : {"compiler", "flags", "cpu", "commit", "options"}) BOOST_TEST(machine.contains(key), key);
  for (const char* map : {"tangent_line", "rim_line", "touching_cylinders"})
    BOOST_TEST(lines_of(dir / "failure_maps" / (std::string(map) + ".csv")).size() == 16u * 16u + 1u, map);
  const auto hunt = lines_of(dir / "hunt.csv");
  BOOST_TEST(hunt.size() > 10u);

  // stages.csv: every cylinder pair of inputs.csv counted once; each family of pairs built to
  // touch has instances proved by the exact touching candidates or the refine stage.
  {
    long pairs = 0;
    for (const auto& line : lines_of(dir / "inputs.csv")) pairs += line.find(",cylinder_cylinder,") != std::string::npos;
    const auto stages = lines_of(dir / "stages.csv");
    BOOST_TEST_REQUIRE(stages.size() > 1u);
    BOOST_TEST(stages[0] == "family,stage,certified_by,gmpfr_bits,instances");
    long counted = 0;
    std::set<std::string> touching_or_refine;
    for (std::size_t i = 1; i < stages.size(); ++i) {
      std::vector<std::string> f;
      std::stringstream ss(stages[i]);
      for (std::string x; std::getline(ss, x, ',');) f.push_back(x);
      BOOST_TEST_REQUIRE(f.size() == 5u, stages[i]);
      counted += std::stol(f[4]);
      if (f[1] == "touching_exact" || f[1] == "refine") touching_or_refine.insert(f[0]);
    }
    BOOST_TEST(pairs > 20);
    BOOST_TEST(counted == pairs);
    for (const char* family : {"c_cap_cap", "c_wall_parallel", "c_wall_crossing", "c_cap_wall", "c_rim_cap", "c_rim_wall", "c_rim_rim"})
      BOOST_TEST(touching_or_refine.count(family) == 1u, family);
    BOOST_TEST(out.str().find("cylinder pairs: the stage of certified_cylinder_cylinder") != std::string::npos, out.str());
  }

  // Two shards merged give the unsharded rows (timings aside) and the same summary counts.
  for (int i = 0; i < 2; ++i) {
    cli::StudyOptions s = tiny(root, "sharded");
    s.shard_index = i;
    s.shard_count = 2;
    std::ostringstream so;
    BOOST_TEST_REQUIRE(cli::run_study(s, so) == 0);
  }
  std::ostringstream mo;
  BOOST_TEST_REQUIRE(cli::run_merge((root / "sharded").string(), false, mo) == 0);
  const auto merged = lines_of(root / "sharded" / "instances.csv");
  BOOST_TEST_REQUIRE(merged.size() == rows.size());
  std::size_t same = 0;
  for (std::size_t i = 0; i < rows.size(); ++i) same += without_ns(rows[i]) == without_ns(merged[i]);
  BOOST_TEST(same == rows.size());
  BOOST_TEST(lines_of(root / "sharded" / "inputs.csv") == lines_of(dir / "inputs.csv"));
  BOOST_TEST(lines_of(root / "sharded" / "stages.csv") == lines_of(dir / "stages.csv"));
  BOOST_TEST(lines_of(root / "sharded" / "hunt.csv").size() == hunt.size());

  // merge refuses shards that do not belong together, naming what differs or is missing.
  auto merge_error = [&](const fs::path& dir) -> std::string {
    std::ostringstream o;
    try {
      cli::run_merge(dir.string(), false, o);
    } catch (const std::runtime_error& e) {
      return e.what();
    }
    return "merged";
  };
  auto copy_shard = [&](const std::string& shard, const fs::path& to) {
    fs::create_directories(to.parent_path());
    fs::copy(root / "sharded" / shard, to, fs::copy_options::recursive);
  };
  copy_shard("shard-0-of-2", root / "missing" / "shard-0-of-2");
  const std::string missing = merge_error(root / "missing");
  BOOST_TEST(missing.find("missing shard(s) 1 of 2") != std::string::npos, missing);
  copy_shard("shard-0-of-2", root / "dup" / "shard-0-of-2");
  copy_shard("shard-1-of-2", root / "dup" / "shard-1-of-2");
  copy_shard("shard-1-of-2", root / "dup" / "shard-1-of-2-again");
  const std::string dup = merge_error(root / "dup");
  BOOST_TEST(dup.find("duplicate shard(s) 1 (shard-1-of-2, shard-1-of-2-again)") != std::string::npos, dup);
  {
    // Shard 1 of 2 with another seed: a different configuration.
    copy_shard("shard-0-of-2", root / "seeds" / "shard-0-of-2");
    cli::StudyOptions s = tiny(root, "seeds");
    s.seed = 2;
    s.shard_index = 1;
    s.shard_count = 2;
    std::ostringstream so;
    BOOST_TEST_REQUIRE(cli::run_study(s, so) == 0);
    const std::string seeds = merge_error(root / "seeds");
    BOOST_TEST(seeds.find("different configurations: seed is 1 in shard-0-of-2 but 2 in shard-1-of-2") != std::string::npos, seeds);
  }
  {
    // Shard 1 of 3 beside shard 0 of 2.
    copy_shard("shard-0-of-2", root / "counts" / "shard-0-of-2");
    cli::StudyOptions s = tiny(root, "counts");
    s.shard_index = 1;
    s.shard_count = 3;
    std::ostringstream so;
    BOOST_TEST_REQUIRE(cli::run_study(s, so) == 0);
    const std::string counts = merge_error(root / "counts");
    BOOST_TEST(counts.find("shards of different counts: shard-0-of-2 is one of 2, shard-1-of-3 one of 3") != std::string::npos, counts);
  }

  // The figures, when /usr/bin/python3 has matplotlib.
  if (std::system("/usr/bin/python3 -c 'import matplotlib, numpy' >/dev/null 2>&1") == 0) {
    const std::string cmd = "/usr/bin/python3 '" CERTCYL_TEST_SOURCE_DIR "/experiments/plot_study.py' '" + dir.string() + "' >/dev/null";
    BOOST_TEST_REQUIRE(std::system(cmd.c_str()) == 0);
    for (const char* fig : {"pareto", "disagreement_line_cylinder", "gap_rate_line_cylinder", "map_tangent_line", "map_touching_cylinders"})
      for (const char* ext : {".png", ".pdf"}) BOOST_TEST(fs::exists(dir / "figures" / (std::string(fig) + ext)), fig << ext);
  } else {
    BOOST_TEST_MESSAGE("matplotlib not installed: figures not checked");
  }
  fs::remove_all(root);
}
