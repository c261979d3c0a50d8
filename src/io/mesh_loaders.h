/* mesh_loaders.h — the loaders behind sr_mesh_load (softrast/files.h): the
 * own OBJ loader (sr_obj_load) and Assimp for every other format. */
#ifndef SOFTRAST_IO_MESH_LOADERS_H
#define SOFTRAST_IO_MESH_LOADERS_H

#include "softrast/files.h"

/* The CPU time an import may take before it is stopped as a hang. */
#define SR_IMPORT_SECONDS 120u

/* A file through Assimp, in a child process given `seconds`; a texture the
 * file embeds goes into texture. False with "FILE: reason" in err, mesh and
 * texture empty. */
bool sr_assimp_load(sr_mesh *mesh, sr_texture *texture, const char *path, unsigned seconds, sr_error *err);

#endif
