/* tests/scene_helpers.h — small scenes, pixel counting and failure pictures
 * shared by the pipeline tests (test_raster*.c, test_watertight*.c,
 * test_cull.c, test_depth.c, test_shading.c, test_pipeline.c,
 * test_draw_errors.c). Per-pixel hit counting is in hit_counter.h, the
 * reference coverage of a triangle in raster_reference.h.
 *
 * Everything is static inline so each test file takes what it uses. A failing
 * rendering test leaves pictures to open, as PortableGL's tests do: under
 * build/test-output/ (relative to $SOFTRAST_ROOT when set, else the current
 * directory) NAME.png is what was drawn, NAME_expected.png what should have
 * been, NAME_diff.png marks the differences (red: drawn but not expected,
 * blue: expected but missing, magenta: both but different) and NAME.txt lists
 * the first differing pixels.
 */
#ifndef SOFTRAST_TESTS_SCENE_HELPERS_H
#define SOFTRAST_TESTS_SCENE_HELPERS_H

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include <criterion/criterion.h>
#include <cglm/cglm.h>
#include <cglm/clipspace/ortho_lh_zo.h>
#include <cglm/clipspace/persp_lh_zo.h>
#include <cglm/clipspace/view_lh.h>

#include "softrast_private.h"
#include "test_rng.h" /* deterministic random numbers */

#define SCENE_BACKGROUND 0x000000u
#define SCENE_OUTPUT_DIR "build/test-output"
#define SCENE_REPORT_PIXELS 32 /* differing pixels listed in NAME.txt */
#define SCENE_PATH_MAX 1024

#define SCENE_DIFF_EXTRA 0xFF0000u   /* drawn, not expected */
#define SCENE_DIFF_MISSING 0x0000FFu /* expected, not drawn */
#define SCENE_DIFF_CHANGED 0xFF00FFu /* both drawn, different values */
#define SCENE_DIFF_SAME 0x404040u    /* drawn and expected alike */

/* ---- meshes ---- */

/* A mesh described by borrowed arrays; NULL attributes are absent. */
typedef struct scene_mesh_arrays {
    uint32_t vertex_count;
    const float (*positions)[3];
    const float (*normals)[3];
    const float (*uvs)[2];
    const float (*colors)[3];
    uint32_t index_count;
    const uint32_t *indices;
    sr_topology topology;
} scene_mesh_arrays;

/* Copies the arrays into a mesh the test frees with sr_mesh_free. */
static inline void scene_mesh_make(sr_mesh *mesh, const scene_mesh_arrays *a)
{
    sr_error err = { "" };
    cr_assert(sr_mesh_alloc(mesh, a->vertex_count, a->index_count, a->normals != NULL, a->uvs != NULL,
                            a->colors != NULL, &err),
              "sr_mesh_alloc: %s", err.message);
    memcpy(mesh->positions, a->positions, a->vertex_count * sizeof(vec3));
    if (a->normals)
        memcpy(mesh->normals, a->normals, a->vertex_count * sizeof(vec3));
    if (a->uvs)
        memcpy(mesh->uvs, a->uvs, a->vertex_count * sizeof(vec2));
    if (a->colors)
        memcpy(mesh->colors, a->colors, a->vertex_count * sizeof(vec3));
    if (a->index_count)
        memcpy(mesh->indices, a->indices, a->index_count * sizeof(uint32_t));
    mesh->topology = a->topology;
}

/* One triangle (0, 1, 2) of positions only. */
static inline void scene_triangle_make(sr_mesh *mesh, const float pos[3][3])
{
    const uint32_t idx[3] = { 0, 1, 2 };
    scene_mesh_make(mesh, &(scene_mesh_arrays){ .vertex_count = 3, .positions = pos, .index_count = 3,
                                                .indices = idx });
}

/* A triangle list of `triangles` slots and `vertices` positions, zeroed, for
 * tests that fill positions and indices themselves. */
static inline void scene_mesh_alloc(sr_mesh *mesh, uint32_t vertices, uint32_t triangles, bool colors)
{
    sr_error err = { "" };
    cr_assert(sr_mesh_alloc(mesh, vertices, 3 * triangles, false, false, colors, &err), "sr_mesh_alloc: %s",
              err.message);
}

/* ---- cameras and draw descriptions ---- */

/* An orthographic projection whose world units are pixels: world (x, y)
 * lands on pixel coordinate (x, y) (top-left origin, y down) and world z in
 * [0, 1] is z_ndc. Every step is exact in float for x, y on the 1/256 grid
 * when width and height are powers of two, so the snapped vertex is exactly
 * the input. */
static inline void scene_pixel_ortho(sr_draw_desc *desc, int width, int height)
{
    glm_mat4_identity(desc->world);
    glm_mat4_identity(desc->view);
    glm_ortho_lh_zo(0.0f, (float)width, (float)height, 0.0f, 0.0f, 1.0f, desc->projection);
}

/* A one-triangle white list in pixel space (x, y in pixels, y down; z = z_ndc),
 * for scene_pixel_ortho. */
static inline void scene_pixel_triangle(sr_mesh *mesh, const float xy[3][2], float z)
{
    scene_mesh_alloc(mesh, 3, 1, true);
    for (uint32_t k = 0; k < 3; k++) {
        mesh->positions[k][0] = xy[k][0];
        mesh->positions[k][1] = xy[k][1];
        mesh->positions[k][2] = z;
        mesh->colors[k][0] = mesh->colors[k][1] = mesh->colors[k][2] = 1.0f;
        mesh->indices[k] = k;
    }
}

/* Draws mesh with the pixel-space camera; returns the stats of this draw. */
static inline sr_stats scene_draw_pixel_space(sr_framebuffer *fb, const sr_mesh *mesh, sr_shade shade, sr_cull cull,
                                              sr_front front)
{
    sr_draw_desc desc = { .mesh = mesh, .shade = shade, .cull = cull, .front = front };
    scene_pixel_ortho(&desc, fb->width, fb->height);
    sr_stats stats = { 0 };
    sr_error err = { "" };
    cr_assert(sr_draw(fb, &desc, &stats, &err), "sr_draw: %s", err.message);
    return stats;
}

/* View and projection of a look-at camera for a width x height target. */
static inline void scene_camera_desc(sr_draw_desc *desc, const sr_camera *cam, int width, int height)
{
    glm_mat4_identity(desc->world);
    sr_camera_view(cam, desc->view);
    sr_camera_projection(cam, (float)width / (float)height, desc->projection);
}

static inline sr_camera scene_camera(float ex, float ey, float ez, float tx, float ty, float tz, float fov_deg,
                                     float near, float far)
{
    return (sr_camera){ .eye = { ex, ey, ez }, .target = { tx, ty, tz }, .up = { 0.0f, 1.0f, 0.0f },
                        .fov_deg = fov_deg, .near = near, .far = far };
}

/* The world-space direction of the ray through the point (px, py) of the
 * image in pixel units (a pixel centre is (i + 0.5, j + 0.5)), scaled so its
 * component along the view direction is 1 (so a hit at eye + t * dir has view
 * depth t). Computed in double from the camera alone, independently of the
 * matrices the pipeline uses. */
static inline void scene_pixel_ray(const sr_camera *cam, int width, int height, double px, double py,
                                   double dir[3])
{
    double f[3], up[3] = { cam->up[0], cam->up[1], cam->up[2] }, r[3], u[3];
    double len = 0.0;
    for (int k = 0; k < 3; k++) {
        f[k] = (double)cam->target[k] - cam->eye[k];
        len += f[k] * f[k];
    }
    for (int k = 0; k < 3; k++)
        f[k] /= sqrt(len);
    /* Left-handed: right = up x forward, true up = forward x right. */
    r[0] = up[1] * f[2] - up[2] * f[1];
    r[1] = up[2] * f[0] - up[0] * f[2];
    r[2] = up[0] * f[1] - up[1] * f[0];
    len = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
    for (int k = 0; k < 3; k++)
        r[k] /= len;
    u[0] = f[1] * r[2] - f[2] * r[1];
    u[1] = f[2] * r[0] - f[0] * r[2];
    u[2] = f[0] * r[1] - f[1] * r[0];
    double t = tan(cam->fov_deg * GLM_PI / 360.0), aspect = (double)width / height;
    double x_ndc = 2.0 * px / width - 1.0, y_ndc = 1.0 - 2.0 * py / height;
    for (int k = 0; k < 3; k++)
        dir[k] = f[k] + r[k] * x_ndc * t * aspect + u[k] * y_ndc * t;
}

/* z_ndc of glm_perspective_lh_zo at view depth d. */
static inline double scene_depth_ndc(double near, double far, double d)
{
    return far / (far - near) * (1.0 - near / d);
}

/* The per-pixel loops a draw may ask for (sr_draw_study.simd), scalar first. */
static const sr_simd scene_loops[] = { SR_SIMD_SCALAR, SR_SIMD_SSE2, SR_SIMD_AVX2, SR_SIMD_AVX512 };
#define SCENE_LOOPS (sizeof scene_loops / sizeof *scene_loops)

/* The loops this CPU (and build) has, into out; returns how many. */
static inline size_t scene_available_loops(sr_simd out[SCENE_LOOPS])
{
    size_t n = 0;
    for (size_t l = 0; l < SCENE_LOOPS; l++)
        if (sr_raster_simd_resolve(scene_loops[l]) == scene_loops[l])
            out[n++] = scene_loops[l];
    return n;
}

/* One draw of *base on a per-pixel loop and path (SR_PATH_DIRECT on one
 * thread; SR_PATH_TILES or SR_PATH_ROWS on more), with a workspace of its
 * own; *stats gets this draw's counts. Returns the calls the draw made to a
 * SIMD kernel or tiny queue shader (sr_workspace_simd_draws): 0 on the
 * scalar loop, and what tells that a vector loop really ran. */
static inline uint64_t scene_draw_on_loop(sr_framebuffer *fb, const sr_draw_desc *base, sr_simd simd, int threads,
                                          sr_draw_path path, sr_stats *stats)
{
    sr_error err = { "" };
    sr_workspace *ws = sr_workspace_create();
    cr_assert_not_null(ws);
    sr_draw_desc desc = *base;
    desc.study = &(sr_draw_study){ .simd = simd, .path = path };
    desc.threads = threads;
    desc.workspace = ws;
    *stats = (sr_stats){ 0 };
    cr_assert(sr_draw(fb, &desc, stats, &err), "sr_draw: %s", err.message);
    uint64_t draws = sr_workspace_simd_draws(ws);
    sr_workspace_destroy(ws);
    return draws;
}

/* A fresh width x height framebuffer with *desc drawn on loop `simd` on
 * one thread, asserting that the loop ran: a vector loop called its
 * kernels, the scalar loop none (a scene that is drawn and not tiny). */
static inline void scene_draw_fresh_on_loop(sr_framebuffer *fb, int width, int height, const sr_draw_desc *desc,
                                            sr_simd simd, sr_stats *stats)
{
    sr_error err = { "" };
    cr_assert(sr_framebuffer_create(fb, width, height, &err), "sr_framebuffer_create: %s", err.message);
    sr_framebuffer_clear(fb, SCENE_BACKGROUND);
    uint64_t calls = scene_draw_on_loop(fb, desc, simd, 1, SR_PATH_DIRECT, stats);
    cr_assert_eq(calls > 0, simd != SR_SIMD_SCALAR, "%s loop: %llu kernel calls", sr_simd_name(simd),
                 (unsigned long long)calls);
}

/* ---- shading by its formulas ---- */

/* Lambert's constants as documented (docs/bench-compare.md: ambient 0.2,
 * albedo gray 0.8), written here, not taken from shade.h. */
#define SCENE_LAMBERT_AMBIENT 0.2
#define SCENE_LAMBERT_GRAY 0.8

/* The lambert intensity of normal n (any length) under the unit light
 * direction l, in double: ambient + (1 − ambient)·max(0, n·l / |n|). */
static inline double scene_lambert(const double n[3], const double l[3])
{
    double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    double d = (n[0] * l[0] + n[1] * l[1] + n[2] * l[2]) / len;
    return SCENE_LAMBERT_AMBIENT + (1.0 - SCENE_LAMBERT_AMBIENT) * (d > 0.0 ? d : 0.0);
}

/* A channel in 0..1 as 8 bits, as the shader's contract says: clamped,
 * times 255, rounded to nearest. */
static inline uint32_t scene_channel(double c)
{
    c = c < 0 ? 0 : c > 1 ? 1 : c;
    return (uint32_t)lround(c * 255);
}

static inline uint32_t scene_rgb(double r, double g, double b)
{
    return scene_channel(r) << 16 | scene_channel(g) << 8 | scene_channel(b);
}

/* ---- framebuffers ---- */

static inline void scene_fb_make(sr_framebuffer *fb, int width, int height)
{
    sr_error err = { "" };
    cr_assert(sr_framebuffer_create(fb, width, height, &err), "sr_framebuffer_create: %s", err.message);
    sr_framebuffer_clear(fb, SCENE_BACKGROUND);
}

static inline size_t scene_pixel_count(const sr_framebuffer *fb)
{
    return (size_t)fb->width * (size_t)fb->height;
}

/* Pixels of exactly this color. */
static inline size_t scene_count_color(const sr_framebuffer *fb, uint32_t color)
{
    size_t n = 0;
    for (size_t i = 0; i < scene_pixel_count(fb); i++)
        n += fb->color[i] == color;
    return n;
}

/* Pixels not of the background color. */
static inline size_t scene_count_drawn(const sr_framebuffer *fb)
{
    return scene_pixel_count(fb) - scene_count_color(fb, SCENE_BACKGROUND);
}

/* Pixels whose depth is below the clear value. */
static inline size_t scene_count_depth_written(const sr_framebuffer *fb)
{
    size_t n = 0;
    for (size_t i = 0; i < scene_pixel_count(fb); i++)
        n += fb->depth[i] < SR_DEPTH_CLEAR;
    return n;
}

/* ---- failure pictures ---- */

static inline void scene_output_path(char *out, const char *name, const char *suffix)
{
    const char *root = getenv("SOFTRAST_ROOT");
    snprintf(out, SCENE_PATH_MAX, "%s%s" SCENE_OUTPUT_DIR "/%s%s", root ? root : "", root ? "/" : "", name,
             suffix);
}

static inline void scene_output_dir(void)
{
    char path[SCENE_PATH_MAX];
    const char *root = getenv("SOFTRAST_ROOT");
    snprintf(path, sizeof path, "%s%sbuild", root ? root : "", root ? "/" : "");
    mkdir(path, 0777);
    scene_output_path(path, "", "");
    mkdir(path, 0777);
}

/* Writes build/test-output/NAME SUFFIX.png; a failure to write is logged, not fatal. */
static inline void scene_write_png(const char *name, const char *suffix, const uint32_t *pixels, int width,
                                   int height)
{
    char path[SCENE_PATH_MAX], file_suffix[64];
    sr_error err = { "" };
    scene_output_dir();
    snprintf(file_suffix, sizeof file_suffix, "%s.png", suffix);
    scene_output_path(path, name, file_suffix);
    if (!sr_image_write_png(path, pixels, width, height, &err))
        cr_log_warn("could not write %s: %s", path, err.message);
}

/* Opens build/test-output/NAME.txt for the list of differing pixels (NULL if it cannot). */
static inline FILE *scene_report_open(const char *name)
{
    char path[SCENE_PATH_MAX];
    scene_output_dir();
    scene_output_path(path, name, ".txt");
    FILE *f = fopen(path, "w");
    if (!f)
        cr_log_warn("could not write %s: %s", path, strerror(errno));
    return f;
}

/* Compares two color images. When they differ, writes NAME.png, NAME_expected.png,
 * NAME_diff.png and NAME.txt, and fills `first` (if given) with a one-line
 * description of the first difference. Returns the number of differing pixels. */
static inline size_t scene_compare_images(const char *name, const uint32_t *actual, const uint32_t *expected,
                                          int width, int height, char *first, size_t first_size)
{
    size_t n = (size_t)width * (size_t)height, bad = 0;
    for (size_t i = 0; i < n; i++)
        bad += actual[i] != expected[i];
    if (first && first_size)
        first[0] = '\0';
    if (bad == 0)
        return 0;
    uint32_t *diff = malloc(n * sizeof *diff);
    cr_assert_not_null(diff);
    FILE *report = scene_report_open(name);
    if (report)
        fprintf(report, "%s: %zu of %zu pixels differ (x y: drawn expected, 0x00RRGGBB)\n", name, bad, n);
    size_t listed = 0;
    for (size_t i = 0; i < n; i++) {
        uint32_t a = actual[i], e = expected[i];
        diff[i] = a == e ? (a == SCENE_BACKGROUND ? SCENE_BACKGROUND : SCENE_DIFF_SAME)
                : e == SCENE_BACKGROUND ? SCENE_DIFF_EXTRA
                : a == SCENE_BACKGROUND ? SCENE_DIFF_MISSING
                                        : SCENE_DIFF_CHANGED;
        if (a == e)
            continue;
        int x = (int)(i % (size_t)width), y = (int)(i / (size_t)width);
        if (listed == 0 && first)
            snprintf(first, first_size, "first at (%d, %d): drawn 0x%06x, expected 0x%06x", x, y, a, e);
        if (report && listed < SCENE_REPORT_PIXELS)
            fprintf(report, "%d %d: 0x%06x 0x%06x\n", x, y, a, e);
        listed++;
    }
    if (report)
        fclose(report);
    scene_write_png(name, "", actual, width, height);
    scene_write_png(name, "_expected", expected, width, height);
    scene_write_png(name, "_diff", diff, width, height);
    free(diff);
    return bad;
}

/* Asserts (non-fatally) that two color images are equal, leaving pictures if not. */
#define scene_expect_images_equal(name, actual, expected, width, height)                                    \
    do {                                                                                                       \
        char scene_first_[256];                                                                                \
        size_t scene_bad_ = scene_compare_images((name), (actual), (expected), (width), (height), scene_first_, \
                                                 sizeof scene_first_);                                         \
        cr_expect_eq(scene_bad_, 0, "%s: %zu pixels differ, %s; see " SCENE_OUTPUT_DIR "/%s*", (name),         \
                     scene_bad_, scene_first_, (name));                                                        \
    } while (0)

/* Coverage (nonzero) as white on black, for pictures of masks. */
static inline void scene_mask_to_image(const unsigned char *mask, size_t n, uint32_t *out)
{
    for (size_t i = 0; i < n; i++)
        out[i] = mask[i] ? 0xFFFFFFu : SCENE_BACKGROUND;
}

#endif
