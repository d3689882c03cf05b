// Fuzz harness: certified cylinder against cylinder, every certificate re-checked exactly by
// fuzz/recheck.hpp (the separating direction re-evaluated in Gmpq with the squaring rule, the
// witness point tested in Gmpq). Input (fuzz_input.hpp): two cylinders p0, p1, radius; the
// pair is also run swapped, and a decided answer must not change. The query runs with a
// resource limit (Gmpfr rounds up to 256 bits, so one input stays under a second); an
// undecided answer is a failure when the input spans at most 64 binades (the refine stage and
// those rounds decide such input: a regression there is caught), and is allowed beyond, where
// the query is not yet proved to decide within the limit.
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
  CylinderCylinderOptions options;
  options.max_precision = 256;
  const bool narrow = detail::cylinder_pair_span_bits(detail::CylinderPair<Rational>::make(a, b)) <= 64;
  const CylinderCylinderResult r = certified_cylinder_cylinder(a, b, options);
  if (const std::string f = recheck::check_cylinder_pair(a, b, r); !f.empty()) fuzz::wrong_answer(f);
  if (narrow && r.answer == Answer::undecided) fuzz::failure("UNDECIDED on input spanning at most 64 binades");
  const CylinderCylinderResult s = certified_cylinder_cylinder(b, a, options);
  if (const std::string f = recheck::check_cylinder_pair(b, a, s); !f.empty()) fuzz::wrong_answer("swapped: " + f);
  if (narrow && s.answer == Answer::undecided) fuzz::failure("UNDECIDED on input spanning at most 64 binades (swapped)");
  if (r.answer != s.answer && r.answer != Answer::undecided && s.answer != Answer::undecided)
    fuzz::wrong_answer("swapping the cylinders changed the answer");
  return 0;
}
