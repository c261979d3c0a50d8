/* src/io/amf_xml.h — private to src/io: an AMF file's XML, read by
 * libexpat, each element named by what it is in AMF.
 *
 * The reader (amf_read.h) and the volume splitter (amf_volumes.h) walk the
 * same file and must agree on what an element is: an <instance> counts
 * only inside a <constellation> of the <amf> root, a <v1> only inside a
 * <triangle> of a <volume>, and so on (Assimp 5.2's reading). An element
 * anywhere else is SR_AMF_OTHER, as is everything below one.
 *
 * Bad input is one line: a file that is not well-formed XML
 * (PATH:LINE: what expat says), a zipped AMF (Assimp 5.2 reads none), or
 * one that declares entities (Assimp's XML parser expands none; expat's
 * expansion would be a way to blow a small file up).
 */
#ifndef SOFTRAST_IO_AMF_XML_H
#define SOFTRAST_IO_AMF_XML_H

#include <stdbool.h>
#include <stddef.h>

#include "softrast/softrast.h"

typedef enum sr_amf_kind {
    SR_AMF_OTHER,
    SR_AMF_ROOT,          /* <amf> */
    SR_AMF_OBJECT,        /* <object> in the root */
    SR_AMF_MESH,          /* <mesh> in an object */
    SR_AMF_VERTICES,      /* <vertices> in a mesh */
    SR_AMF_VERTEX,        /* <vertex> in the vertices */
    SR_AMF_VOLUME,        /* <volume> in a mesh */
    SR_AMF_TRIANGLE,      /* <triangle> in a volume */
    SR_AMF_CORNER,        /* <v1>, <v2>, <v3> in a triangle: a vertex index */
    SR_AMF_CONSTELLATION, /* <constellation> in the root */
    SR_AMF_INSTANCE,      /* <instance> in a constellation */
    SR_AMF_PLACEMENT,     /* <deltax> … <rz> in an instance */
} sr_amf_kind;

/* What a walk does with each element: its start (name and attributes as
 * expat gives them, name/value pairs then NULL), its text (in pieces) and
 * its end, each told the element's kind. A handler returns false to stop
 * the walk, with its error set. */
typedef struct sr_amf_walk {
    void *user;
    bool (*start)(void *user, sr_amf_kind kind, const char *name, const char **attributes);
    bool (*text)(void *user, sr_amf_kind kind, const char *text, size_t len);
    bool (*end)(void *user, sr_amf_kind kind, const char *name);
} sr_amf_walk;

/* The value of the attribute of that name among a start's attributes, ""
 * when it has none. */
const char *sr_amf_attribute(const char **attributes, const char *name);

/* Walks the file at path; *bytes (may be NULL) its size. False, with one
 * line in err, when it cannot be read, is not well-formed XML, is zipped
 * or declares entities, or when a handler stops the walk. */
bool sr_amf_xml_walk(const char *path, const sr_amf_walk *walk, size_t *bytes, sr_error *err);

#endif
