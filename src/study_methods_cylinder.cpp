// The study's methods for cylinder against cylinder: the certified query as users run it, and
// Eberly's separating-axis seed as written and corrected in every generic number type, with
// sweeps of its tolerance choices in double (bisection steps, comparison strictness, the
// parallel-axes threshold).
#include <cmath>

#include "certcyl/certified/cylinder_cylinder.hpp"
#include "certcyl/seeds/eberly_cylinders.hpp"
#include "study_methods.hpp"

namespace certcyl::cli {
namespace {

// The seed in one number type. Its three-valued answer: as written it restates the boolean
// (separated or overlapping), corrected it reports touching when only f(D) = 0 was found;
// invalid when the direction it found is not finite or a value of the seed overflowed
// (non_finite), as `certcyl query` answers "invalid".
study::MethodOutput run_eberly(const NumberTypeSpec& spec, const EberlyParameters& params, const std::vector<double>& x) {
  return dispatch(spec, [&]<class NT>() -> study::MethodOutput {
    if constexpr (NumberTraits<NT>::has_sqrt && NumberTraits<NT>::is_field) {
      try {
        const auto r = eberly_separated(to_nt<NT>(study::cylinder_at(x, 0)), to_nt<NT>(study::cylinder_at(x, 7)), params);
        study::MethodOutput m =
            params.variant == EberlyVariant::as_written ? study::boolean_answer(!r.separated) : study::three_valued(r.answer);
        for (const NT& c : {r.direction.x, r.direction.y, r.direction.z})
          if (!std::isfinite(nt::to_double(c))) m.invalid = true;
        if (!r.non_finite.empty()) m.invalid = true;  // a value overflowed: no answer
        return m;
      } catch (const CGAL::Uncertain_conversion_exception&) {
        return study::three_valued(Answer::undecided);
      }
    } else {
      throw std::logic_error("the seed needs a square root");
    }
  });
}

}  // namespace

void register_cylinder_methods(study::Registry& r) {
  using study::MethodKind;
  using study::Query;
  const Query q = Query::cylinder_cylinder;
  r.push_back({"certified", "exact", MethodKind::certified, q, 1, {}, [](const std::vector<double>& x) {
                 return study::three_valued(certified_cylinder_cylinder(study::cylinder_at(x, 0), study::cylinder_at(x, 7)).answer);
               }});
  // The seed: its iterative searches cost 10^2..10^4 times a line query in the slow types.
  for (const NumberTypeChoice& c : generic_number_types()) {
    const NumberTypeSpec spec = c.spec;
    const unsigned stride = spec.kind == NumberKind::core_expr ? 16 : (spec.kind == NumberKind::gmpfr ? 4 : c.stride);
    // Maps on every 4th (Gmpfr) and 16th (CORE::Expr) row and column: near touching, one call
    // costs up to ~1 ms in Gmpfr and ~10 ms in CORE::Expr.
    const study::Effort effort = spec.kind == NumberKind::core_expr ? study::Effort{16, 2}
                                 : spec.kind == NumberKind::gmpfr   ? study::Effort{4, 1}
                                                                    : study::Effort{1, 1};
    r.push_back({"eberly_cylinders_as_written", spec.name(), MethodKind::seed_as_written, q, stride, effort,
                 [spec](const std::vector<double>& x) { return run_eberly(spec, EberlyParameters::as_written(), x); }});
    r.push_back({"eberly_cylinders", spec.name(), MethodKind::seed_corrected, q, stride, effort,
                 [spec](const std::vector<double>& x) { return run_eberly(spec, EberlyParameters::corrected(), x); }});
  }
  // Sweeps of the tolerance choices, corrected variant in double.
  const NumberTypeSpec dbl{NumberKind::double_, 53};
  auto sweep = [&](const std::string& label, EberlyParameters p) {
    r.push_back({"eberly_cylinders[" + label + "]", "double", MethodKind::sweep, q, 1, {},
                 [dbl, p](const std::vector<double>& x) { return run_eberly(dbl, p, x); }});
  };
  for (int n : {2, 4, 8, 16, 64}) {
    EberlyParameters p;
    p.perpendicular_bisections = n;
    p.line_search_bisections = n;
    sweep("bisections=" + std::to_string(n), p);
  }
  {
    EberlyParameters p;
    p.axis_tests = p.perpendicular_tests = p.other_direction_tests = p.parallel_tests = Strictness::non_strict;
    sweep("non_strict", p);
    EberlyParameters m;
    m.perpendicular_tests = m.other_direction_tests = Strictness::non_strict;
    sweep("mixed_strictness", m);
  }
  for (double t : {1e-12, 1e-8, 1e-4}) {
    EberlyParameters p;
    p.parallel_test = ParallelTest::threshold;
    p.parallel_threshold = t;
    char label[40];
    std::snprintf(label, sizeof label, "parallel<=%g", t);
    sweep(label, p);
  }
}

}  // namespace certcyl::cli
