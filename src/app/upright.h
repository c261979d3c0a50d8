/* upright.h — the world turn that shows a scene upright: the file's up axis
 * to softrast's +y, as a rotation of the look-at camera's world, never a
 * change of the positions (docs/conventions.md, "Axes and units"). */
#ifndef SOFTRAST_APP_UPRIGHT_H
#define SOFTRAST_APP_UPRIGHT_H

#include "io/load_report.h"
#include "softrast_private.h"

/* The rotation of softrast's world that turns `up` (an axis of the file's
 * frame) to +y: in the file's frame the smallest turn that does it, about
 * z for ±x and -y and about x for ±z, so +z stays the front where it can
 * and a +z-up file's front (-y, Blender's) comes to +z, facing the default
 * camera; seen through the loader's z flip when z_negated. A signed
 * permutation: exact in float. */
void sr_upright_matrix(sr_axis up, bool z_negated, mat4 out);

/* lo/hi turned by m (a signed permutation), and origin with them. */
void sr_upright_bounds(const mat4 m, vec3 lo, vec3 hi, double origin[3]);

#endif
