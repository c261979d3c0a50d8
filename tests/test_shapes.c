/* The generated shapes: closed, and wound so outward faces are front faces. */
#include <criterion/criterion.h>

#include "softrast_private.h"

/* The outward direction of a torus around +y of major radius `major`, at
 * point p: away from the nearest point of its core circle. */
static void torus_outward(const float p[3], float major, vec3 out)
{
    float ring = sqrtf(p[0] * p[0] + p[2] * p[2]);
    glm_vec3_copy((vec3){ p[0] - major * p[0] / ring, p[1], p[2] - major * p[2] / ring }, out);
}

/* (b − a) × (c − a) must point along the outward direction at the
 * triangle's centroid, which comes from the shape's geometry (the torus's
 * core circle of radius `major`, or the fixed `facing`), not from the
 * generator's normals: clockwise seen from outside, left-handed. */
static void assert_outward(const sr_mesh *m, float major, const float *facing)
{
    for (uint32_t t = 0; t < m->index_count; t += 3) {
        const uint32_t *i = &m->indices[t];
        vec3 e1, e2, n, centroid = { 0 }, out;
        glm_vec3_sub(m->positions[i[1]], m->positions[i[0]], e1);
        glm_vec3_sub(m->positions[i[2]], m->positions[i[0]], e2);
        glm_vec3_cross(e1, e2, n);
        for (int k = 0; k < 3; k++)
            glm_vec3_muladds(m->positions[i[k]], 1.0f / 3.0f, centroid);
        if (facing)
            glm_vec3_copy((float *)facing, out);
        else
            torus_outward(centroid, major, out);
        cr_assert_gt(glm_vec3_dot(n, out), 0.0f, "triangle %u faces inward", t / 3);
        for (int k = 0; k < 3; k++) { /* and the generator's normals agree */
            if (!facing)
                torus_outward(m->positions[i[k]], major, out);
            cr_assert_gt(glm_vec3_dot(m->normals[i[k]], out), 0.0f, "triangle %u: vertex %u's normal points inward",
                         t / 3, i[k]);
        }
    }
}

/* Every undirected edge of a closed mesh is used by exactly two triangles,
 * once in each direction; seams count by position. */
static void assert_closed(const sr_mesh *m)
{
    uint32_t tris = m->index_count / 3;
    for (uint32_t t = 0; t < tris; t++) {
        for (int e = 0; e < 3; e++) {
            const float *a = m->positions[m->indices[3 * t + e]], *b = m->positions[m->indices[3 * t + (e + 1) % 3]];
            int reverse = 0, same = 0;
            for (uint32_t u = 0; u < tris; u++) {
                for (int f = 0; f < 3; f++) {
                    const float *c = m->positions[m->indices[3 * u + f]];
                    const float *d = m->positions[m->indices[3 * u + (f + 1) % 3]];
                    reverse += glm_vec3_eqv_eps((float *)a, (float *)d) && glm_vec3_eqv_eps((float *)b, (float *)c);
                    same += glm_vec3_eqv_eps((float *)a, (float *)c) && glm_vec3_eqv_eps((float *)b, (float *)d);
                }
            }
            cr_assert_eq(reverse, 1, "edge %d of triangle %u has %d opposite uses", e, t, reverse);
            cr_assert_eq(same, 1, "edge %d of triangle %u is used %d times the same way", e, t, same);
        }
    }
}

Test(shapes, torus_is_closed_and_faces_outward)
{
    sr_mesh m;
    sr_error err;
    cr_assert(sr_shape_torus(&m, 1.0f, 0.35f, 12, 6, &err), "%s", err.message);
    cr_assert_eq(m.index_count, 3u * 2 * 12 * 6);
    assert_outward(&m, 1.0f, NULL);
    assert_closed(&m);
    sr_mesh_free(&m);
}

Test(shapes, torus_grid_gives_about_the_asked_triangles)
{
    uint32_t seg, sides;
    sr_shape_torus_grid(1000000, &seg, &sides);
    uint64_t tris = 2ull * seg * sides;
    cr_assert(tris >= 990000 && tris <= 1010000, "%llu", (unsigned long long)tris);
}

Test(shapes, quads_face_a_camera_at_minus_z)
{
    sr_mesh m;
    sr_error err;
    cr_assert(sr_shape_quads(&m, 3, 2.0f, 1.0f, 0.5f, &err), "%s", err.message);
    assert_outward(&m, 0.0f, (const float[3]){ 0.0f, 0.0f, -1.0f });
    cr_assert_float_eq(m.positions[8][2], 2.0f, 1e-6f);
    sr_mesh_free(&m);
}
