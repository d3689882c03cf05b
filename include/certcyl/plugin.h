/* certcyl/plugin.h -- the C interface of a method judged by `certcyl judge --plugin PATH.so`.
 *
 * A plugin is a shared library exporting certcyl_plugin_name and any of the query functions
 * below; the command judges every query it exports against the certified answers of the study's
 * cases. Each function receives the case's binary64 coordinates and returns one of the answers
 * below; a negative return is an error of the method (counted, not fatal). The plugin runs in a
 * child process: a crash ends the run with the answers given before it kept.
 *
 * A cylinder is 7 doubles: p0[3], p1[3], radius (the solid, closed cylinder around the axis
 * segment p0 p1). A triangle is 9 doubles: three vertices. A line is origin + t direction, a ray
 * the same with t >= 0, a segment p0 + t (p1 - p0) with t in [0, 1]. t[2] receives the parameter
 * interval of a line query when the answer is not separated (may be left unwritten: it starts as
 * NaN). `certcyl judge` scores t[0] against the certified entry parameter, in ulps of
 * max(|t*|, 1) (families.csv's t_error columns), when the answer and the certified answer both
 * say the line meets the cylinder.
 *
 * A plugin may also export certcyl_plugin_contract, returning what its positive answer to a ray
 * or segment promises (the study's contracts, src/study/contract.hpp): "solid" (the default: the
 * set meets the closed solid cylinder), "surface_entry" (a ray cast that reports entering the
 * cylinder from outside: a ray or segment starting in the cylinder is a miss) or "surface_hit"
 * (the first surface point at a positive parameter, an exit counting). Its ray and segment
 * answers are judged against the certified answer under that contract; the other queries under
 * the solid one. `certcyl judge --contract` says the same for an answers file or a program. */
#ifndef CERTCYL_PLUGIN_H
#define CERTCYL_PLUGIN_H

#define CERTCYL_SEPARATED    0
#define CERTCYL_TOUCHING     1
#define CERTCYL_OVERLAPPING  2
#define CERTCYL_INTERSECTING 3   /* the sets meet; for methods that cannot tell touching */
#define CERTCYL_UNDECIDED    4

#ifdef __cplusplus
extern "C" {
#endif

/* a cylinder is 7 doubles: p0[3], p1[3], radius; a triangle 9 doubles; t[2] receives the
   parameter interval of a line query when the answer is not separated (may be ignored) */
const char* certcyl_plugin_name(void);
const char* certcyl_plugin_contract(void); /* optional: "solid", "surface_entry" or "surface_hit" */
int certcyl_plugin_cylinder_cylinder(const double a[7], const double b[7]);
int certcyl_plugin_line_cylinder(const double origin[3], const double direction[3], const double c[7], double t[2]);
int certcyl_plugin_ray_cylinder(const double origin[3], const double direction[3], const double c[7], double t[2]);
int certcyl_plugin_segment_cylinder(const double p0[3], const double p1[3], const double c[7], double t[2]);
int certcyl_plugin_triangle_cylinder(const double v[9], const double c[7]);

#ifdef __cplusplus
}
#endif

#endif
