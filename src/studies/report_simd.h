/* report_simd.h — the per-pixel loops side by side for the error-against-
 * time report: each shaded benchmark scene timed with the scalar loop and
 * every SIMD kernel this CPU runs, its image compared with the scalar one
 * pixel by pixel. */
#ifndef SOFTRAST_APP_REPORT_SIMD_H
#define SOFTRAST_APP_REPORT_SIMD_H

#include <stdbool.h>
#include <stdio.h>

#include "softrast_private.h"

#define SR_REPORT_SIMD_SCENES 2
#define SR_REPORT_SIMD_LOOPS (SR_SIMD_COUNT - 1) /* all but AUTO */

typedef struct sr_report_simd_row {
    sr_simd simd;
    double ms;              /* median per frame, clear + draw */
    uint64_t pixels_differ; /* color or depth differing from the scalar loop's last frame */
} sr_report_simd_row;

typedef struct sr_report_simd_scene {
    const char *name, *what;
    int frames, loops; /* loops: rows measured (the ones this CPU runs) */
    sr_report_simd_row rows[SR_REPORT_SIMD_LOOPS];
} sr_report_simd_scene;

/* Measures the fly and fill scenes at 1 thread, `frames` frames each (fill
 * at most 2: its scalar loop takes seconds a frame). */
bool sr_report_simd_measure(int frames, sr_report_simd_scene out[SR_REPORT_SIMD_SCENES], sr_error *err);

/* The Markdown section for report.md. */
void sr_report_simd_write(FILE *f, const sr_report_simd_scene scenes[SR_REPORT_SIMD_SCENES]);

#endif
