// The module's parts, each binding its functions into the module (module.cpp):
//   batch_line.cpp   line, ray and segment against circular and elliptic cylinders, row by row
//   batch_solid.cpp  point, triangle and cylinder-pair queries, row by row
//   exact_query.cpp  one query line answered as `certcyl query` answers it
//   judge.cpp        a Python implementation judged in process as `certcyl judge` judges one
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstdint>
#include <string>

namespace certcyl::python {

namespace py = pybind11;

// The certified answers of a batch, one row per query: `answer` (int8 codes), `gap` (N x 2,
// the certified enclosure [lo, hi] of the signed gap; None when not asked for) with
// `gap_quantity` its name (study/gap_quantity.hpp: "depth_margin" or "log_phi") and for line,
// ray and segment queries `t_in`, `t_out` (the proved nearest doubles of the exact endpoints of
// the parameter interval, NaN when separated; None for the other queries).
struct BatchResult {
  std::string query;
  py::array_t<std::int8_t> answer;
  py::object gap = py::none(), gap_quantity = py::none(), t_in = py::none(), t_out = py::none();
};

void bind_line_batches(py::module_& m);
void bind_solid_batches(py::module_& m);
void bind_exact_query(py::module_& m);
void bind_judge(py::module_& m);

}  // namespace certcyl::python
