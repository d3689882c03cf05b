#include "scene.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <exception>
#include <functional>
#include <atomic>
#include <chrono>
#include <fstream>
#include <iostream>
#include <mutex>
#include <optional>
#include <thread>
#include <unordered_map>

#include "certcyl/broad_phase.hpp"
#include "certcyl/certified/cylinder_cylinder.hpp"
#include "certcyl/certified/triangle_cylinder.hpp"
#include "certcyl/io/json_input.hpp"
#include "gmp_memory.hpp"
#include "interrupt.hpp"
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

// The path of solid k of the scene ("cylinders[3]", "triangles[0]"), cylinders first.
std::string solid_field(const std::vector<SceneSolid>& solids, std::size_t k) {
  const std::size_t cylinders = static_cast<std::size_t>(std::count_if(solids.begin(), solids.end(), [](const SceneSolid& s) { return s.is_cylinder; }));
  return k < cylinders ? index_field("cylinders", k) : index_field("triangles", k - cylinders);
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

std::vector<SceneSolid> read_scene(const json& scene) {
  if (!scene.is_object()) throw InvalidInput("", "a scene is a JSON object with \"cylinders\" and optionally \"triangles\"");
  for (auto it = scene.begin(); it != scene.end(); ++it)
    if (it.key() != "cylinders" && it.key() != "triangles")
      throw InvalidInput(it.key(), "unexpected member (a scene has \"cylinders\" and \"triangles\")");
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
      try {
        solids.push_back({name_of(entry, field), true, reader.cylinder(operand, field), {}});
      } catch (const InvalidInput& e) {
        // The cylinder reader lists its own members; a scene entry may also have a name.
        const std::string what = e.what();
        if (what.find("unexpected member") == std::string::npos && what.find("expected a cylinder") == std::string::npos) throw;
        throw InvalidInput("", what + "; a scene entry may also have \"name\"");
      }
    }
  }
  if (auto tris = scene.find("triangles"); tris != scene.end()) {
    if (!tris->is_array()) throw InvalidInput("triangles", "expected an array");
    for (std::size_t i = 0; i < tris->size(); ++i) {
      const std::string field = index_field("triangles", i);
      const json& entry = (*tris)[i];
      if (!entry.is_object()) throw InvalidInput(field, "expected an object {\"name\": ..., \"vertices\": [P, P, P]}");
      for (auto it = entry.begin(); it != entry.end(); ++it)
        if (it.key() != "name" && it.key() != "vertices")
          throw InvalidInput(join_field(field, it.key()), "unexpected member (a triangle has \"name\" and \"vertices\")");
      solids.push_back({name_of(entry, field), false, {},
                        reader.triangle(JsonReader::member(entry, field, "vertices"), join_field(field, "vertices"))});
    }
  }
  // Names identify the pairs in the output: they must be distinct.
  std::unordered_map<std::string, std::size_t> first;
  for (std::size_t k = 0; k < solids.size(); ++k) {
    const auto [it, fresh] = first.emplace(solids[k].name, k);
    if (!fresh)
      throw InvalidInput(solid_field(solids, k), "name \"" + solids[k].name + "\" is also the name of " + solid_field(solids, it->second));
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
          {"max_pairs_held", max_pairs_held},
          {"threads", threads},
          {"seconds", {{"read", read_s}, {"boxes", boxes_s}, {"broad", broad_s}, {"narrow", narrow_s}, {"write", write_s}}},
          {"narrow_thread_seconds", {{"query", query_thread_s}, {"format", format_thread_s}}}};
}

namespace {

// Thrown through the broad phase's callback to end a scan early.
struct ScanStopped {
  int status;
};

// The narrow phase's lines for one chunk: the JSON line of each meeting pair (empty for a
// separated one), in chunk order; when a query failed (std::bad_alloc, or GMP's or CGAL's
// exceptions), `failure` holds the exception of the first pair that failed, in chunk order,
// and only the lines before that pair are complete.
struct ChunkLines {
  std::vector<std::string> lines;
  std::size_t complete = 0;  // lines[0, complete) are final
  std::exception_ptr failure;
};

// The narrow phase on one chunk of candidate pairs: the certified query on each, on `threads`
// threads. A worker catches what its pair throws (an exception must not leave a thread: that
// ends the process) and the others then take no new pair. A pair during which an allocation of
// GMP failed (GmpMemoryScope: it went on from the emergency reserve, and a cylinder pair stopped
// at its next check) fails as std::bad_alloc.
ChunkLines narrow_phase(const std::vector<SceneSolid>& solids, const std::vector<std::pair<std::size_t, std::size_t>>& pairs,
                        unsigned threads, std::atomic<std::size_t>& done, SceneStats& stats) {
  using clock = std::chrono::steady_clock;
  ChunkLines out;
  std::vector<std::string>& lines = out.lines;
  lines.resize(pairs.size());
  out.complete = pairs.size();
  std::atomic<std::size_t> next{0};
  std::mutex mutex;
  auto work = [&] {
    double query_s = 0, format_s = 0;
    std::size_t n_touching = 0, n_overlapping = 0, n_undecided = 0;
    std::size_t k = next++;
    try {
      for (; k < pairs.size(); k = next++) {
        const SceneSolid& a = solids[pairs[k].first];
        const SceneSolid& b = solids[pairs[k].second];
        const auto q0 = clock::now();
        Answer verdict;
        std::optional<CylinderCylinderResult> cc;
        std::optional<TriangleCylinderResult> tc;
        {
          const GmpMemoryScope memory;
          if (a.is_cylinder && b.is_cylinder) {
            CylinderCylinderOptions options;
            options.stop = gmp_memory_stop;
            cc = certified_cylinder_cylinder(a.cylinder, b.cylinder, options);
            verdict = cc->answer;
          } else {
            const SceneSolid& tri = a.is_cylinder ? b : a;
            const SceneSolid& cyl = a.is_cylinder ? a : b;
            tc = certified_triangle_cylinder(tri.triangle, cyl.cylinder);
            verdict = tc->answer;
          }
          if (memory.event() != GmpMemoryEvent::none) throw std::bad_alloc();
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
    } catch (...) {
      std::lock_guard lock(mutex);
      if (k < out.complete) {
        out.complete = k;
        out.failure = std::current_exception();
      }
      next = pairs.size();  // the other workers finish their pair and take no other
    }
    std::lock_guard lock(mutex);
    stats.touching += n_touching, stats.overlapping += n_overlapping, stats.undecided += n_undecided;
    stats.query_thread_s += query_s;
    stats.format_thread_s += format_s;
  };
  std::vector<std::thread> pool;
  try {
    for (unsigned i = 1; i < threads && i < pairs.size(); ++i) pool.emplace_back(work);
  } catch (const std::exception&) {
    // No thread (or no memory) for another worker: the ones started, and this one, do the chunk.
  }
  work();
  for (auto& th : pool) th.join();
  return out;
}

}  // namespace

int stream_meeting_pairs(const std::vector<SceneSolid>& solids, unsigned threads, bool progress, SceneStats& stats,
                         const std::function<bool(const std::string&)>& write, std::size_t chunk_size,
                         const std::function<bool()>& chunk_written) {
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  threads = std::max(1u, threads);
  chunk_size = std::max<std::size_t>(1, chunk_size);
  stats.threads = threads;
  stats.cylinders = static_cast<std::size_t>(std::count_if(solids.begin(), solids.end(), [](const SceneSolid& s) { return s.is_cylinder; }));
  stats.triangles = solids.size() - stats.cylinders;

  auto t = clock::now();
  std::vector<Box3> boxes;
  boxes.reserve(solids.size());
  for (const SceneSolid& s : solids) boxes.push_back(s.is_cylinder ? bounding_box(s.cylinder) : bounding_box(s.triangle));
  stats.boxes_s = seconds_since(t);

  std::atomic<std::size_t> done{0};
  std::atomic<bool> finished{false};
  std::thread reporter;
  if (progress)
    reporter = std::thread([&] {
      while (!finished) {
        std::cerr << "\rcertcyl scene: " << done << " candidate pairs examined" << std::flush;
        std::this_thread::sleep_for(std::chrono::milliseconds(500));
      }
    });
  std::vector<std::pair<std::size_t, std::size_t>> chunk;
  chunk.reserve(chunk_size);
  double narrow_s = 0, write_s = 0;
  auto flush = [&] {
    stats.max_pairs_held = std::max(stats.max_pairs_held, chunk.size());
    auto n0 = clock::now();
    const ChunkLines result = narrow_phase(solids, chunk, threads, done, stats);
    auto w0 = clock::now();
    narrow_s += std::chrono::duration<double>(w0 - n0).count();
    // The lines before a failed pair are written, in order, before its exception goes on.
    for (std::size_t k = 0; k < result.complete; ++k)
      if (!result.lines[k].empty() && !write(result.lines[k])) throw ScanStopped{1};
    if (chunk_written && !chunk_written()) throw ScanStopped{1};
    write_s += seconds_since(w0);
    if (result.failure) std::rethrow_exception(result.failure);
    chunk.clear();
    // A signal ends the scan here, between chunks: every line of the pairs examined is out.
    if (const int sig = interrupt_signal()) throw ScanStopped{128 + sig};
  };
  int status = 0;
  std::exception_ptr failure;
  try {
    for_each_candidate_pair(boxes, [&](std::size_t i, std::size_t j) {
      // Triangle-triangle pairs are not a cylinder query.
      if (!solids[i].is_cylinder && !solids[j].is_cylinder) return;
      ++stats.candidate_pairs;
      chunk.emplace_back(i, j);
      if (chunk.size() == chunk_size) flush();
    });
    flush();
  } catch (const ScanStopped& stop) {
    status = stop.status;
  } catch (...) {
    failure = std::current_exception();  // after the progress thread is joined
  }
  finished = true;
  if (reporter.joinable()) {
    reporter.join();
    std::cerr << "\rcertcyl scene: " << done << " candidate pairs examined\n";
  }
  if (failure) std::rethrow_exception(failure);
  stats.narrow_s = narrow_s;
  stats.write_s = write_s;
  stats.broad_s = std::max(0.0, seconds_since(start) - stats.boxes_s - narrow_s - write_s);
  stats.separated = done - stats.touching - stats.overlapping - stats.undecided;
  return status;
}

std::vector<std::string> meeting_pairs(const std::vector<SceneSolid>& solids, unsigned threads, bool progress, SceneStats& stats) {
  std::vector<std::string> lines;
  stream_meeting_pairs(solids, threads, progress, stats, [&](const std::string& l) {
    lines.push_back(l);
    return true;
  });
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
    err << "certcyl scene: cannot open '" << path << "': " << std::strerror(errno) << "\n";
    return 1;
  }
  std::vector<SceneSolid> solids;
  try {
    solids = read_scene(parse_strict_json(file));
  } catch (const json::exception& e) {
    err << "certcyl scene: " << path << ": malformed JSON: " << e.what() << "\n";
    return 2;
  } catch (const InvalidInput& e) {
    err << "certcyl scene: " << path << ": " << e.what() << "\n";
    return 2;
  } catch (const std::bad_alloc&) {
    err << "certcyl scene: " << path << ": out of memory reading the scene\n";
    return 1;
  } catch (const std::ios_base::failure& e) {
    // The file opened but cannot be read (a directory, a device error).
    std::string reason = e.what();
    if (auto colon = reason.rfind(": "); colon != std::string::npos) reason.erase(0, colon + 2);
    err << "certcyl scene: read error: '" << path << "': " << reason << "\n";
    return 1;
  }
  if (file.bad()) {
    err << "certcyl scene: " << path << ": read error\n";
    return 1;
  }
  SceneStats stats;
  stats.read_s = seconds_since(t);

  int status = 0;
  try {
    // Each chunk's lines are flushed before the next chunk's queries: whenever GMP may end the
    // process (gmp_memory.hpp), what was written is complete lines.
    status = stream_meeting_pairs(
        solids, threads, progress, stats,
        [&](const std::string& l) {
          out << l << '\n';
          return static_cast<bool>(out);
        },
        kSceneChunk, [&] { return static_cast<bool>(out.flush()); });
  } catch (const std::bad_alloc&) {
    out.flush();
    err << "certcyl scene: out of memory in the scan; the lines of the pairs examined before are written\n";
    return 1;
  } catch (const std::exception& e) {
    out.flush();
    err << "certcyl scene: internal error in the scan: " << e.what() << "; the lines of the pairs examined before are written\n";
    return 1;
  }
  out.flush();
  if (!out) {
    err << "certcyl scene: error writing standard output\n";
    return 1;
  }
  err << "certcyl scene: " << stats.cylinders << " cylinders, " << stats.triangles << " triangles, " << stats.candidate_pairs
      << " candidate pairs: " << stats.touching << " touching, " << stats.overlapping << " overlapping, " << stats.undecided
      << " undecided; read " << stats.read_s << " s, broad phase " << stats.boxes_s + stats.broad_s << " s, narrow phase " << stats.narrow_s
      << " s" << (status > 128 ? " (interrupted: the pairs examined so far)" : "") << "\n";
  if (want_stats) err << "certcyl scene stats: " << stats.to_json().dump() << '\n';
  return status;
}

}  // namespace certcyl::cli
