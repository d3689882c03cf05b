// The robustness study: `certcyl study` and `certcyl merge` (README, "Main job: the study").
#pragma once

#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

namespace certcyl::cli {

struct StudyOptions {
  std::string name;                  // results/<name>; default: the size
  std::string out_root = "results";
  // tiny | small | default | large | N: N instances per family and query, with the maps and the
  // hunt of the smallest preset holding at least N per family (large's beyond), 1000 N uniform.
  std::string size = "default";
  std::uint64_t seed = 1;
  unsigned threads = 2;
  std::string config_file;           // JSON; --size, --seed and --name given override its keys
  bool size_given = false, seed_given = false, name_given = false;  // on the command line
  int shard_index = 0, shard_count = 1;
  bool plots = true;
  bool progress = true;               // on standard error: a bar on a terminal, else plain lines
  double progress_seconds = 30;      // between two plain progress lines of a phase
  // Filled from the size and the configuration file.
  long per_family = 0;
  int map_cells = 0;                 // failure maps are map_cells x map_cells
  long map_step = 1;                 // ulps between neighbouring cells
  long hunt_evaluations = 0;         // per method
  long uniform_per_query = -1;       // the uniform sample's instances per query (study_uniform.cpp); -1: from the size
  std::vector<std::string> methods;  // substrings of method names to keep (empty: all)
  std::vector<std::string> families; // family names to keep (empty: all)
};

// Parses "i/n" (integers 0 <= i < n <= 100000); throws std::invalid_argument naming --shard.
void parse_shard(const std::string& s, int& index, int& count);

// Throws std::invalid_argument naming `key` unless `name` is one plain, visible folder name (not
// empty, no '/', not starting with '.'), so that results written under --out stay inside it.
void check_folder_name(const std::string& name, const std::string& key);

// "" when text is a decimal integer in [lo, hi] (digits only: no sign, base prefix or fraction),
// else "expected an integer in [lo, hi], got 'text'": the check of --seed and --threads.
std::string integer_error(const std::string& text, unsigned long long lo, unsigned long long hi);

// Fills the options from the configuration file and the size preset (an option given on the
// command line, size_given and the like, wins over the file's key) and checks every option
// and key before any work: its JSON type, its range (integers as JSON integers, never truncated
// or wrapped), the families (names of study::all_families()) and the method filters (each a
// substring of some name in method_names), a plain folder name (results stay inside --out).
// Throws std::invalid_argument naming the option or key and the value.
void configure_study(StudyOptions& o, const std::vector<std::string>& method_names);

// Runs the study; writes the results folder; returns the exit status.
int run_study(StudyOptions options, std::ostream& out);

// Merges the shards results/<name>/shard-*-of-*/ into results/<name>/ (the same outputs as an
// unsharded run of the same configuration and seed).
int run_merge(const std::string& dir, bool plots, std::ostream& out);

}  // namespace certcyl::cli
