/* The shading context of a triangle of a mesh with materials: its part's
 * material's (10_shade.h; draw/materials.c makes the contexts). */
#include "10_shade.h"

/* The last part found, per thread: a thread draws its triangles in
 * increasing order mostly, so the next is in the same part or the one
 * after; else a binary search. */
static _Thread_local uint32_t last_part;

const sr_shade_context *sr_shade_material_of(const sr_shade_context *c, uint32_t id)
{
    const sr_mesh_part *parts = c->parts;
    uint32_t n = c->part_count, i = last_part;
    if (i < n && id - parts[i].first_triangle < parts[i].triangle_count)
        return &c->materials[parts[i].material];
    if (i + 1 < n && id - parts[i + 1].first_triangle < parts[i + 1].triangle_count) {
        last_part = i + 1;
        return &c->materials[parts[i + 1].material];
    }
    uint32_t lo = 0, hi = n; /* the first part starting past id is at hi */
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo) / 2;
        if (parts[mid].first_triangle <= id)
            lo = mid + 1;
        else
            hi = mid;
    }
    if (lo > 0 && id - parts[lo - 1].first_triangle < parts[lo - 1].triangle_count) {
        last_part = lo - 1;
        return &c->materials[parts[lo - 1].material];
    }
    return &c->materials[0]; /* in no part */
}
