// certcyl/seeds/detail/eberly_common.hpp -- parameters, result and bookkeeping of the Eberly
// cylinder-cylinder separation test (certcyl/seeds/eberly_cylinders.hpp describes the algorithm).
#pragma once

#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>

#include "certcyl/answer.hpp"
#include "certcyl/errors.hpp"
#include "certcyl/number_traits.hpp"
#include "certcyl/vec3.hpp"

namespace certcyl {

// The two named variants (eberly_cylinders.hpp lists every difference).
enum class EberlyVariant { as_written, corrected };

// When a value f(D) of the separation function (seed equation (6)) counts as separating.
enum class Strictness {
  strict,      // f(D) < 0 separates; f(D) = 0 is a touching direction
  non_strict,  // f(D) <= 0 separates: touching counted as separated (seed section 3.1)
};

// How the top level decides that the axes are parallel.
enum class ParallelTest {
  exact_zero,  // |W0 x W1| = 0, as the pseudocode's `lenW0xW1 > 0`
  threshold,   // |W0 x W1| <= parallel_threshold
};

// The test that found the reported direction.
enum class EberlyTest {
  none,              // no test separated (overlapping), or none found a touching direction
  delta_zero,        // the centres coincide: overlapping without any test (corrected variant)
  w0,                // D = W0
  w1,                // D = W1
  w0xw1,             // D = W0 x W1
  perpendicular_w0,  // D perpendicular to W0 (SeparatedByCylinderPerpendiculars(0, 1))
  perpendicular_w1,  // D perpendicular to W1 (SeparatedByCylinderPerpendiculars(1, 0))
  other_directions,  // D found by the 2-D minimiser of G (SeparatedByOtherDirections)
  parallel_height,   // parallel axes, D = W0
  parallel_radial,   // parallel axes, D = Delta - (W0.Delta) W0
};

inline constexpr std::string_view to_string(EberlyTest t) {
  switch (t) {
    case EberlyTest::none: return "none";
    case EberlyTest::delta_zero: return "delta_zero";
    case EberlyTest::w0: return "w0";
    case EberlyTest::w1: return "w1";
    case EberlyTest::w0xw1: return "w0xw1";
    case EberlyTest::perpendicular_w0: return "perpendicular_w0";
    case EberlyTest::perpendicular_w1: return "perpendicular_w1";
    case EberlyTest::other_directions: return "other_directions";
    case EberlyTest::parallel_height: return "parallel_height";
    case EberlyTest::parallel_radial: return "parallel_radial";
  }
  return "none";
}

inline constexpr std::string_view to_string(EberlyVariant v) {
  return v == EberlyVariant::as_written ? "as_written" : "corrected";
}

// Which tests run. Disabling tests is for experiments and for the tests' "only this test
// separates" checks; the algorithm is the seed's only with every test enabled.
struct EberlyTestMask {
  bool w0 = true, w1 = true, w0xw1 = true;
  bool perpendicular_w0 = true, perpendicular_w1 = true, other_directions = true;
  bool parallel_height = true, parallel_radial = true;

  static EberlyTestMask none() { return {false, false, false, false, false, false, false, false}; }
  bool enabled(EberlyTest t) const {
    switch (t) {
      case EberlyTest::w0: return w0;
      case EberlyTest::w1: return w1;
      case EberlyTest::w0xw1: return w0xw1;
      case EberlyTest::perpendicular_w0: return perpendicular_w0;
      case EberlyTest::perpendicular_w1: return perpendicular_w1;
      case EberlyTest::other_directions: return other_directions;
      case EberlyTest::parallel_height: return parallel_height;
      case EberlyTest::parallel_radial: return parallel_radial;
      default: return true;
    }
  }
  EberlyTestMask& set(EberlyTest t, bool on) {
    switch (t) {
      case EberlyTest::w0: w0 = on; break;
      case EberlyTest::w1: w1 = on; break;
      case EberlyTest::w0xw1: w0xw1 = on; break;
      case EberlyTest::perpendicular_w0: perpendicular_w0 = on; break;
      case EberlyTest::perpendicular_w1: perpendicular_w1 = on; break;
      case EberlyTest::other_directions: other_directions = on; break;
      case EberlyTest::parallel_height: parallel_height = on; break;
      case EberlyTest::parallel_radial: parallel_radial = on; break;
      default: break;
    }
    return *this;
  }
};

// Every choice the seed leaves to the implementer. The default-constructed value is the
// corrected variant; `as_written()` gives the pseudocode's choices.
struct EberlyParameters {
  EberlyVariant variant = EberlyVariant::corrected;

  // Strictness of each comparison site. The pseudocode uses `< 0` at the top level (axis and
  // parallel tests) and `<= 0` in the perpendicular and other-direction tests.
  Strictness axis_tests = Strictness::strict;              // W0, W1, W0 x W1
  Strictness perpendicular_tests = Strictness::strict;     // F(t) at 0, 1 and each bisection point
  Strictness other_direction_tests = Strictness::strict;   // G(s,t) at every iterate
  Strictness parallel_tests = Strictness::strict;          // height and radial

  // `maxIterations` of the pseudocode: bisection steps on F' per quarter circle (per convex
  // piece in the corrected variant).
  int perpendicular_bisections = 32;
  // Bisection steps on gamma' in each line search of the 2-D minimiser.
  int line_search_bisections = 32;
  // Line searches per octant triangle (the minimiser's iteration limit).
  int max_line_searches = 32;
  // Stopping rule: after a line search from G_prev to G_new, stop the triangle when
  // G_prev - G_new <= min_relative_decrease * |G_new|. With 0 the search stops only when a
  // line search makes no progress, the projected direction vanishes, or max_line_searches is
  // reached.
  double min_relative_decrease = 0.0;

  // The parallel branch: exact zero test of |W0 x W1| (pseudocode) or a threshold on it.
  ParallelTest parallel_test = ParallelTest::exact_zero;
  double parallel_threshold = 0.0;

  EberlyTestMask enabled{};

  static EberlyParameters corrected() { return {}; }
  static EberlyParameters as_written() {
    EberlyParameters p;
    p.variant = EberlyVariant::as_written;
    p.axis_tests = Strictness::strict;
    p.perpendicular_tests = Strictness::non_strict;
    p.other_direction_tests = Strictness::non_strict;
    p.parallel_tests = Strictness::strict;
    return p;
  }
  static EberlyParameters of(EberlyVariant v) { return v == EberlyVariant::as_written ? as_written() : corrected(); }

  void validate() const {
    if (perpendicular_bisections < 0) throw InvalidInput("parameters.perpendicular_bisections", "must be >= 0");
    if (line_search_bisections < 1) throw InvalidInput("parameters.line_search_bisections", "must be >= 1");
    if (max_line_searches < 0) throw InvalidInput("parameters.max_line_searches", "must be >= 0");
    if (!(min_relative_decrease >= 0.0) || !std::isfinite(min_relative_decrease))
      throw InvalidInput("parameters.min_relative_decrease", "must be finite and >= 0");
    if (!(parallel_threshold >= 0.0) || !std::isfinite(parallel_threshold))
      throw InvalidInput("parameters.parallel_threshold", "must be finite and >= 0");
  }
};

// How often each function of the seed was evaluated.
struct EberlyCounters {
  std::uint64_t F = 0;             // F(t), perpendicular directions (seed equation (8))
  std::uint64_t F_derivative = 0;  // F'(t) (equation (9))
  std::uint64_t G = 0;             // G(s,t), other directions (equation (11))
  std::uint64_t G_gradient = 0;    // gradient of G, or a directional derivative of G
  std::uint64_t line_searches = 0;

  EberlyCounters& operator+=(const EberlyCounters& o) {
    F += o.F;
    F_derivative += o.F_derivative;
    G += o.G;
    G_gradient += o.G_gradient;
    line_searches += o.line_searches;
    return *this;
  }
  std::uint64_t evaluations() const { return F + F_derivative + G + G_gradient; }
};

template <class NT>
struct EberlySeparationResult {
  bool separated = false;            // the seed's boolean
  Answer answer = Answer::overlapping;  // as_written: separated or overlapping, as `separated` says
  Vec3<NT> direction;                // the separating (or touching) direction; zero otherwise
  EberlyTest test = EberlyTest::none;  // which test found it
  EberlyCounters counters;
  // Non-empty when a value left the finite numbers of NT (an overflow): the answer is then not
  // meaningful (separated = false, answer undecided) and this names the value, e.g. "h0" or
  // "f(D) of test w0". Both variants check the seed form (C_i, W_i, r_i, h_i, Delta, |Delta|^2);
  // the corrected variant also checks every value f(D) it judges.
  std::string non_finite;
};

namespace detail {

// A value the algorithm computed, or "undefined" where the seed's formula divides by zero or
// takes the square root of a negative rounding error. IEEE arithmetic gives NaN there and
// every comparison with NaN is false; undefined values are compared the same way for every
// number type, so the exact types follow the control flow double would follow.
template <class NT>
bool is_nan(const NT& x) {
  if constexpr (std::is_floating_point_v<NT>) {
    return std::isnan(x);
  } else if constexpr (std::is_same_v<NT, CGAL::Gmpfr>) {
    return x.is_nan();
  } else {
    return false;
  }
}

// Whether x is a finite number of NT: false for an infinity or a NaN of double, long double
// and Gmpfr, and for an interval with an infinite bound; the exact types are always finite.
template <class NT>
bool finite_value(const NT& x) {
  if constexpr (std::is_floating_point_v<NT>) {
    return std::isfinite(x);
  } else if constexpr (std::is_same_v<NT, CGAL::Gmpfr>) {
    return x.is_number();
  } else if constexpr (std::is_same_v<NT, Interval>) {
    return std::isfinite(x.inf()) && std::isfinite(x.sup());
  } else {
    return true;
  }
}
template <class NT>
bool finite_value(const Vec3<NT>& v) {
  return finite_value(v.x) && finite_value(v.y) && finite_value(v.z);
}

// The sign of x, or nullopt for an undefined value (NaN). Intervals throw when undecided.
template <class NT>
std::optional<CGAL::Sign> sign_of(const NT& x) {
  if (is_nan(x)) return std::nullopt;
  return nt::sign(x);
}
template <class NT>
std::optional<CGAL::Sign> sign_of(const std::optional<NT>& x) {
  if (!x) return std::nullopt;
  return sign_of(*x);
}

// The pseudocode's comparisons with 0; false on an undefined value.
template <class X>
bool less_zero(const X& x) { auto s = sign_of(x); return s && *s == CGAL::NEGATIVE; }
template <class X>
bool greater_zero(const X& x) { auto s = sign_of(x); return s && *s == CGAL::POSITIVE; }
template <class X>
bool less_equal_zero(const X& x) { auto s = sign_of(x); return s && *s != CGAL::POSITIVE; }
template <class X>
bool greater_equal_zero(const X& x) { auto s = sign_of(x); return s && *s != CGAL::NEGATIVE; }

// The type of the search parameters (t of the quarter circles; s, t, the line direction and
// the line parameter r of the 2-D minimiser). For double, long double and Gmpfr it is NT, so
// they run the seed's code literally. For CORE::Expr and Interval_nt it is Rational: every
// iterate computed in NT from the previous one would make CORE::Expr's expression DAG grow
// with each step (a deep DAG of square roots makes every later comparison slow), and would
// widen intervals step after step. The parameters only choose WHERE f is evaluated; every
// judged value is still computed in NT at that point. Bisection points are dyadic, hence the
// same in every type (up to binary64's 53 bits); the 2-D line direction, a heuristic, is
// rounded to binary64 for these two types.
template <class NT>
using EberlyParam = std::conditional_t<NumberTraits<NT>::is_exact || std::is_same_v<NT, Interval>, Rational, NT>;

template <class NT, class P>
NT param_to_nt(const P& x) {
  if constexpr (std::is_same_v<P, NT>) {
    return x;
  } else {
    return nt::from_rational<NT>(x);
  }
}

template <class NT>
EberlyParam<NT> nt_to_param(const NT& x) {
  if constexpr (std::is_same_v<EberlyParam<NT>, NT>) {
    return x;
  } else {
    return Rational(nt::to_double(x));
  }
}

template <class NT>
Vec3<NT> zero_vector() {
  return {nt::constant<NT>(0), nt::constant<NT>(0), nt::constant<NT>(0)};
}

// The state of one query: the result so far and the first touching direction seen.
template <class NT>
struct EberlyRun {
  const EberlyParameters& params;
  EberlySeparationResult<NT> result;
  bool touching_found = false;
  Vec3<NT> touching_direction = zero_vector<NT>();
  EberlyTest touching_test = EberlyTest::none;

  explicit EberlyRun(const EberlyParameters& p) : params(p) { result.direction = zero_vector<NT>(); }

  bool corrected() const { return params.variant == EberlyVariant::corrected; }

  // Judges one value f(D) of the separation function. Returns true when D separates (and
  // records it); in the corrected variant a strict site records f(D) = 0 as touching.
  // `direction` is a callable building D, called only when D is recorded.
  template <class MakeDirection>
  bool judge(const NT& f, Strictness strictness, EberlyTest test, MakeDirection&& direction) {
    // Corrected: a value that overflowed decides nothing; the search stops there (true) with
    // the value named and no answer. (As written, undefined values are compared as NaN is.)
    if (corrected() && !finite_value(f)) {
      stop_non_finite("f(D) of test " + std::string(to_string(test)));
      result.test = test;
      return true;
    }
    const auto s = sign_of(f);
    if (!s) return false;  // undefined: every comparison is false
    if (*s == CGAL::NEGATIVE || (*s == CGAL::ZERO && strictness == Strictness::non_strict)) {
      result.separated = true;
      result.answer = Answer::separated;
      result.direction = direction();
      result.test = test;
      return true;
    }
    if (*s == CGAL::ZERO && corrected() && !touching_found) {
      touching_found = true;
      touching_direction = direction();
      touching_test = test;
    }
    return false;
  }

  // Ends a query on a value that left the finite numbers: no answer (see non_finite).
  EberlySeparationResult<NT> stop_non_finite(std::string what) {
    result.separated = false;
    result.answer = Answer::undecided;
    result.direction = zero_vector<NT>();
    result.test = EberlyTest::none;
    result.non_finite = std::move(what);
    return result;
  }

  // Ends a query in which no test separated.
  EberlySeparationResult<NT> finish_not_separated() {
    result.separated = false;
    if (corrected() && touching_found) {
      result.answer = Answer::touching;
      result.direction = touching_direction;
      result.test = touching_test;
    } else {
      result.answer = Answer::overlapping;
      result.direction = zero_vector<NT>();
      result.test = EberlyTest::none;
    }
    return result;
  }
};

}  // namespace detail
}  // namespace certcyl
