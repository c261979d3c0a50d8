/* fuzz/draw_checks.c — four draws of a decoded scene (ids under each cull
 * mode, then the decoded shading) and the invariants between them: what the
 * observer sees, the cull partition, shading-independent coverage, and
 * threads against one thread. */
#include "fuzz_draw.h"


/* Every fan triangle that reaches the rasterizer: on screen (within the
 * slack 06_viewport.h allows for rounding), 1/w finite and positive (DESIGN.md:
 * no division may produce inf or NaN), facing as the cull mode asks, and
 * never from non-finite input. */
static void observe(void *user, const sr_screen_vertex tri[3], bool clipped, uint32_t id)
{
    (void)clipped;
    draw_run *run = user;
    const scene *sc = run->sc;
    run->observed++;
    CHECK(id < slot_count(&sc->mesh), "id %u of %u slots", id, slot_count(&sc->mesh));
    run->id_seen[id] = true;
    uint32_t t[3];
    CHECK(slot_triangle(&sc->mesh, id, t), "observer saw degenerate slot %u", id);
    CHECK(sc->matrices_finite, "triangle %u reached the rasterizer through a non-finite matrix", id);
    for (int k = 0; k < 3; k++)
        CHECK(position_finite(&sc->mesh, t[k]), "triangle %u reached the rasterizer with non-finite vertex %u",
              id, t[k]);

    const int64_t one = SR_SUBPIXEL_ONE;
    const int64_t slack_x = (int64_t)ceil(SR_NDC_SLACK * 0.5 * sc->width * one) + 1;
    const int64_t slack_y = (int64_t)ceil(SR_NDC_SLACK * 0.5 * sc->height * one) + 1;
    const float z_slack = (float)SR_NDC_SLACK + 1e-6f;
    for (int k = 0; k < 3; k++) {
        const sr_screen_vertex *v = &tri[k];
        CHECK(v->x >= -slack_x && v->x <= sc->width * one + slack_x,
              "triangle %u vertex %d: x = %lld subpixels, framebuffer %d px wide", id, k, (long long)v->x,
              sc->width);
        CHECK(v->y >= -slack_y && v->y <= sc->height * one + slack_y,
              "triangle %u vertex %d: y = %lld subpixels, framebuffer %d px high", id, k, (long long)v->y,
              sc->height);
        CHECK(isfinite(v->z) && v->z >= -z_slack && v->z <= 1.0f + z_slack, "triangle %u vertex %d: z = %a",
              id, k, v->z);
        CHECK(isfinite(v->inv_w) && v->inv_w > 0.0f, "triangle %u vertex %d: 1/w = %a", id, k, v->inv_w);
    }

    int64_t area2 = (tri[1].x - tri[0].x) * (tri[2].y - tri[0].y) - (tri[1].y - tri[0].y) * (tri[2].x - tri[0].x);
    CHECK(area2 != 0, "triangle %u: zero-area fan triangle was not culled", id);
    bool clockwise = area2 > 0; /* y down */
    bool front = (sc->front == SR_FRONT_CW) == clockwise;
    CHECK(run->cull == SR_CULL_NONE || front == (run->cull == SR_CULL_BACK),
          "triangle %u: area2 %lld, front %d, cull %d, yet it was drawn", id, (long long)area2, sc->front,
          run->cull);
}

static bool framebuffer_untouched(const sr_framebuffer *fb)
{
    float clear = sr_framebuffer_depth_clear(fb);
    for (int i = 0; i < fb->width * fb->height; i++)
        if (fb->color[i] != 0 || memcmp(&fb->depth[i], &clear, sizeof clear) != 0)
            return false;
    return true;
}

/* A depth a draw wrote: it passed LESS against the clear value 1, or
 * GREATER against 0 in a reversed_z framebuffer (framebuffer.h). */
static bool depth_written(const sr_framebuffer *fb, float d)
{
    return fb->reversed_z ? d > SR_DEPTH_CLEAR_REVERSED : d < SR_DEPTH_CLEAR;
}

static bool stats_equal(const sr_stats *a, const sr_stats *b)
{
    return memcmp(a, b, sizeof *a) == 0;
}

static void stats_print(const char *name, const sr_stats *s)
{
    fprintf(stderr, "  %s: triangles %llu rejected %llu nonfinite %llu clipped %llu culled %llu drawn %llu "
                    "fragments %llu\n",
            name, (unsigned long long)s->triangles, (unsigned long long)s->rejected,
            (unsigned long long)s->nonfinite, (unsigned long long)s->clipped, (unsigned long long)s->culled,
            (unsigned long long)s->drawn, (unsigned long long)s->fragments);
}

/* FUZZ_VERBOSE=1 prints each decoded scene and its stats (for turning a
 * reproducer into a test, or checking that a seed draws what it should). */
static bool verbose(void)
{
    static int cached = -1;
    if (cached < 0)
        cached = getenv("FUZZ_VERBOSE") != NULL;
    return cached;
}

static void print_matrix(const char *name, const mat4 m)
{
    fprintf(stderr, "  %s:", name);
    for (int c = 0; c < 4; c++)
        fprintf(stderr, " [%a %a %a %a]", m[c][0], m[c][1], m[c][2], m[c][3]);
    fprintf(stderr, "\n");
}

static void scene_print(const scene *sc)
{
    const sr_mesh *m = &sc->mesh;
    fprintf(stderr, "scene %dx%d, %u vertices, %u indices (%s, valid %d), shade %d, cull %d, front %d, filter %d, "
                    "normals %d uvs %d colors %d texture %d reversed z %d\n",
            sc->width, sc->height, m->vertex_count, m->index_count,
            m->topology == SR_TRIANGLE_STRIP ? "strip" : "list", sc->indices_valid, sc->shade, sc->cull, sc->front,
            sc->filter, m->normals != NULL, m->uvs != NULL, m->colors != NULL, sc->has_texture, sc->reversed_z);
    for (uint32_t i = 0; i < m->vertex_count; i++)
        fprintf(stderr, "  position %u: %a %a %a\n", i, m->positions[i][0], m->positions[i][1], m->positions[i][2]);
    fprintf(stderr, "  indices:");
    for (uint32_t i = 0; i < m->index_count; i++)
        fprintf(stderr, " %u", m->indices[i]);
    fprintf(stderr, "\n");
    print_matrix("world", sc->world);
    print_matrix("view", sc->view);
    print_matrix("projection", sc->projection);
}

static void draw_run_free(draw_run *run)
{
    sr_framebuffer_destroy(&run->fb);
}

static void draw_and_check(const scene *sc, sr_shade shade, sr_cull cull, draw_run *run)
{
    memset(run, 0, sizeof *run);
    run->sc = sc;
    run->shade = shade;
    run->cull = cull;
    CHECK(sr_framebuffer_create(&run->fb, sc->width, sc->height, NULL), "framebuffer %dx%d", sc->width,
          sc->height);
    run->fb.reversed_z = sc->reversed_z;
    sr_framebuffer_clear(&run->fb, 0);

    sr_draw_desc desc = {
        .mesh = &sc->mesh, .shade = shade, .cull = cull, .front = sc->front, .filter = sc->filter,
        .texture = sc->has_texture ? &sc->texture : NULL,
        .study = &(sr_draw_study){ .observer = observe, .observer_user = run },
    };
    glm_mat4_copy((vec4 *)sc->world, desc.world);
    glm_mat4_copy((vec4 *)sc->view, desc.view);
    glm_mat4_copy((vec4 *)sc->projection, desc.projection);
    glm_vec3_copy((float *)sc->light, desc.light_dir);
    sr_error err = { .message = "" };
    run->ok = sr_draw(&run->fb, &desc, &run->stats, &err);

    bool expected = draw_should_succeed(sc, shade);
    CHECK(run->ok == expected, "sr_draw returned %d, expected %d (shade %d, indices valid %d): %s", run->ok,
          expected, shade, sc->indices_valid, err.message);
    if (!run->ok) {
        static const sr_stats zero;
        CHECK(err.message[0] != '\0', "sr_draw failed without a message");
        CHECK(framebuffer_untouched(&run->fb), "sr_draw failed (%s) but wrote pixels", err.message);
        CHECK(stats_equal(&run->stats, &zero), "sr_draw failed (%s) but counted", err.message);
        CHECK(run->observed == 0, "sr_draw failed (%s) but the observer saw triangles", err.message);
        return;
    }

    /* Depth: finite, in [0, 1]; in id mode on a color buffer cleared to 0,
     * a pixel has a color exactly when its depth was written (< 1). */
    const sr_framebuffer *fb = &run->fb;
    uint64_t written = 0;
    for (int j = 0; j < fb->height; j++)
        for (int i = 0; i < fb->width; i++) {
            size_t p = (size_t)j * (size_t)fb->width + (size_t)i;
            float d = fb->depth[p];
            CHECK(isfinite(d) && d >= 0.0f && d <= 1.0f, "pixel (%d, %d): depth %a", i, j, d);
            written += depth_written(fb, d);
            if (shade != SR_SHADE_ID)
                continue;
            uint32_t c = fb->color[p];
            CHECK((c != 0) == depth_written(fb, d), "pixel (%d, %d): color %#x, depth %a (reversed z %d)", i, j, c,
                  d, fb->reversed_z);
            CHECK(c == 0 || (c - 1 < MAX_INDICES && run->id_seen[c - 1]),
                  "pixel (%d, %d): color %#x is not a triangle the observer saw", i, j, c);
        }

    /* Stats (types.h): triangles counts the non-degenerate slots; the rest
     * are parts of it. */
    const sr_stats *s = &run->stats;
    uint64_t triangles = 0, with_bad_position = 0;
    for (uint32_t k = 0; k < slot_count(&sc->mesh); k++) {
        uint32_t t[3];
        if (!slot_triangle(&sc->mesh, k, t))
            continue;
        triangles++;
        with_bad_position += !position_finite(&sc->mesh, t[0]) || !position_finite(&sc->mesh, t[1]) ||
                             !position_finite(&sc->mesh, t[2]);
    }
    uint64_t pixels = (uint64_t)fb->width * (uint64_t)fb->height;
    bool consistent = s->triangles == triangles && s->rejected <= s->triangles && s->nonfinite <= s->rejected &&
                      s->clipped <= s->triangles && s->drawn == run->observed &&
                      s->culled + s->drawn <= (uint64_t)(SR_MAX_CLIP_VERTS - 2) * s->triangles &&
                      s->fragments <= pixels * s->drawn && s->fragments >= written &&
                      (s->fragments == 0) == (written == 0) && s->nonfinite >= with_bad_position &&
                      (sc->matrices_finite || (s->nonfinite == s->triangles && s->drawn == 0));
    if (!consistent) {
        stats_print("stats", s);
        fprintf(stderr, "  expected triangles %llu, with a non-finite position %llu, observer calls %llu, "
                        "pixels written %llu, matrices finite %d\n",
                (unsigned long long)triangles, (unsigned long long)with_bad_position,
                (unsigned long long)run->observed, (unsigned long long)written, sc->matrices_finite);
    }
    CHECK(consistent, "inconsistent stats (shade %d, cull %d)", shade, cull);
    if (verbose()) {
        fprintf(stderr, "  shade %d cull %d, %llu pixels written:\n", shade, cull, (unsigned long long)written);
        stats_print("stats", s);
    }
}

/* Culling only chooses among the same fan triangles: back and front split
 * what none draws, and none's depth is the nearer of the two at every pixel
 * (each pixel keeps the least z of the triangles covering it, or the
 * greatest in a reversed_z framebuffer). */
static void check_cull_partition(const draw_run run[CULL_MODES])
{
    const draw_run *none = &run[SR_CULL_NONE], *back = &run[SR_CULL_BACK], *front = &run[SR_CULL_FRONT];
    if (!none->ok)
        return;
    const sr_stats *n = &none->stats, *b = &back->stats, *f = &front->stats;
    bool same_geometry = n->triangles == b->triangles && n->triangles == f->triangles &&
                         n->rejected == b->rejected && n->rejected == f->rejected &&
                         n->nonfinite == b->nonfinite && n->nonfinite == f->nonfinite &&
                         n->clipped == b->clipped && n->clipped == f->clipped &&
                         n->culled + n->drawn == b->culled + b->drawn && n->culled + n->drawn == f->culled + f->drawn &&
                         n->drawn == b->drawn + f->drawn;
    if (!same_geometry) {
        stats_print("cull none", n);
        stats_print("cull back", b);
        stats_print("cull front", f);
    }
    CHECK(same_geometry, "cull modes disagree on the fan triangles");
    const sr_framebuffer *fb = &none->fb;
    for (int p = 0; p < fb->width * fb->height; p++) {
        float want = fb->reversed_z ? fmaxf(back->fb.depth[p], front->fb.depth[p])
                                    : fminf(back->fb.depth[p], front->fb.depth[p]);
        CHECK(memcmp(&fb->depth[p], &want, sizeof want) == 0,
              "pixel (%d, %d): depth %a with cull none, %a back, %a front", p % fb->width, p / fb->width,
              fb->depth[p], back->fb.depth[p], front->fb.depth[p]);
    }
}

/* Coverage and depth come from positions alone (DESIGN.md stages 3–9), so
 * the shading mode changes colors only, except that a triangle with a
 * non-finite varying the mode reads is dropped and counted non-finite
 * (10_shade.h). Where any vertex was non-finite the runs are not compared: a
 * triangle dropped before clipping in one mode (its varying/w overflowed) may
 * be clipped in the other and dropped only at a cut vertex, so even equal
 * nonfinite counts can come with different clipped counts
 * (fuzz/regressions/draw/shading_coverage_nonfinite_route). */
static void check_shading_independent(const draw_run *id_run, const draw_run *shaded)
{
    if (!shaded->ok || !id_run->ok || shaded->stats.nonfinite || id_run->stats.nonfinite)
        return;
    bool same = stats_equal(&id_run->stats, &shaded->stats);
    const sr_framebuffer *a = &id_run->fb, *b = &shaded->fb;
    int differ = -1;
    for (int p = 0; p < a->width * a->height && differ < 0; p++)
        if (memcmp(&a->depth[p], &b->depth[p], sizeof(float)) != 0)
            differ = p;
    if ((!same || differ >= 0) && !tolerated("shading_coverage")) {
        stats_print("id", &id_run->stats);
        stats_print("shaded", &shaded->stats);
    }
    CHECK_KNOWN("shading_coverage", same, "shading mode %d changed the stats", shaded->shade);
    CHECK_KNOWN("shading_coverage", differ < 0, "pixel (%d, %d): depth %a in id mode, %a in shading mode %d",
                differ % a->width, differ / a->width, a->depth[differ], b->depth[differ], shaded->shade);
}

/* One draw without an observer (which would force one thread), on the path
 * given: the cost estimate would keep these small scenes on one thread. */
static bool draw_plain(const scene *sc, sr_shade shade, int threads, sr_draw_path path, sr_workspace *ws, int width,
                       int height, sr_framebuffer *fb, sr_stats *stats)
{
    CHECK(sr_framebuffer_create(fb, width, height, NULL), "framebuffer %dx%d", width, height);
    fb->reversed_z = sc->reversed_z;
    sr_framebuffer_clear(fb, 0);
    sr_draw_desc desc = {
        .mesh = &sc->mesh, .shade = shade, .cull = sc->cull, .front = sc->front, .filter = sc->filter,
        .texture = sc->has_texture ? &sc->texture : NULL, .threads = threads, .workspace = ws,
        .study = &(sr_draw_study){ .path = path, .chunk_slots = sc->chunk_slots },
    };
    glm_mat4_copy((vec4 *)sc->world, desc.world);
    glm_mat4_copy((vec4 *)sc->view, desc.view);
    glm_mat4_copy((vec4 *)sc->projection, desc.projection);
    glm_vec3_copy((float *)sc->light, desc.light_dir);
    *stats = (sr_stats){ 0 };
    return sr_draw(fb, &desc, stats, NULL);
}

/* softrast.h, sr_draw: "the image and depth are bit-identical for every
 * thread count and every path" (and so are the counts): the tiles against
 * the direct path. Drawn in the decoded shading mode (id if the mesh cannot
 * be shaded so), on the scene's framebuffer or on one several tiles tall
 * (strips of SR_TILE_ROWS rows), the threaded draw reusing one workspace,
 * on the tiles or on the row bands. */
static void check_threads(const scene *sc)
{
    if (!sc->indices_valid || sc->threads == 0)
        return;
    sr_shade shade = draw_should_succeed(sc, sc->shade) ? sc->shade : SR_SHADE_ID;
    int width = sc->width + (sc->big ? 4 * SR_TILE_ROWS_MAX + 13 : 0);
    int height = sc->height + (sc->big ? 4 * SR_TILE_ROWS_MAX + 7 : 0);
    sr_workspace *ws = sr_workspace_create();
    CHECK(ws != NULL, "no workspace");
    sr_framebuffer one, many;
    sr_stats one_stats, many_stats;
    bool one_ok = draw_plain(sc, shade, 1, SR_PATH_DIRECT, NULL, width, height, &one, &one_stats);
    /* The thread count picks the threaded path; chunks of 1 to 7 slots
     * split the fuzzer's few among the threads. */
    static const sr_draw_path paths[] = { SR_PATH_TILES, SR_PATH_ROWS };
    sr_draw_path path = paths[sc->threads % 2];
    bool many_ok = draw_plain(sc, shade, sc->threads, path, ws, width, height, &many, &many_stats);
    bool again_ok = true;
    if (sc->big) { /* the workspace again, as a viewer reuses it every frame, on the other threaded path */
        sr_framebuffer_destroy(&many);
        path = paths[(sc->threads + 1) % 2];
        again_ok = draw_plain(sc, shade, sc->threads, path, ws, width, height, &many, &many_stats);
    }
    CHECK(one_ok && many_ok && again_ok, "sr_draw failed: %d with one thread, %d/%d with %d", one_ok, many_ok,
          again_ok, sc->threads);
    if (!stats_equal(&one_stats, &many_stats)) {
        stats_print("one thread", &one_stats);
        stats_print("threads", &many_stats);
    }
    CHECK(stats_equal(&one_stats, &many_stats), "%d threads count differently from one (%dx%d, shade %d)",
          sc->threads, width, height, shade);
    for (int p = 0; p < width * height; p++)
        CHECK(one.color[p] == many.color[p] && memcmp(&one.depth[p], &many.depth[p], sizeof(float)) == 0,
              "pixel (%d, %d): color %#x depth %a with one thread, %#x %a with %d (%dx%d, shade %d)", p % width,
              p / width, one.color[p], one.depth[p], many.color[p], many.depth[p], sc->threads, width, height,
              shade);
    sr_framebuffer_destroy(&one);
    sr_framebuffer_destroy(&many);
    sr_workspace_destroy(ws);
}

/* The primitives a point or line topology assembles from the indices:
 * every index a point; a list's pairs, a strip's windows of two, without
 * the repeated ones. */
static uint64_t primitive_count(const sr_mesh *m)
{
    if (m->topology == SR_POINT_LIST)
        return m->index_count;
    uint64_t n = 0;
    bool strip = m->topology == SR_LINE_STRIP;
    for (uint32_t k = 0; strip ? k + 1 < m->index_count : 2 * k + 1 < m->index_count; k++) {
        uint32_t first = strip ? k : 2 * k;
        n += m->indices[first] != m->indices[first + 1];
    }
    return n;
}

/* The scene's vertices and indices as points, a line list and a line
 * strip (docs/conventions.md, "Points and lines"), in id shading, 1..4
 * pixels wide: drawn exactly when the indices are valid; counted as
 * points or lines (never as triangles), each dropped one counted once;
 * every id in range with its depth written, every depth in [0, 1]; the
 * same image, depth and counts on one thread and on several. */
static void check_points_lines(const scene *sc)
{
    static const sr_topology topologies[] = { SR_POINT_LIST, SR_LINE_LIST, SR_LINE_STRIP };
    for (int t = 0; t < 3; t++) {
        scene as = *sc;
        as.mesh.topology = topologies[t];
        float size = (float)(1 + sc->chunk_slots % 4);
        sr_framebuffer one, many;
        sr_stats one_stats, many_stats;
        CHECK(sr_framebuffer_create(&one, sc->width, sc->height, NULL), "framebuffer");
        CHECK(sr_framebuffer_create(&many, sc->width, sc->height, NULL), "framebuffer");
        bool ok[2];
        for (int k = 0; k < 2; k++) {
            sr_framebuffer *fb = k ? &many : &one;
            fb->reversed_z = sc->reversed_z;
            sr_framebuffer_clear(fb, 0);
            sr_draw_desc desc = { .mesh = &as.mesh, .shade = SR_SHADE_ID, .point_size = size, .line_width = size,
                                  .threads = k ? 2 + sc->threads : 1 };
            glm_mat4_copy((vec4 *)sc->world, desc.world);
            glm_mat4_copy((vec4 *)sc->view, desc.view);
            glm_mat4_copy((vec4 *)sc->projection, desc.projection);
            *(k ? &many_stats : &one_stats) = (sr_stats){ 0 };
            ok[k] = sr_draw(fb, &desc, k ? &many_stats : &one_stats, NULL);
        }
        CHECK(ok[0] == sc->indices_valid && ok[1] == ok[0], "topology %d drawn %d/%d, indices valid %d",
              (int)topologies[t], ok[0], ok[1], sc->indices_valid);
        CHECK(stats_equal(&one_stats, &many_stats), "topology %d: threads count differently", (int)topologies[t]);
        const sr_stats *s = &one_stats;
        uint64_t n = ok[0] ? primitive_count(&as.mesh) : 0;
        CHECK(s->triangles == 0 && s->culled == 0 && s->points + s->lines == n &&
                  (topologies[t] == SR_POINT_LIST ? s->lines == 0 && s->clipped == 0 : s->points == 0),
              "topology %d: %llu points, %llu lines, %llu triangles, %llu clipped of %llu", (int)topologies[t],
              (unsigned long long)s->points, (unsigned long long)s->lines, (unsigned long long)s->triangles,
              (unsigned long long)s->clipped, (unsigned long long)n);
        bool points = topologies[t] == SR_POINT_LIST; /* a point is drawn or rejected, a line may be cut away */
        CHECK(s->nonfinite <= s->rejected && s->rejected + s->drawn <= n && s->clipped <= n &&
                  (!points || s->rejected + s->drawn == n),
              "topology %d: rejected %llu (nonfinite %llu), drawn %llu of %llu", (int)topologies[t],
              (unsigned long long)s->rejected, (unsigned long long)s->nonfinite, (unsigned long long)s->drawn,
              (unsigned long long)n);
        float clear = sr_framebuffer_depth_clear(&one);
        uint64_t written = 0;
        for (int p = 0; p < sc->width * sc->height; p++) {
            float z = one.depth[p];
            CHECK(one.color[p] == many.color[p] && memcmp(&one.depth[p], &many.depth[p], sizeof z) == 0,
                  "topology %d pixel %d: one thread and several differ", (int)topologies[t], p);
            CHECK(isfinite(z) && z >= 0.0f && z <= 1.0f, "topology %d pixel %d: depth %a", (int)topologies[t], p, z);
            CHECK(one.color[p] <= sr_assemble_point_line_slots(&as.mesh), "topology %d pixel %d: id %u",
                  (int)topologies[t], p, one.color[p]);
            CHECK((one.color[p] != 0) == (z != clear), "topology %d pixel %d: id %u, depth %a", (int)topologies[t], p,
                  one.color[p], z);
            written += one.color[p] != 0;
        }
        CHECK(written <= s->fragments, "topology %d: %llu pixels written, %llu fragments", (int)topologies[t],
              (unsigned long long)written, (unsigned long long)s->fragments);
        sr_framebuffer_destroy(&one);
        sr_framebuffer_destroy(&many);
    }
}

void fuzz_draw(reader *r)
{
    scene sc;
    if (!scene_decode(r, &sc)) {
        scene_free(&sc);
        return;
    }
    if (verbose())
        scene_print(&sc);
    draw_run id_runs[CULL_MODES], shaded;
    for (int c = 0; c < CULL_MODES; c++)
        draw_and_check(&sc, SR_SHADE_ID, (sr_cull)c, &id_runs[c]);
    check_cull_partition(id_runs);
    if (id_runs[SR_CULL_NONE].ok)
        check_stages(&sc, &id_runs[SR_CULL_NONE].stats);
    draw_and_check(&sc, sc.shade, sc.cull, &shaded);
    check_shading_independent(&id_runs[sc.cull], &shaded);
    check_threads(&sc);
    check_points_lines(&sc);
    check_pinhole(&sc, r);
    for (int c = 0; c < CULL_MODES; c++)
        draw_run_free(&id_runs[c]);
    draw_run_free(&shaded);
    scene_free(&sc);
}
