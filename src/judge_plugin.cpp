// A C plugin (certcyl/plugin.h): loaded with dlopen in a child process, which answers the cases
// one by one into memory shared with the parent (each return value, then the count of cases
// answered), with no system call per answer; so a crash in the plugin ends the run with every
// answer before it in hand, and the parent names the case it crashed on and the signal. The
// parent watches the count: a call that gives no answer within the timeout is named likewise,
// and the child killed.
#include "certcyl/plugin.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <limits>
#include <new>
#include <stdexcept>

#include <dlfcn.h>
#include <fcntl.h>
#include <sys/mman.h>
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

// Calls the plugin's function for the case's query on its coordinates (study/instance.hpp); a
// line query's interval goes into t (left NaN when the plugin does not write it).
int call(void* fn, const Case& c, double* t) {
  const double* x = c.x.data();
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

// What the child and the parent share (mmap, MAP_SHARED, so it outlives the child's crash): the
// count of cases answered, in order (the case at the count is the one being answered), then each
// case's return value, then each case's t[2] (NaN until the plugin writes it).
class Shared {
 public:
  explicit Shared(std::size_t cases)
      : cases_(std::max<std::size_t>(cases, 1)),
        intervals_(kValues + (sizeof(std::int32_t) * cases_ + 15) / 16 * 16),
        bytes_(intervals_ + 2 * sizeof(double) * cases_) {
    void* p = ::mmap(nullptr, bytes_, PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
    if (p == MAP_FAILED) throw std::runtime_error(std::string("--plugin: mmap: ") + std::strerror(errno));
    base_ = static_cast<char*>(p);
    new (base_) std::atomic<std::uint64_t>(0);
    new (base_ + 8) std::atomic<std::uint64_t>(0);
    std::fill_n(intervals(), 2 * cases_, std::numeric_limits<double>::quiet_NaN());
  }
  ~Shared() { ::munmap(base_, bytes_); }
  Shared(const Shared&) = delete;
  Shared& operator=(const Shared&) = delete;
  std::atomic<std::uint64_t>& answered() const { return *std::launder(reinterpret_cast<std::atomic<std::uint64_t>*>(base_)); }
  // The nanoseconds the child spent in the calls, written when it has answered every case.
  std::atomic<std::uint64_t>& call_ns() const { return *std::launder(reinterpret_cast<std::atomic<std::uint64_t>*>(base_ + 8)); }
  std::int32_t* values() const { return reinterpret_cast<std::int32_t*>(base_ + kValues); }
  // Case i's t[2] at intervals() + 2 i.
  double* intervals() const { return reinterpret_cast<double*>(base_ + intervals_); }

 private:
  static_assert(std::atomic<std::uint64_t>::is_always_lock_free, "the count is shared between processes");
  static constexpr std::size_t kValues = 64;  // the count's cache line, then the values
  std::size_t cases_, intervals_, bytes_;
  char* base_;
};

// The child: answers every case into `shared`; it holds a pipe's write end open until it ends, so
// the parent sees its end on the pipe.
[[noreturn]] void answer_in_child(const std::string& path, const std::vector<Case>& cases, const Shared& shared) {
  void* handle = ::dlopen(dlopen_path(path).c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) _exit(3);
  void* fns[study::kQueries.size()] = {};
  for (Query q : study::kQueries)
    if (const char* s = symbol_of(q)) fns[static_cast<std::size_t>(q)] = ::dlsym(handle, s);
  const auto start = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < cases.size(); ++i) {
    void* fn = fns[static_cast<std::size_t>(cases[i].query)];
    if (!fn) _exit(5);  // run_plugin's caller checked that the plugin exports every case's query
    shared.values()[i] = call(fn, cases[i], shared.intervals() + 2 * i);
    shared.answered().store(i + 1, std::memory_order_release);
  }
  const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - start).count();
  shared.call_ns().store(static_cast<std::uint64_t>(std::max<long long>(ns, 1)), std::memory_order_release);
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
  // The optional contract (certcyl/plugin.h), copied before the library is closed.
  std::optional<std::string> contract;
  if (void* fn = ::dlsym(handle, "certcyl_plugin_contract")) {
    const char* s = reinterpret_cast<NameFn>(fn)();
    contract = s ? s : "(null)";
  }
  for (Query q : study::kQueries)
    if (const char* s = symbol_of(q); s && ::dlsym(handle, s)) info.queries.push_back(q);
  ::dlclose(handle);
  if (contract) info.contract = parse_contract(*contract, "--plugin: " + path + ": certcyl_plugin_contract()");
  if (info.queries.empty())
    throw std::runtime_error("--plugin: " + path + " exports no query (certcyl_plugin_line_cylinder, ..._ray_cylinder, "
                             "..._segment_cylinder, ..._triangle_cylinder, ..._cylinder_cylinder)");
  return info;
}

Answers run_plugin(const std::string& path, const std::vector<Case>& cases, const Timeout& timeout) {
  const Shared shared(cases.size());
  int fds[2];  // the child holds the write end: its end closes the pipe
  if (::pipe2(fds, O_CLOEXEC) != 0) throw std::runtime_error(std::string("--plugin: pipe: ") + std::strerror(errno));
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error(std::string("--plugin: fork: ") + std::strerror(errno));
  if (pid == 0) {
    ::close(fds[0]);
    answer_in_child(path, cases, shared);
  }
  ::close(fds[1]);
  Answers result;
  result.answers.resize(cases.size());
  std::size_t next = 0;  // the first case not yet taken from the shared memory
  // Takes the answers given so far; false (and the failure set) on a value no answer.
  const auto take = [&] {
    const std::size_t upto = std::min<std::size_t>(shared.answered().load(std::memory_order_acquire), cases.size());
    for (; next < upto; ++next) {
      const int value = shared.values()[next];
      const std::string a = answer_of(value);
      if (a.empty()) {
        result.failure = "the plugin returned " + std::to_string(value) + " on " + line_of(cases, next) + ", case '" + cases[next].id +
                         "' (expected 0 to 4, or negative for an error)";
        return false;
      }
      result.answers[next] = answered(a);
      if (study::is_line_query(cases[next].query) && value != CERTCYL_SEPARATED) {
        result.answers[next]->output.t_in = shared.intervals()[2 * next];
        result.answers[next]->t_out = shared.intervals()[2 * next + 1];
      }
    }
    return true;
  };
  // Waits for the child's end, looking at its progress every 20 ms: a call that gives no answer
  // within the timeout is a hang.
  const auto poll_ms = 20;
  auto last_progress = std::chrono::steady_clock::now();
  for (;;) {
    pollfd p{fds[0], POLLIN, 0};
    const int ready = ::poll(&p, 1, poll_ms);
    const std::size_t before = next;
    if (!take()) break;
    if (ready > 0) {
      char c;
      const ssize_t n = ::read(fds[0], &c, 1);
      if (n == 0 || (n < 0 && errno != EINTR)) break;  // the child ended
    }
    const auto now = std::chrono::steady_clock::now();
    if (next != before) last_progress = now;
    if (timeout.seconds > 0 && next < cases.size() && std::chrono::duration<double>(now - last_progress).count() > timeout.seconds) {
      result.failure = "plugin hung on " + line_of(cases, next) + ", case '" + cases[next].id + "': " + symbol_of(cases[next].query) +
                       " gave no answer within " + timeout.text() + " (--timeout) and was killed";
      break;
    }
  }
  if (!result.failure.empty()) ::kill(pid, SIGKILL);
  ::close(fds[0]);
  int status = 0;
  ::waitpid(pid, &status, 0);
  if (!result.failure.empty()) return result;
  if (!take()) return result;  // the answers given after the last look
  if (next == cases.size() && WIFEXITED(status) && WEXITSTATUS(status) == 0) {
    if (const std::uint64_t ns = shared.call_ns().load(std::memory_order_acquire); ns > 0 && !cases.empty()) {
      result.ns_per_query = static_cast<double>(ns) / static_cast<double>(cases.size());
      result.timing = "per call in the plugin's child process (the calls' total time over the cases)";
    }
    return result;
  }
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
