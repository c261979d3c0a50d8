#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pipeline/04_clip/expansion.h"
#include "core/clock.h"
#include "truth.h"
#include "truth_exact.h"

#define TILE 8                       /* pixels per side of a grid cell */
#define UNIT_ROUNDOFF (DBL_EPSILON / 2.0)
#define BOUND_ROUNDINGS 10.0         /* the error bounds' roundings, with room (at most 6 are needed) */
#define BOX_MARGIN_PX 1e-3           /* a projected vertex's rounding is far below this */
#define PROGRESS_MS 1000.0

/* A triangle that faces the camera the way the cull keeps. */
typedef struct truth_triangle {
    double edge[3][3];     /* edge k, opposite corner k: v[k+1] × v[k+2] (the ray is inside where d·edge has det's sign) */
    double edge_bound[3];  /* |d·edge[k] - exact| <= edge_bound[k]·|d|_1 */
    double det, det_error; /* v0 · (v1 × v2), and a bound on its error */
    uint32_t slot, corner[3];
    uint16_t box[4];       /* pixel columns and rows whose centres it may cover: x0, y0, x1, y1 */
    int sign;              /* the exact sign of det */
} truth_triangle;

typedef struct truth_scene {
    sr_truth_lens lens;
    int width, height;
    double (*verts)[3];    /* view space */
    truth_triangle *tris;
    uint32_t tri_count;
    uint32_t *tile_first;  /* tile t's triangles are tile_tris[tile_first[t] .. tile_first[t+1]) */
    uint32_t *tile_tris;
} truth_scene;

/* The nearest hit at a pixel so far. */
typedef struct truth_hit {
    const truth_triangle *tri;
    double z, rel_error; /* view z and its relative error bound */
} truth_hit;

static bool lens_make(const mat4 p, sr_truth_lens *lens, sr_error *err)
{
    bool perspective = p[2][3] == 1.0f && p[3][3] == 0.0f && p[0][0] > 0.0f && p[1][1] > 0.0f &&
                       p[2][0] == 0.0f && p[2][1] == 0.0f && p[3][0] == 0.0f && p[3][1] == 0.0f &&
                       p[0][1] == 0.0f && p[1][0] == 0.0f && p[0][3] == 0.0f && p[1][3] == 0.0f;
    if (!perspective)
        return sr_error_set(err, "the truth renderer takes a perspective projection (no --ortho)");
    *lens = (sr_truth_lens){ .sx = p[0][0], .sy = p[1][1], .a = p[2][2], .b = p[3][2] };
    double z0 = -lens->b / lens->a, z1 = lens->b / (1.0 - lens->a);
    bool ok0 = z0 > 0.0 && isfinite(z0), ok1 = z1 > 0.0 && isfinite(z1);
    if (!ok0 && !ok1)
        return sr_error_set(err, "the projection has no near plane in front of the eye");
    lens->near_z = ok0 && ok1 ? fmin(z0, z1) : ok0 ? z0 : z1;
    lens->far_z = ok0 && ok1 ? fmax(z0, z1) : INFINITY;
    return true;
}

double sr_truth_z_ndc(const mat4 projection, double distance)
{
    double a = projection[2][2], b = projection[3][2];
    return isinf(distance) ? (a < 0.5 ? 0.0 : 1.0) : a + b / distance;
}

static void transform_vertices(const sr_draw_desc *desc, double (*out)[3])
{
    sr_dmat4 world = sr_dmat4_desc_matrix(&desc->world_d, desc->world);
    sr_dmat4 view = sr_dmat4_desc_matrix(&desc->view_d, desc->view);
    sr_dmat4 vw = sr_dmat4_mul(&view, &world);
    vw = sr_dmat4_translate(&vw, desc->mesh->origin);
    for (uint32_t i = 0; i < desc->mesh->vertex_count; i++) {
        const float *p = desc->mesh->positions[i];
        for (int r = 0; r < 3; r++)
            out[i][r] = vw.m[0][r] * p[0] + vw.m[1][r] * p[1] + vw.m[2][r] * p[2] + vw.m[3][r];
    }
}

/* fl(b × c), and for each component the sum of its products' magnitudes. */
static void cross_with_magnitude(const double b[3], const double c[3], double out[3], double magnitude[3])
{
    for (int i = 0; i < 3; i++) {
        int j = (i + 1) % 3, k = (i + 2) % 3;
        out[i] = b[j] * c[k] - b[k] * c[j];
        magnitude[i] = fabs(b[j] * c[k]) + fabs(b[k] * c[j]);
    }
}

static int orientation(const double *v[3], double *det, double *det_error)
{
    double n[3], m[3];
    cross_with_magnitude(v[1], v[2], n, m);
    *det = v[0][0] * n[0] + v[0][1] * n[1] + v[0][2] * n[2];
    *det_error = BOUND_ROUNDINGS * UNIT_ROUNDOFF * (fabs(v[0][0]) * m[0] + fabs(v[0][1]) * m[1] + fabs(v[0][2]) * m[2]);
    if (fabs(*det) > *det_error)
        return *det > 0.0 ? 1 : -1;
    return sr_truth_orient_exact(v[0], v[1], v[2]);
}

/* Widens the box by the pixel centres around screen point of view point p (z > 0). */
static void box_add(const truth_scene *s, const double p[3], double box[4])
{
    double px = (s->lens.sx * p[0] / p[2] + 1.0) * 0.5 * s->width;
    double py = (1.0 - s->lens.sy * p[1] / p[2]) * 0.5 * s->height;
    box[0] = fmin(box[0], px);
    box[1] = fmin(box[1], py);
    box[2] = fmax(box[2], px);
    box[3] = fmax(box[3], py);
}

/* The pixel box of the triangle's part at z >= z_cut (half the near
 * distance, well before any hit the truth keeps); false if it holds no
 * pixel centre. */
static bool pixel_box(const truth_scene *s, const double *v[3], uint16_t out[4])
{
    double z_cut = 0.5 * s->lens.near_z, box[4] = { INFINITY, INFINITY, -INFINITY, -INFINITY };
    for (int k = 0; k < 3; k++) {
        const double *p = v[k], *q = v[(k + 1) % 3];
        if (p[2] >= z_cut)
            box_add(s, p, box);
        if ((p[2] >= z_cut) != (q[2] >= z_cut)) {
            double t = (z_cut - p[2]) / (q[2] - p[2]), cut[3];
            for (int r = 0; r < 3; r++)
                cut[r] = p[r] + t * (q[r] - p[r]);
            cut[2] = z_cut;
            box_add(s, cut, box);
        }
    }
    double lo_x = ceil(box[0] - BOX_MARGIN_PX - 0.5), hi_x = floor(box[2] + BOX_MARGIN_PX - 0.5);
    double lo_y = ceil(box[1] - BOX_MARGIN_PX - 0.5), hi_y = floor(box[3] + BOX_MARGIN_PX - 0.5);
    lo_x = fmax(lo_x, 0.0), lo_y = fmax(lo_y, 0.0);
    hi_x = fmin(hi_x, s->width - 1.0), hi_y = fmin(hi_y, s->height - 1.0);
    if (!(lo_x <= hi_x && lo_y <= hi_y))
        return false;
    out[0] = (uint16_t)lo_x, out[1] = (uint16_t)lo_y, out[2] = (uint16_t)hi_x, out[3] = (uint16_t)hi_y;
    return true;
}

static bool beyond_depth_range(const sr_truth_lens *lens, const double *v[3])
{
    double lo = fmin(v[0][2], fmin(v[1][2], v[2][2])), hi = fmax(v[0][2], fmax(v[1][2], v[2][2]));
    return hi < 0.5 * lens->near_z || lo > 2.0 * lens->far_z;
}

/* Sets up the triangle in slot k; false if it covers no pixel centre (degenerate, culled, out of view). */
static bool triangle_make(const truth_scene *s, const sr_draw_desc *desc, uint32_t k, truth_triangle *t)
{
    uint32_t idx[3];
    if (!sr_assemble_triangle(desc->mesh, k, idx))
        return false;
    const double *v[3] = { s->verts[idx[0]], s->verts[idx[1]], s->verts[idx[2]] };
    for (int i = 0; i < 9; i++)
        if (!isfinite(v[i / 3][i % 3]))
            return false;
    if (beyond_depth_range(&s->lens, v))
        return false;
    t->sign = orientation(v, &t->det, &t->det_error);
    /* det > 0 turns counter-clockwise on screen: area2 < 0 in the rasterizer's terms. */
    if (t->sign == 0 || !sr_cull_keeps(-t->sign, desc->cull, desc->front) || !pixel_box(s, v, t->box))
        return false;
    for (int e = 0; e < 3; e++) {
        double m[3];
        cross_with_magnitude(v[(e + 1) % 3], v[(e + 2) % 3], t->edge[e], m);
        t->edge_bound[e] = BOUND_ROUNDINGS * UNIT_ROUNDOFF * fmax(m[0], fmax(m[1], m[2]));
        t->corner[e] = idx[e];
    }
    t->slot = k;
    return true;
}

static bool tiles_make(truth_scene *s, sr_error *err)
{
    int tiles_x = (s->width + TILE - 1) / TILE, tiles_y = (s->height + TILE - 1) / TILE;
    size_t tiles = (size_t)tiles_x * tiles_y, entries = 0;
    s->tile_first = calloc(tiles + 1, sizeof *s->tile_first);
    if (!s->tile_first)
        return sr_error_set(err, "out of memory for the truth's grid");
    for (uint32_t i = 0; i < s->tri_count; i++) {
        const uint16_t *b = s->tris[i].box;
        for (int ty = b[1] / TILE; ty <= b[3] / TILE; ty++)
            for (int tx = b[0] / TILE; tx <= b[2] / TILE; tx++, entries++)
                s->tile_first[(size_t)ty * tiles_x + tx + 1]++;
    }
    if (entries > UINT32_MAX)
        return sr_error_set(err, "the truth's grid has more than 2^32 entries");
    for (size_t t = 0; t < tiles; t++)
        s->tile_first[t + 1] += s->tile_first[t];
    s->tile_tris = malloc((entries ? entries : 1) * sizeof *s->tile_tris);
    uint32_t *fill = malloc(tiles * sizeof *fill);
    if (!s->tile_tris || !fill) {
        free(fill);
        return sr_error_set(err, "out of memory for the truth's grid (%zu entries)", entries);
    }
    memcpy(fill, s->tile_first, tiles * sizeof *fill);
    for (uint32_t i = 0; i < s->tri_count; i++) {
        const uint16_t *b = s->tris[i].box;
        for (int ty = b[1] / TILE; ty <= b[3] / TILE; ty++)
            for (int tx = b[0] / TILE; tx <= b[2] / TILE; tx++)
                s->tile_tris[fill[(size_t)ty * tiles_x + tx]++] = i;
    }
    free(fill);
    return true;
}

static bool scene_make(truth_scene *s, const sr_draw_desc *desc, sr_error *err)
{
    const sr_mesh *mesh = desc->mesh;
    if (!mesh || !sr_assemble_indices_valid(mesh))
        return sr_error_set(err, "the truth needs a mesh whose indices are in range");
    uint32_t slots = sr_mesh_triangle_slots(mesh);
    s->verts = malloc((mesh->vertex_count ? mesh->vertex_count : 1) * sizeof *s->verts);
    s->tris = malloc((slots ? slots : 1) * sizeof *s->tris);
    if (!s->verts || !s->tris)
        return sr_error_set(err, "out of memory for the truth's %u triangles", slots);
    transform_vertices(desc, s->verts);
    for (uint32_t k = 0; k < slots; k++)
        s->tri_count += triangle_make(s, desc, k, &s->tris[s->tri_count]);
    return tiles_make(s, err);
}

static void scene_free(truth_scene *s)
{
    free(s->verts);
    free(s->tris);
    free(s->tile_first);
    free(s->tile_tris);
}

static sr_truth_corners corners_of(const truth_scene *s, const truth_triangle *t)
{
    return (sr_truth_corners){ { s->verts[t->corner[0]], s->verts[t->corner[1]], s->verts[t->corner[2]] } };
}

/* The top-left rule for a pixel centre exactly on edge e: it counts when the
 * edge's inward normal on screen (y down) points right, or straight down. */
static bool top_left(const truth_scene *s, const truth_triangle *t, int e)
{
    const double *a = s->verts[t->corner[(e + 1) % 3]], *b = s->verts[t->corner[(e + 2) % 3]];
    int nx = t->sign * sr_truth_cross_sign(a, b, 0);
    return nx > 0 || (nx == 0 && t->sign * sr_truth_cross_sign(a, b, 1) < 0);
}

/* True if the ray passes inside t (or on an edge the top-left rule gives it);
 * e receives d · edge[k] in double. */
static bool covers(const truth_scene *s, const truth_triangle *t, const double d[3], double d_sum,
                   const sr_truth_ray *ray, double e[3])
{
    int uncertain = 0;
    for (int k = 0; k < 3; k++) {
        e[k] = d[0] * t->edge[k][0] + d[1] * t->edge[k][1] + d[2] * t->edge[k][2];
        double side = t->sign * e[k], bound = t->edge_bound[k] * d_sum;
        if (side < -bound)
            return false;
        uncertain |= (side <= bound) << k;
    }
    for (int k = 0; k < 3; k++) {
        if (!(uncertain >> k & 1))
            continue;
        const double *a = s->verts[t->corner[(k + 1) % 3]], *b = s->verts[t->corner[(k + 2) % 3]];
        int side = t->sign * sr_truth_side_exact(ray, a, b);
        if (side < 0 || (side == 0 && !top_left(s, t, k)))
            return false;
    }
    return true;
}

/* -1, 0 or 1 as value is surely below, undecided, surely above 0. */
static int decided_sign(double value, double error)
{
    return value > error ? 1 : value < -error ? -1 : 0;
}

/* True if the hit at z (relative error rel) lies within the near and far planes. */
static bool within_depth(const truth_scene *s, const truth_triangle *t, const sr_truth_ray *ray, double z, double rel)
{
    const sr_truth_lens *l = &s->lens;
    double a_hi, a_lo, over = l->b / z;
    two_sum(l->a, -1.0, &a_hi, &a_lo);
    double over_error = rel < 0.25 && isfinite(over) ? 2.0 * fabs(over) * (rel + 4.0 * UNIT_ROUNDOFF) : INFINITY;
    sr_truth_corners c = corners_of(s, t);
    int near = decided_sign(l->a + over, over_error + 2.0 * UNIT_ROUNDOFF * fabs(l->a));
    if (near == 0)
        near = t->sign * sr_truth_depth_plane_exact(ray, &c, l->a, 0.0, l->b) >= 0 ? 1 : -1;
    if (near < 0)
        return false;
    int far = decided_sign(a_hi + over, over_error + 2.0 * UNIT_ROUNDOFF * fabs(a_hi));
    if (far == 0)
        far = t->sign * sr_truth_depth_plane_exact(ray, &c, a_hi, a_lo, l->b) <= 0 ? -1 : 1;
    return far < 0;
}

/* Negative if the hit h is nearer than best. */
static int compare_hits(const truth_scene *s, const sr_truth_ray *ray, const truth_hit *h, const truth_hit *best)
{
    double slack = h->rel_error < 0.25 && best->rel_error < 0.25
                       ? 1.1 * (h->rel_error * h->z + best->rel_error * best->z)
                       : INFINITY;
    int c = decided_sign(h->z - best->z, slack);
    if (c != 0)
        return c;
    sr_truth_corners a = corners_of(s, h->tri), b = corners_of(s, best->tri);
    return sr_truth_nearer_exact(ray, &a, &b);
}

static void ray_make(const truth_scene *s, int x, int y, sr_truth_ray *ray, double d[3])
{
    double w = s->width, h = s->height;
    two_product((2.0 * x + 1.0 - w) * h, s->lens.sy, &ray->d[0][1], &ray->d[0][0]);
    two_product((h - 2.0 * y - 1.0) * w, s->lens.sx, &ray->d[1][1], &ray->d[1][0]);
    two_product(w * h, s->lens.sx * s->lens.sy, &ray->d[2][1], &ray->d[2][0]);
    for (int k = 0; k < 3; k++)
        d[k] = ray->d[k][1];
}

static void trace_pixel(const truth_scene *s, const uint32_t *list, uint32_t count, int x, int y,
                        sr_truth_image *out)
{
    sr_truth_ray ray;
    double d[3];
    ray_make(s, x, y, &ray, d);
    double d_sum = fabs(d[0]) + fabs(d[1]) + fabs(d[2]);
    truth_hit best = { 0 };
    double runner_up = INFINITY;
    for (uint32_t i = 0; i < count; i++) {
        const truth_triangle *t = &s->tris[list[i]];
        double e[3];
        if (x < t->box[0] || x > t->box[2] || y < t->box[1] || y > t->box[3] || !covers(s, t, d, d_sum, &ray, e))
            continue;
        double sum = e[0] + e[1] + e[2];
        double sum_error = (t->edge_bound[0] + t->edge_bound[1] + t->edge_bound[2]) * d_sum + 3.0 * UNIT_ROUNDOFF * fabs(sum);
        truth_hit h = { .tri = t, .z = t->det / sum * d[2],
                        .rel_error = t->det_error / fabs(t->det) + sum_error / fabs(sum) + 4.0 * UNIT_ROUNDOFF };
        if (!within_depth(s, t, &ray, h.z, h.rel_error))
            continue;
        if (!best.tri) {
            best = h;
        } else if (compare_hits(s, &ray, &h, &best) < 0) {
            runner_up = best.z;
            best = h;
        } else {
            runner_up = fmin(runner_up, h.z);
        }
    }
    size_t p = (size_t)y * s->width + x;
    out->ids[p] = best.tri ? best.tri->slot + 1 : 0;
    out->distance[p] = best.tri ? best.z : INFINITY;
    out->runner_up[p] = runner_up;
}

static void trace(const truth_scene *s, sr_truth_image *out, double start_ms)
{
    int tiles_x = (s->width + TILE - 1) / TILE, tiles_y = (s->height + TILE - 1) / TILE;
    double last_ms = start_ms;
    for (int ty = 0; ty < tiles_y; ty++) {
        for (int tx = 0; tx < tiles_x; tx++) {
            size_t t = (size_t)ty * tiles_x + tx;
            const uint32_t *list = &s->tile_tris[s->tile_first[t]];
            uint32_t count = s->tile_first[t + 1] - s->tile_first[t];
            for (int y = ty * TILE; y < (ty + 1) * TILE && y < s->height; y++)
                for (int x = tx * TILE; x < (tx + 1) * TILE && x < s->width; x++)
                    trace_pixel(s, list, count, x, y, out);
        }
        double now = sr_now_ms();
        if (now - last_ms >= PROGRESS_MS) {
            fprintf(stderr, "truth: %d of %d rows, %.1f s\n", (ty + 1) * TILE < s->height ? (ty + 1) * TILE : s->height,
                    s->height, (now - start_ms) / 1000.0);
            last_ms = now;
        }
    }
}

static bool image_alloc(sr_truth_image *t, int width, int height, sr_error *err)
{
    size_t n = (size_t)width * height;
    *t = (sr_truth_image){ .width = width, .height = height, .ids = malloc(n * sizeof *t->ids),
                           .distance = malloc(n * sizeof *t->distance), .runner_up = malloc(n * sizeof *t->runner_up) };
    if (!t->ids || !t->distance || !t->runner_up) {
        sr_truth_image_free(t);
        return sr_error_set(err, "out of memory for a %dx%d truth image", width, height);
    }
    return true;
}

bool sr_truth_render(const sr_draw_desc *desc, int width, int height, sr_truth_image *out, sr_error *err)
{
    double start_ms = sr_now_ms();
    truth_scene s = { .width = width, .height = height };
    *out = (sr_truth_image){ 0 };
    if (width < 1 || height < 1 || width > SR_MAX_FRAMEBUFFER_SIDE || height > SR_MAX_FRAMEBUFFER_SIDE)
        return sr_error_set(err, "truth image size %dx%d out of range", width, height);
    bool ok = lens_make(desc->projection, &s.lens, err) && scene_make(&s, desc, err) &&
              image_alloc(out, width, height, err);
    if (ok) {
        trace(&s, out, start_ms);
        out->mesh = desc->mesh;
        out->verts = s.verts; /* the image keeps the view-space vertices for truth_outline.h */
        out->lens = s.lens;
        s.verts = NULL;
    }
    double total_ms = sr_now_ms() - start_ms;
    if (ok && total_ms >= PROGRESS_MS)
        fprintf(stderr, "truth: %u triangles in view, %dx%d, %.1f s\n", s.tri_count, width, height, total_ms / 1000.0);
    scene_free(&s);
    return ok;
}

void sr_truth_image_free(sr_truth_image *t)
{
    free(t->ids);
    free(t->distance);
    free(t->runner_up);
    free(t->verts);
    *t = (sr_truth_image){ 0 };
}
