#include <math.h>

#include "softrast/clip.h"

double sr_clip_distance(sr_clip_plane plane, const float *c)
{
    switch (plane) {
    case SR_PLANE_NEAR:   return (double)c[SR_Z];
    case SR_PLANE_FAR:    return (double)c[SR_W] - c[SR_Z];
    case SR_PLANE_LEFT:   return (double)c[SR_W] + c[SR_X];
    case SR_PLANE_RIGHT:  return (double)c[SR_W] - c[SR_X];
    case SR_PLANE_BOTTOM: return (double)c[SR_W] + c[SR_Y];
    case SR_PLANE_TOP:    return (double)c[SR_W] - c[SR_Y];
    }
    return 0.0;
}

unsigned sr_clip_outcode(const float *c)
{
    if (!isfinite(c[SR_X]) || !isfinite(c[SR_Y]) || !isfinite(c[SR_Z]) || !isfinite(c[SR_W]))
        return SR_OUT_NONFINITE;
    unsigned code = 0;
    for (int p = 0; p < SR_CLIP_PLANES; p++)
        if (sr_clip_distance((sr_clip_plane)p, c) < 0.0)
            code |= 1u << p;
    return code;
}

/* Puts the cut vertex exactly on the plane, so its distance is 0 and later
 * planes, the divide and the viewport see a point that is inside. */
static void place_on_plane(sr_clip_plane plane, float *c)
{
    switch (plane) {
    case SR_PLANE_NEAR:   c[SR_Z] = 0.0f; break;
    case SR_PLANE_FAR:    c[SR_Z] = c[SR_W]; break;
    case SR_PLANE_LEFT:   c[SR_X] = -c[SR_W]; break;
    case SR_PLANE_RIGHT:  c[SR_X] = c[SR_W]; break;
    case SR_PLANE_BOTTOM: c[SR_Y] = -c[SR_W]; break;
    case SR_PLANE_TOP:    c[SR_Y] = c[SR_W]; break;
    }
}

static void intersect_double(sr_clip_plane plane, const sr_vertex_out *inside, const sr_vertex_out *outside,
                             int floats, sr_vertex_out *cut)
{
    double d_in = sr_clip_distance(plane, inside->v);
    double d_out = sr_clip_distance(plane, outside->v);
    double t = d_in / (d_in - d_out);
    for (int i = 0; i < floats; i++) {
        double a = inside->v[i], b = outside->v[i];
        cut->v[i] = (float)(a + t * (b - a));
    }
}

static void intersect_float(sr_clip_plane plane, const sr_vertex_out *inside, const sr_vertex_out *outside,
                            int floats, sr_vertex_out *cut)
{
    float d_in = (float)sr_clip_distance(plane, inside->v);
    float d_out = (float)sr_clip_distance(plane, outside->v);
    float t = d_in / (d_in - d_out);
    for (int i = 0; i < floats; i++)
        cut->v[i] = inside->v[i] + t * (outside->v[i] - inside->v[i]);
}

void sr_clip_intersect(sr_clip_plane plane, const sr_vertex_out *inside, const sr_vertex_out *outside,
                       int floats, sr_clip_precision precision, sr_vertex_out *cut)
{
    if (precision == SR_CLIP_FLOAT)
        intersect_float(plane, inside, outside, floats, cut);
    else
        intersect_double(plane, inside, outside, floats, cut);
    place_on_plane(plane, cut->v);
}

/* One Sutherland–Hodgman pass. Returns the output count, or -1 if rounding
 * made the polygon cross the plane more than twice and the output would pass
 * the bound (only slivers thinner than float precision do that). */
static int clip_against_plane(const sr_vertex_out *in, int n, sr_clip_plane plane, int floats,
                              sr_clip_precision precision, sr_vertex_out *out)
{
    int m = 0;
    for (int i = 0; i < n; i++) {
        const sr_vertex_out *a = &in[i], *b = &in[i + 1 < n ? i + 1 : 0];
        bool a_in = sr_clip_distance(plane, a->v) >= 0.0;
        bool b_in = sr_clip_distance(plane, b->v) >= 0.0;
        if (m + (a_in) + (a_in != b_in) > SR_MAX_CLIP_VERTS)
            return -1;
        if (a_in)
            out[m++] = *a;
        if (a_in && !b_in)
            sr_clip_intersect(plane, a, b, floats, precision, &out[m++]);
        else if (!a_in && b_in)
            sr_clip_intersect(plane, b, a, floats, precision, &out[m++]);
    }
    return m;
}

int sr_clip_polygon(sr_polygon *poly, unsigned planes, int floats, sr_clip_precision precision)
{
    sr_vertex_out scratch[SR_MAX_CLIP_VERTS];
    for (int p = 0; p < SR_CLIP_PLANES && poly->count >= 3; p++) {
        if (!(planes & (1u << p)))
            continue;
        int n = clip_against_plane(poly->vert, poly->count, (sr_clip_plane)p, floats, precision, scratch);
        poly->count = n < 3 ? 0 : n;
        for (int i = 0; i < poly->count; i++)
            poly->vert[i] = scratch[i];
    }
    if (poly->count < 3)
        poly->count = 0;
    /* Inside every plane, w <= 0 leaves only the clip-space origin (|x|, |y|,
     * z <= w and z >= 0): the triangle's plane then contains the eye and the
     * polygon has no area on screen, so dropping it loses no pixel, and the
     * divide never sees w <= 0. Rounding puts such a vertex there when an
     * edge runs through the eye and the near plane is tiny (1e-6). */
    for (int i = 0; i < poly->count; i++)
        if (!(poly->vert[i].v[SR_W] > 0.0f))
            poly->count = 0;
    return poly->count;
}
