// `certcyl judge`: a method's answers to the study's cases, scored as the study scores its own
// methods (study/methods.hpp: judge, disagrees), into results/<name>/ and a summary table.
//
// The answers come from one of three sources: a file of {"id", "answer"} lines (--answers), a
// program answering `certcyl query` lines on its standard input (--exec), or a C plugin
// (certcyl/plugin.h, --plugin). The method's contract (--contract, or the plugin's) says which
// certified answer its rays and segments are judged against. The cases come from a cases file (--cases, written by
// `certcyl cases`) or are made in process (--query, --family, --size, --seed).
//
// A program or plugin that gives no answer for `timeout_seconds` is killed (its whole process
// group for --exec) and the run ends as on any failure, with the answers before it kept.
//
// With --plugin or --exec the method is also judged on the study's failure maps around every
// degeneracy of the judged queries (results/<name>/failure_maps/, as the study writes them, and
// failure_maps.csv); an answers file has no answers for them.
//
// A shard i of n judges the cases whose index (in the cases' order) is i modulo n into
// results/<name>/shard-i-of-n: written as shard-i-of-n.partial and renamed when every case of
// the shard is judged, so a folder by the final name is always a finished shard. Its
// answers.jsonl, the shards' concatenated, is an answers file judging the whole cases file
// exactly as an unsharded run would (with the same --label).
#pragma once

#include <ostream>
#include <string>

#include "cases.hpp"

namespace certcyl::cli {

struct JudgeOptions {
  std::string answers_file;  // --answers
  std::string exec_command;  // --exec, run by /bin/sh -c
  std::string plugin_file;   // --plugin
  std::string cases_file;    // --cases; else the cases of `spec`
  CaseSpec spec;             // spec.query empty: every query a plugin exports
  std::string name = "judge";
  std::string out_root = "results";
  std::string label;             // the method's name in the results; empty: from the source
  // --contract: what the method's positive answer to a ray or segment promises
  // (study/contract.hpp); its ray and segment cases, maps and hunt are judged under it, the
  // other queries under solid. Empty: the plugin's certcyl_plugin_contract, else solid. A given
  // contract other than solid needs a ray or segment case, and must agree with the plugin's.
  std::string contract;
  double timeout_seconds = 60;   // --timeout; 0: no limit
  int shard_index = 0, shard_count = 1;
  // The failure maps (judge_maps.cpp; --plugin and --exec, unsharded runs; --map-cells,
  // --map-step): map_cells x map_cells inputs map_step ulps apart around each degeneracy of the
  // judged queries; -1: the size's (16 for tiny, 32 small, 64 default, 128 large), 0: none
  // (the command line gives 2 to 1024).
  int map_cells = -1;
  long map_step = 1;
  // The hunt for the worst input (with the maps; --hunt-evaluations): evaluations per query (a
  // quarter for cylinder pairs); -1: the size's (20 tiny, 150 small, 1000 default, 5000 large),
  // 0: none (the command line gives 1 to 10^8).
  long hunt_evaluations = -1;
  // --study DIR: a study's results folder; when every case was judged, the study's
  // speed-against-error figures are drawn again with the judged method's point
  // (experiments/plot_study.py DIR --judged <results> --out <results>/figures), the study's
  // folder left unchanged. Not with --shard.
  std::string study_dir;
};

// Runs the command; returns 0 when every case was judged, 1 otherwise (the error on `err`; what
// was judged before it is written all the same).
int run_judge(const JudgeOptions& options, std::ostream& out, std::ostream& err);

}  // namespace certcyl::cli
