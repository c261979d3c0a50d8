/* report.h — `softrast bench --report`: error against run time for every
 * accuracy/speed knob, written as docs/report.md and docs/report.svg. */
#ifndef SOFTRAST_APP_REPORT_H
#define SOFTRAST_APP_REPORT_H

#include <stdbool.h>

#include "bench_scenes.h"
#include "report_svg.h"
#include "softrast_private.h"

/* The report's scenes, in its order: dense, fly, stiff, then the scanned
 * meshes (sr_bench_scan_*). bench-gl --truth draws the same. */
typedef bool (*sr_report_scene_make)(sr_bench_scene *s, sr_error *err);
extern const sr_report_scene_make sr_report_scene_makers[SR_REPORT_SCENES];

/* Measures each knob on the report's scenes against a reference
 * render (double clipping, 16 subpixel bits) and writes the report files
 * into dir. frames: timed frames per configuration. */
bool sr_report_write(const char *dir, int frames, sr_error *err);

/* The cameras the report compares for a scene: its path's key frames (at
 * most 8), or its one camera. */
int sr_report_scene_frames(const sr_bench_scene *s);

#endif
