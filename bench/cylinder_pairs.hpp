// bench/cylinder_pairs.hpp -- what the cylinder-pair benchmarks share: the random pairs'
// distribution (the tests'), and FCL's query on two cylinders (when FCL is installed).
#pragma once

#include <cmath>
#include <memory>
#include <random>

#include "../tests/test_cylinder_cylinder_cases.hpp"
#include "certcyl/primitives.hpp"

#ifdef CERTCYL_HAVE_FCL
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/narrowphase/collision.h>
#endif

namespace certcyl_bench {

using D3 = certcyl::Vec3<double>;

// The random pairs' distribution (tests/test_cylinder_cylinder_cases.hpp).
using cctest::random_cylinder;

#ifdef CERTCYL_HAVE_FCL
// Two fcl::Cylinderd placed like a and b (FCL's cylinders are centred, along z).
struct FclPair {
  std::shared_ptr<fcl::Cylinderd> a, b;
  fcl::Transform3d ta, tb;
};

inline FclPair to_fcl(const certcyl::Cylinder<double>& a, const certcyl::Cylinder<double>& b) {
  auto one = [](const certcyl::Cylinder<double>& c, std::shared_ptr<fcl::Cylinderd>& geom, fcl::Transform3d& tf) {
    const D3 A = c.p1 - c.p0, m = 0.5 * (c.p0 + c.p1);
    const double len = std::sqrt(dot(A, A));
    geom = std::make_shared<fcl::Cylinderd>(c.radius, len);
    tf = fcl::Transform3d::Identity();
    tf.linear() = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), Eigen::Vector3d(A.x, A.y, A.z)).toRotationMatrix();
    tf.translation() = Eigen::Vector3d(m.x, m.y, m.z);
  };
  FclPair f;
  one(a, f.a, f.ta);
  one(b, f.b, f.tb);
  return f;
}

// fcl::collide with its default GJK solver (libccd): whether FCL reports a collision.
inline bool fcl_collide(const FclPair& f) {
  fcl::CollisionRequestd request;
  fcl::CollisionResultd result;
  fcl::collide(f.a.get(), f.ta, f.b.get(), f.tb, request, result);
  return result.isCollision();
}
#endif

}  // namespace certcyl_bench
