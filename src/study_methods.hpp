// The method registries of the study, one function per query group (study_methods_*.cpp) and
// one per peer library (peers/*.cpp, compiled when the library is found).
#pragma once

#include <string>
#include <vector>

#include "certcyl/dispatch.hpp"
#include "study/conversion.hpp"
#include "study/methods.hpp"

namespace certcyl::cli {

// The number types every generic method runs in, with the stride of the slow ones on the
// instances and their effort in the failure maps and hunting (line and triangle queries, one
// call ~13 us in Gmpfr and ~50-150 us in CORE::Expr: maps on every 2nd and 4th row and column).
struct NumberTypeChoice {
  NumberTypeSpec spec;
  unsigned stride = 1;
  study::Effort effort{};
};

inline std::vector<NumberTypeChoice> generic_number_types() {
  return {{{NumberKind::double_, 53}, 1, {1, 1}},     {{NumberKind::long_double, 64}, 1, {1, 1}},
          {{NumberKind::interval, 53}, 1, {1, 1}},    {{NumberKind::gmpfr, 24}, 2, {2, 1}},
          {{NumberKind::gmpfr, 53}, 2, {2, 1}},       {{NumberKind::gmpfr, 113}, 2, {2, 1}},
          {{NumberKind::gmpfr, 256}, 2, {2, 1}},      {{NumberKind::core_expr, 53}, 8, {4, 2}}};
}

// A binary64 input in NT: itself for double and long double, correctly rounded to the
// precision in force for Gmpfr, enclosed for intervals, exact for CORE::Expr.
template <class NT>
NT from_binary64(double d) {
  if constexpr (std::is_same_v<NT, double> || std::is_same_v<NT, long double>)
    return d;
  else
    return nt::from_rational<NT>(Rational(d));
}

template <class NT, class Prim>
auto to_nt(const Prim& p) {
  return p.map([](double d) { return from_binary64<NT>(d); });
}

// Marks the methods that run one at a time on the main thread (CORE::Expr; see Method::serial).
inline void mark_serial(study::Registry& r) {
  for (study::Method& m : r)
    if (m.nt == "core_expr") m.serial = true;
}

// Gives the methods in Gmpfr below 53 bits the instance they receive: every coordinate rounded
// to their precision (study/conversion.hpp; from_binary64 above).
inline void attach_conversions(study::Registry& r) {
  const std::string prefix = "gmpfr<";
  for (study::Method& m : r) {
    if (m.nt.rfind(prefix, 0) != 0) continue;
    const long bits = std::stol(m.nt.substr(prefix.size()));
    if (bits < 53) m.conversion = std::make_shared<const study::Conversion>(study::rounding_to_bits(bits));
  }
}

void register_line_methods(study::Registry& r);
void register_triangle_methods(study::Registry& r);
void register_cylinder_methods(study::Registry& r);
// Every peer library found at configure time; returns their names and versions.
std::vector<std::string> register_peer_methods(study::Registry& r);

inline study::Registry all_methods_registry() {
  study::Registry r;
  register_line_methods(r);
  register_triangle_methods(r);
  register_cylinder_methods(r);
  register_peer_methods(r);
  mark_serial(r);
  attach_conversions(r);
  return r;
}

}  // namespace certcyl::cli
