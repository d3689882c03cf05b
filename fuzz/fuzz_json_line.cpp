// Fuzz harness: the command's line handler (cli::answer_line) on arbitrary bytes. Whatever the
// line, it must return one JSON object with the same "id" as the input (null when the input
// has none or is not an object) and exactly one of "answer" and "error", and its text (as the
// command writes it) must parse back to that object's JSON.
#include <nlohmann/json.hpp>

#include <string>

#include "fuzz_input.hpp"
#include "query.hpp"

using namespace certcyl;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string line(reinterpret_cast<const char*>(data), size);
  const cli::QueryOptions options;
  const cli::ojson out = cli::answer_line(line, options);
  if (!out.is_object()) fuzz::wrong_answer("output is not an object");
  if (out.contains("answer") == out.contains("error")) fuzz::wrong_answer("output has neither or both of answer and error: " + out.dump());
  if (!out.contains("id")) fuzz::wrong_answer("output has no id");
  // The id echoes the input's.
  nlohmann::json input = nlohmann::json::parse(line, nullptr, false);
  const bool has_id = !input.is_discarded() && input.is_object() && input.contains("id");
  if (has_id && cli::ojson(input["id"]) != out["id"]) fuzz::wrong_answer("id not echoed");
  if (!has_id && !out["id"].is_null()) fuzz::wrong_answer("id invented");
  // The written line is valid JSON (invalid UTF-8 in strings is replaced, as the command does).
  const std::string text = out.dump(-1, ' ', false, cli::ojson::error_handler_t::replace);
  if (text.find('\n') != std::string::npos) fuzz::wrong_answer("output spans several lines");
  const nlohmann::json back = nlohmann::json::parse(text, nullptr, false);
  if (back.is_discarded() || !back.is_object()) fuzz::wrong_answer("output does not parse back: " + text);
  return 0;
}
