/* tests/case_oracle.c — the clipper mirror and the ray-cast coverage oracle
 * of the edge-case scenes (case_oracle.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "case_oracle.h"
#include "clip_helpers.h"
#include "scene_helpers.h"
#include "softrast_private.h"

/* ---- stages 1 to 4, as draw.c runs them ---- */

static bool position_finite(const sr_vertex_out *v)
{
    return isfinite(v->v[SR_X]) && isfinite(v->v[SR_Y]) && isfinite(v->v[SR_Z]) && isfinite(v->v[SR_W]);
}

static double vertex_scale(const sr_vertex_out *v)
{
    double s = 0.0;
    for (int k = 0; k < 4; k++)
        s = fmax(s, fabs((double)v->v[k]));
    return s;
}

static void note_bad(case_clip_report *r, uint32_t k, const sr_vertex_out *v, const char *what)
{
    if (r->bad++ == 0)
        snprintf(r->first_bad, sizeof r->first_bad, "triangle %u: clipper output (%.9g, %.9g, %.9g, %.9g) %s", k,
                 (double)v->v[SR_X], (double)v->v[SR_Y], (double)v->v[SR_Z], (double)v->v[SR_W], what);
}

static void check_polygon(const sr_polygon *poly, int returned, uint32_t k, double tolerance, case_clip_report *r)
{
    if (returned != poly->count || poly->count > SR_MAX_CLIP_VERTS) {
        if (r->bad++ == 0)
            snprintf(r->first_bad, sizeof r->first_bad, "triangle %u: the clipper returned %d, polygon has %d "
                     "vertices (bound %d)", k, returned, poly->count, SR_MAX_CLIP_VERTS);
        return;
    }
    r->max_vertices = poly->count > r->max_vertices ? poly->count : r->max_vertices;
    for (int i = 0; i < poly->count; i++) {
        const sr_vertex_out *v = &poly->vert[i];
        if (!position_finite(v)) {
            note_bad(r, k, v, "is not finite");
            continue;
        }
        double allowed = -tolerance * vertex_scale(v);
        for (int p = 0; p < SR_CLIP_PLANES; p++) {
            double d = ref_distance_f(p, v);
            if (d >= allowed)
                continue;
            char what[96];
            snprintf(what, sizeof what, "is %g outside the %s plane (tolerance %g)", -d, plane_name(p), -allowed);
            note_bad(r, k, v, what);
        }
    }
}

void case_clip_run(const sr_mesh *mesh, const mat4 world, const mat4 view, const mat4 projection, sr_shade shade,
                   int width, int height, double tolerance, case_clip_report *r)
{
    /* As sr_draw configures the clipper by default: the default precision,
     * cut vertices within half a subpixel step in NDC, the projection's depth
     * model for near, far and z_ndc. */
    const sr_clip_depth depth = mesh->clip_positions ? (sr_clip_depth){ .on = false }
                                                     : sr_clip_depth_of((const float(*)[4])projection);
    const sr_viewport vp = { .width = width, .height = height, .subpixel_bits = SR_SUBPIXEL_BITS, .guard = 1.0f,
                             .depth = depth };
    const sr_clip_config cfg = { .ndc_tolerance = 1.0 / ((double)SR_SUBPIXEL_ONE * (width > height ? width : height)),
                                 .depth = depth };
    *r = (case_clip_report){ 0 };
    sr_varying_layout layout = sr_vertex_layout(shade, mesh, false);
    sr_vertex_transform xf;
    sr_vertex_make_transform(world, view, projection, &xf);
    uint32_t n = mesh->vertex_count;
    sr_vertex_out *verts = malloc((n ? n : 1) * sizeof *verts);
    unsigned *codes = malloc((n ? n : 1) * sizeof *codes);
    cr_assert(verts && codes);
    sr_vertex_run(mesh, &xf, &layout, 0, n, verts);
    for (uint32_t i = 0; i < n; i++) {
        codes[i] = sr_clip_outcode_with(verts[i].v, &depth);
        /* The contract (DESIGN.md, the issue): NaN or inf in a position or in
         * a varying the mode reads is non-finite input, dropped before
         * clipping whether the vertex is inside or not; and an inside vertex
         * the viewport cannot divide is dropped too, as the vertex phase does. */
        for (int k = 0; k < layout.count; k++)
            codes[i] = isfinite(verts[i].v[SR_VARYINGS_AT + k]) ? codes[i] : SR_OUT_NONFINITE;
        sr_screen_vertex screen;
        if (codes[i] == 0 && !sr_viewport_map(&verts[i], layout.count, &vp, &screen))
            codes[i] = SR_OUT_NONFINITE;
        for (int p = 0; p < SR_CLIP_PLANES && codes[i] != SR_OUT_NONFINITE; p++)
            r->on_plane |= ref_distance_f(p, &verts[i]) == 0.0 ? 1u << p : 0u;
    }
    uint32_t slots = sr_mesh_triangle_slots(mesh);
    for (uint32_t k = 0; k < slots; k++) {
        uint32_t idx[3];
        if (!sr_assemble_triangle(mesh, k, idx))
            continue;
        r->triangles++;
        unsigned c0 = codes[idx[0]], c1 = codes[idx[1]], c2 = codes[idx[2]], any = c0 | c1 | c2;
        if ((any & SR_OUT_NONFINITE) || (c0 & c1 & c2)) {
            r->rejected++;
            continue;
        }
        if (!any)
            continue;
        r->clipped++;
        sr_polygon poly = poly3(verts[idx[0]], verts[idx[1]], verts[idx[2]]);
        int count = sr_clip_polygon(&poly, any, SR_VARYINGS_AT + layout.count, &cfg);
        check_polygon(&poly, count, k, tolerance, r);
        if (poly.count >= 3)
            r->crossed |= any & SR_OUT_PLANES;
    }
    free(verts);
    free(codes);
}

/* ---- the ray cast ---- */

typedef struct ray_triangle {
    double a[3], e1[3], e2[3], n[3];
} ray_triangle;

static void cross3(const double *u, const double *v, double *out)
{
    out[0] = u[1] * v[2] - u[2] * v[1];
    out[1] = u[2] * v[0] - u[0] * v[2];
    out[2] = u[0] * v[1] - u[1] * v[0];
}

static double dot3(const double *u, const double *v)
{
    return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
}

static void world_point(const mat4 world, const float *p, double out[3])
{
    for (int r = 0; r < 3; r++)
        out[r] = (double)world[0][r] * p[0] + (double)world[1][r] * p[1] + (double)world[2][r] * p[2] +
                 (double)world[3][r];
}

/* Möller–Trumbore: the ray parameter t of the hit, or NAN for a miss. With
 * dir's forward component 1, t is the view depth of the hit. */
static double ray_hit(const ray_triangle *tri, const double *o, const double *dir)
{
    double p[3], q[3], s[3];
    cross3(dir, tri->e2, p);
    double det = dot3(tri->e1, p);
    if (det == 0.0)
        return NAN;
    for (int k = 0; k < 3; k++)
        s[k] = o[k] - tri->a[k];
    double u = dot3(s, p) / det;
    if (u < 0.0 || u > 1.0)
        return NAN;
    cross3(s, tri->e1, q);
    double v = dot3(dir, q) / det;
    if (v < 0.0 || u + v > 1.0)
        return NAN;
    return dot3(tri->e2, q) / det;
}

/* Front faces are clockwise on screen: (b - a) x (c - a) points toward the
 * eye, against the ray (quads of sr_shape_quads: n = -z, seen from -z). */
static int ray_keeps(const ray_triangle *tri, const double *dir, sr_cull cull, sr_front front)
{
    double len = sqrt(dot3(tri->n, tri->n) * dot3(dir, dir)), f = dot3(tri->n, dir);
    if (!(fabs(f) > 1e-9 * len))
        return -1; /* edge-on: the pipeline may draw a sliver or nothing */
    bool is_front = (f < 0.0) == (front == SR_FRONT_CW);
    return cull == SR_CULL_NONE || (cull == SR_CULL_BACK) == is_front;
}

/* Hits along one ray, and how many more are uncertain (edge-on triangles). */
static void ray_count(const ray_triangle *tris, size_t count, const sr_camera *cam, const double *dir,
                      sr_cull cull, sr_front front, int *sure, int *unsure)
{
    double eye[3] = { cam->eye[0], cam->eye[1], cam->eye[2] };
    *sure = *unsure = 0;
    for (size_t i = 0; i < count; i++) {
        double t = ray_hit(&tris[i], eye, dir);
        if (!(t >= cam->near && t <= cam->far))
            continue;
        int keep = ray_keeps(&tris[i], dir, cull, front);
        *sure += keep == 1;
        *unsure += keep < 0;
    }
}

static uint8_t saturate(int v)
{
    return (uint8_t)(v > 255 ? 255 : v);
}

void case_raycast(const sr_mesh *mesh, const mat4 world, const sr_camera *cam, int width, int height, sr_cull cull,
                  sr_front front, uint8_t *lo, uint8_t *hi)
{
    uint32_t slots = sr_mesh_triangle_slots(mesh);
    ray_triangle *tris = malloc((slots ? slots : 1) * sizeof *tris);
    cr_assert_not_null(tris);
    size_t count = 0;
    for (uint32_t k = 0; k < slots; k++) {
        uint32_t idx[3];
        if (!sr_assemble_triangle(mesh, k, idx))
            continue;
        double p[3][3];
        for (int v = 0; v < 3; v++)
            world_point(world, mesh->positions[idx[v]], p[v]);
        ray_triangle *t = &tris[count++];
        for (int i = 0; i < 3; i++) {
            t->a[i] = p[0][i];
            t->e1[i] = p[1][i] - p[0][i];
            t->e2[i] = p[2][i] - p[0][i];
        }
        cross3(t->e1, t->e2, t->n);
    }
    static const double offsets[5][2] = { { 0, 0 },
                                          { -CASE_RAY_OFFSET, 0 }, { CASE_RAY_OFFSET, 0 },
                                          { 0, -CASE_RAY_OFFSET }, { 0, CASE_RAY_OFFSET } };
    for (int j = 0; j < height; j++) {
        for (int i = 0; i < width; i++) {
            int least = 1 << 30, most = 0;
            for (int s = 0; s < 5; s++) {
                double dir[3];
                int sure, unsure;
                scene_pixel_ray(cam, width, height, i + 0.5 + offsets[s][0], j + 0.5 + offsets[s][1], dir);
                ray_count(tris, count, cam, dir, cull, front, &sure, &unsure);
                least = sure < least ? sure : least;
                most = sure + unsure > most ? sure + unsure : most;
            }
            lo[(size_t)j * width + i] = saturate(least);
            hi[(size_t)j * width + i] = saturate(most);
        }
    }
    free(tris);
}
