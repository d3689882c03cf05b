// `certcyl merge`: the shards of a study verified against their manifests, checked against each
// other and merged into the outputs of an unsharded run of the same configuration, sealed by a
// manifest of their own.
#include <fstream>
#include <map>
#include <sstream>
#include <set>
#include <stdexcept>

#include "study_internal.hpp"
#include "study_files.hpp"

namespace certcyl::cli {
using namespace detail;

namespace {

// The shards of a study folder, checked: each shard-* folder is first verified against its
// manifest (study_manifest.cpp: every file whole, nothing added), then its machine.json gives
// its "shard" i/n (the folder's name is not trusted: a copied folder is a duplicate); every
// shard shares one n, one configuration (every option but the shard, the thread count and the
// name) and one build (commit, compiler, flags, CGAL, peer libraries); each of 0..n-1 is there
// exactly once. `unfinished` names what killed runs left (hidden .shard-* folders), for the
// message on a missing shard. Throws std::runtime_error naming the shard and what differs, is
// damaged or is missing.
std::vector<fs::path> checked_shards(const fs::path& dir, std::vector<fs::path> shards, const std::vector<std::string>& unfinished,
                                     nlohmann::json& machine) {
  std::sort(shards.begin(), shards.end());
  struct Seen {
    fs::path path;
    nlohmann::json machine;
  };
  std::vector<Seen> seen;
  for (const fs::path& s : shards) {
    try {
      seen.push_back({s, verified_machine(s, s.filename().string())});
    } catch (const std::runtime_error& e) {
      throw std::runtime_error(std::string("merge: ") + e.what());
    }
  }
  const Seen& first = seen.front();
  auto where = [](const Seen& e) { return e.path.filename().string(); };
  int count = -1;
  std::map<int, std::vector<std::string>> by_index;
  for (const Seen& e : seen) {
    int index = 0, n = 0;
    const std::string shard = e.machine["options"]["shard"].get<std::string>();
    try {
      parse_shard(shard, index, n);
    } catch (const std::exception&) {
      throw std::runtime_error("merge: " + where(e) + ": machine.json has shard '" + shard + "'");
    }
    if (count >= 0 && n != count)
      throw std::runtime_error("merge: shards of different counts: " + where(first) + " is one of " + std::to_string(count) + ", " + where(e) +
                               " one of " + std::to_string(n));
    count = n;
    by_index[index].push_back(where(e));
    // The configuration and the build must be the same.
    for (const char* key : {"commit", "compiler", "flags", "cgal", "peers"})
      if (e.machine.value(key, nlohmann::json()) != first.machine.value(key, nlohmann::json()))
        throw std::runtime_error(std::string("merge: shards from different builds: ") + key + " is " + first.machine.value(key, nlohmann::json()).dump() +
                                 " in " + where(first) + " but " + e.machine.value(key, nlohmann::json()).dump() + " in " + where(e));
    const nlohmann::json& a = first.machine["options"];
    const nlohmann::json& b = e.machine["options"];
    std::set<std::string> keys;
    for (const auto& [k, v] : a.items()) keys.insert(k);
    for (const auto& [k, v] : b.items()) keys.insert(k);
    for (const std::string& k : keys) {
      if (k == "shard" || k == "threads" || k == "name") continue;
      const nlohmann::json va = a.value(k, nlohmann::json()), vb = b.value(k, nlohmann::json());
      if (va != vb)
        throw std::runtime_error("merge: shards of different configurations: " + k + " is " + va.dump() + " in " + where(first) + " but " +
                                 vb.dump() + " in " + where(e));
    }
  }
  std::string missing, duplicate;
  for (int i = 0; i < count; ++i) {
    const auto it = by_index.find(i);
    if (it == by_index.end()) missing += (missing.empty() ? "" : ", ") + std::to_string(i);
  }
  for (const auto& [i, folders] : by_index) {
    if (folders.size() < 2) continue;
    duplicate += std::string(duplicate.empty() ? "" : "; ") + std::to_string(i) + " (";
    for (std::size_t k = 0; k < folders.size(); ++k) duplicate += (k ? ", " : "") + folders[k];
    duplicate += ")";
  }
  if (!missing.empty()) {
    std::string left;
    for (const std::string& u : unfinished) left += (left.empty() ? "" : ", ") + u;
    throw std::runtime_error("merge: missing shard(s) " + missing + " of " + std::to_string(count) + " in " + dir.string() +
                             (left.empty() ? "" : " (unfinished runs left " + left + ")"));
  }
  if (!duplicate.empty()) throw std::runtime_error("merge: duplicate shard(s) " + duplicate + " in " + dir.string());
  machine = first.machine;
  return shards;
}

}  // namespace

int run_merge(const std::string& dir_name, bool plots, std::ostream& out) {
  const fs::path dir(dir_name);
  std::vector<fs::path> shards;
  std::vector<std::string> unfinished;
  if (fs::is_directory(dir))
    for (const auto& e : fs::directory_iterator(dir)) {
      const std::string name = e.path().filename().string();
      if (e.is_directory() && name.rfind("shard-", 0) == 0) shards.push_back(e.path());
      if (e.is_directory() && name.rfind(".shard-", 0) == 0) unfinished.push_back(name);
    }
  if (shards.empty()) throw std::runtime_error("merge: no shard-*-of-* folders in " + dir_name);
  std::sort(unfinished.begin(), unfinished.end());
  nlohmann::json machine;
  shards = checked_shards(dir, std::move(shards), unfinished, machine);
  // The merged outputs are written in place: the manifest goes first and comes back last.
  fs::remove(dir / "manifest.json");
  std::sort(shards.begin(), shards.end());
  // Instances and inputs in instance order; hunting lines in method order; maps from shard 0.
  std::vector<std::pair<std::uint64_t, std::string>> rows, inputs;
  std::vector<std::string> hunt;
  std::ostringstream core_diagnostics;
  fs::remove(dir / "Core_Diagnostics");
  for (const fs::path& s : shards) {
    auto read = [&](const char* file, std::vector<std::pair<std::uint64_t, std::string>>& into, std::size_t id_field) {
      std::ifstream in(s / file);
      if (!in) throw std::runtime_error("merge: missing " + (s / file).string());
      std::string line;
      std::getline(in, line);
      for (long n = 2; std::getline(in, line); ++n) {
        try {
          into.emplace_back(std::stoull(split_csv(line).at(id_field)), line);
        } catch (const std::exception&) {
          throw std::runtime_error("merge: " + s.filename().string() + "/" + file + ", line " + std::to_string(n) + ": not a row");
        }
      }
    };
    read("instances.csv", rows, 2);
    read("inputs.csv", inputs, 0);
    std::ifstream h(s / "hunt.csv");
    std::string line;
    std::getline(h, line);
    while (std::getline(h, line)) hunt.push_back(line);
    if (fs::exists(s / "failure_maps")) fs::copy(s / "failure_maps", dir / "failure_maps", fs::copy_options::recursive | fs::copy_options::overwrite_existing);
    // CORE::Expr's warnings, every shard's in shard order.
    if (fs::exists(s / "Core_Diagnostics")) {
      std::ifstream from(s / "Core_Diagnostics", std::ios::binary);
      core_diagnostics << from.rdbuf();
    }
  }
  if (core_diagnostics.tellp() > 0) write_whole(dir / "Core_Diagnostics", core_diagnostics.str());
  std::stable_sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::stable_sort(inputs.begin(), inputs.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::sort(hunt.begin(), hunt.end());
  {
    std::ofstream csv(dir / "instances.csv");
    csv << kRowHeader << '\n';
    for (const auto& r : rows) csv << r.second << '\n';
    close_written(csv, dir / "instances.csv");
    std::ofstream in(dir / "inputs.csv");
    in << kInputsHeader << '\n';
    for (const auto& r : inputs) in << r.second << '\n';
    close_written(in, dir / "inputs.csv");
    std::ofstream h(dir / "hunt.csv");
    h << kHuntHeader << '\n';
    for (const auto& l : hunt) h << l << '\n';
    close_written(h, dir / "hunt.csv");
    machine["merged_shards"] = shards.size();
    machine["options"]["shard"] = "merged";
    write_whole(dir / "machine.json", machine.dump(2) + '\n');
  }
  merge_uniform(shards, dir);
  out << write_summary(dir);
  write_manifest(dir);
  out << "merged " << shards.size() << " shards into " << dir.string() << '\n';
  run_plots(dir, plots, out);
  return 0;
}

}  // namespace certcyl::cli
