// The report of a results folder, read from its CSV files only (so a merge reports the same as
// an unsharded run): the disagreement tables per method, per query and per family
// (summary.txt, summary.csv, summary_families.csv), the stages that decided the certified cylinder
// pairs (stages.csv, study_stages.cpp), the count of CORE::Expr's warnings (Core_Diagnostics), and
// the figures with index.html, the page that presents the summary and the figures
// (experiments/plot_study.py).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
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

}  // namespace

// Summary from instances.csv and inputs.csv (so a merge gives the same tables).
std::string write_summary(const fs::path& dir) {
  std::map<std::string, Tally> by_method;
  std::map<std::tuple<std::string, std::string>, Tally> by_method_query;
  std::map<std::tuple<std::string, std::string, std::string>, Tally> by_family;
  std::set<std::string> boolean;  // the methods that answer "intersecting" (no three-valued error)
  {
    std::ifstream in(dir / "instances.csv");
    std::string line;
    std::getline(in, line);
    while (std::getline(in, line)) {
      const Row r = parse_row(line);
      if (r.answer == "intersecting") boolean.insert(r.method);
      by_method[r.method].add(r);
      by_method_query[{r.query, r.method}].add(r);
      by_family[{r.query, r.family, r.method}].add(r);
    }
  }
  const Checks c = checks_from_inputs(dir / "inputs.csv");
  const std::string table = summary_table(by_method, boolean, c) + core_diagnostics(dir) + '\n' + write_stages(dir);
  // The three-valued rate's field: empty for a Boolean method.
  const auto rate3 = [&boolean](const Tally& t, const std::string& method) { return boolean.count(method) ? std::string() : num(t.rate3()); };
  write_whole(dir / "summary.txt", table);
  std::ofstream csv(dir / "summary.csv");
  csv << "query,method,kind,n,false_positive,false_negative,class_mismatch,undecided,error,invalid,disagreement_rate,median_ns,"
         "three_valued_rate\n";
  for (auto& [key, t] : by_method_query)
    csv << std::get<0>(key) << ',' << std::get<1>(key) << ',' << t.kind << ',' << t.n << ',' << t.fp << ',' << t.fn << ',' << t.cls << ','
        << t.undecided << ',' << t.errors << ',' << t.invalid << ',' << num(t.rate()) << ',' << num(t.median_ns()) << ','
        << rate3(t, std::get<1>(key)) << '\n';
  close_written(csv, dir / "summary.csv");
  std::ofstream fam(dir / "summary_families.csv");
  fam << "query,family,method,kind,n,false_positive,false_negative,class_mismatch,undecided,error,invalid,disagreement_rate,"
         "three_valued_rate\n";
  for (auto& [key, t] : by_family)
    fam << std::get<0>(key) << ',' << std::get<1>(key) << ',' << std::get<2>(key) << ',' << t.kind << ',' << t.n << ',' << t.fp << ','
        << t.fn << ',' << t.cls << ',' << t.undecided << ',' << t.errors << ',' << t.invalid << ',' << num(t.rate()) << ','
        << rate3(t, std::get<2>(key)) << '\n';
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
