// The batch functions' plumbing: numpy operands read as rows of binary64 values (one operand may
// be a single row broadcast against the others), the rows answered by `threads` threads with the
// GIL released, and a row the library rejects raised as certcyl.InvalidInput.
//
// An operand is converted to a C-contiguous float64 array. Accepted dtypes are those whose
// values float64 holds exactly: floating types up to 64 bits, integers up to 32 bits, and 64-bit
// integers whose every value is a binary64 value; anything else (complex, bool, object, strings,
// long double) is a ValueError naming the argument and the dtype. Shapes: (N, width) or (width,)
// (a single row); triangles also (N, 3, 3) or (3, 3). A wrong shape is a ValueError naming the
// argument, the shape expected and the shape given.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "certcyl/answer.hpp"
#include "certcyl/primitives.hpp"

namespace certcyl::python {

namespace py = pybind11;

// The answer codes of the module (and of certcyl/plugin.h).
inline constexpr int kSeparated = 0, kTouching = 1, kOverlapping = 2, kIntersecting = 3, kUndecided = 4;

inline int answer_code(Answer a) {
  switch (a) {
    case Answer::separated: return kSeparated;
    case Answer::touching: return kTouching;
    case Answer::overlapping: return kOverlapping;
    case Answer::undecided: return kUndecided;
  }
  return kUndecided;
}

// One operand: `rows` rows of `width` doubles (rows == 1 is broadcast).
class Rows {
 public:
  Rows(py::handle object, std::string name, std::size_t width, const std::string& function);

  const std::string& name() const { return name_; }
  std::size_t rows() const { return rows_; }
  // Row i (row 0 when broadcast).
  const double* row(std::size_t i) const { return data_ + (rows_ == 1 ? 0 : i * width_); }

  Point3<double> point(std::size_t i, std::size_t at = 0) const {
    const double* r = row(i) + at;
    return {r[0], r[1], r[2]};
  }
  // p0, p1, radius.
  Cylinder<double> cylinder(std::size_t i) const { return {point(i, 0), point(i, 3), row(i)[6]}; }
  // base, a, b, c.
  EllipticCylinder<double> elliptic(std::size_t i) const { return {point(i, 0), point(i, 3), point(i, 6), point(i, 9)}; }
  Triangle<double> triangle(std::size_t i) const { return {{point(i, 0), point(i, 3), point(i, 6)}}; }

 private:
  py::array_t<double, py::array::c_style> array_;
  std::string name_;
  std::size_t width_ = 0, rows_ = 0;
  const double* data_ = nullptr;
};

// The number of queries of a call: the operands' rows, all equal but for single rows. Throws
// ValueError naming the operands that disagree.
std::size_t query_count(const std::vector<const Rows*>& operands, const std::string& function);

// The `threads` argument of a batch function: 0 (every core) or a positive count; a negative
// count is a ValueError naming the function and the argument.
unsigned thread_count(long long threads, const std::string& function);

// Answers rows [0, n) with answer(i) on `threads` threads (0: every core), each a contiguous
// chunk, with the GIL released. A row whose operands the library rejects (InvalidInput) stops
// its chunk; the smallest such row is raised as certcyl.InvalidInput ("<function>: row <i>:
// <the library's message>", with attributes `row` and `field`); any other exception is raised
// with the row.
void for_each_row(std::size_t n, unsigned threads, const std::string& function, const std::function<void(std::size_t)>& answer);

// The exception class certcyl.InvalidInput (a ValueError), registered by the module.
void register_invalid_input(py::module_& m);

}  // namespace certcyl::python
