/* Real files drawn as they mean (issue 33): every file that
 * tests/scenes_manifest.json names, from Debian's assimp-testmodels
 * (tools/deps.sh installs it), held to what `softrast info --json` says of
 * it (up axis and how it was known, triangles, parts, the set of materials,
 * textures found, embedded and missing, what the static pose left out) and
 * to how much of a small default render it covers. The manifest's "shows"
 * says what its picture in docs/images/scenes-sheet.png shows, checked by
 * eye; the coverage floor, half of what it covered then, catches a scene
 * no longer framed or seen edge-on (left out for the three largest files,
 * whose loads dominate the suite's time). */
#include <cJSON.h>
#include <criterion/criterion.h>
#include <criterion/parameterized.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "case_format.h"
#include "run_helpers.h"
#include "softrast_private.h"
#include "temp_dir.h"

#define MANIFEST "tests/scenes_manifest.json"
#define MAX_FILES 256
#define MAX_MATERIALS 512
#define COVER_W 64
#define COVER_H 48

TestSuite(scene_manifest, .init = temp_dir_make, .fini = temp_dir_remove);

/* The manifest, parsed; NULL with a message in why when it cannot be. */
static cJSON *manifest_load(char why[CASE_PATH_MAX + 64])
{
    char path[CASE_PATH_MAX];
    case_root_path(MANIFEST, path);
    FILE *f = fopen(path, "rb");
    if (!f) {
        snprintf(why, CASE_PATH_MAX + 64, "cannot open %s", path);
        return NULL;
    }
    static char text[1 << 17];
    size_t n = fread(text, 1, sizeof text - 1, f);
    fclose(f);
    text[n] = '\0';
    cJSON *m = cJSON_Parse(text);
    if (!m)
        snprintf(why, CASE_PATH_MAX + 64, "%s is not JSON (or is longer than %zu bytes)", path, sizeof text - 1);
    return m;
}

static const cJSON *item(const cJSON *o, const char *key)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);
    cr_assert_not_null(v, "no \"%s\"", key);
    return v;
}

static int number(const cJSON *o, const char *key, int absent)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);
    return v ? v->valueint : absent;
}

/* The info's sorted set of part materials is the manifest's. */
static void expect_materials(const char *file, const cJSON *parts, const cJSON *want)
{
    const char *names[MAX_MATERIALS];
    int n = 0;
    const cJSON *p;
    cJSON_ArrayForEach(p, parts)
    {
        const char *name = item(p, "material")->valuestring;
        bool seen = false;
        for (int i = 0; i < n && !seen; i++)
            seen = strcmp(names[i], name) == 0;
        if (!seen && n < MAX_MATERIALS)
            names[n++] = name;
    }
    cr_expect_eq(n, cJSON_GetArraySize(want), "%s: %d materials, the manifest names %d", file, n,
                 cJSON_GetArraySize(want));
    const cJSON *w;
    cJSON_ArrayForEach(w, want)
    {
        bool found = false;
        for (int i = 0; i < n && !found; i++)
            found = strcmp(names[i], w->valuestring) == 0;
        cr_expect(found, "%s: no part has material '%s'", file, w->valuestring);
    }
}

static void expect_textures(const char *file, const cJSON *textures, const cJSON *want)
{
    static const char *const statuses[] = { "found", "embedded", "missing" };
    for (int s = 0; s < 3; s++) {
        int n = 0;
        const cJSON *t;
        cJSON_ArrayForEach(t, textures) n += strcmp(item(t, "status")->valuestring, statuses[s]) == 0;
        cr_expect_eq(n, number(want, statuses[s], 0), "%s: %d textures %s, the manifest says %d", file, n,
                     statuses[s], number(want, statuses[s], 0));
    }
}

static void expect_info(const char *root, const cJSON *want)
{
    const char *file = item(want, "file")->valuestring;
    char args[1024];
    snprintf(args, sizeof args, "info --json '%s/%s'", root, file);
    run_result r = run_softrast(temp_dir, args);
    cr_assert_eq(r.status, 0, "softrast %s: %s", args, r.err);
    /* Read whole: a scene of many parts prints more than r.out holds. */
    static char out[1 << 20];
    char out_path[600];
    read_all(temp_path(out_path, sizeof out_path, "stdout.txt"), out, sizeof out);
    cJSON *o = cJSON_Parse(out);
    cr_assert_not_null(o, "not JSON: %.200s", out);
    cr_expect_str_eq(item(o, "up_axis")->valuestring, item(want, "up")->valuestring, "%s: up axis", file);
    cr_expect_str_eq(item(o, "up_found")->valuestring, item(want, "up_found")->valuestring, "%s: up found", file);
    cr_expect_eq(item(o, "triangles")->valueint, item(want, "triangles")->valueint, "%s: triangles", file);
    const cJSON *parts = item(o, "parts");
    cr_expect_eq(cJSON_GetArraySize(parts), item(want, "parts")->valueint, "%s: parts", file);
    expect_materials(file, parts, item(want, "materials"));
    expect_textures(file, item(o, "textures"), item(want, "textures"));
    cr_expect_eq(item(item(o, "left_out"), "animations")->valueint, number(want, "animations", 0), "%s: animations",
                 file);
    cr_expect_eq(item(o, "skinned_meshes")->valueint, number(want, "skinned", 0), "%s: skinned meshes", file);
    cr_expect_eq(item(o, "mirrored_meshes")->valueint, number(want, "mirrored", 0), "%s: mirrored meshes", file);
    cJSON_Delete(o);
}

/* The share of a small default render (id shading, so any drawn pixel
 * counts, however dark its colour) that the scene covers. */
static double coverage(const char *root, const char *file)
{
    char args[1024], out[600];
    snprintf(out, sizeof out, "%s/ids.png", temp_dir);
    snprintf(args, sizeof args, "render '%s/%s' --size %dx%d --shade id --quiet --out %s", root, file, COVER_W,
             COVER_H, out);
    run_result r = run_softrast(temp_dir, args);
    cr_assert_eq(r.status, 0, "softrast %s: %s", args, r.err);
    sr_texture image;
    sr_error err;
    cr_assert(sr_texture_load(&image, out, &err), "%s", err.message);
    int drawn = 0;
    for (int i = 0; i < COVER_W * COVER_H; i++)
        drawn += (image.texels[i] & 0xFFFFFFu) != 0;
    sr_texture_free(&image);
    return (double)drawn / (COVER_W * COVER_H);
}

static void free_params(struct criterion_test_params *params)
{
    cr_free(params->params);
}

/* One test per file the manifest names (as many as it has, read here). */
ParameterizedTestParameters(scene_manifest, file)
{
    char why[CASE_PATH_MAX + 64];
    cJSON *m = manifest_load(why);
    int n = m ? cJSON_GetArraySize(cJSON_GetObjectItem(m, "files")) : 0;
    n = n < 1 ? 1 : n > MAX_FILES ? MAX_FILES : n;
    cJSON_Delete(m);
    int *index = cr_calloc((size_t)n, sizeof *index);
    for (int i = 0; i < n; i++)
        index[i] = i;
    return cr_make_param_array(int, index, (size_t)n, free_params);
}

ParameterizedTest(int *index, scene_manifest, file, .timeout = 60.0)
{
    char why[CASE_PATH_MAX + 64];
    cJSON *m = manifest_load(why);
    cr_assert_not_null(m, "%s", why);
    const cJSON *files = item(m, "files");
    cr_assert_lt(*index, cJSON_GetArraySize(files), "%s names no files", MANIFEST);
    cr_assert_leq(cJSON_GetArraySize(files), MAX_FILES, "%s names more than %d files", MANIFEST, MAX_FILES);
    const char *root = item(m, "root")->valuestring;
    const cJSON *want = cJSON_GetArrayItem(files, *index);
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", root, item(want, "file")->valuestring);
    FILE *f = fopen(path, "rb");
    cr_assert_not_null(f, "%s is missing: tools/deps.sh installs assimp-testmodels", path);
    fclose(f);
    expect_info(root, want);
    const cJSON *floor = cJSON_GetObjectItemCaseSensitive(want, "coverage_min"); /* the largest files: none, for time */
    if (floor) {
        double share = coverage(root, item(want, "file")->valuestring);
        cr_expect_geq(share, floor->valuedouble, "%s covers %.3f of the frame, less than %.2f", path, share,
                      floor->valuedouble);
    }
    cJSON_Delete(m);
}
