// Fuzz harness: certified triangle against cylinder, every certificate re-checked exactly by
// fuzz/recheck.hpp (independent of the library's own check_triangle_cylinder_certificate,
// which is run too). Input (fuzz_input.hpp): three vertices, then the cylinder p0, p1, radius.
#include "certcyl/certified/triangle_cylinder.hpp"
#include "fuzz_input.hpp"
#include "recheck.hpp"

using namespace certcyl;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::ByteReader in(data, size);
  Vec3<Rational> v0 = in.vec3(), v1 = in.vec3(), v2 = in.vec3();
  const Triangle<Rational> T{{v0, v1, v2}};
  const Cylinder<Rational> C = in.cylinder();
  if (!in.finite()) return 0;
  try {
    validate(C, "cylinder");
  } catch (const InvalidInput&) {
    return 0;
  }
  const TriangleCylinderResult r = certified_triangle_cylinder(T, C);
  if (const std::string f = recheck::check_triangle(T, C, r); !f.empty()) fuzz::wrong_answer(f);
  if (const std::string f = check_triangle_cylinder_certificate(r, T, C); !f.empty()) fuzz::wrong_answer("library check: " + f);
  return 0;
}
