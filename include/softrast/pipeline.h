/* softrast/pipeline.h — the draw call: a mesh through all ten stages.
 *
 *     sr_framebuffer fb;
 *     sr_framebuffer_create(&fb, 640, 480, &err);
 *     sr_framebuffer_clear(&fb, 0x000000);
 *     sr_stats stats = {0};
 *     if (!sr_draw(&fb, &(sr_draw_desc){ .mesh = &mesh, .view = …, .projection = …,
 *                                        .shade = SR_SHADE_LAMBERT }, &stats, &err))
 *         fprintf(stderr, "%s\n", err.message);
 *
 * Every zero field is a default: an all-zero matrix is the identity, shade 0
 * is lambert, cull 0 is back, front 0 is clockwise, filter 0 is bilinear, a
 * zero light direction is SR_DEFAULT_LIGHT. The caller owns the framebuffer,
 * the mesh and the texture; sr_draw only writes pixels and adds to stats.
 * Triangle ids (for SR_SHADE_ID) are the mesh's triangle slots, from 0.
 *
 * Large world coordinates (docs/precision.md): give the mesh an origin
 * (mesh.h) and the world and view in double (world_d, view_d, e.g. from
 * sr_camera_view_d); the draw composes P·V·W·T(mesh origin) in double and
 * rounds it to float once, so a mesh and camera 1e7 from the world origin
 * draw as they would at it.
 *
 * With threads > 1 the screen is cut into SR_TILE_SIDE-pixel tiles: threads
 * transform vertices and set up triangles in ranges, bin the fan triangles
 * into per-tile lists that keep submission order, then each tile is drawn by
 * one thread. The image and depth are bit-identical for every thread count.
 */
#ifndef SOFTRAST_PIPELINE_H
#define SOFTRAST_PIPELINE_H

#include <stdbool.h>
#include <cglm/cglm.h>

#include "clip.h"
#include "dmat4.h"
#include "error.h"
#include "framebuffer.h"
#include "mesh.h"
#include "texture.h"
#include "types.h"

#define SR_TILE_SIDE 64 /* pixels on a side of a tile of the threaded path */
#define SR_MAX_GUARD_BAND 64.0f
/* Snapped coordinates stay below 2^SR_FIXED_POINT_BITS so the 64-bit edge
 * functions cannot overflow whatever the precision asked for. */
#define SR_FIXED_POINT_BITS 30

/* Toward the light: from above, a little left and in front of a camera at -z. */
#define SR_DEFAULT_LIGHT { -0.35f, 0.8f, -0.5f }

/* Scratch memory a draw reuses from frame to frame (transformed vertices,
 * tile bins). Optional: a draw without one makes and frees its own. One
 * workspace serves one draw at a time. */
typedef struct sr_workspace sr_workspace;
sr_workspace *sr_workspace_create(void); /* NULL when out of memory */
void sr_workspace_destroy(sr_workspace *ws);

/* How many rasterizer calls of the last draw with this workspace a SIMD
 * kernel made (a call is a fan triangle, or with threads its share of one
 * tile; narrow ones take the scalar loop): tests check the kernels ran. */
uint64_t sr_workspace_simd_draws(const sr_workspace *ws);

/* Sees every fan triangle that survives culling, before it is rasterized
 * (the viewer's wireframe overlay, tests of the clipper's output). */
typedef void (*sr_triangle_observer)(void *user, const sr_screen_vertex tri[3], bool clipped, uint32_t id);

typedef struct sr_draw_desc {
    const sr_mesh *mesh;
    mat4 world, view, projection;
    sr_dmat4 world_d, view_d;  /* in double; all zero: the float world / view above */
    sr_shade shade;
    sr_cull cull;
    sr_front front;
    sr_filter filter;
    const sr_texture *texture; /* required by texture shading; lambert uses it when given */
    vec3 light_dir;
    sr_triangle_observer observer; /* called in order, from one thread: a draw with one runs on one */
    void *observer_user;
    int threads;               /* threads in all, the caller's included; 0 or 1: one */
    sr_workspace *workspace;
    /* Accuracy knobs, for measuring what each costs (docs/report.md); zero is
     * the default the contract pins. */
    int subpixel_bits;                  /* 0: SR_SUBPIXEL_BITS; else SR_MIN..SR_MAX_SUBPIXEL_BITS */
    sr_clip_precision clip_precision;   /* SR_CLIP_ADAPTIVE: per edge, within half a subpixel step */
    float guard_band;                   /* 0 or 1: clip x, y at the viewport; G > 1: at ±G·w */
    sr_simd simd;                       /* SR_SIMD_AUTO: the best per-pixel loop the CPU has */
} sr_draw_desc;

/* Draws the mesh into fb (which the caller clears). False, with a message,
 * for a desc that cannot be drawn: no mesh, an index out of range, a shading
 * mode whose inputs the mesh lacks (normals, uvs, colors, texture), a
 * non-finite mesh origin. Bad
 * geometry (NaN, inf, anything behind the eye) is not an error: it is dropped
 * or clipped and counted in stats. */
bool sr_draw(sr_framebuffer *fb, const sr_draw_desc *desc, sr_stats *stats, sr_error *err);

#endif
