/* fuzz/fuzz_materials.h — what both loader targets check of a loaded
 * mesh's parts and materials: every part within the triangles and naming a
 * material the mesh has, every factor finite, and every texture path
 * loading as the program loads it (src/app/scene_setup.c): an image within
 * the limits, or one line saying why not (a directory, a path through
 * "..", a file that is no image), never a crash, a hang or an allocation
 * past the limits. A path that many materials share is loaded once, as
 * the program does. */
#ifndef SOFTRAST_FUZZ_MATERIALS_H
#define SOFTRAST_FUZZ_MATERIALS_H

#include <math.h>
#include <string.h>

#include "softrast_private.h"

#include "fuzz_common.h" /* CHECK() */

static inline void check_texture_path(const char *path)
{
    sr_texture t;
    sr_error err = { "" };
    if (sr_texture_load(&t, path, &err)) {
        CHECK(t.texels && t.width >= 1 && t.height >= 1 && t.width <= SR_MAX_TEXTURE_SIDE &&
                  t.height <= SR_MAX_TEXTURE_SIDE,
              "texture %s is %dx%d", path, t.width, t.height);
        sr_texture_free(&t);
    } else {
        CHECK(err.message[0] && !strchr(err.message, '\n'), "want one line for %s: '%s'", path, err.message);
    }
}

static inline void check_materials(const sr_mesh *m)
{
    CHECK(m->material_count <= SR_MAX_MESH_MATERIALS, "%u materials", m->material_count);
    CHECK((m->materials != NULL) == (m->material_count > 0), "materials %p, count %u", (void *)m->materials,
          m->material_count);
    for (uint32_t i = 0; i < m->part_count; i++) {
        const sr_mesh_part *p = &m->parts[i];
        CHECK((uint64_t)p->first_triangle + p->triangle_count <= m->index_count / 3, "part %u: %u + %u of %u", i,
              p->first_triangle, p->triangle_count, m->index_count / 3);
        CHECK(!m->materials || p->material < m->material_count, "part %u names material %u of %u", i, p->material,
              m->material_count);
    }
    const char *loaded = NULL;
    for (uint32_t i = 0; i < m->material_count; i++) {
        const sr_material *mat = &m->materials[i];
        for (int k = 0; k < 4; k++)
            CHECK(isfinite(mat->base_color[k]), "material %u colour %d is %a", i, k, mat->base_color[k]);
        CHECK((unsigned)mat->alpha_mode <= SR_ALPHA_BLEND && isfinite(mat->alpha_cutoff), "material %u alpha %d %a", i,
              (int)mat->alpha_mode, mat->alpha_cutoff);
        const char *path = mat->texture_path;
        if (path && !(loaded && strcmp(loaded, path) == 0)) {
            check_texture_path(path);
            loaded = path;
        }
    }
}

#endif
