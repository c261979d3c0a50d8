/* temp_dir.h — a fresh directory under /tmp for each test, removed after it
 * (use temp_dir_make / temp_dir_remove as a suite's .init / .fini). */
#ifndef SOFTRAST_TESTS_TEMP_DIR_H
#define SOFTRAST_TESTS_TEMP_DIR_H

#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define TEMP_DIR_TEMPLATE "/tmp/softrast-test-XXXXXX"

static char temp_dir[sizeof TEMP_DIR_TEMPLATE];

static inline void temp_dir_make(void)
{
    memcpy(temp_dir, TEMP_DIR_TEMPLATE, sizeof temp_dir);
    cr_assert_not_null(mkdtemp(temp_dir), "mkdtemp failed");
}

static inline void temp_dir_remove(void)
{
    char cmd[sizeof temp_dir + 16];
    snprintf(cmd, sizeof cmd, "rm -rf %s", temp_dir);
    cr_assert_eq(system(cmd), 0, "could not remove %s", temp_dir);
}

/* temp_dir/name in buf. */
static inline const char *temp_path(char *buf, size_t size, const char *name)
{
    snprintf(buf, size, "%s/%s", temp_dir, name);
    return buf;
}

#endif
