// How the certified reference answers of the cylinder pairs were decided, per family: the stage
// of certified_cylinder_cylinder (result.stage), the arithmetic of the deciding check
// (result.certified_by) and the Gmpfr rounds' precision (result.gmpfr_precision), read from the
// stage, certified_by and gmpfr_bits columns of inputs.csv (so a merge recomputes it from the
// merged rows). stages.csv holds the counts per (family, stage, arithmetic, precision); the text
// table, for summary.txt, one line per family.
#include <array>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "certcyl/certified/cylinder_cylinder.hpp"
#include "study_internal.hpp"
#include "study_files.hpp"

namespace certcyl::cli::detail {

namespace {

// The position of a name in the list of an enum's names (stages and arithmetics in the order of
// the query), the list's size if absent.
template <class E, std::size_t N>
std::size_t rank(const std::string& name, const std::array<E, N>& values) {
  for (std::size_t i = 0; i < N; ++i)
    if (to_string(values[i]) == name) return i;
  return N;
}

constexpr std::array<CylinderStage, kCylinderStages + 1> kStages{CylinderStage::midpoints, CylinderStage::fast_path,
                                                                  CylinderStage::optimiser, CylinderStage::refine,
                                                                  CylinderStage::touching_exact, CylinderStage::gmpfr,
                                                                  CylinderStage::ellipsoid, CylinderStage::none};
constexpr std::array<CylinderArithmetic, 4> kArithmetics{CylinderArithmetic::static_filter, CylinderArithmetic::interval,
                                                         CylinderArithmetic::exact, CylinderArithmetic::none};

struct FamilyStages {
  long n = 0, gmpfr_used = 0, max_bits = 0;
  std::array<long, kStages.size() + 1> by_stage{};
  std::array<long, kArithmetics.size() + 1> by_arithmetic{};
};

}  // namespace

std::string write_stages(const fs::path& dir) {
  std::ifstream in(dir / "inputs.csv");
  std::string line;
  if (!std::getline(in, line)) throw std::runtime_error((dir / "inputs.csv").string() + ": empty");
  const std::vector<std::string> header = split_csv(line);
  auto column = [&](const std::string& name) {
    for (std::size_t i = 0; i < header.size(); ++i)
      if (header[i] == name) return i;
    throw std::runtime_error((dir / "inputs.csv").string() + ": no column " + name);
  };
  const std::size_t c_family = column("family"), c_query = column("query"), c_stage = column("stage"),
                    c_by = column("certified_by"), c_bits = column("gmpfr_bits");
  // (family, stage rank, arithmetic rank, bits) -> instances, with the names kept for output.
  std::map<std::tuple<std::string, std::size_t, std::size_t, long>, long> counts;
  std::map<std::tuple<std::string, std::size_t, std::size_t, long>, std::pair<std::string, std::string>> names;
  std::map<std::string, FamilyStages> families;
  while (std::getline(in, line)) {
    const std::vector<std::string> f = split_csv(line);
    if (f.size() != header.size()) throw std::runtime_error((dir / "inputs.csv").string() + ": bad row '" + line + "'");
    if (f[c_query] != to_string(study::Query::cylinder_cylinder)) continue;
    const long bits = f[c_bits].empty() ? 0 : std::stol(f[c_bits]);
    const std::size_t s = rank(f[c_stage], kStages), a = rank(f[c_by], kArithmetics);
    const auto key = std::make_tuple(f[c_family], s, a, bits);
    ++counts[key];
    names[key] = {f[c_stage], f[c_by]};
    FamilyStages& fs = families[f[c_family]];
    ++fs.n;
    ++fs.by_stage[s];
    ++fs.by_arithmetic[a];
    fs.gmpfr_used += bits > 0;
    fs.max_bits = std::max(fs.max_bits, bits);
  }
  std::ofstream csv(dir / "stages.csv");
  csv << "family,stage,certified_by,gmpfr_bits,instances\n";
  for (const auto& [key, n] : counts)
    csv << std::get<0>(key) << ',' << names[key].first << ',' << names[key].second << ',' << std::get<3>(key) << ',' << n << '\n';
  close_written(csv, dir / "stages.csv");

  std::ostringstream os;
  os << "cylinder pairs: the stage of certified_cylinder_cylinder that decided each certified answer, per family\n";
  os << std::left << std::setw(20) << "family" << std::right << std::setw(5) << "n";
  for (CylinderStage s : kStages) os << ' ' << std::setw(static_cast<int>(to_string(s).size())) << to_string(s);
  for (CylinderArithmetic a : kArithmetics)
    if (a != CylinderArithmetic::none) os << ' ' << std::setw(static_cast<int>(std::max<std::size_t>(to_string(a).size(), 6))) << to_string(a);
  os << std::setw(7) << "gmpfr" << std::setw(6) << "bits" << '\n';
  FamilyStages all;
  auto line_of = [&](const std::string& name, const FamilyStages& f) {
    os << std::left << std::setw(20) << name << std::right << std::setw(5) << f.n;
    for (std::size_t i = 0; i < kStages.size(); ++i) os << ' ' << std::setw(static_cast<int>(to_string(kStages[i]).size())) << f.by_stage[i];
    for (std::size_t i = 0; i < kArithmetics.size(); ++i)
      if (kArithmetics[i] != CylinderArithmetic::none)
        os << ' ' << std::setw(static_cast<int>(std::max<std::size_t>(to_string(kArithmetics[i]).size(), 6))) << f.by_arithmetic[i];
    os << std::setw(7) << f.gmpfr_used << std::setw(6) << f.max_bits << '\n';
  };
  for (const auto& [name, f] : families) {
    line_of(name, f);
    all.n += f.n, all.gmpfr_used += f.gmpfr_used, all.max_bits = std::max(all.max_bits, f.max_bits);
    for (std::size_t i = 0; i < all.by_stage.size(); ++i) all.by_stage[i] += f.by_stage[i];
    for (std::size_t i = 0; i < all.by_arithmetic.size(); ++i) all.by_arithmetic[i] += f.by_arithmetic[i];
  }
  if (!families.empty()) line_of("all", all);
  os << "none = undecided; static, interval, exact = the arithmetic of the deciding check; gmpfr = instances on which Gmpfr\n"
        "ran, bits = the highest precision it needed (0: none).\n";
  return os.str();
}

}  // namespace certcyl::cli::detail
