#include <math.h>

#include "truth_outline.h"

/* Keeps the part of polygon in (n corners) on the side `keep` (+1: z >= z0,
 * -1: z <= z0); each cut vertex from the kept end toward the other. */
static int clip_z(const double (*in)[3], int n, double z0, int keep, double (*out)[3])
{
    int m = 0;
    for (int i = 0; i < n; i++) {
        const double *a = in[i], *b = in[(i + 1) % n];
        bool a_in = keep * (a[2] - z0) >= 0.0, b_in = keep * (b[2] - z0) >= 0.0;
        if (a_in)
            for (int r = 0; r < 3; r++)
                out[m][r] = a[r];
        m += a_in;
        if (a_in != b_in) {
            const double *from = a_in ? a : b, *to = a_in ? b : a;
            double t = (z0 - from[2]) / (to[2] - from[2]);
            for (int r = 0; r < 2; r++)
                out[m][r] = from[r] + t * (to[r] - from[r]);
            out[m++][2] = z0;
        }
    }
    return m;
}

int sr_truth_outline_corners(const sr_truth_image *t, uint32_t slot, double out[SR_TRUTH_OUTLINE_CORNERS][2])
{
    uint32_t idx[3];
    if (!t->mesh || slot >= sr_mesh_triangle_slots(t->mesh) || !sr_assemble_triangle(t->mesh, slot, idx))
        return 0;
    double tri[3][3], near_cut[SR_TRUTH_OUTLINE_CORNERS][3], slab[SR_TRUTH_OUTLINE_CORNERS][3];
    for (int k = 0; k < 3; k++)
        for (int r = 0; r < 3; r++)
            tri[k][r] = t->verts[idx[k]][r];
    const sr_truth_lens *l = &t->lens;
    int n = clip_z(tri, 3, l->near_z, 1, near_cut);
    n = isinf(l->far_z) ? n : clip_z(near_cut, n, l->far_z, -1, slab);
    const double (*kept)[3] = isinf(l->far_z) ? near_cut : slab;
    for (int k = 0; k < n; k++) {
        out[k][0] = (l->sx * kept[k][0] / kept[k][2] + 1.0) * 0.5 * t->width;
        out[k][1] = (1.0 - l->sy * kept[k][1] / kept[k][2]) * 0.5 * t->height;
    }
    return n >= 3 ? n : 0;
}

/* Distance from p to the segment a-b. */
static double segment_distance(const double p[2], const double a[2], const double b[2])
{
    double ex = b[0] - a[0], ey = b[1] - a[1], px = p[0] - a[0], py = p[1] - a[1];
    double len2 = ex * ex + ey * ey;
    double s = len2 > 0.0 ? fmax(0.0, fmin(1.0, (px * ex + py * ey) / len2)) : 0.0;
    return hypot(px - s * ex, py - s * ey);
}

sr_truth_outline_place sr_truth_outline_locate(const sr_truth_image *t, uint32_t slot, const double p[2])
{
    double corner[SR_TRUTH_OUTLINE_CORNERS][2];
    int n = sr_truth_outline_corners(t, slot, corner);
    if (!n)
        return (sr_truth_outline_place){ .distance = INFINITY, .inside = false };
    double distance = INFINITY;
    bool left = false, right = false; /* of some edge (a repeated corner's edge is neither) */
    for (int k = 0; k < n; k++) {
        const double *a = corner[k], *b = corner[(k + 1) % n];
        distance = fmin(distance, segment_distance(p, a, b));
        double cross = (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
        left |= cross > 0.0;
        right |= cross < 0.0;
    }
    /* Inside a convex polygon: on one side of every edge, or on an edge. */
    bool inside = distance == 0.0 || !(left && right);
    return (sr_truth_outline_place){ .distance = distance, .inside = inside };
}
