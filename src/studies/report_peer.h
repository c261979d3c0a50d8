/* report_peer.h — a peer renderer's figures beside the report's: llvmpipe's
 * time per frame and errors against the truth on the report's scenes, as
 * `bench-gl --truth` measures them and writes them (docs/llvmpipe-truth.tsv),
 * for `softrast bench --report` to put in its truth tables and its plot.
 *
 * The file: '#' comment lines, a line "renderer<TAB>what drew it", a header
 * line starting "scene<TAB>", then one line per scene: name, ms, depth ties,
 * edge ties, wrong triangles, coverage, edge distance max, |z − truth| max,
 * p99.9, median, tab-separated. */
#ifndef SOFTRAST_STUDIES_REPORT_PEER_H
#define SOFTRAST_STUDIES_REPORT_PEER_H

#include <stdbool.h>

#include "report_truth.h"
#include "softrast_private.h"

/* The report's scenes (report.c), each a row of the peer's too. */
#define SR_REPORT_SCENES 6

#define SR_REPORT_PEER_FILE "llvmpipe-truth.tsv"
#define SR_REPORT_PEER_RENDERER_CHARS 160

typedef struct sr_report_peer_row {
    char scene[32];
    double ms; /* median per frame over the scene's cameras, id shading */
    sr_truth_errors truth;
} sr_report_peer_row;

typedef struct sr_report_peer {
    char renderer[SR_REPORT_PEER_RENDERER_CHARS];
    int count;
    sr_report_peer_row rows[SR_REPORT_SCENES];
} sr_report_peer;

bool sr_report_peer_write(const char *path, const sr_report_peer *peer, sr_error *err);

/* Reads path into peer; a missing file leaves peer empty (count 0) and is
 * not an error, a malformed line is. */
bool sr_report_peer_read(const char *path, sr_report_peer *peer, sr_error *err);

/* The peer's row for scene, or NULL. */
const sr_report_peer_row *sr_report_peer_find(const sr_report_peer *peer, const char *scene);

#endif
