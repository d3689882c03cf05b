// Fuzz harness: the merge's verification of a shard (detail::verified_machine, then every row of
// its instances.csv read as the merge reads it) on arbitrary bytes as the shard's files. The
// input is split at lines "@@" into manifest.json, machine.json and instances.csv, written into
// a fresh temporary shard folder (an absent part: no file). An input starting with the line
// "SEAL" has its shard sealed by the study's own manifest instead (the manifest part is then
// ignored), so that the checks behind the SHA-256 see arbitrary machine.json and rows too. The
// answer must be a verified shard or a clear refusal: std::runtime_error with a message of the
// merge's own (not a JSON library's or the file system's), never a crash or another exception.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "fuzz_input.hpp"
#include "study_internal.hpp"

using namespace certcyl;
namespace fs = std::filesystem;

namespace {

void clear_refusal(const std::string& what) {
  // A library's own message escaping unwrapped starts with its prefix (the text may quote the
  // input, which can hold anything).
  if (what.empty() || what.rfind("[json.exception", 0) == 0 || what.rfind("filesystem error", 0) == 0)
    fuzz::failure("ERROR: unclear refusal: " + what);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // One folder per process, removed when the fuzzer exits.
  static const struct TempFolder {
    fs::path path = fs::temp_directory_path() / ("certcyl_fuzz_merge_" + std::to_string(::getpid()));
    ~TempFolder() { fs::remove_all(path); }
  } temp;
  const fs::path& root = temp.path;
  const fs::path shard = root / "shard-0-of-2";
  fs::remove_all(root);
  fs::create_directories(shard);
  std::string text(reinterpret_cast<const char*>(data), size);
  const bool seal = text.rfind("SEAL\n", 0) == 0;
  if (seal) text.erase(0, 5);
  std::vector<std::string> parts;
  for (std::size_t at = 0;;) {
    const std::size_t next = text.find("\n@@\n", at);
    parts.push_back(text.substr(at, next == std::string::npos ? std::string::npos : next + 1 - at));
    if (next == std::string::npos || parts.size() == 3) break;
    at = next + 4;
  }
  const char* names[] = {"manifest.json", "machine.json", "instances.csv"};
  for (std::size_t i = seal ? 1 : 0; i < parts.size(); ++i) std::ofstream(shard / names[i], std::ios::binary) << parts[i];
  if (seal) {
    try {
      cli::detail::write_manifest(shard);
    } catch (const std::exception&) {
      return 0;  // the study seals only the machine.json it wrote itself
    }
  }
  try {
    const nlohmann::json machine = cli::detail::verified_machine(shard, "shard-0-of-2");
    // What the merge reads of a verified machine.json: its shard, as a string i/n.
    int index = 0, count = 0;
    const nlohmann::json& s = machine.at("options").at("shard");
    if (!s.is_string()) fuzz::failure("ERROR: verified machine.json has a shard that is not a string: " + s.dump());
    try {
      cli::parse_shard(s.get<std::string>(), index, count);
    } catch (const std::invalid_argument& e) {
      clear_refusal(e.what());
    }
    std::ifstream in(shard / "instances.csv");
    std::string line;
    std::getline(in, line);
    while (std::getline(in, line)) {
      try {
        cli::detail::parse_row(line);
      } catch (const std::runtime_error& e) {
        clear_refusal(e.what());
      }
    }
  } catch (const std::runtime_error& e) {
    clear_refusal(e.what());
  } catch (const std::exception& e) {
    fuzz::failure(std::string("ERROR: unclear refusal (not std::runtime_error): ") + e.what());
  }
  return 0;
}
