#include <stdio.h>

#include "app.h"

int sr_app_fail(const char *message)
{
    fprintf(stderr, "softrast: error: %s\n", message);
    return 1;
}
