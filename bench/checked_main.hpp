// Shared by the benchmarks whose answers are checked while they run (bench_cylinder_hard,
// bench_cylinder_wide_range, bench_line_cylinder, bench_triangle_cylinder): Google Benchmark's
// main, then a non-zero exit status when any answer failed its check (the smoke runs in the
// tests rely on it).
#pragma once

#include <benchmark/benchmark.h>

#include <cstdio>

namespace certcyl::bench {

// Runs the registered benchmarks; 1 if an argument was not recognised or `failures` > 0 after
// the run (then `what` is printed with the count on standard error).
inline int run_checked_benchmarks(int argc, char** argv, const int& failures, const char* what) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  if (failures > 0) std::fprintf(stderr, "%s: %d\n", what, failures);
  return failures > 0 ? 1 : 0;
}

}  // namespace certcyl::bench
