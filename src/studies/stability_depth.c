/* Section 3 of the stability report: the smallest separation s between two
 * planes facing the camera, at view depths d and d + s, that the depth test
 * still orders (the nearer plane's ids at every pixel, drawn far-first and
 * near-first, while the farther plane alone still fills the view: a plane
 * whose depth rounds to the clear value is never drawn and would "lose" to
 * anything), found by bisection over real draws, with the standard mapping
 * and with reversed z. The camera has near = 1 and far = the ratio.
 *
 * A separation s counts only if it orders the planes at PLACES depths
 * d + j·PLACE_SPREAD·s / PLACES: at one depth a separation below the
 * buffer's resolution passes whenever a rounding boundary of the stored
 * depth happens to fall between the planes; sliding the pair over twice its
 * separation finds a position without one unless s spans the spacing of
 * those boundaries, the resolution this table is after. */
#include <math.h>
#include <stdlib.h>

#include "stability_depth.h"

#define DEPTH_SIDE 16             /* framebuffer side: every pixel must agree */
#define FIRST_RATIO_EXPONENT 2    /* far/near = 10^2 … */
#define BISECTION_STEPS 40
#define SMALLEST_TRIED 1e-10      /* s/d; below one float ulp of d */
#define FAR_MARGIN 0.999          /* the farther plane stays this far inside the far plane */
#define LARGEST_TRIED 1.0         /* s/d: farther apart, the planes are no longer "at d" */
#define COVER 2.0                 /* quad side / far: covers the 60° view at every depth up to far */
#define VERTICES_PER_QUAD 4
#define PLACES 16                 /* positions each separation is tried at */
#define PLACE_SPREAD 2.0          /* they span this many separations */

static const double FRACTIONS[SR_STABILITY_DISTANCES] = { 0.01, 0.1, 0.5, 0.9 };

typedef struct depth_probe {
    sr_framebuffer fb;
    sr_mesh quads;
    sr_draw_desc desc; /* with a workspace: thousands of tiny draws */
} depth_probe;

/* The nearer plane's view depth, as the float the mesh can hold. */
static double plane_distance(double ratio, double fraction)
{
    return (double)(float)(1.0 + fraction * (ratio - 1.0));
}

static sr_camera probe_camera(double ratio, bool reversed)
{
    sr_camera cam = { .eye = { 0, 0, 0 }, .target = { 0, 0, 1 }, .up = { 0, 1, 0 }, .fov_deg = SR_CAMERA_FOV,
                      .near = 1.0f, .far = (float)ratio, .reversed_z = reversed };
    return cam;
}

static void set_quad_depth(sr_mesh *m, int quad, float z)
{
    for (int k = 0; k < VERTICES_PER_QUAD; k++)
        m->positions[quad * VERTICES_PER_QUAD + k][2] = z;
}

/* Quad q's two triangles have ids 2q and 2q + 1, shaded as id + 1. */
static bool all_from_quad(const sr_framebuffer *fb, int quad)
{
    uint32_t lo = 2u * (uint32_t)quad + 1u, hi = lo + 1u;
    for (int i = 0; i < fb->width * fb->height; i++)
        if (fb->color[i] < lo || fb->color[i] > hi)
            return false;
    return true;
}

/* Draws quad 0 at depth `first` then quad 1 at `second`; true if quad
 * `expected` shows at every pixel. */
static bool shows(depth_probe *p, float first, float second, int expected, bool *yes, sr_error *err)
{
    set_quad_depth(&p->quads, 0, first);
    set_quad_depth(&p->quads, 1, second);
    sr_framebuffer_clear(&p->fb, 0);
    if (!sr_draw(&p->fb, &p->desc, NULL, err))
        return false;
    *yes = all_from_quad(&p->fb, expected);
    return true;
}

static bool nearer_wins(depth_probe *p, float first, float second, bool *wins, sr_error *err)
{
    return shows(p, first, second, first < second ? 0 : 1, wins, err);
}

/* The far plane alone: quad 1 goes behind the eye, where outcodes reject it. */
static bool far_alone_fills(depth_probe *p, float far_z, bool *fills, sr_error *err)
{
    return shows(p, far_z, -far_z, 0, fills, err);
}

/* The nearer plane's depth at place j. */
static double place(double d, double s, int j)
{
    return d + j * PLACE_SPREAD * s / PLACES;
}

/* Both drawing orders, at every place. */
static bool ordered(depth_probe *p, double d, double s, bool *wins, sr_error *err)
{
    *wins = true;
    for (int j = 0; j < PLACES && *wins; j++) {
        double at = place(d, s, j);
        float near_z = (float)at, far_z = (float)(at + s);
        bool near_first = false, far_first = false;
        if (!nearer_wins(p, near_z, far_z, &near_first, err) || !nearer_wins(p, far_z, near_z, &far_first, err))
            return false;
        *wins = near_z < far_z && near_first && far_first;
    }
    return true;
}

/* The farther plane alone is drawn at every place. */
static bool far_drawn(depth_probe *p, double d, double s, bool *drawn, sr_error *err)
{
    *drawn = true;
    for (int j = 0; j < PLACES && *drawn; j++)
        if (!far_alone_fills(p, (float)(place(d, s, j) + s), drawn, err))
            return false;
    return true;
}

typedef bool (*depth_test)(depth_probe *p, double d, double s, bool *yes, sr_error *err);

/* Geometric bisection of [lo, hi] for where test changes its answer, given
 * that it answers want_hi at hi; *at is the s nearest the change on that side. */
static bool bisect(depth_probe *p, depth_test test, double d, double lo, double hi, bool want_hi, double *at,
                   sr_error *err)
{
    for (int i = 0; i < BISECTION_STEPS; i++) {
        double mid = sqrt(lo * hi);
        bool yes;
        if (!test(p, d, mid, &yes, err))
            return false;
        *(yes == want_hi ? &hi : &lo) = mid;
    }
    *at = want_hi ? hi : lo;
    return true;
}

/* Between SMALLEST_TRIED·d and LARGEST_TRIED·d, or the largest s at which
 * the farther plane is still drawn (past it, its depth rounds to the clear
 * value) if that is smaller. */
static bool smallest_separation(depth_probe *p, double d, double far, double *rel, sr_error *err)
{
    double lo = SMALLEST_TRIED * d, hi = fmin(LARGEST_TRIED * d, FAR_MARGIN * (far - d) / (1.0 + PLACE_SPREAD));
    bool yes;
    *rel = NAN;
    if (!far_drawn(p, d, hi, &yes, err))
        return false;
    if (!yes && !bisect(p, far_drawn, d, lo, hi, false, &hi, err))
        return false;
    if (!ordered(p, d, hi, &yes, err))
        return false;
    if (!yes)
        return true;
    if (!bisect(p, ordered, d, lo, hi, true, &hi, err))
        return false;
    /* What the float positions actually put between the planes. */
    *rel = ((double)(float)(d + hi) - (double)(float)d) / d;
    return true;
}

static bool probe_make(depth_probe *p, double ratio, bool reversed, sr_error *err)
{
    sr_camera cam = probe_camera(ratio, reversed);
    *p = (depth_probe){ .desc = { .shade = SR_SHADE_ID, .workspace = sr_workspace_create() } };
    if (!p->desc.workspace)
        return sr_error_set(err, "out of memory for a workspace");
    if (!sr_framebuffer_create(&p->fb, DEPTH_SIDE, DEPTH_SIDE, err))
        return false;
    p->fb.reversed_z = reversed;
    if (!sr_shape_quads(&p->quads, 2, (float)(COVER * ratio), 1.0f, 1.0f, err))
        return false;
    p->desc.mesh = &p->quads;
    sr_camera_view(&cam, p->desc.view);
    sr_camera_projection(&cam, 1.0f, p->desc.projection);
    return true;
}

static void probe_free(depth_probe *p)
{
    if (p->fb.color)
        sr_framebuffer_destroy(&p->fb);
    sr_mesh_free(&p->quads);
    sr_workspace_destroy(p->desc.workspace);
}

static bool measure_ratio(sr_stability_depth *out, int r, sr_error *err)
{
    double ratio = out->ratio[r];
    for (int m = 0; m < SR_STABILITY_MAPPINGS; m++) {
        depth_probe p;
        bool ok = probe_make(&p, ratio, m == 1, err);
        for (int k = 0; ok && k < SR_STABILITY_DISTANCES; k++) {
            double d = plane_distance(ratio, out->fraction[k]);
            ok = smallest_separation(&p, d, ratio, &out->separation[r][k][m], err);
        }
        probe_free(&p);
        if (!ok)
            return false;
    }
    return true;
}

bool sr_stability_depth_table(sr_stability_depth *out, sr_error *err)
{
    for (int k = 0; k < SR_STABILITY_DISTANCES; k++)
        out->fraction[k] = FRACTIONS[k];
    for (int r = 0; r < SR_STABILITY_RATIOS; r++) {
        out->ratio[r] = pow(10.0, FIRST_RATIO_EXPONENT + r);
        for (int k = 0; k < SR_STABILITY_DISTANCES; k++) {
            double d = plane_distance(out->ratio[r], out->fraction[k]);
            out->distance[r][k] = d;
            out->floor[r][k] = ((double)nextafterf((float)d, INFINITY) - d) / d;
        }
        if (!measure_ratio(out, r, err))
            return false;
    }
    return true;
}
