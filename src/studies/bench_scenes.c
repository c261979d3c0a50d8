#include <limits.h>
#include <stdlib.h>
#include <string.h>

#include "bench_scenes.h"
#include "io/data_find.h"

#define FILL_QUADS 64
#define CHECKER_SIDE 256
#define CHECKER_CELL 32

/* Key frames through the room (eye, target, up, fov, near, far): through the
 * west pillar and wall, back in at a slant, up through the ceiling. */
static float FLY_KEYS[][SR_FLIGHT_NUMBERS] = {
    { -8.0f, 3.0f, -8.0f, 4.0f, 1.5f, 6.0f, 0, 1, 0, 75, 0.1f, 100 },
    { 0.0f, 2.0f, 0.0f, -20.0f, 2.0f, 0.0f, 0, 1, 0, 75, 0.1f, 100 },
    { -5.0f, 2.0f, 0.0f, -25.0f, 2.0f, 0.0f, 0, 1, 0, 75, 0.1f, 100 },
    { -10.0f, 2.0f, 0.3f, -30.0f, 2.0f, 0.3f, 0, 1, 0, 75, 0.1f, 100 },
    { -10.0f, 3.0f, -4.1f, 0.0f, 1.0f, -6.0f, 0, 1, 0, 90, 0.1f, 100 },
    { 2.0f, 5.9f, 2.0f, 2.0f, 0.0f, 2.001f, 0, 1, 0, 60, 0.1f, 100 },
};

/* The room again with stiff planes (near 1e-6, far 1e9): along the west wall,
 * on its plane, a hair above the floor. */
static float STIFF_KEYS[][SR_FLIGHT_NUMBERS] = {
    { -8.0f, 3.0f, -8.0f, 4.0f, 1.5f, 6.0f, 0, 1, 0, 75, 1e-6f, 1e9f },
    { -10.0f, 2.0f, 0.0f, 10.0f, 2.0f, 0.0f, 0, 1, 0, 75, 1e-6f, 1e9f },
    { 0.0f, 1e-6f, 0.0f, 5.0f, 0.0f, 5.0f, 0, 1, 0, 120, 1e-6f, 1e9f },
};

/* The scanned meshes' views (eye, target, fov, near, far), in the mesh's
 * loaded coordinates (OBJ's z negated); bench_scenes.h says what each shows. */
typedef struct scan_view {
    const char *name, *what, *file;
    vec3 eye, target;
    float fov, near, far;
} scan_view;

static const scan_view SCAN_VIEWS[] = {
    { "dragon", "the Stanford dragon, 202k triangles, near 0.1, far 100, steep silhouettes", "build/scans/dragon.obj",
      { -0.12f, 0.15f, 0.14f }, { -0.005f, 0.125f, 0.0f }, 60, 0.1f, 100 },
    { "dragon-close", "the dragon at 48k triangles, camera a hair off its back, fov 100, near 1e-3, far 10",
      "build/scans/dragon-48k.obj", { 0.03f, 0.15f, -0.012f }, { -0.1f, 0.13f, 0.0f }, 100, 1e-3f, 10 },
    { "bunny-stiff", "the Stanford bunny (3674 triangles), its head close by, fov 90, near 1e-3, far 1e6, standard z",
      "build/scans/bunny.obj", { -4.5f, 5.5f, -4.0f }, { 0.0f, 4.3f, 0.0f }, 90, 1e-3f, 1e6f },
};

static void scene_init(sr_bench_scene *s, const char *name, const char *what, sr_shade shade, int w, int h)
{
    *s = (sr_bench_scene){ .name = name, .what = what, .shade = shade, .width = w, .height = h,
                           .camera = sr_camera_default() };
}

/* The torus of the dense scenes: radius 1, tube 0.4, about `triangles`. */
static bool make_torus(sr_bench_scene *s, uint64_t triangles, sr_error *err)
{
    uint32_t segments, sides;
    sr_shape_torus_grid(triangles, &segments, &sides);
    return sr_shape_torus(&s->mesh, 1.0f, 0.4f, segments, sides, err);
}

bool sr_bench_dense(sr_bench_scene *s, uint64_t triangles, int width, int height, sr_shade shade, sr_error *err)
{
    scene_init(s, shade == SR_SHADE_DEPTH ? "depth" : "dense", "closed torus, lambert", shade, width, height);
    if (shade == SR_SHADE_DEPTH)
        s->what = "the dense torus in the depth view: no varyings";
    glm_vec3_copy((vec3){ 0.0f, 1.1f, -1.9f }, s->camera.eye);
    return make_torus(s, triangles, err);
}

bool sr_bench_dense_default(sr_bench_scene *s, sr_error *err)
{
    return sr_bench_dense(s, SR_BENCH_DENSE_TRIANGLES, 1920, 1080, SR_SHADE_LAMBERT, err);
}

bool sr_bench_scan_view(sr_bench_scene *s, int v, sr_error *err)
{
    static const char *const names[SR_BENCH_SCAN_VIEWS] = { "scan-640x480", "scan-640x480-cull", "scan-320x240",
                                                            "scan-320x240-cull" };
    bool small = v >= 2, cull = v % 2 == 1;
    if (!sr_bench_dense(s, SR_BENCH_DENSE_TRIANGLES, small ? 320 : 640, small ? 240 : 480, SR_SHADE_ID, err))
        return false;
    s->name = names[v];
    s->what = "the dense torus at a vision user's size, face ids";
    s->cull = cull ? SR_CULL_BACK : SR_CULL_NONE;
    return true;
}

/* The room and its texture, wherever the program's data is (io/data_find.h). */
static bool load_room(sr_bench_scene *s, sr_error *err)
{
    char obj[PATH_MAX], png[PATH_MAX];
    return sr_data_find("assets/room.obj", obj, sizeof obj, err) && sr_data_find("assets/room.png", png, sizeof png, err) &&
           sr_obj_load(&s->mesh, obj, err) && sr_texture_load(&s->texture, png, err);
}

bool sr_bench_inside(sr_bench_scene *s, sr_error *err)
{
    scene_init(s, "inside", "inside the dense torus's tube, near 0.01, no culling, lambert", SR_SHADE_LAMBERT,
               1920, 1080);
    s->cull = SR_CULL_NONE;
    /* Off the tube's centre line (radius 1, tube 0.4), looking along it. */
    glm_vec3_copy((vec3){ 1.1f, 0.1f, 0.0f }, s->camera.eye);
    glm_vec3_copy((vec3){ 0.9f, 0.0f, 1.0f }, s->camera.target);
    s->camera.near = 0.01f;
    return make_torus(s, SR_BENCH_DENSE_TRIANGLES, err);
}

bool sr_bench_fly(sr_bench_scene *s, sr_error *err)
{
    scene_init(s, "fly", "the room on a path through walls and pillars, lambert + texture", SR_SHADE_LAMBERT,
               1920, 1080);
    s->path = (sr_flight){ .count = sizeof FLY_KEYS / sizeof FLY_KEYS[0], .keys = FLY_KEYS };
    return load_room(s, err);
}

bool sr_bench_stiff(sr_bench_scene *s, sr_error *err)
{
    scene_init(s, "stiff", "the room with near 1e-6 and far 1e9, on and beside its walls and floor",
               SR_SHADE_LAMBERT, 1920, 1080);
    s->path = (sr_flight){ .count = sizeof STIFF_KEYS / sizeof STIFF_KEYS[0], .keys = STIFF_KEYS };
    return load_room(s, err);
}

static bool load_scan(sr_bench_scene *s, const scan_view *v, sr_error *err)
{
    scene_init(s, v->name, v->what, SR_SHADE_LAMBERT, 1920, 1080);
    memcpy(s->camera.eye, v->eye, sizeof(vec3));
    memcpy(s->camera.target, v->target, sizeof(vec3));
    s->camera.fov_deg = v->fov;
    s->camera.near = v->near;
    s->camera.far = v->far;
    char obj[PATH_MAX];
    if (!sr_data_find(v->file, obj, sizeof obj, err))
        return sr_error_set(err, "%s is missing: `make scans` fetches it (tools/fetch-scans, with npm)", v->file);
    return sr_obj_load(&s->mesh, obj, err);
}

bool sr_bench_scan_dragon(sr_bench_scene *s, sr_error *err)
{
    return load_scan(s, &SCAN_VIEWS[0], err);
}

bool sr_bench_scan_close(sr_bench_scene *s, sr_error *err)
{
    return load_scan(s, &SCAN_VIEWS[1], err);
}

bool sr_bench_scan_stiff(sr_bench_scene *s, sr_error *err)
{
    return load_scan(s, &SCAN_VIEWS[2], err);
}

/* A two-tone checker, so bilinear filtering has edges to blend. */
static bool make_checker(sr_texture *t, sr_error *err)
{
    t->texels = malloc((size_t)CHECKER_SIDE * CHECKER_SIDE * sizeof *t->texels);
    if (!t->texels)
        return sr_error_set(err, "out of memory for the checker texture");
    t->width = t->height = CHECKER_SIDE;
    for (int y = 0; y < CHECKER_SIDE; y++)
        for (int x = 0; x < CHECKER_SIDE; x++)
            t->texels[y * CHECKER_SIDE + x] = ((x / CHECKER_CELL + y / CHECKER_CELL) & 1) ? 0xD0C090u : 0x304060u;
    return true;
}

/* FILL_QUADS full-screen quads under an orthographic camera, far to near,
 * so every quad passes the depth test over the last. */
static bool make_fill(sr_bench_scene *s, sr_error *err)
{
    glm_vec3_copy((vec3){ 0.0f, 0.0f, 0.0f }, s->camera.eye);
    glm_vec3_copy((vec3){ 0.0f, 0.0f, 1.0f }, s->camera.target);
    s->camera.ortho_height = 2.0f;
    return sr_shape_quads(&s->mesh, FILL_QUADS, 4.0f, 64.0f, -0.5f, err);
}

bool sr_bench_fill(sr_bench_scene *s, sr_error *err)
{
    scene_init(s, "fill", "64 full-screen textured quads back to front, bilinear", SR_SHADE_TEXTURE, 1920, 1080);
    return make_fill(s, err) && make_checker(&s->texture, err);
}

bool sr_bench_points(sr_bench_scene *s, sr_error *err)
{
    scene_init(s, "points", "1M coloured points over the torus's surface, 1 px, depth tested", SR_SHADE_COLOR,
               1920, 1080);
    glm_vec3_copy((vec3){ 0.0f, 1.1f, -1.9f }, s->camera.eye);
    return sr_shape_torus_cloud(&s->mesh, 1.0f, 0.4f, SR_BENCH_POINTS, err);
}

bool sr_bench_fill_flat(sr_bench_scene *s, sr_error *err)
{
    scene_init(s, "fill-flat", "64 full-screen untextured quads back to front, lambert", SR_SHADE_LAMBERT, 1920,
               1080);
    return make_fill(s, err);
}

void sr_bench_scene_free(sr_bench_scene *s)
{
    sr_mesh_free(&s->mesh);
    sr_texture_free(&s->texture);
    *s = (sr_bench_scene){ 0 };
}

void sr_bench_scene_camera(const sr_bench_scene *s, int f, int n, sr_camera *cam)
{
    if (s->path.count)
        sr_flight_camera(&s->path, f, n, cam);
    else
        *cam = s->camera;
}
