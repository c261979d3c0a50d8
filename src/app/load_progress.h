/* load_progress.h — sr_mesh_load, and a line on stderr when it is slow. */
#ifndef SOFTRAST_APP_LOAD_PROGRESS_H
#define SOFTRAST_APP_LOAD_PROGRESS_H

#include "io/load_report.h"
#include "softrast_private.h"

/* The load a user waits for before the first frame (render, view, truth).
 * The progress line appears after this long; the program passes it. */
#define SR_APP_LOAD_QUIET_MS 1000.0

/* sr_mesh_load(mesh, texture, path), on a thread of its own: if it is not
 * done within quiet_ms, one line says which file is loading and how big it
 * is, and a second, when it succeeds, how long it took and what it read
 * (the error, if any, is the caller's to print). */
bool sr_app_load_mesh(const char *path, sr_mesh *mesh, sr_texture *texture, double quiet_ms, sr_error *err);
/* The same, with the loader's report (io/load_report.h; NULL: not asked). */
bool sr_app_load_mesh_report(const char *path, sr_mesh *mesh, sr_texture *texture, sr_load_report *report,
                             double quiet_ms, sr_error *err);

#endif
