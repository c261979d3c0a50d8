#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "load_progress.h"
#include "scene_setup.h"
#include "upright.h"
#include "io/vertex_colours.h"

const char *const SR_SHADE_NAMES[] = { "lambert", "id", "color", "normal", "texture", "depth", NULL };
const char *const SR_CULL_NAMES[] = { "back", "front", "none", NULL };
static const char *const FRONT_NAMES[] = { "cw", "ccw", NULL };
static const char *const FILTER_NAMES[] = { "bilinear", "nearest", NULL };
static const char *const COLOR_SPACE_NAMES[] = { "raw", "srgb", NULL }; /* sr_color_space */

int sr_scene_default_threads(void)
{
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    return cores < 1 ? 1 : cores > SR_MAX_THREAD_OPTION ? SR_MAX_THREAD_OPTION : (int)cores;
}

void sr_scene_setup_defaults(sr_scene_setup *s)
{
    *s = (sr_scene_setup){ .size = { 1280, 720 }, .camera = sr_camera_default(), .threads = sr_scene_default_threads(),
                          .up_axis = -1, .color_space = SR_COLOR_SRGB };
    for (int k = 0; k < 3; k++) {
        s->eye[k] = s->camera.eye[k];
        s->target[k] = s->camera.target[k];
    }
}

#define SCENE_OPTION_COUNT 19

static void scene_options(sr_scene_setup *s, sr_option *table)
{
    const sr_option entries[] = {
        { "--size", SR_OPT_SIZE, s->size, "WxH", "framebuffer size (default 1280x720)", 1, SR_MAX_FRAMEBUFFER_SIDE, .seen = &s->size_set },
        { "--eye", SR_OPT_DVEC3, s->eye, "X,Y,Z", "camera position (default: framed on the mesh, a three-quarter view from its front)", .seen = &s->eye_set },
        { "--target", SR_OPT_DVEC3, s->target, "X,Y,Z", "point looked at (default: the mesh's centre)", .seen = &s->target_set },
        { "--up", SR_OPT_VEC3, s->camera.up, "X,Y,Z", "up direction (default 0,1,0)", .seen = &s->look_at_set },
        { "--fov", SR_OPT_FLOAT, &s->camera.fov_deg, "DEG", "vertical field of view in degrees (default 60)", 1e-3, 179.999, .seen = &s->fov_set },
        { "--near", SR_OPT_FLOAT, &s->camera.near, "N", "near clip plane distance (default 0.1, or fitted to a framed mesh)", 1e-30, 3e38, .seen = &s->near_set },
        { "--far", SR_OPT_FLOAT, &s->camera.far, "F", "far clip plane distance, or inf (default 100, or fitted to a framed mesh)", 1e-30, 3e38, .allow_infinity = true, .seen = &s->far_set },
        { "--ortho", SR_OPT_FLOAT, &s->camera.ortho_height, "HEIGHT", "orthographic projection of this view height", 1e-30, 3e38, .seen = &s->look_at_set },
        { "--rotate-y", SR_OPT_FLOAT, &s->rotate_y, "DEG", "turn the mesh about +y; positive turns +z toward +x", -1e6, 1e6, .seen = &s->look_at_set },
        { "--up-axis", SR_OPT_CHOICE, &s->up_axis, "x|y|z|-x|-y|-z", "the file's up axis, shown up (default: the file's, else its format's; softrast info FILE)", .choices = SR_AXIS_NAMES, .seen = &s->look_at_set },
        { "--cull", SR_OPT_CHOICE, &s->cull, "back|front|none", "faces to drop (default back; none with a pose)", .choices = SR_CULL_NAMES, .seen = &s->cull_set },
        { "--front", SR_OPT_CHOICE, &s->front, "cw|ccw", "winding on screen of a front face (default cw)", .choices = FRONT_NAMES },
        { "--shade", SR_OPT_CHOICE, &s->shade, "id|color|normal|texture|lambert|depth", "shading mode (default lambert)", .choices = SR_SHADE_NAMES, .seen = &s->shade_set },
        { "--texture", SR_OPT_STRING, &s->texture_path, "FILE.png", "texture (default: the mesh's map_Kd, if any)" },
        { "--reversed-z", SR_OPT_FLAG, &s->camera.reversed_z, NULL, "reversed depth: near maps to 1, far to 0, test GREATER, clear 0", .seen = &s->look_at_set },
        { "--filter", SR_OPT_CHOICE, &s->filter, "bilinear|nearest", "texture filter (default bilinear)", .choices = FILTER_NAMES },
        { "--color-space", SR_OPT_CHOICE, &s->color_space, "raw|srgb", "srgb: textures decoded to linear light, lit, encoded for the image; raw: colours lit as stored (default srgb)", .choices = COLOR_SPACE_NAMES },
        { "--threads", SR_OPT_INT, &s->threads, "N", "threads in all, the calling one included (default: all cores)", 1, SR_MAX_THREAD_OPTION },
        { "--simd", SR_OPT_CHOICE, &s->simd, SR_SIMD_CHOICES, SR_SIMD_HELP, .choices = sr_simd_names },
    };
    _Static_assert(sizeof entries / sizeof *entries == SCENE_OPTION_COUNT, "SCENE_OPTION_COUNT is the entries' count");
    memcpy(table, entries, sizeof entries);
}

static bool listed(const char *name, const char *const *names)
{
    for (; names && *names; names++)
        if (strcmp(name, *names) == 0)
            return true;
    return false;
}

bool sr_scene_setup_parse(sr_scene_setup *s, const sr_option *own, const char *const *skip, const char *usage,
                          int argc, char **argv, bool *help, sr_error *err)
{
    size_t own_count = 1; /* the { 0 } */
    while (own[own_count - 1].name)
        own_count++;
    sr_option *table = malloc((SCENE_OPTION_COUNT + own_count) * sizeof *table);
    if (!table)
        return sr_error_set(err, "out of memory for the option table");
    sr_option shared[SCENE_OPTION_COUNT];
    scene_options(s, shared);
    size_t n = 0;
    for (size_t i = 0; i < SCENE_OPTION_COUNT; i++)
        if (!listed(shared[i].name, skip))
            table[n++] = shared[i];
    memcpy(&table[n], own, own_count * sizeof *own);
    int positional = 0;
    bool ok = sr_options_parse(table, usage, argc, argv, 2, &s->mesh_path, 1, &positional, help, err);
    free(table);
    return ok;
}

static bool shade_uses_texture(sr_shade shade)
{
    return shade == SR_SHADE_TEXTURE || shade == SR_SHADE_LAMBERT;
}

/* A material whose alpha may cut it (MASK, or BLEND drawn as MASK): every
 * shading then reads its texture's alpha, so depth and ids see its holes. */
static bool has_alpha_materials(const sr_mesh *mesh)
{
    for (uint32_t i = 0; i < mesh->material_count; i++)
        if (mesh->materials[i].alpha_mode != SR_ALPHA_OPAQUE)
            return true;
    return false;
}

static bool shade_uses_normals(sr_shade shade)
{
    return shade == SR_SHADE_NORMAL || shade == SR_SHADE_LAMBERT;
}

/* --texture must load; the mesh's own map_Kd may be missing or unreadable
 * (a model shared without its textures): one warning, and it draws untextured. */
static bool load_texture(const sr_scene_setup *s, sr_scene *scene, sr_error *err)
{
    if (s->texture_path)
        return sr_texture_load(&scene->texture, s->texture_path, err);
    sr_error why;
    if (scene->mesh.texture_path && !sr_texture_load(&scene->texture, scene->mesh.texture_path, &why))
        fprintf(stderr, "softrast: warning: %s; drawing the mesh untextured\n", why.message);
    return true;
}

/* One line for a material texture that did not load: its materials draw
 * their base colour. */
static void warn_untextured(void *context, const sr_error *why)
{
    (void)context;
    fprintf(stderr, "softrast: warning: %s; drawing its materials untextured, in their base colour\n", why->message);
}

/* --texture: the whole mesh with it, as before materials. */
static void drop_materials(sr_mesh *mesh)
{
    for (uint32_t i = 0; i < mesh->material_count; i++)
        free(mesh->materials[i].texture_path);
    free(mesh->materials);
    mesh->materials = NULL;
    mesh->material_count = 0;
}

/* Under --color-space srgb the draw takes vertex colours as linear: a
 * file of display values (io/vertex_colours.h) has them decoded once, as
 * it is loaded (docs/conventions.md, "Colour space"). */
static void decode_display_colours(const sr_scene_setup *s, sr_mesh *mesh)
{
    if (s->color_space == SR_COLOR_SRGB && mesh->colors && sr_vertex_colours_are_display(s->mesh_path))
        sr_vertex_colours_to_linear(mesh->colors, mesh->colors, mesh->vertex_count);
}

bool sr_scene_load(const sr_scene_setup *s, bool everything, sr_scene *scene, sr_error *err)
{
    *scene = (sr_scene){ 0 };
    if (!sr_app_load_mesh_report(s->mesh_path, &scene->mesh, &scene->texture, &scene->report, SR_APP_LOAD_QUIET_MS,
                                 err))
        return false;
    sr_scene_print_warnings(&scene->report);
    decode_display_colours(s, &scene->mesh);
    sr_axis up = s->up_axis >= 0 ? (sr_axis)s->up_axis : (sr_axis)scene->report.up;
    sr_upright_matrix(up, (sr_axis)scene->report.front, scene->mesh.z_negated, scene->upright);
    bool wants_texture =
        everything || shade_uses_texture((sr_shade)s->shade) || has_alpha_materials(&scene->mesh);
    if (s->texture_path || !wants_texture)
        sr_texture_free(&scene->texture); /* the file's own, embedded: replaced, or not needed */
    if (s->texture_path)
        drop_materials(&scene->mesh);
    bool materials = scene->mesh.material_count > 0;
    if (wants_texture && materials &&
        !sr_material_textures_load(&scene->mesh, &scene->material_textures, warn_untextured, NULL, err))
        return false;
    if (wants_texture && !materials && !scene->texture.texels && !load_texture(s, scene, err))
        return false;
    bool wants_normals = everything || shade_uses_normals((sr_shade)s->shade);
    if (wants_normals && !sr_mesh_compute_normals(&scene->mesh, err))
        return false;
    scene->workspace = sr_workspace_create();
    if (!scene->workspace)
        return sr_error_set(err, "out of memory for a workspace");
    if (!sr_framebuffer_create(&scene->fb, s->size[0], s->size[1], err))
        return false;
    scene->fb.reversed_z = s->camera.reversed_z;
    return true;
}

void sr_scene_print_warnings(const sr_load_report *r)
{
    for (uint32_t i = 0; i < r->warning_count && i < SR_REPORT_MAX_WARNINGS; i++)
        fprintf(stderr, "softrast: warning: %s\n", r->warnings[i]);
    if (r->warning_count > SR_REPORT_MAX_WARNINGS)
        fprintf(stderr, "softrast: warning: %u more warnings like these\n", r->warning_count - SR_REPORT_MAX_WARNINGS);
}

void sr_scene_free(sr_scene *scene)
{
    sr_mesh_free(&scene->mesh);
    sr_load_report_free(&scene->report);
    sr_texture_free(&scene->texture);
    sr_material_textures_free(&scene->material_textures);
    sr_framebuffer_destroy(&scene->fb);
    sr_workspace_destroy(scene->workspace);
    scene->workspace = NULL;
}

static bool has_origin(const sr_mesh *mesh)
{
    return mesh->origin[0] != 0.0 || mesh->origin[1] != 0.0 || mesh->origin[2] != 0.0;
}

/* The scene's bounds turned upright, relative to origin (the camera's). */
static bool upright_bounds(const sr_scene *scene, const double origin[3], vec3 lo, vec3 hi)
{
    if (!sr_mesh_bounds(&scene->mesh, lo, hi))
        return false;
    double turned[3];
    memcpy(turned, scene->mesh.origin, sizeof turned);
    sr_upright_bounds(scene->upright, lo, hi, turned);
    for (int k = 0; k < 3; k++) {
        float shift = sr_double_to_float(turned[k] - origin[k]);
        lo[k] += shift;
        hi[k] += shift;
    }
    return true;
}

/* Framed (sr_camera_frame_bounds: a three-quarter view from the front)
 * when neither --eye nor --target is given; else the eye given looks at
 * the target given or the scene's centre. Near and far are
 * fitted to the scene unless one of them is given (sr_camera_fit_clip keeps
 * the contract's defaults while the scene lies between them, so its images
 * do not change). */
void sr_scene_frame_camera(sr_scene_setup *s, const sr_scene *scene)
{
    vec3 lo, hi;
    float near = s->camera.near, far = s->camera.far;
    if (!s->eye_set && !s->target_set && sr_mesh_bounds(&scene->mesh, lo, hi)) {
        memcpy(s->camera.origin, scene->mesh.origin, sizeof s->camera.origin);
        sr_upright_bounds(scene->upright, lo, hi, s->camera.origin);
        sr_camera_frame_bounds(&s->camera, lo, hi, (float)s->size[0] / (float)s->size[1]);
    } else {
        static const double world_origin[3];
        const double *origin = !has_origin(&scene->mesh) ? world_origin
                             : s->target_set && !s->eye_set  ? s->target
                                                              : s->eye;
        for (int k = 0; k < 3; k++) {
            s->camera.origin[k] = origin[k];
            s->camera.eye[k] = sr_double_to_float(s->eye[k] - origin[k]);
            s->camera.target[k] = sr_double_to_float(s->target[k] - origin[k]);
        }
        if (upright_bounds(scene, origin, lo, hi)) {
            if (!s->target_set)
                glm_vec3_center(lo, hi, s->camera.target);
            sr_camera_fit_clip(&s->camera, lo, hi);
        }
    }
    if (s->near_set || s->far_set) {
        s->camera.near = near;
        s->camera.far = far;
    }
}

bool sr_scene_desc(const sr_scene_setup *s, const sr_scene *scene, sr_draw_desc *desc, sr_draw_study *study,
                   sr_error *err)
{
    if (!sr_camera_check(&s->camera, err))
        return false;
    float aspect = (float)scene->fb.width / (float)scene->fb.height;
    *desc = (sr_draw_desc){ .mesh = &scene->mesh, .shade = (sr_shade)s->shade, .cull = (sr_cull)s->cull,
                            .front = (sr_front)s->front, .filter = (sr_filter)s->filter,
                            .color_space = (sr_color_space)s->color_space, .texture = scene->texture.texels ? &scene->texture : NULL,
                            .threads = s->threads, .workspace = scene->workspace, .study = study };
    *study = (sr_draw_study){ .simd = (sr_simd)s->simd };
    mat4 turn;
    glm_rotate_make(turn, glm_rad(s->rotate_y), (vec3){ 0.0f, 1.0f, 0.0f });
    glm_mat4_mul(turn, (vec4 *)scene->upright, desc->world);
    sr_camera_view_d(&s->camera, &desc->view_d);
    sr_camera_projection(&s->camera, aspect, desc->projection);
    return true;
}

bool sr_shade_supported(const sr_mesh *mesh, const sr_texture *texture, sr_shade shade)
{
    switch (shade) {
    case SR_SHADE_COLOR:   return mesh->colors != NULL;
    case SR_SHADE_NORMAL:  return mesh->normals != NULL;
    case SR_SHADE_TEXTURE: return mesh->material_count > 0 || (mesh->uvs && texture->texels);
    case SR_SHADE_LAMBERT: return mesh->normals != NULL;
    default:               return true;
    }
}
