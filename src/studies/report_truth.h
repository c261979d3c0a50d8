/* report_truth.h — the report's errors against the truth image
 * (truth.h): per knob, pixels whose visible triangle is not the truth's,
 * sorted by what explains them (a depth tie, a coverage tie of snapping,
 * nothing), pixels covered by one and not the other, and |z − truth| where
 * both show the same triangle. */
#ifndef SOFTRAST_STUDIES_REPORT_TRUTH_H
#define SOFTRAST_STUDIES_REPORT_TRUTH_H

#include <stdint.h>
#include <stdio.h>

#include "softrast_private.h"
#include "truth.h"

/* A gap in z_ndc (the knob's own) between the truth's nearest and
 * runner-up hits at or below this is a tie: either triangle is right. */
#define SR_REPORT_TIE_TOLERANCE 1e-6

/* What a renderer's vertex may be off by, in pixels, before it is snapped:
 * the float vertex transform and the clipper. An allowance measured on the
 * report's scenes (tests/test_truth_judge.c), not a worst-case bound:
 * docs/precision.md, "Vertex error before snapping". */
#define SR_REPORT_VERTEX_ERROR_PX (1.0 / 1024.0)

/* How far from a triangle's exact outline a pixel centre may lie and still
 * be covered or missed by a renderer that snaps vertices to 2^-bits px: a
 * vertex moves by at most √2·2^-(bits+1) in snapping (half a step in x and
 * in y) plus SR_REPORT_VERTEX_ERROR_PX, and every point of an edge by no more
 * than its end points. */
double sr_truth_coverage_tolerance(int subpixel_bits);

/* How a drawn pixel compares with the truth. */
typedef enum sr_truth_verdict {
    SR_TRUTH_SAME,           /* the truth's triangle, or nothing where the truth has nothing */
    SR_TRUTH_COVERAGE,       /* drawn where the truth has nothing, or nothing where it has a triangle */
    SR_TRUTH_DEPTH_TIE,      /* another triangle; the truth's runner-up within the tie tolerance */
    SR_TRUTH_EDGE_TIE,       /* another triangle; the centre within the coverage tolerance of
                                the truth's or the drawn triangle's outline */
    SR_TRUTH_WRONG_TRIANGLE, /* another triangle, beyond both tolerances */
} sr_truth_verdict;

/* The verdict on pixel (x, y) drawn with id `drawn` (slot + 1, 0: nothing)
 * under `projection`; for EDGE_TIE and WRONG_TRIANGLE *edge_distance gets
 * the centre's distance in pixels to the nearer of the two triangles'
 * outlines (truth_outline.h). */
sr_truth_verdict sr_truth_judge(const sr_truth_image *truth, const mat4 projection, uint32_t drawn, int x, int y,
                                double coverage_tolerance, double *edge_distance);

typedef struct sr_truth_errors {
    uint64_t depth_ties, edge_ties, wrong_triangle, coverage; /* pixels per verdict */
    double edge_distance_max; /* over edge ties and wrong triangles */
    double z_max, z_p999, z_median; /* |z_ndc − truth| where both drew the same triangle */
} sr_truth_errors;

/* The comparisons of one knob over its frames; set coverage_tolerance
 * (sr_truth_coverage_tolerance) before the first frame. */
typedef struct sr_truth_tally {
    double coverage_tolerance;
    sr_truth_errors counts;
    double *z_errors;
    size_t z_count, z_capacity;
} sr_truth_tally;

/* Compares the ids and depths fb holds (drawn with `projection`) with the
 * truth of the same camera. */
bool sr_truth_tally_add(sr_truth_tally *tally, const sr_truth_image *truth, const mat4 projection,
                        const sr_framebuffer *fb, sr_error *err);

/* The tally's errors, its percentiles taken; frees the tally. */
sr_truth_errors sr_truth_tally_finish(sr_truth_tally *tally);

/* The report's section heading and the paragraph that says what its tables count. */
void sr_report_truth_intro(FILE *f);

/* The report's table of errors against the truth, for the report's knobs
 * and bench-gl's llvmpipe rows alike: the header (`first` names the first
 * column) and one row. */
void sr_truth_errors_write_header(FILE *f, const char *first);
void sr_truth_errors_write_row(FILE *f, const char *label, const sr_truth_errors *e);

#endif
