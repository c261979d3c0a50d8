/* src/io/amf_read.h — private to src/io: what an AMF file holds that
 * Assimp 5.2 reads wrong, read from the file itself (amf_xml.h).
 *
 * Its unit, which Assimp does not report; its constellations, whose
 * instances Assimp misplaces (amf_constellations.h); its objects of more
 * than one volume, of which Assimp keeps the first alone
 * (amf_volumes.h).
 */
#ifndef SOFTRAST_IO_AMF_READ_H
#define SOFTRAST_IO_AMF_READ_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "core/array.h"
#include "softrast/softrast.h"

/* Names and ids longer than this are kept as "", matching no node. */
#define SR_AMF_MAX_NAME 32
/* A file of more constellations, instances or objects of several volumes
 * than this is refused. */
#define SR_AMF_MAX_ENTRIES (1u << 20)

typedef struct sr_amf_instance {
    char objectid[SR_AMF_MAX_NAME];
    double value[6]; /* deltax, deltay, deltaz, then rx, ry, rz in degrees */
} sr_amf_instance;

typedef struct sr_amf_constellation {
    char id[SR_AMF_MAX_NAME];
    size_t first, count; /* its instances in the file's list */
} sr_amf_constellation;

/* An object of more than one volume with triangles. */
typedef struct sr_amf_split {
    size_t object;     /* which of the root's objects, counted from 0 in the file's order */
    uint32_t vertices; /* how many its mesh lists */
} sr_amf_split;

typedef struct sr_amf_file {
    size_t bytes;
    double metres_per_unit; /* the root's unit, 0 when it states none known */
    sr_array constellations; /* of sr_amf_constellation, in the file's order */
    sr_array instances;      /* of sr_amf_instance */
    sr_array splits;         /* of sr_amf_split, in the file's order */
    bool hash_in_id;         /* an object's or constellation's id holds '#' */
} sr_amf_file;

/* Reads the file at path. False, with one line in err and *out empty, when
 * it cannot be read (amf_xml.h) or holds more than SR_AMF_MAX_ENTRIES
 * constellations, instances or objects to split. */
bool sr_amf_read(const char *path, sr_amf_file *out, sr_error *err);
void sr_amf_file_free(sr_amf_file *file);

#endif
