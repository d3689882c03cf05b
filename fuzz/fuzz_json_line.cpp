// Fuzz harness: the command's line handler (cli::answer_line) on arbitrary bytes. Whatever the
// line, it must return one JSON object with an "id" that is a string, a number or null, and
// exactly one of "answer" and "error"; an answered line echoes its input's id; an id is never
// invented (a line without the text "id" gets null; one that parses as an object without "id"
// too); and the output's text (as the command writes it) must parse back to its JSON.
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
  const cli::ojson& id = out["id"];
  if (!(id.is_null() || id.is_string() || id.is_number())) fuzz::wrong_answer("id is not a string, a number or null: " + out.dump());
  // An answered line echoes its input's id; no id is invented.
  nlohmann::json input = nlohmann::json::parse(line, nullptr, false);
  const bool object = !input.is_discarded() && input.is_object();
  const bool has_id = object && input.contains("id");
  if (has_id && out.contains("answer") && cli::ojson(input["id"]) != id) fuzz::wrong_answer("id not echoed");
  if (object && !has_id && !id.is_null()) fuzz::wrong_answer("id invented");
  if (line.find("\"id\"") == std::string::npos && !id.is_null()) fuzz::wrong_answer("id invented");
  // The written line is valid JSON (invalid UTF-8 in strings is replaced, as the command does).
  const std::string text = out.dump(-1, ' ', false, cli::ojson::error_handler_t::replace);
  if (text.find('\n') != std::string::npos) fuzz::wrong_answer("output spans several lines");
  const nlohmann::json back = nlohmann::json::parse(text, nullptr, false);
  if (back.is_discarded() || !back.is_object()) fuzz::wrong_answer("output does not parse back: " + text);
  return 0;
}
