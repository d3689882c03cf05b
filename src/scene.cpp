#include "scene.hpp"

#include <atomic>
#include <chrono>
#include <fstream>
#include <iostream>
#include <thread>

#include "certcyl/broad_phase.hpp"
#include "certcyl/certified/cylinder_cylinder.hpp"
#include "certcyl/certified/triangle_cylinder.hpp"
#include "certcyl/io/json_input.hpp"
#include "query_cylinder.hpp"
#include "query_support.hpp"
#include "query_triangle.hpp"

namespace certcyl::cli {

namespace {

struct Solid {
  std::string name;
  bool is_cylinder = true;
  Cylinder<Rational> cylinder;
  Triangle<Rational> triangle;
};

// Reads a named solid: the object's "name" (optional) and its operand members.
std::string name_of(const json& entry, const std::string& field) {
  auto it = entry.find("name");
  if (it == entry.end()) return field;
  if (!it->is_string()) throw InvalidInput(join_field(field, "name"), "expected a string");
  return it->get<std::string>();
}

std::vector<Solid> read_scene(const json& scene) {
  if (!scene.is_object()) throw InvalidInput("", "a scene is a JSON object with \"cylinders\" and optionally \"triangles\"");
  for (auto it = scene.begin(); it != scene.end(); ++it)
    if (it.key() != "cylinders" && it.key() != "triangles") throw InvalidInput(it.key(), "unexpected member");
  JsonReader reader;
  std::vector<Solid> solids;
  if (auto cyls = scene.find("cylinders"); cyls != scene.end()) {
    if (!cyls->is_array()) throw InvalidInput("cylinders", "expected an array");
    for (std::size_t i = 0; i < cyls->size(); ++i) {
      const std::string field = index_field("cylinders", i);
      const json& entry = (*cyls)[i];
      if (!entry.is_object()) throw InvalidInput(field, "expected an object");
      json operand = entry;
      operand.erase("name");
      solids.push_back({name_of(entry, field), true, reader.cylinder(operand, field), {}});
    }
  }
  if (auto tris = scene.find("triangles"); tris != scene.end()) {
    if (!tris->is_array()) throw InvalidInput("triangles", "expected an array");
    for (std::size_t i = 0; i < tris->size(); ++i) {
      const std::string field = index_field("triangles", i);
      const json& entry = (*tris)[i];
      if (!entry.is_object()) throw InvalidInput(field, "expected an object {\"name\": ..., \"vertices\": [P, P, P]}");
      for (auto it = entry.begin(); it != entry.end(); ++it)
        if (it.key() != "name" && it.key() != "vertices") throw InvalidInput(join_field(field, it.key()), "unexpected member");
      solids.push_back({name_of(entry, field), false, {},
                        reader.triangle(JsonReader::member(entry, field, "vertices"), join_field(field, "vertices"))});
    }
  }
  return solids;
}

}  // namespace

int run_scene(const std::string& path, std::ostream& out, unsigned threads, bool progress) {
  std::ifstream file(path);
  if (!file) {
    std::cerr << "certcyl scene: cannot open '" << path << "'\n";
    return 1;
  }
  std::vector<Solid> solids;
  try {
    solids = read_scene(json::parse(file));
  } catch (const json::exception& e) {
    std::cerr << "certcyl scene: " << path << ": malformed JSON: " << e.what() << "\n";
    return 2;
  } catch (const InvalidInput& e) {
    std::cerr << "certcyl scene: " << path << ": " << e.what() << "\n";
    return 2;
  }

  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  std::vector<Box3> boxes;
  boxes.reserve(solids.size());
  for (const Solid& s : solids) boxes.push_back(s.is_cylinder ? bounding_box(s.cylinder) : bounding_box(s.triangle));
  auto pairs = candidate_pairs(boxes);
  // Triangle-triangle pairs are not a cylinder query.
  std::erase_if(pairs, [&](const auto& p) { return !solids[p.first].is_cylinder && !solids[p.second].is_cylinder; });
  const auto t1 = clock::now();

  std::vector<std::string> lines(pairs.size());
  std::atomic<std::size_t> next{0}, done{0};
  auto work = [&] {
    for (std::size_t k = next++; k < pairs.size(); k = next++) {
      const Solid& a = solids[pairs[k].first];
      const Solid& b = solids[pairs[k].second];
      ojson answer;
      if (a.is_cylinder && b.is_cylinder) {
        answer = cylinder_cylinder_json(certified_cylinder_cylinder(a.cylinder, b.cylinder, {}));
      } else {
        const Solid& t = a.is_cylinder ? b : a;
        const Solid& c = a.is_cylinder ? a : b;
        answer = triangle_cylinder_json(certified_triangle_cylinder(t.triangle, c.cylinder));
      }
      const std::string verdict = answer["answer"];
      if (verdict != "separated") {
        ojson line{{"a", a.name}, {"b", b.name}};
        for (auto it = answer.begin(); it != answer.end(); ++it) line[it.key()] = it.value();
        lines[k] = line.dump();
      }
      ++done;
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < std::max(1u, threads); ++t) pool.emplace_back(work);
  if (progress) {
    std::thread reporter([&] {
      while (done < pairs.size()) {
        std::cerr << "\rcertcyl scene: " << done << "/" << pairs.size() << " candidate pairs" << std::flush;
        std::this_thread::sleep_for(std::chrono::milliseconds(500));
      }
    });
    work();
    for (auto& t : pool) t.join();
    reporter.join();
    std::cerr << "\rcertcyl scene: " << pairs.size() << "/" << pairs.size() << " candidate pairs\n";
  } else {
    work();
    for (auto& t : pool) t.join();
  }
  const auto t2 = clock::now();
  std::size_t reported = 0;
  for (const auto& l : lines)
    if (!l.empty()) out << l << '\n', ++reported;
  out.flush();
  const double broad = std::chrono::duration<double>(t1 - t0).count();
  const double narrow = std::chrono::duration<double>(t2 - t1).count();
  std::cerr << "certcyl scene: " << solids.size() << " solids, " << pairs.size() << " candidate pairs, " << reported
            << " touching or overlapping (or undecided); broad phase " << broad << " s, narrow phase " << narrow << " s\n";
  if (!out) {
    std::cerr << "certcyl scene: error writing standard output\n";
    return 1;
  }
  return 0;
}

}  // namespace certcyl::cli
