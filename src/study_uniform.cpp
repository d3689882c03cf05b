// The uniform sample: typical-case error rates, from a sample far larger than the families'.
//
// For every query, o.uniform_per_query instances drawn as the `uniform` family draws them
// (study/families.hpp: random lines, rays, segments, triangles and cylinders in [-2, 2]^3), instance
// i from the seed, the query and i alone (so any shard draws the same ones; shard s of n takes the
// i with i mod n = s). Each is certified (uniform_certified_answer: the certified query's answer,
// no gap) and answered by every selected method of its query that runs on every instance of the
// study (Method::stride 1: double, long double, Interval_nt, the sweeps, the robust method, the
// peers; not the certified query, the reference itself). The slow number types (Gmpfr, CORE::Expr), which the study runs on a share of each
// family only, are left out. The sample runs when the configuration keeps the `uniform` family.
//
// Each method is judged against the certified answer under its contract (study/contract.hpp: the
// solid one, or a ray cast's surface entry or surface hit), as on the families; the certified
// answers' counts are the solid ones. Only counts are kept, per query and method: memory does not
// grow with the sample but for three bytes per instance of the query being sampled (its certified
// answers, for the serial methods' pass). The parallel methods answer on o.threads threads; the serial ones (ODE's trimesh
// collider; Method::serial) on the main thread afterwards, each instance drawn again.
//
// uniform.csv (experiments/STUDY_FILES.md): one row per query and method, the query's rows in
// registry order, written for every selected (query, method) even when this shard drew none of
// its instances, so that shards have the same rows and a merge adds them (merge_uniform).
#include <array>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "certcyl/certified/cylinder_cylinder.hpp"
#include "certcyl/certified/line_cylinder.hpp"
#include "certcyl/certified/triangle_cylinder.hpp"
#include "study/contract.hpp"
#include "study/families.hpp"
#include "study_files.hpp"
#include "study_internal.hpp"

namespace certcyl::cli::detail {
using namespace certcyl::study;

const char* const kUniformHeader =
    "query,method,kind,instances,separated,touching,overlapping,uncertified,decided,false_positive,false_negative,"
    "class_mismatch,undecided,error,invalid,intersecting";

namespace {

// The counts of one row; the certified answers' are the query's, the same in each of its rows.
struct UniformCounts {
  long instances = 0, separated = 0, touching = 0, overlapping = 0, uncertified = 0;
  long decided = 0, fp = 0, fn = 0, cls = 0, undecided = 0, error = 0, invalid = 0, intersecting = 0;

  void add_outcome(const MethodOutput& out, Outcome o) {
    intersecting += !out.error && !out.invalid && out.intersecting;
    switch (o) {
      case Outcome::agree: ++decided; break;
      case Outcome::false_positive: ++decided, ++fp; break;
      case Outcome::false_negative: ++decided, ++fn; break;
      case Outcome::class_mismatch: ++decided, ++cls; break;
      case Outcome::undecided: ++undecided; break;
      case Outcome::error: ++error; break;
      case Outcome::invalid: ++invalid; break;
    }
  }
  void add(const UniformCounts& o) {
    instances += o.instances, separated += o.separated, touching += o.touching, overlapping += o.overlapping;
    uncertified += o.uncertified, decided += o.decided, fp += o.fp, fn += o.fn, cls += o.cls;
    undecided += o.undecided, error += o.error, invalid += o.invalid, intersecting += o.intersecting;
  }
  std::array<long, 13> fields() const {
    return {instances, separated, touching, overlapping, uncertified, decided, fp, fn, cls, undecided, error, invalid, intersecting};
  }
};

// The `uniform` family's generator for query q.
const Family& uniform_family(const std::vector<Family>& families, Query q) {
  for (const Family& f : families)
    if (f.name == "uniform" && std::find(f.queries.begin(), f.queries.end(), q) != f.queries.end()) return f;
  throw std::logic_error("study_uniform: no uniform family for " + std::string(to_string(q)));
}

// Instance i of the sample of query q drawn by `f` (the uniform family of q).
std::vector<double> sample_input(const Family& f, std::uint64_t seed, Query q, long i) {
  Rng rng(mix(mix(mix(seed, hash_string("uniform_sample")), static_cast<std::uint64_t>(q)), static_cast<std::uint64_t>(i)));
  return f.make(rng, q, 0).x;
}

}  // namespace

UniformTruth uniform_certified(Query query, const std::vector<double>& x) {
  auto line = [](const CertifiedLineResult& r) {
    return UniformTruth{r.answer, contract_answer(r, Contract::surface_entry), contract_answer(r, Contract::surface_hit)};
  };
  auto solid = [](Answer a) { return UniformTruth{a, a, a}; };
  switch (query) {
    case Query::line_cylinder: return line(certified_line_cylinder(line_at(x), cylinder_at(x, 6)));
    case Query::ray_cylinder: return line(certified_line_cylinder(ray_at(x), cylinder_at(x, 6)));
    case Query::segment_cylinder: return line(certified_line_cylinder(segment_at(x), cylinder_at(x, 6)));
    case Query::line_elliptic_cylinder: return line(certified_line_cylinder(line_at(x), elliptic_at(x, 6)));
    case Query::triangle_cylinder: return solid(certified_triangle_cylinder(triangle_at(x), cylinder_at(x, 9)).answer);
    case Query::cylinder_cylinder: return solid(certified_cylinder_cylinder(cylinder_at(x, 0), cylinder_at(x, 7)).answer);
  }
  return solid(Answer::undecided);
}

Answer uniform_certified_answer(Query query, const std::vector<double>& x) { return uniform_certified(query, x).solid; }

std::vector<double> uniform_sample_input(std::uint64_t seed, Query q, long i) { return sample_input(uniform_family(all_families(), q), seed, q, i); }

bool in_uniform_sample(const Method& m, const StudyOptions& o) {
  return m.kind != MethodKind::certified && m.stride == 1 && m.nt != "core_expr" && keep_name(o.methods, m.name());
}

void run_uniform_sample(const StudyOptions& o, const Registry& registry, const fs::path& dir) {
  std::ofstream csv(dir / "uniform.csv");
  csv << kUniformHeader << '\n';
  const bool wanted = o.uniform_per_query > 0 && (o.families.empty() || std::find(o.families.begin(), o.families.end(), "uniform") != o.families.end());
  const std::vector<Family> families = all_families();
  for (Query q : {Query::line_cylinder, Query::ray_cylinder, Query::segment_cylinder, Query::line_elliptic_cylinder, Query::triangle_cylinder,
                  Query::cylinder_cylinder}) {
    std::vector<const Method*> methods;
    for (const Method& m : registry)
      if (m.query == q && in_uniform_sample(m, o)) methods.push_back(&m);
    if (!wanted || methods.empty()) continue;
    const Family& family = uniform_family(families, q);
    // This shard's instances: i = shard_index, shard_index + shard_count, ...
    const long first = o.shard_index, step = o.shard_count;
    const std::size_t mine = o.uniform_per_query > first ? static_cast<std::size_t>((o.uniform_per_query - first - 1) / step + 1) : 0;
    std::vector<UniformTruth> certified(mine);
    std::vector<UniformCounts> counts(methods.size());
    std::mutex counts_mutex;
    Progress progress(o, "uniform sample, " + std::string(to_string(q)), mine);
    // The parallel methods, in chunks of instances counted apart and added under the lock.
    constexpr std::size_t kChunk = 512;
    parallel_for((mine + kChunk - 1) / kChunk, o.threads, [&](std::size_t chunk) {
      std::vector<UniformCounts> local(methods.size());
      const std::size_t end = std::min(mine, (chunk + 1) * kChunk);
      for (std::size_t k = chunk * kChunk; k < end; ++k) {
        const std::vector<double> x = sample_input(family, o.seed, q, first + static_cast<long>(k) * step);
        const UniformTruth truth = uniform_certified(q, x);
        const Answer c = truth.solid;
        certified[k] = truth;
        for (std::size_t j = 0; j < methods.size(); ++j) {
          UniformCounts& u = local[j];
          ++u.instances;
          u.separated += c == Answer::separated, u.touching += c == Answer::touching, u.overlapping += c == Answer::overlapping;
          if (c == Answer::undecided) {
            ++u.uncertified;
            continue;
          }
          if (methods[j]->serial) continue;
          const MethodOutput out = run_quiet(*methods[j], x);
          u.add_outcome(out, judge(out, truth.under(methods[j]->contract)));
        }
      }
      std::lock_guard lock(counts_mutex);
      for (std::size_t j = 0; j < methods.size(); ++j) counts[j].add(local[j]);
      progress.tick(end - chunk * kChunk);
    });
    // The serial methods, on this thread alone.
    for (std::size_t j = 0; j < methods.size(); ++j) {
      if (!methods[j]->serial) continue;
      for (std::size_t k = 0; k < mine; ++k) {
        if (certified[k].solid == Answer::undecided) continue;
        const MethodOutput out = run_quiet(*methods[j], sample_input(family, o.seed, q, first + static_cast<long>(k) * step));
        counts[j].add_outcome(out, judge(out, certified[k].under(methods[j]->contract)));
      }
    }
    for (std::size_t j = 0; j < methods.size(); ++j) {
      csv << to_string(q) << ',' << csv_field(methods[j]->name()) << ',' << to_string(methods[j]->kind);
      for (long v : counts[j].fields()) csv << ',' << v;
      csv << '\n';
    }
  }
  close_written(csv, dir / "uniform.csv");
}

std::string uniform_table(const fs::path& dir) {
  std::ifstream in(dir / "uniform.csv");
  std::string line;
  if (!in || !std::getline(in, line)) return {};
  std::ostringstream os;
  std::map<std::string, std::pair<long, long>> quiet;  // query -> (methods without a wrong answer, their least decided)
  std::vector<std::string> queries;
  std::ostringstream rows;
  while (std::getline(in, line)) {
    const std::vector<std::string> f = split_csv(line);
    if (f.size() != 16) continue;
    const long instances = std::stol(f[3]), uncertified = std::stol(f[7]), decided = std::stol(f[8]);
    const long fp = std::stol(f[9]), fn = std::stol(f[10]), cls = std::stol(f[11]), undecided = std::stol(f[12]);
    const long failed = std::stol(f[13]) + std::stol(f[14]);
    const bool boolean = std::stol(f[15]) > 0;
    if (std::find(queries.begin(), queries.end(), f[0]) == queries.end()) queries.push_back(f[0]), quiet[f[0]] = {0, -1};
    if (fp + fn + cls + failed == 0) {
      auto& [n, least] = quiet[f[0]];
      ++n;
      least = least < 0 ? decided : std::min(least, decided);
      continue;
    }
    char rate[32], rate3[32];
    std::snprintf(rate, sizeof rate, "%.2e", decided ? static_cast<double>(fp + fn) / static_cast<double>(decided) : 0.0);
    std::snprintf(rate3, sizeof rate3, "%.2e", decided ? static_cast<double>(fp + fn + cls) / static_cast<double>(decided) : 0.0);
    rows << std::left << std::setw(24) << f[0] << std::setw(44) << f[1] << std::right << std::setw(8) << instances - uncertified
         << std::setw(8) << decided << std::setw(7) << fp << std::setw(7) << fn << std::setw(7) << cls << std::setw(7) << undecided
         << std::setw(6) << failed << std::setw(10) << rate << std::setw(10) << (boolean ? "--" : rate3) << '\n';
  }
  if (queries.empty()) return "\nuniform sample (uniform.csv): none\n";
  os << "\nuniform sample (uniform.csv): random instances per query, the methods that run on every instance (not Gmpfr, CORE::Expr);\n"
        "the methods with a wrong answer, an error or an invalid value:\n";
  os << std::left << std::setw(24) << "query" << std::setw(44) << "method" << std::right << std::setw(8) << "n" << std::setw(8) << "decided"
     << std::setw(7) << "FP" << std::setw(7) << "FN" << std::setw(7) << "class" << std::setw(7) << "undec" << std::setw(6) << "err"
     << std::setw(10) << "rate" << std::setw(10) << "rate3" << '\n';
  os << rows.str();
  for (const std::string& q : queries)
    if (quiet[q].first > 0)
      os << q << ": " << quiet[q].first << " other methods without a wrong answer, error or invalid value (each at least " << quiet[q].second
         << " decided)\n";
  os << "n = certified instances, err = errors + invalid; rate = (FP + FN) / decided, rate3 = (FP + FN + class) / decided (-- for a Boolean method).\n";
  return os.str();
}

void merge_uniform(const std::vector<fs::path>& shards, const fs::path& dir) {
  // (query, method) in the order of the first shard, with the kind and the summed counts.
  std::vector<std::pair<std::string, std::vector<std::string>>> order;
  std::map<std::string, std::size_t> at;
  std::vector<std::array<long, 13>> sums;
  std::size_t first_rows = 0;
  for (std::size_t s = 0; s < shards.size(); ++s) {
    const fs::path file = shards[s] / "uniform.csv";
    const std::string where = "merge: " + shards[s].filename().string() + "/uniform.csv";
    std::ifstream in(file);
    std::string line;
    if (!in || !std::getline(in, line)) throw std::runtime_error(where + ": missing");
    if (line != kUniformHeader) throw std::runtime_error(where + ": not the header of uniform.csv");
    std::size_t rows = 0;
    for (long n = 2; std::getline(in, line); ++n, ++rows) {
      const std::vector<std::string> f = split_csv(line);
      std::array<long, 13> v{};
      try {
        if (f.size() != 3 + v.size()) throw std::invalid_argument("fields");
        for (std::size_t i = 0; i < v.size(); ++i) {
          std::size_t used = 0;
          v[i] = std::stol(f[3 + i], &used);
          if (used != f[3 + i].size() || v[i] < 0) throw std::invalid_argument("count");
        }
      } catch (const std::exception&) {
        throw std::runtime_error(where + ", line " + std::to_string(n) + ": not a row");
      }
      const std::string key = f[0] + ',' + csv_field(f[1]) + ',' + f[2];
      const auto it = at.find(key);
      if (s == 0) {
        if (it != at.end()) throw std::runtime_error(where + ", line " + std::to_string(n) + ": " + f[0] + " " + f[1] + " twice");
        at[key] = order.size();
        order.push_back({key, f});
        sums.push_back(v);
        continue;
      }
      if (it == at.end()) throw std::runtime_error(where + ", line " + std::to_string(n) + ": " + f[0] + " " + f[1] + " is not in the first shard's");
      for (std::size_t i = 0; i < v.size(); ++i) {
        // The query's instance and certified-answer counts add; so do the outcomes; `intersecting` too.
        sums[it->second][i] += v[i];
      }
    }
    if (s == 0) first_rows = rows;
    else if (rows != first_rows)
      throw std::runtime_error(where + ": " + std::to_string(rows) + " rows, the first shard's has " + std::to_string(first_rows));
  }
  std::ofstream csv(dir / "uniform.csv");
  csv << kUniformHeader << '\n';
  for (std::size_t r = 0; r < order.size(); ++r) {
    csv << order[r].first;
    for (long v : sums[r]) csv << ',' << v;
    csv << '\n';
  }
  close_written(csv, dir / "uniform.csv");
}

}  // namespace certcyl::cli::detail
