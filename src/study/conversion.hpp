// study/conversion.hpp -- the instance as a method receives it, and why a wrong answer is wrong.
//
// Most methods read the binary64 input exactly. Two kinds do not: a number type narrower than
// binary64 (Gmpfr at 24 bits rounds every coordinate to nearest at 24 bits, nt::from_rational)
// and Bullet, which receives single-precision floats (its pose and half extents, a ray's ends
// computed in float: src/peers/peer_bullet.cpp). Such a method solves a differently rounded
// instance. Its Conversion names that instance and certifies it: the certified answer of the
// instance exactly as the method receives it, under the method's contract (study/contract.hpp),
// or `undecided` when that instance is not one the certified queries answer (Bullet's pose of a
// rotated cylinder: a float rotation matrix is not exactly orthonormal, so Bullet's cylinder is
// an oblique elliptic one, certified for rays and segments but not in pairs).
//
// A wrong answer (false positive, false negative or class mismatch against the certified answer
// C of the input, under the method's contract) is then split by the certified answer C' of the
// received instance:
//   conversion   C' already differs from C (as a Boolean answer for a false positive or
//                negative, as a three-valued one for a class mismatch): the rounding of the input
//                alone changed the answer;
//   algorithm    the method's answer differs from C' too: it is wrong on the instance it solved;
//   both         conversion and algorithm (a class mismatch only: a false positive or negative
//                is split as a Boolean answer, so it is one or the other);
//   unsplit      C' could not be certified.
// A method that reads the input exactly has C' = C: each of its wrong answers is `algorithm`.
#pragma once

#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include <mpfr.h>

#include "certcyl/certified/cylinder_cylinder.hpp"
#include "certcyl/certified/line_cylinder.hpp"
#include "certcyl/certified/triangle_cylinder.hpp"
#include "study/contract.hpp"
#include "study/instance.hpp"
#include "study/methods.hpp"

namespace certcyl::study {

// The instance a method receives: `certified(query, x, contract)` is the certified answer, under
// the contract, of the instance the method receives from the binary64 input x. Methods with the
// same `name` receive the same instance (the study certifies it once per instance).
struct Conversion {
  std::string name;
  std::function<Answer(Query, const std::vector<double>&, Contract)> certified;
};

// The certified answer of a binary64 instance under a contract, without the signed gap.
inline Answer certified_answer(Query q, const std::vector<double>& x, Contract c) {
  switch (q) {
    case Query::line_cylinder: return contract_answer(certified_line_cylinder(line_at(x), cylinder_at(x, 6)), c);
    case Query::ray_cylinder: return contract_answer(certified_line_cylinder(ray_at(x), cylinder_at(x, 6)), c);
    case Query::segment_cylinder: return contract_answer(certified_line_cylinder(segment_at(x), cylinder_at(x, 6)), c);
    case Query::line_elliptic_cylinder: return contract_answer(certified_line_cylinder(line_at(x), elliptic_at(x, 6)), c);
    case Query::triangle_cylinder: return certified_triangle_cylinder(triangle_at(x), cylinder_at(x, 9)).answer;
    case Query::cylinder_cylinder: return certified_cylinder_cylinder(cylinder_at(x, 0), cylinder_at(x, 7)).answer;
  }
  return Answer::undecided;
}

// d rounded to nearest (ties to even) at `bits` significant bits with an unbounded exponent, as
// nt::from_rational rounds for Gmpfr; nullopt when the result is not a finite double (a value
// near the largest double rounded up). A binary64 subnormal keeps at most `bits` significant
// bits at its own exponent, so it stays a double.
inline std::optional<double> round_to_bits(double d, long bits) {
  mpfr_t r;
  mpfr_init2(r, bits);
  mpfr_set_d(r, d, MPFR_RNDN);
  const double out = mpfr_get_d(r, MPFR_RNDN);
  const bool exact = mpfr_cmp_d(r, out) == 0;
  mpfr_clear(r);
  if (!exact || !std::isfinite(out)) return std::nullopt;
  return out;
}

// The conversion of a Gmpfr method at `bits` < 53: every coordinate rounded to `bits` bits.
inline Conversion rounding_to_bits(long bits) {
  return {"round" + std::to_string(bits), [bits](Query q, const std::vector<double>& x, Contract c) {
            std::vector<double> y(x.size());
            for (std::size_t i = 0; i < x.size(); ++i) {
              const std::optional<double> v = round_to_bits(x[i], bits);
              if (!v) return Answer::undecided;
              y[i] = *v;
            }
            try {
              return certified_answer(q, y, c);
            } catch (const std::exception&) {  // the rounding made the input invalid (a zero direction, p0 == p1)
              return Answer::undecided;
            }
          }};
}

enum class ErrorCause { none, algorithm, conversion, both, unsplit };

inline constexpr std::string_view to_string(ErrorCause e) {
  switch (e) {
    case ErrorCause::none: return "";
    case ErrorCause::algorithm: return "algorithm";
    case ErrorCause::conversion: return "conversion";
    case ErrorCause::both: return "conversion+algorithm";
    case ErrorCause::unsplit: return "unsplit";
  }
  return "";
}

inline std::ostream& operator<<(std::ostream& os, ErrorCause e) { return os << (e == ErrorCause::none ? "none" : to_string(e)); }

// Why the output m is wrong against the certified answer `original` (under the method's
// contract), given the certified answer `received` of the instance the method received
// (nullopt: it received the input exactly). `none` when m is not wrong.
inline ErrorCause error_cause(const MethodOutput& m, Answer original, const std::optional<Answer>& received) {
  if (original == Answer::undecided) return ErrorCause::none;
  const Outcome o = judge(m, original);
  if (o != Outcome::false_positive && o != Outcome::false_negative && o != Outcome::class_mismatch) return ErrorCause::none;
  if (!received) return ErrorCause::algorithm;
  if (*received == Answer::undecided) return ErrorCause::unsplit;
  // A false positive or negative is split as a Boolean answer: exactly one of the two holds (when
  // the rounding flipped the Boolean answer, the method's Boolean answer is the received one's).
  // A class mismatch is split as a three-valued answer, where both may hold.
  bool conversion = false, algorithm = false;
  if (o == Outcome::class_mismatch) {
    conversion = *received != original;
    const Outcome on_received = judge(m, *received);
    algorithm = on_received == Outcome::false_positive || on_received == Outcome::false_negative || on_received == Outcome::class_mismatch;
  } else {
    conversion = intersects(*received) != intersects(original);
    algorithm = !conversion;
  }
  if (conversion && algorithm) return ErrorCause::both;
  return conversion ? ErrorCause::conversion : ErrorCause::algorithm;
}

}  // namespace certcyl::study
