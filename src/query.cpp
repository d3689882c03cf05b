#include "query.hpp"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>
#include <thread>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include "certcyl/errors.hpp"
#include "fd_io.hpp"
#include "gmp_memory.hpp"
#include "interrupt.hpp"

namespace certcyl::cli {

const std::map<std::string, QueryKind>& query_kinds() {
  static const std::map<std::string, QueryKind> kinds = [] {
    std::map<std::string, QueryKind> k;
    register_point_queries(k);
    register_line_queries(k);
    register_triangle_queries(k);
    register_cylinder_queries(k);
    return k;
  }();
  return kinds;
}

std::vector<std::string> all_methods() {
  std::set<std::string> names;
  for (const auto& [name, kind] : query_kinds()) names.insert(kind.methods.begin(), kind.methods.end());
  return {names.begin(), names.end()};
}

namespace {

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

ojson error_line(const json& id, std::size_t line_number, const std::string& message) {
  ojson e{{"id", ojson(id)}};
  if (line_number > 0) e["line"] = line_number;
  e["error"] = message;
  return e;
}

// Rejects a member name twice in one object and nesting deeper than kMaxNesting while parsing.
auto strict_callback() {
  return [names = std::vector<std::vector<std::string>>()](int depth, json::parse_event_t event, json& parsed) mutable {
    switch (event) {
      case json::parse_event_t::object_start:
      case json::parse_event_t::array_start:
        if (depth >= kMaxNesting) throw InvalidInput("", "nested deeper than " + std::to_string(kMaxNesting) + " levels");
        if (event == json::parse_event_t::object_start) names.emplace_back();
        break;
      case json::parse_event_t::object_end: names.pop_back(); break;
      case json::parse_event_t::key: {
        auto& seen = names.back();
        const auto& key = parsed.get_ref<const std::string&>();
        if (std::find(seen.begin(), seen.end(), key) != seen.end())
          throw InvalidInput("", "member \"" + key + "\" appears twice in one object");
        seen.push_back(key);
        break;
      }
      default: break;
    }
    return true;
  };
}

// The id of a line that is not valid JSON, when its text still shows one at the top level:
// "id": followed by a number or a string. Null otherwise.
json recover_id(const std::string& line) {
  int depth = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (in_string) {
      if (c == '\\') ++i;
      else if (c == '"') in_string = false;
      continue;
    }
    if (c == '{' || c == '[') ++depth;
    else if (c == '}' || c == ']') --depth;
    else if (c == '"') {
      if (depth == 1 && line.compare(i, 4, "\"id\"") == 0) {
        std::size_t j = line.find_first_not_of(" \t", i + 4);
        if (j == std::string::npos || line[j] != ':') return nullptr;
        j = line.find_first_not_of(" \t", j + 1);
        if (j == std::string::npos) return nullptr;
        // The longest prefix of the rest that parses as a number or a string.
        std::size_t end = j;
        if (line[j] == '"') {
          for (end = j + 1; end < line.size() && line[end] != '"'; ++end)
            if (line[end] == '\\') ++end;
          ++end;
        } else {
          end = line.find_first_of(",}] \t", j);
        }
        const json id = json::parse(line.substr(j, end == std::string::npos ? std::string::npos : end - j), nullptr, false);
        return id.is_number() || id.is_string() ? id : json(nullptr);
      }
      in_string = true;
    }
  }
  return nullptr;
}

// The path of the first number in j that is not finite ("interval[0].approx"), or "".
std::string non_finite_member(const ojson& j, const std::string& path) {
  if (j.is_number_float()) return std::isfinite(j.get<double>()) ? std::string() : path;
  if (j.is_object()) {
    for (auto it = j.begin(); it != j.end(); ++it)
      if (auto p = non_finite_member(it.value(), path.empty() ? it.key() : path + "." + it.key()); !p.empty()) return p;
  } else if (j.is_array()) {
    for (std::size_t i = 0; i < j.size(); ++i)
      if (auto p = non_finite_member(j[i], path + "[" + std::to_string(i) + "]"); !p.empty()) return p;
  }
  return {};
}

// The --brief form of an answer line (QueryOptions::brief).
ojson brief_answer(const ojson& full) {
  ojson b{{"id", full["id"]}};
  if (full.contains("meta")) b["meta"] = full["meta"];
  b["answer"] = full["answer"];
  if (auto it = full.find("interval"); it != full.end()) {
    ojson t = ojson::array();
    for (const auto& end : *it) t.push_back(end.value("approx", ojson(nullptr)));
    b["interval"] = t;
  }
  if (auto it = full.find("gap"); it != full.end()) b["gap"] = *it;
  if (auto it = full.find("gap_quantity"); it != full.end()) b["gap_quantity"] = *it;
  if (auto it = full.find("reason"); it != full.end()) b["reason"] = *it;
  return b;
}

}  // namespace

json parse_strict_json(const std::string& text) { return json::parse(text, strict_callback()); }
json parse_strict_json(std::istream& in) { return json::parse(in, strict_callback()); }

namespace {

// The error of a line whose GMP memory scope had an event, or "".
std::string memory_error(const GmpMemoryScope& memory) {
  switch (memory.event()) {
    case GmpMemoryEvent::none: return {};
    case GmpMemoryEvent::over_limit:
      return "out of memory answering this line: its GMP memory went over the limit of " + std::to_string(memory.limit()) +
             " bytes (--memory-limit)";
    case GmpMemoryEvent::allocation_failed: return "out of memory answering this line: an allocation of GMP failed";
  }
  return {};
}

}  // namespace

ojson answer_line(const std::string& line, const QueryOptions& options, std::size_t line_number) {
  const GmpMemoryScope memory(options.memory_limit_bytes);
  if (line.size() > kMaxLineBytes)
    return error_line(nullptr, line_number, "line longer than the limit of " + std::to_string(kMaxLineBytes) + " bytes");
  json input;
  try {
    input = parse_strict_json(line);
  } catch (const json::exception& e) {
    // The parser's message names the column where the line stopped being JSON ("line 1" of
    // its input, which is this one line).
    std::string what = e.what();
    if (auto at = what.find("at line 1, "); at != std::string::npos) what.erase(at, std::string("at line 1, ").size()).insert(at, "at ");
    return error_line(recover_id(line), line_number, "malformed JSON: " + what);
  } catch (const InvalidInput& e) {
    return error_line(recover_id(line), line_number, std::string("malformed JSON: ") + e.what());
  }
  if (!input.is_object())
    return error_line(nullptr, line_number, "expected a JSON object per line, got " + std::string(input.type_name()));
  // The id is echoed only when it is a string or a number (null otherwise).
  const auto given_id = input.find("id");
  const json id = given_id != input.end() && (given_id->is_string() || given_id->is_number()) ? *given_id : json(nullptr);
  try {
    if (given_id != input.end() && !(given_id->is_null() || given_id->is_string() || given_id->is_number()))
      throw InvalidInput("id", "expected a string or a number, got " + std::string(given_id->type_name()));
    auto q = input.find("query");
    if (q == input.end()) throw InvalidInput("query", "missing");
    if (!q->is_string()) throw InvalidInput("query", "expected a string");
    const auto& kinds = query_kinds();
    auto kind = kinds.find(q->get<std::string>());
    if (kind == kinds.end()) {
      std::vector<std::string> names;
      for (const auto& [name, k] : kinds) names.push_back(name);
      throw InvalidInput("query", "unknown query '" + q->get<std::string>() + "' (expected one of: " + join(names) + ")");
    }
    const auto& methods = kind->second.methods;
    if (std::find(methods.begin(), methods.end(), options.method) == methods.end())
      throw InvalidInput("method", "'" + options.method + "' does not answer " + kind->first + " (methods: " + join(methods) + ")");
    // Every member must be one the query reads: a misspelt member is an error, not a default.
    const std::vector<std::string> members = line_members(kind->second, options.method);
    for (auto m = input.begin(); m != input.end(); ++m) {
      if (std::find(members.begin(), members.end(), m.key()) != members.end()) continue;
      if (m.key() == "method" || m.key() == "nt")
        throw InvalidInput(m.key(), "not a member of a line: the command's --" + m.key() + " option sets it for every line");
      throw InvalidInput(m.key(), "unknown member of a " + kind->first + " line with --method " + options.method +
                                      " (expected: " + join(members) + ")");
    }
    ojson result{{"id", ojson(id)}};
    if (auto meta = input.find("meta"); meta != input.end()) result["meta"] = ojson(*meta);
    const ojson answer = kind->second.answer(input, options);
    // Over --memory-limit, or an allocation failed (the answer, if any, may come from a stop).
    if (const std::string error = memory_error(memory); !error.empty()) return error_line(id, line_number, error);
    for (auto it = answer.begin(); it != answer.end(); ++it) result[it.key()] = it.value();
    // A floating-point method whose computation left the finite doubles (an overflow, a 0/0)
    // answers "invalid", naming the value: a failure the judgement counts, never a crash and
    // never a silent null.
    if (options.method != "certified") {
      if (const std::string where = non_finite_member(answer, ""); !where.empty()) {
        result["computed_answer"] = result["answer"];
        result["answer"] = "invalid";
        result["reason"] = "non-finite value in " + where;
      }
    }
    if (options.brief) return brief_answer(result);
    return result;
  } catch (const InvalidInput& e) {
    return error_line(id, line_number, e.what());
  } catch (const std::bad_alloc&) {
    return error_line(id, line_number, "out of memory answering this line");
  } catch (const std::exception& e) {
    return error_line(id, line_number, std::string("internal error: ") + e.what());
  }
}

std::vector<std::string> line_members(const QueryKind& kind, const std::string& method) {
  std::vector<std::string> m{"id", "query", "meta"};
  m.insert(m.end(), kind.operands.begin(), kind.operands.end());
  if (auto extra = kind.method_members.find(method); extra != kind.method_members.end())
    m.insert(m.end(), extra->second.begin(), extra->second.end());
  return m;
}

namespace {

// Reads one line (without its '\n') from sb, keeping at most limit + 1 bytes of it, so that a
// line without end cannot exhaust memory. False at the end of input.
bool read_line(std::streambuf& sb, std::string& line, std::size_t limit) {
  line.clear();
  using traits = std::streambuf::traits_type;
  int c = sb.sbumpc();
  if (traits::eq_int_type(c, traits::eof())) return false;
  for (; !traits::eq_int_type(c, traits::eof()) && c != '\n'; c = sb.sbumpc())
    if (line.size() <= limit) line.push_back(traits::to_char_type(c));
  return true;
}

// CORE::Expr ends the process on some inputs: std::exit(1) from its BigFloat division ("possible
// zero divisor"), SIGFPE from GMP on a non-finite double (experiments/STUDY.md). Lines answered in
// core_expr are therefore answered one at a time in a child process; the parent keeps every
// answer the child wrote, and a line whose computation ended the child is answered "invalid" with
// the reason, and the next child goes on from the line after it. The child works in a temporary
// folder, removed afterwards, so that CORE's Core_Diagnostics file never lands in the working
// directory, and its standard error is closed to CORE's messages (the reason carries them).
bool isolated(const QueryOptions& options) {
  return options.nt.kind == NumberKind::core_expr && options.method != "certified" && options.method != "robust_double";
}

// The answer to a line whose computation ended the process that answered it.
std::string ended_answer(const std::string& line, const QueryOptions& options, std::size_t line_number, const std::string& reason) {
  json input;
  try {
    input = parse_strict_json(line);
  } catch (const std::exception&) {
    return error_line(recover_id(line), line_number, "internal error: " + reason).dump();
  }
  const auto given_id = input.is_object() ? input.find("id") : input.end();
  const json id = input.is_object() && given_id != input.end() && (given_id->is_string() || given_id->is_number()) ? *given_id : json(nullptr);
  ojson result{{"id", ojson(id)}};
  if (input.is_object())
    if (auto meta = input.find("meta"); meta != input.end()) result["meta"] = ojson(*meta);
  result["answer"] = "invalid";
  result["certified"] = false;
  result["method"] = options.method;
  result["nt"] = options.nt.name();
  result["reason"] = reason;
  if (options.brief) result = brief_answer(result);
  return result.dump(-1, ' ', false, ojson::error_handler_t::replace);
}

// Why the child ended: CORE's last error in its diagnostics file, else the signal or status.
std::string ended_reason(int status, const std::filesystem::path& diagnostics) {
  std::ifstream in(diagnostics);
  std::string last;
  for (std::string l; std::getline(in, l);)
    if (l.rfind("CORE ERROR", 0) == 0) last = l;
  if (!last.empty()) {
    if (auto colon = last.find("): "); colon != std::string::npos) last.erase(0, colon + 3);
    return "CORE::Expr ended the computation: " + last;
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == kGmpOutOfMemoryStatus)
    return "the computation ran out of memory: GMP could not allocate (exit status " + std::to_string(kGmpOutOfMemoryStatus) + ")";
  if (WIFSIGNALED(status))
    return "the computation ended by signal " + std::to_string(WTERMSIG(status)) + " (" + strsignal(WTERMSIG(status)) + ")";
  return "the computation ended the process with exit status " + std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1);
}

// Answers lines[i...] in child processes as above; answers[i] is set for every line answered
// (all of them unless a signal interrupted the run). No other thread runs during the call.
void answer_isolated(const std::vector<std::string>& lines, const std::vector<std::size_t>& numbers, const QueryOptions& options,
                     std::vector<std::string>& answers, bool& batch_error) {
  namespace fs = std::filesystem;
  std::size_t i = 0;
  while (i < lines.size() && !interrupt_signal()) {
    std::error_code ec;
    std::string pattern = (fs::temp_directory_path(ec) / "certcyl-core-XXXXXX").string();
    const bool have_dir = !ec && mkdtemp(pattern.data()) != nullptr;
    const fs::path dir = have_dir ? fs::path(pattern) : fs::path();
    int fds[2];
    const pid_t pid = pipe(fds) == 0 ? fork() : -2;
    if (pid == -1) close(fds[0]), close(fds[1]);
    if (pid < 0) {
      if (have_dir) fs::remove_all(dir, ec);
      throw std::runtime_error(std::string("cannot start a process for core_expr: ") + std::strerror(errno));
    }
    if (pid == 0) {
      close(fds[0]);
      if (!have_dir || chdir(dir.c_str()) != 0) _exit(4);
      if (const int null_fd = open("/dev/null", O_WRONLY); null_fd >= 0) dup2(null_fd, 2);
      for (std::size_t j = i; j < lines.size() && !interrupt_signal(); ++j) {
        const ojson a = answer_line(lines[j], options, numbers[j]);
        std::string data(1, a.contains("error") ? 'E' : 'A');
        data.append(a.dump(-1, ' ', false, ojson::error_handler_t::replace)).push_back('\n');
        if (!write_all(fds[1], data.data(), data.size())) _exit(3);
      }
      _exit(0);
    }
    close(fds[1]);
    std::string pending;
    char buf[65536];
    bool forwarded = false;
    for (;;) {
      const ssize_t n = read(fds[0], buf, sizeof buf);
      if (n == 0) break;
      if (n < 0) {
        if (errno != EINTR) break;
        // An interruption: the child finishes its line and stops (it shares the handlers).
        if (interrupt_signal() && !forwarded) kill(pid, SIGTERM), forwarded = true;
        continue;
      }
      pending.append(buf, static_cast<std::size_t>(n));
      for (std::size_t end; (end = pending.find('\n')) != std::string::npos && i < lines.size();) {
        if (pending[0] == 'E') batch_error = true;
        answers[i++] = pending.substr(1, end - 1);
        pending.erase(0, end + 1);
      }
    }
    close(fds[0]);
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    const bool clean = WIFEXITED(status) && WEXITSTATUS(status) == 0;
    if (!clean && WIFEXITED(status) && WEXITSTATUS(status) == 4) {
      fs::remove_all(dir, ec);
      throw std::runtime_error("cannot make a temporary folder for core_expr's diagnostics");
    }
    if (!clean && i < lines.size() && !(forwarded && WIFSIGNALED(status)))
      answers[i] = ended_answer(lines[i], options, numbers[i], ended_reason(status, dir / "Core_Diagnostics")), ++i;
    fs::remove_all(dir, ec);
  }
}

}  // namespace

int run_query(std::istream& in, std::ostream& out, const QueryOptions& options, unsigned threads) {
  threads = std::max(1u, threads);
  // Lines are answered in batches; within a batch the threads take lines in any order, and
  // the batch is written in input order.
  const std::size_t batch_size = 256 * threads;
  std::vector<std::string> lines;
  std::vector<std::size_t> numbers;  // each line's number in the input, from 1
  std::vector<std::string> answers;
  std::size_t line_number = 0;
  bool any_error = false;
  bool eof = false;
  std::string fatal;  // a read error or a failure to isolate a line: written after the answers
  std::streambuf* sb = in.rdbuf();
  while (!eof) {
    lines.clear();
    numbers.clear();
    std::string line;
    {
      const InterruptibleRead reading;
      while (lines.size() < batch_size) {
        // No more input at hand, or --line-buffered: answer what was read now (a co-process
        // that writes a line and waits for its answer gets it; input from a file still fills
        // whole batches without the option).
        bool more = false;
        try {
          if (!lines.empty() && (options.line_buffered || sb->in_avail() <= 0)) break;
          more = read_line(*sb, line, kMaxLineBytes);
        } catch (const std::ios_base::failure& e) {
          // A read error (standard input is a directory, a device failed): the lines read
          // before it are answered and written, then the run ends with status 1.
          std::string reason = e.what();
          if (auto colon = reason.rfind(": "); colon != std::string::npos) reason.erase(0, colon + 2);
          fatal = "certcyl query: read error: standard input: " + reason;
        }
        if (!more) {
          eof = true;
          break;
        }
        ++line_number;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        // Blank lines carry no query and get no answer.
        if (line.find_first_not_of(" \t") == std::string::npos) continue;
        lines.push_back(line);
        numbers.push_back(line_number);
      }
    }
    answers.assign(lines.size(), std::string());
    std::atomic<std::size_t> next{0};
    std::atomic<bool> batch_error{false};
    auto work = [&] {
      // After an interruption no new line is started.
      for (std::size_t i = next++; i < lines.size() && !interrupt_signal(); i = next++) {
        const ojson a = answer_line(lines[i], options, numbers[i]);
        if (a.contains("error")) batch_error = true;
        answers[i] = a.dump(-1, ' ', false, ojson::error_handler_t::replace);
      }
    };
    if (isolated(options)) {
      bool isolated_error = false;
      try {
        answer_isolated(lines, numbers, options, answers, isolated_error);
      } catch (const std::exception& e) {
        fatal = std::string("certcyl query: ") + e.what();
      }
      if (isolated_error) batch_error = true;
    } else if (threads == 1 || lines.size() < 2) {
      work();
    } else {
      std::vector<std::thread> pool;
      for (unsigned t = 0; t < threads; ++t) pool.emplace_back(work);
      for (auto& t : pool) t.join();
    }
    any_error = any_error || batch_error;
    // Every complete answer up to the first line not answered, in input order.
    for (const auto& a : answers) {
      if (a.empty()) break;
      out << a << '\n';
    }
    out.flush();
    if (!out) {
      std::cerr << "certcyl query: error writing standard output\n";
      return 1;
    }
    if (!fatal.empty()) {
      std::cerr << fatal << '\n';
      return 1;
    }
    if (const int sig = interrupt_signal()) return 128 + sig;
  }
  return any_error ? 2 : 0;
}

}  // namespace certcyl::cli
