#include <math.h>

#include <cglm/clipspace/ortho_lh_zo.h>
#include <cglm/clipspace/persp_lh_zo.h>

#include "softrast/softrast.h"
#include "core/error.h"
#include "core/dmat4.h"

#define FRAME_MARGIN 1.05f /* a little room around the framed bounds */

/* Where the framed camera stands, seen from the scene's centre: in front
 * (-z), turned 30 degrees to the right and raised 20 above it, a
 * three-quarter view (docs/cli.md, "The default camera", says why). */
#define FRAME_AZIMUTH_DEG 30.0
#define FRAME_ELEVATION_DEG 20.0

/* Slack around the bounding sphere when near and far are fitted to it, so
 * its nearest and farthest points are never clipped; an eye inside the
 * sphere keeps near above FIT_NEAR_MIN of far (the depth buffer's
 * resolution near the eye). */
#define FIT_NEAR_SLACK 0.99f
#define FIT_FAR_SLACK 1.01f
#define FIT_NEAR_MIN 1e-5f

static bool all_finite(const float *v, int n)
{
    for (int i = 0; i < n; i++)
        if (!isfinite(v[i]))
            return false;
    return true;
}

sr_camera sr_camera_default(void)
{
    return (sr_camera){ .eye = { 0.0f, 0.0f, -3.0f }, .target = { 0.0f, 0.0f, 0.0f }, .up = { 0.0f, 1.0f, 0.0f },
                        .fov_deg = SR_CAMERA_FOV, .near = SR_CAMERA_NEAR, .far = SR_CAMERA_FAR };
}

void sr_camera_frame_bounds(sr_camera *cam, const vec3 lo, const vec3 hi, float aspect)
{
    vec3 centre;
    glm_vec3_center((float *)lo, (float *)hi, centre);
    float radius = 0.5f * sr_vec3_distance_d(lo, hi);
    float half_fov = glm_rad(cam->fov_deg) * 0.5f;
    float half_fov_x = atanf(tanf(half_fov) * aspect);
    float narrow = half_fov < half_fov_x ? half_fov : half_fov_x;
    float distance = radius > 0.0f ? FRAME_MARGIN * radius / sinf(narrow) : 1.0f;
    const double az = FRAME_AZIMUTH_DEG * GLM_PI / 180.0, el = FRAME_ELEVATION_DEG * GLM_PI / 180.0;
    const double toward_eye[3] = { sin(az) * cos(el), sin(el), -cos(az) * cos(el) };
    glm_vec3_copy(centre, cam->target);
    for (int k = 0; k < 3; k++)
        cam->eye[k] = sr_double_to_float(centre[k] + distance * toward_eye[k]);
    if (cam->ortho_height > 0.0f)
        cam->ortho_height = 2.0f * FRAME_MARGIN * radius;
    sr_camera_fit_clip(cam, lo, hi);
}

void sr_camera_fit_clip(sr_camera *cam, const vec3 lo, const vec3 hi)
{
    /* In double: a scene near float's range still has a finite span. */
    double centre[3], axis[3], to_centre[3], length2 = 0.0, along = 0.0, dist2 = 0.0;
    for (int k = 0; k < 3; k++) {
        centre[k] = 0.5 * ((double)lo[k] + (double)hi[k]);
        axis[k] = (double)cam->target[k] - cam->eye[k];
        to_centre[k] = centre[k] - cam->eye[k];
        length2 += axis[k] * axis[k];
        along += to_centre[k] * axis[k];
        dist2 += to_centre[k] * to_centre[k];
    }
    double radius = sr_vec3_distance_d(lo, hi) * 0.5;
    if (!(length2 > 0.0) || !isfinite(length2) || !isfinite(along) || !isfinite(radius))
        return;
    along /= sqrt(length2);
    double nearest = along - radius, farthest = along + radius;
    bool inside = dist2 <= radius * radius;
    if (!(farthest > 0.0) || ((nearest >= cam->near || inside) && farthest <= cam->far))
        return;
    cam->far = sr_double_to_float(FIT_FAR_SLACK * farthest);
    if (!inside)
        cam->near = sr_double_to_float(FIT_NEAR_SLACK * nearest);
    float near_min = FIT_NEAR_MIN * cam->far;
    if (!(cam->near >= near_min))
        cam->near = near_min;
}

bool sr_camera_check(const sr_camera *cam, sr_error *err)
{
    if (!all_finite(cam->eye, 3) || !all_finite(cam->target, 3) || !all_finite(cam->up, 3))
        return sr_error_set(err, "camera eye, target and up must be finite");
    if (!isfinite(cam->origin[0]) || !isfinite(cam->origin[1]) || !isfinite(cam->origin[2]))
        return sr_error_set(err, "camera origin must be finite");
    vec3 dir, side;
    glm_vec3_sub((float *)cam->target, (float *)cam->eye, dir);
    if (glm_vec3_norm(dir) == 0.0f)
        return sr_error_set(err, "camera eye and target are the same point");
    glm_vec3_cross(dir, (float *)cam->up, side);
    if (glm_vec3_norm(side) == 0.0f)
        return sr_error_set(err, "camera up is zero or parallel to the view direction");
    if (!(cam->near > 0.0f) || !isfinite(cam->near))
        return sr_error_set(err, "near plane must be a positive finite number (got %g)", cam->near);
    bool far_ok = cam->far > cam->near && (isfinite(cam->far) || cam->ortho_height <= 0.0f);
    if (!far_ok)
        return sr_error_set(err, "far plane must be beyond near, and finite for an orthographic camera "
                                 "(near %g, far %g)", cam->near, cam->far);
    if (cam->ortho_height > 0.0f ? !isfinite(cam->ortho_height)
                                 : !(cam->fov_deg > 0.0f && cam->fov_deg < 180.0f))
        return sr_error_set(err, "fov must be between 0 and 180 degrees (got %g)", cam->fov_deg);
    return true;
}

static void dvec3_from(const float *v, double out[3])
{
    for (int k = 0; k < 3; k++)
        out[k] = v[k];
}

static void dvec3_normalize(double v[3])
{
    double len = sqrt(sr_dvec3_dot(v, v));
    for (int k = 0; k < 3; k++)
        v[k] /= len;
}

/* glm_lookat_lh in double: rows right, up, forward; then T(-eye). */
static sr_dmat4 lookat_lh_d(const double eye[3], const double target[3], const double up[3])
{
    double f[3] = { target[0] - eye[0], target[1] - eye[1], target[2] - eye[2] }, s[3], u[3];
    dvec3_normalize(f);
    sr_dvec3_cross(up, f, s);
    dvec3_normalize(s);
    sr_dvec3_cross(f, s, u);
    sr_dmat4 v = sr_dmat4_identity();
    for (int k = 0; k < 3; k++) {
        v.m[k][0] = s[k];
        v.m[k][1] = u[k];
        v.m[k][2] = f[k];
    }
    v.m[3][0] = -sr_dvec3_dot(s, eye);
    v.m[3][1] = -sr_dvec3_dot(u, eye);
    v.m[3][2] = -sr_dvec3_dot(f, eye);
    return v;
}

void sr_camera_view_d(const sr_camera *cam, sr_dmat4 *out)
{
    double eye[3], target[3], up[3], back[3];
    dvec3_from(cam->eye, eye);
    dvec3_from(cam->target, target);
    dvec3_from(cam->up, up);
    sr_dmat4 look = lookat_lh_d(eye, target, up);
    for (int k = 0; k < 3; k++)
        back[k] = -cam->origin[k];
    *out = sr_dmat4_translate(&look, back);
}

void sr_camera_view(const sr_camera *cam, mat4 out)
{
    sr_dmat4 view;
    sr_camera_view_d(cam, &view);
    sr_dmat4_to_mat4(&view, out);
}

/* z_clip = a·z_view + b (w is z_view for perspective, 1 for orthographic),
 * in every mode from double, so the coefficients are the correctly rounded
 * ones: cglm's float f/(f − n) is off by an ulp or more, a bias every depth
 * carries (and n·f may overflow float for a scene near float's range though
 * a and b themselves fit). */
static void z_row_in_double(const sr_camera *cam, mat4 out)
{
    double n = cam->near, f = cam->far, a, b;
    bool reversed = cam->reversed_z;
    if (cam->ortho_height > 0.0f) {
        a = (reversed ? -1.0 : 1.0) / (f - n);
        b = (reversed ? f : -n) / (f - n);
    } else if (isinf(f)) {
        a = reversed ? 0.0 : 1.0;
        b = reversed ? n : -n;
    } else {
        a = (reversed ? -n : f) / (f - n);
        b = (reversed ? n * f : -n * f) / (f - n);
    }
    out[2][2] = sr_double_to_float(a);
    out[3][2] = sr_double_to_float(b);
}

void sr_camera_projection(const sr_camera *cam, float aspect, mat4 out)
{
    float far = isinf(cam->far) ? 2.0f * cam->near : cam->far; /* the z row is rewritten below */
    if (cam->ortho_height > 0.0f) {
        float h = cam->ortho_height * 0.5f, w = h * aspect;
        glm_ortho_lh_zo(-w, w, -h, h, cam->near, far, out);
    } else {
        glm_perspective_lh_zo(glm_rad(cam->fov_deg), aspect, cam->near, far, out);
    }
    z_row_in_double(cam, out);
}

double sr_camera_view_distance(float z_ndc, const void *camera)
{
    const sr_camera *cam = camera;
    double n = cam->near, f = cam->far, z = cam->reversed_z ? 1.0 - z_ndc : z_ndc;
    if (cam->ortho_height > 0.0f)
        return n + z * (f - n);
    if (isinf(f))
        return n / (1.0 - z);
    return n * f / (f - z * (f - n));
}
