/* A plugin for tests/test_judge_contract.cpp: a ray cast with the surface_entry contract
 * (certcyl_plugin_contract), exact on that test's hand-made cases (small integers and halves, so
 * every double operation below is exact): a ray or segment whose start lies in the closed
 * cylinder is a miss; otherwise a ray hits when it heads towards the axis within the slab, a
 * segment when its end lies in the cylinder. Its name and contract come from the environment
 * (CERTCYL_TEST_CONTRACT, default surface_entry), so the test can make it declare others. */
#include <certcyl/plugin.h>

#include <stdlib.h>

const char* certcyl_plugin_name(void) { return "contract_test_plugin"; }

const char* certcyl_plugin_contract(void) {
  const char* c = getenv("CERTCYL_TEST_CONTRACT");
  return c ? c : "surface_entry";
}

/* Whether x lies in the closed cylinder c (axis p0 p1, radius). */
static int inside(const double x[3], const double c[7]) {
  double a[3], w[3], aa = 0, wa = 0, ww = 0;
  for (int i = 0; i < 3; ++i) a[i] = c[3 + i] - c[i], w[i] = x[i] - c[i];
  for (int i = 0; i < 3; ++i) aa += a[i] * a[i], wa += w[i] * a[i], ww += w[i] * w[i];
  if (wa < 0 || wa > aa) return 0;
  return ww * aa - wa * wa <= c[6] * c[6] * aa;
}

int certcyl_plugin_ray_cylinder(const double origin[3], const double direction[3], const double c[7], double t[2]) {
  (void)t;
  if (inside(origin, c)) return CERTCYL_SEPARATED;
  /* Heading towards the axis point (p0 + p1) / 2 */
  double towards = 0;
  for (int i = 0; i < 3; ++i) towards += direction[i] * ((c[i] + c[3 + i]) / 2 - origin[i]);
  return towards > 0 ? CERTCYL_OVERLAPPING : CERTCYL_SEPARATED;
}

int certcyl_plugin_segment_cylinder(const double p0[3], const double p1[3], const double c[7], double t[2]) {
  (void)t;
  if (inside(p0, c)) return CERTCYL_SEPARATED;
  return inside(p1, c) ? CERTCYL_OVERLAPPING : CERTCYL_SEPARATED;
}
