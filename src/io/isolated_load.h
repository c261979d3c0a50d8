/* isolated_load.h — a mesh loader run in a child process, so that a file
 * which crashes or hangs a third-party importer becomes a one-line error. */
#ifndef SOFTRAST_IO_ISOLATED_LOAD_H
#define SOFTRAST_IO_ISOLATED_LOAD_H

#include "softrast/files.h"

typedef bool (*sr_isolated_loader)(sr_mesh *mesh, const char *path, sr_error *err);

/* Runs load(mesh, path) in a child limited to `seconds` (CPU and wall) and
 * copies its mesh back. False, with one line in err, for the loader's own
 * error, a crash ("the importer crashed on this file (…)"), the time limit,
 * or counts past SR_MAX_MESH_VERTICES / SR_MAX_MESH_TRIANGLES; the mesh is
 * then zeroed. */
bool sr_isolated_load(sr_mesh *mesh, const char *path, sr_isolated_loader load, unsigned seconds, sr_error *err);

#endif
