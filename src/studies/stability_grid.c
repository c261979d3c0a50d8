/* Section 2 of the stability report: a flat grid of GRID_CELLS² quads drawn
 * under each stiff camera, counting hits (sr_draw_study.count_hits): each
 * pixel's color ends as the number of fan triangles covering it. On a
 * watertight grid every pixel inside the grid's picture is hit exactly once. */
#include <math.h>
#include <stdlib.h>

#include "stability_grid.h"

#define GRID_CELLS 64
#define GRID_SIDE (GRID_CELLS + 1) /* vertices per side */
#define OUTLINE_MARGIN_PX 1.0      /* pixels this close to the grid's outline may go either way */

/* Grid line k (0 … GRID_CELLS) as a coordinate in [-1, 1]. */
static double grid_line(int k, double inner)
{
    int from_centre = k - GRID_CELLS / 2, steps = abs(from_centre);
    if (inner <= 0.0)
        return (double)from_centre / (GRID_CELLS / 2);
    /* Line 1 from the centre at `inner`, the last at 1, geometric between. */
    double a = steps ? pow(inner, (double)(GRID_CELLS / 2 - steps) / (GRID_CELLS / 2 - 1)) : 0.0;
    return from_centre < 0 ? -a : a;
}

/* Two front-facing triangles per cell (clockwise seen from the eye). */
static void grid_indices(const sr_stability_case *c, uint32_t *idx)
{
    double n[3], to_eye[3];
    for (int i = 0; i < 3; i++)
        to_eye[i] = (double)c->camera.eye[i] - c->grid_centre[i];
    n[0] = (double)c->grid_u[1] * c->grid_v[2] - (double)c->grid_u[2] * c->grid_v[1];
    n[1] = (double)c->grid_u[2] * c->grid_v[0] - (double)c->grid_u[0] * c->grid_v[2];
    n[2] = (double)c->grid_u[0] * c->grid_v[1] - (double)c->grid_u[1] * c->grid_v[0];
    /* (p00, p10, p11) turns like u × v; it is front-facing if that normal points at the eye. */
    bool flip = n[0] * to_eye[0] + n[1] * to_eye[1] + n[2] * to_eye[2] < 0.0;
    for (uint32_t j = 0; j < GRID_CELLS; j++) {
        for (uint32_t i = 0; i < GRID_CELLS; i++) {
            uint32_t p00 = j * GRID_SIDE + i, p10 = p00 + 1, p01 = p00 + GRID_SIDE, p11 = p01 + 1;
            uint32_t cell[6] = { p00, p10, p11, p00, p11, p01 };
            if (flip) {
                cell[1] = p11, cell[2] = p10;
                cell[4] = p01, cell[5] = p11;
            }
            for (int k = 0; k < 6; k++)
                *idx++ = cell[k];
        }
    }
}

static bool grid_mesh(const sr_stability_case *c, double inner, sr_mesh *m, sr_error *err)
{
    if (!sr_mesh_alloc(m, GRID_SIDE * GRID_SIDE, 6 * GRID_CELLS * GRID_CELLS, false, false, false, err))
        return false;
    for (int j = 0; j < GRID_SIDE; j++) {
        for (int i = 0; i < GRID_SIDE; i++) {
            double a = grid_line(i, inner), b = grid_line(j, inner);
            for (int k = 0; k < 3; k++)
                m->positions[j * GRID_SIDE + i][k] =
                    (float)(c->grid_centre[k] + a * c->grid_u[k] + b * c->grid_v[k]);
        }
    }
    grid_indices(c, m->indices);
    return true;
}

/* Where the grid shows on screen, from the camera and the plane alone, in double. */
typedef struct grid_region {
    sr_stability_frame frame;
    double tan_x, tan_y, near, far;
    double centre[3], u[3], v[3];
} grid_region;

static double det3(const double a[3], const double b[3], const double c[3])
{
    return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
}

/* Does the ray through screen point (sx, sy) meet the grid between near and far? */
static bool sample_on_grid(const grid_region *r, double sx, double sy)
{
    double ndc_x = 2.0 * sx / SR_STABILITY_WIDTH - 1.0, ndc_y = 1.0 - 2.0 * sy / SR_STABILITY_HEIGHT;
    double dir[3], rhs[3], minus_dir[3];
    for (int i = 0; i < 3; i++) {
        /* forward has unit depth, so the ray parameter t is the view depth. */
        dir[i] = r->frame.forward[i] + ndc_x * r->tan_x * r->frame.right[i] + ndc_y * r->tan_y * r->frame.up[i];
        minus_dir[i] = -dir[i];
        rhs[i] = r->frame.eye[i] - r->centre[i];
    }
    /* centre + a·u + b·v = eye + t·dir, by Cramer's rule. */
    double d = det3(r->u, r->v, minus_dir);
    if (d == 0.0)
        return false;
    double a = det3(rhs, r->v, minus_dir) / d, b = det3(r->u, rhs, minus_dir) / d, t = det3(r->u, r->v, rhs) / d;
    return fabs(a) <= 1.0 && fabs(b) <= 1.0 && t >= r->near && t <= r->far;
}

/* Inside iff the 3×3 block of sample points 1 px apart around the centre is
 * on the grid: the visible grid is convex on screen, so the pixel is then at
 * least OUTLINE_MARGIN_PX from its outline (the grid's edges and its cuts by
 * the near and far planes). */
static bool pixel_inside(const grid_region *r, int x, int y)
{
    for (int dy = -1; dy <= 1; dy++)
        for (int dx = -1; dx <= 1; dx++)
            if (!sample_on_grid(r, x + 0.5 + dx * OUTLINE_MARGIN_PX, y + 0.5 + dy * OUTLINE_MARGIN_PX))
                return false;
    return true;
}

static grid_region region_of(const sr_stability_case *c)
{
    grid_region r = { .frame = sr_stability_frame_of(&c->camera), .near = c->camera.near, .far = c->camera.far };
    r.tan_y = tan(glm_rad(c->camera.fov_deg) * 0.5);
    r.tan_x = r.tan_y * SR_STABILITY_WIDTH / SR_STABILITY_HEIGHT;
    for (int i = 0; i < 3; i++) {
        r.centre[i] = c->grid_centre[i];
        r.u[i] = c->grid_u[i];
        r.v[i] = c->grid_v[i];
    }
    return r;
}

static void tally(const sr_stability_case *c, const uint32_t *counts, sr_stability_hits *out)
{
    grid_region r = region_of(c);
    for (int y = 0; y < SR_STABILITY_HEIGHT; y++) {
        for (int x = 0; x < SR_STABILITY_WIDTH; x++) {
            uint32_t hits = counts[y * SR_STABILITY_WIDTH + x];
            out->double_hits += hits >= 2;
            if (pixel_inside(&r, x, y)) {
                out->inside++;
                out->holes += hits == 0;
            }
        }
    }
}

/* The grid drawn counting hits into fb's color. */
static bool draw_counting(const sr_stability_case *c, const sr_mesh *grid, sr_clip_precision precision,
                          sr_framebuffer *fb, sr_stats *stats, sr_error *err)
{
    sr_draw_study study = { .clip_precision = precision, .count_hits = true };
    sr_draw_desc desc = { .mesh = grid, .study = &study };
    sr_camera_view(&c->camera, desc.view);
    sr_camera_projection(&c->camera, (float)SR_STABILITY_WIDTH / SR_STABILITY_HEIGHT, desc.projection);
    sr_framebuffer_clear(fb, 0);
    return sr_draw(fb, &desc, stats, err);
}

bool sr_stability_grid_hits(const sr_stability_case *c, bool graded, const sr_stability_clipper *clipper,
                            sr_stability_hits *out, sr_error *err)
{
    *out = (sr_stability_hits){ .measured = !graded || c->grid_inner > 0.0 };
    if (!out->measured)
        return true;
    sr_mesh grid = { 0 };
    sr_framebuffer counts = { 0 };
    bool ok = grid_mesh(c, graded ? c->grid_inner : 0.0, &grid, err) &&
              sr_framebuffer_create(&counts, SR_STABILITY_WIDTH, SR_STABILITY_HEIGHT, err) &&
              draw_counting(c, &grid, clipper->precision, &counts, &out->stats, err);
    if (ok)
        tally(c, counts.color, out);
    sr_framebuffer_destroy(&counts);
    sr_mesh_free(&grid);
    return ok;
}
