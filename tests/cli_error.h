/* cli_error.h — asserting that a command line fails as every bad input
 * must: one "softrast: error: ..." line, a non-zero exit, no crash, no hang.
 * The command runs in the test's temp_dir. */
#ifndef SOFTRAST_TESTS_CLI_ERROR_H
#define SOFTRAST_TESTS_CLI_ERROR_H

#include "run_helpers.h"
#include "temp_dir.h"

/* One error line that starts with the prefix and mentions `needle`, at
 * once: a run that hangs is killed (exit 128 + 9) and fails the test. */
static inline void assert_one_error(const char *args, const char *needle)
{
    char full[1024];
    snprintf(full, sizeof full, args, temp_dir, temp_dir);
    run_result r = run_softrast_env(temp_dir, "timeout -s KILL 20", full);
    cr_assert(r.status != 0 && r.status < 128, "`softrast %s` exited %d", full, r.status);
    cr_assert_eq(strncmp(r.err, "softrast: error: ", 17), 0, "stderr was: %s", r.err);
    cr_assert_eq(count_lines(r.err), 1, "want one line, stderr was: %s", r.err);
    cr_assert_not_null(strstr(r.err, needle), "'%s' not in: %s", needle, r.err);
}

#endif
