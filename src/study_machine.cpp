// machine.json: the compiler, flags, CPU, commit, libraries and options of a study run.
#include <cstdio>
#include <ctime>
#include <fstream>

#include <CGAL/version.h>

#include "study_internal.hpp"

#ifndef CERTCYL_SOURCE_DIR
#define CERTCYL_SOURCE_DIR "."
#endif
#ifndef CERTCYL_GIT_COMMIT
#define CERTCYL_GIT_COMMIT "unknown"
#endif
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

}  // namespace

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
                  {"hunt_evaluations", o.hunt_evaluations}, {"uniform_per_query", o.uniform_per_query}, {"shard", std::to_string(o.shard_index) + "/" + std::to_string(o.shard_count)},
                  {"methods", o.methods}, {"families", o.families}};
  const auto now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  char date[64];
  std::strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  j["date"] = date;
  return j;
}

}  // namespace certcyl::cli::detail
