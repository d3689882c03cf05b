// plugin_fcl.cpp -- FCL (the Flexible Collision Library) as a plugin for `certcyl judge --plugin`
// (certcyl/plugin.h), written the way an FCL user calls it: fcl::collide with the default request
// (GJK through libccd) on fcl::Cylinderd shapes placed by a pose.
//
// A certcyl cylinder (p0, p1, radius) becomes an FCL cylinder centred at the origin along z: the
// radius, the length |p1 - p0|, and the pose taking it to the midpoint of p0 p1 with a rotation
// taking z to the axis. A triangle is a one-triangle mesh, fcl::BVHModel<fcl::OBBRSSd>.
//
// fcl::collide answers a boolean (isCollision()): it cannot tell touching from overlapping, so
// the plugin returns CERTCYL_INTERSECTING when the shapes collide and CERTCYL_SEPARATED otherwise;
// the judge scores it as a boolean (touching and overlapping both count as meeting). An exception
// thrown by FCL or Eigen is caught at the C boundary and returned as -1, the method's error.
//
// Outside this project (Debian/Ubuntu libfcl-dev; FCL's headers need Eigen):
//   c++ -std=c++17 -O2 -shared -fPIC -I<certcyl>/include -I/usr/include/eigen3 plugin_fcl.cpp -o plugin_fcl.so -lfcl -lccd
//   certcyl judge --plugin ./plugin_fcl.so --size small
#include <certcyl/plugin.h>

#include <fcl/fcl.h>

#include <exception>
#include <memory>

namespace {

constexpr int kError = -1;

struct PlacedCylinder {
  std::shared_ptr<fcl::Cylinderd> shape;
  fcl::Transform3d pose = fcl::Transform3d::Identity();
};

fcl::Vector3d point(const double* p) { return fcl::Vector3d(p[0], p[1], p[2]); }

// c: p0[3], p1[3], radius. A zero-length axis gives FCL a flat cylinder (a disk) around z.
PlacedCylinder placed_cylinder(const double c[7]) {
  const fcl::Vector3d p0 = point(c), p1 = point(c + 3), axis = p1 - p0;
  PlacedCylinder f;
  f.shape = std::make_shared<fcl::Cylinderd>(c[6], axis.norm());
  f.pose.linear() = Eigen::Quaterniond::FromTwoVectors(fcl::Vector3d::UnitZ(), axis).toRotationMatrix();
  f.pose.translation() = 0.5 * (p0 + p1);
  return f;
}

int collide(const fcl::CollisionGeometryd* a, const fcl::Transform3d& ta, const fcl::CollisionGeometryd* b,
            const fcl::Transform3d& tb) {
  fcl::CollisionRequestd request;
  fcl::CollisionResultd result;
  fcl::collide(a, ta, b, tb, request, result);
  return result.isCollision() ? CERTCYL_INTERSECTING : CERTCYL_SEPARATED;
}

}  // namespace

extern "C" {

const char* certcyl_plugin_name(void) { return "fcl " FCL_VERSION; }

int certcyl_plugin_cylinder_cylinder(const double a[7], const double b[7]) {
  try {
    const PlacedCylinder ca = placed_cylinder(a), cb = placed_cylinder(b);
    return collide(ca.shape.get(), ca.pose, cb.shape.get(), cb.pose);
  } catch (const std::exception&) {
    return kError;
  }
}

int certcyl_plugin_triangle_cylinder(const double v[9], const double c[7]) {
  try {
    fcl::BVHModel<fcl::OBBRSSd> mesh;
    mesh.beginModel(1, 3);
    mesh.addTriangle(point(v), point(v + 3), point(v + 6));
    mesh.endModel();
    const PlacedCylinder cc = placed_cylinder(c);
    return collide(&mesh, fcl::Transform3d::Identity(), cc.shape.get(), cc.pose);
  } catch (const std::exception&) {
    return kError;
  }
}

}  // extern "C"
