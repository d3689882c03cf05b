// study/contract.hpp -- what a method's positive answer promises, and the certified answer under
// that promise.
//
// The study's certified answer is the SOLID one: the query set (line, ray, segment, triangle,
// cylinder) meets the closed solid cylinder C. A ray-cast API answers a different question, and
// is judged against its own (experiments/STUDY.md, "Contracts"):
//
//   solid          X(I) meets C. Every method of the study but the two below.
//   surface_entry  the ray (or segment) enters C from outside: X(0) is not in C and X(I) meets C.
//                  A ray or segment starting in C (interior or boundary) is a miss.
//                  Bullet's btCollisionWorld::rayTestSingle (measured: no hit from the centre of
//                  a cylinder in any direction, none from a point of the wall in either
//                  direction).
//   surface_hit    X(t) lies on the boundary of C for some t > 0 of the range I: the first
//                  surface point along the ray, an exit counting. A ray starting in the interior
//                  of the bounded C always hits (it exits); a segment starting in the interior
//                  hits iff its end is not in the interior; a ray starting on the boundary hits
//                  iff it meets C at some t > 0. ODE's dCollide of a ray geom (measured: the exit
//                  point from the centre, no contact for a segment inside, no contact for a ray
//                  leaving a point of the wall outward, the far wall for one entering).
// Here X(t) = origin + t d, I = [0, inf) for a ray and [0, 1] for a segment.
//
// All three are exact functions of the certified line result's endpoints
// (certcyl/line_result.hpp): X(I) meets C in [in, out]; in.feature == origin iff t_in = 0, i.e.
// X(0) is in C; an endpoint's surface is none iff the point is interior to C, both decided by
// exact comparisons; so no tolerance enters. Boolean contracts: under a surface contract the
// answer is `separated` for a miss and the solid answer (touching or overlapping) for a hit.
// A contract that is not solid is defined for rays and segments only (the peers' ray casts);
// a line or another query always has the solid contract.
#pragma once

#include <string_view>

#include "certcyl/answer.hpp"
#include "certcyl/certified/line_cylinder.hpp"
#include "study/instance.hpp"
#include "study/methods.hpp"  // Contract

namespace certcyl::study {

// The certified answer of a line query's result under a contract.
inline Answer contract_answer(const CertifiedLineResult& r, Contract c) {
  if (c == Contract::solid || r.answer == Answer::separated || r.answer == Answer::undecided || !r.in || !r.out) return r.answer;
  const bool starts_in_c = r.in->feature == LineFeature::origin;  // t_in = 0 exactly
  switch (c) {
    case Contract::solid: break;
    case Contract::surface_entry:
      // else: the ray starts in C (interior or boundary): nothing is entered.
      return starts_in_c ? Answer::separated : r.answer;
    case Contract::surface_hit: {
      // Starting outside C, the first point of C is a boundary point at t_in > 0.
      if (!starts_in_c) return r.answer;
      // else: the last point of C, t_out, must lie on the boundary at t_out > 0 (every point of
      // X(I) in C before it is then in C too; when the whole chord lies on the boundary, t_out's
      // surface says so).
      const bool hit = r.out->feature != LineFeature::origin && r.out->surface != LineFeature::none;
      return hit ? r.answer : Answer::separated;
    }
  }
  return r.answer;
}

// The certified answer of a certified instance (study/gap.hpp, certify) under a contract.
inline Answer certified_under(const Instance& inst, Contract c) {
  switch (c) {
    case Contract::solid: return inst.certified;
    case Contract::surface_entry: return inst.certified_entry;
    case Contract::surface_hit: return inst.certified_surface_hit;
  }
  return inst.certified;
}

}  // namespace certcyl::study
