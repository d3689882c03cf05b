// certcyl: certified cylinder intersection queries from the command line.
#include <CLI/CLI.hpp>

#include <iostream>
#include <thread>

#include <unistd.h>

#include "demo.hpp"
#include "query.hpp"
#include "scene.hpp"

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
      "error (that line is {\"id\":..., \"error\": \"<field>: <what>\"}), 1 fatal (I/O, usage).\n\n"
      "Queries and their methods:\n";
  for (const auto& [name, kind] : certcyl::cli::query_kinds()) s += "  " + name + ": " + join(kind.methods) + "\n";
  s += "\nNumbers: a JSON number is its binary64 value; a string is an exact rational\n"
       "(\"p/q\", decimal \"0.1\", hexfloat \"0x1.8p-3\"). See README.md for the operand formats.";
  return s;
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
          certcyl::parse_number_type(s);
          return std::string();
        } catch (const certcyl::InvalidInput& e) {
          return std::string(e.what());
        }
      });
  query->add_option("--threads", threads, "Worker threads (default 1; 0 = all cores)");

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
      "queries. A summary and timings go to standard error. Exit status: 0 done, 2 invalid scene, 1 I/O error.");
  scene->add_option("FILE", scene_file, "Scene JSON file")->required();
  scene->add_option("--threads", scene_threads, "Worker threads for the narrow phase (default 1; 0 = all cores)");
  scene->add_flag("--progress", scene_progress, "Report progress on standard error (default: when it is a terminal)");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 1;
  }

  if (demo->parsed()) return certcyl::cli::run_demo(std::cout);
  if (query->parsed()) {
    options.nt = certcyl::parse_number_type(nt_name);
    options.nt_given = query->count("--nt") > 0;
    if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
    std::ios::sync_with_stdio(false);
    return certcyl::cli::run_query(std::cin, std::cout, options, threads);
  }
  if (scene->parsed()) {
    if (scene_threads == 0) scene_threads = std::max(1u, std::thread::hardware_concurrency());
    return certcyl::cli::run_scene(scene_file, std::cout, scene_threads, scene_progress || isatty(2));
  }
  return 0;
}
