#include <string.h>

#include "assemble.h"

bool sr_assemble_triangle(const sr_mesh *mesh, uint32_t k, uint32_t out[3])
{
    if (mesh->topology == SR_TRIANGLE_STRIP) {
        uint32_t odd = k & 1;
        out[0] = mesh->indices[k];
        out[1] = mesh->indices[k + 1 + odd];
        out[2] = mesh->indices[k + 2 - odd];
    } else {
        memcpy(out, &mesh->indices[3 * (size_t)k], 3 * sizeof(uint32_t));
    }
    return out[0] != out[1] && out[1] != out[2] && out[0] != out[2];
}

bool sr_assemble_indices_valid_in(const sr_mesh *mesh, uint32_t first, uint32_t end)
{
    for (uint32_t i = first; i < end; i++)
        if (mesh->indices[i] >= mesh->vertex_count)
            return false;
    return true;
}

bool sr_assemble_indices_valid(const sr_mesh *mesh)
{
    return sr_assemble_indices_valid_in(mesh, 0, mesh->index_count);
}
