/* softrast view — the fly-through window, and scripted flights. */
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/app.h"
#include "io/output_file.h"
#include "scene/flight.h"
#include "io/data_find.h"
#include "softrast_private.h"
#include "viewer.h"

#define DEFAULT_SCENE "assets/room.obj"
#define MAX_FRAMES 100000
#define MAX_KEYS_TEXT 256
#define TITLE_EVERY_MS 250.0

/* Where the default scene is first seen from: inside the room, by a pillar. */
static const sr_camera ROOM_SPAWN = { .eye = { -8.0f, 3.0f, -8.0f }, .target = { 4.0f, 1.5f, 6.0f },
                                      .up = { 0.0f, 1.0f, 0.0f }, .fov_deg = 75.0f,
                                      .near = SR_CAMERA_NEAR, .far = SR_CAMERA_FAR };

typedef struct view_job {
    sr_scene_setup scene;
    const char *script_path, *shots_dir, *grab_dir, *keys;
    int frames;
    int range[2]; /* --frame-range A:B: frames A up to, not including, B */
    bool range_set, no_window, overlays;
    char default_scene[PATH_MAX]; /* where the default scene was found */
} view_job;

/* The window and what presents the framebuffer in it (no GPU rendering of
 * the scene: the CPU image is copied into a streaming texture). */
typedef struct window {
    SDL_Window *window;
    SDL_Renderer *renderer;
    SDL_Texture *texture;
} window;

static const char USAGE[] =
    "usage: softrast view [MESH.obj] [options]\n"
    "Flies a camera through MESH.obj (default: " DEFAULT_SCENE ", a room to fly through).\n"
    "Press F1 in the window for the keys. With --script the camera follows a path instead;\n"
    "--shots saves every frame, and works with no display (SDL_VIDEODRIVER=offscreen, or --no-window).";

static bool parse_job(void *j, int argc, char **argv, bool *help, sr_error *err)
{
    view_job *job = j;
    const sr_option own[] = {
        { "--script", SR_OPT_STRING, &job->script_path, "FILE", "fly the key frames in FILE (one line each: eye target up fov near far)" },
        { "--frames", SR_OPT_INT, &job->frames, "N", "frames of the scripted flight (default: one per key frame)", 1, MAX_FRAMES },
        { "--frame-range", SR_OPT_RANGE, job->range, "A:B", "fly only frames A up to, not including, B (a shard; files keep their global frame numbers)", 0, MAX_FRAMES, .seen = &job->range_set },
        { "--shots", SR_OPT_STRING, &job->shots_dir, "DIR", "save each scripted frame as DIR/frame-NNNN.png and .pfm" },
        { "--grab", SR_OPT_STRING, &job->grab_dir, "DIR", "save what the window shows of each scripted frame as DIR/window-NNNN.png" },
        { "--no-window", SR_OPT_FLAG, &job->no_window, NULL, "scripted flight without opening a window" },
        { "--keys", SR_OPT_STRING, &job->keys, "K1,K2,...", "press these keys first (SDL names: F2,F4,L,...), as if typed" },
        { "--overlays", SR_OPT_FLAG, &job->overlays, NULL, "draw the status line, help and wireframe on scripted frames too" },
        { 0 },
    };
    if (!sr_scene_setup_parse(&job->scene, own, NULL, USAGE, argc, argv, help, err))
        return false;
    if (!job->script_path &&
        (job->shots_dir || job->grab_dir || job->frames || job->range_set || job->no_window || job->overlays))
        return sr_error_set(err,
                            "--frames, --frame-range, --shots, --grab, --no-window and --overlays go with --script");
    if (job->grab_dir && job->no_window)
        return sr_error_set(err, "--grab reads the window back, so it cannot go with --no-window");
    return true;
}

/* With no MESH, the room from the program's data (io/data_find.h), into path. */
static bool use_default_scene(view_job *job, sr_error *err)
{
    if (job->scene.mesh_path)
        return true;
    if (!sr_data_find(DEFAULT_SCENE, job->default_scene, sizeof job->default_scene, err))
        return false;
    job->scene.mesh_path = job->default_scene;
    if (!job->scene.eye_set && !job->scene.target_set) {
        for (int k = 0; k < 3; k++) {
            job->scene.eye[k] = ROOM_SPAWN.eye[k];
            job->scene.target[k] = ROOM_SPAWN.target[k];
        }
        job->scene.camera.fov_deg = ROOM_SPAWN.fov_deg;
        job->scene.eye_set = job->scene.target_set = true;
    }
    return true;
}

static void window_close(window *w)
{
    if (w->texture)
        SDL_DestroyTexture(w->texture);
    if (w->renderer)
        SDL_DestroyRenderer(w->renderer);
    if (w->window)
        SDL_DestroyWindow(w->window);
    *w = (window){ 0 };
}

static bool window_texture(window *w, int width, int height, sr_error *err)
{
    if (w->texture)
        SDL_DestroyTexture(w->texture);
    /* RGB888 is 0x00RRGGBB in a 32-bit word: the framebuffer's own layout. */
    w->texture = SDL_CreateTexture(w->renderer, SDL_PIXELFORMAT_RGB888, SDL_TEXTUREACCESS_STREAMING, width, height);
    return w->texture ? true : sr_error_set(err, "cannot make a %dx%d texture: %s", width, height, SDL_GetError());
}

static bool window_open(window *w, int width, int height, sr_error *err)
{
    *w = (window){ 0 };
    w->window = SDL_CreateWindow("softrast", SDL_WINDOWPOS_CENTERED, SDL_WINDOWPOS_CENTERED, width, height,
                                 SDL_WINDOW_RESIZABLE);
    if (w->window)
        w->renderer = SDL_CreateRenderer(w->window, -1, 0);
    if (!w->renderer) {
        sr_error_set(err, "cannot open a window: %s (no display? a scripted flight runs without one: --no-window)",
                     SDL_GetError());
        window_close(w);
        return false;
    }
    return window_texture(w, width, height, err);
}

static void window_present(window *w, const sr_viewer *v)
{
    SDL_UpdateTexture(w->texture, NULL, v->display, v->scene.fb.width * (int)sizeof *v->display);
    SDL_RenderClear(w->renderer);
    SDL_RenderCopy(w->renderer, w->texture, NULL, NULL);
    SDL_RenderPresent(w->renderer);
}

/* Reads back what the window shows, as a person's screenshot would. The
 * window must still be the framebuffer's size: a window resized during a
 * scripted flight would be read at its new size. */
static bool window_grab(window *w, const sr_viewer *v, const char *path, sr_error *err)
{
    const sr_framebuffer *fb = &v->scene.fb;
    int out_w = 0, out_h = 0;
    if (SDL_GetRendererOutputSize(w->renderer, &out_w, &out_h) != 0 || out_w != fb->width || out_h != fb->height)
        return sr_error_set(err, "--grab: the window is %dx%d, not the framebuffer's %dx%d (was it resized?)", out_w,
                            out_h, fb->width, fb->height);
    uint32_t *pixels = SDL_malloc((size_t)fb->width * (size_t)fb->height * sizeof *pixels);
    SDL_Rect all = { 0, 0, fb->width, fb->height };
    bool ok = pixels && SDL_RenderReadPixels(w->renderer, &all, SDL_PIXELFORMAT_RGB888, pixels,
                                             fb->width * (int)sizeof *pixels) == 0;
    ok = ok ? sr_image_write_png(path, pixels, fb->width, fb->height, err)
            : sr_error_set(err, "cannot read the window back: %s", SDL_GetError());
    SDL_free(pixels);
    return ok;
}

/* Digits of a flight's frame numbers: 4, or as many as its last frame
 * needs, so that the files of any flight (and of each of its shards) sort
 * in frame order. */
static int frame_digits(int frames)
{
    int digits = 4;
    for (int last = frames - 1; last >= 10000; last /= 10)
        digits++;
    return digits;
}

static bool save_frame(const char *dir, int digits, int frame, const sr_viewer *v, sr_error *err)
{
    char prefix[1024];
    if (snprintf(prefix, sizeof prefix, "%s/frame-%0*d", dir, digits, frame) >= (int)sizeof prefix)
        return sr_error_set(err, "--shots: the folder's path is too long (%zu bytes)", strlen(dir));
    return sr_viewer_save(v, prefix, err);
}

static bool grab_frame(window *w, const sr_viewer *v, const char *dir, int digits, int frame, sr_error *err)
{
    char path[1024];
    if (snprintf(path, sizeof path, "%s/window-%0*d.png", dir, digits, frame) >= (int)sizeof path)
        return sr_error_set(err, "--grab: the folder's path is too long (%zu bytes)", strlen(dir));
    return window_grab(w, v, path, err);
}

static void print_frame_camera(int digits, int frame, const sr_camera *c)
{
    printf("frame %0*d: --eye %.9g,%.9g,%.9g --target %.9g,%.9g,%.9g --up %.9g,%.9g,%.9g --fov %.9g --near %.9g "
           "--far %.9g\n", digits, frame, c->eye[0], c->eye[1], c->eye[2], c->target[0], c->target[1], c->target[2],
           c->up[0], c->up[1], c->up[2], c->fov_deg, c->near, c->far);
}

/* Feeds each named key to the viewer as a press and release, the same
 * events a window delivers. An empty name (",,", a leading or trailing
 * comma) is an error, not skipped: it is a typo more often than not. */
static bool press_keys(const char *names, sr_viewer *v, sr_error *err)
{
    char buf[MAX_KEYS_TEXT];
    if (strlen(names) >= sizeof buf)
        return sr_error_set(err, "--keys is longer than %d characters", MAX_KEYS_TEXT - 1);
    strcpy(buf, names);
    for (char *name = buf, *end; name; name = end ? end + 1 : NULL) {
        end = strchr(name, ',');
        if (end)
            *end = '\0';
        if (!*name)
            return sr_error_set(err, "--keys: an empty key name in '%s' (names separated by commas, such as F4,L)",
                                names);
        SDL_Keycode key = SDL_GetKeyFromName(name);
        if (key == SDLK_UNKNOWN)
            return sr_error_set(err, "--keys: unknown key '%s' (SDL key names, such as F4, L, Tab)", name);
        SDL_Event e = { .key = { .type = SDL_KEYDOWN, .keysym = { .sym = key } } };
        sr_viewer_handle_event(v, &e);
        e.key.type = SDL_KEYUP;
        sr_viewer_handle_event(v, &e);
    }
    return true;
}

static bool fly_script(const view_job *job, sr_viewer *v, window *w, sr_error *err)
{
    sr_flight script;
    if (!sr_flight_load(&script, job->script_path, err))
        return false;
    int frames = job->frames ? job->frames : script.count;
    int first = job->range_set ? job->range[0] : 0, end = job->range_set ? job->range[1] : frames;
    int digits = frame_digits(frames);
    bool ok = end <= frames ||
              sr_error_set(err, "--frame-range %d:%d ends past the flight's %d frames (B is at most %d)", first, end,
                           frames, frames);
    ok = ok && (!job->shots_dir || sr_output_make_dir(job->shots_dir, err)) &&
         (!job->grab_dir || sr_output_make_dir(job->grab_dir, err));
    for (int f = first; ok && f < end && !v->quit; f++) {
        SDL_Event e;
        while (w->window && SDL_PollEvent(&e))
            sr_viewer_handle_event(v, &e);
        sr_flight_camera(&script, f, frames, &v->setup.camera);
        print_frame_camera(digits, f, &v->setup.camera);
        ok = sr_viewer_draw(v, job->overlays, err) && (!job->shots_dir || save_frame(job->shots_dir, digits, f, v, err));
        if (ok && w->window)
            window_present(w, v);
        ok = ok && (!job->grab_dir || grab_frame(w, v, job->grab_dir, digits, f, err));
    }
    sr_flight_free(&script);
    return ok;
}

static bool take_screenshot(sr_viewer *v, sr_error *err)
{
    static int counter;
    char prefix[64];
    v->screenshot_wanted = false;
    snprintf(prefix, sizeof prefix, "softrast-shot-%03d", ++counter);
    if (!sr_viewer_draw(v, false, err) || !sr_viewer_save(v, prefix, err))
        return false;
    printf("saved ./%s.png and ./%s.pfm\n", prefix, prefix);
    return true;
}

static int framebuffer_side(int window_side)
{
    return window_side < 1 ? 1 : window_side > SR_MAX_FRAMEBUFFER_SIDE ? SR_MAX_FRAMEBUFFER_SIDE : window_side;
}

/* A window past the framebuffer's limit keeps the largest framebuffer, and
 * the presentation stretches it. */
static bool handle_window_event(sr_viewer *v, window *w, const SDL_Event *e, sr_error *err)
{
    if (e->type == SDL_WINDOWEVENT && e->window.event == SDL_WINDOWEVENT_SIZE_CHANGED) {
        int width = framebuffer_side(e->window.data1), height = framebuffer_side(e->window.data2);
        return sr_viewer_resize(v, width, height, err) && window_texture(w, width, height, err);
    }
    sr_viewer_handle_event(v, e);
    return true;
}

static bool fly_interactive(sr_viewer *v, window *w, sr_error *err)
{
    Uint64 last = SDL_GetPerformanceCounter();
    double title_ms = 0.0;
    bool ok = true;
    while (ok && !v->quit) {
        SDL_Event e;
        while (ok && SDL_PollEvent(&e))
            ok = handle_window_event(v, w, &e, err);
        Uint64 now = SDL_GetPerformanceCounter();
        double dt = (double)(now - last) / (double)SDL_GetPerformanceFrequency();
        last = now;
        sr_viewer_advance(v, dt);
        ok = ok && (!v->screenshot_wanted || take_screenshot(v, err)) && sr_viewer_draw(v, true, err);
        if (ok)
            window_present(w, v);
        title_ms += dt * 1e3;
        if (ok && title_ms >= TITLE_EVERY_MS) {
            char status[512];
            sr_viewer_status(v, status, sizeof status);
            *strchr(status, '\n') = '\0';
            SDL_SetWindowTitle(w->window, status);
            title_ms = 0.0;
        }
    }
    return ok;
}

/* Only the video drivers that show a person a window, in SDL's order:
 * otherwise SDL falls back to its offscreen driver when there is no display
 * and the viewer runs for ever with no window. SDL_VIDEODRIVER (offscreen,
 * for --shots without a display) still wins over this hint. Wayland is
 * tried only where a compositor could be found: its probe prints a line of
 * its own on stderr when XDG_RUNTIME_DIR is unset. */
static bool start_video(sr_error *err)
{
    bool wayland = getenv("WAYLAND_DISPLAY") || getenv("XDG_RUNTIME_DIR");
    SDL_SetHint(SDL_HINT_VIDEODRIVER, wayland ? "x11,wayland,KMSDRM" : "x11,KMSDRM");
    if (SDL_Init(SDL_INIT_VIDEO) == 0)
        return true;
    return sr_error_set(err, "cannot open a window: no display (%s); run under xvfb-run -a, or fly a script "
                             "without a window: --no-window", SDL_GetError());
}

/* The viewer keeps its scene in its own sr_viewer, not the runner's. */
static bool run(void *j, sr_scene *unused, sr_error *err)
{
    (void)unused;
    view_job *job = j;
    if (!use_default_scene(job, err))
        return false;
    sr_viewer v;
    window w = { 0 };
    bool windowed = !job->no_window;
    if (windowed && !start_video(err))
        return false;
    bool ok = sr_viewer_init(&v, &job->scene, err) &&
              (!windowed || window_open(&w, v.scene.fb.width, v.scene.fb.height, err));
    ok = ok && (!job->keys || press_keys(job->keys, &v, err));
    if (ok)
        ok = job->script_path ? fly_script(job, &v, &w, err) : fly_interactive(&v, &w, err);
    window_close(&w);
    sr_viewer_free(&v);
    if (windowed)
        SDL_Quit();
    return ok;
}

int sr_app_view(int argc, char **argv)
{
    view_job job = { 0 };
    sr_scene_setup_defaults(&job.scene);
    return sr_app_command_run(&(sr_app_command){ parse_job, run }, &job, argc, argv);
}
