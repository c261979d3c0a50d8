/* viewer.h — the interactive viewer's state, apart from any window.
 *
 * The window loop (view.c) feeds SDL events to sr_viewer_handle_event,
 * advances the camera with sr_viewer_advance and presents what
 * sr_viewer_draw leaves in `display`. Tests drive the same functions with
 * synthetic SDL events and no window.
 */
#ifndef SOFTRAST_APP_VIEWER_H
#define SOFTRAST_APP_VIEWER_H

#include <SDL.h>

#include "app/scene_setup.h"
#include "app/hidden_lines.h"
#include "flycam.h"

#define SR_VIEWER_MIN_NEAR 1e-6f
#define SR_VIEWER_MAX_FAR 1e30f
#define SR_VIEWER_LOOK_DEG_PER_PIXEL 0.15f
#define SR_VIEWER_FAST 4.0f       /* Shift multiplies the speed */
#define SR_VIEWER_WHEEL_STEP 1.25f /* one wheel notch multiplies or divides the speed */

enum sr_viewer_move {
    SR_MOVE_FORWARD = 1 << 0,
    SR_MOVE_BACK = 1 << 1,
    SR_MOVE_LEFT = 1 << 2,
    SR_MOVE_RIGHT = 1 << 3,
    SR_MOVE_DOWN = 1 << 4,
    SR_MOVE_UP = 1 << 5,
    SR_MOVE_FAST = 1 << 6,
};

/* One fan triangle edge for the wireframe overlay. */
typedef struct sr_wire {
    int64_t x0, y0, x1, y1;
    bool clipped;
} sr_wire;

typedef struct sr_viewer {
    sr_scene_setup setup; /* camera, shading and culling in use */
    sr_scene scene;
    sr_flycam fly, home;
    float speed; /* units per second */
    unsigned held; /* sr_viewer_move bits */
    bool mouse_look, look_button, show_depth, depth_linear, wireframe, help, quit;
    bool hidden_lines;   /* F6: the mesh's edges, hidden lines removed (app/hidden_lines.h) */
    sr_hidden_lines wire; /* the mesh's edges, made at the first F6 */
    bool screenshot_wanted;
    sr_stats stats;
    double frame_ms;
    uint32_t *display; /* fb-sized: shaded or depth view, then overlays */
    sr_wire *wires;
    size_t wire_count, wire_cap;
} sr_viewer;

bool sr_viewer_init(sr_viewer *v, const sr_scene_setup *setup, sr_error *err);
void sr_viewer_free(sr_viewer *v);
bool sr_viewer_resize(sr_viewer *v, int width, int height, sr_error *err);

/* Keys and mouse; sets quit, screenshot_wanted and the toggles. */
void sr_viewer_handle_event(sr_viewer *v, const SDL_Event *e);

/* Moves the fly camera for dt seconds of the movement keys held and makes
 * it the camera the next draw uses. */
void sr_viewer_advance(sr_viewer *v, double dt);

/* Renders the frame from setup.camera into scene.fb, then the shown image (shaded or depth
 * view) into display, with the overlays when `overlays`. */
bool sr_viewer_draw(sr_viewer *v, bool overlays, sr_error *err);

/* The status line: frame time, counts, camera and near/far. */
void sr_viewer_status(const sr_viewer *v, char *buf, size_t cap);

/* Saves display as PREFIX.png and the depth buffer as PREFIX.pfm. */
bool sr_viewer_save(const sr_viewer *v, const char *prefix, sr_error *err);

#endif
