/* tests/line_oracle.c — the hidden-line oracle (line_oracle.h). */
#include "line_oracle.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/dmat4.h"
#include "pipeline/01_vertex.h"
#include "pipeline/02_assemble.h"

#define CELL 8 /* pixels a side of a grid cell */

/* A drawn triangle through a screen point (sx, sy) in NDC: v = inv·(sx, sy,
 * 1) are the weights with Σ v_i·(x_i, y_i, w_i) on the ray there; the
 * plane's point is in front of the eye for Σ v > 0, inside the triangle
 * for every v_i ≥ 0, and its z_ndc is Σ v_i·z_i. */
typedef struct occluder {
    double inv[3][3];
    double z[3];
    uint32_t corner[3];
} occluder;

struct line_oracle {
    const sr_mesh *mesh;
    int width, height, cells_x, cells_y;
    bool reversed_z;
    double (*clip)[4];
    bool *drawn; /* per slot */
    occluder *tris;
    uint32_t *cell_start, *cell_items; /* each cell's occluders: cell_items[cell_start[c] .. cell_start[c + 1]) */
};

static double det3(const double m[3][3])
{
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

/* The occluder of corners c[3], and its det[x y w]. */
static double occluder_of(const line_oracle *o, const uint32_t c[3], occluder *t)
{
    double m[3][3]; /* columns: the corners' (x, y, w) */
    for (int i = 0; i < 3; i++) {
        m[0][i] = o->clip[c[i]][0];
        m[1][i] = o->clip[c[i]][1];
        m[2][i] = o->clip[c[i]][3];
        t->z[i] = o->clip[c[i]][2];
        t->corner[i] = c[i];
    }
    double d = det3((const double(*)[3])m);
    for (int r = 0; r < 3; r++)
        for (int k = 0; k < 3; k++) {
            int r1 = (k + 1) % 3, r2 = (k + 2) % 3, c1 = (r + 1) % 3, c2 = (r + 2) % 3;
            t->inv[r][k] = (m[r1][c1] * m[r2][c2] - m[r1][c2] * m[r2][c1]) / d;
        }
    return d;
}

/* The screen box of corners c in cells, the whole screen when one is not
 * in front of the eye. */
static void cell_box(const line_oracle *o, const uint32_t c[3], int box[4])
{
    double lo[2] = { INFINITY, INFINITY }, hi[2] = { -INFINITY, -INFINITY };
    for (int i = 0; i < 3; i++) {
        const double *v = o->clip[c[i]];
        if (!(v[3] > 0.0)) {
            lo[0] = lo[1] = -INFINITY;
            hi[0] = hi[1] = INFINITY;
            break;
        }
        double p[2] = { (v[0] / v[3] + 1.0) * o->width / 2.0, (1.0 - v[1] / v[3]) * o->height / 2.0 };
        for (int a = 0; a < 2; a++) {
            lo[a] = fmin(lo[a], p[a]);
            hi[a] = fmax(hi[a], p[a]);
        }
    }
    int cells[2] = { o->cells_x, o->cells_y };
    for (int a = 0; a < 2; a++) {
        double first = floor(lo[a] / CELL) - 1.0, last = floor(hi[a] / CELL) + 1.0;
        box[a] = first < 0.0 ? 0 : first >= cells[a] ? cells[a] : (int)first;
        box[2 + a] = last < 0.0 ? -1 : last >= cells[a] ? cells[a] - 1 : (int)last;
    }
}

static bool kept_by_culling(const sr_draw_desc *desc, double det)
{
    if (det == 0.0 || !isfinite(det))
        return false;
    bool front = desc->front == SR_FRONT_CW ? det < 0.0 : det > 0.0;
    return desc->cull == SR_CULL_NONE || (desc->cull == SR_CULL_BACK) == front;
}

/* The occluders into their cells: counted (fill false), then placed. */
static void bin(line_oracle *o, uint32_t count, bool fill)
{
    uint32_t *next = fill ? o->cell_start : NULL;
    for (uint32_t t = 0; t < count; t++) {
        int box[4];
        cell_box(o, o->tris[t].corner, box);
        for (int cy = box[1]; cy <= box[3]; cy++)
            for (int cx = box[0]; cx <= box[2]; cx++) {
                size_t c = (size_t)cy * o->cells_x + cx;
                if (fill)
                    o->cell_items[next[c]++] = t;
                else
                    o->cell_start[c + 1]++;
            }
    }
}

line_oracle *line_oracle_make(const sr_draw_desc *desc, int width, int height, bool reversed_z)
{
    const sr_mesh *mesh = desc->mesh;
    uint32_t slots = sr_assemble_slots(mesh);
    line_oracle *o = calloc(1, sizeof *o);
    if (!o)
        return NULL;
    *o = (line_oracle){ .mesh = mesh, .width = width, .height = height, .reversed_z = reversed_z,
                        .cells_x = (width + CELL - 1) / CELL, .cells_y = (height + CELL - 1) / CELL };
    size_t cells = (size_t)o->cells_x * o->cells_y;
    o->clip = malloc(((size_t)mesh->vertex_count + 1) * sizeof *o->clip);
    o->drawn = calloc((size_t)slots + 1, sizeof *o->drawn);
    o->tris = malloc(((size_t)slots + 1) * sizeof *o->tris);
    o->cell_start = calloc(cells + 1, sizeof *o->cell_start);
    if (!o->clip || !o->drawn || !o->tris || !o->cell_start) {
        line_oracle_free(o);
        return NULL;
    }
    sr_dmat4 world = sr_dmat4_desc_matrix(&desc->world_d, desc->world);
    sr_dmat4 view = sr_dmat4_desc_matrix(&desc->view_d, desc->view), none = { { { 0 } } };
    sr_dmat4 projection = sr_dmat4_desc_matrix(&none, desc->projection);
    sr_vertex_transform xf;
    sr_vertex_make_transform_d(&world, &view, &projection, mesh->origin, &xf);
    for (uint32_t i = 0; i < mesh->vertex_count; i++)
        sr_vertex_mesh_clip_d(mesh, i, &xf, o->clip[i]);
    uint32_t count = 0;
    for (uint32_t k = 0; k < slots; k++) {
        uint32_t idx[3];
        if (!sr_assemble_triangle(mesh, k, idx))
            continue;
        o->drawn[k] = kept_by_culling(desc, occluder_of(o, idx, &o->tris[count]));
        count += o->drawn[k];
    }
    bin(o, count, false);
    for (size_t c = 0; c < cells; c++)
        o->cell_start[c + 1] += o->cell_start[c];
    o->cell_items = malloc(((size_t)o->cell_start[cells] + 1) * sizeof *o->cell_items);
    if (!o->cell_items) {
        line_oracle_free(o);
        return NULL;
    }
    bin(o, count, true);
    /* bin moved each start to the next cell's: back one cell. */
    for (size_t c = cells; c > 0; c--)
        o->cell_start[c] = o->cell_start[c - 1];
    o->cell_start[0] = 0;
    return o;
}

void line_oracle_free(line_oracle *o)
{
    if (!o)
        return;
    free(o->clip);
    free(o->drawn);
    free(o->tris);
    free(o->cell_start);
    free(o->cell_items);
    free(o);
}

bool line_oracle_drawn(const line_oracle *o, uint32_t k)
{
    return k < sr_assemble_slots(o->mesh) && o->drawn[k];
}

static bool same_place(const line_oracle *o, uint32_t a, uint32_t b)
{
    const sr_mesh *m = o->mesh;
    return a == b || (m->positions && memcmp(m->positions[a], m->positions[b], sizeof(vec3)) == 0);
}

/* Whether the occluder has both a and b as corners, by position. */
static bool owns(const line_oracle *o, const occluder *t, uint32_t a, uint32_t b)
{
    bool has_a = false, has_b = false;
    for (int i = 0; i < 3; i++) {
        has_a = has_a || same_place(o, t->corner[i], a);
        has_b = has_b || same_place(o, t->corner[i], b);
    }
    return has_a && has_b;
}

static bool nearer(const line_oracle *o, double z, double than)
{
    return o->reversed_z ? z > than + LINE_ORACLE_MARGIN : z < than - LINE_ORACLE_MARGIN;
}

/* Whether the point p (clip space) of the edge a-b shows. */
static bool point_shows(const line_oracle *o, const double p[4], uint32_t a, uint32_t b)
{
    double sx = p[0] / p[3], sy = p[1] / p[3], z = p[2] / p[3];
    double px = (sx + 1.0) * o->width / 2.0, py = (1.0 - sy) * o->height / 2.0;
    if (!(px >= 0.0 && py >= 0.0 && px < o->width && py < o->height))
        return false; /* off screen: no pixel's */
    size_t c = (size_t)(py / CELL) * o->cells_x + (size_t)(px / CELL);
    for (uint32_t i = o->cell_start[c]; i < o->cell_start[c + 1]; i++) {
        const occluder *t = &o->tris[o->cell_items[i]];
        double v[3], sum = 0.0, zt = 0.0;
        for (int r = 0; r < 3; r++) {
            v[r] = t->inv[r][0] * sx + t->inv[r][1] * sy + t->inv[r][2];
            sum += v[r];
            zt += v[r] * t->z[r];
        }
        if (!(sum > 0.0) || v[0] < 0.0 || v[1] < 0.0 || v[2] < 0.0 || !(zt >= 0.0 && zt <= 1.0))
            continue;
        if (nearer(o, zt, z) && !owns(o, t, a, b))
            return false;
    }
    return true;
}

/* The parameters [t0, t1] of the segment c0 → c1 (clip space) in
 * 0 ≤ z ≤ w with w > 0; false when it has none. */
static bool between_near_and_far(const double c0[4], const double c1[4], double *t0, double *t1)
{
    /* z ≥ 0, w − z ≥ 0 and w > 0, each linear in t. */
    double f0[3] = { c0[2], c0[3] - c0[2], c0[3] }, f1[3] = { c1[2], c1[3] - c1[2], c1[3] };
    *t0 = 0.0;
    *t1 = 1.0;
    for (int k = 0; k < 3; k++) {
        double d = f1[k] - f0[k];
        if (d == 0.0) {
            if (f0[k] < 0.0 || (k == 2 && f0[k] == 0.0))
                return false;
        } else if (d > 0.0) {
            *t0 = fmax(*t0, -f0[k] / d);
        } else {
            *t1 = fmin(*t1, -f0[k] / d);
        }
    }
    return *t0 < *t1;
}

/* The parameters [u0, u1] of the screen segment s0 → s1 (pixels) in the
 * square lo..hi (Liang–Barsky); false when it misses it. */
static bool in_square(const double s0[2], const double s1[2], const double lo[2], const double hi[2], double *u0,
                      double *u1)
{
    *u0 = 0.0;
    *u1 = 1.0;
    for (int a = 0; a < 2; a++) {
        double d = s1[a] - s0[a];
        if (d == 0.0) {
            if (s0[a] < lo[a] || s0[a] > hi[a])
                return false;
            continue;
        }
        double ta = (lo[a] - s0[a]) / d, tb = (hi[a] - s0[a]) / d;
        *u0 = fmax(*u0, fmin(ta, tb));
        *u1 = fmin(*u1, fmax(ta, tb));
    }
    return *u0 <= *u1;
}

bool line_oracle_shows_in(const line_oracle *o, uint32_t a, uint32_t b, int x, int y, double slack)
{
    double t0, t1, c0[4], c1[4];
    if (!between_near_and_far(o->clip[a], o->clip[b], &t0, &t1))
        return false;
    for (int k = 0; k < 4; k++) {
        c0[k] = o->clip[a][k] + t0 * (o->clip[b][k] - o->clip[a][k]);
        c1[k] = o->clip[a][k] + t1 * (o->clip[b][k] - o->clip[a][k]);
    }
    double s0[2] = { (c0[0] / c0[3] + 1.0) * o->width / 2.0, (1.0 - c0[1] / c0[3]) * o->height / 2.0 };
    double s1[2] = { (c1[0] / c1[3] + 1.0) * o->width / 2.0, (1.0 - c1[1] / c1[3]) * o->height / 2.0 };
    double lo[2] = { x - slack, y - slack }, hi[2] = { x + 1 + slack, y + 1 + slack }, u0, u1;
    if (!in_square(s0, s1, lo, hi, &u0, &u1))
        return false;
    double length = (u1 - u0) * hypot(s1[0] - s0[0], s1[1] - s0[1]);
    int n = 1 + (int)ceil(length * LINE_ORACLE_SAMPLES);
    for (int i = 0; i <= n; i++) {
        /* Screen parameter u to the segment's: s = u·w0 / ((1 − u)·w1 + u·w0). */
        double u = u0 + (u1 - u0) * i / n, s = u * c0[3] / ((1.0 - u) * c1[3] + u * c0[3]), p[4];
        for (int k = 0; k < 4; k++)
            p[k] = c0[k] + s * (c1[k] - c0[k]);
        if (point_shows(o, p, a, b))
            return true;
    }
    return false;
}

