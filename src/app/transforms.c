/* transforms.json datasets (transforms.h), through cJSON. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <cJSON.h>

#include "core/input_file.h"
#include "io/output_file.h"
#include "transforms.h"

struct sr_transforms {
    cJSON *root;
    cJSON *frames; /* root's "frames" array */
    char *path;    /* as given, for messages */
};

/* The camera fields a frame may override, in their order. */
enum { FL_X, FL_Y, CX, CY, W, H, ANGLE_X, ANGLE_Y, FIELDS };
static const char *const FIELD_NAMES[FIELDS] = { "fl_x", "fl_y", "cx", "cy", "w", "h", "camera_angle_x",
                                                 "camera_angle_y" };

/* The whole file, a regular one (sr_input_open), read at its size. */
static char *read_text(const char *path, sr_error *err)
{
    const char *why;
    FILE *f = sr_input_open(path, &why);
    if (!f) {
        sr_error_set(err, "%s: cannot open: %s", path, why);
        return NULL;
    }
    off_t size = fseeko(f, 0, SEEK_END) == 0 ? ftello(f) : -1;
    char *text = size >= 0 && size < SR_TRANSFORMS_MAX_BYTES && fseeko(f, 0, SEEK_SET) == 0 ? malloc((size_t)size + 1)
                                                                                          : NULL;
    bool read = text && fread(text, 1, (size_t)size, f) == (size_t)size;
    fclose(f);
    if (!read) {
        bool too_big = size >= SR_TRANSFORMS_MAX_BYTES, no_memory = size >= 0 && !too_big && !text;
        free(text);
        sr_error_set(err, "%s: %s", path, too_big ? "larger than 256 MB" : no_memory ? "out of memory" : "cannot read");
        return NULL;
    }
    text[size] = '\0';
    return text;
}

bool sr_transforms_read(const char *path, sr_transforms **out, sr_error *err)
{
    *out = NULL;
    char *text = read_text(path, err);
    if (!text)
        return false;
    const char *at = NULL;
    cJSON *root = cJSON_ParseWithOpts(text, &at, true);
    size_t offset = root || !at ? 0 : (size_t)(at - text);
    free(text);
    if (!root)
        return sr_error_set(err, "%s: not JSON (at byte %zu)", path, offset);
    cJSON *frames = cJSON_GetObjectItemCaseSensitive(root, "frames");
    int count = cJSON_IsArray(frames) ? cJSON_GetArraySize(frames) : -1;
    if (!cJSON_IsObject(root) || count < 1 || count > SR_TRANSFORMS_MAX_FRAMES) {
        cJSON_Delete(root);
        return sr_error_set(err, "%s: needs a \"frames\" array of 1 to %d frames", path, SR_TRANSFORMS_MAX_FRAMES);
    }
    sr_transforms *t = calloc(1, sizeof *t);
    char *copy = strdup(path);
    if (!t || !copy) {
        free(t);
        free(copy);
        cJSON_Delete(root);
        return sr_error_set(err, "%s: out of memory", path);
    }
    *t = (sr_transforms){ .root = root, .frames = frames, .path = copy };
    *out = t;
    return true;
}

void sr_transforms_free(sr_transforms *t)
{
    if (!t)
        return;
    cJSON_Delete(t->root);
    free(t->path);
    free(t);
}

int sr_transforms_count(const sr_transforms *t)
{
    return cJSON_GetArraySize(t->frames);
}

/* A camera field of the frame, else of the top level; NAN when neither
 * has it. */
static double field(const sr_transforms *t, const cJSON *frame, int k)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(frame, FIELD_NAMES[k]);
    if (!v)
        v = cJSON_GetObjectItemCaseSensitive(t->root, FIELD_NAMES[k]);
    return cJSON_IsNumber(v) ? v->valuedouble : NAN;
}

/* Frame i's 4x4 transform_matrix, rows of four finite numbers. */
static bool matrix_of(const sr_transforms *t, const cJSON *frame, int i, double m[4][4], sr_error *err)
{
    const cJSON *rows = cJSON_GetObjectItemCaseSensitive(frame, "transform_matrix");
    bool ok = cJSON_IsArray(rows) && cJSON_GetArraySize(rows) == 4;
    for (int r = 0; ok && r < 4; r++) {
        const cJSON *row = cJSON_GetArrayItem(rows, r);
        ok = cJSON_IsArray(row) && cJSON_GetArraySize(row) == 4;
        for (int c = 0; ok && c < 4; c++) {
            const cJSON *v = cJSON_GetArrayItem(row, c);
            ok = cJSON_IsNumber(v) && isfinite(v->valuedouble);
            m[r][c] = ok ? v->valuedouble : 0.0;
        }
    }
    return ok || sr_error_set(err, "%s: frame %d: transform_matrix must be 4 rows of 4 finite numbers", t->path, i);
}

bool sr_transforms_camera(const sr_transforms *t, int i, sr_pinhole *cam, int size[2], sr_error *err)
{
    const cJSON *frame = cJSON_GetArrayItem(t->frames, i);
    if (!cJSON_IsObject(frame))
        return sr_error_set(err, "%s: frame %d is not an object", t->path, i);
    double v[FIELDS];
    for (int k = 0; k < FIELDS; k++)
        v[k] = field(t, frame, k);
    if (!(v[W] >= 1 && v[W] <= SR_MAX_FRAMEBUFFER_SIDE && v[H] >= 1 && v[H] <= SR_MAX_FRAMEBUFFER_SIDE) ||
        v[W] != floor(v[W]) || v[H] != floor(v[H]))
        return sr_error_set(err, "%s: frame %d: needs whole w and h from 1 to %d", t->path, i,
                            SR_MAX_FRAMEBUFFER_SIDE);
    size[0] = (int)v[W];
    size[1] = (int)v[H];
    if (isnan(v[FL_X]) && v[ANGLE_X] > 0 && v[ANGLE_X] < GLM_PI)
        v[FL_X] = 0.5 * v[W] / tan(0.5 * v[ANGLE_X]);
    if (isnan(v[FL_Y]))
        v[FL_Y] = v[ANGLE_Y] > 0 && v[ANGLE_Y] < GLM_PI ? 0.5 * v[H] / tan(0.5 * v[ANGLE_Y]) : v[FL_X];
    if (isnan(v[FL_X]))
        return sr_error_set(err, "%s: frame %d: needs fl_x or camera_angle_x (0 to pi)", t->path, i);
    *cam = (sr_pinhole){ .fx = v[FL_X], .fy = v[FL_Y],
                         /* from the corner to OpenCV's pixel-centre origin */
                         .cx = (isnan(v[CX]) ? 0.5 * v[W] : v[CX]) - 0.5,
                         .cy = (isnan(v[CY]) ? 0.5 * v[H] : v[CY]) - 0.5 };
    double gl[4][4], c2w[4][4];
    if (!matrix_of(t, frame, i, gl, err))
        return false;
    for (int r = 0; r < 4; r++) /* OpenGL's camera y up and z backward: OpenCV's y down and z forward */
        for (int c = 0; c < 4; c++)
            c2w[r][c] = c == 1 || c == 2 ? -gl[r][c] : gl[r][c];
    sr_error why = { "" };
    if (!sr_pinhole_pose_from_c2w(c2w, cam->w2c, &why))
        return sr_error_set(err, "%s: frame %d: transform_matrix: %s", t->path, i, why.message);
    return sr_pinhole_check(cam, &why) || sr_error_set(err, "%s: frame %d: %s", t->path, i, why.message);
}

bool sr_transforms_set_path(sr_transforms *t, int i, const char *key, const char *relative, sr_error *err)
{
    cJSON *frame = cJSON_GetArrayItem(t->frames, i);
    cJSON *value = cJSON_CreateString(relative);
    if (!value)
        return sr_error_set(err, "out of memory for frame %d's %s", i, key);
    if (cJSON_GetObjectItemCaseSensitive(frame, key))
        return cJSON_ReplaceItemInObjectCaseSensitive(frame, key, value) ||
               (cJSON_Delete(value), sr_error_set(err, "cannot set frame %d's %s", i, key));
    return cJSON_AddItemToObject(frame, key, value) ||
           (cJSON_Delete(value), sr_error_set(err, "cannot set frame %d's %s", i, key));
}

bool sr_transforms_write(const sr_transforms *t, const char *path, sr_error *err)
{
    char *text = cJSON_Print(t->root);
    if (!text)
        return sr_error_set(err, "%s: out of memory", path);
    sr_output o;
    bool ok = sr_output_open(&o, path, err);
    if (ok) {
        errno = 0;
        bool written = fputs(text, o.f) >= 0 && fputc('\n', o.f) != EOF;
        ok = sr_output_close(&o, path, written, err);
    }
    cJSON_free(text);
    return ok;
}
