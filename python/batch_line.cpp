// certcyl.line_cylinder, ray_cylinder, segment_cylinder and their elliptic counterparts: the
// certified query (certified/line_cylinder.hpp) on each row, its answer, the proved nearest
// doubles of its endpoints and the study's certified signed gap (study/gap.hpp: the depth
// margin, computed exactly from the rows' binary64 values and enclosed in doubles).
#include <cmath>
#include <limits>

#include "arrays.hpp"
#include "batch.hpp"
#include "certcyl/certified/line_cylinder.hpp"
#include "study/gap.hpp"

namespace certcyl::python {
namespace {

Rational exact(double x) { return Rational(x); }

// The line-like set as an exact origin and direction (a segment's direction p1 - p0 computed
// exactly, never rounded), and its range of t.
Line<Rational> exact_line(const Line<double>& l) { return {l.origin.map(exact), l.direction.map(exact)}; }
Line<Rational> exact_line(const Ray<double>& r) { return {r.origin.map(exact), r.direction.map(exact)}; }
Line<Rational> exact_line(const Segment<double>& g) {
  const Segment<Rational> e = g.map(exact);
  return {e.p0, e.direction()};
}
LineRange range_of(const Line<double>&) { return LineRange::line; }
LineRange range_of(const Ray<double>&) { return LineRange::ray; }
LineRange range_of(const Segment<double>&) { return LineRange::segment; }

// The depth margin against a circular cylinder (study/gap.hpp).
study::MarginEnclosure line_gap(const Line<Rational>& l, const Cylinder<double>& c, LineRange range) {
  return study::detail::circular_line_gap(l, c.map(exact), range);
}

// The same against an elliptic cylinder, in its unit frame y = M^-1 (X - base), M = [a b c].
study::MarginEnclosure line_gap(const Line<Rational>& l, const EllipticCylinder<double>& ed, LineRange range) {
  return study::detail::elliptic_line_gap(l, ed.map(exact), range);
}

template <class LineLike, class Solid>
study::MarginEnclosure gap_of(const LineLike& l, const Solid& s) {
  return line_gap(exact_line(l), s, range_of(l));
}

// The rows of one call: `make(first, second, i)` builds row i's line, ray or segment; `solid(i)`
// its cylinder.
template <class MakeLine, class MakeSolid>
BatchResult line_batch(const std::string& query, const Rows& first, const Rows& second, const Rows& solids, unsigned threads,
                       bool want_gap, MakeLine make, MakeSolid solid) {
  const std::size_t n = query_count({&first, &second, &solids}, query);
  const auto count = static_cast<py::ssize_t>(n);
  BatchResult out{query, py::array_t<std::int8_t>(count)};
  py::array_t<double> t_in(count), t_out(count), gap;
  if (want_gap) gap = py::array_t<double>({count, py::ssize_t{2}});
  std::int8_t* answer = out.answer.mutable_data();
  double* in = t_in.mutable_data();
  double* end = t_out.mutable_data();
  double* g = want_gap ? gap.mutable_data() : nullptr;
  for_each_row(n, threads, query, [&](std::size_t i) {
    const auto line = make(first, second, i);
    const auto cylinder = solid(i);
    const CertifiedLineResult r = certified_line_cylinder(line, cylinder);
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    answer[i] = static_cast<std::int8_t>(answer_code(r.answer));
    in[i] = r.in ? r.in->nearest : nan;
    end[i] = r.out ? r.out->nearest : nan;
    if (g) std::tie(g[2 * i], g[2 * i + 1]) = study::detail::enclose_margin_doubles(gap_of(line, cylinder));
  });
  out.t_in = std::move(t_in);
  out.t_out = std::move(t_out);
  if (want_gap) {
    out.gap = std::move(gap);
    out.gap_quantity = py::str(std::string(study::to_string(study::gap_quantity(out.query))));
  }
  return out;
}

template <template <class> class LineLike>
LineLike<double> line_row(const Rows& a, const Rows& b, std::size_t i) {
  return {a.point(i), b.point(i)};
}

constexpr const char* kLineDoc = R"(Certified {what} against {solid}, one query per row.

{operands}
One operand may be a single row, broadcast against the others. threads: threads answering the
rows (0: every core); the GIL is released. gap: also compute the certified signed gap (the
study's depth margin: negative separated, zero touching, positive overlapping).

Returns a BatchResult: answer (int8 codes SEPARATED, TOUCHING, OVERLAPPING), t_in and t_out (the
proved nearest doubles of the exact ends of the parameter interval {param}, NaN when separated)
and gap (N x 2, the enclosure [lo, hi] of the exact gap; None with gap=False).
Raises ValueError on a wrong shape or dtype, certcyl.InvalidInput on a row the library rejects
(non-finite number, zero direction{segment_error}, radius <= 0, {solid_error}).)";

std::string line_doc(const std::string& what, bool elliptic, const std::string& operands, const std::string& param,
                     bool segment) {
  std::string doc = kLineDoc;
  const auto put = [&](const std::string& key, const std::string& value) {
    const auto at = doc.find(key);
    doc.replace(at, key.size(), value);
  };
  put("{what}", what);
  put("{solid}", elliptic ? "solid elliptic cylinders" : "solid circular cylinders");
  put("{operands}", operands + (elliptic ? "\ncylinders: N x 12 (base, a, b, c: {base + x a + y b + z c : x^2 + y^2 <= 1, 0 <= z <= 1})."
                                          : "\ncylinders: N x 7 (p0, p1, radius)."));
  put("{param}", param);
  put("{segment_error}", segment ? ", p0 == p1" : "");
  put("{solid_error}", elliptic ? "det[a b c] = 0" : "p0 == p1 of a cylinder");
  return doc;
}

template <template <class> class Solid>
void bind_family(py::module_& m, const std::string& suffix) {
  constexpr bool elliptic = std::is_same_v<Solid<double>, EllipticCylinder<double>>;
  const std::size_t width = elliptic ? 12 : 7;
  const auto solid_of = [](const Rows& rows) {
    return [&rows](std::size_t i) {
      if constexpr (elliptic) {
        return rows.elliptic(i);
      } else {
        return rows.cylinder(i);
      }
    };
  };
  const std::string lines = "origins, directions: N x 3 (X = origin + t direction, direction not normalised).";
  for (const auto& [kind, param] : {std::pair{std::string("line"), std::string("(all t)")}, std::pair{std::string("ray"), std::string("(t >= 0)")}}) {
    const std::string name = kind + suffix;
    const bool ray = kind == "ray";
    m.def(
        name.c_str(),
        [name, width, solid_of, ray](py::handle origins, py::handle directions, py::handle cylinders, long long threads, bool gap) {
          const Rows o(origins, "origins", 3, name), d(directions, "directions", 3, name), c(cylinders, "cylinders", width, name);
          if (ray) return line_batch(name, o, d, c, thread_count(threads, name), gap, line_row<Ray>, solid_of(c));
          return line_batch(name, o, d, c, thread_count(threads, name), gap, line_row<Line>, solid_of(c));
        },
        py::arg("origins"), py::arg("directions"), py::arg("cylinders"), py::kw_only(), py::arg("threads") = 1,
        py::arg("gap") = true, line_doc(ray ? "rays" : "lines", elliptic, lines, param, false).c_str());
  }
  const std::string name = "segment" + suffix;
  m.def(
      name.c_str(),
      [name, width, solid_of](py::handle p0s, py::handle p1s, py::handle cylinders, long long threads, bool gap) {
        const Rows a(p0s, "p0s", 3, name), b(p1s, "p1s", 3, name), c(cylinders, "cylinders", width, name);
        return line_batch(name, a, b, c, thread_count(threads, name), gap, line_row<Segment>, solid_of(c));
      },
      py::arg("p0s"), py::arg("p1s"), py::arg("cylinders"), py::kw_only(), py::arg("threads") = 1, py::arg("gap") = true,
      line_doc("segments", elliptic, "p0s, p1s: N x 3 (X = p0 + t (p1 - p0)).", "(t in [0, 1] from p0 to p1)", true).c_str());
}

}  // namespace

void bind_line_batches(py::module_& m) {
  bind_family<Cylinder>(m, "_cylinder");
  bind_family<EllipticCylinder>(m, "_elliptic_cylinder");
}

}  // namespace certcyl::python
