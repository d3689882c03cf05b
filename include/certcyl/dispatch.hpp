// certcyl/dispatch.hpp -- choosing a number type at run time.
//
// `dispatch(spec, f)` calls the generic callable `f.template operator()<NT>()` with the number
// type named by `spec`, inside what that type needs: a GmpfrPrecision scope for Gmpfr, the
// upward FPU rounding of Interval_nt<false>. Names accepted by `parse_number_type`:
//   double, long_double, interval, gmpq, mpzf, gmpfr<BITS> (2 <= BITS <= 65536; "gmpfr" is
//   gmpfr<53>), lazy_gmpq, core_expr.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>

#include "certcyl/errors.hpp"
#include "certcyl/number_traits.hpp"
#include "certcyl/number_traits_core.hpp"

namespace certcyl {

enum class NumberKind { double_, long_double, interval, gmpq, mpzf, gmpfr, lazy_gmpq, core_expr };

struct NumberTypeSpec {
  NumberKind kind = NumberKind::double_;
  long precision = 53;  // bits, used by gmpfr only

  std::string name() const {
    switch (kind) {
      case NumberKind::double_: return "double";
      case NumberKind::long_double: return "long_double";
      case NumberKind::interval: return "interval";
      case NumberKind::gmpq: return "gmpq";
      case NumberKind::mpzf: return "mpzf";
      case NumberKind::gmpfr: return "gmpfr<" + std::to_string(precision) + ">";
      case NumberKind::lazy_gmpq: return "lazy_gmpq";
      case NumberKind::core_expr: return "core_expr";
    }
    return "?";
  }
};

inline NumberTypeSpec parse_number_type(std::string_view s, const std::string& field = "nt") {
  constexpr std::array<std::pair<std::string_view, NumberKind>, 7> fixed{{{"double", NumberKind::double_},
                                                                         {"long_double", NumberKind::long_double},
                                                                         {"interval", NumberKind::interval},
                                                                         {"gmpq", NumberKind::gmpq},
                                                                         {"mpzf", NumberKind::mpzf},
                                                                         {"lazy_gmpq", NumberKind::lazy_gmpq},
                                                                         {"core_expr", NumberKind::core_expr}}};
  for (auto [name, kind] : fixed)
    if (s == name) return {kind, 53};
  if (s == "gmpfr") return {NumberKind::gmpfr, 53};
  if (s.size() > 7 && s.substr(0, 6) == "gmpfr<" && s.back() == '>') {
    const std::string digits(s.substr(6, s.size() - 7));
    long bits = 0;
    for (char c : digits) {
      if (c < '0' || c > '9' || bits > 65536) throw InvalidInput(field, "bad Gmpfr precision in '" + std::string(s) + "'");
      bits = bits * 10 + (c - '0');
    }
    if (digits.empty() || bits < 2 || bits > 65536)
      throw InvalidInput(field, "Gmpfr precision must be 2..65536 bits, got '" + std::string(s) + "'");
    return {NumberKind::gmpfr, bits};
  }
  throw InvalidInput(field, "unknown number type '" + std::string(s) +
                                "' (expected double, long_double, interval, gmpq, mpzf, gmpfr<BITS>, lazy_gmpq or core_expr)");
}

// Calls f.template operator()<NT>() for the number type spec names; returns what f returns.
template <class F>
decltype(auto) dispatch(const NumberTypeSpec& spec, F&& f) {
  switch (spec.kind) {
    case NumberKind::double_: return f.template operator()<double>();
    case NumberKind::long_double: return f.template operator()<long double>();
    case NumberKind::interval: {
      CGAL::Protect_FPU_rounding<true> protect;
      return f.template operator()<Interval>();
    }
    case NumberKind::gmpq: return f.template operator()<CGAL::Gmpq>();
    case NumberKind::mpzf: return f.template operator()<CGAL::Mpzf>();
    case NumberKind::gmpfr: {
      GmpfrPrecision precision(spec.precision);
      return f.template operator()<CGAL::Gmpfr>();
    }
    case NumberKind::lazy_gmpq: return f.template operator()<LazyRational>();
    case NumberKind::core_expr: return f.template operator()<CORE::Expr>();
  }
  throw InvalidInput("nt", "unknown number kind");
}

}  // namespace certcyl
