// The JSON form of a certified triangle-cylinder result (shared by query and scene).
#pragma once

#include "certcyl/certified/triangle_cylinder.hpp"
#include "query.hpp"

namespace certcyl::cli {

ojson triangle_cylinder_json(const TriangleCylinderResult& r);

}  // namespace certcyl::cli
