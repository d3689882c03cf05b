// `certcyl cases`: the study's planned instances of one query, certified, as `certcyl query`
// lines carrying their certified answer, gap, family and k in "meta"; and reading them back.
#include "cases.hpp"

#include <algorithm>
#include <cmath>
#include <istream>
#include <limits>
#include <ostream>
#include <set>
#include <stdexcept>

#include "study/families.hpp"
#include "study/gap.hpp"
#include "study/gap_quantity.hpp"
#include "judge_internal.hpp"
#include "query.hpp"
#include "study_internal.hpp"

namespace certcyl::cli {
namespace {

using ojson = nlohmann::ordered_json;
using study::Query;

ojson point(const std::vector<double>& x, std::size_t i) { return ojson::array({x[i], x[i + 1], x[i + 2]}); }

ojson cylinder(const std::vector<double>& x, std::size_t i) {
  return ojson{{"p0", point(x, i)}, {"p1", point(x, i + 3)}, {"radius", x[i + 6]}};
}

// The operands of `certcyl query` for the study's flat coordinates (study/instance.hpp).
ojson operands(Query q, const std::vector<double>& x) {
  switch (q) {
    case Query::line_cylinder: return {{"line", {{"origin", point(x, 0)}, {"direction", point(x, 3)}}}, {"cylinder", cylinder(x, 6)}};
    case Query::ray_cylinder: return {{"ray", {{"origin", point(x, 0)}, {"direction", point(x, 3)}}}, {"cylinder", cylinder(x, 6)}};
    case Query::segment_cylinder: return {{"segment", {{"p0", point(x, 0)}, {"p1", point(x, 3)}}}, {"cylinder", cylinder(x, 6)}};
    case Query::line_elliptic_cylinder:
      return {{"line", {{"origin", point(x, 0)}, {"direction", point(x, 3)}}},
              {"elliptic_cylinder", {{"base", point(x, 6)}, {"a", point(x, 9)}, {"b", point(x, 12)}, {"c", point(x, 15)}}}};
    case Query::triangle_cylinder:
      return {{"triangle", ojson::array({point(x, 0), point(x, 3), point(x, 6)})}, {"cylinder", cylinder(x, 9)}};
    case Query::cylinder_cylinder: return {{"a", cylinder(x, 0)}, {"b", cylinder(x, 7)}};
  }
  return {};
}

// Reads the coordinates back: `shape` is operands() of the indices 0, 1, 2, ..., so each number
// of it says where the number at the same place of `given` goes.
void read_coordinates(const ojson& shape, const nlohmann::json& given, const std::string& path, std::vector<double>& x) {
  if (shape.is_number()) {
    if (!given.is_number()) throw std::runtime_error(path + ": expected a JSON number");
    x[shape.get<std::size_t>()] = given.get<double>();
  } else if (shape.is_array()) {
    if (!given.is_array() || given.size() != shape.size())
      throw std::runtime_error(path + ": expected an array of " + std::to_string(shape.size()));
    for (std::size_t i = 0; i < shape.size(); ++i) read_coordinates(shape[i], given[i], path + "[" + std::to_string(i) + "]", x);
  } else {
    if (!given.is_object() || given.size() != shape.size()) throw std::runtime_error(path + ": expected the members of " + shape.dump());
    for (const auto& [key, value] : shape.items()) {
      if (!given.contains(key)) throw std::runtime_error(path + ": missing member '" + key + "'");
      read_coordinates(value, given.at(key), path.empty() ? key : path + "." + key, x);
    }
  }
}

}  // namespace

void take_certified(Case& c, const study::Instance& inst) {
  c.certified = inst.certified, c.gap_lo = inst.gap_lo, c.gap_hi = inst.gap_hi, c.t_in = inst.t_in;
  c.certified_entry = inst.certified_entry, c.certified_surface_hit = inst.certified_surface_hit;
}

study::Instance certified_instance(const Case& c) {
  study::Instance inst;
  inst.query = c.query;
  inst.certified = c.certified, inst.certified_entry = c.certified_entry, inst.certified_surface_hit = c.certified_surface_hit;
  inst.gap_lo = c.gap_lo, inst.gap_hi = c.gap_hi, inst.t_in = c.t_in;
  return inst;
}

study::Contract parse_contract(const std::string& name, const std::string& where) {
  for (const study::Contract c : {study::Contract::solid, study::Contract::surface_entry, study::Contract::surface_hit})
    if (name == study::to_string(c)) return c;
  throw std::invalid_argument(where + ": unknown contract '" + name + "' (expected solid, surface_entry or surface_hit)");
}

namespace {

ojson gap_json(const Case& c) {
  if (!std::isfinite(c.gap_lo) || !std::isfinite(c.gap_hi)) return nullptr;
  return ojson::array({c.gap_lo, c.gap_hi});
}

// Case from one line of a cases file; throws std::runtime_error (without the line's number).
Case parse_case(const std::string& text) {
  // Strict: a member named twice (a second "answer" or "meta") is an error, not the last one.
  const nlohmann::json j = parse_strict_json(text);
  if (!j.is_object()) throw std::runtime_error("expected a JSON object");
  Case c;
  if (!j.contains("id") || !j["id"].is_string()) throw std::runtime_error("id: expected a string");
  c.id = j["id"].get<std::string>();
  if (!j.contains("query") || !j["query"].is_string()) throw std::runtime_error("query: expected a string");
  try {
    c.query = parse_study_query(j["query"].get<std::string>());
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(e.what());
  }
  if (!j.contains("meta") || !j["meta"].is_object()) throw std::runtime_error("meta: expected an object");
  const nlohmann::json& meta = j["meta"];
  if (!meta.contains("family") || !meta["family"].is_string()) throw std::runtime_error("meta.family: expected a string");
  c.family = meta["family"].get<std::string>();
  if (!meta.contains("k") || !meta["k"].is_number_integer()) throw std::runtime_error("meta.k: expected an integer");
  c.k = meta["k"].get<long long>();
  const auto certified = meta.contains("certified") && meta["certified"].is_string()
                             ? answer_from_string(meta["certified"].get<std::string>())
                             : std::nullopt;
  if (!certified) throw std::runtime_error("meta.certified: expected separated, touching, overlapping or undecided");
  c.certified = *certified;
  if (!meta.contains("gap")) throw std::runtime_error("meta.gap: missing (null when unbounded)");
  const nlohmann::json& gap = meta["gap"];
  if (gap.is_null()) {
    c.gap_lo = c.gap_hi = std::numeric_limits<double>::infinity();
  } else if (gap.is_array() && gap.size() == 2 && gap[0].is_number() && gap[1].is_number()) {
    c.gap_lo = gap[0].get<double>(), c.gap_hi = gap[1].get<double>();
  } else {
    throw std::runtime_error("meta.gap: expected [lo, hi] or null");
  }
  if (meta.contains("gap_quantity")) {
    const std::string_view expected = study::to_string(study::gap_quantity(c.query));
    if (!meta["gap_quantity"].is_string() || meta["gap_quantity"].get<std::string>() != expected)
      throw std::runtime_error("meta.gap_quantity: expected \"" + std::string(expected) + "\" for " +
                               std::string(study::to_string(c.query)) + ", got " + meta["gap_quantity"].dump());
  }
  if (meta.contains("t_in")) {
    if (!meta["t_in"].is_number()) throw std::runtime_error("meta.t_in: expected a JSON number");
    c.t_in = meta["t_in"].get<double>();
  }
  if (meta.contains("map")) {
    const nlohmann::json& m = meta["map"];
    const auto integer = [&m](const char* key, long long lo, long long hi) {
      if (!m.is_object() || !m.contains(key) || !m[key].is_number_integer() || m[key].get<long long>() < lo || m[key].get<long long>() > hi)
        throw std::runtime_error(std::string("meta.map.") + key + ": expected an integer from " + std::to_string(lo) + " to " +
                                 std::to_string(hi));
      return m[key].get<long long>();
    };
    MapCell cell;
    cell.cells = static_cast<int>(integer("cells", 2, 1024));
    cell.step = static_cast<long>(integer("step", 1, 1000000000));
    if (!m.contains("seed") || !m["seed"].is_number_unsigned()) throw std::runtime_error("meta.map.seed: expected an unsigned integer");
    cell.seed = m["seed"].get<std::uint64_t>();
    if (c.family.rfind("failure_map/", 0) != 0) throw std::runtime_error("meta.map: only on a failure map's cell (family failure_map/...)");
    c.map = cell;
  } else if (c.family.rfind("failure_map/", 0) == 0) {
    throw std::runtime_error("meta.map: missing on a failure map's cell");
  }
  const std::size_t n = study::coordinate_count(c.query);
  std::vector<double> index(n);
  for (std::size_t i = 0; i < n; ++i) index[i] = static_cast<double>(i);
  const ojson shape = operands(c.query, index);
  nlohmann::json given = j;
  for (const char* member : {"id", "query", "meta"}) given.erase(member);
  c.x.assign(n, 0.0);
  read_coordinates(shape, given, "", c.x);
  return c;
}

}  // namespace

Query parse_study_query(const std::string& name) {
  std::string names;
  for (Query q : study::kQueries) {
    if (name == study::to_string(q)) return q;
    names += (names.empty() ? "" : ", ") + std::string(study::to_string(q));
  }
  throw std::invalid_argument("--query: expected one of " + names + ", got '" + name + "'");
}

std::vector<Case> make_cases(const CaseSpec& spec) {
  const Query q = parse_study_query(spec.query);
  std::vector<std::string> known;
  for (const study::Family& f : study::all_families())
    if (std::find(f.queries.begin(), f.queries.end(), q) != f.queries.end()) known.push_back(f.name);
  for (const std::string& f : spec.families) {
    if (std::find(known.begin(), known.end(), f) == known.end()) {
      std::string list;
      for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
      throw std::invalid_argument("--family: " + spec.query + " has no family '" + f + "' (" + list + ")");
    }
  }
  StudyOptions o;
  o.size = spec.size;
  o.seed = spec.seed;
  o.families = spec.families.empty() ? known : spec.families;
  detail::apply_size(o);
  std::vector<detail::Planned> plan = detail::plan_instances(o);
  std::erase_if(plan, [&](const detail::Planned& p) { return p.inst.query != q; });
  detail::parallel_for(plan.size(), spec.threads, [&](std::size_t i) { study::certify(plan[i].inst); });
  std::vector<Case> cases;
  cases.reserve(plan.size());
  for (const detail::Planned& p : plan) {
    Case c;
    c.id = spec.query + "/" + p.inst.family + "/" + std::to_string(p.index_in_family);
    c.query = q, c.family = p.inst.family, c.k = p.k;
    take_certified(c, p.inst);
    c.x = p.inst.x;
    c.line = cases.size() + 1;
    cases.push_back(std::move(c));
  }
  return cases;
}

ojson query_line(const Case& c) {
  ojson line{{"id", c.id}, {"query", std::string(study::to_string(c.query))}};
  const ojson members = operands(c.query, c.x);
  for (const auto& [key, value] : members.items()) line[key] = value;
  return line;
}

ojson case_line(const Case& c) {
  ojson line = query_line(c);
  line["meta"] = ojson{{"family", c.family}, {"k", c.k}, {"certified", std::string(to_string(c.certified))}, {"gap", gap_json(c)},
                       {"gap_quantity", std::string(study::to_string(study::gap_quantity(c.query)))}};
  if (std::isfinite(c.t_in)) line["meta"]["t_in"] = c.t_in;
  if (c.map) line["meta"]["map"] = ojson{{"cells", c.map->cells}, {"step", c.map->step}, {"seed", c.map->seed}};
  return line;
}

std::vector<Case> read_cases(std::istream& in, const std::string& label) {
  std::vector<Case> cases;
  std::set<std::string> ids;
  std::string text;
  for (std::size_t n = 1; std::getline(in, text); ++n) {
    if (text.find_first_not_of(" \t\r") == std::string::npos) continue;
    try {
      Case c = parse_case(text);
      c.line = n;
      if (!ids.insert(c.id).second) throw std::runtime_error("duplicate id '" + c.id + "'");
      cases.push_back(std::move(c));
    } catch (const std::exception& e) {
      throw std::runtime_error(label + " line " + std::to_string(n) + ": " + e.what());
    }
  }
  if (in.bad()) throw std::runtime_error(label + ": read error");
  return cases;
}

void recertify(std::vector<Case>& cases, unsigned threads, const std::string& label) {
  std::vector<study::Instance> insts(cases.size());
  for (std::size_t i = 0; i < cases.size(); ++i) insts[i].query = cases[i].query, insts[i].x = cases[i].x;
  detail::parallel_for(insts.size(), threads, [&](std::size_t i) { study::certify(insts[i]); });
  for (std::size_t i = 0; i < cases.size(); ++i) {
    Case& c = cases[i];
    const study::Instance& inst = insts[i];
    if (inst.certified != c.certified)
      throw std::runtime_error(label + " line " + std::to_string(c.line) + ": case '" + c.id + "' says meta.certified " +
                               std::string(to_string(c.certified)) + ", its certified answer is " + std::string(to_string(inst.certified)));
    take_certified(c, inst);
  }
}

int run_cases(const CaseSpec& spec, std::ostream& out) {
  for (const Case& c : make_cases(spec)) out << case_line(c).dump() << '\n';
  if (spec.map_cells > 0)
    for (const Case& c : judging::map_cell_cases({parse_study_query(spec.query)}, spec.map_cells, spec.map_step, spec.seed,
                                                 spec.threads))
      out << case_line(c).dump() << '\n';
  out.flush();
  return out ? 0 : 1;
}

}  // namespace certcyl::cli
