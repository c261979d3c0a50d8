/* A mesh's materials' texture files, each loaded once
 * (sr_material_textures_load in softrast/files.h). The materials are
 * sorted by path, so a thousand naming one file cost a sort, not a
 * thousand loads or searches. */
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "softrast/files.h"

typedef struct by_path {
    const char *path;
    uint32_t material;
} by_path;

/* Paths in strcmp order, then materials in order (qsort is not stable). */
static int path_order(const void *a, const void *b)
{
    const by_path *pa = a, *pb = b;
    int c = strcmp(pa->path, pb->path);
    return c ? c : (pa->material > pb->material) - (pa->material < pb->material);
}

bool sr_material_textures_load(sr_mesh *mesh, sr_material_textures *out, sr_material_texture_warning *warn,
                               void *context, sr_error *err)
{
    sr_material_textures_free(out);
    uint32_t n = 0;
    for (uint32_t i = 0; i < mesh->material_count; i++)
        n += mesh->materials[i].texture_path != NULL;
    if (n == 0)
        return true;
    by_path *order = malloc(n * sizeof *order);
    out->textures = calloc(n, sizeof *out->textures);
    if (!order || !out->textures) {
        free(order);
        free(out->textures);
        out->textures = NULL;
        return sr_error_set(err, "out of memory for %u materials' textures", mesh->material_count);
    }
    for (uint32_t i = 0, k = 0; i < mesh->material_count; i++)
        if (mesh->materials[i].texture_path)
            order[k++] = (by_path){ mesh->materials[i].texture_path, i };
    qsort(order, n, sizeof *order, path_order);
    for (uint32_t i = 0; i < n;) {
        const char *path = order[i].path;
        sr_texture *t = &out->textures[out->count++];
        sr_error why;
        if (!sr_texture_load(t, path, &why) && warn)
            warn(context, &why);
        uint32_t end = i + 1;
        while (end < n && strcmp(order[end].path, path) == 0)
            end++;
        for (; i < end; i++) {
            sr_material *m = &mesh->materials[order[i].material];
            if (t->texels) {
                m->texture = t;
            } else {
                free(m->texture_path);
                m->texture_path = NULL;
            }
        }
    }
    free(order);
    return true;
}

void sr_material_textures_free(sr_material_textures *t)
{
    for (uint32_t i = 0; i < t->count; i++)
        sr_texture_free(&t->textures[i]);
    free(t->textures);
    *t = (sr_material_textures){ 0 };
}
