// The study's methods for line, ray and segment queries: the certified query, the robust double
// method, and the seeds (Shene and Gullotti, each as written and corrected) in every generic number type.
#include <cmath>

#include "certcyl/certified/line_cylinder.hpp"
#include "certcyl/robust/line_cylinder.hpp"
#include "certcyl/seeds/gullotti_line_elliptic_cylinder.hpp"
#include "certcyl/seeds/shene_line_cylinder.hpp"
#include "study_methods.hpp"

namespace certcyl::cli {
namespace {

using study::Instance;
using study::Method;
using study::MethodKind;
using study::MethodOutput;
using study::Query;

// The answer and the entry parameter; invalid when an endpoint it reports is not finite (its
// enclosure leaves the doubles), as `certcyl query` answers "invalid".
template <class NT>
MethodOutput from_interval(const LineInterval<NT>& r) {
  MethodOutput m = study::three_valued(r.answer, r.in ? nt::to_double(r.in->t) : std::numeric_limits<double>::quiet_NaN());
  for (const auto* e : {&r.in, &r.out}) {
    if (!*e) continue;
    const auto [lo, hi] = nt::to_interval((*e)->t);
    if (!std::isfinite(lo) || !std::isfinite(hi)) m.invalid = true;
  }
  return m;
}

// Calls f(line_like, solid) with the instance's primitives of the query, built by `make`.
template <class F>
decltype(auto) with_line_primitives(Query q, const std::vector<double>& x, F&& f) {
  using namespace study;
  switch (q) {
    case Query::line_cylinder: return f(line_at(x), cylinder_at(x, 6));
    case Query::ray_cylinder: return f(ray_at(x), cylinder_at(x, 6));
    case Query::segment_cylinder: return f(segment_at(x), cylinder_at(x, 6));
    default: return f(line_at(x), elliptic_at(x, 6));
  }
}

enum class Seed { shene_as_written, shene, gullotti_as_written, gullotti };

template <class NT>
MethodOutput run_seed(Seed seed, Query q, const std::vector<double>& x) {
  return with_line_primitives(q, x, [&](const auto& l, const auto& s) -> MethodOutput {
    const auto ln = to_nt<NT>(l);
    const auto sn = to_nt<NT>(s);
    using Solid = std::decay_t<decltype(sn)>;
    if (seed == Seed::shene || seed == Seed::shene_as_written) {
      const auto v = seed == Seed::shene ? SheneVariant::corrected : SheneVariant::as_written;
      if constexpr (std::is_same_v<Solid, Cylinder<NT>>) return from_interval(shene_line_cylinder(ln, sn, v));
      throw std::logic_error("shene has no elliptic form");
    }
    const auto v = seed == Seed::gullotti_as_written ? GullottiVariant::as_written : GullottiVariant::corrected;
    if constexpr (std::is_same_v<std::decay_t<decltype(ln)>, Line<NT>>) {
      if constexpr (std::is_same_v<Solid, Cylinder<NT>>)
        return from_interval(gullotti_line_cylinder(ln, sn, v));
      else
        return from_interval(gullotti_line_elliptic_cylinder(ln, sn, v));
    } else {
      return from_interval(gullotti_line_elliptic_cylinder(ln, sn, v));
    }
  });
}

// One seed in one number type: dispatch sets the Gmpfr precision and the interval rounding;
// an undecided interval comparison is the answer undecided.
MethodOutput run_seed_in(const NumberTypeSpec& spec, Seed seed, Query q, const std::vector<double>& x) {
  return dispatch(spec, [&]<class NT>() -> MethodOutput {
    if constexpr (NumberTraits<NT>::has_sqrt && NumberTraits<NT>::is_field) {
      try {
        return run_seed<NT>(seed, q, x);
      } catch (const CGAL::Uncertain_conversion_exception&) {
        return study::three_valued(Answer::undecided);
      }
    } else {
      throw std::logic_error("the seeds need a square root");
    }
  });
}

}  // namespace

void register_line_methods(study::Registry& r) {
  const Query lines[] = {Query::line_cylinder, Query::ray_cylinder, Query::segment_cylinder, Query::line_elliptic_cylinder};
  for (Query q : lines) {
    r.push_back({"certified", "exact", MethodKind::certified, q, 1, {}, [q](const std::vector<double>& x) {
                   return with_line_primitives(q, x, [](const auto& l, const auto& s) {
                     const CertifiedLineResult c = certified_line_cylinder(l, s);
                     return study::three_valued(c.answer, c.in ? c.in->nearest : std::numeric_limits<double>::quiet_NaN());
                   });
                 }});
    r.push_back({"robust", "double", MethodKind::robust, q, 1, {}, [q](const std::vector<double>& x) {
                   return with_line_primitives(q, x, [](const auto& l, const auto& s) { return from_interval(robust_line_cylinder(l, s)); });
                 }});
    for (const NumberTypeChoice& c : generic_number_types()) {
      const NumberTypeSpec spec = c.spec;
      if (q != Query::line_elliptic_cylinder) {
        r.push_back({"shene_as_written", spec.name(), MethodKind::seed_as_written, q, c.stride, c.effort,
                     [=](const std::vector<double>& x) { return run_seed_in(spec, Seed::shene_as_written, q, x); }});
        r.push_back({"shene", spec.name(), MethodKind::seed_corrected, q, c.stride, c.effort,
                     [=](const std::vector<double>& x) { return run_seed_in(spec, Seed::shene, q, x); }});
      }
      r.push_back({"gullotti_as_written", spec.name(), MethodKind::seed_as_written, q, c.stride, c.effort,
                   [=](const std::vector<double>& x) { return run_seed_in(spec, Seed::gullotti_as_written, q, x); }});
      r.push_back({"gullotti", spec.name(), MethodKind::seed_corrected, q, c.stride, c.effort,
                   [=](const std::vector<double>& x) { return run_seed_in(spec, Seed::gullotti, q, x); }});
    }
  }
}

}  // namespace certcyl::cli
