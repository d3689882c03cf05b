// Helpers of the judge's command tests (test_judge, test_judge_maps): a scratch folder per test
// case, removed at the end, in which a shell command line runs with its output captured; a
// file's text; a text's non-empty lines; the occurrences of a string in a text. A test file
// takes them all with `using namespace judge_test;` (fs included).
#pragma once

#include <boost/test/unit_test.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

namespace judge_test {

namespace fs = std::filesystem;

inline std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

inline std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> v;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);)
    if (!l.empty()) v.push_back(l);
  return v;
}

// The occurrences of `what` in `text` (overlapping ones counted).
inline std::size_t occurrences(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

struct Run {
  int status = -1;
  std::string out, err;
};

// A scratch folder per test case, removed at the end.
struct Scratch {
  fs::path dir;
  Scratch() {
    dir = fs::temp_directory_path() / ("certcyl_judge_" + std::to_string(::getpid()) + "_" +
                                       boost::unit_test::framework::current_test_case().p_name.get());
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  ~Scratch() { fs::remove_all(dir); }
  std::string operator/(const std::string& name) const { return (dir / name).string(); }
  // Runs a shell command line in the folder; its output is also kept in out.txt and err.txt.
  Run run(const std::string& command) const {
    const std::string cmd = "cd '" + dir.string() + "' && { " + command + "; } > out.txt 2> err.txt";
    const int s = std::system(cmd.c_str());
    return {WIFEXITED(s) ? WEXITSTATUS(s) : -1, slurp(dir / "out.txt"), slurp(dir / "err.txt")};
  }
};

}  // namespace judge_test
