// `certcyl judge`: the cases (a cases file, or made as `certcyl cases` makes them, and this
// shard's share of them), the judged method's answers (an answers file, a co-process or a
// plugin), and the results folder (a shard's renamed into place when it is finished).
#include "judge.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "judge_internal.hpp"
#include "study.hpp"
#include "study_internal.hpp"

namespace certcyl::cli {

namespace {

// The judged method's name goes into every CSV row, the report and the figures: a control
// character (a newline splits a CSV record for a line-based reader) is refused, naming where the
// name came from.
void check_method_name(const std::string& name, const std::string& where) {
  for (const char ch : name) {
    const auto c = static_cast<unsigned char>(ch);
    if (c < 0x20 || c == 0x7f) {
      static const char hex[] = "0123456789abcdef";
      const std::string hint = where == "--label" ? "" : " (name it with --label NAME)";
      throw std::invalid_argument(where + ": the method's name '" + name.substr(0, name.find(ch)) + "...' holds the control character 0x" +
                                  hex[c >> 4] + hex[c & 15] + hint);
    }
  }
}

// The failure maps of an answers file (header comment of cases.hpp): the maps of the cells'
// (cells, step, seed), each cell's answer looked up by its id; a cell the cases file does not
// hold, or holds with another input than the map's, is an error of the exchange for that map.
judging::MapsResult answered_maps(const std::filesystem::path& dir, const std::string& method, const std::vector<Case>& given,
                                  const std::map<std::string, std::optional<judging::Answered>>& answer_of, unsigned threads,
                                  study::Contract contract) {
  const MapCell m = *given.front().map;
  std::vector<study::Query> queries;
  std::map<std::string, const Case*> by_id;
  for (const Case& c : given) {
    if (std::find(queries.begin(), queries.end(), c.query) == queries.end()) queries.push_back(c.query);
    by_id[c.id] = &c;
  }
  const judging::AnswerSource source = [&](const std::vector<Case>& cells) {
    judging::Answers a;
    a.answers.resize(cells.size());
    for (std::size_t i = 0; i < cells.size(); ++i) {
      const auto it = by_id.find(cells[i].id);
      if (it == by_id.end()) {
        a.failure = "the cases file has no cell " + cells[i].id;
        break;
      }
      if (it->second->x != cells[i].x) {
        a.failure = "the cases file's cell " + cells[i].id + " (line " + std::to_string(it->second->line) +
                    ") has another input than the map's";
        break;
      }
      a.answers[i] = answer_of.at(cells[i].id);
    }
    return a;
  };
  return judging::judge_failure_maps(dir, method, queries, source, m.cells, m.step, m.seed, threads, contract);
}

// The study's figures with the judged method's point (JudgeOptions::study_dir), into
// folder/figures; what happened on `out`. Returns false when they could not be drawn.
bool draw_on_study(const std::filesystem::path& study, const std::filesystem::path& folder, std::ostream& out) {
  const std::filesystem::path figures = folder / "figures";
  if (!detail::run_plot_study(detail::shell_word(study.string()) + " --judged " + detail::shell_word(folder.string()) + " --out " +
                                  detail::shell_word(figures.string()),
                              out))
    return false;
  out << "figures: " << figures.string() << " (the study's figures with the judged method's point; page "
      << (figures / "index.html").string() << ")\n";
  return true;
}

}  // namespace

int run_judge(const JudgeOptions& o, std::ostream& out, std::ostream& err) {
  using namespace judging;
  try {
    const int sources = !o.answers_file.empty() + !o.exec_command.empty() + !o.plugin_file.empty();
    if (sources != 1) throw std::invalid_argument("give one of --answers, --exec and --plugin");
    check_folder_name(o.name, "--name");  // the results stay inside --out
    if (!o.study_dir.empty()) {
      if (o.shard_count > 1) throw std::invalid_argument("--study: not with --shard (draw the figures when judging the merged answers)");
      if (!o.answers_file.empty()) throw std::invalid_argument("--study: needs --exec or --plugin (an answers file has no time per query)");
      if (!std::filesystem::is_regular_file(std::filesystem::path(o.study_dir) / "summary.csv"))
        throw std::invalid_argument("--study: '" + o.study_dir + "' is not a study's results folder (no summary.csv)");
    }
    std::optional<PluginInfo> plugin;
    if (!o.plugin_file.empty()) plugin = inspect_plugin(o.plugin_file);
    study::Contract contract = plugin && plugin->contract ? *plugin->contract : study::Contract::solid;
    if (!o.contract.empty()) {
      const study::Contract given = parse_contract(o.contract, "--contract");
      if (plugin && plugin->contract && *plugin->contract != given)
        throw std::invalid_argument("--contract " + o.contract + ": the plugin " + plugin->name + " declares " +
                                    std::string(study::to_string(*plugin->contract)) + " (certcyl_plugin_contract)");
      contract = given;
    }
    if (!o.label.empty())
      check_method_name(o.label, "--label");
    else if (plugin)
      check_method_name(plugin->name, "--plugin: certcyl_plugin_name()");
    else if (!o.exec_command.empty())
      check_method_name(o.exec_command, "--exec");
    else
      check_method_name(std::filesystem::path(o.answers_file).stem().string(), "--answers");

    std::vector<Case> cases;
    if (!o.cases_file.empty()) {
      if (!o.spec.query.empty() || !o.spec.families.empty()) throw std::invalid_argument("--cases excludes --query and --family");
      std::ifstream in(o.cases_file);
      if (!in) throw std::runtime_error("--cases: cannot read '" + o.cases_file + "'");
      cases = read_cases(in, o.cases_file);
    } else if (!o.spec.query.empty()) {
      cases = make_cases(o.spec);
    } else if (plugin) {
      if (!o.spec.families.empty()) throw std::invalid_argument("--family needs --query (family names are per query)");
      for (study::Query q : plugin->queries) {
        CaseSpec spec = o.spec;
        spec.query = std::string(study::to_string(q));
        for (Case& c : make_cases(spec)) cases.push_back(std::move(c));
      }
    } else {
      throw std::invalid_argument("give --cases FILE or --query Q");
    }
    // A cases file may hold failure-map cells (`certcyl cases --map-cells`): answered in an
    // answers file they give the maps; they are never scored as a family's cases, and with
    // --exec or --plugin the exchange draws the maps itself.
    std::vector<Case> given_cells;
    {
      const auto cells = std::stable_partition(cases.begin(), cases.end(), [](const Case& c) { return !c.map; });
      given_cells.assign(std::make_move_iterator(cells), std::make_move_iterator(cases.end()));
      cases.erase(cells, cases.end());
      if (cases.empty() && !given_cells.empty()) throw std::runtime_error("--cases: only failure-map cells, no case to judge");
      // One set of maps (before anything is judged).
      for (const Case& c : given_cells) {
        const MapCell& m = *given_cells.front().map;
        if (c.map->cells != m.cells || c.map->step != m.step || c.map->seed != m.seed)
          throw std::runtime_error("--cases: line " + std::to_string(c.line) + ": map cell " + c.id + " of other maps (meta.map) than line " +
                                   std::to_string(given_cells.front().line) + "'s");
      }
      if (!o.answers_file.empty() && !given_cells.empty() && o.map_cells > 0 && o.map_cells != given_cells.front().map->cells)
        throw std::invalid_argument("--map-cells " + std::to_string(o.map_cells) + ": the cases file's maps have " +
                                    std::to_string(given_cells.front().map->cells) + " x " + std::to_string(given_cells.front().map->cells) +
                                    " cells");
    }
    if (plugin) {
      std::erase_if(cases, [&](const Case& c) {
        return std::find(plugin->queries.begin(), plugin->queries.end(), c.query) == plugin->queries.end();
      });
      if (cases.empty()) throw std::runtime_error("--plugin: " + plugin->name + " exports none of the cases' queries");
    }

    // A contract given on the command line must apply to some case (a plugin's declared one
    // simply does not apply to its other queries).
    if (!o.contract.empty() && contract != study::Contract::solid &&
        std::none_of(cases.begin(), cases.end(), [](const Case& c) { return has_ray_contracts(c.query); }))
      throw std::invalid_argument("--contract " + o.contract +
                                  ": defined for ray_cylinder and segment_cylinder only, and no case is one of them");

    // This shard's cases: every n-th from the i-th, as the study deals its instances.
    const bool sharded = o.shard_count > 1;
    if (sharded) {
      std::vector<Case> mine;
      for (std::size_t i = static_cast<std::size_t>(o.shard_index); i < cases.size(); i += static_cast<std::size_t>(o.shard_count))
        mine.push_back(std::move(cases[i]));
      cases = std::move(mine);
    }
    // A cases file's inputs are certified again (this shard's): its meta is not trusted.
    if (!o.cases_file.empty()) recertify(cases, o.spec.threads, "--cases: " + o.cases_file);
    namespace fs = std::filesystem;
    const fs::path folder = fs::path(o.out_root) / o.name;
    const fs::path shard_folder =
        folder / std::string("shard-").append(std::to_string(o.shard_index)).append("-of-").append(std::to_string(o.shard_count));
    const fs::path partial = fs::path(shard_folder).concat(".partial");
    if (sharded) {
      fs::remove_all(partial);
      fs::remove_all(shard_folder);
    }

    const Timeout timeout{o.timeout_seconds};
    Answers answers;
    std::string method;
    // An answers file answers the cases file's map cells too; their answers, by id.
    std::map<std::string, std::optional<Answered>> cell_answers;
    if (!o.answers_file.empty()) {
      std::ifstream in(o.answers_file);
      if (!in) throw std::runtime_error("--answers: cannot read '" + o.answers_file + "'");
      if (!given_cells.empty()) {
        std::vector<Case> asked = cases;
        asked.insert(asked.end(), given_cells.begin(), given_cells.end());
        answers = read_answers(in, o.answers_file, asked);
        for (std::size_t i = 0; i < given_cells.size(); ++i) cell_answers[given_cells[i].id] = answers.answers[cases.size() + i];
        answers.answers.resize(cases.size());
      } else {
        answers = read_answers(in, o.answers_file, cases);
      }
      method = fs::path(o.answers_file).stem().string();
    } else if (!o.exec_command.empty()) {
      answers = run_exec(o.exec_command, cases, timeout);
      method = o.exec_command;
    } else {
      answers = run_plugin(o.plugin_file, cases, timeout);
      method = plugin->name;
    }
    if (!o.label.empty()) method = o.label;

    // The failure maps, by the same exchange; what the exchange answered is kept whatever fails.
    std::optional<MapsResult> maps;
    std::optional<HuntResult> hunt;
    const int map_cells = o.map_cells < 0 ? map_cells_of_size(o.spec.size) : o.map_cells;
    if (map_cells > 0) {
      maps.emplace();
      if (sharded) {
        maps->note = "a shard does not draw them (judge unsharded to draw them)";
      } else if (!o.answers_file.empty() && cell_answers.empty()) {
        maps->note = "an answers file gives them when the cases file holds the maps' cells (certcyl cases --map-cells N)";
      } else if (!o.answers_file.empty()) {
        *maps = answered_maps(folder, method, given_cells, cell_answers, std::max(1u, o.spec.threads), contract);
      } else if (!answers.failure.empty()) {
        maps->note = "not drawn, the method having failed on the cases";
      } else {
        std::vector<study::Query> queries;
        for (const Case& c : cases)
          if (std::find(queries.begin(), queries.end(), c.query) == queries.end()) queries.push_back(c.query);
        AnswerSource source;
        if (!o.exec_command.empty())
          source = [&](const std::vector<Case>& cells) { return run_exec(o.exec_command, cells, timeout); };
        else
          source = [&](const std::vector<Case>& cells) { return run_plugin(o.plugin_file, cells, timeout); };
        *maps = judge_failure_maps(sharded ? partial : folder, method, queries, source, map_cells, o.map_step, o.spec.seed,
                                   std::max(1u, o.spec.threads), contract);
        const long evaluations = o.hunt_evaluations < 0 ? hunt_evaluations_of_size(o.spec.size) : o.hunt_evaluations;
        if (evaluations > 0) hunt = judge_hunt(folder, method, queries, source, evaluations, o.spec.seed, contract);
      }
    }
    // A complete shard is renamed from its temporary name below: the printed paths name the result.
    const fs::path written = sharded ? partial : folder;
    write_results(written, sharded && answers.failure.empty() ? shard_folder : written, method, cases, answers, out, maps ? &*maps : nullptr,
                  hunt ? &*hunt : nullptr, contract);
    out.flush();
    if (!answers.failure.empty()) {
      err << "certcyl judge: " << answers.failure << '\n';
      if (sharded) err << "certcyl judge: the shard is not finished; what was judged is in " << partial.string() << '\n';
      return 1;
    }
    if (!o.study_dir.empty()) {
      std::ostringstream said;
      const bool drawn = draw_on_study(o.study_dir, folder, said);
      (drawn ? out : err) << (drawn ? "" : "certcyl judge: ") << said.str();
      if (!drawn) return 1;
    }
    if (!out) {
      err << "certcyl judge: error writing standard output\n";
      return 1;
    }
    if (sharded) fs::rename(partial, shard_folder);
    return 0;
  } catch (const std::exception& e) {
    err << "certcyl judge: " << e.what() << '\n';
    return 1;
  }
}

}  // namespace certcyl::cli
