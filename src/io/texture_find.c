/* Texture files found by the rules of texture_find.h. */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "obj_parse.h"
#include "texture_find.h"

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

char *sr_texture_find(const char *base_file, const char *written)
{
    char *as_written = sr_obj_path_beside(base_file, written);
    if (!as_written || is_regular(as_written))
        return as_written;
    free(as_written);
    const char *base = base_name(written);
    if (!*base || strcmp(base, ".") == 0 || strcmp(base, "..") == 0)
        return NULL;
    const char *slash = strrchr(base_file, '/');
    char *dir = slash ? strndup(base_file, (size_t)(slash - base_file)) : strdup("");
    if (!dir)
        return NULL;
    if (slash && !*dir) { /* a file in "/" */
        free(dir);
        dir = strdup("/");
        if (!dir)
            return NULL;
    }
    char *found = search_folder(dir, base);
    if (!found) {
        char *textures = textures_folder(dir);
        found = textures ? search_folder(textures, base) : NULL;
        free(textures);
    }
    free(dir);
    return found;
}
