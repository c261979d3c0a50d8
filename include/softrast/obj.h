/* softrast/obj.h — Wavefront OBJ loading.
 *
 * Reads `v` (optionally with r g b, or with a w that is ignored), `vt` (u v,
 * an optional w ignored), `vn`, `f` in the forms v, v/vt, v//vn and v/vt/vn
 * (mixed freely) with positive or negative (relative) indices, polygons,
 * comments (whole-line and trailing), blank lines and CRLF line ends;
 * `mtllib` + `usemtl` give the texture path from the material's `map_Kd`.
 * Other statements (o, g, s, l, p, …) are ignored. OBJ is right-handed: the
 * loader negates z (of positions and normals) and reverses each face's
 * winding, so outward faces are front faces (clockwise on screen) in
 * softrast's left-handed convention. A face c0 … c(n-1) becomes triangles
 * (c0, ck, c(k+1)), k = 1 … n-2, written as (c0, c(k+1), ck); triangle ids
 * count them in file order.
 *
 * The mesh: a TriangleList in which each distinct v/vt/vn combination used by
 * a face becomes one vertex, numbered in order of first use (a file without
 * faces gives an empty mesh, which is not an error). normals / uvs exist iff
 * some face corner gives vn / vt; corners without one get (0,0,0) / (0,0).
 * colors exist iff some `v` has r g b; the other vertices are white.
 * texture_path is the first `map_Kd` of a material that a face is drawn
 * with, resolved against the .mtl's folder (the .mtl against the OBJ's).
 * Coordinates are read in double. A mesh far from the world origin — the
 * centre of its bounds more than SR_MESH_RECENTRE_RATIO (16) times their
 * largest side away — is stored relative to that centre (computed in
 * double), which becomes mesh->origin; any other mesh keeps its positions as
 * written and origin zero (mesh.h, docs/precision.md).
 *
 * Errors: false with "FILE:LINE: what" in err (or "FILE: what" when the file
 * cannot be read); the mesh is left zeroed, never half-filled, whatever it
 * held before (it is not freed: pass an empty or freed mesh). Errors include
 * a malformed or non-finite number, a wrong count of numbers, an index that
 * is 0 or outside the elements read so far, a malformed face corner, a face
 * of fewer than 3 vertices, a line over 64 KiB or with a NUL byte, a missing
 * material library and, once a library is loaded, a `usemtl` of a material it
 * does not define. Loading is one pass, O(file size).
 */
#ifndef SOFTRAST_OBJ_H
#define SOFTRAST_OBJ_H

#include <stdbool.h>

#include "error.h"
#include "mesh.h"

bool sr_obj_load(sr_mesh *mesh, const char *path, sr_error *err);

#endif
