/* sr_mesh_load: the file's ending picks the loader. */
#include <stdio.h>
#include <string.h>
#include <strings.h>

#include "core/error.h"
#include "core/input_file.h"
#include "mesh_loaders.h"

static bool ends_with_obj(const char *path)
{
    size_t n = strlen(path);
    return n >= 4 && strcasecmp(path + n - 4, ".obj") == 0;
}

/* Assimp opens the file itself: it must be a regular file before that
 * (a FIFO would block the importer until its time limit). */
static bool regular_file(const char *path, sr_error *err)
{
    const char *why;
    FILE *f = sr_input_open(path, &why);
    if (!f)
        return sr_error_set(err, "%s: cannot open: %s", path, why);
    fclose(f);
    return true;
}

bool sr_mesh_load_report(sr_mesh *mesh, sr_texture *texture, const char *path, sr_load_report *report,
                         sr_error *err)
{
    sr_texture unwanted;
    sr_texture *embedded = texture ? texture : &unwanted;
    *embedded = (sr_texture){ 0 };
    if (report)
        *report = (sr_load_report){ 0 };
    if (ends_with_obj(path))
        return sr_obj_load_report(mesh, path, report, err);
    *mesh = (sr_mesh){ 0 };
    bool ok = regular_file(path, err) &&
              sr_assimp_load_report(mesh, embedded, path, SR_IMPORT_SECONDS, report, err);
    mesh->z_negated = ok; /* as OBJ's: Assimp's formats are right-handed too */
    if (!texture) { /* skipped: its materials draw their colour */
        for (uint32_t i = 0; i < mesh->material_count; i++)
            if (mesh->materials[i].texture == &unwanted)
                mesh->materials[i].texture = NULL;
        sr_texture_free(&unwanted);
    }
    return ok;
}

bool sr_mesh_load(sr_mesh *mesh, sr_texture *texture, const char *path, sr_error *err)
{
    return sr_mesh_load_report(mesh, texture, path, NULL, err);
}
