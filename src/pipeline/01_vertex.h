/* 01_vertex.h — stage 1: the vertex stage.
 *
 * Transforms each unique vertex of a mesh once: clip = P·V·W·T(origin)·position
 * (column vectors; origin is the mesh's, docs/precision.md), the product
 * composed in double and rounded to float once, and writes only the
 * varyings the shading mode reads, as
 * sr_varying_layout lays them out (world-space unit normals through the
 * inverse transpose of W, as its cofactor matrix so a singular W is fine).
 */
#ifndef SOFTRAST_PIPELINE_VERTEX_H
#define SOFTRAST_PIPELINE_VERTEX_H

#include <stdint.h>
#include <cglm/cglm.h>

#include "core/dmat4.h"
#include "softrast/softrast.h"
#include "stages.h"

typedef struct sr_vertex_transform {
    mat4 clip_from_object; /* P · V · W · T(origin), rounded from double once */
    sr_dmat4 clip_from_object_d; /* the same before the rounding */
    mat3 normal_matrix;    /* cofactors of W's upper 3x3: a positive multiple of the inverse transpose */
    float normal_bound;    /* normals within it in every component stay finite through normal_matrix */
} sr_vertex_transform;

/* The varyings `shade` reads, given what the mesh and texture provide:
 * color → color; normal → normal; texture → uv; lambert → normal plus the
 * albedo source (uv if textured, else color if the mesh has colors). */
sr_varying_layout sr_vertex_layout(sr_shade shade, const sr_mesh *mesh, bool textured);

/* Composes in double, so the large translations of world·T(origin) and of
 * view cancel before the one rounding; the normal matrix comes from world's
 * upper 3x3. */
void sr_vertex_make_transform_d(const sr_dmat4 *world, const sr_dmat4 *view, const sr_dmat4 *projection,
                                const double origin[3], sr_vertex_transform *xf);

/* The same for float matrices and a mesh whose origin is zero. */
void sr_vertex_make_transform(const mat4 world, const mat4 view, const mat4 projection,
                              sr_vertex_transform *xf);

/* A position's clip coordinates in double, through clip_from_object_d:
 * the unsnapped screen point and depth of a vertex inside every plane, and
 * of a clipped triangle's vertices and cuts, come from them
 * (sr_viewport_map_d), since the float product is off by up to about 1e-4
 * px (docs/precision.md, "Depth from the unsnapped vertices"). Inline: it
 * runs once per vertex. */
static inline void sr_vertex_clip_d(const float p[3], const sr_vertex_transform *xf, double out[4])
{
    const sr_dmat4 *m = &xf->clip_from_object_d;
    for (int r = 0; r < 4; r++)
        out[r] = m->m[0][r] * p[0] + m->m[1][r] * p[1] + m->m[2][r] * p[2] + m->m[3][r];
}

/* Mesh vertex i's clip position in double: its position's
 * (sr_vertex_clip_d), or a clip-space mesh's own, exact as given. */
static inline void sr_vertex_mesh_clip_d(const sr_mesh *mesh, uint32_t i, const sr_vertex_transform *xf,
                                         double out[4])
{
    if (mesh->clip_positions) {
        for (int r = 0; r < 4; r++)
            out[r] = mesh->clip_positions[i][r];
    } else {
        sr_vertex_clip_d(mesh->positions[i], xf, out);
    }
}

/* Runs vertices [first, first + count) of mesh into out[0 .. count), which
 * is 16-byte aligned (cglm's vector stores; an sr_vertex_out is 48 bytes). */
void sr_vertex_run(const sr_mesh *mesh, const sr_vertex_transform *xf, const sr_varying_layout *layout,
                   uint32_t first, uint32_t count, sr_vertex_out *out);

/* The same, with each vertex's outcode under depth (sr_clip_outcode_with)
 * into codes[0 .. count), and the varyings only of the vertices inside
 * every plane (code 0): no other's screen vertex is ever drawn from, and
 * a clipped triangle transforms its corners again. Four vertices at a
 * time in SSE2 lanes, eight in AVX2 ones with avx2 (the draw's SIMD level
 * has it); the same bits as one at a time. */
void sr_vertex_run_inside(const sr_mesh *mesh, const sr_vertex_transform *xf, const sr_varying_layout *layout,
                          const sr_clip_depth *depth, bool avx2, uint32_t first, uint32_t count, sr_vertex_out *out,
                          unsigned char *codes);


/* Whether every varying sr_vertex_run would write for vertex i is finite,
 * told from the mesh's values, without transforming a normal whose size
 * the normal matrix cannot take past float range: the rule of a vertex
 * sr_vertex_run_inside gave no varyings. */
bool sr_vertex_varyings_finite(const sr_mesh *mesh, const sr_vertex_transform *xf, const sr_varying_layout *layout,
                               uint32_t i);

/* True when sr_vertex_varyings_finite holds for every vertex of [first,
 * first + count), decided from bounds on the mesh's values in one pass;
 * false when some vertex may fail it. */
bool sr_vertex_block_finite(const sr_mesh *mesh, const sr_vertex_transform *xf, const sr_varying_layout *layout,
                            uint32_t first, uint32_t count);

#endif
