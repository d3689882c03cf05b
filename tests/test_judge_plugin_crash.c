/* A plugin for tests/test_judge.cpp and tests/test_judge_maps.cpp: answers line queries
 * "separated", fails (-1) on its second call and dies by SIGSEGV on its fifth, as a buggy plugin
 * would; hangs on its third ray query; returns 7, no answer, on its second segment query; answers
 * triangle queries "separated" and abort()s on the 100th call of its process (past the few cases
 * of a triangle family, inside the failure map's 256 cells at --size tiny). Each run of the
 * plugin is a process of its own, so the counts start again at every run. */
#include <certcyl/plugin.h>

#include <signal.h>
#include <stdlib.h>
#include <unistd.h>

const char* certcyl_plugin_name(void) { return "faulty_test_plugin"; }

int certcyl_plugin_line_cylinder(const double origin[3], const double direction[3], const double c[7], double t[2]) {
  static int calls = 0;
  (void)origin, (void)direction, (void)c, (void)t;
  if (++calls == 2) return -1;
  if (calls == 5) raise(SIGSEGV);
  return CERTCYL_SEPARATED;
}

int certcyl_plugin_ray_cylinder(const double origin[3], const double direction[3], const double c[7], double t[2]) {
  static int calls = 0;
  (void)origin, (void)direction, (void)c, (void)t;
  if (++calls == 3)
    for (;;) pause();
  return CERTCYL_SEPARATED;
}

int certcyl_plugin_segment_cylinder(const double p0[3], const double p1[3], const double c[7], double t[2]) {
  static int calls = 0;
  (void)p0, (void)p1, (void)c, (void)t;
  return ++calls == 2 ? 7 : CERTCYL_SEPARATED;
}

int certcyl_plugin_triangle_cylinder(const double v[9], const double c[7]) {
  static int calls = 0;
  (void)v, (void)c;
  if (++calls == 100) abort();
  return CERTCYL_SEPARATED;
}
