#include <stdlib.h>
#include <string.h>

#include "draw_state.h"

/* aligned_alloc keeps the per-thread parts on their own cache lines. */
sr_workspace *sr_workspace_create(void)
{
    size_t size = (sizeof(sr_workspace) + SR_CACHE_LINE - 1) / SR_CACHE_LINE * SR_CACHE_LINE;
    sr_workspace *ws = aligned_alloc(SR_CACHE_LINE, size);
    if (ws)
        memset(ws, 0, size);
    return ws;
}

uint64_t sr_workspace_simd_draws(const sr_workspace *ws)
{
    uint64_t draws = 0;
    for (int t = 0; t < SR_MAX_THREADS; t++)
        draws += ws->threads[t].simd_draws;
    return draws;
}

static void thread_work_free(sr_thread_work *w)
{
    sr_array_free(&w->clip_verts);
    sr_array_free(&w->setups);
    for (size_t i = 0; i < w->bin_count; i++)
        sr_array_free(&w->bins[i].entries);
    free(w->bins);
    for (size_t i = 0; i < w->fragment_bin_count; i++)
        sr_array_free(&w->fragment_bins[i]);
    free(w->fragment_bins);
    *w = (sr_thread_work){ 0 };
}

void sr_workspace_destroy(sr_workspace *ws)
{
    if (!ws)
        return;
    sr_pool_stop(&ws->pool);
    sr_array_free(&ws->outcodes);
    sr_array_free(&ws->snapped_points);
    sr_array_free(&ws->double_wanted);
    sr_array_free(&ws->band_slots);
    sr_array_free(&ws->chunk_kept);
    sr_array_free(&ws->screen);
    sr_array_free(&ws->tile_order);
    sr_array_free(&ws->material_shades);
    for (int t = 0; t < SR_MAX_THREADS; t++)
        thread_work_free(&ws->threads[t]);
    free(ws);
}
