// The worst-input hunt: per method, a search for the wrong answer farthest from any degeneracy
// (hunt.csv); the methods that may end the process are hunted in a child process.
#include <cerrno>
#include <cmath>
#include <fstream>
#include <functional>
#include <sstream>

#include <sys/wait.h>
#include <unistd.h>

#include "fd_io.hpp"
#include "study/families.hpp"
#include "study/gap.hpp"
#include "study_internal.hpp"
#include "study_files.hpp"

namespace certcyl::cli::detail {
using namespace certcyl::study;

namespace {

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
      if (!write_all(fds[1], data.data(), data.size())) _exit(3);
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

}  // namespace

std::string hunt_worst(const std::string& name, Query query, std::uint64_t seed, long budget,
                       const std::function<MethodOutput(const std::vector<double>&)>& run,
                       const std::function<void(const std::string&)>& trace) {
  const auto families = all_families();
  std::vector<const Family*> starts;
  for (const Family& f : families)
    if (std::find(f.queries.begin(), f.queries.end(), query) != f.queries.end() && f.name != "uniform") starts.push_back(&f);
  Rng rng(mix(seed, hash_string(name + std::string(to_string(query)))));
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
    out = run(inst.x);
    if (!disagrees(judge(out, inst.certified))) return -std::numeric_limits<double>::infinity();
    // The certified lower bound of |gap| (0 when the enclosure contains 0).
    const double g = inst.gap_lo > 0 ? inst.gap_lo : (inst.gap_hi < 0 ? -inst.gap_hi : 0.0);
    return g > 0 ? std::log(g) : -1e300;
  };
  for (long r = 0; r < restarts && evaluations < budget; ++r) {
    const Family* f = starts[static_cast<std::size_t>(rng.integer(0, static_cast<long long>(starts.size()) - 1))];
    Instance cur;
    cur.query = query;
    cur.x = f->make(rng, query, 0).x;
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
  line << csv_field(name) << ',' << to_string(query) << ',' << (found ? best_family : "") << ',' << evaluations << ',' << (found ? 1 : 0);
  if (found)
    line << ',' << answer_label(best_out) << ',' << to_string(best.certified) << ',' << to_string(judge(best_out, best.certified))
         << ',' << num(best.gap_lo) << ',' << num(best.gap_hi) << ',' << x_hex(best.x);
  else
    line << ",,,,,,";
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
  std::vector<std::string> lines(methods.size());
  Progress progress(o, "hunting", methods.size());
  auto hunt_one = [&](std::size_t mi, const std::function<void(const std::string&)>& trace) {
    const Method& m = *methods[mi];
    const long query_budget = m.query == Query::cylinder_cylinder ? std::max(1L, o.hunt_evaluations / 4) : o.hunt_evaluations;
    const long budget = std::max(1L, query_budget / static_cast<long>(std::max(1u, m.effort.hunt_divisor)));
    lines[mi] = hunt_worst(m.name(), m.query, o.seed, budget, [&m](const std::vector<double>& x) { return run_quiet(m, x); }, trace);
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
  csv << kHuntHeader << '\n';
  for (const auto& l : lines) csv << l << '\n';
  close_written(csv, dir / "hunt.csv");
}

}  // namespace certcyl::cli::detail
