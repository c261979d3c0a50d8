/* softrast info — what a mesh file holds, in a few lines or one JSON object. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <cJSON.h>

#include "app.h"
#include "load_progress.h"
#include "upright.h"

typedef struct info_job {
    const char *path;
    bool json;
    int up_axis; /* -1: the file's */
} info_job;

static const char USAGE[] =
    "usage: softrast info MESH [--json]\n"
    "What MESH holds: its format, counts, bounds in the file's frame and in softrast's world,\n"
    "its up axis and units (read from the file or guessed from its format), its parts with\n"
    "their materials, its textures (found, embedded or missing) and what was left out.";

/* The bounds of the loaded mesh in double: softrast's world, and the
 * file's frame (the loader's z flip undone). */
typedef struct info_bounds {
    double world[2][3], file[2][3];
    bool any;
} info_bounds;

static info_bounds mesh_bounds(const sr_mesh *m)
{
    info_bounds b = { .any = false };
    vec3 lo, hi;
    if (!sr_mesh_bounds(m, lo, hi))
        return b;
    b.any = true;
    for (int k = 0; k < 3; k++) {
        b.world[0][k] = m->origin[k] + lo[k];
        b.world[1][k] = m->origin[k] + hi[k];
        b.file[0][k] = b.world[0][k];
        b.file[1][k] = b.world[1][k];
    }
    if (m->z_negated) { /* 0 − z, not −z: a plane at z = 0 prints 0, not -0 */
        b.file[0][2] = 0.0 - b.world[1][2];
        b.file[1][2] = 0.0 - b.world[0][2];
    }
    return b;
}

static const char *up_found(const info_job *job, const sr_load_report *r)
{
    return job->up_axis >= 0 ? "given" : SR_FOUND_NAMES[r->up_found];
}

static sr_axis up_axis(const info_job *job, const sr_load_report *r)
{
    return job->up_axis >= 0 ? (sr_axis)job->up_axis : (sr_axis)r->up;
}

/* The axis the upright turn brings to the front: the file's when it says
 * one across the up axis, else the up axis's default. */
static sr_axis front_axis(const info_job *job, const sr_load_report *r)
{
    sr_axis up = up_axis(job, r), front = (sr_axis)r->front;
    return front < SR_AXIS_COUNT && front / 2 != up / 2 ? front : sr_upright_default_front(up);
}

/* ---- JSON ---- */

static cJSON *json_box(const double box[2][3])
{
    cJSON *o = cJSON_CreateObject(), *lo = cJSON_AddArrayToObject(o, "min"), *hi = cJSON_AddArrayToObject(o, "max");
    for (int k = 0; k < 3; k++) {
        cJSON_AddItemToArray(lo, cJSON_CreateNumber(box[0][k]));
        cJSON_AddItemToArray(hi, cJSON_CreateNumber(box[1][k]));
    }
    return o;
}

static void json_report(cJSON *o, const sr_load_report *r)
{
    cJSON *parts = cJSON_AddArrayToObject(o, "parts");
    for (uint32_t i = 0; i < r->part_count; i++) {
        cJSON *p = cJSON_CreateObject();
        cJSON_AddNumberToObject(p, "first_triangle", r->parts[i].first_triangle);
        cJSON_AddNumberToObject(p, "triangle_count", r->parts[i].triangle_count);
        cJSON_AddStringToObject(p, "material", r->parts[i].material);
        if (r->parts[i].texture >= 0)
            cJSON_AddNumberToObject(p, "texture", r->parts[i].texture);
        else
            cJSON_AddNullToObject(p, "texture");
        cJSON_AddItemToArray(parts, p);
    }
    cJSON_AddNumberToObject(o, "parts_unlisted", r->parts_unlisted);
    cJSON *textures = cJSON_AddArrayToObject(o, "textures");
    for (uint32_t i = 0; i < r->texture_count; i++) {
        cJSON *t = cJSON_CreateObject();
        cJSON_AddStringToObject(t, "name", r->textures[i].name);
        cJSON_AddStringToObject(t, "status", SR_TEXTURE_STATUS_NAMES[r->textures[i].status]);
        if (r->textures[i].status == SR_TEXTURE_FOUND)
            cJSON_AddStringToObject(t, "path", r->textures[i].path);
        else
            cJSON_AddNullToObject(t, "path");
        cJSON_AddItemToArray(textures, t);
    }
    cJSON *left = cJSON_AddObjectToObject(o, "left_out");
    cJSON_AddNumberToObject(left, "points", (double)r->points);
    cJSON_AddNumberToObject(left, "lines", (double)r->lines);
    cJSON_AddNumberToObject(left, "animations", r->animations);
    cJSON_AddNumberToObject(left, "cameras", r->cameras);
    cJSON_AddNumberToObject(left, "lights", r->lights);
    cJSON_AddNumberToObject(o, "skinned_meshes", r->skinned_meshes);
    cJSON_AddNumberToObject(o, "morphed_meshes", r->morphed_meshes);
    cJSON_AddNumberToObject(o, "mirrored_meshes", r->mirrored_meshes);
    cJSON *warnings = cJSON_AddArrayToObject(o, "warnings");
    for (uint32_t i = 0; i < r->warning_count && i < SR_REPORT_MAX_WARNINGS; i++)
        cJSON_AddItemToArray(warnings, cJSON_CreateString(r->warnings[i]));
}

static bool print_json(const info_job *job, const sr_mesh *m, const sr_load_report *r, sr_error *err)
{
    info_bounds b = mesh_bounds(m);
    mat4 turn;
    sr_upright_matrix(up_axis(job, r), front_axis(job, r), m->z_negated, turn);
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "file", job->path);
    cJSON_AddStringToObject(o, "format", r->format);
    cJSON_AddNumberToObject(o, "vertices", m->vertex_count);
    cJSON_AddNumberToObject(o, "triangles", sr_mesh_triangle_slots(m));
    if (b.any) {
        cJSON_AddItemToObject(o, "bounds_file", json_box(b.file));
        cJSON_AddItemToObject(o, "bounds_world", json_box(b.world));
    } else {
        cJSON_AddNullToObject(o, "bounds_file");
        cJSON_AddNullToObject(o, "bounds_world");
    }
    cJSON_AddBoolToObject(o, "z_negated", m->z_negated);
    cJSON_AddStringToObject(o, "up_axis", SR_AXIS_SIGNED[up_axis(job, r)]);
    cJSON_AddStringToObject(o, "up_found", up_found(job, r));
    cJSON_AddStringToObject(o, "up_why", job->up_axis >= 0 ? "--up-axis" : r->up_why);
    cJSON_AddStringToObject(o, "front_axis", SR_AXIS_SIGNED[front_axis(job, r)]);
    cJSON *rows = cJSON_AddArrayToObject(o, "upright_turn"); /* rows of the world turn, softrast's world */
    for (int row = 0; row < 3; row++) {
        cJSON *line = cJSON_CreateArray();
        for (int c = 0; c < 3; c++)
            cJSON_AddItemToArray(line, cJSON_CreateNumber(turn[c][row]));
        cJSON_AddItemToArray(rows, line);
    }
    if (r->metres_per_unit > 0.0)
        cJSON_AddNumberToObject(o, "metres_per_unit", r->metres_per_unit);
    else
        cJSON_AddNullToObject(o, "metres_per_unit");
    cJSON_AddStringToObject(o, "units_found", SR_FOUND_NAMES[r->units_found]);
    cJSON_AddStringToObject(o, "units_why", r->units_why);
    json_report(o, r);
    char *text = cJSON_PrintUnformatted(o);
    cJSON_Delete(o);
    if (!text)
        return sr_error_set(err, "out of memory for the JSON");
    puts(text);
    cJSON_free(text);
    return true;
}

/* ---- text ---- */

static void print_box(const char *label, const double box[2][3])
{
    printf("%s %g,%g,%g to %g,%g,%g", label, box[0][0], box[0][1], box[0][2], box[1][0], box[1][1], box[1][2]);
}

static void print_units(const sr_load_report *r)
{
    if (r->metres_per_unit > 0.0)
        printf("units: %g m per unit (%s: %s)\n", r->metres_per_unit, SR_FOUND_NAMES[r->units_found], r->units_why);
    else
        printf("units: unknown (%s)\n", r->units_why);
}

static void print_parts(const sr_load_report *r)
{
    printf("parts: %u", r->part_count + r->parts_unlisted);
    for (uint32_t i = 0; i < r->part_count; i++) {
        const sr_report_part *p = &r->parts[i];
        printf("%s triangles %u-%u '%s'", i ? ";" : ":", p->first_triangle,
               p->first_triangle + p->triangle_count - (p->triangle_count > 0), p->material);
        if (p->texture >= 0)
            printf(" texture %d", p->texture);
    }
    printf(r->parts_unlisted ? "; %u more\n" : "\n", r->parts_unlisted);
    printf("textures: %u", r->texture_count);
    for (uint32_t i = 0; i < r->texture_count; i++) {
        const sr_report_texture *t = &r->textures[i];
        printf("%s %d '%s' %s%s%s", i ? ";" : ":", (int)i, t->name, SR_TEXTURE_STATUS_NAMES[t->status],
               t->status == SR_TEXTURE_FOUND ? " at " : "", t->status == SR_TEXTURE_FOUND ? t->path : "");
    }
    printf("\n");
}

static void print_text(const info_job *job, const sr_mesh *m, const sr_load_report *r)
{
    info_bounds b = mesh_bounds(m);
    printf("%s: %s, %u vertices, %u triangles\n", job->path, r->format, m->vertex_count, sr_mesh_triangle_slots(m));
    if (b.any) {
        print_box("bounds: file's frame", b.file);
        print_box(m->z_negated ? "; softrast's world (z negated)" : "; softrast's world", b.world);
        printf("\n");
    }
    printf("up: %s, front %s (%s: %s)\n", SR_AXIS_SIGNED[up_axis(job, r)], SR_AXIS_SIGNED[front_axis(job, r)],
           up_found(job, r), job->up_axis >= 0 ? "--up-axis" : r->up_why);
    print_units(r);
    print_parts(r);
    printf("left out: %llu points, %llu lines, %u animations, %u cameras, %u lights",
           (unsigned long long)r->points, (unsigned long long)r->lines, r->animations, r->cameras, r->lights);
    if (r->skinned_meshes)
        printf("; %u skinned meshes posed by their skeletons", r->skinned_meshes);
    if (r->morphed_meshes)
        printf("; %u meshes with morph targets at their default weights", r->morphed_meshes);
    if (r->mirrored_meshes)
        printf("; %u mirrored meshes turned outward", r->mirrored_meshes);
    printf("\n");
    for (uint32_t i = 0; i < r->warning_count && i < SR_REPORT_MAX_WARNINGS; i++)
        printf("warning: %s\n", r->warnings[i]);
}

/* ---- the command ---- */

static bool parse_job(void *j, int argc, char **argv, bool *help, sr_error *err)
{
    info_job *job = j;
    const sr_option table[] = {
        { "--json", SR_OPT_FLAG, &job->json, NULL, "print one JSON object (docs/cli.md has its keys)" },
        { "--up-axis", SR_OPT_CHOICE, &job->up_axis, "x|y|z|-x|-y|-z", "report this up axis, as render and view would use it", .choices = SR_AXIS_NAMES },
        { 0 },
    };
    int positional = 0;
    if (!sr_options_parse(table, USAGE, argc, argv, 2, &job->path, 1, &positional, help, err))
        return false;
    return *help || job->path || sr_error_set(err, "info needs one MESH (see softrast info --help)");
}

static bool run(void *j, sr_scene *scene, sr_error *err)
{
    info_job *job = j;
    if (!sr_app_load_mesh_report(job->path, &scene->mesh, &scene->texture, &scene->report, SR_APP_LOAD_QUIET_MS,
                                 err))
        return false;
    if (job->json)
        return print_json(job, &scene->mesh, &scene->report, err);
    print_text(job, &scene->mesh, &scene->report);
    return true;
}

int sr_app_info(int argc, char **argv)
{
    info_job job = { .up_axis = -1 };
    return sr_app_command_run(&(sr_app_command){ parse_job, run }, &job, argc, argv);
}
