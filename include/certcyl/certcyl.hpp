// certcyl/certcyl.hpp -- everything certcyl offers, in one include.
#pragma once

#include "certcyl/answer.hpp"
#include "certcyl/errors.hpp"
#include "certcyl/io/json_input.hpp"
#include "certcyl/number_traits.hpp"
#include "certcyl/predicates/point_in_cylinder.hpp"
#include "certcyl/primitives.hpp"
#include "certcyl/rational.hpp"
#include "certcyl/vec3.hpp"
#include "certcyl/dispatch.hpp"
#include "certcyl/filtered.hpp"
