// `certcyl scene FILE`: every touching or overlapping pair in a scene of cylinders (and
// triangles), certified, with a broad phase on safe bounding boxes.
//
// Scene file: {"cylinders": [{"name": "c1", <cylinder members>}, ...],
//              "triangles": [{"name": "t1", "vertices": [P, P, P]}, ...]}   ("triangles" optional)
// A missing name defaults to the entry's path ("cylinders[3]"). Output: one JSON line per pair
// that touches, overlaps or could not be decided, {"a": name, "b": name, <answer fields>}, in
// the order of the pairs' indices (cylinders first, then triangles). Triangle-triangle pairs
// are not examined.
#pragma once

#include <iosfwd>
#include <string>

namespace certcyl::cli {

// Returns 0 on success, 2 when the scene file is invalid (the message names the field), 1 on
// an I/O failure.
int run_scene(const std::string& path, std::ostream& out, unsigned threads, bool progress);

}  // namespace certcyl::cli
