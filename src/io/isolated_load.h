/* isolated_load.h — a mesh loader run in a child process, so that a file
 * which crashes or hangs a third-party importer becomes a one-line error. */
#ifndef SOFTRAST_IO_ISOLATED_LOAD_H
#define SOFTRAST_IO_ISOLATED_LOAD_H

#include "softrast/files.h"

#include "load_report.h"

typedef bool (*sr_isolated_loader)(sr_mesh *mesh, sr_texture *texture, const char *path, sr_error *err);

/* Runs load(mesh, texture, path) in a child limited to `seconds` (CPU and
 * wall) and copies its mesh and texture (empty when it made none) back. False, with one line in err, for the loader's own
 * error, a crash ("the importer crashed on this file (…)"), the time limit,
 * or counts past SR_MAX_MESH_VERTICES / SR_MAX_MESH_TRIANGLES or a texture
 * past SR_MAX_TEXTURE_SIDE / SR_MAX_TEXTURE_TEXELS; mesh and texture are
 * then empty. */
bool sr_isolated_load(sr_mesh *mesh, sr_texture *texture, const char *path, sr_isolated_loader load, unsigned seconds,
                      sr_error *err);

/* The same with a loader that also fills a report (load_report.h): the
 * child's report comes back into report (when not NULL), checked against
 * the report's limits, its texts NUL-terminated. */
typedef bool (*sr_isolated_report_loader)(sr_mesh *mesh, sr_texture *texture, const char *path,
                                          sr_load_report *report, sr_error *err);
bool sr_isolated_load_report(sr_mesh *mesh, sr_texture *texture, const char *path, sr_isolated_report_loader load,
                             unsigned seconds, sr_load_report *report, sr_error *err);

#endif
