/* cost_model.h — `softrast bench --cost-model`: time per frame of the dense
 * torus against its triangle count (10k … 10M at 1920x1080) and against the
 * framebuffer's pixels (640x360 … 3840x2160 at 1M triangles), at one thread
 * and at several, with the phases' wall times and the fitted log-log
 * slopes; written as cost-model.md and cost-model.svg (docs/performance.md
 * reads them). */
#ifndef SOFTRAST_STUDIES_COST_MODEL_H
#define SOFTRAST_STUDIES_COST_MODEL_H

#include <stdbool.h>

#include "softrast_private.h"

/* Measures with `frames` timed frames a point, at 1 thread and at `threads`
 * (when more than 1), printing a line per point on stderr, and writes the
 * files into dir. */
bool sr_cost_model_write(const char *dir, int frames, int threads, sr_error *err);

#endif
