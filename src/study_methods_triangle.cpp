// The study's methods for triangle against cylinder: the certified classification and Eberly's
// seed (as written: its boolean) in every generic number type.
#include "certcyl/certified/triangle_cylinder.hpp"
#include "certcyl/seeds/eberly_triangle_cylinder.hpp"
#include "study_methods.hpp"

namespace certcyl::cli {

void register_triangle_methods(study::Registry& r) {
  using study::MethodKind;
  using study::Query;
  r.push_back({"certified", "exact", MethodKind::certified, Query::triangle_cylinder, 1, {}, [](const std::vector<double>& x) {
                 FilterCounter counter;
                 return study::three_valued(classify_triangle_cylinder(study::triangle_at(x), study::cylinder_at(x, 9), counter));
               }});
  for (const NumberTypeChoice& c : generic_number_types()) {
    const NumberTypeSpec spec = c.spec;
    r.push_back({"eberly_triangle", spec.name(), MethodKind::seed_as_written, Query::triangle_cylinder, c.stride, c.effort,
                 [spec](const std::vector<double>& x) {
                   return dispatch(spec, [&]<class NT>() -> study::MethodOutput {
                     if constexpr (NumberTraits<NT>::has_sqrt && NumberTraits<NT>::is_field) {
                       try {
                         const auto res = eberly_triangle_cylinder(to_nt<NT>(study::triangle_at(x)), to_nt<NT>(study::cylinder_at(x, 9)));
                         return study::boolean_answer(res.intersect);
                       } catch (const CGAL::Uncertain_conversion_exception&) {
                         return study::three_valued(Answer::undecided);
                       }
                     } else {
                       throw std::logic_error("the seed needs a square root");
                     }
                   });
                 }});
  }
}

}  // namespace certcyl::cli
