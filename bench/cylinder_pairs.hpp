// bench/cylinder_pairs.hpp -- what the cylinder-pair benchmarks share: the random pairs'
// distribution, and FCL's query on two cylinders (when FCL is installed).
#pragma once

#include <cmath>
#include <memory>
#include <random>

#include "certcyl/primitives.hpp"

#ifdef CERTCYL_HAVE_FCL
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/narrowphase/collision.h>
#endif

namespace certcyl_bench {

using D3 = certcyl::Vec3<double>;

// Midpoint uniform in [-1, 1]^3, axis direction uniform, length in [0.2, 2], radius in
// [0.05, 0.5] (binary64 values).
inline certcyl::Cylinder<double> random_cylinder(std::mt19937_64& g) {
  std::uniform_real_distribution<double> u(-1, 1), len(0.2, 2), rad(0.05, 0.5);
  D3 w;
  double n2;
  do {
    w = {u(g), u(g), u(g)};
    n2 = dot(w, w);
  } while (n2 < 0.01 || n2 > 1);
  const double h = len(g) / (2 * std::sqrt(n2));
  const D3 c{u(g), u(g), u(g)};
  return {c - h * w, c + h * w, rad(g)};
}

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
