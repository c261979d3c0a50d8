/* A slow mesh load says so: one line naming the file and its size while it
 * loads, one with the time and the counts once it has. */
#include <criterion/criterion.h>
#include <criterion/redirect.h>
#include <stdio.h>
#include <string.h>

#include "app/load_progress.h"

#define SPIDER "/usr/share/assimp/models/STL/Spider_ascii.stl"

/* The import runs in a child process, so with no quiet time at all the
 * line always comes before the load is done. */
Test(load_progress, a_load_past_the_quiet_time_says_what_it_loads_and_what_it_read, .init = cr_redirect_stderr)
{
    sr_mesh m;
    sr_texture t;
    sr_error err = { "" };
    cr_assert(sr_app_load_mesh(SPIDER, &m, &t, 0.0, &err), "%s", err.message);
    fflush(stderr);
    char said[1024] = "";
    size_t n = fread(said, 1, sizeof said - 1, cr_get_redirected_stderr());
    said[n] = '\0';
    cr_assert_not_null(strstr(said, "softrast: loading " SPIDER " ("), "%s", said);
    cr_assert_not_null(strstr(said, "softrast: loaded " SPIDER " in "), "%s", said);
    cr_assert_not_null(strstr(said, "1368 triangles\n"), "%s", said);
    sr_mesh_free(&m);
    sr_texture_free(&t);
}

Test(load_progress, a_quick_load_is_silent, .init = cr_redirect_stderr)
{
    sr_mesh m;
    sr_texture t;
    sr_error err = { "" };
    cr_assert(sr_app_load_mesh("assets/cube.obj", &m, &t, 60000.0, &err), "%s", err.message);
    cr_assert_eq(m.index_count, 36);
    fflush(stderr);
    cr_assert_stderr_eq_str("");
    sr_mesh_free(&m);
    sr_texture_free(&t);
}

Test(load_progress, a_failed_load_keeps_its_error)
{
    sr_mesh m;
    sr_texture t;
    sr_error err = { "" };
    cr_assert_not(sr_app_load_mesh("/nonexistent.ply", &m, &t, 60000.0, &err));
    cr_assert_not_null(strstr(err.message, "/nonexistent.ply"), "%s", err.message);
}
