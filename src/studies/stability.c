/* softrast bench --stability: runs the three measurements of stability.h and
 * writes the report. Progress goes to stderr, one line per case. */
#include <stdio.h>

#include "core/clock.h"
#include "stability.h"
#include "stability_doc.h"

static void print_case(const sr_stability_case *c, const sr_stability_report *r, int i)
{
    fprintf(stderr, "stability: %s\n", c->name);
    for (int k = 0; k < SR_STABILITY_CLIPPERS; k++) {
        const sr_stability_clip_stats *s = &r->clip[i][k];
        fprintf(stderr, "  %-20s clip error max %.3g p99 %.3g, lost %llu; holes / double hits / fan triangles:",
                sr_stability_clippers[k].name, s->max, s->p99, (unsigned long long)s->lost);
        for (int g = 0; g < SR_STABILITY_GRIDS; g++) {
            const sr_stability_hits *h = &r->hits[i][g][k];
            if (h->measured)
                fprintf(stderr, " %llu / %llu / %llu of %llu;", (unsigned long long)h->holes,
                        (unsigned long long)h->double_hits, (unsigned long long)h->stats.drawn,
                        (unsigned long long)h->inside);
        }
        fprintf(stderr, "\n");
    }
}

static bool run_cases(sr_stability_report *r, sr_error *err)
{
    const sr_stability_case *cases = sr_stability_cases();
    for (int i = 0; i < SR_STABILITY_CASES; i++) {
        if (!sr_stability_clip_errors(&cases[i], r->clip[i], err))
            return false;
        for (int g = 0; g < SR_STABILITY_GRIDS; g++)
            for (int k = 0; k < SR_STABILITY_CLIPPERS; k++)
                if (!sr_stability_grid_hits(&cases[i], g == 1, &sr_stability_clippers[k], &r->hits[i][g][k], err))
                    return false;
        print_case(&cases[i], r, i);
    }
    return true;
}

bool sr_stability_write(const char *dir, sr_error *err)
{
    static sr_stability_report r; /* large; one run at a time */
    double start = sr_now_ms();
    r = (sr_stability_report){ 0 };
    if (!run_cases(&r, err))
        return false;
    fprintf(stderr, "stability: depth table\n");
    if (!sr_stability_depth_table(&r.depth, err))
        return false;
    r.seconds = (sr_now_ms() - start) * 1e-3;
    fprintf(stderr, "stability: %.1f s\n", r.seconds);
    return sr_stability_files(dir, &r, err);
}
