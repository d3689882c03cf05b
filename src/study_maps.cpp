// The failure maps: 2-D grids of ulp perturbations of two coordinates around a degenerate
// configuration of each query, every method's answer per cell (failure_maps/*.csv and *.json).
#include <array>
#include <cmath>
#include <fstream>
#include <stdexcept>

#include "study/families.hpp"
#include "study/gap.hpp"
#include "study_internal.hpp"
#include "study_files.hpp"

namespace certcyl::cli::detail {
using namespace certcyl::study;

namespace {

char answer_code(const MethodOutput& m) {
  if (m.error || m.invalid) return 'e';
  if (m.intersecting) return 'i';
  switch (m.answer) {
    case Answer::separated: return 's';
    case Answer::touching: return 't';
    case Answer::overlapping: return 'o';
    case Answer::undecided: return 'u';
  }
  return 'u';
}

struct MapSpec {
  std::string name, family, description;
  Query query;
  std::size_t c0, c1;  // the perturbed coordinates
  // When set (the aligned families, whose axis is a random coordinate axis): c0 and c1 are
  // offsets into the point at `c0`, replaced by its two coordinates across the axis of the
  // cylinder at this offset, so the map moves the point off the wall and not along the axis.
  std::size_t across_cylinder_at = std::numeric_limits<std::size_t>::max();
};

// One map per query, each around a degenerate configuration of one of its families (k = 0).
std::vector<MapSpec> map_specs() {
  return {{"tangent_line", "tangent_rotated", "line tangent to the wall; origin x and y perturbed", Query::line_cylinder, 0, 1},
          {"rim_line", "rim_rotated", "line grazing the rim at p1; origin x and y perturbed", Query::line_cylinder, 0, 1},
          {"ray_ends_on_wall", "ends_on_wall", "ray starting on the wall, pointing out; origin perturbed across the axis",
           Query::ray_cylinder, 0, 0, 6},
          {"segment_ends_on_wall", "ends_on_wall", "segment from outside ending on the wall; p1 perturbed across the axis",
           Query::segment_cylinder, 3, 0, 6},
          {"elliptic_tangent", "e_tangent_oblique", "line tangent to a sheared elliptic cylinder; origin x and z perturbed",
           Query::line_elliptic_cylinder, 0, 2},
          {"triangle_edge_wall", "t_edge_rotated", "triangle edge tangent to the wall; vertex v0 x and y perturbed",
           Query::triangle_cylinder, 0, 1},
          {"touching_cylinders", "c_crossing_rotated", "crossing cylinders touching wall to wall; b.p0 x and y perturbed",
           Query::cylinder_cylinder, 7, 8}};
}

}  // namespace

// Every method of the query but the certified one; slow ones on a sub-grid (Effort).
void run_failure_maps(const StudyOptions& o, const Registry& registry, const fs::path& dir) {
  const fs::path maps = dir / "failure_maps";
  fs::create_directories(maps);
  const auto families = all_families();
  for (MapSpec spec : map_specs()) {
    const Family* fam = nullptr;
    for (const Family& f : families)
      if (f.name == spec.family && std::find(f.queries.begin(), f.queries.end(), spec.query) != f.queries.end()) fam = &f;
    if (!fam) throw std::logic_error("failure map " + spec.name + ": no family " + spec.family);
    Rng rng(mix(o.seed, hash_string(spec.name)));
    const std::vector<double> base = fam->make(rng, spec.query, 0).x;
    if (spec.across_cylinder_at != std::numeric_limits<std::size_t>::max()) {
      const std::size_t point = spec.c0, cyl = spec.across_cylinder_at;
      std::array<std::size_t, 3> order{0, 1, 2};
      std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return std::fabs(base[cyl + 3 + a] - base[cyl + a]) < std::fabs(base[cyl + 3 + b] - base[cyl + b]);
      });
      spec.c0 = point + std::min(order[0], order[1]);
      spec.c1 = point + std::max(order[0], order[1]);
    }
    std::vector<const Method*> methods;
    for (const Method& m : registry)
      if (m.query == spec.query && m.kind != MethodKind::certified && keep_name(o.methods, m.name())) methods.push_back(&m);
    const int n = o.map_cells;
    // A method with map_stride s runs on the rows and columns i with i = n/2 (mod s): the
    // centre cell, the degenerate configuration itself, is always among them.
    auto evaluated = [n](const Method& m, long i, long j) {
      const long s = static_cast<long>(std::max(1u, m.effort.map_stride));
      return (i - n / 2) % s == 0 && (j - n / 2) % s == 0;
    };
    const std::size_t cells = static_cast<std::size_t>(n) * n;
    std::vector<std::string> lines(cells), codes(cells, std::string(methods.size(), '.'));
    auto cell_input = [&](std::size_t cell) {
      const long i = static_cast<long>(cell) / n, j = static_cast<long>(cell) % n;
      std::vector<double> x = base;
      x[spec.c0] = ulp_step(base[spec.c0], (i - n / 2) * o.map_step);
      x[spec.c1] = ulp_step(base[spec.c1], (j - n / 2) * o.map_step);
      return x;
    };
    Progress progress(o, spec.name, cells);
    parallel_for(cells, o.threads, [&](std::size_t cell) {
      const long i = static_cast<long>(cell) / n, j = static_cast<long>(cell) % n;
      const long d0 = (i - n / 2) * o.map_step, d1 = (j - n / 2) * o.map_step;
      Instance inst;
      inst.query = spec.query;
      inst.x = cell_input(cell);
      certify(inst);
      lines[cell] = std::to_string(i) + "," + std::to_string(j) + "," + std::to_string(d0) + "," + std::to_string(d1) + "," +
                    std::string(1, answer_code(three_valued(inst.certified))) + "," + num(inst.gap_lo) + "," + num(inst.gap_hi);
      for (std::size_t k = 0; k < methods.size(); ++k)
        if (!methods[k]->serial && evaluated(*methods[k], i, j)) codes[cell][k] = answer_code(run_quiet(*methods[k], inst.x));
      progress.tick();
    });
    // The serial methods, on this thread only (see Method::serial).
    for (std::size_t k = 0; k < methods.size(); ++k) {
      if (!methods[k]->serial) continue;
      for (std::size_t cell = 0; cell < cells; ++cell)
        if (evaluated(*methods[k], static_cast<long>(cell) / n, static_cast<long>(cell) % n))
          codes[cell][k] = answer_code(run_quiet(*methods[k], cell_input(cell)));
    }
    std::ofstream csv(maps / (spec.name + ".csv"));
    csv << "i,j,d0_ulps,d1_ulps,certified,gap_lo,gap_hi";
    for (const Method* m : methods) csv << ',' << m->name();
    csv << '\n';
    for (std::size_t cell = 0; cell < cells; ++cell) {
      csv << lines[cell];
      for (char c : codes[cell]) csv << ',' << c;
      csv << '\n';
    }
    close_written(csv, maps / (spec.name + ".csv"));
    nlohmann::ordered_json strides = nlohmann::ordered_json::object();
    for (const Method* m : methods)
      if (m->effort.map_stride > 1) strides[m->name()] = m->effort.map_stride;
    nlohmann::ordered_json meta{{"name", spec.name},
                                {"query", std::string(to_string(spec.query))},
                                {"description", spec.description},
                                {"base_input", x_hex(base)},
                                {"perturbed_coordinates", {spec.c0, spec.c1}},
                                {"cells", n},
                                {"ulps_per_cell", o.map_step},
                                {"map_strides", strides},
                                {"codes", "s separated, t touching, o overlapping, i intersecting (boolean methods), u undecided, e error or invalid (a reported value not finite), "
                                          ". not evaluated (a slow method runs on every map_stride-th row and column through the centre)"}};
    write_whole(maps / (spec.name + ".json"), meta.dump(2) + '\n');
  }
}

}  // namespace certcyl::cli::detail
