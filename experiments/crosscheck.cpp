// The cross-check driver: random and degenerate cases for every certified query, each answer
// re-checked exactly through an independent path (fuzz/recheck.hpp) and compared across exactly
// equivalent inputs (fuzz/crosscheck_cases.hpp has the cases and the invariances).
//
//   crosscheck [--cases N] [--seed S] [--query line|triangle|cylinder|all]
// N cases per query (default 1,000,000). Prints cases, re-checked answers, wrong answers and
// crashes per query; exits 1 if any answer was wrong or any query threw.
#include <chrono>
#include <cstdlib>
#include <iostream>
#include <string>

#include "../fuzz/crosscheck_cases.hpp"

int main(int argc, char** argv) {
  std::uint64_t cases = 1000000, seed = 1;
  std::string query = "all";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if ((a == "--cases" || a == "--seed" || a == "--query") && i + 1 < argc) {
      const std::string v = argv[++i];
      if (a == "--cases") cases = std::stoull(v);
      else if (a == "--seed") seed = std::stoull(v);
      else query = v;
    } else {
      std::cerr << "usage: crosscheck [--cases N] [--seed S] [--query line|triangle|cylinder|all]\n";
      return 2;
    }
  }
  bool bad = false;
  const auto run = [&](const std::string& name, auto check, std::uint64_t offset) {
    if (query != "all" && query != name) return;
    const auto start = std::chrono::steady_clock::now();
    certcyl::crosscheck::Stats s;
    check(cases, seed + offset, s);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    certcyl::crosscheck::print(std::cout, name, s);
    std::cout << "  seed " << seed + offset << ", " << seconds << " s\n" << std::flush;
    bad = bad || s.wrong != 0 || s.crashes != 0;
  };
  run("line", certcyl::crosscheck::check_lines, 0);
  run("triangle", certcyl::crosscheck::check_triangles, 1);
  run("cylinder", certcyl::crosscheck::check_cylinder_pairs, 2);
  return bad ? 1 : 0;
}
