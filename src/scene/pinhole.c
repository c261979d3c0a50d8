/* pinhole.c — cameras in OpenCV's convention (softrast.h, "pinhole
 * cameras"): their checks, their clip planes and the draw's matrices. What
 * each pixel shows is resolved in pinhole_resolve.c. */
#include <math.h>
#include <string.h>

#include "mesh_bounds.h"
#include "pinhole_frame.h"
#include "softrast/softrast.h"
#include "core/error.h"

/* Room around the mesh's nearest and farthest corners when the clip planes
 * are fitted, and the smallest near as a fraction of far (a camera inside
 * the bounds sees surfaces arbitrarily close; the depth test needs some
 * room between near and far). */
#define FIT_NEAR_SLACK 0.999
#define FIT_FAR_SLACK 1.001
#define FIT_NEAR_MIN 1e-6

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

void sr_pinhole_fit_clip(sr_pinhole *cam, const sr_mesh *mesh)
{
    if (cam->near != 0.0 || cam->far != 0.0)
        return;
    vec3 lo, hi;
    double nearest = INFINITY, farthest = 0.0;
    camera_frame frame = camera_frame_of(cam, mesh);
    /* The bounds the mesh keeps, which the draw trusts too: a vision user
     * fits every view of one mesh, which then need not walk its vertices
     * each time. A mesh keeps none when a position is not finite (an
     * organised depth-sensor cloud marks its pixels without a return so). */
    bool bounded = mesh->bounded;
    if (bounded) {
        glm_vec3_copy((float *)mesh->bounds_lo, lo);
        glm_vec3_copy((float *)mesh->bounds_hi, hi);
    } else {
        bounded = sr_mesh_finite_bounds(mesh, lo, hi);
    }
    if (bounded)
        for (int k = 0; k < 8; k++) {
            float corner[3] = { (k & 1) ? hi[0] : lo[0], (k & 2) ? hi[1] : lo[1], (k & 4) ? hi[2] : lo[2] };
            double c[3];
            to_camera(&frame, corner, c);
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

void sr_pinhole_matrices(const sr_pinhole *cam, const sr_mesh *mesh, sr_framebuffer *fb, sr_draw_desc *desc)
{
    fb->reversed_z = true;
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
    double w = fb->width, h = fb->height, n = cam->near, f = cam->far;
    glm_mat4_zero(desc->projection);
    desc->projection[0][0] = (float)(2.0 * cam->fx / w);
    desc->projection[2][0] = (float)((2.0 * cam->cx + 1.0) / w - 1.0);
    desc->projection[1][1] = (float)(2.0 * cam->fy / h);
    desc->projection[2][1] = (float)(1.0 - (2.0 * cam->cy + 1.0) / h);
    /* Reversed z (near → 1, far → 0): float z_ndc then keeps about the same
     * relative precision at every distance, so a surface far away is not
     * hidden by one a float step behind it. */
    desc->projection[2][2] = (float)(-n / (f - n));
    desc->projection[3][2] = (float)(f * n / (f - n));
    desc->projection[2][3] = 1.0f;
    glm_mat4_identity(desc->world);
    memset(&desc->world_d, 0, sizeof desc->world_d);
}
