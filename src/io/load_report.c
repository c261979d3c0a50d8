/* The loaders' report on a file (load_report.h). */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "load_report.h"

const char *const SR_AXIS_NAMES[] = { "x", "-x", "y", "-y", "z", "-z", NULL };
const char *const SR_AXIS_SIGNED[] = { "+x", "-x", "+y", "-y", "+z", "-z", NULL };
const char *const SR_FOUND_NAMES[] = { "unknown", "guessed", "read", NULL };
const char *const SR_TEXTURE_STATUS_NAMES[] = { "found", "embedded", "missing", NULL };

void sr_report_copy(char dst[SR_REPORT_TEXT], const char *src)
{
    snprintf(dst, SR_REPORT_TEXT, "%s", src ? src : "");
    for (char *c = dst; *c; c++)
        if ((unsigned char)*c < 0x20 || *c == 0x7f)
            *c = '?';
}

void sr_load_report_free(sr_load_report *r)
{
    if (!r)
        return;
    free(r->parts);
    free(r->textures);
    *r = (sr_load_report){ 0 };
}

bool sr_report_add_part(sr_load_report *r, uint32_t first, uint32_t count, const char *material, int32_t texture)
{
    if (r->part_count >= SR_REPORT_MAX_PARTS) {
        r->parts_unlisted++;
        return true;
    }
    sr_report_part *parts = realloc(r->parts, (r->part_count + 1) * sizeof *parts);
    if (!parts)
        return false;
    r->parts = parts;
    sr_report_part *p = &parts[r->part_count++];
    *p = (sr_report_part){ first, count, "", texture };
    sr_report_copy(p->material, material);
    return true;
}

int32_t sr_report_add_texture(sr_load_report *r, const char *name, const char *found, sr_texture_status status)
{
    char key[SR_REPORT_TEXT];
    sr_report_copy(key, name);
    for (uint32_t i = 0; i < r->texture_count; i++)
        if (strcmp(r->textures[i].name, key) == 0)
            return (int32_t)i;
    if (r->texture_count >= SR_REPORT_MAX_TEXTURES)
        return -1;
    sr_report_texture *t = realloc(r->textures, (r->texture_count + 1) * sizeof *t);
    if (!t)
        return -1;
    r->textures = t;
    t = &t[r->texture_count];
    *t = (sr_report_texture){ .status = status };
    memcpy(t->name, key, sizeof key);
    sr_report_copy(t->path, found);
    return (int32_t)r->texture_count++;
}

void sr_report_warn(sr_load_report *r, const char *fmt, ...)
{
    if (r->warning_count < SR_REPORT_MAX_WARNINGS) {
        char line[SR_REPORT_TEXT];
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(line, sizeof line, fmt, ap);
        va_end(ap);
        sr_report_copy(r->warnings[r->warning_count], line);
    }
    r->warning_count++;
}

void sr_report_obj_format(sr_load_report *r)
{
    sr_report_copy(r->format, "Wavefront OBJ");
    r->up = SR_AXIS_PY;
    r->up_found = SR_FOUND_GUESSED;
    r->front = SR_AXIS_COUNT;
    sr_report_copy(r->up_why, "OBJ states no axis; Blender, Maya and most exporters write it +y up");
    r->units_found = SR_FOUND_UNKNOWN;
    sr_report_copy(r->units_why, "OBJ states no unit");
}
