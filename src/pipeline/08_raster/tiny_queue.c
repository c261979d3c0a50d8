#include "simd_select.h"
#include "tiny_queue.h"

/* The tiny queue (tiny_queue.h): one per thread, since
 * a thread draws its triangles in order; it holds the pixels of one
 * framebuffer, shading context and mode at a time, whose shader it keeps
 * until sr_tiny_queue_flush: a later draw's context may lie where an earlier
 * one's did. */
typedef struct tiny_queue_state {
    sr_tiny_queue q;
    sr_framebuffer *fb; /* NULL: no context, the shader not looked up */
    const sr_shade_context *shade;
    sr_shade mode;
    sr_tiny_shader shader; /* for fb, shade and mode; NULL: none, the tiny loop draws */
    uint64_t fragments, draws; /* passed since the last flush: pixels, triangles with one at least */
    uint32_t id[SR_TINY_QUEUE_TRIANGLES]; /* each queued triangle's id, by its number as queued */
} tiny_queue_state;

static _Thread_local tiny_queue_state tiny_pending;

/* Queued triangle `from`'s interpolants as triangle `to`'s (to < from),
 * of a layout of `varyings` (the context's: every queued triangle's
 * set-up has that many). */
static void renumber_triangle(sr_tiny_queue *q, int varyings, int from, int to)
{
    for (int r = SR_TINY_IW0; r <= SR_TINY_DIW2; r++)
        q->param[r][to] = q->param[r][from];
    for (int k = 0; k < varyings; k++) {
        q->param[SR_TINY_VAR0 + k][to] = q->param[SR_TINY_VAR0 + k][from];
        q->param[SR_TINY_DVAR1 + k][to] = q->param[SR_TINY_DVAR1 + k][from];
        q->param[SR_TINY_DVAR2 + k][to] = q->param[SR_TINY_DVAR2 + k][from];
    }
}

/* The queued pixels' depth tests and writes (and with_ids, their ids'), in
 * the queue's order, and the queue kept to the pixels that passed, their triangles numbered again
 * without those left with none: the shaders take a group of lanes to span
 * at most SR_SIMD_MAX_LANES triangles, each with a pixel (tiny_queue.h). Up
 * to the first pixel that fails, nothing moves. */
static SR_ALWAYS_INLINE void test_depths(tiny_queue_state *t, bool greater, bool with_ids)
{
    sr_tiny_queue *q = &t->q;
    float *depth = t->fb->depth;
    uint32_t *ids = t->fb->ids;
    int p = 0;
    for (; p < q->pixels && sr_depth_passes(q->z[p], depth[q->at[p]], greater); p++) {
        depth[q->at[p]] = q->z[p];
        if (with_ids)
            ids[q->at[p]] = t->id[q->triangle[p]] + 1u;
    }
    int kept = p, last = p > 0 ? q->triangle[p - 1] : -1, renumbered = last;
    for (; p < q->pixels; p++) {
        if (!sr_depth_passes(q->z[p], depth[q->at[p]], greater))
            continue;
        depth[q->at[p]] = q->z[p];
        if (with_ids) /* t->id is by the numbers as queued, which renumbering leaves */
            ids[q->at[p]] = t->id[q->triangle[p]] + 1u;
        if (q->triangle[p] != last) {
            last = q->triangle[p];
            renumber_triangle(q, t->shade->layout.count, last, ++renumbered);
        }
        q->l1[kept] = q->l1[p];
        q->l2[kept] = q->l2[p];
        q->at[kept] = q->at[p];
        q->triangle[kept] = renumbered;
        kept++;
    }
    q->pixels = kept;
    q->triangles = renumbered + 1;
    t->fragments += (uint64_t)kept;
    t->draws += (uint64_t)q->triangles;
}

/* Tests and colors the queued pixels; the context stays. */
static void tiny_queue_drain(tiny_queue_state *t)
{
    sr_tiny_queue *q = &t->q;
    if (q->pixels == 0)
        return;
    bool greater = t->fb->reversed_z;
    if (t->fb->ids)
        greater ? test_depths(t, true, true) : test_depths(t, false, true);
    else
        greater ? test_depths(t, true, false) : test_depths(t, false, false);
    if (q->pixels > 0) {
        for (int l = q->pixels; l < q->pixels + SR_SIMD_MAX_LANES; l++) {
            q->l1[l] = q->l2[l] = 0.0f;
            q->triangle[l] = q->triangle[q->pixels - 1];
        }
        t->shader(q, t->shade, t->fb);
    }
    q->pixels = q->triangles = 0;
}

void sr_tiny_queue_drain(void)
{
    tiny_queue_drain(&tiny_pending);
}

void sr_tiny_queue_flush(uint64_t *fragments, uint64_t *draws)
{
    tiny_queue_state *t = &tiny_pending;
    tiny_queue_drain(t);
    t->fb = NULL;
    *fragments += t->fragments;
    *draws += t->draws;
    t->fragments = t->draws = 0;
}

/* The queue for a tiny triangle of fb, shade and mode (SR_INTERP_PERSPECTIVE),
 * flushed to make room for one more, or NULL where the tiny loop draws
 * it (no shader: the scalar loop was asked for, or the layout is not one
 * the kernels know). */
static sr_tiny_queue *tiny_queue_for(sr_framebuffer *fb, const sr_shade_context *shade, sr_shade mode)
{
    tiny_queue_state *t = &tiny_pending;
    if (t->fb != fb || t->shade != shade || t->mode != mode) {
        tiny_queue_drain(t);
        t->fb = fb;
        t->shade = shade;
        t->mode = mode;
        t->shader = sr_tiny_shader_for(shade, mode);
    }
    if (!t->shader)
        return NULL;
    if (t->q.pixels > SR_TINY_QUEUE_PIXELS - SR_TINY_SIDE * SR_TINY_SIDE || t->q.triangles == SR_TINY_QUEUE_TRIANGLES)
        tiny_queue_drain(t);
    return &t->q;
}

/* The tiny loop's covered pixels queued with their depths, λ1 and λ2 (the
 * loop's values), and the triangle's interpolants and id. */
static void push(const sr_tri_setup *s, const sr_framebuffer *fb, uint32_t id, tiny_queue_state *state)
{
    sr_tiny_queue *q = &state->q;
    int p = q->pixels, t = q->triangles;
    for (uint64_t m = s->tiny; m; m &= m - 1) {
        sr_tiny_pixel px = sr_tiny_pixel_of(s, fb, __builtin_ctzll(m));
        q->z[p] = sr_depth_at(s, px.z_row, px.k);
        q->l1[p] = (float)sr_edge_at(&s->e[1], px.px, px.py) * s->inv_area2;
        q->l2[p] = (float)sr_edge_at(&s->e[2], px.px, px.py) * s->inv_area2;
        q->at[p] = px.at;
        q->triangle[p] = t;
        p++;
    }
    if (p == q->pixels)
        return;
    state->id[t] = id;
    q->param[SR_TINY_IW0][t] = s->iw0;
    q->param[SR_TINY_DIW1][t] = s->diw1;
    q->param[SR_TINY_DIW2][t] = s->diw2;
    for (int k = 0; k < s->varyings; k++) {
        q->param[SR_TINY_VAR0 + k][t] = s->var0[k];
        q->param[SR_TINY_DVAR1 + k][t] = s->dvar1[k];
        q->param[SR_TINY_DVAR2 + k][t] = s->dvar2[k];
    }
    q->pixels = p;
    q->triangles = t + 1;
}

bool sr_tiny_queue_push(const sr_tri_setup *s, sr_framebuffer *fb, sr_shade mode, const sr_shade_context *shade,
                        uint32_t triangle_id)
{
    sr_tiny_queue *q = tiny_queue_for(fb, shade, mode);
    if (q)
        push(s, fb, triangle_id, &tiny_pending);
    return q != NULL;
}
