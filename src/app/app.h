/* app.h — the softrast program's subcommands. Each returns the exit status. */
#ifndef SOFTRAST_APP_H
#define SOFTRAST_APP_H

#include <stdio.h>

#include "scene_setup.h"
#include "softrast_private.h"

/* A subcommand: its command line parsed into its job (false: err says why;
 * *help: the help was printed), then run on a scene the runner frees. */
typedef struct sr_app_command {
    bool (*parse)(void *job, int argc, char **argv, bool *help, sr_error *err);
    bool (*run)(void *job, sr_scene *scene, sr_error *err);
} sr_app_command;

/* Parses and runs, and turns the outcome into the exit status: 0, or 1
 * after one "softrast: error: …" line. */
int sr_app_command_run(const sr_app_command *cmd, void *job, int argc, char **argv);

int sr_app_render(int argc, char **argv);
int sr_app_view(int argc, char **argv);
int sr_app_bench(int argc, char **argv);
int sr_app_truth(int argc, char **argv);
int sr_app_info(int argc, char **argv);

/* Prints "softrast: error: <message>" on stderr and returns the exit status 1. */
static inline int sr_app_fail(const char *message)
{
    fprintf(stderr, "softrast: error: %s\n", message);
    return 1;
}

#endif
