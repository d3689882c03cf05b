// The page of a `certcyl judge` results folder, index.html: one self-contained HTML page (no
// script, no external resource, the figures inline SVG) for a reader who does not know certcyl.
//   - what was tested: the method, the cases and what a family, the certified answer, the gap
//     and a failure are;
//   - per query, one row per family: the failures (false positives and negatives) among the
//     certified cases, the rate with its 95% Wilson interval (drawn as a bar), rows with a
//     failure shaded;
//   - the five most instructive counterexamples: first the clearest error (the largest |gap|) of
//     each failing query and family, taking the queries in turn, then the clearest of the rest;
//     each drawn in two orthographic projections of the cylinder's frame (along its axis, and
//     from the side facing the other operand), the cylinder blue, the line, ray, segment,
//     triangle or second cylinder red, with the certified answer, the method's answer, the gap
//     and its ready-to-run `certcyl query` line.
// Every coordinate of a drawing is mapped to the figure's pixels here (relative to the
// cylinder's centre, so translated and scaled inputs draw as well as the others); lines and
// rays are clipped to the figure.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "judge_internal.hpp"
#include "study/gap_quantity.hpp"

namespace certcyl::cli::judging {
namespace {

// ---- Text -------------------------------------------------------------------------------------

std::string escape(const std::string& s) {
  std::string e;
  for (const char c : s) {
    switch (c) {
      case '&': e += "&amp;"; break;
      case '<': e += "&lt;"; break;
      case '>': e += "&gt;"; break;
      case '"': e += "&quot;"; break;
      default: e += c;
    }
  }
  return e;
}

std::string fmt(const char* format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

// The gap as the page states it, named by its quantity (study/gap.hpp): the depth margin G of a
// line, ray, segment or triangle, log(phi*) of a cylinder pair; one number when the enclosure
// is tight, else the interval.
std::string gap_text(const Case& c) {
  if (!std::isfinite(c.gap_lo) || !std::isfinite(c.gap_hi)) return "log(phi*) unbounded (equal midpoints: overlapping)";
  const std::string name = std::string(study::gap_label(study::gap_quantity(c.query))) + " ";
  if (c.gap_lo == c.gap_hi || std::fabs(c.gap_hi - c.gap_lo) <= 1e-3 * std::max(std::fabs(c.gap_lo), std::fabs(c.gap_hi)))
    return name + "= " + fmt("%.3g", 0.5 * c.gap_lo + 0.5 * c.gap_hi);
  return name + "between " + fmt("%.3g", c.gap_lo) + " and " + fmt("%.3g", c.gap_hi);
}

const char* query_title(study::Query q) {
  switch (q) {
    case study::Query::line_cylinder: return "line against cylinder";
    case study::Query::ray_cylinder: return "ray against cylinder";
    case study::Query::segment_cylinder: return "segment against cylinder";
    case study::Query::line_elliptic_cylinder: return "line against elliptic cylinder";
    case study::Query::triangle_cylinder: return "triangle against cylinder";
    case study::Query::cylinder_cylinder: return "cylinder against cylinder";
  }
  return "";
}

const char* operand_name(study::Query q) {
  switch (q) {
    case study::Query::line_cylinder:
    case study::Query::line_elliptic_cylinder: return "line";
    case study::Query::ray_cylinder: return "ray";
    case study::Query::segment_cylinder: return "segment";
    case study::Query::triangle_cylinder: return "triangle";
    case study::Query::cylinder_cylinder: return "second cylinder";
  }
  return "";
}

// What each family is, in a sentence (study/families.hpp); k is the displacement in ulps.
std::string family_text(const std::string& f) {
  static const std::map<std::string, std::string> kText = {
      {"tangent", "tangent to the wall, tilted toward the axis"},
      {"near_parallel", "tangent, at an angle down to 2^-50 to the axis"},
      {"rim", "grazing a rim circle from outside"},
      {"on_wall", "lying on the wall, parallel to the axis"},
      {"cap_plane", "a chord lying in a cap's plane"},
      {"far", "tangent, translated by 2^20 to 2^40"},
      {"extreme_scale", "tangent, scaled by 2^-40 to 2^40, radius down to 2^-20 of the height"},
      {"ends_on_wall", "ending on the wall, coming from outside"},
      {"tangent_rotated", "tangent, in general position (rotated)"},
      {"rim_rotated", "grazing a rim, in general position (rotated)"},
      {"uniform", "random inputs in [-2, 2]^3 (no degeneracy)"},
      {"e_tangent", "tangent to an elliptic cylinder (sheared frame)"},
      {"e_parallel_axis", "parallel to the axis, inside, on or outside the wall"},
      {"e_rim", "grazing a rim ellipse"},
      {"e_cap_plane", "a chord in a cap's plane"},
      {"e_tangent_oblique", "tangent, oblique frame (rounded)"},
      {"t_vertex_wall", "a vertex on the wall"},
      {"t_edge_wall", "an edge tangent to the wall"},
      {"t_face_cap", "the face lying on a cap"},
      {"t_vertex_rim", "a vertex on a rim"},
      {"t_axis_plane", "the plane contains the axis direction, away from the axis (separated)"},
      {"t_edge_rotated", "an edge tangent to the wall, rotated"},
      {"c_cap_cap", "cap against cap"},
      {"c_wall_parallel", "walls touching, axes parallel"},
      {"c_wall_crossing", "walls touching, axes crossing"},
      {"c_cap_wall", "a cap against the other's wall"},
      {"c_near_parallel", "walls touching, skew axes at an angle down to 2^-50"},
      {"c_rim_cap", "a rim against the other's cap"},
      {"c_rim_wall", "a rim against the other's wall"},
      {"c_rim_rim", "rim against rim"},
      {"c_coaxial", "nested on one axis (overlapping)"},
      {"c_equal_midpoints", "equal midpoints (overlapping)"},
      {"c_crossing_rotated", "walls touching, in general position (rotated)"},
  };
  const auto it = kText.find(f);
  return it == kText.end() ? "" : it->second;
}

// ---- Geometry ---------------------------------------------------------------------------------

struct P3 {
  double x = 0, y = 0, z = 0;
};
P3 operator+(P3 a, P3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
P3 operator-(P3 a, P3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
P3 operator*(double s, P3 a) { return {s * a.x, s * a.y, s * a.z}; }
double dot(P3 a, P3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
P3 cross(P3 a, P3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double norm(P3 a) { return std::sqrt(dot(a, a)); }
P3 unit(P3 a) {
  const double n = norm(a);
  return n > 0 && std::isfinite(n) ? (1 / n) * a : P3{1, 0, 0};
}
// A unit vector perpendicular to the unit vector w.
P3 perpendicular(P3 w) {
  const P3 e = std::fabs(w.x) < 0.6 ? P3{1, 0, 0} : P3{0, 1, 0};
  return unit(e - dot(e, w) * w);
}

P3 at(const std::vector<double>& x, std::size_t i) { return {x[i], x[i + 1], x[i + 2]}; }

// A solid cylinder as { base + u a + v b + s c : u^2 + v^2 <= 1, 0 <= s <= 1 }.
struct Solid {
  P3 base, a, b, c;
  P3 centre() const { return base + 0.5 * c; }
  // The two cap curves, n points each.
  std::vector<P3> rims(int n) const {
    std::vector<P3> pts;
    for (int cap = 0; cap < 2; ++cap)
      for (int i = 0; i < n; ++i) {
        const double t = 2 * std::numbers::pi * i / n;
        pts.push_back(base + std::cos(t) * a + std::sin(t) * b + (cap ? c : P3{}));
      }
    return pts;
  }
};

Solid circular(const std::vector<double>& x, std::size_t i) {
  const P3 p0 = at(x, i), p1 = at(x, i + 3);
  const double r = x[i + 6];
  const P3 w = unit(p1 - p0), u = perpendicular(w), v = cross(w, u);
  return {p0, r * u, r * v, p1 - p0};
}

// The case's operands: the cylinder and the other one, as what to draw.
struct Scene {
  Solid cylinder;
  enum Kind { line, ray, segment, triangle, solid } kind = line;
  std::vector<P3> points;  // line, ray: origin and direction; segment: ends; triangle: vertices
  Solid other;             // kind solid
  // The other operand's point nearest the cylinder's centre (a line's, a ray's or a segment's),
  // its vertices' centroid, or the second cylinder's centre: what the side view faces.
  P3 focus() const {
    const P3 m = cylinder.centre();
    switch (kind) {
      case line:
      case ray:
      case segment: {
        const P3 o = points[0], d = kind == segment ? points[1] - points[0] : points[1];
        double t = dot(d, d) > 0 ? dot(m - o, d) / dot(d, d) : 0;
        if (kind != line) t = std::max(t, 0.0);
        if (kind == segment) t = std::min(t, 1.0);
        return o + t * d;
      }
      case triangle: return (1.0 / 3) * (points[0] + points[1] + points[2]);
      case solid: return other.centre();
    }
    return m;
  }
};

Scene scene_of(const Case& c) {
  using study::Query;
  Scene s;
  const auto& x = c.x;
  switch (c.query) {
    case Query::line_cylinder:
    case Query::ray_cylinder:
    case Query::segment_cylinder:
      s.kind = c.query == Query::line_cylinder ? Scene::line : (c.query == Query::ray_cylinder ? Scene::ray : Scene::segment);
      s.points = {at(x, 0), at(x, 3)};
      s.cylinder = circular(x, 6);
      break;
    case Query::line_elliptic_cylinder:
      s.kind = Scene::line;
      s.points = {at(x, 0), at(x, 3)};
      s.cylinder = {at(x, 6), at(x, 9), at(x, 12), at(x, 15)};
      break;
    case Query::triangle_cylinder:
      s.kind = Scene::triangle;
      s.points = {at(x, 0), at(x, 3), at(x, 6)};
      s.cylinder = circular(x, 9);
      break;
    case Query::cylinder_cylinder:
      s.kind = Scene::solid;
      s.cylinder = circular(x, 0);
      s.other = circular(x, 7);
      break;
  }
  return s;
}

struct P2 {
  double x = 0, y = 0;
};

// The convex hull of points (Andrew's monotone chain), counter-clockwise.
std::vector<P2> hull(std::vector<P2> p) {
  std::sort(p.begin(), p.end(), [](P2 a, P2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  if (p.size() < 3) return p;
  auto turn = [](P2 o, P2 a, P2 b) { return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x); };
  std::vector<P2> h(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && turn(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && turn(h[k - 2], h[k - 1], p[i - 1]) <= 0) --k;
    h[k++] = p[i - 1];
  }
  h.resize(k - 1);
  return h;
}

// ---- Drawing ----------------------------------------------------------------------------------

constexpr double kSize = 300;  // a view's width and height in pixels
constexpr double kPad = 14;
constexpr int kRim = 72;  // points per cap curve
const char* const kBlue = "#1f77b4";
const char* const kRed = "#d62728";

// One projection: coordinates (e1, e2) relative to `origin`, then the box mapped to pixels.
class View {
 public:
  View(P3 origin, P3 e1, P3 e2) : origin_(origin), e1_(e1), e2_(e2) {}
  P2 project(P3 p) const {
    const P3 d = p - origin_;
    return {dot(d, e1_), dot(d, e2_)};
  }
  P2 project_direction(P3 d) const { return {dot(d, e1_), dot(d, e2_)}; }
  void fit(const std::vector<P2>& pts) {
    for (const P2& p : pts) {
      lo_.x = std::min(lo_.x, p.x), lo_.y = std::min(lo_.y, p.y);
      hi_.x = std::max(hi_.x, p.x), hi_.y = std::max(hi_.y, p.y);
    }
  }
  double extent() const { return std::max(hi_.x - lo_.x, hi_.y - lo_.y); }
  // Fixes the box: square, centred on what was fitted.
  void freeze() {
    double e = extent();
    if (!(e > 0) || !std::isfinite(e)) e = 1;
    const P2 mid{0.5 * lo_.x + 0.5 * hi_.x, 0.5 * lo_.y + 0.5 * hi_.y};
    lo_ = {mid.x - e / 2, mid.y - e / 2};
    scale_ = (kSize - 2 * kPad) / e;
  }
  P2 pixel(P2 p) const { return {kPad + (p.x - lo_.x) * scale_, kSize - kPad - (p.y - lo_.y) * scale_}; }
  double scale() const { return scale_; }

 private:
  P3 origin_, e1_, e2_;
  P2 lo_{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  P2 hi_{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  double scale_ = 1;
};

std::string coords(P2 p) { return fmt("%.2f", p.x) + "," + fmt("%.2f", p.y); }

std::string polygon(const std::vector<P2>& px, const char* colour, double opacity, double width) {
  std::string s = "<polygon points=\"";
  for (const P2& p : px) s += coords(p) + " ";
  s += "\" fill=\"" + std::string(colour) + "\" fill-opacity=\"" + fmt("%.2f", opacity) + "\" stroke=\"" + colour +
       "\" stroke-width=\"" + fmt("%.1f", width) + "\" stroke-linejoin=\"round\"/>";
  return s;
}

// The segment a + t (b - a), t in [t0, t1], clipped to the figure with a margin (Liang-Barsky);
// false when it misses it.
bool clip(P2 a, P2 b, double t0, double t1, P2& from, P2& to) {
  const double lo = -kSize, hi = 2 * kSize;
  const double d[2] = {b.x - a.x, b.y - a.y}, p[2] = {a.x, a.y};
  for (int i = 0; i < 2; ++i) {
    if (d[i] == 0) {
      if (p[i] < lo || p[i] > hi) return false;
      continue;
    }
    double ta = (lo - p[i]) / d[i], tb = (hi - p[i]) / d[i];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta), t1 = std::min(t1, tb);
  }
  if (t0 > t1) return false;
  from = {a.x + t0 * d[0], a.y + t0 * d[1]};
  to = {a.x + t1 * d[0], a.y + t1 * d[1]};
  return true;
}

// One view of the scene as an <svg>: the cylinder's outline (the hull of its caps) and cap
// curves, then the other operand.
std::string draw(const Scene& s, const View& v, const std::string& title) {
  std::ostringstream o;
  o << "<svg class=\"view\" xmlns=\"http://www.w3.org/2000/svg\" width=\"" << kSize << "\" height=\"" << kSize
    << "\" viewBox=\"0 0 " << kSize << ' ' << kSize << "\" role=\"img\"><title>" << escape(title) << "</title>";
  o << "<rect x=\"0.5\" y=\"0.5\" width=\"" << kSize - 1 << "\" height=\"" << kSize - 1 << "\" fill=\"#fff\" stroke=\"#ccc\"/>";
  auto solid = [&](const Solid& b, const char* colour) {
    std::vector<P2> px;
    for (const P3& p : b.rims(kRim)) px.push_back(v.pixel(v.project(p)));
    o << polygon(hull(px), colour, 0.22, 2);
    for (int cap = 0; cap < 2; ++cap) {
      o << "<polyline points=\"";
      for (int i = 0; i <= kRim; ++i) o << coords(px[static_cast<std::size_t>(cap * kRim + i % kRim)]) << ' ';
      o << "\" fill=\"none\" stroke=\"" << colour << "\" stroke-width=\"1\"/>";
    }
  };
  auto dot_at = [&](P3 p) {
    const P2 q = v.pixel(v.project(p));
    if (q.x > -kSize && q.x < 2 * kSize && q.y > -kSize && q.y < 2 * kSize)
      o << "<circle cx=\"" << fmt("%.2f", q.x) << "\" cy=\"" << fmt("%.2f", q.y) << "\" r=\"3.5\" fill=\"" << kRed << "\"/>";
  };
  solid(s.cylinder, kBlue);
  switch (s.kind) {
    case Scene::line:
    case Scene::ray:
    case Scene::segment: {
      const P3 a3 = s.points[0], b3 = s.kind == Scene::segment ? s.points[1] : s.points[0] + s.points[1];
      const P2 a = v.pixel(v.project(a3)), b = v.pixel(v.project(b3));
      const double len = std::hypot(b.x - a.x, b.y - a.y);
      P2 from, to;
      if (!(len > 1e-9 * kSize)) {
        dot_at(a3);  // seen end on
      } else {
        // A parameter range reaching well past the figure for a line or a ray.
        const double far = (3 * kSize + std::hypot(a.x, a.y)) / len;
        const double t0 = s.kind == Scene::line ? -far : 0, t1 = s.kind == Scene::segment ? 1 : far;
        if (clip(a, b, t0, t1, from, to))
          o << "<line x1=\"" << fmt("%.2f", from.x) << "\" y1=\"" << fmt("%.2f", from.y) << "\" x2=\"" << fmt("%.2f", to.x)
            << "\" y2=\"" << fmt("%.2f", to.y) << "\" stroke=\"" << kRed << "\" stroke-width=\"2.5\"/>";
        if (s.kind != Scene::line) dot_at(a3);
        if (s.kind == Scene::segment) dot_at(b3);
      }
      break;
    }
    case Scene::triangle: {
      std::vector<P2> px;
      for (const P3& p : s.points) px.push_back(v.pixel(v.project(p)));
      o << polygon(px, kRed, 0.3, 2);
      break;
    }
    case Scene::solid: solid(s.other, kRed); break;
  }
  o << "</svg>";
  return o.str();
}

// The two views of a case: along the cylinder's axis, and from the side facing the other
// operand (the axis horizontal). The box holds the cylinder and the other operand near it;
// what lies further than a few cylinder sizes (a far ray origin, a long segment) is cut.
std::pair<std::string, double> figure(const Case& c) {
  const Scene s = scene_of(c);
  const P3 m = s.cylinder.centre(), w = unit(s.cylinder.c), f = s.focus();
  P3 toward = (f - m) - dot(f - m, w) * w;
  const double size = std::max({norm(s.cylinder.c), norm(s.cylinder.a), norm(s.cylinder.b)});
  const P3 e1 = norm(toward) > 1e-12 * size ? unit(toward) : perpendicular(w), e2 = cross(w, e1);
  std::vector<View> views{View(m, e1, e2), View(m, w, e1)};
  for (View& v : views) {
    std::vector<P2> body;
    for (const P3& p : s.cylinder.rims(kRim)) body.push_back(v.project(p));
    v.fit(body);
    const double reach = 3 * std::max(v.extent(), 1e-300);
    std::vector<P2> more{v.project(f)};
    if (s.kind == Scene::segment || s.kind == Scene::triangle)
      for (const P3& p : s.points) more.push_back(v.project(p));
    if (s.kind == Scene::ray) more.push_back(v.project(s.points[0]));
    if (s.kind == Scene::solid)
      for (const P3& p : s.other.rims(kRim)) more.push_back(v.project(p));
    const P2 centre = v.project(m);
    for (const P2& p : more)
      if (std::fabs(p.x - centre.x) <= reach && std::fabs(p.y - centre.y) <= reach) v.fit({p});
    v.freeze();
  }
  const std::string what = query_title(c.query);
  std::string svg = draw(s, views[0], what + ", seen along the cylinder's axis") + draw(s, views[1], what + ", seen from the side");
  return {svg, (kSize - 2 * kPad) / views[0].scale()};
}

// ---- Choosing the counterexamples -------------------------------------------------------------

// Up to `n`: the clearest error (largest |gap|) of each failing query and family, the queries
// taken in turn (each query's families by their clearest error), then the clearest of the rest.
std::vector<const Counterexample*> instructive(const std::vector<Counterexample>& all, std::size_t n) {
  std::map<std::string, std::map<std::string, const Counterexample*>> best;  // query -> family -> clearest
  for (const Counterexample& e : all) {
    const Counterexample*& b = best[std::string(study::to_string(e.c->query))][e.c->family];
    if (!b || gap_size(*e.c) > gap_size(*b->c)) b = &e;
  }
  auto clearer = [](const Counterexample* a, const Counterexample* b) { return gap_size(*a->c) > gap_size(*b->c); };
  std::vector<std::vector<const Counterexample*>> queues;
  for (const auto& [query, families] : best) {
    std::vector<const Counterexample*> q;
    for (const auto& [family, e] : families) q.push_back(e);
    std::stable_sort(q.begin(), q.end(), clearer);
    queues.push_back(q);
  }
  std::vector<const Counterexample*> chosen;
  for (std::size_t round = 0; chosen.size() < n; ++round) {
    bool any = false;
    for (const auto& q : queues)
      if (round < q.size() && chosen.size() < n) chosen.push_back(q[round]), any = true;
    if (!any) break;
  }
  std::vector<const Counterexample*> rest;
  for (const Counterexample& e : all)
    if (std::find(chosen.begin(), chosen.end(), &e) == chosen.end()) rest.push_back(&e);
  std::stable_sort(rest.begin(), rest.end(), clearer);
  for (const Counterexample* e : rest)
    if (chosen.size() < n) chosen.push_back(e);
  return chosen;
}

const char* outcome_text(const std::string& outcome) {
  if (outcome == "false_positive") return "a false positive: the method says they meet, they do not";
  if (outcome == "false_negative") return "a false negative: the method says they are apart, they meet";
  return "a wrong answer";
}

const char* const kStyle = R"(
body { font-family: sans-serif; margin: 1.5em auto; max-width: 70em; padding: 0 1em; color: #222; }
h1 { font-size: 1.5em; } h2 { font-size: 1.25em; border-bottom: 1px solid #ccc; margin-top: 1.5em; } h3 { font-size: 1.05em; }
table { border-collapse: collapse; font-size: 0.8em; margin: 0.5em 0 1em; }
th, td { border: 1px solid #ccc; padding: 0.15em 0.5em; text-align: left; }
th { background: #eee; } td.num { text-align: right; font-variant-numeric: tabular-nums; }
tr.wrong td { background: #fde0e0; } tr.all td { font-weight: bold; }
.bar { display: inline-block; position: relative; width: 10em; height: 0.7em; background: #f2f2f2; border: 1px solid #bbb; vertical-align: middle; }
.bar span { position: absolute; top: 0; bottom: 0; background: #777; min-width: 1px; }
.bar b { position: absolute; top: -0.15em; bottom: -0.15em; width: 2px; background: #000; }
figure { margin: 1.5em 0; padding-top: 0.5em; border-top: 1px solid #ddd; } figure svg { margin-right: 0.5em; }
figcaption { max-width: 62em; font-size: 0.9em; } figcaption table { font-size: 0.95em; }
pre { font-size: 0.75em; white-space: pre-wrap; word-break: break-all; background: #f6f6f6; padding: 0.5em; }
.note { color: #555; font-size: 0.9em; } .key { display: inline-block; width: 0.9em; height: 0.9em; vertical-align: middle; }
)";

std::string rate_cells(const FamilyJudgement& r) {
  if (r.certified == 0) return "<td class=\"num\">-</td><td>-</td><td></td>";
  const auto pos = [](double p) { return fmt("%.2f", 100 * std::clamp(p, 0.0, 1.0)); };
  return "<td class=\"num\">" + percent(r.rate) + "</td><td class=\"ci\">" + percent(r.lo95) + " to " + percent(r.hi95) +
         "</td><td><span class=\"bar\"><span style=\"left:" + pos(r.lo95) + "%;width:" + pos(r.hi95 - r.lo95) +
         "%\"></span><b style=\"left:" + pos(r.rate) + "%\"></b></span></td>";
}

}  // namespace

// The colours of a failure map's cells by code (none is the drawings' blue or red).
const char* map_colour(char code) {
  switch (code) {
    case 's': return "#e4e4e4";
    case 't': return "#f2b33d";
    case 'o': return "#3f9e6e";
    case 'i': return "#7fc79f";
    case 'u': return "#f7ef8a";
    case 'e': return "#303030";
    default: return "#ffffff";
  }
}
const char* const kWrong = "#e000e0";

// One panel of a failure map as an <svg>: a cell per input (row i down, column j across), the
// centre cell (the degenerate configuration) outlined; with `wrong`, the wrong cells magenta.
std::string map_panel(const MapJudgement& m, const std::string& codes, const std::vector<bool>* wrong, const std::string& title) {
  const int n = m.cells;
  const double cell = std::max(3.0, std::min(12.0, 240.0 / n)), side = cell * n;
  std::ostringstream o;
  o << "<svg class=\"map\" xmlns=\"http://www.w3.org/2000/svg\" width=\"" << fmt("%.0f", side) << "\" height=\"" << fmt("%.0f", side)
    << "\" viewBox=\"0 0 " << fmt("%.1f", side) << ' ' << fmt("%.1f", side) << "\" role=\"img\"><title>" << escape(title) << "</title>";
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < n; ++k) {
      const std::size_t c = static_cast<std::size_t>(i) * static_cast<std::size_t>(n) + static_cast<std::size_t>(k);
      const char* fill = wrong && (*wrong)[c] ? kWrong : map_colour(codes[c]);
      o << "<rect x=\"" << fmt("%.1f", k * cell) << "\" y=\"" << fmt("%.1f", i * cell) << "\" width=\"" << fmt("%.1f", cell)
        << "\" height=\"" << fmt("%.1f", cell) << "\" fill=\"" << fill << "\"/>";
    }
  o << "<rect x=\"" << fmt("%.1f", (n / 2) * cell) << "\" y=\"" << fmt("%.1f", (n / 2) * cell) << "\" width=\"" << fmt("%.1f", cell)
    << "\" height=\"" << fmt("%.1f", cell) << "\" fill=\"none\" stroke=\"#000\" stroke-width=\"1\"/></svg>";
  return o.str();
}

void write_report_page(const std::filesystem::path& file, const Judgement& j) {
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>certcyl judge: " << escape(j.method)
    << "</title>\n<style>" << kStyle << "</style>\n</head>\n<body>\n";
  h << "<h1>certcyl judge: " << escape(j.method) << "</h1>\n";
  std::size_t failures = 0, certified = 0;
  std::vector<std::string> queries;
  for (const FamilyJudgement& r : j.rows)
    if (r.family == "all") failures += r.failures, certified += r.certified, queries.push_back(r.query);
  h << "<p id=\"verdict\"><b>" << failures << " failure" << (failures == 1 ? "" : "s") << "</b> among the " << certified
    << " certified cases (" << j.judged << " of " << j.cases << " cases judged)";
  if (certified > 0) h << ": " << percent(static_cast<double>(failures) / static_cast<double>(certified)) << " of the answers are wrong";
  h << ".</p>\n";
  if (std::isfinite(j.ns_per_query))
    h << "<p id=\"speed\">Speed: <b>" << fmt("%.1f", j.ns_per_query) << " ns per query</b>, " << escape(j.timing)
      << ". <a href=\"speed.csv\">speed.csv</a> holds it per query in the columns of the study's summary.csv (kind "
         "<i>judged</i>; its last column, <i>mean_ns</i>, is this mean where summary.csv has a median), to draw it on "
         "the study's speed-against-error figure beside the built-in methods.</p>\n";
  if (j.contract == study::Contract::surface_entry)
    h << "<p id=\"contract\">Contract: <b>surface_entry</b>. The method declared that a ray or segment hits only when it enters "
         "the cylinder from outside; one starting inside the cylinder or on its boundary is judged correct when it reports no "
         "hit. The other queries are judged as solids.</p>\n";
  else if (j.contract == study::Contract::surface_hit)
    h << "<p id=\"contract\">Contract: <b>surface_hit</b>. The method declared that a ray or segment hits when it reaches the "
         "cylinder's surface at a positive parameter, an exit counting; it is judged against that answer. The other queries "
         "are judged as solids.</p>\n";
  if (!j.failure.empty())
    h << "<p><b>Not every case was judged:</b> " << escape(j.failure) << ". The counts below are of the cases judged before.</p>\n";
  h << "<p>Contents: <a href=\"#tested\">what was tested</a>, <a href=\"#families\">failure rate per family</a>, "
       "<a href=\"#counterexamples\">counterexamples</a>, "
    << (j.maps ? "<a href=\"#maps\">failure maps</a>, " : "") << "<a href=\"#files\">files</a>.</p>\n";

  // What was tested.
  h << "<h2 id=\"tested\">What was tested</h2>\n<p>The method <code>" << escape(j.method)
    << "</code> answered whether two solids meet: a cylinder (closed, caps included) and a line, ray, segment, triangle or "
       "second cylinder. Its answers were compared with answers computed exactly by certcyl (rational arithmetic on the "
       "binary64 inputs as given): <i>separated</i> (no common point), <i>touching</i> (common points on the boundaries "
       "only) or <i>overlapping</i> (common interior points).</p>\n"
       "<p>The inputs are the hard-case <i>families</i> of certcyl's robustness study: each places a configuration exactly "
       "at a degeneracy (a line tangent to the wall, a rim grazed, two caps in contact, ...) and then moves one coordinate "
       "by k units in the last place (k = 0 on it, k of either sign up to 2^40), so the exact answer changes within "
       "rounding distance; the family <i>uniform</i> holds random inputs for comparison. Each case also has a certified "
       "<i>gap</i>: its sign is the exact answer's (negative separated, zero touching, positive overlapping) and its size how "
       "far the input is from a change of answer. Lines, rays, segments and triangles: the depth margin G, the largest over "
       "the set of min(1 - q, s, 1 - s) (s the axial coordinate in heights, q the squared distance from the axis in units of "
       "r^2); it is exactly the offset of the cylinder (radius r sqrt(1 - G), each cap moved by G heights) at which the "
       "answer changes. Cylinder pairs: log(phi*), the logarithm of the common scale factor about the midpoints at which "
       "the two cylinders touch.</p>\n"
       "<p>A <b>failure</b> is a false positive (the method says the solids meet; they are separated) or a false negative "
       "(it says they are separated; they meet). Touching and overlapping confused, undecided answers, errors of the method "
       "and non-finite values are counted apart. The failure rate is taken among the cases with a certified answer, with "
       "its 95% Wilson score interval.</p>\n<ul>\n";
  for (const FamilyJudgement& r : j.rows)
    if (r.family == "all") {
      std::size_t families = 0;
      for (const FamilyJudgement& f : j.rows) families += f.query == r.query && f.family != "all";
      h << "<li><code>" << escape(r.query) << "</code> (" << query_title(parse_study_query(r.query)) << "): " << r.cases
        << " cases in " << families << " families, " << r.failures << " failure" << (r.failures == 1 ? "" : "s") << "</li>\n";
    }
  h << "</ul>\n";

  // The failure rate per family.
  h << "<h2 id=\"families\">Failure rate per family</h2>\n<p>One row per family (<a href=\"families.csv\">families.csv</a>), "
       "then the query's total; rows with a failure are shaded. FP: false positives, FN: false negatives, other: touching "
       "and overlapping confused, undecided, errors and non-finite values. The bar shows the 95% interval (grey) and the "
       "observed rate (black) on a scale from 0 to 100%.</p>\n";
  for (const std::string& q : queries) {
    h << "<h3 id=\"family-" << escape(q) << "\">" << escape(q) << " (" << query_title(parse_study_query(q)) << ")</h3>\n";
    h << "<table class=\"families\">\n<thead><tr><th>family</th><th>configuration</th><th>cases</th><th>certified</th><th>FP</th>"
         "<th>FN</th><th>other</th><th>failure rate</th><th>95% interval</th><th></th></tr></thead>\n<tbody>\n";
    for (const FamilyJudgement& r : j.rows) {
      if (r.query != q) continue;
      const std::size_t other = r.at("class_mismatch") + r.at("undecided") + r.at("error") + r.at("invalid");
      std::vector<std::string> cls;
      if (r.failures > 0) cls.push_back("wrong");
      if (r.family == "all") cls.push_back("all");
      h << "<tr" << (cls.empty() ? "" : " class=\"" + (cls.size() == 2 ? cls[0] + " " + cls[1] : cls[0]) + "\"") << "><td>"
        << escape(r.family) << "</td><td>" << escape(r.family == "all" ? "every family" : family_text(r.family)) << "</td><td class=\"num\">"
        << r.cases << "</td><td class=\"num\">" << r.certified << "</td><td class=\"num\">" << r.at("false_positive")
        << "</td><td class=\"num\">" << r.at("false_negative") << "</td><td class=\"num\">" << other << "</td>" << rate_cells(r)
        << "</tr>\n";
    }
    h << "</tbody>\n</table>\n";
  }

  // The counterexamples.
  const auto chosen = instructive(j.counterexamples, 5);
  h << "<h2 id=\"counterexamples\">Counterexamples</h2>\n";
  if (chosen.empty()) {
    h << "<p>None: the method agrees with the certified answer on every certified case it answered.</p>\n";
  } else {
    h << "<p>" << chosen.size() << " of the " << j.counterexamples.size()
      << " distinct inputs the method gets wrong (all in <a href=\"counterexamples.jsonl\">counterexamples.jsonl</a>, the "
         "smallest |gap| first): first the clearest error of each failing family (the largest |gap|, the furthest from a "
         "change of answer), the queries in turn, then the clearest of the rest. Each is drawn to scale in two orthographic "
         "views: along the cylinder's axis, and from the side facing the other operand (axis horizontal); "
         "<span class=\"key\" style=\"background:"
      << kBlue << "\"></span> the cylinder, <span class=\"key\" style=\"background:" << kRed
      << "\"></span> the line, ray (its origin a dot), segment, triangle or second cylinder. A gap far smaller than the "
         "drawing cannot be seen: the configuration then looks touching, which is why it is hard. To reproduce one, pipe "
         "its line to <code>certcyl query</code>.</p>\n";
  }
  int number = 0;
  for (const Counterexample* e : chosen) {
    const Case& c = *e->c;
    const auto [svg, width] = figure(c);
    ++number;
    h << "<figure class=\"counterexample\" id=\"cx-" << number << "\" data-id=\"" << escape(c.id) << "\">\n<div>" << svg
      << "</div>\n<figcaption><b>" << number << ". " << escape(c.id) << "</b>: " << query_title(c.query) << ", family <i>"
      << escape(c.family) << "</i> (" << escape(family_text(c.family)) << "), k = " << c.k << ".\n<table class=\"facts\">"
      << "<tr><th>certified answer</th><td class=\"certified\">" << escape(std::string(to_string(c.certified)))
      << "</td></tr><tr><th>the method's answer</th><td class=\"answer\">" << escape(e->answer) << "</td></tr>"
      << "<tr><th>so it is</th><td>" << outcome_text(e->outcome) << "</td></tr><tr><th>certified gap</th><td class=\"gap\">"
      << escape(gap_text(c)) << "</td></tr><tr><th>drawing width</th><td>" << fmt("%.3g", width) << " (the "
      << operand_name(c.query) << " red, the cylinder blue)</td></tr></table>\n<pre>"
      << escape(query_line(c).dump()) << "</pre></figcaption>\n</figure>\n";
  }

  // The failure maps.
  if (j.maps) {
    const MapsResult& maps = *j.maps;
    h << "<h2 id=\"maps\">Failure maps</h2>\n";
    if (maps.maps.empty()) {
      h << "<p>None: " << escape(maps.note) << ".</p>\n";
    } else {
      h << "<p>The grids of certcyl's study around one degenerate configuration of each query: the configuration at the "
           "centre cell (outlined), two of its coordinates moved by whole units in the last place across the grid (rows the "
           "first, columns the second). Left the certified answer, right the method's: <span class=\"key\" style=\"background:"
        << map_colour('s') << "\"></span> separated, <span class=\"key\" style=\"background:" << map_colour('t')
        << "\"></span> touching, <span class=\"key\" style=\"background:" << map_colour('o')
        << "\"></span> overlapping, <span class=\"key\" style=\"background:" << map_colour('i')
        << "\"></span> intersecting, <span class=\"key\" style=\"background:" << map_colour('u')
        << "\"></span> undecided, <span class=\"key\" style=\"background:" << map_colour('e')
        << "\"></span> error, <span class=\"key\" style=\"background:" << kWrong
        << "\"></span> wrong (a false positive or negative), white not evaluated. Each map's cells are in "
           "<code>failure_maps/&lt;name&gt;.csv</code> (the study's format), the counts in "
           "<a href=\"failure_maps.csv\">failure_maps.csv</a>.</p>\n";
      if (!maps.failure.empty()) h << "<p><b>The method failed on the way:</b> " << escape(maps.failure) << ".</p>\n";
      for (const MapJudgement& m : maps.maps) {
        const std::size_t wrong = m.false_positive + m.false_negative;
        h << "<figure class=\"failure-map\" id=\"map-" << escape(m.name) << "\">\n<div>"
          << map_panel(m, m.certified, nullptr, m.name + ": the certified answers") << ' '
          << map_panel(m, m.codes, &m.wrong, m.name + ": the method's answers, wrong cells marked") << "</div>\n<figcaption><b>"
          << escape(m.name) << "</b> (<code>" << escape(m.query) << "</code>): " << escape(m.description) << "; " << m.cells << " x "
          << m.cells << " cells " << m.step << " ulp apart. <b>" << wrong << " wrong</b> of " << m.evaluated
          << " cells evaluated (" << m.false_positive << " false positive" << (m.false_positive == 1 ? "" : "s") << ", "
          << m.false_negative << " false negative" << (m.false_negative == 1 ? "" : "s") << "). <a href=\"failure_maps/"
          << escape(m.name) << ".csv\">" << escape(m.name) << ".csv</a></figcaption>\n</figure>\n";
      }
    }
  }

  if (j.hunt) {
    h << "<h2 id=\"hunt\">Worst input found</h2>\n<p>The study's hunt (<a href=\"hunt.csv\">hunt.csv</a>): from the "
         "degenerate configurations of each query's families, a search over ulp moves of single coordinates that keeps the "
         "method wrong while moving the input as far from a change of answer as it can (the certified gap's lower bound).</p>\n<ul>\n";
    for (const std::string& l : j.hunt->lines) h << "<li class=\"hunt\">" << escape(hunt_text(l)) << "</li>\n";
    h << "</ul>\n";
    if (!j.hunt->failure.empty()) h << "<p><b>The hunt ended early:</b> " << escape(j.hunt->failure) << ".</p>\n";
  }

  h << "<h2 id=\"files\">Files</h2>\n<ul>\n"
       "<li><a href=\"families.csv\">families.csv</a>: the table above, with every outcome's count</li>\n"
       "<li><a href=\"counterexamples.jsonl\">counterexamples.jsonl</a>: every wrong answer as a ready-to-run "
       "<code>certcyl query</code> line, with both answers and the gap</li>\n"
       "<li><a href=\"answers.jsonl\">answers.jsonl</a>: the method's answers as judged</li>\n"
       "<li><a href=\"summary.txt\">summary.txt</a>: the table as printed</li>\n</ul>\n</body>\n</html>\n";

  std::ofstream out(file);
  out << h.str();
  out.flush();
  if (!out) throw std::runtime_error("cannot write " + file.string());
}

}  // namespace certcyl::cli::judging
