// FCL (Debian libfcl-dev) as its users call it: fcl::collide with the default request (GJK
// through libccd) on fcl::Cylinderd shapes; a triangle is a one-triangle BVHModel<OBBRSSd>.
// Boolean answers: isCollision().
#include <fcl/fcl.h>

#include "peer_frame.hpp"
#include "peers.hpp"

namespace certcyl::cli {
namespace {

struct FclCylinder {
  std::shared_ptr<fcl::Cylinderd> shape;
  fcl::Transform3d pose = fcl::Transform3d::Identity();
};

FclCylinder fcl_cylinder(const Cylinder<double>& c) {
  const PeerPose p = peer_pose(c);
  FclCylinder f;
  f.shape = std::make_shared<fcl::Cylinderd>(c.radius, p.length);
  f.pose.linear() = p.rotation;
  f.pose.translation() = p.centre;
  return f;
}

bool collide(const fcl::CollisionGeometryd* a, const fcl::Transform3d& ta, const fcl::CollisionGeometryd* b, const fcl::Transform3d& tb) {
  fcl::CollisionRequestd request;
  fcl::CollisionResultd result;
  fcl::collide(a, ta, b, tb, request, result);
  return result.isCollision();
}

}  // namespace

std::string register_fcl_methods(study::Registry& r) {
  using study::MethodKind;
  using study::Query;
  r.push_back({"fcl", "double", MethodKind::peer, Query::cylinder_cylinder, 1, {}, [](const std::vector<double>& x) {
                 const FclCylinder a = fcl_cylinder(study::cylinder_at(x, 0)), b = fcl_cylinder(study::cylinder_at(x, 7));
                 return study::boolean_answer(collide(a.shape.get(), a.pose, b.shape.get(), b.pose));
               }});
  r.push_back({"fcl_mesh", "double", MethodKind::peer, Query::triangle_cylinder, 1, {}, [](const std::vector<double>& x) {
                 const Triangle<double> t = study::triangle_at(x);
                 auto v = [](const Vec3<double>& p) { return fcl::Vector3d(p.x, p.y, p.z); };
                 fcl::BVHModel<fcl::OBBRSSd> mesh;
                 mesh.beginModel(1, 3);
                 mesh.addTriangle(v(t.v[0]), v(t.v[1]), v(t.v[2]));
                 mesh.endModel();
                 const FclCylinder c = fcl_cylinder(study::cylinder_at(x, 9));
                 return study::boolean_answer(collide(&mesh, fcl::Transform3d::Identity(), c.shape.get(), c.pose));
               }});
  return "FCL " FCL_VERSION;
}

}  // namespace certcyl::cli
