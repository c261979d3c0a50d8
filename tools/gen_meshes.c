/* tools/gen_meshes.c — the shape emitters of gen-assets.
 *
 * Every shape is emitted through the OBJ writer (gen_obj.c) in its own
 * coordinates; the writer's placement moves it and picks its uv range.
 * Faces are counter-clockwise seen from the side their normals point to.
 * Shapes around the y axis use p(theta) = (cos theta, ., -sin theta), for
 * which increasing theta runs counter-clockwise seen from +y; every quad is
 * listed (theta0, theta1) bottom then top, which is counter-clockwise seen
 * from outside.
 */
#include "gen_assets.h"

#include <math.h>

#define EDGE_EPSILON 1e-4f /* a length this close to a whole tile count is one */
#define TWO_PI 6.283185307179586

/* How many cells of at most `tile` cover `length`. */
static int cells_along(float length, float tile)
{
    int n = (int)ceilf(length / tile - EDGE_EPSILON);
    return n < 1 ? 1 : n;
}

/* origin + eu*s/ns + ev*t/nt; multiplying before dividing keeps whole
 * numbers whole, so neighbouring grids print their shared edge alike. */
static void grid_point(const grid_quad *q, int s, int ns, int t, int nt,
                       vec3 out)
{
    for (int k = 0; k < 3; k++)
        out[k] = q->origin[k] + q->eu[k] * (float)s / (float)ns
                 + q->ev[k] * (float)t / (float)nt;
}

void emit_grid_quad(obj_writer *w, const grid_quad *q)
{
    vec3 n, eu, ev;
    glm_vec3_copy((float *)q->eu, eu);
    glm_vec3_copy((float *)q->ev, ev);
    glm_vec3_cross(eu, ev, n);
    glm_vec3_normalize(n);
    int nu = cells_along(glm_vec3_norm(eu), q->tile);
    int nv = cells_along(glm_vec3_norm(ev), q->tile);
    float su = glm_vec3_norm(eu) / (float)nu / q->tile; /* a cell's uv extent */
    float sv = glm_vec3_norm(ev) / (float)nv / q->tile;
    for (int j = 0; j < nv; j++) {
        for (int i = 0; i < nu; i++) {
            vec3 p00, p10, p11, p01;
            grid_point(q, i, nu, j, nv, p00);
            grid_point(q, i + 1, nu, j, nv, p10);
            grid_point(q, i + 1, nu, j + 1, nv, p11);
            grid_point(q, i, nu, j + 1, nv, p01);
            obj_quad(w, obj_corner_at(w, p00, n, 0.0f, 0.0f),
                     obj_corner_at(w, p10, n, su, 0.0f),
                     obj_corner_at(w, p11, n, su, sv),
                     obj_corner_at(w, p01, n, 0.0f, sv));
        }
    }
}

/* Side faces keep the texture upright (ev = +y); eu = ev x n makes
 * eu x ev = n, so the face is counter-clockwise seen from where n points. */
void emit_box_face(obj_writer *w, vec3 lo, vec3 hi, int axis,
                          float sign, float tile, bool inward)
{
    vec3 n = GLM_VEC3_ZERO_INIT, ev = GLM_VEC3_ZERO_INIT, eu, mid, size;
    n[axis] = inward ? -sign : sign;
    if (axis == 1)
        ev[2] = -sign; /* top and bottom: texture up runs along -z or +z */
    else
        ev[1] = 1.0f;
    glm_vec3_cross(ev, n, eu);
    glm_vec3_sub(hi, lo, size);
    glm_vec3_center(lo, hi, mid);
    float len_u = fabsf(glm_vec3_dot(eu, size));
    float len_v = fabsf(glm_vec3_dot(ev, size));
    grid_quad q = {.tile = tile};
    for (int k = 0; k < 3; k++) {
        float face = k == axis ? (sign > 0 ? hi[k] : lo[k]) : mid[k];
        q.origin[k] = face - 0.5f * (eu[k] * len_u + ev[k] * len_v);
        q.eu[k] = eu[k] * len_u;
        q.ev[k] = ev[k] * len_v;
    }
    emit_grid_quad(w, &q);
}

void emit_box(obj_writer *w, vec3 lo, vec3 hi, float tile, bool inward)
{
    static const float SIDES[2] = {-1.0f, 1.0f};
    for (int axis = 0; axis < 3; axis++)
        for (int s = 0; s < 2; s++)
            emit_box_face(w, lo, hi, axis, SIDES[s], tile, inward);
}

/* Direction at longitude `seg` (of `segments`) and latitude `ring` (of
 * `rings`, 0 at the north pole). The seam reuses segment 0's angle exactly. */
static void sphere_dir(int seg, int segments, int ring, int rings, vec3 out)
{
    double theta = TWO_PI * (seg % segments) / segments;
    double phi = TWO_PI * 0.5 * ring / rings;
    out[0] = (float)(sin(phi) * cos(theta));
    out[1] = (float)cos(phi);
    out[2] = (float)(-sin(phi) * sin(theta));
}

static obj_corner sphere_corner(obj_writer *w, float radius, int seg,
                                float u_seg, int segments, int ring, int rings)
{
    vec3 n, p;
    sphere_dir(seg, segments, ring, rings, n);
    glm_vec3_scale(n, radius, p);
    return obj_corner_at(w, p, n, u_seg / (float)segments,
                         1.0f - (float)ring / (float)rings);
}

/* Pole caps are single triangles whose pole corner takes the u of the
 * segment's middle, so no zero-area triangles are written. */
void emit_uv_sphere(obj_writer *w, float radius, int segments, int rings)
{
    for (int k = 0; k < segments; k++) {
        float mid = (float)k + 0.5f;
        obj_tri(w, sphere_corner(w, radius, k, (float)k, segments, 1, rings),
                sphere_corner(w, radius, k + 1, (float)k + 1, segments, 1, rings),
                sphere_corner(w, radius, k, mid, segments, 0, rings));
        for (int j = 1; j + 1 < rings; j++)
            obj_quad(w, sphere_corner(w, radius, k, (float)k, segments, j + 1, rings),
                     sphere_corner(w, radius, k + 1, (float)k + 1, segments, j + 1, rings),
                     sphere_corner(w, radius, k + 1, (float)k + 1, segments, j, rings),
                     sphere_corner(w, radius, k, (float)k, segments, j, rings));
        obj_tri(w, sphere_corner(w, radius, k, mid, segments, rings, rings),
                sphere_corner(w, radius, k + 1, (float)k + 1, segments, rings - 1, rings),
                sphere_corner(w, radius, k, (float)k, segments, rings - 1, rings));
    }
}

/* Point seg (around the axis) / side (around the tube, 0 on the outer
 * equator, rising first) of a torus. */
static obj_corner torus_corner(obj_writer *w, float major, float minor,
                               int seg, int segments, int side, int sides)
{
    double theta = TWO_PI * (seg % segments) / segments;
    double psi = TWO_PI * (side % sides) / sides;
    vec3 n = {(float)(cos(psi) * cos(theta)), (float)sin(psi),
              (float)(-cos(psi) * sin(theta))};
    double ring = major + minor * cos(psi);
    vec3 p = {(float)(ring * cos(theta)), (float)(minor * sin(psi)),
              (float)(-ring * sin(theta))};
    return obj_corner_at(w, p, n, (float)seg / (float)segments,
                         (float)side / (float)sides);
}

void emit_torus(obj_writer *w, float major, float minor, int segments,
                int sides)
{
    for (int k = 0; k < segments; k++)
        for (int m = 0; m < sides; m++)
            obj_quad(w, torus_corner(w, major, minor, k, segments, m, sides),
                     torus_corner(w, major, minor, k + 1, segments, m, sides),
                     torus_corner(w, major, minor, k + 1, segments, m + 1, sides),
                     torus_corner(w, major, minor, k, segments, m + 1, sides));
}

static void circle_point(float radius, int seg, int segments, float y,
                         vec3 out)
{
    double theta = TWO_PI * (seg % segments) / segments;
    out[0] = (float)(radius * cos(theta));
    out[1] = y;
    out[2] = (float)(-radius * sin(theta));
}

/* A cap is a fan around its centre, uv a view of the disc from outside
 * (v runs along -z on top, +z below, so neither cap is mirrored). */
static void emit_cylinder_cap(obj_writer *w, float radius, float y,
                              int segments, bool top)
{
    vec3 centre = {0.0f, y, 0.0f}, n = {0.0f, top ? 1.0f : -1.0f, 0.0f};
    float diameter = 2.0f * radius;
    float v_per_z = (top ? -1.0f : 1.0f) / diameter;
    obj_corner c = obj_corner_at(w, centre, n, 0.5f, 0.5f);
    for (int k = 0; k < segments; k++) {
        vec3 a, b;
        circle_point(radius, k, segments, y, a);
        circle_point(radius, k + 1, segments, y, b);
        obj_corner ca = obj_corner_at(w, a, n, 0.5f + a[0] / diameter,
                                      0.5f + a[2] * v_per_z);
        obj_corner cb = obj_corner_at(w, b, n, 0.5f + b[0] / diameter,
                                      0.5f + b[2] * v_per_z);
        if (top)
            obj_tri(w, c, ca, cb);
        else
            obj_tri(w, c, cb, ca);
    }
}

void emit_cylinder(obj_writer *w, float radius, float height, int segments,
                   float tile)
{
    int rows = cells_along(height, tile);
    float sv = height / (float)rows / tile; /* a row's uv extent, as in a grid */
    for (int k = 0; k < segments; k++) {
        float u0 = (float)k / (float)segments, u1 = (float)(k + 1) / (float)segments;
        vec3 n0, n1;
        circle_point(1.0f, k, segments, 0.0f, n0);
        circle_point(1.0f, k + 1, segments, 0.0f, n1);
        for (int j = 0; j < rows; j++) {
            float y0 = height * (float)j / (float)rows;
            float y1 = height * (float)(j + 1) / (float)rows;
            vec3 p00, p10, p11, p01;
            circle_point(radius, k, segments, y0, p00);
            circle_point(radius, k + 1, segments, y0, p10);
            circle_point(radius, k + 1, segments, y1, p11);
            circle_point(radius, k, segments, y1, p01);
            obj_quad(w, obj_corner_at(w, p00, n0, u0, 0.0f),
                     obj_corner_at(w, p10, n1, u1, 0.0f),
                     obj_corner_at(w, p11, n1, u1, sv),
                     obj_corner_at(w, p01, n0, u0, sv));
        }
    }
    emit_cylinder_cap(w, radius, 0.0f, segments, false);
    emit_cylinder_cap(w, radius, height, segments, true);
}
