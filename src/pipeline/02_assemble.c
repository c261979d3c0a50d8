#include <string.h>

#include "02_assemble.h"

/* Indices checked at once: 4-lane compares ORed, one branch per block
 * instead of one per index, where the compiler has vector types
 * (docs/performance.md, "The vertex phase"). */
#define INDEX_BLOCK 64
/* The blocks ahead whose indices the check prefetches: further than the
 * loops over slots do (SR_PREFETCH_SLOT_INDICES), as it runs through them
 * faster. */
#define AHEAD_BLOCKS 16

static bool each_valid(const uint32_t *indices, uint32_t count, uint32_t vertex_count)
{
    for (uint32_t k = 0; k < count; k++)
        if (indices[k] >= vertex_count)
            return false;
    return true;
}

static bool block_valid(const uint32_t *indices, uint32_t vertex_count)
{
#if defined(__GNUC__)
    typedef uint32_t four_indices __attribute__((vector_size(16)));
    four_indices limit = { vertex_count, vertex_count, vertex_count, vertex_count }, past = { 0 };
#pragma GCC unroll 16
    for (int k = 0; k < INDEX_BLOCK; k += 4) {
        four_indices v;
        memcpy(&v, indices + k, sizeof v);
        past |= (four_indices)(v >= limit);
    }
    return (past[0] | past[1] | past[2] | past[3]) == 0;
#else
    return each_valid(indices, INDEX_BLOCK, vertex_count);
#endif
}

bool sr_assemble_indices_valid_in(const sr_mesh *mesh, uint32_t first, uint32_t end)
{
    if (first >= end)
        return true;
    uint32_t i = first;
    for (; end - i >= INDEX_BLOCK; i += INDEX_BLOCK) {
        /* The four lines of the block AHEAD_BLOCKS on, or of this one. */
        const uint32_t *ahead =
            mesh->indices + (end - i > AHEAD_BLOCKS * INDEX_BLOCK ? i + AHEAD_BLOCKS * INDEX_BLOCK : i);
        for (int line = 0; line < INDEX_BLOCK; line += 16)
            __builtin_prefetch(ahead + line);
        if (!block_valid(mesh->indices + i, mesh->vertex_count))
            return false;
    }
    return each_valid(mesh->indices + i, end - i, mesh->vertex_count);
}

bool sr_assemble_indices_valid(const sr_mesh *mesh)
{
    return sr_assemble_indices_valid_in(mesh, 0, mesh->index_count);
}
