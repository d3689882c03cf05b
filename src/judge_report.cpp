// The judged method's outcomes, exactly as the study's (outcome_of: judge against the certified
// answer, "uncertified" where the certified query was undecided), counted per query and family
// with a 95% Wilson interval of the failure rate (failures: the study's disagreements, false
// positives and false negatives, among the certified cases), the counterexamples, the answers
// as judged, and the summary table; the page (judge_html.cpp) is written from the same counts.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "cases.hpp"
#include "judge_internal.hpp"
#include "study/contract.hpp"
#include "study/gap_quantity.hpp"
#include "study_files.hpp"
#include "study_internal.hpp"

namespace certcyl::cli::judging {
namespace {

namespace fs = std::filesystem;

const char* const kOutcomes[] = {"agree",     "false_positive", "false_negative", "class_mismatch",
                                 "undecided", "error",          "invalid",        "uncertified"};

// The 95% Wilson score interval of a proportion of `failures` in `n` trials (n > 0).
std::pair<double, double> wilson(std::size_t failures, std::size_t n) {
  const double z = 1.959963984540054, p = static_cast<double>(failures) / static_cast<double>(n), nn = static_cast<double>(n);
  const double denom = 1 + z * z / nn;
  const double centre = (p + z * z / (2 * nn)) / denom;
  const double half = z / denom * std::sqrt(p * (1 - p) / nn + z * z / (4 * nn * nn));
  return {std::max(0.0, centre - half), std::min(1.0, centre + half)};
}

}  // namespace

std::string hunt_text(const std::string& line) {
  const std::vector<std::string> f = detail::split_csv(line);
  if (f.size() < 11) return line;
  std::string t = f[1] + ": ";
  if (f[4] != "1") return t + "no wrong answer found in " + f[3] + " inputs";
  const std::string_view gap = study::gap_label(study::gap_quantity(parse_study_query(f[1])));
  return t + f[5] + " where the certified answer is " + f[6] + " (" + f[7] + "), certified " + std::string(gap) + " [" + f[8] + ", " + f[9] +
         "], found from family " + f[2] + " in " + f[3] + " inputs";
}

std::string percent(double p) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f%%", 100 * p);
  return buf;
}

// The median (the mean of the middle two of an even count) and the largest of a non-empty list.
std::pair<double, double> median_and_max(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return {n % 2 ? v[n / 2] : 0.5 * v[n / 2 - 1] + 0.5 * v[n / 2], v.back()};
}

double gap_size(const Case& c) {
  if (!std::isfinite(c.gap_lo) || !std::isfinite(c.gap_hi)) return std::numeric_limits<double>::infinity();
  return std::fabs(0.5 * c.gap_lo + 0.5 * c.gap_hi);
}

Answered answered(const std::string& answer) {
  Answered a{answer, {}};
  if (answer == "intersecting") {
    a.output = study::boolean_answer(true);
  } else if (answer == "invalid") {
    a.output.invalid = true;
  } else if (answer == "error") {
    a.output.error = true;
  } else if (const auto x = answer_from_string(answer)) {
    a.output = study::three_valued(*x);
  } else {
    throw std::invalid_argument("answer: expected separated, touching, overlapping, intersecting, undecided, invalid or error, got '" +
                                answer + "'");
  }
  return a;
}

Answered answered_line(const nlohmann::json& j) {
  Answered a;
  if (j.contains("answer")) {
    if (!j["answer"].is_string()) throw std::invalid_argument("answer: expected a string");
    a = answered(j["answer"].get<std::string>());
  } else if (j.contains("error")) {
    return answered("error");
  } else {
    throw std::invalid_argument("answer: missing");
  }
  if (!j.contains("interval") || j["interval"].is_null() || (j["interval"].is_array() && j["interval"].empty())) return a;
  const nlohmann::json& v = j["interval"];
  const auto value = [](const nlohmann::json& x) -> std::optional<double> {
    if (x.is_null()) return std::numeric_limits<double>::quiet_NaN();
    if (x.is_number()) return x.get<double>();
    return std::nullopt;
  };
  std::optional<double> t[2];
  if (v.is_array() && v.size() == 2)
    for (std::size_t i = 0; i < 2; ++i) t[i] = v[i].is_object() ? (v[i].contains("approx") ? value(v[i]["approx"]) : std::nullopt) : value(v[i]);
  if (!t[0] || !t[1])
    throw std::invalid_argument("interval: expected [t_in, t_out] (numbers, or `certcyl query`'s endpoints with \"approx\"), got " +
                                v.dump().substr(0, 80));
  a.output.t_in = *t[0];
  a.t_out = *t[1];
  return a;
}

double t_error_of(const Answered& a, const Case& c) {
  const study::MethodOutput& m = a.output;
  if (!study::is_line_query(c.query) || m.intersecting || !intersects(m.answer) || !intersects(c.certified) || !std::isfinite(m.t_in) ||
      !std::isfinite(c.t_in))
    return std::numeric_limits<double>::quiet_NaN();
  return detail::t_error_ulps(m.t_in, c.t_in);
}

void write_results(const fs::path& dir, const fs::path& shown, const std::string& method, const std::vector<Case>& cases,
                   const Answers& answers, std::ostream& out, const MapsResult* maps,
                   const HuntResult* hunt, study::Contract contract) {
  fs::create_directories(dir);
  std::map<std::pair<std::string, std::string>, FamilyJudgement> by_family;  // (query, family)
  std::map<std::string, FamilyJudgement> by_query;
  std::vector<Counterexample> counterexamples;
  Judgement j;
  j.method = method;
  j.cases = cases.size();
  j.failure = answers.failure;
  j.maps = maps;
  j.hunt = hunt;
  j.ns_per_query = answers.ns_per_query;
  j.timing = answers.timing;
  j.contract = contract;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    if (!answers.answers[i]) continue;
    ++j.judged;
    const Case& c = cases[i];
    const study::Instance inst = certified_instance(c);
    const study::Contract under = contract_for(c, contract);
    const std::string outcome = detail::outcome_of(answers.answers[i]->output, inst, under);
    const std::string query(study::to_string(c.query));
    const double t_error = t_error_of(*answers.answers[i], c);
    for (FamilyJudgement* n : {&by_family[{query, c.family}], &by_query[query]}) {
      ++n->cases;
      ++n->outcomes[outcome];
      if (std::isfinite(t_error)) n->t_errors.push_back(t_error);
    }
    if (c.certified != Answer::undecided && study::disagrees(study::judge(answers.answers[i]->output, study::certified_under(inst, under))))
      counterexamples.push_back({&c, answers.answers[i]->answer, outcome});
  }
  auto judged_row = [](const std::string& query, const std::string& family, FamilyJudgement r) {
    r.query = query;
    r.family = family;
    r.certified = r.cases - r.at("uncertified");
    r.failures = r.at("false_positive") + r.at("false_negative");
    if (r.certified > 0) {
      r.rate = static_cast<double>(r.failures) / static_cast<double>(r.certified);
      std::tie(r.lo95, r.hi95) = wilson(r.failures, r.certified);
    } else {
      r.rate = r.lo95 = r.hi95 = std::numeric_limits<double>::quiet_NaN();
    }
    return r;
  };
  for (const auto& [key, n] : by_family) j.rows.push_back(judged_row(key.first, key.second, n));
  for (const auto& [query, n] : by_query) j.rows.push_back(judged_row(query, "all", n));

  // families.csv and the table, one row per query and family, then one per query (family "all").
  std::ofstream csv(dir / "families.csv");
  csv << "method,query,family,cases";
  for (const char* o : kOutcomes) csv << ',' << o;
  csv << ",failures,failure_rate,failure_rate_lo95,failure_rate_hi95,t_errors,t_error_median_ulps,t_error_max_ulps\n";
  std::ostringstream table;
  table << "certcyl judge: " << method << ", " << j.judged << " of " << cases.size() << " cases judged";
  if (contract != study::Contract::solid) table << ", rays and segments under the contract " << study::to_string(contract);
  table << '\n';
  char line[256];
  std::snprintf(line, sizeof line, "%-24s %-20s %6s %6s %6s %6s %6s %6s %6s %6s %6s  %s\n", "query", "family", "cases", "agree",
                "f.pos", "f.neg", "mism.", "undec.", "error", "inval.", "uncert", "failure rate [95% CI]");
  table << line;
  for (const FamilyJudgement& n : j.rows) {
    csv << detail::csv_field(method) << ',' << detail::csv_field(n.query) << ',' << detail::csv_field(n.family) << ',' << n.cases;
    for (const char* o : kOutcomes) csv << ',' << n.at(o);
    csv << ',' << n.failures;
    std::string rate = "-";
    if (n.certified > 0) {
      csv << ',' << detail::num(n.rate) << ',' << detail::num(n.lo95) << ',' << detail::num(n.hi95);
      rate = percent(n.rate) + " [" + percent(n.lo95) + ", " + percent(n.hi95) + "]";
    } else {
      csv << ",,,";
    }
    csv << ',' << n.t_errors.size();
    if (!n.t_errors.empty()) {
      const auto [median, max] = median_and_max(n.t_errors);
      csv << ',' << detail::num(median) << ',' << detail::num(max) << '\n';
    } else {
      csv << ",,\n";
    }
    std::snprintf(line, sizeof line, "%-24s %-20s %6zu %6zu %6zu %6zu %6zu %6zu %6zu %6zu %6zu  %s\n", n.query.c_str(), n.family.c_str(),
                  n.cases, n.at("agree"), n.at("false_positive"), n.at("false_negative"), n.at("class_mismatch"), n.at("undecided"),
                  n.at("error"), n.at("invalid"), n.at("uncertified"), rate.c_str());
    table << line;
  }
  table << "failures: false positives and false negatives among the certified cases (the study's disagreements)\n";
  for (const FamilyJudgement& n : j.rows) {
    if (n.t_errors.empty()) continue;
    const auto [median, max] = median_and_max(n.t_errors);
    std::snprintf(line, sizeof line, "entry parameter t, %s %s: %zu intervals, error median %.3g, max %.3g ulps\n", n.query.c_str(),
                  n.family.c_str(), n.t_errors.size(), median, max);
    table << line;
  }

  // counterexamples.jsonl: smallest |gap| first, one line per distinct input.
  std::stable_sort(counterexamples.begin(), counterexamples.end(),
                   [](const Counterexample& a, const Counterexample& b) { return gap_size(*a.c) < gap_size(*b.c); });
  std::ofstream cx(dir / "counterexamples.jsonl");
  std::set<std::string> seen;
  for (const Counterexample& e : counterexamples) {
    nlohmann::ordered_json input = query_line(*e.c);
    input.erase("id");
    if (!seen.insert(input.dump()).second) continue;
    nlohmann::ordered_json l = case_line(*e.c);
    l["meta"]["answer"] = e.answer;
    l["meta"]["outcome"] = e.outcome;
    l["meta"]["method"] = method;
    if (const study::Contract under = contract_for(*e.c, contract); under != study::Contract::solid) {
      l["meta"]["contract"] = std::string(study::to_string(under));
      l["meta"]["contract_answer"] = std::string(to_string(study::certified_under(certified_instance(*e.c), under)));
    }
    cx << l.dump() << '\n';
    j.counterexamples.push_back(e);
  }
  table << j.counterexamples.size() << " counterexamples (distinct inputs) in " << (shown / "counterexamples.jsonl").string() << '\n';
  if (!answers.failure.empty()) table << "not all cases judged: " << answers.failure << '\n';
  if (maps) {
    for (const MapJudgement& m : maps->maps)
      table << "failure map " << m.name << " (" << m.query << "): " << (m.false_positive + m.false_negative) << " wrong of " << m.evaluated
            << " cells evaluated (" << m.cells << " x " << m.cells << ", " << m.step << " ulp apart)\n";
    if (!maps->maps.empty()) table << "failure maps in " << (shown / "failure_maps").string() << '\n';
    if (!maps->note.empty()) table << "failure maps: " << maps->note << '\n';
    if (!maps->failure.empty()) table << "failure maps: " << maps->failure << '\n';
  }
  if (hunt) {
    for (const std::string& l : hunt->lines) table << "hunt: " << hunt_text(l) << '\n';
    if (!hunt->lines.empty()) table << "hunt: the worst inputs in " << (shown / "hunt.csv").string() << '\n';
    if (!hunt->failure.empty()) table << "hunt: ended early, " << hunt->failure << '\n';
  }

  // speed.csv: the method beside the study's methods on its speed-against-error figure, one row per
  // query in the columns of the study's summary.csv up to its timing (the disagreement rate among
  // the decided answers of the certified cases, as the study's), then mean_ns: the judged time is
  // a total over all the cases (a program's exchange cannot be split per query), so its mean,
  // the same on every row, where summary.csv has the median of per-instance times (and then
  // its three-valued rate, which speed.csv leaves out).
  if (std::isfinite(answers.ns_per_query)) {
    std::ofstream speed(dir / "speed.csv");
    speed << "query,method,kind,n,false_positive,false_negative,class_mismatch,undecided,error,invalid,disagreement_rate,mean_ns\n";
    for (const FamilyJudgement& r : j.rows) {
      if (r.family != "all") continue;
      const std::size_t decided = r.certified - r.at("undecided") - r.at("error") - r.at("invalid");
      const double rate = decided > 0 ? static_cast<double>(r.failures) / static_cast<double>(decided) : 0.0;
      speed << detail::csv_field(r.query) << ',' << detail::csv_field(method) << ",judged," << r.certified << ',' << r.at("false_positive") << ','
            << r.at("false_negative") << ',' << r.at("class_mismatch") << ',' << r.at("undecided") << ',' << r.at("error") << ','
            << r.at("invalid") << ',' << detail::num(rate) << ',' << detail::num(answers.ns_per_query) << '\n';
    }
    detail::close_written(speed, dir / "speed.csv");
    char ns[64];
    std::snprintf(ns, sizeof ns, "%.1f", answers.ns_per_query);
    table << "speed: " << ns << " ns per query, " << answers.timing << " (speed.csv)\n";
  }

  // answers.jsonl: the answers as judged, an answers file for the same cases (a shard's, merged).
  std::ofstream given(dir / "answers.jsonl");
  for (std::size_t i = 0; i < cases.size(); ++i)
    if (answers.answers[i]) {
      nlohmann::ordered_json l{{"id", cases[i].id}, {"answer", answers.answers[i]->answer}};
      const Answered& a = *answers.answers[i];
      if (std::isfinite(a.output.t_in) || std::isfinite(a.t_out)) {
        const auto number = [](double t) { return std::isfinite(t) ? nlohmann::ordered_json(t) : nlohmann::ordered_json(nullptr); };
        l["interval"] = nlohmann::ordered_json::array({number(a.output.t_in), number(a.t_out)});
      }
      given << l.dump() << '\n';
    }

  std::ofstream summary(dir / "summary.txt");
  summary << table.str();
  for (std::ofstream* f : {&csv, &cx, &given, &summary}) {
    f->flush();
    if (!*f) throw std::runtime_error("cannot write the results in " + dir.string());
  }
  write_report_page(dir / "index.html", j);
  out << table.str() << "report: " << (shown / "index.html").string() << '\n';
}

}  // namespace certcyl::cli::judging
