// A results folder that cannot lie: written in a temporary folder beside its final place, sealed
// by manifest.json (written last: every file's size, data rows and SHA-256, the configuration,
// the build and the shard) and then renamed into place; verified file by file before a merge
// reads it (experiments/STUDY.md, "Shards and their manifest").
#include <openssl/evp.h>

#include <fstream>
#include <memory>
#include <stdexcept>

#include "study_internal.hpp"
#include "study_files.hpp"

namespace certcyl::cli::detail {

namespace {

// The files a manifest covers, by path relative to `dir` ('/'-separated), sorted: every regular
// file below dir but manifest.json itself, the figures (plotted after sealing, with their own
// manifest), the shards of a merged folder and hidden entries (unfinished runs).
std::vector<std::string> covered_files(const fs::path& dir) {
  std::vector<std::string> files;
  for (auto it = fs::recursive_directory_iterator(dir); it != fs::recursive_directory_iterator(); ++it) {
    const std::string rel = fs::relative(it->path(), dir).generic_string();
    const std::string name = it->path().filename().string();
    if (it.depth() == 0 && (rel == "manifest.json" || rel == "figures" || rel.rfind("shard-", 0) == 0 || name.rfind('.', 0) == 0)) {
      if (it->is_directory()) it.disable_recursion_pending();
      continue;
    }
    if (it->is_regular_file()) files.push_back(rel);
  }
  std::sort(files.begin(), files.end());
  return files;
}

// Data rows of a CSV file: its lines but the header (a last line without '\n' counts).
long csv_rows(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  long lines = 0;
  char last = '\n';
  for (char c; in.get(c);) {
    lines += c == '\n';
    last = c;
  }
  lines += last != '\n';
  return std::max(0L, lines - 1);
}

bool is_csv(const std::string& rel) { return rel.size() > 4 && rel.compare(rel.size() - 4, 4, ".csv") == 0; }

nlohmann::json file_entry(const fs::path& p, const std::string& rel) {
  nlohmann::json e;
  e["bytes"] = fs::file_size(p);
  if (is_csv(rel)) e["rows"] = csv_rows(p);
  e["sha256"] = sha256_file(p);
  return e;
}

// What an entry that is neither a regular file nor a folder is, for a message.
const char* kind_of(fs::file_type t) {
  switch (t) {
    case fs::file_type::symlink: return "a symbolic link";
    case fs::file_type::fifo: return "a FIFO";
    case fs::file_type::character:
    case fs::file_type::block: return "a device";
    case fs::file_type::socket: return "a socket";
    case fs::file_type::not_found: return "missing";
    default: return "not a regular file";
  }
}

// Throws unless the folder and everything in it are regular files and folders (links not
// followed): a symbolic link, a FIFO or a device could lead outside the folder, block a read or
// never end (a link to /dev/zero, or to a folder holding the shard, copied into itself).
void check_plain_entries(const fs::path& dir, const std::string& label) {
  const fs::file_type top = fs::symlink_status(dir).type();
  if (top != fs::file_type::directory) throw std::runtime_error(label + ": " + kind_of(top) + ", not a folder");
  for (auto it = fs::recursive_directory_iterator(dir); it != fs::recursive_directory_iterator(); ++it) {
    const fs::file_type t = it->symlink_status().type();
    if (t != fs::file_type::regular && t != fs::file_type::directory)
      throw std::runtime_error(label + "/" + it->path().lexically_relative(dir).generic_string() + ": " + kind_of(t) +
                               ", not a regular file of the size its manifest lists");
  }
}

}  // namespace

std::string sha256_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  if (!in) throw std::runtime_error(p.string() + ": cannot read");
  const std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> ctx(EVP_MD_CTX_new(), &EVP_MD_CTX_free);
  if (!ctx || EVP_DigestInit_ex(ctx.get(), EVP_sha256(), nullptr) != 1) throw std::runtime_error("SHA-256: OpenSSL initialisation failed");
  std::vector<char> buf(1 << 16);
  while (in) {
    in.read(buf.data(), static_cast<std::streamsize>(buf.size()));
    if (in.gcount() > 0 && EVP_DigestUpdate(ctx.get(), buf.data(), static_cast<std::size_t>(in.gcount())) != 1)
      throw std::runtime_error("SHA-256: OpenSSL update failed");
  }
  unsigned char md[EVP_MAX_MD_SIZE];
  unsigned int len = 0;
  if (EVP_DigestFinal_ex(ctx.get(), md, &len) != 1) throw std::runtime_error("SHA-256: OpenSSL finalisation failed");
  static const char* hex = "0123456789abcdef";
  std::string out;
  for (unsigned int i = 0; i < len; ++i) out += {hex[md[i] >> 4], hex[md[i] & 15]};
  return out;
}

// The hidden sibling ".NAME<suffix>" of dir. Appended in place: GCC 12's -Wrestrict misreads
// the inlined "." + name + suffix at -O3 (a false overlap of 2^63 bytes).
fs::path hidden_sibling(const fs::path& dir, const char* suffix) {
  std::string name = ".";
  name += dir.filename().string();
  name += suffix;
  return dir.parent_path() / name;
}

fs::path partial_folder(const fs::path& dir) { return hidden_sibling(dir, ".partial"); }

fs::path begin_folder(const fs::path& dir) {
  const fs::path partial = partial_folder(dir);
  fs::remove_all(partial);
  fs::create_directories(partial);
  return partial;
}

nlohmann::json configuration_of(const nlohmann::json& machine) {
  nlohmann::json c;
  c["shard"] = machine.at("options").at("shard");
  c["options"] = machine.at("options");
  c["options"].erase("threads");
  c["options"].erase("name");
  nlohmann::json build;
  for (const char* key : {"commit", "compiler", "flags", "cgal", "peers"}) build[key] = machine.value(key, nlohmann::json());
  c["build"] = build;
  return c;
}

void write_manifest(const fs::path& dir) {
  const fs::path machine_file = dir / "machine.json";
  std::ifstream in(machine_file);
  if (!in) throw std::logic_error("manifest: " + machine_file.string() + " not written");
  nlohmann::json manifest = configuration_of(nlohmann::json::parse(in));
  nlohmann::json files = nlohmann::json::object();
  for (const std::string& rel : covered_files(dir)) files[rel] = file_entry(dir / rel, rel);
  manifest["files"] = files;
  const fs::path tmp = dir / ".manifest.json.tmp";
  write_whole(tmp, manifest.dump(2) + '\n');
  fs::rename(tmp, dir / "manifest.json");
}

void seal_folder(const fs::path& partial, const fs::path& dir) {
  write_manifest(partial);
  // Between the two renames `dir` is absent, never a mixture of two runs.
  const fs::path old = hidden_sibling(dir, ".old");
  fs::remove_all(old);
  if (fs::exists(dir)) fs::rename(dir, old);
  fs::rename(partial, dir);
  fs::remove_all(old);
}

nlohmann::json verified_machine(const fs::path& dir, const std::string& label) {
  check_plain_entries(dir, label);
  const fs::path manifest_file = dir / "manifest.json";
  std::ifstream in(manifest_file);
  if (!in) throw std::runtime_error(label + ": no manifest.json (an unfinished, killed or foreign run)");
  const nlohmann::json manifest = nlohmann::json::parse(in, nullptr, false);
  if (manifest.is_discarded() || !manifest.is_object() || !manifest.contains("files") || !manifest["files"].is_object())
    throw std::runtime_error(label + "/manifest.json: not a study manifest");
  const std::vector<std::string> present = covered_files(dir);
  for (const auto& [rel, entry] : manifest["files"].items()) {
    const std::string where = label + "/" + rel;
    // Only files inside the folder, named as covered_files names them.
    if (std::find(present.begin(), present.end(), rel) == present.end()) {
      const fs::path r(rel);
      if (rel.empty() || r.is_absolute() || rel != r.lexically_normal().generic_string() || rel.rfind("../", 0) == 0 || rel == "..")
        throw std::runtime_error(label + "/manifest.json: lists '" + rel + "', not a file of the folder");
      throw std::runtime_error(where + ": missing (listed in the manifest)");
    }
    const fs::path p = dir / rel;
    const bool entry_ok = entry.is_object() && entry.contains("bytes") && entry["bytes"].is_number_unsigned() && entry.contains("sha256") &&
                          entry["sha256"].is_string() && (!entry.contains("rows") || entry["rows"].is_number_unsigned());
    if (!entry_ok) throw std::runtime_error(label + "/manifest.json: not a study manifest (entry of " + rel + ")");
    if (entry.contains("rows")) {
      const long rows = csv_rows(p);
      if (entry["rows"] != rows)
        throw std::runtime_error(where + ": " + std::to_string(rows) + " data rows, the manifest lists " + entry["rows"].dump());
    }
    if (entry["bytes"] != fs::file_size(p))
      throw std::runtime_error(where + ": " + std::to_string(fs::file_size(p)) + " bytes, the manifest lists " + entry["bytes"].dump());
    if (sha256_file(p) != entry["sha256"].get<std::string>())
      throw std::runtime_error(where + ": SHA-256 differs from the manifest (the file was altered)");
  }
  for (const std::string& rel : present)
    if (!manifest["files"].contains(rel)) throw std::runtime_error(label + "/" + rel + ": not in the manifest");
  // machine.json is covered above; its configuration must be the manifest's.
  std::ifstream m(dir / "machine.json");
  if (!m) throw std::runtime_error(label + "/machine.json: missing");
  nlohmann::json machine = nlohmann::json::parse(m, nullptr, false);
  if (machine.is_discarded() || !machine.is_object() || !machine.contains("options") || !machine["options"].is_object() ||
      !machine["options"].contains("shard") || !machine["options"]["shard"].is_string())
    throw std::runtime_error(label + "/machine.json: not a study's machine.json");
  const nlohmann::json expected = configuration_of(machine);
  for (const char* key : {"shard", "options", "build"})
    if (manifest.value(key, nlohmann::json()) != expected[key])
      throw std::runtime_error(label + "/manifest.json: its " + key + " differs from machine.json's");
  return machine;
}

}  // namespace certcyl::cli::detail
