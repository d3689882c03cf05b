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
// Certificates (all exact rationals, each checked exactly; see detail/cylinder_certificates.hpp):
//   separated    direction D with phi(D) < D.Delta (sign of sqrt(p) + sqrt(q) + c by squaring);
//   overlapping  witness point strictly inside both (the polynomial point-in-cylinder test);
//   touching     contact: normal D with phi(D) = D.Delta exactly, and a point in both closed
//                cylinders, with the features that meet (cap, wall, rim; detail/cylinder_touching.hpp).
//
// Stages, in order; the first that proves an answer decides (result.stage):
//   midpoints        Delta = 0: the common midpoint is interior to both.
//   fast_path        cheap candidates, evaluated in double: directions A0, A1, A0 x A1, Delta and
//                    its parts orthogonal to each axis; points m0, m1, the closest points of the
//                    axis segments, their midpoint and their r0:r1 division point. The best
//                    direction and the best point are checked in intervals, then in Gmpq.
//   optimiser        smoothed Newton in double on the plane D.Delta = 1 (detail/cylinder_optimiser.hpp),
//                    giving a direction and a dual point, checked in intervals then in Gmpq.
//   touching_exact   rational candidate normals (A0, A1, A0 x A1, the parts of Delta orthogonal to
//                    the axes, the exact rim-wall and rim-rim normals of
//                    detail/cylinder_rim_contacts.hpp, a small-height rational reconstruction of
//                    the optimiser's direction), each proved or rejected exactly.
//   gmpfr            the optimiser at 128, 256, ... bits up to options.max_precision; its direction
//                    and point, converted exactly to rationals, are checked in Gmpq, and its
//                    direction is reconstructed as a candidate normal for a touching proof.
// Undecided results carry the certified bounds phi_lower <= phi* <= phi_upper, so
// |phi* - 1| <= distance_bound().
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

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string_view>

#include "certcyl/answer.hpp"
#include "certcyl/certified/detail/cylinder_certificates.hpp"
#include "certcyl/certified/detail/cylinder_optimiser.hpp"
#include "certcyl/certified/detail/cylinder_touching.hpp"
#include "certcyl/errors.hpp"
#include "certcyl/primitives.hpp"

namespace certcyl {

enum class CylinderStage { midpoints, fast_path, optimiser, touching_exact, gmpfr, none };
inline constexpr std::size_t kCylinderStages = 5;  // stages that can decide (none excluded)

inline constexpr std::string_view to_string(CylinderStage s) {
  switch (s) {
    case CylinderStage::midpoints: return "midpoints";
    case CylinderStage::fast_path: return "fast_path";
    case CylinderStage::optimiser: return "optimiser";
    case CylinderStage::touching_exact: return "touching_exact";
    case CylinderStage::gmpfr: return "gmpfr";
    case CylinderStage::none: return "none";
  }
  return "none";
}

struct CylinderCylinderOptions {
  // The Gmpfr stage runs at 128, 256, ... bits while the precision is at most this; 0 skips it.
  long max_precision = 1024;
  // Try the exact touching proofs (stages touching_exact and the reconstruction in gmpfr).
  bool prove_touching = true;
  // Compute the certified enclosure of phi* (costs two interval evaluations on the fast path).
  bool gap_enclosure = true;
};

struct CylinderCylinderCounters {
  std::uint32_t directions_checked = 0;   // candidate directions given to the certified check
  std::uint32_t points_checked = 0;       // candidate points given to the certified check
  std::uint32_t exact_checks = 0;         // checks the intervals could not decide, rerun in Gmpq
  std::uint32_t newton_steps = 0;         // optimiser steps, all precisions
  std::uint32_t touching_candidates = 0;  // candidate normals given to the touching proof
};

struct CylinderCylinderResult {
  Answer answer = Answer::undecided;
  CylinderStage stage = CylinderStage::none;

  // separated: phi(D) < D.Delta. touching: the contact normal. Exact.
  std::optional<Vec3<Rational>> direction;
  // overlapping: a point interior to both. touching: a common point. Exact.
  std::optional<Point3<Rational>> witness;
  // touching only: the features that meet, the normal and a common point.
  std::optional<CylinderContact> contact;

  // Certified phi_lower <= phi* <= phi_upper and log_gap_lower <= log(phi*) <= log_gap_upper.
  // gap_known is false when Delta = 0 (phi* is undefined: the cylinders overlap at every scale)
  // or when options.gap_enclosure is off; the four numbers are then meaningless.
  bool gap_known = false;
  double phi_lower = 0, phi_upper = 0, log_gap_lower = 0, log_gap_upper = 0;

  long gmpfr_precision = 0;  // highest Gmpfr precision used, 0 if none
  CylinderCylinderCounters counters;
  std::array<double, kCylinderStages> stage_seconds{};  // indexed by CylinderStage

  // A certified bound on |phi* - 1| (meaningful when gap_known).
  double distance_bound() const { return std::max(phi_upper - 1, 1 - phi_lower); }
};

namespace detail {

inline Rational to_rational(const CGAL::Gmpfr& x) {
  Rational q;
  mpfr_get_q(q.mpq(), x.fr());
  return q;
}

inline double round_down(double x) { return std::nextafter(x, -std::numeric_limits<double>::infinity()); }
inline double round_up(double x) { return std::nextafter(x, std::numeric_limits<double>::infinity()); }

// Closest points of the segments [a0, a0 + e0] and [a1, a1 + e1] (double; candidates only).
inline std::pair<Point3<double>, Point3<double>> closest_segment_points(const Point3<double>& a0, const Vec3<double>& e0,
                                                                         const Point3<double>& a1, const Vec3<double>& e1) {
  const Vec3<double> w = a0 - a1;
  const double a = dot(e0, e0), b = dot(e0, e1), c = dot(e1, e1), d = dot(e0, w), e = dot(e1, w);
  const double den = a * c - b * b;
  double s;
  if (den > 1e-12 * a * c) {
    s = std::clamp((b * e - c * d) / den, 0.0, 1.0);
  } else {
    // else: (nearly) parallel axes; the middle of the overlap of their parameter ranges on
    // segment 0 keeps the candidate away from the caps.
    double t0 = -d / a, t1 = (b - d) / a;
    if (t1 < t0) std::swap(t0, t1);
    s = std::clamp(0.5 * (std::max(t0, 0.0) + std::min(t1, 1.0)), 0.0, 1.0);
  }
  const double t = std::clamp((b * s + e) / c, 0.0, 1.0);
  s = std::clamp((b * t - d) / a, 0.0, 1.0);
  return {a0 + s * e0, a1 + t * e1};
}

class CylinderCylinderSolver {
 public:
  CylinderCylinderSolver(const Cylinder<Rational>& c0, const Cylinder<Rational>& c1, const CylinderCylinderOptions& options)
      : options_(options), exact_input_{c0, c1} {
    const auto to_d = [](const Rational& q) { return nearest_double(q); };
    const auto to_i = [](const Rational& q) { return enclose_interval(q); };
    dbl_ = CylinderPair<double>::make(c0.map(to_d), c1.map(to_d));
    make_interval(c0.map(to_i), c1.map(to_i));
  }

  // Every double is exact: the rational input is built only if an exact stage needs it.
  CylinderCylinderSolver(const Cylinder<double>& c0, const Cylinder<double>& c1, const CylinderCylinderOptions& options)
      : options_(options), double_input_{c0, c1} {
    dbl_ = CylinderPair<double>::make(c0, c1);
    const auto to_i = [](double x) { return Interval(x); };
    make_interval(c0.map(to_i), c1.map(to_i));
  }

  CylinderCylinderResult run() {
    if (midpoints()) return finish();
    if (fast_path()) return finish();
    if (optimiser()) return finish();
    if (options_.prove_touching && touching_exact()) return finish();
    if (gmpfr()) return finish();
    result_.stage = CylinderStage::none;
    return finish();
  }

 private:
  using Clock = std::chrono::steady_clock;

  // ---- stage bookkeeping ----------------------------------------------------------------------
  // One clock reading per stage boundary: a stage starts when the previous one ends.
  void begin(CylinderStage s) {
    stage_ = s;
    if (!started_) start_ = Clock::now(), started_ = true;
  }
  void end() {
    const Clock::time_point now = Clock::now();
    result_.stage_seconds[static_cast<std::size_t>(stage_)] += std::chrono::duration<double>(now - start_).count();
    start_ = now;
  }
  bool decide(Answer a) {
    end();
    result_.answer = a;
    result_.stage = stage_;
    return true;
  }
  bool pass() {
    end();
    return false;
  }

  CylinderCylinderResult finish() {
    if (result_.answer == Answer::touching) {
      result_.phi_lower = result_.phi_upper = 1;
      result_.log_gap_lower = result_.log_gap_upper = 0;
      result_.gap_known = true;
    } else if (options_.gap_enclosure && !coincident_ && phi_upper_ && phi_lower_ > 0) {
      result_.gap_known = true;
      result_.phi_lower = phi_lower_;
      result_.phi_upper = *phi_upper_;
      // std::log is within one ulp; two steps outward make the enclosure safe.
      result_.log_gap_lower = round_down(round_down(std::log(phi_lower_)));
      result_.log_gap_upper = round_up(round_up(std::log(*phi_upper_)));
    }
    return result_;
  }

  // ---- inputs in each number type ---------------------------------------------------------------
  void make_interval(const Cylinder<Interval>& c0, const Cylinder<Interval>& c1) {
    CGAL::Protect_FPU_rounding<true> upward;
    iv_ = CylinderPair<Interval>::make(c0, c1);
  }

  const Cylinder<Rational>& exact_cylinder(int i) {
    if (!exact_input_[0]) {
      const auto to_q = [](double x) { return Rational(x); };
      exact_input_[0] = double_input_[0]->map(to_q);
      exact_input_[1] = double_input_[1]->map(to_q);
    }
    return *exact_input_[i];
  }

  const CylinderPair<Rational>& exact() {
    if (!ex_) ex_ = CylinderPair<Rational>::make(exact_cylinder(0), exact_cylinder(1));
    return *ex_;
  }

  // ---- certified checks: intervals first, Gmpq when they cannot decide --------------------------
  CGAL::Sign check_direction(const Vec3<double>& D) {
    ++result_.counters.directions_checked;
    const auto s = interval_attempt([&] { return separation_sign(iv_, D.map([](double x) { return Interval(x); })); });
    if (s) return *s;
    ++result_.counters.exact_checks;
    return separation_sign(exact(), D.map([](double x) { return Rational(x); }));
  }

  bool check_point(const Point3<double>& X) {
    ++result_.counters.points_checked;
    const auto s = interval_attempt([&] { return strictly_inside_both(iv_, X.map([](double x) { return Interval(x); })); });
    if (s) return *s;
    ++result_.counters.exact_checks;
    return strictly_inside_both(exact(), X.map([](double x) { return Rational(x); }));
  }

  // ---- certified bounds on phi* ------------------------------------------------------------------
  void bound_by_direction(const Vec3<Interval>& D) {
    if (!options_.gap_enclosure) return;
    CGAL::Protect_FPU_rounding<true> upward;
    const std::optional<Interval> r = ratio_enclosure(iv_, D);
    if (r && (!phi_upper_ || r->sup() < *phi_upper_)) phi_upper_ = r->sup();
  }
  void bound_by_point(const Point3<Interval>& X) {
    if (!options_.gap_enclosure) return;
    CGAL::Protect_FPU_rounding<true> upward;
    const Interval s = scale_enclosure(iv_, X);
    if (!(s.sup() > 0)) return;
    const double lower = (Interval(1) / Interval(s.sup())).inf();
    if (lower > phi_lower_) phi_lower_ = lower;
  }
  static Vec3<Interval> to_iv(const Vec3<double>& v) {
    return v.map([](double x) { return Interval(x); });
  }
  static Vec3<Interval> to_iv(const Vec3<Rational>& v) {
    return v.map([](const Rational& x) { return enclose_interval(x); });
  }

  // ---- the answers ------------------------------------------------------------------------------
  bool separated_by(Vec3<Rational> D) {
    result_.direction = std::move(D);
    return decide(Answer::separated);
  }
  bool overlapping_at(Point3<Rational> X) {
    result_.witness = std::move(X);
    return decide(Answer::overlapping);
  }
  bool touching_with(CylinderContact c) {
    result_.direction = c.normal;
    result_.witness = c.point;
    result_.contact = std::move(c);
    return decide(Answer::touching);
  }

  // ---- stage midpoints ----------------------------------------------------------------------------
  bool midpoints() {
    begin(CylinderStage::midpoints);
    const auto zero = interval_attempt([&] { return sign_is(iv_.T.x, CGAL::ZERO) && sign_is(iv_.T.y, CGAL::ZERO) && sign_is(iv_.T.z, CGAL::ZERO); });
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
    if (!strictly_inside_both(exact(), m)) return pass();
    return overlapping_at(std::move(m));
  }

  // ---- stage fast_path ------------------------------------------------------------------------------
  double ratio_double(const Vec3<double>& D) const {
    const double dt = std::abs(dot(D, dbl_.T));
    if (!(dt > 0)) return std::numeric_limits<double>::infinity();
    const double phi2 = std::abs(dot(D, dbl_.A0)) + std::abs(dot(D, dbl_.A1)) +
                        2 * dbl_.c0.radius * std::sqrt(squared_norm(cross(D, dbl_.A0)) / dbl_.AA0) +
                        2 * dbl_.c1.radius * std::sqrt(squared_norm(cross(D, dbl_.A1)) / dbl_.AA1);
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

  bool fast_path() {
    begin(CylinderStage::fast_path);
    const CylinderPair<double>& d = dbl_;
    const std::array<Vec3<double>, 6> directions{d.A0,
                                                 d.A1,
                                                 cross(d.A0, d.A1),
                                                 d.T,
                                                 d.AA0 * d.T - dot(d.A0, d.T) * d.A0,
                                                 d.AA1 * d.T - dot(d.A1, d.T) * d.A1};
    std::size_t best_d = 0;
    double best_ratio = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < directions.size(); ++i) {
      const double r = ratio_double(directions[i]);
      if (r < best_ratio) best_ratio = r, best_d = i;
    }
    if (best_ratio < 1) {
      const Vec3<double>& D = directions[best_d];
      bound_by_direction(to_iv(D));
      if (check_direction(D) == CGAL::POSITIVE) {
        bound_by_point(to_iv(cheap_points()[0]));
        return separated_by(D.map([](double x) { return Rational(x); }));
      }
    }
    const std::array<Point3<double>, 5> points = cheap_points();
    std::size_t best_p = 0;
    double best_scale = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < points.size(); ++i) {
      const double s = scale_double(points[i]);
      if (s < best_scale) best_scale = s, best_p = i;
    }
    if (best_scale < 1) {
      const Point3<double>& X = points[best_p];
      bound_by_point(to_iv(X));
      if (check_point(X)) {
        bound_by_direction(to_iv(directions[best_d]));
        return overlapping_at(X.map([](double x) { return Rational(x); }));
      }
    }
    return pass();
  }

  // m0, m1, the closest points c0, c1 of the axis segments, their midpoint, their r0:r1 point.
  std::array<Point3<double>, 5> cheap_points() const {
    const CylinderPair<double>& d = dbl_;
    const auto [c0, c1] = closest_segment_points(d.c0.p0, d.A0, d.c1.p0, d.A1);
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
    bound_by_direction(to_iv(m.direction));
    bound_by_point(to_iv(m.point));
    if (std::isfinite(m.value) && m.value < 1 && check_direction(m.direction) == CGAL::POSITIVE)
      return separated_by(m.direction.map([](double x) { return Rational(x); }));
    if (scale_double(m.point) < 1 && check_point(m.point))
      return overlapping_at(m.point.map([](double x) { return Rational(x); }));
    return pass();
  }

  // ---- stage touching_exact -----------------------------------------------------------------------------
  bool try_touching(const Vec3<Rational>& D) {
    // Interval pre-filter: the proof needs phi2(D) = |D.T| exactly, so skip D when the interval
    // enclosure of their ratio excludes 1.
    {
      CGAL::Protect_FPU_rounding<true> upward;
      const std::optional<Interval> r = ratio_enclosure(iv_, to_iv(D));
      if (r && (r->inf() > 1 || r->sup() < 1)) return false;
    }
    ++result_.counters.touching_candidates;
    std::optional<CylinderContact> c = prove_touching(exact(), D);
    if (!c) return false;
    return touching_with(std::move(*c));
  }

  bool touching_exact() {
    begin(CylinderStage::touching_exact);
    const CylinderPair<Rational>& e = exact();
    const std::array<Vec3<Rational>, 5> structural{e.A0, e.A1, cross(e.A0, e.A1), e.AA0 * e.T - dot(e.A0, e.T) * e.A0,
                                                   e.AA1 * e.T - dot(e.A1, e.T) * e.A1};
    for (const Vec3<Rational>& D : structural)
      if (try_touching(D)) return true;
    // Rim-wall and rim-rim normals, exactly (detail/cylinder_rim_contacts.hpp).
    for (const Vec3<Rational>& D : rim_contact_normals(e))
      if (try_touching(D)) return true;
    if (optimum_) {
      const Vec3<Rational> D = optimum_->map([](double x) { return Rational(x); });
      if (!(D.x == 0 && D.y == 0 && D.z == 0) && try_touching(reconstruct_direction(D, Rational(1, 1 << 20)))) return true;
    }
    return pass();
  }

  // ---- stage gmpfr --------------------------------------------------------------------------------------
  bool gmpfr() {
    begin(CylinderStage::gmpfr);
    for (long precision = 128; precision <= options_.max_precision; precision *= 2) {
      result_.gmpfr_precision = precision;
      Vec3<Rational> D;
      Point3<Rational> X;
      {
        GmpfrPrecision scope(precision);
        const auto to_f = [](const Rational& q) { return nt::from_rational<CGAL::Gmpfr>(q); };
        const CylinderPair<CGAL::Gmpfr> g = CylinderPair<CGAL::Gmpfr>::make(exact_cylinder(0).map(to_f), exact_cylinder(1).map(to_f));
        PlaneProblem<CGAL::Gmpfr> problem(g, static_cast<int>(precision * 4 / 5));
        const PlaneMinimum<CGAL::Gmpfr> m = problem.minimise(true, static_cast<int>(precision * 3 / 5));
        result_.counters.newton_steps += static_cast<std::uint32_t>(m.iterations);
        D = m.direction.map([](const CGAL::Gmpfr& x) { return to_rational(x); });
        X = m.point.map([](const CGAL::Gmpfr& x) { return to_rational(x); });
      }
      bound_by_direction(to_iv(D));
      bound_by_point(to_iv(X));
      ++result_.counters.directions_checked;
      ++result_.counters.exact_checks;
      if (separation_sign(exact(), D) == CGAL::POSITIVE) return separated_by(std::move(D));
      ++result_.counters.points_checked;
      ++result_.counters.exact_checks;
      if (strictly_inside_both(exact(), X)) return overlapping_at(std::move(X));
      if (options_.prove_touching && !(D.x == 0 && D.y == 0 && D.z == 0)) {
        CGAL::Gmpz two_power;
        mpz_ui_pow_ui(two_power.mpz(), 2, static_cast<unsigned long>(precision / 2));
        if (try_touching(reconstruct_direction(D, Rational(CGAL::Gmpz(1), two_power)))) return true;
      }
    }
    return pass();
  }

  CylinderCylinderOptions options_;
  std::array<std::optional<Cylinder<Rational>>, 2> exact_input_;
  std::array<std::optional<Cylinder<double>>, 2> double_input_;
  CylinderPair<double> dbl_;
  CylinderPair<Interval> iv_;
  std::optional<CylinderPair<Rational>> ex_;
  std::optional<Vec3<double>> optimum_;
  double phi_lower_ = 0;
  std::optional<double> phi_upper_;
  bool coincident_ = false;
  CylinderCylinderResult result_;
  CylinderStage stage_ = CylinderStage::midpoints;
  Clock::time_point start_;
  bool started_ = false;
};

}  // namespace detail

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
  return detail::CylinderCylinderSolver(a, b, options).run();
}

// The same for binary64 input, each double taken as the exact rational it denotes (no rounding
// anywhere); faster, since the rational input is built only when an exact stage needs it.
inline CylinderCylinderResult certified_cylinder_cylinder(const Cylinder<double>& a, const Cylinder<double>& b,
                                                          const CylinderCylinderOptions& options = {}) {
  const auto check = [](const Cylinder<double>& c, const std::string& field) {
    for (double x : {c.p0.x, c.p0.y, c.p0.z, c.p1.x, c.p1.y, c.p1.z, c.radius})
      if (!std::isfinite(x)) throw InvalidInput(field, "non-finite value");
    if (!(c.radius > 0)) throw InvalidInput(join_field(field, "radius"), "must be positive");
    if (c.p0 == c.p1) throw InvalidInput(field, "zero-length axis (p0 == p1)");
  };
  check(a, "a");
  check(b, "b");
  return detail::CylinderCylinderSolver(a, b, options).run();
}

}  // namespace certcyl
