/* Writes docs/stability.md from a run's numbers, and the plot beside it. */
#include <math.h>
#include <stdio.h>

#include "doc_file.h"
#include "core/clock.h"
#include "stability_doc.h"
#include "stability_svg.h"

#define LARGE_CLIP_ERROR 1e-3 /* NDC: half a pixel on a 1000-pixel screen */

static int clipper_index(sr_clip_precision p)
{
    for (int k = 0; k < SR_STABILITY_CLIPPERS; k++)
        if (sr_stability_clippers[k].precision == p)
            return k;
    return 0;
}

static const char *const MAPPING_NAMES[SR_STABILITY_MAPPINGS] = { "standard", "reversed" };

static void write_intro(FILE *f, const sr_stability_report *r)
{
    fprintf(f, "# Numerical stability under stiff cameras\n\n"
               "Regenerate: `./build/softrast bench --stability` from the project's root; it writes this file\n"
               "and [stability.svg](stability.svg) (`--report-dir DIR` writes them elsewhere). This run took %.0f s\n"
               "on this machine. Every number below comes from that run; nothing is edited by hand.\n\n"
               "The stiff cases (cameras: 60° vertical fov, %dx%d; every grid is %s):\n\n"
               "| case | camera and grid | random triangles (section 1) |\n| --- | --- | --- |\n",
            r->seconds, SR_STABILITY_WIDTH, SR_STABILITY_HEIGHT, "64×64 quads");
    const sr_stability_case *cases = sr_stability_cases();
    for (int i = 0; i < SR_STABILITY_CASES; i++)
        fprintf(f, "| %s | %s | %s |\n", cases[i].name, cases[i].what, cases[i].triangles);
}

static double worst_over_cases(const sr_stability_report *r, int clipper)
{
    double worst = 0.0;
    for (int i = 0; i < SR_STABILITY_CASES; i++)
        worst = r->clip[i][clipper].max > worst ? r->clip[i][clipper].max : worst;
    return worst;
}

/* A table's head: the leading columns (`lead`, aligned by `rule`), then one
 * right-aligned column per clipper, titled by its name and `suffix`. */
static void write_table_head(FILE *f, const char *lead, const char *suffix, const char *rule)
{
    fprintf(f, "\n| %s |", lead);
    for (int k = 0; k < SR_STABILITY_CLIPPERS; k++)
        fprintf(f, " %s%s |", sr_stability_clippers[k].name, suffix);
    fprintf(f, "\n| %s |", rule);
    for (int k = 0; k < SR_STABILITY_CLIPPERS; k++)
        fprintf(f, " ---: |");
}

static void write_clip_table(FILE *f, const sr_stability_report *r)
{
    write_table_head(f, "case | triangles", ": max / p99", "--- | ---:");
    for (int i = 0; i < SR_STABILITY_CASES; i++) {
        fprintf(f, "\n| %s | %llu |", sr_stability_cases()[i].name, (unsigned long long)r->clip[i][0].triangles);
        for (int k = 0; k < SR_STABILITY_CLIPPERS; k++)
            fprintf(f, " %.2g / %.2g |", r->clip[i][k].max, r->clip[i][k].p99);
    }
    fprintf(f, "\n");
}

static void write_worst_cut(FILE *f, const sr_stability_clip_stats *s)
{
    fprintf(f, " %.2g: w %.2g, ends %.1e× |", s->max, s->worst_w, s->worst_spread);
}

/* Triangles lost, the default's mix of precisions, and where the fixed
 * precisions fail worst. */
static void write_cut_table(FILE *f, const sr_stability_report *r)
{
    int dbl = clipper_index(SR_CLIP_DOUBLE), flt = clipper_index(SR_CLIP_FLOAT);
    fprintf(f, "\n| case |");
    for (int k = 0; k < SR_STABILITY_CLIPPERS; k++)
        fprintf(f, " lost by %s |", sr_stability_clippers[k].name);
    fprintf(f, " default's cuts in float / double / exact | double's worst cut | float's worst cut |\n| --- |");
    for (int k = 0; k < SR_STABILITY_CLIPPERS + 3; k++)
        fprintf(f, " ---: |");
    for (int i = 0; i < SR_STABILITY_CASES; i++) {
        const sr_clip_counts *cuts = &r->clip[i][0].cuts;
        double all = (double)(cuts->cuts[SR_CLIP_FLOAT] + cuts->cuts[SR_CLIP_DOUBLE] + cuts->cuts[SR_CLIP_EXACT]);
        fprintf(f, "\n| %s |", sr_stability_cases()[i].name);
        for (int k = 0; k < SR_STABILITY_CLIPPERS; k++)
            fprintf(f, " %llu |", (unsigned long long)r->clip[i][k].lost);
        fprintf(f, " %.1f%% / %.1f%% / %.1f%% |", 100.0 * cuts->cuts[SR_CLIP_FLOAT] / all,
                100.0 * cuts->cuts[SR_CLIP_DOUBLE] / all, 100.0 * cuts->cuts[SR_CLIP_EXACT] / all);
        write_worst_cut(f, &r->clip[i][dbl]);
        write_worst_cut(f, &r->clip[i][flt]);
    }
    fprintf(f, "\n");
}

/* The largest share of cuts the default sent to the exact path, over cases. */
static double most_exact_share(const sr_stability_report *r)
{
    double most = 0.0;
    for (int i = 0; i < SR_STABILITY_CASES; i++) {
        const sr_clip_counts *c = &r->clip[i][0].cuts;
        double all = (double)(c->cuts[SR_CLIP_FLOAT] + c->cuts[SR_CLIP_DOUBLE] + c->cuts[SR_CLIP_EXACT]);
        most = fmax(most, (double)c->cuts[SR_CLIP_EXACT] / all);
    }
    return most;
}

/* The cases where a clipper's largest error passes LARGE_CLIP_ERROR, as a list. */
static int list_large(FILE *f, const sr_stability_report *r, int clipper)
{
    int n = 0;
    for (int i = 0; i < SR_STABILITY_CASES; i++)
        if (r->clip[i][clipper].max > LARGE_CLIP_ERROR)
            fprintf(f, "%s%s (%.2g)", n++ ? ", " : "", sr_stability_cases()[i].name, r->clip[i][clipper].max);
    if (!n)
        fprintf(f, "none");
    return n;
}

static void write_clip_section(FILE *f, const sr_stability_report *r)
{
    fprintf(f, "\n## 1. Clipped-vertex error\n\n"
               "Per case, random triangles (fixed seed) that cross at least one plane, transformed to clip space\n"
               "in float by the camera's P·V (cglm) as the vertex stage does, are clipped against the planes\n"
               "their outcodes name by `sr_clip_polygon`. Every cut vertex it makes (its trace hook hands each\n"
               "over) is compared with the exact cut of the same float edge by the same plane,\n"
               "v = (d_in·b − d_out·a) / (d_in − d_out), or, for a corner (the default and exact cut a\n"
               "triangle on two planes or more from its own vertices, docs/precision.md), with the\n"
               "triangle's exact point on both planes, Σ c_k·v_k / Σ c_k, c = P × Q of the vertices'\n"
               "distances; both sums and all products carried error-free (two-sum, fma) and one rounding at\n"
               "the end (long double).\n"
               "**Metric:** e = max(|Δx|, |Δy|, |Δz|, |Δw|) / max(|x|, |y|, |z|, |w|) of the exact vertex. Inside\n"
               "the clip volume the denominator is |w|, so e is an NDC-sized error: the vertex moves by at most\n"
               "e·W pixels on a W-pixel screen (e ≤ %.1e is below half a 1/256 subpixel step at 1920 px, the\n"
               "tolerance the default gets here); a cut that later planes clip away may have |x| ≫ w, and there\n"
               "e is the plain relative error. A triangle's error is its worst cut's; *max* and *p99* are over\n"
               "triangles. Float rounding alone is 2^-24 ≈ 6.0e-8.\n",
            sr_stability_clip_tolerance());
    write_clip_table(f, r);
    double def = worst_over_cases(r, 0), tolerance = sr_stability_clip_tolerance();
    fprintf(f, "\n**What it means:** over all cases the largest error is %.2g for the default", def);
    for (int k = 1; k < SR_STABILITY_CLIPPERS; k++)
        fprintf(f, ", %.2g for %s (%.2g× the default's)", worst_over_cases(r, k), sr_stability_clippers[k].name,
                worst_over_cases(r, k) / def);
    fprintf(f, ". The default %s its tolerance (%.1e) in every case, so it is the clipper to use; the\n"
               "price is exact arithmetic on the cuts that need it (at most %.0f%% of the cuts in these\n"
               "deliberately hostile triangle sets, table below). An error of 1 means the cut kept no correct\n"
               "digit. Cases where a fixed precision errs by more than %g — double: ",
            def <= tolerance ? "stays within" : "exceeds", tolerance, 100.0 * most_exact_share(r), LARGE_CLIP_ERROR);
    list_large(f, r, clipper_index(SR_CLIP_DOUBLE));
    fprintf(f, "; float: ");
    list_large(f, r, clipper_index(SR_CLIP_FLOAT));
    fprintf(f, ".\n\nWhere the large errors come from (the last two columns: each fixed precision's worst cut, the\n"
               "exact cut's w, and how many times larger than the cut vertex the edge's end points are): the\n"
               "cut of an edge whose end points are many orders of magnitude larger than the cut vertex. The\n"
               "watertight rule starts every cut at the inside end, so with the inside end at |w| ≈ 1e10 and the\n"
               "cut at w ≈ near = 1e-6, a + t·(b − a) has t ≈ 1 − 1e-16 and cancels ~16 digits: double keeps\n"
               "none, float none from 1e7 on. The cut can land at w ≤ 0 and the polygon is then dropped (*lost*:\n"
               "clipped to nothing where the exact clipper keeps a polygon).\n");
    write_cut_table(f, r);
}

static const char *const GRID_NAMES[SR_STABILITY_GRIDS] = { "even", "graded" };

static void total_hits(const sr_stability_report *r, int clipper, uint64_t *holes, uint64_t *doubles)
{
    *holes = *doubles = 0;
    for (int i = 0; i < SR_STABILITY_CASES; i++) {
        for (int g = 0; g < SR_STABILITY_GRIDS; g++) {
            *holes += r->hits[i][g][clipper].holes;
            *doubles += r->hits[i][g][clipper].double_hits;
        }
    }
}

static void write_hits_table(FILE *f, const sr_stability_report *r)
{
    write_table_head(f, "case | grid | inside pixels | fan triangles drawn", "", "--- | --- | ---: | ---:");
    for (int i = 0; i < SR_STABILITY_CASES; i++) {
        for (int g = 0; g < SR_STABILITY_GRIDS; g++) {
            const sr_stability_hits *h = r->hits[i][g];
            if (!h[0].measured)
                continue;
            fprintf(f, "\n| %s | %s | %llu | %llu |", sr_stability_cases()[i].name, GRID_NAMES[g],
                    (unsigned long long)h[0].inside, (unsigned long long)h[0].stats.drawn);
            for (int k = 0; k < SR_STABILITY_CLIPPERS; k++)
                fprintf(f, " %llu / %llu |", (unsigned long long)h[k].holes, (unsigned long long)h[k].double_hits);
        }
    }
    fprintf(f, "\n");
}

/* Every grid and clipper with holes, as a list. */
static void list_holes(FILE *f, const sr_stability_report *r)
{
    int listed = 0;
    for (int i = 0; i < SR_STABILITY_CASES; i++) {
        for (int g = 0; g < SR_STABILITY_GRIDS; g++) {
            for (int k = 0; k < SR_STABILITY_CLIPPERS; k++) {
                const sr_stability_hits *h = &r->hits[i][g][k];
                if (h->measured && h->holes)
                    fprintf(f, "%s %s, %s grid, %s: %llu of %llu", listed++ ? ";" : "", sr_stability_cases()[i].name,
                            GRID_NAMES[g], sr_stability_clippers[k].name, (unsigned long long)h->holes,
                            (unsigned long long)h->inside);
            }
        }
    }
    fprintf(f, "%s", listed ? "" : " none");
}

static void write_hits_section(FILE *f, const sr_stability_report *r)
{
    fprintf(f, "\n## 2. Cracks and double hits\n\n"
               "Each case draws a flat grid of 64×64 quads (`sr_mesh_alloc`, 8192 triangles, front faces toward\n"
               "the eye, back faces culled as by default) once per clipper: with *even* cells (the cells around\n"
               "the eye are then huge, the clipper's hardest input) and, where the grid spans many decades,\n"
               "*graded* cells that grow geometrically from the centre (so hundreds of cells and their shared\n"
               "edges reach the screen). The draw counts hits (`sr_draw_study.count_hits`): every pixel a fan\n"
               "triangle covers adds 1 to its color, with the rasterizer's own coverage and no depth test, so\n"
               "nothing hides anything and this counts coverage. *Inside* pixels: the rays through the pixel centre and\n"
               "through the 8 points 1 px away around it all meet the grid's plane within its extent and between\n"
               "near and far (in double, from the camera and the plane, not from the pipeline); the visible grid\n"
               "is convex on screen, so such a pixel is at least 1 px from its outline. Each clipper's cell is\n"
               "*holes (inside, hit 0 times) / double hits (anywhere, hit ≥ 2 times)*; watertight is 0 / 0.\n");
    write_hits_table(f, r);
    fprintf(f, "\n**What it means:**");
    for (int k = 0; k < SR_STABILITY_CLIPPERS; k++) {
        uint64_t holes, doubles;
        total_hits(r, k, &holes, &doubles);
        fprintf(f, "%s %s: %llu holes and %llu double hits in all", k ? ";" : "", sr_stability_clippers[k].name,
                (unsigned long long)holes, (unsigned long long)doubles);
    }
    fprintf(f, ". A hole is a crack between neighbours or a part of a triangle the clipper lost to a wrong\n"
               "cut (section 1); the fan-triangle counts tell which: a crack leaves them unchanged. Holes:");
    list_holes(f, r);
    fprintf(f, ".\n");
}

static void write_depth_cell(FILE *f, double v)
{
    if (isnan(v))
        fprintf(f, " — |");
    else
        fprintf(f, " %.1e |", v);
}

static void write_depth_table(FILE *f, const sr_stability_depth *d)
{
    fprintf(f, "\n| far/near |");
    for (int k = 0; k < SR_STABILITY_DISTANCES; k++)
        for (int m = 0; m < SR_STABILITY_MAPPINGS; m++)
            fprintf(f, " %g%%: %s |", 100.0 * d->fraction[k], MAPPING_NAMES[m]);
    fprintf(f, "\n| ---: |");
    for (int k = 0; k < SR_STABILITY_DISTANCES * SR_STABILITY_MAPPINGS; k++)
        fprintf(f, " ---: |");
    for (int r = 0; r < SR_STABILITY_RATIOS; r++) {
        fprintf(f, "\n| 1e%d |", (int)lround(log10(d->ratio[r])));
        for (int k = 0; k < SR_STABILITY_DISTANCES; k++)
            for (int m = 0; m < SR_STABILITY_MAPPINGS; m++)
                write_depth_cell(f, d->separation[r][k][m]);
    }
    fprintf(f, "\n");
}

#define FLOAT_STEP 0x1.0p-24 /* relative spacing of floats just below 1 */

typedef struct depth_findings {
    double median_gain;       /* standard / reversed, over cells both order */
    double reversed_steps;    /* reversed's worst, in float steps of d */
    double theory_lo, theory_hi; /* standard / (FLOAT_STEP·d/near), over ordered cells */
    int unordered;            /* standard cells with no ordered separation */
} depth_findings;

/* Standard z_ndc = (1 − near/d)·far/(far − near) moves near/d² per unit
 * of d, so one float step of depth spans s/d ≈ FLOAT_STEP·d/near. */
static depth_findings depth_summary(const sr_stability_depth *d)
{
    depth_findings out = { .theory_lo = INFINITY };
    double gains[SR_STABILITY_RATIOS * SR_STABILITY_DISTANCES];
    int n = 0;
    for (int r = 0; r < SR_STABILITY_RATIOS; r++) {
        for (int k = 0; k < SR_STABILITY_DISTANCES; k++) {
            double std = d->separation[r][k][0], rev = d->separation[r][k][1];
            out.unordered += isnan(std);
            out.reversed_steps = fmax(out.reversed_steps, rev / d->floor[r][k]);
            if (isnan(std))
                continue;
            double theory = std / (FLOAT_STEP * d->distance[r][k]);
            out.theory_lo = fmin(out.theory_lo, theory);
            out.theory_hi = fmax(out.theory_hi, theory);
            if (!isnan(rev))
                gains[n++] = std / rev;
        }
    }
    sr_sort_doubles(gains, (size_t)n);
    out.median_gain = n ? gains[n / 2] : NAN;
    return out;
}

static void write_depth_section(FILE *f, const sr_stability_depth *d)
{
    depth_findings s = depth_summary(d);
    fprintf(f, "\n## 3. Depth precision\n\n"
               "Two planes facing the camera (`sr_shape_quads`) at view depths d and d + s; near = 1, far = the\n"
               "ratio, d at 1%%, 10%%, 50%% and 90%% of the way from near to far. Each cell is the smallest s/d for\n"
               "which, in a 16x16 `SR_SHADE_ID` draw through `sr_draw`, the nearer plane's ids fill every pixel\n"
               "when it is drawn first and when it is drawn second, and the farther plane alone fills the view\n"
               "(its depth must not round to the clear value). It is found by bisection, and a separation counts\n"
               "only if it holds with the pair slid to 16 positions over twice its width (otherwise a tiny s\n"
               "passes whenever a rounding boundary happens to fall between the planes). *standard* is the\n"
               "default mapping (near → 0, LESS); *reversed* sets `camera.reversed_z` and `fb.reversed_z` (near\n"
               "→ 1, GREATER). s is what the float vertex positions hold, so no cell can go below one float step\n"
               "of d (6e-8 to 1.2e-7 of d). — : not ordered for any s up to d.\n");
    write_depth_table(f, d);
    fprintf(f, "\n**What it means:** the standard mapping needs s/d ≈ 2^-24·d/near (one float step of depth\n"
               "near z = 1; the measured cells are %.1f to %.1f times that), so it worsens tenfold per decade of\n"
               "distance and orders nothing in %d of %d cells. Reversed z needs at most %.1f float steps of d in\n"
               "every cell: the limit is the vertex positions, not the depth buffer. Where both order the planes,\n"
               "reversed z separates them %.0f× closer (median over those cells). Use reversed z whenever\n"
               "far/near is large.\n\n"
               "![smallest ordered separation against far/near](stability.svg)\n",
            s.theory_lo, s.theory_hi, s.unordered, SR_STABILITY_RATIOS * SR_STABILITY_DISTANCES, s.reversed_steps,
            s.median_gain);
}

static bool write_markdown(const char *path, const sr_stability_report *r, sr_error *err)
{
    sr_doc doc;
    if (!sr_doc_open(&doc, path, err))
        return false;
    FILE *f = doc.f;
    write_intro(f, r);
    write_clip_section(f, r);
    write_hits_section(f, r);
    write_depth_section(f, &r->depth);
    return sr_doc_close(&doc, err);
}

bool sr_stability_files(const char *dir, const sr_stability_report *r, sr_error *err)
{
    char md[1024], svg[1024];
    snprintf(md, sizeof md, "%s/stability.md", dir);
    snprintf(svg, sizeof svg, "%s/stability.svg", dir);
    return write_markdown(md, r, err) && sr_stability_svg(svg, &r->depth, err);
}
