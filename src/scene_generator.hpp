// A seeded random scene for `certcyl scene` (`certcyl make-scene`, bench/bench_scene.cpp).
//
// Random cylinders: centre uniform in the cube [0, S]^3, axis direction uniform on the sphere,
// length uniform in [1/2, 3/2], radius uniform in [1/20, 3/20], endpoints p0, p1 = centre -+
// length/2 * direction rounded to binary64. The side S = cbrt(n * 2.1 / neighbours) is chosen
// so that a cylinder's bounding box meets about `neighbours` others (2.1 was measured: the
// mean count is 2 * candidate pairs / n), so there are many candidate pairs, a good share of
// which really meet.
//
// Exactly touching pairs: a share `touching_share` of the cylinders comes in pairs built to
// touch, axis-parallel, with dyadic coordinates (multiples of 2^-10) so every coordinate and
// every sum below is exact in binary64. The host has axis e_a, radius r1 and half-length h1;
// the partner, radius r2:
//   walls    parallel, its axis moved by r1 + r2 along e_b (b != a): the walls touch along a
//            segment;
//   caps     coaxial up to a shift of less than r1 + r2 across the axis, its p0 the host's p1:
//            the caps touch on a region of the common cap plane;
//   crossing along e_b, its axis at distance r1 + r2 along e_c across the host's middle: the
//            walls touch at one point;
//   capwall  along e_c, its p0 on the host's wall line at distance r1 along e_c: its cap disk
//            touches the host's wall along a segment.
// Their names are "<kind><j>a" (the host) and "<kind><j>b" (the partner); random cylinders
// are "c<i>". The pairs are placed at random in the cube like the others (and may also meet
// random cylinders).
#pragma once

#include <nlohmann/json.hpp>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <string>
#include <utility>
#include <vector>

namespace certcyl::cli {

struct SceneSpec {
  std::size_t cylinders = 100000;
  std::uint64_t seed = 1;
  double neighbours = 8;         // mean number of other boxes a cylinder's box meets (target)
  double touching_share = 0.02;  // share of the cylinders in exactly touching pairs
};

struct GeneratedScene {
  nlohmann::ordered_json document;  // {"cylinders": [{"name", "p0", "p1", "radius"}, ...]}
  // The pairs built to touch (indices into "cylinders", smaller first), by construction.
  std::vector<std::pair<std::size_t, std::size_t>> touching;
  double side = 0;  // S
};

// The whole scene in memory (tests, benchmarks).
GeneratedScene generate_scene(const SceneSpec& spec);

// The same cylinders, in the same order, passed one at a time to `emit` as they are generated
// (emit returns false to stop); the touching pairs are appended to `touching` when it is not
// null. Returns the side S. Memory is that of one cylinder, whatever spec.cylinders.
double for_each_scene_cylinder(const SceneSpec& spec, const std::function<bool(const nlohmann::ordered_json&)>& emit,
                               std::vector<std::pair<std::size_t, std::size_t>>* touching);

// `certcyl make-scene`: writes generate_scene(spec).document.dump() and a newline to `out`,
// byte for byte, as the cylinders are generated: memory is that of one cylinder and the
// stream's buffer, whatever spec.cylinders. Stops at the first failed write; returns whether
// every write succeeded.
bool write_scene(const SceneSpec& spec, std::ostream& out);

}  // namespace certcyl::cli
