// The pose of a certcyl cylinder in a peer library's convention (a cylinder centred at the
// origin along z, given its radius and full length): the midpoint, the length |A| and a
// rotation taking z to A/|A| (computed in double; the peers round further as they store it).
// An axis along a coordinate axis gets the exact signed permutation a user would write (Eigen's
// FromTwoVectors leaves entries of 2^-52 there); any other axis Eigen's rotation.
//
// received_pose: the same pose exactly as a peer storing scalars of type S receives it (each
// number rounded to S), as rationals; and the solid it then describes,
//   { centre + R (u, v, w) : u^2 + v^2 <= radius^2, |w| <= half },
// an elliptic cylinder (oblique when the rounded R is not orthogonal), which is a circular
// cylinder when R is exactly orthonormal (R^T R = I, checked in rational arithmetic).
#pragma once

#include <Eigen/Geometry>

#include <array>
#include <cmath>
#include <optional>

#include "certcyl/primitives.hpp"

namespace certcyl::cli {

struct PeerPose {
  Eigen::Vector3d centre;
  Eigen::Matrix3d rotation;
  double length = 0;
};

// The rotation taking z to the unit vector e_i (i = 0, 1, 2) or to -e_i, exactly (a rotation by a
// right angle about a coordinate axis, or by a half turn about x for -z).
inline Eigen::Matrix3d axis_rotation(int i, bool negative) {
  Eigen::Matrix3d R;
  const double s = negative ? -1 : 1;
  switch (i) {
    case 0: R << 0, 0, s, 0, 1, 0, -s, 0, 0; break;    // columns (0,0,-s), (0,1,0), (s,0,0)
    case 1: R << 1, 0, 0, 0, 0, s, 0, -s, 0; break;    // columns (1,0,0), (0,0,-s), (0,s,0)
    default: R << 1, 0, 0, 0, s, 0, 0, 0, s; break;    // columns (1,0,0), (0,s,0), (0,0,s)
  }
  return R;
}

inline PeerPose peer_pose(const Cylinder<double>& c) {
  const Eigen::Vector3d p0(c.p0.x, c.p0.y, c.p0.z), p1(c.p1.x, c.p1.y, c.p1.z);
  const Eigen::Vector3d A = p1 - p0;
  PeerPose pose;
  pose.centre = 0.5 * (p0 + p1);
  pose.length = A.norm();
  int nonzero = 0, axis = 0;
  for (int i = 0; i < 3; ++i)
    if (A[i] != 0) ++nonzero, axis = i;
  pose.rotation = nonzero == 1 ? axis_rotation(axis, A[axis] < 0)
                               : Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), A).toRotationMatrix();
  return pose;
}

// The pose as received in scalars S, exactly.
struct ReceivedPose {
  Vec3<Rational> centre;
  std::array<Vec3<Rational>, 3> column;  // the columns of the rotation as received
  Rational radius, half;
};

// nullopt when a number does not survive the rounding to S (overflow to an infinity).
template <class S>
std::optional<ReceivedPose> received_pose(const Cylinder<double>& c) {
  const PeerPose p = peer_pose(c);
  bool finite = true;
  const auto in_s = [&finite](double d) {
    const S s = static_cast<S>(d);
    if (!std::isfinite(s)) finite = false;
    return finite ? Rational(static_cast<double>(s)) : Rational(0);
  };
  ReceivedPose r;
  r.centre = {in_s(p.centre.x()), in_s(p.centre.y()), in_s(p.centre.z())};
  for (int j = 0; j < 3; ++j) r.column[j] = {in_s(p.rotation(0, j)), in_s(p.rotation(1, j)), in_s(p.rotation(2, j))};
  r.radius = in_s(c.radius);
  r.half = in_s(p.length / 2);
  if (!finite) return std::nullopt;
  return r;
}

inline EllipticCylinder<Rational> as_elliptic(const ReceivedPose& r) {
  const Vec3<Rational> axis = r.half * r.column[2];
  return {Point3<Rational>(r.centre - axis), r.radius * r.column[0], r.radius * r.column[1], Rational(2) * axis};
}

inline std::optional<Cylinder<Rational>> as_circular(const ReceivedPose& r) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (dot(r.column[i], r.column[j]) != Rational(i == j ? 1 : 0)) return std::nullopt;
  const Vec3<Rational> axis = r.half * r.column[2];
  return Cylinder<Rational>{Point3<Rational>(r.centre - axis), Point3<Rational>(r.centre + axis), r.radius};
}

}  // namespace certcyl::cli
