// Adapters from the study's inputs to the peer libraries (FCL, Bullet, ODE). Each returns the
// library's name and version and adds its methods to the registry.
#pragma once

#include <string>

#include "study_methods.hpp"

namespace certcyl::cli {

std::string register_fcl_methods(study::Registry& r);
std::string register_bullet_methods(study::Registry& r);
std::string register_ode_methods(study::Registry& r);

}  // namespace certcyl::cli
