// certcyl/number_traits_core.hpp -- CORE::Expr (CGAL's CORE library) as a number type of
// certcyl/number_traits.hpp: include it where an algorithm is instantiated with CORE::Expr (the
// seeds' methods in the study, the command's --nt core_expr). It is a header of its own
// because CGAL/CORE_Expr.h is heavy: about two thirds of the compile time of a program that
// uses one query, which therefore does not pay for it.
#pragma once

#include <CGAL/CORE_Expr.h>

#include <string>

#include "certcyl/number_traits.hpp"

namespace certcyl {

template <>
struct NumberTraits<CORE::Expr> {
  static constexpr bool is_exact = true, is_certified = true, has_sqrt = true, is_field = true;
  static std::string name() { return "CORE::Expr"; }
  static CORE::Expr from_rational(const Rational& q) { return CORE::Expr(CORE::BigRat(q.mpq())); }
  static CORE::Expr constant(long k) { return CORE::Expr(k); }
};

}  // namespace certcyl
