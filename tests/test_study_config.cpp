// The study's configuration is checked before any work, and its results are written whole or
// the command fails: every option and configuration key with a wrong type, a value out of range
// (never truncated or wrapped), an unknown method or family, a folder name leaving --out, a
// missing or malformed file, each with its exact message and no results folder; and, through the
// binary, option values that would wrap (study and make-scene), standard output on a full device
// (/dev/full) and a merged file on a full device, each a message and exit status 1.
#define BOOST_TEST_MODULE study_config
#include <boost/test/unit_test.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <sys/wait.h>
#include <unistd.h>

#include "study.hpp"
#include "study_internal.hpp"

using namespace certcyl;
namespace fs = std::filesystem;

namespace {

const fs::path root = fs::temp_directory_path() / ("certcyl_study_config_" + std::to_string(::getpid()));

std::string text_of(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The names configure_study checks method filters against (the real registry's are longer).
const std::vector<std::string> kMethods = {"shene/double", "shene/gmpfr53", "gullotti/double", "eberly_cylinders/double"};

// The message of configure_study on a configuration file holding `json` ("" if it passes);
// checks that nothing was written under --out.
std::string config_error(const std::string& json, cli::StudyOptions o = {}) {
  fs::create_directories(root);
  const fs::path file = root / "config.json";
  std::ofstream(file, std::ios::binary) << json;
  o.config_file = file.string();
  o.out_root = (root / "out").string();
  try {
    cli::configure_study(o, kMethods);
  } catch (const std::invalid_argument& e) {
    BOOST_TEST(!fs::exists(root / "out"));
    return e.what();
  }
  return "";
}

std::string option_error(cli::StudyOptions o) {
  o.out_root = (root / "out").string();
  try {
    cli::configure_study(o, kMethods);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

std::string shard_error(const std::string& s) {
  int i = -1, n = -1;
  try {
    cli::parse_shard(s, i, n);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

struct Run {
  int status;
  std::string err;
};

// Runs the binary with `args` (a shell command line tail) and standard error to a file.
Run run(const std::string& args) {
  fs::create_directories(root);
  const fs::path err = root / "stderr.txt";
  const int raw = std::system((std::string(CERTCYL_BINARY) + " " + args + " 2> '" + err.string() + "'").c_str());
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, text_of(err)};
}

// A study of a few seconds: one family, the double methods, one instance per query.
const std::string kSmall =
    R"({"per_family": 1, "map_cells": 2, "hunt_evaluations": 1, "families": ["c_cap_cap"], "methods": ["/double"]})";

}  // namespace

BOOST_AUTO_TEST_CASE(unknown_method_or_family) {
  BOOST_TEST(config_error(R"({"families": ["c_cap_cop"]})") == "--config: families: unknown family 'c_cap_cop' (nearest: c_cap_cap)");
  // Filters are substrings: "gulloti" is 1 edit from "gullotti" in one name only.
  BOOST_TEST(config_error(R"({"methods": ["gulloti/"]})") == "--config: methods: 'gulloti/' is in no method's name (nearest: gullotti/double)");
  BOOST_TEST(config_error(R"({"methods": ["/double", ""]})") == "--config: methods[1]: expected a non-empty string");
  BOOST_TEST(config_error(R"({"families": ["c_cap_cap"], "methods": ["shene"]})").empty());
}

BOOST_AUTO_TEST_CASE(integers_in_range_never_truncated) {
  BOOST_TEST(config_error(R"({"per_family": -3})") == "--config: per_family: expected an integer in [1, 10000000], got -3");
  BOOST_TEST(config_error(R"({"per_family": 0})") == "--config: per_family: expected an integer in [1, 10000000], got 0");
  BOOST_TEST(config_error(R"({"per_family": 2.5})") == "--config: per_family: expected an integer in [1, 10000000], got 2.5");
  BOOST_TEST(config_error(R"({"per_family": "3"})") == "--config: per_family: expected an integer in [1, 10000000], got \"3\"");
  // 2^32 + 16 would wrap to 16 in an int.
  BOOST_TEST(config_error(R"({"map_cells": 4294967312})") == "--config: map_cells: expected an integer in [2, 1024], got 4294967312");
  BOOST_TEST(config_error(R"({"map_step": 0})") == "--config: map_step: expected an integer in [1, 1000000000], got 0");
  BOOST_TEST(config_error(R"({"hunt_evaluations": 100000001})") ==
             "--config: hunt_evaluations: expected an integer in [1, 100000000], got 100000001");
  BOOST_TEST(config_error(R"({"seed": -1})") == "--config: seed: expected an integer in [0, 18446744073709551615], got -1");
  // 2^64 is read as a double: out of range, not wrapped to 0.
  BOOST_TEST(config_error(R"({"seed": 18446744073709551616})") ==
             "--config: seed: expected an integer in [0, 18446744073709551615], got 1.8446744073709552e+19");
  BOOST_TEST(config_error(R"({"size": 20000000})") == "--config: size: expected an integer in [1, 10000000], got 20000000");
  BOOST_TEST(config_error(R"({"seed": 18446744073709551615, "per_family": 10000000, "size": 7})").empty());
}

BOOST_AUTO_TEST_CASE(type_errors_name_their_key) {
  BOOST_TEST(config_error(R"({"size": true})") == "--config: size: expected a string, got true");
  BOOST_TEST(config_error(R"({"methods": "shene"})") == "--config: methods: expected an array of strings, got \"shene\"");
  BOOST_TEST(config_error(R"({"families": [1]})") == "--config: families[0]: expected a string, got 1");
  BOOST_TEST(config_error(R"({"name": null})") == "--config: name: expected a string, got null");
  BOOST_TEST(config_error(R"([1, 2])") == "--config: expected a JSON object, got array");
  BOOST_TEST(config_error(R"({"per_famliy": 3})") ==
             "--config: unknown key 'per_famliy' (per_family, map_cells, map_step, hunt_evaluations, uniform_per_query, methods, families, size, seed, name)");
}

BOOST_AUTO_TEST_CASE(name_stays_inside_out) {
  const std::string expected = "--config: name: expected a plain folder name (not empty, no '/', not starting with '.'), got '";
  BOOST_TEST(config_error(R"({"name": "../escape"})") == expected + "../escape'");
  BOOST_TEST(config_error(R"({"name": "/tmp/escape"})") == expected + "/tmp/escape'");
  BOOST_TEST(config_error(R"({"name": ".."})") == expected + "..'");
  BOOST_TEST(config_error(R"({"name": ".hidden"})") == expected + ".hidden'");
  BOOST_TEST(config_error(R"({"name": "a/b"})") == expected + "a/b'");
  BOOST_TEST(config_error(R"({"name": ""})") == expected + "'");
  cli::StudyOptions o;
  o.name = "x/../../y";
  BOOST_TEST(option_error(o) == "--name: expected a plain folder name (not empty, no '/', not starting with '.'), got 'x/../../y'");
  BOOST_TEST(config_error(R"({"name": "plain-name_1"})").empty());
}

BOOST_AUTO_TEST_CASE(options_checked) {
  cli::StudyOptions o;
  for (const char* size : {"-3", "0", "2.5", "3x", "99999999999999999999", "10000001", ""}) {
    o.size = size;
    BOOST_TEST(option_error(o) == "--size: expected tiny, small, default, large or an integer in [1, 10000000], got '" + std::string(size) + "'");
  }
  o.size = "tiny";
  o.out_root = "";
  try {
    cli::configure_study(o, kMethods);
    BOOST_TEST(false, "empty --out accepted");
  } catch (const std::invalid_argument& e) {
    BOOST_TEST(std::string(e.what()) == "--out: expected a folder, got ''");
  }
  fs::create_directories(root);
  std::ofstream(root / "a_file") << "x";
  o.out_root = (root / "a_file").string();
  try {
    cli::configure_study(o, kMethods);
    BOOST_TEST(false, "a file as --out accepted");
  } catch (const std::invalid_argument& e) {
    BOOST_TEST(std::string(e.what()) == "--out: '" + (root / "a_file").string() + "' is not a folder");
  }
  const std::string shard = "--shard: expected i/n with integers 0 <= i < n <= 100000, got '";
  for (const char* s : {"a/b", "3/2", "-1/2", "1/-2", "0/0", "1", "0x1/2", " 1/2", "1/2.0", "0/4294967297"})
    BOOST_TEST(shard_error(s) == shard + s + "'");
  BOOST_TEST(shard_error("3/8").empty());
  BOOST_TEST(cli::integer_error("-1", 0, 1024) == "expected an integer in [0, 1024], got '-1'");
  BOOST_TEST(cli::integer_error("0x10", 0, 1024) == "expected an integer in [0, 1024], got '0x10'");
  BOOST_TEST(cli::integer_error("18446744073709551616", 0, UINT64_MAX) == "expected an integer in [0, 18446744073709551615], got '18446744073709551616'");
  BOOST_TEST(cli::integer_error("18446744073709551615", 0, UINT64_MAX).empty());
}

// An integer --size N is N instances per family and query (README, experiments/STUDY.md), with
// the failure maps and the hunt of the smallest preset holding at least N per family (tiny 3,
// small 12, default 96, large 400; large's beyond) and 1000 N uniform instances per query; the
// preset values are those the README and STUDY.md give.
BOOST_AUTO_TEST_CASE(an_integer_size_takes_the_maps_of_the_preset_it_lies_under) {
  struct Expected {
    const char* size;
    long per_family;
    int map_cells;
    long hunt, uniform;
  };
  for (const Expected& e : {Expected{"tiny", 3, 16, 20, 200}, Expected{"1", 1, 16, 20, 1000}, Expected{"3", 3, 16, 20, 3000},
                            Expected{"4", 4, 64, 150, 4000}, Expected{"12", 12, 64, 150, 12000}, Expected{"small", 12, 64, 150, 5000},
                            Expected{"13", 13, 128, 250, 13000}, Expected{"96", 96, 128, 250, 96000},
                            Expected{"default", 96, 128, 250, 100000}, Expected{"97", 97, 256, 5000, 97000},
                            Expected{"large", 400, 256, 5000, 1000000}, Expected{"10000000", 10000000, 256, 5000, 100000000}}) {
    cli::StudyOptions o;
    o.size = e.size;
    cli::detail::apply_size(o);
    BOOST_TEST(o.per_family == e.per_family, e.size);
    BOOST_TEST(o.map_cells == e.map_cells, e.size);
    BOOST_TEST(o.hunt_evaluations == e.hunt, e.size);
    BOOST_TEST(o.uniform_per_query == e.uniform, e.size);
  }
  // What the file or the command line sets is kept.
  cli::StudyOptions o;
  o.size = "5";
  o.map_cells = 8;
  cli::detail::apply_size(o);
  BOOST_TEST(o.map_cells == 8);
  BOOST_TEST(o.per_family == 5);
}

BOOST_AUTO_TEST_CASE(missing_or_malformed_file) {
  cli::StudyOptions o;
  o.config_file = (root / "no_such.json").string();
  BOOST_TEST(option_error(o) == "--config: cannot read '" + o.config_file + "': No such file or directory");
  // A file that exists but is not JSON is malformed, with the line and column.
  const std::string e = config_error("{\n  \"per_family\": 3,\n}\n");
  BOOST_TEST(e.rfind("--config: '" + (root / "config.json").string() + "' is malformed JSON at line 3, column 1: syntax error", 0) == 0, e);
  BOOST_TEST(config_error(R"({"seed": 1e999})") == "--config: '" + (root / "config.json").string() + "' is malformed JSON: number overflow parsing '1e999'");
  const std::string empty = config_error("");
  BOOST_TEST(empty.rfind("--config: '" + (root / "config.json").string() + "' is malformed JSON at line 1, column 1: ", 0) == 0, empty);
}

BOOST_AUTO_TEST_CASE(command_line_values_never_wrap) {
  Run r = run("study --seed -1 --no-plots");
  BOOST_TEST(r.status == 1);
  BOOST_TEST(r.err.rfind("--seed: expected an integer in [0, 18446744073709551615], got '-1'\n", 0) == 0, r.err);
  r = run("study --threads -1 --no-plots");
  BOOST_TEST(r.status == 1);
  BOOST_TEST(r.err.rfind("--threads: expected an integer in [0, 1024], got '-1'\n", 0) == 0, r.err);
  // The scene generator's seed likewise (it wrapped -1 to 2^64 - 1).
  r = run("make-scene --cylinders 2 --seed -1 > /dev/null");
  BOOST_TEST(r.status == 1);
  BOOST_TEST(r.err.rfind("--seed: expected an integer in [0, 18446744073709551615], got '-1'\n", 0) == 0, r.err);
  r = run("study --shard 1/x --no-plots --out '" + (root / "out").string() + "'");
  BOOST_TEST(r.status == 1);
  BOOST_TEST(r.err == "certcyl: --shard: expected i/n with integers 0 <= i < n <= 100000, got '1/x'\n");
  BOOST_TEST(!fs::exists(root / "out"));
}

BOOST_AUTO_TEST_CASE(command_line_wins_over_the_file) {
  const std::string file = R"({"size": "small", "seed": 7, "name": "from_file"})";
  cli::StudyOptions o;
  BOOST_TEST(config_error(file, o).empty());
  // The file alone: its size, seed and name.
  o.config_file = (root / "config.json").string();
  o.out_root = (root / "out").string();
  cli::configure_study(o, kMethods);
  BOOST_TEST(o.size == "small");
  BOOST_TEST(o.seed == 7u);
  BOOST_TEST(o.name == "from_file");
  BOOST_TEST(o.per_family == 12);
  // The same keys given on the command line win, each on its own.
  for (int given = 0; given < 3; ++given) {
    cli::StudyOptions c;
    c.config_file = (root / "config.json").string();
    c.out_root = (root / "out").string();
    c.size = "tiny", c.seed = 3, c.name = "from_command_line";
    c.size_given = given == 0, c.seed_given = given == 1, c.name_given = given == 2;
    cli::configure_study(c, kMethods);
    BOOST_TEST(c.size == (given == 0 ? "tiny" : "small"));
    BOOST_TEST(c.per_family == (given == 0 ? 3 : 12));
    BOOST_TEST(c.seed == (given == 1 ? 3u : 7u));
    BOOST_TEST(c.name == (given == 2 ? "from_command_line" : "from_file"));
  }
  // A key the command line overrides is still checked.
  cli::StudyOptions c;
  c.seed_given = true;
  BOOST_TEST(config_error(R"({"seed": -1})", c) == "--config: seed: expected an integer in [0, 18446744073709551615], got -1");
  c.name_given = true;
  BOOST_TEST(config_error(R"({"name": "../escape"})", c) ==
             "--config: name: expected a plain folder name (not empty, no '/', not starting with '.'), got '../escape'");
}

BOOST_AUTO_TEST_CASE(command_line_wins_through_the_binary) {
  // The options the command line gave are the ones machine.json records, and the folder is its name.
  fs::create_directories(root);
  std::ofstream(root / "named.json") << R"({"per_family": 1, "map_cells": 2, "hunt_evaluations": 1, "families": ["c_cap_cap"],
      "methods": ["/double"], "size": "small", "seed": 7, "name": "from_file"})";
  const std::string out = (root / "precedence").string();
  const std::string common = "study --config '" + (root / "named.json").string() + "' --out '" + out + "' --no-plots --no-progress --threads 1";
  BOOST_TEST_REQUIRE(run(common + " --size 2 --seed 5 --name from_command_line > /dev/null").status == 0);
  BOOST_TEST(!fs::exists(out + "/from_file"));
  std::string machine = text_of(out + "/from_command_line/machine.json");
  BOOST_TEST(machine.find(R"("name": "from_command_line")") != std::string::npos, machine);
  BOOST_TEST(machine.find(R"("size": "2")") != std::string::npos, machine);
  BOOST_TEST(machine.find(R"("seed": 5,)") != std::string::npos, machine);
  BOOST_TEST_REQUIRE(run(common + " > /dev/null").status == 0);
  machine = text_of(out + "/from_file/machine.json");
  BOOST_TEST(machine.find(R"("size": "small")") != std::string::npos, machine);
  BOOST_TEST(machine.find(R"("seed": 7,)") != std::string::npos, machine);
  fs::remove_all(out);
}

BOOST_AUTO_TEST_CASE(progress_lines_in_a_log) {
  // Standard error is a file here, as in a log or a batch job's output: progress is on by
  // default, as plain lines (no carriage return), one at the end of each phase and one every
  // --progress-every seconds; --no-progress turns it off.
  fs::create_directories(root);
  std::ofstream(root / "small.json") << kSmall;
  const std::string out = (root / "progress").string();
  const std::string common = "study --config '" + (root / "small.json").string() + "' --out '" + out + "' --no-plots --threads 1";
  const auto lines_of = [](const std::string& text, const std::string& prefix) {
    std::size_t n = 0;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) n += line.rfind(prefix, 0) == 0 && line.find("%, ") != std::string::npos;
    return n;
  };
  Run r = run(common + " --name default_on > /dev/null");
  BOOST_TEST_REQUIRE(r.status == 0);
  BOOST_TEST(r.err.find('\r') == std::string::npos);
  BOOST_TEST(lines_of(r.err, "instances: ") == 1u, r.err);
  BOOST_TEST(r.err.find("(100%, ") != std::string::npos, r.err);
  BOOST_TEST(lines_of(r.err, "hunting: ") == 1u, r.err);
  // An interval shorter than one step: a line per step, the last at 100%.
  r = run(common + " --name every_step --progress-every 0 > /dev/null");
  BOOST_TEST_REQUIRE(r.status == 0);
  BOOST_TEST(r.err.find('\r') == std::string::npos);
  BOOST_TEST(lines_of(r.err, "hunting: ") > 1u, r.err);
  BOOST_TEST(r.err.find("hunting: 1/") != std::string::npos, r.err);
  r = run(common + " --name quiet --no-progress > /dev/null");
  BOOST_TEST(r.status == 0);
  BOOST_TEST(r.err.empty(), r.err);
  fs::remove_all(out);
}

BOOST_AUTO_TEST_CASE(full_device) {
  fs::create_directories(root);
  std::ofstream(root / "small.json") << kSmall;
  const std::string out = (root / "results").string();
  const std::string common = "--config '" + (root / "small.json").string() + "' --out '" + out + "' --no-plots --no-progress --threads 1";
  // The summary on a full standard output.
  Run r = run("study " + common + " --name whole > /dev/full");
  BOOST_TEST(r.status == 1);
  BOOST_TEST(r.err == "certcyl study: error writing standard output\n");
  // Two shards merged; the merge's summary and its instances.csv on a full device.
  BOOST_TEST_REQUIRE(run("study " + common + " --name sharded --shard 0/2 > /dev/null").status == 0);
  BOOST_TEST_REQUIRE(run("study " + common + " --name sharded --shard 1/2 > /dev/null").status == 0);
  r = run("merge --no-plots '" + out + "/sharded' > /dev/full");
  BOOST_TEST(r.status == 1);
  BOOST_TEST(r.err == "certcyl merge: error writing standard output\n");
  fs::remove(out + "/sharded/instances.csv");
  fs::create_symlink("/dev/full", out + "/sharded/instances.csv");
  r = run("merge --no-plots '" + out + "/sharded' > /dev/null");
  BOOST_TEST(r.status == 1);
  BOOST_TEST(r.err == "certcyl: error writing " + out + "/sharded/instances.csv: No space left on device\n");
  fs::remove_all(root);
}
