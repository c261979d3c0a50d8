/* softrast.h — a software rasterizer that never breaks: draw a triangle mesh
 * into color and depth buffers you own, on the CPU.
 *
 *     #include "softrast/softrast.h"     // cc … $(pkg-config --cflags --libs softrast)
 *
 *     uint32_t color[640 * 480]; float depth[640 * 480];
 *     sr_framebuffer fb = { .width = 640, .height = 480, .color = color, .depth = depth };
 *     sr_framebuffer_clear(&fb, 0x000000);
 *
 *     sr_camera cam = sr_camera_default();          // at -z, looking at the origin
 *     sr_draw_desc desc = { .mesh = &mesh };        // every zero field is a default
 *     sr_camera_view(&cam, desc.view);
 *     sr_camera_projection(&cam, 640.0f / 480.0f, desc.projection);
 *
 *     sr_stats stats = { 0 };
 *     sr_error err;
 *     if (!sr_draw(&fb, &desc, &stats, &err))
 *         fprintf(stderr, "%s\n", err.message);
 *
 * What happens inside: every triangle is clipped in homogeneous clip space
 * against -w <= x, y <= w, 0 <= z <= w (Sutherland–Hodgman, watertight cut
 * vertices), fanned before the divide, snapped to 1/256 pixel, culled on its
 * exact area, rasterized with 64-bit edge functions and the top-left rule,
 * depth-tested on z_ndc (LESS, cleared to 1) and shaded with perspective-
 * correct varyings. Conventions (left-handed, Direct3D style; column-vector
 * cglm matrices, clip = P·V·W·p) are in docs/conventions.md.
 *
 * This header is the core library: it needs libc, libm, pthreads and cglm,
 * nothing else. Files (OBJ meshes, PNG textures, PNG and PFM output) are in
 * softrast/files.h (library softrast-files, on SDL2_image); measuring the
 * pipeline itself (accuracy knobs, a per-triangle trace) in softrast/study.h.
 * The caller owns every buffer; a function that can fail on input returns
 * false with one line in an sr_error. Non-finite or degenerate geometry is
 * dropped and counted in sr_stats, never drawn and never a crash.
 */
#ifndef SOFTRAST_H
#define SOFTRAST_H

#include <stdbool.h>
#include <stdint.h>
#include <cglm/cglm.h>

#if defined(__GNUC__)
#define SR_API __attribute__((visibility("default")))
#else
#define SR_API
#endif

/* ---- errors ------------------------------------------------------------ */

/* One line, without the "softrast: error: " prefix a program adds; parse
 * errors start with "FILE:LINE: ". Every function taking an sr_error * also
 * takes NULL, which discards the message. */
#define SR_ERROR_MAX 512
typedef struct sr_error {
    char message[SR_ERROR_MAX];
} sr_error;

/* ---- meshes ------------------------------------------------------------ */

typedef enum sr_topology {
    SR_TRIANGLE_LIST = 0, /* triangle k = (i[3k], i[3k+1], i[3k+2]) */
    SR_TRIANGLE_STRIP,    /* triangle k = (i[k], i[k+1], i[k+2]); odd k swaps its last two */
    SR_POINT_LIST,        /* point k = i[k]: a square of sr_draw_desc.point_size pixels */
    SR_LINE_LIST,         /* line k = (i[2k], i[2k+1]) */
    SR_LINE_STRIP         /* line k = (i[k], i[k+1]) */
} sr_topology;

/* A run of triangle slots that came from one part of a file: an OBJ's
 * group, or a node's instance of a mesh in a scene (softrast/files.h), in
 * the file's order. With materials (sr_mesh.materials), a part's triangles
 * are drawn with its material; parts then follow each other
 * (first_triangle increasing, no overlap), and a triangle in no part takes
 * material 0. */
typedef struct sr_mesh_part {
    uint32_t first_triangle, triangle_count;
    uint32_t material; /* an index of sr_mesh.materials; ignored without materials */
} sr_mesh_part;

/* ---- textures ---------------------------------------------------------- */

/* Sides up to this keep every texel index below 2^28 (the SIMD kernels'
 * 32-bit lanes); loaders refuse larger images and a draw a larger texture. */
#define SR_MAX_TEXTURE_SIDE 16384

/* Texels 0x00RRGGBB, row 0 at the top of the image; wrap = repeat, uv (0, 0)
 * is the bottom-left. With `alpha`, texels are 0xAARRGGBB and the top byte
 * is the texel's alpha (255 opaque), which a MASK material tests; without,
 * every texel is opaque and the top byte is never read. Colours are shaded
 * from the low 24 bits either way. Fill one with memory of your own, or load
 * one (softrast/files.h). */
typedef struct sr_texture {
    int width, height;
    uint32_t *texels; /* width * height, row-major, top row first */
    bool alpha;       /* the top byte of each texel is its alpha */
} sr_texture;

/* ---- materials --------------------------------------------------------- */

/* How a material's alpha (the base colour factor's times its texture's)
 * draws. MASK discards a fragment whose alpha is below alpha_cutoff: no
 * depth and no colour is written there, so a cut-out (a leaf, a fence) is a
 * hole in every buffer. BLEND is blended by its alpha in a draw that
 * blends (sr_draw_desc.blend), and drawn as MASK with a cutoff of 0.5 in
 * one that replaces. */
typedef enum sr_alpha_mode { SR_ALPHA_OPAQUE = 0, SR_ALPHA_MASK, SR_ALPHA_BLEND } sr_alpha_mode;

/* What lambert and texture shading draw a part with (glTF's metallic-
 * roughness base colour, without the metal and the roughness). The albedo
 * is base_color's RGB times the texel at the uv (with a texture, on a mesh
 * with uvs) or times the vertex colour (without a texture, on a mesh with
 * colours and no textured material); else base_color's RGB alone. Under
 * SR_COLOR_SRGB the texture is sRGB and base_color linear, as in glTF; the
 * alpha is never encoded. A texture needs the mesh's uvs: without
 * them it is ignored, as lambert ignores desc's texture. Other modes (id,
 * normal, color, depth) ignore the materials' colours, and draw their
 * coverage: what MASK cuts (or BLEND drawn as MASK) is a hole there too,
 * so depth and ids agree with the colour image. */
typedef struct sr_material {
    float base_color[4];       /* RGBA, 0..1 */
    const sr_texture *texture; /* optional (NULL) */
    sr_alpha_mode alpha_mode;
    float alpha_cutoff;        /* MASK: alpha below it is discarded (glTF's default is 0.5) */
    /* A loader's: where the texture is, for sr_texture_load; or NULL. A
     * material with a path and no texture draws desc's texture, so code
     * that loads mesh->texture_path into desc->texture draws as before. */
    char *texture_path;
} sr_material;

/* An indexed triangle mesh in plain arrays, positions in softrast's
 * left-handed world. A triangle with a repeated index is degenerate and
 * skipped (a strip's way of restarting); triangle ids count the slots of the
 * topology from 0, degenerate ones included. The point and line topologies
 * draw the same arrays as points or segments (docs/conventions.md, "Points
 * and lines"): a line with a repeated index is skipped, and ids count
 * points or lines as they count triangles.
 *
 * Positions are float and relative to the double `origin` (world position =
 * origin + position; zero makes them absolute): a mesh 1e7 from the world
 * origin keeps its float precision that way, and the draw adds the origin in
 * double (docs/precision.md). Bounds are relative to the origin too.
 *
 * A mesh built in code may point at arrays of its own (sr_mesh_free is then
 * not for it); sr_mesh_alloc and the loaders make meshes that own theirs. */
typedef struct sr_mesh {
    uint32_t vertex_count;
    vec3 *positions;
    /* Optional: positions already in clip space (x, y, z, w), as conformance
     * suites write their cases. When given, the draw uses them as they are
     * (no world, view or projection matrix; positions may then be NULL) and
     * clips them exactly as it clips transformed ones. sr_mesh_free frees it. */
    vec4 *clip_positions;
    vec3 *normals; /* optional (NULL) */
    vec2 *uvs;     /* optional; v = 0 is the bottom row of the texture */
    vec3 *colors;  /* optional; 0..1 RGB, linear under SR_COLOR_SRGB */
    uint32_t index_count;
    uint32_t *indices;
    sr_topology topology;
    double origin[3];   /* world position = origin + position; zero: positions are absolute */
    bool bounded;       /* bounds_lo/hi hold the positions' bounds (sr_mesh_update_bounds) */
    vec3 bounds_lo, bounds_hi;
    char *texture_path; /* a loader's: the used material's map_Kd, or NULL */
    bool z_negated;     /* a loader's: positions are the file's with z negated (right-handed files
                           in softrast's left-handed world); sr_pinhole poses undo it */
    uint32_t part_count; /* a loader's: the file's parts as runs of triangle ids; 0 for one */
    sr_mesh_part *parts;
    /* Optional: the parts' materials, each part drawn with its own in one
     * draw (lambert and texture shading). 0: every triangle drawn as
     * always, with desc's texture. sr_mesh_free frees the array and the
     * texture paths, not the textures. */
    uint32_t material_count;
    sr_material *materials;
    /* Optional, a loader's: the file's face each triangle slot came from,
     * counted from 0 in the file's order (a polygon of n corners is fanned
     * into n − 2 triangles that name it), one per triangle slot. NULL:
     * triangle i is face i.
     * sr_mesh_free frees it. */
    uint32_t *file_faces;
} sr_mesh;

/* Allocates zeroed arrays for the attributes asked for. False on overflow or
 * out of memory (mesh left empty). */
SR_API bool sr_mesh_alloc(sr_mesh *mesh, uint32_t vertex_count, uint32_t index_count, bool normals, bool uvs,
                          bool colors, sr_error *err);
SR_API void sr_mesh_free(sr_mesh *mesh);

/* Axis-aligned bounds of the positions; false for a mesh with no vertices or
 * with a non-finite position. */
SR_API bool sr_mesh_bounds(const sr_mesh *mesh, vec3 lo, vec3 hi);

/* Stores the bounds in the mesh so a draw can skip clipping for a mesh
 * inside the view and skip a mesh outside it. Call it again after moving
 * positions (a mesh with stale bounds draws wrongly, one without bounds just
 * draws without the shortcut). */
SR_API void sr_mesh_update_bounds(sr_mesh *mesh);

/* Sets where positions are measured from. False, with one line in err, if
 * origin is not finite; the mesh is then unchanged. */
SR_API bool sr_mesh_set_origin(sr_mesh *mesh, const double origin[3], sr_error *err);

/* Fills in smooth vertex normals (area-weighted face normals, front faces
 * clockwise as seen from outside) when the mesh has none. False if out of
 * memory. The normals array is then the caller's to free. */
SR_API bool sr_mesh_compute_normals(sr_mesh *mesh, sr_error *err);

/* Number of triangle slots the topology defines (ids run over these); 0
 * for the point and line topologies. */
SR_API uint32_t sr_mesh_triangle_slots(const sr_mesh *mesh);

/* ---- the framebuffer --------------------------------------------------- */

/* Color is 0x00RRGGBB per pixel, row 0 at the top; depth is float32 z_ndc in
 * [0, 1]. The framebuffer owns the depth convention: standard (the default)
 * clears to 1.0 and keeps the nearer fragment with LESS; reversed_z clears to
 * 0.0 and tests GREATER, for a camera with reversed_z, which spreads float
 * precision evenly over distance. The caller owns the memory: either
 * sr_framebuffer_create/destroy, or fill the struct with buffers of its own.
 *
 * ids is optional (NULL: none): where it is given, every draw writes the
 * triangle id + 1 of each fragment that passes the depth test there, the
 * value SR_SHADE_ID writes to color, whatever the shading; clearing sets it
 * to 0. So one draw gives the shaded image and what each pixel shows (what
 * sr_pinhole_resolve reads), and a draw without the plane pays nothing for
 * it. */
#define SR_MAX_FRAMEBUFFER_SIDE 16384
#define SR_DEPTH_CLEAR 1.0f          /* standard: nothing drawn */
#define SR_DEPTH_CLEAR_REVERSED 0.0f /* reversed_z: nothing drawn */

typedef struct sr_framebuffer {
    int width, height;
    uint32_t *color; /* width * height */
    float *depth;    /* width * height */
    bool reversed_z; /* clear to 0, test GREATER */
    uint32_t *ids;   /* optional, width * height: triangle id + 1 where drawn, 0 where cleared */
} sr_framebuffer;

/* Color and depth, no ids. False (with a message) for a side < 1 or >
 * SR_MAX_FRAMEBUFFER_SIDE, or out of memory. */
SR_API bool sr_framebuffer_create(sr_framebuffer *fb, int width, int height, sr_error *err);
/* Gives a framebuffer of sr_framebuffer_create an ids plane, zeroed (none
 * yet: a new one; one already: kept). False (with a message, fb unchanged)
 * when out of memory. */
SR_API bool sr_framebuffer_create_ids(sr_framebuffer *fb, sr_error *err);
/* Frees the planes sr_framebuffer_create and sr_framebuffer_create_ids made. */
SR_API void sr_framebuffer_destroy(sr_framebuffer *fb);
/* Color to `color`, depth to the clear value of fb's convention, ids (if any) to 0. */
SR_API void sr_framebuffer_clear(sr_framebuffer *fb, uint32_t color);

/* The clear value of fb's depth convention. */
SR_API float sr_framebuffer_depth_clear(const sr_framebuffer *fb);

/* The range of depths actually written (finite and not the clear value); false if none. */
SR_API bool sr_framebuffer_depth_range(const sr_framebuffer *fb, float *lo, float *hi);

/* Depth as gray into out (width * height, 0x00RRGGBB): the written range
 * maps from white (near) to dark gray (far), whichever the convention;
 * background is black. */
SR_API void sr_framebuffer_depth_to_gray(const sr_framebuffer *fb, uint32_t *out);

/* The same view of a function of depth that increases with distance, such as
 * the linear view distance (sr_camera_view_distance): the written range of
 * map(depth) goes from white (smallest) to dark gray. */
typedef double (*sr_depth_map)(float depth, const void *ctx);
SR_API void sr_framebuffer_depth_to_gray_mapped(const sr_framebuffer *fb, sr_depth_map map, const void *ctx,
                                                uint32_t *out);

/* ---- the camera -------------------------------------------------------- */

/* A 4x4 matrix in double, laid out as cglm's mat4 (m[column][row], column
 * vectors), for large world coordinates; all zero in a desc: "not given". */
typedef struct sr_dmat4 {
    double m[4][4];
} sr_dmat4;

/* A look-at camera and its projection. Left-handed (+x right, +y up, +z
 * forward): view = glm_lookat_lh, projection = glm_perspective_lh_zo
 * (vertical fov) or glm_ortho_lh_zo, mapping view depth near → z_ndc 0 and
 * far → 1. reversed_z maps near → 1 and far → 0 (draw into a reversed_z
 * framebuffer); far = +inf (perspective only) puts the far plane at infinity.
 *
 * eye and target are float and relative to the double `origin` (world point
 * = origin + eye; zero makes them absolute), so a camera 1e7 from the world
 * origin still moves in small steps: put the origin at or near the eye, and
 * give the draw sr_camera_view_d as view_d. */
#define SR_CAMERA_FOV 60.0f
#define SR_CAMERA_NEAR 0.1f
#define SR_CAMERA_FAR 100.0f

typedef struct sr_camera {
    double origin[3];   /* eye and target are relative to it */
    vec3 eye, target, up;
    float fov_deg;      /* vertical */
    float near, far;
    float ortho_height; /* > 0: orthographic with this view height */
    bool reversed_z;    /* near → z_ndc 1, far → 0 */
} sr_camera;

/* At -z looking at the origin, up +y, 60°, near 0.1, far 100. */
SR_API sr_camera sr_camera_default(void);

/* Points the camera at the centre of [lo, hi] (relative to the camera's
 * origin, as eye and target are) from a three-quarter view: from -z,
 * turned 30° toward +x and raised 20° toward +y. Far enough back that the
 * bounding sphere fits the vertical and horizontal fov; near and far
 * fitted to it (sr_camera_fit_clip). */
SR_API void sr_camera_frame_bounds(sr_camera *cam, const vec3 lo, const vec3 hi, float aspect);

/* Keeps near and far while the bounding sphere of [lo, hi] lies between
 * them along the view axis (or the eye is inside it and far reaches past
 * it); else far goes just past the sphere and near just before it (an eye
 * inside keeps its near), near staying above 1e-5 of far. So a scene of any
 * size and distance is drawn whole, with the depth precision the contract's
 * 0.1 .. 100 would not give it. */
SR_API void sr_camera_fit_clip(sr_camera *cam, const vec3 lo, const vec3 hi);

/* False, with one line in err, for a camera no matrix can be built from. */
SR_API bool sr_camera_check(const sr_camera *cam, sr_error *err);
SR_API void sr_camera_view(const sr_camera *cam, mat4 out);
/* look-at from eye to target, after a translation by -origin, in double. */
SR_API void sr_camera_view_d(const sr_camera *cam, sr_dmat4 *out);
SR_API void sr_camera_projection(const sr_camera *cam, float aspect, mat4 out);

/* The view-space distance along the view axis of a point stored with depth
 * z_ndc (inverts the projection); camera is the sr_camera. Fits sr_depth_map. */
SR_API double sr_camera_view_distance(float z_ndc, const void *camera);

/* ---- the draw ---------------------------------------------------------- */

typedef enum sr_shade {
    SR_SHADE_LAMBERT = 0, /* one directional light on the albedo (texture, vertex color or gray) */
    SR_SHADE_ID,          /* triangle id + 1, all 32 bits (a PNG shows its low 24 as 0xRRGGBB) */
    SR_SHADE_COLOR,       /* vertex colors */
    SR_SHADE_NORMAL,      /* world normal mapped to 0.5 + 0.5 n */
    SR_SHADE_TEXTURE,     /* texture at the interpolated uv */
    SR_SHADE_DEPTH,       /* depth only; color is left as it was */
    SR_SHADE_COUNT
} sr_shade;

typedef enum sr_cull { SR_CULL_BACK = 0, SR_CULL_FRONT, SR_CULL_NONE } sr_cull;
typedef enum sr_front { SR_FRONT_CW = 0, SR_FRONT_CCW } sr_front;
typedef enum sr_filter { SR_FILTER_BILINEAR = 0, SR_FILTER_NEAREST } sr_filter;

/* What a draw's colours mean (docs/conventions.md, "Colour space"). RAW
 * draws them as stored: a texel or colour of 0.5 is lit as 0.5 and written
 * as 128. SRGB takes textures as sRGB-encoded (as image files are), vertex
 * colours and material colours as linear (as glTF says), lights in linear
 * light and writes sRGB, as viewers that manage colour (Blender, the glTF
 * sample viewer) show a file; the command line draws so. Lambert, texture
 * and color shading change with it; id, normal, depth and the ids plane
 * never do. */
typedef enum sr_color_space { SR_COLOR_RAW = 0, SR_COLOR_SRGB } sr_color_space;

/* How a draw's fragments meet the colour already in the framebuffer
 * (docs/conventions.md, "Blending"), with a fragment's alpha a from its
 * material (a BLEND material's base_color alpha times its texel's alpha;
 * 1 for OPAQUE and MASK), or for a mesh without materials its texture's
 * alpha (1 without one). The colour buffer stays 8-bit RGB: it holds no
 * alpha. Under SR_COLOR_SRGB both colours are decoded to linear light,
 * blended there and encoded. Fragments meet the buffer in submission order
 * on every path and thread count, so the result is the same bits. */
typedef enum sr_blend {
    SR_BLEND_REPLACE = 0,  /* the fragment's colour, as every draw did */
    SR_BLEND_ALPHA,        /* src·a + dst·(1 − a) */
    SR_BLEND_ADD,          /* src·a + dst, clamped to 1 */
    SR_BLEND_PREMULTIPLIED /* src + dst·(1 − a), clamped: src already multiplied by a */
} sr_blend;

/* Toward the light: from above, a little left and in front of a camera at -z. */
#define SR_DEFAULT_LIGHT { -0.35f, 0.8f, -0.5f }

/* What one draw did; sr_draw adds to it, so zero it first. */
typedef struct sr_stats {
    uint64_t triangles; /* assembled (non-degenerate) */
    uint64_t rejected;  /* dropped whole: outside one plane, or non-finite */
    uint64_t nonfinite; /* of those, dropped for NaN or inf in a position or a read varying,
                           or a divide past float range */
    uint64_t clipped;   /* crossed at least one plane */
    uint64_t culled;    /* fan triangles dropped as facing away or zero area */
    uint64_t drawn;     /* fan triangles rasterized */
    uint64_t fragments; /* pixels that passed the depth test */
    uint64_t cuts_float, cuts_double, cuts_exact; /* cut vertices by the precision the clipper used */
    /* Of the rejected, those outside a plane, in the order near, far, left,
     * right, bottom, top: each under the first plane all its corners are
     * outside, or (a mesh rejected whole by its bounds) the first its
     * bounding box is outside. With nonfinite they sum to rejected. */
    uint64_t rejected_by_plane[6];
    /* A point or line draw counts its primitives here, and in rejected,
     * nonfinite, rejected_by_plane, clipped, drawn, fragments and the cuts
     * as a triangle draw counts its triangles; triangles and culled stay 0
     * (a triangle draw's counts are what they always were). */
    uint64_t points, lines; /* assembled (a line with two distinct indices) */
} sr_stats;

/* Scratch memory and worker threads a draw reuses from frame to frame
 * (transformed vertices, tile bins; the threads of a draw with threads > 1,
 * asleep between draws and ended by sr_workspace_destroy; the time each
 * thread's rows took, by which the next draw of the mesh splits them:
 * never a pixel changes with it). Optional: a draw without one makes and
 * frees its own, so its memory is fresh pages, faulted in again at their
 * first touch, its threads start anew and its row split has no measured
 * costs to follow, every time: keep one for a loop of draws (the viewer
 * and the benchmarks do; docs/performance.md, "Threads and the
 * workspace"). One workspace serves one draw at a
 * time: never use it from two threads at once, nor in a child of fork()
 * (the child has none of its threads). */
typedef struct sr_workspace sr_workspace;
SR_API sr_workspace *sr_workspace_create(void); /* NULL when out of memory */
SR_API void sr_workspace_destroy(sr_workspace *ws);

/* softrast/study.h */
typedef struct sr_draw_study sr_draw_study;

/* Every zero field is a default: an all-zero matrix is the identity, shade 0
 * is lambert, cull 0 is back, front 0 is clockwise, filter 0 is bilinear,
 * color_space 0 is raw, blend 0 replaces, a zero light direction is SR_DEFAULT_LIGHT, threads
 * 0 is one. */
typedef struct sr_draw_desc {
    const sr_mesh *mesh;
    mat4 world, view, projection;
    /* Large worlds (docs/precision.md): the world and view in double (all
     * zero: the float ones above), composed with the mesh's origin as
     * P·V·W·T(origin) in double and rounded to float once. */
    sr_dmat4 world_d, view_d;
    sr_shade shade;
    sr_cull cull;
    sr_front front;
    sr_filter filter;
    sr_color_space color_space;
    sr_blend blend;
    bool no_depth_write; /* test depth, but write neither depth nor ids: a translucent layer over opaque ones */
    const sr_texture *texture; /* required by texture shading; lambert uses it when given (a mesh
                                  with materials uses theirs instead) */
    vec3 light_dir;            /* toward the light, world space */
    int threads;               /* threads in all, the caller's included; 0 or 1: one */
    sr_workspace *workspace;   /* optional */
    const sr_draw_study *study; /* optional measurement knobs (softrast/study.h); NULL: the defaults */
    /* true: the draw first clears fb as sr_framebuffer_clear(fb, clear_color)
     * would, on the tiles each tile just before its triangles (while it is
     * in cache, and in parallel), on the row bands each thread its rows
     * before it draws. */
    bool clear;
    uint32_t clear_color;
    /* The point and line topologies (docs/conventions.md, "Points and
     * lines"); ignored by triangles. point_size: the side of a point's
     * square in pixels, 1 .. SR_MAX_POINT_SIZE (0: 1). line_width: rounded
     * to a whole number of pixels, 1 .. SR_MAX_LINE_WIDTH (0: 1); a wider
     * line repeats each pixel of the thin one across its minor axis.
     * depth_bias: moves every point and line fragment this much nearer in
     * z_ndc before its depth test (>= 0), so a line drawn over the
     * triangles it borders passes where their depths tie. */
    float point_size, line_width, depth_bias;
} sr_draw_desc;
#define SR_MAX_POINT_SIZE 256.0f
#define SR_MAX_LINE_WIDTH 64.0f

/* Draws the mesh into fb (which the caller clears, or desc->clear). False, with a message,
 * for a desc that cannot be drawn: no mesh, an index out of range, a shading
 * mode whose inputs the mesh lacks (normals, uvs, colors, texture), a
 * non-finite mesh origin; then fb is untouched. Out of memory for the tile
 * bins or the row bands is also false, found before fb is touched. Bad
 * geometry (NaN, inf, anything behind the eye) is not an error: it is
 * dropped or clipped and counted in stats. Where the draw's cost estimate
 * says they pay (softrast/study.h, sr_draw_study.path), threads share the
 * draw and the screen is cut into tiles or bands (strips of whole rows);
 * the image, depth and counts are bit-identical for every thread count
 * and every path. */
SR_API bool sr_draw(sr_framebuffer *fb, const sr_draw_desc *desc, sr_stats *stats, sr_error *err);

/* sr_draw of a mesh as its materials mean it (docs/conventions.md,
 * "Blending"), what the command line, its datasets and Python draw: the
 * parts of OPAQUE and MASK materials first, in one draw, then under
 * lambert and texture shading each part of a BLEND material in a draw of
 * its own, farthest first by the distance from the eye of its bounds'
 * centre, alpha-blended over what is drawn, depth-tested and writing no
 * depth and no ids. So depth and ids (and sr_pinhole_resolve's outputs)
 * hold the surfaces behind a BLEND part, whatever the shading: id, normal,
 * color and depth shading, which picture those buffers and ignore
 * materials' colours, leave the BLEND parts out. A desc that already blends or
 * keeps its depth, a mesh of no BLEND part, of strips, of points or lines
 * or of clip positions: one sr_draw of desc as it is. stats gets every
 * draw's counts, each triangle once (a BLEND part's triangles are left
 * out of the first draw as degenerate slots, so ids stay the file's). */
SR_API bool sr_draw_layered(sr_framebuffer *fb, const sr_draw_desc *desc, sr_stats *stats, sr_error *err);

/* ---- pinhole cameras ---------------------------------------------------- */

/* A camera as vision pipelines give it, in OpenCV's convention: a point
 * (X, Y, Z) of the camera frame (x right, y down, z forward) lands at
 * u = fx·X/Z + cx, v = fy·Y/Z + cy in pixels, the centre of the top-left
 * pixel being (0, 0) (a centred camera of width W has cx = (W − 1)/2). No
 * skew, no lens distortion. w2c takes a world point to the camera frame;
 * the world is the mesh file's own frame: for a mesh with z_negated (every
 * loader's) the loader's z negation is undone first, so a dataset's poses
 * apply as they are. near and far only clip: 0 fits them to the mesh's
 * bounds (sr_pinhole_fit_clip), so nothing in front of the camera is cut. */
typedef struct sr_pinhole {
    double fx, fy, cx, cy;
    double w2c[4][4]; /* row-major, w2c[row][column]: rigid, last row 0 0 0 1 */
    double near, far;
} sr_pinhole;

/* The largest |RᵀR − I| entry a pose's rotation may have, and of its last
 * row's difference from 0 0 0 1. */
#define SR_POSE_TOLERANCE 1e-5

/* False, with one line in err, for fx or fy not above 0, anything not
 * finite, a pose that is not rigid (within SR_POSE_TOLERANCE; a reflection
 * neither), or clip planes other than 0 < near < far. */
SR_API bool sr_pinhole_check(const sr_pinhole *cam, sr_error *err);

/* The world-to-camera pose of a camera-to-world one (a rigid inverse);
 * false, with one line in err, when c2w is not rigid. */
SR_API bool sr_pinhole_pose_from_c2w(const double c2w[4][4], double w2c[4][4], sr_error *err);

/* Sets near and far where they are 0: the mesh's bounds (those it keeps
 * when `bounded`, else its finite positions') seen from the camera, with
 * room on both sides; near stays above 1e-6 of far. */
SR_API void sr_pinhole_fit_clip(sr_pinhole *cam, const sr_mesh *mesh);

/* The draw's view_d and projection for cam at fb's size (near and far
 * set); world is left as the identity. The projection is reversed z (near
 * → 1, far → 0), so fb is made reversed_z too (clear it in the draw: desc's
 * clear). Culling keeps the file's front faces, as for the look-at camera. */
SR_API void sr_pinhole_matrices(const sr_pinhole *cam, const sr_mesh *mesh, sr_framebuffer *fb, sr_draw_desc *desc);

/* What sr_pinhole_resolve writes per pixel, each width x height values
 * (normals: x 3), row 0 at the top; a NULL array is not wanted. */
typedef struct sr_pinhole_outputs {
    float *depth;     /* z along the optical axis, in mesh units */
    float *range;     /* distance from the camera centre to the surface point */
    uint32_t *face_ids; /* triangle id + 1, or the file's face + 1 (0: nothing drawn) */
    uint32_t *part_ids; /* sr_mesh.parts index + 1, 1 for a mesh of one part (0: nothing drawn) */
    float *normals;   /* unit normal in the camera frame (x right, y down, z forward); 0 where nothing,
                         or where the vertex normals give no direction (zero, or not finite) */
    bool interpolated_normals; /* the vertex normals interpolated at the surface point; false: the
                                  triangle's own, by its winding (the file's front side) */
    float invalid;    /* depth and range where nothing is drawn: 0, or NAN */
    int threads;      /* threads in all, the caller's included; 0 or 1: one */
    bool file_faces;  /* face_ids name the file's face (sr_mesh.file_faces) rather than the triangle */
} sr_pinhole_outputs;

/* The outputs asked for, from ids: the framebuffer of a draw of mesh with
 * cam's matrices, which says what each pixel shows in its ids plane
 * (sr_framebuffer.ids: a draw in any shading gives color and these outputs
 * at once) or, without one, in its color (an SR_SHADE_ID draw). Each
 * pixel's surface point is the ray through its centre met with the plane
 * of the triangle it shows, in double, each value rounded to float once
 * (where the ray runs in that plane, or so nearly that it meets it
 * outside the clip planes, the depth buffer's value gives the point). The threads take chunks of rows as they come; every value is
 * the same for every thread count. A pixel that shows a point or a line takes the
 * primitive's point nearest its ray (a point's vertex; a line's closest
 * approach to the ray, clamped to the part of the segment drawn, between
 * the clip planes), its normal the vertex normals there, whichever
 * `interpolated_normals` says. False, with one
 * line in err, for a mesh without positions, normals asked of a mesh
 * without vertex normals where they are needed, a camera sr_pinhole_check
 * refuses or whose clip planes are unset, or an ids plane that is no draw
 * of mesh (an id past its primitives, or one naming a vertex it lacks:
 * the outputs are then partly written). */
SR_API bool sr_pinhole_resolve(const sr_pinhole *cam, const sr_mesh *mesh, const sr_framebuffer *ids,
                               const sr_pinhole_outputs *out, sr_error *err);

#endif
