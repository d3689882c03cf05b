// Fuzz harness: certified line/ray/segment against a circular or elliptic cylinder, every
// answer re-checked exactly by fuzz/recheck.hpp (an independent recomputation of the interval).
// Input: a selector byte (range: line, ray, segment; solid: circular or elliptic), then the
// numbers (fuzz_input.hpp): origin, direction (segment: second point), and the solid.
#include "certcyl/certified/line_cylinder.hpp"
#include "fuzz_input.hpp"
#include "recheck.hpp"

using namespace certcyl;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::ByteReader in(data, size);
  const std::uint8_t selector = in.byte();
  const auto range = static_cast<LineRange>(selector % 3);
  const bool elliptic = (selector / 3) % 2 == 1;
  const Vec3<Rational> O = in.vec3(), second = in.vec3();
  const Vec3<Rational> d = range == LineRange::segment ? Vec3<Rational>(second - O) : second;
  try {
    if (range == LineRange::segment) validate(Segment<Rational>{O, second}, "segment");
    else validate(Line<Rational>{O, d}, "line");
    if (elliptic) {
      const EllipticCylinder<Rational> e{in.vec3(), in.vec3(), in.vec3(), in.vec3()};
      if (!in.finite()) return 0;
      validate(e, "elliptic_cylinder");
      const auto run = [&]() {
        switch (range) {
          case LineRange::line: return certified_line_cylinder(Line<Rational>{O, d}, e);
          case LineRange::ray: return certified_line_cylinder(Ray<Rational>{O, d}, e);
          default: return certified_line_cylinder(Segment<Rational>{O, second}, e);
        }
      };
      if (const std::string f = recheck::check_line(O, d, range, e, run()); !f.empty()) fuzz::wrong_answer(f);
    } else {
      const Cylinder<Rational> c = in.cylinder();
      if (!in.finite()) return 0;
      validate(c, "cylinder");
      const auto run = [&]() {
        switch (range) {
          case LineRange::line: return certified_line_cylinder(Line<Rational>{O, d}, c);
          case LineRange::ray: return certified_line_cylinder(Ray<Rational>{O, d}, c);
          default: return certified_line_cylinder(Segment<Rational>{O, second}, c);
        }
      };
      if (const std::string f = recheck::check_line(O, d, range, c, run()); !f.empty()) fuzz::wrong_answer(f);
    }
  } catch (const InvalidInput&) {
    // Rejected at the boundary, as the command would.
  }
  return 0;
}
