// The C++ side of bench/bench_python_rays.py: the certified line and ray queries
// (certified/line_cylinder.hpp) on the rows the script sends, timed as the Python module runs
// them (python/batch_line.cpp): per row the answer and the nearest doubles of the interval's
// ends, and with the gap also the study's depth margin (study/gap.hpp) computed exactly and
// enclosed in doubles.
//
//   bench_python_rays_cpp N GAP_ROWS < rows > results
//
// Standard input: N rows of 13 float64 (origin, direction, cylinder p0, p1, radius), native byte
// order. Standard output: one JSON line of timings (ns per row of each run: line and ray without
// the gap on the N rows, line and ray with the gap on the first GAP_ROWS rows), then per run, in
// that order, the answers (int8 codes 0 separated, 1 touching, 2 overlapping), t_in and t_out
// (float64), and for the gap runs the gap (float64 pairs lo, hi), all in native byte order.
// Exit status 1 on bad usage, short input or a row the library rejects.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <limits>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "certcyl/certified/line_cylinder.hpp"
#include "study/gap.hpp"

using namespace certcyl;

namespace {

constexpr std::size_t kWidth = 13;

struct Run {
  std::string name;
  std::size_t rows = 0;
  bool gap = false;
  double ns_per_row = 0;
  std::vector<std::int8_t> answer;
  std::vector<double> t_in, t_out, gaps;
};

std::int8_t code(Answer a) {
  switch (a) {
    case Answer::separated: return 0;
    case Answer::touching: return 1;
    case Answer::overlapping: return 2;
    case Answer::undecided: return 4;
  }
  return 4;
}

Rational exact(double x) { return Rational(x); }

template <template <class> class LineLike>
void run(const std::vector<double>& rows, Run& r, LineRange range) {
  r.answer.resize(r.rows);
  r.t_in.resize(r.rows);
  r.t_out.resize(r.rows);
  if (r.gap) r.gaps.resize(2 * r.rows);
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  const auto start = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < r.rows; ++i) {
    const double* x = rows.data() + i * kWidth;
    const LineLike<double> line{{x[0], x[1], x[2]}, {x[3], x[4], x[5]}};
    const Cylinder<double> cylinder{{x[6], x[7], x[8]}, {x[9], x[10], x[11]}, x[12]};
    const CertifiedLineResult c = certified_line_cylinder(line, cylinder);
    r.answer[i] = code(c.answer);
    r.t_in[i] = c.in ? c.in->nearest : nan;
    r.t_out[i] = c.out ? c.out->nearest : nan;
    if (r.gap) {
      const Line<Rational> l{line.origin.map(exact), line.direction.map(exact)};
      std::tie(r.gaps[2 * i], r.gaps[2 * i + 1]) =
          study::detail::enclose_margin_doubles(study::detail::circular_line_gap(l, cylinder.map(exact), range));
    }
  }
  const std::chrono::duration<double, std::nano> elapsed = std::chrono::steady_clock::now() - start;
  r.ns_per_row = elapsed.count() / static_cast<double>(r.rows ? r.rows : 1);
}

template <class T>
void write(const std::vector<T>& v) {
  if (!v.empty() && std::fwrite(v.data(), sizeof(T), v.size(), stdout) != v.size()) throw std::runtime_error("write failed");
}

}  // namespace

int main(int argc, char** argv) {
  try {
    if (argc != 3) {
      std::fprintf(stderr, "usage: %s N GAP_ROWS < rows > results\n", argv[0]);
      return 1;
    }
    const std::size_t n = std::strtoull(argv[1], nullptr, 10);
    const std::size_t gap_rows = std::min<std::size_t>(n, std::strtoull(argv[2], nullptr, 10));
    std::vector<double> rows(n * kWidth);
    if (std::fread(rows.data(), sizeof(double), rows.size(), stdin) != rows.size()) {
      std::fprintf(stderr, "bench_python_rays_cpp: expected %zu rows of %zu float64 on standard input\n", n, kWidth);
      return 1;
    }
    std::vector<Run> runs(4);
    for (std::size_t k = 0; k < runs.size(); ++k) {
      runs[k].name = std::string(k % 2 ? "ray" : "line") + (k >= 2 ? "_gap" : "");
      runs[k].rows = k >= 2 ? gap_rows : n;
      runs[k].gap = k >= 2;
    }
    for (Run& r : runs) {
      if (r.name.starts_with("line")) {
        run<Line>(rows, r, LineRange::line);
      } else {
        run<Ray>(rows, r, LineRange::ray);
      }
    }
    std::printf("{");
    for (std::size_t k = 0; k < runs.size(); ++k)
      std::printf("%s\"%s\": %.3f", k ? ", " : "", runs[k].name.c_str(), runs[k].ns_per_row);
    std::printf("}\n");
    for (const Run& r : runs) {
      write(r.answer);
      write(r.t_in);
      write(r.t_out);
      write(r.gaps);
    }
    return std::fflush(stdout) == 0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_python_rays_cpp: %s\n", e.what());
    return 1;
  }
}
