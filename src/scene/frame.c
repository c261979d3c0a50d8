/* frame.c — one timed frame (frame.h). */
#include "frame.h"

#include "core/clock.h"
#include "softrast/softrast.h"

static bool draw_timed(sr_framebuffer *fb, const sr_draw_desc *desc, bool layers, sr_stats *stats, double *ms,
                       sr_error *err)
{
    double start = sr_now_ms();
    if (stats)
        *stats = (sr_stats){ 0 };
    sr_draw_desc clearing = *desc;
    clearing.clear = true; /* to color 0, inside the draw (each tile by its thread) */
    bool ok = layers ? sr_draw_layered(fb, &clearing, stats, err) : sr_draw(fb, &clearing, stats, err);
    *ms = sr_now_ms() - start;
    return ok;
}

bool sr_frame_draw_timed(sr_framebuffer *fb, const sr_draw_desc *desc, sr_stats *stats, double *ms, sr_error *err)
{
    return draw_timed(fb, desc, false, stats, ms, err);
}

bool sr_frame_draw_layers_timed(sr_framebuffer *fb, const sr_draw_desc *desc, sr_stats *stats, double *ms,
                                sr_error *err)
{
    return draw_timed(fb, desc, true, stats, ms, err);
}
