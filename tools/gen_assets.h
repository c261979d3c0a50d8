/* tools/gen_assets.h — shared by the three files of the asset generator.
 *
 * gen_assets.c   main: which asset goes into which file (meshes, materials,
 *                the room's layout, the quad3x3 documentation); checked output
 * gen_obj.c      the OBJ writer
 * gen_meshes.c   the shape emitters
 * gen_textures.c the procedural textures and their PNG output
 *
 * Everything is deterministic: no clock, no random seed, fixed iteration
 * order, so `make assets` writes the same bytes every time. Any failure
 * prints "gen-assets: error: ..." and exits non-zero.
 */
#ifndef SOFTRAST_TOOLS_GEN_ASSETS_H
#define SOFTRAST_TOOLS_GEN_ASSETS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include <cglm/cglm.h>

/* ---- errors and checked file output (gen_assets.c) ---------------------- */

_Noreturn void gen_fail(const char *fmt, ...)
    __attribute__((format(printf, 1, 2)));
/* dir + "/" + name into buf, failing if it does not fit. */
void gen_path(char *buf, size_t size, const char *dir, const char *name);
FILE *gen_open(const char *path);
void gen_printf(FILE *file, const char *path, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
void gen_close(FILE *file, const char *path);

/* ---- OBJ writer (gen_obj.c) --------------------------------------------- */

/* Maps a shape's own uv in [0,1] to the file's uv: (u0 + su*u, v0 + sv*v).
 * Lets one emitter draw into a whole texture or into one atlas cell. */
typedef struct uv_map {
    float u0, v0, su, sv;
} uv_map;

#define UV_WHOLE ((uv_map){0.0f, 0.0f, 1.0f, 1.0f})

/* Distinct printed lines of one kind (v, vt or vn) and their 1-based ids.
 * Keying on the printed text welds every pair of points that a reader would
 * parse to the same floats, so shared edges are shared exactly. */
typedef struct obj_pool {
    char **keys;
    long *ids;
    size_t cap, count;
} obj_pool;

/* Text gathered in memory until the writer flushes it. */
typedef struct text_buf {
    char *data;
    size_t len, cap;
} text_buf;

/* Lines are grouped as Blender groups them: each object's new v, then vt,
 * then vn, then its usemtl and f lines; indices count from the file start. */
typedef struct obj_writer {
    FILE *file;
    const char *path;
    obj_pool v, vt, vn;
    text_buf v_text, vt_text, vn_text, body; /* not yet written */
    long triangles;
    mat4 model;         /* applied to every position */
    mat3 normal_matrix; /* inverse transpose of model's 3x3 */
    uv_map uv;          /* applied to every uv */
} obj_writer;

/* One face corner: 1-based indices into v, vt, vn. */
typedef struct obj_corner {
    long v, vt, vn;
} obj_corner;

/* Opens path and writes the header; mtllib may be NULL. The obj_object
 * that follows a usemtl starts a new group: say usemtl after obj_object. */
void obj_open(obj_writer *w, const char *path, const char *mtllib);
/* Closes the file, frees the pools and prints the one-line summary. */
void obj_close(obj_writer *w);
void obj_object(obj_writer *w, const char *name);
void obj_usemtl(obj_writer *w, const char *material);
/* Sets the placement applied by everything emitted afterwards. */
void obj_place(obj_writer *w, mat4 model, uv_map uv);
void obj_place_identity(obj_writer *w);

long obj_vertex(obj_writer *w, vec3 p);
long obj_vertex_rgb(obj_writer *w, vec3 p, vec3 rgb);
long obj_uv(obj_writer *w, float u, float v);
long obj_normal(obj_writer *w, vec3 n);
obj_corner obj_corner_at(obj_writer *w, vec3 p, vec3 n, float u, float v);
/* A polygon, counter-clockwise seen from the side its normals face. */
void obj_face(obj_writer *w, int count, const obj_corner *corners);
void obj_tri(obj_writer *w, obj_corner a, obj_corner b, obj_corner c);
/* Two triangles (a,b,c) and (a,c,d). */
void obj_quad(obj_writer *w, obj_corner a, obj_corner b, obj_corner c,
              obj_corner d);

/* ---- shape emitters (gen_meshes.c); all in the writer's placement ------- */

/* A rectangle origin + s*eu + t*ev (s, t in [0,1]) facing eu x ev, cut into
 * cells no longer than `tile` on each side. Each cell gets its own uv range
 * [0, cell/tile], so a texture repeats once per tile without any uv passing
 * 1 — the room atlas depends on that. */
typedef struct grid_quad {
    vec3 origin, eu, ev;
    float tile;
} grid_quad;

void emit_grid_quad(obj_writer *w, const grid_quad *q);
/* Axis-aligned box lo..hi; faces outward, or inward (a room) if asked. */
void emit_box(obj_writer *w, vec3 lo, vec3 hi, float tile, bool inward);
/* One face of that box: the one on the lo (sign < 0) or hi (sign > 0) side
 * of axis 0 (x), 1 (y) or 2 (z). */
void emit_box_face(obj_writer *w, vec3 lo, vec3 hi, int axis, float sign,
                   float tile, bool inward);
/* Centred at the origin, poles on the y axis. */
void emit_uv_sphere(obj_writer *w, float radius, int segments, int rings);
/* Centred at the origin, ring in the xz plane (y is the axis). */
void emit_torus(obj_writer *w, float major, float minor, int segments,
                int sides);
/* Closed cylinder on the y axis from y = 0 to y = height. */
void emit_cylinder(obj_writer *w, float radius, float height, int segments,
                   float tile);

/* ---- textures (gen_textures.c) ------------------------------------------ */

#define TEXTURE_SIZE 256 /* pixels per side of every texture and atlas cell */
#define ATLAS_CELLS 2    /* room.png is ATLAS_CELLS x ATLAS_CELLS textures */

/* The four textures of room.png. Cell c sits at image column c % ATLAS_CELLS
 * and image row c / ATLAS_CELLS counted from the top, so the floor is the
 * top-left quarter and the checker the bottom-left one. */
typedef enum atlas_cell {
    ATLAS_FLOOR,   /* square floor tiles */
    ATLAS_BRICK,   /* running-bond bricks */
    ATLAS_CHECKER, /* the same picture as checker.png */
    ATLAS_STONE,   /* large ashlar blocks */
    ATLAS_COUNT
} atlas_cell;

/* The uv_map that puts a shape's [0,1] uv inside one atlas cell, inset by
 * half a texel so that bilinear filtering never reads a neighbouring cell. */
uv_map atlas_uv(atlas_cell cell);
void write_checker_png(const char *path);
void write_room_png(const char *path);

#endif
