/* report.h — `softrast bench --report`: error against run time for every
 * accuracy/speed knob, written as docs/report.md and docs/report.svg. */
#ifndef SOFTRAST_APP_REPORT_H
#define SOFTRAST_APP_REPORT_H

#include <stdbool.h>

#include "bench_scenes.h"
#include "softrast_private.h"

/* Measures each knob on the dense, fly and stiff scenes against a reference
 * render (double clipping, 16 subpixel bits) and writes the report files
 * into dir. frames: timed frames per configuration. */
bool sr_report_write(const char *dir, int frames, sr_error *err);

/* The cameras the report compares for a scene: its path's key frames (at
 * most 8), or its one camera. */
int sr_report_scene_frames(const sr_bench_scene *s);

#endif
