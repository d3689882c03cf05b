// Exact input: parsing, correct rounding, exact printing and round trips of binary64 values.
#define BOOST_TEST_MODULE rational
#include <boost/test/unit_test.hpp>

#include <nlohmann/json.hpp>

#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <random>

#include "certcyl/rational.hpp"

using namespace certcyl;

namespace {
double from_bits(std::uint64_t b) {
  double d;
  std::memcpy(&d, &b, sizeof d);
  return d;
}
Rational pow2(int e) { return e >= 0 ? Rational(detail::power(2, e)) : Rational(CGAL::Gmpz(1), detail::power(2, -e)); }
}  // namespace

BOOST_AUTO_TEST_CASE(parses_each_form_exactly) {
  BOOST_TEST(parse_rational("-3/4") == Rational(-3, 4));
  BOOST_TEST(parse_rational("6/8") == Rational(3, 4));
  BOOST_TEST(parse_rational("+7") == Rational(7));
  BOOST_TEST(parse_rational("0.1") == Rational(1, 10));
  BOOST_TEST(parse_rational("-1.25e-3") == Rational(-1, 800));
  BOOST_TEST(parse_rational(".5") == Rational(1, 2));
  BOOST_TEST(parse_rational("5.") == Rational(5));
  BOOST_TEST(parse_rational("2E+3") == Rational(2000));
  BOOST_TEST(parse_rational("0x1.8p-3") == Rational(3, 16));
  BOOST_TEST(parse_rational("-0x10") == Rational(-16));
  BOOST_TEST(parse_rational("0X.8P1") == Rational(1));
  BOOST_TEST(parse_rational("0x1p-1074") == pow2(-1074));
  // Far beyond binary64's range, still exact.
  BOOST_TEST(parse_rational("1e400") == Rational(detail::power(10, 400)));
}

BOOST_AUTO_TEST_CASE(decimal_one_tenth_is_not_the_double) {
  const Rational tenth = parse_rational("0.1");
  BOOST_TEST(tenth != Rational(0.1));
  // The double 0.1 is 0x1.999999999999ap-4 = 3602879701896397 / 2^55.
  BOOST_TEST(Rational(0.1) == Rational(CGAL::Gmpz(3602879701896397L), detail::power(2, 55)));
  BOOST_TEST(!is_binary64(tenth));
  BOOST_TEST(round_to_nearest<double>(tenth) == 0.1);
}

BOOST_AUTO_TEST_CASE(rejects_what_is_not_a_number) {
  for (const char* bad : {"", "-", "abc", "1/0", "1/", "/2", "1/-2", "1e", "1e+", "0x", "0xg", "inf", "-inf", "nan",
                          "NaN", "1.2.3", "--1", "1 ", " 1", "1e999999999", "0x1p99999999", "1,5", "0x1.8q3"}) {
    BOOST_CHECK_THROW(parse_rational(bad, "x"), InvalidInput);
    try {
      parse_rational(bad, "a.radius");
    } catch (const InvalidInput& e) {
      BOOST_TEST(e.field() == "a.radius", bad);
      BOOST_TEST(std::string(e.what()).rfind("a.radius: ", 0) == 0, bad);
    }
  }
}

BOOST_AUTO_TEST_CASE(rounds_to_nearest_with_ties_to_even_and_subnormals) {
  const Rational one(1);
  const Rational ulp1 = pow2(-52);  // ulp of 1
  // Halfway between 1 and 1 + 2^-52: ties to even, i.e. to 1.
  BOOST_TEST(round_to_nearest<double>(one + ulp1 / 2) == 1.0);
  // Halfway between 1 + 2^-52 and 1 + 2^-51: ties to even, i.e. up to 1 + 2^-51.
  BOOST_TEST(round_to_nearest<double>(one + ulp1 * Rational(3, 2)) == 1.0 + 0x1p-51);
  // Just above the first halfway point rounds up.
  BOOST_TEST(round_to_nearest<double>(one + ulp1 / 2 + pow2(-200)) == 1.0 + 0x1p-52);
  // Subnormals: 1.5 * 2^-1074 ties to the even 2 * 2^-1074; 2.5 * 2^-1074 to 2 * 2^-1074.
  BOOST_TEST(round_to_nearest<double>(pow2(-1074) * Rational(3, 2)) == 0x1p-1073);
  BOOST_TEST(round_to_nearest<double>(pow2(-1074) * Rational(5, 2)) == 0x1p-1073);
  // Below half the smallest subnormal rounds to zero; exactly half ties to even (zero).
  BOOST_TEST(round_to_nearest<double>(pow2(-1076)) == 0.0);
  BOOST_TEST(round_to_nearest<double>(pow2(-1075)) == 0.0);
  BOOST_TEST(round_to_nearest<double>(pow2(-1075) + pow2(-1200)) == 0x1p-1074);
  // Overflow: DBL_MAX + half an ulp (2^970) ties to even, which is 2^1024, i.e. infinity;
  // anything below stays DBL_MAX.
  const Rational max(DBL_MAX);
  BOOST_TEST(std::isinf(round_to_nearest<double>(max + pow2(970))));
  BOOST_TEST(round_to_nearest<double>(max + pow2(970) - pow2(-10)) == DBL_MAX);
  BOOST_TEST(round_to_nearest<double>(-max - pow2(971)) == -HUGE_VAL);
}

BOOST_AUTO_TEST_CASE(enclosure_is_tight) {
  const Rational third(1, 3);
  const auto [lo, hi] = enclose(third);
  BOOST_TEST(Rational(lo) < third);
  BOOST_TEST(third < Rational(hi));
  BOOST_TEST(std::nextafter(lo, 1.0) == hi);
  const auto [a, b] = enclose(Rational(0.1));
  BOOST_TEST(a == 0.1);
  BOOST_TEST(b == 0.1);
  const auto [c, d] = enclose(-third);
  BOOST_TEST(c == -hi);
  BOOST_TEST(d == -lo);
  // Beyond the range: [DBL_MAX, inf].
  const auto [e, f] = enclose(parse_rational("1e400"));
  BOOST_TEST(e == DBL_MAX);
  BOOST_TEST(std::isinf(f));
  // The upper end is rounded up independently (round_rational with MPFR_RNDU): the same double,
  // over the range's edges, subnormals, zero and random rationals of every size.
  std::vector<Rational> qs = {parse_rational("-1e400"), parse_rational("1e-400"), parse_rational("-1e-400"), Rational(0),
                              Rational(DBL_MAX), Rational(-DBL_MAX), Rational(0x1p-1074), Rational(0x1p-1074) / 3,
                              Rational(-0x1p-1074) / 3, Rational(DBL_MIN) - Rational(0x1p-1074) / 7, Rational(1) - pow2(-200),
                              Rational(DBL_MAX) + pow2(969), -(Rational(DBL_MAX) + pow2(969))};
  std::mt19937_64 g(20261127);
  std::uniform_int_distribution<int> shift(-1200, 1200);
  for (int i = 0; i < 2000; ++i) {
    const Rational n(static_cast<long>(g() >> 1) - (1L << 62)), d(static_cast<long>(g() >> 2) + 1);
    qs.push_back(n / d * pow2(shift(g)));
  }
  for (const Rational& q : qs) {
    const auto [l, h] = enclose(q);
    BOOST_TEST(l == certcyl::detail::round_rational<double>(q, MPFR_RNDD));
    BOOST_TEST(h == certcyl::detail::round_rational<double>(q, MPFR_RNDU));
  }
}

BOOST_AUTO_TEST_CASE(every_binary64_prints_and_parses_back_exactly) {
  std::vector<double> values{0.0,      -0.0,     1.0,       -1.0,    0.1,          DBL_MAX, -DBL_MAX, DBL_MIN,
                             -DBL_MIN, 0x1p-1074, -0x1p-1074, 0x1.fffffffffffffp-1023, 1e308,  5e-324,   0x1p1023};
  std::mt19937_64 rng(20261122);  // fixed seed, printed on failure through the value
  for (int i = 0; i < 20000; ++i) {
    const double d = from_bits(rng());
    if (std::isfinite(d)) values.push_back(d);
  }
  for (int i = 0; i < 2000; ++i) values.push_back(from_bits(rng() & 0x000fffffffffffffULL));  // subnormals
  for (double d : values) {
    const std::string hex = to_hex_string(d);
    BOOST_TEST_REQUIRE(parse_rational(hex) == Rational(d), hex);
    BOOST_TEST_REQUIRE(is_binary64(parse_rational(hex)), hex);
    // The exact rational text reads back too.
    BOOST_TEST_REQUIRE(parse_rational(to_exact_string(Rational(d))) == Rational(d), hex);
    // Shortest decimal: reads back as the same binary64 (as a JSON number would), and its exact
    // rational rounds back to d.
    const std::string shortest = to_shortest_string(d);
    BOOST_TEST_REQUIRE(std::strtod(shortest.c_str(), nullptr) == d, hex);
    BOOST_TEST_REQUIRE(round_to_nearest<double>(parse_rational(shortest)) == d, hex);
    // Through JSON text and back.
    const nlohmann::json j = d;
    BOOST_TEST_REQUIRE(nlohmann::json::parse(j.dump()).get<double>() == d, hex);
    BOOST_TEST_REQUIRE(std::signbit(nlohmann::json::parse(j.dump()).get<double>()) == std::signbit(d), hex);
  }
}

BOOST_AUTO_TEST_CASE(exact_strings_are_canonical) {
  BOOST_TEST(to_exact_string(Rational(-6, 8)) == "-3/4");
  BOOST_TEST(to_exact_string(Rational(5)) == "5");
  BOOST_TEST(to_exact_string(parse_rational("0.1")) == "1/10");
  BOOST_TEST(to_hex_string(0.1875) == "0x1.8p-3");
  BOOST_TEST(to_hex_string(-2.0) == "-0x1p+1");
}
