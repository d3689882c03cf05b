#include "scene.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <fstream>
#include <iostream>
#include <mutex>
#include <optional>
#include <thread>

#include "certcyl/broad_phase.hpp"
#include "certcyl/certified/cylinder_cylinder.hpp"
#include "certcyl/certified/triangle_cylinder.hpp"
#include "certcyl/io/json_input.hpp"
#include "query_cylinder.hpp"
#include "query_support.hpp"
#include "query_triangle.hpp"

namespace certcyl::cli {

namespace {

// Reads a named solid: the object's "name" (optional) and its operand members.
std::string name_of(const json& entry, const std::string& field) {
  auto it = entry.find("name");
  if (it == entry.end()) return field;
  if (!it->is_string()) throw InvalidInput(join_field(field, "name"), "expected a string");
  return it->get<std::string>();
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

std::vector<SceneSolid> read_scene(const json& scene) {
  if (!scene.is_object()) throw InvalidInput("", "a scene is a JSON object with \"cylinders\" and optionally \"triangles\"");
  for (auto it = scene.begin(); it != scene.end(); ++it)
    if (it.key() != "cylinders" && it.key() != "triangles") throw InvalidInput(it.key(), "unexpected member");
  JsonReader reader;
  std::vector<SceneSolid> solids;
  if (auto cyls = scene.find("cylinders"); cyls != scene.end()) {
    if (!cyls->is_array()) throw InvalidInput("cylinders", "expected an array");
    solids.reserve(cyls->size());
    for (std::size_t i = 0; i < cyls->size(); ++i) {
      const std::string field = index_field("cylinders", i);
      const json& entry = (*cyls)[i];
      if (!entry.is_object()) throw InvalidInput(field, "expected an object");
      json operand = entry;
      operand.erase("name");
      solids.push_back({name_of(entry, field), true, reader.cylinder(operand, field), {}});
    }
  }
  if (auto tris = scene.find("triangles"); tris != scene.end()) {
    if (!tris->is_array()) throw InvalidInput("triangles", "expected an array");
    for (std::size_t i = 0; i < tris->size(); ++i) {
      const std::string field = index_field("triangles", i);
      const json& entry = (*tris)[i];
      if (!entry.is_object()) throw InvalidInput(field, "expected an object {\"name\": ..., \"vertices\": [P, P, P]}");
      for (auto it = entry.begin(); it != entry.end(); ++it)
        if (it.key() != "name" && it.key() != "vertices") throw InvalidInput(join_field(field, it.key()), "unexpected member");
      solids.push_back({name_of(entry, field), false, {},
                        reader.triangle(JsonReader::member(entry, field, "vertices"), join_field(field, "vertices"))});
    }
  }
  return solids;
}

nlohmann::ordered_json SceneStats::to_json() const {
  return {{"cylinders", cylinders},
          {"triangles", triangles},
          {"candidate_pairs", candidate_pairs},
          {"separated", separated},
          {"touching", touching},
          {"overlapping", overlapping},
          {"undecided", undecided},
          {"threads", threads},
          {"seconds", {{"read", read_s}, {"boxes", boxes_s}, {"broad", broad_s}, {"narrow", narrow_s}, {"write", write_s}}},
          {"narrow_thread_seconds", {{"query", query_thread_s}, {"format", format_thread_s}}}};
}

std::vector<std::string> meeting_pairs(const std::vector<SceneSolid>& solids, unsigned threads, bool progress, SceneStats& stats) {
  using clock = std::chrono::steady_clock;
  threads = std::max(1u, threads);
  stats.threads = threads;
  stats.cylinders = static_cast<std::size_t>(std::count_if(solids.begin(), solids.end(), [](const SceneSolid& s) { return s.is_cylinder; }));
  stats.triangles = solids.size() - stats.cylinders;

  auto t = clock::now();
  std::vector<Box3> boxes;
  boxes.reserve(solids.size());
  for (const SceneSolid& s : solids) boxes.push_back(s.is_cylinder ? bounding_box(s.cylinder) : bounding_box(s.triangle));
  stats.boxes_s = seconds_since(t);

  t = clock::now();
  auto pairs = candidate_pairs(boxes);
  // Triangle-triangle pairs are not a cylinder query.
  std::erase_if(pairs, [&](const auto& p) { return !solids[p.first].is_cylinder && !solids[p.second].is_cylinder; });
  stats.broad_s = seconds_since(t);
  stats.candidate_pairs = pairs.size();

  t = clock::now();
  std::vector<std::string> lines(pairs.size());
  std::atomic<std::size_t> next{0}, done{0};
  std::atomic<std::size_t> touching{0}, overlapping{0}, undecided{0};
  std::mutex time_mutex;
  auto work = [&] {
    double query_s = 0, format_s = 0;
    std::size_t n_touching = 0, n_overlapping = 0, n_undecided = 0;
    for (std::size_t k = next++; k < pairs.size(); k = next++) {
      const SceneSolid& a = solids[pairs[k].first];
      const SceneSolid& b = solids[pairs[k].second];
      const auto q0 = clock::now();
      Answer verdict;
      std::optional<CylinderCylinderResult> cc;
      std::optional<TriangleCylinderResult> tc;
      if (a.is_cylinder && b.is_cylinder) {
        cc = certified_cylinder_cylinder(a.cylinder, b.cylinder, {});
        verdict = cc->answer;
      } else {
        const SceneSolid& tri = a.is_cylinder ? b : a;
        const SceneSolid& cyl = a.is_cylinder ? a : b;
        tc = certified_triangle_cylinder(tri.triangle, cyl.cylinder);
        verdict = tc->answer;
      }
      const auto q1 = clock::now();
      if (verdict != Answer::separated) {
        const ojson answer = cc ? cylinder_cylinder_json(*cc) : triangle_cylinder_json(*tc);
        ojson line{{"a", a.name}, {"b", b.name}};
        for (auto it = answer.begin(); it != answer.end(); ++it) line[it.key()] = it.value();
        lines[k] = line.dump();
        n_touching += verdict == Answer::touching;
        n_overlapping += verdict == Answer::overlapping;
        n_undecided += verdict == Answer::undecided;
      }
      query_s += std::chrono::duration<double>(q1 - q0).count();
      format_s += seconds_since(q1);
      ++done;
    }
    touching += n_touching, overlapping += n_overlapping, undecided += n_undecided;
    std::lock_guard lock(time_mutex);
    stats.query_thread_s += query_s;
    stats.format_thread_s += format_s;
  };
  std::vector<std::thread> pool;
  for (unsigned i = 1; i < threads; ++i) pool.emplace_back(work);
  if (progress) {
    std::thread reporter([&] {
      while (done < pairs.size()) {
        std::cerr << "\rcertcyl scene: " << done << "/" << pairs.size() << " candidate pairs" << std::flush;
        std::this_thread::sleep_for(std::chrono::milliseconds(500));
      }
    });
    work();
    for (auto& th : pool) th.join();
    reporter.join();
    std::cerr << "\rcertcyl scene: " << pairs.size() << "/" << pairs.size() << " candidate pairs\n";
  } else {
    work();
    for (auto& th : pool) th.join();
  }
  stats.narrow_s = seconds_since(t);
  stats.touching = touching, stats.overlapping = overlapping, stats.undecided = undecided;
  stats.separated = pairs.size() - stats.touching - stats.overlapping - stats.undecided;
  return lines;
}

int run_scene(const std::string& path, std::ostream& out, unsigned threads, bool progress) {
  return run_scene(path, out, threads, progress, false, std::cerr);
}

int run_scene(const std::string& path, std::ostream& out, unsigned threads, bool progress, bool want_stats, std::ostream& err) {
  using clock = std::chrono::steady_clock;
  auto t = clock::now();
  std::ifstream file(path);
  if (!file) {
    err << "certcyl scene: cannot open '" << path << "'\n";
    return 1;
  }
  std::vector<SceneSolid> solids;
  try {
    solids = read_scene(json::parse(file));
  } catch (const json::exception& e) {
    err << "certcyl scene: " << path << ": malformed JSON: " << e.what() << "\n";
    return 2;
  } catch (const InvalidInput& e) {
    err << "certcyl scene: " << path << ": " << e.what() << "\n";
    return 2;
  }
  SceneStats stats;
  stats.read_s = seconds_since(t);

  const std::vector<std::string> lines = meeting_pairs(solids, threads, progress, stats);

  t = clock::now();
  for (const auto& l : lines)
    if (!l.empty()) out << l << '\n';
  out.flush();
  stats.write_s = seconds_since(t);
  err << "certcyl scene: " << stats.cylinders << " cylinders, " << stats.triangles << " triangles, " << stats.candidate_pairs
      << " candidate pairs: " << stats.touching << " touching, " << stats.overlapping << " overlapping, " << stats.undecided
      << " undecided; read " << stats.read_s << " s, broad phase " << stats.boxes_s + stats.broad_s << " s, narrow phase " << stats.narrow_s
      << " s\n";
  if (want_stats) err << "certcyl scene stats: " << stats.to_json().dump() << '\n';
  if (!out) {
    err << "certcyl scene: error writing standard output\n";
    return 1;
  }
  return 0;
}

}  // namespace certcyl::cli
