/* upright.h — the world turn that shows a scene upright: the file's up axis
 * to softrast's +y, as a rotation of the look-at camera's world, never a
 * change of the positions (docs/scene-files.md, "Axes and units"). */
#ifndef SOFTRAST_APP_UPRIGHT_H
#define SOFTRAST_APP_UPRIGHT_H

#include "io/load_report.h"
#include "softrast_private.h"

/* The front a file with this up axis has when it says none: +z (glTF's)
 * for ±x and ±y up, -y (Blender's) for +z up, +y for -z up; so the turn
 * below is the smallest that takes the up axis to +y, about z for ±x and
 * -y and about x for ±z. */
sr_axis sr_upright_default_front(sr_axis up);

/* The rotation of softrast's world that turns `up` (an axis of the file's
 * frame) to +y and `front` to +z of the file's frame, facing the default
 * camera (front not perpendicular to up, or SR_AXIS_COUNT: the up axis's
 * default front); seen through the loader's z flip when z_negated. A
 * signed permutation: exact in float. */
void sr_upright_matrix(sr_axis up, sr_axis front, bool z_negated, mat4 out);

/* lo/hi turned by m (a signed permutation), and origin with them. */
void sr_upright_bounds(const mat4 m, vec3 lo, vec3 hi, double origin[3]);

#endif
