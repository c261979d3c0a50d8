/* sr_mesh_load: the file's ending picks the loader. */
#include <string.h>
#include <strings.h>

#include "mesh_loaders.h"

static bool ends_with_obj(const char *path)
{
    size_t n = strlen(path);
    return n >= 4 && strcasecmp(path + n - 4, ".obj") == 0;
}

bool sr_mesh_load(sr_mesh *mesh, const char *path, sr_error *err)
{
    return ends_with_obj(path) ? sr_obj_load(mesh, path, err) : sr_assimp_load(mesh, path, SR_IMPORT_SECONDS, err);
}
