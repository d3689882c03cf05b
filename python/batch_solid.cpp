// certcyl.point_cylinder, point_elliptic_cylinder, triangle_cylinder and cylinder_cylinder: the
// certified query on each row, its answer and its certified signed gap: for points and
// triangles the study's depth margin (study/gap.hpp; for a point, the margin of the one point),
// for cylinder pairs log(phi*), enclosed as `certcyl query` encloses it (refine_gap).
#include <cmath>
#include <limits>

#include "arrays.hpp"
#include "batch.hpp"
#include "certcyl/certified/cylinder_cylinder.hpp"
#include "certcyl/certified/point_cylinder.hpp"
#include "certcyl/certified/triangle_cylinder.hpp"
#include "study/gap.hpp"

namespace certcyl::python {
namespace {

Rational exact(double x) { return Rational(x); }

// The depth margin of one point, its depth min(1 - q, s, 1 - s) with s its axial and q its
// squared radial coordinate (study/gap.hpp).
Rational point_gap(const Point3<double>& x, const Cylinder<double>& cd) {
  return study::detail::circular_point_gap(x.map(exact), cd.map(exact));
}

Rational point_gap(const Point3<double>& x, const EllipticCylinder<double>& ed) {
  return study::detail::elliptic_point_gap(x.map(exact), ed.map(exact));
}

// Allocates the result of n rows; `row(i, answer, gap)` fills row i (gap: two doubles, or null).
template <class Row>
BatchResult solid_batch(const std::string& query, std::size_t n, unsigned threads, bool want_gap, Row row) {
  const auto count = static_cast<py::ssize_t>(n);
  BatchResult out{query, py::array_t<std::int8_t>(count)};
  py::array_t<double> gap;
  if (want_gap) gap = py::array_t<double>({count, py::ssize_t{2}});
  std::int8_t* answer = out.answer.mutable_data();
  double* g = want_gap ? gap.mutable_data() : nullptr;
  for_each_row(n, threads, query, [&](std::size_t i) {
    answer[i] = static_cast<std::int8_t>(answer_code(row(i, g ? g + 2 * i : nullptr)));
  });
  if (want_gap) {
    out.gap = std::move(gap);
    out.gap_quantity = py::str(std::string(study::to_string(study::gap_quantity(out.query))));
  }
  return out;
}

template <class Solid>
BatchResult point_batch(const std::string& query, const Rows& points, const Rows& solids, unsigned threads, bool want_gap) {
  const std::size_t n = query_count({&points, &solids}, query);
  return solid_batch(query, n, threads, want_gap, [&](std::size_t i, double* g) {
    const Point3<double> x = points.point(i);
    Solid s;
    if constexpr (std::is_same_v<Solid, Cylinder<double>>) {
      s = solids.cylinder(i);
    } else {
      s = solids.elliptic(i);
    }
    const CertifiedPointResult r = certified_point_cylinder(x, s);
    if (g) std::tie(g[0], g[1]) = study::detail::enclose_rational(point_gap(x, s));
    return r.answer;
  });
}

BatchResult triangle_batch(const Rows& triangles, const Rows& cylinders, unsigned threads, bool want_gap) {
  const std::string query = "triangle_cylinder";
  const std::size_t n = query_count({&triangles, &cylinders}, query);
  return solid_batch(query, n, threads, want_gap, [&](std::size_t i, double* g) {
    const Triangle<double> t = triangles.triangle(i);
    const Cylinder<double> c = cylinders.cylinder(i);
    const TriangleCylinderResult r = certified_triangle_cylinder(t, c);
    if (g) std::tie(g[0], g[1]) = study::detail::enclose_margin_doubles(study::detail::triangle_margin(t.map(exact), c.map(exact)));
    return r.answer;
  });
}

BatchResult pair_batch(const Rows& a, const Rows& b, unsigned threads, bool want_gap) {
  const std::string query = "cylinder_cylinder";
  const std::size_t n = query_count({&a, &b}, query);
  CylinderCylinderOptions options;
  options.refine_gap = want_gap;  // as `certcyl query`
  if (!want_gap) options.gap_enclosure = GapEnclosure::off;
  return solid_batch(query, n, threads, want_gap, [&](std::size_t i, double* g) {
    const CylinderCylinderResult r = certified_cylinder_cylinder(a.cylinder(i), b.cylinder(i), options);
    if (g) {
      const CylinderGap gap = r.gap();
      constexpr double inf = std::numeric_limits<double>::infinity();
      g[0] = gap.known ? gap.log_lower() : inf;
      g[1] = gap.known ? gap.log_upper() : inf;
    }
    return r.answer;
  });
}

constexpr const char* kRowsNote = R"(
One operand may be a single row, broadcast against the others. threads: threads answering the
rows (0: every core); the GIL is released.
Raises ValueError on a wrong shape or dtype, certcyl.InvalidInput on a row the library rejects
(the message names the row and the field).)";

}  // namespace

void bind_solid_batches(py::module_& m) {
  m.def(
      "point_cylinder",
      [](py::handle points, py::handle cylinders, long long threads, bool gap) {
        const std::string q = "point_cylinder";
        return point_batch<Cylinder<double>>(q, Rows(points, "points", 3, q), Rows(cylinders, "cylinders", 7, q),
                                             thread_count(threads, q), gap);
      },
      py::arg("points"), py::arg("cylinders"), py::kw_only(), py::arg("threads") = 1, py::arg("gap") = true,
      (std::string(R"(Certified position of points against solid circular cylinders, one query per row.

points: N x 3; cylinders: N x 7 (p0, p1, radius). answer: OVERLAPPING strictly inside, TOUCHING on
the boundary, SEPARATED outside; gap (N x 2, None with gap=False): the enclosure of the point's
depth margin min(1 - q, s, 1 - s, 1), s its axial coordinate in units of the height, q its
squared distance to the axis in units of the radius squared (negative outside).)") +
       kRowsNote)
          .c_str());
  m.def(
      "point_elliptic_cylinder",
      [](py::handle points, py::handle cylinders, long long threads, bool gap) {
        const std::string q = "point_elliptic_cylinder";
        return point_batch<EllipticCylinder<double>>(q, Rows(points, "points", 3, q), Rows(cylinders, "cylinders", 12, q),
                                                     thread_count(threads, q), gap);
      },
      py::arg("points"), py::arg("cylinders"), py::kw_only(), py::arg("threads") = 1, py::arg("gap") = true,
      (std::string(R"(Certified position of points against solid elliptic cylinders, one query per row.

points: N x 3; cylinders: N x 12 (base, a, b, c). answer and gap as point_cylinder, in the
cylinder's unit frame (x^2 + y^2 <= 1, 0 <= z <= 1).)") +
       kRowsNote)
          .c_str());
  m.def(
      "triangle_cylinder",
      [](py::handle triangles, py::handle cylinders, long long threads, bool gap) {
        const std::string q = "triangle_cylinder";
        return triangle_batch(Rows(triangles, "triangles", 9, q), Rows(cylinders, "cylinders", 7, q), thread_count(threads, q), gap);
      },
      py::arg("triangles"), py::arg("cylinders"), py::kw_only(), py::arg("threads") = 1, py::arg("gap") = true,
      (std::string(R"(Certified triangle against solid circular cylinder, one query per row.

triangles: N x 9 or N x 3 x 3 (three vertices; a degenerate triangle is a segment or a point);
cylinders: N x 7 (p0, p1, radius). gap (N x 2, None with gap=False): the enclosure of the
study's depth margin of the triangle (negative separated, zero touching, positive overlapping).)") +
       kRowsNote)
          .c_str());
  m.def(
      "cylinder_cylinder",
      [](py::handle a, py::handle b, long long threads, bool gap) {
        const std::string q = "cylinder_cylinder";
        return pair_batch(Rows(a, "a", 7, q), Rows(b, "b", 7, q), thread_count(threads, q), gap);
      },
      py::arg("a"), py::arg("b"), py::kw_only(), py::arg("threads") = 1, py::arg("gap") = true,
      (std::string(R"(Certified pairs of solid circular cylinders, one query per row.

a, b: N x 7 (p0, p1, radius). answer: SEPARATED, TOUCHING, OVERLAPPING or UNDECIDED (beyond the
configured precision, never a guess). gap (N x 2, None with gap=False): the certified enclosure
[lo, hi] of log(phi*) as `certcyl query` gives it (negative separated, zero touching, positive
overlapping; +inf when the midpoints coincide).)") +
       kRowsNote)
          .c_str());
}

}  // namespace certcyl::python
