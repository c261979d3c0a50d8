#include <math.h>
#include <stddef.h>

#include "pipeline/04_clip/clip_corner.h"
#include "06_viewport.h"
#include "06_viewport_lanes.h"

static bool within_slack(double ndc, double lo)
{
    return ndc >= lo - SR_NDC_SLACK && ndc <= 1.0 + SR_NDC_SLACK;
}

/* llrint without the library call (a call through the PLT per coordinate),
 * for |v| < 2^51, which a snapped coordinate is (below 2^SR_FIXED_POINT_BITS
 * after the slack test): adding 1.5 * 2^52 leaves no bits for a fraction,
 * so the sum rounds v to an integer as llrint does (to nearest, ties to
 * even), and taking 1.5 * 2^52 away again is exact. */
static int64_t round_to_integer(double v)
{
    const double no_fraction = 6755399441055744.0;
    return (int64_t)((v + no_fraction) - no_fraction);
}

/* Subpixel units per NDC unit over half the framebuffer, on each axis:
 * W·2^bits/2 is exact, so t·(W·2^bits/2) rounds as ((t·0.5)·W)·2^bits
 * did (the two powers of two are exact for the t of a mapped point, never
 * subnormal): one product per axis and point instead of three. */
typedef struct screen_scale {
    double guard, x_units, y_units;
} screen_scale;

static screen_scale screen_scale_of(const sr_viewport *vp)
{
    double half_scale = (double)((int64_t)1 << vp->subpixel_bits) * 0.5;
    return (screen_scale){ vp->guard, vp->width * half_scale, vp->height * half_scale };
}

/* The point a vertex of NDC (x, y) maps to, in subpixel units, unsnapped. */
static void screen_point(double x, double y, const screen_scale *s, double *sx, double *sy)
{
    *sx = (s->guard * x + 1.0) * s->x_units;
    *sy = (1.0 - s->guard * y) * s->y_units;
}

/* 1/w and b/w (b the depth model's, or anything when it is off), as one
 * two-lane division where the compiler has vector types: each lane rounds
 * as the scalar division does. */
static void divide_by_w(double w, double b, double *inv_w, double *b_over_w)
{
#if defined(__GNUC__)
    typedef double two_doubles __attribute__((vector_size(16)));
    two_doubles q = (two_doubles){ 1.0, b } / (two_doubles){ w, w };
    *inv_w = q[0];
    *b_over_w = q[1];
#else
    *inv_w = 1.0 / w;
    *b_over_w = b / w;
#endif
}

/* Under the depth model z_ndc follows from w (a·w + b over w), exact but
 * for this one division and sum, whatever z could hold. */
static double depth_ndc(double z, double inv_w, double b_over_w, const sr_viewport *vp)
{
    return vp->depth.on ? vp->depth.a + b_over_w : z * inv_w;
}

/* The unsnapped point and z of a clip position in double. Checked (a
 * polygon vertex's point on two lines, which may barely meet): false where
 * it is not finite, has w <= 0 or lies past the slack. A mesh vertex's
 * position in double is the twin of its float one, which passed those
 * tests: the vertex phase maps it unchecked, as many times a frame as the
 * mesh has vertices inside. */
static inline bool map_double(const double c[4], bool checked, const screen_scale *scale, const sr_viewport *vp,
                              double *sx, double *sy, double *z)
{
    double w = c[SR_W];
    if (checked && (!(w > 0.0) || !isfinite(w)))
        return false;
    double inv_w, b_over_w;
    divide_by_w(w, vp->depth.b, &inv_w, &b_over_w);
    double x = c[SR_X] * inv_w, y = c[SR_Y] * inv_w;
    *z = depth_ndc(c[SR_Z], inv_w, b_over_w, vp);
    if (checked && (!within_slack(x, -1.0) || !within_slack(y, -1.0) || !within_slack(*z, 0.0)))
        return false;
    screen_point(x, y, scale, sx, sy);
    return true;
}

/* The float half of a mapping: the snapped point, 1/w and the varyings
 * divided by w, all from the float position; its unsnapped point and z to
 * sx, sy, z. False where the vertex is refused (sr_viewport_map). */
static SR_ALWAYS_INLINE bool map_float(const sr_vertex_out *v, int varyings, const sr_viewport *vp,
                                       const screen_scale *scale, sr_screen_vertex *out, double *sx, double *sy,
                                       double *z)
{
    double w = v->v[SR_W];
    if (!(w > 0.0) || !isfinite(w))
        return false;
    double inv_w, b_over_w;
    divide_by_w(w, vp->depth.b, &inv_w, &b_over_w);
    double x = v->v[SR_X] * inv_w, y = v->v[SR_Y] * inv_w;
    *z = depth_ndc(v->v[SR_Z], inv_w, b_over_w, vp);
    if (!within_slack(x, -1.0) || !within_slack(y, -1.0) || !within_slack(*z, 0.0))
        return false;
    screen_point(x, y, scale, sx, sy);
    out->x = round_to_integer(*sx);
    out->y = round_to_integer(*sy);
    out->inv_w = (float)inv_w;
    bool finite = isfinite(out->inv_w); /* 1/w overflows float for w < 2^-128 */
    for (int i = 0; i < varyings; i++) {
        out->var_w[i] = (float)(v->v[SR_VARYINGS_AT + i] * inv_w);
        finite = finite && isfinite(out->var_w[i]);
    }
    return finite;
}

/* The rest: the offsets of the unsnapped point (sx, sy) from the snapped
 * one, and z. */
static SR_ALWAYS_INLINE void place(double sx, double sy, double z, sr_screen_vertex *out)
{
    out->x_off = (float)(sx - (double)out->x); /* the difference exact, then 24 bits of it */
    out->y_off = (float)(sy - (double)out->y);
    out->z = (float)z;
}

/* sr_viewport_map, with the unsnapped point and z from clip_d (the clip
 * position in double) when given and of use: the snapped point stays the
 * float position's. */
static SR_ALWAYS_INLINE bool map_vertex(const sr_vertex_out *v, const double *clip_d, bool checked,
                                        int varyings, const sr_viewport *vp, sr_screen_vertex *out)
{
    screen_scale scale = screen_scale_of(vp);
    double sx, sy, z;
    if (!map_float(v, varyings, vp, &scale, out, &sx, &sy, &z))
        return false;
    double sx_d, sy_d, z_d;
    if (clip_d && map_double(clip_d, checked, &scale, vp, &sx_d, &sy_d, &z_d)) {
        sx = sx_d;
        sy = sy_d;
        z = z_d;
    }
    place(sx, sy, z, out);
    return true;
}

bool sr_viewport_map(const sr_vertex_out *v, int varyings, const sr_viewport *vp, sr_screen_vertex *out)
{
    return map_vertex(v, NULL, false, varyings, vp, out);
}

bool sr_viewport_map_d(const sr_vertex_out *v, const double clip_d[4], int varyings, const sr_viewport *vp,
                       sr_screen_vertex *out)
{
    return map_vertex(v, clip_d, false, varyings, vp, out);
}

/* The viewport's numbers for the lanes (06_viewport_lanes.h). */
static sr_viewport_lanes lanes_of(const sr_viewport *vp, const screen_scale *scale)
{
    return (sr_viewport_lanes){ .guard = scale->guard, .x_units = scale->x_units, .y_units = scale->y_units,
                                .a = vp->depth.a, .b = vp->depth.b, .depth_on = vp->depth.on,
                                /* within_slack's bounds */
                                .xy_lo = -1.0 - SR_NDC_SLACK, .z_lo = 0.0 - SR_NDC_SLACK, .hi = 1.0 + SR_NDC_SLACK };
}

void sr_viewport_map_float_block(const sr_vertex_out *v, uint32_t n, int varyings, const sr_viewport *vp, bool avx2,
                                 unsigned char *codes, void *out, size_t stride, sr_snapped_point *points)
{
    screen_scale scale = screen_scale_of(vp);
    sr_viewport_lanes r = lanes_of(vp, &scale);
    uint32_t k = avx2 ? sr_viewport_float_lanes_avx2(v, n, varyings, &r, codes, out, stride, points)
                      : sr_viewport_float_lanes_sse2(v, n, varyings, &r, codes, out, stride, points);
    for (; k < n; k++) {
        double sx, sy, z;
        sr_screen_vertex *o = (sr_screen_vertex *)((char *)out + k * stride);
        if (codes[k] == 0 && !map_float(&v[k], varyings, vp, &scale, o, &sx, &sy, &z))
            codes[k] = SR_OUT_NONFINITE;
        if (points)
            points[k] = codes[k] ? SR_SNAPPED_OUTSIDE : sr_snapped_point_of(o->x, o->y);
    }
}

void sr_viewport_map_double_block(const sr_mesh *mesh, const sr_vertex_transform *xf, const uint32_t *index,
                                  uint32_t n, const sr_viewport *vp, bool avx2, void *screen, size_t stride)
{
    screen_scale scale = screen_scale_of(vp);
    uint32_t k = 0;
    if (!mesh->clip_positions) {
        sr_viewport_lanes r = lanes_of(vp, &scale);
        const double(*m)[4] = (const double(*)[4])xf->clip_from_object_d.m;
        k = avx2 ? sr_viewport_double_lanes_avx2((const float(*)[3])mesh->positions, m, index, n, &r, screen, stride)
                 : sr_viewport_double_lanes_sse2((const float(*)[3])mesh->positions, m, index, n, &r, screen, stride);
    }
    for (; k < n; k++) {
        double clip_d[4], sx, sy, z;
        sr_vertex_mesh_clip_d(mesh, index[k], xf, clip_d);
        map_double(clip_d, false, &scale, vp, &sx, &sy, &z);
        place(sx, sy, z, (sr_screen_vertex *)((char *)screen + (size_t)index[k] * stride));
    }
}

bool sr_viewport_map_checked_d(const sr_vertex_out *v, const double clip_d[4], int varyings, const sr_viewport *vp,
                               sr_screen_vertex *out)
{
    return map_vertex(v, clip_d, true, varyings, vp, out);
}

bool sr_viewport_map_polygon(const sr_polygon *poly, const double tri_d[3][4], int varyings, const sr_viewport *vp,
                             sr_screen_vertex *out)
{
    for (int i = 0; i < poly->count; i++) {
        double point[4];
        sr_clip_point_on_lines_d(tri_d, poly->line[i > 0 ? i - 1 : poly->count - 1], poly->line[i], &vp->depth,
                                 point);
        if (!map_vertex(&poly->vert[i], point, true, varyings, vp, &out[i]))
            return false;
    }
    return true;
}
