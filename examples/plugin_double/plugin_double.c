/* plugin_double.c -- a line and cylinder-pair test in double arithmetic, written the way a
 * physics or ray-tracing engine writes it, as a plugin for `certcyl judge --plugin`
 * (certcyl/plugin.h).
 *
 * Line, ray, segment: the parameter range is clipped to the slab between the cap planes, then to
 * the roots of the tube quadratic |(w + t d) x A|^2 = r^2 |A|^2 (w = origin - p0, A = p1 - p0),
 * solved by the textbook formula; touching when the clipped range is one point. Near tangency the
 * discriminant b^2 - 4ac cancels, and its rounding decides the answer.
 *
 * Cylinder pair: the distance between the axis segments (closest points of two segments, clamped)
 * against r0 + r1, the capsule test many engines use for cylinders: it says "intersecting"
 * (it cannot tell touching) wherever the capsules meet, which is wrong near the caps.
 *
 * No triangle query: certcyl judges the queries a plugin exports. */
#include <certcyl/plugin.h>

#include <math.h>

static double dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static void sub(const double a[3], const double b[3], double out[3]) {
  out[0] = a[0] - b[0], out[1] = a[1] - b[1], out[2] = a[2] - b[2];
}

/* The points o + t d, t in [lo, hi], against the cylinder c. */
static int clip(const double o[3], const double d[3], const double c[7], double lo, double hi, double t[2]) {
  double A[3], w[3];
  sub(c + 3, c, A);
  sub(o, c, w);
  const double AA = dot(A, A), dA = dot(d, A), wA = dot(w, A), r = c[6];
  /* The slab 0 <= (w + t d).A <= A.A. */
  if (dA == 0) {
    if (wA < 0 || wA > AA) return CERTCYL_SEPARATED;
  } else {
    double t0 = -wA / dA, t1 = (AA - wA) / dA;
    if (t0 > t1) {
      const double s = t0;
      t0 = t1, t1 = s;
    }
    if (t0 > lo) lo = t0;
    if (t1 < hi) hi = t1;
  }
  /* The tube: a t^2 + b t + cc <= 0. */
  const double a = dot(d, d) * AA - dA * dA;
  const double b = 2 * (dot(w, d) * AA - wA * dA);
  const double cc = dot(w, w) * AA - wA * wA - r * r * AA;
  if (a == 0) {
    if (cc > 0) return CERTCYL_SEPARATED;
  } else {
    const double disc = b * b - 4 * a * cc;
    if (disc < 0) return CERTCYL_SEPARATED;
    const double s = sqrt(disc);
    const double t0 = (-b - s) / (2 * a), t1 = (-b + s) / (2 * a);
    if (t0 > lo) lo = t0;
    if (t1 < hi) hi = t1;
  }
  if (lo > hi) return CERTCYL_SEPARATED;
  t[0] = lo, t[1] = hi;
  return lo == hi ? CERTCYL_TOUCHING : CERTCYL_OVERLAPPING;
}

const char* certcyl_plugin_name(void) { return "plugin_double"; }

int certcyl_plugin_line_cylinder(const double origin[3], const double direction[3], const double c[7], double t[2]) {
  return clip(origin, direction, c, -INFINITY, INFINITY, t);
}

int certcyl_plugin_ray_cylinder(const double origin[3], const double direction[3], const double c[7], double t[2]) {
  return clip(origin, direction, c, 0, INFINITY, t);
}

int certcyl_plugin_segment_cylinder(const double p0[3], const double p1[3], const double c[7], double t[2]) {
  double d[3];
  sub(p1, p0, d);
  return clip(p0, d, c, 0, 1, t);
}

static double clamp01(double x) { return x < 0 ? 0 : (x > 1 ? 1 : x); }

/* The squared distance between the segments p0 + s u and q0 + t v, s, t in [0, 1]. */
static double segment_distance2(const double p0[3], const double u[3], const double q0[3], const double v[3]) {
  double w[3];
  sub(p0, q0, w);
  const double a = dot(u, u), b = dot(u, v), c = dot(v, v), d = dot(u, w), e = dot(v, w);
  const double den = a * c - b * b;
  double s = den > 0 ? clamp01((b * e - c * d) / den) : 0;
  double t = (b * s + e) / c;
  if (t < 0 || t > 1) {
    t = clamp01(t);
    s = clamp01((b * t - d) / a);
  }
  double diff[3];
  for (int i = 0; i < 3; ++i) diff[i] = w[i] + s * u[i] - t * v[i];
  return dot(diff, diff);
}

int certcyl_plugin_cylinder_cylinder(const double a[7], const double b[7]) {
  double u[3], v[3];
  sub(a + 3, a, u);
  sub(b + 3, b, v);
  const double r = a[6] + b[6];
  return segment_distance2(a, u, b, v) <= r * r ? CERTCYL_INTERSECTING : CERTCYL_SEPARATED;
}
