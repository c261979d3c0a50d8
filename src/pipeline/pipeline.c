#include <stdlib.h>
#include <string.h>

#include "softrast/assemble.h"
#include "softrast/clip.h"
#include "softrast/cull.h"
#include "softrast/pipeline.h"
#include "softrast/raster.h"
#include "softrast/vertex.h"
#include "softrast/viewport.h"

/* What one draw call carries from triangle to triangle. */
typedef struct draw_state {
    sr_framebuffer *fb;
    const sr_draw_desc *desc;
    sr_shade_context shade;
    sr_raster_rect rect;
    const sr_vertex_out *verts;
    const unsigned char *outcodes;
    sr_stats *stats;
} draw_state;

static bool matrix_is_zero(const mat4 m)
{
    static const mat4 zero;
    return memcmp(m, zero, sizeof zero) == 0;
}

static void matrix_or_identity(const mat4 m, mat4 out)
{
    if (matrix_is_zero(m))
        glm_mat4_identity(out);
    else
        glm_mat4_copy((vec4 *)m, out);
}

static bool check_inputs(const sr_framebuffer *fb, const sr_draw_desc *d, const sr_varying_layout *l,
                         sr_error *err)
{
    if (!fb || !fb->color || !fb->depth || fb->width < 1 || fb->height < 1 ||
        fb->width > SR_MAX_FRAMEBUFFER_SIDE || fb->height > SR_MAX_FRAMEBUFFER_SIDE)
        return sr_error_set(err, "draw into a framebuffer without buffers or of a bad size");
    if (!d->mesh)
        return sr_error_set(err, "draw without a mesh");
    if ((unsigned)d->shade >= SR_SHADE_COUNT || (unsigned)d->cull > SR_CULL_NONE ||
        (unsigned)d->front > SR_FRONT_CCW || (unsigned)d->filter > SR_FILTER_NEAREST)
        return sr_error_set(err, "draw with an unknown shading, culling, front or filter mode");
    if (!sr_assemble_indices_valid(d->mesh))
        return sr_error_set(err, "mesh has an index past its %u vertices", d->mesh->vertex_count);
    if (l->normal >= 0 && !d->mesh->normals)
        return sr_error_set(err, "this shading mode needs vertex normals and the mesh has none");
    if (l->color >= 0 && !d->mesh->colors)
        return sr_error_set(err, "color shading needs vertex colors and the mesh has none");
    if (d->shade == SR_SHADE_TEXTURE && (!d->mesh->uvs || !d->texture || !d->texture->texels))
        return sr_error_set(err, "texture shading needs texture coordinates and a texture");
    if (d->texture && d->texture->texels && (d->texture->width < 1 || d->texture->height < 1))
        return sr_error_set(err, "texture of size %dx%d cannot be sampled", d->texture->width, d->texture->height);
    return true;
}

static void shade_context_make(const sr_draw_desc *d, const sr_varying_layout *l, sr_shade_context *c)
{
    vec3 light = SR_DEFAULT_LIGHT;
    if (!glm_vec3_eq(((float *)d->light_dir), 0.0f))
        glm_vec3_copy((float *)d->light_dir, light);
    glm_vec3_normalize(light);
    *c = (sr_shade_context){ .layout = *l, .texture = d->texture, .filter = d->filter };
    glm_vec3_copy(light, c->light_dir);
}

/* Stages 6 to 10 for one fan triangle. */
static void draw_fan_triangle(draw_state *st, const sr_screen_vertex tri[3], bool clipped, uint32_t id)
{
    int64_t area2 = sr_cull_area2(&tri[0], &tri[1], &tri[2]);
    if (!sr_cull_keeps(area2, st->desc->cull, st->desc->front)) {
        st->stats->culled++;
        return;
    }
    st->stats->drawn++;
    if (st->desc->observer)
        st->desc->observer(st->desc->observer_user, tri, clipped, id);
    st->stats->fragments += sr_raster_triangle(st->fb, st->rect, st->desc->shade, &st->shade, tri, area2, id);
}

/* Stages 5 and 6: map every polygon vertex once, then fan (v0, vi, vi+1).
 * A vertex the viewport refuses (only possible from rounding on absurd
 * input) drops the polygon, counted as rejected. */
static void draw_polygon(draw_state *st, const sr_polygon *poly, bool clipped, uint32_t id)
{
    sr_screen_vertex screen[SR_MAX_CLIP_VERTS];
    for (int i = 0; i < poly->count; i++) {
        if (!sr_viewport_map(&poly->vert[i], st->shade.layout.count, st->fb->width, st->fb->height, &screen[i])) {
            st->stats->rejected++;
            return;
        }
    }
    for (int i = 1; i + 1 < poly->count; i++)
        draw_fan_triangle(st, (sr_screen_vertex[3]){ screen[0], screen[i], screen[i + 1] }, clipped, id);
}

/* Stages 2 to 4 for triangle slot k. */
static void draw_slot(draw_state *st, uint32_t k)
{
    uint32_t idx[3];
    if (!sr_assemble_triangle(st->desc->mesh, k, idx))
        return;
    st->stats->triangles++;
    unsigned c0 = st->outcodes[idx[0]], c1 = st->outcodes[idx[1]], c2 = st->outcodes[idx[2]];
    unsigned any = c0 | c1 | c2;
    if ((any & SR_OUT_NONFINITE) || (c0 & c1 & c2)) {
        st->stats->rejected++;
        st->stats->nonfinite += (any & SR_OUT_NONFINITE) != 0;
        return;
    }
    sr_polygon poly = { .count = 3, .vert = { st->verts[idx[0]], st->verts[idx[1]], st->verts[idx[2]] } };
    if (any) {
        st->stats->clipped++;
        sr_clip_polygon(&poly, any, SR_VARYINGS_AT + st->shade.layout.count);
    }
    draw_polygon(st, &poly, any != 0, k);
}

static bool run_vertex_stage(const sr_draw_desc *d, const sr_varying_layout *l, sr_vertex_out **verts,
                             unsigned char **outcodes, sr_error *err)
{
    uint32_t n = d->mesh->vertex_count;
    sr_vertex_transform xf;
    mat4 world, view, projection;
    matrix_or_identity(d->world, world);
    matrix_or_identity(d->view, view);
    matrix_or_identity(d->projection, projection);
    sr_vertex_make_transform(world, view, projection, &xf);
    *verts = malloc((n ? n : 1) * sizeof **verts);
    *outcodes = malloc(n ? n : 1);
    if (!*verts || !*outcodes)
        return sr_error_set(err, "out of memory for %u transformed vertices", n);
    sr_vertex_run(d->mesh, &xf, l, 0, n, *verts);
    for (uint32_t i = 0; i < n; i++)
        (*outcodes)[i] = (unsigned char)sr_clip_outcode((*verts)[i].v);
    return true;
}

bool sr_draw(sr_framebuffer *fb, const sr_draw_desc *desc, sr_stats *stats, sr_error *err)
{
    if (!desc)
        return sr_error_set(err, "draw without a description");
    sr_varying_layout layout = { .color = -1, .uv = -1, .normal = -1 };
    if (desc->mesh)
        layout = sr_vertex_layout(desc->shade, desc->mesh, desc->texture && desc->texture->texels);
    if (!check_inputs(fb, desc, &layout, err))
        return false;
    sr_stats scratch_stats = { 0 };
    draw_state st = { .fb = fb, .desc = desc, .stats = stats ? stats : &scratch_stats,
                      .rect = { 0, 0, fb->width, fb->height } };
    shade_context_make(desc, &layout, &st.shade);
    sr_vertex_out *verts = NULL;
    unsigned char *outcodes = NULL;
    bool ok = run_vertex_stage(desc, &layout, &verts, &outcodes, err);
    if (ok) {
        st.verts = verts;
        st.outcodes = outcodes;
        uint32_t slots = sr_mesh_triangle_slots(desc->mesh);
        for (uint32_t k = 0; k < slots; k++)
            draw_slot(&st, k);
    }
    free(verts);
    free(outcodes);
    return ok;
}
