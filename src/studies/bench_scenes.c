#include <limits.h>
#include <stdlib.h>
#include <string.h>

#include "bench_scenes.h"
#include "data.h"

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

/* The room and its texture, wherever the program's data is (data.h). */
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
