/* load_refused.h — asserting that the library refuses a file as every bad
 * input must: one line naming the file, the mesh and texture left empty.
 * For a large file, whose command line would first print a line saying
 * that a slow load is under way. The file lies in the test's temp_dir. */
#ifndef SOFTRAST_TESTS_LOAD_REFUSED_H
#define SOFTRAST_TESTS_LOAD_REFUSED_H

#include <criterion/criterion.h>
#include <string.h>

#include "softrast/files.h"
#include "temp_dir.h"

static inline void assert_load_refused(const char *name, const char *needle)
{
    char path[600];
    temp_path(path, sizeof path, name);
    sr_mesh m;
    sr_texture tex = { 0 };
    sr_error err = { "" };
    cr_assert_not(sr_mesh_load(&m, &tex, path, &err), "%s loaded", name);
    cr_assert_eq(strncmp(err.message, path, strlen(path)), 0, "not naming the file: %s", err.message);
    cr_assert_null(strchr(err.message, '\n'), "more than one line: %s", err.message);
    cr_assert_not_null(strstr(err.message, needle), "'%s' not in: %s", needle, err.message);
    cr_assert(m.positions == NULL && m.vertex_count == 0 && tex.texels == NULL);
}

#endif
