// `certcyl scene FILE`: every touching or overlapping pair in a scene of cylinders (and
// triangles), certified, with a broad phase on safe bounding boxes.
//
// Scene file: {"cylinders": [{"name": "c1", <cylinder members>}, ...],
//              "triangles": [{"name": "t1", "vertices": [P, P, P]}, ...]}   ("triangles" optional)
// A missing name defaults to the entry's path ("cylinders[3]"). Output: one JSON line per pair
// that touches, overlaps or could not be decided, {"a": name, "b": name, <answer fields>}, in
// the order of the pairs' indices (cylinders first, then triangles). Triangle-triangle pairs
// are not examined.
//
// The phases (each timed in SceneStats): read (parse the JSON file and the exact solids),
// boxes (a safe bounding box per solid, interval arithmetic), broad (CGAL::box_self_intersection_d
// on the closed boxes, the candidate pairs sorted), narrow (the certified query on every
// candidate pair and its JSON line, on `threads` threads), write (the lines to the output).
#pragma once

#include <nlohmann/json.hpp>

#include <cstddef>
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
  unsigned threads = 1;
  // Wall-clock seconds per phase (read and write are filled by run_scene only).
  double read_s = 0, boxes_s = 0, broad_s = 0, narrow_s = 0, write_s = 0;
  // Of the narrow phase, seconds summed over the threads: in the certified queries, and in
  // turning their results into JSON lines.
  double query_thread_s = 0, format_thread_s = 0;

  // One JSON object: the counts, and the seconds per phase.
  nlohmann::ordered_json to_json() const;
};

// The JSON line of every candidate pair that touches, overlaps or is undecided, in pair order;
// fills every field of `stats` except read_s and write_s.
std::vector<std::string> meeting_pairs(const std::vector<SceneSolid>& solids, unsigned threads, bool progress, SceneStats& stats);

// Returns 0 on success, 2 when the scene file is invalid (the message names the field), 1 on
// an I/O failure. Writes a one-line summary to `err`; with `stats`, also the SceneStats JSON
// object on one line, prefixed "certcyl scene stats: ".
int run_scene(const std::string& path, std::ostream& out, unsigned threads, bool progress, bool stats, std::ostream& err);
int run_scene(const std::string& path, std::ostream& out, unsigned threads, bool progress);

}  // namespace certcyl::cli
