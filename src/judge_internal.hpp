// What the parts of `certcyl judge` share (judge*.cpp): a judged method's answer to one case,
// the three sources of answers and the results folder. Internal to the command:
//   judge.cpp          the command: the cases, the source of answers, the results
//   judge_answers.cpp  an answers file ({"id", "answer"} lines)
//   judge_exec.cpp     a co-process answering `certcyl query` lines
//   judge_plugin.cpp   a C plugin (certcyl/plugin.h) run in a child process
//   judge_report.cpp   the outcomes, the results folder and the summary table
//   judge_html.cpp     the results folder's page, index.html
#pragma once

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <istream>
#include <limits>
#include <map>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <poll.h>

#include "cases.hpp"
#include "study/methods.hpp"

namespace certcyl::cli::detail {
struct MapGrid;
}

namespace certcyl::cli::judging {

// The judged method's answer to one case: as it said it, and as the study reads it.
// output.t_in and t_out: the line query's interval as the method gave it (NaN when it gave
// none); t_in is scored against the certified entry parameter (Case::t_in), t_out is carried
// into answers.jsonl.
struct Answered {
  std::string answer;  // separated, touching, overlapping, intersecting, undecided, invalid, error
  study::MethodOutput output;
  double t_out = std::numeric_limits<double>::quiet_NaN();
};

// answers[i] answers cases[i]; the cases after a failure have none. `failure` says what went
// wrong (empty when every case was answered).
struct Answers {
  std::vector<std::optional<Answered>> answers;
  std::string failure;
  // The method's time per query when every case was answered (NaN otherwise), and what it
  // measures: a plugin's calls timed in its child process, a program's exchange as a whole.
  double ns_per_query = std::numeric_limits<double>::quiet_NaN();
  std::string timing;
};

// The study's reading of an answer: separated, touching, overlapping (three-valued),
// intersecting (a boolean "they meet"), undecided; invalid (a value the method reported left the
// finite doubles: the study's `invalid`, counted apart) and error (the method failed on the
// input: the study's `error`). Throws std::invalid_argument on any other word.
Answered answered(const std::string& answer);

// The answer of one answer line (an object): its "answer" (a `certcyl query` line's "invalid"
// is invalid whatever its "computed_answer", as the study counts a method whose reported value
// is not finite), or an error line {"id", "error"}, the method's error; and its optional
// "interval": [t_in, t_out] (numbers, null for none), or `certcyl query`'s two endpoint objects,
// read by their "approx"; [] or null: none. Throws std::invalid_argument as answered() does, when
// there is no answer, and on any other interval.
Answered answered_line(const nlohmann::json& line);

// |t - t*| in units of the ulp of max(|t*|, 1), as the study scores a line method's entry
// parameter (study_instances.cpp, with the same conditions): NaN unless the query is a line
// query, the answer is a three-valued one that meets, the certified answer meets, and both
// parameters are finite.
double t_error_of(const Answered& a, const Case& c);

// How long a program or a plugin may take for one answer (--timeout); 0: no limit.
struct Timeout {
  double seconds = 0;
  // "60 s", as the messages quote it.
  std::string text() const {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g s", seconds);
    return buf;
  }
};

// The moment the answer awaited now is due.
class Deadline {
 public:
  explicit Deadline(const Timeout& t)
      : limited_(t.seconds > 0), at_(std::chrono::steady_clock::now() + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                                                            std::chrono::duration<double>(limited_ ? t.seconds : 0))) {}
  // Waits until fd has input (or its writer has gone); false when the deadline passed first.
  bool wait_readable(int fd) const {
    for (;;) {
      int ms = -1;
      if (limited_) {
        const auto left = std::chrono::duration<double, std::milli>(at_ - std::chrono::steady_clock::now()).count();
        if (left <= 0) return false;
        ms = static_cast<int>(std::min(std::ceil(left), 3.6e6));
      }
      pollfd p{fd, POLLIN, 0};
      const int n = ::poll(&p, 1, ms);
      if (n > 0) return true;
      if (n < 0 && errno != EINTR) return true;  // the read that follows reports the error
    }
  }

 private:
  bool limited_;
  std::chrono::steady_clock::time_point at_;
};

// An answers file: one {"id", "answer"} line per case, any order, other members ignored (so the
// output of `certcyl query` is an answers file; its error lines {"id", "error"} are errors of
// the method). Throws std::runtime_error naming `label` and the line: not JSON, no id, an id
// that is no case, an id twice, an unknown answer, a case without an answer.
Answers read_answers(std::istream& in, const std::string& label, const std::vector<Case>& cases);

// Starts `command` with /bin/sh -c, writes query_line() of every case to its standard input and
// reads one line back per case: {"id", "answer"} (or a `certcyl query` error line) with the
// case's id. The program runs in a process group of its own, killed as a whole when it fails
// or gives no answer within `timeout`.
Answers run_exec(const std::string& command, const std::vector<Case>& cases, const Timeout& timeout);

// A plugin's name, the study queries it exports (certcyl_plugin_<query>) and the contract it
// declares (certcyl_plugin_contract, optional); throws std::runtime_error when it cannot be
// loaded or exports none, std::invalid_argument when its contract is none of the names.
struct PluginInfo {
  std::string name;
  std::vector<study::Query> queries;
  std::optional<study::Contract> contract;
};
PluginInfo inspect_plugin(const std::string& path);
// Runs the plugin on the cases in a child process; every case's query must be one it exports.
// The child is killed when one call gives no answer within `timeout`.
Answers run_plugin(const std::string& path, const std::vector<Case>& cases, const Timeout& timeout);

// The judged method's answers to any cases, by the same exchange as its answers to the families
// (run_plugin or run_exec with the run's plugin or command and timeout).
using AnswerSource = std::function<Answers(const std::vector<Case>&)>;

// One failure map of the judged method (judge_maps.cpp): per cell (row-major) the certified
// answer's code, the method's ('.' not evaluated) and whether it is a failure (a false positive
// or negative against a certified answer).
struct MapJudgement {
  std::string name, query, description;
  int cells = 0;
  long step = 1;
  std::string certified, codes;
  std::vector<bool> wrong;
  std::size_t evaluated = 0, decided = 0, false_positive = 0, false_negative = 0;
};

// The maps judged, or why there are none (`note`), and what went wrong on the way (`failure`:
// the exchange's failures, each followed by a restart after the cell it failed on).
struct MapsResult {
  std::vector<MapJudgement> maps;
  std::string note, failure;
  std::size_t failed_cells = 0;
};

// The failure maps' size for a --size: tiny 16 x 16 cells, small (and a number) 32, default 64,
// large 128.
int map_cells_of_size(const std::string& size);

// The cells of the failure maps of the given queries (map_grids(seed, cells, step)), each a
// certified case: id failure_map/<map>/<row>/<column>, family failure_map/<map>, k 0, `map` set,
// in the maps' order, row-major; with `grids` and `lines`, the maps and each cell's first CSV
// columns (MapGrid::certified_line). Empty when no map is drawn for the queries.
std::vector<Case> map_cell_cases(const std::vector<study::Query>& queries, int cells, long step, std::uint64_t seed, unsigned threads,
                                 std::vector<detail::MapGrid>* grids = nullptr, std::vector<std::string>* lines = nullptr);

// The study's failure maps (study_maps.cpp: map_grids) of the given queries, each cell certified
// and answered by `source`, written to dir/failure_maps/<name>.csv and .json as the study writes
// them (one method column, `method`), with dir/failure_maps.csv counting each map's failures.
// A cell is wrong under `contract` (contract_for); the maps show the method's own answers.
MapsResult judge_failure_maps(const std::filesystem::path& dir, const std::string& method, const std::vector<study::Query>& queries,
                              const AnswerSource& source, int cells, long step, std::uint64_t seed, unsigned threads,
                              study::Contract contract = study::Contract::solid);

// The hunt for the judged method's worst input (judge_maps.cpp, the study's hunt_worst of
// study_hunt.cpp): per query, `evaluations` inputs (a quarter for cylinder pairs) each answered
// by one exchange; dir/hunt.csv as the study writes it (one row per query). A failure of the
// exchange ends the hunt (the input it failed on an error).
struct HuntResult {
  std::vector<std::string> lines;  // hunt.csv's rows
  std::string failure;
};
long hunt_evaluations_of_size(const std::string& size);
// A hunt.csv row in words: the query, the worst wrong answer and its certified gap.
std::string hunt_text(const std::string& line);
// Ray and segment queries are hunted under `contract` (hunt_worst's), the others under solid.
HuntResult judge_hunt(const std::filesystem::path& dir, const std::string& method, const std::vector<study::Query>& queries,
                      const AnswerSource& source, long evaluations, std::uint64_t seed,
                      study::Contract contract = study::Contract::solid);

// The judgement of one query and family (family "all": the query's), as families.csv counts
// it: the outcomes by the study's name, the failures (false positives and negatives) and the
// failure rate among the certified cases with its 95% Wilson interval (NaN when none is
// certified).
struct FamilyJudgement {
  std::string query, family;
  std::size_t cases = 0, certified = 0, failures = 0;
  std::vector<double> t_errors;  // t_error_of each answer that has one (line queries)
  std::map<std::string, std::size_t> outcomes;
  double rate = 0, lo95 = 0, hi95 = 0;
  std::size_t at(const std::string& outcome) const {
    const auto it = outcomes.find(outcome);
    return it == outcomes.end() ? 0 : it->second;
  }
};

// A case the method gets wrong (a false positive or negative): the method's answer as given
// and the study's outcome.
struct Counterexample {
  const Case* c = nullptr;
  std::string answer, outcome;
};

// What the results folder reports: the method, the cases judged, one row per query and family
// then one per query (family "all"), in families.csv's order, and the counterexamples, one per
// distinct input, the smallest |gap| first.
struct Judgement {
  std::string method;
  std::size_t cases = 0, judged = 0;
  std::vector<FamilyJudgement> rows;
  std::vector<Counterexample> counterexamples;
  std::string failure;  // why not every case was judged (empty: all were)
  const MapsResult* maps = nullptr;  // the failure maps, when they were judged
  const HuntResult* hunt = nullptr;  // the hunt, when there was one
  double ns_per_query = std::numeric_limits<double>::quiet_NaN();  // Answers::ns_per_query
  std::string timing;
  // The method's contract (study/contract.hpp), under which its ray and segment cases are judged.
  study::Contract contract = study::Contract::solid;
};

// A proportion as the summary table and the page print it ("12.3%").
std::string percent(double p);

// Sort key of a counterexample: the size of its gap (the midpoint of the enclosure; unbounded last).
double gap_size(const Case& c);

// Writes dir/families.csv, dir/counterexamples.jsonl, dir/answers.jsonl (an answers file of
// the answered cases, in the cases' order: {"id", "answer"} with the answer as judged),
// dir/speed.csv (when the answers were timed: one row per query in the columns of the study's
// summary.csv, kind "judged", but for the last, mean_ns: Answers::ns_per_query, the mean time per
// query over all the cases, where the study's summary.csv has median_ns), dir/summary.txt and
// dir/index.html
// (write_report_page), and prints the summary table and
// "report: shown/index.html" on `out`; `shown` is where the files will be when the command ends
// (a shard's folder is written under a temporary name and renamed when complete).
// With `maps`, the summary and the page also report the failure maps (judge_failure_maps).
// The ray and segment cases are judged under `contract` (the study's outcome_of and
// certified_under; the other queries under the solid one), and a counterexample's meta then also
// names the contract and the certified answer under it.
void write_results(const std::filesystem::path& dir, const std::filesystem::path& shown, const std::string& method,
                   const std::vector<Case>& cases, const Answers& answers, std::ostream& out, const MapsResult* maps = nullptr,
                   const HuntResult* hunt = nullptr, study::Contract contract = study::Contract::solid);

// The contract a case is judged under: the method's for a ray or segment, else solid.
inline study::Contract contract_for(const Case& c, study::Contract method_contract) {
  return has_ray_contracts(c.query) ? method_contract : study::Contract::solid;
}


// Writes `file`, one self-contained HTML page (no script, no external resource: the figures are
// inline SVG) for a reader who does not know certcyl: what was tested, the failure rate of each
// family with its 95% interval, and the five most instructive counterexamples (one per failing
// query and family first, each its family's clearest error, the largest |gap|), each drawn in two
// projections with the certified answer, the method's and the gap. Throws std::runtime_error
// when it cannot be written.
void write_report_page(const std::filesystem::path& file, const Judgement& judgement);

}  // namespace certcyl::cli::judging
