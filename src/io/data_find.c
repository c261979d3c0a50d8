/* data_find.c — finding the program's data (data_find.h). */
#include "data_find.h"

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/error.h"

#ifndef SR_INSTALL_DATA
#define SR_INSTALL_DATA "/usr/local/share/softrast"
#endif

#define MAX_PLACES 5

/* Cuts the last path component off path (in place); false when none is left. */
static bool cut_last(char *path)
{
    char *slash = strrchr(path, '/');
    if (!slash || slash == path)
        return false;
    *slash = '\0';
    return true;
}

/* The data directories in search order, written into places[]; returns how many. */
static int data_places(char places[][PATH_MAX])
{
    int n = 0;
    char exe[PATH_MAX];
    ssize_t len = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (len > 0) {
        exe[len] = '\0';
        if (cut_last(exe) && cut_last(exe)) {      /* build/softrast -> the tree, bin/softrast -> the prefix */
            char installed[PATH_MAX];
            snprintf(installed, sizeof installed, "%.*s/share/softrast", PATH_MAX - 16, exe);
            memcpy(places[n++], exe, PATH_MAX);
            if (cut_last(exe))                     /* build/san/softrast -> the tree */
                memcpy(places[n++], exe, PATH_MAX);
            memcpy(places[n++], installed, PATH_MAX);
        }
    }
    snprintf(places[n++], PATH_MAX, "%s", SR_INSTALL_DATA);
    const char *env = getenv("SOFTRAST_DATA");
    if (env && *env)
        snprintf(places[n++], PATH_MAX, "%.*s", PATH_MAX - 1, env);
    return n;
}

bool sr_data_find(const char *name, char *out, size_t cap, sr_error *err)
{
    char places[MAX_PLACES][PATH_MAX];
    int n = data_places(places);
    char looked[SR_ERROR_MAX] = "";
    size_t used = 0;
    for (int i = 0; i < n; i++) {
        int w = snprintf(out, cap, "%s/%s", places[i], name);
        if (w > 0 && (size_t)w < cap && access(out, R_OK) == 0)
            return true;
        if (used < sizeof looked)
            used += (size_t)snprintf(looked + used, sizeof looked - used, "%s%s", i ? ", " : "", places[i]);
    }
    const char *env = getenv("SOFTRAST_DATA");
    return sr_error_set(err, "%s: not found in %s%s", name, looked,
                        env && *env ? "" : " (set SOFTRAST_DATA to a directory holding it)");
}
