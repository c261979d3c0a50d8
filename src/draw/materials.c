/* A mesh's materials as shading contexts (10_shade.h): one per material,
 * made once per draw, and the one each triangle is drawn with, found from
 * its part.
 *
 * A material becomes what the per-pixel loops test: its colour as the
 * albedo where it has no texture (else as a tint of the texels, and of the
 * vertex colours), and its alpha as an integer floor on the texel alpha
 * (alpha_min), so every loop discards the same fragments with one integer
 * compare; a constant alpha below the cutoff hides the material whole.
 * The rasterizer finds a triangle's (10_shade.c). */
#include <math.h>

#include "draw_state.h"
#include "materials.h"
#include "core/error.h"
#include "pipeline/02_assemble.h"
#include "pipeline/11_merge.h"

/* BLEND in a draw that replaces: MASK at this cutoff. */
#define BLEND_AS_MASK_CUTOFF 0.5f

bool sr_materials_check(const sr_mesh *mesh, sr_error *err)
{
    if (mesh->material_count == 0)
        return true;
    if (!mesh->materials)
        return sr_error_set(err, "mesh has %u materials and no material array", mesh->material_count);
    for (uint32_t i = 0; i < mesh->material_count; i++) {
        const sr_material *m = &mesh->materials[i];
        if ((unsigned)m->alpha_mode > SR_ALPHA_BLEND)
            return sr_error_set(err, "material %u has an unknown alpha mode %d", i, (int)m->alpha_mode);
        for (int c = 0; c < 4; c++)
            if (!isfinite(m->base_color[c]))
                return sr_error_set(err, "material %u has a base colour that is not finite", i);
        if (!isfinite(m->alpha_cutoff))
            return sr_error_set(err, "material %u has an alpha cutoff that is not finite", i);
        const sr_texture *t = m->texture;
        if (t && t->texels && (t->width < 1 || t->height < 1 || t->width > SR_MAX_TEXTURE_SIDE ||
                               t->height > SR_MAX_TEXTURE_SIDE))
            return sr_error_set(err, "material %u's texture of size %dx%d cannot be sampled (each side 1..%d)", i,
                                t->width, t->height, SR_MAX_TEXTURE_SIDE);
    }
    uint32_t end = 0;
    for (uint32_t i = 0; i < mesh->part_count; i++) {
        const sr_mesh_part *p = &mesh->parts[i];
        if (p->material >= mesh->material_count)
            return sr_error_set(err, "part %u names material %u of %u", i, p->material, mesh->material_count);
        if (p->first_triangle < end || p->triangle_count > UINT32_MAX - p->first_triangle)
            return sr_error_set(err, "part %u overlaps the part before it or runs past 2^32 triangles", i);
        end = p->first_triangle + p->triangle_count;
    }
    return true;
}

/* The material's texture: its own, or for one that names a file but was
 * given none, the desc's (a caller that loads the mesh's texture_path for
 * desc->texture, as before materials, draws as it did). */
static const sr_texture *texture_of(const sr_material *m, const sr_texture *desc_texture)
{
    const sr_texture *t = m->texture ? m->texture : m->texture_path ? desc_texture : NULL;
    return t && t->texels ? t : NULL;
}

bool sr_materials_textured(const sr_mesh *mesh, const sr_texture *desc_texture)
{
    for (uint32_t i = 0; i < mesh->material_count; i++)
        if (texture_of(&mesh->materials[i], desc_texture))
            return true;
    return false;
}

/* The smallest texel alpha a (0..255) whose alpha a/255 · factor reaches
 * the cutoff, 256 where none does; in float, in this order, once per draw. */
static uint32_t alpha_floor(float factor, float cutoff)
{
    uint32_t a = 0;
    while (a < 256 && !((float)a * SR_SHADE_CHANNEL_SCALE * factor >= cutoff))
        a++;
    return a;
}

/* Whether the material's alpha cuts it in a draw of this blend: MASK, or
 * BLEND in a draw that replaces (as MASK at BLEND_AS_MASK_CUTOFF). */
static bool masked(const sr_material *m, sr_blend blend)
{
    return m->alpha_mode == SR_ALPHA_MASK || (m->alpha_mode == SR_ALPHA_BLEND && blend == SR_BLEND_REPLACE);
}

/* The modes that shade the materials' albedo, and test their alpha in
 * their own loops; the others (id, depth, normal, colour) draw the
 * materials' coverage alone, and make contexts only for a draw in which
 * some material is masked. */
static bool shades_albedo(sr_shade mode)
{
    return mode == SR_SHADE_LAMBERT || mode == SR_SHADE_TEXTURE;
}

static bool draws_coverage(sr_shade mode)
{
    return mode == SR_SHADE_ID || mode == SR_SHADE_DEPTH || mode == SR_SHADE_NORMAL || mode == SR_SHADE_COLOR;
}

sr_varying_layout sr_materials_layout(sr_shade mode, const sr_draw_desc *d, sr_varying_layout l)
{
    const sr_mesh *mesh = d->mesh;
    if (!draws_coverage(mode) || !mesh->uvs || !mesh->materials || !sr_assemble_triangles(mesh))
        return l;
    for (uint32_t i = 0; i < mesh->material_count; i++) {
        const sr_material *m = &mesh->materials[i];
        const sr_texture *t = texture_of(m, d->texture);
        if (masked(m, d->blend) && t && t->alpha) {
            l.uv = l.count;
            l.count += 2;
            return l;
        }
    }
    return l;
}

static void material_context(sr_shade mode, const sr_shade_context *base, const sr_material *m,
                             const sr_texture *desc_texture, sr_shade_context *c)
{
    *c = *base;
    c->materials = NULL;
    c->material_count = 0;
    c->parts = NULL;
    c->part_count = 0;
    const sr_texture *t = base->layout.uv >= 0 ? texture_of(m, desc_texture) : NULL;
    bool texture = t != NULL;
    c->texture = t;
    if (!texture)
        c->layout.uv = -1;
    c->alpha_scale = SR_MERGE_ALPHA_ONE; /* opaque but for a BLEND material blended (below) */
    c->alpha_texel = false;
    for (int i = 0; i < 3; i++) {
        c->albedo[i] = m->base_color[i];
        c->tint[i] = m->base_color[i];
        c->tinted = c->tinted || m->base_color[i] != 1.0f;
    }
    if (m->alpha_mode == SR_ALPHA_OPAQUE)
        return;
    if (m->alpha_mode == SR_ALPHA_BLEND && base->blend != SR_BLEND_REPLACE) {
        /* the factor's alpha in 8.8 fixed point, as 11_merge.h takes it */
        float a = m->base_color[3] > 0.0f ? (m->base_color[3] < 1.0f ? m->base_color[3] : 1.0f) : 0.0f;
        c->alpha_scale = (uint32_t)(a * (float)SR_MERGE_ALPHA_ONE + 0.5f);
        c->alpha_texel = texture && t->alpha;
        return;
    }
    float cutoff = m->alpha_mode == SR_ALPHA_BLEND ? BLEND_AS_MASK_CUTOFF : m->alpha_cutoff;
    uint32_t floor = texture && t->alpha ? alpha_floor(m->base_color[3], cutoff)
                                                  : (m->base_color[3] >= cutoff ? 0 : 256);
    bool hidden = floor > 255;
    c->alpha_min = hidden ? 0 : floor;
    c->cut = hidden ? SR_CUT_ALL : c->alpha_min && !shades_albedo(mode) ? SR_CUT_TEXELS : SR_CUT_NONE;
}

bool sr_materials_make(sr_draw_state *st, sr_error *err)
{
    const sr_mesh *mesh = st->desc->mesh;
    if (mesh->material_count == 0 || !(shades_albedo(st->mode) || draws_coverage(st->mode)) ||
        !sr_assemble_triangles(mesh))
        return true;
    bool any_masked = false;
    for (uint32_t i = 0; !any_masked && i < mesh->material_count; i++)
        any_masked = masked(&mesh->materials[i], st->desc->blend);
    if (!shades_albedo(st->mode) && !any_masked)
        return true; /* every triangle drawn whole, as without materials */
    sr_array *a = &st->ws->material_shades;
    if (!sr_array_reserve(a, mesh->material_count, sizeof(sr_shade_context)))
        return sr_error_set(err, "out of memory for %u materials", mesh->material_count);
    sr_shade_context *contexts = a->data;
    for (uint32_t i = 0; i < mesh->material_count; i++)
        material_context(st->mode, &st->shade, &mesh->materials[i], st->desc->texture, &contexts[i]);
    st->shade.materials = contexts;
    st->shade.material_count = mesh->material_count;
    /* Parts that all take material 0 (a mesh of one material in several
     * groups) are not searched per triangle: every triangle's is 0. */
    bool one = true;
    for (uint32_t i = 0; one && i < mesh->part_count; i++)
        one = mesh->parts[i].material == 0;
    st->shade.parts = one ? NULL : mesh->parts;
    st->shade.part_count = one ? 0 : mesh->part_count;
    return true;
}
