/* pinhole_resolve.c — a pinhole view's depth, range, ids and normals
 * from the primitive each pixel shows (sr_pinhole_resolve, softrast.h),
 * in chunks of rows on threads. */
#include <float.h>
#include <limits.h>
#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "pinhole_sparse.h"
#include "pinhole_triangles.h"
#include "pipeline/02_assemble.h"
#include "pipeline/08_raster/simd_select.h"
#include "softrast/softrast.h"
#include "core/dmat4.h"
#include "core/error.h"

/* Two lanes of doubles (camera_v2's), and their bits and floats. */
typedef camera_v2 resolve_v2;
typedef uint64_t resolve_u2 __attribute__((vector_size(16)));
typedef float resolve_f2 __attribute__((vector_size(8)));

/* The view z a depth-buffer value stands for, under cam's reversed
 * projection: z_ndc = (fn/Z − n)/(f − n). */
static double z_of_depth(const sr_pinhole *cam, float z_ndc)
{
    double n = cam->near, f = cam->far;
    return f * n / ((double)z_ndc * (f - n) + n);
}

/* A file-frame direction (a normal) in the camera frame: the pose's rotation. */
static void rotate(const sr_pinhole *cam, const double d[3], double out[3])
{
    for (int r = 0; r < 3; r++)
        out[r] = cam->w2c[r][0] * d[0] + cam->w2c[r][1] * d[1] + cam->w2c[r][2] * d[2];
}

/* v made unit length; 0 where it has no direction: zero, NaN, or an
 * infinite component (vertex normals that are not finite), whose length
 * is infinite and would make a component inf/inf. */
static void normalize_into(const double v[3], float out[3])
{
    double length = sqrt(sr_dvec3_dot(v, v));
    bool direction = length > 0.0 && length < INFINITY;
    for (int k = 0; k < 3; k++)
        out[k] = direction ? (float)(v[k] / length) : 0.0f;
}

/* The view z a drawn pixel's ray may meet its triangle's plane at: between
 * the clip planes, give or take 1/256 of them for the draw's rounding.
 * Elsewhere (NaN, ±inf, behind the camera, or a plane through the eye met
 * next to it) the ray runs in the plane, or so nearly that its z is
 * rounding alone: an edge-on triangle, whose depth buffer value gives the
 * point. As bits too: a z of bits b lies in [lo, hi] when
 * b − bits(lo), unsigned, is at most bits(hi) − bits(lo) =: span, which
 * plane_z_bad tests with integer adds and ors, as SSE2 has them for
 * 64-bit lanes (GCC lowers a test of a double comparison's lanes to
 * scalar code). */
#define RESOLVE_Z_SLACK 0x1p-8

typedef struct z_window {
    double lo, hi;
    uint64_t lo_bits, bias; /* bias: 2^63 − 1 − span, which carries into the top bit past span */
} z_window;

static z_window z_window_of(const sr_pinhole *cam)
{
    z_window w = { cam->near * (1.0 - RESOLVE_Z_SLACK), fmin(cam->far * (1.0 + RESOLVE_Z_SLACK), DBL_MAX), 0, 0 };
    uint64_t hi_bits;
    memcpy(&w.lo_bits, &w.lo, sizeof w.lo_bits);
    memcpy(&hi_bits, &w.hi, sizeof hi_bits);
    w.bias = (UINT64_C(1) << 63) - 1 - (hi_bits - w.lo_bits);
    return w;
}

/* The chunks of rows per thread, handed to whichever thread asks next:
 * the pixels that show something lie anywhere in the frame, so equal
 * bands of rows left one thread the heavier half. Few: a chunk's first
 * two rows start with nothing prefetched. One thread takes every row at
 * once. */
#define RESOLVE_CHUNKS_PER_THREAD 4

/* What every thread of a resolve reads, the plane of ids it reads, and
 * the next chunk of rows to take. */
typedef struct resolve_job {
    const sr_pinhole *cam;
    const sr_mesh *mesh;
    const sr_framebuffer *fb;
    const uint32_t *ids; /* fb's ids plane, or its color of an SR_SHADE_ID draw */
    uint32_t slots;      /* the mesh's primitive slots: the largest id a draw of it writes */
    const sr_pinhole_outputs *out;
    camera_frame frame;    /* cam's, for mesh */
    bool avx2;             /* the triangles set up in AVX2 lanes (the CPU has them) */
    z_window window;       /* cam's */
    double *ray_x, *ray_y; /* (x − cx)/fx of each column, (y − cy)/fy of each row */
    int chunk_rows;
    atomic_int next_chunk; /* chunks, not rows: a row count past the last row could wrap */
} resolve_job;

static uint32_t part_of(const sr_mesh *mesh, uint32_t slot)
{
    uint32_t lo = 0, hi = mesh->part_count;
    while (hi - lo > 1) { /* the last part whose first triangle is at or before slot */
        uint32_t mid = lo + (hi - lo) / 2;
        if (mesh->parts[mid].first_triangle <= slot)
            lo = mid;
        else
            hi = mid;
    }
    return mesh->part_count ? lo + 1 : 1;
}

/* What the outputs ask of triangle t->slot, whose corners are the mesh
 * vertices idx and whose geometry t holds (pinhole_triangles.h): its
 * front normal, vertex normals and part. */
static void finish_triangle(const resolve_job *job, const uint32_t idx[3], resolved_triangle *t)
{
    const sr_mesh *mesh = job->mesh;
    const sr_pinhole_outputs *out = job->out;
    if (out->normals && !out->interpolated_normals) {
        /* The loader reversed a z-negated file's winding: its front side is the other one. */
        double front[3];
        for (int k = 0; k < 3; k++)
            front[k] = mesh->z_negated ? -t->cross[k] : t->cross[k];
        normalize_into(front, t->front);
    }
    for (int c = 0; out->normals && out->interpolated_normals && c < 3; c++) {
        const float *n = mesh->normals[idx[c]];
        double file[3] = { n[0], n[1], mesh->z_negated ? -(double)n[2] : n[2] };
        rotate(job->cam, file, t->vertex_normals[c]);
    }
    t->part = out->part_ids && mesh->parts ? part_of(mesh, t->slot) : 1;
}

/* The view z of the ray through a pixel centre, ((x − cx)/fx, (y − cy)/fy, 1),
 * met with t's plane: (c·v0) / (c·ray), c = e1 × e2, the dot product summed
 * in its usual order (c0·rx + c1·ry) + c2·1, where c1·ry (cross_y) is the
 * row's and c2·1 is c2. */
static inline double plane_z(const resolved_triangle *t, double cross_y, double ray_x)
{
    return t->offset / (t->cross[0] * ray_x + cross_y + t->cross[2]);
}

static inline bool plane_z_ok(const z_window *w, double z)
{
    return z >= w->lo && z <= w->hi;
}

/* plane_z_ok's negation, in each lane's top bit. */
static inline resolve_u2 plane_z_bad(const z_window *w, resolve_v2 z)
{
    resolve_u2 above_lo = (resolve_u2)z - w->lo_bits;
    return above_lo | (above_lo + w->bias);
}

/* z[i] for the run's n pixels, whose rays' x are ray_x[i]; false if any is
 * not plane_z_ok (an edge-on triangle), which the caller then mends. */
static bool run_z(const resolved_triangle *t, const z_window *w, double ray_y, const double *ray_x, int n,
                  double *z)
{
    /* Locals: the stores to z may alias t, and would reload them. */
    double cross_y = t->cross[1] * ray_y, cross_x = t->cross[0], cross_z = t->cross[2], offset = t->offset;
    int i = 0;
    resolve_u2 bad = { 0, 0 };
    for (; i + 2 <= n; i += 2) {
        resolve_v2 rx, zv;
        memcpy(&rx, ray_x + i, sizeof rx);
        zv = offset / (cross_x * rx + cross_y + cross_z);
        bad |= plane_z_bad(w, zv);
        memcpy(z + i, &zv, sizeof zv);
    }
    bool all = ((bad[0] | bad[1]) >> 63) == 0;
    if (i < n) {
        z[i] = plane_z(t, cross_y, ray_x[i]);
        all = all && plane_z_ok(w, z[i]);
    }
    return all;
}

/* The run's view z rounded to float, two at a time. */
static void run_depth(const double *z, int n, float *depth)
{
    int i = 0;
    for (; i + 2 <= n; i += 2) {
        resolve_v2 zv;
        memcpy(&zv, z + i, sizeof zv);
        resolve_f2 f = __builtin_convertvector(zv, resolve_f2);
        memcpy(depth + i, &f, sizeof f);
    }
    if (i < n)
        depth[i] = (float)z[i];
}

/* The run's ranges |z·ray|, the ray's third coordinate 1 so the point's
 * z: its squares summed in dot product order, two at a time; the square
 * root of both lanes in one SSE2 instruction (vector extensions have
 * none, and sqrt() of a lane is a branch for errno besides), IEEE's, so
 * rounded as sqrt() rounds. */
static void run_range(const double *z, const double *ray_x, double ray_y, int n, float *range)
{
    int i = 0;
    for (; i + 2 <= n; i += 2) {
        resolve_v2 zv, rx;
        memcpy(&zv, z + i, sizeof zv);
        memcpy(&rx, ray_x + i, sizeof rx);
        resolve_v2 px = zv * rx, py = zv * ray_y, squared = px * px + py * py + zv * zv;
#if defined(__SSE2__)
        resolve_v2 length = (resolve_v2)_mm_sqrt_pd((__m128d)squared);
#else
        resolve_v2 length = { sqrt(squared[0]), sqrt(squared[1]) };
#endif
        resolve_f2 f = __builtin_convertvector(length, resolve_f2);
        memcpy(range + i, &f, sizeof f);
    }
    if (i < n) {
        double px = z[i] * ray_x[i], py = z[i] * ray_y;
        range[i] = (float)sqrt(px * px + py * py + z[i] * z[i]);
    }
}

/* The vertex normals at point p of t, weighted by its barycentrics:
 * λ1 = c·((p − v0) × e2) / c·c and λ2 = c·(e1 × (p − v0)) / c·c, c = e1 × e2. */
static void interpolated_normal(const resolved_triangle *t, const double p[3], double out[3])
{
    double w[3], a[3], b[3];
    for (int k = 0; k < 3; k++)
        w[k] = p[k] - t->v0[k];
    sr_dvec3_cross(w, t->e2, a);
    sr_dvec3_cross(t->e1, w, b);
    double l1 = sr_dvec3_dot(t->cross, a) / t->cross_squared, l2 = sr_dvec3_dot(t->cross, b) / t->cross_squared;
    for (int k = 0; k < 3; k++)
        out[k] = (1.0 - l1 - l2) * t->vertex_normals[0][k] + l1 * t->vertex_normals[1][k] +
                 l2 * t->vertex_normals[2][k];
}

/* A resolve's threads at most, as a draw's (draw_state.h). */
#define RESOLVE_MAX_THREADS 64

/* A row's runs of pixels that show one primitive, left to right: run r
 * covers columns start[r] .. start[r + 1] − 1 and shows id[r] (0:
 * nothing); start[count] is the row's width. Found once per row, and
 * then the prefetches and the resolve walk the runs, not the pixels.
 * corners[r]: the mesh vertices of triangle id[r] − 1, noted as its
 * vertices are prefetched (where id[r] is a triangle of the mesh's). */
typedef struct row_runs {
    int count;
    int *start;  /* width + 1 */
    uint32_t *id; /* width */
    uint32_t (*corners)[3]; /* width */
} row_runs;

/* A thread's rows in flight: the runs of the row it resolves and of the
 * two ahead whose loads it has started (indexed by row modulo 3), and a
 * row of view z. */
typedef struct resolve_scratch {
    row_runs runs[3];
    double *z;
} resolve_scratch;

/* The triangles a thread keeps resolved, by slot modulo this many: a
 * row's pixels come back to the triangles of the row above, and a
 * triangle's set-up costs many pixels' work. */
#define TRIANGLE_CACHE 256

/* value into to[0 .. n), four at a time: most of a frame's pixels may
 * show nothing. */
static void fill_floats(float *to, float value, int n)
{
    typedef float f4 __attribute__((vector_size(16)));
    f4 four = { value, value, value, value };
    int i = 0;
    for (; i + 4 <= n; i += 4)
        memcpy(to + i, &four, sizeof four);
    for (; i < n; i++)
        to[i] = value;
}

/* The n pixels from `at` on, where nothing is drawn. */
static void resolve_empty(const sr_pinhole_outputs *out, size_t at, int n)
{
    if (out->depth)
        fill_floats(&out->depth[at], out->invalid, n);
    if (out->range)
        fill_floats(&out->range[at], out->invalid, n);
    if (out->part_ids)
        memset(&out->part_ids[at], 0, (size_t)n * sizeof *out->part_ids);
    if (out->normals)
        memset(&out->normals[3 * at], 0, 3 * (size_t)n * sizeof *out->normals);
}

/* A run of n pixels of row y from column x that show triangle t: its view
 * z into z[0..n), each output from it. */
static void resolve_run(const resolve_job *job, const resolved_triangle *t, int y, int x, int n, double *z)
{
    const sr_pinhole_outputs *out = job->out;
    size_t at = (size_t)y * (size_t)job->fb->width + (size_t)x;
    double ray_y = job->ray_y[y];
    const double *ray_x = job->ray_x + x;
    if (!run_z(t, &job->window, ray_y, ray_x, n, z))
        for (int i = 0; i < n; i++)
            if (!plane_z_ok(&job->window, z[i])) /* the ray runs in the plane: an edge-on triangle */
                z[i] = z_of_depth(job->cam, job->fb->depth[at + i]);
    if (out->depth)
        run_depth(z, n, &out->depth[at]);
    if (out->range)
        run_range(z, ray_x, ray_y, n, &out->range[at]);
    for (int i = 0; out->part_ids && i < n; i++)
        out->part_ids[at + i] = t->part;
    if (!out->normals)
        return;
    float *normals = &out->normals[3 * at];
    if (!out->interpolated_normals)
        for (int i = 0; i < n; i++)
            memcpy(&normals[3 * i], t->front, sizeof t->front);
    else
        for (int i = 0; i < n; i++) {
            const double p[3] = { z[i] * ray_x[i], z[i] * ray_y, z[i] };
            double normal[3];
            interpolated_normal(t, p, normal);
            normalize_into(normal, &normals[3 * i]);
        }
}

/* A row of face ids from its ids: the plane itself, or each triangle's
 * file face + 1 where the file's faces are asked for and the mesh has them. */
static void write_face_ids(const resolve_job *job, const uint32_t *ids, uint32_t *face_ids)
{
    const sr_mesh *mesh = job->mesh;
    int width = job->fb->width;
    if (!job->out->file_faces || !mesh->file_faces) {
        memcpy(face_ids, ids, (size_t)width * sizeof *ids);
        return;
    }
    for (int x = 0; x < width; x++) /* an id past the mesh's stops the resolve after this row */
        face_ids[x] = ids[x] && ids[x] <= job->slots ? mesh->file_faces[ids[x] - 1] + 1 : 0;
}

/* The runs of a row of ids: from its second pixel on, a run's pixels are
 * compared eight at a time, as four pairs against the id twice over. */
static void find_runs(const uint32_t *ids, int width, row_runs *r)
{
    int n = 0;
    for (int x = 0; x < width;) {
        uint32_t id = ids[x];
        r->start[n] = x;
        r->id[n++] = id;
        uint64_t twice = (uint64_t)id * 0x100000001u, pairs[4];
        for (x++; width - x >= 8 && ids[x] == id; x += 8) {
            memcpy(pairs, ids + x, sizeof pairs);
            if ((pairs[0] ^ twice) | (pairs[1] ^ twice) | (pairs[2] ^ twice) | (pairs[3] ^ twice))
                break;
        }
        for (; x < width && ids[x] == id;)
            x++;
    }
    r->start[n] = width;
    r->count = n;
}

/* Readies the triangles of a row's runs: prefetches their indices (stage
 * 0) or, those fetched a row before, notes each triangle's corners
 * (row_runs.corners, which the set-up reads) and prefetches its vertices
 * (stage 1). On
 * a dense mesh nearly every pixel shows a triangle of its own, far from
 * its neighbours' in the mesh's arrays, and each set-up would wait on
 * memory twice (its indices, then its vertices and normals), one triangle
 * after the other; resolve_rows fetches the indices two rows ahead and
 * the vertices one row ahead, so a row's loads are under way at once. */
static void ready_runs(const resolve_job *job, row_runs *r, int stage)
{
    const sr_mesh mesh = *job->mesh; /* a copy: the stores of corners could alias its members */
    bool file_faces = job->out->face_ids && job->out->file_faces && mesh.file_faces;
    bool vertex_normals = job->out->normals && job->out->interpolated_normals;
    uint32_t slots = job->slots;
    if (!sr_assemble_triangles(&mesh)) /* points and lines: their slots are not triples */
        return;
    for (int i = 0; i < r->count; i++) {
        uint32_t id = r->id[i];
        if (id == 0 || id > slots)
            continue;
        if (stage == 0) {
            __builtin_prefetch(sr_assemble_slot_indices(&mesh, id - 1));
            if (file_faces)
                __builtin_prefetch(&mesh.file_faces[id - 1]);
            continue;
        }
        uint32_t *idx = r->corners[i];
        sr_assemble_triangle(&mesh, id - 1, idx); /* drawn, so not degenerate */
        for (int k = 0; k < 3; k++) {
            __builtin_prefetch(mesh.positions[idx[k]]);
            if (vertex_normals)
                __builtin_prefetch(mesh.normals[idx[k]]);
        }
    }
}

/* Row y's runs into the thread's ring, their indices prefetched. */
static void start_row(const resolve_job *job, resolve_scratch *s, int y)
{
    row_runs *r = &s->runs[y % 3];
    find_runs(job->ids + (size_t)y * (size_t)job->fb->width, job->fb->width, r);
    ready_runs(job, r, 0);
}

/* Pixel `at` showing point or line slot id − 1: each output from the
 * primitive's point nearest its ray. Per pixel: a point cloud's pixels
 * rarely share a primitive with their neighbours for long. */
static bool resolve_sparse_pixel(const resolve_job *job, uint32_t id, size_t at, double ray_x, double ray_y)
{
    const sr_pinhole_outputs *out = job->out;
    sr_seen_point sp;
    if (!sr_pinhole_seen_point(job->cam, &job->frame, job->mesh, id - 1, ray_x, ray_y, &sp))
        return false;
    if (out->depth)
        out->depth[at] = (float)sp.p[2];
    if (out->range)
        out->range[at] = (float)sqrt(sr_dvec3_dot(sp.p, sp.p));
    if (out->part_ids)
        out->part_ids[at] = job->mesh->parts ? part_of(job->mesh, id - 1) : 1;
    if (!out->normals)
        return true;
    double normal[3];
    for (int k = 0; k < 3; k++) {
        const float *n0 = job->mesh->normals[sp.idx[0]], *n1 = job->mesh->normals[sp.idx[1]];
        double z_sign = job->mesh->z_negated && k == 2 ? -1.0 : 1.0;
        normal[k] = z_sign * ((1.0 - sp.t) * n0[k] + sp.t * n1[k]);
    }
    double camera[3];
    rotate(job->cam, normal, camera);
    normalize_into(camera, &out->normals[3 * at]);
    return true;
}

/* The triangles one batch sets up in lanes at most. */
#define TRIANGLE_BATCH 64

/* A thread's triangles: entry[slot % TRIANGLE_CACHE] holds triangle slot
 * once set up, and `batch` counts the batches it has gathered. */
typedef struct triangle_cache {
    resolved_triangle entry[TRIANGLE_CACHE];
    uint64_t batch;
} triangle_cache;

/* The runs from *next on that one batch serves: each run's triangle
 * found in the cache or, not there, set up into its entry, all those
 * together in lanes. The batch ends before a run whose entry it already
 * holds for another triangle, so every entry it sets up serves its runs
 * until they are resolved. *next becomes the first run it does not serve.
 * Returns 0, or the id of the run it stops before that is no triangle of
 * the mesh (or one whose vertices it lacks). */
static uint32_t set_up_batch(const resolve_job *job, const row_runs *r, int *next, triangle_cache *cache)
{
    const sr_mesh *mesh = job->mesh;
    uint32_t corners[TRIANGLE_BATCH][3], n = 0, stranger = 0;
    resolved_triangle *to[TRIANGLE_BATCH];
    uint64_t batch = ++cache->batch;
    int i = *next;
    for (; i < r->count && n < TRIANGLE_BATCH; i++) {
        uint32_t id = r->id[i];
        if (id == 0)
            continue;
        resolved_triangle *t = &cache->entry[(id - 1) % TRIANGLE_CACHE];
        if (t->slot == id - 1) { /* set up before (so a triangle of the mesh's): the batch holds it from here */
            t->claim = batch;
            continue;
        }
        const uint32_t *idx = r->corners[i];
        if (id > job->slots || idx[0] >= mesh->vertex_count || idx[1] >= mesh->vertex_count ||
            idx[2] >= mesh->vertex_count) {
            stranger = id;
            break;
        }
        if (t->claim == batch) /* held for another triangle */
            break;
        t->slot = id - 1;
        t->claim = batch;
        memcpy(corners[n], idx, sizeof corners[n]);
        to[n++] = t;
    }
    *next = i;
    if (n == 0)
        return stranger;
    (job->avx2 ? sr_pinhole_triangles_avx2 : sr_pinhole_triangles_sse2)(
        &job->frame, (const float(*)[3])mesh->positions, (const uint32_t(*)[3])corners, to, n);
    for (uint32_t k = 0; k < n; k++)
        finish_triangle(job, corners[k], to[k]);
    return stranger;
}

/* Row y's runs of triangles, a batch at a time. Returns 0, or the id of
 * the run it stops at that is no triangle of the mesh. */
static uint32_t resolve_triangle_runs(const resolve_job *job, int y, const row_runs *r, double *z,
                                      triangle_cache *cache)
{
    size_t row = (size_t)y * (size_t)job->fb->width;
    for (int i = 0; i < r->count;) {
        int first = i;
        uint32_t stranger = set_up_batch(job, r, &i, cache);
        for (int k = first; k < i; k++) {
            uint32_t id = r->id[k];
            int x = r->start[k], end = r->start[k + 1];
            if (id == 0)
                resolve_empty(job->out, row + (size_t)x, end - x);
            else
                resolve_run(job, &cache->entry[(id - 1) % TRIANGLE_CACHE], y, x, end - x, z + x);
        }
        if (stranger)
            return stranger;
    }
    return 0;
}

/* Row y's runs of points or lines, pixel by pixel. Returns 0, or the id
 * of the run it stops at that is no primitive of the mesh. */
static uint32_t resolve_sparse_runs(const resolve_job *job, int y, const row_runs *r)
{
    size_t row = (size_t)y * (size_t)job->fb->width;
    for (int i = 0; i < r->count; i++) {
        uint32_t id = r->id[i];
        int x = r->start[i], end = r->start[i + 1];
        if (id == 0) {
            resolve_empty(job->out, row + (size_t)x, end - x);
            continue;
        }
        if (id > job->slots)
            return id;
        for (int k = x; k < end; k++)
            if (!resolve_sparse_pixel(job, id, row + (size_t)k, job->ray_x[k], job->ray_y[y]))
                return id;
    }
    return 0;
}

/* Rows y0 … y1 − 1: a run sets its triangle up once (or finds it in the
 * thread's cache) and each output is a loop of its own over the run.
 * Returns 0, or an id that is no primitive of the mesh (or one whose
 * vertices it lacks): the ids plane is not a draw of it, and the thread
 * stops there. */
static uint32_t resolve_rows(const resolve_job *job, int y0, int y1, resolve_scratch *s, triangle_cache *cache)
{
    const sr_pinhole_outputs *out = job->out;
    int width = job->fb->width;
    for (int y = y0; y < y0 + 2 && y < y1; y++)
        start_row(job, s, y);
    if (y0 < y1)
        ready_runs(job, &s->runs[y0 % 3], 1);
    for (int y = y0; y < y1; y++) {
        if (y + 2 < y1)
            start_row(job, s, y + 2);
        if (y + 1 < y1)
            ready_runs(job, &s->runs[(y + 1) % 3], 1);
        const uint32_t *ids = job->ids + (size_t)y * (size_t)width;
        if (out->face_ids) /* the id + 1 each pixel shows, 0 where nothing: the plane itself */
            write_face_ids(job, ids, &out->face_ids[(size_t)y * (size_t)width]);
        const row_runs *r = &s->runs[y % 3];
        uint32_t stranger = sr_assemble_triangles(job->mesh) ? resolve_triangle_runs(job, y, r, s->z, cache)
                                                               : resolve_sparse_runs(job, y, r);
        if (stranger)
            return stranger;
    }
    return 0;
}

/* One thread of a resolve: chunks of rows as they come, until none is
 * left or it meets an id that is not the mesh's (the first it meets in
 * its rows, which it takes in order). */
typedef struct resolve_thread {
    resolve_job *job; /* its next_chunk changes */
    resolve_scratch scratch;
    pthread_t thread;
    uint32_t stranger; /* resolve_rows' verdict */
    int stranger_chunk; /* the first row of the chunk it lies in */
} resolve_thread;

static void *resolve_thread_run(void *arg)
{
    resolve_thread *th = arg;
    resolve_job *job = th->job;
    int height = job->fb->height;
    triangle_cache cache = { .batch = 0 };
    for (int i = 0; i < TRIANGLE_CACHE; i++)
        cache.entry[i].slot = UINT32_MAX;
    for (;;) {
        int64_t chunk = atomic_fetch_add_explicit(&job->next_chunk, 1, memory_order_relaxed),
                first = chunk * job->chunk_rows;
        if (first >= height)
            return NULL;
        int y0 = (int)first, y1 = height - y0 > job->chunk_rows ? y0 + job->chunk_rows : height;
        th->stranger = resolve_rows(job, y0, y1, &th->scratch, &cache);
        if (th->stranger) {
            th->stranger_chunk = y0;
            return NULL;
        }
    }
}

bool sr_pinhole_resolve(const sr_pinhole *cam, const sr_mesh *mesh, const sr_framebuffer *ids,
                        const sr_pinhole_outputs *out, sr_error *err)
{
    if (!mesh->positions)
        return sr_error_set(err, "view depth needs the mesh's positions (not clip-space ones)");
    bool sparse = !sr_assemble_triangles(mesh);
    if (out->normals && (out->interpolated_normals || sparse) && !mesh->normals)
        return sr_error_set(err, sparse ? "normals of points or lines are their vertex normals, which the mesh lacks"
                                        : "interpolated normals need the mesh's vertex normals");
    if (!sr_pinhole_check(cam, err))
        return false;
    if (cam->near == 0.0)
        return sr_error_set(err, "the camera's clip planes are unset: fit them (sr_pinhole_fit_clip) as for its draw");
    if (ids->width < 1 || ids->height < 1 || !(ids->ids || ids->color) || !ids->depth)
        return sr_error_set(err, "the ids framebuffer has no pixels, or no ids, colour or depth plane");
    /* Each pixel's values are its own, whichever thread computes them: the
     * chunks change no bit. */
    int threads = out->threads < 1 ? 1 : out->threads > RESOLVE_MAX_THREADS ? RESOLVE_MAX_THREADS : out->threads;
    threads = threads > ids->height ? ids->height : threads;
    int chunks = threads == 1 ? 1 : threads * RESOLVE_CHUNKS_PER_THREAD;
    size_t width = (size_t)ids->width;
    /* Per thread: a row of z, and three rows of runs; each thread's on
     * cache lines of its own. */
    size_t run_bytes = (width + 1) * sizeof(int) + width * (sizeof(uint32_t) + 3 * sizeof(uint32_t));
    size_t per_thread = (width * sizeof(double) + 3 * run_bytes + 63) / 64 * 64;
    resolve_job job = { cam, mesh, ids, ids->ids ? ids->ids : ids->color,
                        sparse ? sr_assemble_point_line_slots(mesh) : sr_assemble_slots(mesh), out,
                        camera_frame_of(cam, mesh), sr_raster_simd_resolve(SR_SIMD_AUTO) >= SR_SIMD_AVX2,
                        z_window_of(cam), malloc(width * sizeof *job.ray_x),
                        malloc((size_t)ids->height * sizeof *job.ray_y),
                        (int)(((int64_t)ids->height + chunks - 1) / chunks), 0 };
    char *scratch = aligned_alloc(64, (size_t)threads * per_thread);
    if (!job.ray_x || !job.ray_y || !scratch) {
        free(job.ray_x);
        free(job.ray_y);
        free(scratch);
        return sr_error_set(err, "out of memory for the rays and rows of a %dx%d view", ids->width, ids->height);
    }
    for (int x = 0; x < ids->width; x++)
        job.ray_x[x] = (x - cam->cx) / cam->fx;
    for (int y = 0; y < ids->height; y++)
        job.ray_y[y] = (y - cam->cy) / cam->fy;
    resolve_thread thread[RESOLVE_MAX_THREADS];
    for (int t = 0; t < threads; t++) {
        char *mine = scratch + (size_t)t * per_thread;
        resolve_scratch *s = &thread[t].scratch;
        s->z = (double *)mine;
        mine += width * sizeof(double);
        for (int k = 0; k < 3; k++) {
            s->runs[k].start = (int *)mine;
            s->runs[k].id = (uint32_t *)(mine + (width + 1) * sizeof(int));
            s->runs[k].corners = (uint32_t(*)[3])(mine + (width + 1) * sizeof(int) + width * sizeof(uint32_t));
            mine += run_bytes;
        }
        thread[t].job = &job;
        thread[t].stranger = 0;
    }
    int started = 1; /* thread 0 is the caller */
    while (started < threads && pthread_create(&thread[started].thread, NULL, resolve_thread_run, &thread[started]) == 0)
        started++;
    resolve_thread_run(&thread[0]); /* and the rows of threads that could not start */
    uint32_t stranger = 0;
    int stranger_chunk = INT_MAX; /* the first in raster order, whatever the threads */
    for (int t = 0; t < started; t++) {
        if (t >= 1)
            pthread_join(thread[t].thread, NULL);
        if (thread[t].stranger && thread[t].stranger_chunk < stranger_chunk) {
            stranger = thread[t].stranger;
            stranger_chunk = thread[t].stranger_chunk;
        }
    }
    free(job.ray_x);
    free(job.ray_y);
    free(scratch);
    return !stranger || sr_error_set(err, "the ids plane holds id %u, and this mesh has %u primitives over %u "
                                          "vertices: it is not a draw of this mesh",
                                     stranger, job.slots, mesh->vertex_count);
}
