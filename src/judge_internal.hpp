// What the parts of `certcyl judge` share (judge*.cpp): a judged method's answer to one case,
// the three sources of answers and the results folder. Internal to the command:
//   judge.cpp          the command: the cases, the source of answers, the results
//   judge_answers.cpp  an answers file ({"id", "answer"} lines)
//   judge_exec.cpp     a co-process answering `certcyl query` lines
//   judge_plugin.cpp   a C plugin (certcyl/plugin.h) run in a child process
//   judge_report.cpp   the outcomes, the results folder and the summary table
#pragma once

#include <nlohmann/json.hpp>

#include <filesystem>
#include <istream>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "cases.hpp"
#include "certcyl/study/methods.hpp"

namespace certcyl::cli::judging {

// The judged method's answer to one case: as it said it, and as the study reads it.
struct Answered {
  std::string answer;  // separated, touching, overlapping, intersecting, undecided, invalid, error
  study::MethodOutput output;
};

// answers[i] answers cases[i]; the cases after a failure have none. `failure` says what went
// wrong (empty when every case was answered).
struct Answers {
  std::vector<std::optional<Answered>> answers;
  std::string failure;
};

// The study's reading of an answer: separated, touching, overlapping (three-valued),
// intersecting (a boolean "they meet"), undecided; invalid (the method's computation left the
// finite doubles) and error (the method failed on the input) are the study's `error`. Throws
// std::invalid_argument on any other word.
Answered answered(const std::string& answer);

// The answer of one answer line (an object): its "answer", or the study's reading of a
// `certcyl query` line: an error line {"id", "error"} is the method's error, and "invalid" with
// a "computed_answer" (a floating method whose interval left the finite doubles) is judged by
// the computed answer, as the study judges the answer and not the interval. Throws
// std::invalid_argument as answered() does, and when there is no answer.
Answered answered_line(const nlohmann::json& line);

// An answers file: one {"id", "answer"} line per case, any order, other members ignored (so the
// output of `certcyl query` is an answers file; its error lines {"id", "error"} are errors of
// the method). Throws std::runtime_error naming `label` and the line: not JSON, no id, an id
// that is no case, an id twice, an unknown answer, a case without an answer.
Answers read_answers(std::istream& in, const std::string& label, const std::vector<Case>& cases);

// Starts `command` with /bin/sh -c, writes query_line() of every case to its standard input and
// reads one line back per case: {"id", "answer"} (or a `certcyl query` error line) with the
// case's id.
Answers run_exec(const std::string& command, const std::vector<Case>& cases);

// A plugin's name and the study queries it exports (certcyl_plugin_<query>); throws
// std::runtime_error when it cannot be loaded or exports none.
struct PluginInfo {
  std::string name;
  std::vector<study::Query> queries;
};
PluginInfo inspect_plugin(const std::string& path);
// Runs the plugin on the cases in a child process; every case's query must be one it exports.
Answers run_plugin(const std::string& path, const std::vector<Case>& cases);

// Writes dir/families.csv, dir/counterexamples.jsonl and dir/summary.txt for the answered
// cases and prints the summary table on `out`.
void write_results(const std::filesystem::path& dir, const std::string& method, const std::vector<Case>& cases,
                   const Answers& answers, std::ostream& out);

}  // namespace certcyl::cli::judging
