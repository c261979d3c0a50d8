/* run_helpers.h — running the softrast program from a test and reading what
 * it printed. The binary is $SOFTRAST_BIN (the Makefile sets it to the
 * optimised or the sanitised build), else build/softrast. */
#ifndef SOFTRAST_TESTS_RUN_HELPERS_H
#define SOFTRAST_TESTS_RUN_HELPERS_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

typedef struct run_result {
    int status; /* exit status, or 128 + signal */
    char out[8192], err[8192];
} run_result;

static inline const char *softrast_bin(void)
{
    const char *bin = getenv("SOFTRAST_BIN");
    return bin ? bin : "build/softrast";
}

static inline void read_all(const char *path, char *buf, size_t cap)
{
    FILE *f = fopen(path, "rb");
    size_t n = f ? fread(buf, 1, cap - 1, f) : 0;
    buf[n] = '\0';
    if (f)
        fclose(f);
}

/* Runs `ENV softrast ARGS` (shell text, already quoted; env may be "") and
 * keeps its output in dir. */
static inline run_result run_softrast_env(const char *dir, const char *env, const char *args)
{
    run_result r;
    char cmd[4096], out_path[512], err_path[512];
    snprintf(out_path, sizeof out_path, "%s/stdout.txt", dir);
    snprintf(err_path, sizeof err_path, "%s/stderr.txt", dir);
    snprintf(cmd, sizeof cmd, "%s %s %s >%s 2>%s", env, softrast_bin(), args, out_path, err_path);
    int raw = system(cmd);
    r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
    read_all(out_path, r.out, sizeof r.out);
    read_all(err_path, r.err, sizeof r.err);
    return r;
}

static inline run_result run_softrast(const char *dir, const char *args)
{
    return run_softrast_env(dir, "", args);
}

static inline void write_text(const char *dir, const char *name, const char *text)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "wb");
    if (f) {
        fputs(text, f);
        fclose(f);
    }
}

static inline int count_lines(const char *text)
{
    int n = 0;
    for (const char *p = text; *p; p++)
        n += *p == '\n';
    return n;
}

#endif
