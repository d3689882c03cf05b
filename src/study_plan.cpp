// The study's configuration (size presets, --config, --shard) and its instances.
#include <fstream>
#include <stdexcept>

#include "certcyl/study/families.hpp"
#include "study_internal.hpp"

namespace certcyl::cli::detail {
using namespace certcyl::study;

void apply_size(StudyOptions& o) {
  struct Preset {
    const char* name;
    long per_family;
    int map_cells;
    long hunt;
  };
  const Preset presets[] = {{"tiny", 3, 16, 20}, {"small", 12, 64, 150}, {"default", 96, 256, 1000}, {"large", 400, 256, 5000}};
  for (const Preset& p : presets) {
    if (o.size == p.name) {
      if (o.per_family == 0) o.per_family = p.per_family;
      if (o.map_cells == 0) o.map_cells = p.map_cells;
      if (o.hunt_evaluations == 0) o.hunt_evaluations = p.hunt;
      return;
    }
  }
  long n = 0;
  try {
    n = std::stol(o.size);
  } catch (const std::exception&) {
  }
  if (n <= 0) throw std::invalid_argument("--size: expected tiny, small, default, large or a positive count, got '" + o.size + "'");
  if (o.per_family == 0) o.per_family = n;
  if (o.map_cells == 0) o.map_cells = 256;
  if (o.hunt_evaluations == 0) o.hunt_evaluations = std::max(20L, 12 * n);
}

void apply_config(StudyOptions& o) {
  if (o.config_file.empty()) return;
  std::ifstream in(o.config_file);
  if (!in) throw std::invalid_argument("--config: cannot read '" + o.config_file + "'");
  const nlohmann::json j = nlohmann::json::parse(in);
  for (const auto& [key, value] : j.items()) {
    if (key == "per_family") o.per_family = value.get<long>();
    else if (key == "map_cells") o.map_cells = value.get<int>();
    else if (key == "map_step") o.map_step = value.get<long>();
    else if (key == "hunt_evaluations") o.hunt_evaluations = value.get<long>();
    else if (key == "methods") o.methods = value.get<std::vector<std::string>>();
    else if (key == "families") o.families = value.get<std::vector<std::string>>();
    else if (key == "size") o.size = value.get<std::string>();
    else if (key == "seed") o.seed = value.get<std::uint64_t>();
    else if (key == "name") o.name = value.get<std::string>();
    else throw std::invalid_argument("--config: unknown key '" + key + "' (per_family, map_cells, map_step, hunt_evaluations, methods, families, size, seed, name)");
  }
}


std::uint64_t mix(std::uint64_t h, std::uint64_t v) {
  h ^= v + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
  h ^= h >> 31;
  h *= 0xbf58476d1ce4e5b9ULL;
  return h ^ (h >> 29);
}
std::uint64_t hash_string(const std::string& s) {
  std::uint64_t h = 1469598103934665603ULL;
  for (unsigned char c : s) h = (h ^ c) * 1099511628211ULL;
  return h;
}

bool keep_name(const std::vector<std::string>& filter, const std::string& name) {
  if (filter.empty()) return true;
  return std::any_of(filter.begin(), filter.end(), [&](const std::string& f) { return name.find(f) != std::string::npos; });
}

// Every instance of the configuration, in a fixed order; each depends only on the seed, its
// family, its query and its index, so any shard builds the same ones.
std::vector<Planned> plan_instances(const StudyOptions& o) {
  std::vector<Planned> out;
  std::uint64_t id = 0;
  for (const Family& f : all_families()) {
    if (!o.families.empty() && std::find(o.families.begin(), o.families.end(), f.name) == o.families.end()) continue;
    for (Query q : f.queries) {
      for (long i = 0; i < o.per_family; ++i, ++id) {
        if (static_cast<int>(id % o.shard_count) != o.shard_index) continue;
        Rng rng(mix(mix(mix(o.seed, hash_string(f.name)), static_cast<std::uint64_t>(q)), static_cast<std::uint64_t>(i)));
        Planned p;
        p.k = ulp_offset(rng, static_cast<std::size_t>(i));
        FamilyInput in = f.make(rng, q, p.k);
        p.inst.id = id;
        p.inst.family = f.name;
        p.inst.query = q;
        p.inst.x = std::move(in.x);
        p.inst.expected = in.expected;
        p.index_in_family = static_cast<std::size_t>(i);
        out.push_back(std::move(p));
      }
    }
  }
  return out;
}

}  // namespace certcyl::cli::detail

namespace certcyl::cli {

void parse_shard(const std::string& s, int& index, int& count) {
  const auto slash = s.find('/');
  if (slash == std::string::npos) throw std::invalid_argument("--shard: expected i/n, got '" + s + "'");
  index = std::stoi(s.substr(0, slash));
  count = std::stoi(s.substr(slash + 1));
  if (count < 1 || index < 0 || index >= count) throw std::invalid_argument("--shard: need 0 <= i < n, got '" + s + "'");
}

}  // namespace certcyl::cli
