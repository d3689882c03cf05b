#include "scene_generator.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <ostream>
#include <stdexcept>

namespace certcyl::cli {
namespace {

// splitmix64: the same stream on every platform and standard library.
class SplitMix {
 public:
  explicit SplitMix(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  double uniform(double lo, double hi) { return lo + (hi - lo) * (static_cast<double>(next() >> 11) * 0x1p-53); }
  // A multiple of 2^-10 in [lo, hi] (lo, hi multiples of 2^-10).
  double dyadic(double lo, double hi) {
    const auto a = static_cast<std::int64_t>(std::ldexp(lo, 10)), b = static_cast<std::int64_t>(std::ldexp(hi, 10));
    return std::ldexp(static_cast<double>(a + static_cast<std::int64_t>(next() % static_cast<std::uint64_t>(b - a + 1))), -10);
  }
  unsigned below(unsigned n) { return static_cast<unsigned>(next() % n); }

 private:
  std::uint64_t state_;
};

using P = std::array<double, 3>;

nlohmann::ordered_json cylinder(const std::string& name, const P& p0, const P& p1, double r) {
  return {{"name", name}, {"p0", p0}, {"p1", p1}, {"radius", r}};
}

}  // namespace

double for_each_scene_cylinder(const SceneSpec& spec, const std::function<bool(const nlohmann::ordered_json&)>& emit,
                               std::vector<std::pair<std::size_t, std::size_t>>* touching) {
  if (spec.neighbours <= 0 || spec.touching_share < 0 || spec.touching_share > 1)
    throw std::invalid_argument("make-scene: need neighbours > 0 and 0 <= touching share <= 1");
  SplitMix rng(spec.seed);
  const double n = static_cast<double>(std::max<std::size_t>(spec.cylinders, 1));
  // Side rounded to a multiple of 2^-10 so the dyadic placements below stay exact.
  const double S = std::max(4.0, std::round(std::ldexp(std::cbrt(n * 2.1 / spec.neighbours), 10)) / 1024.0);
  const auto pairs = static_cast<std::size_t>(std::floor(n * spec.touching_share / 2));
  const std::size_t random_count = spec.cylinders - std::min(spec.cylinders, 2 * pairs);
  std::size_t emitted = 0;
  for (std::size_t i = 0; i < random_count; ++i) {
    P d;
    double len2;
    do {
      d = {rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)};
      len2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    } while (len2 > 1 || len2 < 1e-6);
    const double half = rng.uniform(0.5, 1.5) / 2 / std::sqrt(len2);
    const P c{rng.uniform(0, S), rng.uniform(0, S), rng.uniform(0, S)};
    const double r = rng.uniform(0.05, 0.15);
    std::string name("c");
    name.append(std::to_string(i));
    if (!emit(cylinder(name, {c[0] - half * d[0], c[1] - half * d[1], c[2] - half * d[2]},
                       {c[0] + half * d[0], c[1] + half * d[1], c[2] + half * d[2]}, r)))
      return S;
    ++emitted;
  }
  const char* kinds[] = {"walls", "caps", "crossing", "capwall"};
  for (std::size_t j = 0; j < pairs; ++j) {
    const unsigned kind = static_cast<unsigned>(j % 4);
    const unsigned a = rng.below(3), b = (a + 1 + rng.below(2)) % 3, c = 3 - a - b;
    const double r1 = rng.dyadic(0.0625, 0.15), r2 = rng.dyadic(0.0625, 0.15);
    const double h1 = rng.dyadic(0.25, 0.75), h2 = rng.dyadic(0.25, 0.75);
    const P centre{rng.dyadic(1, S - 1), rng.dyadic(1, S - 1), rng.dyadic(1, S - 1)};
    P h0 = centre, h1p = centre;  // host: centre -+ h1 e_a
    h0[a] -= h1, h1p[a] += h1;
    P q0 = centre, q1 = centre;  // partner
    switch (kind) {
      case 0: {  // walls: parallel, axes r1 + r2 apart along e_b, shifted along e_a
        const double shift = rng.dyadic(-0.25, 0.25);
        q0[b] += r1 + r2, q1[b] += r1 + r2;
        q0[a] += shift - h2, q1[a] += shift + h2;
        break;
      }
      case 1: {  // caps: partner's p0 is the host's p1 moved across by less than r1 + r2
        q0 = h1p;
        q0[b] += rng.dyadic(-0.0625, 0.0625);
        q1 = q0;
        q1[a] += 2 * h2;
        break;
      }
      case 2: {  // crossing: along e_b through the host's middle, r1 + r2 away along e_c
        q0[c] += r1 + r2, q1[c] += r1 + r2;
        q0[b] -= h2, q1[b] += h2;
        break;
      }
      default: {  // capwall: along e_c, p0 on the host's wall line x_c = centre_c + r1
        const double along = rng.dyadic(-0.25, 0.25);
        q0[a] += along, q1[a] += along;
        q0[c] += r1;
        q1 = q0;
        q1[c] += 2 * h2;
        break;
      }
    }
    // (Appended piece by piece: g++ 12 warns falsely on operator+ of a short literal.)
    std::string host(kinds[kind]);
    host.append(std::to_string(j));
    std::string partner = host;
    host.push_back('a');
    partner.push_back('b');
    if (touching) touching->emplace_back(emitted, emitted + 1);
    if (!emit(cylinder(host, h0, h1p, r1)) || !emit(cylinder(partner, q0, q1, r2))) return S;
    emitted += 2;
  }
  return S;
}

GeneratedScene generate_scene(const SceneSpec& spec) {
  GeneratedScene out;
  nlohmann::ordered_json cyls = nlohmann::ordered_json::array();
  out.side = for_each_scene_cylinder(
      spec,
      [&](const nlohmann::ordered_json& c) {
        cyls.push_back(c);
        return true;
      },
      &out.touching);
  out.document = {{"cylinders", std::move(cyls)}};
  return out;
}

bool write_scene(const SceneSpec& spec, std::ostream& out) {
  out << "{\"cylinders\":[";
  bool first = true;
  std::string text;
  for_each_scene_cylinder(
      spec,
      [&](const nlohmann::ordered_json& c) {
        text.clear();
        if (!first) text.push_back(',');
        first = false;
        text += c.dump();
        out.write(text.data(), static_cast<std::streamsize>(text.size()));
        return static_cast<bool>(out);  // a failed write ends the scene
      },
      nullptr);
  out << "]}\n";
  out.flush();
  return static_cast<bool>(out);
}

}  // namespace certcyl::cli
