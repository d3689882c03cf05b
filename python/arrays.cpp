// Numpy operands as rows of doubles, the threaded loop over rows, certcyl.InvalidInput.
#include "arrays.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <exception>
#include <limits>
#include <mutex>
#include <optional>
#include <sstream>
#include <thread>

#include "certcyl/errors.hpp"

namespace certcyl::python {
namespace {

PyObject* invalid_input_type = nullptr;  // certcyl.InvalidInput, alive as long as the process

std::string shape_text(const py::array& a) {
  std::ostringstream s;
  s << '(';
  for (py::ssize_t d = 0; d < a.ndim(); ++d) s << (d ? ", " : "") << a.shape(d);
  s << (a.ndim() == 1 ? ",)" : ")");
  return s.str();
}

// Whether every value of a 64-bit integer array is a binary64 value.
template <class Int>
bool all_binary64(const py::array& a) {
  const auto values = py::array_t<Int, py::array::c_style>::ensure(a);
  const Int* p = values.data();
  for (py::ssize_t i = 0; i < values.size(); ++i) {
    const double d = static_cast<double>(p[i]);
    // 2^63 (or 2^64) is out of the integer's range: compare before converting back.
    if (d >= std::ldexp(1.0, std::numeric_limits<Int>::digits) || static_cast<Int>(d) != p[i]) return false;
  }
  return true;
}

}  // namespace

Rows::Rows(py::handle object, std::string name, std::size_t width, const std::string& function) : name_(std::move(name)), width_(width) {
  const auto fail = [&](const std::string& what) { throw py::value_error(function + ": " + name_ + ": " + what); };
  py::array a;
  try {
    a = py::array::ensure(object);
  } catch (const py::error_already_set&) {
  }
  if (!a) fail("not convertible to a numpy array");
  const py::dtype dt = a.dtype();
  const char kind = dt.kind();
  const auto size = dt.itemsize();
  const bool exact = (kind == 'f' && size <= 8) || ((kind == 'i' || kind == 'u') && size <= 4) ||
                     (kind == 'i' && size == 8 && all_binary64<std::int64_t>(a)) ||
                     (kind == 'u' && size == 8 && all_binary64<std::uint64_t>(a));
  if (!exact) {
    const std::string type = dt.attr("name").cast<std::string>();
    if ((kind == 'i' || kind == 'u') && size == 8) fail("dtype " + type + " holds a value that is not a binary64 value");
    fail("dtype " + type + " is not a real dtype float64 holds exactly (float16/32/64, integers)");
  }
  const auto w = static_cast<py::ssize_t>(width);
  const bool triangle = width == 9;
  bool ok = false;
  if (a.ndim() == 1 && a.shape(0) == w) {
    rows_ = 1, ok = true;
  } else if (a.ndim() == 2 && a.shape(1) == w) {
    rows_ = static_cast<std::size_t>(a.shape(0)), ok = true;
  } else if (triangle && a.ndim() == 2 && a.shape(0) == 3 && a.shape(1) == 3) {
    rows_ = 1, ok = true;
  } else if (triangle && a.ndim() == 3 && a.shape(1) == 3 && a.shape(2) == 3) {
    rows_ = static_cast<std::size_t>(a.shape(0)), ok = true;
  }
  if (!ok) {
    const std::string ws = std::to_string(width);
    fail("expected shape (N, " + ws + ") or (" + ws + ",)" + (triangle ? " or (N, 3, 3) or (3, 3)" : "") + ", got " +
         shape_text(a));
  }
  if (rows_ == 0) fail("no rows: shape " + shape_text(a));
  array_ = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
  data_ = array_.data();
}

std::size_t query_count(const std::vector<const Rows*>& operands, const std::string& function) {
  const Rows* many = nullptr;
  for (const Rows* r : operands) {
    if (r->rows() == 1) continue;
    if (many && many->rows() != r->rows())
      throw py::value_error(function + ": " + many->name() + " has " + std::to_string(many->rows()) + " rows and " +
                            r->name() + " " + std::to_string(r->rows()) + " (each operand has N rows or one)");
    many = r;
  }
  return many ? many->rows() : 1;
}

unsigned thread_count(long long threads, const std::string& function) {
  if (threads < 0)
    throw py::value_error(function + ": threads: expected 0 (every core) or a positive number of threads, got " +
                          std::to_string(threads));
  return static_cast<unsigned>(std::min<long long>(threads, 1 << 16));
}

void for_each_row(std::size_t n, unsigned threads, const std::string& function, const std::function<void(std::size_t)>& answer) {
  struct Failure {
    std::size_t row;
    std::string message, field;
    bool invalid_input;
  };
  std::optional<Failure> first;
  std::mutex mutex;
  const auto record = [&](Failure f) {
    const std::lock_guard lock(mutex);
    if (!first || f.row < first->row) first = std::move(f);
  };
  const auto run = [&](std::size_t begin, std::size_t end) {
    std::size_t i = begin;
    try {
      for (; i < end; ++i) answer(i);
    } catch (const InvalidInput& e) {
      record({i, e.what(), e.field(), true});
    } catch (const std::exception& e) {
      record({i, e.what(), "", false});
    }
  };
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  const std::size_t chunks = std::min<std::size_t>(threads, n);
  {
    const py::gil_scoped_release release;
    if (chunks <= 1) {
      run(0, n);
    } else {
      std::vector<std::thread> pool;
      for (std::size_t c = 0; c < chunks; ++c) pool.emplace_back(run, n * c / chunks, n * (c + 1) / chunks);
      for (std::thread& t : pool) t.join();
    }
  }
  if (!first) return;
  const std::string message = function + ": row " + std::to_string(first->row) + ": " + first->message;
  if (!first->invalid_input) throw std::runtime_error(message);
  const py::object error = py::reinterpret_borrow<py::object>(invalid_input_type)(message);
  error.attr("row") = first->row;
  error.attr("field") = first->field;
  PyErr_SetObject(invalid_input_type, error.ptr());
  throw py::error_already_set();
}

void register_invalid_input(py::module_& m) {
  invalid_input_type = PyErr_NewExceptionWithDoc(
      "certcyl.InvalidInput",
      "A row the library rejects (a ValueError): the message is '<function>: row <i>: <field>: <what>', as the\n"
      "certcyl command names the field; `row` is the row's index and `field` the field alone (\"cylinder.radius\").",
      PyExc_ValueError, nullptr);
  if (!invalid_input_type) throw py::error_already_set();
  m.add_object("InvalidInput", py::reinterpret_borrow<py::object>(invalid_input_type));
}

}  // namespace certcyl::python
