// `certcyl cases`: the study's instances of one query as ready-to-run `certcyl query` lines.
//
// A case is one planned instance of the study (study_plan.cpp: the hard-case families and the
// uniform inputs, each depending only on the seed, its family, its query and its index) with its
// certified answer and certified signed gap (study/gap.hpp). Its line is
//   {"id": "<query>/<family>/<index>", "query": Q, operands..., "meta": {"family", "k",
//    "certified", "gap": [lo, hi], "gap_quantity"}}
// with every coordinate a JSON number (its binary64 value, written to round trip), so
// `certcyl query` answers it as it stands and passes "meta" through. The gap is null when it is
// unbounded (cylinder pairs with equal midpoints); gap_quantity names what it measures
// (study/gap_quantity.hpp: log_phi for cylinder pairs, else depth_margin). Reading a case, a
// gap_quantity is optional (files written before it) but must be the query's when given.
// A line, ray or segment case whose certified answer meets the cylinder also carries "t_in": the
// certified entry parameter (the nearest double to the exact one; a segment's on p0 + t (p1 -
// p0)), which the judge scores an answer's interval against (t_error_ulps, as the study scores
// its methods).
// With map_cells, the cells of the query's failure maps follow (the maps `certcyl judge` draws
// for a plugin or a program): id "failure_map/<map>/<row>/<column>", family "failure_map/<map>",
// k 0 and "meta.map": {"cells", "step", "seed"}; answered in an answers file, they give the
// judge its maps (judge.cpp).
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <iosfwd>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "certcyl/answer.hpp"
#include "study/instance.hpp"
#include "study/methods.hpp"  // Contract

namespace certcyl::cli {

struct CaseSpec {
  std::string query;                  // a study query: line_cylinder, ..., cylinder_cylinder
  std::vector<std::string> families;  // family names to keep (empty: every family of the query)
  std::string size = "small";         // tiny | small | default | large | N (cases per family)
  std::uint64_t seed = 1;
  unsigned threads = 2;               // for certifying
  int map_cells = 0;                  // run_cases: also the failure maps' cells (N x N), 0: none
  long map_step = 1;                  // ulps between neighbouring cells
};

// The failure maps a map cell belongs to (`certcyl cases --map-cells`): the maps of
// map_grids(seed, cells, step) (study_maps.cpp).
struct MapCell {
  int cells = 0;
  long step = 1;
  std::uint64_t seed = 1;
};

struct Case {
  std::string id;
  study::Query query = study::Query::line_cylinder;
  std::string family;
  long long k = 0;
  Answer certified = Answer::undecided;
  // The certified answer under the ray-cast contracts (study/contract.hpp): for rays and
  // segments; the solid answer for the other queries.
  Answer certified_entry = Answer::undecided, certified_surface_hit = Answer::undecided;
  double gap_lo = 0, gap_hi = 0;
  double t_in = std::numeric_limits<double>::quiet_NaN();  // line queries that meet: the certified entry parameter
  std::vector<double> x;       // study/instance.hpp layout
  std::size_t line = 0;        // its line in the cases file, or in `certcyl cases` of the same options (from 1)
  std::optional<MapCell> map;  // a failure map's cell (family failure_map/<map>), not a family's case
};

// The study query named `name`; throws std::invalid_argument listing the names.
study::Query parse_study_query(const std::string& name);

// What the case is scored by, from its certified instance: the answers under the three
// contracts, the gap and t_in.
void take_certified(Case& c, const study::Instance& inst);

// The instance holding the case's certified answers (under every contract), as the study's
// outcome_of and certified_under read them.
study::Instance certified_instance(const Case& c);

// The contract named `name` (solid, surface_entry, surface_hit; study/contract.hpp); throws
// std::invalid_argument naming `where` and listing the names.
study::Contract parse_contract(const std::string& name, const std::string& where);

// Whether a contract other than solid is defined for the query: rays and segments (the ray
// casts' queries); any other query is judged under the solid contract.
constexpr bool has_ray_contracts(study::Query q) { return q == study::Query::ray_cylinder || q == study::Query::segment_cylinder; }

// The planned instances of the spec, certified, in the study's order. Throws
// std::invalid_argument on an unknown query, family or size.
std::vector<Case> make_cases(const CaseSpec& spec);

// The case's `certcyl query` line without "meta": id, query and operands.
nlohmann::ordered_json query_line(const Case& c);
// The same with "meta" (family, k, certified, gap; a map cell's "map": {cells, step, seed}).
nlohmann::ordered_json case_line(const Case& c);

// Reads a cases file (lines written by case_line; blank lines skipped). Throws
// std::runtime_error naming `label` and the line: not JSON, a missing or malformed member, a
// query that is not a study query, a duplicate id.
std::vector<Case> read_cases(std::istream& in, const std::string& label);

// Certifies cases read from a file again from their inputs, as make_cases does (threads at a
// time): the judge scores by the certified answer, gap and t_in it computes, never by what a file
// says. A case whose meta.certified differs from its certified answer is an error: throws
// std::runtime_error naming `label`, the line and both answers.
void recertify(std::vector<Case>& cases, unsigned threads, const std::string& label);

// `certcyl cases`: writes the lines; returns the exit status (1 when a write failed).
int run_cases(const CaseSpec& spec, std::ostream& out);

}  // namespace certcyl::cli
