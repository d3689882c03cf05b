// The study's treatment of the peers: the ray-cast contracts (study/contract.hpp) on hand-derived
// rays and segments, the split of a wrong answer into conversion and algorithm
// (study/conversion.hpp), the rounding of the 24-bit runs and Bullet's received pose, ODE's
// trimesh collider on a triangle inside the cylinder, and the hunt finding a method that is wrong
// on generic inputs only (far from every degeneracy).
#define BOOST_TEST_MODULE study_peers
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "peers/peer_frame.hpp"
#include "study/contract.hpp"
#include "study/conversion.hpp"
#include "study/gap.hpp"
#include "study_internal.hpp"
#include "study_methods.hpp"

using namespace certcyl;
using namespace certcyl::study;

namespace {

// The cylinder of radius 1 from (0,0,0) to (0,0,2), after a ray's or segment's six numbers.
std::vector<double> with_unit_cylinder(std::vector<double> x) {
  x.insert(x.end(), {0, 0, 0, 0, 0, 2, 1});
  return x;
}

struct ContractCase {
  const char* name;
  Query query;
  std::vector<double> x;
  Answer solid, entry, hit;
};

}  // namespace

// Each answer below is read off the picture: the cylinder x^2 + y^2 <= 1, 0 <= z <= 2.
BOOST_AUTO_TEST_CASE(contracts_by_hand) {
  const Answer S = Answer::separated, T = Answer::touching, O = Answer::overlapping;
  const std::vector<ContractCase> cases{
      {"ray from the centre, radial", Query::ray_cylinder, with_unit_cylinder({0, 0, 1, 1, 0, 0}), O, S, O},
      {"ray from the centre, along the axis", Query::ray_cylinder, with_unit_cylinder({0, 0, 1, 0, 0, 1}), O, S, O},
      {"segment inside", Query::segment_cylinder, with_unit_cylinder({0, 0, 1, 0.5, 0, 1}), O, S, S},
      {"segment from inside to the wall", Query::segment_cylinder, with_unit_cylinder({0, 0, 1, 1, 0, 1}), O, S, O},
      {"segment from inside out", Query::segment_cylinder, with_unit_cylinder({0, 0, 1, 3, 0, 1}), O, S, O},
      {"ray from the wall, outward", Query::ray_cylinder, with_unit_cylinder({1, 0, 1, 1, 0, 0}), T, S, S},
      {"ray from the wall, inward", Query::ray_cylinder, with_unit_cylinder({1, 0, 1, -1, 0, 0}), O, S, O},
      {"ray from the wall, along it up to the rim", Query::ray_cylinder, with_unit_cylinder({1, 0, 1, 0, 0, 1}), T, S, T},
      {"ray from outside, through", Query::ray_cylinder, with_unit_cylinder({3, 0, 1, -1, 0, 0}), O, O, O},
      {"ray from outside, tangent", Query::ray_cylinder, with_unit_cylinder({3, 1, 1, -1, 0, 0}), T, T, T},
      {"ray from outside, away", Query::ray_cylinder, with_unit_cylinder({3, 0, 1, 1, 0, 0}), S, S, S},
      {"segment from outside, ending inside", Query::segment_cylinder, with_unit_cylinder({3, 0, 1, 0, 0, 1}), O, O, O},
      {"segment from outside, ending on the wall", Query::segment_cylinder, with_unit_cylinder({3, 0, 1, 1, 0, 1}), T, T, T},
      {"line through the centre", Query::line_cylinder, with_unit_cylinder({0, 0, 1, 1, 0, 0}), O, O, O},
  };
  for (const ContractCase& c : cases) {
    Instance inst;
    inst.query = c.query;
    inst.x = c.x;
    certify(inst);
    BOOST_TEST(inst.certified == c.solid, c.name);
    BOOST_TEST(certified_under(inst, Contract::solid) == c.solid, c.name);
    BOOST_TEST(certified_under(inst, Contract::surface_entry) == c.entry, c.name);
    BOOST_TEST(certified_under(inst, Contract::surface_hit) == c.hit, c.name);
    // The study's cheaper path (no gap) gives the same answers.
    BOOST_TEST(certified_answer(c.query, c.x, Contract::surface_entry) == c.entry, c.name);
    BOOST_TEST(certified_answer(c.query, c.x, Contract::surface_hit) == c.hit, c.name);
  }
}

BOOST_AUTO_TEST_CASE(error_causes_by_hand) {
  const MethodOutput says_apart = boolean_answer(false), says_meet = boolean_answer(true);
  const Answer S = Answer::separated, T = Answer::touching, O = Answer::overlapping, U = Answer::undecided;
  // Right answers have no cause.
  BOOST_TEST(error_cause(says_apart, S, std::nullopt) == ErrorCause::none);
  BOOST_TEST(error_cause(says_meet, O, S) == ErrorCause::none);
  // A method reading the input exactly: every wrong answer is the algorithm's.
  BOOST_TEST(error_cause(says_apart, O, std::nullopt) == ErrorCause::algorithm);
  // The rounded instance is separated: the method answered it right, the conversion is wrong.
  BOOST_TEST(error_cause(says_apart, T, S) == ErrorCause::conversion);
  BOOST_TEST(error_cause(says_meet, S, O) == ErrorCause::conversion);
  // The rounded instance meets as the original does: the method is wrong on it too.
  BOOST_TEST(error_cause(says_apart, O, T) == ErrorCause::algorithm);
  BOOST_TEST(error_cause(says_meet, S, S) == ErrorCause::algorithm);
  BOOST_TEST(error_cause(says_apart, O, U) == ErrorCause::unsplit);
  // Three-valued: original touching, rounded separated, the method says overlapping: both.
  BOOST_TEST(error_cause(three_valued(O), T, S) == ErrorCause::both);
  // A three-valued method's false positive is split as a Boolean answer: the rounding made the
  // instance touch, and the method says the sets meet (overlapping): conversion only.
  BOOST_TEST(error_cause(three_valued(O), S, T) == ErrorCause::conversion);
  // A class mismatch caused by the rounding alone.
  BOOST_TEST(error_cause(three_valued(O), T, O) == ErrorCause::conversion);
}

BOOST_AUTO_TEST_CASE(rounding_to_24_bits) {
  BOOST_TEST(*round_to_bits(1 + 0x1p-30, 24) == 1.0);
  BOOST_TEST(*round_to_bits(1 + 0x1p-23, 24) == 1 + 0x1p-23);
  // Ties to even: 1 + 2^-24 lies halfway between 1 and 1 + 2^-23.
  BOOST_TEST(*round_to_bits(1 + 0x1p-24, 24) == 1.0);
  BOOST_TEST(*round_to_bits(1 + 0x1p-23 + 0x1p-24, 24) == 1 + 0x1p-22);
  // A subnormal keeps 24 significant bits at its own exponent.
  BOOST_TEST(*round_to_bits(0x1.000001p-1060, 24) == 0x1p-1060);
  // The largest double rounds up to 2^1024: not a double.
  BOOST_TEST(!round_to_bits(0x1.fffffffffffffp+1023, 24));

  // A segment ending 2^-30 outside the wall is separated; at 24 bits its end lies on the wall.
  const std::vector<double> x = with_unit_cylinder({3, 0, 1, 1 + 0x1p-30, 0, 1});
  BOOST_TEST(certified_answer(Query::segment_cylinder, x, Contract::solid) == Answer::separated);
  const Conversion c = rounding_to_bits(24);
  BOOST_TEST(c.certified(Query::segment_cylinder, x, Contract::solid) == Answer::touching);
  // So a 24-bit method answering "they meet" is wrong by conversion, not by its algorithm.
  BOOST_TEST(error_cause(boolean_answer(true), Answer::separated, c.certified(Query::segment_cylinder, x, Contract::solid)) ==
             ErrorCause::conversion);

  // The study gives exactly the Gmpfr methods below 53 bits a conversion.
  study::Registry r = cli::all_methods_registry();
  int rounded = 0;
  for (const Method& m : r) {
    const bool narrow = m.nt == "gmpfr<24>" || m.nt == "float";
    BOOST_TEST(static_cast<bool>(m.conversion) == narrow, m.name());
    rounded += m.nt == "gmpfr<24>";
  }
  BOOST_TEST(rounded > 0);
}

BOOST_AUTO_TEST_CASE(received_pose_of_a_peer) {
  // An axis along a coordinate axis: an exact rotation (a signed permutation, determinant 1)
  // taking z to the axis, and a circular received cylinder equal to the input.
  for (int i = 0; i < 3; ++i) {
    for (bool negative : {false, true}) {
      const Eigen::Matrix3d R = cli::axis_rotation(i, negative);
      BOOST_TEST((R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() == 0.0);
      BOOST_TEST(R.determinant() == 1.0);
      Eigen::Vector3d e = Eigen::Vector3d::Zero();
      e[i] = negative ? -1 : 1;
      BOOST_TEST((R.col(2) - e).cwiseAbs().maxCoeff() == 0.0);
    }
  }
  const Cylinder<double> aligned{{1, 2, 3}, {1, 2, -5}, 0.75};
  const auto pose = cli::received_pose<float>(aligned);
  BOOST_TEST_REQUIRE(pose.has_value());
  const auto circular = cli::as_circular(*pose);
  BOOST_TEST_REQUIRE(circular.has_value());
  BOOST_TEST((circular->p0 == Point3<Rational>{Rational(1), Rational(2), Rational(3)}));
  BOOST_TEST((circular->p1 == Point3<Rational>{Rational(1), Rational(2), Rational(-5)}));
  BOOST_TEST(circular->radius == Rational(0.75));
  // A rotated axis: the float rotation is not exactly orthonormal, so the received solid is an
  // (oblique) elliptic cylinder and no circular one.
  const Cylinder<double> rotated{{0, 0, 0}, {1, 2, 3}, 0.5};
  const auto tilted = cli::received_pose<float>(rotated);
  BOOST_TEST_REQUIRE(tilted.has_value());
  BOOST_TEST(!cli::as_circular(*tilted).has_value());
  const EllipticCylinder<Rational> e = cli::as_elliptic(*tilted);
  BOOST_TEST(determinant(e.a, e.b, e.c) != Rational(0));
}

// ODE's cylinder-trimesh collider proves the overlap by separating axes, then makes contacts by
// clipping one line of the cylinder's wall (on the side of the deepest axis) against the
// triangle's prism when that axis is more than about 26 degrees from the cylinder's axis; a
// triangle that line misses gets no contact. A small tilted triangle at the centre of the
// cylinder is missed in both windings; the same triangle scaled up to cross the wall is found.
BOOST_AUTO_TEST_CASE(ode_trimesh_misses_a_triangle_inside) {
  study::Registry r;
  cli::register_peer_methods(r);
  const Method* ode_mesh = nullptr;
  for (const Method& m : r)
    if (m.name() == "ode_mesh/double") ode_mesh = &m;
  if (!ode_mesh) {
    BOOST_TEST_MESSAGE("ODE not built in: skipped");
    return;
  }
  // The cylinder of radius 1 from (0,0,-1) to (0,0,1); the triangle about its centre.
  const auto input = [](double s) {
    return std::vector<double>{-0.1 * s, -0.1 * s, 0.2 * s, 0.1 * s, -0.1 * s, -0.2 * s, 0, 0.1 * s, 0.05 * s, 0, 0, -1, 0, 0, 1, 1};
  };
  BOOST_TEST(certified_answer(Query::triangle_cylinder, input(1), Contract::solid) == Answer::overlapping);
  BOOST_TEST(judge(ode_mesh->run(input(1)), Answer::overlapping) == Outcome::false_negative);
  BOOST_TEST(judge(ode_mesh->run(input(30)), Answer::overlapping) == Outcome::agree);
}

// A method wrong only on triangles whose centroid lies deep in the cylinder (depth more than 1/8
// of the radius and height: no degeneracy near) is found by the hunt's samples of generic
// inputs, with a certified margin G of at least the centroid's depth; local moves within 2^-6
// of the degenerate configurations alone would not reach such an input.
BOOST_AUTO_TEST_CASE(hunt_finds_generic_misses) {
  const auto deep_centroid = [](const std::vector<double>& x) {
    const Triangle<Rational> T = triangle_at(exact(x));
    const Cylinder<Rational> C = cylinder_at(exact(x), 9);
    const Rational third(1, 3);
    const Point3<Rational> g{third * (T.v[0].x + T.v[1].x + T.v[2].x), third * (T.v[0].y + T.v[1].y + T.v[2].y),
                             third * (T.v[0].z + T.v[1].z + T.v[2].z)};
    return study::detail::circular_point_gap(g, C) > Rational(1, 8);
  };
  const auto run = [&](const std::vector<double>& x) {
    if (deep_centroid(x)) return boolean_answer(false);
    return boolean_answer(intersects(certified_answer(Query::triangle_cylinder, x, Contract::solid)));
  };
  const std::string line = cli::detail::hunt_worst("deep_miss", Query::triangle_cylinder, 1, 1000, run, {});
  const auto f = cli::detail::split_csv(line);
  BOOST_TEST_REQUIRE(f.size() == 11u, line);
  BOOST_TEST(f[4] == "1", line);
  BOOST_TEST(f[7] == "false_negative", line);
  BOOST_TEST(std::stod(f[8]) > 0.125, line);  // the certified lower bound of G
}
