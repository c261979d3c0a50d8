/* mesh_bounds.h — the bounds of a mesh's finite positions, for what must
 * not give up on a vertex at NaN or inf (the draw drops such a vertex's
 * primitives and counts them): fitted clip planes, the normals' scale.
 * Not public API: sr_mesh_bounds is, and gives up. */
#ifndef SOFTRAST_SCENE_MESH_BOUNDS_H
#define SOFTRAST_SCENE_MESH_BOUNDS_H

#include "softrast/softrast.h"

/* The axis-aligned bounds of the finite positions; false when none is. */
bool sr_mesh_finite_bounds(const sr_mesh *mesh, vec3 lo, vec3 hi);

#endif
