// `certcyl query`: certified reference answers as JSON lines.
//
// Each input line is one JSON object {"id": ..., "query": Q, operands..., "meta": ...}; each
// output line answers it, in the same order, echoing "id" and "meta" (a line's own annotations,
// passed through untouched). A line that cannot be answered gets
// {"id": ..., "line": N, "error": "<field>: <what>"} (N its number in the input, from 1) and
// processing goes on.
//
// Input is strict: a member the query does not read, a member name twice in one object, an id
// that is not a string or a number, nesting deeper than kMaxNesting and lines longer than
// kMaxLineBytes are errors of that line. The id of a line that is not JSON is recovered from its
// text when it shows one.
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
  // --brief: each answer line holds only id, meta, answer, the interval of a line query as its
  // two (proved nearest, for the certified method) doubles, the gap and its gap_quantity, and
  // the reason of an invalid answer.
  bool brief = false;
  // --line-buffered: every line is answered and its answer written and flushed as soon as it is
  // read. Without it lines are answered in batches of up to 256 x threads, cut short whenever
  // no more input is at hand, so a co-process gets its answer either way; the option makes it
  // so whatever the input reports as available (and gives up batching across threads).
  bool line_buffered = false;
  // --time-limit: the certified cylinder-pair query's time limit per line in seconds
  // (CylinderCylinderOptions::time_limit_seconds); 0, the default, is none. A line that runs out
  // is answered undecided with a reason.
  double time_limit_seconds = 0;
  // --memory-limit: the most bytes of GMP (and MPFR) memory a line may hold (GmpMemoryScope,
  // counted once the command has installed GMP's memory functions); 0, the default, is none. A
  // line over it is an error line; the certified cylinder-pair query stops at its next check
  // (CylinderCylinderOptions::stop), the other queries when they end, so a line can hold more
  // than the limit before it stops.
  std::size_t memory_limit_bytes = 0;
};

// Limits on one input line.
inline constexpr std::size_t kMaxLineBytes = std::size_t{1} << 20;
inline constexpr int kMaxNesting = 16;

// One query kind: the methods that answer it and how.
struct QueryKind {
  std::string name;
  std::vector<std::string> methods;  // the first is the default ("certified")
  std::function<ojson(const json& input, const QueryOptions& options)> answer;
  std::vector<std::string> operands;  // the members every method reads
  std::map<std::string, std::vector<std::string>> method_members = {};  // members only some methods read
};

// Parses JSON strictly: a member name twice in one object (JSON leaves its meaning open; the
// last would silently win) and nesting deeper than kMaxNesting throw InvalidInput (empty field);
// syntax errors throw json::exception.
json parse_strict_json(const std::string& text);
json parse_strict_json(std::istream& in);

// The members a line of `kind` may have under `method`: id, query, meta and its operands.
std::vector<std::string> line_members(const QueryKind& kind, const std::string& method);

// Every query kind the command knows, by name.
const std::map<std::string, QueryKind>& query_kinds();

// Every method name any query accepts (for --help and validation).
std::vector<std::string> all_methods();

// Answers one input line (already split off the stream; line_number, from 1, is reported with an
// error, 0 for none); never throws.
ojson answer_line(const std::string& line, const QueryOptions& options, std::size_t line_number = 0);

// Runs the command on a stream (batches as QueryOptions::line_buffered says). Returns 0 when every line was answered, 2 when some line had an
// error, 1 on an I/O failure, 128 + the signal's number when SIGINT or SIGTERM ended the run
// (interrupt.hpp: every complete answered line is written first, never a partial one).
int run_query(std::istream& in, std::ostream& out, const QueryOptions& options, unsigned threads);

// Registration of each query family (one source file each).
void register_point_queries(std::map<std::string, QueryKind>& kinds);
void register_line_queries(std::map<std::string, QueryKind>& kinds);
void register_triangle_queries(std::map<std::string, QueryKind>& kinds);
void register_cylinder_queries(std::map<std::string, QueryKind>& kinds);

}  // namespace certcyl::cli
