// `certcyl query`: certified reference answers as JSON lines.
//
// Each input line is one JSON object {"id": ..., "query": Q, operands...}; each output line
// answers it, in the same order, echoing "id". A line that cannot be answered gets
// {"id": ..., "error": "<field>: <what>"} and processing goes on.
#pragma once

#include <nlohmann/json.hpp>

#include <functional>
#include <iosfwd>
#include <map>
#include <string>
#include <vector>

#include "certcyl/dispatch.hpp"

namespace certcyl::cli {

using json = nlohmann::json;           // input lines
using ojson = nlohmann::ordered_json;  // output lines keep their fields in a fixed order

struct QueryOptions {
  std::string method = "certified";
  NumberTypeSpec nt{NumberKind::double_, 53};
  bool nt_given = false;  // --nt was on the command line
};

// One query kind: the methods that answer it and how.
struct QueryKind {
  std::string name;
  std::vector<std::string> methods;  // the first is the default ("certified")
  std::function<ojson(const json& input, const QueryOptions& options)> answer;
};

// Every query kind the command knows, by name.
const std::map<std::string, QueryKind>& query_kinds();

// Every method name any query accepts (for --help and validation).
std::vector<std::string> all_methods();

// Answers one input line (already split off the stream); never throws.
ojson answer_line(const std::string& line, const QueryOptions& options);

// Runs the command on a stream. Returns 0 when every line was answered, 2 when some line had an
// error, 1 on an I/O failure.
int run_query(std::istream& in, std::ostream& out, const QueryOptions& options, unsigned threads);

// Registration of each query family (one source file each).
void register_point_queries(std::map<std::string, QueryKind>& kinds);
void register_line_queries(std::map<std::string, QueryKind>& kinds);
void register_triangle_queries(std::map<std::string, QueryKind>& kinds);
void register_cylinder_queries(std::map<std::string, QueryKind>& kinds);

}  // namespace certcyl::cli
