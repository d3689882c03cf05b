// Bullet (Debian libbullet-dev, single precision: btScalar is float) as its users call it:
//   cylinder-cylinder  btCollisionWorld::contactPairTest on two btCylinderShapeZ objects; they
//                      collide when a reported contact point has distance <= 0. Measured with the
//                      default collision margin (0.04: Bullet keeps the extents and rounds the
//                      edges by the margin) and with setMargin(0).
//   ray, segment       btCollisionWorld::rayTestSingle from the origin to origin + direction
//                      (segment) or origin + 1e4 direction (ray); hasHit(). Its contract is
//                      surface entry (study/contract.hpp): a ray starting in the cylinder does
//                      not hit it.
// The inputs are rounded to float on the way in, as a Bullet user's would be, so Bullet solves a
// differently rounded instance; its Conversion (study/conversion.hpp) certifies that instance:
// the pose, radius and half length as floats (peer_frame.hpp, received_pose) and, for rays and
// segments, the float ends Bullet casts between, exactly (a cast whose ends round to one point
// enters nothing). A ray or segment is certified against
// the received cylinder as an elliptic cylinder (the float rotation is not orthonormal unless
// the axis is a coordinate axis); a pair only when both received rotations are exactly
// orthonormal (circular cylinders), else it is left unsplit.
#include <btBulletCollisionCommon.h>

#include <cmath>
#include <memory>
#include <stdexcept>
#include <utility>

#include "certcyl/certified/cylinder_cylinder.hpp"
#include "certcyl/certified/line_cylinder.hpp"
#include "peer_frame.hpp"
#include "peers.hpp"
#include "study/contract.hpp"
#include "study/conversion.hpp"

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

// The ends Bullet casts between, in float: the segment's, or the ray's origin and origin + 1e4
// direction.
std::pair<btVector3, btVector3> bullet_ray_ends(const std::vector<double>& x, bool segment) {
  const btVector3 from{btScalar(x[0]), btScalar(x[1]), btScalar(x[2])};
  const btVector3 to = segment ? btVector3(btScalar(x[3]), btScalar(x[4]), btScalar(x[5]))
                               : from + btScalar(1e4) * btVector3(btScalar(x[3]), btScalar(x[4]), btScalar(x[5]));
  return {from, to};
}

bool bullet_ray(const std::vector<double>& x, bool segment, bool default_margin) {
  const Cylinder<double> c = study::cylinder_at(x, 6);
  const PeerPose p = peer_pose(c);
  btCylinderShapeZ shape(btVector3(btScalar(c.radius), btScalar(c.radius), btScalar(p.length / 2)));
  if (!default_margin) shape.setMargin(0);
  btCollisionObject object;
  object.setCollisionShape(&shape);
  object.setWorldTransform(bt_pose(p));
  const auto [from, to] = bullet_ray_ends(x, segment);
  btTransform tf, tt;
  tf.setIdentity(), tt.setIdentity();
  tf.setOrigin(from), tt.setOrigin(to);
  btCollisionWorld::ClosestRayResultCallback result(from, to);
  btCollisionWorld::rayTestSingle(tf, tt, &object, &shape, object.getWorldTransform(), result);
  return result.hasHit();
}

// The certified answer of the instance Bullet receives (see the file's comment); undecided when
// it is not one the certified queries answer.
Answer bullet_received(study::Query q, const std::vector<double>& x, study::Contract contract) {
  using study::Query;
  if (q == Query::cylinder_cylinder) {
    const auto a = received_pose<float>(study::cylinder_at(x, 0)), b = received_pose<float>(study::cylinder_at(x, 7));
    if (!a || !b) return Answer::undecided;
    const auto ca = as_circular(*a), cb = as_circular(*b);
    if (!ca || !cb) return Answer::undecided;
    return certified_cylinder_cylinder(*ca, *cb).answer;
  }
  const auto pose = received_pose<float>(study::cylinder_at(x, 6));
  if (!pose) return Answer::undecided;
  const auto [from, to] = bullet_ray_ends(x, q == Query::segment_cylinder);
  const auto point = [](const btVector3& v) {
    if (!std::isfinite(v.x()) || !std::isfinite(v.y()) || !std::isfinite(v.z())) throw std::domain_error("an end overflowed in float");
    return Point3<Rational>{Rational(double(v.x())), Rational(double(v.y())), Rational(double(v.z()))};
  };
  // A cast whose ends round to one float (a segment far from the origin) is a point; it
  // enters nothing, so under the surface-entry contract it misses.
  if (from == to) {
    if (contract == study::Contract::surface_entry) return Answer::separated;
    return Answer::undecided;
  }
  const Segment<Rational> cast{point(from), point(to)};
  return study::contract_answer(certified_line_cylinder(cast, as_elliptic(*pose)), contract);
}

}  // namespace

std::string register_bullet_methods(study::Registry& r) {
  using study::MethodKind;
  using study::Query;
  const auto received = std::make_shared<const study::Conversion>(study::Conversion{"bullet_float", bullet_received});
  for (bool margin : {true, false}) {
    const std::string base = margin ? "bullet" : "bullet_margin0";
    r.push_back({base, "float", MethodKind::peer, Query::cylinder_cylinder, 1, {},
                 [margin](const std::vector<double>& x) { return study::boolean_answer(bullet_cylinders(x, margin)); }});
    r.push_back({base, "float", MethodKind::peer, Query::ray_cylinder, 1, {},
                 [margin](const std::vector<double>& x) { return study::boolean_answer(bullet_ray(x, false, margin)); }});
    r.push_back({base, "float", MethodKind::peer, Query::segment_cylinder, 1, {},
                 [margin](const std::vector<double>& x) { return study::boolean_answer(bullet_ray(x, true, margin)); }});
    for (std::size_t i = r.size() - 3; i < r.size(); ++i) {
      r[i].conversion = received;
      if (r[i].query != Query::cylinder_cylinder) r[i].contract = study::Contract::surface_entry;
    }
  }
  return "Bullet " + std::to_string(BT_BULLET_VERSION);
}

}  // namespace certcyl::cli
