// The compiled module certcyl._certcyl (re-exported by certcyl/__init__.py): the answer codes,
// certcyl.InvalidInput, the BatchResult of the batch functions and the functions of each part
// (batch.hpp).
#include <sstream>

#include "arrays.hpp"
#include "batch.hpp"

namespace certcyl::python {
namespace {

std::string batch_repr(const BatchResult& r) {
  const std::int8_t* a = r.answer.data();
  std::size_t counts[5] = {};
  for (py::ssize_t i = 0; i < r.answer.size(); ++i) ++counts[a[i]];
  std::ostringstream s;
  s << "<certcyl.BatchResult " << r.query << ", " << r.answer.size() << (r.answer.size() == 1 ? " query" : " queries") << ": "
    << counts[kSeparated] << " separated, " << counts[kTouching] << " touching, " << counts[kOverlapping] << " overlapping";
  if (counts[kUndecided]) s << ", " << counts[kUndecided] << " undecided";
  s << ">";
  return s.str();
}

}  // namespace

PYBIND11_MODULE(_certcyl, m) {
  m.doc() = "Certified cylinder queries on numpy arrays (the compiled part of the certcyl package).";
  m.attr("SEPARATED") = kSeparated;
  m.attr("TOUCHING") = kTouching;
  m.attr("OVERLAPPING") = kOverlapping;
  m.attr("INTERSECTING") = kIntersecting;
  m.attr("UNDECIDED") = kUndecided;
  register_invalid_input(m);

  py::class_<BatchResult>(m, "BatchResult",
                          "The certified answers of a batch, one row per query (see the function that returned it).")
      .def_readonly("query", &BatchResult::query, "The query's name.")
      .def_readonly("answer", &BatchResult::answer, "int8 answer codes: SEPARATED, TOUCHING, OVERLAPPING (UNDECIDED: cylinder pairs).")
      .def_readonly("gap", &BatchResult::gap, "N x 2: the certified enclosure [lo, hi] of the signed gap (None when not computed).")
      .def_readonly("gap_quantity", &BatchResult::gap_quantity,
                    "What gap measures: 'log_phi' (cylinder pairs) or 'depth_margin' (the other queries); None without gap.")
      .def_readonly("t_in", &BatchResult::t_in, "Line, ray, segment: the nearest double of the exact entry parameter (NaN when separated).")
      .def_readonly("t_out", &BatchResult::t_out, "Line, ray, segment: the nearest double of the exact exit parameter (NaN when separated).")
      .def("__len__", [](const BatchResult& r) { return r.answer.size(); })
      .def("__repr__", &batch_repr);

  bind_line_batches(m);
  bind_solid_batches(m);
  bind_exact_query(m);
  bind_judge(m);
}

}  // namespace certcyl::python
