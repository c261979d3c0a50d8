#include <math.h>

#include "viewport.h"

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

/* The point a vertex of NDC (x, y) maps to, in subpixel units, unsnapped. */
static void screen_point(double x, double y, const sr_viewport *vp, double *sx, double *sy)
{
    double scale = (double)((int64_t)1 << vp->subpixel_bits), guard = vp->guard;
    *sx = (guard * x + 1.0) * 0.5 * vp->width * scale;
    *sy = (1.0 - guard * y) * 0.5 * vp->height * scale;
}

/* Under the depth model z_ndc follows from w (a·w + b over w), exact but
 * for this one division and sum, whatever z could hold. */
static double depth_ndc(double z, double w, double inv_w, const sr_viewport *vp)
{
    return vp->depth.on ? vp->depth.a + vp->depth.b / w : z * inv_w;
}

/* sr_viewport_map, with the unsnapped point and z from clip_d (the clip
 * position in double) when given: the snapped point stays the float
 * position's. */
static inline bool map_vertex(const sr_vertex_out *v, const double *clip_d, int varyings, const sr_viewport *vp,
                              sr_screen_vertex *out)
{
    double w = v->v[SR_W];
    if (!(w > 0.0) || !isfinite(w))
        return false;
    double inv_w = 1.0 / w;
    double x = v->v[SR_X] * inv_w, y = v->v[SR_Y] * inv_w;
    double z = depth_ndc(v->v[SR_Z], w, inv_w, vp);
    if (!within_slack(x, -1.0) || !within_slack(y, -1.0) || !within_slack(z, 0.0))
        return false;
    double sx, sy;
    screen_point(x, y, vp, &sx, &sy);
    out->x = round_to_integer(sx);
    out->y = round_to_integer(sy);
    if (clip_d) {
        double w_d = clip_d[SR_W], inv_w_d = 1.0 / w_d;
        screen_point(clip_d[SR_X] * inv_w_d, clip_d[SR_Y] * inv_w_d, vp, &sx, &sy);
        z = depth_ndc(clip_d[SR_Z], w_d, inv_w_d, vp);
    }
    out->x_off = (float)(sx - (double)out->x); /* the difference exact, then 24 bits of it */
    out->y_off = (float)(sy - (double)out->y);
    out->z = (float)z;
    out->inv_w = (float)inv_w;
    bool finite = isfinite(out->inv_w); /* 1/w overflows float for w < 2^-128 */
    for (int i = 0; i < varyings; i++) {
        out->var_w[i] = (float)(v->v[SR_VARYINGS_AT + i] * inv_w);
        finite = finite && isfinite(out->var_w[i]);
    }
    return finite;
}

bool sr_viewport_map(const sr_vertex_out *v, int varyings, const sr_viewport *vp, sr_screen_vertex *out)
{
    return map_vertex(v, NULL, varyings, vp, out);
}

bool sr_viewport_map_d(const sr_vertex_out *v, const double clip_d[4], int varyings, const sr_viewport *vp,
                       sr_screen_vertex *out)
{
    return map_vertex(v, clip_d, varyings, vp, out);
}
