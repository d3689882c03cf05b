// ODE (Debian libode-dev, double precision) as its users call it: dCollide between geoms
// outside any space, true when it returns a contact.
//   cylinder-cylinder  two dCreateCylinder geoms (ODE's cylinder is along z, centred)
//   ray, segment       dCreateRay from the origin along the direction, of length |direction|
//                      (segment) or 1e4 |direction| (ray). Its contract is surface hit
//                      (study/contract.hpp): a ray starting in the cylinder hits where it exits.
//   triangle           a one-triangle dCreateTriMesh against the cylinder, in both windings
//                      (ODE skips back-facing triangles)
#include <ode/ode.h>

#include <array>
#include <mutex>

#include "peer_frame.hpp"
#include "peers.hpp"

namespace certcyl::cli {
namespace {

void ode_thread_init() {
  static std::once_flag once;
  std::call_once(once, [] { dInitODE2(0); });
  thread_local bool ready = [] { return dAllocateODEDataForThread(dAllocateMaskAll) != 0; }();
  (void)ready;
}

struct Geom {
  dGeomID id;
  explicit Geom(dGeomID g) : id(g) {}
  ~Geom() { dGeomDestroy(id); }
  Geom(const Geom&) = delete;
  Geom& operator=(const Geom&) = delete;
};

dGeomID ode_cylinder(const Cylinder<double>& c) {
  const PeerPose p = peer_pose(c);
  dGeomID g = dCreateCylinder(nullptr, c.radius, p.length);
  dGeomSetPosition(g, p.centre.x(), p.centre.y(), p.centre.z());
  dMatrix3 R;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) R[4 * i + j] = p.rotation(i, j);
    R[4 * i + 3] = 0;
  }
  dGeomSetRotation(g, R);
  return g;
}

bool touches(dGeomID a, dGeomID b) {
  dContactGeom contacts[4];
  return dCollide(a, b, 4, contacts, sizeof(dContactGeom)) > 0;
}

bool ode_ray(const std::vector<double>& x, bool segment) {
  ode_thread_init();
  Geom cyl(ode_cylinder(study::cylinder_at(x, 6)));
  double d[3] = {x[3], x[4], x[5]};
  if (segment)
    for (int i = 0; i < 3; ++i) d[i] -= x[i];
  const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  Geom ray(dCreateRay(nullptr, segment ? len : 1e4 * len));
  dGeomRaySet(ray.id, x[0], x[1], x[2], d[0], d[1], d[2]);
  return touches(ray.id, cyl.id);
}

// One triangle, with its vertices in the order `order`, as a trimesh against the cylinder.
bool ode_mesh(const std::vector<double>& x, std::array<dTriIndex, 3> order) {
  ode_thread_init();
  const dReal vertices[9] = {x[0], x[1], x[2], x[3], x[4], x[5], x[6], x[7], x[8]};
  dTriMeshDataID data = dGeomTriMeshDataCreate();
  dGeomTriMeshDataBuildDouble(data, vertices, 3 * sizeof(dReal), 3, order.data(), 3, 3 * sizeof(dTriIndex));
  bool hit = false;
  {
    Geom mesh(dCreateTriMesh(nullptr, data, nullptr, nullptr, nullptr));
    Geom cyl(ode_cylinder(study::cylinder_at(x, 9)));
    hit = touches(cyl.id, mesh.id);
  }
  dGeomTriMeshDataDestroy(data);
  return hit;
}

}  // namespace

std::string register_ode_methods(study::Registry& r) {
  using study::MethodKind;
  using study::Query;
  r.push_back({"ode", "double", MethodKind::peer, Query::cylinder_cylinder, 1, {}, [](const std::vector<double>& x) {
                 ode_thread_init();
                 Geom a(ode_cylinder(study::cylinder_at(x, 0))), b(ode_cylinder(study::cylinder_at(x, 7)));
                 return study::boolean_answer(touches(a.id, b.id));
               }});
  r.push_back({"ode", "double", MethodKind::peer, Query::ray_cylinder, 1, {},
               [](const std::vector<double>& x) { return study::boolean_answer(ode_ray(x, false)); }});
  r.back().contract = study::Contract::surface_hit;
  r.push_back({"ode", "double", MethodKind::peer, Query::segment_cylinder, 1, {},
               [](const std::vector<double>& x) { return study::boolean_answer(ode_ray(x, true)); }});
  r.back().contract = study::Contract::surface_hit;
  // ODE's trimesh colliders skip a back-facing triangle (one winding alone misses even a
  // triangle crossing the cylinder through its axis): a one-sided surface is what a user
  // meshing a closed solid gets, so a lone triangle is tested with both windings.
  r.push_back({"ode_mesh", "double", MethodKind::peer, Query::triangle_cylinder, 1, {},
               [](const std::vector<double>& x) { return study::boolean_answer(ode_mesh(x, {0, 1, 2}) || ode_mesh(x, {0, 2, 1})); }});
  // Debian's ODE keeps the trimesh colliders' cache in shared state: two threads colliding
  // trimeshes at once abort in fetchMeshTriangle ("ODE INTERNAL ERROR 1", about one default
  // study in four). The study runs these calls one at a time, as it does CORE::Expr.
  r.back().serial = true;
  return std::string("ODE ") + dODE_VERSION;
}

}  // namespace certcyl::cli
