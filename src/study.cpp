// The robustness study: every method of the registry on the hard-case families and uniform
// inputs, judged against the certified answers; failure maps; failure hunting; the results
// folder; the plots (experiments/plot_study.py).
//
// Results folder (results/<name>/):
//   instances.csv         one row per instance and method (tidy)
//   inputs.csv            one row per instance: its certified answer, gap and hexfloat input
//   summary.txt/.csv      the disagreement table per method and query (and per family in
//                         summary_families.csv)
//   machine.json          compiler, flags, CPU, commit, libraries, options
//   failure_maps/*.csv    the 2-D ulp perturbation grids, one column per method (+ *.json)
//   hunt.csv              the worst input found per method, in hexfloats
//   figures/*.png|pdf     written by experiments/plot_study.py from the CSV files
#include "study.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <map>
#include <mutex>
#include <set>
#include <sstream>
#include <stdexcept>
#include <thread>

#include <sys/wait.h>
#include <unistd.h>

#include <CGAL/version.h>

#include "certcyl/study/families.hpp"
#include "certcyl/study/gap.hpp"
#include "study_methods.hpp"

#ifndef CERTCYL_SOURCE_DIR
#define CERTCYL_SOURCE_DIR "."
#endif
#ifndef CERTCYL_GIT_COMMIT
#define CERTCYL_GIT_COMMIT "unknown"
#endif
#ifndef CERTCYL_CXX_FLAGS
#define CERTCYL_CXX_FLAGS "unknown"
#endif

namespace certcyl::cli {
namespace fs = std::filesystem;
using namespace certcyl::study;

namespace {

// ---- Rows and their CSV form --------------------------------------------------------------

struct Row {
  std::string family, query;
  std::uint64_t instance = 0;
  long long k = 0;
  std::string expected, method, base, nt, kind, answer, certified, outcome;
  double gap_lo = 0, gap_hi = 0, ns = 0;
  double t_error = std::numeric_limits<double>::quiet_NaN();
};

const char* kRowHeader =
    "family,query,instance,k_ulps,expected,method,base,nt,kind,answer,certified_answer,outcome,gap_lo,gap_hi,ns,t_error_ulps";

std::string num(double d) {
  if (std::isnan(d)) return "";
  if (std::isinf(d)) return d > 0 ? "inf" : "-inf";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", d);
  return buf;
}
double parse_num(const std::string& s) {
  if (s.empty()) return std::numeric_limits<double>::quiet_NaN();
  if (s == "inf") return std::numeric_limits<double>::infinity();
  if (s == "-inf") return -std::numeric_limits<double>::infinity();
  return std::strtod(s.c_str(), nullptr);  // not stod: it rejects subnormal values
}

void write_row(std::ostream& os, const Row& r) {
  os << r.family << ',' << r.query << ',' << r.instance << ',' << r.k << ',' << r.expected << ',' << r.method << ',' << r.base
     << ',' << r.nt << ',' << r.kind << ',' << r.answer << ',' << r.certified << ',' << r.outcome << ',' << num(r.gap_lo) << ','
     << num(r.gap_hi) << ',' << num(r.ns) << ',' << num(r.t_error) << '\n';
}

std::vector<std::string> split(const std::string& line, char sep) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : line) {
    if (c == sep) {
      out.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  out.push_back(cur);
  return out;
}

Row parse_row(const std::string& line) {
  const auto f = split(line, ',');
  if (f.size() != 16) throw std::runtime_error("instances.csv: bad row '" + line + "'");
  Row r;
  r.family = f[0], r.query = f[1], r.instance = std::stoull(f[2]), r.k = std::stoll(f[3]), r.expected = f[4];
  r.method = f[5], r.base = f[6], r.nt = f[7], r.kind = f[8], r.answer = f[9], r.certified = f[10], r.outcome = f[11];
  r.gap_lo = parse_num(f[12]), r.gap_hi = parse_num(f[13]), r.ns = parse_num(f[14]), r.t_error = parse_num(f[15]);
  return r;
}

// ---- Timing ---------------------------------------------------------------------------------

// Runs a method and measures it: one timed call; calls under 2 us are repeated 16 times and
// the mean of the repetitions is reported (the clock costs ~20 ns per reading).
std::mutex serial_mutex;

std::pair<MethodOutput, double> timed(const Method& m, const std::vector<double>& x) {
  using clock = std::chrono::steady_clock;
  std::unique_lock<std::mutex> lock(serial_mutex, std::defer_lock);
  if (m.serial) lock.lock();  // before the clock starts: waiting is not the method's time
  MethodOutput out;
  auto t0 = clock::now();
  try {
    out = m.run(x);
  } catch (const std::exception&) {
    out = MethodOutput{};
    out.error = true;
  }
  double ns = std::chrono::duration<double, std::nano>(clock::now() - t0).count();
  if (ns < 2000 && !out.error) {
    constexpr int reps = 16;
    t0 = clock::now();
    for (int i = 0; i < reps; ++i) (void)m.run(x);
    ns = std::chrono::duration<double, std::nano>(clock::now() - t0).count() / reps;
  }
  return {out, ns};
}

MethodOutput run_quiet(const Method& m, const std::vector<double>& x) {
  std::unique_lock<std::mutex> lock(serial_mutex, std::defer_lock);
  if (m.serial) lock.lock();
  try {
    return m.run(x);
  } catch (const std::exception&) {
    MethodOutput out;
    out.error = true;
    return out;
  }
}

// ---- Progress -------------------------------------------------------------------------------

class Progress {
 public:
  Progress(bool on, std::string label, std::size_t total) : on_(on), label_(std::move(label)), total_(total) {}
  void tick(std::size_t n = 1) {
    const std::size_t d = done_ += n;
    if (!on_) return;
    const auto now = std::chrono::steady_clock::now();
    std::lock_guard lock(mutex_);
    if (d < total_ && now - last_ < std::chrono::milliseconds(200)) return;
    last_ = now;
    const int width = 30, filled = total_ ? static_cast<int>(width * d / total_) : width;
    std::cerr << '\r' << std::left << std::setw(16) << label_ << " [" << std::string(filled, '#') << std::string(width - filled, ' ')
              << "] " << d << '/' << total_ << std::flush;
    if (d >= total_) std::cerr << '\n';
  }

 private:
  bool on_;
  std::string label_;
  std::size_t total_;
  std::atomic<std::size_t> done_{0};
  std::mutex mutex_;
  std::chrono::steady_clock::time_point last_{};
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

// ---- Instances --------------------------------------------------------------------------------

std::uint64_t mix(std::uint64_t h, std::uint64_t v) {
  h ^= v + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
  h ^= h >> 31;
  h *= 0xbf58476d1ce4e5b9ULL;
  return h ^ (h >> 29);
}
std::uint64_t hash_string(const std::string& s) {
  std::uint64_t h = 1469598103934665603ULL;
  for (unsigned char c : s) h = (h ^ c) * 1099511628211ULL;
  return h;
}

struct Planned {
  Instance inst;
  std::size_t index_in_family = 0;
  long long k = 0;
};

bool keep_name(const std::vector<std::string>& filter, const std::string& name) {
  if (filter.empty()) return true;
  return std::any_of(filter.begin(), filter.end(), [&](const std::string& f) { return name.find(f) != std::string::npos; });
}

// Every instance of the configuration, in a fixed order; each depends only on the seed, its
// family, its query and its index, so any shard builds the same ones.
std::vector<Planned> plan_instances(const StudyOptions& o) {
  std::vector<Planned> out;
  std::uint64_t id = 0;
  for (const Family& f : all_families()) {
    if (!o.families.empty() && std::find(o.families.begin(), o.families.end(), f.name) == o.families.end()) continue;
    for (Query q : f.queries) {
      for (long i = 0; i < o.per_family; ++i, ++id) {
        if (static_cast<int>(id % o.shard_count) != o.shard_index) continue;
        Rng rng(mix(mix(mix(o.seed, hash_string(f.name)), static_cast<std::uint64_t>(q)), static_cast<std::uint64_t>(i)));
        Planned p;
        p.k = ulp_offset(rng, static_cast<std::size_t>(i));
        FamilyInput in = f.make(rng, q, p.k);
        p.inst.id = id;
        p.inst.family = f.name;
        p.inst.query = q;
        p.inst.x = std::move(in.x);
        p.inst.expected = in.expected;
        p.index_in_family = static_cast<std::size_t>(i);
        out.push_back(std::move(p));
      }
    }
  }
  return out;
}

std::string x_hex(const std::vector<double>& x) {
  std::string s;
  for (double d : x) {
    if (!s.empty()) s += ' ';
    s += hexfloat(d);
  }
  return s;
}

// |t - t*| in units of the ulp of max(|t*|, 1): the parameter's own ulp away from 0, and an
// absolute measure near 0 (where counting representable doubles would make 1e-17 against 0
// an error of 2^62 "ulps").
double t_error_ulps(double t, double exact) {
  const double scale = std::max(std::fabs(exact), 1.0);
  const double ulp = std::nextafter(scale, std::numeric_limits<double>::infinity()) - scale;
  return static_cast<double>(std::fabs(static_cast<long double>(t) - static_cast<long double>(exact)) / ulp);
}

std::string outcome_of(const MethodOutput& m, const Instance& inst) {
  if (inst.certified == Answer::undecided) return "uncertified";
  return std::string(to_string(judge(m, inst.certified)));
}

// ---- Summary --------------------------------------------------------------------------------

struct Tally {
  std::string kind;
  std::set<std::string> queries;
  long n = 0, fp = 0, fn = 0, cls = 0, undecided = 0, errors = 0;
  std::vector<double> ns;
  double rate() const {
    const long decided = n - undecided - errors;
    return decided > 0 ? static_cast<double>(fp + fn) / static_cast<double>(decided) : 0.0;
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
    ns.push_back(r.ns);
  }
};

struct Checks {
  long instances = 0, uncertified = 0, gap_sign_mismatch = 0, construction_mismatch = 0;
};

std::string summary_table(std::map<std::string, Tally>& by_method, const Checks& c) {
  std::ostringstream os;
  os << std::left << std::setw(46) << "method" << ' ' << std::setw(16) << "kind" << std::right << std::setw(4) << "q" << std::setw(8) << "n"
     << std::setw(7) << "FP" << std::setw(7) << "FN" << std::setw(7) << "class" << std::setw(7) << "undec" << std::setw(6) << "err"
     << std::setw(10) << "rate" << std::setw(11) << "ns(med)" << '\n';
  os << std::string(130, '-') << '\n';
  for (auto& [name, t] : by_method) {
    char rate[32];
    std::snprintf(rate, sizeof rate, "%.2e", t.rate());
    os << std::left << std::setw(46) << name << ' ' << std::setw(16) << t.kind << std::right << std::setw(4) << t.queries.size() << std::setw(8)
       << t.n << std::setw(7) << t.fp << std::setw(7) << t.fn << std::setw(7) << t.cls << std::setw(7) << t.undecided << std::setw(6)
       << t.errors << std::setw(10) << rate << std::setw(11) << std::fixed << std::setprecision(0) << t.median_ns() << '\n';
    os.unsetf(std::ios::fixed);
  }
  os << "rate = (FP + FN) / decided answers; class = touching/overlapping confused; q = queries covered.\n";
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
    const auto f = split(line, ',');
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

// Summary from instances.csv and inputs.csv (so a merge gives the same tables).
std::string write_summary(const fs::path& dir) {
  std::map<std::string, Tally> by_method;
  std::map<std::tuple<std::string, std::string>, Tally> by_method_query;
  std::map<std::tuple<std::string, std::string, std::string>, Tally> by_family;
  {
    std::ifstream in(dir / "instances.csv");
    std::string line;
    std::getline(in, line);
    while (std::getline(in, line)) {
      const Row r = parse_row(line);
      by_method[r.method].add(r);
      by_method_query[{r.query, r.method}].add(r);
      by_family[{r.query, r.family, r.method}].add(r);
    }
  }
  const Checks c = checks_from_inputs(dir / "inputs.csv");
  const std::string table = summary_table(by_method, c);
  std::ofstream(dir / "summary.txt") << table;
  std::ofstream csv(dir / "summary.csv");
  csv << "query,method,kind,n,false_positive,false_negative,class_mismatch,undecided,error,disagreement_rate,median_ns\n";
  for (auto& [key, t] : by_method_query)
    csv << std::get<0>(key) << ',' << std::get<1>(key) << ',' << t.kind << ',' << t.n << ',' << t.fp << ',' << t.fn << ',' << t.cls << ','
        << t.undecided << ',' << t.errors << ',' << num(t.rate()) << ',' << num(t.median_ns()) << '\n';
  std::ofstream fam(dir / "summary_families.csv");
  fam << "query,family,method,kind,n,false_positive,false_negative,class_mismatch,undecided,error,disagreement_rate\n";
  for (auto& [key, t] : by_family)
    fam << std::get<0>(key) << ',' << std::get<1>(key) << ',' << std::get<2>(key) << ',' << t.kind << ',' << t.n << ',' << t.fp << ','
        << t.fn << ',' << t.cls << ',' << t.undecided << ',' << t.errors << ',' << num(t.rate()) << '\n';
  return table;
}

// ---- Machine facts ----------------------------------------------------------------------------

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown";
}

std::string run_command(const std::string& cmd) {
  std::string out;
  if (FILE* p = popen(cmd.c_str(), "r")) {
    char buf[256];
    while (fgets(buf, sizeof buf, p)) out += buf;
    pclose(p);
  }
  while (!out.empty() && (out.back() == '\n' || out.back() == ' ')) out.pop_back();
  return out;
}

nlohmann::ordered_json machine_json(const StudyOptions& o, const std::vector<std::string>& peers) {
  nlohmann::ordered_json j;
  j["compiler"] = std::string("g++ ") + __VERSION__;
  j["flags"] = CERTCYL_CXX_FLAGS;
  j["cpu"] = cpu_model();
  j["hardware_threads"] = std::thread::hardware_concurrency();
  std::string commit = run_command(std::string("git -C '") + CERTCYL_SOURCE_DIR + "' rev-parse HEAD 2>/dev/null");
  const std::string dirty = commit.empty() ? "" : run_command(std::string("git -C '") + CERTCYL_SOURCE_DIR + "' status --porcelain --untracked-files=no 2>/dev/null");
  j["commit"] = commit.empty() ? std::string(CERTCYL_GIT_COMMIT) : commit + (dirty.empty() ? "" : "+modified");
  j["cgal"] = CGAL_VERSION_STR;
  j["peers"] = peers;
  j["options"] = {{"name", o.name}, {"size", o.size}, {"seed", o.seed}, {"threads", o.threads},
                  {"per_family", o.per_family}, {"map_cells", o.map_cells}, {"map_step", o.map_step},
                  {"hunt_evaluations", o.hunt_evaluations}, {"shard", std::to_string(o.shard_index) + "/" + std::to_string(o.shard_count)},
                  {"methods", o.methods}, {"families", o.families}};
  const auto now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  char date[64];
  std::strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  j["date"] = date;
  return j;
}

// ---- Failure maps -----------------------------------------------------------------------------

char answer_code(const MethodOutput& m) {
  if (m.error) return 'e';
  if (m.intersecting) return 'i';
  switch (m.answer) {
    case Answer::separated: return 's';
    case Answer::touching: return 't';
    case Answer::overlapping: return 'o';
    case Answer::undecided: return 'u';
  }
  return 'u';
}

struct MapSpec {
  std::string name, family, description;
  Query query;
  std::size_t c0, c1;  // the perturbed coordinates
  // When set (the aligned families, whose axis is a random coordinate axis): c0 and c1 are
  // offsets into the point at `c0`, replaced by its two coordinates across the axis of the
  // cylinder at this offset, so the map moves the point off the wall and not along the axis.
  std::size_t across_cylinder_at = std::numeric_limits<std::size_t>::max();
};

// One map per query, each around a degenerate configuration of one of its families (k = 0).
std::vector<MapSpec> map_specs() {
  return {{"tangent_line", "tangent_rotated", "line tangent to the wall; origin x and y perturbed", Query::line_cylinder, 0, 1},
          {"rim_line", "rim_rotated", "line grazing the rim at p1; origin x and y perturbed", Query::line_cylinder, 0, 1},
          {"ray_ends_on_wall", "ends_on_wall", "ray starting on the wall, pointing out; origin perturbed across the axis",
           Query::ray_cylinder, 0, 0, 6},
          {"segment_ends_on_wall", "ends_on_wall", "segment from outside ending on the wall; p1 perturbed across the axis",
           Query::segment_cylinder, 3, 0, 6},
          {"elliptic_tangent", "e_tangent_oblique", "line tangent to a sheared elliptic cylinder; origin x and z perturbed",
           Query::line_elliptic_cylinder, 0, 2},
          {"triangle_edge_wall", "t_edge_rotated", "triangle edge tangent to the wall; vertex v0 x and y perturbed",
           Query::triangle_cylinder, 0, 1},
          {"touching_cylinders", "c_crossing_rotated", "crossing cylinders touching wall to wall; b.p0 x and y perturbed",
           Query::cylinder_cylinder, 7, 8}};
}

// Every method of the query but the certified one; slow ones on a sub-grid (Effort).
void run_failure_maps(const StudyOptions& o, const Registry& registry, const fs::path& dir) {
  const fs::path maps = dir / "failure_maps";
  fs::create_directories(maps);
  const auto families = all_families();
  for (MapSpec spec : map_specs()) {
    const Family* fam = nullptr;
    for (const Family& f : families)
      if (f.name == spec.family && std::find(f.queries.begin(), f.queries.end(), spec.query) != f.queries.end()) fam = &f;
    if (!fam) throw std::logic_error("failure map " + spec.name + ": no family " + spec.family);
    Rng rng(mix(o.seed, hash_string(spec.name)));
    const std::vector<double> base = fam->make(rng, spec.query, 0).x;
    if (spec.across_cylinder_at != std::numeric_limits<std::size_t>::max()) {
      const std::size_t point = spec.c0, cyl = spec.across_cylinder_at;
      std::array<std::size_t, 3> order{0, 1, 2};
      std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return std::fabs(base[cyl + 3 + a] - base[cyl + a]) < std::fabs(base[cyl + 3 + b] - base[cyl + b]);
      });
      spec.c0 = point + std::min(order[0], order[1]);
      spec.c1 = point + std::max(order[0], order[1]);
    }
    std::vector<const Method*> methods;
    for (const Method& m : registry)
      if (m.query == spec.query && m.kind != MethodKind::certified && keep_name(o.methods, m.name())) methods.push_back(&m);
    const int n = o.map_cells;
    // A method with map_stride s runs on the rows and columns i with i = n/2 (mod s): the
    // centre cell, the degenerate configuration itself, is always among them.
    auto evaluated = [n](const Method& m, long i, long j) {
      const long s = static_cast<long>(std::max(1u, m.effort.map_stride));
      return (i - n / 2) % s == 0 && (j - n / 2) % s == 0;
    };
    const std::size_t cells = static_cast<std::size_t>(n) * n;
    std::vector<std::string> lines(cells), codes(cells, std::string(methods.size(), '.'));
    auto cell_input = [&](std::size_t cell) {
      const long i = static_cast<long>(cell) / n, j = static_cast<long>(cell) % n;
      std::vector<double> x = base;
      x[spec.c0] = ulp_step(base[spec.c0], (i - n / 2) * o.map_step);
      x[spec.c1] = ulp_step(base[spec.c1], (j - n / 2) * o.map_step);
      return x;
    };
    Progress progress(o.progress, spec.name, cells);
    parallel_for(cells, o.threads, [&](std::size_t cell) {
      const long i = static_cast<long>(cell) / n, j = static_cast<long>(cell) % n;
      const long d0 = (i - n / 2) * o.map_step, d1 = (j - n / 2) * o.map_step;
      Instance inst;
      inst.query = spec.query;
      inst.x = cell_input(cell);
      certify(inst);
      lines[cell] = std::to_string(i) + "," + std::to_string(j) + "," + std::to_string(d0) + "," + std::to_string(d1) + "," +
                    std::string(1, answer_code(three_valued(inst.certified))) + "," + num(inst.gap_lo) + "," + num(inst.gap_hi);
      for (std::size_t k = 0; k < methods.size(); ++k)
        if (!methods[k]->serial && evaluated(*methods[k], i, j)) codes[cell][k] = answer_code(run_quiet(*methods[k], inst.x));
      progress.tick();
    });
    // The serial methods, on this thread only (see Method::serial).
    for (std::size_t k = 0; k < methods.size(); ++k) {
      if (!methods[k]->serial) continue;
      for (std::size_t cell = 0; cell < cells; ++cell)
        if (evaluated(*methods[k], static_cast<long>(cell) / n, static_cast<long>(cell) % n))
          codes[cell][k] = answer_code(run_quiet(*methods[k], cell_input(cell)));
    }
    std::ofstream csv(maps / (spec.name + ".csv"));
    csv << "i,j,d0_ulps,d1_ulps,certified,gap_lo,gap_hi";
    for (const Method* m : methods) csv << ',' << m->name();
    csv << '\n';
    for (std::size_t cell = 0; cell < cells; ++cell) {
      csv << lines[cell];
      for (char c : codes[cell]) csv << ',' << c;
      csv << '\n';
    }
    nlohmann::ordered_json strides = nlohmann::ordered_json::object();
    for (const Method* m : methods)
      if (m->effort.map_stride > 1) strides[m->name()] = m->effort.map_stride;
    nlohmann::ordered_json meta{{"name", spec.name},
                                {"query", std::string(to_string(spec.query))},
                                {"description", spec.description},
                                {"base_input", x_hex(base)},
                                {"perturbed_coordinates", {spec.c0, spec.c1}},
                                {"cells", n},
                                {"ulps_per_cell", o.map_step},
                                {"map_strides", strides},
                                {"codes", "s separated, t touching, o overlapping, i intersecting (boolean methods), u undecided, e error, "
                                          ". not evaluated (a slow method runs on every map_stride-th row and column through the centre)"}};
    std::ofstream(maps / (spec.name + ".json")) << meta.dump(2) << '\n';
  }
}

// ---- Failure hunting --------------------------------------------------------------------------

// Runs `hunt(trace)` in a child process; returns its hunt.csv line, or, when the child did not
// finish, a line naming the input it was evaluating when it ended.
std::string hunt_in_child(const Method& m, const std::function<std::string(const std::function<void(const std::string&)>&)>& hunt) {
  int fds[2];
  if (pipe(fds) != 0) return hunt({});
  std::cout.flush(), std::cerr.flush();
  const pid_t pid = fork();
  if (pid < 0) {
    close(fds[0]), close(fds[1]);
    return hunt({});
  }
  if (pid == 0) {
    close(fds[0]);
    auto send = [&](const std::string& msg) {
      const std::string data = msg + '\n';
      for (std::size_t done = 0; done < data.size();) {
        const ssize_t n = write(fds[1], data.data() + done, data.size() - done);
        if (n <= 0) _exit(3);
        done += static_cast<std::size_t>(n);
      }
    };
    const std::string line = hunt(send);
    send("L " + line);
    close(fds[1]);
    _exit(0);
  }
  close(fds[1]);
  std::string received;
  char buf[4096];
  for (ssize_t n; (n = read(fds[0], buf, sizeof buf)) != 0;) {
    if (n < 0) {
      if (errno == EINTR) continue;
      break;
    }
    received.append(buf, static_cast<std::size_t>(n));
  }
  close(fds[0]);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  std::string family, input, result;
  long evaluations = 0;
  std::istringstream lines(received);
  for (std::string l; std::getline(lines, l);) {
    if (l.rfind("F ", 0) == 0) family = l.substr(2);
    if (l.rfind("X ", 0) == 0) input = l.substr(2), ++evaluations;
    if (l.rfind("L ", 0) == 0) result = l.substr(2);
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0 && !result.empty()) return result;
  std::ostringstream line;
  line << m.name() << ',' << to_string(m.query) << ',' << family << ',' << evaluations << ',';
  if (input.empty()) {
    line << "0,,,,,,";
    return line.str();
  }
  Instance inst;
  inst.query = m.query;
  std::istringstream hex(input);
  for (std::string v; hex >> v;) inst.x.push_back(std::strtod(v.c_str(), nullptr));
  certify(inst);
  line << "1,process_ended," << to_string(inst.certified) << ",error," << num(inst.gap_lo) << ',' << num(inst.gap_hi) << ',' << input;
  return line.str();
}

// For each method: random restarts at the degenerate configurations of its query's families
// (k = 0), then a local search over ulp perturbations of single coordinates (each coordinate
// kept within 2^-6 of its start, relative to the largest input coordinate) that keeps the
// method wrong (false positive or false negative) while pushing the certified lower bound of
// |gap| up. The result is the wrong answer farthest from any degeneracy that the search found.
// Every method but the certified one is hunted; a slow one gets 1/hunt_divisor of the budget.
void run_hunt(const StudyOptions& o, const Registry& registry, const fs::path& dir) {
  std::vector<const Method*> methods;
  for (std::size_t i = 0; i < registry.size(); ++i) {
    const Method& m = registry[i];
    if (m.kind != MethodKind::certified && keep_name(o.methods, m.name()) &&
        static_cast<int>(i % o.shard_count) == o.shard_index)
      methods.push_back(&m);
  }
  const auto families = all_families();
  std::vector<std::string> lines(methods.size());
  Progress progress(o.progress, "hunting", methods.size());
  // `trace`, when set, hears of each start family ("F name") and of each input before the
  // method runs on it ("X hexfloats"): the parent of a hunt run in a child process learns
  // which input ended the process.
  auto hunt_one = [&](std::size_t mi, const std::function<void(const std::string&)>& trace) {
    const Method& m = *methods[mi];
    std::vector<const Family*> starts;
    for (const Family& f : families)
      if (std::find(f.queries.begin(), f.queries.end(), m.query) != f.queries.end() && f.name != "uniform") starts.push_back(&f);
    Rng rng(mix(o.seed, hash_string(m.name() + std::string(to_string(m.query)))));
    const long query_budget = m.query == Query::cylinder_cylinder ? std::max(1L, o.hunt_evaluations / 4) : o.hunt_evaluations;
    const long budget = std::max(1L, query_budget / static_cast<long>(std::max(1u, m.effort.hunt_divisor)));
    const long restarts = std::max(1L, budget / 50);
    long evaluations = 0;
    double best_score = -std::numeric_limits<double>::infinity();
    Instance best;
    MethodOutput best_out;
    std::string best_family;
    auto score = [&](Instance& inst, MethodOutput& out) {
      ++evaluations;
      certify(inst);
      if (inst.certified == Answer::undecided) return -std::numeric_limits<double>::infinity();
      if (trace) trace("X " + x_hex(inst.x));
      out = run_quiet(m, inst.x);
      if (!disagrees(judge(out, inst.certified))) return -std::numeric_limits<double>::infinity();
      // The certified lower bound of |gap| (0 when the enclosure contains 0).
      const double g = inst.gap_lo > 0 ? inst.gap_lo : (inst.gap_hi < 0 ? -inst.gap_hi : 0.0);
      return g > 0 ? std::log(g) : -1e300;
    };
    for (long r = 0; r < restarts && evaluations < budget; ++r) {
      const Family* f = starts[static_cast<std::size_t>(rng.integer(0, static_cast<long long>(starts.size()) - 1))];
      Instance cur;
      cur.query = m.query;
      cur.x = f->make(rng, m.query, 0).x;
      if (trace) trace("F " + f->name);
      const std::vector<double> start = cur.x;
      double scale = 0;
      for (double v : start) scale = std::max(scale, std::fabs(v));
      MethodOutput cur_out;
      double cur_score = score(cur, cur_out);
      const long steps = budget / restarts;
      for (long s = 0; s < steps && evaluations < budget; ++s) {
        Instance next = cur;
        const std::size_t c = static_cast<std::size_t>(rng.integer(0, static_cast<long long>(next.x.size()) - 1));
        const long long e = rng.integer(0, 44);
        const long long step = (1LL << e) * (rng.coin() ? 1 : -1);
        next.x[c] = ulp_step(next.x[c], step);
        // Stay near the restart's configuration (each coordinate within 2^-6 of its start,
        // relative to the input's scale): the search asks how far from the degeneracy a method
        // stays wrong, not where double overflows.
        if (std::fabs(next.x[c] - start[c]) > 0x1p-6 * scale) continue;
        MethodOutput next_out;
        const double sc = score(next, next_out);
        // Before a first failure, wander; afterwards, only climb.
        if (sc >= cur_score || cur_score == -std::numeric_limits<double>::infinity()) {
          if (sc == -std::numeric_limits<double>::infinity() && cur_score == -std::numeric_limits<double>::infinity() && e > 20) continue;
          cur = std::move(next), cur_out = next_out, cur_score = sc;
        }
        if (cur_score > best_score) best_score = cur_score, best = cur, best_out = cur_out, best_family = f->name;
      }
      if (cur_score > best_score) best_score = cur_score, best = cur, best_out = cur_out, best_family = f->name;
    }
    std::ostringstream line;
    const bool found = best_score > -std::numeric_limits<double>::infinity();
    line << m.name() << ',' << to_string(m.query) << ',' << (found ? best_family : "") << ',' << evaluations << ',' << (found ? 1 : 0);
    if (found)
      line << ',' << answer_label(best_out) << ',' << to_string(best.certified) << ',' << to_string(judge(best_out, best.certified))
           << ',' << num(best.gap_lo) << ',' << num(best.gap_hi) << ',' << x_hex(best.x);
    else
      line << ",,,,,,";
    lines[mi] = line.str();
  };
  // The parallel methods on the threads, then the serial ones on this thread only, each in a
  // child process: CORE::Expr ends the process (abort, or exit(1) from its BigFloat division)
  // on some inputs the hunt reaches, tiny non-zero components among them (experiments/STUDY.md).
  // The worst input is then the one that ended the process (answer process_ended, outcome
  // error). No other thread runs when the child is forked.
  std::vector<std::size_t> parallel_ones, serial_ones;
  for (std::size_t mi = 0; mi < methods.size(); ++mi) (methods[mi]->serial ? serial_ones : parallel_ones).push_back(mi);
  parallel_for(parallel_ones.size(), o.threads, [&](std::size_t k) {
    hunt_one(parallel_ones[k], {});
    progress.tick();
  });
  for (std::size_t mi : serial_ones) {
    lines[mi] = hunt_in_child(*methods[mi], [&](const std::function<void(const std::string&)>& trace) {
      hunt_one(mi, trace);
      return lines[mi];
    });
    progress.tick();
  }
  std::sort(lines.begin(), lines.end());  // the order of a merge of shards
  std::ofstream csv(dir / "hunt.csv");
  csv << "method,query,start_family,evaluations,found,answer,certified_answer,outcome,gap_lo,gap_hi,input_hex\n";
  for (const auto& l : lines) csv << l << '\n';
}

// ---- Plots ------------------------------------------------------------------------------------

void run_plots(const fs::path& dir, bool want, std::ostream& out) {
  const std::string script = std::string(CERTCYL_SOURCE_DIR) + "/experiments/plot_study.py";
  const std::string cmd = "/usr/bin/python3 '" + script + "' '" + dir.string() + "'";
  if (!want) {
    out << "figures: run  " << cmd << '\n';
    return;
  }
  const bool have = fs::exists(script) && std::system("/usr/bin/python3 -c 'import matplotlib' >/dev/null 2>&1") == 0;
  if (!have) {
    out << "figures: /usr/bin/python3 with matplotlib (Debian python3-matplotlib) not found; when it is installed run\n  " << cmd << '\n';
    return;
  }
  if (std::system((cmd + " >/dev/null").c_str()) != 0)
    out << "figures: the plotting script failed; run it by hand to see why:\n  " << cmd << '\n';
  else
    out << "figures: " << (dir / "figures").string() << '\n';
}

void apply_size(StudyOptions& o) {
  struct Preset {
    const char* name;
    long per_family;
    int map_cells;
    long hunt;
  };
  const Preset presets[] = {{"tiny", 3, 16, 20}, {"small", 12, 64, 150}, {"default", 96, 256, 1000}, {"large", 400, 256, 5000}};
  for (const Preset& p : presets) {
    if (o.size == p.name) {
      if (o.per_family == 0) o.per_family = p.per_family;
      if (o.map_cells == 0) o.map_cells = p.map_cells;
      if (o.hunt_evaluations == 0) o.hunt_evaluations = p.hunt;
      return;
    }
  }
  long n = 0;
  try {
    n = std::stol(o.size);
  } catch (const std::exception&) {
  }
  if (n <= 0) throw std::invalid_argument("--size: expected tiny, small, default, large or a positive count, got '" + o.size + "'");
  if (o.per_family == 0) o.per_family = n;
  if (o.map_cells == 0) o.map_cells = 256;
  if (o.hunt_evaluations == 0) o.hunt_evaluations = std::max(20L, 12 * n);
}

void apply_config(StudyOptions& o) {
  if (o.config_file.empty()) return;
  std::ifstream in(o.config_file);
  if (!in) throw std::invalid_argument("--config: cannot read '" + o.config_file + "'");
  const nlohmann::json j = nlohmann::json::parse(in);
  for (const auto& [key, value] : j.items()) {
    if (key == "per_family") o.per_family = value.get<long>();
    else if (key == "map_cells") o.map_cells = value.get<int>();
    else if (key == "map_step") o.map_step = value.get<long>();
    else if (key == "hunt_evaluations") o.hunt_evaluations = value.get<long>();
    else if (key == "methods") o.methods = value.get<std::vector<std::string>>();
    else if (key == "families") o.families = value.get<std::vector<std::string>>();
    else if (key == "size") o.size = value.get<std::string>();
    else if (key == "seed") o.seed = value.get<std::uint64_t>();
    else if (key == "name") o.name = value.get<std::string>();
    else throw std::invalid_argument("--config: unknown key '" + key + "' (per_family, map_cells, map_step, hunt_evaluations, methods, families, size, seed, name)");
  }
}

}  // namespace

void parse_shard(const std::string& s, int& index, int& count) {
  const auto slash = s.find('/');
  if (slash == std::string::npos) throw std::invalid_argument("--shard: expected i/n, got '" + s + "'");
  index = std::stoi(s.substr(0, slash));
  count = std::stoi(s.substr(slash + 1));
  if (count < 1 || index < 0 || index >= count) throw std::invalid_argument("--shard: need 0 <= i < n, got '" + s + "'");
}

int run_study(StudyOptions o, std::ostream& out) {
  apply_config(o);
  apply_size(o);
  if (o.name.empty()) o.name = o.size;
  const auto start = std::chrono::steady_clock::now();
  Registry registry;
  register_line_methods(registry);
  register_triangle_methods(registry);
  register_cylinder_methods(registry);
  const std::vector<std::string> peers = register_peer_methods(registry);
  mark_serial(registry);

  fs::path dir = fs::path(o.out_root) / o.name;
  const bool sharded = o.shard_count > 1;
  if (sharded) dir /= "shard-" + std::to_string(o.shard_index) + "-of-" + std::to_string(o.shard_count);
  fs::create_directories(dir);

  std::vector<Planned> plan = plan_instances(o);
  std::vector<std::vector<Row>> rows(plan.size());
  auto evaluate = [&](Planned& p, const Method& m) {
    const Instance& inst = p.inst;
    // The slow types run on a pseudo-random 1/stride of each family (not every stride-th
    // index, which would pick the k = 0 instances: ulp_offset makes every 8th one k = 0).
    if (m.query != inst.query || (mix(0, p.index_in_family) >> 32) % m.stride != 0 || !keep_name(o.methods, m.name())) return;
    const auto [res, ns] = timed(m, inst.x);
    Row r;
    r.family = inst.family, r.query = std::string(to_string(inst.query)), r.instance = inst.id, r.k = p.k;
    r.expected = std::string(to_string(inst.expected));
    r.method = m.name(), r.base = m.base, r.nt = m.nt, r.kind = std::string(to_string(m.kind));
    r.answer = answer_label(res), r.certified = std::string(to_string(inst.certified)), r.outcome = outcome_of(res, inst);
    r.gap_lo = inst.gap_lo, r.gap_hi = inst.gap_hi, r.ns = ns;
    if (is_line_query(inst.query) && !res.intersecting && intersects(res.answer) && intersects(inst.certified) &&
        std::isfinite(res.t_in) && std::isfinite(inst.t_in))
      r.t_error = t_error_ulps(res.t_in, inst.t_in);
    rows[&p - plan.data()].push_back(std::move(r));
  };
  Progress progress(o.progress, "instances", plan.size());
  parallel_for(plan.size(), o.threads, [&](std::size_t pi) {
    certify(plan[pi].inst);
    for (const Method& m : registry)
      if (!m.serial) evaluate(plan[pi], m);
    progress.tick();
  });
  // The serial methods, on this thread only (see Method::serial), in registry order per instance.
  Progress serial_progress(o.progress, "instances (serial)", plan.size());
  for (Planned& p : plan) {
    std::vector<Row> parallel_rows = std::move(rows[&p - plan.data()]);
    rows[&p - plan.data()].clear();
    std::size_t next_parallel = 0;
    for (const Method& m : registry) {
      if (m.serial) {
        evaluate(p, m);
      } else if (m.query == p.inst.query && next_parallel < parallel_rows.size() && parallel_rows[next_parallel].method == m.name()) {
        rows[&p - plan.data()].push_back(std::move(parallel_rows[next_parallel++]));
      }
    }
    serial_progress.tick();
  }
  {
    std::ofstream csv(dir / "instances.csv");
    csv << kRowHeader << '\n';
    for (const auto& rs : rows)
      for (const Row& r : rs) write_row(csv, r);
    std::ofstream inputs(dir / "inputs.csv");
    inputs << "instance,family,query,k_ulps,expected,certified_answer,gap_lo,gap_hi,gap_sign_ok,input_hex\n";
    for (const Planned& p : plan)
      inputs << p.inst.id << ',' << p.inst.family << ',' << to_string(p.inst.query) << ',' << p.k << ',' << to_string(p.inst.expected) << ','
             << to_string(p.inst.certified) << ',' << num(p.inst.gap_lo) << ',' << num(p.inst.gap_hi) << ',' << (p.inst.certified_ok ? 1 : 0)
             << ',' << x_hex(p.inst.x) << '\n';
  }
  if (o.map_cells > 0 && o.shard_index == 0) run_failure_maps(o, registry, dir);
  if (o.hunt_evaluations > 0) run_hunt(o, registry, dir);
  std::ofstream(dir / "machine.json") << machine_json(o, peers).dump(2) << '\n';

  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (sharded) {
    out << "shard " << o.shard_index << '/' << o.shard_count << ": " << plan.size() << " instances in " << std::fixed << std::setprecision(1)
        << seconds << " s, written to " << dir.string() << "\nmerge the shards with: certcyl merge " << (fs::path(o.out_root) / o.name).string()
        << '\n';
    return 0;
  }
  out << write_summary(dir);
  out << "results: " << dir.string() << " (" << std::fixed << std::setprecision(1) << seconds << " s)\n";
  run_plots(dir, o.plots, out);
  return 0;
}

namespace {

// The shards of a study folder, checked: each shard-* folder holds a machine.json whose
// "shard" is i/n (the folder's name is not trusted: a copied folder is a duplicate); every
// shard shares one n, one configuration (every option but the shard, the thread count and the
// name) and one build (commit, compiler, flags, CGAL, peer libraries); each of
// 0..n-1 is there exactly once. Throws std::runtime_error naming what differs or is missing.
std::vector<fs::path> checked_shards(const fs::path& dir, std::vector<fs::path> shards, nlohmann::json& machine) {
  std::sort(shards.begin(), shards.end());
  struct Seen {
    fs::path path;
    nlohmann::json machine;
  };
  std::vector<Seen> seen;
  for (const fs::path& s : shards) {
    std::ifstream in(s / "machine.json");
    if (!in) throw std::runtime_error("merge: " + s.string() + ": no machine.json (an unfinished or foreign shard?)");
    Seen entry{s, nlohmann::json::parse(in, nullptr, false)};
    if (entry.machine.is_discarded() || !entry.machine.contains("options") || !entry.machine["options"].contains("shard"))
      throw std::runtime_error("merge: " + (s / "machine.json").string() + ": not a study's machine.json");
    seen.push_back(std::move(entry));
  }
  const Seen& first = seen.front();
  auto where = [](const Seen& e) { return e.path.filename().string(); };
  int count = -1;
  std::map<int, std::vector<std::string>> by_index;
  for (const Seen& e : seen) {
    int index = 0, n = 0;
    const std::string shard = e.machine["options"]["shard"].get<std::string>();
    try {
      parse_shard(shard, index, n);
    } catch (const std::exception&) {
      throw std::runtime_error("merge: " + where(e) + ": machine.json has shard '" + shard + "'");
    }
    if (count >= 0 && n != count)
      throw std::runtime_error("merge: shards of different counts: " + where(first) + " is one of " + std::to_string(count) + ", " + where(e) +
                               " one of " + std::to_string(n));
    count = n;
    by_index[index].push_back(where(e));
    // The configuration and the build must be the same.
    for (const char* key : {"commit", "compiler", "flags", "cgal", "peers"})
      if (e.machine.value(key, nlohmann::json()) != first.machine.value(key, nlohmann::json()))
        throw std::runtime_error(std::string("merge: shards from different builds: ") + key + " is " + first.machine.value(key, nlohmann::json()).dump() +
                                 " in " + where(first) + " but " + e.machine.value(key, nlohmann::json()).dump() + " in " + where(e));
    const nlohmann::json& a = first.machine["options"];
    const nlohmann::json& b = e.machine["options"];
    std::set<std::string> keys;
    for (const auto& [k, v] : a.items()) keys.insert(k);
    for (const auto& [k, v] : b.items()) keys.insert(k);
    for (const std::string& k : keys) {
      if (k == "shard" || k == "threads" || k == "name") continue;
      const nlohmann::json va = a.value(k, nlohmann::json()), vb = b.value(k, nlohmann::json());
      if (va != vb)
        throw std::runtime_error("merge: shards of different configurations: " + k + " is " + va.dump() + " in " + where(first) + " but " +
                                 vb.dump() + " in " + where(e));
    }
  }
  std::string missing, duplicate;
  for (int i = 0; i < count; ++i) {
    const auto it = by_index.find(i);
    if (it == by_index.end()) missing += (missing.empty() ? "" : ", ") + std::to_string(i);
  }
  for (const auto& [i, folders] : by_index) {
    if (folders.size() < 2) continue;
    duplicate += std::string(duplicate.empty() ? "" : "; ") + std::to_string(i) + " (";
    for (std::size_t k = 0; k < folders.size(); ++k) duplicate += (k ? ", " : "") + folders[k];
    duplicate += ")";
  }
  if (!missing.empty())
    throw std::runtime_error("merge: missing shard(s) " + missing + " of " + std::to_string(count) + " in " + dir.string());
  if (!duplicate.empty()) throw std::runtime_error("merge: duplicate shard(s) " + duplicate + " in " + dir.string());
  machine = first.machine;
  return shards;
}

}  // namespace

int run_merge(const std::string& dir_name, bool plots, std::ostream& out) {
  const fs::path dir(dir_name);
  std::vector<fs::path> shards;
  if (fs::is_directory(dir))
    for (const auto& e : fs::directory_iterator(dir))
      if (e.is_directory() && e.path().filename().string().rfind("shard-", 0) == 0) shards.push_back(e.path());
  if (shards.empty()) {
    out << "merge: no shard-*-of-* folders in " << dir_name << '\n';
    return 1;
  }
  nlohmann::json machine;
  shards = checked_shards(dir, std::move(shards), machine);
  std::sort(shards.begin(), shards.end());
  // Instances and inputs in instance order; hunting lines in method order; maps from shard 0.
  std::vector<std::pair<std::uint64_t, std::string>> rows, inputs;
  std::vector<std::string> hunt;
  for (const fs::path& s : shards) {
    auto read = [&](const char* file, std::vector<std::pair<std::uint64_t, std::string>>& into, std::size_t id_field) {
      std::ifstream in(s / file);
      if (!in) throw std::runtime_error("merge: missing " + (s / file).string());
      std::string line;
      std::getline(in, line);
      while (std::getline(in, line)) into.emplace_back(std::stoull(split(line, ',')[id_field]), line);
    };
    read("instances.csv", rows, 2);
    read("inputs.csv", inputs, 0);
    std::ifstream h(s / "hunt.csv");
    std::string line;
    std::getline(h, line);
    while (std::getline(h, line)) hunt.push_back(line);
    if (fs::exists(s / "failure_maps")) fs::copy(s / "failure_maps", dir / "failure_maps", fs::copy_options::recursive | fs::copy_options::overwrite_existing);
  }
  std::stable_sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::stable_sort(inputs.begin(), inputs.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::sort(hunt.begin(), hunt.end());
  {
    std::ofstream csv(dir / "instances.csv");
    csv << kRowHeader << '\n';
    for (const auto& r : rows) csv << r.second << '\n';
    std::ofstream in(dir / "inputs.csv");
    in << "instance,family,query,k_ulps,expected,certified_answer,gap_lo,gap_hi,gap_sign_ok,input_hex\n";
    for (const auto& r : inputs) in << r.second << '\n';
    std::ofstream h(dir / "hunt.csv");
    h << "method,query,start_family,evaluations,found,answer,certified_answer,outcome,gap_lo,gap_hi,input_hex\n";
    for (const auto& l : hunt) h << l << '\n';
    machine["merged_shards"] = shards.size();
    machine["options"]["shard"] = "merged";
    std::ofstream(dir / "machine.json") << machine.dump(2) << '\n';
  }
  out << write_summary(dir);
  out << "merged " << shards.size() << " shards into " << dir.string() << '\n';
  run_plots(dir, plots, out);
  return 0;
}

}  // namespace certcyl::cli
