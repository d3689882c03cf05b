// certcyl/broad_phase.hpp -- safe bounding boxes and candidate pairs for scenes of many solids.
//
// `bounding_box` gives an axis-aligned box of binary64 bounds that is guaranteed to contain the
// exact solid: it is evaluated in interval arithmetic from the exact input, and each bound is
// the outward end of its interval. For a cylinder with axis A = p1 - p0 and radius r, the
// extent around the axis segment along coordinate i is r sqrt(A_j^2 + A_k^2) / |A| ({i,j,k} a
// permutation), the half-width of the rim circles' shadow on that coordinate.
//
// `for_each_candidate_pair` (streaming) and `candidate_pairs` (all, sorted) run
// CGAL::box_self_intersection_d on closed boxes, so two solids that merely touch are never
// dropped: every pair of solids that share a point is reported (and more; the narrow phase
// decides).
#pragma once

#include <CGAL/Box_intersection_d/Box_with_handle_d.h>
#include <CGAL/Box_intersection_d/Box_d.h>
#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <array>
#include <utility>
#include <vector>

#include "certcyl/number_traits.hpp"
#include "certcyl/primitives.hpp"

namespace certcyl {

// An axis-aligned box [lo[i], hi[i]], i = 0..2, in binary64.
struct Box3 {
  std::array<double, 3> lo, hi;

  bool contains(const Point3<Rational>& x) const {
    for (std::size_t i = 0; i < 3; ++i)
      if (x[i] < Rational(lo[i]) || Rational(hi[i]) < x[i]) return false;
    return true;
  }
};

inline Box3 bounding_box(const Cylinder<Rational>& c) {
  NumberScope<Interval> upward;
  const auto p0 = convert<Interval>(c.p0), p1 = convert<Interval>(c.p1);
  const Interval r = nt::from_rational<Interval>(c.radius);
  const Vec3<Interval> A = p1 - p0;
  const Interval length = CGAL::sqrt(squared_length(A));
  Box3 box;
  for (std::size_t i = 0; i < 3; ++i) {
    const std::size_t j = (i + 1) % 3, k = (i + 2) % 3;
    const Interval extent = r * CGAL::sqrt(CGAL::square(A[j]) + CGAL::square(A[k])) / length;
    box.lo[i] = (CGAL::min(p0[i], p1[i]) - extent).inf();
    box.hi[i] = (CGAL::max(p0[i], p1[i]) + extent).sup();
  }
  return box;
}

inline Box3 bounding_box(const Triangle<Rational>& t) {
  Box3 box;
  for (std::size_t i = 0; i < 3; ++i) {
    box.lo[i] = enclose(std::min({t.v[0][i], t.v[1][i], t.v[2][i]})).first;
    box.hi[i] = enclose(std::max({t.v[0][i], t.v[1][i], t.v[2][i]})).second;
  }
  return box;
}

// Calls report(i, j), i < j, once for each pair of boxes that intersect as closed boxes, in the
// order CGAL's algorithm finds them (deterministic: its random splits use a fixed seed). Memory
// is linear in the number of boxes, whatever the number of pairs.
template <class Report>
void for_each_candidate_pair(const std::vector<Box3>& boxes, Report&& report) {
  using CgalBox = CGAL::Box_intersection_d::Box_d<double, 3, CGAL::Box_intersection_d::ID_EXPLICIT>;
  std::vector<CgalBox> cgal_boxes;
  cgal_boxes.reserve(boxes.size());
  for (Box3 b : boxes) cgal_boxes.emplace_back(b.lo.data(), b.hi.data());
  // ID_EXPLICIT numbers the boxes in construction order; map ids back to indices.
  const std::size_t first_id = cgal_boxes.empty() ? 0 : cgal_boxes.front().id();
  CGAL::box_self_intersection_d(
      cgal_boxes.begin(), cgal_boxes.end(),
      [&](const CgalBox& a, const CgalBox& b) {
        std::size_t i = a.id() - first_id, j = b.id() - first_id;
        if (i > j) std::swap(i, j);
        report(i, j);
      },
      std::ptrdiff_t(10), CGAL::Box_intersection_d::CLOSED);
}

// Index pairs (i < j) of boxes that intersect as closed boxes, sorted.
inline std::vector<std::pair<std::size_t, std::size_t>> candidate_pairs(const std::vector<Box3>& boxes) {
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for_each_candidate_pair(boxes, [&](std::size_t i, std::size_t j) { pairs.emplace_back(i, j); });
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

}  // namespace certcyl
