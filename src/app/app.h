/* app.h — the softrast program's subcommands. Each returns the exit status. */
#ifndef SOFTRAST_APP_H
#define SOFTRAST_APP_H

#include <stdio.h>

#include "softrast_private.h"

int sr_app_render(int argc, char **argv);
int sr_app_view(int argc, char **argv);
int sr_app_bench(int argc, char **argv);
int sr_app_truth(int argc, char **argv);

/* Prints "softrast: error: <message>" on stderr and returns the exit status 1. */
static inline int sr_app_fail(const char *message)
{
    fprintf(stderr, "softrast: error: %s\n", message);
    return 1;
}

#endif
