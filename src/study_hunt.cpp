// The worst-input hunt: per method, a search for the wrong answer farthest from any degeneracy
// (hunt.csv); the methods that may end the process are hunted in a child process.
#include <cerrno>
#include <cmath>
#include <fstream>
#include <functional>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <sys/wait.h>
#include <unistd.h>

#include "fd_io.hpp"
#include "study/contract.hpp"
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
                       const std::function<void(const std::string&)>& trace, Contract contract) {
  const auto families = all_families();
  std::vector<const Family*> starts, samples;
  for (const Family& f : families) {
    if (std::find(f.queries.begin(), f.queries.end(), query) == f.queries.end()) continue;
    samples.push_back(&f);
    if (f.name != "uniform") starts.push_back(&f);
  }
  const Family* uniform = nullptr;
  for (const Family* f : samples)
    if (f->name == "uniform") uniform = f;
  Rng rng(mix(seed, hash_string(name + std::string(to_string(query)))));
  long evaluations = 0;
  const double none = -std::numeric_limits<double>::infinity();
  double best_score = none;
  Instance best;
  MethodOutput best_out;
  std::string best_family;
  auto score = [&](Instance& inst, MethodOutput& out) {
    ++evaluations;
    try {
      certify(inst);
    } catch (const std::exception&) {  // a move left the valid inputs (a radius <= 0, p0 == p1, ...)
      return std::numeric_limits<double>::quiet_NaN();
    }
    if (inst.certified == Answer::undecided) return none;
    if (trace) trace("X " + x_hex(inst.x));
    out = run(inst.x);
    if (!disagrees(judge(out, certified_under(inst, contract)))) return none;
    // The certified lower bound of |gap| (0 when the enclosure contains 0).
    const double g = inst.gap_lo > 0 ? inst.gap_lo : (inst.gap_hi < 0 ? -inst.gap_hi : 0.0);
    return g > 0 ? std::log(g) : -1e300;
  };
  auto keep = [&](const Instance& inst, const MethodOutput& out, double sc, const std::string& family) {
    if (sc > best_score) best_score = sc, best = inst, best_out = out, best_family = family;
  };

  // Phase 1, sampling: a quarter of the budget on independent inputs, every other one from the
  // uniform family (generic input, far from every degeneracy: where a method wrong on a share of
  // typical inputs is found) and the others from a random family at a random displacement k.
  // A budget below 200 (a smoke run: `certcyl judge --size small` spends 150) is all local search.
  const long sampled = budget >= 200 ? budget / 4 : 0;
  for (long i = 0; i < sampled; ++i) {
    const Family* f = uniform && (i % 2 == 0 || starts.empty())
                          ? uniform
                          : samples[static_cast<std::size_t>(rng.integer(0, static_cast<long long>(samples.size()) - 1))];
    Instance inst;
    inst.query = query;
    inst.x = f->make(rng, query, ulp_offset(rng, static_cast<std::size_t>(rng.integer(1, 7)))).x;
    if (trace) trace("F " + f->name);
    MethodOutput out;
    keep(inst, out, score(inst, out), f->name);
  }

  // Phase 2, local searches: restarts at the degenerate configurations of the query's families
  // (k = 0) and, once a wrong answer is known, every other restart from the best one so far; each
  // climbs by moves of one coordinate that keep the method wrong and raise the score.
  const long remaining = budget - evaluations;
  const long restarts = std::max(1L, budget / 50);
  for (long r = 0; r < restarts && evaluations < budget; ++r) {
    const bool from_best = best_score > none && (r % 2 == 1 || starts.empty());
    Instance cur;
    MethodOutput cur_out;
    double cur_score = none;
    std::string family;
    if (from_best) {
      cur = best, cur_out = best_out, cur_score = best_score, family = best_family;
      if (trace) trace("F " + family);
    } else {
      const Family* f = starts.empty() ? samples.front()
                                       : starts[static_cast<std::size_t>(rng.integer(0, static_cast<long long>(starts.size()) - 1))];
      family = f->name;
      cur.query = query;
      cur.x = f->make(rng, query, 0).x;
      if (trace) trace("F " + family);
      cur_score = score(cur, cur_out);
    }
    const std::vector<double> start = cur.x;
    double scale = 0;
    for (double v : start) scale = std::max(scale, std::fabs(v));
    // Stay near the restart's input (each coordinate within `reach` of its start, relative to
    // the input's scale): the search asks how far from the degeneracy a method stays wrong, not
    // where double overflows. From a wrong input already found the reach is wider, 1/4.
    const double reach = from_best ? 0.25 : 0x1p-6;
    const long steps = remaining / restarts;
    for (long st = 0; st < steps && evaluations < budget; ++st) {
      Instance next = cur;
      const std::size_t c = static_cast<std::size_t>(rng.integer(0, static_cast<long long>(next.x.size()) - 1));
      bool long_step = false;  // an ulp step of more than 2^20 ulps
      if (from_best && rng.coin()) {
        // A relative move: by up to 2^-e of the input's scale, e in [2, 24].
        const int e = static_cast<int>(rng.integer(2, 24));
        next.x[c] += std::ldexp(scale, -e) * rng.uniform(-1, 1);
      } else {
        const long long e = rng.integer(0, 44);
        const long long step = (1LL << e) * (rng.coin() ? 1 : -1);
        next.x[c] = ulp_step(next.x[c], step);
        long_step = e > 20;
      }
      if (!std::isfinite(next.x[c]) || std::fabs(next.x[c] - start[c]) > reach * scale) continue;
      MethodOutput next_out;
      const double sc = score(next, next_out);
      if (std::isnan(sc)) continue;  // not a valid input: not a move
      // Before a first failure, wander; afterwards, only climb.
      if (sc >= cur_score || cur_score == none) {
        if (sc == none && cur_score == none && long_step) continue;
        cur = std::move(next), cur_out = next_out, cur_score = sc;
      }
      keep(cur, cur_out, cur_score, family);
    }
    keep(cur, cur_out, cur_score, family);
  }
  std::ostringstream line;
  const bool found = best_score > none;
  line << csv_field(name) << ',' << to_string(query) << ',' << (found ? best_family : "") << ',' << evaluations << ',' << (found ? 1 : 0);
  if (found) {
    const Answer under = certified_under(best, contract);
    line << ',' << answer_label(best_out) << ',' << to_string(under) << ',' << to_string(judge(best_out, under)) << ','
         << num(best.gap_lo) << ',' << num(best.gap_hi) << ',' << x_hex(best.x);
  } else {
    line << ",,,,,,";
  }
  return line.str();
}

// For each method (hunt_worst): a quarter of the evaluations (of 200 or more) on independent inputs, half of them
// uniform random ones and half from the query's families at random displacements; then random
// restarts at the degenerate configurations of its query's families (k = 0), alternating, once
// a wrong answer is known, with restarts from the best one; each a local search over ulp
// perturbations of single coordinates (and, from a wrong input found, relative moves) that keeps
// the method wrong (false positive or false negative, under its contract) while pushing the
// certified lower bound of |gap| up. The result is the wrong answer farthest from any degeneracy
// that the search found.
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
    lines[mi] = hunt_worst(m.name(), m.query, o.seed, budget, [&m](const std::vector<double>& x) { return run_quiet(m, x); }, trace,
                           m.contract);
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
