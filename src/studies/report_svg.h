/* report_svg.h — writing the error-against-time report: a Markdown table per
 * scene and one SVG scatter plot of id error against milliseconds. */
#ifndef SOFTRAST_APP_REPORT_SVG_H
#define SOFTRAST_APP_REPORT_SVG_H

#include <stdbool.h>

#include "report_peer.h"
#include "report_simd.h"
#include "report_truth.h"
#include "softrast_private.h"

#define SR_REPORT_KNOBS 9

typedef struct sr_report_point {
    const char *knob;
    double ms;          /* median per frame */
    double id_error;    /* fraction of pixels whose triangle id differs from the reference */
    double depth_error; /* largest depth difference where both drew */
    sr_truth_errors truth;
} sr_report_point;

typedef struct sr_report_scene {
    const char *name, *what;
    int frames; /* camera positions compared */
    sr_report_point points[SR_REPORT_KNOBS];
} sr_report_scene;


/* Writes report.md and the plots into dir; peer: llvmpipe's figures, read
 * before measuring (count 0 when its file is missing). */
bool sr_report_files(const char *dir, const sr_report_scene *scenes, const sr_report_simd_scene *loops,
                     const struct sr_report_peer *peer, int frames, sr_error *err);

#endif
