// A C plugin (certcyl/plugin.h): loaded with dlopen in a child process, which answers the cases
// one by one and writes each answer to a pipe as it is given (case index, return value), so a
// crash in the plugin ends the run with every answer before it in hand, and the parent names
// the case it crashed on and the signal; a call that gives no answer within the timeout is
// named likewise, and the child killed.
#include "certcyl/plugin.h"

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <stdexcept>

#include <dlfcn.h>
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include "judge_internal.hpp"

namespace certcyl::cli::judging {
namespace {

using study::Query;

// The plugin symbol answering a study query, or nullptr (line_elliptic_cylinder has none).
const char* symbol_of(Query q) {
  switch (q) {
    case Query::line_cylinder: return "certcyl_plugin_line_cylinder";
    case Query::ray_cylinder: return "certcyl_plugin_ray_cylinder";
    case Query::segment_cylinder: return "certcyl_plugin_segment_cylinder";
    case Query::triangle_cylinder: return "certcyl_plugin_triangle_cylinder";
    case Query::cylinder_cylinder: return "certcyl_plugin_cylinder_cylinder";
    case Query::line_elliptic_cylinder: return nullptr;
  }
  return nullptr;
}

using LineFn = int (*)(const double*, const double*, const double*, double*);
using TriangleFn = int (*)(const double*, const double*);
using PairFn = int (*)(const double*, const double*);

// Calls the plugin's function for the case's query on its coordinates (study/instance.hpp).
int call(void* fn, const Case& c) {
  const double* x = c.x.data();
  double t[2] = {0, 0};
  switch (c.query) {
    case Query::line_cylinder:
    case Query::ray_cylinder:
    case Query::segment_cylinder: return reinterpret_cast<LineFn>(fn)(x, x + 3, x + 6, t);
    case Query::triangle_cylinder: return reinterpret_cast<TriangleFn>(fn)(x, x + 9);
    case Query::cylinder_cylinder: return reinterpret_cast<PairFn>(fn)(x, x + 7);
    case Query::line_elliptic_cylinder: break;
  }
  return -1;
}

// dlopen searches the library path for a bare name; a path with a slash is opened as it is.
std::string dlopen_path(const std::string& path) { return path.find('/') == std::string::npos ? "./" + path : path; }

void* open_plugin(const std::string& path) {
  void* handle = ::dlopen(dlopen_path(path).c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) throw std::runtime_error(std::string("--plugin: ") + ::dlerror());
  return handle;
}

struct Record {
  std::uint32_t index;
  std::int32_t value;
};

// The child: answers every case whose query the plugin exports, one record per answer.
[[noreturn]] void answer_in_child(const std::string& path, const std::vector<Case>& cases, int fd) {
  void* handle = ::dlopen(dlopen_path(path).c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) _exit(3);
  void* fns[study::kQueries.size()] = {};
  for (Query q : study::kQueries)
    if (const char* s = symbol_of(q)) fns[static_cast<std::size_t>(q)] = ::dlsym(handle, s);
  for (std::size_t i = 0; i < cases.size(); ++i) {
    void* fn = fns[static_cast<std::size_t>(cases[i].query)];
    if (!fn) continue;
    const Record r{static_cast<std::uint32_t>(i), call(fn, cases[i])};
    if (::write(fd, &r, sizeof r) != static_cast<ssize_t>(sizeof r)) _exit(4);
  }
  _exit(0);
}

std::string answer_of(int value) {
  switch (value) {
    case CERTCYL_SEPARATED: return "separated";
    case CERTCYL_TOUCHING: return "touching";
    case CERTCYL_OVERLAPPING: return "overlapping";
    case CERTCYL_INTERSECTING: return "intersecting";
    case CERTCYL_UNDECIDED: return "undecided";
    default: return value < 0 ? "error" : "";
  }
}

std::string line_of(const std::vector<Case>& cases, std::size_t i) { return "line " + std::to_string(cases[i].line); }

}  // namespace

PluginInfo inspect_plugin(const std::string& path) {
  void* handle = open_plugin(path);
  PluginInfo info;
  using NameFn = const char* (*)();
  if (void* name = ::dlsym(handle, "certcyl_plugin_name")) {
    const char* s = reinterpret_cast<NameFn>(name)();
    info.name = s ? s : "";
  }
  if (info.name.empty()) info.name = path;
  for (Query q : study::kQueries)
    if (const char* s = symbol_of(q); s && ::dlsym(handle, s)) info.queries.push_back(q);
  ::dlclose(handle);
  if (info.queries.empty())
    throw std::runtime_error("--plugin: " + path + " exports no query (certcyl_plugin_line_cylinder, ..._ray_cylinder, "
                             "..._segment_cylinder, ..._triangle_cylinder, ..._cylinder_cylinder)");
  return info;
}

Answers run_plugin(const std::string& path, const std::vector<Case>& cases, const Timeout& timeout) {
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) throw std::runtime_error(std::string("--plugin: pipe: ") + std::strerror(errno));
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error(std::string("--plugin: fork: ") + std::strerror(errno));
  if (pid == 0) {
    ::close(fds[0]);
    answer_in_child(path, cases, fds[1]);
  }
  ::close(fds[1]);
  Answers result;
  result.answers.resize(cases.size());
  std::size_t next = 0;  // the first case not yet answered
  Record r{};
  for (;;) {
    std::size_t got = 0;
    const Deadline deadline(timeout);
    bool hung = false;
    while (got < sizeof r) {
      if (!deadline.wait_readable(fds[0])) {
        hung = true;
        break;
      }
      const ssize_t n = ::read(fds[0], reinterpret_cast<char*>(&r) + got, sizeof r - got);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) break;
      got += static_cast<std::size_t>(n);
    }
    if (hung && next < cases.size()) {
      result.failure = "plugin hung on " + line_of(cases, next) + ", case '" + cases[next].id + "': " + symbol_of(cases[next].query) +
                       " gave no answer within " + timeout.text() + " (--timeout) and was killed";
      break;
    }
    if (got < sizeof r) break;
    if (r.index >= cases.size()) {
      result.failure = "the plugin's child wrote an answer to no case";
      break;
    }
    const std::string a = answer_of(r.value);
    if (a.empty()) {
      result.failure = "the plugin returned " + std::to_string(r.value) + " on " + line_of(cases, r.index) + ", case '" +
                       cases[r.index].id + "' (expected 0 to 4, or negative for an error)";
      break;
    }
    result.answers[r.index] = answered(a);
    next = r.index + 1;
  }
  if (!result.failure.empty()) ::kill(pid, SIGKILL);
  ::close(fds[0]);
  int status = 0;
  ::waitpid(pid, &status, 0);
  if (!result.failure.empty()) return result;
  if (next == cases.size() && WIFEXITED(status) && WEXITSTATUS(status) == 0) return result;
  const std::string at = next < cases.size() ? line_of(cases, next) : "the end";
  const std::string which = next < cases.size() ? ", case '" + cases[next].id + "'" : "";
  if (WIFSIGNALED(status)) {
    const int s = WTERMSIG(status);
    result.failure = "plugin crashed on " + at + " (signal " + std::to_string(s) + ", " + (sigdescr_np(s) ? sigdescr_np(s) : "?") + ")" + which;
  } else {
    result.failure = "the plugin's process exited with status " + std::to_string(WEXITSTATUS(status)) + " on " + at + which;
  }
  return result;
}

}  // namespace certcyl::cli::judging
