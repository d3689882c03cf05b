// The study's configuration (size presets, --config, --shard; every option and key checked before
// any work: its type, its range without truncation, names that exist, a plain folder name) and
// its instances.
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "study/families.hpp"
#include "query.hpp"
#include "study_internal.hpp"

namespace certcyl::cli::detail {
using namespace certcyl::study;

// The ranges of the configuration (experiments/STUDY.md, "Configuration").
constexpr long kMaxPerFamily = 10000000;
constexpr long kMaxHuntEvaluations = 100000000;
constexpr long kMaxUniformPerQuery = 100000000;
constexpr int kMaxMapCells = 1024;
constexpr long kMaxMapStep = 1000000000;
constexpr unsigned long long kMaxShards = 100000;

namespace {

// A JSON integer in [lo, hi]; a fraction, a string or a value out of range is an error naming
// the key and the value as written.
template <class T>
T json_integer(const nlohmann::json& v, const std::string& key, long long lo, unsigned long long hi) {
  bool fits = false;
  if (v.is_number_unsigned()) fits = v.get<unsigned long long>() <= hi && (lo <= 0 || v.get<unsigned long long>() >= static_cast<unsigned long long>(lo));
  else if (v.is_number_integer()) fits = v.get<long long>() >= lo && (v.get<long long>() < 0 || static_cast<unsigned long long>(v.get<long long>()) <= hi);
  if (!fits) throw std::invalid_argument(key + ": expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + v.dump());
  return v.is_number_unsigned() ? static_cast<T>(v.get<unsigned long long>()) : static_cast<T>(v.get<long long>());
}

// A decimal integer at most hi written as text: digits only (no sign, no space, no fraction).
bool parse_count(const std::string& s, unsigned long long hi, unsigned long long& n) {
  if (s.empty() || s.size() > 20 || s.find_first_not_of("0123456789") != std::string::npos) return false;
  n = 0;
  for (char c : s) {
    const unsigned d = static_cast<unsigned>(c - '0');
    if (n > (std::numeric_limits<unsigned long long>::max() - d) / 10) return false;
    n = n * 10 + d;
  }
  return n <= hi;
}

std::string json_string(const nlohmann::json& v, const std::string& key) {
  if (!v.is_string()) throw std::invalid_argument(key + ": expected a string, got " + v.dump());
  return v.get<std::string>();
}

std::vector<std::string> json_strings(const nlohmann::json& v, const std::string& key) {
  if (!v.is_array()) throw std::invalid_argument(key + ": expected an array of strings, got " + v.dump());
  std::vector<std::string> out;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const std::string at = key + "[" + std::to_string(i) + "]";
    out.push_back(json_string(v[i], at));
    if (out.back().empty()) throw std::invalid_argument(at + ": expected a non-empty string");
  }
  return out;
}

// Levenshtein distance from a to b, or (within) to the nearest substring of b: for the nearest
// valid names in an error.
std::size_t edit_distance(const std::string& a, const std::string& b, bool within = false) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = within ? 0 : j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return within ? *std::min_element(row.begin(), row.end()) : row[b.size()];
}

// The valid names nearest to `wrong` (all at the least distance, at most 4), comma-separated.
std::string nearest(const std::string& wrong, const std::vector<std::string>& valid, bool within) {
  std::size_t least = std::numeric_limits<std::size_t>::max();
  std::vector<std::string> names;
  for (const std::string& v : valid) {
    const std::size_t d = edit_distance(wrong.substr(0, 256), v, within);
    if (d < least) least = d, names.clear();
    if (d == least && names.size() < 4 && std::find(names.begin(), names.end(), v) == names.end()) names.push_back(v);
  }
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}


// The file's bytes; a missing or unreadable file is an error with the system's reason.
std::string read_config(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::invalid_argument("--config: cannot read '" + file + "': " + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad() || fs::is_directory(file)) throw std::invalid_argument("--config: cannot read '" + file + "': " + std::strerror(fs::is_directory(file) ? EISDIR : errno));
  return text.str();
}

}  // namespace

void apply_size(StudyOptions& o) {
  struct Preset {
    const char* name;
    long per_family;
    int map_cells;
    long hunt;
    long uniform;
  };
  const Preset presets[] = {{"tiny", 3, 16, 20, 200},
                            {"small", 12, 64, 150, 5000},
                            {"default", 96, 128, 250, 100000},
                            {"large", 400, 256, 5000, 1000000}};
  for (const Preset& p : presets) {
    if (o.size == p.name) {
      if (o.per_family == 0) o.per_family = p.per_family;
      if (o.map_cells == 0) o.map_cells = p.map_cells;
      if (o.hunt_evaluations == 0) o.hunt_evaluations = p.hunt;
      if (o.uniform_per_query < 0) o.uniform_per_query = p.uniform;
      return;
    }
  }
  unsigned long long n = 0;
  if (!parse_count(o.size, kMaxPerFamily, n) || n < 1)
    throw std::invalid_argument("--size: expected tiny, small, default, large or an integer in [1, " + std::to_string(kMaxPerFamily) + "], got '" +
                                o.size + "'");
  // N instances per family and query; the failure maps and the hunt of the smallest preset with
  // at least N per family (large's beyond it), so that N never draws larger maps than the preset
  // it lies under; the uniform sample 1000 N per query.
  const long count = static_cast<long>(n);
  const Preset* under = &presets[3];
  for (const Preset& p : presets)
    if (count <= p.per_family) {
      under = &p;
      break;
    }
  if (o.per_family == 0) o.per_family = count;
  if (o.map_cells == 0) o.map_cells = under->map_cells;
  if (o.hunt_evaluations == 0) o.hunt_evaluations = under->hunt;
  if (o.uniform_per_query < 0) o.uniform_per_query = std::min(kMaxUniformPerQuery, 1000 * count);
}

// The file's keys, each checked; --size, --seed and --name given on the command line win over its
// size, seed and name.
void apply_config(StudyOptions& o) {
  if (o.config_file.empty()) return;
  const std::string text = read_config(o.config_file);
  nlohmann::json j;
  try {
    j = parse_strict_json(text);  // a key given twice is an error, not the last one winning
  } catch (const InvalidInput& e) {
    throw std::invalid_argument("--config: '" + o.config_file + "': " + e.what());
  } catch (const nlohmann::json::exception& e) {
    // e.what() is "[json.exception.parse_error.N] parse error at line L, column C: ..." or, for a
    // number beyond the doubles, "[json.exception.out_of_range.406] number overflow parsing '...'".
    const std::string what = e.what();
    const auto at = what.find(" at line "), tag = what.find("] ");
    throw std::invalid_argument("--config: '" + o.config_file + "' is malformed JSON" +
                                (at != std::string::npos ? what.substr(at) : ": " + (tag == std::string::npos ? what : what.substr(tag + 2))));
  }
  if (!j.is_object()) throw std::invalid_argument("--config: expected a JSON object, got " + std::string(j.type_name()));
  const StudyOptions command_line = o;
  for (const auto& [key, value] : j.items()) {
    const std::string k = "--config: " + key;
    if (key == "per_family") o.per_family = json_integer<long>(value, k, 1, kMaxPerFamily);
    else if (key == "map_cells") o.map_cells = json_integer<int>(value, k, 2, kMaxMapCells);
    else if (key == "map_step") o.map_step = json_integer<long>(value, k, 1, kMaxMapStep);
    else if (key == "hunt_evaluations") o.hunt_evaluations = json_integer<long>(value, k, 1, kMaxHuntEvaluations);
    else if (key == "uniform_per_query") o.uniform_per_query = json_integer<long>(value, k, 0, kMaxUniformPerQuery);
    else if (key == "methods") o.methods = json_strings(value, k);
    else if (key == "families") o.families = json_strings(value, k);
    else if (key == "size") o.size = value.is_number() ? std::to_string(json_integer<long>(value, k, 1, kMaxPerFamily)) : json_string(value, k);
    else if (key == "seed") o.seed = json_integer<std::uint64_t>(value, k, 0, std::numeric_limits<std::uint64_t>::max());
    else if (key == "name") check_folder_name(o.name = json_string(value, k), k);
    else throw std::invalid_argument("--config: unknown key '" + key + "' (per_family, map_cells, map_step, hunt_evaluations, uniform_per_query, methods, families, size, seed, name)");
  }
  if (o.size_given) o.size = command_line.size;
  if (o.seed_given) o.seed = command_line.seed;
  if (o.name_given) o.name = command_line.name;
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

void check_folder_name(const std::string& name, const std::string& key) {
  if (name.empty() || name == ".." || name.find('/') != std::string::npos || name.find('\0') != std::string::npos || name[0] == '.')
    throw std::invalid_argument(key + ": expected a plain folder name (not empty, no '/', not starting with '.'), got '" + name + "'");
}
using namespace detail;

void parse_shard(const std::string& s, int& index, int& count) {
  const auto slash = s.find('/');
  unsigned long long i = 0, n = 0;
  if (slash == std::string::npos || !parse_count(s.substr(0, slash), kMaxShards, i) || !parse_count(s.substr(slash + 1), kMaxShards, n) || n < 1 ||
      i >= n)
    throw std::invalid_argument("--shard: expected i/n with integers 0 <= i < n <= " + std::to_string(kMaxShards) + ", got '" + s + "'");
  index = static_cast<int>(i);
  count = static_cast<int>(n);
}

std::string integer_error(const std::string& text, unsigned long long lo, unsigned long long hi) {
  unsigned long long n = 0;
  if (parse_count(text, hi, n) && n >= lo) return {};
  return "expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got '" + text + "'";
}

void configure_study(StudyOptions& o, const std::vector<std::string>& method_names) {
  apply_config(o);
  apply_size(o);
  if (o.name.empty()) o.name = o.size;
  check_folder_name(o.name, "--name");
  if (o.out_root.empty()) throw std::invalid_argument("--out: expected a folder, got ''");
  if (fs::exists(o.out_root) && !fs::is_directory(o.out_root)) throw std::invalid_argument("--out: '" + o.out_root + "' is not a folder");
  if (o.threads < 1 || o.threads > 1024) throw std::invalid_argument("--threads: expected an integer in [0, 1024], got " + std::to_string(o.threads));
  std::vector<std::string> families;
  for (const Family& f : all_families())
    if (std::find(families.begin(), families.end(), f.name) == families.end()) families.push_back(f.name);
  for (const std::string& f : o.families)
    if (std::find(families.begin(), families.end(), f) == families.end())
      throw std::invalid_argument("--config: families: unknown family '" + f + "' (nearest: " + nearest(f, families, false) + ")");
  for (const std::string& m : o.methods)
    if (std::none_of(method_names.begin(), method_names.end(), [&](const std::string& n) { return n.find(m) != std::string::npos; }))
      throw std::invalid_argument("--config: methods: '" + m + "' is in no method's name (nearest: " + nearest(m, method_names, true) + ")");
}

}  // namespace certcyl::cli
