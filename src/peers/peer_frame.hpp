// The pose of a certcyl cylinder in a peer library's convention (a cylinder centred at the
// origin along z, given its radius and full length): the midpoint, the length |A| and a
// rotation taking z to A/|A| (computed in double; the peers round further as they store it).
#pragma once

#include <Eigen/Geometry>

#include <cmath>

#include "certcyl/primitives.hpp"

namespace certcyl::cli {

struct PeerPose {
  Eigen::Vector3d centre;
  Eigen::Matrix3d rotation;
  double length = 0;
};

inline PeerPose peer_pose(const Cylinder<double>& c) {
  const Eigen::Vector3d p0(c.p0.x, c.p0.y, c.p0.z), p1(c.p1.x, c.p1.y, c.p1.z);
  const Eigen::Vector3d A = p1 - p0;
  PeerPose pose;
  pose.centre = 0.5 * (p0 + p1);
  pose.length = A.norm();
  pose.rotation = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), A).toRotationMatrix();
  return pose;
}

}  // namespace certcyl::cli
