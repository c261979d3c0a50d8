/* The viewer's keys and mouse, as SDL events; see HELP_TEXT in viewer.c. */
#include "viewer.h"

#define NEAR_FAR_STEP 2.0f

static unsigned move_bit(SDL_Keycode key)
{
    switch (key) {
    case SDLK_w:      return SR_MOVE_FORWARD;
    case SDLK_s:      return SR_MOVE_BACK;
    case SDLK_a:      return SR_MOVE_LEFT;
    case SDLK_d:      return SR_MOVE_RIGHT;
    case SDLK_q:      return SR_MOVE_DOWN;
    case SDLK_e:      return SR_MOVE_UP;
    case SDLK_LSHIFT:
    case SDLK_RSHIFT: return SR_MOVE_FAST;
    default:          return 0;
    }
}

/* The next shading mode this scene can show (id and depth always can). */
static void cycle_shade(sr_viewer *v)
{
    int mode = v->setup.shade;
    do
        mode = (mode + 1) % SR_SHADE_COUNT;
    while (!sr_shade_supported(&v->scene.mesh, &v->scene.texture, (sr_shade)mode));
    v->setup.shade = mode;
}

/* [ and ] halve and double near, { and } (with Shift) far; near stays in
 * [SR_VIEWER_MIN_NEAR, far) and far in (near, SR_VIEWER_MAX_FAR]. */
static void step_clip_plane(sr_viewer *v, bool far, float factor)
{
    sr_camera *cam = &v->setup.camera;
    if (far)
        cam->far = glm_clamp(cam->far * factor, cam->near * NEAR_FAR_STEP, SR_VIEWER_MAX_FAR);
    else
        cam->near = glm_clamp(cam->near * factor, SR_VIEWER_MIN_NEAR, cam->far / NEAR_FAR_STEP);
}

static void set_mouse_look(sr_viewer *v, bool on)
{
    v->mouse_look = on;
    SDL_SetRelativeMouseMode(on ? SDL_TRUE : SDL_FALSE);
}

static void key_down(sr_viewer *v, const SDL_KeyboardEvent *k)
{
    bool shift = (k->keysym.mod & KMOD_SHIFT) != 0;
    v->held |= move_bit(k->keysym.sym);
    switch (k->keysym.sym) {
    case SDLK_ESCAPE:       v->quit = true; break;
    case SDLK_F1:           v->help = !v->help; break;
    case SDLK_F2:           v->wireframe = !v->wireframe; break;
    case SDLK_F3:           cycle_shade(v); break;
    case SDLK_F4:           v->show_depth = !v->show_depth; break;
    case SDLK_F5:           v->setup.cull = (v->setup.cull + 1) % (SR_CULL_NONE + 1); break;
    case SDLK_F6:           v->hidden_lines = !v->hidden_lines; break;
    case SDLK_F12:          v->screenshot_wanted = true; break;
    case SDLK_l:            v->depth_linear = !v->depth_linear; break;
    case SDLK_z:            v->setup.camera.reversed_z = v->scene.fb.reversed_z = !v->scene.fb.reversed_z; break;
    case SDLK_r:            v->fly = v->home; break;
    case SDLK_TAB:          set_mouse_look(v, !v->mouse_look); break;
    case SDLK_LEFTBRACKET:  step_clip_plane(v, shift, 1.0f / NEAR_FAR_STEP); break;
    case SDLK_RIGHTBRACKET: step_clip_plane(v, shift, NEAR_FAR_STEP); break;
    default:                break;
    }
}

static void mouse_button(sr_viewer *v, const SDL_MouseButtonEvent *b, bool down)
{
    if (b->button == SDL_BUTTON_RIGHT && v->look_button != down) {
        v->look_button = down;
        set_mouse_look(v, down);
    }
}

void sr_viewer_handle_event(sr_viewer *v, const SDL_Event *e)
{
    switch (e->type) {
    case SDL_QUIT:            v->quit = true; break;
    case SDL_KEYDOWN:         key_down(v, &e->key); break;
    case SDL_KEYUP:           v->held &= ~move_bit(e->key.keysym.sym); break;
    case SDL_MOUSEBUTTONDOWN: mouse_button(v, &e->button, true); break;
    case SDL_MOUSEBUTTONUP:   mouse_button(v, &e->button, false); break;
    case SDL_MOUSEWHEEL:
        v->speed *= e->wheel.y > 0 ? SR_VIEWER_WHEEL_STEP : e->wheel.y < 0 ? 1.0f / SR_VIEWER_WHEEL_STEP : 1.0f;
        break;
    case SDL_MOUSEMOTION:
        if (v->mouse_look)
            sr_flycam_turn(&v->fly, (float)e->motion.xrel * SR_VIEWER_LOOK_DEG_PER_PIXEL,
                           -(float)e->motion.yrel * SR_VIEWER_LOOK_DEG_PER_PIXEL);
        break;
    default:
        break;
    }
}

static float axis(unsigned held, unsigned plus, unsigned minus)
{
    return (float)((held & plus) != 0) - (float)((held & minus) != 0);
}

void sr_viewer_advance(sr_viewer *v, double dt)
{
    float step = v->speed * (float)dt * ((v->held & SR_MOVE_FAST) ? SR_VIEWER_FAST : 1.0f);
    sr_flycam_move(&v->fly, step * axis(v->held, SR_MOVE_FORWARD, SR_MOVE_BACK),
                   step * axis(v->held, SR_MOVE_RIGHT, SR_MOVE_LEFT), step * axis(v->held, SR_MOVE_UP, SR_MOVE_DOWN));
    sr_flycam_apply(&v->fly, &v->setup.camera);
}
