/* src/io/load_report.h — private to softrast: what a loader found in a file
 * beyond the mesh, for `softrast info` and for the program's upright turn.
 *
 * The format (the Assimp importer's name, or "Wavefront OBJ"), the up axis
 * and units the file states or that its format implies, the parts with their
 * materials and textures (found at which path, embedded, or missing), what
 * was left out (points, lines, animations, cameras, lights) and warnings
 * (one line each) that the program prints. Fixed-size records, so the
 * Assimp child sends them through its pipe as they are.
 */
#ifndef SOFTRAST_IO_LOAD_REPORT_H
#define SOFTRAST_IO_LOAD_REPORT_H

#include <stdbool.h>
#include <stdint.h>

#include "softrast/files.h"

#define SR_REPORT_TEXT 256        /* a name, path or reason, NUL included; longer ones are cut */
#define SR_REPORT_MAX_PARTS 4096u /* parts listed; the rest counted in parts_unlisted */
#define SR_REPORT_MAX_TEXTURES 256u
#define SR_REPORT_MAX_WARNINGS 8u

/* A direction of the file's frame: +x, -x, +y, -y, +z, -z. */
typedef enum sr_axis { SR_AXIS_PX, SR_AXIS_NX, SR_AXIS_PY, SR_AXIS_NY, SR_AXIS_PZ, SR_AXIS_NZ, SR_AXIS_COUNT } sr_axis;
extern const char *const SR_AXIS_NAMES[]; /* "x", "-x", "y", … for --up-axis, NULL-terminated */
extern const char *const SR_AXIS_SIGNED[]; /* "+x", "-x", "+y", … for reports */

/* How the up axis or the units were known. */
typedef enum sr_found { SR_FOUND_UNKNOWN, SR_FOUND_GUESSED, SR_FOUND_READ } sr_found;
extern const char *const SR_FOUND_NAMES[]; /* "unknown", "guessed", "read" */

typedef enum sr_texture_status { SR_TEXTURE_FOUND, SR_TEXTURE_EMBEDDED, SR_TEXTURE_MISSING } sr_texture_status;
extern const char *const SR_TEXTURE_STATUS_NAMES[]; /* "found", "embedded", "missing" */

typedef struct sr_report_part {
    uint32_t first_triangle, triangle_count;
    char material[SR_REPORT_TEXT]; /* "" without a material */
    int32_t texture;               /* index into textures, or -1 */
} sr_report_part;

typedef struct sr_report_texture {
    char name[SR_REPORT_TEXT]; /* as the file writes it */
    char path[SR_REPORT_TEXT]; /* where it was found ("" when embedded or missing) */
    uint32_t status;           /* sr_texture_status */
} sr_report_texture;

typedef struct sr_load_report {
    char format[SR_REPORT_TEXT];
    uint32_t up;                   /* sr_axis, in the file's frame */
    uint32_t up_found;             /* sr_found */
    char up_why[SR_REPORT_TEXT];   /* "glTF 2.0 defines +y up", … */
    uint32_t front;                /* sr_axis the scene faces, said with the up axis; SR_AXIS_COUNT: unsaid */
    double metres_per_unit;        /* 0 when unknown */
    uint32_t units_found;          /* sr_found */
    char units_why[SR_REPORT_TEXT];
    uint64_t points, lines;        /* primitives left out */
    uint32_t animations, cameras, lights, skinned_meshes, mirrored_meshes;
    uint32_t morphed_meshes;       /* drawn with their morph targets at the default weights */
    uint32_t part_count, parts_unlisted, texture_count, warning_count;
    sr_report_part *parts;          /* part_count */
    sr_report_texture *textures;    /* texture_count */
    char warnings[SR_REPORT_MAX_WARNINGS][SR_REPORT_TEXT];
} sr_load_report;

/* sr_mesh_load (softrast/files.h), and what the loader found into report
 * (which may be NULL). The report is the caller's to free with
 * sr_load_report_free, whatever the outcome. */
bool sr_mesh_load_report(sr_mesh *mesh, sr_texture *texture, const char *path, sr_load_report *report,
                         sr_error *err);

void sr_load_report_free(sr_load_report *r);

/* Appends a part (false when out of memory; past SR_REPORT_MAX_PARTS it is
 * counted, not listed). */
bool sr_report_add_part(sr_load_report *r, uint32_t first, uint32_t count, const char *material, int32_t texture);
/* The index of the texture named `name`, added if new with its status and
 * found path (NULL: none); -1 when out of memory or past the limit. */
int32_t sr_report_add_texture(sr_load_report *r, const char *name, const char *found, sr_texture_status status);
/* One warning line: all are counted in warning_count, the first
 * SR_REPORT_MAX_WARNINGS kept. */
void sr_report_warn(sr_load_report *r, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* An OBJ's format, axes and units: +y up guessed, units unknown. */
void sr_report_obj_format(sr_load_report *r);
/* Copies src into a SR_REPORT_TEXT field, cut to fit, control characters as '?'. */
void sr_report_copy(char dst[SR_REPORT_TEXT], const char *src);

#endif
