// Fuzz harness: the study's configuration (cli::configure_study) on arbitrary bytes as its
// --config file. The answer must be a clear error (std::invalid_argument naming --config or
// --name) or a configuration within its documented ranges: every count in range, the name a
// plain folder name, the families known and every method filter in some method's name. The
// study itself is not run.
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "study/families.hpp"
#include "fuzz_input.hpp"
#include "study.hpp"

using namespace certcyl;

namespace {

const std::vector<std::string> kMethods = {"shene/double", "shene/gmpfr53", "gullotti/long_double", "eberly_cylinders/interval"};

void check(bool ok, const std::string& what) {
  if (!ok) fuzz::failure("ERROR: accepted configuration out of range: " + what);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // One file per process, removed when the fuzzer exits.
  static const struct TempFile {
    std::filesystem::path path = std::filesystem::temp_directory_path() / ("certcyl_fuzz_config_" + std::to_string(::getpid()) + ".json");
    ~TempFile() { std::filesystem::remove(path); }
  } temp;
  const std::filesystem::path& file = temp.path;
  std::ofstream(file, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  cli::StudyOptions o;
  o.config_file = file.string();
  o.out_root = "certcyl-fuzz-results-never-written";
  try {
    cli::configure_study(o, kMethods);
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    if (what.rfind("--config: ", 0) != 0 && what.rfind("--name: ", 0) != 0 && what.rfind("--size: ", 0) != 0)
      fuzz::failure("ERROR: error naming no option or key: " + what);
    return 0;
  } catch (const std::exception& e) {
    fuzz::failure(std::string("ERROR: unclear error (not std::invalid_argument): ") + e.what());
  }
  check(o.per_family >= 1 && o.per_family <= 10000000, "per_family " + std::to_string(o.per_family));
  check(o.map_cells >= 2 && o.map_cells <= 1024, "map_cells " + std::to_string(o.map_cells));
  check(o.map_step >= 1 && o.map_step <= 1000000000, "map_step " + std::to_string(o.map_step));
  check(o.hunt_evaluations >= 1 && o.hunt_evaluations <= 100000000, "hunt_evaluations " + std::to_string(o.hunt_evaluations));
  check(!o.name.empty() && o.name[0] != '.' && o.name.find('/') == std::string::npos && o.name.find('\0') == std::string::npos, "name '" + o.name + "'");
  for (const std::string& f : o.families) {
    const auto all = study::all_families();
    check(std::any_of(all.begin(), all.end(), [&](const study::Family& g) { return g.name == f; }), "family '" + f + "'");
  }
  for (const std::string& m : o.methods)
    check(std::any_of(kMethods.begin(), kMethods.end(), [&](const std::string& n) { return !m.empty() && n.find(m) != std::string::npos; }),
          "method '" + m + "'");
  return 0;
}
