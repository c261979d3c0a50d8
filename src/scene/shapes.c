#include <math.h>

#include "shapes.h"
#include "core/error.h"

#define TWO_PI 6.283185307179586

/* Torus vertex (k, m) on a (segments + 1) × (sides + 1) grid: the seams are
 * duplicated so uvs run 0..1 without wrapping. */
static void torus_vertex(sr_mesh *mesh, uint32_t at, float major, float minor, double u, double v)
{
    double theta = TWO_PI * u, psi = TWO_PI * v;
    double ring = major + minor * cos(psi);
    float *p = mesh->positions[at], *n = mesh->normals[at];
    p[0] = (float)(ring * cos(theta));
    p[1] = (float)(minor * sin(psi));
    p[2] = (float)(ring * sin(theta));
    n[0] = (float)(cos(psi) * cos(theta));
    n[1] = (float)sin(psi);
    n[2] = (float)(cos(psi) * sin(theta));
    mesh->uvs[at][0] = (float)u;
    mesh->uvs[at][1] = (float)v;
}

/* Two triangles per grid cell, wound so (b − a) × (c − a) points along the
 * outward normal: clockwise seen from outside in a left-handed frame. */
static void torus_cell(uint32_t *idx, uint32_t row, uint32_t k, uint32_t m)
{
    uint32_t a = k * row + m, b = (k + 1) * row + m, c = (k + 1) * row + m + 1, d = k * row + m + 1;
    uint32_t quad[6] = { a, d, c, a, c, b };
    for (int i = 0; i < 6; i++)
        idx[i] = quad[i];
}

bool sr_shape_torus(sr_mesh *mesh, float major, float minor, uint32_t segments, uint32_t sides, sr_error *err)
{
    if (segments < 3 || sides < 3 || (uint64_t)segments * sides > UINT32_MAX / 8)
        return sr_error_set(err, "a torus needs 3 to ~500M segments x sides (got %u x %u)", segments, sides);
    uint32_t row = sides + 1;
    if (!sr_mesh_alloc(mesh, (segments + 1) * row, 6 * segments * sides, true, true, false, err))
        return false;
    for (uint32_t k = 0; k <= segments; k++)
        for (uint32_t m = 0; m <= sides; m++)
            torus_vertex(mesh, k * row + m, major, minor, (double)k / segments, (double)m / sides);
    for (uint32_t k = 0; k < segments; k++)
        for (uint32_t m = 0; m < sides; m++)
            torus_cell(&mesh->indices[6 * (k * sides + m)], row, k, m);
    sr_mesh_update_bounds(mesh);
    return true;
}

/* The next of a 64-bit linear congruential sequence (Knuth's MMIX
 * constants), as a double in [0, 1) from its top 53 bits. */
static double next_unit(uint64_t *state)
{
    *state = *state * 6364136223846793005u + 1442695040888963407u;
    return (double)(*state >> 11) * 0x1p-53;
}

bool sr_shape_torus_cloud(sr_mesh *mesh, float major, float minor, uint32_t count, sr_error *err)
{
    if (count == 0 || count > UINT32_MAX / 8)
        return sr_error_set(err, "bad point count %u", count);
    if (!sr_mesh_alloc(mesh, count, count, false, false, true, err))
        return false;
    uint64_t state = 1;
    for (uint32_t i = 0; i < count; i++) {
        double u = next_unit(&state), v = next_unit(&state);
        double theta = TWO_PI * u, psi = TWO_PI * v, ring = major + minor * cos(psi);
        float *p = mesh->positions[i], *c = mesh->colors[i];
        p[0] = (float)(ring * cos(theta));
        p[1] = (float)(minor * sin(psi));
        p[2] = (float)(ring * sin(theta));
        c[0] = (float)u;
        c[1] = (float)v;
        c[2] = (float)(0.5 + 0.5 * sin(psi));
        mesh->indices[i] = i;
    }
    mesh->topology = SR_POINT_LIST;
    sr_mesh_update_bounds(mesh);
    return true;
}

void sr_shape_torus_grid(uint64_t triangles, uint32_t *segments, uint32_t *sides)
{
    double s = sqrt((double)triangles); /* 2 · s · s/2 = triangles */
    *segments = s < 3.0 ? 3u : (uint32_t)lround(s);
    *sides = *segments / 2 < 3 ? 3u : *segments / 2;
}

bool sr_shape_quads(sr_mesh *mesh, uint32_t count, float size, float first_z, float step, sr_error *err)
{
    if (count == 0 || count > UINT32_MAX / 8)
        return sr_error_set(err, "bad quad count %u", count);
    if (!sr_mesh_alloc(mesh, 4 * count, 6 * count, true, true, false, err))
        return false;
    static const float corner[4][2] = { { -1, -1 }, { -1, 1 }, { 1, 1 }, { 1, -1 } };
    for (uint32_t q = 0; q < count; q++) {
        for (uint32_t c = 0; c < 4; c++) {
            uint32_t at = 4 * q + c;
            glm_vec3_copy((vec3){ 0.5f * size * corner[c][0], 0.5f * size * corner[c][1], first_z + step * q },
                          mesh->positions[at]);
            glm_vec3_copy((vec3){ 0.0f, 0.0f, -1.0f }, mesh->normals[at]);
            mesh->uvs[at][0] = 0.5f + 0.5f * corner[c][0];
            mesh->uvs[at][1] = 0.5f + 0.5f * corner[c][1];
        }
        /* (-1,-1) → (-1,1) → (1,1): up then right, clockwise seen from -z. */
        uint32_t base = 4 * q, tri[6] = { base, base + 1, base + 2, base, base + 2, base + 3 };
        for (int i = 0; i < 6; i++)
            mesh->indices[6 * q + i] = tri[i];
    }
    sr_mesh_update_bounds(mesh);
    return true;
}
