// The peer libraries the study measures, each compiled only when CMake found it
// (CERTCYL_HAVE_FCL, CERTCYL_HAVE_BULLET, CERTCYL_HAVE_ODE).
#include "peers.hpp"

namespace certcyl::cli {

std::vector<std::string> register_peer_methods(study::Registry& r) {
  std::vector<std::string> found;
#ifdef CERTCYL_HAVE_FCL
  found.push_back(register_fcl_methods(r));
#endif
#ifdef CERTCYL_HAVE_BULLET
  found.push_back(register_bullet_methods(r));
#endif
#ifdef CERTCYL_HAVE_ODE
  found.push_back(register_ode_methods(r));
#endif
  (void)r;
  return found;
}

}  // namespace certcyl::cli
