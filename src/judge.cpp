// `certcyl judge`: the cases (a cases file, or made as `certcyl cases` makes them, and this
// shard's share of them), the judged method's answers (an answers file, a co-process or a
// plugin), and the results folder (a shard's renamed into place when it is finished).
#include "judge.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <optional>
#include <stdexcept>

#include "judge_internal.hpp"
#include "study.hpp"

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

}  // namespace

int run_judge(const JudgeOptions& o, std::ostream& out, std::ostream& err) {
  using namespace judging;
  try {
    const int sources = !o.answers_file.empty() + !o.exec_command.empty() + !o.plugin_file.empty();
    if (sources != 1) throw std::invalid_argument("give one of --answers, --exec and --plugin");
    check_folder_name(o.name, "--name");  // the results stay inside --out
    std::optional<PluginInfo> plugin;
    if (!o.plugin_file.empty()) plugin = inspect_plugin(o.plugin_file);
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
    if (plugin) {
      std::erase_if(cases, [&](const Case& c) {
        return std::find(plugin->queries.begin(), plugin->queries.end(), c.query) == plugin->queries.end();
      });
      if (cases.empty()) throw std::runtime_error("--plugin: " + plugin->name + " exports none of the cases' queries");
    }

    // This shard's cases: every n-th from the i-th, as the study deals its instances.
    const bool sharded = o.shard_count > 1;
    if (sharded) {
      std::vector<Case> mine;
      for (std::size_t i = static_cast<std::size_t>(o.shard_index); i < cases.size(); i += static_cast<std::size_t>(o.shard_count))
        mine.push_back(std::move(cases[i]));
      cases = std::move(mine);
    }
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
    if (!o.answers_file.empty()) {
      std::ifstream in(o.answers_file);
      if (!in) throw std::runtime_error("--answers: cannot read '" + o.answers_file + "'");
      answers = read_answers(in, o.answers_file, cases);
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
      } else if (!o.answers_file.empty()) {
        maps->note = "they need --plugin or --exec (an answers file holds no answers for the maps' inputs)";
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
                                   std::max(1u, o.spec.threads));
        const long evaluations = o.hunt_evaluations < 0 ? hunt_evaluations_of_size(o.spec.size) : o.hunt_evaluations;
        if (evaluations > 0) hunt = judge_hunt(folder, method, queries, source, evaluations, o.spec.seed);
      }
    }
    // A complete shard is renamed from its temporary name below: the printed paths name the result.
    const fs::path written = sharded ? partial : folder;
    write_results(written, sharded && answers.failure.empty() ? shard_folder : written, method, cases, answers, out, maps ? &*maps : nullptr, hunt ? &*hunt : nullptr);
    out.flush();
    if (!answers.failure.empty()) {
      err << "certcyl judge: " << answers.failure << '\n';
      if (sharded) err << "certcyl judge: the shard is not finished; what was judged is in " << partial.string() << '\n';
      return 1;
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
