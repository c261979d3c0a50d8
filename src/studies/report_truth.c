#include <math.h>
#include <stdlib.h>

#include "report_truth.h"
#include "core/clock.h"
#include "truth_outline.h"

double sr_truth_coverage_tolerance(int subpixel_bits)
{
    return sqrt(2.0) * ldexp(1.0, -(subpixel_bits + 1)) + SR_REPORT_VERTEX_ERROR_PX;
}

/* The distance from the centre of (x, y) to the nearer outline of slots a and b. */
static double nearer_outline(const sr_truth_image *truth, uint32_t a, uint32_t b, int x, int y)
{
    double centre[2] = { x + 0.5, y + 0.5 };
    return fmin(sr_truth_outline_locate(truth, a, centre).distance, sr_truth_outline_locate(truth, b, centre).distance);
}

sr_truth_verdict sr_truth_judge(const sr_truth_image *truth, const mat4 projection, uint32_t drawn, int x, int y,
                                double coverage_tolerance, double *edge_distance)
{
    size_t i = (size_t)y * truth->width + x;
    uint32_t exact = truth->ids[i];
    if (drawn == exact)
        return SR_TRUTH_SAME;
    if (!drawn || !exact)
        return SR_TRUTH_COVERAGE;
    double gap = fabs(sr_truth_z_ndc(projection, truth->runner_up[i]) - sr_truth_z_ndc(projection, truth->distance[i]));
    if (gap <= SR_REPORT_TIE_TOLERANCE)
        return SR_TRUTH_DEPTH_TIE;
    /* Farther than the tolerance from both outlines, snapping decides both
     * triangles' coverage as exact arithmetic does: the truth's is drawn
     * unless the other one's depth is wrong by more than the tie. */
    *edge_distance = nearer_outline(truth, exact - 1, drawn - 1, x, y);
    return *edge_distance <= coverage_tolerance ? SR_TRUTH_EDGE_TIE : SR_TRUTH_WRONG_TRIANGLE;
}

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
        double edge = 0.0;
        int x = (int)(i % fb->width), y = (int)(i / fb->width);
        switch (sr_truth_judge(truth, projection, fb->color[i], x, y, tally->coverage_tolerance, &edge)) {
        case SR_TRUTH_SAME:
            if (fb->color[i])
                tally->z_errors[tally->z_count++] = fabs(fb->depth[i] - sr_truth_z_ndc(projection, truth->distance[i]));
            break;
        case SR_TRUTH_COVERAGE:
            c->coverage++;
            break;
        case SR_TRUTH_DEPTH_TIE:
            c->depth_ties++;
            break;
        case SR_TRUTH_EDGE_TIE:
            c->edge_ties++;
            break;
        case SR_TRUTH_WRONG_TRIANGLE:
            c->wrong_triangle++;
            break;
        }
        c->edge_distance_max = fmax(c->edge_distance_max, edge);
    }
    return true;
}

sr_truth_errors sr_truth_tally_finish(sr_truth_tally *tally)
{
    sr_truth_errors e = tally->counts;
    size_t n = tally->z_count;
    if (n) {
        sr_sort_doubles(tally->z_errors, n);
        e.z_max = tally->z_errors[n - 1];
        e.z_p999 = tally->z_errors[(size_t)(0.999 * (double)(n - 1))];
        e.z_median = tally->z_errors[(n - 1) / 2];
    }
    free(tally->z_errors);
    *tally = (sr_truth_tally){ 0 };
    return e;
}

void sr_report_truth_intro(FILE *f)
{
    fprintf(f, "\n## Against the truth\n\n"
               "The same draws against the truth image (`softrast truth`, src/studies/truth.c): for each pixel\n"
               "centre the triangle exact arithmetic says is nearest and its z_ndc, for the knob's own camera\n"
               "(standard or reversed z). Counts of pixels over all cameras. Where both drew but not the\n"
               "truth's triangle (src/studies/report_truth.c): a *depth tie* if the truth's runner-up at that\n"
               "pixel lies within the tie tolerance %g (in the knob's z_ndc) of its nearest; else an *edge\n"
               "tie* if the pixel centre lies within the coverage tolerance of the outline of the truth's or\n"
               "the drawn triangle (its part between the near and far planes, projected in double:\n"
               "src/studies/truth_outline.c); else a *wrong triangle*, which no tolerance explains. The\n"
               "coverage tolerance at b subpixel bits is √2·2^−(b+1) + 2^−10 px (%.3g px at 8 bits, %.3g at\n"
               "12): snapping moves a vertex by at most half a step in x and in y, every point of an edge by\n"
               "no more than its end points, and 2^−10 px allows for the vertex's error before snapping (the\n"
               "float vertex transform and clipping measure at most 3.7e−4 px on these scenes: docs/precision.md,\n"
               "\"Vertex error before snapping\"). Farther than that from both outlines, snapping covers or\n"
               "misses both triangles as exact arithmetic does. *edge distance max*: the largest distance from\n"
               "the centre to the nearer outline over the edge ties and wrong triangles. *coverage*: drawn by\n"
               "one and not the other; *|z − truth|*: in the knob's z_ndc, over the pixels where both drew the\n"
               "same triangle. llvmpipe's rows, on the same cameras and with the same tolerances (it snaps to\n"
               "8 bits too): docs/bench-compare.md (`./build/bench-gl --truth`).\n\n"
               "The floor under every |z − truth| column: the depth buffer holds float32, whose step just below\n"
               "1 is 2^−24 = %.3g, so storing an exact z there is off by up to %.3g. On the stiff scenes\n"
               "nearly every z is that close to 1 (standard z), and a renderer can be at most about\n"
               "(its peer's error) / %.3g times closer to the truth than the peer: with llvmpipe at 2–2.6e−7\n"
               "there, about 7 times.\n",
            SR_REPORT_TIE_TOLERANCE, sr_truth_coverage_tolerance(SR_SUBPIXEL_BITS), sr_truth_coverage_tolerance(12),
            ldexp(1.0, -24), ldexp(1.0, -25), ldexp(1.0, -25));
}

void sr_truth_errors_write_header(FILE *f, const char *first)
{
    fprintf(f, "| %s | depth ties | edge ties | wrong triangle | edge distance max (px) | coverage "
               "| \\|z − truth\\| max | p99.9 | median |\n"
               "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n",
            first);
}

void sr_truth_errors_write_row(FILE *f, const char *label, const sr_truth_errors *e)
{
    fprintf(f, "| %s | %llu | %llu | %llu | %.3g | %llu | %.3g | %.3g | %.3g |\n", label,
            (unsigned long long)e->depth_ties, (unsigned long long)e->edge_ties,
            (unsigned long long)e->wrong_triangle, e->edge_distance_max, (unsigned long long)e->coverage, e->z_max,
            e->z_p999, e->z_median);
}
