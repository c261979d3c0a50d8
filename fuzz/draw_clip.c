/* fuzz/draw_clip.c — the clipper on its own: three clip-space vertices and a
 * plane mask, clipped in each precision and both walk directions. */
#include "fuzz_draw.h"
#include "pipeline/04_clip/clip_segment.h"

/* w first, then x, y, z each either free or on a plane through w (tag
 * 0xE0–0xFF: ±w, a few ulps off), then the varyings. All finite: the
 * pipeline never hands the clipper anything else. */
static void take_clip_vertex(reader *r, sr_vertex_out *v, int varyings)
{
    memset(v, 0, sizeof *v);
    float w = take_finite_float(r);
    v->v[SR_W] = w;
    for (int k = SR_X; k <= SR_Z; k++) {
        r->prev = w;
        v->v[k] = take_finite_float(r);
    }
    for (int k = 0; k < varyings; k++)
        v->v[SR_VARYINGS_AT + k] = take_finite_float(r);
}

static bool vertices_identical(const sr_vertex_out *a, const sr_vertex_out *b, int floats)
{
    return memcmp(a->v, b->v, (size_t)floats * sizeof(float)) == 0;
}

/* True if b is a rotation of a (reversed: of a read backwards), bit for bit. */
static bool same_cycle(const sr_polygon *a, const sr_polygon *b, bool reversed, int floats)
{
    if (a->count != b->count)
        return false;
    int n = a->count;
    if (n == 0)
        return true;
    for (int shift = 0; shift < n; shift++) {
        bool all = true;
        for (int i = 0; i < n && all; i++) {
            int j = reversed ? ((shift - i) % n + n) % n : (shift + i) % n;
            all = vertices_identical(&a->vert[i], &b->vert[j], floats);
        }
        if (all)
            return true;
    }
    return false;
}

void print_polygon(const char *name, const sr_polygon *p, int floats)
{
    fprintf(stderr, "  %s (%d vertices):\n", name, p->count);
    for (int i = 0; i < p->count; i++) {
        fprintf(stderr, "   ");
        for (int k = 0; k < floats; k++)
            fprintf(stderr, " %a", p->vert[i].v[k]);
        fprintf(stderr, "\n");
    }
}

/* Each edge of the triangle clipped as a segment (clip_segment.h): the
 * same ends whichever way it runs; and under adaptive and exact precision,
 * for each polygon edge on a triangle edge, that edge's segment keeps the
 * same ends, bit for bit (x, y, w; z too, with no depth model). */
static void check_segments(const sr_polygon *in, const sr_polygon *out, const sr_clip_config *cfg, bool exact,
                           bool by_edge, int floats)
{
    for (int e = 0; e < 3; e++) {
        const sr_vertex_out ends[2] = { in->vert[e], in->vert[(e + 1) % 3] }, back[2] = { ends[1], ends[0] };
        unsigned planes = (sr_clip_outcode(ends[0].v) | sr_clip_outcode(ends[1].v)) & SR_OUT_PLANES;
        sr_vertex_out got[2], got_back[2];
        int cut[2], cut_back[2];
        bool kept = sr_clip_segment(ends, planes, floats, cfg, got, cut);
        bool kept_back = sr_clip_segment(back, planes, floats, cfg, got_back, cut_back);
        CHECK(kept == kept_back && (!kept || (vertices_identical(&got[0], &got_back[1], floats) &&
                                               vertices_identical(&got[1], &got_back[0], floats))),
              "edge %d clips differently backwards (kept %d, %d)", e, kept, kept_back);
        for (int i = 0; exact && !by_edge && i < out->count; i++) {
            if (out->line[i] != e)
                continue;
            const sr_vertex_out *want[2] = { &out->vert[i], &out->vert[(i + 1) % out->count] };
            CHECK(kept, "edge %d: the triangle keeps a piece, the segment none", e);
            for (int k = 0; k < 2; k++)
                CHECK(memcmp(&got[k].v[SR_X], &want[k]->v[SR_X], 2 * sizeof(float)) == 0 &&
                          got[k].v[SR_W] == want[k]->v[SR_W] && got[k].v[SR_Z] == want[k]->v[SR_Z],
                      "edge %d end %d: segment (%a %a %a %a), triangle (%a %a %a %a)", e, k, got[k].v[0],
                      got[k].v[1], got[k].v[2], got[k].v[3], want[k]->v[0], want[k]->v[1], want[k]->v[2],
                      want[k]->v[3]);
        }
    }
}

void fuzz_clip(reader *r)
{
    uint8_t mode = take_u8(r);
    int varyings = ((mode >> 1) & 0x1F) % (SR_MAX_VARYINGS + 1);
    /* Adaptive (the default) and exact promise accurate cut vertices; float
     * and double are knobs for measuring what accuracy costs, promised
     * nothing but the structural checks. */
    sr_clip_config cfg = { .precision = (sr_clip_precision)(mode >> 6) };
    sr_clip_precision precision = cfg.precision;
    bool exact = precision == SR_CLIP_ADAPTIVE || precision == SR_CLIP_EXACT;
    int floats = SR_VARYINGS_AT + varyings;
    sr_polygon in;
    memset(&in, 0, sizeof in);
    in.count = 3;
    for (int i = 0; i < 3; i++)
        take_clip_vertex(r, &in.vert[i], varyings);
    unsigned c0 = sr_clip_outcode(in.vert[0].v), c1 = sr_clip_outcode(in.vert[1].v),
             c2 = sr_clip_outcode(in.vert[2].v);
    bool as_pipeline = !(mode & 1); /* the mask the draw call would pass */
    unsigned planes = as_pipeline ? (c0 | c1 | c2) & SR_OUT_PLANES : take_u8(r) & SR_OUT_PLANES;
    if (as_pipeline && (c0 & c1 & c2))
        return; /* the pipeline rejects these without clipping */

    sr_polygon out = in, rotated = in, reversed = in;
    for (int i = 0; i < 3; i++) {
        rotated.vert[i] = in.vert[(i + 1) % 3];
        reversed.vert[i] = in.vert[2 - i];
    }
    sr_clip_counts counts = { { 0 } };
    cfg.counts = &counts;
    int n = sr_clip_polygon(&out, planes, floats, &cfg);
    bool by_edge = counts.edge_by_edge > 0; /* a degenerate triangle: not cut from its edges */
    sr_clip_polygon(&rotated, planes, floats, &cfg);
    sr_clip_polygon(&reversed, planes, floats, &cfg);
    if (as_pipeline)
        check_segments(&in, &out, &cfg, exact, by_edge, floats);

    CHECK(n == out.count, "returned %d, polygon holds %d", n, out.count);
    CHECK(n == 0 || (n >= 3 && n <= SR_MAX_CLIP_VERTS), "%d vertices", n);

    /* Watertight (DESIGN.md): every cut is made from the inside end toward
     * the outside one, so walking the triangle from another vertex or the
     * other way round gives the same vertices, bit for bit. */
    bool tight = same_cycle(&out, &rotated, false, floats) && same_cycle(&out, &reversed, true, floats);
    if (!tight) {
        print_polygon("input", &in, floats);
        print_polygon("clipped", &out, floats);
        print_polygon("clipped from v1", &rotated, floats);
        print_polygon("clipped backwards", &reversed, floats);
    }
    CHECK(tight, "clipping depends on the walk order (planes %#x)", planes);

    /* All three inside every plane asked for: the triangle comes back as it was. */
    bool all_inside = true, one_plane_all_outside = false;
    for (int p = 0; p < SR_CLIP_PLANES; p++) {
        if (!(planes & (1u << p)))
            continue;
        int outside = 0;
        for (int i = 0; i < 3; i++)
            outside += sr_clip_distance((sr_clip_plane)p, in.vert[i].v) < 0.0;
        all_inside &= outside == 0;
        one_plane_all_outside |= outside == 3;
    }
    /* (A vertex at w <= 0 inside every plane is the eye itself, and such a
     * polygon, seen edge-on, may be dropped: clip.c.) */
    bool w_positive = in.vert[0].v[SR_W] > 0.0f && in.vert[1].v[SR_W] > 0.0f && in.vert[2].v[SR_W] > 0.0f;
    if (all_inside)
        CHECK((n == 0 && !w_positive) || (n == 3 && same_cycle(&in, &out, false, floats)),
              "a triangle inside planes %#x came back with %d vertices", planes, n);
    if (one_plane_all_outside)
        CHECK(n == 0, "a triangle outside one of planes %#x left %d vertices", planes, n);

    /* Each coordinate of the output lies within the inputs' range (every
     * vertex is a convex combination of the inputs), up to rounding. */
    float lo[SR_VERTEX_FLOATS], hi[SR_VERTEX_FLOATS];
    double pos_scale = 0.0;
    for (int k = 0; k < floats; k++) {
        lo[k] = fminf(fminf(in.vert[0].v[k], in.vert[1].v[k]), in.vert[2].v[k]);
        hi[k] = fmaxf(fmaxf(in.vert[0].v[k], in.vert[1].v[k]), in.vert[2].v[k]);
        if (k < SR_VARYINGS_AT)
            pos_scale = fmax(pos_scale, fmax(fabs(lo[k]), fabs(hi[k])));
    }
    for (int i = 0; i < n; i++) {
        const float *v = out.vert[i].v;
        for (int k = 0; k < floats; k++) {
            /* Forced float evaluates b − a in float, which overflows for end
             * points of opposite sign near FLT_MAX (the adaptive choice goes
             * exact there): fuzz/regressions/draw/clip_float_difference_overflow. */
            if (precision == SR_CLIP_FLOAT && (double)hi[k] - lo[k] > FLT_MAX)
                continue;
            double scale = k < SR_VARYINGS_AT ? pos_scale : fmax(fabs(lo[k]), fabs(hi[k]));
            double tol = CLIP_RANGE_REL_TOL * scale;
            CHECK(isfinite(v[k]) && v[k] >= lo[k] - tol && v[k] <= hi[k] + tol,
                  "vertex %d float %d = %a outside the inputs' [%a, %a] (precision %d)", i, k, v[k], lo[k], hi[k],
                  precision);
        }
        double mag = fmax(fmax(fabs(v[SR_X]), fabs(v[SR_Y])), fmax(fabs(v[SR_Z]), fabs(v[SR_W])));
        for (int p = 0; p < SR_CLIP_PLANES && exact; p++) {
            if (!(planes & (1u << p)))
                continue;
            double d = sr_clip_distance((sr_clip_plane)p, v);
            if (!(d >= -CLIP_INSIDE_REL_TOL * mag) && !tolerated("clip_precision")) {
                print_polygon("input", &in, floats);
                print_polygon("clipped", &out, floats);
            }
            CHECK_KNOWN("clip_precision", d >= -CLIP_INSIDE_REL_TOL * mag,
                        "vertex %d is %a outside plane %d (magnitude %a, planes %#x)", i, -d, p, mag, planes);
        }
        /* What the pipeline clips, the viewport stage must accept
         * (06_viewport.h: all but w < 2^-128) and map without an inf or NaN
         * (DESIGN.md). */
        if (as_pipeline && exact && !viewport_may_refuse(v, varyings)) {
            sr_screen_vertex sv;
            bool mapped = map_vertex(&out.vert[i], varyings, MAX_SIDE, MAX_SIDE, &cfg.depth, &sv);
            if (!mapped && !tolerated("clip_precision")) {
                print_polygon("input", &in, floats);
                print_polygon("clipped", &out, floats);
            }
            if (!mapped && tolerated("clip_precision"))
                continue;
            CHECK_KNOWN("clip_precision", mapped, "vertex %d (%a, %a, %a, %a) left by the clipper is refused by the viewport",
                        i, v[SR_X], v[SR_Y], v[SR_Z], v[SR_W]);
            CHECK(isfinite(sv.inv_w) && sv.inv_w > 0.0f && isfinite(sv.z), "vertex %d (%a, %a, %a, %a) maps to 1/w = %a, z = %a",
                  i, v[SR_X], v[SR_Y], v[SR_Z], v[SR_W], sv.inv_w, sv.z);
        }
    }
    if (as_pipeline && exact)
        check_clip_area(&in, planes, &out, precision == SR_CLIP_ADAPTIVE ? SR_CLIP_DEFAULT_TOLERANCE : 0.0, &cfg.depth,
                        "clip");
}
