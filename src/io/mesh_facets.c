/* A mesh shaded by its facets (mesh_facets.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "mesh_facets.h"
#include "softrast/files.h"

/* The triangle's outward unit normal from its corners, in double; zero for
 * a triangle without area. */
static void facet_normal(const float *a, const float *b, const float *c, vec3 out)
{
    const double e1[3] = { (double)b[0] - a[0], (double)b[1] - a[1], (double)b[2] - a[2] };
    const double e2[3] = { (double)c[0] - a[0], (double)c[1] - a[1], (double)c[2] - a[2] };
    const double n[3] = { e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                          e1[0] * e2[1] - e1[1] * e2[0] };
    const double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; k++)
        out[k] = len > 0.0 && isfinite(len) ? (float)(n[k] / len) : 0.0f;
}

bool sr_mesh_facet(sr_mesh *mesh, sr_error *err)
{
    const uint32_t n = mesh->index_count - mesh->index_count % 3;
    if (mesh->topology != SR_TRIANGLE_LIST || n == 0)
        return true;
    if (n > SR_MAX_MESH_VERTICES)
        return sr_error_set(err, "%u facet corners exceed the limit of %u vertices", n, SR_MAX_MESH_VERTICES);
    sr_mesh flat;
    if (!sr_mesh_alloc(&flat, n, n, true, mesh->uvs != NULL, mesh->colors != NULL, err))
        return false;
    for (uint32_t t = 0; t < n; t += 3) {
        const uint32_t *old = &mesh->indices[t];
        for (uint32_t c = 0; c < 3; c++) {
            /* a corner that repeats an earlier one keeps the triangle degenerate */
            const uint32_t v = t + (old[c] == old[0] ? 0 : old[c] == old[1] ? 1 : c);
            flat.indices[t + c] = v;
            glm_vec3_copy(mesh->positions[old[c]], flat.positions[t + c]);
            if (flat.uvs)
                glm_vec2_copy(mesh->uvs[old[c]], flat.uvs[t + c]);
            if (flat.colors)
                glm_vec3_copy(mesh->colors[old[c]], flat.colors[t + c]);
        }
        vec3 normal;
        facet_normal(flat.positions[t], flat.positions[t + 1], flat.positions[t + 2], normal);
        for (uint32_t c = 0; c < 3; c++)
            glm_vec3_copy(normal, flat.normals[t + c]);
    }
    free(mesh->positions);
    free(mesh->normals);
    free(mesh->uvs);
    free(mesh->colors);
    free(mesh->indices);
    mesh->vertex_count = n;
    mesh->index_count = n;
    mesh->positions = flat.positions;
    mesh->normals = flat.normals;
    mesh->uvs = flat.uvs;
    mesh->colors = flat.colors;
    mesh->indices = flat.indices;
    return true;
}
