/* softrast/vertex.h — stage 1: the vertex stage.
 *
 * Transforms each unique vertex of a mesh once: clip = P·V·W·position (cglm,
 * column vectors), and writes only the varyings the shading mode reads, as
 * sr_varying_layout lays them out (world-space unit normals through the
 * inverse transpose of W, as its cofactor matrix so a singular W is fine).
 */
#ifndef SOFTRAST_VERTEX_H
#define SOFTRAST_VERTEX_H

#include <stdint.h>
#include <cglm/cglm.h>

#include "mesh.h"
#include "types.h"

typedef struct sr_vertex_transform {
    mat4 clip_from_object; /* P · V · W */
    mat3 normal_matrix;    /* cofactors of W's upper 3x3: a positive multiple of the inverse transpose */
} sr_vertex_transform;

/* The varyings `shade` reads, given what the mesh and texture provide:
 * color → color; normal → normal; texture → uv; lambert → normal plus the
 * albedo source (uv if textured, else color if the mesh has colors). */
sr_varying_layout sr_vertex_layout(sr_shade shade, const sr_mesh *mesh, bool textured);

void sr_vertex_make_transform(const mat4 world, const mat4 view, const mat4 projection,
                              sr_vertex_transform *xf);

/* Runs vertices [first, first + count) of mesh into out[0 .. count). */
void sr_vertex_run(const sr_mesh *mesh, const sr_vertex_transform *xf, const sr_varying_layout *layout,
                   uint32_t first, uint32_t count, sr_vertex_out *out);

#endif
