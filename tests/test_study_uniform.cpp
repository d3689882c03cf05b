// The study's uniform sample (src/study_uniform.cpp): its counts against methods whose answers
// are known in advance (always separated, always "they meet", always throwing, always undecided,
// a serial twin), the certified answers against the gap path (study::certify, its own exact
// depth margin or cylinder-pair enclosure), which methods take part, its size from the presets and
// the configuration, and shards that merge into the unsharded file (and the merge's refusals).
#define BOOST_TEST_MODULE study_uniform
#include <boost/test/unit_test.hpp>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "study/gap.hpp"
#include "study_internal.hpp"
#include "study_methods.hpp"

using namespace certcyl;
using namespace certcyl::study;
using certcyl::cli::detail::split_csv;
namespace fs = std::filesystem;

namespace {

using CsvRow = std::map<std::string, std::string>;

std::vector<CsvRow> read_csv(const fs::path& p) {
  std::ifstream in(p);
  std::string line;
  std::vector<CsvRow> rows;
  BOOST_TEST_REQUIRE(static_cast<bool>(std::getline(in, line)), p.string());
  const auto header = split_csv(line);
  while (std::getline(in, line)) {
    const auto f = split_csv(line);
    BOOST_TEST_REQUIRE(f.size() == header.size(), line);
    CsvRow r;
    for (std::size_t i = 0; i < f.size(); ++i) r[header[i]] = f[i];
    rows.push_back(std::move(r));
  }
  return rows;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

long n(const CsvRow& r, const std::string& key) { return std::stol(r.at(key)); }

Method fake(const std::string& base, Query q, std::function<MethodOutput(const std::vector<double>&)> run) {
  Method m;
  m.base = base, m.nt = "double", m.kind = MethodKind::robust, m.query = q, m.run = std::move(run);
  return m;
}

// Methods whose answers on every input are known: the expected counts follow from the certified
// answers' counts alone.
Registry fake_registry() {
  Registry r;
  for (Query q : {Query::line_cylinder, Query::cylinder_cylinder}) {
    r.push_back(fake("always_separated", q, [](const std::vector<double>&) { return three_valued(Answer::separated); }));
    r.push_back(fake("always_meet", q, [](const std::vector<double>&) { return boolean_answer(true); }));
    r.push_back(fake("always_overlapping", q, [](const std::vector<double>&) { return three_valued(Answer::overlapping); }));
    r.push_back(fake("always_throws", q, [](const std::vector<double>&) -> MethodOutput { throw std::runtime_error("no"); }));
    r.push_back(fake("always_undecided", q, [](const std::vector<double>&) { return three_valued(Answer::undecided); }));
    r.push_back(fake("serial_separated", q, [](const std::vector<double>&) { return three_valued(Answer::separated); }));
    r.back().serial = true;
    // Not in the sample: a slow type's stride, and CORE::Expr.
    r.push_back(fake("strided", q, [](const std::vector<double>&) { return three_valued(Answer::separated); }));
    r.back().stride = 2;
    r.push_back(fake("core", q, [](const std::vector<double>&) { return three_valued(Answer::separated); }));
    r.back().nt = "core_expr";
  }
  return r;
}

cli::StudyOptions sample_options(long per_query) {
  cli::StudyOptions o;
  o.uniform_per_query = per_query, o.threads = 2, o.progress = false;
  return o;
}

fs::path fresh(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("certcyl_study_uniform_" + std::to_string(::getpid())) / name;
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

// Shard K of n of the uniform sample of `per_query` instances per query, for K = 0 .. n-1, each
// written into folder/shard-K-of-n (created); returns the shards' folders in order.
std::vector<fs::path> write_uniform_shards(long per_query, int n, const Registry& registry, const fs::path& folder) {
  std::vector<fs::path> shards;
  for (int k = 0; k < n; ++k) {
    cli::StudyOptions o = sample_options(per_query);
    o.shard_index = k, o.shard_count = n;
    shards.push_back(folder / ("shard-" + std::to_string(k) + "-of-" + std::to_string(n)));
    fs::create_directories(shards.back());
    cli::detail::run_uniform_sample(o, registry, shards.back());
  }
  return shards;
}

}  // namespace

BOOST_AUTO_TEST_CASE(counts_of_methods_with_known_answers) {
  const fs::path dir = fresh("counts");
  cli::detail::run_uniform_sample(sample_options(300), fake_registry(), dir);
  const auto rows = read_csv(dir / "uniform.csv");
  // Six methods of two queries; neither the strided nor the CORE::Expr one.
  BOOST_TEST_REQUIRE(rows.size() == 12u);
  std::map<std::string, const CsvRow*> by;
  for (const CsvRow& r : rows) {
    BOOST_TEST(r.at("method").find("strided") == std::string::npos);
    BOOST_TEST(r.at("method").find("core") == std::string::npos);
    by[r.at("query") + " " + r.at("method")] = &r;
  }
  for (const std::string q : {"line_cylinder", "cylinder_cylinder"}) {
    const CsvRow& sep = *by.at(q + " always_separated/double");
    const long certified = n(sep, "instances") - n(sep, "uncertified");
    const long meet = n(sep, "touching") + n(sep, "overlapping");
    BOOST_TEST(n(sep, "instances") == 300);
    BOOST_TEST(n(sep, "separated") + meet + n(sep, "uncertified") == 300);
    // Uniform random inputs meet and miss: both answers occur.
    BOOST_TEST(n(sep, "separated") > 0);
    BOOST_TEST(meet > 0);
    for (const auto& [name, r] : by) {
      if (name.rfind(q + " ", 0) != 0) continue;
      // The certified answers are the query's, the same in each of its rows.
      for (const char* key : {"instances", "separated", "touching", "overlapping", "uncertified"}) BOOST_TEST(n(*r, key) == n(sep, key), name);
    }
    BOOST_TEST(n(sep, "decided") == certified);
    BOOST_TEST(n(sep, "false_positive") == 0);
    BOOST_TEST(n(sep, "false_negative") == meet);
    BOOST_TEST(n(sep, "class_mismatch") == 0);
    BOOST_TEST(n(sep, "intersecting") == 0);
    const CsvRow& yes = *by.at(q + " always_meet/double");
    BOOST_TEST(n(yes, "false_positive") == n(sep, "separated"));
    BOOST_TEST(n(yes, "false_negative") == 0);
    BOOST_TEST(n(yes, "class_mismatch") == 0);  // a Boolean answer has no class
    BOOST_TEST(n(yes, "intersecting") == certified);
    const CsvRow& over = *by.at(q + " always_overlapping/double");
    BOOST_TEST(n(over, "false_positive") == n(sep, "separated"));
    BOOST_TEST(n(over, "class_mismatch") == n(sep, "touching"));
    BOOST_TEST(n(over, "intersecting") == 0);
    const CsvRow& thrown = *by.at(q + " always_throws/double");
    BOOST_TEST(n(thrown, "error") == certified);
    BOOST_TEST(n(thrown, "decided") == 0);
    const CsvRow& undecided = *by.at(q + " always_undecided/double");
    BOOST_TEST(n(undecided, "undecided") == certified);
    BOOST_TEST(n(undecided, "decided") == 0);
    // The serial pass (the instances drawn again) counts what the parallel one counts.
    const CsvRow& serial = *by.at(q + " serial_separated/double");
    for (const char* key : {"decided", "false_positive", "false_negative", "class_mismatch", "undecided", "error", "invalid"})
      BOOST_TEST(n(serial, key) == n(sep, key), key);
  }
  // The table for summary.txt names the wrong methods and counts the others.
  const std::string table = cli::detail::uniform_table(dir);
  BOOST_TEST(table.find("always_separated/double") != std::string::npos, table);
  BOOST_TEST(table.find("always_throws/double") != std::string::npos, table);
}

BOOST_AUTO_TEST_CASE(certified_answers_agree_with_the_gap_path) {
  // The sample's reference (uniform_certified_answer, the filtered queries on the doubles) against
  // certify (the gap's own exact comparisons for lines and triangles, the refined pair stages).
  for (Query q : {Query::line_cylinder, Query::ray_cylinder, Query::segment_cylinder, Query::line_elliptic_cylinder, Query::triangle_cylinder,
                  Query::cylinder_cylinder}) {
    std::map<Answer, int> seen;
    for (long i = 0; i < 40; ++i) {
      Instance inst;
      inst.query = q;
      inst.x = cli::detail::uniform_sample_input(1, q, i);
      BOOST_TEST_REQUIRE(inst.x.size() == (q == Query::line_elliptic_cylinder ? 18u : (q == Query::triangle_cylinder ? 16u : (q == Query::cylinder_cylinder ? 14u : 13u))));
      // The same seed, query and index draw the same input; another index another.
      BOOST_TEST((cli::detail::uniform_sample_input(1, q, i) == inst.x));
      BOOST_TEST((cli::detail::uniform_sample_input(1, q, i + 1) != inst.x));
      certify(inst);
      BOOST_TEST(inst.certified_ok);
      BOOST_TEST((cli::detail::uniform_certified_answer(q, inst.x) == inst.certified), to_string(q) << " instance " << i);
      // The ray casts' contracts: the same answers as certify's.
      const cli::detail::UniformTruth truth = cli::detail::uniform_certified(q, inst.x);
      BOOST_TEST((truth.under(Contract::surface_entry) == inst.certified_entry), to_string(q) << " instance " << i);
      BOOST_TEST((truth.under(Contract::surface_hit) == inst.certified_surface_hit), to_string(q) << " instance " << i);
      BOOST_TEST((truth.under(Contract::solid) == inst.certified));
      ++seen[inst.certified];
    }
    // A uniform sample holds both separated and meeting inputs.
    BOOST_TEST(seen[Answer::separated] > 0, to_string(q));
    BOOST_TEST(seen[Answer::overlapping] > 0, to_string(q));
  }
}

BOOST_AUTO_TEST_CASE(which_methods_and_how_many) {
  // The real registry: the slow number types, CORE::Expr and the certified query (the reference)
  // are left out, every other method is in.
  const Registry registry = cli::all_methods_registry();
  const cli::StudyOptions all = sample_options(10);
  long in = 0, out = 0;
  for (const Method& m : registry) {
    const bool left_out = m.nt.rfind("gmpfr", 0) == 0 || m.nt == "core_expr" || m.base == "certified";
    BOOST_TEST(cli::detail::in_uniform_sample(m, all) == !left_out, m.name());
    (left_out ? out : in) += 1;
  }
  BOOST_TEST(in > 0);
  BOOST_TEST(out > 0);
  // A method filter applies.
  cli::StudyOptions robust = sample_options(10);
  robust.methods = {"robust/"};
  for (const Method& m : registry) BOOST_TEST(cli::detail::in_uniform_sample(m, robust) == (m.base == "robust"), m.name());

  // Sizes: the presets, an integer size (1000 per instance of a family), the configuration's key.
  for (const auto& [size, expected] : std::vector<std::pair<std::string, long>>{{"tiny", 200}, {"small", 5000}, {"default", 100000}, {"large", 1000000}, {"7", 7000}}) {
    cli::StudyOptions o;
    o.size = size;
    cli::detail::apply_size(o);
    BOOST_TEST(o.uniform_per_query == expected, size);
  }
  const fs::path dir = fresh("config");
  auto configured = [&](const std::string& json) {
    std::ofstream(dir / "c.json") << json;
    cli::StudyOptions o;
    o.config_file = (dir / "c.json").string();
    cli::detail::apply_config(o);
    cli::detail::apply_size(o);
    return o.uniform_per_query;
  };
  BOOST_TEST(configured(R"({"uniform_per_query": 0})") == 0);
  BOOST_TEST(configured(R"({"uniform_per_query": 123, "size": "large"})") == 123);
  for (const char* bad : {R"({"uniform_per_query": -1})", R"({"uniform_per_query": 2.5})", R"({"uniform_per_query": "3"})",
                          R"({"uniform_per_query": 100000001})"}) {
    std::string what;
    try {
      configured(bad);
    } catch (const std::invalid_argument& e) {
      what = e.what();
    }
    BOOST_TEST(what.find("--config: uniform_per_query: expected an integer in [0, 100000000], got ") == 0u, bad << ": " << what);
  }

  // None when the families leave `uniform` out or the size is 0: the header alone.
  cli::StudyOptions no_uniform = sample_options(50);
  no_uniform.families = {"tangent"};
  cli::detail::run_uniform_sample(no_uniform, fake_registry(), dir);
  BOOST_TEST(read_csv(dir / "uniform.csv").empty());
  cli::detail::run_uniform_sample(sample_options(0), fake_registry(), dir);
  BOOST_TEST(read_csv(dir / "uniform.csv").empty());
  BOOST_TEST(slurp(dir / "uniform.csv") == std::string(cli::detail::kUniformHeader) + "\n");
}

BOOST_AUTO_TEST_CASE(shards_merge_into_the_unsharded_sample) {
  const Registry registry = fake_registry();
  const fs::path whole = fresh("whole"), merged = fresh("merged");
  cli::detail::run_uniform_sample(sample_options(101), registry, whole);
  const std::vector<fs::path> shards = write_uniform_shards(101, 3, registry, merged);
  // 101 = 34 + 34 + 33 instances per query.
  for (std::size_t s = 0; s < shards.size(); ++s)
    for (const CsvRow& r : read_csv(shards[s] / "uniform.csv")) BOOST_TEST(n(r, "instances") == (s < 2 ? 34 : 33));
  cli::detail::merge_uniform(shards, merged);
  BOOST_TEST(slurp(merged / "uniform.csv") == slurp(whole / "uniform.csv"));

  // A shard of more shards than instances has rows of zeros and still merges.
  const fs::path sparse = fresh("sparse");
  const std::vector<fs::path> many = write_uniform_shards(2, 4, registry, sparse);
  BOOST_TEST(n(read_csv(many[3] / "uniform.csv").at(0), "instances") == 0);
  cli::detail::merge_uniform(many, sparse);
  for (const CsvRow& r : read_csv(sparse / "uniform.csv")) BOOST_TEST(n(r, "instances") == 2);

  // Refused: a missing file, a row left out, a row of another method, a count that is not one.
  auto refusal = [&](const std::function<void(const fs::path&)>& damage) {
    const fs::path copy = fresh("damaged");
    std::vector<fs::path> copies;
    for (const fs::path& s : shards) {
      copies.push_back(copy / s.filename());
      fs::copy(s, copies.back(), fs::copy_options::recursive);
    }
    damage(copies[1] / "uniform.csv");
    try {
      cli::detail::merge_uniform(copies, copy);
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string text = slurp(shards[1] / "uniform.csv");
  BOOST_TEST(refusal([](const fs::path& p) { fs::remove(p); }) == "merge: shard-1-of-3/uniform.csv: missing");
  BOOST_TEST(refusal([&](const fs::path& p) { std::ofstream(p) << text.substr(0, text.rfind('\n', text.size() - 2) + 1); }) ==
             "merge: shard-1-of-3/uniform.csv: 11 rows, the first shard's has 12");
  BOOST_TEST(refusal([&](const fs::path& p) {
               std::string t = text;
               t.replace(t.find("always_meet"), 11, "always_mean");
               std::ofstream(p) << t;
             }).find("merge: shard-1-of-3/uniform.csv, line 3: line_cylinder always_mean/double is not in the first shard's") == 0u);
  BOOST_TEST(refusal([&](const fs::path& p) {
               std::string t = text;
               t.replace(t.find(",34,"), 4, ",3x,");
               std::ofstream(p) << t;
             }) == "merge: shard-1-of-3/uniform.csv, line 2: not a row");
}
