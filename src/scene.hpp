// `certcyl scene FILE`: every touching or overlapping pair in a scene of cylinders (and
// triangles), certified, with a broad phase on safe bounding boxes.
//
// Scene file: {"cylinders": [{"name": "c1", <cylinder members>}, ...],
//              "triangles": [{"name": "t1", "vertices": [P, P, P]}, ...]}   ("triangles" optional)
// A missing name defaults to the entry's path ("cylinders[3]"); names must be distinct. Output:
// one JSON line per pair that touches, overlaps or could not be decided, {"a": name, "b": name,
// <answer fields>}, a before b in the scene (cylinders first, then triangles), in the order the
// broad phase finds the pairs: deterministic, the same on every run and thread count.
// Triangle-triangle pairs are not examined.
//
// Streaming: the broad phase (CGAL::box_self_intersection_d on safe closed boxes) hands its
// candidate pairs over in chunks of at most kSceneChunk; each chunk goes through the narrow
// phase (the certified query on every pair, on `threads` threads) and its lines are written
// before the scan goes on. Memory is the scene (the solids, their boxes, CGAL's copy) plus one
// chunk of pairs and lines, whatever the number of pairs: a scene of 10,000 identical cylinders
// (5 * 10^7 overlapping pairs) runs in the memory of its 10,000 solids. SIGINT and SIGTERM end
// the scan after the chunk in progress, with every line of the pairs examined written (exit 128
// + the signal's number).
//
// The phases (each timed in SceneStats): read (parse the JSON file and the exact solids),
// boxes (a safe bounding box per solid, interval arithmetic), broad (the box intersection scan,
// without the chunks' narrow and write time), narrow (the certified queries and their lines),
// write (the lines to the output).
#pragma once

#include <nlohmann/json.hpp>

#include <cstddef>
#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

#include "certcyl/primitives.hpp"
#include "certcyl/rational.hpp"

namespace certcyl::cli {

struct SceneSolid {
  std::string name;
  bool is_cylinder = true;
  Cylinder<Rational> cylinder;
  Triangle<Rational> triangle;
};

// The solids of a scene document, cylinders first; throws InvalidInput naming the field.
std::vector<SceneSolid> read_scene(const nlohmann::json& scene);

struct SceneStats {
  std::size_t cylinders = 0, triangles = 0;
  std::size_t candidate_pairs = 0;  // pairs whose boxes meet (triangle-triangle pairs dropped)
  std::size_t separated = 0, touching = 0, overlapping = 0, undecided = 0;
  std::size_t max_pairs_held = 0;  // the most candidate pairs held at once (at most one chunk)
  unsigned threads = 1;
  // Wall-clock seconds per phase (read and write are filled by run_scene only).
  double read_s = 0, boxes_s = 0, broad_s = 0, narrow_s = 0, write_s = 0;
  // Of the narrow phase, seconds summed over the threads: in the certified queries, and in
  // turning their results into JSON lines.
  double query_thread_s = 0, format_thread_s = 0;

  // One JSON object: the counts, and the seconds per phase.
  nlohmann::ordered_json to_json() const;
};

// Candidate pairs held at once by the streaming scan.
inline constexpr std::size_t kSceneChunk = 16384;

// Streams the JSON line of every candidate pair that touches, overlaps or is undecided to
// `write`, chunk by chunk (header comment), and calls `chunk_written` (when given) after each
// chunk's lines, before the next chunk's queries; fills every field of `stats` except read_s.
// Returns 0, 1 when `write` or `chunk_written` returned false (the scan stops), or 128 + the
// signal's number when SIGINT or SIGTERM stopped it between chunks.
int stream_meeting_pairs(const std::vector<SceneSolid>& solids, unsigned threads, bool progress, SceneStats& stats,
                         const std::function<bool(const std::string&)>& write, std::size_t chunk_size = kSceneChunk,
                         const std::function<bool()>& chunk_written = {});

// All of them at once (for tests and small scenes).
std::vector<std::string> meeting_pairs(const std::vector<SceneSolid>& solids, unsigned threads, bool progress, SceneStats& stats);

// Returns 0 on success, 2 when the scene file is invalid (the message names the field), 1 on
// an I/O failure (a file that cannot be read, a write that failed, memory exhausted), 130 or 143
// when interrupted. Writes a one-line summary to `err`; with `stats`, also the SceneStats JSON
// object on one line, prefixed "certcyl scene stats: ".
int run_scene(const std::string& path, std::ostream& out, unsigned threads, bool progress, bool stats, std::ostream& err);
int run_scene(const std::string& path, std::ostream& out, unsigned threads, bool progress);

}  // namespace certcyl::cli
