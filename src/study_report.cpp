// The report of a results folder, read from its CSV files only (so a merge reports the same as
// an unsharded run): the disagreement tables per method, per query and per family
// (summary.txt, summary.csv, summary_families.csv), the times' distributions per query, per
// family and per deciding stage of the certified cylinder pairs, generic and near-degenerate
// inputs apart (timing.csv, timing_families.csv, timing_stages.csv), the stages that decided the
// certified cylinder pairs (stages.csv, study_stages.cpp), the count of CORE::Expr's warnings
// (Core_Diagnostics), the uniform sample's table (uniform.csv, study_uniform.cpp), and the figures with index.html, the page that presents the summary and the
// figures (experiments/plot_study.py).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

#include "study_internal.hpp"
#include "study_files.hpp"

#ifndef CERTCYL_SOURCE_DIR
#define CERTCYL_SOURCE_DIR "."
#endif

namespace certcyl::cli::detail {
using namespace certcyl::study;

namespace {

struct Tally {
  std::string kind;
  std::set<std::string> queries;
  long n = 0, fp = 0, fn = 0, cls = 0, undecided = 0, errors = 0, invalid = 0;
  // The Boolean errors (FP + FN) by cause (study/conversion.hpp: each is one of conversion,
  // algorithm and unsplit),
  // the instances whose answer under the method's contract differs from the solid one as a
  // Boolean answer (judged under the contract, so not errors), and whether the method receives
  // another instance than the input or has a contract other than solid.
  long conversion = 0, algorithm = 0, unsplit = 0, contract_differs = 0;
  bool converts = false, own_contract = false;
  std::string contract = "solid";
  std::vector<double> ns;
  // The Boolean error, (FP + FN) / decided; and the three-valued one, (FP + FN + class) / decided,
  // which a Boolean method (one that answers "intersecting") does not have.
  double rate() const { return share(fp + fn); }
  double rate3() const { return share(fp + fn + cls); }
  double share(long wrong) const {
    const long decided = n - undecided - errors - invalid;
    return decided > 0 ? static_cast<double>(wrong) / static_cast<double>(decided) : 0.0;
  }
  double median_ns() {
    if (ns.empty()) return 0;
    std::nth_element(ns.begin(), ns.begin() + static_cast<long>(ns.size() / 2), ns.end());
    return ns[ns.size() / 2];
  }
  void add(const Row& r) {
    kind = r.kind;
    queries.insert(r.query);
    if (r.outcome == "uncertified") return;
    ++n;
    fp += r.outcome == "false_positive";
    fn += r.outcome == "false_negative";
    cls += r.outcome == "class_mismatch";
    undecided += r.outcome == "undecided";
    errors += r.outcome == "error";
    invalid += r.outcome == "invalid";
    if (r.outcome == "false_positive" || r.outcome == "false_negative") {
      conversion += r.cause == "conversion" || r.cause == "conversion+algorithm";
      algorithm += r.cause == "algorithm" || r.cause == "conversion+algorithm";
      unsplit += r.cause == "unsplit";
    }
    const auto meets = [](const std::string& a) { return a == "touching" || a == "overlapping"; };
    contract_differs += meets(r.contract_answer) != meets(r.certified);
    converts = converts || !r.received_answer.empty();
    if (r.contract != "solid") own_contract = true, contract = r.contract;
    ns.push_back(r.ns);
  }
};

struct Checks {
  long instances = 0, uncertified = 0, gap_sign_mismatch = 0, construction_mismatch = 0;
};

std::string summary_table(std::map<std::string, Tally>& by_method, const std::set<std::string>& boolean, const Checks& c) {
  std::ostringstream os;
  os << std::left << std::setw(46) << "method" << ' ' << std::setw(16) << "kind" << std::right << std::setw(4) << "q" << std::setw(8) << "n"
     << std::setw(7) << "FP" << std::setw(7) << "FN" << std::setw(7) << "class" << std::setw(7) << "undec" << std::setw(6) << "err"
     << std::setw(6) << "inv" << std::setw(10) << "rate" << std::setw(10) << "rate3" << std::setw(11) << "ns(med)" << '\n';
  os << std::string(146, '-') << '\n';
  for (auto& [name, t] : by_method) {
    char rate[32], rate3[32];
    std::snprintf(rate, sizeof rate, "%.2e", t.rate());
    std::snprintf(rate3, sizeof rate3, "%.2e", t.rate3());
    os << std::left << std::setw(46) << name << ' ' << std::setw(16) << t.kind << std::right << std::setw(4) << t.queries.size() << std::setw(8)
       << t.n << std::setw(7) << t.fp << std::setw(7) << t.fn << std::setw(7) << t.cls << std::setw(7) << t.undecided << std::setw(6)
       << t.errors << std::setw(6) << t.invalid << std::setw(10) << rate << std::setw(10) << (boolean.count(name) ? "--" : rate3) << std::setw(11)
       << std::fixed << std::setprecision(0) << t.median_ns() << '\n';
    os.unsetf(std::ios::fixed);
  }
  os << "rate = (FP + FN) / decided answers (Boolean error); rate3 = (FP + FN + class) / decided answers (three-valued error; --\n"
        "for a Boolean method, one that answers \"intersecting\"); class = touching/overlapping confused; inv = a reported value not\n"
        "finite; q = queries covered.\n";
  os << "checks: " << c.instances << " instances, " << c.uncertified << " left undecided by the certified query, "
     << c.gap_sign_mismatch << " gap-sign mismatches, " << c.construction_mismatch
     << " disagreements between construction and certified answer.\n";
  return os.str();
}

// The methods that receive another instance than the input, or answer under a ray cast's
// contract: their Boolean errors by cause and the instances where the contract differs.
std::string cause_table(std::map<std::tuple<std::string, std::string>, Tally>& by_method_query) {
  std::ostringstream os;
  os << "\nWrong answers by cause (FP + FN; conversion: the certified answer of the instance the method received already\n"
        "differs; algorithm: the method's answer differs from it; unsplit: that instance not certified) and instances where\n"
        "the method's contract differs from the solid answer (judged under its contract, not counted as errors):\n";
  os << std::left << std::setw(24) << "query" << std::setw(40) << "method" << std::setw(15) << "contract" << std::right << std::setw(8) << "n"
     << std::setw(8) << "wrong" << std::setw(8) << "conv" << std::setw(8) << "alg" << std::setw(8) << "unsplit" << std::setw(9) << "contract"
     << '\n';
  for (auto& [key, t] : by_method_query) {
    if (!t.converts && !t.own_contract) continue;
    os << std::left << std::setw(24) << std::get<0>(key) << std::setw(40) << std::get<1>(key) << std::setw(15) << t.contract << std::right << std::setw(8) << t.n << std::setw(8) << t.fp + t.fn << std::setw(8)
       << t.conversion << std::setw(8) << t.algorithm << std::setw(8) << t.unsplit << std::setw(9) << t.contract_differs << '\n';
  }
  return os.str();
}

Checks checks_from_inputs(const fs::path& inputs_csv) {
  Checks c;
  std::ifstream in(inputs_csv);
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    const auto f = split_csv(line);
    if (f.size() < 10) continue;
    ++c.instances;
    const std::string& expected = f[4];
    const std::string& cert = f[5];
    c.uncertified += cert == "undecided";
    c.gap_sign_mismatch += f[8] != "1";
    c.construction_mismatch += expected != "unknown" && cert != "undecided" && expected != cert;
  }
  return c;
}

// CORE::Expr's warnings in dir/Core_Diagnostics (one line each, "CORE WARNING (at FILE: LINE):
// MESSAGE"), counted per message, most frequent first.
std::string core_diagnostics(const fs::path& dir) {
  std::ifstream in(dir / "Core_Diagnostics");
  std::map<std::string, long> by_message;
  long total = 0;
  for (std::string line; std::getline(in, line);) {
    if (line.empty()) continue;
    const auto colon = line.find("): ");
    ++by_message[colon == std::string::npos ? line : line.substr(colon + 3)];
    ++total;
  }
  std::vector<std::pair<long, std::string>> counts;
  for (const auto& [message, n] : by_message) counts.emplace_back(-n, message);
  std::sort(counts.begin(), counts.end());
  std::ostringstream os;
  os << "CORE::Expr diagnostics: " << total << " warning" << (total == 1 ? "" : "s") << " in Core_Diagnostics";
  for (std::size_t i = 0; i < counts.size(); ++i) os << (i == 0 ? " (" : ", ") << -counts[i].first << " \"" << counts[i].second << '"';
  os << (counts.empty() ? "" : ")") << ".\n";
  return os.str();
}

// ---- Times ----------------------------------------------------------------------------------

// The inputs a time belongs to: "generic" for the uniform random family, "near_degenerate" for
// every hard-case family (built on a degeneracy and moved at most 2^41 ulps off it).
const char* input_class(const std::string& family) { return family == "uniform" ? "generic" : "near_degenerate"; }

// The times of a set of rows: nearest-rank percentiles (the value of rank ceil(p n / 100)), the
// mean summed in row order, the maximum.
struct Times {
  std::vector<double> ns;
  std::string kind;
  double percentile(double p) const {
    std::vector<double> v = ns;
    std::sort(v.begin(), v.end());
    const double rank = std::ceil(p / 100.0 * static_cast<double>(v.size()));
    const long k = std::max(0L, std::min(static_cast<long>(v.size()) - 1, static_cast<long>(rank) - 1));
    return v[static_cast<std::size_t>(k)];
  }
  double mean() const {
    double sum = 0;
    for (double d : ns) sum += d;
    return sum / static_cast<double>(ns.size());
  }
  // n,p10_ns,p50_ns,p90_ns,mean_ns,max_ns
  std::string fields() const {
    return std::to_string(ns.size()) + ',' + num(percentile(10)) + ',' + num(percentile(50)) + ',' + num(percentile(90)) + ',' + num(mean()) +
           ',' + num(percentile(100));
  }
};

constexpr const char* kTimesColumns = "n,p10_ns,p50_ns,p90_ns,mean_ns,max_ns";

// The rows of dir/timing_thread.csv; in a merged folder (one holding shard-* folders) its shards'
// rows, written into dir/timing_thread.csv (again at every merge).
std::vector<std::string> timing_threads(const fs::path& dir) {
  std::vector<fs::path> files;
  if (fs::is_directory(dir))
    for (const auto& e : fs::directory_iterator(dir))
      if (e.is_directory() && e.path().filename().string().rfind("shard-", 0) == 0 && fs::exists(e.path() / "timing_thread.csv"))
        files.push_back(e.path() / "timing_thread.csv");
  std::sort(files.begin(), files.end());
  const bool merged = !files.empty();
  if (!merged && fs::exists(dir / "timing_thread.csv")) files.push_back(dir / "timing_thread.csv");
  std::vector<std::string> lines;
  for (const fs::path& f : files) {
    std::ifstream in(f);
    std::string line;
    std::getline(in, line);
    while (std::getline(in, line))
      if (!line.empty()) lines.push_back(line);
  }
  if (merged) {
    std::ofstream out(dir / "timing_thread.csv");
    out << kTimingThreadHeader << '\n';
    for (const std::string& l : lines) out << l << '\n';
    close_written(out, dir / "timing_thread.csv");
  }
  return lines;
}

// timing.csv, timing_families.csv and timing_stages.csv from the rows (a call that ended its
// process has no time); returns the table of summary.txt: the certified methods per query.
std::string write_timing(const fs::path& dir, const std::vector<Row>& rows) {
  std::map<std::string, std::string> stage_of;  // instance -> deciding stage (cylinder pairs)
  {
    std::ifstream in(dir / "inputs.csv");
    std::string line;
    std::getline(in, line);
    const std::vector<std::string> header = split_csv(line);
    const auto c_stage = std::find(header.begin(), header.end(), "stage") - header.begin();
    while (std::getline(in, line)) {
      const auto f = split_csv(line);
      if (static_cast<std::size_t>(c_stage) < f.size() && !f[static_cast<std::size_t>(c_stage)].empty())
        stage_of[f[0]] = f[static_cast<std::size_t>(c_stage)];
    }
  }
  using Key = std::tuple<std::string, std::string, std::string>;
  std::map<Key, Times> by_query;                                                 // (query, method, inputs)
  std::map<std::tuple<std::string, std::string, std::string>, Times> by_family;  // (query, family, method)
  std::map<std::tuple<std::string, std::string, std::string, std::string>, Times> by_stage;  // (query, method, stage, inputs)
  for (const Row& r : rows) {
    if (r.answer == "process_ended" || !std::isfinite(r.ns)) continue;
    const std::string inputs = input_class(r.family);
    for (const std::string& g : {std::string("all"), inputs}) {
      Times& t = by_query[{r.query, r.method, g}];
      t.kind = r.kind, t.ns.push_back(r.ns);
    }
    Times& f = by_family[{r.query, r.family, r.method}];
    f.kind = r.kind, f.ns.push_back(r.ns);
    const auto st = stage_of.find(std::to_string(r.instance));
    if (r.kind == "certified" && st != stage_of.end())
      for (const std::string& g : {std::string("all"), inputs}) by_stage[{r.query, r.method, st->second, g}].ns.push_back(r.ns);
  }
  std::ofstream q(dir / "timing.csv");
  q << "query,method,kind,inputs," << kTimesColumns << '\n';
  for (const auto& [key, t] : by_query)
    q << std::get<0>(key) << ',' << csv_field(std::get<1>(key)) << ',' << t.kind << ',' << std::get<2>(key) << ',' << t.fields() << '\n';
  close_written(q, dir / "timing.csv");
  std::ofstream fam(dir / "timing_families.csv");
  fam << "query,family,method,kind,inputs," << kTimesColumns << '\n';
  for (const auto& [key, t] : by_family)
    fam << std::get<0>(key) << ',' << std::get<1>(key) << ',' << csv_field(std::get<2>(key)) << ',' << t.kind << ',' << input_class(std::get<1>(key))
        << ',' << t.fields() << '\n';
  close_written(fam, dir / "timing_families.csv");
  std::ofstream stages(dir / "timing_stages.csv");
  stages << "query,method,stage,inputs," << kTimesColumns << '\n';
  for (const auto& [key, t] : by_stage)
    stages << std::get<0>(key) << ',' << csv_field(std::get<1>(key)) << ',' << std::get<2>(key) << ',' << std::get<3>(key) << ',' << t.fields() << '\n';
  close_written(stages, dir / "timing_stages.csv");

  std::ostringstream os;
  os << "\ntimes of the certified methods in ns per call (timing.csv; generic: the uniform family, near-degenerate: the hard-case families)\n";
  os << std::left << std::setw(24) << "query" << std::setw(17) << "inputs" << std::right << std::setw(7) << "n" << std::setw(11) << "p10"
     << std::setw(11) << "p50" << std::setw(11) << "p90" << std::setw(11) << "mean" << std::setw(11) << "max" << '\n';
  for (const auto& [key, t] : by_query) {
    if (t.kind != "certified" || std::get<2>(key) == "all") continue;
    os << std::left << std::setw(24) << std::get<0>(key) << std::setw(17) << std::get<2>(key) << std::right << std::setw(7) << t.ns.size()
       << std::fixed << std::setprecision(0);
    for (double v : {t.percentile(10), t.percentile(50), t.percentile(90), t.mean(), t.percentile(100)}) os << std::setw(11) << v;
    os << '\n';
    os.unsetf(std::ios::fixed);
  }
  for (const std::string& line : timing_threads(dir)) {
    const auto f = split_csv(line);
    if (f.size() >= 6) os << "timing (shard " << f[0] << "): one thread, " << f[5] << "; the time per call the median of " << f[4]
                          << " measurements, each of calls in doubling batches until " << f[3] << " ns had elapsed\n";
  }
  return os.str();
}

}  // namespace

// Summary from instances.csv and inputs.csv (so a merge gives the same tables).
std::string write_summary(const fs::path& dir) {
  std::map<std::string, Tally> by_method;
  std::map<std::tuple<std::string, std::string>, Tally> by_method_query;
  std::map<std::tuple<std::string, std::string, std::string>, Tally> by_family;
  std::set<std::string> boolean;  // the methods that answer "intersecting" (no three-valued error)
  std::vector<Row> rows;
  {
    std::ifstream in(dir / "instances.csv");
    std::string line;
    std::getline(in, line);
    while (std::getline(in, line)) {
      rows.push_back(parse_row(line));
      const Row& r = rows.back();
      if (r.answer == "intersecting") boolean.insert(r.method);
      by_method[r.method].add(r);
      by_method_query[{r.query, r.method}].add(r);
      by_family[{r.query, r.family, r.method}].add(r);
    }
  }
  const Checks c = checks_from_inputs(dir / "inputs.csv");
  const std::string table = summary_table(by_method, boolean, c) + cause_table(by_method_query) + core_diagnostics(dir) + uniform_table(dir) +
                            '\n' + write_stages(dir) + write_timing(dir, rows);
  // The three-valued rate's field: empty for a Boolean method.
  const auto rate3 = [&boolean](const Tally& t, const std::string& method) { return boolean.count(method) ? std::string() : num(t.rate3()); };
  write_whole(dir / "summary.txt", table);
  std::ofstream csv(dir / "summary.csv");
  csv << "query,method,kind,n,false_positive,false_negative,class_mismatch,undecided,error,invalid,disagreement_rate,median_ns,"
         "three_valued_rate,contract_differs,conversion_errors,algorithm_errors,unsplit_errors\n";
  for (auto& [key, t] : by_method_query)
    csv << std::get<0>(key) << ',' << std::get<1>(key) << ',' << t.kind << ',' << t.n << ',' << t.fp << ',' << t.fn << ',' << t.cls << ','
        << t.undecided << ',' << t.errors << ',' << t.invalid << ',' << num(t.rate()) << ',' << num(t.median_ns()) << ','
        << rate3(t, std::get<1>(key)) << ',' << t.contract_differs << ',' << t.conversion << ',' << t.algorithm << ',' << t.unsplit << '\n';
  close_written(csv, dir / "summary.csv");
  std::ofstream fam(dir / "summary_families.csv");
  fam << "query,family,method,kind,n,false_positive,false_negative,class_mismatch,undecided,error,invalid,disagreement_rate,"
         "three_valued_rate,contract_differs,conversion_errors,algorithm_errors,unsplit_errors\n";
  for (auto& [key, t] : by_family)
    fam << std::get<0>(key) << ',' << std::get<1>(key) << ',' << std::get<2>(key) << ',' << t.kind << ',' << t.n << ',' << t.fp << ','
        << t.fn << ',' << t.cls << ',' << t.undecided << ',' << t.errors << ',' << t.invalid << ',' << num(t.rate()) << ','
        << rate3(t, std::get<2>(key)) << ',' << t.contract_differs << ',' << t.conversion << ',' << t.algorithm << ',' << t.unsplit << '\n';
  close_written(fam, dir / "summary_families.csv");
  return table;
}

std::string shell_word(const std::string& s) {
  std::string q = "'";
  for (const char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

namespace {
// experiments/plot_study.py of the source tree this program was built from.
std::string plot_study_script() { return std::string(CERTCYL_SOURCE_DIR) + "/experiments/plot_study.py"; }
}  // namespace

std::string plot_study_command(const std::string& args) { return "/usr/bin/python3 " + shell_word(plot_study_script()) + " " + args; }

bool run_plot_study(const std::string& args, std::ostream& out) {
  const std::string cmd = plot_study_command(args);
  const bool have = fs::exists(plot_study_script()) &&
                    std::system("/usr/bin/python3 -c 'import matplotlib' >/dev/null 2>&1") == 0;
  if (!have) {
    out << "figures: /usr/bin/python3 with matplotlib (Debian python3-matplotlib) not found; when it is installed run\n  " << cmd << '\n';
    return false;
  }
  if (std::system((cmd + " >/dev/null").c_str()) != 0) {
    out << "figures: the plotting script failed; run it by hand to see why:\n  " << cmd << '\n';
    return false;
  }
  return true;
}

void run_plots(const fs::path& dir, bool want, std::ostream& out) {
  const std::string args = shell_word(dir.string());
  if (!want) {
    out << "figures: run  " << plot_study_command(args) << '\n';
    return;
  }
  // The script names each figure on standard error as it writes it (plotting takes longer than a
  // tiny study); its standard output, one closing line, is not wanted.
  std::cerr << "figures: plotting into " << (dir / "figures").string() << " (experiments/plot_study.py)" << std::endl;
  if (run_plot_study(args, out)) {
    out << "figures: " << (dir / "figures").string() << '\n';
    out << "report: " << (dir / "index.html").string() << '\n';
  }
}

}  // namespace certcyl::cli::detail
