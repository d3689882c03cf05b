/* my_plugin.c -- a segment and cylinder test as many engines write it, for `certcyl judge
 * --plugin` (certcyl/plugin.h): the segment meets the cylinder when its distance to the axis
 * segment is at most the radius. That is the capsule around the axis, not the cylinder: near the
 * caps it says "intersecting" for segments that pass beyond them, which certcyl finds. */
#include <certcyl/plugin.h>

static double dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static double clamp01(double x) { return x < 0 ? 0 : (x > 1 ? 1 : x); }

const char* certcyl_plugin_name(void) { return "my_plugin"; }

int certcyl_plugin_segment_cylinder(const double p0[3], const double p1[3], const double c[7], double t[2]) {
  double u[3], v[3], w[3];
  for (int i = 0; i < 3; ++i) u[i] = p1[i] - p0[i], v[i] = c[3 + i] - c[i], w[i] = p0[i] - c[i];
  /* The closest points p0 + s u and c.p0 + q v, s and q in [0, 1]. */
  const double a = dot(u, u), b = dot(u, v), cc = dot(v, v), d = dot(u, w), e = dot(v, w);
  if (cc == 0) return -1; /* a degenerate cylinder: an error of the method, counted */
  const double den = a * cc - b * b;
  double s = den > 0 ? clamp01((b * e - cc * d) / den) : 0;
  double q = (b * s + e) / cc;
  if (q < 0 || q > 1) q = clamp01(q), s = a > 0 ? clamp01((b * q - d) / a) : 0;
  double diff[3];
  for (int i = 0; i < 3; ++i) diff[i] = w[i] + s * u[i] - q * v[i];
  (void)t; /* the parameter interval is optional */
  return dot(diff, diff) <= c[6] * c[6] ? CERTCYL_INTERSECTING : CERTCYL_SEPARATED;
}
