// Bullet (Debian libbullet-dev, single precision: btScalar is float) as its users call it:
//   cylinder-cylinder  btCollisionWorld::contactPairTest on two btCylinderShapeZ objects; they
//                      collide when a reported contact point has distance <= 0. Measured with the
//                      default collision margin (0.04: Bullet keeps the extents and rounds the
//                      edges by the margin) and with setMargin(0).
//   ray, segment       btCollisionWorld::rayTestSingle from the origin to origin + direction
//                      (segment) or origin + 1e4 direction (ray); hasHit().
// The inputs are rounded to float on the way in, as a Bullet user's would be.
#include <btBulletCollisionCommon.h>

#include <memory>

#include "peer_frame.hpp"
#include "peers.hpp"

namespace certcyl::cli {
namespace {

btTransform bt_pose(const PeerPose& p) {
  btMatrix3x3 m;
  m.setValue(btScalar(p.rotation(0, 0)), btScalar(p.rotation(0, 1)), btScalar(p.rotation(0, 2)), btScalar(p.rotation(1, 0)),
             btScalar(p.rotation(1, 1)), btScalar(p.rotation(1, 2)), btScalar(p.rotation(2, 0)), btScalar(p.rotation(2, 1)),
             btScalar(p.rotation(2, 2)));
  return btTransform(m, btVector3(btScalar(p.centre.x()), btScalar(p.centre.y()), btScalar(p.centre.z())));
}

// One collision world per thread, reused across queries.
struct World {
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  btDbvtBroadphase broadphase;
  btCollisionWorld world{&dispatcher, &broadphase, &config};
};
World& world() {
  thread_local World w;
  return w;
}

struct Contact : btCollisionWorld::ContactResultCallback {
  bool hit = false;
  btScalar addSingleResult(btManifoldPoint& cp, const btCollisionObjectWrapper*, int, int, const btCollisionObjectWrapper*, int, int) override {
    if (cp.getDistance() <= 0) hit = true;
    return 0;
  }
};

bool bullet_cylinders(const std::vector<double>& x, bool default_margin) {
  btCylinderShapeZ* shapes[2];
  std::unique_ptr<btCylinderShapeZ> owned[2];
  btCollisionObject objects[2];
  for (int i = 0; i < 2; ++i) {
    const Cylinder<double> c = study::cylinder_at(x, static_cast<std::size_t>(7 * i));
    const PeerPose p = peer_pose(c);
    owned[i] = std::make_unique<btCylinderShapeZ>(btVector3(btScalar(c.radius), btScalar(c.radius), btScalar(p.length / 2)));
    shapes[i] = owned[i].get();
    if (!default_margin) shapes[i]->setMargin(0);
    objects[i].setCollisionShape(shapes[i]);
    objects[i].setWorldTransform(bt_pose(p));
  }
  Contact result;
  world().world.contactPairTest(&objects[0], &objects[1], result);
  return result.hit;
}

bool bullet_ray(const std::vector<double>& x, bool segment, bool default_margin) {
  const Cylinder<double> c = study::cylinder_at(x, 6);
  const PeerPose p = peer_pose(c);
  btCylinderShapeZ shape(btVector3(btScalar(c.radius), btScalar(c.radius), btScalar(p.length / 2)));
  if (!default_margin) shape.setMargin(0);
  btCollisionObject object;
  object.setCollisionShape(&shape);
  object.setWorldTransform(bt_pose(p));
  const btVector3 from{btScalar(x[0]), btScalar(x[1]), btScalar(x[2])};
  const btVector3 to = segment ? btVector3(btScalar(x[3]), btScalar(x[4]), btScalar(x[5]))
                               : from + btScalar(1e4) * btVector3(btScalar(x[3]), btScalar(x[4]), btScalar(x[5]));
  btTransform tf, tt;
  tf.setIdentity(), tt.setIdentity();
  tf.setOrigin(from), tt.setOrigin(to);
  btCollisionWorld::ClosestRayResultCallback result(from, to);
  btCollisionWorld::rayTestSingle(tf, tt, &object, &shape, object.getWorldTransform(), result);
  return result.hasHit();
}

}  // namespace

std::string register_bullet_methods(study::Registry& r) {
  using study::MethodKind;
  using study::Query;
  for (bool margin : {true, false}) {
    const std::string base = margin ? "bullet" : "bullet_margin0";
    r.push_back({base, "float", MethodKind::peer, Query::cylinder_cylinder, 1, {},
                 [margin](const std::vector<double>& x) { return study::boolean_answer(bullet_cylinders(x, margin)); }});
    r.push_back({base, "float", MethodKind::peer, Query::ray_cylinder, 1, {},
                 [margin](const std::vector<double>& x) { return study::boolean_answer(bullet_ray(x, false, margin)); }});
    r.push_back({base, "float", MethodKind::peer, Query::segment_cylinder, 1, {},
                 [margin](const std::vector<double>& x) { return study::boolean_answer(bullet_ray(x, true, margin)); }});
  }
  return "Bullet " + std::to_string(BT_BULLET_VERSION);
}

}  // namespace certcyl::cli
