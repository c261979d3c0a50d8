/* The life of a subcommand: parse, run, exit status. */
#include "app.h"

int sr_app_command_run(const sr_app_command *cmd, void *job, int argc, char **argv)
{
    sr_scene scene = { 0 };
    sr_error err = { { 0 } };
    bool help = false;
    if (!cmd->parse(job, argc, argv, &help, &err))
        return sr_app_fail(err.message);
    if (help)
        return 0;
    bool ok = cmd->run(job, &scene, &err);
    sr_scene_free(&scene);
    return ok ? 0 : sr_app_fail(err.message);
}
