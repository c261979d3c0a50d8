/* mesh_loaders.h — the loaders behind sr_mesh_load (softrast/files.h): the
 * own OBJ loader (sr_obj_load) and Assimp for every other format. */
#ifndef SOFTRAST_IO_MESH_LOADERS_H
#define SOFTRAST_IO_MESH_LOADERS_H

#include "softrast/files.h"

/* A file through Assimp; false with "FILE: reason" in err, mesh zeroed. */
bool sr_assimp_load(sr_mesh *mesh, const char *path, sr_error *err);

#endif
