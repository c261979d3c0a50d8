/* The clipping torture suite: every tests/cases/NAME.case is one scene, run as
 * one instance of the parameterized test cases::run (so adding a file adds
 * a test; --filter 'cases/run' runs them all). The format, and what each
 * `expect` line checks, is in tests/cases/README.md; the parser is
 * case_format.c, the clipper mirror and the ray-cast oracle case_oracle.c.
 *
 * Every case, whatever it expects, must also hold the invariants of
 * DESIGN.md's clipping contract:
 *   - sr_draw succeeds (and nothing crashes: the suite also runs under
 *     ASan + UBSan);
 *   - every depth in the buffer is the clear value or finite in [0, 1];
 *   - the clipper never returns more than SR_MAX_CLIP_VERTS vertices, and
 *     each is inside all six planes within a relative tolerance (default
 *     CASE_CLIP_TOLERANCE, `expect clip-tolerance T` to state another);
 *   - every fan triangle the observer sees has finite vertices, 1/w > 0,
 *     z_ndc in [0, 1] and x, y within the viewport, to the same tolerance;
 *   - a draw that reports no fragments leaves depth untouched;
 *   - the mirror of stages 1–4 agrees with the draw's stats on triangles
 *     and clipped (so the clipper output it checked is the one drawn);
 *   - the same draw on CASE_THREADS threads gives a bit-identical image,
 *     depth buffer and stats (softrast.h).
 * A failure names the case file and the line of the expectation, and writes
 * build/test-output/case-NAME.png (the draw) and case-NAME_hits.png (hits per
 * pixel: gray once, red twice or more, blue missing) for pixel checks.
 */
#include <glob.h>
#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <criterion/criterion.h>
#include <criterion/parameterized.h>

#include "case_format.h"
#include "case_oracle.h"
#include "hit_counter.h"

#define CASES_GLOB "tests/cases/" "*.case"
#define PICTURE_MAX_SIDE 2048 /* failure pictures are written up to this size */
#define CASE_THREADS 3        /* the threaded draw compared with the observed one */

typedef struct case_param {
    char path[CASE_PATH_MAX];
} case_param;

/* ---- what the draw's observer sees ---- */

typedef struct fan_report {
    int width, height;
    int64_t slack; /* subpixels a vertex may stray past the viewport */
    double z_slack;
    uint64_t fans;
    double area; /* px², |area2| / 2 summed over the fan triangles */
    uint64_t bad;
    char first_bad[256];
} fan_report;

static void fan_observe(void *user, const sr_screen_vertex tri[3], bool clipped, uint32_t id)
{
    (void)clipped;
    fan_report *r = user;
    r->fans++;
    int64_t area2 = (tri[1].x - tri[0].x) * (tri[2].y - tri[0].y) - (tri[1].y - tri[0].y) * (tri[2].x - tri[0].x);
    r->area += fabs((double)area2) * 0.5 / ((double)SR_SUBPIXEL_ONE * SR_SUBPIXEL_ONE);
    int64_t right = (int64_t)r->width * SR_SUBPIXEL_ONE, bottom = (int64_t)r->height * SR_SUBPIXEL_ONE;
    for (int k = 0; k < 3; k++) {
        const sr_screen_vertex *v = &tri[k];
        bool ok = v->x >= -r->slack && v->x <= right + r->slack && v->y >= -r->slack && v->y <= bottom + r->slack &&
                  isfinite(v->z) && v->z >= -r->z_slack && v->z <= 1.0 + r->z_slack && isfinite(v->inv_w) &&
                  v->inv_w > 0.0f;
        if (!ok && r->bad++ == 0)
            snprintf(r->first_bad, sizeof r->first_bad,
                     "triangle %u: fan vertex at (%.4f, %.4f) px, z %g, 1/w %g", id,
                     (double)v->x / SR_SUBPIXEL_ONE, (double)v->y / SR_SUBPIXEL_ONE, (double)v->z, (double)v->inv_w);
    }
}

/* ---- one case ---- */

typedef struct case_run {
    const case_desc *c;
    char name[CASE_PATH_MAX]; /* case-BASENAME, for pictures */
    sr_mesh mesh;
    mat4 world, view, projection;
    sr_framebuffer fb;
    sr_stats stats;
    fan_report fans;
    case_clip_report clip;
    uint32_t *hits; /* per pixel, from the counting draw; NULL until needed */
    bool failed;    /* some check failed: leave a picture of the draw */
} case_run;

/* The first failure of a case also prints its title (the file's first
 * comment line), so a failing run says what the scene was about. */
static void case_note(case_run *r, bool ok)
{
    if (!ok && !r->failed)
        cr_log_error("%s: %s", r->c->path, r->c->title);
    r->failed |= !ok;
}

/* cr_expect that remembers the failure in the run; case_require also
 * returns false from the calling function, so the run still frees what it
 * holds (a fatal cr_assert would leave leaks for LeakSanitizer to report). */
#define case_expect(r, cond, ...)                                                                                     \
    do {                                                                                                              \
        bool case_ok_ = (cond);                                                                                       \
        case_note((r), case_ok_);                                                                                     \
        cr_expect(case_ok_, __VA_ARGS__);                                                                             \
    } while (0)
#define case_require(r, cond, ...)                                                                                    \
    do {                                                                                                              \
        bool case_ok_ = (cond);                                                                                       \
        case_note((r), case_ok_);                                                                                     \
        cr_expect(case_ok_, __VA_ARGS__);                                                                             \
        if (!case_ok_)                                                                                                \
            return false;                                                                                             \
    } while (0)

static void picture_name(const char *path, char out[CASE_PATH_MAX])
{
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    snprintf(out, CASE_PATH_MAX, "case-%.*s", (int)strcspn(base, "."), base);
}

static bool pictures_fit(const case_run *r)
{
    return r->fb.width <= PICTURE_MAX_SIDE && r->fb.height <= PICTURE_MAX_SIDE;
}

static sr_draw_desc case_draw_desc(case_run *r)
{
    sr_draw_desc d = { .mesh = &r->mesh, .shade = r->c->shade, .cull = r->c->cull, .front = r->c->front };
    glm_mat4_copy(r->world, d.world);
    glm_mat4_copy(r->view, d.view);
    glm_mat4_copy(r->projection, d.projection);
    return d;
}

/* The draw the case describes, observed fan triangle by fan triangle. */
static bool draw_observed(case_run *r)
{
    const case_desc *c = r->c;
    int side = c->width > c->height ? c->width : c->height;
    r->fans = (fan_report){ .width = c->width, .height = c->height, .z_slack = c->clip_tolerance,
                            .slack = 1 + (int64_t)ceil(c->clip_tolerance * side * SR_SUBPIXEL_ONE) };
    sr_draw_desc d = case_draw_desc(r);
    d.study = &(sr_draw_study){ .observer = fan_observe, .observer_user = &r->fans };
    sr_error err = { "" };
    case_require(r, sr_draw(&r->fb, &d, &r->stats, &err), "%s: sr_draw failed: %s", c->path, err.message);
    return true;
}

/* FNV-1a (a word at a time) over the color and depth buffers: compares two draws of any size
 * without keeping a copy. */
static uint64_t framebuffer_hash(const sr_framebuffer *fb)
{
    uint64_t h = 0xCBF29CE484222325ull;
    size_t n = scene_pixel_count(fb);
    for (size_t i = 0; i < n; i++) {
        uint32_t depth;
        memcpy(&depth, &fb->depth[i], sizeof depth);
        h = (h ^ fb->color[i]) * 0x100000001B3ull;
        h = (h ^ depth) * 0x100000001B3ull;
    }
    return h;
}

/* The threaded path must give the same picture, depth and stats as the
 * one-thread path the observed draw took (softrast.h: bit-identical). */
static bool check_threads(case_run *r)
{
    uint64_t one = framebuffer_hash(&r->fb);
    sr_framebuffer_clear(&r->fb, SCENE_BACKGROUND);
    sr_draw_desc d = case_draw_desc(r);
    d.threads = CASE_THREADS;
    sr_stats stats = { 0 };
    sr_error err = { "" };
    case_require(r, sr_draw(&r->fb, &d, &stats, &err), "%s: sr_draw with %d threads failed: %s", r->c->path,
                 CASE_THREADS, err.message);
    case_expect(r, framebuffer_hash(&r->fb) == one, "%s: %d threads drew a different image or depth than one",
                r->c->path, CASE_THREADS);
    case_expect(r, memcmp(&stats, &r->stats, sizeof stats) == 0, "%s: %d threads counted different stats "
                "(fragments %" PRIu64 " against %" PRIu64 ")", r->c->path, CASE_THREADS, stats.fragments,
                r->stats.fragments);
    return true;
}

/* Hits per pixel: the same draw again, counting hits (sr_draw_study.count_hits). */
static bool draw_counted(case_run *r)
{
    sr_draw_desc d = case_draw_desc(r);
    d.study = &(sr_draw_study){ .count_hits = true };
    size_t n = scene_pixel_count(&r->fb);
    r->hits = malloc(n * sizeof *r->hits); /* freed by the run */
    case_require(r, r->hits != NULL, "%s: out of memory for the hit counts", r->c->path);
    sr_framebuffer_clear(&r->fb, 0);
    sr_error err = { "" };
    case_require(r, sr_draw(&r->fb, &d, NULL, &err), "%s: counting sr_draw failed: %s", r->c->path, err.message);
    memcpy(r->hits, r->fb.color, n * sizeof *r->hits);
    return true;
}

/* must_hit: per pixel (NULL: must_all for every pixel) whether a miss is wrong. */
static void write_hits_picture(const case_run *r, const uint8_t *must_hit, bool must_all)
{
    if (!pictures_fit(r))
        return;
    size_t n = scene_pixel_count(&r->fb);
    uint32_t *img = malloc(n * sizeof *img);
    unsigned char *must = malloc(n);
    cr_assert(img && must);
    for (size_t i = 0; i < n; i++)
        must[i] = must_hit ? must_hit[i] > 0 : must_all;
    scene_counts_to_image(r->hits, must, n, img);
    scene_write_png(r->name, "_hits", img, r->fb.width, r->fb.height);
    free(img);
    free(must);
}

/* ---- the invariants every case holds ---- */

static void check_universal(case_run *r)
{
    const case_desc *c = r->c;
    case_expect(r, r->clip.bad == 0, "%s: %" PRIu64 " clipper outputs break the contract; first: %s", c->path,
                r->clip.bad, r->clip.first_bad);
    case_expect(r, r->fans.bad == 0, "%s: %" PRIu64 " fan vertices outside the viewport or depth range; first: %s",
                 c->path, r->fans.bad, r->fans.first_bad);
    float clear = sr_framebuffer_depth_clear(&r->fb);
    size_t n = scene_pixel_count(&r->fb), bad = 0, written = 0, first = 0;
    for (size_t i = 0; i < n; i++) {
        float d = r->fb.depth[i];
        written += d != clear;
        if (d != clear && !(isfinite(d) && d >= 0.0f && d <= 1.0f) && bad++ == 0)
            first = i;
    }
    case_expect(r, bad == 0, "%s: %zu depths not finite in [0, 1]; first at (%zu, %zu): %g", c->path, bad,
                 first % (size_t)r->fb.width, first / (size_t)r->fb.width, bad ? (double)r->fb.depth[first] : 0.0);
    case_expect(r, r->stats.fragments > 0 || written == 0, "%s: no fragments reported but %zu depths written", c->path,
              written);
    case_expect(r, r->clip.triangles == r->stats.triangles,
                "%s: mirror assembled %" PRIu64 " triangles, sr_draw %" PRIu64, c->path, r->clip.triangles,
                r->stats.triangles);
    case_expect(r, r->clip.clipped == r->stats.clipped,
                "%s: the mirror (which drops a vertex with a non-finite position or read varying before clipping) "
                "clipped %" PRIu64 " triangles, sr_draw %" PRIu64, c->path, r->clip.clipped, r->stats.clipped);
}

/* ---- the expectations a case states ---- */

static uint64_t stat_value(const sr_stats *s, case_stat which)
{
    const uint64_t v[CASE_STAT_COUNT] = { s->triangles, s->rejected, s->nonfinite, s->clipped,
                                          s->culled,    s->drawn,    s->fragments };
    return v[which];
}

static void planes_text(unsigned planes, char *out, size_t size)
{
    out[0] = '\0';
    for (int p = 0; p < SR_CLIP_PLANES; p++)
        if (planes & (1u << p))
            snprintf(out + strlen(out), size - strlen(out), "%s%s", out[0] ? " " : "", case_plane_name(p));
    if (!out[0])
        snprintf(out, size, "none");
}

/* Pixels whose hit count is outside [lo, hi] (NULL: the bound is the number given). */
static void check_hits(case_run *r, const case_expect *e, const uint8_t *lo, int lo_all, const uint8_t *hi,
                       int hi_all)
{
    size_t n = scene_pixel_count(&r->fb), bad = 0, first = 0;
    for (size_t i = 0; i < n; i++) {
        int64_t hits = r->hits[i], least = lo ? lo[i] : lo_all, most = hi ? hi[i] : hi_all;
        if ((hits < least || hits > most) && bad++ == 0)
            first = i;
    }
    int least = lo ? lo[first] : lo_all, most = hi ? hi[first] : hi_all;
    case_expect(r, bad == 0, "%s:%d: %s: %zu pixels wrong; first at (%zu, %zu): hit %u times, expected %d to %d; "
                 "see " SCENE_OUTPUT_DIR "/%s_hits.png", r->c->path, e->line, e->text, bad, first % (size_t)r->fb.width,
                 first / (size_t)r->fb.width, (unsigned)r->hits[first], least, most, r->name);
    if (bad || getenv("SOFTRAST_TEST_PICTURES")) /* set it to see the passing scenes too */
        write_hits_picture(r, lo, lo_all > 0);
}

static void check_raycast(case_run *r, const case_expect *e)
{
    const case_desc *c = r->c;
    /* The rays come from the camera: a view or projection matrix line must
     * then only restate the camera's (`matrix view identity` pins exactness). */
    mat4 view, projection;
    bool usable = c->has_camera && c->camera.ortho_height <= 0.0f;
    if (usable) {
        sr_camera_view(&c->camera, view);
        sr_camera_projection(&c->camera, (float)c->width / (float)c->height, projection);
        for (int k = 0; k < 16; k++) /* == rather than memcmp: -0 restates 0 */
            usable = usable && view[k / 4][k % 4] == r->view[k / 4][k % 4] &&
                     projection[k / 4][k % 4] == r->projection[k / 4][k % 4];
    }
    case_expect(r, usable, "%s:%d: raycast needs a perspective camera, and view and projection matrices (if "
                "given) equal to the camera's", c->path, e->line);
    if (!usable)
        return;
    size_t n = scene_pixel_count(&r->fb);
    uint8_t *lo = malloc(n), *hi = malloc(n);
    cr_assert(lo && hi);
    case_raycast(&r->mesh, r->world, &c->camera, c->width, c->height, c->cull, c->front, lo, hi);
    check_hits(r, e, lo, 0, hi, 0);
    free(lo);
    free(hi);
}

static void check_stats(case_run *r, const case_expect *e)
{
    for (int i = 0; i < e->stat_count; i++) {
        const case_stat_check *s = &e->stats[i];
        uint64_t got = stat_value(&r->stats, s->stat);
        bool ok = s->op == CASE_OP_EQ ? got == s->value : s->op == CASE_OP_LE ? got <= s->value : got >= s->value;
        static const char *const ops[] = { "=", "<=", ">=" };
        case_expect(r, ok, "%s:%d: %s: %s is %" PRIu64 ", expected %s %" PRIu64, r->c->path, e->line, e->text,
                  case_stat_name(s->stat), got, ops[s->op], s->value);
    }
}

static void check_expectation(case_run *r, const case_expect *e)
{
    const case_desc *c = r->c;
    char want[64], got[64];
    switch (e->kind) {
    case CASE_EXPECT_STATS:
        check_stats(r, e);
        break;
    case CASE_EXPECT_AREA:
        case_expect(r, fabs(r->fans.area - e->a) <= e->b,
                    "%s:%d: %s: the fan triangles cover %.6f px², expected %.6f ± %g", c->path, e->line, e->text,
                    r->fans.area, e->a, e->b);
        break;
    case CASE_EXPECT_COVERED_ALL:
        check_hits(r, e, NULL, 1, NULL, 1 << 16);
        break;
    case CASE_EXPECT_HIT_AT_MOST_ONCE:
        check_hits(r, e, NULL, 0, NULL, 1);
        break;
    case CASE_EXPECT_RAYCAST:
        check_raycast(r, e);
        break;
    case CASE_EXPECT_CLIP_VERTICES:
        case_expect(r, r->clip.max_vertices == (int)e->a, "%s:%d: %s: the largest clipper output has %d vertices",
                     c->path, e->line, e->text, r->clip.max_vertices);
        break;
    case CASE_EXPECT_CROSSES:
    case CASE_EXPECT_ON_PLANE: {
        unsigned have = e->kind == CASE_EXPECT_CROSSES ? r->clip.crossed : r->clip.on_plane;
        planes_text(e->planes, want, sizeof want);
        planes_text(have, got, sizeof got);
        case_expect(r, (have & e->planes) == e->planes, "%s:%d: %s: wanted %s, the scene has %s", c->path, e->line,
                  e->text, want, got);
        break;
    }
    case CASE_EXPECT_DEPTH_AT: {
        int x = (int)e->a, y = (int)e->b;
        bool inside = x >= 0 && y >= 0 && x < c->width && y < c->height;
        case_expect(r, inside, "%s:%d: pixel outside the framebuffer", c->path, e->line);
        if (!inside)
            break;
        double d = r->fb.depth[(size_t)y * (size_t)c->width + (size_t)x];
        case_expect(r, fabs(d - e->c) <= e->d, "%s:%d: %s: depth is %.9g", c->path, e->line, e->text, d);
        break;
    }
    case CASE_EXPECT_CAMERA_INVALID:
        break; /* handled before anything is drawn */
    }
}

static bool wants_hits(const case_desc *c)
{
    return case_wants(c, CASE_EXPECT_COVERED_ALL) || case_wants(c, CASE_EXPECT_HIT_AT_MOST_ONCE) ||
           case_wants(c, CASE_EXPECT_RAYCAST);
}

static bool run_case(case_run *r)
{
    const case_desc *c = r->c;
    sr_error err = { "" };
    if (c->has_camera) {
        bool valid = sr_camera_check(&c->camera, &err);
        if (case_wants(c, CASE_EXPECT_CAMERA_INVALID)) {
            case_expect(r, !valid, "%s: sr_camera_check accepted a camera the case says is invalid", c->path);
            return true;
        }
        case_require(r, valid, "%s: camera: %s", c->path, err.message);
    }
    case_require(r, case_make_mesh(c, &r->mesh, &err), "%s: mesh: %s", c->path, err.message);
    case_make_matrices(c, r->world, r->view, r->projection);
    case_clip_run(&r->mesh, r->world, r->view, r->projection, c->shade, c->width, c->height, c->clip_tolerance,
                  &r->clip);
    case_require(r, sr_framebuffer_create(&r->fb, c->width, c->height, &err), "%s: %s", c->path, err.message);
    r->fb.reversed_z = c->reversed_z >= 0 ? c->reversed_z == 1 : c->has_camera && c->camera.reversed_z;
    sr_framebuffer_clear(&r->fb, SCENE_BACKGROUND);
    if (!draw_observed(r))
        return false;
    if (getenv("SOFTRAST_CASES_VERBOSE")) /* what a case measures, for writing its expectations */
        fprintf(stderr, "%s: triangles %" PRIu64 " rejected %" PRIu64 " nonfinite %" PRIu64 " clipped %" PRIu64
                " culled %" PRIu64 " drawn %" PRIu64 " fragments %" PRIu64 "; area %.6f px²; clipper max %d "
                "vertices, crossed 0x%x, on-plane 0x%x\n", c->path, r->stats.triangles, r->stats.rejected,
                r->stats.nonfinite, r->stats.clipped, r->stats.culled, r->stats.drawn, r->stats.fragments,
                r->fans.area, r->clip.max_vertices, r->clip.crossed, r->clip.on_plane);
    check_universal(r);
    for (int i = 0; i < c->expect_count; i++)
        if (c->expect[i].kind != CASE_EXPECT_COVERED_ALL && c->expect[i].kind != CASE_EXPECT_HIT_AT_MOST_ONCE &&
            c->expect[i].kind != CASE_EXPECT_RAYCAST)
            check_expectation(r, &c->expect[i]);
    if ((r->failed || getenv("SOFTRAST_TEST_PICTURES")) && pictures_fit(r))
        scene_write_png(r->name, "", r->fb.color, r->fb.width, r->fb.height);
    if (!check_threads(r))
        return false;
    if (!wants_hits(c))
        return true;
    if (!draw_counted(r))
        return false;
    for (int i = 0; i < c->expect_count; i++)
        if (c->expect[i].kind == CASE_EXPECT_COVERED_ALL || c->expect[i].kind == CASE_EXPECT_HIT_AT_MOST_ONCE ||
            c->expect[i].kind == CASE_EXPECT_RAYCAST)
            check_expectation(r, &c->expect[i]);
    return true;
}

/* ---- the parameterized test ---- */

static void free_params(struct criterion_test_params *params)
{
    cr_free(params->params);
}

ParameterizedTestParameters(cases, run)
{
    char pattern[CASE_PATH_MAX];
    case_root_path(CASES_GLOB, pattern);
    glob_t found = { 0 };
    size_t n = glob(pattern, 0, NULL, &found) == 0 ? found.gl_pathc : 0;
    case_param *params = cr_calloc(n ? n : 1, sizeof *params);
    for (size_t i = 0; i < n; i++)
        snprintf(params[i].path, sizeof params[i].path, "%.*s", CASE_PATH_MAX - 1, found.gl_pathv[i]);
    globfree(&found);
    return cr_make_param_array(case_param, params, n ? n : 1, free_params);
}

ParameterizedTest(case_param *param, cases, run, .timeout = 120.0)
{
    cr_assert(param->path[0], "no case files match %s", CASES_GLOB);
    static case_desc c; /* large: keep it off the stack */
    sr_error err = { "" };
    cr_assert(case_load(&c, param->path, &err), "%s", err.message);
    case_run r = { .c = &c };
    picture_name(c.path, r.name);
    (void)run_case(&r); /* failures are reported as they happen */
    free(r.hits);
    sr_framebuffer_destroy(&r.fb);
    sr_mesh_free(&r.mesh);
    case_free(&c);
}
