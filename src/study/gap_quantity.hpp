// study/gap_quantity.hpp -- which quantity a query's signed gap measures (study/gap.hpp), by
// one short fixed name shared by `certcyl query` ("gap_quantity"), `certcyl cases`
// (meta.gap_quantity), the judge's reports and the Python module:
//
//   depth_margin   the depth margin G of a line, ray, segment, triangle or point against one
//                  cylinder (circular or elliptic): dimensionless, G <= 1/2.
//   log_phi        log(phi*) of a cylinder pair: the natural log of the common scale factor
//                  about the midpoints at which the two cylinders touch.
//
// The label is the quantity as a page or a figure names it.
#pragma once

#include <optional>
#include <string_view>

#include "study/instance.hpp"

namespace certcyl::study {

enum class GapQuantity { depth_margin, log_phi };

inline constexpr std::string_view to_string(GapQuantity g) { return g == GapQuantity::log_phi ? "log_phi" : "depth_margin"; }

inline constexpr std::string_view gap_label(GapQuantity g) { return g == GapQuantity::log_phi ? "log(phi*)" : "depth margin G"; }

inline std::optional<GapQuantity> parse_gap_quantity(std::string_view s) {
  if (s == "depth_margin") return GapQuantity::depth_margin;
  if (s == "log_phi") return GapQuantity::log_phi;
  return std::nullopt;
}

inline constexpr GapQuantity gap_quantity(Query q) {
  return q == Query::cylinder_cylinder ? GapQuantity::log_phi : GapQuantity::depth_margin;
}

// The same by a `certcyl query` query name (point and elliptic ray and segment queries included).
inline constexpr GapQuantity gap_quantity(std::string_view query_name) {
  return query_name == "cylinder_cylinder" ? GapQuantity::log_phi : GapQuantity::depth_margin;
}

}  // namespace certcyl::study
