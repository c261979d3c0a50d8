/* The stiff cases of `softrast bench --stability`: a camera each, the flat
 * grid section 2 draws under it, and the random triangles section 1 clips. */
#include <math.h>

#include "stability_cases.h"

#define LATERAL_SPREAD 2.0   /* random points reach twice the frustum's half-width, so side planes cut */
#define BEHIND_CHANCE 0.15   /* share of random points behind the eye */
#define SLIVER_WIDTH 1e-7
#define FAR_BEHIND 1000.0    /* the eye-spanning triangle's far vertex has w = -FAR_BEHIND */
#define HUGE_COORDINATE 1e30
#define GROUND_EXTENT 1e7

const sr_stability_clipper sr_stability_clippers[SR_STABILITY_CLIPPERS] = {
    { "default (adaptive)", SR_CLIP_ADAPTIVE },
    { "double", SR_CLIP_DOUBLE },
    { "float", SR_CLIP_FLOAT },
    { "exact", SR_CLIP_EXACT },
};

double sr_stability_uniform(sr_stability_rng *rng, double lo, double hi)
{
    /* splitmix64: tiny, fast, and the same sequence on every platform. */
    uint64_t z = (rng->state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return lo + (hi - lo) * ((double)(z >> 11) * 0x1.0p-53);
}

double sr_stability_log_uniform(sr_stability_rng *rng, double lo, double hi)
{
    return exp(sr_stability_uniform(rng, log(lo), log(hi)));
}

static void normalize(double v[3])
{
    double n = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int i = 0; i < 3; i++)
        v[i] /= n;
}

static void cross(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

sr_stability_frame sr_stability_frame_of(const sr_camera *cam)
{
    sr_stability_frame f;
    double up[3];
    for (int i = 0; i < 3; i++) {
        f.eye[i] = cam->eye[i];
        f.forward[i] = (double)cam->target[i] - cam->eye[i];
        up[i] = cam->up[i];
    }
    normalize(f.forward);
    cross(up, f.forward, f.right);
    normalize(f.right);
    cross(f.forward, f.right, f.up);
    return f;
}

void sr_stability_clip_matrix(const sr_camera *cam, mat4 clip_from_world)
{
    mat4 view, projection;
    sr_camera_view(cam, view);
    sr_camera_projection(cam, (float)SR_STABILITY_WIDTH / SR_STABILITY_HEIGHT, projection);
    glm_mat4_mul(projection, view, clip_from_world); /* the order sr_vertex_make_transform uses */
}

/* The world point at view coordinates (x right, y up, depth forward). */
static void view_point(const sr_stability_case *c, double x, double y, double depth, float out[3])
{
    sr_stability_frame f = sr_stability_frame_of(&c->camera);
    for (int i = 0; i < 3; i++)
        out[i] = (float)(f.eye[i] + x * f.right[i] + y * f.up[i] + depth * f.forward[i]);
}

/* A point at this depth, spread laterally past the frustum's sides. */
static void lateral_point(const sr_stability_case *c, sr_stability_rng *rng, double depth, float out[3])
{
    double tan_y = tan(glm_rad(c->camera.fov_deg) * 0.5);
    double tan_x = tan_y * SR_STABILITY_WIDTH / SR_STABILITY_HEIGHT;
    double reach = fabs(depth) * LATERAL_SPREAD;
    view_point(c, sr_stability_uniform(rng, -reach, reach) * tan_x, sr_stability_uniform(rng, -reach, reach) * tan_y,
               depth, out);
}

/* A point at a log-uniform distance in [lo, hi], in front or (by chance) behind. */
static void frustum_point(const sr_stability_case *c, sr_stability_rng *rng, double lo, double hi, float out[3])
{
    double depth = sr_stability_log_uniform(rng, lo, hi);
    lateral_point(c, rng, sr_stability_uniform(rng, 0.0, 1.0) < BEHIND_CHANCE ? -depth : depth, out);
}

/* Anywhere from a hundredth of near to ten times far (or 1e30 past near for an infinite far). */
static void span_triangle(const sr_stability_case *c, sr_stability_rng *rng, vec3 out[3])
{
    double far = isinf(c->camera.far) ? HUGE_COORDINATE * c->camera.near : 10.0 * c->camera.far;
    for (int k = 0; k < 3; k++)
        frustum_point(c, rng, 0.01 * c->camera.near, far, out[k]);
}

/* One or two vertices at 1e30 in a random direction, the rest within a few units of the origin. */
static void huge_triangle(const sr_stability_case *c, sr_stability_rng *rng, vec3 out[3])
{
    (void)c;
    int huge = sr_stability_uniform(rng, 0.0, 1.0) < 0.5 ? 1 : 2;
    for (int k = 0; k < 3; k++) {
        double v[3] = { sr_stability_uniform(rng, -1, 1), sr_stability_uniform(rng, -1, 1),
                        sr_stability_uniform(rng, -1, 1) };
        if (k < huge)
            normalize(v);
        for (int i = 0; i < 3; i++)
            out[k][i] = (float)(v[i] * (k < huge ? HUGE_COORDINATE : 3.0));
    }
}

static void ground_triangle(const sr_stability_case *c, sr_stability_rng *rng, vec3 out[3])
{
    (void)c;
    for (int k = 0; k < 3; k++)
        glm_vec3_copy((vec3){ (float)sr_stability_uniform(rng, -GROUND_EXTENT, GROUND_EXTENT), 0.0f,
                              (float)sr_stability_uniform(rng, -GROUND_EXTENT, GROUND_EXTENT) }, out[k]);
}

/* Edge a–b straddles the near plane by a relative 1e-9 … 1e-3 either side:
 * nearly parallel to it, so the cut's t comes from nearly equal depths. */
static void parallel_triangle(const sr_stability_case *c, sr_stability_rng *rng, vec3 out[3])
{
    double n = c->camera.near;
    double above = n * (1.0 + sr_stability_log_uniform(rng, 1e-9, 1e-3));
    double below = n * (1.0 - sr_stability_log_uniform(rng, 1e-9, 1e-3));
    lateral_point(c, rng, above, out[0]);
    lateral_point(c, rng, below, out[1]);
    frustum_point(c, rng, 1e-3 * n, 1e3 * n, out[2]);
}

/* In the plane y = -h just below the eye (h = 1e-7 … 1): two vertices in
 * front on either side, one FAR_BEHIND behind, so the triangle spans the eye. */
static void eye_spanning_triangle(const sr_stability_case *c, sr_stability_rng *rng, vec3 out[3])
{
    double h = sr_stability_log_uniform(rng, 1e-7, 1.0);
    double reach = sr_stability_log_uniform(rng, 1e-6, FAR_BEHIND);
    view_point(c, -reach * sr_stability_uniform(rng, 0.01, 1), -h, reach * sr_stability_uniform(rng, 0.01, 1),
               out[0]);
    view_point(c, reach * sr_stability_uniform(rng, 0.01, 1), -h, reach * sr_stability_uniform(rng, 0.01, 1), out[1]);
    view_point(c, sr_stability_uniform(rng, -FAR_BEHIND, FAR_BEHIND), -h, -FAR_BEHIND, out[2]);
}

/* Two vertices SLIVER_WIDTH apart, the third anywhere: a long thin sliver. */
static void sliver_triangle(const sr_stability_case *c, sr_stability_rng *rng, vec3 out[3])
{
    frustum_point(c, rng, 1e3 * c->camera.near, c->camera.far, out[0]);
    double d[3] = { sr_stability_uniform(rng, -1, 1), sr_stability_uniform(rng, -1, 1),
                    sr_stability_uniform(rng, -1, 1) };
    normalize(d);
    for (int i = 0; i < 3; i++)
        out[1][i] = (float)(out[0][i] + SLIVER_WIDTH * d[i]);
    frustum_point(c, rng, 0.1 * c->camera.near, 100.0 * c->camera.far, out[2]);
}

#define CAMERA(ex, ey, ez, tx, ty, tz, ux, uy, uz, n, f) \
    { .eye = { ex, ey, ez }, .target = { tx, ty, tz }, .up = { ux, uy, uz }, .fov_deg = SR_CAMERA_FOV, \
      .near = n, .far = f }
/* The camera, grid and inner radius of an eye `height` above a level ground
 * (the grid: `half` to each side of the origin in x and z), looking along +z
 * at its own height; the grid's cells start `inner` out. */
#define LEVEL_GROUND(height, n, f, half, inner) \
    CAMERA(0, height, 0, 0, height, 1, 0, 1, 0, n, f), { 0, 0, 0 }, { half, 0, 0 }, { 0, 0, half }, (inner) / (half)

/* Grids lie in y = 0 (or z = const for the near-parallel case), so their
 * float vertices are exactly in the plane the region test intersects. An eye
 * closer to the ground than near puts the near plane's cut across the screen. */
static const sr_stability_case CASES[SR_STABILITY_CASES] = {
    { "near 1e-6, far 1e9", "eye 2e-7 above a ground 4e9 across, cells from 1e-7 out: near and far both cut it",
      "vertices 1e-8 … 1e10 away, 15% behind the eye, spread past the sides",
      LEVEL_GROUND(2e-7f, 1e-6f, 1e9f, 2e9, 1e-7), span_triangle },
    { "far = +inf", "near 1e-3, eye 1e-4 above a ground 2e12 across, cells from 1e-4 out",
      "vertices 1e-5 … 1e27 away, 15% behind the eye, spread past the sides",
      LEVEL_GROUND(1e-4f, 1e-3f, INFINITY, 1e12, 1e-4), span_triangle },
    { "1e30 vertices", "near 0.1, far 100, ground 2e30 across in even cells (3e28) seen from 4 units",
      "one or two vertices 1e30 from the origin, the rest within 3 of it",
      CAMERA(0, 3, -3, 0, 0, 0, 0, 1, 0, 0.1f, 100.0f),
      { 0, 0, 0 }, { 1e30f, 0, 0 }, { 0, 0, 1e30f }, 0.0, huge_triangle },
    { "ground 1e7", "near 0.1, far 1e8, eye 1 above a ground 2e7 across, cells from 1 out",
      "vertices anywhere on the ground (±1e7)",
      CAMERA(0, 1, 0, 0, 0.5f, 1, 0, 1, 0, 0.1f, 1e8f),
      { 0, 0, 0 }, { 1e7f, 0, 0 }, { 0, 0, 1e7f }, 1.0 / 1e7, ground_triangle },
    { "edge parallel to near", "near 0.01; a wall at depth 0.01 turned 1e-4 rad, so the near plane cuts it at a graze",
      "an edge from near·(1 + ε) to near·(1 − ε), ε = 1e-9 … 1e-3, third vertex 1e-5 … 10 away",
      CAMERA(0, 0, 0, 1e-4f, 0, 1, 0, 1, 0, 0.01f, 100.0f),
      { 0, 0, 0.01f }, { 0.02f, 0, 0 }, { 0, 0.02f, 0 }, 0.0, parallel_triangle },
    { "eye-spanning, w = -1000", "near 1e-6, far 1e4, eye 1e-7 above a ground from z = -1000 to 1000, cells from 1e-7 out",
      "in a plane 1e-7 … 1 below the eye: two vertices in front on either side, one at w = -1000",
      LEVEL_GROUND(1e-7f, 1e-6f, 1e4f, 1000, 1e-7), eye_spanning_triangle },
    { "sliver 1e-7", "near 1e-6, far 1; even grid cells 15.6 by 1e-7 seen from 1e-5 above",
      "two vertices 1e-7 apart, 1e-3 … 1 away; the third anywhere, 1e-7 … 100 away",
      CAMERA(0, 1e-5f, 3.2e-6f, 0, 0, 3.2e-6f, 0, 0, 1, 1e-6f, 1.0f),
      { 0, 0, 3.2e-6f }, { 500, 0, 0 }, { 0, 0, 3.2e-6f }, 0.0, sliver_triangle },
};

const sr_stability_case *sr_stability_cases(void)
{
    return CASES;
}
