/* softrast/mesh.h — an indexed triangle mesh in plain arrays.
 *
 * A mesh is vertex attribute arrays (positions always; normals, uvs and colors
 * optional, NULL when absent) plus an index array read as a TriangleList or a
 * TriangleStrip. The mesh owns its arrays: build one with sr_mesh_alloc (or a
 * loader such as sr_obj_load) and release it with sr_mesh_free. Positions are
 * in the left-handed world convention of docs/conventions.md.
 *
 * Positions are float and relative to the mesh's double `origin`: the world
 * position is origin + position (zero, the default, makes them absolute).
 * A mesh far from the world origin keeps its float precision that way — a
 * float at 1e7 is 1 unit apart — and the draw adds the origin in double
 * (vertex.h, docs/precision.md). Bounds are relative to the origin too.
 */
#ifndef SOFTRAST_MESH_H
#define SOFTRAST_MESH_H

#include <stdbool.h>
#include <stdint.h>
#include <cglm/cglm.h>

#include "error.h"

typedef enum sr_topology {
    SR_TRIANGLE_LIST = 0,  /* triangle k = (i[3k], i[3k+1], i[3k+2]) */
    SR_TRIANGLE_STRIP      /* triangle k = (i[k], i[k+1], i[k+2]); odd k swaps its last two */
} sr_topology;

typedef struct sr_mesh {
    uint32_t vertex_count;
    vec3 *positions;
    vec3 *normals;    /* optional */
    vec2 *uvs;        /* optional; v = 0 is the bottom row of the texture */
    vec3 *colors;     /* optional; linear 0..1 RGB */
    uint32_t index_count;
    uint32_t *indices;
    sr_topology topology;
    double origin[3];    /* world position = origin + position; zero: positions are absolute */
    bool bounded;        /* bounds_lo/hi hold the positions' bounds (sr_mesh_update_bounds) */
    vec3 bounds_lo, bounds_hi;
    char *texture_path; /* the used material's map_Kd (relative to the .mtl's folder, the .mtl to the OBJ's), or NULL */
} sr_mesh;

/* A loader stores positions relative to the centre of their bounds when the
 * centre is more than this many times the bounds' largest side from the
 * world origin (largest coordinate, ∞-norm): there absolute float positions
 * would lose over 4 of their 24 bits to the offset. Nearer meshes keep their
 * positions as written. */
#define SR_MESH_RECENTRE_RATIO 16.0

/* Allocates zeroed arrays for the attributes asked for. False on overflow or
 * out of memory (mesh left empty). */
bool sr_mesh_alloc(sr_mesh *mesh, uint32_t vertex_count, uint32_t index_count,
                   bool normals, bool uvs, bool colors, sr_error *err);
void sr_mesh_free(sr_mesh *mesh);

/* Axis-aligned bounds of the positions; false for a mesh with no vertices or
 * with a non-finite position. */
bool sr_mesh_bounds(const sr_mesh *mesh, vec3 lo, vec3 hi);

/* Stores the bounds in the mesh so a draw can skip clipping for a mesh
 * inside the view and skip a mesh outside it. Loaders and shapes call it;
 * call it again after moving positions (a mesh with stale bounds draws
 * wrongly, one without bounds just draws without the shortcut). */
void sr_mesh_update_bounds(sr_mesh *mesh);

/* Sets where positions are measured from (a mesh built in code around its
 * own centre, placed far away). False, with one line in err, if origin is
 * not finite; the mesh is then unchanged. */
bool sr_mesh_set_origin(sr_mesh *mesh, const double origin[3], sr_error *err);

/* The origin a loader gives positions with bounds [lo, hi] (in double):
 * their centre if it lies over SR_MESH_RECENTRE_RATIO times the largest
 * side from the world origin, else zero. */
void sr_mesh_origin_for_bounds(const double lo[3], const double hi[3], double origin[3]);

/* Fills in smooth vertex normals (area-weighted face normals, front faces
 * clockwise as seen from outside) when the mesh has none. False if out of memory. */
bool sr_mesh_compute_normals(sr_mesh *mesh, sr_error *err);

/* Number of triangle slots the topology defines (ids run over these). */
uint32_t sr_mesh_triangle_slots(const sr_mesh *mesh);

#endif
