// certcyl/certified/cylinder_cylinder.hpp -- certified test-intersection of two solid closed
// circular cylinders: separated, touching or overlapping, each answer with an exact certificate.
//
// Semantics: each cylinder is the closed solid of primitives.hpp (endpoints p0, p1, radius r).
// separated: no common point; touching: common points, none interior to both; overlapping: a
// point interior to both; undecided: no proof within the configured limits (never a guess).
//
// Formulation (design note, section 4; Eberly's equation (6)): with Delta = m1 - m0 the
// difference of the midpoints and
//   phi(D) = |D.A0|/2 + |D.A1|/2 + r0 |D x A0| / |A0| + r1 |D x A1| / |A1|,
// phi* = min { phi(D) : D.Delta = 1 } is < 1, = 1, > 1 for separated, touching, overlapping, and
// 1/phi* is the growth distance (the factor by which both cylinders, scaled about their
// midpoints, just touch). log(phi*) is the signed gap reported with every answer.
//
// Certificates (exact rationals, or binary64 vectors, which are exact rationals too; each proved
// by a rigorous sign computation, never a tolerance; see detail/cylinder_certificates.hpp):
//   separated    direction D with phi(D) < D.Delta (sign of sqrt(p) + sqrt(q) + c by squaring);
//   overlapping  witness point strictly inside both (the polynomial point-in-cylinder test);
//   touching     contact: normal D with phi(D) = D.Delta exactly, and a point in both closed
//                cylinders, with the features that meet (cap, wall, rim; detail/cylinder_touching.hpp).
//
// Every check runs in up to three arithmetics, the first that decides wins (result.certified_by):
// the semi-static double filter (detail/cylinder_static_filter.hpp; binary64 input only, in a
// frame scaled by a power of two), Interval_nt, then Gmpq (a direction's sign there, and in the
// ring frames' Mpzf, first by outward-rounded MPFR bounds). Each decides only what it proves.
//
// Stages, in order; the first that proves an answer decides (result.stage):
//   midpoints        Delta = 0: the common midpoint is interior to both.
//   fast_path        binary64 input first takes the quick path (detail/cylinder_quick_filter.hpp):
//                    the direction Delta (as T = 2 Delta; first by a sufficient test without
//                    division or square root), then the r0:r1 point and the midpoint of the
//                    closest points of the axes inset by half a radius from the caps, each checked
//                    by a static filter whose error bounds are fixed in advance (no copy, no
//                    scaling, no allocation); it decides about nine random pairs in ten in a few
//                    dozen floating-point operations, and leaves the gap enclosure to gap().
//                    Then cheap candidates, evaluated in double: directions Delta, its parts
//                    orthogonal to each axis, A0 x A1, the difference of the closest points of the axis
//                    segments, A0, A1; points: the closest points' r0:r1 division point and
//                    midpoint, m0, m1, the closest point on axis 0; when none of them is interior
//                    and no direction separates, up to 12 rounds of alternating projections onto
//                    the two cylinders shrunk about their midpoints. By default Delta is tried
//                    first by the static filter alone, then the points, then the directions, the
//                    first promising one of each checked; with options.refine_gap all are ranked
//                    and the best direction, then the best point, is checked.
//   optimiser        smoothed Newton in double on the plane D.Delta = 1 (detail/cylinder_optimiser.hpp),
//                    giving a direction and a dual point, checked likewise.
//   refine           Newton's method on the optimality conditions of min sigma(X), in double
//                    then double-double (QD's dd_real), from the optimiser's point, with the
//                    active caps, walls and rims read off the gauges
//                    (detail/cylinder_active_set.hpp); where it stalls, the optimiser's
//                    smoothing path in double-double. A point and a direction accurate to about
//                    2^-100, checked exactly in Mpzf, in the ring frame of
//                    detail/cylinder_ring_frame.hpp (the input times a power of two for binary64
//                    input, times the lcm of its denominators for other rational input; Gmpq
//                    when that lcm is too large); it
//                    decides pairs 2^-50 .. 2^-95 from touching, and its direction leads the
//                    touching candidates.
//   touching_exact   rational candidate normals (A0, A1, A0 x A1, the parts of Delta orthogonal to
//                    the axes, the exact rim-wall and rim-rim normals of
//                    detail/cylinder_rim_contacts.hpp, a small-height rational reconstruction of
//                    the optimiser's direction), each proved or rejected exactly: an interval
//                    pre-filter, then prove_touching_ring in Mpzf in the ring frame (Gmpq's
//                    prove_touching when there is no ring frame: rational input whose
//                    denominators' lcm exceeds 4,096 bits).
//   gmpfr            exact candidates first (directions: T, its parts orthogonal to the axes, the
//                    axes, their cross product and each one's part orthogonal to the other;
//                    witnesses: the midpoints, the closest points of the axes, points of an
//                    end disc of one cylinder whose end lies in the other, an end's step along
//                    its axis sized from its depth in the other,
//                    points of one tube beside its axis's closest point, points of the line
//                    where the slabs' mid-planes meet, and points of a cap disk inside the other
//                    pushed into the cylinder, among them the rim points nearest the other's
//                    axis line (detail/cylinder_rim_nearest.hpp); each checked exactly, in the
//                    ring frame when there is one), then the corner
//                    candidates of detail/cylinder_corner_plane.hpp (the best direction of one
//                    cylinder's rim wedge in the plane through its axis and the other, and the
//                    other's deepest point in it, on quantities reduced exactly to the smaller
//                    cylinder's scale: they decide a huge against a tiny cylinder without
//                    precision to match their span; for input spanning over 256 binades they
//                    run before the touching stage, with short ellipsoid runs; up to 4,096 bits,
//                    and a plane left short of bits goes on in each round below, at up to
//                    max(64 times the ellipsoid's precision, twice the bit size of the largest
//                    input number)), then the optimiser at
//                    doubling precisions up to options.max_precision (by default set from the
//                    input's span in bits); its direction
//                    and point, converted exactly to rationals, are checked in Gmpq, and its
//                    direction is reconstructed as a candidate normal for a touching proof.
//   ellipsoid        the complete stage (detail/cylinder_ellipsoid.hpp): the central-cut ellipsoid
//                    method on the open convex sets of interior points and of separating
//                    directions, with exact rational cuts (a violated constraint's gradient; a
//                    rational linear minorant of phi), each centre checked exactly, at 128, 256,
//                    ... bits, each precision in a fast floating-point run and in the rounded run
//                    of Grotschel, Lovasz and Schrijver, which provably reaches a certificate once
//                    the precision is high enough. With the touching stage complete for touching
//                    pairs, the query decides every valid input (the completeness theorem of the
//                    paper). How high: with the fourteen input numbers scaled to integers of
//                    absolute value at most M, a pair that does not touch has
//                    |phi* - 1| >= 2^-14337 M^-4096 (the paper's Theorem "gap", from the bound of
//                    Jeronimo, Perrucci and Tsigaridas on the minimum of a polynomial on a compact
//                    semialgebraic set), so every precision p >= 2^21 (3 + log2 M) decides it
//                    (Theorem "precision"): linear in the input's bit size, and astronomically
//                    pessimistic (about 4.4e9 bits for binary64 input of full range; the precisions
//                    the stage reaches are reported per answer in ellipsoid_precision). Only a
//                    caller's max_precision, time_limit_seconds, stop or prove_touching = false leaves
//                    it bounded, and the answer undecided when no proof was found within it.
// Undecided results carry the certified bounds gap().phi_lower <= phi* <= gap().phi_upper, so
// |phi* - 1| <= gap().distance_bound().
//
// Touching is proved for every contact type: with rational data every touching pair touches with
// a rational normal at a rational point (the theorem of detail/cylinder_rim_contacts.hpp), and
// the touching_exact stage computes the candidates of every type exactly (cap-cap, cap-wall,
// wall-wall, rim-cap from the axes; rim-wall and rim-rim from exact rational roots).
//
// Preconditions: valid cylinders (validate(): radius > 0, p0 != p1); the double overload also
// needs finite values, and treats every double as the exact rational it denotes.
#pragma once

#include <CGAL/Gmpfr.h>
#include <CGAL/Mpzf.h>

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string_view>
#include <utility>
#include <variant>

#include "certcyl/answer.hpp"
#include "certcyl/certified/detail/cylinder_active_set.hpp"
#include "certcyl/certified/detail/cylinder_cap_disk.hpp"
#include "certcyl/certified/detail/cylinder_certificates.hpp"
#include "certcyl/certified/detail/cylinder_corner_plane.hpp"
#include "certcyl/certified/detail/cylinder_ellipsoid.hpp"
#include "certcyl/certified/detail/cylinder_optimiser.hpp"
#include "certcyl/certified/detail/cylinder_quick_filter.hpp"
#include "certcyl/certified/detail/cylinder_rim_nearest.hpp"
#include "certcyl/certified/detail/cylinder_ring_frame.hpp"
#include "certcyl/certified/detail/cylinder_static_filter.hpp"
#include "certcyl/certified/detail/cylinder_touching.hpp"
#include "certcyl/errors.hpp"
#include "certcyl/primitives.hpp"

namespace certcyl {

enum class CylinderStage { midpoints, fast_path, optimiser, refine, touching_exact, gmpfr, ellipsoid, none };
inline constexpr std::size_t kCylinderStages = 7;  // stages that can decide (none excluded)

inline constexpr std::string_view to_string(CylinderStage s) {
  switch (s) {
    case CylinderStage::midpoints: return "midpoints";
    case CylinderStage::fast_path: return "fast_path";
    case CylinderStage::optimiser: return "optimiser";
    case CylinderStage::refine: return "refine";
    case CylinderStage::touching_exact: return "touching_exact";
    case CylinderStage::gmpfr: return "gmpfr";
    case CylinderStage::ellipsoid: return "ellipsoid";
    case CylinderStage::none: return "none";
  }
  return "none";
}

// The arithmetic of the check that proved the answer: the semi-static double filter
// (detail/cylinder_static_filter.hpp), Interval_nt, or Gmpq.
enum class CylinderArithmetic { static_filter, interval, exact, none };

inline constexpr std::string_view to_string(CylinderArithmetic a) {
  switch (a) {
    case CylinderArithmetic::static_filter: return "static";
    case CylinderArithmetic::interval: return "interval";
    case CylinderArithmetic::exact: return "exact";
    case CylinderArithmetic::none: return "none";
  }
  return "none";
}

// When the certified enclosure of phi* (CylinderCylinderResult::gap()) is computed.
//   off        never: gap().known is false.
//   on_access  the stages after the quick path record it as they go (it costs them little); an
//              answer of the quick path keeps its binary64 input instead, and gap() computes the
//              enclosure from it on each call (about the cost of the quick path again), so a
//              query whose enclosure is not read does not pay for it.
//   in_query   the quick path computes it too, during the query: cheaper than on_access when the
//              enclosure is always read, dearer when it is not.
enum class GapEnclosure { off, on_access, in_query };

struct CylinderCylinderOptions {
  // The resource limit of the arbitrary-precision stages, in bits. 0 (the default): none, and
  // the query decides every valid input. The Gmpfr stage (a heuristic) then runs at doubling
  // precisions from 128 bits, or from the first power of two above the number of binades s the
  // geometry spans (from the smallest radius or coordinate of an axis or of T to the largest
  // input number; the digits of a rational do not count), up to 4 s + 1024 bits, a measured
  // choice; the ellipsoid stage after it runs at 128, 256, ... bits until it proves an answer,
  // which it provably does for every pair that does not touch (detail/cylinder_ellipsoid.hpp;
  // touching pairs are decided before it). A positive value stops both stages above that
  // precision, and a negative value skips both: the answer may then be undecided, the only way
  // it can be.
  long max_precision = 0;
  // A resource limit on the query's time, in seconds. 0 (the default): none. Positive: once that
  // much wall time has passed, the query stops at its next check and answers undecided, with
  // time_limit_reached set. The checks come before each stage after the optimiser, before each
  // group of exact candidates (the witnesses beside the ends, each cylinder's cap-disk points),
  // corner plane, Newton step of a Gmpfr round and ellipsoid step; a check never interrupts an
  // exact evaluation or one such step, so the query can overrun the limit by the longest of
  // these (on input of thousands of digits, a second or more). A limit above 10^9 s is taken as
  // 10^9 s, and NaN as none. The study and the command's default never set it.
  double time_limit_seconds = 0;
  // A caller's request to stop (a resource the caller tracks, such as memory): null (the default)
  // or a function the query calls with stop_context at each check of the time limit; once it
  // returns true, the query stops there as when the time limit runs out and answers undecided,
  // with stopped set. The same checks, so the same overrun.
  bool (*stop)(void* context) = nullptr;
  void* stop_context = nullptr;
  // Try the exact touching proofs (stages touching_exact and the reconstruction in gmpfr).
  bool prove_touching = true;
  // Run the refine stage (Newton's method in double-double on the optimality conditions). Off,
  // near-touching pairs go to the Gmpfr stage; the switch exists to measure the stage.
  bool refine = true;
  // The certified enclosure of phi* (GapEnclosure), from the candidates the deciding stage
  // evaluates: on the fast path, the direction Delta and the segment between the midpoints
  // (exact for two balls), or the witness point; its width varies with the pair.
  GapEnclosure gap_enclosure = GapEnclosure::on_access;
  // Rank every cheap candidate of the fast path (seven directions, five points) and certify the
  // best, for a tighter enclosure computed in the query (the quick path is skipped); 5 to 17 times
  // the quick path's median time on random pairs (bench/RESULTS.md). Only when gap_enclosure is
  // not off.
  bool refine_gap = false;
  // Also fill the Rational certificate fields (direction, witness) when the certificate is a
  // binary64 vector. Off: it is given only in direction_binary64 / witness_binary64 (the same
  // exact numbers, without the Gmpq allocations); exact_direction() and exact_witness() give
  // either as rationals. Certificates that are not binary64 vectors are always Rational.
  bool rational_certificates = false;
  // Measure the time spent in each stage (stage_seconds): one clock reading per stage boundary.
  bool time_stages = false;
};

struct CylinderCylinderCounters {
  std::uint32_t directions_checked = 0;   // candidate directions given to the certified check
  std::uint32_t points_checked = 0;       // candidate points given to the certified check
  std::uint32_t static_decisions = 0;     // checks the static filter decided
  std::uint32_t interval_decisions = 0;   // checks left by the filter that intervals decided
  std::uint32_t exact_checks = 0;         // checks decided in Gmpq
  std::uint32_t newton_steps = 0;         // optimiser steps, all precisions
  std::uint32_t touching_candidates = 0;  // candidate normals given to the touching proof
  std::uint32_t ellipsoid_steps = 0;      // steps of the ellipsoid stage's runs
};

// A certified enclosure phi_lower <= phi* <= phi_upper, and so of the signed gap log(phi*).
struct CylinderGap {
  // False when Delta = 0 (phi* is undefined: the cylinders overlap at every scale), when
  // options.gap_enclosure is GapEnclosure::off, or when no finite bound was found (input whose
  // binary64 range exceeds what the scaled frame can hold exactly, so intervals overflow or
  // underflow); the numbers are then meaningless.
  bool known = false;
  double phi_lower = 0, phi_upper = 0;

  // The enclosure of log(phi*): std::log is within one ulp; two steps outward make it safe.
  double log_lower() const {
    return phi_lower == 1 ? 0 : std::nextafter(std::nextafter(std::log(phi_lower), -HUGE_VAL), -HUGE_VAL);
  }
  double log_upper() const {
    return phi_upper == 1 ? 0 : std::nextafter(std::nextafter(std::log(phi_upper), HUGE_VAL), HUGE_VAL);
  }
  // A certified bound on |phi* - 1|.
  double distance_bound() const { return std::max(phi_upper - 1, 1 - phi_lower); }
};

struct CylinderCylinderResult;
namespace detail {
class CylinderCylinderSolver;
inline bool quick_answer(const Cylinder<double>& c0, const Cylinder<double>& c1, const CylinderCylinderOptions& options,
                         CylinderCylinderResult& r);
}  // namespace detail

struct CylinderCylinderResult {
  // User-provided, so that the members are initialised one by one: GCC clears a whole object
  // of this size with `rep stos`, which costs about as much as the quick path itself.
  CylinderCylinderResult() noexcept {}

  Answer answer = Answer::undecided;
  CylinderStage stage = CylinderStage::none;
  CylinderArithmetic certified_by = CylinderArithmetic::none;

  // separated: phi(D) < D.Delta. touching: the contact normal. Exact.
  std::optional<Vec3<Rational>> direction;
  // overlapping: a point interior to both. touching: a common point. Exact.
  std::optional<Point3<Rational>> witness;
  // The same certificates when they are binary64 vectors (each double is the exact rational it
  // denotes): always set in that case, whatever options.rational_certificates says.
  std::optional<Vec3<double>> direction_binary64;
  std::optional<Point3<double>> witness_binary64;
  // touching only: the features that meet, the normal and a common point.
  std::optional<CylinderContact> contact;

  // The certified enclosure of phi* and log(phi*) (CylinderGap). For an answer of the quick path
  // with GapEnclosure::on_access it is computed here, on each call, from the input the answer
  // keeps (about the cost of the quick path again: keep the value); otherwise it was recorded by
  // the query.
  CylinderGap gap() const;

  // The highest precision of the Gmpfr stage's rounds, 0 if none ran. The candidates' own Gmpfr
  // evaluations (corner planes, rim points, axis witnesses) are not counted.
  long gmpfr_precision = 0;
  long ellipsoid_precision = 0;  // highest precision of the ellipsoid stage, 0 if it did not run
  bool time_limit_reached = false;  // undecided because options.time_limit_seconds ran out (false when decided)
  bool stopped = false;             // undecided because options.stop asked to stop (false when decided)
  CylinderCylinderCounters counters;
  std::array<double, kCylinderStages> stage_seconds{};  // indexed by CylinderStage; zero unless time_stages

  // The certificates as exact rationals, whichever field holds them.
  std::optional<Vec3<Rational>> exact_direction() const {
    if (direction) return direction;
    if (direction_binary64) return direction_binary64->map([](double x) { return Rational(x); });
    return std::nullopt;
  }
  std::optional<Point3<Rational>> exact_witness() const {
    if (witness) return witness;
    if (witness_binary64) return witness_binary64->map([](double x) { return Rational(x); });
    return std::nullopt;
  }

 private:
  friend class detail::CylinderCylinderSolver;
  friend bool detail::quick_answer(const Cylinder<double>&, const Cylinder<double>&, const CylinderCylinderOptions&,
                                   CylinderCylinderResult&);
  CylinderGap gap_;  // recorded by the query
  // An answer of the quick path with GapEnclosure::on_access: its binary64 input, for gap().
  bool quick_gap_ = false;
  std::array<Cylinder<double>, 2> quick_input_{};
};

namespace detail {


// Closest points of the segments [a0, a0 + e0] and [a1, a1 + e1] (double; candidates only), or,
// with insets i0, i1 in [0, 1/2], of the parts [a0 + i0 e0, a0 + (1 - i0) e0] and likewise.
inline std::pair<Point3<double>, Point3<double>> closest_segment_points(const Point3<double>& a0, const Vec3<double>& e0,
                                                                         const Point3<double>& a1, const Vec3<double>& e1,
                                                                         double i0 = 0, double i1 = 0) {
  const Vec3<double> w = a0 - a1;
  const double a = dot(e0, e0), b = dot(e0, e1), c = dot(e1, e1), d = dot(e0, w), e = dot(e1, w);
  const double den = a * c - b * b;
  double s;
  if (den > 1e-12 * a * c) {
    s = std::clamp((b * e - c * d) / den, i0, 1 - i0);
  } else {
    // else: (nearly) parallel axes; the middle of the overlap of their parameter ranges on
    // segment 0 keeps the candidate away from the caps.
    double t0 = -d / a, t1 = (b - d) / a;
    if (t1 < t0) std::swap(t0, t1);
    s = std::clamp(0.5 * (std::max(t0, 0.0) + std::min(t1, 1.0)), i0, 1 - i0);
  }
  const double t = std::clamp((b * s + e) / c, i1, 1 - i1);
  s = std::clamp((b * t - d) / a, i0, 1 - i0);
  return {a0 + s * e0, a1 + t * e1};
}

// The lower bound 1 / sigma of phi* from an upper bound sigma_upper of a point's scale sigma
// (1 / phi* is the least scale), rounded down: fl(rho' fl(1 / s)) <= rho' (1 + u)^2 / s <= 1 / s.
// 0 (no bound) unless sigma_upper is positive and finite.
inline double phi_lower_from_sigma(double sigma_upper) {
  if (!(sigma_upper > 0) || !std::isfinite(sigma_upper)) return 0;
  return kStaticRoundDown * (1 / sigma_upper);
}

// The span in binades of an exact pair (CylinderCylinderOptions::max_precision): from the
// smallest nonzero magnitude among the radii and the coordinates of A0, A1 and T (the sizes the
// geometry works at) to the largest coordinate or radius (what a rounded Gmpfr input loses its
// bits against). The digits of a rational do not count: the Gmpfr rounds only produce
// candidates, and every check is exact. NT is Rational or, for a dyadic pair, Mpzf: the same
// number for the pair in either type, and for the pair times any power of two (the binades of
// dyadic numbers are exact, and the scaling moves them all alike).
template <class NT>
long cylinder_pair_span_bits(const CylinderPair<NT>& e) {
  long hi = std::numeric_limits<long>::min(), lo = std::numeric_limits<long>::max();
  for (const Cylinder<NT>* c : {&e.c0, &e.c1})
    for (const NT* q : {&c->p0.x, &c->p0.y, &c->p0.z, &c->p1.x, &c->p1.y, &c->p1.z, &c->radius})
      if (CGAL::sign(*q) != CGAL::ZERO) hi = std::max(hi, binade(*q));
  for (const NT* q : {&e.c0.radius, &e.c1.radius, &e.A0.x, &e.A0.y, &e.A0.z, &e.A1.x, &e.A1.y, &e.A1.z, &e.T.x, &e.T.y, &e.T.z})
    if (CGAL::sign(*q) != CGAL::ZERO) lo = std::min(lo, binade(*q));
  return std::max(0L, hi - lo + 2);
}

// The bit size of the largest input number (numerator and denominator together).
inline long cylinder_pair_number_bits(const CylinderPair<Rational>& e) {
  long bits = 0;
  for (const Cylinder<Rational>* c : {&e.c0, &e.c1})
    for (const Rational* q : {&c->p0.x, &c->p0.y, &c->p0.z, &c->p1.x, &c->p1.y, &c->p1.z, &c->radius})
      bits = std::max(bits, static_cast<long>(mpz_sizeinbase(mpq_numref(q->mpq()), 2) + mpz_sizeinbase(mpq_denref(q->mpq()), 2)));
  return bits;
}

// Frames. Binary64 input (the double overload, or Rational input whose every number is a
// binary64 value) is moved to the "world" frame, multiplied by 2^k so that its largest
// magnitude lies in [1, 2) (exact, checked; k = 0 when the scaling would not be exact). All
// double and interval work happens there: it is what the static filter needs, and it keeps the
// intervals far from overflow and underflow for any input magnitude. Directions are the same
// in both frames; points are divided by 2^k on the way out. Other Rational input is scaled the
// same way from its nearest doubles, which are then only candidates (its intervals enclose the
// scaled input), and the filter is off.
class CylinderCylinderSolver {
 public:
  CylinderCylinderSolver(const Cylinder<Rational>& c0, const Cylinder<Rational>& c1, const CylinderCylinderOptions& options)
      : options_(options), input_{&c0, &c1} {
    bool binary64 = true;
    const auto to_d = [&binary64](const Rational& q) {
      double d;
      if (exact_double(q, d)) return d;
      binary64 = false;
      return round_to_nearest<double>(q);
    };
    const Cylinder<double> d0 = c0.map(to_d), d1 = c1.map(to_d);
    if (binary64) {
      make_world(d0, d1);
    } else {
      // The nearest doubles, scaled like a world frame (candidates only; the filter is off).
      const double s = power_of_two_normaliser(std::max(largest_magnitude(d0), largest_magnitude(d1)));
      if (s != 0) {
        world_scale_ = s;
        world_exponent_ = static_cast<int>((std::bit_cast<std::uint64_t>(s) >> 52) & 0x7ff) - 1023;
      }
      const auto scaled = [this](double x) { return x * world_scale_; };
      dbl_ = CylinderPair<double>::make(d0.map(scaled), d1.map(scaled));
    }
  }

  // Every double is exact: the rational input is built only if an exact stage needs it.
  CylinderCylinderSolver(const Cylinder<double>& c0, const Cylinder<double>& c1, const CylinderCylinderOptions& options)
      : options_(options), double_input_{c0, c1} {
    make_world(c0, c1);
  }

  CylinderCylinderResult run() {
    if (options_.time_limit_seconds > 0) {  // (NaN is no limit; at most 10^9 s, so that the clock's count cannot overflow)
      const double limit = std::min(options_.time_limit_seconds, 1e9);
      deadline_ = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(limit));
    }
    if (midpoints()) return finish();
    if (fast_path()) return finish();
    if (optimiser()) return finish();
    if (options_.refine && !out_of_time() && refine()) return finish();
    if (options_.prove_touching && !out_of_time() && ellipsoid_probe()) return finish();
    if (options_.prove_touching && !touching_tried_ && !out_of_time() && touching_exact()) return finish();
    if (!out_of_time() && arbitrary_precision()) return finish();
    result_.stage = CylinderStage::none;
    return finish();
  }

 private:
  using Clock = std::chrono::steady_clock;

  // The caller's time limit (options.time_limit_seconds) has run out, or its stop predicate
  // (options.stop) asked to stop; once true, always true.
  bool out_of_time() {
    if (result_.time_limit_reached || result_.stopped) return true;
    if (options_.stop && options_.stop(options_.stop_context)) return result_.stopped = true;
    if (!deadline_) return false;
    return result_.time_limit_reached = Clock::now() >= *deadline_;
  }

  // ---- frames -----------------------------------------------------------------------------------
  static double largest_magnitude(const Cylinder<double>& c) {
    return std::max({std::abs(c.p0.x), std::abs(c.p0.y), std::abs(c.p0.z), std::abs(c.p1.x), std::abs(c.p1.y), std::abs(c.p1.z),
                     std::abs(c.radius)});
  }

  void make_world(const Cylinder<double>& c0, const Cylinder<double>& c1) {
    binary64_ = true;
    const double s = power_of_two_normaliser(std::max(largest_magnitude(c0), largest_magnitude(c1)));
    // x s is exact when it is zero or a normal number (s is a power of two, |x s| < 2).
    bool exact = s != 0;
    const auto scaled = [&exact, s](double x) {
      const double y = x * s;
      exact = exact && (x == 0 || std::abs(y) >= std::numeric_limits<double>::min());
      return y;
    };
    Cylinder<double> w0 = c0.map(scaled), w1 = c1.map(scaled);
    if (exact) {
      world_exponent_ = static_cast<int>((std::bit_cast<std::uint64_t>(s) >> 52) & 0x7ff) - 1023;
      world_scale_ = s;
      stat_ = StaticPair::make(w0, w1);
      world_exact_ = true;
      static_ok_ = stat_.usable;
      // The filter's values are CylinderPair<double>::make's, operation for operation.
      const auto value = [](const Vec3<Bounded>& v) { return Vec3<double>{v.x.v, v.y.v, v.z.v}; };
      dbl_ = {w0, w1, value(stat_.A0), value(stat_.A1), value(stat_.T), stat_.AA0.v, stat_.AA1.v};
    } else {
      dbl_ = CylinderPair<double>::make(c0, c1);
    }
  }

  // Intervals of the world input, built when first needed.
  const CylinderPair<Interval>& iv() {
    if (!iv_) {
      CGAL::Protect_FPU_rounding<true> upward;
      if (binary64_) {
        const auto to_i = [](double x) { return Interval(x); };
        iv_ = CylinderPair<Interval>::make(dbl_.c0.map(to_i), dbl_.c1.map(to_i));
      } else {
        const Interval s(world_scale_);
        const auto to_i = [&s](const Rational& q) { return enclose_interval(q) * s; };
        iv_ = CylinderPair<Interval>::make(input_[0]->map(to_i), input_[1]->map(to_i));
      }
    }
    return *iv_;
  }

  const Cylinder<Rational>& exact_cylinder(int i) {
    if (!input_[0]) {
      const auto to_q = [](double x) { return Rational(x); };
      converted_input_[0] = double_input_[0]->map(to_q);
      converted_input_[1] = double_input_[1]->map(to_q);
      input_ = {&*converted_input_[0], &*converted_input_[1]};
    }
    return *input_[i];
  }

  const CylinderPair<Rational>& exact() {
    if (!ex_) ex_ = CylinderPair<Rational>::make(exact_cylinder(0), exact_cylinder(1));
    return *ex_;
  }

  // A world point in the input frame, exactly.
  Point3<Rational> to_input_frame(const Point3<double>& X) const {
    return X.map([this](double x) { return times_two_power(Rational(x), -world_exponent_); });
  }

  bool gap_on() const { return options_.gap_enclosure != GapEnclosure::off; }

  // ---- stage bookkeeping ----------------------------------------------------------------------
  // One clock reading per stage boundary (when timing is on): a stage starts when the previous
  // one ends.
  void begin(CylinderStage s) {
    stage_ = s;
    if (options_.time_stages && !started_) start_ = Clock::now(), started_ = true;
  }
  void end() {
    if (!options_.time_stages) return;
    const Clock::time_point now = Clock::now();
    result_.stage_seconds[static_cast<std::size_t>(stage_)] += std::chrono::duration<double>(now - start_).count();
    start_ = now;
  }
  bool decide(Answer a) {
    end();
    result_.answer = a;
    result_.stage = stage_;
    result_.certified_by = last_check_;
    return true;
  }
  bool pass() {
    end();
    return false;
  }

  CylinderCylinderResult finish() {
    if (result_.answer != Answer::undecided) result_.time_limit_reached = result_.stopped = false;  // a candidate past a check decided
    if (result_.answer == Answer::touching) {
      result_.gap_ = {true, 1, 1};
    } else if (gap_on() && !coincident_ && phi_upper_ && phi_lower_ > 0) {
      result_.gap_ = {true, phi_lower_, *phi_upper_};
    }
    return std::move(result_);
  }

  // ---- certified checks: static filter, then intervals, then Gmpq ------------------------------
  // Candidates computed in double may be non-finite (overflow, 0/0 in degenerate input).
  static bool finite(const Vec3<double>& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

  // Sign of |D.T| - phi2(D) for a world direction D. With the filter on, D is first scaled by a
  // power of two to |D_i| < 2 (the scaled D is the certificate; the sign does not change) and
  // its filter values are left in *terms for the gap bound.
  // With exact = false, a check the filter and the intervals leave open answers ZERO (proves
  // nothing) instead of going on to Gmpq.
  CGAL::Sign check_direction(Vec3<double>& D, std::optional<StaticDirection>* terms = nullptr, bool exact_allowed = true) {
    if (!finite(D)) return CGAL::ZERO;  // not a candidate: proves nothing
    ++result_.counters.directions_checked;
    if (static_ok_) {
      const double s = power_of_two_normaliser(std::max({std::abs(D.x), std::abs(D.y), std::abs(D.z)}));
      if (s != 0) {
        D = s * D;
        const StaticDirection t = static_direction(stat_, D);
        if (terms) *terms = t;
        const StaticSign g = static_separation_sign(t);
        if (g != StaticSign::unknown) {
          ++result_.counters.static_decisions;
          last_check_ = CylinderArithmetic::static_filter;
          return g == StaticSign::positive ? CGAL::POSITIVE : CGAL::NEGATIVE;
        }
      }
    }
    const auto s = interval_attempt([&] { return separation_sign(iv(), to_iv(D)); });
    if (s) {
      ++result_.counters.interval_decisions;
      last_check_ = CylinderArithmetic::interval;
      return *s;
    }
    if (!exact_allowed) return CGAL::ZERO;
    ++result_.counters.exact_checks;
    last_check_ = CylinderArithmetic::exact;
    if (const RingFrame* f = world_ring())  // a direction is the same in the world frame
      return separation_sign(f->pair, D.map([](double x) { return CGAL::Mpzf(x); }));
    return separation_sign(exact(), D.map([](double x) { return Rational(x); }));
  }

  // Whether the world point X is strictly inside both cylinders.
  bool check_point(const Point3<double>& X, std::optional<StaticPoint>* values = nullptr, bool exact_allowed = true) {
    if (!finite(X)) return false;  // not a candidate
    ++result_.counters.points_checked;
    if (static_ok_) {
      const StaticPoint p = static_point(stat_, X);
      if (values) *values = p;
      const StaticSign g = static_inside_both(p);
      if (g != StaticSign::unknown) {
        ++result_.counters.static_decisions;
        last_check_ = CylinderArithmetic::static_filter;
        return g == StaticSign::positive;
      }
    }
    const auto s = interval_attempt([&] { return strictly_inside_both(iv(), to_iv(X)); });
    if (s) {
      ++result_.counters.interval_decisions;
      last_check_ = CylinderArithmetic::interval;
      return *s;
    }
    if (!exact_allowed) return false;
    ++result_.counters.exact_checks;
    last_check_ = CylinderArithmetic::exact;
    if (const RingFrame* f = world_ring()) return strictly_inside_both(f->pair, X.map([](double x) { return CGAL::Mpzf(x); }));
    return strictly_inside_both(exact(), to_input_frame(X));
  }

  // ---- certified bounds on phi* ------------------------------------------------------------------
  // A bound that overflowed (or is NaN) says nothing: it is dropped, so that a known enclosure
  // is finite (CylinderGap::known).
  void lower_phi_upper(double u) {
    if (!(u < HUGE_VAL)) return;
    if (!phi_upper_ || u < *phi_upper_) phi_upper_ = u;
  }
  void raise_phi_lower(double sigma_upper) {
    const double lower = phi_lower_from_sigma(sigma_upper);
    if (lower > phi_lower_) phi_lower_ = lower;
  }

  void bound_by_direction(Vec3<double> D, const StaticDirection* terms = nullptr) {
    if (!gap_on() || !finite(D)) return;
    if (static_ok_) {
      if (terms) return lower_phi_upper(static_ratio_upper(*terms));
      const double s = power_of_two_normaliser(std::max({std::abs(D.x), std::abs(D.y), std::abs(D.z)}));
      if (s != 0) return lower_phi_upper(static_ratio_upper(static_direction(stat_, s * D)));
    }
    bound_by_direction(to_iv(D));
  }
  void bound_by_direction(const Vec3<Interval>& D) {
    if (!gap_on()) return;
    const CylinderPair<Interval>& d = iv();
    CGAL::Protect_FPU_rounding<true> upward;
    const std::optional<Interval> r = ratio_enclosure(d, D);
    if (r) lower_phi_upper(r->sup());
  }

  void bound_by_point(const Point3<double>& X, const StaticPoint* values = nullptr) {
    if (!gap_on() || !finite(X)) return;
    if (static_ok_) return raise_phi_lower(static_sigma_upper(stat_, values ? *values : static_point(stat_, X)));
    bound_by_point(to_iv(X));
  }
  // X: world frame.
  void bound_by_point(const Point3<Interval>& X) {
    if (!gap_on()) return;
    const CylinderPair<Interval>& d = iv();
    CGAL::Protect_FPU_rounding<true> upward;
    const Interval s = scale_enclosure(d, X);
    if (!(s.sup() > 0) || !std::isfinite(s.sup())) return;
    const double lower = (Interval(1) / Interval(s.sup())).inf();
    if (lower > phi_lower_) phi_lower_ = lower;
  }
  // The segment between the midpoints (static_segment_phi_lower); needs the filter.
  void bound_by_segment() {
    if (!gap_on() || !static_ok_) return;
    const double lower = static_segment_phi_lower(stat_);
    if (lower > phi_lower_) phi_lower_ = lower;
  }
  // An input-frame rational point in world intervals.
  Point3<Interval> world_iv(const Point3<Rational>& X) const {
    CGAL::Protect_FPU_rounding<true> upward;
    const Interval s(world_scale_);
    return X.map([&s](const Rational& x) { return enclose_interval(x) * s; });
  }
  static Vec3<Interval> to_iv(const Vec3<double>& v) {
    return v.map([](double x) { return Interval(x); });
  }
  static Vec3<Interval> to_iv(const Vec3<Rational>& v) {
    return v.map([](const Rational& x) { return enclose_interval(x); });
  }

  // ---- the answers ------------------------------------------------------------------------------
  bool separated_by(const Vec3<double>& D) {
    result_.direction_binary64 = D;
    if (options_.rational_certificates) result_.direction = D.map([](double x) { return Rational(x); });
    return decide(Answer::separated);
  }
  bool separated_by(Vec3<Rational> D) {
    result_.direction = std::move(D);
    return decide(Answer::separated);
  }
  // X: world frame.
  bool overlapping_at(const Point3<double>& X) {
    // X / 2^k is exact when each coordinate is zero or normal.
    const double inverse = 1 / world_scale_;
    bool exact = true;
    const Point3<double> Y = X.map([&](double x) {
      const double y = x * inverse;
      exact = exact && (x == 0 || std::abs(y) >= std::numeric_limits<double>::min());
      return y;
    });
    if (exact) {
      result_.witness_binary64 = Y;
      if (options_.rational_certificates) result_.witness = Y.map([](double x) { return Rational(x); });
    } else {
      result_.witness = to_input_frame(X);
    }
    return decide(Answer::overlapping);
  }
  bool overlapping_at(Point3<Rational> X) {
    result_.witness = std::move(X);
    return decide(Answer::overlapping);
  }
  bool touching_with(CylinderContact c) {
    result_.direction = c.normal;
    result_.witness = c.point;
    result_.contact = std::move(c);
    last_check_ = CylinderArithmetic::exact;
    return decide(Answer::touching);
  }

  // ---- stage midpoints ----------------------------------------------------------------------------
  bool midpoints() {
    begin(CylinderStage::midpoints);
    if (world_exact_) {
      // T = 0 exactly? The filter proves T != 0 in nearly every case.
      for (std::size_t i = 0; i < 3; ++i)
        if (static_sign(stat_.T[i]) != StaticSign::unknown) return pass();
    }
    const auto zero = interval_attempt([&] {
      const CylinderPair<Interval>& d = iv();
      return sign_is(d.T.x, CGAL::ZERO) && sign_is(d.T.y, CGAL::ZERO) && sign_is(d.T.z, CGAL::ZERO);
    });
    bool coincident = zero ? *zero : false;
    if (!zero) {
      ++result_.counters.exact_checks;
      const Vec3<Rational>& T = exact().T;
      coincident = T.x == 0 && T.y == 0 && T.z == 0;
    }
    if (!coincident) return pass();
    coincident_ = true;
    // The common midpoint m0 is interior to both (radius > 0, p0 != p1); checked all the same.
    const Cylinder<Rational>& c0 = exact_cylinder(0);
    Point3<Rational> m = (c0.p0 + c0.p1) / Rational(2);
    ++result_.counters.points_checked;
    ++result_.counters.exact_checks;
    last_check_ = CylinderArithmetic::exact;
    if (!strictly_inside_both(exact(), m)) return pass();
    return overlapping_at(std::move(m));
  }

  // ---- stage fast_path ------------------------------------------------------------------------------
  // phi2(D) / |D.T| with k_i = 4 r_i^2 / A_i.A_i precomputed (double; ranking only).
  double ratio_double(const Vec3<double>& D, double k0, double k1) const {
    const double dt = std::abs(dot(D, dbl_.T));
    if (!(dt > 0)) return std::numeric_limits<double>::infinity();
    const double phi2 = std::abs(dot(D, dbl_.A0)) + std::abs(dot(D, dbl_.A1)) + std::sqrt(k0 * squared_norm(cross(D, dbl_.A0))) +
                        std::sqrt(k1 * squared_norm(cross(D, dbl_.A1)));
    return phi2 / dt;
  }

  double scale_double(const Point3<double>& X) const {
    auto one = [&](const Cylinder<double>& c, const Vec3<double>& A, double AA) {
      const double axial = std::abs(dot(2.0 * X - c.p0 - c.p1, A)) / AA;
      const double radial = std::sqrt(squared_norm(cross(X - c.p0, A)) / (c.radius * c.radius * AA));
      return std::max(axial, radial);
    };
    return std::max(one(dbl_.c0, dbl_.A0, dbl_.AA0), one(dbl_.c1, dbl_.A1, dbl_.AA1));
  }

  // Cheap candidates. Two orders:
  //  - default: the direction T alone, by the static filter only (it separates about 9 separated
  //    random pairs in 10); then the cheap points, in order, the first whose double scale is
  //    below 1 checked; then the other cheap directions, the first whose double ratio is below 1
  //    checked. Gap bounds: the T direction's and the segment between the midpoints
  //    (static_segment_phi_lower), or the witness point's.
  //  - refine_gap: every candidate ranked by its double ratio / scale, the best checked (the
  //    best direction also gives the tightest phi_upper of the candidates).
  // Then, when no point is interior although no direction separates, alternating projections.
  bool fast_path() {
    begin(CylinderStage::fast_path);
    if (options_.refine_gap && gap_on()) return fast_path_ranked();
    const CylinderPair<double>& d = dbl_;
    const double k0 = 4 * d.c0.radius * d.c0.radius / d.AA0, k1 = 4 * d.c1.radius * d.c1.radius / d.AA1;
    std::optional<StaticDirection> t_terms;  // the static values of T, scaled (for phi_upper)
    if (static_ok_) {
      // T, certified by the static filter alone (when it cannot decide, T is tried again below
      // with the other directions, gated by its double ratio).
      const double s = power_of_two_normaliser(std::max({std::abs(d.T.x), std::abs(d.T.y), std::abs(d.T.z)}));
      if (s != 0) {
        const Vec3<double> D = s * d.T;
        t_terms = static_direction(stat_, D);
        ++result_.counters.directions_checked;
        if (static_separation_sign(*t_terms) == StaticSign::positive) {
          ++result_.counters.static_decisions;
          last_check_ = CylinderArithmetic::static_filter;
          if (gap_on()) lower_phi_upper(static_ratio_upper(*t_terms));
          bound_by_segment();
          return separated_by(D);
        }
      }
    }
    const auto bound_upper_by_t = [&] {
      if (!gap_on()) return;
      if (t_terms) return lower_phi_upper(static_ratio_upper(*t_terms));
      bound_by_direction(d.T);
    };
    const std::pair<Point3<double>, Point3<double>> closest = closest_segment_points(d.c0.p0, d.A0, d.c1.p0, d.A1);
    const std::array<Point3<double>, 5> points = cheap_points(closest);
    double best_scale = std::numeric_limits<double>::infinity();
    Point3<double> X = points[0];
    for (const Point3<double>& P : points) {
      const double sc = scale_double(P);
      if (sc < best_scale) best_scale = sc, X = P;
      if (!(sc < 1)) continue;
      std::optional<StaticPoint> values;
      if (check_point(P, &values)) {
        bound_by_point(P, values ? &*values : nullptr);
        bound_upper_by_t();
        return overlapping_at(P);
      }
    }
    // else: no cheap point is proved interior; the cheap directions, T again among them.
    const std::array<Vec3<double>, 7> directions = cheap_directions(closest);
    Vec3<double> best_D = d.T;
    double best_ratio = std::numeric_limits<double>::infinity();
    for (Vec3<double> D : directions) {
      const double r = ratio_double(D, k0, k1);
      if (r < best_ratio) best_ratio = r, best_D = D;
      if (!(r < 1)) continue;
      std::optional<StaticDirection> terms;
      if (check_direction(D, &terms) == CGAL::POSITIVE) {
        if (gap_on()) {
          bound_by_direction(D, terms ? &*terms : nullptr);
          bound_by_segment();
          bound_by_point(X);
        }
        return separated_by(D);
      }
    }
    return fast_path_projections(X, best_scale, best_D, best_ratio);
  }

  // The ranked order (refine_gap).
  bool fast_path_ranked() {
    const CylinderPair<double>& d = dbl_;
    const double k0 = 4 * d.c0.radius * d.c0.radius / d.AA0, k1 = 4 * d.c1.radius * d.c1.radius / d.AA1;
    const std::pair<Point3<double>, Point3<double>> closest = closest_segment_points(d.c0.p0, d.A0, d.c1.p0, d.A1);
    const std::array<Vec3<double>, 7> directions = cheap_directions(closest);
    Vec3<double> D = d.T;
    double best_ratio = std::numeric_limits<double>::infinity();
    for (const Vec3<double>& E : directions) {
      const double r = ratio_double(E, k0, k1);
      if (r < best_ratio) best_ratio = r, D = E;
    }
    const std::array<Point3<double>, 5> points = cheap_points(closest);
    if (best_ratio < 1) {
      std::optional<StaticDirection> terms;
      if (check_direction(D, &terms) == CGAL::POSITIVE) {
        bound_by_direction(D, terms ? &*terms : nullptr);
        bound_by_segment();
        bound_by_point(points[0]);
        return separated_by(D);
      }
    }
    // else: no cheap direction is proved to separate; look for an interior point.
    std::size_t best_p = 0;
    double best_scale = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < points.size(); ++i) {
      const double s = scale_double(points[i]);
      if (s < best_scale) best_scale = s, best_p = i;
    }
    const Point3<double> X = points[best_p];
    if (best_scale < 1) {
      std::optional<StaticPoint> values;
      if (check_point(X, &values)) {
        bound_by_point(X, values ? &*values : nullptr);
        bound_by_direction(D);
        return overlapping_at(X);
      }
    }
    return fast_path_projections(X, best_scale, D, best_ratio);
  }

  // No cheap point is interior and no cheap direction separates (typically a contact near a
  // cap, where the cheap points sit on a cap plane): a few rounds of alternating projections
  // onto both cylinders shrunk by 1 - 2^-6 (then 1 - 2^-10) about their midpoints move X inside
  // when the overlap is not shallow. Records the gap bounds of X and D either way.
  bool fast_path_projections(Point3<double> X, double best_scale, const Vec3<double>& D, double best_ratio) {
    const CylinderPair<double>& d = dbl_;
    if (!(best_scale < 1) && !(best_ratio < 1)) {
      for (int round = 0; round < 12 && !(best_scale < 1); ++round) {
        const double shrink = round < 6 ? 1 - 0x1p-6 : 1 - 0x1p-10;
        X = project_shrunk(d.c1, d.A1, d.AA1, shrink, project_shrunk(d.c0, d.A0, d.AA0, shrink, X));
        best_scale = scale_double(X);
      }
      if (best_scale < 1) {
        std::optional<StaticPoint> values;
        if (check_point(X, &values)) {
          bound_by_point(X, values ? &*values : nullptr);
          bound_by_direction(D);
          return overlapping_at(X);
        }
      }
    }
    bound_by_direction(D);
    bound_by_point(X);
    bound_by_segment();
    return pass();
  }

  // Nearest point to X of cylinder c (axis A, A.A = AA) shrunk by 1 - 2^-6 about its midpoint:
  // the solid is a segment times a disk in its own frame, so the axial and radial parts clamp
  // apart (double; candidates only).
  static Point3<double> project_shrunk(const Cylinder<double>& c, const Vec3<double>& A, double AA, double s, const Point3<double>& X) {
    const Point3<double> m = 0.5 * (c.p0 + c.p1);
    const Vec3<double> w = X - m;
    const double t = dot(w, A) / AA;
    Vec3<double> radial = w - t * A;
    const double rl = std::sqrt(dot(radial, radial)), limit = s * c.radius;
    if (rl > limit) radial = (limit / rl) * radial;
    return m + std::clamp(t, -s / 2, s / 2) * A + radial;
  }

  // T, its parts orthogonal to each axis, A0 x A1, the difference of the closest points of the
  // axis segments, A0, A1.
  std::array<Vec3<double>, 7> cheap_directions(const std::pair<Point3<double>, Point3<double>>& closest) const {
    const CylinderPair<double>& d = dbl_;
    return {d.T, d.AA0 * d.T - dot(d.A0, d.T) * d.A0, d.AA1 * d.T - dot(d.A1, d.T) * d.A1, cross(d.A0, d.A1),
            closest.second - closest.first, d.A0, d.A1};
  }

  // The r0:r1 point and the midpoint of the closest points c0, c1 of the axis segments, the
  // midpoints m0, m1, and c0.
  std::array<Point3<double>, 5> cheap_points(const std::pair<Point3<double>, Point3<double>>& closest) const {
    const CylinderPair<double>& d = dbl_;
    const auto& [c0, c1] = closest;
    const double r0 = d.c0.radius, r1 = d.c1.radius;
    return {c0 + (r0 / (r0 + r1)) * (c1 - c0), 0.5 * (c0 + c1), 0.5 * (d.c0.p0 + d.c0.p1), 0.5 * (d.c1.p0 + d.c1.p1), c0};
  }

  // ---- stage optimiser ---------------------------------------------------------------------------------
  bool optimiser() {
    begin(CylinderStage::optimiser);
    PlaneProblem<double> problem(dbl_, 44);
    const PlaneMinimum<double> m = problem.minimise(true, 30);
    result_.counters.newton_steps += static_cast<std::uint32_t>(m.iterations);
    optimum_ = m.direction;
    optimum_point_ = m.point;
    optimum_value_ = std::isfinite(m.value) ? m.value : std::numeric_limits<double>::infinity();
    bound_by_direction(m.direction);
    bound_by_point(m.point);
    // When the refine stage follows, a check that the filter and the intervals leave open is
    // left to it (its candidates are better by some 50 bits); it comes back here only if the
    // refine stage finds no optimum.
    Vec3<double> D = m.direction;
    if (std::isfinite(m.value) && m.value < 1 && check_direction(D, nullptr, !options_.refine) == CGAL::POSITIVE) return separated_by(D);
    if (scale_double(m.point) < 1 && check_point(m.point, nullptr, !options_.refine)) return overlapping_at(m.point);
    return pass();
  }

  // The optimiser's checks in Gmpq, when the refine stage could not improve on its candidates.
  bool optimiser_exact() {
    if (!optimum_ || !optimum_point_) return false;
    Vec3<double> D = *optimum_;
    if (optimum_value_ < 1 && check_direction(D) == CGAL::POSITIVE) return separated_by(D);
    if (scale_double(*optimum_point_) < 1 && check_point(*optimum_point_)) return overlapping_at(*optimum_point_);
    return false;
  }

  // ---- stage refine -------------------------------------------------------------------------------------
  // What the Newton iteration of the refine stage found.
  struct Refined {
    bool decided = false;
    bool near_touching = false;  // sigma(X) within the precision's noise of 1
  };

  // The world input in QD: exact for binary64 input, correctly rounded otherwise.
  // Rational input is rounded once per query (the refine stage may ask twice).
  template <class QD>
  CylinderPair<QD> world_pair() {
    const auto to_q = [](double x) { return QD(x); };
    if (binary64_) return CylinderPair<QD>::make(dbl_.c0.map(to_q), dbl_.c1.map(to_q));
    const auto rational_to_q = [this](const Rational& q) { return qd_from_rational<QD>(q, world_exponent_); };
    if constexpr (std::is_same_v<QD, dd_real>) {
      if (!dd_pair_) dd_pair_ = CylinderPair<QD>::make(exact_cylinder(0).map(rational_to_q), exact_cylinder(1).map(rational_to_q));
      return *dd_pair_;
    }
    return CylinderPair<QD>::make(exact_cylinder(0).map(rational_to_q), exact_cylinder(1).map(rational_to_q));
  }
  template <class QD>
  static bool finite_q(const QD& x) {
    for (double t : x.x)
      if (!std::isfinite(t)) return false;
    return true;
  }
  template <class QD>
  static bool finite_q(const Vec3<QD>& v) {
    return finite_q(v.x) && finite_q(v.y) && finite_q(v.z);
  }

  // Newton's method on the optimality conditions in QD (dd_real) from the world
  // point X0 (first_pieces: one attempt from that active set only; max_steps per attempt); its
  // point or its direction checked exactly.
  template <class QD>
  Refined refine_in(const Point3<QD>& X0, int epsilon_exponent, int touching_exponent, unsigned first_pieces = 0, int max_steps = 24) {
    Refined r;
    const CylinderPair<QD> d = world_pair<QD>();
    ActiveSetProblem<QD> problem(d, -epsilon_exponent, true);
    const std::optional<ActiveSetOptimum<QD>> o = problem.solve(X0, first_pieces, max_steps);
    if (!o) return r;
    result_.counters.newton_steps += static_cast<std::uint32_t>(o->iterations);
    if (!finite_q(o->value) || !finite_q(o->point)) return r;
    if (finite_q(o->direction)) {
      Vec3<Rational> D = o->direction.map([](const QD& x) { return nt::to_rational(x); });
      if (!(D.x == 0 && D.y == 0 && D.z == 0)) refined_ = std::move(D);
    }
    const QD excess = o->value - QD(1);
    if (std::abs(excess.x[0]) < std::ldexp(1.0, touching_exponent)) {
      r.near_touching = true;
      return r;
    }
    if (excess.x[0] < 0) {
      bound_by_point(o->point.map([](const QD& x) {
        const auto [lo, hi] = nt::to_interval(x);
        return Interval(lo, hi);
      }));
      r.decided = ring() ? dyadic_overlaps(o->point) : exact_overlaps(world_to_input(o->point));
    } else if (refined_) {
      bound_by_direction(to_iv(*refined_));
      r.decided = ring() ? dyadic_separates(o->direction) : exact_separates(*refined_);
    }
    return r;
  }

  // The smoothing path of the optimiser (detail/cylinder_optimiser.hpp) in QD, to 2^-mu of the
  // value: slower than Newton's method on the optimality conditions but indifferent to how the
  // pieces meet; its direction and point checked exactly.
  template <class QD>
  bool smoothed_in(int mu, int stop) {
    const CylinderPair<QD> d = world_pair<QD>();
    PlaneProblem<QD> problem(d, mu);
    const PlaneMinimum<QD> m = problem.minimise(true, stop);
    result_.counters.newton_steps += static_cast<std::uint32_t>(m.iterations);
    if (finite_q(m.value) && m.value < QD(1) && finite_q(m.direction)) {
      Vec3<Rational> D = m.direction.map([](const QD& x) { return nt::to_rational(x); });
      if (!(D.x == 0 && D.y == 0 && D.z == 0)) {
        refined_ = std::move(D);
        if (ring() ? dyadic_separates(m.direction) : exact_separates(*refined_)) return true;
      }
    }
    if (finite_q(m.point))
      return ring() ? dyadic_overlaps(m.point) : exact_overlaps(world_to_input(m.point));
    return false;
  }

  // Double-double from the optimiser's point; where it stalls short of a decision (the pieces
  // meet almost tangentially and the system is ill-conditioned), the smoothing path in
  // double-double.
  bool refine() {
    begin(CylinderStage::refine);
    if (!optimum_point_ || !finite(*optimum_point_)) return optimiser_exact() || pass();
    // The same Newton iteration in double first (a double-double step costs about ten double
    // ones): from its point, double-double needs a step or two.
    Point3<double> start = *optimum_point_;
    std::optional<Point3<double>> vertex;
    {
      ActiveSetProblem<double> problem(dbl_, 48);
      const std::optional<ActiveSetOptimum<double>> o = problem.solve(start);
      if (o && finite(o->point)) {
        result_.counters.newton_steps += static_cast<std::uint32_t>(o->iterations);
        start = o->point;
      }
      // Where two caps meet almost flat (the start above ends with the two caps active), the
      // optimum is usually a vertex of all four pieces, at the rim, that double-double reaches
      // from there only by a walk of several steps along the nearly flat crease of the caps;
      // double takes a few cheap steps to it from all four pieces (at most eight: where the caps
      // coincide the system is singular and it does not converge). It is tried first (one
      // attempt of at most three double-double steps: from the right vertex one or two decide)
      // when double ends there and the axes are not parallel (parallel caps have no crease: their
      // optimum is where double found it); otherwise the usual start follows.
      if (o && o->pieces == 5u && axes_surely_not_parallel()) {
        const std::optional<ActiveSetOptimum<double>> v = problem.solve(*optimum_point_, 15u, 8);
        if (v) result_.counters.newton_steps += static_cast<std::uint32_t>(v->iterations);
        if (v && v->pieces == 15u && finite(v->point)) vertex = v->point;
      }
    }
    if (vertex) {
      const Refined dd = refine_in<dd_real>(vertex->map([](double x) { return dd_real(x); }), -96, -98, 15u, 3);
      if (dd.decided) return true;
      if (dd.near_touching) return pass();
    }
    const Refined dd = refine_in<dd_real>(start.map([](double x) { return dd_real(x); }), -96, -98);
    if (dd.decided) return true;
    if (dd.near_touching) return pass();
    if (smoothed_in<dd_real>(96, 60)) return true;
    return optimiser_exact() || pass();
  }

  // Whether A0 x A1 != 0 is proved by intervals (a guess that steers the refine stage; false
  // when the enclosure cannot tell).
  bool axes_surely_not_parallel() {
    const CylinderPair<Interval>& d = iv();
    CGAL::Protect_FPU_rounding<true> upward;
    const Vec3<Interval> c = cross(d.A0, d.A1);
    const auto nonzero = [](const Interval& x) { return x.inf() > 0 || x.sup() < 0; };
    return nonzero(c.x) || nonzero(c.y) || nonzero(c.z);
  }

  // The ring frame (detail/cylinder_ring_frame.hpp): the input times L 2^e in Mpzf, built when
  // first needed. Binary64 input in an exact world frame: the world input itself (L = 1); other
  // rational input: times the lcm L of its denominators. A double-double candidate has dyadic
  // coordinates, so it is checked exactly there (the signs are those of the input frame: the
  // checks are homogeneous in the lengths and in the direction), without Gmpq's gcds. nullptr
  // when there is no such frame (binary64 input whose world frame is not exact, rational input
  // whose L is too large): the checks are then made in Gmpq.
  const RingFrame* ring() {
    if (!ring_tried_) {
      ring_tried_ = true;
      // Binary64 input whose world frame is not exact (it spans more binades than a double
      // holds, so the world frame is the input frame) takes the rational frame: its
      // denominators are powers of two, L at most 2^1074.
      if (binary64_ && world_exact_) {
        ring_ = RingFrame::from_world(dbl_.c0, dbl_.c1, world_exponent_);
      } else {
        ring_ = RingFrame::from_rational(exact_cylinder(0), exact_cylinder(1));
      }
    }
    return ring_ ? &*ring_ : nullptr;
  }
  // The ring frame when it is the world frame itself (binary64 input with an exact world frame):
  // a world double is then a ring number as it stands, and the exact checks of the double stages
  // run in Mpzf, without building the Gmpq pair (its gcds cost some 20 us a check on rotated and
  // rounded input).
  const RingFrame* world_ring() { return binary64_ && world_exact_ ? ring() : nullptr; }
  template <class QD>
  static CGAL::Mpzf to_mpzf(const QD& x) {
    CGAL::Mpzf m(x.x[0]);
    for (std::size_t i = 1; i < std::size(x.x); ++i) m = m + CGAL::Mpzf(x.x[i]);
    return m;
  }
  // A world point in QD, in the input frame exactly.
  template <class QD>
  Point3<Rational> world_to_input(const Point3<QD>& X) const {
    return X.map([this](const QD& x) { return times_two_power(nt::to_rational(x), -world_exponent_); });
  }
  template <class QD>
  bool dyadic_overlaps(const Point3<QD>& X) {
    ++result_.counters.points_checked;
    ++result_.counters.exact_checks;
    last_check_ = CylinderArithmetic::exact;
    const RingFrame& f = *ring();
    const int e = world_exponent_;
    return strictly_inside_both(f.pair, X.map([&f, e](const QD& x) { return f.from_world(to_mpzf(x), e); })) &&
           overlapping_at(world_to_input(X));
  }
  template <class QD>
  bool dyadic_separates(const Vec3<QD>& D) {
    ++result_.counters.directions_checked;
    ++result_.counters.exact_checks;
    last_check_ = CylinderArithmetic::exact;
    return separation_sign(ring()->pair, D.map([](const QD& x) { return to_mpzf(x); })) == CGAL::POSITIVE && separated_by(*refined_);
  }

  // ---- stage touching_exact -----------------------------------------------------------------------------
  bool try_touching(const Vec3<Rational>& D) {
    // Interval pre-filter: the proof needs phi2(D) = |D.T| exactly, so skip D when the interval
    // enclosure of their ratio excludes 1.
    {
      const CylinderPair<Interval>& d = iv();
      CGAL::Protect_FPU_rounding<true> upward;
      const std::optional<Interval> r = ratio_enclosure(d, to_iv(D));
      if (r && (r->inf() > 1 || r->sup() < 1)) return false;
    }
    ++result_.counters.touching_candidates;
    std::optional<CylinderContact> c = prove_touching(exact(), D);
    if (!c) return false;
    return touching_with(std::move(*c));
  }

  // A0, A1, A0 x A1 and the parts of T orthogonal to each axis, exactly: the contact normals of
  // cap and wall contacts (detail/cylinder_rim_contacts.hpp), and separating candidates.
  template <class R>
  static std::array<Vec3<R>, 5> structural_directions(const CylinderPair<R>& e) {
    return {e.A0, e.A1, cross(e.A0, e.A1), e.AA0 * e.T - dot(e.A0, e.T) * e.A0, e.AA1 * e.T - dot(e.A1, e.T) * e.A1};
  }

  // Whether the rational directions D and R are parallel to about 2^-40 (in double; a guess
  // that orders the candidates, not a proof).
  static bool nearly_parallel(const Vec3<Rational>& D, const Vec3<Rational>& R) {
    const auto d = [](const Vec3<Rational>& v) { return v.map([](const Rational& x) { return CGAL::to_double(x); }); };
    const Vec3<double> a = d(D), b = d(R), c = cross(a, b);
    return dot(c, c) <= std::ldexp(dot(a, a) * dot(b, b), -80);
  }

  // The same candidates, proved in the ring frame (prove_touching_ring, detail/cylinder_touching.hpp):
  // the interval pre-filter of try_touching, then the proof in Mpzf; the contact's normal and
  // point are converted to the input frame once, when proved.
  bool try_touching_ring(const Vec3<CGAL::Mpzf>& D) {
    {
      const CylinderPair<Interval>& d = iv();
      CGAL::Protect_FPU_rounding<true> upward;
      Vec3<Interval> Di;
      bool finite_enclosure = true;
      for (std::size_t i = 0; i < 3; ++i) {
        const std::pair<double, double> b = CGAL::to_interval(D[i]);
        finite_enclosure = finite_enclosure && std::isfinite(b.first) && std::isfinite(b.second);
        Di[i] = Interval(b.first, b.second);
      }
      if (finite_enclosure) {
        const std::optional<Interval> r = ratio_enclosure(d, Di);
        if (r && (r->inf() > 1 || r->sup() < 1)) return false;
      }
    }
    ++result_.counters.touching_candidates;
    const RingFrame& f = *ring();
    std::optional<RingContact> c = prove_touching_ring(f.pair, D);
    if (!c) return false;
    const CGAL::Mpzf& w = c->point.w;
    return touching_with(CylinderContact{c->feature0, c->feature1, mpzf_to_rational(c->normal),
                                         c->point.n.map([&f, &w](const CGAL::Mpzf& x) { return f.to_input(x, w); })});
  }

  static bool nearly_parallel(const Vec3<double>& a, const Vec3<double>& b) {
    const Vec3<double> c = cross(a, b);
    return dot(c, c) <= std::ldexp(dot(a, a) * dot(b, b), -80);
  }

  // touching_exact in the ring frame: the same candidates in the same order.
  bool touching_exact_ring() {
    const CylinderPair<CGAL::Mpzf>& d = ring()->pair;
    const std::array<Vec3<CGAL::Mpzf>, 5> structural = {d.A0, d.A1, cross(d.A0, d.A1), d.AA0 * d.T - dot(d.A0, d.T) * d.A0,
                                                        d.AA1 * d.T - dot(d.A1, d.T) * d.A1};
    std::array<bool, 5> tried{};
    if (refined_) {
      const Vec3<double> R = refined_->map([](const Rational& x) { return CGAL::to_double(x); });
      for (std::size_t i = 0; i < structural.size(); ++i)
        if (nearly_parallel(structural[i].map([](const CGAL::Mpzf& x) { return CGAL::to_double(x); }), R)) {
          tried[i] = true;
          if (try_touching_ring(structural[i])) return true;
        }
      if (try_touching_ring(ring_direction(reconstruct_direction(*refined_, Rational(1L, 1UL << 50))))) return true;
    }
    for (std::size_t i = 0; i < structural.size(); ++i)
      if (!tried[i] && try_touching_ring(structural[i])) return true;
    for (const Vec3<Rational>& D : rim_contact_normals(exact()))
      if (try_touching_ring(ring_direction(D))) return true;
    if (optimum_ && finite(*optimum_)) {
      const Vec3<Rational> D = optimum_->map([](double x) { return Rational(x); });
      if (!(D.x == 0 && D.y == 0 && D.z == 0) && try_touching_ring(ring_direction(reconstruct_direction(D, Rational(1, 1 << 20)))))
        return true;
    }
    return false;
  }

  bool touching_exact() {
    touching_tried_ = true;
    begin(CylinderStage::touching_exact);
    if (ring()) return touching_exact_ring() || pass();
    const CylinderPair<Rational>& e = exact();
    const std::array<Vec3<Rational>, 5> structural = structural_directions(e);
    // The refine stage's direction is within about 2^-100 of the contact normal when there is
    // one: the structural direction parallel to it first, then its rational reconstruction.
    std::array<bool, 5> tried{};
    if (refined_) {
      for (std::size_t i = 0; i < structural.size(); ++i)
        if (nearly_parallel(structural[i], *refined_)) {
          tried[i] = true;
          if (try_touching(structural[i])) return true;
        }
      if (try_touching(reconstruct_direction(*refined_, Rational(1L, 1UL << 50)))) return true;
    }
    for (std::size_t i = 0; i < structural.size(); ++i)
      if (!tried[i] && try_touching(structural[i])) return true;
    // Rim-wall and rim-rim normals, exactly (detail/cylinder_rim_contacts.hpp).
    for (const Vec3<Rational>& D : rim_contact_normals(e))
      if (try_touching(D)) return true;
    if (optimum_ && finite(*optimum_)) {
      const Vec3<Rational> D = optimum_->map([](double x) { return Rational(x); });
      if (!(D.x == 0 && D.y == 0 && D.z == 0) && try_touching(reconstruct_direction(D, Rational(1, 1 << 20)))) return true;
    }
    return pass();
  }

  // ---- stage gmpfr --------------------------------------------------------------------------------------
  // Binary64 input with an exact world frame reads it off the ring frame's Mpzf pair (the world
  // frame exactly, built for the touching proofs anyway), without building the Gmpq pair; the
  // same number (binades are those of the world frame, a power-of-two scaling of the input).
  long input_span_bits() {
    if (!span_bits_) {
      span_bits_ = binary64_ && world_exact_ && ring() ? cylinder_pair_span_bits(ring()->pair) : cylinder_pair_span_bits(exact());
    }
    return *span_bits_;
  }

  // Exact candidates, before any Gmpfr round: the midpoints m0, m1 as witnesses (each is interior
  // to its own cylinder; in double they may be rounded off a needle's axis), and the directions
  // T, its parts orthogonal to each axis, A0, A1, A0 x A1 and the part of each axis orthogonal to
  // the other; then the exact closest points c0, c1 of the axis segments: their r0:r1 division
  // point and midpoint as witnesses and c1 - c0 as a direction. These decide every pair whose
  // contact is between the walls away from the caps at any distance from touching: with c0, c1
  // interior to the axis segments and d = |c1 - c0|, the r0:r1 point is at distance
  // r0 d / (r0 + r1) < r0 from axis 0 and r1 d / (r0 + r1) < r1 from axis 1 when d < r0 + r1,
  // and c1 - c0, orthogonal to both axes, separates when d > r0 + r1. In the ring frame when the
  // pair has one (Mpzf, in homogeneous coordinates: no division, no gcd), else on the input in
  // Gmpq.
  bool exact_candidates() {
    if (exact_candidates_tried_) return false;
    exact_candidates_tried_ = true;
    return ring() ? exact_candidates(ring()->pair) : exact_candidates(exact());
  }
  template <class R>
  static bool is_zero_vector(const Vec3<R>& v) {
    return CGAL::is_zero(v.x) && CGAL::is_zero(v.y) && CGAL::is_zero(v.z);
  }
  template <class R>
  bool exact_candidates(const CylinderPair<R>& e) {
    if (!is_zero_vector(e.T) && exact_separates(e.T)) return true;
    for (const Vec3<R>& D : structural_directions(e))
      if (!is_zero_vector(D) && exact_separates(D)) return true;
    // The part of each axis orthogonal to the other: with A0 x A1, the part of A1 spans the plane
    // orthogonal to A0, near which every separating direction lies when A0 is long beside the
    // gap (|D.A0| / 2 <= phi(D) < D.Delta); likewise with the indices exchanged.
    const R b = dot(e.A0, e.A1);
    for (const Vec3<R>& D : {e.AA0 * e.A1 - b * e.A0, e.AA1 * e.A0 - b * e.A1})
      if (!is_zero_vector(D) && exact_separates(D)) return true;
    const R two(2);
    for (const Cylinder<R>* c : {&e.c0, &e.c1})
      if (exact_overlaps(HomogeneousPoint<R>{c->p0 + c->p1, two})) return true;
    const auto [c0, c1] = closest_axis_points(e);
    const Vec3<R> between = c1.n * c0.w - c0.n * c1.w;  // c0.w c1.w (c1 - c0)
    if (!is_zero_vector(between) && exact_separates(between)) return true;
    // c0 + r0 / (r0 + r1) (c1 - c0) and (c0 + c1) / 2, over c0.w c1.w (r0 + r1) and 2 c0.w c1.w.
    const R rr = e.c0.radius + e.c1.radius, ww = c0.w * c1.w;
    const Vec3<R> c0n = c1.w * c0.n, c1n = c0.w * c1.n;
    if (exact_overlaps(HomogeneousPoint<R>{e.c1.radius * c0n + e.c0.radius * c1n, rr * ww}) ||
        exact_overlaps(HomogeneousPoint<R>{c0n + c1n, two * ww}))
      return true;
    if (out_of_time()) return false;
    return end_disc_witness(e, 0) || end_disc_witness(e, 1) || tube_shift_witness(e, c1, c0, 1) || tube_shift_witness(e, c0, c1, 0) ||
           mid_plane_witness(e);
  }

  // Closest points of the axis segments p0_i + s A_i (s in [0, 1]), exactly: the parameters are
  // clamped in turn (s on the line-line optimum, t for that s, s again for that t), which gives a
  // pair of closest points of two segments; for parallel axes (a c = b^2), s is the middle of the
  // overlap of their parameter ranges on segment 0, so the points stay away from the caps. In
  // homogeneous coordinates: each parameter is n / d (d > 0), clamped by comparing n with 0 and d.
  template <class R>
  static std::pair<HomogeneousPoint<R>, HomogeneousPoint<R>> closest_axis_points(const CylinderPair<R>& e) {
    const R zero(0), one(1), two(2);
    struct Fraction {
      R n, d;  // n / d, d > 0
    };
    const auto clamp01 = [&](R n, R d) { return n < zero ? Fraction{zero, one} : (n > d ? Fraction{one, one} : Fraction{std::move(n), std::move(d)}); };
    const Vec3<R> w = e.c0.p0 - e.c1.p0;
    const R& a = e.AA0;
    const R& c = e.AA1;
    const R b = dot(e.A0, e.A1), d = dot(e.A0, w), f = dot(e.A1, w);
    const R den = a * c - b * b;
    Fraction s;
    if (den != zero) {
      s = clamp01(b * f - c * d, den);
    } else {  // parallel axes: the middle of the overlap of the parameter ranges, over 2 a
      R t0 = -d, t1 = b - d;
      if (t1 < t0) std::swap(t0, t1);
      s = clamp01((t0 > zero ? t0 : zero) + (t1 < a ? t1 : a), two * a);
    }
    const Fraction t = clamp01(b * s.n + f * s.d, c * s.d);
    s = clamp01(b * t.n - d * t.d, a * t.d);
    return {HomogeneousPoint<R>{s.d * e.c0.p0 + s.n * e.A0, s.d}, HomogeneousPoint<R>{t.d * e.c1.p0 + t.n * e.A1, t.d}};
  }

  // Points of j's tube beside the closest point c_j of its axis to i's: X = c_j + s w, w the part
  // orthogonal to A_j of A_i, -A_i or c_i - c_j, s = r_j / (2 max |w_k|) and s / 2 (so
  // |s w| <= r_j sqrt(3) / 2 < r_j: X is inside j's tube when c_j is interior to its axis
  // segment). They find the overlap of a thin cylinder whose tube, not its axis, reaches into the
  // other's slab (the sliver between a cap plane and the side of a tube it crosses).
  template <class R>
  bool tube_shift_witness(const CylinderPair<R>& e, const HomogeneousPoint<R>& cj_point, const HomogeneousPoint<R>& ci_point, int j) {
    const auto [cj, ci, Aj, Ai, AAj, AAi] = pair_roles(e, j);
    const Vec3<R> towards = ci_point.n * cj_point.w - cj_point.n * ci_point.w;  // a positive multiple of c_i - c_j
    const R two(2), four(4);
    for (const Vec3<R>& d : {Ai, Vec3<R>(-Ai), towards}) {
      const Vec3<R> w = AAj * d - dot(d, Aj) * Aj;
      const R w_max = largest_coordinate(w);
      if (CGAL::is_zero(w_max)) continue;
      // c_j + r_j w / (k w_max) = (k w_max n + W r_j w) / (k w_max W), k = 2 and 4.
      const Vec3<R> shift = (cj_point.w * cj.radius) * w;
      for (const R& k : {two, four})
        if (exact_overlaps(HomogeneousPoint<R>{(k * w_max) * cj_point.n + shift, k * w_max * cj_point.w})) return true;
    }
    return false;
  }

  // Points of the line where the mid-planes (X - m_i).A_i = 0 of the two slabs meet (A0 x A1 != 0):
  // on it, |X - m_i| is X's distance from axis i, so X is interior to both when
  // |X - m_i| < r_i for both. Candidates: the points of the line nearest m0 and m1, and the
  // r0 : r1 point between them. They decide two flat cylinders (radius far above height) whose
  // slabs cross inside both tubes, however far from the axes.
  // With M_i = 2 m_i and h_i = 2 A_i.m_i, the line's point X0 = N0 / (2 LL) (LL = |A0 x A1|^2),
  // N0 = (h0 A1.A1 - h1 A0.A1) A0 + (h1 A0.A0 - h0 A0.A1) A1, and the point nearest m_i is
  // X0 + tau_i L / (2 LL^2) = (LL N0 + tau_i L) / (2 LL^2), tau_i = (LL M_i - N0).L.
  template <class R>
  bool mid_plane_witness(const CylinderPair<R>& e) {
    const Vec3<R> L = cross(e.A0, e.A1);
    if (is_zero_vector(L)) return false;
    const R two(2);
    const R LL = dot(L, L), AB = dot(e.A0, e.A1);
    const Vec3<R> M0 = two * e.c0.p0 + e.A0, M1 = two * e.c1.p0 + e.A1;
    const R h0 = dot(e.A0, M0), h1 = dot(e.A1, M1);
    const Vec3<R> N0 = (h0 * e.AA1 - h1 * AB) * e.A0 + (h1 * e.AA0 - h0 * AB) * e.A1;
    const R tau0 = dot(LL * M0 - N0, L), tau1 = dot(LL * M1 - N0, L), W = two * LL * LL;
    const Vec3<R> base = LL * N0;
    if (exact_overlaps(HomogeneousPoint<R>{base + tau0 * L, W}) || exact_overlaps(HomogeneousPoint<R>{base + tau1 * L, W})) return true;
    // tau0 + r0 / (r0 + r1) (tau1 - tau0), over r0 + r1.
    const R rr = e.c0.radius + e.c1.radius;
    return exact_overlaps(HomogeneousPoint<R>{rr * base + (e.c1.radius * tau0 + e.c0.radius * tau1) * L, rr * W});
  }

  // Corner candidates (detail/cylinder_corner_plane.hpp), for each cylinder i against the other,
  // j, the larger first: in the plane of i's axis through m_j, the best direction of i's rim
  // wedge (whose support on i is exact) and, when none separates, j's deepest point in the
  // wedge; then again in the plane through j's support point there (near the contact, where the
  // plane's only error, the curvature of i's rim over j's distance from the plane, is smallest).
  // The quantities are reduced exactly to the contact's scale; the precision starts at 192 bits
  // and rises to what the gain found needs against its terms, or doubles when the gain rounds to
  // zero (at most `max_precision`; the best direction is found in closed form, a few evaluations
  // at any precision). The next plane goes through the witness found, else through the support
  // point: up to six planes, more while each gives a witness, up to twelve at a cap of 4,096 bits
  // and one more for each doubling of the cap, fewer when the planes fall into a 2-cycle (a
  // point back within 2^-16 of the one two planes before, at the same precision: the two
  // alternate, each only refined); more bits for the same plane do not count as a
  // plane (the planes through witnesses on a face of j's support converge, as Newton's method on
  // i's rim circle, to where that face crosses the rim, and the wedge's curvature error with
  // them: each plane needs about twice the bits of the last, and a rim-rim contact 2^-k off
  // touching is decided at about the (log2(k) - 4)th plane). They decide pairs of a huge and a
  // tiny cylinder (2^900 against 2^-900), needles against pancakes, and slivers at a rim or a cap
  // (common interiors 2^-800 thin), whose separating directions or common interior are far too
  // narrow for the rounded optimiser below thousands of bits. Each candidate is checked exactly.
  // Tried once per query and cap: a call with a higher cap than the last goes on where the last
  // cap stopped a cylinder's planes (a gain it could not resolve, or the last plane it allowed),
  // and skips a cylinder whose planes ended with every gain resolved within the last cap (a
  // higher cap would change at most the precision of a plane on the way; the candidates are
  // heuristics either way). The planes are computed in the ring frame when the pair has one (its
  // integers in Mpzf: no gcds), else on the input in Gmpq.
  static constexpr long kCornerFirstCap = 1024, kCornerMaxPrecision = 4096;
  bool corner_candidates(long max_precision) {
    if (corner_cap_ >= max_precision) return false;
    const bool first_call = corner_cap_ == 0;
    corner_cap_ = max_precision;
    if (const RingFrame* f = ring()) return corner_planes(f->pair, max_precision, first_call);
    return corner_planes(exact(), max_precision, first_call);
  }
  // A ring-frame direction or point (nothing to undo for a direction), checked exactly.
  bool exact_separates(const Vec3<CGAL::Mpzf>& D) {
    ++result_.counters.directions_checked;
    ++result_.counters.exact_checks;
    last_check_ = CylinderArithmetic::exact;
    return separation_sign(ring()->pair, D) == CGAL::POSITIVE && separated_by(mpzf_to_rational(D));
  }
  bool exact_overlaps(const Point3<CGAL::Mpzf>& X) {
    ++result_.counters.points_checked;
    ++result_.counters.exact_checks;
    last_check_ = CylinderArithmetic::exact;
    const RingFrame& f = *ring();
    const CGAL::Mpzf one(1);
    return strictly_inside_both(f.pair, X) && overlapping_at(X.map([&](const CGAL::Mpzf& x) { return f.to_input(x, one); }));
  }
  template <class R>
  bool corner_planes(const CylinderPair<R>& e, long max_precision, bool first_call) {
    constexpr long first_precision = 192;
    // Twelve planes at 4,096 bits, one more for each doubling of the cap (a plane's bits double).
    const int max_passes = 12 + std::max(0, static_cast<int>(std::bit_width(static_cast<unsigned long>(max_precision / kCornerMaxPrecision))) - 1);
    const R four = nt::constant<R>(4);
    const int larger = e.AA0 + four * e.c0.radius * e.c0.radius >= e.AA1 + four * e.c1.radius * e.c1.radius ? 0 : 1;
    for (const int i : {larger, 1 - larger}) {
      const Cylinder<R>& ci = i == 0 ? e.c0 : e.c1;
      const Cylinder<R>& cj = i == 0 ? e.c1 : e.c0;
      Point3<R> y = cj.p0 + cj.axis() * ring_two_power<R>(-1);
      long precision = first_precision;
      int first_pass = 0;
      if (!first_call) {
        // Planes whose run ended with every gain resolved within the last cap are not rerun.
        if (!corner_resume_[i]) continue;
        const CornerResume& r = *corner_resume_[i];
        y = std::get<Point3<R>>(r.y);
        first_pass = r.pass;  // the plane short of bits, or the one after the last allowed
        precision = std::min(max_precision, std::max(2 * r.precision, r.needed));
        corner_resume_[i].reset();
      }
      std::optional<std::pair<Point3<R>, long>> before;  // the last plane's point and starting precision
      long start = precision;                            // this plane's starting precision
      for (int pass = first_pass; pass < max_passes;) {  // a pass is a plane; more bits for it are not a pass
        if (out_of_time()) return false;
        std::optional<Vec3<R>> D;
        std::optional<Point3<R>> X;
        Point3<R> next;
        long needed = 0;
        {
          GmpfrPrecision scope(precision);
          const CornerPlane<R> plane = CornerPlane<R>::make(ci, cj, y);
          const CGAL::Gmpfr t = plane.best();
          const CGAL::Gmpfr g = plane.gain(t);
          // A gain rounded to zero says only that this precision is short: double it (rather
          // than jump to the cap, which made every later plane cost 4,096-bit products).
          needed = g == 0 ? 2 * precision : plane.bits_to_resolve(t, g);
          if (g > 0) {
            D = plane.direction(t);
          } else if (g < 0) {
            CGAL::Gmpfr spread = nt::constant<CGAL::Gmpfr>(1);
            mpfr_mul_2si(spread.fr(), spread.fr(), -(precision * 9 / 10), MPFR_RNDN);
            X = plane.witness(t, spread, precision);
          }
          next = X ? *X : plane.support(t).x;
        }
        if (D && exact_separates(std::move(*D))) return true;
        if (X && exact_overlaps(std::move(*X))) return true;
        if (needed > precision && precision < max_precision) {
          precision = std::min(max_precision, std::max(2 * precision, needed));
          continue;  // the same plane, more bits
        }
        if (needed > precision) {
          corner_resume_[i] = CornerResume{y, pass, precision, needed};  // a higher cap goes on from here
          break;
        }
        if (next == y || (pass >= 5 && !X)) break;  // beyond six planes only while witnesses come
        // A plane is a function of its point and starting precision: back to the point of the
        // last plane at its starting precision (so none of the two raised it), they would repeat.
        if (before && next == before->first && precision == before->second) break;
        // Back within 2^-16 of the last plane's point after a step 2^16 times longer: the planes
        // alternate between two points, a 2-cycle that only refines them.
        if (before && precision == before->second && returns_to(next, before->first, y)) break;
        before = std::pair{y, start};
        y = next;
        start = precision;
        if (++pass == max_passes) corner_resume_[i] = CornerResume{y, pass, precision, precision};  // a higher cap allows more
      }
    }
    return false;
  }

  // Whether b is back within 2^-16 of a after a step from y: |b - a| < 2^-16 |b - y| (max norms,
  // compared by binade).
  template <class R>
  static bool returns_to(const Point3<R>& b, const Point3<R>& a, const Point3<R>& y) {
    const auto top = [](const Vec3<R>& v) {
      long t = std::numeric_limits<long>::min();
      for (const R* c : {&v.x, &v.y, &v.z})
        if (!CGAL::is_zero(*c)) t = std::max(t, binade(*c));
      return t;
    };
    const long back = top(b - a), step = top(b - y);
    return step != std::numeric_limits<long>::min() && (back == std::numeric_limits<long>::min() || back + 16 < step);
  }

  // Cylinder j of the exact pair and the other one, i, with their axes and squared lengths.
  PairRoles<Rational> roles(int j) { return pair_roles(exact(), j); }  // of the exact pair

  // Points of an end disc of cylinder j, for an end E of j that lies in the closed cylinder i
  // (a thin cylinder ending on or in the other, whose common interior can be a sliver of its end
  // disc, far below any rounded optimiser's reach): X = E + s w - eta A (A = j's axis pointing
  // out of j at E), with w the part orthogonal to A of a direction into i (A_i, -A_i, towards
  // i's axis), s = r_j / (4 max |w_k|) so that |s w| < r_j / 2 (X is interior to j for every
  // 0 < eta < 1), and eta = s max|w_k| / max|A_k| 2^-4k for k = 1, 2, 3: over
  // D = 4 max|w_k| max|A_k|, X = (D E + r_j max|A_k| w - r_j max|w_k| 2^-4k A) / D. Each is
  // checked exactly.
  template <class R>
  bool end_disc_witness(const CylinderPair<R>& e, int j) {
    const auto [cj, ci, Aj, Ai, AAj, AAi] = pair_roles(e, j);
    const R a_max = largest_coordinate(Aj), two(2), four(4);
    for (const bool far_end : {false, true}) {
      const Point3<R>& E = far_end ? cj.p1 : cj.p0;
      if (classify_point(E, ci) == Side::outside) continue;
      const Vec3<R> out = far_end ? Aj : Vec3<R>(-Aj);  // out of j at E
      if (deep_end_witness(E, out, ci, Ai, AAi, AAj)) return true;
      const Vec3<R> M = (ci.p0 + ci.p1) - two * E;  // 2 (m_i - E)
      const Vec3<R> towards_axis = AAi * M - dot(M, Ai) * Ai;
      for (const Vec3<R>& d : {Ai, Vec3<R>(-Ai), towards_axis}) {
        const Vec3<R> w = AAj * d - dot(d, Aj) * Aj;
        const R w_max = largest_coordinate(w);
        if (CGAL::is_zero(w_max)) continue;
        const R D = four * w_max * a_max;
        const Vec3<R> base = D * E + (cj.radius * a_max) * w, step = (cj.radius * w_max) * out;
        for (int k = 1; k <= 3; ++k)
          if (exact_overlaps(HomogeneousPoint<R>{base - ring_two_power<R>(-4 * k) * step, D})) return true;
      }
    }
    return false;
  }

  // Y + 2^-k V for the k that makes |2^-k V| a few binades below 2^depth, and 16 binades further
  // (candidates only: each point is checked exactly). Y = n / w homogeneous, in R.
  template <class R>
  bool stepped_witness(const HomogeneousPoint<R>& Y, const Vec3<R>& V, const R& VV, long depth) {
    const long k = std::max(1L, binade(VV) / 2 - depth + 4);
    for (const long shift : {k, k + 16})
      if (exact_overlaps(HomogeneousPoint<R>{Y.n + (Y.w * ring_two_power<R>(-shift)) * V, Y.w})) return true;
    return false;
  }

  // An end E of j strictly inside i: E - eta A (A out of j at E) is on j's open axis segment for
  // 0 < eta < 1 and inside i while eta |A| is below E's depth in i (depth_binade). It decides an
  // end poking 2^-100 or 2^-1000 into the other cylinder, whatever the sizes.
  template <class R>
  bool deep_end_witness(const Point3<R>& E, const Vec3<R>& out, const Cylinder<R>& ci, const Vec3<R>& Ai, const R& AAi, const R& AAj) {
    const HomogeneousPoint<R> Y{E, R(1)};
    const std::optional<long> depth = depth_binade(Y, ci, Ai, AAi);
    return depth && stepped_witness(Y, Vec3<R>(-out), AAj, *depth);
  }

  // Points of a cap disk of i strictly inside j, pushed into i (detail/cylinder_cap_disk.hpp):
  // on the cap plane through the end E (inward normal n = +-A_i), Y where j's axis line crosses
  // it, the point nearest E of the line where it meets j's mid-plane, or the point nearest E of
  // j's axis line projected orthogonally onto it (the cap plane's points nearest j's axis: where
  // a wall of j lying along the cap plane, or dipping below a cap tilted by far less than an ulp,
  // is deepest). When Y is in the open disk (|Y - E| < r_i) and strictly inside j, Y + eta n is
  // interior to both for eta |A_i| below both Y's depth in j and r_i - |Y - E| >=
  // (r_i^2 - |Y - E|^2) / (2 r_i). They decide flat cylinders whose slabs overlap only far from
  // the axes, beside a cap of one of them, and walls sunk 2^-1000 into a cap.
  // Once per query, after the corner candidates (they cost a few exact checks of large numbers,
  // which most pairs reaching the exact candidates do not need). In the ring frame when the pair
  // has one (Mpzf, homogeneous: no gcds), else on the input in Gmpq.
  bool cap_disk_candidates() {
    if (cap_disks_tried_) return false;
    cap_disks_tried_ = true;
    for (const bool rim : {false, true})
      for (const int i : {0, 1}) {
        if (out_of_time()) return false;
        if (ring() ? cap_disk_witness(ring()->pair, i, rim) : cap_disk_witness(exact(), i, rim)) return true;
      }
    return false;
  }
  // rim: the rim points (they need square roots at the input's span, or Gmpfr iterations at twice
  // it), after the others failed.
  template <class R>
  bool cap_disk_witness(const CylinderPair<R>& e, int i, bool rim) {
    const PairRoles<R> parts = pair_roles(e, 1 - i);  // (not a structured binding: the lambda below captures its parts)
    const Cylinder<R>&ci = parts.ci, &cj = parts.cj;
    const Vec3<R>&Ai = parts.Ai, &Aj = parts.Aj;
    const R&AAi = parts.AAi, &AAj = parts.AAj;
    const long ri_binade = binade(ci.radius);
    for (const bool far_end : {false, true}) {
      const Point3<R>& E = far_end ? ci.p1 : ci.p0;
      const Vec3<R> n = far_end ? Vec3<R>(-Ai) : Ai;  // into i
      // Y in the open disk, pushed into i by less than both its depth in j and its room in the disk.
      const auto try_point = [&](const HomogeneousPoint<R>& y, const std::optional<long>& depth) {
        if (!depth) return false;
        const R disk = disk_room(y, E, ci.radius);
        return disk > 0 && stepped_witness(y, n, AAi, std::min(*depth, binade(disk) - 2 * binade(y.w) - ri_binade - 1));
      };
      for (const HomogeneousPoint<R>& y : cap_disk_points(e, i, far_end, rim, input_span_bits())) {
        const std::optional<long> depth = depth_binade(y, cj, Aj, AAj);
        if (!depth) {
          // Y in the open disk on j's boundary (j's wall tangent to the cap plane, or a rim of j
          // meeting it): Y moved toward j's axis within the cap plane (cap_disk_toward_axis).
          const std::optional<HomogeneousPoint<R>> z = cap_disk_toward_axis(y, E, ci.radius, Ai, AAi, cj, Aj, AAj);
          if (z && try_point(*z, depth_binade(*z, cj, Aj, AAj))) return true;
          continue;
        }
        if (try_point(y, depth)) return true;
        // Y on the rim or just outside it (a line of j tangent to i's rim, tilted far below an
        // ulp): Y pulled toward E by about 2^(depth - 2), which keeps it inside j, and by about
        // 2^(3 depth / 4), which keeps it inside j where j's boundary is tangent to the pull (a
        // loss of about 2^(3 depth / 2) / r_j) and clears an overshoot of about 2^depth.
        const Vec3<R> radial = y.n - y.w * E;
        for (const long pull : {*depth - 2, 3 * *depth / 4}) {
          const long t = ri_binade - pull;
          if (t <= 1) continue;
          const HomogeneousPoint<R> z{y.n - ring_two_power<R>(-t) * radial, y.w};
          if (try_point(z, depth_binade(z, cj, Aj, AAj))) return true;
        }
      }
    }
    return false;
  }

  // An input-frame rational direction or point, checked exactly; decides when it proves. With a
  // ring frame the check runs there, without a gcd: D as the parallel integer direction
  // (ring_direction), X = U / q (U integers, q > 0 the least common multiple of its denominators)
  // as the homogeneous ring point n / q, n = s U, whose slacks of classify_point times powers of q
  // are polynomials in n and q (interior_slacks). Else in Gmpq. On input of
  // thousands of bits the Gmpq checks spent most of their time in gcds.
  bool exact_separates(Vec3<Rational> D) {
    ++result_.counters.directions_checked;
    ++result_.counters.exact_checks;
    last_check_ = CylinderArithmetic::exact;
    const CGAL::Sign sign = ring() ? separation_sign(ring()->pair, ring_direction(D)) : separation_sign(exact(), D);
    return sign == CGAL::POSITIVE && separated_by(std::move(D));
  }
  bool exact_overlaps(Point3<Rational> X) {
    ++result_.counters.points_checked;
    ++result_.counters.exact_checks;
    last_check_ = CylinderArithmetic::exact;
    return (ring() ? ring_strictly_inside_both(X) : strictly_inside_both(exact(), X)) && overlapping_at(std::move(X));
  }
  bool ring_strictly_inside_both(const Point3<Rational>& X) {
    const RingFrame& f = *ring();
    CGAL::Gmpz q;
    const Point3<CGAL::Mpzf> n = ring_direction(X, q).map([&f](const CGAL::Mpzf& u) {  // q X, integers
      const CGAL::Mpzf y = mpzf_times_two_power(u, f.e);
      return f.L != 1 ? CGAL::Mpzf(y * f.L_mpzf) : y;
    });
    return ring_strictly_inside_both({n, mpzf_from_integer(q)});
  }
  // The ring point n / w, w > 0, by the slacks of classify_point times powers of w (interior_slacks).
  bool ring_strictly_inside_both(const HomogeneousPoint<CGAL::Mpzf>& X) {
    const CylinderPair<CGAL::Mpzf>& d = ring()->pair;
    return interior_slacks(X, d.c0, d.A0, d.AA0) && interior_slacks(X, d.c1, d.A1, d.AA1);
  }
  // A homogeneous point of the ring frame (Mpzf) or of the input (Rational), checked exactly.
  bool exact_overlaps(const HomogeneousPoint<CGAL::Mpzf>& X) {
    ++result_.counters.points_checked;
    ++result_.counters.exact_checks;
    last_check_ = CylinderArithmetic::exact;
    const RingFrame& f = *ring();
    return ring_strictly_inside_both(X) && overlapping_at(X.n.map([&](const CGAL::Mpzf& x) { return f.to_input(x, X.w); }));
  }
  bool exact_overlaps(const HomogeneousPoint<Rational>& X) {
    return exact_overlaps(X.w == 1 ? X.n : X.n.map([&X](const Rational& q) { return Rational(q / X.w); }));
  }

  // The best point of the segment between the midpoints, X = m0 + t T / 2 with t = s1 / (s0 + s1),
  // s0 = sigma_0(m1) and s1 = sigma_1(m0) the gauges (the scale factor about each midpoint that
  // reaches the other midpoint): sigma(X) = s0 s1 / (s0 + s1), so X is interior to both whenever
  // 1/s0 + 1/s1 > 1 (the segment lower bound on phi* exceeds 1). t is computed in Gmpfr at the
  // given precision, rounded to a rational, and the point is checked exactly.
  bool segment_witness(long precision) {
    const CylinderPair<Rational>& e = exact();
    Rational t;
    {
      GmpfrPrecision scope(precision);
      using F = CGAL::Gmpfr;
      const auto f = [](const Rational& q) { return nt::from_rational<F>(q); };
      const auto gauge = [&](const Cylinder<Rational>& c, const Vec3<Rational>& A, const Rational& AA, const Vec3<Rational>& v) {
        // v = Y - m, the midpoint m of c: max(|2 v.A| / A.A, |v x A| / (r |A|)).
        const Vec3<Rational> x = cross(v, A);
        const F axial = f(abs(2 * dot(v, A)) / AA);
        const F radial = CGAL::sqrt(f(dot(x, x) / (AA * c.radius * c.radius)));
        return axial > radial ? axial : radial;
      };
      const Vec3<Rational> half = e.T / Rational(2);
      const F s0 = gauge(e.c0, e.A0, e.AA0, half), s1 = gauge(e.c1, e.A1, e.AA1, -half);
      if (!(s0 + s1 > 0)) return false;
      t = to_rational(s1 / (s0 + s1));
    }
    return exact_overlaps(e.c0.p0 + (e.A0 / Rational(2)) + t * (e.T / Rational(2)));
  }

  // A point of the open axis segment of cylinder j (interior to j) strictly inside cylinder i:
  // the parameters u in (0, 1) of X = p0_j + u A_j with 0 < (X - p0_i).A_i < A_i.A_i and
  // |(X - p0_i) x A_i|^2 < r_i^2 A_i.A_i form an open interval (a linear and a quadratic
  // condition); its midpoint, computed in Gmpfr and rounded to a rational, is checked exactly.
  // It finds the witness of a needle through the other cylinder.
  bool axis_witness(long precision, int j) {
    const auto [cj, ci, Aj, Ai, AAj, AAi] = roles(j);
    const Vec3<Rational> w = cj.p0 - ci.p0, c = cross(w, Ai), g = cross(Aj, Ai);
    Rational u;
    {
      GmpfrPrecision scope(precision);
      using F = CGAL::Gmpfr;
      const auto f = [](const Rational& q) { return nt::from_rational<F>(q); };
      F lo(0), hi(1);
      // 0 < w.A_i + u A_j.A_i < A_i.A_i
      const Rational a0 = dot(w, Ai), a1 = dot(Aj, Ai);
      if (a1 == 0) {
        if (!(a0 > 0 && a0 < AAi)) return false;
      } else {
        F u0 = f(-a0 / a1), u1 = f((AAi - a0) / a1);
        if (u1 < u0) std::swap(u0, u1);
        if (u0 > lo) lo = u0;
        if (u1 < hi) hi = u1;
      }
      // q(u) = |c|^2 - r_i^2 A_i.A_i + 2 u c.g + u^2 |g|^2 < 0
      const Rational q0 = dot(c, c) - ci.radius * ci.radius * AAi, q1 = dot(c, g), q2 = dot(g, g);
      if (q2 == 0) {
        if (!(q0 < 0)) return false;
      } else {
        const Rational disc = q1 * q1 - q0 * q2;
        if (!(disc > 0)) return false;
        const F root = CGAL::sqrt(f(disc)), Q2 = f(q2), Q1 = f(q1);
        const F r0 = (-Q1 - root) / Q2, r1 = (-Q1 + root) / Q2;
        if (r0 > lo) lo = r0;
        if (r1 < hi) hi = r1;
      }
      if (!(lo < hi)) return false;
      u = to_rational((lo + hi) / 2);
    }
    return exact_overlaps(cj.p0 + u * Aj);
  }

  // Stages gmpfr and ellipsoid, interleaved: round j runs the Gmpfr optimiser at first 2^j bits
  // (first the power of two above the input's span, up to its limit) and the ellipsoid stage at
  // 128 2^j bits. A Gmpfr round costs far less than an ellipsoid round (a few hundred Newton
  // steps in two variables against up to 18 p ellipsoid steps), so it goes first unless its
  // precision is more than four times the ellipsoid's (input spanning over 512 binades), where
  // it would cost seconds that the ellipsoid round often saves. The ellipsoid rounds go on until
  // an answer is proved (or up to a caller's limit).
  bool arbitrary_precision() {
    begin(CylinderStage::gmpfr);
    if (options_.max_precision < 0) return pass();
    if (exact_candidates() || corner_candidates(kCornerMaxPrecision) || cap_disk_candidates()) return true;
    const long span = input_span_bits();
    const long heuristic_limit = options_.max_precision > 0 ? options_.max_precision : 4 * span + 1024;
    long first = 128;
    while (first < span) first *= 2;
    long limit = options_.max_precision;  // of the ellipsoid stage; 0: none
    if (limit == 0 && !options_.prove_touching) limit = heuristic_limit;
    const CylinderPair<Rational>& e = exact();
    const bool ellipsoid_on = !(e.T.x == 0 && e.T.y == 0 && e.T.z == 0);  // T = 0 was decided by the midpoints stage
    // The corner planes left short of bits go on in every round, at up to 64 times the
    // ellipsoid's precision and at least twice the bit size of the largest input number: a rim
    // contact 2^-k deep needs about k bits, and rational input of L-bit numbers can place one
    // 2^-L deep, where the ellipsoid rounds at that precision would cost minutes.
    const long corner_number_cap = 2 * cylinder_pair_number_bits(e);
    // j stops after 128 2^48 = 2^55 bits (4 PiB a number): no machine gets there, and the
    // shifts below stay within a long.
    for (int j = 0; j < 49; ++j) {
      if (out_of_time()) break;
      const long ph = first << j, pe = 128L << j;
      const bool heuristic = ph <= heuristic_limit, complete = ellipsoid_on && (limit == 0 || pe <= limit);
      if (!heuristic && !complete) break;
      const bool gmpfr_first = ph <= 4 * pe;
      if (heuristic && gmpfr_first && gmpfr_round(ph)) return true;
      if (!out_of_time() && corner_candidates(std::max({kCornerMaxPrecision, 64 * pe, corner_number_cap}))) return true;
      if (complete && !out_of_time() && ellipsoid_round(pe)) return true;
      if (heuristic && !gmpfr_first && !out_of_time() && gmpfr_round(ph)) return true;
    }
    return pass();
  }

  void switch_stage(CylinderStage s) {
    if (stage_ == s) return;
    end();
    begin(s);
  }

  bool gmpfr_round(long precision) {
    switch_stage(CylinderStage::gmpfr);
    result_.gmpfr_precision = precision;
    if (segment_witness(precision) || axis_witness(precision, 0) || axis_witness(precision, 1)) return true;
    Vec3<Rational> D;
    Point3<Rational> X;
    {
      GmpfrPrecision scope(precision);
      const auto to_f = [](const Rational& q) { return nt::from_rational<CGAL::Gmpfr>(q); };
      const CylinderPair<CGAL::Gmpfr> g = CylinderPair<CGAL::Gmpfr>::make(exact_cylinder(0).map(to_f), exact_cylinder(1).map(to_f));
      PlaneProblem<CGAL::Gmpfr> problem(g, static_cast<int>(precision * 4 / 5));
      const PlaneMinimum<CGAL::Gmpfr> m = problem.minimise(true, static_cast<int>(precision * 3 / 5), [this] { return out_of_time(); });
      result_.counters.newton_steps += static_cast<std::uint32_t>(m.iterations);
      if (out_of_time()) return false;
      D = m.direction.map([](const CGAL::Gmpfr& x) { return to_rational(x); });
      X = m.point.map([](const CGAL::Gmpfr& x) { return to_rational(x); });
    }
    bound_by_direction(to_iv(D));
    bound_by_point(world_iv(X));
    gmpfr_direction_ = D;
    gmpfr_point_ = X;
    if (exact_separates(D) || exact_overlaps(std::move(X))) return true;
    if (options_.prove_touching && !(D.x == 0 && D.y == 0 && D.z == 0)) {
      CGAL::Gmpz two_power;
      mpz_ui_pow_ui(two_power.mpz(), 2, static_cast<unsigned long>(precision / 2));
      if (try_touching(reconstruct_direction(D, Rational(CGAL::Gmpz(1), two_power)))) return true;
    }
    return false;
  }

  // ---- stage ellipsoid ----------------------------------------------------------------------------
  // One round at p bits (detail/cylinder_ellipsoid.hpp): fast runs on the points and on the
  // directions (up to 12 p and 6 p steps), first from the last Gmpfr round's point and direction
  // (good to about half its precision) inside a ball of radius 2^-(its precision / 2), then from
  // the unit ball; then the rounded runs of the proof (p / 8 steps each). With the rounds at
  // p = 128, 256, ... it ends for every pair that does not touch; without touching proofs
  // (prove_touching off) a touching pair would never end it, so it then stops at the Gmpfr
  // stage's limit, as it does at a caller's max_precision.
  bool ellipsoid_round(long p) {
    switch_stage(CylinderStage::ellipsoid);
    result_.ellipsoid_precision = p;
    ellipsoid_problems();
    if (gmpfr_point_) point_start_ = point_problem_->coordinates(*gmpfr_point_);
    if (gmpfr_direction_) direction_start_ = direction_problem_->coordinates(*gmpfr_direction_);
    const PointProblem& points = *point_problem_;
    const DirectionProblem& directions = *direction_problem_;
    const long warm = result_.gmpfr_precision / 2;
    if (point_start_ && p > warm && point_run(points, EllipsoidMode::fast, p, 12 * p, &*point_start_, warm)) return true;
    if (direction_start_ && p > warm && !out_of_time() && direction_run(directions, EllipsoidMode::fast, p, 6 * p, &*direction_start_, warm))
      return true;
    return (!out_of_time() && point_run(points, EllipsoidMode::fast, p, 12 * p)) ||
           (!out_of_time() && direction_run(directions, EllipsoidMode::fast, p, 6 * p)) ||
           (!out_of_time() && point_run(points, EllipsoidMode::rounded, p, p / 8)) ||
           (!out_of_time() && direction_run(directions, EllipsoidMode::rounded, p, p / 8));
  }

  // The frames fitted to the slab and tube bounds for input spanning over 256 binades, where they
  // make thin targets fat; the ball and disc frames otherwise.
  void ellipsoid_problems() {
    if (point_problem_) return;
    integer_pair();
    const bool fitted = input_span_bits() > 256;
    point_problem_.emplace(*integer_, fitted);
    direction_problem_.emplace(*integer_, fitted);
  }

  // Before the touching and Gmpfr stages, for input spanning over 256 binades, in this order:
  // 1. the exact candidates (they decide crossing walls at any distance from touching, cheaply),
  //    the axis and segment witnesses of the Gmpfr rounds at the input's span plus 128 bits (a
  //    needle through the other cylinder: the interval of its axis inside the other is about
  //    2^-span of its length), and the corner candidates up to 1,024 bits (stage gmpfr);
  // 2. when the pair has a ring frame, the touching proofs (stage touching_exact);
  // 3. the corner candidates up to 4,096 bits, from where 1,024 stopped them;
  // 4. short fast runs of the point and direction searches (128 bits, 24 steps each) in the
  //    frames of the pair's slab and tube bounds (detail/cylinder_ellipsoid.hpp). A needle
  //    crossing a pancake overlaps in a region those frames make fat, and a needle's separating
  //    directions form a set they make fat: the runs find a certificate in a few steps, where
  //    the Gmpfr stage would spend tens or hundreds of milliseconds.
  // Steps 3 and 4 cannot decide a touching pair, so its proofs come before them: a touching
  // pair costs the candidates to 1,024 bits and its proof, and a sliver (an overlap or gap 2^-800
  // thin, for which the candidates need up to 3,000 bits) pays for failed touching proofs.
  // Without a ring frame (rational input whose denominators' lcm exceeds 4,096 bits) the proofs
  // run in Gmpq and cost several times the candidates (their gcds), so there they keep their
  // place after step 4.
  bool ellipsoid_probe() {
    if (input_span_bits() <= 256) return false;
    const CylinderPair<Rational>& e = exact();
    if (e.T.x == 0 && e.T.y == 0 && e.T.z == 0) return false;
    begin(CylinderStage::gmpfr);
    if (exact_candidates() || (!out_of_time() && axis_candidates()) || corner_candidates(kCornerFirstCap)) return true;
    if (ring() && !out_of_time() && touching_exact()) return true;
    begin(CylinderStage::gmpfr);
    if (corner_candidates(kCornerMaxPrecision) || cap_disk_candidates()) return true;
    if (out_of_time()) return pass();
    switch_stage(CylinderStage::ellipsoid);
    result_.ellipsoid_precision = 128;
    ellipsoid_problems();
    return point_run(*point_problem_, EllipsoidMode::fast, 128, 24) ||
           (!out_of_time() && direction_run(*direction_problem_, EllipsoidMode::fast, 128, 24)) || pass();
  }

  // The Gmpfr rounds' axis and segment witnesses (checked exactly) at one precision.
  bool axis_candidates() {
    const long p = input_span_bits() + 128;
    return axis_witness(p, 0) || axis_witness(p, 1) || segment_witness(p);
  }

  bool point_run(const PointProblem& points, EllipsoidMode mode, long p, long steps, const std::array<Rational, 3>* start = nullptr,
                 long j = 0) {
    return run_ellipsoid<3>(mode, p, steps, result_.counters.ellipsoid_steps,
                            [&](const DyadicVector<3>& y, long bits) -> std::optional<EllipsoidCut<3>> {
                              std::optional<EllipsoidCut<3>> k = points.cut(y, bits);
                              if (k) return k;
                              Point3<Rational> X = points.point(y);
                              bound_by_point(world_iv(X));
                              if (exact_overlaps(std::move(X))) return std::nullopt;
                              return EllipsoidCut<3>{};  // not reached (cut() checked the same constraints): ends the run
                            },
                            start, j, [this] { return out_of_time(); });
  }

  // Rounded runs refine the minorant until it cuts the centre off by more than 2^(-p/4) below
  // 1, as their proof needs, with no cap on its precision: it converges to phi(D_y) >= 1, so the
  // loop ends (detail/cylinder_ellipsoid.hpp, "Termination").
  bool direction_run(const DirectionProblem& directions, EllipsoidMode mode, long p, long steps,
                     const std::array<Rational, 2>* start = nullptr, long j = 0) {
    return run_ellipsoid<2>(mode, p, steps, result_.counters.ellipsoid_steps,
                            [&](const DyadicVector<2>& y, long bits) -> std::optional<EllipsoidCut<2>> {
                              long sigma = 0;
                              const Vec3<CGAL::Gmpz> Ds = directions.direction(y, sigma);
                              if (separation_sign(integer_pair(), Ds) == CGAL::POSITIVE) {
                                Vec3<Rational> D = Ds.map([](const CGAL::Gmpz& x) { return Rational(x); });
                                bound_by_direction(to_iv(D));
                                if (exact_separates(std::move(D))) return std::nullopt;
                                return EllipsoidCut<2>{};  // not reached: ends the run
                              }
                              if (mode == EllipsoidMode::fast) return directions.minorant_cut(Ds, sigma, bits);
                              bool cuts_off = false;
                              for (long b = bits;; b *= 2) {
                                EllipsoidCut<2> k = directions.minorant_cut(Ds, sigma, b, p / 4, &cuts_off);
                                if (cuts_off) return k;
                              }
                            },
                            start, j, [this] { return out_of_time(); });
  }

  const CylinderPair<CGAL::Gmpz>& integer_pair() {
    if (!integer_) integer_.emplace(exact());
    return integer_->d;
  }

  CylinderCylinderOptions options_;
  std::optional<Clock::time_point> deadline_;  // options_.time_limit_seconds after run() began
  // The exact input: the caller's Rational cylinders (they outlive the solver, which lives in
  // one call), or the converted double input, built when first needed.
  std::array<const Cylinder<Rational>*, 2> input_{nullptr, nullptr};
  std::array<std::optional<Cylinder<Rational>>, 2> converted_input_;
  std::array<std::optional<Cylinder<double>>, 2> double_input_;
  bool binary64_ = false;     // every input number is a binary64 value
  bool world_exact_ = false;  // the world frame is an exact scaling of the input
  bool static_ok_ = false;    // ... and the filter's guards hold
  int world_exponent_ = 0;    // world = 2^world_exponent_ input
  double world_scale_ = 1;    // 2^world_exponent_
  StaticPair stat_;
  CylinderPair<double> dbl_;  // world frame (nearest values when not binary64_)
  std::optional<CylinderPair<Interval>> iv_;
  std::optional<CylinderPair<Rational>> ex_;
  std::optional<long> span_bits_;  // input_span_bits()
  std::optional<IntegerPair> integer_;  // the input scaled to integers (ellipsoid stage)
  std::optional<Vec3<Rational>> gmpfr_direction_;  // the last Gmpfr round's direction and point
  std::optional<Point3<Rational>> gmpfr_point_;
  std::optional<PointProblem> point_problem_;  // the ellipsoid stage's problems, and warm starts
  std::optional<DirectionProblem> direction_problem_;
  std::optional<std::array<Rational, 3>> point_start_;
  std::optional<std::array<Rational, 2>> direction_start_;
  std::optional<RingFrame> ring_;  // ring()
  bool ring_tried_ = false;
  long corner_cap_ = 0;          // the highest precision cap corner_candidates() ran with
  struct CornerResume {          // where that cap stopped the planes of cylinder i
    std::variant<Point3<Rational>, Point3<CGAL::Mpzf>> y;  // in the frame of the planes
    int pass;
    long precision, needed;
  };
  std::array<std::optional<CornerResume>, 2> corner_resume_;
  bool touching_tried_ = false;  // touching_exact() ran
  bool exact_candidates_tried_ = false;
  bool cap_disks_tried_ = false;
  std::optional<CylinderPair<dd_real>> dd_pair_;  // world_pair<dd_real>() of rational input
  std::optional<Vec3<double>> optimum_;
  std::optional<Point3<double>> optimum_point_;
  double optimum_value_ = std::numeric_limits<double>::infinity();
  std::optional<Vec3<Rational>> refined_;  // the refine stage's direction, exactly
  double phi_lower_ = 0;
  std::optional<double> phi_upper_;
  bool coincident_ = false;
  CylinderArithmetic last_check_ = CylinderArithmetic::none;
  CylinderCylinderResult result_;
  CylinderStage stage_ = CylinderStage::midpoints;
  Clock::time_point start_;
  bool started_ = false;
};

// The enclosures of the quick path's answers, from QuickSeparation's bounds (bounds asked for):
// the upper bound of phi* from T; the lower bound from the segment between the midpoints for a
// separated pair, or from the witness X (phi_lower_from_sigma, with sigma_upper >= sigma(X)) for
// an overlapping one.
inline CylinderGap quick_gap_separated(const QuickSeparation& q) {
  if (q.phi_lower > 0 && std::isfinite(q.phi_upper)) return {true, q.phi_lower, q.phi_upper};
  return {};
}
inline CylinderGap quick_gap_overlapping(const QuickSeparation& q, double sigma_upper) {
  const double lower = phi_lower_from_sigma(sigma_upper);
  if (std::isfinite(q.phi_upper) && lower > 0) return {true, lower, q.phi_upper};
  return {};
}

// The quick path's overlap: the r0:r1 division point of the closest points of the axis segments,
// then their midpoint, proved strictly inside both by detail/cylinder_quick_filter.hpp. Fills the
// answer's own fields (quick_answer the common ones) and sigma_upper, quick_point's bound of the
// witness's scale.
inline bool quick_overlap(const Cylinder<double>& c0, const Cylinder<double>& c1, double w, const CylinderCylinderOptions& options,
                          CylinderCylinderResult& r, double& sigma_upper) {
  // Closest points of the axes inset by half a radius from the caps: the division point then
  // lies off the cap planes (it decides about four overlapping random pairs in five).
  const Vec3<double> A0 = c0.p1 - c0.p0, A1 = c1.p1 - c1.p0;
  const double i0 = std::min(0.5, 0.5 * c0.radius / std::sqrt(dot(A0, A0)));
  const double i1 = std::min(0.5, 0.5 * c1.radius / std::sqrt(dot(A1, A1)));
  const auto [a0, a1] = closest_segment_points(c0.p0, A0, c1.p0, A1, i0, i1);
  Point3<double> X = a0 + (c0.radius / (c0.radius + c1.radius)) * (a1 - a0);
  QuickPoint p = quick_point(c0, c1, w, X);
  std::uint32_t points = 1;
  if (!p.inside) {
    X = 0.5 * (a0 + a1);
    p = quick_point(c0, c1, w, X);
    ++points;
  }
  if (!p.inside) return false;
  r.answer = Answer::overlapping;
  r.witness_binary64 = X;
  if (options.rational_certificates) r.witness = X.map([](double x) { return Rational(x); });
  r.counters.points_checked = points;
  sigma_upper = p.sigma_upper;
  return true;
}

// The quick path: binary64 input, and the direction Delta proved to separate, or a cheap point
// proved interior (quick_overlap), by the static filters of detail/cylinder_quick_filter.hpp.
// Returns false, leaving r untouched, when that does not apply (invalid, non-finite or extreme
// input included: the caller validates afterwards) or does not decide; the solver then runs
// from the start. The gap enclosure as options.gap_enclosure says (GapEnclosure).
inline bool quick_answer(const Cylinder<double>& c0, const Cylinder<double>& c1, const CylinderCylinderOptions& options,
                         CylinderCylinderResult& r) {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = options.time_stages ? Clock::now() : Clock::time_point{};
  if (options.refine_gap && options.gap_enclosure != GapEnclosure::off) return false;  // the ranked fast path instead
  if (!(c0.radius > 0 && c1.radius > 0)) return false;
  // The frame (cylinder_quick_filter.hpp): w = 2^k with every number below 2w in magnitude; 0
  // for non-finite or extreme input.
  const double w = quick_frame(c0, c1);
  if (w == 0) return false;
  const bool in_query = options.gap_enclosure == GapEnclosure::in_query;
  QuickSeparation q;
  double sigma_upper = 0;
  if (quick_separation(c0, c1, w, in_query, q)) {
    r.answer = Answer::separated;
    r.direction_binary64 = q.direction;
    if (options.rational_certificates) r.direction = q.direction.map([](double x) { return Rational(x); });
    if (in_query) r.gap_ = quick_gap_separated(q);
  } else if (quick_overlap(c0, c1, w, options, r, sigma_upper)) {
    if (in_query) r.gap_ = quick_gap_overlapping(q, sigma_upper);
  } else {
    return false;
  }
  r.stage = CylinderStage::fast_path;
  r.certified_by = CylinderArithmetic::static_filter;
  r.counters.directions_checked = 1;
  r.counters.static_decisions = 1;
  if (options.gap_enclosure == GapEnclosure::on_access) {
    r.quick_gap_ = true;
    r.quick_input_[0] = c0;
    r.quick_input_[1] = c1;
  }
  if (options.time_stages)
    r.stage_seconds[static_cast<std::size_t>(CylinderStage::fast_path)] = std::chrono::duration<double>(Clock::now() - start).count();
  return true;
}

// The enclosure of an answer of the quick path, from its input (GapEnclosure::on_access): the
// same numbers as GapEnclosure::in_query gives.
inline CylinderGap quick_gap(const Cylinder<double>& c0, const Cylinder<double>& c1, Answer answer,
                             const std::optional<Point3<double>>& witness) {
  const double w = quick_frame(c0, c1);
  QuickSeparation q;
  quick_separation(c0, c1, w, true, q);
  if (answer == Answer::separated) return quick_gap_separated(q);
  if (witness) return quick_gap_overlapping(q, quick_point(c0, c1, w, *witness).sigma_upper);
  return {};
}

}  // namespace detail

inline CylinderGap CylinderCylinderResult::gap() const {
  return quick_gap_ ? detail::quick_gap(quick_input_[0], quick_input_[1], answer, witness_binary64) : gap_;
}

// The certified test-intersection of two cylinders (header comment). Throws InvalidInput on an
// invalid cylinder (field "a" or "b").
inline CylinderCylinderResult certified_cylinder_cylinder(const Cylinder<Rational>& a, const Cylinder<Rational>& b,
                                                          const CylinderCylinderOptions& options = {}) {
  // validate(), with the common valid case decided without temporaries.
  const auto fine = [](const Cylinder<Rational>& c) {
    return mpq_sgn(c.radius.mpq()) > 0 &&
           !(mpq_equal(c.p0.x.mpq(), c.p1.x.mpq()) && mpq_equal(c.p0.y.mpq(), c.p1.y.mpq()) && mpq_equal(c.p0.z.mpq(), c.p1.z.mpq()));
  };
  if (!fine(a)) validate(a, "a");
  if (!fine(b)) validate(b, "b");
  // Binary64 input (the common case) first tries the quick path.
  bool binary64 = true;
  const auto to_d = [&binary64](const Rational& q) {
    double d = 0;
    if (binary64 && !detail::exact_double(q, d)) binary64 = false;
    return d;
  };
  const Cylinder<double> da = a.map(to_d), db = b.map(to_d);
  CylinderCylinderResult r;
  if (binary64 && detail::quick_answer(da, db, options, r)) return r;
  r = detail::CylinderCylinderSolver(a, b, options).run();
  return r;
}

// The same for binary64 input, each double taken as the exact rational it denotes (no rounding
// anywhere); faster, since the rational input is built only when an exact stage needs it.
inline CylinderCylinderResult certified_cylinder_cylinder(const Cylinder<double>& a, const Cylinder<double>& b,
                                                          const CylinderCylinderOptions& options = {}) {
  CylinderCylinderResult r;
  if (detail::quick_answer(a, b, options, r)) return r;  // valid input only
  // The messages of every other query and of the command ("a.radius: must be positive, got -1").
  validate(a, "a");
  validate(b, "b");
  r = detail::CylinderCylinderSolver(a, b, options).run();
  return r;
}

}  // namespace certcyl
