// machine.json: the compiler, flags, CPU, commit (of the build), libraries and options of a study
// run.
#include <cstdio>
#include <ctime>
#include <fstream>

#include <CGAL/version.h>

#include "certcyl_build_commit.hpp"  // generated at build time: CERTCYL_BUILD_COMMIT
#include "study_internal.hpp"

#ifndef CERTCYL_CXX_FLAGS
#define CERTCYL_CXX_FLAGS "unknown"
#endif

namespace certcyl::cli::detail {
using namespace certcyl::study;

namespace {

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown";
}

}  // namespace

nlohmann::ordered_json machine_json(const StudyOptions& o, const std::vector<std::string>& peers) {
  nlohmann::ordered_json j;
  j["compiler"] = std::string("g++ ") + __VERSION__;
  j["flags"] = CERTCYL_CXX_FLAGS;
  j["cpu"] = cpu_model();
  j["hardware_threads"] = std::thread::hardware_concurrency();
  // The commit the binary was built from ("+modified": tracked files differed from it), not
  // the source folder's state when the study runs.
  j["commit"] = CERTCYL_BUILD_COMMIT;
  j["cgal"] = CGAL_VERSION_STR;
  j["peers"] = peers;
  j["options"] = {{"name", o.name}, {"size", o.size}, {"seed", o.seed}, {"threads", o.threads},
                  {"per_family", o.per_family}, {"map_cells", o.map_cells}, {"map_step", o.map_step},
                  {"hunt_evaluations", o.hunt_evaluations}, {"uniform_per_query", o.uniform_per_query}, {"shard", std::to_string(o.shard_index) + "/" + std::to_string(o.shard_count)},
                  {"methods", o.methods}, {"families", o.families}};
  const auto now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  char date[64];
  std::strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  j["date"] = date;
  return j;
}

}  // namespace certcyl::cli::detail
