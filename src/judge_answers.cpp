// An answers file: one {"id", "answer"} line per case, in any order, matched to the cases by id.
#include <map>
#include <stdexcept>

#include "judge_internal.hpp"
#include "query.hpp"

namespace certcyl::cli::judging {

Answers read_answers(std::istream& in, const std::string& label, const std::vector<Case>& cases) {
  std::map<std::string, std::size_t> index;  // id -> case
  for (std::size_t i = 0; i < cases.size(); ++i) index.emplace(cases[i].id, i);
  Answers result;
  result.answers.resize(cases.size());
  std::vector<std::size_t> answered_on(cases.size(), 0);  // the line that answered each case
  std::string text;
  for (std::size_t n = 1; std::getline(in, text); ++n) {
    if (text.find_first_not_of(" \t\r") == std::string::npos) continue;
    const std::string where = label + " line " + std::to_string(n) + ": ";
    nlohmann::json j;
    try {
      j = parse_strict_json(text);
    } catch (const nlohmann::json::exception& e) {
      throw std::runtime_error(where + "not JSON (" + e.what() + ")");
    } catch (const std::invalid_argument& e) {
      throw std::runtime_error(where + e.what());  // a member named twice, nesting too deep
    }
    if (!j.is_object()) throw std::runtime_error(where + "expected a JSON object");
    if (!j.contains("id") || !(j["id"].is_string() || j["id"].is_number_integer()))
      throw std::runtime_error(where + "id: expected the id of a case");
    const std::string id = j["id"].is_string() ? j["id"].get<std::string>() : j["id"].dump();
    const auto it = index.find(id);
    if (it == index.end()) throw std::runtime_error(where + "id '" + id + "' is not a case");
    if (answered_on[it->second] != 0)
      throw std::runtime_error(where + "id '" + id + "' answered twice (first on line " + std::to_string(answered_on[it->second]) + ")");
    answered_on[it->second] = n;
    try {
      result.answers[it->second] = answered_line(j);
    } catch (const std::invalid_argument& e) {
      throw std::runtime_error(where + e.what());
    }
  }
  if (in.bad()) throw std::runtime_error(label + ": read error");
  for (std::size_t i = 0; i < cases.size(); ++i)
    if (!result.answers[i])
      throw std::runtime_error(label + ": no answer for case '" + cases[i].id + "'" +
                               (cases[i].line ? " (cases line " + std::to_string(cases[i].line) + ")" : ""));
  return result;
}

}  // namespace certcyl::cli::judging
