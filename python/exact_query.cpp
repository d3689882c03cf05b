// certcyl._answer_line: one query line answered exactly as `certcyl query` answers it
// (query.hpp: answer_line, the same reader, validation, methods and certificate), for
// certcyl.query, which builds the line from Python numbers (Fraction and strings exact) and
// reads the answer back with Fractions.
#include <string>

#include "batch.hpp"
#include "certcyl/dispatch.hpp"
#include "query.hpp"

namespace certcyl::python {

void bind_exact_query(py::module_& m) {
  m.def(
      "_answer_line",
      [](const std::string& line, const std::string& method, const std::string& nt) {
        cli::QueryOptions options;
        options.method = method;
        if (!nt.empty()) {
          options.nt = parse_number_type(nt);
          options.nt_given = true;
        }
        cli::ojson answer;
        {
          const py::gil_scoped_release release;
          answer = cli::answer_line(line, options, 1);
        }
        return answer.dump();
      },
      py::arg("line"), py::arg("method") = "certified", py::arg("nt") = "",
      "The answer line `certcyl query --method METHOD [--nt NT]` writes for one input line (JSON text).");
}

}  // namespace certcyl::python
