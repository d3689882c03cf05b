// The failure maps: 2-D grids of ulp perturbations of two coordinates around a degenerate
// configuration of each query, every method's answer per cell (failure_maps/*.csv and *.json).
#include <array>
#include <cmath>
#include <fstream>
#include <stdexcept>

#include "study/families.hpp"
#include "study/contract.hpp"
#include "study/gap.hpp"
#include "study_internal.hpp"
#include "study_files.hpp"

namespace certcyl::cli::detail {
using namespace certcyl::study;

namespace {

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

// RFC 4180 quoting of a column name that needs it (a judged method's label; the study's
// method names never do).
std::string csv_name(const std::string& s) {
  if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
  std::string q = "\"";
  for (const char c : s) {
    if (c == '"') q += '"';
    q += c;
  }
  return q + '"';
}

}  // namespace

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

char contract_code(const MethodOutput& m, const Instance& inst, Contract c) {
  const char code = answer_code(m);
  const Answer under = certified_under(inst, c);
  if (c == Contract::solid || inst.certified == Answer::undecided || intersects(under) == intersects(inst.certified) || code == 'e' ||
      code == 'u')
    return code;
  // else: the contract's answer is not the solid one here.
  return judge(m, under) == Outcome::agree ? 'c' : 'x';
}

std::vector<double> MapGrid::input(std::size_t cell) const {
  const long i = static_cast<long>(cell) / cells, j = static_cast<long>(cell) % cells;
  std::vector<double> x = base;
  x[c0] = ulp_step(base[c0], (i - cells / 2) * step);
  x[c1] = ulp_step(base[c1], (j - cells / 2) * step);
  return x;
}

std::string MapGrid::certified_line(std::size_t cell, const Instance& inst) const {
  const long i = static_cast<long>(cell) / cells, j = static_cast<long>(cell) % cells;
  const long d0 = (i - cells / 2) * step, d1 = (j - cells / 2) * step;
  return std::to_string(i) + "," + std::to_string(j) + "," + std::to_string(d0) + "," + std::to_string(d1) + "," +
         std::string(1, answer_code(three_valued(inst.certified))) + "," + num(inst.gap_lo) + "," + num(inst.gap_hi);
}

std::vector<MapGrid> map_grids(std::uint64_t seed, int cells, long step) {
  const auto families = all_families();
  std::vector<MapGrid> grids;
  for (MapSpec spec : map_specs()) {
    const Family* fam = nullptr;
    for (const Family& f : families)
      if (f.name == spec.family && std::find(f.queries.begin(), f.queries.end(), spec.query) != f.queries.end()) fam = &f;
    if (!fam) throw std::logic_error("failure map " + spec.name + ": no family " + spec.family);
    Rng rng(mix(seed, hash_string(spec.name)));
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
    grids.push_back({spec.name, spec.description, spec.query, base, spec.c0, spec.c1, cells, step});
  }
  return grids;
}

void write_failure_map(const fs::path& maps, const MapGrid& g, const std::vector<std::string>& lines,
                       const std::vector<std::string>& methods, const std::vector<std::string>& codes,
                       const nlohmann::ordered_json& strides) {
  const std::size_t cells = static_cast<std::size_t>(g.cells) * static_cast<std::size_t>(g.cells);
  std::ofstream csv(maps / (g.name + ".csv"));
  csv << "i,j,d0_ulps,d1_ulps,certified,gap_lo,gap_hi";
  for (const std::string& m : methods) csv << ',' << csv_name(m);
  csv << '\n';
  for (std::size_t cell = 0; cell < cells; ++cell) {
    csv << lines[cell];
    for (char c : codes[cell]) csv << ',' << c;
    csv << '\n';
  }
  close_written(csv, maps / (g.name + ".csv"));
  nlohmann::ordered_json meta{{"name", g.name},
                              {"query", std::string(to_string(g.query))},
                              {"description", g.description},
                              {"base_input", x_hex(g.base)},
                              {"perturbed_coordinates", {g.c0, g.c1}},
                              {"cells", g.cells},
                              {"ulps_per_cell", g.step},
                              {"map_strides", strides},
                              {"codes", "s separated, t touching, o overlapping, i intersecting (boolean methods), u undecided, e error or invalid (a reported value not finite), "
                                        "c as the method's contract says where it differs from the solid answer (not wrong), x not as its contract says there (wrong), "
                                        ". not evaluated (a slow method runs on every map_stride-th row and column through the centre)"}};
  write_whole(maps / (g.name + ".json"), meta.dump(2) + '\n');
}

// Every method of the query but the certified one; slow ones on a sub-grid (Effort).
void run_failure_maps(const StudyOptions& o, const Registry& registry, const fs::path& dir) {
  const fs::path maps = dir / "failure_maps";
  fs::create_directories(maps);
  for (const MapGrid& grid : map_grids(o.seed, o.map_cells, o.map_step)) {
    std::vector<const Method*> methods;
    for (const Method& m : registry)
      if (m.query == grid.query && m.kind != MethodKind::certified && keep_name(o.methods, m.name())) methods.push_back(&m);
    const int n = o.map_cells;
    // A method with map_stride s runs on the rows and columns i with i = n/2 (mod s): the
    // centre cell, the degenerate configuration itself, is always among them.
    auto evaluated = [n](const Method& m, long i, long j) {
      const long s = static_cast<long>(std::max(1u, m.effort.map_stride));
      return (i - n / 2) % s == 0 && (j - n / 2) % s == 0;
    };
    const std::size_t cells = static_cast<std::size_t>(n) * n;
    std::vector<std::string> lines(cells), codes(cells, std::string(methods.size(), '.'));
    Progress progress(o, grid.name, cells);
    parallel_for(cells, o.threads, [&](std::size_t cell) {
      const long i = static_cast<long>(cell) / n, j = static_cast<long>(cell) % n;
      Instance inst;
      inst.query = grid.query;
      inst.x = grid.input(cell);
      certify(inst);
      lines[cell] = grid.certified_line(cell, inst);
      for (std::size_t k = 0; k < methods.size(); ++k)
        if (!methods[k]->serial && evaluated(*methods[k], i, j))
          codes[cell][k] = contract_code(run_quiet(*methods[k], inst.x), inst, methods[k]->contract);
      progress.tick();
    });
    // The serial methods, on this thread only (see Method::serial), each call in a child process
    // (ChildRunner: a call that ends it, as CORE::Expr does on some inputs, is an error, 'e');
    // all of them have the solid contract.
    std::vector<const Method*> serial;
    for (const Method* m : methods)
      if (m->serial) serial.push_back(m);
    ChildRunner child(serial);
    for (std::size_t k = 0; k < methods.size(); ++k) {
      if (!methods[k]->serial) continue;
      for (std::size_t cell = 0; cell < cells; ++cell)
        if (evaluated(*methods[k], static_cast<long>(cell) / n, static_cast<long>(cell) % n)) {
          const ChildCall c = child.run(*methods[k], grid.input(cell), /*timed=*/false);
          if (c.ended)
            std::cerr << "certcyl study: " << methods[k]->name() << " ended its process on map " << grid.name << " cell " << cell << " ("
                      << c.reason << "): an error ('e')\n";
          codes[cell][k] = answer_code(c.out);
        }
    }
    std::vector<std::string> names;
    nlohmann::ordered_json strides = nlohmann::ordered_json::object();
    for (const Method* m : methods) {
      names.push_back(m->name());
      if (m->effort.map_stride > 1) strides[m->name()] = m->effort.map_stride;
    }
    write_failure_map(maps, grid, lines, names, codes, strides);
  }
}

}  // namespace certcyl::cli::detail
