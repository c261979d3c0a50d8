/* pinhole_sparse.c — the point of a point or line primitive that a
 * pinhole pixel sees (pinhole_sparse.h). */
#include <math.h>
#include <string.h>

#include "pinhole_sparse.h"
#include "core/dmat4.h"
#include "pipeline/02_assemble.h"

/* The part of a segment from `base` towards `other`, base + r·(other −
 * base) for r in [*lo, *hi] ⊆ [0, 1], whose view z lies between the clip
 * planes: the part a draw shows. The whole segment if no part does (an
 * id that is no draw of it). */
static void visible_part(const sr_pinhole *cam, double base_z, double other_z, double *lo, double *hi)
{
    const double plane[2] = { cam->near, cam->far }, side[2] = { 1.0, -1.0 }; /* in front of near, behind far */
    double dz = other_z - base_z, from = 0.0, to = 1.0;
    for (int k = 0; k < 2; k++) {
        double base_in = side[k] * (base_z - plane[k]), other_in = side[k] * (other_z - plane[k]);
        if (base_in < 0.0 && other_in >= 0.0)
            from = fmax(from, (plane[k] - base_z) / dz);
        else if (base_in >= 0.0 && other_in < 0.0)
            to = fmin(to, (plane[k] - base_z) / dz);
        else if (base_in < 0.0)
            from = 2.0; /* wholly outside */
    }
    *lo = from <= to ? from : 0.0;
    *hi = from <= to ? to : 1.0;
}

/* The point of the visible part of segment base → other nearest the ray
 * along d = (ray_x, ray_y, 1), as r from base: |(A + r·u) × d| / |d|, u =
 * other − A, is least at r = −(A × d)·(u × d) / |u × d|², clamped. Cross
 * products, so a segment nearly along the ray loses no digits to
 * cancellation; one exactly along it shows its nearer end. */
static double nearest_from(const sr_pinhole *cam, const double base[3], const double other[3], const double d[3],
                           double p[3])
{
    double u[3], a_d[3], u_d[3], lo, hi;
    for (int k = 0; k < 3; k++)
        u[k] = other[k] - base[k];
    sr_dvec3_cross(base, d, a_d);
    sr_dvec3_cross(u, d, u_d);
    double along = sr_dvec3_dot(u_d, u_d);
    double r = along > 0.0 ? -sr_dvec3_dot(a_d, u_d) / along : (other[2] < base[2] ? 1.0 : 0.0);
    visible_part(cam, base[2], other[2], &lo, &hi);
    r = r > lo ? (r < hi ? r : hi) : lo; /* NaN (an overflow) takes the visible part's first point */
    for (int k = 0; k < 3; k++)
        p[k] = base[k] + r * u[k];
    return r;
}

bool sr_pinhole_seen_point(const sr_pinhole *cam, const camera_frame *frame, const sr_mesh *mesh, uint32_t slot,
                           double ray_x, double ray_y, sr_seen_point *sp)
{
    if (mesh->topology == SR_POINT_LIST) {
        sp->idx[0] = sp->idx[1] = mesh->indices[slot];
        if (sp->idx[0] >= mesh->vertex_count)
            return false;
        to_camera(frame, mesh->positions[sp->idx[0]], sp->p);
        sp->t = 0.0;
        return true;
    }
    double a[3], b[3], from_b[3];
    sr_assemble_line(mesh, slot, sp->idx); /* drawn, so not degenerate */
    if (sp->idx[0] >= mesh->vertex_count || sp->idx[1] >= mesh->vertex_count)
        return false;
    to_camera(frame, mesh->positions[sp->idx[0]], a);
    to_camera(frame, mesh->positions[sp->idx[1]], b);
    /* From the nearer end: b − a rounds away the digits of the smaller end
     * when the other lies far off (behind the camera, say, outside the part
     * drawn), and from the far end they would be lost again in a + r·u. A
     * point in a's half is found well from a; past it, from b too, and the
     * nearer end's taken. */
    const double d[3] = { ray_x, ray_y, 1.0 };
    double r_a = nearest_from(cam, a, b, d, sp->p);
    sp->t = r_a;
    if (r_a > 0.5) {
        double r_b = nearest_from(cam, b, a, d, from_b);
        if (r_b < r_a) {
            memcpy(sp->p, from_b, sizeof from_b);
            sp->t = 1.0 - r_b;
        }
    }
    return true;
}
