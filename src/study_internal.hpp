// What the stages of the study share (study*.cpp): the rows of instances.csv and their CSV
// form, the planned instances, the methods run quietly or timed, a thread pool and a progress
// bar, and each stage's entry point. Internal to the command; the stages, in order:
//   study_plan.cpp       the configuration (size presets, --config, --shard) and the instances
//   study_instances.cpp  every method on every instance: answers, then timing on one pinned thread;
//                        instances.csv, inputs.csv, timing_thread.csv
//   study_child.cpp      the serial methods' calls in a child process (CORE::Expr may end it)
//   study_uniform.cpp    the uniform sample: typical-case error counts per query and method (uniform.csv)
//   study_maps.cpp       the failure maps (failure_maps/)
//   study_hunt.cpp       the worst-input hunt (hunt.csv)
//   study_machine.cpp    the build and machine facts (machine.json)
//   study_report.cpp     the summary tables from the CSV files, and the figures
//   study_stages.cpp     the stages that decided the certified cylinder pairs (stages.csv)
//   study_manifest.cpp   the results folder written aside, sealed by its manifest, renamed
//   study_merge.cpp      the shards verified, checked against each other and merged
//   study.cpp            `certcyl study`: the stages in order
#pragma once

#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <iostream>
#include <limits>
#include <mutex>
#include <ostream>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <unistd.h>

#include "study/instance.hpp"
#include "study/methods.hpp"
#include "study.hpp"

namespace certcyl::cli::detail {

namespace fs = std::filesystem;

// ---- Rows and their CSV form (study_rows.cpp) --------------------------------------------------

// One row of instances.csv: one method on one instance.
struct Row {
  std::string family, query;
  std::uint64_t instance = 0;
  long long k = 0;
  std::string expected, method, base, nt, kind, answer, certified, outcome;
  double gap_lo = 0, gap_hi = 0, ns = 0;
  double t_error = std::numeric_limits<double>::quiet_NaN();
  // The method's contract, the certified answer under it (outcome judges against this one), the
  // certified answer of the instance the method received (empty: the input itself) and, for a
  // wrong answer, its cause (study/conversion.hpp).
  std::string contract = "solid", contract_answer, received_answer, cause;
};

extern const char* const kRowHeader;     // instances.csv
extern const char* const kInputsHeader;  // inputs.csv
extern const char* const kHuntHeader;    // hunt.csv

// A double as %.17g (round trip), "" for NaN, "inf" and "-inf"; parse_num is its inverse.
std::string num(double d);
double parse_num(const std::string& s);
void write_row(std::ostream& os, const Row& r);
// Throws std::runtime_error on a line that is not a row of instances.csv.
Row parse_row(const std::string& line);
// One CSV field as RFC 4180 writes it: as is, or in double quotes (each quote doubled) when it
// holds a comma, a quote, a line break or leading or trailing space (a judged method's name is
// free text: a command, a label, a file's name); split_csv is its inverse on a line of fields,
// the one reader of the study's CSV rows.
std::string csv_field(const std::string& s);
std::vector<std::string> split_csv(const std::string& line);
// The coordinates as hexfloats separated by spaces.
std::string x_hex(const std::vector<double>& x);

// ---- Configuration and plan (study_plan.cpp) ---------------------------------------------------

// The configuration file fills the options (the command line's --size, --seed and --name win),
// then the size preset what is left unset (an integer size N: N per family, the maps and the
// hunt of the smallest preset with at least N per family, large's beyond, 1000 N uniform).
void apply_size(StudyOptions& o);
void apply_config(StudyOptions& o);

std::uint64_t mix(std::uint64_t h, std::uint64_t v);
std::uint64_t hash_string(const std::string& s);
// True when the filter is empty or some entry is a substring of name.
bool keep_name(const std::vector<std::string>& filter, const std::string& name);

struct Planned {
  study::Instance inst;
  std::size_t index_in_family = 0;
  long long k = 0;
};

// This shard's instances of the configuration, in a fixed order; each depends only on the seed,
// its family, its query and its index, so any shard builds the same ones.
std::vector<Planned> plan_instances(const StudyOptions& o);

// ---- Running methods (study_instances.cpp) -----------------------------------------------------

// The outcome column of instances.csv: "uncertified" when the certified query left the instance
// undecided, else the judgement of the method's output (study/methods.hpp) against the certified
// answer under the method's contract (study/contract.hpp).
std::string outcome_of(const study::MethodOutput& m, const study::Instance& inst, study::Contract c = study::Contract::solid);

// The method's output (error set when it throws); serial methods one at a time.
study::MethodOutput run_quiet(const study::Method& m, const std::vector<double>& x);
// The timing protocol: a measurement calls a method until this many nanoseconds have elapsed,
// and the time is the median of kTimingMeasurements measurements.
constexpr double kTimingBudgetNs = 20000;
constexpr int kTimingMeasurements = 3;
// The first call's output and the time per call in nanoseconds under the study's one repetition
// protocol: kTimingMeasurements measurements, each of calls in batches of 1, 2, 4, ..., the clock
// read after each batch, until kTimingBudgetNs have elapsed since its first call began (at least
// one call), giving the elapsed time over its calls; the time is their median. A call that
// throws is made once (its time that call's).
std::pair<study::MethodOutput, double> run_timed(const study::Method& m, const std::vector<double>& x);

// The thread of the timing pass (timing_thread.csv, one row per run or shard): pinned to `cpu`
// or not, and the note that says what was pinned or why pinning failed.
struct TimingThread {
  int shard = 0;
  bool pinned = false;
  int cpu = -1;
  std::string note;
};
extern const char* const kTimingThreadHeader;  // timing_thread.csv

// A line method's entry parameter t against the certified t* (instances.csv's t_error_ulps, and
// the judge's): |t - t*| in units of the ulp of max(|t*|, 1), the parameter's own ulp away from
// 0 and an absolute measure near 0 (where counting representable doubles would make 1e-17
// against 0 an error of 2^62 "ulps").
double t_error_ulps(double t, double exact);

// One call of a serial method in ChildRunner: the output and time (run_timed; 0 untimed), or
// `ended` when the call ended the child (`reason`: the exit status or the signal; out.error set).
// `isolated` is false when no child could be started and the call ran in this process.
struct ChildCall {
  study::MethodOutput out;
  double ns = 0;
  bool ended = false, isolated = true;
  std::string reason;
};

// The serial methods' calls in a child process (study_child.cpp): a call that ends the child
// (CORE::Expr's exit(1), a signal) is answered `ended`, and the next call starts a new child.
// Used on the main thread while no other thread runs (the child is forked); writes to a child
// that ended need SIGPIPE ignored, as the command does (certcyl_main.cpp).
class ChildRunner {
 public:
  explicit ChildRunner(std::vector<const study::Method*> methods);
  ~ChildRunner();
  ChildRunner(const ChildRunner&) = delete;
  ChildRunner& operator=(const ChildRunner&) = delete;
  // m (one of the methods given) on x, timed or not.
  ChildCall run(const study::Method& m, const std::vector<double>& x, bool timed);

 private:
  bool start();
  void stop();
  std::vector<const study::Method*> methods_;
  int pid_ = -1, to_child_ = -1, from_child_ = -1;
};

// Certifies every planned instance and runs every applicable method on it: the answers on
// o.threads threads, then every method's time on the main thread alone, pinned to one CPU
// (run_timed; the serial methods answered there too); the rows of each instance in registry order.
std::vector<std::vector<Row>> run_instances(const StudyOptions& o, const study::Registry& registry, std::vector<Planned>& plan);

// instances.csv, inputs.csv and timing_thread.csv (the last run_instances's timing thread) in dir.
void write_instances(const fs::path& dir, const std::vector<Planned>& plan, const std::vector<std::vector<Row>>& rows);

// ---- The other stages ------------------------------------------------------------------------

// The uniform sample (study_uniform.cpp): uniform.csv in dir, this shard's share of
// o.uniform_per_query instances per query, counted per method; merge_uniform adds the shards'
// rows into dir/uniform.csv (throws std::runtime_error naming the shard when a file is missing,
// malformed or has other rows than the first shard's). in_uniform_sample: whether a method takes
// part (it runs on every instance: stride 1, not CORE::Expr, not the certified query; kept by the
// method filter).
extern const char* const kUniformHeader;  // uniform.csv
bool in_uniform_sample(const study::Method& m, const StudyOptions& o);
// Instance i of the uniform sample of query q: drawn as the uniform family draws, from its own
// stream of the seed (mix of the seed, "uniform_sample", the query and i), so not one of the
// uniform family's instances in instances.csv.
std::vector<double> uniform_sample_input(std::uint64_t seed, study::Query q, long i);
// The certified answers alone, from the binary64 input (the filtered certified queries; no gap,
// no refined enclosure): the sample's reference, the solid answer and those under the ray casts'
// contracts (study/contract.hpp; the solid one for a query other than a ray or a segment). The
// same queries as study::certify on the same input, so the same answers; uniform_certified_answer
// is the solid one.
struct UniformTruth {
  Answer solid = Answer::undecided, entry = Answer::undecided, hit = Answer::undecided;
  Answer under(study::Contract c) const {
    return c == study::Contract::surface_entry ? entry : (c == study::Contract::surface_hit ? hit : solid);
  }
};
UniformTruth uniform_certified(study::Query q, const std::vector<double>& x);
Answer uniform_certified_answer(study::Query q, const std::vector<double>& x);
void run_uniform_sample(const StudyOptions& o, const study::Registry& registry, const fs::path& dir);
void merge_uniform(const std::vector<fs::path>& shards, const fs::path& dir);
// The table of dir/uniform.csv for summary.txt ("" when the folder has none).
std::string uniform_table(const fs::path& dir);

// failure_maps/ in dir (study_maps.cpp).
void run_failure_maps(const StudyOptions& o, const study::Registry& registry, const fs::path& dir);

// The failure maps' grids, shared by the study and `certcyl judge` (study_maps.cpp): one per
// degenerate configuration, cells x cells inputs `step` ulps apart in coordinates c0 (rows) and
// c1 (columns) around `base`, the centre cell (cells/2, cells/2) the configuration itself.
struct MapGrid {
  std::string name, description;
  study::Query query = study::Query::line_cylinder;
  std::vector<double> base;
  std::size_t c0 = 0, c1 = 0;
  int cells = 0;
  long step = 1;
  // The input of a cell (row-major: cell = i * cells + j).
  std::vector<double> input(std::size_t cell) const;
  // The first columns of a map's CSV row: i, j, d0_ulps, d1_ulps, certified code, gap_lo, gap_hi
  // (`inst` the cell's input, certified).
  std::string certified_line(std::size_t cell, const study::Instance& inst) const;
};
std::vector<MapGrid> map_grids(std::uint64_t seed, int cells, long step);
// A map cell's code of an answer: s, t, o, i (a boolean "they meet"), u, e (error or invalid).
char answer_code(const study::MethodOutput& m);
// The code of a method's answer on a certified cell under its contract (study/contract.hpp):
// where the contract's certified answer differs from the solid one as a Boolean answer, 'c' when
// the method answers as its contract says (not wrong) and 'x' when it does not (wrong under its
// contract: it says the sets meet where the contract says it misses); else answer_code.
char contract_code(const study::MethodOutput& m, const study::Instance& inst, study::Contract c);
// Writes maps/<name>.csv (lines[cell] then one code per method: codes[cell][k] for methods[k],
// '.' not evaluated) and maps/<name>.json (the grid, and the methods' map_strides).
void write_failure_map(const fs::path& maps, const MapGrid& grid, const std::vector<std::string>& lines,
                       const std::vector<std::string>& methods, const std::vector<std::string>& codes,
                       const nlohmann::ordered_json& strides);
// hunt.csv in dir: this shard's share of the methods (study_hunt.cpp).
void run_hunt(const StudyOptions& o, const study::Registry& registry, const fs::path& dir);
// The hunt of one method (`run` its answer to an input), shared by the study and `certcyl
// judge` (study_hunt.cpp): `budget` evaluations, a quarter (for a budget of 200 or more) on
// independent samples of the query's families (half of them uniform random inputs), the rest local searches from the degenerate
// configurations and from the worst wrong answer found, judged under `contract`
// (study/contract.hpp); returns its hunt.csv line. `trace`, when set, hears of each start family
// ("F name") and of each input before the method runs on it ("X hexfloats"), so the parent of a
// hunt run in a child process learns which input ended the process.
std::string hunt_worst(const std::string& name, study::Query query, std::uint64_t seed, long budget,
                       const std::function<study::MethodOutput(const std::vector<double>&)>& run,
                       const std::function<void(const std::string&)>& trace, study::Contract contract = study::Contract::solid);
// The contents of machine.json (study_machine.cpp).
nlohmann::ordered_json machine_json(const StudyOptions& o, const std::vector<std::string>& peers);
// summary.txt, summary.csv, summary_families.csv and stages.csv from dir's instances.csv and
// inputs.csv; returns the tables of summary.txt (study_report.cpp).
std::string write_summary(const fs::path& dir);
// stages.csv from dir's inputs.csv: how the certified answers of the cylinder pairs were
// decided, per family; returns its table for summary.txt (study_stages.cpp).
std::string write_stages(const fs::path& dir);
// Runs experiments/plot_study.py on dir when wanted and possible (figures/ and index.html, one
// line per figure on standard error), else says how (study_report.cpp).
void run_plots(const fs::path& dir, bool want, std::ostream& out);
// s as one word of /bin/sh (in single quotes).
std::string shell_word(const std::string& s);
// `/usr/bin/python3 <experiments/plot_study.py of the source tree this program was built from>
// ARGS` (ARGS already shell words).
std::string plot_study_command(const std::string& args);
// Runs that command (its standard output discarded); false, with the reason and the command to
// run by hand on `out`, when /usr/bin/python3 has no matplotlib or the script fails.
bool run_plot_study(const std::string& args, std::ostream& out);

// ---- The sealed results folder (study_manifest.cpp) --------------------------------------------

// The SHA-256 of a file's bytes, in lowercase hex (OpenSSL's EVP interface).
std::string sha256_file(const fs::path& p);
// Where a run writes before its folder `dir` is complete: <parent>/.<name>.partial.
fs::path partial_folder(const fs::path& dir);
// Removes what an earlier run left in the partial folder of `dir`, creates it and returns it.
fs::path begin_folder(const fs::path& dir);
// Writes dir/manifest.json (last): every file the folder holds, with its size, data rows (CSV)
// and SHA-256, and the shard, options and build of dir/machine.json.
void write_manifest(const fs::path& dir);
// Writes the manifest of `partial`, then puts `partial` in the place of `dir` (any earlier
// `dir` removed: between the two renames `dir` is absent, never a mixture of two runs).
void seal_folder(const fs::path& partial, const fs::path& dir);
// Verifies `dir` against its manifest (every listed file present, with its rows, size and
// SHA-256; no other file; the manifest's configuration that of machine.json) and returns its
// machine.json. Throws std::runtime_error naming `label` (the folder as reported) and the file.
nlohmann::json verified_machine(const fs::path& dir, const std::string& label);

// ---- Threads and progress --------------------------------------------------------------------

// Progress of a phase on standard error when o.progress: on a terminal a bar redrawn at most
// every 200 ms; otherwise (a log file, a batch job's output) a plain line "label: done/total
// (p%, t s)" every o.progress_seconds and one when the phase completes, so that a log shows the
// run advancing.
class Progress {
 public:
  Progress(const StudyOptions& o, std::string label, std::size_t total)
      : on_(o.progress), bar_(o.progress && isatty(2) != 0), label_(std::move(label)), total_(total),
        interval_(bar_ ? std::chrono::milliseconds(200)
                       : std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(o.progress_seconds))),
        start_(std::chrono::steady_clock::now()), last_(bar_ ? std::chrono::steady_clock::time_point{} : start_) {}
  void tick(std::size_t n = 1) {
    const std::size_t d = done_ += n;
    if (!on_) return;
    const auto now = std::chrono::steady_clock::now();
    std::lock_guard lock(mutex_);
    if (d < total_ && now - last_ < interval_) return;
    last_ = now;
    if (!bar_) {
      std::ostringstream line;
      line << label_ << ": " << d << '/' << total_ << " (" << (total_ ? 100 * std::min(d, total_) / total_ : 100) << "%, " << std::fixed
           << std::setprecision(1) << std::chrono::duration<double>(now - start_).count() << " s)\n";
      std::cerr << line.str() << std::flush;
      return;
    }
    const int width = 30, filled = total_ ? static_cast<int>(width * d / total_) : width;
    std::cerr << '\r' << std::left << std::setw(16) << label_ << " [" << std::string(filled, '#') << std::string(width - filled, ' ')
              << "] " << d << '/' << total_ << std::flush;
    if (d >= total_) std::cerr << '\n';
  }

 private:
  bool on_, bar_;
  std::string label_;
  std::size_t total_;
  std::chrono::steady_clock::duration interval_;
  std::atomic<std::size_t> done_{0};
  std::mutex mutex_;
  std::chrono::steady_clock::time_point start_, last_;
};

// Runs body(i) for i in [0, n) on `threads` threads.
template <class F>
void parallel_for(std::size_t n, unsigned threads, F&& body) {
  std::atomic<std::size_t> next{0};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  auto worker = [&] {
    try {
      for (std::size_t i; (i = next++) < n;) body(i);
    } catch (...) {
      std::lock_guard lock(failure_mutex);
      failure = std::current_exception();
      next = n;
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < std::max(1u, threads); ++t) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace certcyl::cli::detail
