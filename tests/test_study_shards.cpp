// Shards that cannot lie: SHA-256 against the published test vectors; a shard sealed by its
// manifest; merge refusing every damaged shard (naming the shard and the file) and a killed
// re-run leaving the old shard whole or absent, never mixed; a killed shard detected and re-run.
// A small configuration (two families, the double methods) keeps each shard to a second or so.
#define BOOST_TEST_MODULE study_shards
#include <boost/test/unit_test.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <sys/wait.h>
#include <unistd.h>

#include "study.hpp"
#include "study_internal.hpp"

using namespace certcyl;
namespace fs = std::filesystem;

namespace {

const fs::path root = fs::temp_directory_path() / ("certcyl_study_shards_" + std::to_string(::getpid()));

std::string text_of(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_text(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

cli::StudyOptions small(const std::string& name, int index, int count) {
  cli::StudyOptions o;
  o.out_root = root.string();
  o.name = name;
  o.size = "4";
  o.map_cells = 4;
  o.hunt_evaluations = 8;
  o.families = {"tangent", "c_cap_cap"};
  o.methods = {"/double"};
  o.threads = 2;
  o.progress = false;
  o.plots = false;
  o.shard_index = index;
  o.shard_count = count;
  return o;
}

void run_shard(const std::string& name, int index, int count) {
  std::ostringstream out;
  BOOST_TEST_REQUIRE(cli::run_study(small(name, index, count), out) == 0);
}

// The message merge refuses with, or "merged".
std::string merge_error(const fs::path& dir) {
  std::ostringstream out;
  try {
    if (cli::run_merge(dir.string(), false, out) != 0) return out.str();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "merged";
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// Two good shards of 2, made once; each damage test copies them.
const fs::path& good_pair() {
  static const fs::path dir = [] {
    run_shard("good", 0, 2);
    run_shard("good", 1, 2);
    return root / "good";
  }();
  return dir;
}

fs::path copy_of_good(const std::string& name) {
  const fs::path to = root / name;
  fs::remove_all(to);
  fs::create_directories(to);
  for (const char* s : {"shard-0-of-2", "shard-1-of-2"}) fs::copy(good_pair() / s, to / s, fs::copy_options::recursive);
  return to;
}

// Runs shard index/count of `name` in a child process with a hunt too long to finish, and kills
// it once it has written `file` in its partial folder: a run killed part-way.
void killed_run(const std::string& name, int index, int count, const std::string& file) {
  std::cout.flush(), std::cerr.flush();
  const pid_t pid = fork();
  BOOST_TEST_REQUIRE(pid >= 0);
  if (pid == 0) {
    cli::StudyOptions o = small(name, index, count);
    o.hunt_evaluations = 1L << 40;
    std::ostringstream out;
    cli::run_study(o, out);
    _exit(0);
  }
  const fs::path partial = root / name / (".shard-" + std::to_string(index) + "-of-" + std::to_string(count) + ".partial");
  int status = 0;
  bool ended = false;
  while (!fs::exists(partial / file) && !ended) {
    ended = waitpid(pid, &status, WNOHANG) == pid;
    usleep(1000);
  }
  BOOST_TEST_REQUIRE(!ended, "the run ended before it wrote " << file);
  kill(pid, SIGKILL);
  waitpid(pid, &status, 0);
}

struct Cleanup {
  ~Cleanup() { fs::remove_all(root); }
};
Cleanup cleanup;

}  // namespace

BOOST_AUTO_TEST_CASE(sha256_test_vectors) {
  // FIPS 180-2, appendix B.1 and B.2, and the empty message.
  fs::create_directories(root);
  const fs::path p = root / "vector";
  write_text(p, "abc");
  BOOST_TEST(cli::detail::sha256_file(p) == "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  write_text(p, "abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq");
  BOOST_TEST(cli::detail::sha256_file(p) == "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  write_text(p, "");
  BOOST_TEST(cli::detail::sha256_file(p) == "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
}

BOOST_AUTO_TEST_CASE(a_shard_is_sealed_by_its_manifest) {
  const fs::path shard = good_pair() / "shard-1-of-2";
  BOOST_TEST(!fs::exists(good_pair() / ".shard-1-of-2.partial"));
  const auto manifest = nlohmann::json::parse(std::ifstream(shard / "manifest.json"));
  BOOST_TEST(manifest["shard"] == "1/2");
  BOOST_TEST(manifest["options"]["seed"] == 1);
  BOOST_TEST(manifest["build"].contains("commit"));
  for (const char* file : {"instances.csv", "inputs.csv", "hunt.csv", "machine.json"}) {
    BOOST_TEST_REQUIRE(manifest["files"].contains(file), file);
    BOOST_TEST(manifest["files"][file]["sha256"].get<std::string>().size() == 64u, file);
    BOOST_TEST(manifest["files"][file]["bytes"] == fs::file_size(shard / file), file);
  }
  // Rows: the lines of the file but its header, counted here independently.
  const std::string instances = text_of(shard / "instances.csv");
  const long lines = static_cast<long>(std::count(instances.begin(), instances.end(), '\n'));
  BOOST_TEST(lines > 10);
  BOOST_TEST(manifest["files"]["instances.csv"]["rows"] == lines - 1);
  BOOST_TEST(merge_error(copy_of_good("intact")) == "merged");
  // A re-run into a finished shard's folder replaces it whole: a file only the old one had is gone.
  const fs::path again = copy_of_good("again");
  write_text(again / "shard-0-of-2" / "stray.csv", "a\n1\n");
  run_shard("again", 0, 2);
  BOOST_TEST(!fs::exists(again / "shard-0-of-2" / "stray.csv"));
  BOOST_TEST(merge_error(again) == "merged");
}

BOOST_AUTO_TEST_CASE(merge_refuses_damaged_shards) {
  // instances.csv empty.
  {
    const fs::path d = copy_of_good("empty");
    write_text(d / "shard-0-of-2" / "instances.csv", "");
    const std::string e = merge_error(d);
    BOOST_TEST(contains(e, "shard-0-of-2/instances.csv: 0 data rows, the manifest lists"), e);
  }
  // Cut at a row boundary: the header and the first row only.
  {
    const fs::path d = copy_of_good("cut");
    const fs::path f = d / "shard-1-of-2" / "instances.csv";
    const std::string text = text_of(f);
    const std::size_t second = text.find('\n', text.find('\n') + 1);
    write_text(f, text.substr(0, second + 1));
    const std::string e = merge_error(d);
    BOOST_TEST(contains(e, "shard-1-of-2/instances.csv: 1 data rows, the manifest lists"), e);
  }
  // Rows appended twice.
  {
    const fs::path d = copy_of_good("twice");
    const fs::path f = d / "shard-0-of-2" / "inputs.csv";
    const std::string text = text_of(f);
    write_text(f, text + text.substr(text.find('\n') + 1));
    const std::string e = merge_error(d);
    BOOST_TEST(contains(e, "shard-0-of-2/inputs.csv:"), e);
    BOOST_TEST(contains(e, "data rows, the manifest lists"), e);
  }
  // Garbage of the same length and line count: only the digest tells.
  {
    const fs::path d = copy_of_good("garbage");
    const fs::path f = d / "shard-1-of-2" / "instances.csv";
    std::string text = text_of(f);
    for (char& c : text)
      if (c != '\n') c = '#';
    write_text(f, text);
    const std::string e = merge_error(d);
    BOOST_TEST(e == "merge: shard-1-of-2/instances.csv: SHA-256 differs from the manifest (the file was altered)");
  }
  // A file missing, a file not in the manifest, no manifest.
  {
    const fs::path d = copy_of_good("missing_file");
    fs::remove(d / "shard-1-of-2" / "hunt.csv");
    const std::string e = merge_error(d);
    BOOST_TEST(e == "merge: shard-1-of-2/hunt.csv: missing (listed in the manifest)");
  }
  {
    const fs::path d = copy_of_good("extra_file");
    write_text(d / "shard-0-of-2" / "more.csv", "a,b\n1,2\n");
    const std::string e = merge_error(d);
    BOOST_TEST(e == "merge: shard-0-of-2/more.csv: not in the manifest");
  }
  {
    const fs::path d = copy_of_good("no_manifest");
    fs::remove(d / "shard-0-of-2" / "manifest.json");
    const std::string e = merge_error(d);
    BOOST_TEST(contains(e, "shard-0-of-2: no manifest.json"), e);
  }
  // A shard of another configuration (another seed), sealed and intact.
  {
    const fs::path d = copy_of_good("other_configuration");
    fs::remove_all(d / "shard-1-of-2");
    cli::StudyOptions o = small("other_configuration", 1, 2);
    o.seed = 2;
    std::ostringstream out;
    BOOST_TEST_REQUIRE(cli::run_study(o, out) == 0);
    const std::string e = merge_error(d);
    BOOST_TEST(contains(e, "different configurations: seed is 1 in shard-0-of-2 but 2 in shard-1-of-2"), e);
  }
}

// A re-run of a finished shard killed part-way: the old shard stays whole (the run writes
// elsewhere and replaces it only when complete); the re-run, had it finished, would be of
// another configuration (its hunt), so a mixture would not merge.
BOOST_AUTO_TEST_CASE(killed_rerun_never_mixes) {
  const fs::path d = copy_of_good("rerun");
  // instances.csv holds the timings: any rewrite of it would show.
  const std::string before = text_of(d / "shard-1-of-2" / "instances.csv");
  killed_run("rerun", 1, 2, "inputs.csv");
  BOOST_TEST(fs::exists(d / ".shard-1-of-2.partial" / "inputs.csv"));
  BOOST_TEST(text_of(d / "shard-1-of-2" / "instances.csv") == before);
  BOOST_TEST(merge_error(d) == "merged");
}

// Shards 0 and 1 of 3 finish: merge names the missing shard 2. Shard 2 killed part-way: merge
// names it and the unfinished run it left. Shard 2 re-run: the merge completes.
BOOST_AUTO_TEST_CASE(killed_shard_detected_and_rerun) {
  run_shard("three", 0, 3);
  run_shard("three", 1, 3);
  std::string e = merge_error(root / "three");
  BOOST_TEST(contains(e, "missing shard(s) 2 of 3 in "), e);
  killed_run("three", 2, 3, "instances.csv");
  BOOST_TEST_REQUIRE(!fs::exists(root / "three" / "shard-2-of-3"));
  e = merge_error(root / "three");
  BOOST_TEST(contains(e, "missing shard(s) 2 of 3 in "), e);
  BOOST_TEST(contains(e, "(unfinished runs left .shard-2-of-3.partial)"), e);
  // The re-run starts clean: nothing of the killed run's folder survives into the shard.
  write_text(root / "three" / ".shard-2-of-3.partial" / "stray.csv", "a\n1\n");
  run_shard("three", 2, 3);
  BOOST_TEST(!fs::exists(root / "three" / ".shard-2-of-3.partial"));
  BOOST_TEST(!fs::exists(root / "three" / "shard-2-of-3" / "stray.csv"));
  BOOST_TEST(merge_error(root / "three") == "merged");
  BOOST_TEST(fs::exists(root / "three" / "manifest.json"));
  // The merged instances: every shard's, each instance once.
  std::ifstream in(root / "three" / "inputs.csv");
  std::string line;
  std::getline(in, line);
  std::set<std::string> ids;
  long rows = 0;
  while (std::getline(in, line)) ++rows, ids.insert(line.substr(0, line.find(',')));
  BOOST_TEST(rows == static_cast<long>(ids.size()));
  BOOST_TEST(rows == 4 * 4);  // 4 per family and query: tangent (line, ray, segment), c_cap_cap
}
