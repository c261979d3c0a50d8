#include <math.h>
#include <stdlib.h>

#include "report_truth.h"
#include "timing.h"

bool sr_truth_tally_add(sr_truth_tally *tally, const sr_truth_image *truth, const mat4 projection,
                        const sr_framebuffer *fb, sr_error *err)
{
    size_t n = (size_t)fb->width * fb->height;
    if (tally->z_count + n > tally->z_capacity) {
        size_t capacity = 2 * (tally->z_count + n);
        double *grown = realloc(tally->z_errors, capacity * sizeof *grown);
        if (!grown)
            return sr_error_set(err, "out of memory for %zu depth errors", capacity);
        tally->z_errors = grown;
        tally->z_capacity = capacity;
    }
    sr_truth_errors *c = &tally->counts;
    for (size_t i = 0; i < n; i++) {
        uint32_t drawn = fb->color[i], exact = truth->ids[i];
        if (!drawn != !exact) {
            c->coverage++;
        } else if (drawn != exact) {
            double gap = fabs(sr_truth_z_ndc(projection, truth->runner_up[i]) -
                              sr_truth_z_ndc(projection, truth->distance[i]));
            c->ties += gap <= SR_REPORT_TIE_TOLERANCE;
            c->wrong_triangle += gap > SR_REPORT_TIE_TOLERANCE;
        } else if (drawn) {
            tally->z_errors[tally->z_count++] = fabs(fb->depth[i] - sr_truth_z_ndc(projection, truth->distance[i]));
        }
    }
    return true;
}

sr_truth_errors sr_truth_tally_finish(sr_truth_tally *tally)
{
    sr_truth_errors e = tally->counts;
    size_t n = tally->z_count;
    if (n) {
        sr_study_sort_doubles(tally->z_errors, n);
        e.z_max = tally->z_errors[n - 1];
        e.z_p999 = tally->z_errors[(size_t)(0.999 * (double)(n - 1))];
        e.z_median = tally->z_errors[(n - 1) / 2];
    }
    free(tally->z_errors);
    *tally = (sr_truth_tally){ 0 };
    return e;
}
