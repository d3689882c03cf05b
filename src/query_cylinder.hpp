// The JSON form of a certified cylinder-cylinder result (shared by query and scene).
#pragma once

#include "certcyl/certified/cylinder_cylinder.hpp"
#include "query.hpp"

namespace certcyl::cli {

// The options of the certified cylinder-cylinder query in the command (refine_gap on).
CylinderCylinderOptions command_options(const QueryOptions& o);
ojson cylinder_cylinder_json(const CylinderCylinderResult& r);

}  // namespace certcyl::cli
