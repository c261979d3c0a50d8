/* pinhole.c — cameras in OpenCV's convention (softrast.h, "pinhole
 * cameras"): their checks, their clip planes, the draw's matrices, and view
 * depth and range from the triangle each pixel shows. */
#include <math.h>
#include <string.h>

#include "pipeline/02_assemble.h"
#include "softrast/softrast.h"
#include "core/error.h"

/* Room around the mesh's nearest and farthest corners when the clip planes
 * are fitted, and the smallest near as a fraction of far (a camera inside
 * the bounds sees surfaces arbitrarily close; the depth test needs some
 * room between near and far). */
#define FIT_NEAR_SLACK 0.999
#define FIT_FAR_SLACK 1.001
#define FIT_NEAR_MIN 1e-6

/* The ids an SR_SHADE_ID color tells apart: id + 1 in 24 bits. */
#define ID_COLOR_MASK 0xFFFFFFu

static bool all_finite(const double *v, int n)
{
    for (int i = 0; i < n; i++)
        if (!isfinite(v[i]))
            return false;
    return true;
}

/* Whether m is a rotation and translation: RᵀR = I and det R > 0 within
 * the tolerance, last row 0 0 0 1. */
static bool rigid(const double m[4][4])
{
    for (int c = 0; c < 4; c++)
        if (fabs(m[3][c] - (c == 3)) > SR_POSE_TOLERANCE)
            return false;
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++) {
            double dot = m[0][a] * m[0][b] + m[1][a] * m[1][b] + m[2][a] * m[2][b];
            if (fabs(dot - (a == b)) > SR_POSE_TOLERANCE)
                return false;
        }
    double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                 m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                 m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    return det > 0.0;
}

static bool pose_ok(const double m[4][4], const char *name, sr_error *err)
{
    if (!all_finite(&m[0][0], 16))
        return sr_error_set(err, "%s: every entry must be finite", name);
    if (!rigid(m))
        return sr_error_set(err,
                            "%s is not a rigid pose (rotation and translation, last row 0 0 0 1, within %g); "
                            "scale, shear and mirroring are not camera poses",
                            name, SR_POSE_TOLERANCE);
    return true;
}

bool sr_pinhole_check(const sr_pinhole *cam, sr_error *err)
{
    const double k[4] = { cam->fx, cam->fy, cam->cx, cam->cy };
    if (!all_finite(k, 4))
        return sr_error_set(err, "intrinsics fx, fy, cx, cy must be finite");
    if (!(cam->fx > 0.0) || !(cam->fy > 0.0))
        return sr_error_set(err, "intrinsics: fx and fy must be above 0 (got %g, %g)", cam->fx, cam->fy);
    if (!pose_ok(cam->w2c, "the world-to-camera pose", err))
        return false;
    bool fitted = cam->near == 0.0 && cam->far == 0.0;
    if (!fitted && !(isfinite(cam->far) && cam->near > 0.0 && cam->near < cam->far))
        return sr_error_set(err, "clip planes need 0 < near < far, both finite (got %g, %g)", cam->near, cam->far);
    return true;
}

bool sr_pinhole_pose_from_c2w(const double c2w[4][4], double w2c[4][4], sr_error *err)
{
    if (!pose_ok(c2w, "the camera-to-world pose", err))
        return false;
    for (int r = 0; r < 3; r++) {
        w2c[r][3] = 0.0;
        for (int c = 0; c < 3; c++) {
            w2c[r][c] = c2w[c][r];
            w2c[r][3] -= c2w[c][r] * c2w[c][3];
        }
        w2c[3][r] = 0.0;
    }
    w2c[3][3] = 1.0;
    return true;
}

/* A point of the mesh (its vertex, or a corner of its bounds, relative to
 * its origin) in the camera frame, in double. */
static void to_camera(const sr_pinhole *cam, const sr_mesh *mesh, const float p[3], double out[3])
{
    double file[3] = { mesh->origin[0] + p[0], mesh->origin[1] + p[1], mesh->origin[2] + p[2] };
    if (mesh->z_negated)
        file[2] = -file[2];
    for (int r = 0; r < 3; r++)
        out[r] = cam->w2c[r][0] * file[0] + cam->w2c[r][1] * file[1] + cam->w2c[r][2] * file[2] + cam->w2c[r][3];
}

void sr_pinhole_fit_clip(sr_pinhole *cam, const sr_mesh *mesh)
{
    if (cam->near != 0.0 || cam->far != 0.0)
        return;
    vec3 lo, hi;
    double nearest = INFINITY, farthest = 0.0;
    if (sr_mesh_bounds(mesh, lo, hi))
        for (int k = 0; k < 8; k++) {
            float corner[3] = { (k & 1) ? hi[0] : lo[0], (k & 2) ? hi[1] : lo[1], (k & 4) ? hi[2] : lo[2] };
            double c[3];
            to_camera(cam, mesh, corner, c);
            nearest = fmin(nearest, c[2]);
            farthest = fmax(farthest, c[2]);
        }
    if (!(farthest > 0.0) || !isfinite(farthest)) { /* nothing in front: any planes show nothing */
        cam->near = 1.0;
        cam->far = 2.0;
        return;
    }
    cam->far = FIT_FAR_SLACK * farthest;
    cam->near = fmax(FIT_NEAR_SLACK * nearest, FIT_NEAR_MIN * cam->far);
}

void sr_pinhole_matrices(const sr_pinhole *cam, const sr_mesh *mesh, int width, int height, sr_draw_desc *desc)
{
    /* view = F · w2c · S: S undoes the loader's z negation, F turns the
     * camera's y down into softrast's view y up. */
    double s = mesh->z_negated ? -1.0 : 1.0;
    memset(&desc->view_d, 0, sizeof desc->view_d);
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++)
            desc->view_d.m[c][r] = (r == 1 ? -1.0 : 1.0) * cam->w2c[r][c] * (c == 2 ? s : 1.0);
    /* Pixel x + 0.5 is u (softrast samples pixel centres at x + 0.5, OpenCV
     * at u), so x_ndc = (2(fx·X/Z + cx) + 1)/W − 1, and y likewise with
     * y_ndc up. Each entry is computed in double and rounded once. */
    double w = width, h = height, n = cam->near, f = cam->far;
    glm_mat4_zero(desc->projection);
    desc->projection[0][0] = (float)(2.0 * cam->fx / w);
    desc->projection[2][0] = (float)((2.0 * cam->cx + 1.0) / w - 1.0);
    desc->projection[1][1] = (float)(2.0 * cam->fy / h);
    desc->projection[2][1] = (float)(1.0 - (2.0 * cam->cy + 1.0) / h);
    desc->projection[2][2] = (float)(f / (f - n));
    desc->projection[3][2] = (float)(-f * n / (f - n));
    desc->projection[2][3] = 1.0f;
    glm_mat4_identity(desc->world);
    memset(&desc->world_d, 0, sizeof desc->world_d);
}

/* The view z a depth-buffer value stands for, under cam's projection. */
static double z_of_depth(const sr_pinhole *cam, float z_ndc)
{
    double n = cam->near, f = cam->far;
    return f * n / (f - (double)z_ndc * (f - n));
}

/* Triangle `slot`'s plane in the camera frame: a point on it and its normal. */
typedef struct plane {
    uint32_t slot;
    double point[3], normal[3];
} plane;

static void plane_of(const sr_pinhole *cam, const sr_mesh *mesh, uint32_t slot, plane *p)
{
    uint32_t idx[3];
    double v[3][3];
    sr_assemble_triangle(mesh, slot, idx); /* drawn, so not degenerate */
    for (int k = 0; k < 3; k++)
        to_camera(cam, mesh, mesh->positions[idx[k]], v[k]);
    double a[3], b[3];
    for (int k = 0; k < 3; k++) {
        a[k] = v[1][k] - v[0][k];
        b[k] = v[2][k] - v[0][k];
        p->point[k] = v[0][k];
    }
    p->normal[0] = a[1] * b[2] - a[2] * b[1];
    p->normal[1] = a[2] * b[0] - a[0] * b[2];
    p->normal[2] = a[0] * b[1] - a[1] * b[0];
    p->slot = slot;
}

bool sr_pinhole_depth(const sr_pinhole *cam, const sr_mesh *mesh, const sr_framebuffer *ids, float invalid,
                      float *depth, float *range, sr_error *err)
{
    if (!mesh->positions)
        return sr_error_set(err, "view depth needs the mesh's positions (not clip-space ones)");
    if (sr_mesh_triangle_slots(mesh) >= ID_COLOR_MASK)
        return sr_error_set(err, "%u triangles: view depth tells apart at most %u", sr_mesh_triangle_slots(mesh),
                            ID_COLOR_MASK - 1);
    plane p = { .slot = UINT32_MAX };
    for (int y = 0; y < ids->height; y++)
        for (int x = 0; x < ids->width; x++) {
            size_t at = (size_t)y * (size_t)ids->width + (size_t)x;
            uint32_t id = ids->color[at] & ID_COLOR_MASK;
            double z = NAN, length = NAN;
            if (id != 0) {
                if (p.slot != id - 1)
                    plane_of(cam, mesh, id - 1, &p);
                const double ray[3] = { (x - cam->cx) / cam->fx, (y - cam->cy) / cam->fy, 1.0 };
                double along = p.normal[0] * ray[0] + p.normal[1] * ray[1] + p.normal[2] * ray[2];
                z = (p.normal[0] * p.point[0] + p.normal[1] * p.point[1] + p.normal[2] * p.point[2]) / along;
                if (!(z > 0.0) || !isfinite(z)) /* the ray runs in the plane: an edge-on triangle */
                    z = z_of_depth(cam, ids->depth[at]);
                length = z * sqrt(ray[0] * ray[0] + ray[1] * ray[1] + 1.0);
            }
            if (depth)
                depth[at] = id ? (float)z : invalid;
            if (range)
                range[at] = id ? (float)length : invalid;
        }
    return true;
}
