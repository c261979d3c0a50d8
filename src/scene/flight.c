#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flight.h"
#include "core/error.h"
#include "core/input_file.h"

#define LINE_MAX_CHARS 4096

#define FAR_INDEX 11 /* the one number that may be inf, as --far inf */

/* Reads exactly twelve finite numbers from one line (far may also be inf);
 * false if it has more, fewer, or anything that is not a number. */
static bool parse_key(char *line, float key[SR_FLIGHT_NUMBERS])
{
    int n = 0;
    for (char *tok = strtok(line, " \t,\r\n"); tok; tok = strtok(NULL, " \t,\r\n")) {
        char *end;
        errno = 0;
        double v = strtod(tok, &end);
        bool infinite_far = n == FAR_INDEX && isinf(v) && v > 0.0;
        if (n == SR_FLIGHT_NUMBERS || *end != '\0' || end == tok || errno == ERANGE ||
            (!infinite_far && !(fabs(v) <= 3.0e38)))
            return false;
        key[n++] = (float)v;
    }
    return n == SR_FLIGHT_NUMBERS;
}

static bool is_blank(const char *line)
{
    return line[strspn(line, " \t\r\n")] == '\0';
}

static bool add_key(sr_flight *s, const char *path, int line_no, char *line, sr_error *err)
{
    if (s->count == SR_FLIGHT_MAX_KEYS)
        return sr_error_set(err, "%s:%d: more than %d key frames", path, line_no, SR_FLIGHT_MAX_KEYS);
    float (*grown)[SR_FLIGHT_NUMBERS] = realloc(s->keys, (size_t)(s->count + 1) * sizeof *s->keys);
    if (!grown)
        return sr_error_set(err, "%s:%d: out of memory", path, line_no);
    s->keys = grown;
    if (!parse_key(line, s->keys[s->count]))
        return sr_error_set(err, "%s:%d: expected 12 finite numbers (far may be inf): eye(3) target(3) up(3) fov near far",
                            path, line_no);
    s->count++;
    return true;
}

static bool read_keys(sr_flight *s, FILE *f, const char *path, sr_error *err)
{
    char line[LINE_MAX_CHARS];
    for (int line_no = 1; fgets(line, sizeof line, f); line_no++) {
        if (!strchr(line, '\n') && !feof(f))
            return sr_error_set(err, "%s:%d: line longer than %d characters", path, line_no, LINE_MAX_CHARS - 2);
        char *hash = strchr(line, '#');
        if (hash)
            *hash = '\0';
        if (!is_blank(line) && !add_key(s, path, line_no, line, err))
            return false;
    }
    return s->count > 0 ? true : sr_error_set(err, "%s: no key frames", path);
}

bool sr_flight_load(sr_flight *s, const char *path, sr_error *err)
{
    *s = (sr_flight){ 0 };
    const char *why;
    FILE *f = sr_input_open(path, &why);
    if (!f)
        return sr_error_set(err, "%s: cannot open: %s", path, why);
    bool ok = read_keys(s, f, path, err);
    fclose(f);
    if (!ok)
        sr_flight_free(s);
    return ok;
}

void sr_flight_free(sr_flight *s)
{
    free(s->keys);
    *s = (sr_flight){ 0 };
}

void sr_flight_camera(const sr_flight *s, int frame, int frames, sr_camera *cam)
{
    double pos = frames > 1 ? (double)frame * (s->count - 1) / (frames - 1) : 0.0;
    int k = (int)pos < s->count - 1 ? (int)pos : s->count - 1;
    float t = (float)(pos - k);
    const float *a = s->keys[k], *b = s->keys[k + 1 < s->count ? k + 1 : k];
    float v[SR_FLIGHT_NUMBERS];
    for (int i = 0; i < SR_FLIGHT_NUMBERS; i++)
        v[i] = t == 0.0f ? a[i] : isinf(a[i]) || isinf(b[i]) ? INFINITY : a[i] + t * (b[i] - a[i]);
    *cam = (sr_camera){ .eye = { v[0], v[1], v[2] }, .target = { v[3], v[4], v[5] }, .up = { v[6], v[7], v[8] },
                        .fov_deg = v[9], .near = v[10], .far = v[11] };
}
