// certcyl._judge: a Python implementation of one study query judged in process as `certcyl
// judge` judges a co-process or a plugin (judge_internal.hpp): the cases of `certcyl cases`
// (make_cases), the function's answer to each read as the study reads an answer (answered),
// and the results folder and summary table (write_results).
//
// The function gets a case's operands as numpy arrays in the module's layout (line, ray:
// origin, direction, cylinder; segment: p0, p1, cylinder; elliptic: origin, direction, the
// 12 numbers of the elliptic cylinder; triangle: a 3 x 3 triangle, cylinder; cylinder pair: a,
// b; cylinders as p0, p1, radius): one case per call, or, vectorised, every case in one call
// with N rows per operand, returning N answers. An answer is an answer code (SEPARATED ...
// UNDECIDED of the module; a negative code is an error of the method), a bool (True: the sets
// meet, False: separated) or a word (`separated`, ..., `intersecting`, `undecided`, `invalid`,
// `error`); for a line query also (answer, t_in[, t_out]), its interval scored as an answers
// file's. Then, as for a plugin or a program, the failure maps of the query (judge_failure_maps:
// every cell in one call when vectorised) and the hunt for its worst input (judge_hunt, one input
// per call), sized by map_cells and hunt_evaluations as `certcyl judge` sizes them; a ray or
// segment query judged under `contract` (`certcyl judge --contract`). An exception
// raised by the function ends the run as a crashed plugin ends it: what was answered before it
// is written (the maps and the hunt with their failure), and the exception is raised again
// naming the case. The cases' calls are timed as a whole (speed.csv, the report's speed).
#include <algorithm>
#include <chrono>
#include <exception>
#include <filesystem>
#include <limits>
#include <optional>
#include <sstream>
#include <vector>

#include <pybind11/stl.h>

#include "arrays.hpp"
#include "batch.hpp"
#include "judge_internal.hpp"

namespace certcyl::python {
namespace {

// The widths of a query's operands in the study's flat layout (study/instance.hpp).
std::vector<std::size_t> operand_widths(study::Query q) {
  switch (q) {
    case study::Query::line_cylinder:
    case study::Query::ray_cylinder:
    case study::Query::segment_cylinder: return {3, 3, 7};
    case study::Query::line_elliptic_cylinder: return {3, 3, 12};
    case study::Query::triangle_cylinder: return {9, 7};
    case study::Query::cylinder_cylinder: return {7, 7};
  }
  return {};
}

// The operands of cases [begin, end) as arrays: N x width (or width alone for a single case;
// triangles N x 3 x 3 or 3 x 3).
py::tuple operands(const std::vector<cli::Case>& cases, std::size_t begin, std::size_t end, bool vectorized) {
  const std::vector<std::size_t> widths = operand_widths(cases[begin].query);
  const bool triangle_first = cases[begin].query == study::Query::triangle_cylinder;
  py::tuple args(widths.size());
  std::size_t at = 0;
  for (std::size_t k = 0; k < widths.size(); ++k) {
    const auto n = static_cast<py::ssize_t>(end - begin), w = static_cast<py::ssize_t>(widths[k]);
    std::vector<py::ssize_t> shape;
    if (vectorized) shape.push_back(n);
    if (k == 0 && triangle_first) {
      shape.insert(shape.end(), {3, 3});
    } else {
      shape.push_back(w);
    }
    py::array_t<double> a(shape);
    double* p = a.mutable_data();
    for (std::size_t i = begin; i < end; ++i)
      for (std::size_t j = 0; j < widths[k]; ++j) *p++ = cases[i].x[at + j];
    args[k] = std::move(a);
    at += widths[k];
  }
  return args;
}

// The answer word of one value the function returned; throws ValueError for anything else.
std::string answer_word(py::handle value, const cli::Case& c) {
  const auto fail = [&](const std::string& what) {
    throw py::value_error("judge: case " + c.id + ": " + what + " (expected an answer code, a bool or an answer word)");
  };
  if (py::isinstance<py::bool_>(value) || py::isinstance(value, py::module_::import("numpy").attr("bool_")))
    return value.cast<bool>() ? "intersecting" : "separated";
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::hasattr(value, "__index__")) {
    const long code = py::int_(py::reinterpret_borrow<py::object>(value)).cast<long>();
    if (code < 0) return "error";
    switch (code) {
      case kSeparated: return "separated";
      case kTouching: return "touching";
      case kOverlapping: return "overlapping";
      case kIntersecting: return "intersecting";
      case kUndecided: return "undecided";
      default: fail("answer code " + std::to_string(code));
    }
  }
  fail("the function returned " + py::repr(value).cast<std::string>());
  return {};
}

cli::judging::Answered read_word(py::handle value, const cli::Case& c) {
  const std::string word = answer_word(value, c);
  try {
    return cli::judging::answered(word);
  } catch (const std::invalid_argument&) {
    throw py::value_error("judge: case " + c.id + ": unknown answer '" + word + "'");
  }
}

// An answer, or (answer, t_in) / (answer, t_in, t_out) for a line query: the interval, scored as
// `certcyl judge` scores an answers file's (judge_report.cpp, t_error_of); None for none.
cli::judging::Answered read_answer(py::handle value, const cli::Case& c) {
  if (!py::isinstance<py::tuple>(value) && !py::isinstance<py::list>(value)) return read_word(value, c);
  const py::sequence s = py::reinterpret_borrow<py::sequence>(value);
  if (!study::is_line_query(c.query) || (s.size() != 2 && s.size() != 3) || py::isinstance<py::tuple>(s[0]) ||
      py::isinstance<py::list>(s[0]))
    throw py::value_error("judge: case " + c.id + ": the function returned " + py::repr(value).cast<std::string>() +
                          " (a line, ray or segment query may return (answer, t_in) or (answer, t_in, t_out))");
  cli::judging::Answered a = read_word(s[0], c);
  const auto number = [&](py::handle x) {
    if (x.is_none()) return std::numeric_limits<double>::quiet_NaN();
    try {
      return py::float_(py::reinterpret_borrow<py::object>(x)).cast<double>();
    } catch (const py::error_already_set&) {
      throw py::value_error("judge: case " + c.id + ": interval: not a number: " + py::repr(x).cast<std::string>());
    }
  };
  a.output.t_in = number(s[1]);
  if (s.size() == 3) a.t_out = number(s[2]);
  return a;
}

// The function's answers to `cases` (one call with every case when vectorized, else one per
// case). Its first exception ends the answers (Answers::failure names the case) and is kept in
// `error` with a note; after it, no call is made (every later exchange fails at once).
cli::judging::Answers answer_cases(const py::function& function, const std::vector<cli::Case>& cases, bool vectorized,
                                   const std::filesystem::path& dir, std::exception_ptr& error) {
  cli::judging::Answers answers;
  answers.answers.resize(cases.size());
  if (error) {
    answers.failure = "not called after the function's exception";
    return answers;
  }
  if (cases.empty()) return answers;
  // The function's exception gets a note naming the case; the run's failure says the same.
  const auto failed = [&](const std::string& what) {
    answers.failure = what;
    error = std::current_exception();
    try {
      throw;
    } catch (py::error_already_set& e) {
      if (py::hasattr(e.value(), "add_note")) e.value().attr("add_note")("certcyl.judge: " + what + "; results so far in " + dir.string());
    } catch (...) {
    }
  };
  if (vectorized) {
    try {
      const py::object result = function(*operands(cases, 0, cases.size(), true));
      const py::list values = py::list(py::module_::import("numpy").attr("asarray")(result, "object").attr("tolist")());
      if (values.size() != cases.size())
        throw py::value_error("judge: the function returned " + std::to_string(values.size()) + " answers for " +
                              std::to_string(cases.size()) + " cases");
      for (std::size_t i = 0; i < cases.size(); ++i) answers.answers[i] = read_answer(values[i], cases[i]);
    } catch (const std::exception& e) {
      answers.answers.assign(cases.size(), std::nullopt);
      failed(std::string("the function failed: ") + e.what());
    }
  } else {
    for (std::size_t i = 0; i < cases.size() && !error; ++i) {
      try {
        answers.answers[i] = read_answer(function(*operands(cases, i, i + 1, false)), cases[i]);
      } catch (const std::exception& e) {
        failed("the function failed on case " + cases[i].id + " (line " + std::to_string(cases[i].line) + "): " + e.what());
      }
    }
  }
  return answers;
}

// map_cells, hunt_evaluations: -1 for the size's (as `certcyl judge`), 0 for none.
py::tuple judge(py::function function, const std::string& query, const std::string& size, std::uint64_t seed,
                const std::vector<std::string>& families, bool vectorized, const std::string& method, const std::string& out_root,
                const std::string& name, unsigned threads, int map_cells, long map_step, long hunt_evaluations,
                const std::string& contract_name) {
  const study::Contract contract = cli::parse_contract(contract_name, "judge: contract");
  cli::CaseSpec spec;
  spec.query = query;
  spec.size = size;
  spec.seed = seed;
  spec.families = families;
  spec.threads = threads;
  std::vector<cli::Case> cases;
  {
    const py::gil_scoped_release release;
    cases = cli::make_cases(spec);
  }
  if (cases.empty()) throw py::value_error("judge: no cases for query " + query);

  const std::filesystem::path dir = std::filesystem::path(out_root) / name;
  std::exception_ptr error;
  const auto start = std::chrono::steady_clock::now();
  cli::judging::Answers answers = answer_cases(function, cases, vectorized, dir, error);
  if (answers.failure.empty()) {
    answers.ns_per_query = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start).count() /
                           static_cast<double>(cases.size());
    answers.timing = vectorized ? "per query in process, the one call with every case (the operands' arrays included)"
                                : "per query in process, one call per case (the operands' arrays and the call included)";
  }

  // The failure maps and the hunt, by the same calls, as `certcyl judge` draws them for a plugin
  // or a program (not after an exception on the cases).
  std::optional<cli::judging::MapsResult> maps;
  std::optional<cli::judging::HuntResult> hunt;
  const int cells = map_cells < 0 ? cli::judging::map_cells_of_size(size) : map_cells;
  if (cells > 0) {
    maps.emplace();
    if (!answers.failure.empty()) {
      maps->note = "not drawn, the method having failed on the cases";
    } else {
      const std::vector<study::Query> queries{cases.front().query};
      const cli::judging::AnswerSource source = [&](const std::vector<cli::Case>& cells_asked) {
        const py::gil_scoped_acquire acquire;
        return answer_cases(function, cells_asked, vectorized, dir, error);
      };
      const py::gil_scoped_release release;
      std::filesystem::create_directories(dir);
      *maps = cli::judging::judge_failure_maps(dir, method, queries, source, cells, map_step, seed, std::max(1u, threads), contract);
      const long evaluations = hunt_evaluations < 0 ? cli::judging::hunt_evaluations_of_size(size) : hunt_evaluations;
      if (evaluations > 0) hunt = cli::judging::judge_hunt(dir, method, queries, source, evaluations, seed, contract);
    }
  }
  std::ostringstream summary;
  {
    const py::gil_scoped_release release;
    cli::judging::write_results(dir, dir, method, cases, answers, summary, maps ? &*maps : nullptr, hunt ? &*hunt : nullptr, contract);
  }
  if (error) std::rethrow_exception(error);
  return py::make_tuple(summary.str(), dir.string());
}

}  // namespace

void bind_judge(py::module_& m) {
  m.def("_judge", &judge, py::arg("function"), py::arg("query"), py::arg("size"), py::arg("seed"), py::arg("families"),
        py::arg("vectorized"), py::arg("method"), py::arg("out"), py::arg("name"), py::arg("threads"), py::arg("map_cells"),
        py::arg("map_step"), py::arg("hunt_evaluations"), py::arg("contract"),
        "The in-process judge behind certcyl.judge: returns (summary table, results folder).");
}

}  // namespace certcyl::python
