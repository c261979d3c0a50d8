/* layers.c — opaque parts, then BLEND parts back to front: sr_draw_layered
 * (softrast.h). */
#include <stdlib.h>
#include <string.h>

#include "core/dmat4.h"
#include "core/error.h"
#include "softrast/softrast.h"

static bool is_blend_part(const sr_mesh *mesh, const sr_mesh_part *p)
{
    return p->material < mesh->material_count && mesh->materials[p->material].alpha_mode == SR_ALPHA_BLEND;
}

static uint32_t blend_part_count(const sr_mesh *mesh)
{
    uint32_t n = 0;
    for (uint32_t i = 0; i < mesh->part_count; i++)
        n += is_blend_part(mesh, &mesh->parts[i]);
    return n;
}

/* Whether desc is drawn in layers: it replaces and writes depth (as the
 * file's materials mean it), and its mesh is a triangle list in world
 * positions with BLEND parts in range (sr_draw refuses what is not). */
static bool layered(const sr_draw_desc *desc)
{
    const sr_mesh *m = desc->mesh;
    if (desc->blend != SR_BLEND_REPLACE || desc->no_depth_write || m->topology != SR_TRIANGLE_LIST ||
        m->clip_positions || !m->positions || !m->indices || (m->material_count && !m->materials))
        return false;
    for (uint32_t i = 0; i < m->part_count; i++) {
        const sr_mesh_part *p = &m->parts[i];
        if ((uint64_t)p->first_triangle + p->triangle_count > m->index_count / 3)
            return false; /* sr_draw's to refuse */
    }
    return blend_part_count(m) > 0;
}

/* One BLEND part to draw: its mesh (a view of the whole one's arrays) and
 * its centre's distance from the eye. */
typedef struct layer {
    sr_mesh mesh;
    sr_mesh_part part;
    double distance;
    uint32_t order; /* the part's index: ties keep the file's order */
} layer;

/* Farthest first; at equal distances, the file's order. */
static int farthest_first(const void *a, const void *b)
{
    const layer *x = a, *y = b;
    if (x->distance != y->distance)
        return x->distance < y->distance ? 1 : -1;
    return x->order < y->order ? -1 : x->order > y->order;
}

/* Eye space from the mesh's positions: view · world · T(origin), in double
 * as the draw composes it. */
static sr_dmat4 eye_from_mesh(const sr_draw_desc *desc)
{
    sr_dmat4 world = sr_dmat4_desc_matrix(&desc->world_d, desc->world);
    sr_dmat4 view = sr_dmat4_desc_matrix(&desc->view_d, desc->view);
    sr_dmat4 vw = sr_dmat4_mul(&view, &world);
    return sr_dmat4_translate(&vw, desc->mesh->origin);
}

/* The part as a mesh of its own triangles, with its bounds, and the
 * distance of their centre from the eye. */
static void layer_make(const sr_mesh *mesh, const sr_mesh_part *p, uint32_t order, const sr_dmat4 *eye, layer *l)
{
    l->mesh = *mesh;
    l->mesh.indices = mesh->indices + 3 * (size_t)p->first_triangle;
    l->mesh.index_count = 3 * p->triangle_count;
    l->mesh.file_faces = mesh->file_faces ? mesh->file_faces + p->first_triangle : NULL;
    l->part = (sr_mesh_part){ 0, p->triangle_count, p->material };
    l->mesh.part_count = 1; /* parts: &l->part, set once the layers are sorted (they move) */
    l->order = order;
    double lo[3] = { 0 }, hi[3] = { 0 };
    for (uint32_t i = 0; i < l->mesh.index_count; i++) {
        const float *v = mesh->positions[l->mesh.indices[i] < mesh->vertex_count ? l->mesh.indices[i] : 0];
        for (int k = 0; k < 3; k++) {
            lo[k] = i == 0 || v[k] < lo[k] ? v[k] : lo[k];
            hi[k] = i == 0 || v[k] > hi[k] ? v[k] : hi[k];
        }
    }
    l->mesh.bounded = false; /* sr_draw clips it as it would any mesh */
    double c[3], d2 = 0.0;
    for (int k = 0; k < 3; k++)
        c[k] = 0.5 * (lo[k] + hi[k]);
    for (int r = 0; r < 3; r++) {
        double e = eye->m[3][r];
        for (int k = 0; k < 3; k++)
            e += eye->m[k][r] * c[k];
        d2 += e * e;
    }
    l->distance = d2;
}

/* Whether the shading draws materials (their colours and alpha): the
 * others picture depth and ids, which no BLEND part writes. */
static bool shades_materials(sr_shade shade)
{
    return shade == SR_SHADE_LAMBERT || shade == SR_SHADE_TEXTURE;
}

bool sr_draw_layered(sr_framebuffer *fb, const sr_draw_desc *desc, sr_stats *stats, sr_error *err)
{
    if (!desc || !desc->mesh || !layered(desc))
        return sr_draw(fb, desc, stats, err);
    const sr_mesh *mesh = desc->mesh;
    uint32_t n = shades_materials(desc->shade) ? blend_part_count(mesh) : 0;
    uint32_t *indices = malloc((size_t)mesh->index_count * sizeof *indices);
    layer *layers = n ? malloc((size_t)n * sizeof *layers) : NULL;
    bool ok = indices && (layers || n == 0);
    if (!ok) {
        sr_error_set(err, "out of memory for the layers of %u BLEND parts", n);
    } else {
        /* The first draw: every slot of a BLEND part made degenerate, so
         * it draws nothing there, counts nothing, and ids stay the file's. */
        memcpy(indices, mesh->indices, (size_t)mesh->index_count * sizeof *indices);
        sr_dmat4 eye = eye_from_mesh(desc);
        for (uint32_t i = 0, j = 0; i < mesh->part_count; i++) {
            const sr_mesh_part *p = &mesh->parts[i];
            if (!is_blend_part(mesh, p))
                continue;
            for (uint32_t t = p->first_triangle; t < p->first_triangle + p->triangle_count; t++)
                indices[3 * t + 1] = indices[3 * t + 2] = indices[3 * t];
            if (j < n)
                layer_make(mesh, p, i, &eye, &layers[j++]);
        }
        if (n)
            qsort(layers, n, sizeof *layers, farthest_first);
        sr_mesh opaque = *mesh;
        opaque.indices = indices;
        sr_draw_desc d = *desc;
        d.mesh = &opaque;
        ok = sr_draw(fb, &d, stats, err);
        d.clear = false;
        d.blend = SR_BLEND_ALPHA;
        d.no_depth_write = true;
        for (uint32_t j = 0; ok && j < n; j++) {
            layers[j].mesh.parts = &layers[j].part;
            d.mesh = &layers[j].mesh;
            ok = sr_draw(fb, &d, stats, err);
        }
    }
    free(indices);
    free(layers);
    return ok;
}
