// The study's timing protocol: run_timed's repetition rule (measurements of calls in batches of
// 1, 2, 4, ... until the budget has elapsed, the first call's output kept, a throwing call made
// once), and the timing files of a small study: timing_thread.csv says what was pinned, and
// timing.csv, timing_families.csv and timing_stages.csv hold ordered percentiles whose counts add
// up to the rows of instances.csv. No assertion depends on how fast anything ran.
#define BOOST_TEST_MODULE study_timing
#include <boost/test/unit_test.hpp>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "study_internal.hpp"

using namespace certcyl;
using namespace certcyl::study;
using certcyl::cli::detail::split_csv;
namespace fs = std::filesystem;

namespace {

Method counting_method(long& calls, std::function<void()> body = {}) {
  Method m;
  m.base = "counting", m.nt = "double";
  m.run = [&calls, body](const std::vector<double>&) {
    ++calls;
    if (body) body();
    MethodOutput o;
    o.answer = Answer::separated;
    return o;
  };
  return m;
}

// The rows of a CSV file as maps from column to field.
std::vector<std::map<std::string, std::string>> read_csv(const fs::path& p) {
  std::ifstream in(p);
  std::string line;
  std::vector<std::map<std::string, std::string>> rows;
  if (!std::getline(in, line)) return rows;
  const auto header = split_csv(line);
  while (std::getline(in, line)) {
    const auto f = split_csv(line);
    BOOST_TEST_REQUIRE(f.size() == header.size(), p.filename().string() + ": " + line);
    std::map<std::string, std::string> r;
    for (std::size_t i = 0; i < f.size(); ++i) r[header[i]] = f[i];
    rows.push_back(std::move(r));
  }
  return rows;
}

// p10 <= p50 <= p90 <= max, the mean within [p0, max] (so at most max), all positive.
void check_times(const std::map<std::string, std::string>& r, const std::string& where) {
  const double p10 = std::stod(r.at("p10_ns")), p50 = std::stod(r.at("p50_ns")), p90 = std::stod(r.at("p90_ns")),
               mean = std::stod(r.at("mean_ns")), max = std::stod(r.at("max_ns"));
  BOOST_TEST(p10 > 0, where);
  BOOST_TEST(p10 <= p50, where);
  BOOST_TEST(p50 <= p90, where);
  BOOST_TEST(p90 <= max, where);
  BOOST_TEST(mean <= max, where);
  BOOST_TEST(std::stol(r.at("n")) > 0, where);
}

}  // namespace

BOOST_AUTO_TEST_CASE(repetition_protocol) {
  // A fast call is repeated in doubling batches in each measurement: more than once in each.
  long calls = 0;
  const Method fast = counting_method(calls);
  const auto [out, ns] = cli::detail::run_timed(fast, {});
  BOOST_TEST(out.answer == Answer::separated);
  BOOST_TEST(calls > 2 * cli::detail::kTimingMeasurements, calls);
  BOOST_TEST(ns > 0);
  // A call that lasts longer than the budget is made once per measurement.
  long slow_calls = 0;
  const Method slow = counting_method(slow_calls, [] {
    std::this_thread::sleep_for(std::chrono::nanoseconds(static_cast<long>(2 * cli::detail::kTimingBudgetNs)));
  });
  const double slow_ns = cli::detail::run_timed(slow, {}).second;
  BOOST_TEST(slow_calls == cli::detail::kTimingMeasurements);
  BOOST_TEST(slow_ns >= 2 * cli::detail::kTimingBudgetNs);
  // A call that throws: an error, made once.
  long throwing_calls = 0;
  const Method throwing = counting_method(throwing_calls, [] { throw std::runtime_error("no"); });
  BOOST_TEST(cli::detail::run_timed(throwing, {}).first.error);
  BOOST_TEST(throwing_calls == 1);
}

BOOST_AUTO_TEST_CASE(timing_files_of_a_study) {
  const fs::path root = fs::temp_directory_path() / ("certcyl_study_timing_" + std::to_string(::getpid()));
  fs::remove_all(root);
  cli::StudyOptions o;
  o.out_root = root.string(), o.name = "t", o.size = "4", o.threads = 2, o.progress = false, o.plots = false;
  o.map_cells = 2, o.hunt_evaluations = 1;
  o.families = {"uniform", "c_cap_cap", "c_rim_rim", "tangent"};
  std::ostringstream out;
  BOOST_TEST_REQUIRE(cli::run_study(o, out) == 0);
  const fs::path dir = root / "t";

  // The timing thread: pinned to a CPU, or not pinned with the reason.
  const auto thread = read_csv(dir / "timing_thread.csv");
  BOOST_TEST_REQUIRE(thread.size() == 1u);
  const auto& t = thread[0];
  BOOST_TEST(t.at("shard") == "0");
  BOOST_TEST((t.at("pinned") == "1" || t.at("pinned") == "0"));
  BOOST_TEST(t.at("cpu").empty() == (t.at("pinned") == "0"));
  BOOST_TEST(t.at("note").find(t.at("pinned") == "1" ? "pinned the main thread" : "not pinned") == 0u, t.at("note"));
  BOOST_TEST(std::stod(t.at("budget_ns")) == cli::detail::kTimingBudgetNs);
  BOOST_TEST(std::stoi(t.at("measurements")) == cli::detail::kTimingMeasurements);
  BOOST_TEST(out.str().find("timing (shard 0): one thread") != std::string::npos, out.str());

  // The rows timed per (query, method), per input class, per family.
  std::map<std::string, long> rows_of, generic_of, family_of;
  long certified_pairs = 0;
  for (const auto& r : read_csv(dir / "instances.csv")) {
    if (r.at("answer") == "process_ended") continue;
    const std::string key = r.at("query") + " " + r.at("method");
    ++rows_of[key];
    generic_of[key + (r.at("family") == "uniform" ? " generic" : " near_degenerate")] += 1;
    ++family_of[key + " " + r.at("family")];
    certified_pairs += r.at("query") == "cylinder_cylinder" && r.at("kind") == "certified";
  }
  BOOST_TEST_REQUIRE(certified_pairs > 0);

  // timing.csv: per (query, method) an "all" row and one per input class, adding up.
  std::map<std::string, long> all_n, class_n;
  for (const auto& r : read_csv(dir / "timing.csv")) {
    const std::string key = r.at("query") + " " + r.at("method");
    check_times(r, "timing.csv " + key + " " + r.at("inputs"));
    if (r.at("inputs") == "all") {
      all_n[key] = std::stol(r.at("n"));
    } else {
      BOOST_TEST((r.at("inputs") == "generic" || r.at("inputs") == "near_degenerate"), r.at("inputs"));
      class_n[key] += std::stol(r.at("n"));
      BOOST_TEST(std::stol(r.at("n")) == generic_of[key + " " + r.at("inputs")], key + " " + r.at("inputs"));
    }
  }
  BOOST_TEST(all_n.size() == rows_of.size());
  for (const auto& [key, n] : rows_of) {
    BOOST_TEST(all_n[key] == n, key);
    BOOST_TEST(class_n[key] == n, key);
  }

  // timing_families.csv: one row per (query, family, method), its count that of instances.csv.
  std::size_t families = 0;
  for (const auto& r : read_csv(dir / "timing_families.csv")) {
    const std::string key = r.at("query") + " " + r.at("method") + " " + r.at("family");
    check_times(r, "timing_families.csv " + key);
    BOOST_TEST(std::stol(r.at("n")) == family_of[key], key);
    BOOST_TEST(r.at("inputs") == (r.at("family") == "uniform" ? "generic" : "near_degenerate"), key);
    ++families;
  }
  BOOST_TEST(families == family_of.size());

  // timing_stages.csv: the certified cylinder pairs by deciding stage, adding up to all of them.
  long staged = 0;
  for (const auto& r : read_csv(dir / "timing_stages.csv")) {
    check_times(r, "timing_stages.csv " + r.at("method") + " " + r.at("stage") + " " + r.at("inputs"));
    BOOST_TEST(r.at("query") == "cylinder_cylinder");
    if (r.at("inputs") == "all") staged += std::stol(r.at("n"));
  }
  BOOST_TEST(staged == certified_pairs);
  fs::remove_all(root);
}
