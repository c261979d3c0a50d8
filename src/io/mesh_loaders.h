/* mesh_loaders.h — the loaders behind sr_mesh_load (softrast/files.h): the
 * own OBJ loader (sr_obj_load) and Assimp for every other format. */
#ifndef SOFTRAST_IO_MESH_LOADERS_H
#define SOFTRAST_IO_MESH_LOADERS_H

#include "softrast/files.h"

#include "load_report.h"

/* The CPU time an import may take before it is stopped as a hang. */
#define SR_IMPORT_SECONDS 120u

/* A file through Assimp, in a child process given `seconds`; a texture the
 * file embeds goes into texture. False with "FILE: reason" in err, mesh and
 * texture empty. */
bool sr_assimp_load(sr_mesh *mesh, sr_texture *texture, const char *path, unsigned seconds, sr_error *err);
/* The same, with what the importer found into report (NULL: not asked). */
bool sr_assimp_load_report(sr_mesh *mesh, sr_texture *texture, const char *path, unsigned seconds,
                           sr_load_report *report, sr_error *err);

/* sr_obj_load, with what the file says of itself into report (NULL: not
 * asked): parts are the runs of faces of one material, a `usemtl` of a
 * material no library defines is a warning there. */
bool sr_obj_load_report(sr_mesh *mesh, const char *path, sr_load_report *report, sr_error *err);

#endif
