// A co-process: the program runs once (/bin/sh -c COMMAND, in a process group of its own); a
// writer thread feeds it the cases' query lines in batches while this thread reads its answers,
// one line per case in order, so neither side waits on a full pipe. A program that dies, writes
// a line that is not an answer to the case in turn, stops early or gives no answer within the
// timeout ends the run (its process group killed); the answers read until then are kept.
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstring>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <thread>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include "fd_io.hpp"
#include "judge_internal.hpp"
#include "query.hpp"

namespace certcyl::cli::judging {
namespace {

constexpr std::size_t kBatchLines = 256;

// The text of query_line(c).dump() without building the JSON: per query, the line's fixed text
// (member names, brackets, separators) is cut once around the id and the coordinates, from the
// line of a case whose coordinates are their indices; a line is then the pieces with the id and
// the coordinates written in between, each as dump() writes it (the shortest decimal that reads
// back to the same double, null for a value that is not finite). The first line of each query is
// checked against dump(); a query whose line does not match is written by dump().
class QueryLines {
 public:
  void append(std::string& out, const Case& c) {
    auto it = templates_.find(c.query);
    if (it == templates_.end()) it = templates_.emplace(c.query, make(c)).first;
    const Template& t = it->second;
    if (!t.valid) {
      out += query_line(c).dump();
      return;
    }
    out += t.text[0];
    for (std::size_t k = 0; k < t.slots.size(); ++k) {
      if (t.slots[k] == kId) {
        append_id(out, c.id);
      } else {
        append_double(out, c.x[t.slots[k]]);
      }
      out += t.text[k + 1];
    }
  }

 private:
  static constexpr std::size_t kId = std::numeric_limits<std::size_t>::max();
  struct Template {
    std::vector<std::string> text;   // text[k] comes before slots[k], the last after the last slot
    std::vector<std::size_t> slots;  // a coordinate's index, or kId
    bool valid = false;
  };

  static void append_double(std::string& out, double v) {
    if (!std::isfinite(v)) {
      out += "null";
      return;
    }
    char buf[64];
    const char* end = nlohmann::detail::to_chars(buf, buf + sizeof buf, v);
    out.append(buf, static_cast<std::size_t>(end - buf));
  }

  static void append_id(std::string& out, const std::string& id) {
    for (const char ch : id) {
      const auto u = static_cast<unsigned char>(ch);
      if (u < 0x20 || u >= 0x7f || ch == '"' || ch == '\\') {
        out += nlohmann::ordered_json(id).dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
        return;
      }
    }
    out += '"';
    out += id;
    out += '"';
  }

  static void walk(const nlohmann::ordered_json& j, Template& t, bool top) {
    if (j.is_object()) {
      t.text.back() += '{';
      bool first = true;
      for (const auto& [key, value] : j.items()) {
        if (!first) t.text.back() += ',';
        first = false;
        t.text.back() += nlohmann::ordered_json(key).dump() + ':';
        if (top && key == "id") {
          t.slots.push_back(kId);
          t.text.emplace_back();
        } else {
          walk(value, t, false);
        }
      }
      t.text.back() += '}';
    } else if (j.is_array()) {
      t.text.back() += '[';
      for (std::size_t i = 0; i < j.size(); ++i) {
        if (i > 0) t.text.back() += ',';
        walk(j[i], t, false);
      }
      t.text.back() += ']';
    } else if (j.is_number_float()) {
      t.slots.push_back(static_cast<std::size_t>(j.get<double>()));
      t.text.emplace_back();
    } else {
      t.text.back() += j.dump();
    }
  }

  static Template make(const Case& c) {
    Case shape = c;
    for (std::size_t i = 0; i < shape.x.size(); ++i) shape.x[i] = static_cast<double>(i);
    Template t;
    t.text.emplace_back();
    walk(query_line(shape), t, true);
    t.valid = t.slots.size() == c.x.size() + 1 &&
              std::all_of(t.slots.begin(), t.slots.end(), [&](std::size_t k) { return k == kId || k < c.x.size(); });
    if (t.valid) {
      std::string mine;
      Template check = t;
      check.valid = true;
      QueryLines one;
      one.templates_.emplace(c.query, check);
      one.append(mine, c);
      t.valid = mine == query_line(c).dump();
    }
    return t;
  }

  std::map<study::Query, Template> templates_;
};

std::string describe_status(int status) {
  if (WIFSIGNALED(status)) {
    const int s = WTERMSIG(status);
    return "was killed by signal " + std::to_string(s) + " (" + (sigdescr_np(s) ? sigdescr_np(s) : "?") + ")";
  }
  if (WIFEXITED(status)) return "exited with status " + std::to_string(WEXITSTATUS(status));
  return "ended";
}

std::string excerpt(const std::string& s) { return s.size() <= 120 ? s : s.substr(0, 120) + "..."; }

// The answer of a line of the commonest form, {"id":ID,"answer":"WORD"} (blanks allowed between
// the tokens), ID the case's id as a plain JSON string, read without the JSON parser; nullopt for
// any other line, which the parser reads. answered() judges the word as it does for the parser.
std::optional<Answered> quick_answer(const std::string& line, const std::string& id) {
  std::size_t p = 0;
  const auto blanks = [&] {
    while (p < line.size() && (line[p] == ' ' || line[p] == '\t' || line[p] == '\r')) ++p;
  };
  const auto token = [&](std::string_view t) {
    blanks();
    if (line.compare(p, t.size(), t) != 0) return false;
    p += t.size();
    return true;
  };
  for (const char ch : id) {
    const auto u = static_cast<unsigned char>(ch);
    if (u < 0x20 || u >= 0x7f || ch == '"' || ch == '\\') return std::nullopt;
  }
  if (!token("{") || !token("\"id\"") || !token(":") || !token("\"") || line.compare(p, id.size(), id) != 0) return std::nullopt;
  p += id.size();
  if (!token("\"") || !token(",") || !token("\"answer\"") || !token(":") || !token("\"")) return std::nullopt;
  const std::size_t start = p;
  while (p < line.size() && ((line[p] >= 'a' && line[p] <= 'z') || line[p] == '_')) ++p;
  const std::size_t end = p;
  if (!token("\"") || !token("}")) return std::nullopt;
  blanks();
  if (p != line.size()) return std::nullopt;
  return answered(line.substr(start, end - start));
}

enum class Read { line, end, timed_out };

// Reads lines from a file descriptor.
class LineReader {
 public:
  explicit LineReader(int fd) : fd_(fd) {}
  // The next line without its newline; `end` at the end of input (a last line without a newline
  // is returned first), `timed_out` when no line is complete by the deadline.
  Read next(std::string& line, const Deadline& deadline) {
    for (;;) {
      const auto nl = buffer_.find('\n', start_);
      if (nl != std::string::npos) {
        line.assign(buffer_, start_, nl - start_);
        start_ = nl + 1;
        return Read::line;
      }
      buffer_.erase(0, start_);
      start_ = 0;
      if (!deadline.wait_readable(fd_)) return Read::timed_out;
      char chunk[65536];
      const ssize_t n = ::read(fd_, chunk, sizeof chunk);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        if (buffer_.empty()) return Read::end;
        line = std::move(buffer_);
        buffer_.clear();
        return Read::line;
      }
      buffer_.append(chunk, static_cast<std::size_t>(n));
    }
  }

 private:
  int fd_;
  std::string buffer_;
  std::size_t start_ = 0;
};

// Whether the process has ended within the timeout (it is left to be reaped).
bool ended_within(pid_t pid, const Timeout& timeout) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout.seconds);
  for (;;) {
    siginfo_t info{};
    const int r = ::waitid(P_PID, static_cast<id_t>(pid), &info, WEXITED | WNOHANG | WNOWAIT);
    if (r == 0 && info.si_pid == pid) return true;
    if (r != 0 && errno != EINTR) return true;  // nothing to wait for
    if (timeout.seconds > 0 && std::chrono::steady_clock::now() >= end) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
}

}  // namespace

Answers run_exec(const std::string& command, const std::vector<Case>& cases, const Timeout& timeout) {
  int to_child[2], from_child[2];
  if (::pipe2(to_child, O_CLOEXEC) != 0) throw std::runtime_error(std::string("--exec: pipe: ") + std::strerror(errno));
  if (::pipe2(from_child, O_CLOEXEC) != 0) {
    ::close(to_child[0]), ::close(to_child[1]);
    throw std::runtime_error(std::string("--exec: pipe: ") + std::strerror(errno));
  }
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error(std::string("--exec: fork: ") + std::strerror(errno));
  if (pid == 0) {
    // A process group of its own: killing it ends the shell and whatever it started.
    ::setpgid(0, 0);
    ::dup2(to_child[0], 0);
    ::dup2(from_child[1], 1);
    ::signal(SIGPIPE, SIG_DFL);
    ::execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  ::setpgid(pid, pid);  // as the child does, whichever comes first
  ::close(to_child[0]);
  ::close(from_child[1]);

  std::thread writer([&, fd = to_child[1]] {
    // A program gone makes write() fail with EPIPE; the signal stays off this thread.
    sigset_t pipe_signal;
    sigemptyset(&pipe_signal);
    sigaddset(&pipe_signal, SIGPIPE);
    pthread_sigmask(SIG_BLOCK, &pipe_signal, nullptr);
    std::string batch;
    QueryLines lines;
    for (std::size_t i = 0; i < cases.size(); ++i) {
      lines.append(batch, cases[i]);
      batch += '\n';
      if ((i + 1) % kBatchLines == 0 || i + 1 == cases.size()) {
        if (!write_all(fd, batch.data(), batch.size())) break;
        batch.clear();
      }
    }
    ::close(fd);
  });

  Answers result;
  result.answers.resize(cases.size());
  LineReader reader(from_child[0]);
  std::string text;
  std::size_t n = 0;
  const auto answered_so_far = [&] { return "after answering " + std::to_string(n) + " of " + std::to_string(cases.size()) + " lines"; };
  for (; n < cases.size(); ++n) {
    const Read r = reader.next(text, Deadline(timeout));
    if (r == Read::end) break;
    if (r == Read::timed_out) {
      result.failure = "the program gave no answer to line " + std::to_string(n + 1) + " (case '" + cases[n].id + "') within " +
                       timeout.text() + " (--timeout) and was killed, " + answered_so_far();
      break;
    }
    try {
      if (auto quick = quick_answer(text, cases[n].id)) {
        result.answers[n] = std::move(*quick);
        continue;
      }
      const nlohmann::json j = parse_strict_json(text);
      if (!j.is_object() || !j.contains("id")) throw std::invalid_argument("expected a JSON object with \"id\"");
      if (j["id"] != cases[n].id) throw std::invalid_argument("id " + j["id"].dump() + " answers another case");
      result.answers[n] = answered_line(j);
    } catch (const std::exception& e) {
      result.failure = "line " + std::to_string(n + 1) + " of the program's output (case '" + cases[n].id + "'): " + e.what() + ": " +
                       excerpt(text);
      break;
    }
  }
  if (n == cases.size() && result.failure.empty() && n > 0) {
    result.ns_per_query = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start).count() / static_cast<double>(n);
    result.timing = "per query including the exchange (the program's start, writing the query lines, reading its answers), over all the cases";
  }
  bool silent = false;  // every line answered, but the output neither ended nor went on
  if (result.failure.empty() && n == cases.size()) {
    const Read r = reader.next(text, Deadline(timeout));
    if (r == Read::line) result.failure = "the program wrote more lines than it was given: " + excerpt(text);
    silent = r == Read::timed_out;
  }
  // A program that failed is killed at once; one that stopped answering or has answered every
  // line is given the timeout to end.
  const bool ended = result.failure.empty() && !silent && ended_within(pid, timeout);
  ::kill(-pid, SIGKILL);  // whatever is left of its process group
  ::close(from_child[0]);
  writer.join();
  int status = 0;
  ::waitpid(pid, &status, 0);
  if (result.failure.empty() && n < cases.size()) {
    // The program closed its output early: say how it ended.
    result.failure = "the program " +
                     (ended ? describe_status(status) : "stopped answering, did not end within " + timeout.text() + " (--timeout) and was killed") +
                     " " + answered_so_far() + " (no answer to line " + std::to_string(n + 1) + ", case '" + cases[n].id + "')";
  }
  return result;
}

}  // namespace certcyl::cli::judging
