/* classify.c — the planes, distances and outcodes (classify.h). */
#include <math.h>

#include "03_classify.h"
#include "pipeline/04_clip/expansion.h"

/* Near a·w + b and far w − a·w − b: a·w of two floats is exact in double,
 * so one two-sum or two make them exact. */
static int depth_distance(sr_clip_plane plane, double w, const sr_clip_depth *depth, double d[])
{
    double aw = (double)depth->a * w;
    if (!sr_clip_plane_table[plane].bounded_by_w) {
        two_sum(aw, depth->b, &d[1], &d[0]);
        return 2;
    }
    two_sum(w, -aw, &d[1], &d[0]);
    return grow(d, 2, -(double)depth->b);
}

int sr_clip_distance_exact(sr_clip_plane plane, const float *c, const sr_clip_depth *depth,
                           double d[SR_CLIP_DISTANCE_TERMS])
{
    double w = c[SR_W];
    if (depth && depth->on && sr_clip_plane_in_depth_model(plane))
        return depth_distance(plane, w, depth, d);
    const sr_clip_plane_row *row = &sr_clip_plane_table[plane];
    double along = row->sign * (double)c[row->axis];
    if (!row->bounded_by_w) {
        d[0] = along;
        return 1;
    }
    two_sum(w, along, &d[1], &d[0]);
    return 2;
}

double sr_clip_distance_d(sr_clip_plane plane, const double c[4], const sr_clip_depth *depth)
{
    if (depth && depth->on && sr_clip_plane_in_depth_model(plane)) {
        double aw = (double)depth->a * c[SR_W];
        return sr_clip_plane_table[plane].bounded_by_w ? (c[SR_W] - aw) - depth->b : aw + depth->b;
    }
    return sr_clip_plane_distance(plane, c[sr_clip_plane_table[plane].axis], c[SR_W]);
}

double sr_clip_distance(sr_clip_plane plane, const float *c)
{
    return sr_clip_plane_distance(plane, c[sr_clip_plane_table[plane].axis], c[SR_W]);
}

sr_clip_depth sr_clip_depth_of(const float m[4][4])
{
    float s = m[2][3], a = m[2][2] / s, b = m[3][2];
    bool perspective = m[0][3] == 0.0f && m[1][3] == 0.0f && m[3][3] == 0.0f && (s == 1.0f || s == -1.0f);
    bool affine_z = m[0][2] == 0.0f && m[1][2] == 0.0f && isfinite(a) && isfinite(b);
    if (!perspective || !affine_z)
        return (sr_clip_depth){ .on = false };
    return (sr_clip_depth){ .on = true, .a = a, .b = b };
}

double sr_clip_distance_with(sr_clip_plane plane, const float *c, const sr_clip_depth *depth)
{
    if (!depth || !depth->on || !sr_clip_plane_in_depth_model(plane))
        return sr_clip_distance(plane, c);
    double d[SR_CLIP_DISTANCE_TERMS];
    int n = sr_clip_distance_exact(plane, c, depth, d);
    return expansion_signed_value(d, n);
}

unsigned sr_clip_outcode(const float *c)
{
    return sr_clip_outcode_with(c, NULL);
}

/* Corner k of the box, through the transform (column-major, column vectors);
 * returns the largest sum of term magnitudes, the scale of the vertex
 * stage's float rounding there. */
static double box_corner(const float m[4][4], const float lo[3], const float hi[3], int k, double c[4])
{
    double p[3] = { (k & 1) ? hi[0] : lo[0], (k & 2) ? hi[1] : lo[1], (k & 4) ? hi[2] : lo[2] }, scale = 0.0;
    for (int r = 0; r < 4; r++) {
        c[r] = m[0][r] * p[0] + m[1][r] * p[1] + m[2][r] * p[2] + m[3][r];
        double size = fabs(m[0][r] * p[0]) + fabs(m[1][r] * p[1]) + fabs(m[2][r] * p[2]) + fabs(m[3][r]);
        scale = size > scale ? size : scale;
    }
    return scale;
}

sr_clip_box sr_clip_classify_box(const float clip_from_object[4][4], const float lo[3], const float hi[3])
{
    unsigned outside;
    return sr_clip_classify_box_planes(clip_from_object, lo, hi, &outside);
}

sr_clip_box sr_clip_classify_box_planes(const float clip_from_object[4][4], const float lo[3], const float hi[3],
                                        unsigned *outside)
{
    unsigned all_out = SR_OUT_PLANES, any_near = 0;
    *outside = 0;
    for (int k = 0; k < 8; k++) {
        double c[4];
        double margin = SR_CLIP_BOX_MARGIN * box_corner(clip_from_object, lo, hi, k, c);
        if (!isfinite(c[0]) || !isfinite(c[1]) || !isfinite(c[2]) || !isfinite(c[3]) || !isfinite(margin))
            return SR_BOX_CROSSES;
        unsigned out = 0;
        for (int p = 0; p < SR_CLIP_PLANES; p++) {
            double d = sr_clip_distance_d((sr_clip_plane)p, c, NULL);
            out |= (unsigned)(d < -margin) << p;
            any_near |= (unsigned)(d < margin) << p;
        }
        all_out &= out;
    }
    *outside = all_out;
    if (all_out)
        return SR_BOX_OUTSIDE;
    return any_near ? SR_BOX_CROSSES : SR_BOX_INSIDE;
}

/* Under the depth model z is a·w + b of the vertex's w, rounded once. */
void sr_clip_z_from_w(const sr_clip_depth *depth, float *c)
{
    c[SR_Z] = (float)((double)depth->a * c[SR_W] + depth->b);
}

/* Puts the cut vertex exactly on the plane, so its distance is 0 and later
 * planes, the divide and the viewport see a point that is inside. Under the
 * depth model near and far are planes in w alone: the interpolated w is the
 * cut, and z follows it (the viewport's z_ndc comes from w too, so this z
 * is for the record). */
void sr_clip_place_on_plane(sr_clip_plane plane, const sr_clip_depth *depth, float *c)
{
    if (depth && depth->on && sr_clip_plane_in_depth_model(plane)) {
        sr_clip_z_from_w(depth, c);
        return;
    }
    c[sr_clip_plane_table[plane].axis] = sr_clip_plane_coordinate_at(plane, c[SR_W]);
}
