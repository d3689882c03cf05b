// `certcyl scene` on a random scene of 100,000 cylinders (src/scene_generator.hpp, seed 1,
// about 8 box neighbours per cylinder, 2% of the cylinders in exactly touching pairs): every
// touching or overlapping pair, certified.
//
//   BM_scene_read/N            parse the scene JSON text and build the exact solids
//   BM_scene_pairs/N/T         the scene's pairs from the solids on T threads: safe boxes,
//                              CGAL::box_self_intersection_d, the certified narrow phase and
//                              the output lines (the code path of `certcyl scene` after the read)
//   BM_scene_command/N/T       `certcyl scene FILE` end to end (read, pairs, write to a null
//                              stream) on a temporary file
//
// One iteration takes seconds, so each runs once per repetition (Iterations(1), wall-clock
// time). Counters: candidate_pairs, touching, overlapping, undecided; pairs_per_s = candidate
// pairs per second of the whole run after the read; broad_share and narrow_share = the shares of
// that time in the broad phase (boxes and box intersection) and the narrow phase;
// query_share = the share of the narrow phase's thread-seconds in the certified queries (the
// rest formats the JSON lines of the meeting pairs).
#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <ostream>
#include <sstream>
#include <streambuf>

#include "certcyl/io/json_input.hpp"
#include "scene.hpp"
#include "scene_generator.hpp"

using namespace certcyl::cli;

namespace {

struct Scene {
  std::string text;
  std::vector<SceneSolid> solids;
};

const Scene& scene_of(std::size_t n) {
  static std::map<std::size_t, Scene> cache;
  auto it = cache.find(n);
  if (it == cache.end()) {
    SceneSpec spec;
    spec.cylinders = n;
    Scene s;
    s.text = generate_scene(spec).document.dump();
    s.solids = read_scene(nlohmann::json::parse(s.text));
    it = cache.emplace(n, std::move(s)).first;
  }
  return it->second;
}

void set_counters(benchmark::State& state, const SceneStats& s) {
  const double total = s.boxes_s + s.broad_s + s.narrow_s;
  state.counters["candidate_pairs"] = static_cast<double>(s.candidate_pairs);
  state.counters["touching"] = static_cast<double>(s.touching);
  state.counters["overlapping"] = static_cast<double>(s.overlapping);
  state.counters["undecided"] = static_cast<double>(s.undecided);
  state.counters["pairs_per_s"] = static_cast<double>(s.candidate_pairs) / total;
  state.counters["broad_share"] = (s.boxes_s + s.broad_s) / total;
  state.counters["narrow_share"] = s.narrow_s / total;
  state.counters["query_share"] = s.query_thread_s / (s.query_thread_s + s.format_thread_s);
}

void BM_scene_read(benchmark::State& state) {
  const Scene& scene = scene_of(static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(read_scene(nlohmann::json::parse(scene.text)));
  state.counters["cylinders"] = static_cast<double>(scene.solids.size());
}

void BM_scene_pairs(benchmark::State& state) {
  const Scene& scene = scene_of(static_cast<std::size_t>(state.range(0)));
  SceneStats stats;
  for (auto _ : state) {
    stats = SceneStats{};
    benchmark::DoNotOptimize(meeting_pairs(scene.solids, static_cast<unsigned>(state.range(1)), false, stats));
  }
  set_counters(state, stats);
}

class NullBuffer : public std::streambuf {
 protected:
  int overflow(int c) override { return c; }
  std::streamsize xsputn(const char*, std::streamsize n) override { return n; }
};

void BM_scene_command(benchmark::State& state) {
  const Scene& scene = scene_of(static_cast<std::size_t>(state.range(0)));
  const auto path = std::filesystem::temp_directory_path() / ("bench_scene_" + std::to_string(state.range(0)) + ".json");
  std::ofstream(path) << scene.text;
  NullBuffer null_buffer;
  std::ostream null_out(&null_buffer);
  for (auto _ : state) {
    std::ostringstream err;
    if (run_scene(path.string(), null_out, static_cast<unsigned>(state.range(1)), false, true, err) != 0) state.SkipWithError("scene failed");
  }
  std::filesystem::remove(path);
}

}  // namespace

BENCHMARK(BM_scene_read)->Arg(100000)->Unit(benchmark::kMillisecond)->Iterations(1)->Repetitions(2);
BENCHMARK(BM_scene_pairs)
    ->ArgsProduct({{100000}, {1, 2}})
    ->ArgNames({"n", "threads"})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1)
    ->Repetitions(3)
    ->UseRealTime();
BENCHMARK(BM_scene_command)
    ->ArgsProduct({{100000}, {1, 2}})
    ->ArgNames({"n", "threads"})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1)
    ->UseRealTime();

BENCHMARK_MAIN();
