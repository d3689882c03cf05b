// certcyl/certcyl.hpp -- everything certcyl offers, in one include: number types and exact
// input, primitives and point classification, the certified queries (line, ray and segment
// against circular and elliptic cylinders, triangle, cylinder pair), the robust double line
// method, the seeds' algorithms, the broad phase and the JSON input. Each query also has its own
// header (certcyl/certified/..., certcyl/seeds/..., certcyl/robust/...), lighter to compile.
#pragma once

#include "certcyl/answer.hpp"
#include "certcyl/broad_phase.hpp"
#include "certcyl/certified/cylinder_cylinder.hpp"
#include "certcyl/certified/line_cylinder.hpp"
#include "certcyl/certified/point_cylinder.hpp"
#include "certcyl/certified/triangle_cylinder.hpp"
#include "certcyl/dispatch.hpp"
#include "certcyl/errors.hpp"
#include "certcyl/filtered.hpp"
#include "certcyl/io/json_input.hpp"
#include "certcyl/line_result.hpp"
#include "certcyl/number_traits.hpp"
#include "certcyl/number_traits_core.hpp"
#include "certcyl/predicates/point_in_cylinder.hpp"
#include "certcyl/primitives.hpp"
#include "certcyl/rational.hpp"
#include "certcyl/robust/line_cylinder.hpp"
#include "certcyl/seeds/eberly_cylinders.hpp"
#include "certcyl/seeds/eberly_triangle_cylinder.hpp"
#include "certcyl/seeds/gullotti_line_elliptic_cylinder.hpp"
#include "certcyl/seeds/shene_line_cylinder.hpp"
#include "certcyl/vec3.hpp"
