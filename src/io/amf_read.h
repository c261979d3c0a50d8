/* src/io/amf_read.h — private to src/io: what an AMF file holds that
 * Assimp 5.2 reads wrong, read from the file itself (amf_xml.h).
 *
 * Its constellations, whose instances Assimp misplaces
 * (amf_constellations.h).
 */
#ifndef SOFTRAST_IO_AMF_READ_H
#define SOFTRAST_IO_AMF_READ_H

#include <stdbool.h>
#include <stddef.h>

#include "core/array.h"
#include "softrast/softrast.h"

/* Names and ids longer than this are kept as "", matching no node. */
#define SR_AMF_MAX_NAME 32
/* A file of more constellations or instances than this is refused. */
#define SR_AMF_MAX_ENTRIES (1u << 20)

typedef struct sr_amf_instance {
    char objectid[SR_AMF_MAX_NAME];
    double value[6]; /* deltax, deltay, deltaz, then rx, ry, rz in degrees */
} sr_amf_instance;

typedef struct sr_amf_constellation {
    char id[SR_AMF_MAX_NAME];
    size_t first, count; /* its instances in the file's list */
} sr_amf_constellation;

typedef struct sr_amf_file {
    sr_array constellations; /* of sr_amf_constellation, in the file's order */
    sr_array instances;      /* of sr_amf_instance */
} sr_amf_file;

/* Reads the file at path. False, with one line in err and *out empty, when
 * it cannot be read (amf_xml.h) or holds more than SR_AMF_MAX_ENTRIES
 * constellations or instances. */
bool sr_amf_read(const char *path, sr_amf_file *out, sr_error *err);
void sr_amf_file_free(sr_amf_file *file);

#endif
