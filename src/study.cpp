// `certcyl study`: the robustness study, its stages in order (study_internal.hpp): the plan,
// every method of the registry on the hard-case families and uniform inputs judged against the
// certified answers, the failure maps, the failure hunting, the machine facts, the summary and
// the plots (experiments/plot_study.py).
//
// Results folder (results/<name>/):
//   instances.csv         one row per instance and method (tidy)
//   inputs.csv            one row per instance: its certified answer, gap, (cylinder pairs)
//                         the stage that decided it, and its hexfloat input
//   uniform.csv           the uniform sample: per query and method, its error counts on
//                         uniform_per_query random instances (study_uniform.cpp)
//   summary.txt/.csv      the disagreement table per method and query (and per family in
//                         summary_families.csv)
//   stages.csv            per family, the stages that decided the certified cylinder pairs
//   machine.json          compiler, flags, CPU, commit, libraries, options
//   failure_maps/*.csv    the 2-D ulp perturbation grids, one column per method (+ *.json)
//   hunt.csv              the worst input found per method, in hexfloats
//   Core_Diagnostics      CORE::Expr's warnings (when it gave any), counted in summary.txt
//   figures/*.png|pdf     written by experiments/plot_study.py from the CSV files
//   manifest.json         written last: size, rows and SHA-256 of every file but the figures
// The folder is written as <parent>/.<name>.partial and renamed when complete, replacing any
// earlier one. A shard (--shard i/n) writes results/<name>/shard-i-of-n/ without summary and
// figures; `certcyl merge` verifies the shards and makes the rest (study_merge.cpp).
#include <chrono>
#include <fstream>
#include <iomanip>
#include <optional>

#include "study_internal.hpp"
#include "study_files.hpp"
#include "study_methods.hpp"

namespace certcyl::cli {
using namespace detail;
using namespace certcyl::study;

namespace {

// CORE::Expr appends its warnings to Core_Diagnostics in the working directory
// (CGAL/CORE/CoreAux_impl.h, core_error): the run works inside its folder, so they stay with its
// results (its forked hunts inherit the folder), never in the caller's directory.
class WorkingDirectory {
 public:
  explicit WorkingDirectory(const fs::path& dir) : previous_(fs::current_path()) { fs::current_path(dir); }
  ~WorkingDirectory() {
    std::error_code ignored;
    fs::current_path(previous_, ignored);
  }
  WorkingDirectory(const WorkingDirectory&) = delete;
  WorkingDirectory& operator=(const WorkingDirectory&) = delete;

 private:
  fs::path previous_;
};

}  // namespace

int run_study(StudyOptions o, std::ostream& out) {
  const auto start = std::chrono::steady_clock::now();
  Registry registry;
  register_line_methods(registry);
  register_triangle_methods(registry);
  register_cylinder_methods(registry);
  const std::vector<std::string> peers = register_peer_methods(registry);
  mark_serial(registry);
  attach_conversions(registry);
  std::vector<std::string> method_names;
  for (const Method& m : registry) method_names.push_back(m.name());
  configure_study(o, method_names);

  fs::path dir = fs::path(o.out_root) / o.name;
  const bool sharded = o.shard_count > 1;
  if (sharded) dir /= "shard-" + std::to_string(o.shard_index) + "-of-" + std::to_string(o.shard_count);
  // Everything is written aside and the folder takes its place when complete (study_manifest.cpp).
  const fs::path work = fs::absolute(begin_folder(dir));
  std::optional<WorkingDirectory> inside(std::in_place, work);

  std::vector<Planned> plan = plan_instances(o);
  std::vector<std::vector<Row>> rows = run_instances(o, registry, plan);
  write_instances(work, plan, rows);
  // Their writer does not report errors: the lines on disk must be all the lines written.
  std::size_t row_count = 0;
  for (const auto& r : rows) row_count += r.size();
  check_lines(work / "instances.csv", row_count + 1);
  check_lines(work / "inputs.csv", plan.size() + 1);
  run_uniform_sample(o, registry, work);
  if (o.map_cells > 0 && o.shard_index == 0) run_failure_maps(o, registry, work);
  if (o.hunt_evaluations > 0) run_hunt(o, registry, work);
  write_whole(work / "machine.json", machine_json(o, peers).dump(2) + '\n');
  const std::string table = sharded ? std::string() : write_summary(work);
  inside.reset();
  seal_folder(work, dir);

  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (sharded) {
    out << "shard " << o.shard_index << '/' << o.shard_count << ": " << plan.size() << " instances in " << std::fixed << std::setprecision(1)
        << seconds << " s, written to " << dir.string() << "\nmerge the shards with: certcyl merge " << (fs::path(o.out_root) / o.name).string()
        << '\n';
    return 0;
  }
  out << table;
  out << "results: " << dir.string() << " (" << std::fixed << std::setprecision(1) << seconds << " s)\n";
  run_plots(dir, o.plots, out);
  return 0;
}

}  // namespace certcyl::cli
