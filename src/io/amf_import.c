/* An AMF file through Assimp 5.2, mended (amf_import.h). */
#include <assimp/cimport.h>

#include "amf_constellations.h"
#include "amf_import.h"
#include "amf_read.h"

bool sr_amf_import(const char *path, unsigned flags, const struct aiScene **scene, sr_error *err)
{
    *scene = NULL;
    sr_amf_file file;
    if (!sr_amf_read(path, &file, err))
        return false;
    *scene = aiImportFile(path, flags);
    if (*scene)
        sr_amf_place_instances(*scene, &file);
    sr_amf_file_free(&file);
    return true;
}
