#include "query.hpp"

#include <algorithm>
#include <atomic>
#include <iostream>
#include <set>
#include <thread>

#include "certcyl/errors.hpp"

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

ojson error_line(const json& id, const std::string& message) { return ojson{{"id", ojson(id)}, {"error", message}}; }

}  // namespace

ojson answer_line(const std::string& line, const QueryOptions& options) {
  json input;
  try {
    input = json::parse(line);
  } catch (const json::exception& e) {
    // The parser's message names the byte where the line stopped being JSON.
    return error_line(nullptr, std::string("malformed JSON: ") + e.what());
  }
  if (!input.is_object()) return error_line(nullptr, "expected a JSON object per line, got " + std::string(input.type_name()));
  const json id = input.contains("id") ? input["id"] : json(nullptr);
  try {
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
    ojson result{{"id", ojson(id)}};
    const ojson answer = kind->second.answer(input, options);
    for (auto it = answer.begin(); it != answer.end(); ++it) result[it.key()] = it.value();
    return result;
  } catch (const InvalidInput& e) {
    return error_line(id, e.what());
  } catch (const std::exception& e) {
    return error_line(id, std::string("internal error: ") + e.what());
  }
}

int run_query(std::istream& in, std::ostream& out, const QueryOptions& options, unsigned threads) {
  threads = std::max(1u, threads);
  // Lines are answered in batches; within a batch the threads take lines in any order, and
  // the batch is written in input order.
  const std::size_t batch_size = 256 * threads;
  std::vector<std::string> lines;
  std::vector<std::string> answers;
  bool any_error = false;
  bool eof = false;
  while (!eof) {
    lines.clear();
    std::string line;
    while (lines.size() < batch_size) {
      if (!std::getline(in, line)) {
        eof = true;
        break;
      }
      if (!line.empty() && line.back() == '\r') line.pop_back();
      // Blank lines carry no query and get no answer.
      if (line.find_first_not_of(" \t") == std::string::npos) continue;
      lines.push_back(line);
    }
    if (in.bad()) {
      std::cerr << "certcyl query: error reading standard input\n";
      return 1;
    }
    answers.assign(lines.size(), std::string());
    std::atomic<std::size_t> next{0};
    std::atomic<bool> batch_error{false};
    auto work = [&] {
      for (std::size_t i = next++; i < lines.size(); i = next++) {
        const ojson a = answer_line(lines[i], options);
        if (a.contains("error")) batch_error = true;
        answers[i] = a.dump(-1, ' ', false, ojson::error_handler_t::replace);
      }
    };
    if (threads == 1 || lines.size() < 2) {
      work();
    } else {
      std::vector<std::thread> pool;
      for (unsigned t = 0; t < threads; ++t) pool.emplace_back(work);
      for (auto& t : pool) t.join();
    }
    any_error = any_error || batch_error;
    for (const auto& a : answers) out << a << '\n';
    out.flush();
    if (!out) {
      std::cerr << "certcyl query: error writing standard output\n";
      return 1;
    }
  }
  return any_error ? 2 : 0;
}

}  // namespace certcyl::cli
