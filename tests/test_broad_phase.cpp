// Safe bounding boxes and the candidate pairs of the broad phase.
#define BOOST_TEST_MODULE broad_phase
#include <boost/test/unit_test.hpp>

#include <random>

#include "certcyl/broad_phase.hpp"

using namespace certcyl;

BOOST_AUTO_TEST_CASE(axis_aligned_box_is_exact) {
  // Radius 2 around the z axis from z = -1 to z = 3: the box is [-2,2] x [-2,2] x [-1,3].
  const Box3 b = bounding_box(Cylinder<Rational>{{0, 0, -1}, {0, 0, 3}, 2});
  BOOST_TEST(b.lo[0] == -2.0);
  BOOST_TEST(b.hi[0] == 2.0);
  BOOST_TEST(b.lo[1] == -2.0);
  BOOST_TEST(b.hi[2] == 3.0);
  BOOST_TEST(b.lo[2] == -1.0);
}

BOOST_AUTO_TEST_CASE(box_contains_extreme_points_of_random_cylinders) {
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<int> coord(-1000, 1000), rad(1, 300);
  auto q = [&](int den) { return Rational(coord(rng), den); };
  for (int n = 0; n < 300; ++n) {
    Cylinder<Rational> c{{q(7), q(7), q(7)}, {q(3), q(3), q(3)}, Rational(rad(rng), 11)};
    if (c.p0 == c.p1) continue;
    const Box3 box = bounding_box(c);
    const Vec3<Rational> A = c.axis();
    const Rational AA = squared_length(A);
    for (std::size_t i = 0; i < 3; ++i) {
      for (int s : {-1, 1}) {
        // u: the direction in the plane perpendicular to A that moves coordinate i most.
        Vec3<Rational> e{0, 0, 0};
        e[i] = s;
        const Vec3<Rational> u = e - (dot(e, A) / AA) * A;
        if (squared_length(u) == 0) continue;
        // lambda <= r / |u|, as close as binary64 allows, checked exactly.
        Rational lambda(round_to_nearest<double>(c.radius) / std::sqrt(CGAL::to_double(squared_length(u))));
        while (lambda * lambda * squared_length(u) > c.radius * c.radius) lambda = lambda * Rational(999999, 1000000);
        for (const auto& end : {c.p0, c.p1}) {
          const Point3<Rational> x = end + lambda * u;  // on the rim circle, or just inside it
          BOOST_TEST_REQUIRE(box.contains(x));
        }
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(candidate_pairs_match_brute_force_on_closed_boxes) {
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<int> pos(0, 40), len(0, 6);  // small integers: many boxes share faces
  std::vector<Box3> boxes;
  for (int n = 0; n < 400; ++n) {
    Box3 b;
    for (int i = 0; i < 3; ++i) {
      b.lo[i] = pos(rng);
      b.hi[i] = b.lo[i] + len(rng);
    }
    boxes.push_back(b);
  }
  std::vector<std::pair<std::size_t, std::size_t>> expected;
  for (std::size_t i = 0; i < boxes.size(); ++i)
    for (std::size_t j = i + 1; j < boxes.size(); ++j) {
      bool overlap = true;
      for (int k = 0; k < 3; ++k) overlap = overlap && boxes[i].lo[k] <= boxes[j].hi[k] && boxes[j].lo[k] <= boxes[i].hi[k];
      if (overlap) expected.emplace_back(i, j);
    }
  const auto got = candidate_pairs(boxes);
  BOOST_TEST(got.size() == expected.size());
  BOOST_TEST((got == expected));
}
