/* An AMF file through Assimp 5.2, mended (amf_import.h). */
#include <assimp/cimport.h>
#include <stdlib.h>

#include "amf_constellations.h"
#include "amf_import.h"
#include "amf_read.h"
#include "amf_volumes.h"

bool sr_amf_import(const char *path, unsigned flags, const struct aiScene **scene, double *metres_per_unit,
                   sr_error *err)
{
    *scene = NULL;
    sr_amf_file file;
    if (!sr_amf_read(path, &file, err))
        return false;
    *metres_per_unit = file.metres_per_unit;
    if (file.splits.count == 0) {
        *scene = aiImportFile(path, flags);
    } else {
        char *text;
        size_t size;
        if (!sr_amf_split_volumes(path, &file, &text, &size, err)) {
            sr_amf_file_free(&file);
            return false;
        }
        *scene = aiImportFileFromMemory(text, (unsigned)size, flags, "amf");
        free(text);
    }
    if (*scene)
        sr_amf_place_instances(*scene, &file);
    sr_amf_file_free(&file);
    return true;
}
