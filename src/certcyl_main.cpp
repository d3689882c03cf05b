// certcyl: certified cylinder intersection queries from the command line.
#include <CLI/CLI.hpp>

#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <sstream>
#include <thread>
#include <utility>

#include <unistd.h>

#include "cases.hpp"
#include "demo.hpp"
#include "gmp_memory.hpp"
#include "interrupt.hpp"
#include "judge.hpp"
#include "query.hpp"
#include "scene.hpp"
#include "scene_generator.hpp"
#include "study.hpp"

namespace {

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

std::string query_help() {
  std::string s =
      "Reads one JSON object per line on standard input and writes one JSON line per input line,\n"
      "in the same order, echoing \"id\". Exit status: 0 all lines answered, 2 some line had an\n"
      "error (that line is {\"id\":..., \"error\": \"<field>: <what>\"}), 1 fatal (I/O, usage), 3 memory\n"
      "exhausted in GMP even after its reserve (every line written is complete).\n\n"
      "Queries and their methods:\n";
  for (const auto& [name, kind] : certcyl::cli::query_kinds()) s += "  " + name + ": " + join(kind.methods) + "\n";
  s += "\nNumbers: a JSON number is its binary64 value; a string is an exact rational\n"
       "(\"p/q\", decimal \"0.1\", hexfloat \"0x1.8p-3\"). See README.md for the operand formats.";
  return s;
}

// A finite number in [lo, hi]: "nan" and "inf" are rejected (CLI::Range lets NaN through).
CLI::Validator finite_in(double lo, double hi) {
  std::ostringstream range;
  range << '[' << lo << ", " << hi << ']';
  return CLI::Validator(
      [lo, hi, r = range.str()](std::string& s) -> std::string {
        char* end = nullptr;
        errno = 0;
        const double v = std::strtod(s.c_str(), &end);
        if (s.empty() || end != s.c_str() + s.size() || !std::isfinite(v) || v < lo || v > hi)
          return "expected a finite number in " + r + ", got '" + s + "'";
        return {};
      },
      "FLOAT in " + range.str());
}

// A number of bytes, optionally with a binary suffix K, M, G or T (or KiB, MiB, GiB, TiB): "64M"
// is 64 * 2^20; rewritten as the plain number.
CLI::Validator byte_size() {
  return CLI::Validator(
      [](std::string& s) -> std::string {
        const std::string error = "expected a number of bytes, optionally with K, M, G or T (KiB, MiB, GiB, TiB), got '" + s + "'";
        std::size_t digits = 0;
        while (digits < s.size() && s[digits] >= '0' && s[digits] <= '9') ++digits;
        if (digits == 0 || digits > 19) return error;
        static const std::pair<const char*, int> units[] = {{"", 0},   {"K", 10}, {"KiB", 10}, {"M", 20}, {"MiB", 20},
                                                            {"G", 30}, {"GiB", 30}, {"T", 40},  {"TiB", 40}};
        int shift = -1;
        for (const auto& [unit, bits] : units)
          if (s.compare(digits, std::string::npos, unit) == 0) shift = bits;
        if (shift < 0) return error;
        const unsigned long long value = std::stoull(s.substr(0, digits));
        if (value > (std::numeric_limits<std::size_t>::max() >> shift)) return "more bytes than a size can hold: '" + s + "'";
        s = std::to_string(value << shift);
        return {};
      },
      "BYTES");
}

// An integer in [0, 2^64 - 1]: a negative value is an error, never wrapped.
CLI::Validator uint64_option() {
  return CLI::Validator([](std::string& s) { return certcyl::cli::integer_error(s, 0, UINT64_MAX); }, "UINT64");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"certcyl: exact cylinder intersection queries and where floating point gets them wrong"};
  app.require_subcommand(1);

  CLI::App* demo = app.add_subcommand("demo", "Answer a few built-in queries of each kind in every number type");

  certcyl::cli::QueryOptions options;
  std::string nt_name = "double";
  unsigned threads = 1;
  CLI::App* query = app.add_subcommand("query", "Answer JSON-lines queries from standard input");
  query->footer(query_help());
  query->add_option("--method", options.method, "Method answering every line (default certified); see below")
      ->check(CLI::IsMember(certcyl::cli::all_methods()));
  query->add_option("--nt", nt_name,
                    "Number type of generic methods: double, long_double, interval, gmpq, mpzf, gmpfr<BITS>, "
                    "lazy_gmpq, core_expr (default double)")
      ->check([](const std::string& s) {
        try {
          certcyl::parse_number_type(s, "");
          return std::string();
        } catch (const certcyl::InvalidInput& e) {
          return std::string(e.what());
        }
      });
  query->add_flag("--brief", options.brief,
                  "Only id, meta, answer, the interval of a line query as two doubles (certified: the proved\n"
                  "nearest doubles of the exact endpoints), the certified gap and the reason of an invalid answer");
  query->add_option("--threads", threads, "Worker threads (default 1; 0 = all cores)")->check(CLI::Range(0u, 1024u));
  query->add_option("--time-limit", options.time_limit_seconds,
                    "Seconds a certified cylinder-pair line may take before it is answered undecided with a\n"
                    "reason (checked between its stages and rounds, so it can run over; default 0: no limit)")
      ->check([](const std::string& text) {
        // CLI::Range lets "nan" through; a limit must be a finite number of seconds.
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (end == text.c_str() || *end != '\0' || !(v >= 0 && v <= 1e9))
          return "expected a number of seconds in [0, 1e9] (0: no limit), got '" + text + "'";
        return std::string();
      });
  query->add_option("--memory-limit", options.memory_limit_bytes,
                    "Bytes of GMP memory a line may hold (K, M, G suffixes: 1024-based) before it is answered\n"
                    "with an error line (a certified cylinder pair stops at its next check, so it can run over;\n"
                    "default 0: no limit)")
      ->transform(byte_size());
  query->add_flag("--line-buffered", options.line_buffered,
                  "Answer every line and flush its answer as soon as it is read (for a co-process; without it\n"
                  "lines are answered in batches, cut short whenever no more input is at hand)");

  std::string scene_file;
  unsigned scene_threads = 1;
  bool scene_progress = false;
  CLI::App* scene = app.add_subcommand("scene", "Find every touching or overlapping pair in a scene of cylinders");
  scene->footer(
      "Scene file: {\"cylinders\": [{\"name\": \"c1\", \"p0\": [x,y,z], \"p1\": [x,y,z], \"radius\": r}, ...],\n"
      "             \"triangles\": [{\"name\": \"t1\", \"vertices\": [P, P, P]}, ...]}  (triangles optional;\n"
      "cylinders may use the center/axis/radius/height form). Writes one JSON line per pair that touches,\n"
      "overlaps or is undecided: {\"a\": name, \"b\": name, \"answer\": ..., \"certificate\": ...}.\n"
      "Broad phase: CGAL::box_intersection_d on closed boxes rounded outward; narrow phase: the certified\n"
      "queries. A one-line summary (counts, seconds per phase) goes to standard error; --stats adds the\n"
      "same as JSON. Exit status: 0 done, 2 invalid scene, 1 I/O error or memory exhausted, 3 memory\n"
      "exhausted in GMP even after its reserve.\n"
      "A random scene to try it on: certcyl make-scene --cylinders 100000 --seed 1 > scene.json");
  scene->add_option("FILE", scene_file, "Scene JSON file")->required();
  scene->add_option("--threads", scene_threads, "Worker threads for the narrow phase (default 1; 0 = all cores)")
      ->check(CLI::Range(0u, 1024u));
  scene->add_flag("--progress", scene_progress, "Report progress on standard error (default: when it is a terminal)");
  bool scene_stats = false;
  scene->add_flag("--stats", scene_stats,
                  "Also print on standard error one line 'certcyl scene stats: {JSON}' with the counts (cylinders,\n"
                  "triangles, candidate_pairs, separated, touching, overlapping, undecided), the wall-clock seconds\n"
                  "of each phase (read, boxes, broad, narrow, write) and the narrow phase's thread-seconds in the\n"
                  "certified queries and in formatting their lines");

  certcyl::cli::SceneSpec scene_spec;
  CLI::App* make_scene = app.add_subcommand("make-scene", "Write a seeded random scene of cylinders for `certcyl scene`");
  make_scene->footer(
      "Random cylinders (uniform centres in a cube, uniform axis directions, length in [1/2, 3/2], radius in\n"
      "[1/20, 3/20]) in a cube sized so that each bounding box meets about --neighbours others, and a share\n"
      "of exactly touching axis-parallel pairs with dyadic coordinates, named walls<j>a/b, caps<j>a/b,\n"
      "crossing<j>a/b and capwall<j>a/b (wall to wall, cap to cap, crossing walls, cap on wall). The same\n"
      "seed gives the same scene on every machine. Writes the scene JSON to standard output.");
  make_scene->add_option("--cylinders", scene_spec.cylinders, "Number of cylinders (default 100000)")
      ->check(CLI::Range(1, 100000000));
  make_scene->add_option("--seed", scene_spec.seed, "Random seed (default 1)")->check(uint64_option());
  make_scene->add_option("--neighbours", scene_spec.neighbours, "Mean number of boxes meeting a cylinder's box (default 8)")
      ->check(finite_in(0.01, 1000.0));
  make_scene->add_option("--touching", scene_spec.touching_share, "Share of cylinders in exactly touching pairs (default 0.02)")
      ->check(finite_in(0.0, 1.0));

  certcyl::cli::StudyOptions study_options;
  std::string shard;
  bool no_plots = false;
  CLI::App* study = app.add_subcommand("study", "The robustness study: every method against the certified answers (the main job)");
  study->footer(
      "Runs the hard-case families of every query and uniform inputs through every method (the seeds as\n"
      "written and corrected, the robust double method, the generic methods in double, long double,\n"
      "intervals, Gmpfr and CORE::Expr, and the peer libraries found at build time), judges each answer\n"
      "against the certified one, draws failure maps and hunts for each method's worst input. Writes\n"
      "results/<name>/ (instances.csv, inputs.csv, uniform.csv, summary.txt/csv, machine.json, failure_maps/, hunt.csv,\n"
      "figures/) and prints the summary table. Sizes: tiny (seconds), small, default (minutes), large.");
  study->add_option("--name", study_options.name, "Results folder name under --out (default: the size)");
  study->add_option("--out", study_options.out_root, "Results root (default: results)");
  study->add_option("--config", study_options.config_file, "JSON configuration (per_family, map_cells, map_step, hunt_evaluations, uniform_per_query, methods, families, size, seed, name)");
  study->add_option("--size", study_options.size,
                    "tiny, small, default, large, or N instances per family and query (the failure maps and hunt\n"
                    "of the smallest preset with at least N per family, large's beyond; 1000 N uniform per query)");
  study->add_option("--seed", study_options.seed, "Random seed (default 1)")
      ->check(CLI::Validator([](std::string& s) { return certcyl::cli::integer_error(s, 0, UINT64_MAX); }, "UINT64"));
  study->add_option("--threads", study_options.threads, "Worker threads (default 2; 0 = all cores)")
      ->check(CLI::Validator([](std::string& s) { return certcyl::cli::integer_error(s, 0, 1024); }, "0..1024"));
  study->add_option("--shard", shard, "Run shard i of n (i/n, 0-based) into results/<name>/shard-i-of-n; then `certcyl merge`");
  study->add_flag("--no-plots", no_plots, "Do not run the plotting script");
  study->add_flag("--progress,!--no-progress", study_options.progress,
                  "Progress on standard error (default on): a bar on a terminal, else a plain line per phase every "
                  "--progress-every seconds and at its end; --no-progress: none");
  study->add_option("--progress-every", study_options.progress_seconds,
                    "Seconds between two plain progress lines when standard error is not a terminal (default 30)")
      ->check(CLI::Range(0.0, 86400.0));

  std::string merge_dir;
  bool merge_no_plots = false;
  CLI::App* merge = app.add_subcommand("merge", "Merge the shards of a study into one results folder");
  merge->add_option("DIR", merge_dir, "results/<name>, holding shard-*-of-* folders")->required();
  merge->add_flag("--no-plots", merge_no_plots, "Do not run the plotting script");

  certcyl::cli::CaseSpec case_spec;
  CLI::App* cases = app.add_subcommand("cases", "Write the study's cases of one query as `certcyl query` lines");
  cases->footer(
      "Writes the study's hard-case families and uniform inputs of the query (the instances `certcyl study`\n"
      "plans, certified) as JSON lines `certcyl query` answers as they stand; \"meta\" carries the family, k\n"
      "(the ulps off the degeneracy), the certified answer and the certified signed gap [lo, hi].\n"
      "Judge a method's answers to them with `certcyl judge`.");
  cases->add_option("--query", case_spec.query, "line_cylinder, ray_cylinder, segment_cylinder, line_elliptic_cylinder, "
                                                "triangle_cylinder or cylinder_cylinder")->required();
  cases->add_option("--family", case_spec.families, "Only these families (repeatable; default all of the query's)");
  cases->add_option("--size", case_spec.size, "tiny, small (default), default, large, or cases per family");
  cases->add_option("--seed", case_spec.seed, "Random seed (default 1, the study's)")->check(uint64_option());
  cases->add_option("--threads", case_spec.threads, "Threads certifying the cases (default 2; 0 = all cores)")
      ->check(CLI::Range(0u, 1024u));
  // The failure maps' size and step, in the ranges of the study's --config keys of the same names
  // (map_cells, map_step), for `cases` and `judge`.
  const auto add_map_options = [](CLI::App* command, int& cells, long& step, const std::string& cells_help) {
    command->add_option("--map-cells", cells, cells_help)
        ->check(CLI::Validator([](std::string& v) { return certcyl::cli::integer_error(v, 2, 1024); }, "2..1024"));
    command->add_option("--map-step", step, "Ulps between neighbouring cells of a map, 1 to 10^9 (default 1)")
        ->check(CLI::Validator([](std::string& v) { return certcyl::cli::integer_error(v, 1, 1000000000); }, "1..10^9"));
  };
  add_map_options(cases, case_spec.map_cells, case_spec.map_step,
                  "Also the cells of the query's failure maps, N x N each, N from 2 to 1024 (an answers file\n"
                  "answering them gives `certcyl judge --answers` the maps; default none)");

  certcyl::cli::JudgeOptions judge_options;
  CLI::App* judge = app.add_subcommand("judge", "Score a method's answers to the study's cases against the certified answers");
  judge->footer(
      "The answers come from --answers FILE ({\"id\", \"answer\"} lines), --exec COMMAND (a program reading\n"
      "`certcyl query` lines on standard input and writing one answer line per line read) or --plugin\n"
      "PATH.so (certcyl/plugin.h). The cases come from --cases FILE (`certcyl cases`) or are made as\n"
      "`certcyl cases` makes them (--query, --family, --size, --seed; a plugin without --query: every\n"
      "query it exports). Answers: separated, touching, overlapping, intersecting, undecided, invalid.\n"
      "Writes results/<name>/ (families.csv, counterexamples.jsonl, answers.jsonl, summary.txt, index.html;\n"
      "with --plugin or --exec also failure_maps/, failure_maps.csv, hunt.csv and speed.csv; the maps also\n"
      "with --answers when the cases file holds their cells, `certcyl cases --map-cells N`) and prints\n"
      "the summary. --map-cells, --map-step and --hunt-evaluations size the failure maps and the hunt.\n"
      "Exit status: 0 every case judged, 1 otherwise (what was judged before the error is written).");
  judge->add_option("--answers", judge_options.answers_file, "The method's answers, one JSON line per case");
  judge->add_option("--exec", judge_options.exec_command, "A program answering query lines (run by /bin/sh -c)");
  judge->add_option("--plugin", judge_options.plugin_file, "A shared library implementing certcyl/plugin.h");
  judge->add_option("--cases", judge_options.cases_file, "Cases file written by `certcyl cases`");
  judge->add_option("--query", judge_options.spec.query, "Make the cases of this query");
  judge->add_option("--family", judge_options.spec.families, "Only these families (repeatable)");
  judge->add_option("--size", judge_options.spec.size, "tiny, small (default), default, large, or cases per family");
  judge->add_option("--seed", judge_options.spec.seed, "Random seed (default 1)")->check(uint64_option());
  judge->add_option("--threads", judge_options.spec.threads, "Threads certifying the cases (default 2; 0 = all cores)")
      ->check(CLI::Range(0u, 1024u));
  judge->add_option("--name", judge_options.name, "Results folder name under --out (default judge)");
  judge->add_option("--out", judge_options.out_root, "Results root (default: results)");
  judge->add_option("--label", judge_options.label,
                    "The judged method's name in the results (default: the plugin's name, the --exec command or\n"
                    "the answers file's name)");
  judge->add_option("--timeout", judge_options.timeout_seconds,
                    "Seconds --exec's program or --plugin's function may take for one answer; then it is killed,\n"
                    "the answers before it are kept and the judge exits 1 naming the line (default 60; 0: no limit)")
      ->check(finite_in(0.0, 1e6));
  judge->add_option("--contract", judge_options.contract,
                    "What the method's hit promises for rays and segments: solid (default; the set meets the solid\n"
                    "cylinder), surface_entry (entering from outside: a ray starting inside is a miss) or surface_hit\n"
                    "(a surface point at t > 0, an exit counting); default: the plugin's certcyl_plugin_contract, else solid");
  // The failure maps' and the hunt's sizes (the hunt's in the range of the study's
  // hunt_evaluations).
  add_map_options(judge, judge_options.map_cells, judge_options.map_step,
                  "Failure maps of N x N cells, N from 2 to 1024 (--plugin and --exec; default the size's: 16 tiny,\n"
                  "32 small, 64 default, 128 large; --answers: the cases file's map cells, and only their N)");
  judge->add_option("--hunt-evaluations", judge_options.hunt_evaluations,
                    "Inputs the worst-input hunt evaluates per query, 1 to 10^8, a quarter of them for cylinder\n"
                    "pairs (--plugin and --exec; default the size's: 20 tiny, 150 small, 1000 default, 5000 large)")
      ->check(CLI::Validator([](std::string& s) { return certcyl::cli::integer_error(s, 1, 100000000); }, "1..10^8"));
  judge->add_option("--study", judge_options.study_dir,
                    "A study's results folder: when every case was judged, its speed-against-error figures drawn again\n"
                    "with the judged method's point, into <results>/figures (--exec and --plugin; not with --shard)");
  std::string judge_shard;
  judge->add_option("--shard", judge_shard,
                    "Judge shard i of n (i/n, 0-based: the cases whose index is i modulo n) into\n"
                    "results/<name>/shard-i-of-n, renamed into place when every case is judged; merge the shards'\n"
                    "answers.jsonl with --answers (experiments/slurm/judge-merge.sh)");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 1;
  }

  // A closed output is a write error with a message, not a silent death by SIGPIPE.
  std::signal(SIGPIPE, SIG_IGN);
  if (demo->parsed()) {
    const int status = certcyl::cli::run_demo(std::cout);
    std::cout.flush();
    if (!std::cout) {
      std::cerr << "certcyl demo: error writing standard output\n";
      return 1;
    }
    return status;
  }
  if (query->parsed()) {
    certcyl::cli::install_gmp_memory("certcyl query", "every answer line written is complete; the answers of the batch in progress (with --line-buffered, the line in progress) and the lines after it are not written");
    certcyl::cli::install_interrupt_handlers();
    options.nt = certcyl::parse_number_type(nt_name);
    options.nt_given = query->count("--nt") > 0;
    if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
    std::ios::sync_with_stdio(false);
    return certcyl::cli::run_query(std::cin, std::cout, options, threads);
  }
  if (study->parsed() || merge->parsed()) {
    const char* command = merge->parsed() ? "merge" : "study";
    int status = 0;
    try {
      if (merge->parsed()) {
        status = certcyl::cli::run_merge(merge_dir, !merge_no_plots, std::cout);
      } else {
        if (!shard.empty()) certcyl::cli::parse_shard(shard, study_options.shard_index, study_options.shard_count);
        if (study_options.threads == 0) study_options.threads = std::max(1u, std::thread::hardware_concurrency());
        study_options.plots = !no_plots;
        study_options.size_given = study->count("--size") > 0;
        study_options.seed_given = study->count("--seed") > 0;
        study_options.name_given = study->count("--name") > 0;
        status = certcyl::cli::run_study(study_options, std::cout);
      }
    } catch (const std::exception& e) {
      std::cerr << "certcyl: " << e.what() << '\n';
      return 1;
    }
    // The summary on standard output is part of the result: losing it is an error.
    std::cout.flush();
    if (!std::cout) {
      std::cerr << "certcyl " << command << ": error writing standard output\n";
      return 1;
    }
    return status;
  }
  if (cases->parsed() || judge->parsed()) {
    for (unsigned* t : {&case_spec.threads, &judge_options.spec.threads})
      if (*t == 0) *t = std::max(1u, std::thread::hardware_concurrency());
    if (judge->parsed()) {
      try {
        if (!judge_shard.empty()) certcyl::cli::parse_shard(judge_shard, judge_options.shard_index, judge_options.shard_count);
      } catch (const std::exception& e) {
        std::cerr << "certcyl judge: " << e.what() << '\n';
        return 1;
      }
      return certcyl::cli::run_judge(judge_options, std::cout, std::cerr);
    }
    try {
      if (certcyl::cli::run_cases(case_spec, std::cout) == 0) return 0;
      std::cerr << "certcyl cases: error writing standard output\n";
    } catch (const std::exception& e) {
      std::cerr << "certcyl cases: " << e.what() << '\n';
    }
    return 1;
  }
  if (make_scene->parsed()) {
    try {
      // Streamed as generated: memory does not grow with --cylinders.
      certcyl::cli::write_scene(scene_spec, std::cout);
    } catch (const std::exception& e) {
      std::cerr << "certcyl: " << e.what() << '\n';
      return 1;
    }
    std::cout.flush();
    if (!std::cout) {
      std::cerr << "certcyl make-scene: error writing standard output\n";
      return 1;
    }
    return 0;
  }
  if (scene->parsed()) {
    certcyl::cli::install_gmp_memory("certcyl scene", "every line written is complete; the lines of the chunk in progress and after it are not written");
    certcyl::cli::install_interrupt_handlers();
    if (scene_threads == 0) scene_threads = std::max(1u, std::thread::hardware_concurrency());
    return certcyl::cli::run_scene(scene_file, std::cout, scene_threads, scene_progress || isatty(2), scene_stats, std::cerr);
  }
  return 0;
}
