#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "hidden_lines.h"
#include "core/clock.h"
#include "core/dmat4.h"
#include "core/error.h"
#include "draw/draw.h"
#include "pipeline/01_vertex.h"
#include "pipeline/02_assemble.h"
#include "scene/frame.h"

/* z_ndc within which a line lies in the plane of a face it does not
 * border (a pillar's foot on the floor, a top in the ceiling's plane): far
 * above the rounding of the double plane solve, far below any gap between
 * two faces the camera can tell apart. */
#define TIE_DEPTH 1e-9

bool sr_hidden_lines_make(const sr_mesh *mesh, sr_hidden_lines *h, sr_error *err)
{
    *h = (sr_hidden_lines){ 0 };
    if (!sr_wireframe_make(mesh, &h->wire, err))
        return false;
    h->clip = malloc(((size_t)mesh->vertex_count + 1) * sizeof *h->clip);
    h->kept = malloc(((size_t)h->wire.edges.index_count / 2 + 1) * sizeof *h->kept);
    if (h->clip && h->kept)
        return true;
    sr_hidden_lines_destroy(h);
    return sr_error_set(err, "out of memory for the hidden lines of %u vertices", mesh->vertex_count);
}

void sr_hidden_lines_destroy(sr_hidden_lines *h)
{
    sr_wireframe_destroy(&h->wire);
    free(h->clip);
    free(h->kept);
    free(h->fill_ids);
    free(h->fill_depth);
    *h = (sr_hidden_lines){ 0 };
}

/* What the line filter reads: the fill's planes, the wireframe, and per
 * frame the mesh's clip positions in double and which lines border a
 * face that culling keeps. */
typedef struct line_judge {
    const uint32_t *ids;
    const float *depth;
    int width, height;
    bool reversed_z;
    const sr_wireframe *wire;
    const sr_mesh *mesh;
    const double (*clip)[4];
    const bool *kept;
} line_judge;

static bool nearer(double a, double b, bool reversed_z)
{
    return reversed_z ? a > b : a < b;
}

/* Whether the triangle of id + 1 `id` has line `line` as an edge. */
static bool owns(const line_judge *j, uint32_t id, uint32_t line)
{
    const uint32_t *e = j->wire->triangle_edges + 3 * (size_t)(id - 1);
    return e[0] == line || e[1] == line || e[2] == line;
}

/* The part of the segment c0 → c1 (clip space) in 0 ≤ z ≤ w with w > 0,
 * into c0 and c1; false when it has none. */
static bool between_near_and_far(double c0[4], double c1[4])
{
    double f0[3] = { c0[2], c0[3] - c0[2], c0[3] }, f1[3] = { c1[2], c1[3] - c1[2], c1[3] }, t0 = 0.0, t1 = 1.0;
    for (int k = 0; k < 3; k++) {
        double d = f1[k] - f0[k];
        if (d > 0.0)
            t0 = fmax(t0, -f0[k] / d);
        else if (d < 0.0)
            t1 = fmin(t1, -f0[k] / d);
        else if (f0[k] < 0.0 || (k == 2 && f0[k] == 0.0))
            return false;
    }
    if (!(t0 < t1))
        return false;
    double a[4], b[4];
    for (int r = 0; r < 4; r++) {
        a[r] = c0[r] + t0 * (c1[r] - c0[r]);
        b[r] = c0[r] + t1 * (c1[r] - c0[r]);
    }
    memcpy(c0, a, sizeof a);
    memcpy(c1, b, sizeof b);
    return true;
}

/* A clip-space point's place on screen, in pixels. */
static void to_pixels(const line_judge *j, const double c[4], double out[2])
{
    out[0] = (c[0] / c[3] + 1.0) * j->width / 2.0;
    out[1] = (1.0 - c[1] / c[3]) * j->height / 2.0;
}

/* The point of line `line` (clip space) whose place on screen is nearest
 * the centre of pixel (x, y), on its part between the near and far
 * planes; false when it has none. */
static bool line_point_near(const line_judge *j, uint32_t line, int x, int y, double p[4])
{
    double c0[4], c1[4], s0[2], s1[2];
    memcpy(c0, j->clip[j->wire->edges.indices[2 * (size_t)line]], sizeof c0);
    memcpy(c1, j->clip[j->wire->edges.indices[2 * (size_t)line + 1]], sizeof c1);
    if (!between_near_and_far(c0, c1))
        return false;
    to_pixels(j, c0, s0);
    to_pixels(j, c1, s1);
    double dx = s1[0] - s0[0], dy = s1[1] - s0[1], length2 = dx * dx + dy * dy;
    double u = length2 > 0.0 ? ((x + 0.5 - s0[0]) * dx + (y + 0.5 - s0[1]) * dy) / length2 : 0.0;
    u = fmin(fmax(u, 0.0), 1.0);
    /* The screen's u to the segment's own parameter (perspective). */
    double s = u * c0[3] / ((1.0 - u) * c1[3] + u * c0[3]);
    for (int r = 0; r < 4; r++)
        p[r] = c0[r] + s * (c1[r] - c0[r]);
    return true;
}

/* z_ndc of the plane of triangle slot k where the ray through the clip
 * point p's place on screen meets it, and whether the triangle covers that
 * point (its part between the near and far planes); false where the ray
 * meets the plane behind the eye or not at all. With the corners' (x, y,
 * w) as the columns of M, the weights v = M⁻¹·(x/w, y/w, 1) of p put the
 * point in front of the eye for Σ v > 0, inside the triangle for every
 * v_i ≥ 0, and give its z_ndc as Σ v_i·z_i; row i of M⁻¹ is the cross
 * product of the other two corners over det M. */
static bool plane_through(const line_judge *j, uint32_t k, const double p[4], double *z, bool *covers)
{
    uint32_t idx[3];
    if (!sr_assemble_triangle(j->mesh, k, idx))
        return false;
    const double *c[3] = { j->clip[idx[0]], j->clip[idx[1]], j->clip[idx[2]] };
    double row[3][3], r[3] = { p[0] / p[3], p[1] / p[3], 1.0 }, v[3], sum = 0.0;
    for (int i = 0; i < 3; i++) {
        const double *a = c[(i + 1) % 3], *b = c[(i + 2) % 3];
        row[i][0] = a[1] * b[3] - a[3] * b[1];
        row[i][1] = a[3] * b[0] - a[0] * b[3];
        row[i][2] = a[0] * b[1] - a[1] * b[0];
    }
    double det = c[0][0] * row[0][0] + c[0][1] * row[0][1] + c[0][3] * row[0][2];
    *z = 0.0;
    for (int i = 0; i < 3; i++) {
        v[i] = (row[i][0] * r[0] + row[i][1] * r[1] + row[i][2] * r[2]) / det;
        sum += v[i];
        *z += v[i] * c[i][2];
    }
    *covers = v[0] >= 0.0 && v[1] >= 0.0 && v[2] >= 0.0 && *z >= 0.0 && *z <= 1.0;
    return isfinite(*z) && sum > 0.0;
}

/* The faces the fill shows at pixel (x, y) and its 8 neighbours that do
 * not own line `line`, each once, into others (ids + 1); their count, and
 * whether one that owns it is seen. */
static int faces_next_to(const line_judge *j, uint32_t line, int x, int y, uint32_t others[9], bool *owned)
{
    int n = 0;
    *owned = false;
    int x0 = x > 0 ? x - 1 : 0, x1 = x + 1 < j->width ? x + 1 : x;
    int y0 = y > 0 ? y - 1 : 0, y1 = y + 1 < j->height ? y + 1 : y;
    for (int qy = y0; qy <= y1; qy++) {
        const uint32_t *ids = j->ids + (size_t)qy * (size_t)j->width;
        for (int qx = x0; qx <= x1; qx++) {
            uint32_t id = ids[qx];
            if (id == 0 || id > j->wire->triangle_slots || (n > 0 && others[n - 1] == id))
                continue;
            if (owns(j, id, line)) {
                *owned = true;
                continue;
            }
            bool again = false;
            for (int k = 0; k < n - 1 && !again; k++)
                again = others[k] == id;
            if (!again)
                others[n++] = id;
        }
    }
    return n;
}

static bool same_place(const sr_mesh *mesh, uint32_t a, uint32_t b)
{
    return a == b || (mesh->positions && memcmp(mesh->positions[a], mesh->positions[b], sizeof(vec3)) == 0);
}

/* Whether triangle slot k has an end of line `line` as a corner. */
static bool touches(const line_judge *j, uint32_t k, uint32_t line)
{
    uint32_t idx[3];
    sr_assemble_triangle(j->mesh, k, idx);
    for (int e = 0; e < 2; e++)
        for (int i = 0; i < 3; i++)
            if (same_place(j->mesh, idx[i], j->wire->edges.indices[2 * (size_t)line + e]))
                return true;
    return false;
}

/* The face seen at the pixel whose square holds the clip point p, when
 * that pixel is (x, y) or a neighbour of it; else the face at (x, y). A
 * line snapped onto a pixel its exact path only skirts has its point
 * nearest the centre in the neighbour's square, whose face stands for
 * the surface over it. */
static uint32_t face_over(const line_judge *j, const double p[4], int x, int y)
{
    double s[2];
    to_pixels(j, p, s);
    double px = floor(s[0]), py = floor(s[1]);
    if (px >= x - 1 && px <= x + 1 && py >= y - 1 && py <= y + 1 && px >= 0 && py >= 0 && px < j->width &&
        py < j->height)
        return j->ids[(size_t)py * (size_t)j->width + (size_t)px];
    return j->ids[(size_t)y * (size_t)j->width + (size_t)x];
}

/* Whether the faces seen at and next to (x, y), the face at (x, y) not
 * owning line `line`, hide it there. One that does not own it hides it
 * when its plane is nearer than the line's point nearest the pixel centre
 * by more than TIE_DEPTH and it covers that point; or no face that owns
 * the line is seen (the line lies behind the plane of the surface around
 * it: a far side seen through a near one); or it is the face seen over
 * that point (face_over) and has neither end of the line as a corner (it
 * stands for a surface in front whose face over the point is too small
 * to hold a pixel centre: a cylinder's silhouette facets). A neighbour of
 * the line seen beside a face of it, not over the point, is the next
 * facet of a curved surface, which bends away from the line. */
static bool hidden_at(const line_judge *j, uint32_t line, int x, int y)
{
    uint32_t others[9];
    bool owned;
    int n = faces_next_to(j, line, x, y, others, &owned);
    double p[4];
    if (n == 0 || !line_point_near(j, line, x, y, p))
        return false;
    uint32_t over = face_over(j, p, x, y);
    double z = p[2] / p[3], tie = j->reversed_z ? z + TIE_DEPTH : z - TIE_DEPTH, face;
    for (int k = 0; k < n; k++) {
        bool covers;
        if (plane_through(j, others[k] - 1, p, &face, &covers) && nearer(face, tie, j->reversed_z) &&
            (covers || !owned || (others[k] == over && !touches(j, others[k] - 1, line))))
            return true;
    }
    return false;
}

/* The depth one float step nearer than d, which is in [0, 1]; d itself
 * where none is (at the near plane). */
static float hair_nearer(float d, bool reversed_z)
{
    if (reversed_z ? d >= 1.0f : d <= 0.0f)
        return d;
    uint32_t bits;
    memcpy(&bits, &d, sizeof bits);
    bits = reversed_z ? bits + 1 : bits - 1; /* a positive float's neighbours */
    memcpy(&d, &bits, sizeof d);
    return d;
}

/* The hidden-line rule, as an sr_line_filter: a fragment of a line that
 * borders a face culling keeps, where the face seen at the pixel borders
 * the line too, or the faces seen there do not hide it (hidden_at). */
static bool keep_fragment(const void *user, uint32_t line, int x, int y, float *z)
{
    const line_judge *j = user;
    size_t at = (size_t)y * (size_t)j->width + (size_t)x;
    uint32_t here = j->ids[at];
    bool bordered = here != 0 && here <= j->wire->triangle_slots && owns(j, here, line);
    if (!j->kept[line] || (!bordered && hidden_at(j, line, x, y)))
        return false;
    float hair = hair_nearer(j->depth[at], j->reversed_z);
    if (!nearer(*z, hair, j->reversed_z))
        *z = hair;
    return true;
}

/* det[x y w] of three clip positions. */
static double orientation(const double a[4], const double b[4], const double c[4])
{
    return a[0] * (b[1] * c[3] - b[3] * c[1]) - a[1] * (b[0] * c[3] - b[3] * c[0]) + a[3] * (b[0] * c[1] - b[1] * c[0]);
}

/* The mesh's clip positions in double for fill's camera, and which lines
 * border a triangle that fill's culling keeps (by the orientation of its
 * part in front of the eye: the sign of det[x y w] of its corners, whose
 * negative is clockwise on screen). */
static void judge_frame(sr_hidden_lines *h, const sr_draw_desc *fill)
{
    const sr_mesh *mesh = fill->mesh;
    sr_dmat4 world = sr_dmat4_desc_matrix(&fill->world_d, fill->world), none = { { { 0 } } };
    sr_dmat4 view = sr_dmat4_desc_matrix(&fill->view_d, fill->view);
    sr_dmat4 projection = sr_dmat4_desc_matrix(&none, fill->projection);
    sr_vertex_transform xf;
    sr_vertex_make_transform_d(&world, &view, &projection, mesh->origin, &xf);
    for (uint32_t i = 0; i < mesh->vertex_count; i++)
        sr_vertex_mesh_clip_d(mesh, i, &xf, h->clip[i]);
    memset(h->kept, 0, (size_t)h->wire.edges.index_count / 2 * sizeof *h->kept);
    for (uint32_t k = 0; k < h->wire.triangle_slots; k++) {
        uint32_t idx[3];
        if (!sr_assemble_triangle(mesh, k, idx))
            continue;
        double det = orientation(h->clip[idx[0]], h->clip[idx[1]], h->clip[idx[2]]);
        if (!sr_cull_keeps(det < 0.0 ? 1 : det > 0.0 ? -1 : 0, fill->cull, fill->front))
            continue;
        for (int e = 0; e < 3; e++)
            h->kept[h->wire.triangle_edges[3 * (size_t)k + e]] = true;
    }
}

/* The fill's planes, fb-sized. */
static bool planes_ready(sr_hidden_lines *h, size_t pixels, sr_error *err)
{
    if (h->pixels == pixels)
        return true;
    free(h->fill_ids);
    free(h->fill_depth);
    h->fill_ids = malloc(pixels * sizeof *h->fill_ids);
    h->fill_depth = malloc(pixels * sizeof *h->fill_depth);
    h->pixels = h->fill_ids && h->fill_depth ? pixels : 0;
    return h->pixels || sr_error_set(err, "out of memory for the hidden-line planes of %zu pixels", pixels);
}

bool sr_hidden_lines_frame(sr_hidden_lines *h, sr_framebuffer *fb, const sr_draw_desc *fill, sr_stats *fill_stats,
                           sr_stats *line_stats, double *ms, sr_error *err)
{
    double start = sr_now_ms(), fill_ms;
    *line_stats = (sr_stats){ 0 };
    size_t pixels = (size_t)fb->width * (size_t)fb->height;
    if (!planes_ready(h, pixels, err))
        return false;
    sr_draw_desc depth_only = *fill;
    depth_only.shade = SR_SHADE_DEPTH;
    sr_framebuffer filled = *fb;
    filled.ids = h->fill_ids;
    bool ok = sr_frame_draw_timed(&filled, &depth_only, fill_stats, &fill_ms, err);
    if (ok) {
        memcpy(h->fill_depth, fb->depth, pixels * sizeof *fb->depth);
        if (fb->ids)
            memset(fb->ids, 0, pixels * sizeof *fb->ids);
        judge_frame(h, fill);
        line_judge judge = { h->fill_ids, h->fill_depth, fb->width, fb->height, fb->reversed_z, &h->wire, fill->mesh,
                             (const double(*)[4])h->clip, h->kept };
        sr_line_filter filter = { keep_fragment, &judge };
        sr_draw_study study = fill->study ? *fill->study : (sr_draw_study){ 0 };
        study.observer = NULL;
        sr_draw_desc lines = *fill;
        lines.mesh = &h->wire.edges;
        lines.line_width = h->line_width;
        lines.study = &study;
        ok = sr_draw_lines_filtered(fb, &lines, &filter, line_stats, err);
    }
    *ms = sr_now_ms() - start;
    return ok;
}
