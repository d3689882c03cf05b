// The study's methods for cylinder against cylinder: the certified query as users run it.
// (The Eberly seed's variants and its tolerance sweeps register here as further entries.)
#include "certcyl/certified/cylinder_cylinder.hpp"
#include "study_methods.hpp"

namespace certcyl::cli {

void register_cylinder_methods(study::Registry& r) {
  using study::MethodKind;
  using study::Query;
  r.push_back({"certified", "exact", MethodKind::certified, Query::cylinder_cylinder, 1, true, [](const std::vector<double>& x) {
                 return study::three_valued(certified_cylinder_cylinder(study::cylinder_at(x, 0), study::cylinder_at(x, 7)).answer);
               }});
}

}  // namespace certcyl::cli
