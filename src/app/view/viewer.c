#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/app.h"
#include "scene/frame.h"
#include "overlay.h"
#include "viewer.h"

#define SPEED_PER_RADIUS 0.5f /* seconds to fly across half the scene's bounding sphere */
#define WIRE_COLOR 0x00FFFF00u
#define WIRE_CLIPPED_COLOR 0x00FF3030u
#define TEXT_COLOR 0x00FFFFFFu
#define PANEL_PAD 4

static const char HELP_TEXT[] =
    "W A S D   move          Q E    down / up\n"
    "mouse     look (hold right button, or Tab to toggle)\n"
    "Shift     faster        wheel  change speed\n"
    "R         reset camera  Esc    quit\n"
    "F1 help   F2 wireframe (clipped triangles in red)\n"
    "F3 shading mode         F5 culling mode\n"
    "F6 the mesh's edges, hidden lines removed\n"
    "F4 depth view           L  depth: z_ndc / linear distance\n"
    "Z         reversed z (near 1, far 0, GREATER) on / off\n"
    "[ ]  near plane / 2, x 2    { }  far plane / 2, x 2\n"
    "F12 save screenshot (PNG) and depth (PFM)";

static float scene_speed(const sr_mesh *mesh)
{
    vec3 lo, hi;
    if (!sr_mesh_bounds(mesh, lo, hi))
        return 1.0f;
    float radius = 0.5f * glm_vec3_distance(lo, hi);
    return radius > 0.0f ? radius * SPEED_PER_RADIUS : 1.0f;
}

bool sr_viewer_init(sr_viewer *v, const sr_scene_setup *setup, sr_error *err)
{
    *v = (sr_viewer){ .setup = *setup };
    if (!sr_scene_load(&v->setup, true, &v->scene, err))
        return false;
    sr_scene_frame_camera(&v->setup, &v->scene);
    if (!sr_camera_check(&v->setup.camera, err))
        return false;
    v->fly = v->home = sr_flycam_from_camera(&v->setup.camera);
    v->speed = scene_speed(&v->scene.mesh);
    v->display = calloc((size_t)v->scene.fb.width * (size_t)v->scene.fb.height, sizeof *v->display);
    return v->display ? true : sr_error_set(err, "out of memory for the display image");
}

void sr_viewer_free(sr_viewer *v)
{
    sr_hidden_lines_destroy(&v->wire);
    sr_scene_free(&v->scene);
    free(v->display);
    free(v->wires);
    *v = (sr_viewer){ 0 };
}

bool sr_viewer_resize(sr_viewer *v, int width, int height, sr_error *err)
{
    sr_framebuffer fb;
    if (!sr_framebuffer_create(&fb, width, height, err))
        return false;
    uint32_t *display = calloc((size_t)width * (size_t)height, sizeof *display);
    if (!display) {
        sr_framebuffer_destroy(&fb);
        return sr_error_set(err, "out of memory for a %dx%d display image", width, height);
    }
    fb.reversed_z = v->scene.fb.reversed_z;
    sr_framebuffer_destroy(&v->scene.fb);
    free(v->display);
    v->scene.fb = fb;
    v->display = display;
    v->setup.size[0] = width;
    v->setup.size[1] = height;
    return true;
}

static void collect_wire(void *user, const sr_screen_vertex tri[3], bool clipped, uint32_t id)
{
    (void)id;
    sr_viewer *v = user;
    if (v->wire_count + 3 > v->wire_cap) {
        size_t cap = v->wire_cap ? 2 * v->wire_cap : 1024;
        sr_wire *grown = realloc(v->wires, cap * sizeof *grown);
        if (!grown)
            return; /* the overlay is a view aid: a partial wireframe beats failing the frame */
        v->wires = grown;
        v->wire_cap = cap;
    }
    for (int k = 0; k < 3; k++) {
        const sr_screen_vertex *a = &tri[k], *b = &tri[(k + 1) % 3];
        v->wires[v->wire_count++] = (sr_wire){ a->x, a->y, b->x, b->y, clipped };
    }
}

static void show_image(sr_viewer *v)
{
    const sr_framebuffer *fb = &v->scene.fb;
    size_t n = (size_t)fb->width * (size_t)fb->height;
    if (!v->show_depth && v->setup.shade != SR_SHADE_DEPTH)
        memcpy(v->display, fb->color, n * sizeof *v->display);
    else if (v->depth_linear)
        sr_framebuffer_depth_to_gray_mapped(fb, sr_camera_view_distance, &v->setup.camera, v->display);
    else
        sr_framebuffer_depth_to_gray(fb, v->display);
}

static void draw_overlays(sr_viewer *v)
{
    sr_canvas canvas = { v->display, v->scene.fb.width, v->scene.fb.height };
    for (size_t i = 0; v->wireframe && i < v->wire_count; i++) {
        const sr_wire *w = &v->wires[i];
        sr_overlay_line(&canvas, w->x0, w->y0, w->x1, w->y1, w->clipped ? WIRE_CLIPPED_COLOR : WIRE_COLOR);
    }
    char status[512];
    sr_viewer_status(v, status, sizeof status);
    const char *text = v->help ? HELP_TEXT : status;
    sr_overlay_panel(&canvas, 0, 0, sr_overlay_text_width(text) + 2 * PANEL_PAD,
                     sr_overlay_text_height(text) + 2 * PANEL_PAD);
    sr_overlay_text(&canvas, PANEL_PAD, PANEL_PAD, text, TEXT_COLOR);
}

bool sr_viewer_draw(sr_viewer *v, bool overlays, sr_error *err)
{
    sr_draw_desc desc;
    sr_draw_study study;
    if (!sr_scene_desc(&v->setup, &v->scene, &desc, &study, err))
        return false;
    v->wire_count = 0;
    if (overlays && v->wireframe) {
        study.observer = collect_wire;
        study.observer_user = v;
    }
    bool ok;
    if (v->hidden_lines) {
        if (!v->wire.wire.edges.indices && !sr_hidden_lines_make(&v->scene.mesh, &v->wire, err))
            return false;
        sr_stats fill;
        ok = sr_hidden_lines_frame(&v->wire, &v->scene.fb, &desc, &fill, &v->stats, &v->frame_ms, err);
    } else {
        ok = sr_frame_draw_layers_timed(&v->scene.fb, &desc, &v->stats, &v->frame_ms, err);
    }
    show_image(v);
    if (ok && overlays)
        draw_overlays(v);
    return ok;
}

void sr_viewer_status(const sr_viewer *v, char *buf, size_t cap)
{
    const sr_stats *s = &v->stats;
    const sr_camera *cam = &v->setup.camera;
    double eye[3]; /* in the world, not relative to the camera's origin */
    for (int k = 0; k < 3; k++)
        eye[k] = cam->origin[k] + cam->eye[k];
    snprintf(buf, cap,
             "%.1f ms  %.0f fps  %s%s  cull %s  %s   F1 help\n"
             "%s %llu  rejected %llu  clipped %llu  culled %llu  drawn %llu\n"
             "cut vertices: float %llu  double %llu  exact %llu\n"
             "eye %.3g %.3g %.3g  near %.3g  far %.3g%s  speed %.3g",
             v->frame_ms, v->frame_ms > 0.0 ? 1000.0 / v->frame_ms : 0.0, SR_SHADE_NAMES[v->setup.shade],
             v->show_depth ? (v->depth_linear ? " (depth view, linear)" : " (depth view)") : "",
             SR_CULL_NAMES[v->setup.cull], sr_simd_name(sr_raster_simd_resolve((sr_simd)v->setup.simd)),
             s->lines ? "lines" : "triangles", (unsigned long long)(s->lines ? s->lines : s->triangles),
             (unsigned long long)s->rejected,
             (unsigned long long)s->clipped, (unsigned long long)s->culled, (unsigned long long)s->drawn, (unsigned long long)s->cuts_float,
             (unsigned long long)s->cuts_double, (unsigned long long)s->cuts_exact, eye[0], eye[1], eye[2],
             v->setup.camera.near, v->setup.camera.far, v->setup.camera.reversed_z ? " (reversed z)" : "", v->speed);
}

bool sr_viewer_save(const sr_viewer *v, const char *prefix, sr_error *err)
{
    char png[1024], pfm[1024];
    const sr_framebuffer *fb = &v->scene.fb;
    if (snprintf(png, sizeof png, "%s.png", prefix) >= (int)sizeof png ||
        snprintf(pfm, sizeof pfm, "%s.pfm", prefix) >= (int)sizeof pfm)
        return sr_error_set(err, "%.40s…: the path is too long (%zu bytes)", prefix, strlen(prefix) + 4);
    return sr_image_write_png(png, v->display, fb->width, fb->height, err) &&
           sr_image_write_pfm(pfm, fb->depth, fb->width, fb->height, err);
}
