// Fuzz harness: certified cylinder against cylinder, every certificate re-checked exactly by
// fuzz/recheck.hpp (the separating direction re-evaluated in Gmpq with the squaring rule, the
// witness point tested in Gmpq). Input (fuzz_input.hpp): two cylinders p0, p1, radius; the
// pair is also run swapped, and the answer must not change. The query runs with its default
// options, without a resource limit, so it must decide every valid input (the completeness
// theorem): an undecided answer is a failure, and so is one input taking longer than the
// fuzzer's timeout.
#include "certcyl/certified/cylinder_cylinder.hpp"
#include "fuzz_input.hpp"
#include "recheck.hpp"

using namespace certcyl;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::ByteReader in(data, size);
  const Cylinder<Rational> a = in.cylinder(), b = in.cylinder();
  if (!in.finite()) return 0;
  try {
    validate(a, "a");
    validate(b, "b");
  } catch (const InvalidInput&) {
    return 0;
  }
  const CylinderCylinderOptions options{};
  const CylinderCylinderResult r = certified_cylinder_cylinder(a, b, options);
  if (const std::string f = recheck::check_cylinder_pair(a, b, r); !f.empty()) fuzz::wrong_answer(f);
  if (r.answer == Answer::undecided) fuzz::failure("UNDECIDED without a resource limit");
  const CylinderCylinderResult s = certified_cylinder_cylinder(b, a, options);
  if (const std::string f = recheck::check_cylinder_pair(b, a, s); !f.empty()) fuzz::wrong_answer("swapped: " + f);
  if (s.answer == Answer::undecided) fuzz::failure("UNDECIDED without a resource limit (swapped)");
  if (r.answer != s.answer) fuzz::wrong_answer("swapping the cylinders changed the answer");
  return 0;
}
