// The number-type layer: traits, conversion of exact input, sign and sqrt, for every type.
#define BOOST_TEST_MODULE number_traits
#include <boost/mpl/list.hpp>
#include <boost/test/unit_test.hpp>

#include <cfloat>
#include <cmath>

#include "certcyl/number_traits.hpp"
#include "certcyl/number_traits_core.hpp"

using namespace certcyl;

using AllTypes = boost::mpl::list<double, long double, Interval, CGAL::Gmpq, CGAL::Mpzf, CGAL::Gmpfr, LazyRational, CORE::Expr, dd_real>;
using FieldTypes = boost::mpl::list<double, long double, Interval, CGAL::Gmpq, CGAL::Gmpfr, LazyRational, CORE::Expr, dd_real>;

// Hand-derived constants.
//   1/3 = 0x0.5555...p0; nearest binary64 0x1.5555555555555p-2 (the next bit after the 52
//   stored ones is 0, so it rounds down); the binary64 just above is 0x1.5555555555556p-2.
const double third_down = 0x1.5555555555555p-2;
const double third_up = 0x1.5555555555556p-2;

BOOST_AUTO_TEST_CASE(flags_match_the_promises) {
  BOOST_TEST(!NumberTraits<double>::is_exact);
  BOOST_TEST(!NumberTraits<double>::is_certified);
  BOOST_TEST(!NumberTraits<long double>::is_certified);
  BOOST_TEST(!NumberTraits<Interval>::is_exact);
  BOOST_TEST(NumberTraits<Interval>::is_certified);
  BOOST_TEST(NumberTraits<CGAL::Gmpq>::is_exact);
  BOOST_TEST(!NumberTraits<CGAL::Gmpq>::has_sqrt);
  BOOST_TEST(NumberTraits<CGAL::Mpzf>::is_exact);
  BOOST_TEST(!NumberTraits<CGAL::Mpzf>::is_field);
  BOOST_TEST(!NumberTraits<CGAL::Mpzf>::has_sqrt);
  BOOST_TEST(!NumberTraits<CGAL::Gmpfr>::is_certified);
  BOOST_TEST(NumberTraits<CGAL::Gmpfr>::has_sqrt);
  BOOST_TEST(NumberTraits<LazyRational>::is_exact);
  BOOST_TEST(!NumberTraits<LazyRational>::has_sqrt);
  BOOST_TEST(NumberTraits<CORE::Expr>::is_exact);
  BOOST_TEST(NumberTraits<CORE::Expr>::has_sqrt);
}

BOOST_AUTO_TEST_CASE(names_are_distinct_and_gmpfr_names_its_precision) {
  const std::vector<std::string> names{nt::name<double>(), nt::name<long double>(), nt::name<Interval>(),
                                       nt::name<CGAL::Gmpq>(), nt::name<CGAL::Mpzf>(), nt::name<LazyRational>(),
                                       nt::name<CORE::Expr>()};
  for (std::size_t i = 0; i < names.size(); ++i)
    for (std::size_t j = i + 1; j < names.size(); ++j) BOOST_TEST(names[i] != names[j]);
  GmpfrPrecision p(113);
  BOOST_TEST(nt::name<CGAL::Gmpfr>() == "Gmpfr<113>");
}

BOOST_AUTO_TEST_CASE_TEMPLATE(sign_and_compare, NT, AllTypes) {
  NumberScope<NT> scope;
  const NT a = nt::from_rational<NT>(Rational(-3, 4)), b = nt::constant<NT>(2), z = nt::constant<NT>(0);
  BOOST_TEST(nt::sign(a) == CGAL::NEGATIVE);
  BOOST_TEST(nt::sign(b) == CGAL::POSITIVE);
  BOOST_TEST(nt::sign(z) == CGAL::ZERO);
  BOOST_TEST(nt::is_zero(NT(b - b)));
  BOOST_TEST(nt::compare(a, b) == CGAL::SMALLER);
  BOOST_TEST(nt::compare(b, a) == CGAL::LARGER);
  BOOST_TEST(nt::compare(b, b) == CGAL::EQUAL);
  BOOST_TEST(nt::compare(nt::abs(a), nt::from_rational<NT>(Rational(3, 4))) == CGAL::EQUAL);
  BOOST_TEST(nt::compare(nt::min(a, b), a) == CGAL::EQUAL);
  BOOST_TEST(nt::compare(nt::max(a, b), b) == CGAL::EQUAL);
}

BOOST_AUTO_TEST_CASE_TEMPLATE(to_interval_encloses_exact_input, NT, FieldTypes) {
  NumberScope<NT> scope;
  const Rational third(1, 3);
  const auto [lo, hi] = nt::to_interval(nt::from_rational<NT>(third));
  if constexpr (NumberTraits<NT>::is_exact || std::is_same_v<NT, Interval>) {
    // Exact types and intervals hold 1/3 (or an enclosure of it): the interval must contain it.
    BOOST_TEST(Rational(lo) <= third);
    BOOST_TEST(third <= Rational(hi));
    BOOST_TEST(lo == third_down);
    BOOST_TEST(hi == third_up);
  } else {
    // Floating types hold a rounded value x; [lo, hi] must enclose x (doubles are exact in
    // every floating type here, so the comparisons below are exact) and stay within the
    // binary64 neighbours of 1/3.
    const NT x = nt::from_rational<NT>(third);
    BOOST_TEST(nt::compare(nt::from_rational<NT>(Rational(lo)), x) != CGAL::LARGER);
    BOOST_TEST(nt::compare(x, nt::from_rational<NT>(Rational(hi))) != CGAL::LARGER);
    BOOST_TEST(lo >= std::nextafter(third_down, 0.0));
    BOOST_TEST(hi <= std::nextafter(third_up, 1.0));
  }
}

BOOST_AUTO_TEST_CASE(conversion_of_one_third) {
  const Rational third(1, 3);
  BOOST_TEST(nt::from_rational<double>(third) == third_down);
  // long double (x87, 64-bit significand): 1/3 = 0xA.AAA...p-5; 64 bits 0xAAAAAAAAAAAAAAAA
  // followed by 1010...: the next bit is 1 and more follow, so it rounds up.
  BOOST_TEST(nt::from_rational<long double>(third) == 0xA.AAAAAAAAAAAAAABp-5L);
  {
    NumberScope<Interval> scope;
    const Interval i = nt::from_rational<Interval>(third);
    BOOST_TEST(i.inf() == third_down);
    BOOST_TEST(i.sup() == third_up);
  }
  BOOST_TEST(nt::from_rational<CGAL::Gmpq>(third) == third);
  BOOST_TEST(nt::from_rational<LazyRational>(third).exact() == third);
  BOOST_TEST(CGAL::compare(nt::from_rational<CORE::Expr>(third) * 3, CORE::Expr(1)) == CGAL::EQUAL);
  BOOST_CHECK_THROW(nt::from_rational<CGAL::Mpzf>(third), InvalidInput);
}

// 1/3 = third_down + 2^-54 / 3 (third_down = (2^54 - 1) / (3 2^54)), and the double nearest
// 2^-54 / 3 is third_down 2^-54 = 0x1.5555555555555p-56: the double-double of 1/3 is that pair,
// within 2^-108 / 3 of 1/3; times 2^10 it is the same pair scaled.
BOOST_AUTO_TEST_CASE(double_double_of_one_third) {
  const Rational third(1, 3);
  const dd_real x = nt::from_rational<dd_real>(third);
  BOOST_TEST(x.x[0] == third_down);
  BOOST_TEST(x.x[1] == 0x1.5555555555555p-56);
  BOOST_TEST(nt::to_rational(x) == Rational(third_down) + Rational(0x1.5555555555555p-56));
  const dd_real y = qd_from_rational<dd_real>(third, 10);
  BOOST_TEST(y.x[0] == std::ldexp(third_down, 10));
  BOOST_TEST(y.x[1] == std::ldexp(0x1.5555555555555p-56, 10));
  BOOST_TEST(nt::sign(dd_real(third_down) - x) == CGAL::NEGATIVE);
  BOOST_TEST(nt::compare(x, dd_real(third_up)) == CGAL::SMALLER);
}

BOOST_AUTO_TEST_CASE(gmpfr_precision_is_chosen_at_run_time) {
  const Rational third(1, 3);
  {
    GmpfrPrecision p(24);
    // 1/3 to 24 bits: 0xAAAAAA.AA...p-25 rounds up to 0xAAAAAB p-25.
    const CGAL::Gmpfr x = nt::from_rational<CGAL::Gmpfr>(third);
    BOOST_TEST(x.get_precision() == 24);
    BOOST_TEST(Rational(x.to_double()) == Rational(0xAAAAAB, 1 << 25));
    // Arithmetic and constants stay at 24 bits.
    const CGAL::Gmpfr y = x * nt::constant<CGAL::Gmpfr>(3) + nt::constant<CGAL::Gmpfr>(1);
    BOOST_TEST(y.get_precision() == 24);
  }
  {
    GmpfrPrecision p(200);
    const CGAL::Gmpfr x = nt::from_rational<CGAL::Gmpfr>(third);
    BOOST_TEST(x.get_precision() == 200);
    BOOST_TEST(nt::sqrt(x).get_precision() == 200);
  }
}

BOOST_AUTO_TEST_CASE(mpzf_holds_dyadic_input_exactly) {
  // Signs and zero survive (CGAL's Mpzf(Gmpz) loses both).
  for (const char* s : {"-3/8", "0", "-0x1.8p-60", "123456789012345678901234567890", "-5"}) {
    const Rational q = parse_rational(s);
    const CGAL::Mpzf m = nt::from_rational<CGAL::Mpzf>(q);
    BOOST_TEST(CGAL::Gmpq(m) == q, s);
    BOOST_TEST(CGAL::sign(m) == CGAL::sign(q), s);
  }
  const CGAL::Mpzf zero = nt::from_rational<CGAL::Mpzf>(Rational(0));
  BOOST_TEST(CGAL::sign(zero * CGAL::Mpzf(2)) == CGAL::ZERO);
}

using SqrtTypes = boost::mpl::list<double, long double, Interval, CGAL::Gmpfr, CORE::Expr, dd_real>;

BOOST_AUTO_TEST_CASE_TEMPLATE(sqrt_where_the_type_has_one, NT, SqrtTypes) {
  NumberScope<NT> scope;
  const NT r = nt::sqrt(nt::constant<NT>(9));
  BOOST_TEST(nt::compare(r, nt::constant<NT>(3)) == CGAL::EQUAL);
}

BOOST_AUTO_TEST_CASE(core_expr_sqrt_is_exact) {
  const CORE::Expr s = nt::sqrt(CORE::Expr(2));
  BOOST_TEST(nt::sign(CORE::Expr(s * s - 2)) == CGAL::ZERO);
}

BOOST_AUTO_TEST_CASE(interval_refuses_to_guess) {
  NumberScope<Interval> scope;
  const Interval x = nt::from_rational<Interval>(Rational(1, 10));
  const Interval ten = nt::constant<Interval>(10);
  // 10 * [0.1] - 1 straddles zero: the sign is undecided and must not be guessed.
  BOOST_CHECK_THROW(nt::sign(Interval(x * ten - nt::constant<Interval>(1))), CGAL::Uncertain_conversion_exception);
  // A clear sign is decided.
  BOOST_TEST(nt::sign(Interval(x - nt::constant<Interval>(1))) == CGAL::NEGATIVE);
}
