// Every method of the registry on every planned instance: the certified answer, each method's
// answer, outcome and time (the rows of instances.csv), and the CSV files they make.
//
// Two passes. The answer pass certifies every instance and runs every parallel method once on
// o.threads threads (answers only). The timing pass then runs on the main thread alone, pinned
// to one CPU (sched_setaffinity; when pinning fails it runs unpinned and says why), while no
// other thread of the study runs: every method on every instance under one repetition protocol
// (run_timed), the serial methods (CORE::Expr) answered and timed there in their child process,
// which is forked from the pinned thread and so pinned to the same CPU.
#include <sched.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <tuple>

#include "study/contract.hpp"
#include "study/conversion.hpp"
#include "study/gap.hpp"
#include "study_internal.hpp"
#include "study_files.hpp"

namespace certcyl::cli::detail {
using namespace certcyl::study;

const char* const kTimingThreadHeader = "shard,pinned,cpu,budget_ns,measurements,note";

namespace {

std::mutex serial_mutex;

// The timing pass's thread of the last run_instances (timing_thread.csv).
TimingThread last_timing_thread;

// Pins the calling thread to the CPU it runs on; `previous` receives the affinity to restore.
TimingThread pin_this_thread(cpu_set_t& previous) {
  TimingThread t;
  CPU_ZERO(&previous);
  if (::sched_getaffinity(0, sizeof previous, &previous) != 0) {
    t.note = std::string("not pinned: sched_getaffinity failed: ") + std::strerror(errno);
    return t;
  }
  int cpu = ::sched_getcpu();
  if (cpu < 0 || cpu >= CPU_SETSIZE || !CPU_ISSET(cpu, &previous)) {
    cpu = -1;
    for (int c = 0; c < CPU_SETSIZE && cpu < 0; ++c)
      if (CPU_ISSET(c, &previous)) cpu = c;
  }
  if (cpu < 0) {
    t.note = "not pinned: no CPU in the thread's affinity mask";
    return t;
  }
  cpu_set_t one;
  CPU_ZERO(&one);
  CPU_SET(cpu, &one);
  if (::sched_setaffinity(0, sizeof one, &one) != 0) {
    t.note = std::string("not pinned: sched_setaffinity to CPU ") + std::to_string(cpu) + " failed: " + std::strerror(errno);
    return t;
  }
  t.pinned = true, t.cpu = cpu;
  t.note = "pinned the main thread (and the serial methods' child processes) to CPU " + std::to_string(cpu) + " of " +
           std::to_string(CPU_COUNT(&previous)) + " allowed";
  return t;
}

}  // namespace

double t_error_ulps(double t, double exact) {
  const double scale = std::max(std::fabs(exact), 1.0);
  const double ulp = std::nextafter(scale, std::numeric_limits<double>::infinity()) - scale;
  return static_cast<double>(std::fabs(static_cast<long double>(t) - static_cast<long double>(exact)) / ulp);
}

// The repetition protocol, the same for every call: a measurement runs the method on the input
// in batches of 1, 2, 4, ... back-to-back calls, the clock read after each batch, until
// kTimingBudgetNs have elapsed since its first call began (at least one call), and gives the
// elapsed time over its calls; the time is the median of kTimingMeasurements measurements (a
// measurement that a time slice of another process fell into, 4 ms on a shared core, does not
// set it). A call of 20 us or more is so made three times, a 25 ns call some 3000 times, the ~10
// clock readings of a measurement costing about 1% of its budget. The output is the first
// call's; a call that throws is made once.
std::pair<MethodOutput, double> run_timed(const Method& m, const std::vector<double>& x) {
  using clock = std::chrono::steady_clock;
  std::unique_lock<std::mutex> lock(serial_mutex, std::defer_lock);
  if (m.serial) lock.lock();  // before the clock starts: waiting is not the method's time
  MethodOutput out;
  double times[kTimingMeasurements];
  for (int k = 0; k < kTimingMeasurements; ++k) {
    const auto t0 = clock::now();
    long calls = 0;
    double ns = 0;
    try {
      if (k == 0) {
        try {
          out = m.run(x);
        } catch (const std::exception&) {
          out = MethodOutput{};
          out.error = true;
        }
        calls = 1;
        ns = std::chrono::duration<double, std::nano>(clock::now() - t0).count();
        if (out.error) return {out, ns};
      }
      for (long batch = 1; calls == 0 || ns < kTimingBudgetNs; batch *= 2) {
        for (long i = 0; i < batch; ++i) (void)m.run(x);
        calls += batch;
        ns = std::chrono::duration<double, std::nano>(clock::now() - t0).count();
      }
    } catch (const std::exception&) {
      // A method that threw on a repetition but not on its first call: the calls completed so far.
      ns = std::chrono::duration<double, std::nano>(clock::now() - t0).count();
      calls = std::max(calls, 1L);
    }
    times[k] = ns / static_cast<double>(calls);
  }
  std::sort(times, times + kTimingMeasurements);
  return {out, times[kTimingMeasurements / 2]};
}

std::string outcome_of(const MethodOutput& m, const Instance& inst, Contract c) {
  if (inst.certified == Answer::undecided) return "uncertified";
  return std::string(to_string(judge(m, certified_under(inst, c))));
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

std::vector<std::vector<Row>> run_instances(const StudyOptions& o, const Registry& registry, std::vector<Planned>& plan) {
  std::vector<std::vector<Row>> rows(plan.size());
  // The methods that run on an instance: its query's, on a pseudo-random 1/stride of each family
  // for the slow types (not every stride-th index, which would pick the k = 0 instances:
  // ulp_offset makes every 8th one k = 0), as the method filter allows.
  auto applies = [&](const Planned& p, const Method& m) {
    return m.query == p.inst.query && (mix(0, p.index_in_family) >> 32) % m.stride == 0 && keep_name(o.methods, m.name());
  };
  // The certified answers of the instances the methods received (study/conversion.hpp), per
  // planned instance and conversion name: each certified once, on the thread of its instance.
  std::vector<std::map<std::string, Answer>> received(plan.size());
  auto received_answer = [&](std::size_t pi, const Method& m) -> std::optional<Answer> {
    if (!m.conversion || plan[pi].inst.certified == Answer::undecided) return std::nullopt;
    const std::string key = m.conversion->name + "/" + std::string(to_string(m.contract));
    const auto it = received[pi].find(key);
    if (it != received[pi].end()) return it->second;
    Answer a = Answer::undecided;
    try {
      a = m.conversion->certified(plan[pi].inst.query, plan[pi].inst.x, m.contract);
    } catch (const std::exception&) {  // the received instance is not a valid input
    }
    return received[pi][key] = a;
  };
  auto row_of = [&](std::size_t pi, const Method& m, const MethodOutput& res, bool ended) {
    const Planned& p = plan[pi];
    const Instance& inst = p.inst;
    Row r;
    r.family = inst.family, r.query = std::string(to_string(inst.query)), r.instance = inst.id, r.k = p.k;
    r.expected = std::string(to_string(inst.expected));
    r.method = m.name(), r.base = m.base, r.nt = m.nt, r.kind = std::string(to_string(m.kind));
    r.answer = ended ? "process_ended" : answer_label(res), r.certified = std::string(to_string(inst.certified));
    r.outcome = outcome_of(res, inst, m.contract);
    r.contract = std::string(to_string(m.contract));
    const Answer under = certified_under(inst, m.contract);
    r.contract_answer = std::string(to_string(under));
    const std::optional<Answer> got = received_answer(pi, m);
    if (got) r.received_answer = std::string(to_string(*got));
    if (!ended) r.cause = std::string(to_string(error_cause(res, under, got)));
    r.gap_lo = inst.gap_lo, r.gap_hi = inst.gap_hi;
    if (is_line_query(inst.query) && !res.intersecting && intersects(res.answer) && intersects(inst.certified) &&
        std::isfinite(res.t_in) && std::isfinite(inst.t_in))
      r.t_error = t_error_ulps(res.t_in, inst.t_in);
    return r;
  };
  // The answer pass: certified answers and the parallel methods' answers, on o.threads threads.
  Progress progress(o, "instances", plan.size());
  parallel_for(plan.size(), o.threads, [&](std::size_t pi) {
    certify(plan[pi].inst);
    for (const Method& m : registry)
      if (!m.serial && applies(plan[pi], m)) rows[pi].push_back(row_of(pi, m, run_quiet(m, plan[pi].inst.x), false));
    progress.tick();
  });
  // The timing pass, on this thread alone, pinned: every method timed by run_timed, in registry
  // order per instance; the serial methods answered here too, each call in a child process
  // (ChildRunner: CORE::Expr ends its process on some inputs; such a call is answered
  // process_ended, outcome error, and the study goes on).
  cpu_set_t previous;
  last_timing_thread = pin_this_thread(previous);
  if (!last_timing_thread.pinned) std::cerr << "certcyl study: timing " << last_timing_thread.note << '\n';
  std::vector<const Method*> serial;
  for (const Method& m : registry)
    if (m.serial) serial.push_back(&m);
  {
    ChildRunner child(serial);  // forked from the pinned thread: pinned too
    Progress timing_progress(o, "timing", plan.size());
    for (std::size_t pi = 0; pi < plan.size(); ++pi) {
      Planned& p = plan[pi];
      std::vector<Row> answered = std::move(rows[pi]);
      rows[pi].clear();
      std::size_t next = 0;
      for (const Method& m : registry) {
        if (!applies(p, m)) continue;
        if (m.serial) {
          const ChildCall c = child.run(m, p.inst.x, /*timed=*/true);
          if (c.ended)
            std::cerr << "certcyl study: " << m.name() << " ended its process on instance " << p.inst.id << " (" << c.reason
                      << "): answered process_ended\n";
          rows[pi].push_back(row_of(pi, m, c.out, c.ended));
          rows[pi].back().ns = c.ns;
        } else {
          if (next >= answered.size() || answered[next].method != m.name()) throw std::logic_error("run_instances: answer pass out of order");
          rows[pi].push_back(std::move(answered[next++]));
          rows[pi].back().ns = run_timed(m, p.inst.x).second;
        }
      }
      timing_progress.tick();
    }
  }
  if (last_timing_thread.pinned) ::sched_setaffinity(0, sizeof previous, &previous);
  last_timing_thread.shard = o.shard_index;
  return rows;
}

void write_instances(const fs::path& dir, const std::vector<Planned>& plan, const std::vector<std::vector<Row>>& rows) {
  std::ofstream csv(dir / "instances.csv");
  csv << kRowHeader << '\n';
  for (const auto& rs : rows)
    for (const Row& r : rs) write_row(csv, r);
  std::ofstream inputs(dir / "inputs.csv");
  inputs << kInputsHeader << '\n';
  for (const Planned& p : plan)
    inputs << p.inst.id << ',' << p.inst.family << ',' << to_string(p.inst.query) << ',' << p.k << ',' << to_string(p.inst.expected) << ','
           << to_string(p.inst.certified) << ',' << num(p.inst.gap_lo) << ',' << num(p.inst.gap_hi) << ',' << (p.inst.certified_ok ? 1 : 0)
           << ',' << p.inst.stage << ',' << p.inst.certified_by << ',' << (p.inst.stage.empty() ? "" : std::to_string(p.inst.gmpfr_precision))
           << ',' << x_hex(p.inst.x) << '\n';
  std::ofstream timing(dir / "timing_thread.csv");
  timing << kTimingThreadHeader << '\n'
         << last_timing_thread.shard << ',' << (last_timing_thread.pinned ? 1 : 0) << ','
         << (last_timing_thread.pinned ? std::to_string(last_timing_thread.cpu) : std::string()) << ',' << num(kTimingBudgetNs) << ','
         << kTimingMeasurements << ',' << csv_field(last_timing_thread.note) << '\n';
  close_written(timing, dir / "timing_thread.csv");
}

}  // namespace certcyl::cli::detail
