// Every method of the registry on every planned instance: the certified answer, each method's
// answer, outcome and time (the rows of instances.csv), and the two CSV files they make.
#include <cmath>
#include <fstream>
#include <iostream>
#include <mutex>
#include <tuple>

#include "study/gap.hpp"
#include "study_internal.hpp"

namespace certcyl::cli::detail {
using namespace certcyl::study;

namespace {

std::mutex serial_mutex;

}  // namespace

double t_error_ulps(double t, double exact) {
  const double scale = std::max(std::fabs(exact), 1.0);
  const double ulp = std::nextafter(scale, std::numeric_limits<double>::infinity()) - scale;
  return static_cast<double>(std::fabs(static_cast<long double>(t) - static_cast<long double>(exact)) / ulp);
}

// Runs a method and measures it: one timed call; calls under 2 us are repeated 16 times and
// the mean of the repetitions is reported (the clock costs ~20 ns per reading).
std::pair<MethodOutput, double> run_timed(const Method& m, const std::vector<double>& x) {
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

std::string outcome_of(const MethodOutput& m, const Instance& inst) {
  if (inst.certified == Answer::undecided) return "uncertified";
  return std::string(to_string(judge(m, inst.certified)));
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
  // With `child`, the call runs in that child process (the serial methods).
  auto evaluate = [&](Planned& p, const Method& m, ChildRunner* child) {
    const Instance& inst = p.inst;
    // The slow types run on a pseudo-random 1/stride of each family (not every stride-th
    // index, which would pick the k = 0 instances: ulp_offset makes every 8th one k = 0).
    if (m.query != inst.query || (mix(0, p.index_in_family) >> 32) % m.stride != 0 || !keep_name(o.methods, m.name())) return;
    MethodOutput res;
    double ns = 0;
    bool ended = false;
    if (child != nullptr) {
      const ChildCall c = child->run(m, inst.x, /*timed=*/true);
      res = c.out, ns = c.ns, ended = c.ended;
      if (c.ended)
        std::cerr << "certcyl study: " << m.name() << " ended its process on instance " << inst.id << " (" << c.reason
                  << "): answered process_ended\n";
    } else {
      std::tie(res, ns) = run_timed(m, inst.x);
    }
    Row r;
    r.family = inst.family, r.query = std::string(to_string(inst.query)), r.instance = inst.id, r.k = p.k;
    r.expected = std::string(to_string(inst.expected));
    r.method = m.name(), r.base = m.base, r.nt = m.nt, r.kind = std::string(to_string(m.kind));
    r.answer = ended ? "process_ended" : answer_label(res), r.certified = std::string(to_string(inst.certified)), r.outcome = outcome_of(res, inst);
    r.gap_lo = inst.gap_lo, r.gap_hi = inst.gap_hi, r.ns = ns;
    if (is_line_query(inst.query) && !res.intersecting && intersects(res.answer) && intersects(inst.certified) &&
        std::isfinite(res.t_in) && std::isfinite(inst.t_in))
      r.t_error = t_error_ulps(res.t_in, inst.t_in);
    rows[&p - plan.data()].push_back(std::move(r));
  };
  Progress progress(o, "instances", plan.size());
  parallel_for(plan.size(), o.threads, [&](std::size_t pi) {
    certify(plan[pi].inst);
    for (const Method& m : registry)
      if (!m.serial) evaluate(plan[pi], m, nullptr);
    progress.tick();
  });
  // The serial methods, on this thread only (see Method::serial), in registry order per instance,
  // each call in a child process (ChildRunner: CORE::Expr ends its process on some inputs; such
  // a call is answered process_ended, outcome error, and the study goes on).
  std::vector<const Method*> serial;
  for (const Method& m : registry)
    if (m.serial) serial.push_back(&m);
  ChildRunner child(serial);
  Progress serial_progress(o, "instances (serial)", plan.size());
  for (Planned& p : plan) {
    std::vector<Row> parallel_rows = std::move(rows[&p - plan.data()]);
    rows[&p - plan.data()].clear();
    std::size_t next_parallel = 0;
    for (const Method& m : registry) {
      if (m.serial) {
        evaluate(p, m, &child);
      } else if (m.query == p.inst.query && next_parallel < parallel_rows.size() && parallel_rows[next_parallel].method == m.name()) {
        rows[&p - plan.data()].push_back(std::move(parallel_rows[next_parallel++]));
      }
    }
    serial_progress.tick();
  }
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
}

}  // namespace certcyl::cli::detail
