/* Texture files found by the rules of texture_find.h. */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "obj_parse.h"
#include "texture_find.h"

/* The name Assimp's MD2 importer gives a skin the file does not name. */
#define ASSIMP_UNNAMED_TEXTURE "$texture_dummy.bmp"

/* The endings tried for a base name, in order of preference. */
static const char *const IMAGE_ENDINGS[] = { "png", "jpg", "jpeg", "tga", "bmp" };
#define ENDING_COUNT (sizeof IMAGE_ENDINGS / sizeof *IMAGE_ENDINGS)

static bool is_regular(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

/* The last component of a path written on any system. */
static const char *base_name(const char *written)
{
    const char *base = written;
    for (const char *c = written; *c; c++)
        if (*c == '/' || *c == '\\')
            base = c + 1;
    return base;
}

/* "dir/name" (dir "" is the current folder), malloc'd. */
static char *join(const char *dir, const char *name)
{
    size_t n = strlen(dir) + strlen(name) + 2;
    char *p = malloc(n);
    if (p)
        snprintf(p, n, "%s%s%s", dir, *dir ? "/" : "", name);
    return p;
}

/* How well an entry matches: 0 the name in any case, 1 + k the stem with
 * ending k, -1 not at all. */
static int match_rank(const char *entry, const char *base, size_t stem_len)
{
    if (strcasecmp(entry, base) == 0)
        return 0;
    if (strncasecmp(entry, base, stem_len) != 0 || entry[stem_len] != '.')
        return -1;
    for (size_t k = 0; k < ENDING_COUNT; k++)
        if (strcasecmp(entry + stem_len + 1, IMAGE_ENDINGS[k]) == 0)
            return 1 + (int)k;
    return -1;
}

/* The best match for base in dir (ties: the smaller name, so the answer
 * does not depend on the directory's order), or NULL. */
static char *search_folder(const char *dir, const char *base)
{
    DIR *d = opendir(*dir ? dir : ".");
    if (!d)
        return NULL;
    const char *dot = strrchr(base, '.');
    size_t stem_len = dot && dot != base ? (size_t)(dot - base) : strlen(base);
    char *best = NULL;
    int best_rank = -1;
    for (struct dirent *e; (e = readdir(d));) {
        int rank = match_rank(e->d_name, base, stem_len);
        if (rank < 0 || (best && (rank > best_rank || (rank == best_rank && strcmp(e->d_name, best) >= 0))))
            continue;
        char *path = join(dir, e->d_name);
        if (path && is_regular(path)) {
            free(best);
            best = strdup(e->d_name);
            best_rank = rank;
        }
        free(path);
    }
    closedir(d);
    char *found = best ? join(dir, best) : NULL;
    free(best);
    return found;
}

/* The folder "textures" beside, in any case, or NULL. */
static char *textures_folder(const char *dir)
{
    DIR *d = opendir(*dir ? dir : ".");
    if (!d)
        return NULL;
    char *found = NULL;
    for (struct dirent *e; !found && (e = readdir(d));) {
        if (strcasecmp(e->d_name, "textures") != 0)
            continue;
        char *path = join(dir, e->d_name);
        struct stat st;
        if (path && stat(path, &st) == 0 && S_ISDIR(st.st_mode))
            found = path;
        else
            free(path);
    }
    closedir(d);
    return found;
}

/* The folder of a path ("" for none, "/" for the root), malloc'd. */
static char *folder_of(const char *path)
{
    const char *slash = strrchr(path, '/');
    return !slash ? strdup("") : slash == path ? strdup("/") : strndup(path, (size_t)(slash - path));
}

/* Steps 2 and 3: base beside base_file, else in its textures folder. */
static char *search_beside(const char *base_file, const char *base)
{
    char *dir = folder_of(base_file);
    if (!dir)
        return NULL;
    char *found = search_folder(dir, base);
    if (!found) {
        char *textures = textures_folder(dir);
        found = textures ? search_folder(textures, base) : NULL;
        free(textures);
    }
    free(dir);
    return found;
}

/* The model's own file name without its ending ("sydney" of
 * "models/sydney.md2"), malloc'd. */
static char *model_stem(const char *base_file)
{
    const char *base = base_name(base_file), *dot = strrchr(base, '.');
    return dot && dot != base ? strndup(base, (size_t)(dot - base)) : strdup(base);
}

static char *find_one(const char *base_file, const char *written)
{
    char *as_written = sr_obj_path_beside(base_file, written);
    if (!as_written || is_regular(as_written))
        return as_written;
    const char *base = base_name(written);
    if (!*base || strcmp(base, ".") == 0 || strcmp(base, "..") == 0) {
        free(as_written);
        return NULL;
    }
    char *found = NULL;
    if (base != written) { /* 1b: in the folder it names, any case */
        char *named = folder_of(as_written);
        found = named && *named ? search_folder(named, base) : NULL;
        free(named);
    }
    free(as_written);
    if (!found && strcmp(base, ASSIMP_UNNAMED_TEXTURE) == 0) {
        char *stem = model_stem(base_file);
        found = stem && *stem ? search_beside(base_file, stem) : NULL;
        free(stem);
        return found;
    }
    return found ? found : search_beside(base_file, base);
}

/* Assimp's X3D importer joins the quoted names of a url list,
 * url='"a.png" "b.gif"', into one: a.png""b.gif. */
#define JOINED_NAMES "\"\""

char *sr_texture_find(const char *base_file, const char *written)
{
    if (!strstr(written, JOINED_NAMES))
        return find_one(base_file, written);
    char *names = strdup(written), *found = NULL;
    for (char *name = names, *next; name && !found; name = next) {
        next = strstr(name, JOINED_NAMES);
        if (next) {
            *next = '\0';
            next += strlen(JOINED_NAMES);
        }
        found = *name ? find_one(base_file, name) : NULL;
    }
    free(names);
    return found;
}
