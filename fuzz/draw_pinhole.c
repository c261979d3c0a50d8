/* fuzz/draw_pinhole.c — the pinhole camera's draw and resolve
 * (softrast.h, "pinhole cameras") on the fuzzer's mesh, from the bytes
 * the scene leaves: a camera (sane intrinsics and a rotation from a
 * quaternion, or raw values), the mesh as triangles, points or lines, and
 * sometimes one pixel of the ids plane overwritten.
 *
 * Invariants: a camera sr_pinhole_check refuses is refused by the resolve
 * too, with a message; the ids plane of the mesh's own draw resolves
 * (normals asked only of a mesh that has them), the same bits on one
 * thread and on several; face ids are the plane; where nothing is drawn
 * depth and range are the `invalid` value, part ids 0 and normals 0;
 * where something is, part id 1, depth not NaN and above 0, range at
 * least the depth, and a normal of length 1 or 0. An overwritten pixel
 * resolves or is refused with a message, never read out of bounds. */
#include "fuzz_draw.h"

/* A camera from the input: intrinsics for a view of the scene's size, a
 * rotation from a quaternion and a translation; or, by the mode byte,
 * raw intrinsics, a raw pose or raw clip planes. */
static sr_pinhole take_camera(reader *r, const scene *sc)
{
    uint8_t mode = take_u8(r);
    sr_pinhole cam = { 0 };
    cam.fx = sc->width * (0.125 + take_u8(r) / 32.0);
    cam.fy = cam.fx * (0.5 + take_u8(r) / 128.0);
    cam.cx = (sc->width - 1) * (take_u8(r) / 128.0);
    cam.cy = (sc->height - 1) * (take_u8(r) / 128.0);
    if (mode & 1) {
        cam.fx = take_finite_float(r);
        cam.cy = take_finite_float(r);
    }
    double q[4], n = 0.0;
    for (int k = 0; k < 4; k++) {
        q[k] = take_finite_float(r);
        n += q[k] * q[k];
    }
    if (!(n > 0.0) || !isfinite(n)) {
        q[0] = n = 1.0;
        q[1] = q[2] = q[3] = 0.0;
    }
    n = sqrt(n);
    double w = q[0] / n, x = q[1] / n, y = q[2] / n, z = q[3] / n;
    const double rot[3][3] = {
        { 1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y) },
        { 2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x) },
        { 2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y) },
    };
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++)
            cam.w2c[i][j] = rot[i][j];
        cam.w2c[i][3] = take_finite_float(r);
    }
    cam.w2c[3][3] = 1.0;
    if (mode & 2)
        cam.w2c[take_u8(r) % 4][take_u8(r) % 4] = take_finite_float(r);
    if (mode & 4) {
        cam.near = take_finite_float(r);
        cam.far = take_finite_float(r);
    }
    return cam;
}

/* The resolve's outputs, one plane each. */
typedef struct planes {
    float depth[MAX_SIDE * MAX_SIDE], range[MAX_SIDE * MAX_SIDE], normals[3 * MAX_SIDE * MAX_SIDE];
    uint32_t face_ids[MAX_SIDE * MAX_SIDE], part_ids[MAX_SIDE * MAX_SIDE];
} planes;

static sr_pinhole_outputs outputs_into(planes *p, bool normals, bool interpolated, float invalid, int threads)
{
    return (sr_pinhole_outputs){ .depth = p->depth, .range = p->range, .face_ids = p->face_ids,
                                 .part_ids = p->part_ids, .normals = normals ? p->normals : NULL,
                                 .interpolated_normals = interpolated, .invalid = invalid, .threads = threads };
}

static bool same_float(float a, float b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

/* Each pixel's outputs against what the header promises for it. */
static void check_pixels(const sr_framebuffer *fb, const planes *p, bool normals, float invalid)
{
    for (int i = 0; i < fb->width * fb->height; i++) {
        uint32_t id = fb->color[i];
        CHECK(p->face_ids[i] == id, "pixel %d: face id %u, plane %u", i, p->face_ids[i], id);
        const float *nv = &p->normals[3 * i];
        double length = sqrt((double)nv[0] * nv[0] + (double)nv[1] * nv[1] + (double)nv[2] * nv[2]);
        if (id == 0) {
            CHECK(same_float(p->depth[i], invalid) && same_float(p->range[i], invalid) && p->part_ids[i] == 0 &&
                      (!normals || length == 0.0),
                  "pixel %d shows nothing: depth %a, range %a, part %u, normal length %g", i, p->depth[i],
                  p->range[i], p->part_ids[i], length);
            continue;
        }
        CHECK(p->part_ids[i] == 1, "pixel %d: part %u of a mesh of one", i, p->part_ids[i]);
        CHECK(p->depth[i] > 0.0f, "pixel %d (id %u): depth %a", i, id, p->depth[i]);
        CHECK(p->range[i] >= p->depth[i], "pixel %d (id %u): range %a below depth %a", i, id, p->range[i],
              p->depth[i]);
        CHECK(!normals || length == 0.0 || fabs(length - 1.0) < 1e-5, "pixel %d (id %u): normal length %.9g", i, id,
              length);
    }
}

void check_pinhole(const scene *sc, reader *r)
{
    static const sr_topology topologies[] = { SR_TRIANGLE_LIST, SR_POINT_LIST, SR_LINE_LIST, SR_LINE_STRIP };
    sr_pinhole cam = take_camera(r, sc);
    uint8_t how = take_u8(r);
    sr_mesh mesh = sc->mesh;
    if (how & 3)
        mesh.topology = topologies[how & 3];
    bool normals = (how & 4) && mesh.normals, interpolated = how & 8, poke = how & 16;
    float invalid = how & 32 ? NAN : 0.0f;
    int threads = 2 + sc->threads;
    sr_error err = { "" };
    static planes one, many;
    sr_framebuffer fb;
    CHECK(sr_framebuffer_create(&fb, sc->width, sc->height, NULL), "framebuffer");
    if (!sr_pinhole_check(&cam, &err)) {
        CHECK(err.message[0], "a refused camera without a message");
        err.message[0] = '\0';
        sr_pinhole_outputs out = outputs_into(&one, normals, interpolated, invalid, 1);
        CHECK(!sr_pinhole_resolve(&cam, &mesh, &fb, &out, &err) && err.message[0],
              "a camera sr_pinhole_check refuses resolved");
        sr_framebuffer_destroy(&fb);
        return;
    }
    sr_pinhole_fit_clip(&cam, &mesh);
    sr_draw_desc desc = { .mesh = &mesh, .shade = SR_SHADE_ID, .clear = true, .point_size = 1.0f, .line_width = 1.0f };
    sr_pinhole_matrices(&cam, &mesh, &fb, &desc);
    if (!sr_draw(&fb, &desc, NULL, NULL)) {
        sr_framebuffer_destroy(&fb);
        return; /* the draws above check when a draw may fail */
    }
    if (poke) { /* any id at any pixel: small ones, and ones near the largest */
        int at = take_u8(r) % (sc->width * sc->height);
        uint8_t small = take_u8(r), id = take_u8(r);
        fb.color[at] = small & 1 ? id : UINT32_MAX - id;
    }
    sr_pinhole_outputs out_one = outputs_into(&one, normals, interpolated, invalid, 1);
    sr_pinhole_outputs out_many = outputs_into(&many, normals, interpolated, invalid, threads);
    bool ok_one = sr_pinhole_resolve(&cam, &mesh, &fb, &out_one, &err);
    CHECK(ok_one || err.message[0], "a refused resolve without a message");
    CHECK(ok_one || poke, "the plane of the mesh's own draw refused: %s", err.message);
    bool ok_many = sr_pinhole_resolve(&cam, &mesh, &fb, &out_many, &err);
    CHECK(ok_one == ok_many, "resolved %d on one thread, %d on %d", ok_one, ok_many, threads);
    if (ok_one) {
        size_t n = (size_t)sc->width * (size_t)sc->height;
        CHECK(memcmp(one.depth, many.depth, n * sizeof *one.depth) == 0 &&
                  memcmp(one.range, many.range, n * sizeof *one.range) == 0 &&
                  memcmp(one.part_ids, many.part_ids, n * sizeof *one.part_ids) == 0 &&
                  (!normals || memcmp(one.normals, many.normals, 3 * n * sizeof *one.normals) == 0),
              "one thread and %d resolve differently", threads);
        if (!poke) /* a poked id names a primitive that may lie anywhere, behind the camera too */
            check_pixels(&fb, &one, normals, invalid);
    }
    sr_framebuffer_destroy(&fb);
}
