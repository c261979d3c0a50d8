/* material_textures.h — the texture files a mesh's materials name, each
 * loaded once and hung on its materials (sr_material.texture), so every
 * part draws its own. The command line (app/scene_setup.c) and Python's
 * Mesh.load load them so, with this one rule. */
#ifndef SOFTRAST_IO_MATERIAL_TEXTURES_H
#define SOFTRAST_IO_MATERIAL_TEXTURES_H

#include <stdbool.h>
#include <stdint.h>

#include "softrast/softrast.h"

/* The loaded textures, each distinct path once; the materials point into
 * them, so they outlive the mesh's draws. */
typedef struct sr_material_textures {
    sr_texture *textures;
    uint32_t count;
} sr_material_textures;

/* Called for each texture file that is missing or unreadable, with the
 * loader's line; its materials draw their base colour. */
typedef void sr_material_texture_warning(void *context, const sr_error *why);

/* Loads the texture of every material with a texture_path into out
 * (emptied first), each path once, and points the materials at it; a path that fails is dropped from its materials (freed, NULL), so a
 * draw does not give them desc's texture, which an embedded one may be,
 * and warn(context, why) is called once for it. False only when out of
 * memory (out is left empty). */
bool sr_material_textures_load(sr_mesh *mesh, sr_material_textures *out, sr_material_texture_warning *warn,
                               void *context);

/* Frees the textures (the materials still point at them: free the mesh
 * too, or load again) and empties out. */
void sr_material_textures_free(sr_material_textures *t);

#endif
