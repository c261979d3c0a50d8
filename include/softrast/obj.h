/* softrast/obj.h — Wavefront OBJ loading.
 *
 * Reads `v` (optionally with r g b), `vt`, `vn`, `f` in the forms v, v/vt,
 * v//vn and v/vt/vn with positive or negative (relative) indices, polygons,
 * comments, blank lines and CRLF line ends; `mtllib` + `usemtl` give the
 * texture path from the material's `map_Kd`. Other statements (o, g, s, …)
 * are ignored. OBJ is right-handed: the loader negates z and reverses each
 * face's winding, so outward faces are front faces (clockwise on screen) in
 * softrast's left-handed convention. A face c0 … c(n-1) becomes triangles
 * (c0, ck, c(k+1)), k = 1 … n-2, before the reversal; triangle ids count them
 * in file order. Each distinct v/vt/vn combination becomes one vertex.
 *
 * Errors: false with "FILE:LINE: what" in err (or "FILE: what"); the mesh is
 * left empty, never half-filled.
 */
#ifndef SOFTRAST_OBJ_H
#define SOFTRAST_OBJ_H

#include <stdbool.h>

#include "error.h"
#include "mesh.h"

bool sr_obj_load(sr_mesh *mesh, const char *path, sr_error *err);

#endif
