// fuzz/fuzz_input.hpp -- decoding a fuzzer's bytes into the numbers of a query.
//
// Each number takes a tag byte, then:
//   tag >= 0x80   the next 8 bytes as a binary64 bit pattern (every pattern: subnormals, huge
//                 values, negative zero; NaN and infinities are reported as non-finite);
//   tag <  0x80   the next byte as a signed integer k, and the number is k * 2^-(tag % 8):
//                 small dyadic values, so coincidences (tangencies, shared planes) are common.
// Missing bytes read as zero. A harness skips inputs with a non-finite number or that fail
// the library's validation, as the command's input boundary would reject them.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>

#include "certcyl/primitives.hpp"
#include "certcyl/rational.hpp"

namespace certcyl::fuzz {

class ByteReader {
 public:
  ByteReader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

  std::uint8_t byte() { return pos_ < size_ ? data_[pos_++] : 0; }

  double number() {
    const std::uint8_t tag = byte();
    if (tag >= 0x80) {
      std::uint64_t bits = 0;
      for (int i = 0; i < 8; ++i) bits |= static_cast<std::uint64_t>(byte()) << (8 * i);
      double d;
      std::memcpy(&d, &bits, sizeof d);
      finite_ = finite_ && std::isfinite(d);
      return d;
    }
    const int k = static_cast<std::int8_t>(byte());
    return std::ldexp(static_cast<double>(k), -(tag % 8));
  }

  Rational rational() {
    const double d = number();
    return std::isfinite(d) ? Rational(d) : Rational(0);
  }
  Vec3<Rational> vec3() {
    Rational x = rational(), y = rational(), z = rational();
    return {x, y, z};
  }
  Cylinder<Rational> cylinder() {
    Vec3<Rational> p0 = vec3(), p1 = vec3();
    return {p0, p1, rational()};
  }

  // False when some number was NaN or infinite.
  bool finite() const { return finite_; }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
  bool finite_ = true;
};

// A failure: print what failed and abort, so the fuzzer saves the input.
[[noreturn]] inline void failure(const std::string& what) {
  std::cerr << what << std::endl;
  std::abort();
}

// A wrong answer.
[[noreturn]] inline void wrong_answer(const std::string& what) { failure("WRONG CERTIFIED ANSWER: " + what); }

}  // namespace certcyl::fuzz
