/* bench_scenes.h — the benchmark's scenes: made in memory where they can be
 * (a dense torus seen from outside and from inside its tube, full-screen
 * quads textured and untextured), read from the program's data (the room)
 * or from build/scans (the scanned meshes, `make scans`). */
#ifndef SOFTRAST_APP_BENCH_SCENES_H
#define SOFTRAST_APP_BENCH_SCENES_H

#include "scene/flight.h"
#include "softrast_private.h"

#define SR_BENCH_DENSE_TRIANGLES 1048576u

typedef struct sr_bench_scene {
    const char *name, *what;
    sr_mesh mesh;
    sr_texture texture;
    sr_shade shade;
    sr_cull cull; /* 0: back faces culled */
    int width, height;
    sr_camera camera;  /* the fixed camera, when path.count is 0 */
    sr_flight path;    /* a camera path over the timed frames */
} sr_bench_scene;

/* A torus of about `triangles` triangles filling most of the frame. */
bool sr_bench_dense(sr_bench_scene *s, uint64_t triangles, int width, int height, sr_shade shade, sr_error *err);

/* The dense scene as the benchmark times it: 1M triangles at 1920x1080. */
bool sr_bench_dense_default(sr_bench_scene *s, sr_error *err);

/* The camera inside the dense torus's tube, near 0.01, no culling: most
 * triangles are behind the camera or cut by the near plane, and the walls
 * ahead overlap many times. */
bool sr_bench_inside(sr_bench_scene *s, sr_error *err);

/* The dense torus as a vision user renders a scan: SR_BENCH_DENSE_TRIANGLES
 * triangles at 640x480 and 320x240, face ids, culling off (a ray caster
 * sees both faces) and on; most triangles cover no pixel centre. View v of
 * SR_BENCH_SCAN_VIEWS, named scan-WxH or scan-WxH-cull. */
#define SR_BENCH_SCAN_VIEWS 4
bool sr_bench_scan_view(sr_bench_scene *s, int v, sr_error *err);

/* The room from assets/, on a path through its walls and pillars. */
bool sr_bench_fly(sr_bench_scene *s, sr_error *err);

/* The room with near 1e-6 and far 1e9, on and beside its walls. */
bool sr_bench_stiff(sr_bench_scene *s, sr_error *err);

/* Scanned meshes (build/scans/, fetched by `make scans`: tools/fetch-scans),
 * one camera each, id-comparable by the report and bench-gl --truth:
 * the 202k-triangle dragon whole, near 0.1, far 100, its horns, claws and
 * body edge-on at the silhouettes; */
bool sr_bench_scan_dragon(sr_bench_scene *s, sr_error *err);

/* the 48k-triangle dragon with the camera a hair off its back, fov 100,
 * near 1e-3, far 10: the body's surface fills half the frame at grazing
 * angles, the head and horns behind it; */
bool sr_bench_scan_close(sr_bench_scene *s, sr_error *err);

/* the bunny (3674 triangles) with stiff planes, near 1e-3, far 1e6,
 * standard z: its head from close by, fov 90, edge-on against its back. */
bool sr_bench_scan_stiff(sr_bench_scene *s, sr_error *err);

/* 64 full-screen textured quads drawn back to front, bilinear. */
bool sr_bench_fill(sr_bench_scene *s, sr_error *err);

/* The same quads untextured, lambert: the per-pixel loop's peak rate, every
 * pixel shaded 64 times (bench prints it in Gpix/s). */
bool sr_bench_fill_flat(sr_bench_scene *s, sr_error *err);

/* A point cloud: SR_BENCH_POINTS points with colours over the dense
 * torus's surface (the dense camera), drawn 1 pixel each with depth at
 * 1920x1080, colour shading; many land on the same pixel, so the depth
 * test decides which shows. */
#define SR_BENCH_POINTS 1048576u
bool sr_bench_points(sr_bench_scene *s, sr_error *err);

void sr_bench_scene_free(sr_bench_scene *s);

/* The camera of frame f of n. */
void sr_bench_scene_camera(const sr_bench_scene *s, int f, int n, sr_camera *cam);

#endif
