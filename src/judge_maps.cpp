// The failure maps of a judged method: the study's grids around each degeneracy (study_maps.cpp:
// map_grids), every cell certified as the study certifies it and answered by the judged method
// through the same exchange as the families (a plugin's child process, a program's lines), and
// written as the study writes its maps (failure_maps/<name>.csv and .json, one method column).
//
// A plugin that crashes or a program that fails on a cell does not lose the map: the cells
// answered before are kept, the cell it failed on is recorded as an error ('e', as the study's
// hunt records a method that ended its process), and the exchange starts again after it, at
// most kRestarts times; the cells left after the last failure are not evaluated ('.').
#include <algorithm>
#include <fstream>
#include <set>
#include <stdexcept>

#include "judge_internal.hpp"
#include "study/contract.hpp"
#include "study/gap.hpp"
#include "study_files.hpp"
#include "study_internal.hpp"

namespace certcyl::cli::judging {
namespace {

namespace fs = std::filesystem;

constexpr int kRestarts = 3;

}  // namespace

int map_cells_of_size(const std::string& size) {
  if (size == "tiny") return 16;
  if (size == "default") return 64;
  if (size == "large") return 128;
  return 32;  // small, or a number of cases per family
}

std::vector<Case> map_cell_cases(const std::vector<study::Query>& queries, int cells, long step, std::uint64_t seed, unsigned threads,
                                 std::vector<detail::MapGrid>* grids_out, std::vector<std::string>* lines_out) {
  std::vector<detail::MapGrid> grids;
  for (detail::MapGrid& g : detail::map_grids(seed, cells, step))
    if (std::find(queries.begin(), queries.end(), g.query) != queries.end()) grids.push_back(std::move(g));
  const std::size_t per_map = static_cast<std::size_t>(cells) * static_cast<std::size_t>(cells);
  std::vector<Case> all(grids.size() * per_map);
  std::vector<std::string> lines(all.size());
  detail::parallel_for(all.size(), threads, [&](std::size_t n) {
    const detail::MapGrid& g = grids[n / per_map];
    const std::size_t cell = n % per_map;
    study::Instance inst;
    inst.query = g.query;
    inst.x = g.input(cell);
    study::certify(inst);
    Case& c = all[n];
    c.id = "failure_map/" + g.name + "/" + std::to_string(cell / static_cast<std::size_t>(cells)) + "/" +
           std::to_string(cell % static_cast<std::size_t>(cells));
    c.query = g.query;
    c.family = "failure_map/" + g.name;
    take_certified(c, inst);
    c.x = std::move(inst.x);
    c.line = n + 1;
    c.map = MapCell{cells, step, seed};
    lines[n] = g.certified_line(cell, inst);
  });
  if (grids_out) *grids_out = std::move(grids);
  if (lines_out) *lines_out = std::move(lines);
  return all;
}

MapsResult judge_failure_maps(const fs::path& dir, const std::string& method, const std::vector<study::Query>& queries,
                              const AnswerSource& source, int cells, long step, std::uint64_t seed, unsigned threads,
                              study::Contract contract) {
  MapsResult result;
  std::vector<detail::MapGrid> grids;
  std::vector<std::string> lines;
  // Every cell of every map, certified, as a case of the exchange.
  const std::vector<Case> all = map_cell_cases(queries, cells, step, seed, threads, &grids, &lines);
  if (grids.empty()) {
    result.note = "no failure map is drawn for the judged queries";
    return result;
  }
  const std::size_t per_map = static_cast<std::size_t>(cells) * static_cast<std::size_t>(cells);

  // The method's answers, resumed after a failure.
  std::vector<char> codes(all.size(), '.');
  std::vector<std::optional<Answered>> answers(all.size());
  std::size_t start = 0;
  for (int failures = 0; start < all.size();) {
    const std::vector<Case> rest(all.begin() + static_cast<std::ptrdiff_t>(start), all.end());
    const Answers got = source(rest);
    std::size_t k = 0;
    for (; k < rest.size() && got.answers[k]; ++k) answers[start + k] = got.answers[k];
    // Answers after a gap are kept too (an answers source may leave holes).
    for (std::size_t r = k; r < rest.size(); ++r)
      if (got.answers[r]) answers[start + r] = got.answers[r];
    if (got.failure.empty()) break;
    if (!result.failure.empty()) result.failure += "; ";
    result.failure += got.failure;
    if (start + k < all.size()) {
      answers[start + k] = answered("error");
      ++result.failed_cells;
    }
    start += k + 1;
    if (++failures > kRestarts) {
      result.failure += "; the cells after it were not evaluated";
      break;
    }
  }

  const fs::path maps = dir / "failure_maps";
  fs::create_directories(maps);
  std::ofstream summary(dir / "failure_maps.csv");
  summary << "map,query,cells,evaluated,certified,false_positive,false_negative,wrong\n";
  for (std::size_t m = 0; m < grids.size(); ++m) {
    const detail::MapGrid& g = grids[m];
    MapJudgement mj;
    mj.name = g.name;
    mj.query = std::string(study::to_string(g.query));
    mj.description = g.description;
    mj.cells = g.cells;
    mj.step = g.step;
    std::vector<std::string> column(per_map);
    std::vector<std::string> map_lines(lines.begin() + static_cast<std::ptrdiff_t>(m * per_map),
                                       lines.begin() + static_cast<std::ptrdiff_t>((m + 1) * per_map));
    for (std::size_t cell = 0; cell < per_map; ++cell) {
      const Case& c = all[m * per_map + cell];
      const auto& a = answers[m * per_map + cell];
      // The map shows the solid answer; a cell is judged under the contract.
      const char certified = detail::answer_code(study::three_valued(c.certified));
      mj.certified += certified;
      char code = '.';
      bool wrong = false;
      if (a) {
        code = detail::answer_code(a->output);
        ++mj.evaluated;
        if (c.certified != Answer::undecided) {
          ++mj.decided;
          const study::Outcome o = study::judge(a->output, study::certified_under(certified_instance(c), contract_for(c, contract)));
          mj.false_positive += o == study::Outcome::false_positive;
          mj.false_negative += o == study::Outcome::false_negative;
          wrong = study::disagrees(o);
        }
      }
      codes[m * per_map + cell] = code;
      mj.codes += code;
      mj.wrong.push_back(wrong);
      column[cell] = std::string(1, code);
    }
    detail::write_failure_map(maps, g, map_lines, {method}, column, nlohmann::ordered_json::object());
    summary << g.name << ',' << mj.query << ',' << per_map << ',' << mj.evaluated << ',' << mj.decided << ',' << mj.false_positive << ','
            << mj.false_negative << ',' << (mj.false_positive + mj.false_negative) << '\n';
    result.maps.push_back(std::move(mj));
  }
  detail::close_written(summary, dir / "failure_maps.csv");
  return result;
}

}  // namespace certcyl::cli::judging

namespace certcyl::cli::judging {

long hunt_evaluations_of_size(const std::string& size) {
  if (size == "tiny") return 20;
  if (size == "default") return 1000;
  if (size == "large") return 5000;
  return 150;  // small, or a number of cases per family
}

HuntResult judge_hunt(const fs::path& dir, const std::string& method, const std::vector<study::Query>& queries, const AnswerSource& source,
                      long evaluations, std::uint64_t seed, study::Contract contract) {
  HuntResult result;
  std::size_t calls = 0;
  for (const study::Query q : queries) {
    if (!result.failure.empty()) break;
    const long budget = q == study::Query::cylinder_cylinder ? std::max(1L, evaluations / 4) : evaluations;
    // One exchange per input: the search is sequential. After a failure of the exchange the
    // method's answer is an error (the study's process_ended), and the hunt stops there.
    const auto run = [&](const std::vector<double>& x) {
      study::MethodOutput out;
      if (!result.failure.empty()) {
        out.error = true;
        return out;
      }
      Case c;
      c.id = "hunt/" + std::string(study::to_string(q)) + "/" + std::to_string(++calls);
      c.query = q;
      c.family = "hunt";
      c.x = x;
      c.line = calls;
      const Answers a = source({c});
      if (!a.failure.empty() || a.answers.empty() || !a.answers[0]) {
        result.failure = a.failure.empty() ? "no answer" : a.failure;
        out.error = true;
        return out;
      }
      return a.answers[0]->output;
    };
    result.lines.push_back(detail::hunt_worst(method, q, seed, budget, run, {}, has_ray_contracts(q) ? contract : study::Contract::solid));
  }
  std::ofstream csv(dir / "hunt.csv");
  csv << detail::kHuntHeader << '\n';
  for (const std::string& l : result.lines) csv << l << '\n';
  detail::close_written(csv, dir / "hunt.csv");
  return result;
}

}  // namespace certcyl::cli::judging
