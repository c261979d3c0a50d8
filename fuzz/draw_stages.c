/* fuzz/draw_stages.c — stages 2 to 6 redone by hand for a scene (assembly,
 * outcodes, clipping against an exact reference area, the viewport), checked
 * against the counts sr_draw reported. */
#include "fuzz_draw.h"

/* 06_viewport.h: a vertex with w below 2^-128 is refused (1/w overflows). */
#define VIEWPORT_MIN_W 0x1p-128
/* It also refuses one whose varying/w overflows float, which a finite
 * varying does for w up to |varying|·2^-128 (06_viewport.h only names the
 * w < 2^-128 case). */
bool viewport_may_refuse(const float *v, int varyings)
{
    if (v[SR_W] < VIEWPORT_MIN_W)
        return true;
    for (int k = 0; k < varyings; k++)
        if (fabs((double)v[SR_VARYINGS_AT + k]) / v[SR_W] > FLT_MAX)
            return true;
    return false;
}

/* The reference clip's vertices must stay well clear of that. */
#define REFERENCE_MIN_W 0x1p-120
/* What the pipeline keeps of a triangle must cover the part of the screen
 * the exact clip covers (clip.h: adaptive keeps every cut vertex within
 * SR_CLIP_DEFAULT_TOLERANCE in NDC of it), in NDC area (the screen is 4). */
#define AREA_ABS_TOL 1e-4
#define AREA_REL_TOL 1e-4

/* Shoelace area of a clip-space polygon's NDC (x/w, y/w) outline; NAN if a
 * vertex has w too small to divide by. */
static double ndc_area(const sr_polygon *p)
{
    double twice = 0.0;
    for (int i = 0; i < p->count; i++) {
        const float *a = p->vert[i].v, *b = p->vert[(i + 1) % p->count].v;
        if (!(a[SR_W] >= REFERENCE_MIN_W))
            return NAN;
        twice += ((double)a[SR_X] / a[SR_W]) * ((double)b[SR_Y] / b[SR_W]) -
                 ((double)b[SR_X] / b[SR_W]) * ((double)a[SR_Y] / a[SR_W]);
    }
    return fabs(twice) * 0.5;
}

/* The NDC area of the exact clip of tri with every input coordinate moved
 * one ulp (up, down, or alternating), the largest change: how much the
 * float quantisation of the input alone decides. Near the eye a triangle
 * can be so ill-conditioned that this is large, and no float clipper can do
 * better; elsewhere it is tiny. */
static double exact_area(const sr_polygon *tri, unsigned planes, const sr_clip_depth *depth)
{
    sr_polygon ref = *tri;
    sr_clip_polygon(&ref, planes, SR_VARYINGS_AT, &(sr_clip_config){ .precision = SR_CLIP_EXACT, .depth = *depth });
    return ref.count >= 3 ? ndc_area(&ref) : 0.0;
}

static double area_sensitivity(const sr_polygon *tri, unsigned planes, const sr_clip_depth *depth, double area)
{
    double worst = 0.0;
    for (int pattern = 0; pattern < 3; pattern++) {
        sr_polygon moved = *tri;
        for (int i = 0; i < 3; i++)
            for (int k = 0; k < 4; k++) {
                bool up = pattern == 0 || (pattern == 2 && (i + k) % 2 == 0);
                float *c = &moved.vert[i].v[k];
                *c = nextafterf(*c, up ? INFINITY : -INFINITY);
                if (!isfinite(*c))
                    return INFINITY;
            }
        double a = exact_area(&moved, planes, depth);
        worst = isnan(a) ? INFINITY : fmax(worst, fabs(a - area));
    }
    return worst;
}

/* Compares what the pipeline draws of triangle `tri` (the clipper's `got`,
 * nothing if the viewport refuses one of its vertices) with the exact clip
 * (SR_CLIP_EXACT: exact expansions, rounded once), allowing for what one
 * ulp of input changes (area_sensitivity). Skipped when the exact clip
 * lands in the documented refusal zone of tiny w. */
/* The NDC perimeter of a polygon (NaN where a w is too small to divide). */
static double ndc_perimeter(const sr_polygon *p)
{
    double sum = 0.0;
    for (int i = 0; i < p->count; i++) {
        const float *a = p->vert[i].v, *b = p->vert[(i + 1) % p->count].v;
        sum += hypot((double)a[SR_X] / a[SR_W] - (double)b[SR_X] / b[SR_W],
                     (double)a[SR_Y] / a[SR_W] - (double)b[SR_Y] / b[SR_W]);
    }
    return sum;
}

/* vertex_tolerance: the NDC error the clipper may leave in a cut vertex
 * (the adaptive mode's tolerance; 0 for exact), which moves the area by at
 * most twice the perimeter times it. */
void check_clip_area(const sr_polygon *tri, unsigned planes, const sr_polygon *got, double vertex_tolerance,
                            const sr_clip_depth *depth, const char *what)
{
    double want = exact_area(tri, planes, depth);
    if (isnan(want))
        return;
    bool drawn = got->count >= 3;
    for (int i = 0; i < got->count && drawn; i++) {
        sr_screen_vertex sv;
        drawn = map_vertex(&got->vert[i], 0, MAX_SIDE, MAX_SIDE, depth, &sv);
    }
    double have = drawn ? ndc_area(got) : 0.0;
    double promised = drawn ? 2.0 * ndc_perimeter(got) * vertex_tolerance : 0.0;
    double tolerance = AREA_ABS_TOL + AREA_REL_TOL * want + (isfinite(promised) ? promised : 0.0);
    if (fabs(have - want) <= tolerance)
        return;
    double sensitivity = area_sensitivity(tri, planes, depth, want);
    bool close = fabs(have - want) <= tolerance + 4.0 * sensitivity;
    if (!close && !tolerated("clip_precision")) {
        sr_polygon ref = *tri;
        sr_clip_polygon(&ref, planes, SR_VARYINGS_AT, &(sr_clip_config){ .precision = SR_CLIP_EXACT, .depth = *depth });
        print_polygon("triangle in clip space", tri, SR_VARYINGS_AT);
        print_polygon(drawn ? "clipped" : "clipped (dropped: refused or empty)", got, SR_VARYINGS_AT);
        print_polygon("exact clip", &ref, SR_VARYINGS_AT);
    }
    CHECK_KNOWN("clip_precision", close,
                "%s: the pipeline draws NDC area %.9g of this triangle, an exact clip %.9g (one input ulp moves "
                "it by %.3g)", what, have, want, sensitivity);
}

static void matrix_or_identity(const mat4 m, mat4 out)
{
    if (matrix_is_zero(m))
        glm_mat4_identity(out);
    else
        glm_mat4_copy((vec4 *)m, out);
}

/* Stages 1 to 6 again through their public headers, triangle by triangle:
 * what the clipper leaves of a triangle the pipeline clips, the viewport
 * stage must accept (06_viewport.h: all but w < 2^-128), and it must cover
 * what an exact clip covers (check_clip_area). Also ties sr_stats.rejected
 * to the stages: outcode and non-finite rejections plus refused polygons. */
void check_stages(const scene *sc, const sr_stats *stats)
{
    const sr_mesh *m = &sc->mesh;
    if (!sc->indices_valid)
        return;
    mat4 world, view, projection;
    matrix_or_identity(sc->world, world);
    matrix_or_identity(sc->view, view);
    matrix_or_identity(sc->projection, projection);
    sr_vertex_transform xf;
    sr_vertex_make_transform(world, view, projection, &xf);
    sr_varying_layout layout = sr_vertex_layout(SR_SHADE_ID, m, false);
    sr_vertex_out verts[MAX_VERTS];
    sr_vertex_run(m, &xf, &layout, 0, m->vertex_count, verts);
    /* A vertex inside every plane is mapped once, up front; one the viewport
     * refuses drops every triangle that uses it (draw.c counts those as
     * non-finite). */
    unsigned codes[MAX_VERTS];
    sr_clip_depth depth = sr_clip_depth_of((const float(*)[4])projection);
    for (uint32_t i = 0; i < m->vertex_count; i++) {
        sr_screen_vertex sv;
        codes[i] = sr_clip_outcode_with(verts[i].v, &depth);
        if (codes[i] == 0 && !map_vertex(&verts[i], 0, sc->width, sc->height, &depth, &sv))
            codes[i] = SR_OUT_NONFINITE;
    }
    /* The draw's default clip: adaptive, within half a subpixel step in NDC
     * of the framebuffer's longer side (draw.c). */
    int side = sc->width > sc->height ? sc->width : sc->height;
    sr_clip_config cfg = { .precision = SR_CLIP_ADAPTIVE, .ndc_tolerance = 1.0 / ((double)SR_SUBPIXEL_ONE * side),
                           .depth = depth };
    uint64_t rejected = 0;
    for (uint32_t k = 0; k < slot_count(m); k++) {
        uint32_t t[3];
        if (!slot_triangle(m, k, t))
            continue;
        unsigned c0 = codes[t[0]], c1 = codes[t[1]], c2 = codes[t[2]];
        if (((c0 | c1 | c2) & SR_OUT_NONFINITE) || (c0 & c1 & c2)) {
            rejected++;
            continue;
        }
        sr_polygon poly = { .count = 3, .vert = { verts[t[0]], verts[t[1]], verts[t[2]] } };
        sr_polygon in = poly;
        if (c0 | c1 | c2)
            sr_clip_polygon(&poly, c0 | c1 | c2, SR_VARYINGS_AT, &cfg);
        bool refused = false;
        for (int i = 0; i < poly.count; i++) {
            sr_screen_vertex sv;
            if (!map_vertex(&poly.vert[i], 0, sc->width, sc->height, &depth, &sv)) {
                refused = true;
                if (viewport_may_refuse(poly.vert[i].v, 0))
                    continue;
                if (!tolerated("clip_precision")) {
                    print_polygon("triangle in clip space", &in, SR_VARYINGS_AT);
                    print_polygon("clipped", &poly, SR_VARYINGS_AT);
                }
                CHECK_KNOWN("clip_precision", false,
                            "triangle %u: clipped vertex %d (%a, %a, %a, %a) is refused by the viewport", k, i,
                            poly.vert[i].v[SR_X], poly.vert[i].v[SR_Y], poly.vert[i].v[SR_Z], poly.vert[i].v[SR_W]);
            }
        }
        char what[32];
        snprintf(what, sizeof what, "triangle %u", k);
        check_clip_area(&in, c0 | c1 | c2, &poly, cfg.ndc_tolerance, &depth, what);
        rejected += refused;
    }
    CHECK(stats->rejected == rejected || tolerated("clip_precision"),
          "sr_draw rejected %llu triangles, its stages %llu", (unsigned long long)stats->rejected,
          (unsigned long long)rejected);
}
