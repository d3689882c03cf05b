// `certcyl scene`: the statistics of --stats on a scene worked out by hand, and a generated
// scene (`certcyl make-scene`) against its construction and against every pair of cylinders.
#define BOOST_TEST_MODULE cli_scene
#include <boost/test/unit_test.hpp>

#include <array>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <new>
#include <set>
#include <sstream>
#include <thread>

#include "certcyl/certified/cylinder_cylinder.hpp"
#include "query.hpp"
#include "scene.hpp"
#include "scene_generator.hpp"

using namespace certcyl;
using namespace certcyl::cli;

// Fault injection: while `fail_off_thread` is set, operator new throws std::bad_alloc in every
// thread but `allowed_thread` (the test's own), as it would when memory runs out in a worker.
namespace {
std::atomic<bool> fail_off_thread{false};
std::thread::id allowed_thread;
}  // namespace

// (GCC sees the malloc and free below and takes them for a mismatched new and free.)
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void* operator new(std::size_t n) {
  if (fail_off_thread.load() && std::this_thread::get_id() != allowed_thread) throw std::bad_alloc();
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace {

std::vector<json> json_lines(const std::string& text) {
  std::vector<json> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(json::parse(line));
  return lines;
}

json stats_line(const std::string& err) {
  const std::string prefix = "certcyl scene stats: ";
  const auto at = err.find(prefix);
  BOOST_TEST_REQUIRE(at != std::string::npos);
  const auto end = err.find('\n', at);
  return json::parse(err.substr(at + prefix.size(), end - at - prefix.size()));
}

}  // namespace

BOOST_AUTO_TEST_CASE(stats_count_the_pairs_worked_out_by_hand) {
  const std::string path = "test_cli_scene_hand.json";
  {
    std::ofstream f(path);
    f << R"({"cylinders": [
      {"name": "a", "p0": [0,0,0], "p1": [0,0,2], "radius": 1},
      {"name": "b", "p0": [2,0,0], "p1": [2,0,2], "radius": 1},
      {"name": "far", "p0": [10,0,0], "p1": [10,0,2], "radius": 1},
      {"name": "x", "center": [0,0,1], "axis": [1,0,0], "radius": "1/2", "height": 4},
      {"name": "near", "p0": [1.5,1.5,0], "p1": [1.5,1.5,2], "radius": 0.5}],
      "triangles": [{"name": "t", "vertices": [[0,0,2],[5,0,2],[0,5,2]]}]})";
  }
  // Bounding boxes (exact here): a [-1,1]x[-1,1]x[0,2], b [1,3]x[-1,1]x[0,2], far [9,11]x[-1,1]x[0,2],
  // x [-2,2]x[-1/2,1/2]x[1/2,3/2], near [1,2]x[1,2]x[0,2], t [0,5]x[0,5]x[2,2]. Closed boxes
  // meet for a-b (at x = 1), a-x, a-near (at the edge x = y = 1), a-t (at z = 2), b-x, b-near
  // (at y = 1), b-t and near-t: 8 candidate pairs. Of these, by hand:
  //   a-b touching (walls at (1, 0, z)); a-x, b-x overlapping (x passes through both);
  //   a-t, b-t touching (their top caps lie in the triangle's plane z = 2 and meet the
  //   triangle); near-t touching (its top cap, the disk of radius 1/2 around (3/2, 3/2, 2),
  //   lies inside the triangle: x + y <= 7/2 < 5);
  //   a-near separated (axes sqrt(9/2) > 3/2 apart), b-near separated (axes
  //   sqrt(1/4 + 9/4) = sqrt(5/2) > 3/2 apart).
  for (unsigned threads : {1u, 2u}) {
    std::ostringstream out, err;
    BOOST_TEST(run_scene(path, out, threads, false, true, err) == 0);
    const json s = stats_line(err.str());
    BOOST_TEST(s["cylinders"] == 5);
    BOOST_TEST(s["triangles"] == 1);
    BOOST_TEST(s["candidate_pairs"] == 8);
    BOOST_TEST(s["separated"] == 2);
    BOOST_TEST(s["touching"] == 4);
    BOOST_TEST(s["overlapping"] == 2);
    BOOST_TEST(s["undecided"] == 0);
    BOOST_TEST(s["threads"] == threads);
    for (const char* phase : {"read", "boxes", "broad", "narrow", "write"}) BOOST_TEST(s["seconds"][phase].get<double>() >= 0.0);
    const auto lines = json_lines(out.str());
    // The lines come in the broad phase's order; as a set they are the pairs worked out above.
    const std::set<std::array<std::string, 3>> expected{{"a", "b", "touching"},   {"a", "x", "overlapping"}, {"a", "t", "touching"},
                                                        {"b", "x", "overlapping"}, {"b", "t", "touching"},   {"near", "t", "touching"}};
    std::set<std::array<std::string, 3>> found;
    for (const json& l : lines) {
      found.insert({l["a"].get<std::string>(), l["b"].get<std::string>(), l["answer"].get<std::string>()});
      BOOST_TEST(l["certified"] == true);
    }
    BOOST_TEST(lines.size() == expected.size());
    BOOST_TEST((found == expected));
  }
  // Without --stats, only the one-line summary.
  std::ostringstream out, err;
  BOOST_TEST(run_scene(path, out, 1, false, false, err) == 0);
  BOOST_TEST(err.str().find("stats:") == std::string::npos);
  BOOST_TEST(err.str().find("4 touching, 2 overlapping, 0 undecided") != std::string::npos);
  std::remove(path.c_str());
}

// A generated scene: every pair built to touch is reported touching, and the scene's lines are
// exactly the meeting pairs found by the certified query on every pair of cylinders (no broad
// phase), in pair order, on 1 and 2 threads.
BOOST_AUTO_TEST_CASE(generated_scene_against_construction_and_all_pairs) {
  SceneSpec spec;
  spec.cylinders = 900;
  spec.seed = 7;
  spec.touching_share = 0.2;
  const GeneratedScene g = generate_scene(spec);
  BOOST_TEST(g.document["cylinders"].size() == 900u);
  BOOST_TEST(g.touching.size() == 90u);
  BOOST_TEST(generate_scene(spec).document == g.document);  // seeded: the same scene again
  const std::vector<SceneSolid> solids = read_scene(json::parse(g.document.dump()));

  std::map<std::pair<std::string, std::string>, std::string> brute;
  for (std::size_t i = 0; i < solids.size(); ++i)
    for (std::size_t j = i + 1; j < solids.size(); ++j) {
      const Answer a = certified_cylinder_cylinder(solids[i].cylinder, solids[j].cylinder, {}).answer;
      if (a != Answer::separated) brute[{solids[i].name, solids[j].name}] = std::string(to_string(a));
    }
  std::string previous;
  for (unsigned threads : {1u, 2u}) {
    SceneStats stats;
    const std::vector<std::string> lines = meeting_pairs(solids, threads, false, stats);
    std::map<std::pair<std::string, std::string>, std::string> found;
    std::string all;
    for (const std::string& l : lines) {
      if (l.empty()) continue;
      all += l + '\n';
      const json j = json::parse(l);
      found[{j["a"], j["b"]}] = j["answer"];
    }
    BOOST_TEST(found == brute);
    BOOST_TEST(stats.touching + stats.overlapping + stats.undecided == brute.size());
    BOOST_TEST(stats.candidate_pairs >= brute.size());
    if (!previous.empty()) BOOST_TEST(all == previous);  // the same lines in the same order
    previous = all;
  }
  for (const auto& [i, j] : g.touching) {
    const std::string a = solids[i].name, b = solids[j].name;
    BOOST_TEST_CONTEXT(a << " " << b) {
      BOOST_TEST(a.substr(0, a.size() - 1) == b.substr(0, b.size() - 1));
      const std::string answer = brute[std::make_pair(a, b)];
      BOOST_TEST(answer == "touching");
    }
  }
  // The scene has the density it was built for: many candidate pairs, a good share meeting.
  SceneStats stats;
  meeting_pairs(solids, 1, false, stats);
  BOOST_TEST(stats.candidate_pairs > 900u);
  BOOST_TEST(stats.overlapping > 100u);
}

namespace {

std::vector<SceneSolid> identical_cylinders(std::size_t n) {
  json cyls = json::array();
  for (std::size_t i = 0; i < n; ++i)
    cyls.push_back({{"name", std::string("c").append(std::to_string(i))}, {"p0", {0, 0, 0}}, {"p1", {0, 0, 1}}, {"radius", 1}});
  return read_scene(json{{"cylinders", cyls}});
}

}  // namespace

// The scan streams: at most one chunk of pairs is held, whatever the number of pairs, and every
// pair is written exactly once, in the same order for every chunk size and thread count.
BOOST_AUTO_TEST_CASE(streaming_holds_one_chunk) {
  const std::vector<SceneSolid> solids = identical_cylinders(120);  // 7,140 pairs, all overlapping
  std::vector<std::string> reference;
  for (const std::size_t chunk : {std::size_t{1000}, std::size_t{7}, kSceneChunk}) {
    for (unsigned threads : {1u, 2u}) {
      SceneStats stats;
      std::vector<std::string> lines;
      const int status = stream_meeting_pairs(solids, threads, false, stats, [&](const std::string& l) {
        lines.push_back(l);
        return true;
      }, chunk);
      BOOST_TEST_CONTEXT("chunk " << chunk << ", " << threads << " threads") {
        BOOST_TEST(status == 0);
        BOOST_TEST(stats.candidate_pairs == 7140u);
        BOOST_TEST(stats.overlapping == 7140u);
        BOOST_TEST(stats.max_pairs_held == std::min<std::size_t>(chunk, 7140));
        BOOST_TEST(lines.size() == 7140u);
        std::set<std::pair<std::string, std::string>> distinct;
        for (const std::string& l : lines) {
          const json j = json::parse(l);
          BOOST_TEST(j["answer"] == "overlapping");
          const std::string a = j["a"], b = j["b"];
          BOOST_TEST(std::stoi(a.substr(1)) < std::stoi(b.substr(1)));  // a before b in the scene
          distinct.emplace(a, b);
        }
        BOOST_TEST(distinct.size() == 7140u);
        if (reference.empty()) reference = lines;
        BOOST_TEST((lines == reference));
      }
    }
  }
}

// A write that fails stops the scan with status 1 after the failing line: nothing more is
// computed for output that cannot be written.
BOOST_AUTO_TEST_CASE(a_failed_write_stops_the_scan) {
  const std::vector<SceneSolid> solids = identical_cylinders(40);
  SceneStats stats;
  std::size_t written = 0;
  const int status = stream_meeting_pairs(solids, 1, false, stats, [&](const std::string&) { return ++written < 5; }, 10);
  BOOST_TEST(status == 1);
  BOOST_TEST(written == 5u);
  BOOST_TEST(stats.candidate_pairs < 780u);
}

// chunk_written is called after each chunk's lines, before the next chunk's queries (run_scene
// flushes there, so that an end of the process in GMP leaves no cut line); false stops the scan
// with status 1.
BOOST_AUTO_TEST_CASE(chunk_written_follows_each_chunk_and_can_stop_the_scan) {
  const std::vector<SceneSolid> solids = identical_cylinders(40);  // 780 pairs, all overlapping
  SceneStats stats;
  std::size_t written = 0;
  std::vector<std::size_t> at;  // the lines written at each call
  const auto write = [&](const std::string&) { return ++written, true; };
  BOOST_TEST(stream_meeting_pairs(solids, 2, false, stats, write, 100, [&] { return at.push_back(written), true; }) == 0);
  BOOST_TEST(written == 780u);
  BOOST_TEST((at == std::vector<std::size_t>{100, 200, 300, 400, 500, 600, 700, 780}));
  written = 0;
  at.clear();
  BOOST_TEST(stream_meeting_pairs(solids, 2, false, stats, write, 100, [&] { return at.push_back(written), at.size() < 3; }) == 1);
  BOOST_TEST(written == 300u);
}

// A worker thread that runs out of memory does not end the process: the scan throws
// std::bad_alloc after writing, in order, the lines of the pairs before the failed one.
BOOST_AUTO_TEST_CASE(out_of_memory_in_a_worker_keeps_the_lines_written) {
  const std::vector<SceneSolid> solids = identical_cylinders(120);  // 7,140 pairs, all overlapping
  std::vector<std::string> reference;
  SceneStats stats;
  BOOST_TEST_REQUIRE(stream_meeting_pairs(solids, 4, false, stats, [&](const std::string& l) {
    reference.push_back(l);
    return true;
  }, 64) == 0);
  BOOST_TEST_REQUIRE(reference.size() == 7140u);

  allowed_thread = std::this_thread::get_id();
  std::vector<std::string> lines;
  bool threw = false;
  try {
    // From the 50th line on, every allocation of the three worker threads fails.
    stream_meeting_pairs(solids, 4, false, stats, [&](const std::string& l) {
      lines.push_back(l);
      if (lines.size() == 50) fail_off_thread = true;
      return true;
    }, 64);
  } catch (const std::bad_alloc&) {
    threw = true;
  }
  fail_off_thread = false;
  BOOST_TEST(threw);
  BOOST_TEST(lines.size() >= 64u);  // the first chunk, computed before the failures began
  BOOST_TEST(lines.size() < 7140u);
  BOOST_TEST_REQUIRE(lines.size() <= reference.size());
  BOOST_TEST((std::vector<std::string>(reference.begin(), reference.begin() + static_cast<std::ptrdiff_t>(lines.size())) == lines));
}

// The command: the message, status 1, and only complete lines of the pairs before the failure.
BOOST_AUTO_TEST_CASE(out_of_memory_in_a_worker_is_reported_by_the_command) {
  const std::string path = "test_cli_scene_oom.json";
  {
    json cyls = json::array();
    for (int i = 0; i < 200; ++i)
      cyls.push_back({{"name", std::string("c").append(std::to_string(i))}, {"p0", {0, 0, 0}}, {"p1", {0, 0, 1}}, {"radius", 1}});
    std::ofstream(path) << json{{"cylinders", cyls}}.dump();
  }
  std::ostringstream out, err;
  allowed_thread = std::this_thread::get_id();
  fail_off_thread = true;
  const int status = run_scene(path, out, 4, false, false, err);
  fail_off_thread = false;
  std::remove(path.c_str());
  BOOST_TEST(status == 1);
  BOOST_TEST(err.str() == "certcyl scene: out of memory in the scan; the lines of the pairs examined before are written\n");
  const std::string text = out.str();
  BOOST_TEST((text.empty() || text.back() == '\n'));
  const std::vector<json> lines = json_lines(text);
  BOOST_TEST(lines.size() < 19900u);
  for (std::size_t k = 0; k < lines.size(); ++k) BOOST_TEST(lines[k]["answer"] == "overlapping");
}

// make-scene streams: the document written as generated is byte for byte the one built in
// memory, and the touching pairs are where the construction puts them.
BOOST_AUTO_TEST_CASE(make_scene_streams_the_same_document) {
  SceneSpec spec;
  spec.cylinders = 901;
  spec.seed = 11;
  spec.touching_share = 0.2;  // 90 touching pairs after 721 random cylinders
  std::ostringstream out;
  BOOST_TEST(write_scene(spec, out));
  const GeneratedScene g = generate_scene(spec);
  BOOST_TEST(out.str() == g.document.dump() + "\n");
  BOOST_TEST(g.touching.size() == 90u);
  BOOST_TEST(g.touching.front().first == 721u);
  BOOST_TEST(g.touching.back().second == 900u);
  BOOST_TEST(g.document["cylinders"][721]["name"] == "walls0a");
  BOOST_TEST(g.document["cylinders"][900]["name"] == "caps89b");
  // A stream that fails stops the generation.
  std::ostringstream failed;
  failed.setstate(std::ios::badbit);
  BOOST_TEST(!write_scene(spec, failed));
}

BOOST_AUTO_TEST_CASE(scene_names_are_distinct) {
  const json twice = json::parse(R"({"cylinders": [
      {"name": "a", "p0": [0,0,0], "p1": [0,0,2], "radius": 1},
      {"name": "b", "p0": [2,0,0], "p1": [2,0,2], "radius": 1}],
      "triangles": [{"name": "a", "vertices": [[0,0,2],[5,0,2],[0,5,2]]}]})");
  try {
    read_scene(twice);
    BOOST_FAIL("a duplicate name was accepted");
  } catch (const InvalidInput& e) {
    BOOST_TEST(std::string(e.what()) == "triangles[0]: name \"a\" is also the name of cylinders[0]");
  }
  // A default name (the entry's path) can clash with a given one too.
  const json clash = json::parse(R"({"cylinders": [
      {"p0": [0,0,0], "p1": [0,0,2], "radius": 1},
      {"name": "cylinders[0]", "p0": [2,0,0], "p1": [2,0,2], "radius": 1}]})");
  BOOST_CHECK_THROW(read_scene(clash), InvalidInput);
}

BOOST_AUTO_TEST_CASE(misspelt_scene_members_are_named_with_the_valid_ones) {
  try {
    read_scene(json::parse(R"({"cylinders": [{"nme": "a", "p0": [0,0,0], "p1": [0,0,2], "radius": 1}]})"));
    BOOST_FAIL("a misspelt member was accepted");
  } catch (const InvalidInput& e) {
    BOOST_TEST(std::string(e.what()) ==
               "cylinders[0].nme: unexpected member (endpoint form: p0, p1, radius); a scene entry may also have \"name\"");
  }
  try {
    read_scene(json::parse(R"({"cylinders": [], "triangle": []})"));
    BOOST_FAIL("a misspelt member was accepted");
  } catch (const InvalidInput& e) {
    BOOST_TEST(std::string(e.what()) == "triangle: unexpected member (a scene has \"cylinders\" and \"triangles\")");
  }
}
