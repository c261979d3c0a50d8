#include <errno.h>
#include <stdio.h>
#include <string.h>

#include "doc_file.h"
#include "report_peer.h"

#define LINE_MAX_CHARS 512

static const char HEADER[] =
    "scene\tms\tdepth_ties\tedge_ties\twrong_triangle\tcoverage\tedge_distance_max\tz_max\tz_p999\tz_median\n";

bool sr_report_peer_write(const char *path, const sr_report_peer *peer, sr_error *err)
{
    sr_doc doc;
    if (!sr_doc_open(&doc, path, err))
        return false;
    FILE *f = doc.f;
    fprintf(f, "# A peer against the truth on softrast's report scenes, written by ./build/bench-gl --truth\n"
               "# (docs/bench-compare.md) and read by softrast bench --report (docs/report.md).\n"
               "renderer\t%s\n%s", peer->renderer, HEADER);
    for (int i = 0; i < peer->count; i++) {
        const sr_report_peer_row *r = &peer->rows[i];
        const sr_truth_errors *e = &r->truth;
        fprintf(f, "%s\t%.4g\t%llu\t%llu\t%llu\t%llu\t%.3g\t%.3g\t%.3g\t%.3g\n", r->scene, r->ms,
                (unsigned long long)e->depth_ties, (unsigned long long)e->edge_ties,
                (unsigned long long)e->wrong_triangle, (unsigned long long)e->coverage, e->edge_distance_max,
                e->z_max, e->z_p999, e->z_median);
    }
    return sr_doc_close(&doc, err);
}

static bool parse_row(const char *line, sr_report_peer_row *r)
{
    unsigned long long depth_ties, edge_ties, wrong, coverage;
    sr_truth_errors *e = &r->truth;
    *r = (sr_report_peer_row){ 0 };
    if (sscanf(line, "%31[^\t]\t%lf\t%llu\t%llu\t%llu\t%llu\t%lf\t%lf\t%lf\t%lf", r->scene, &r->ms, &depth_ties,
               &edge_ties, &wrong, &coverage, &e->edge_distance_max, &e->z_max, &e->z_p999, &e->z_median) != 10)
        return false;
    e->depth_ties = depth_ties;
    e->edge_ties = edge_ties;
    e->wrong_triangle = wrong;
    e->coverage = coverage;
    return true;
}

bool sr_report_peer_read(const char *path, sr_report_peer *peer, sr_error *err)
{
    *peer = (sr_report_peer){ 0 };
    FILE *f = fopen(path, "r");
    if (!f)
        return errno == ENOENT ? true : sr_error_set(err, "%s: cannot read: %s", path, strerror(errno));
    char line[LINE_MAX_CHARS];
    bool ok = true;
    for (int n = 1; ok && fgets(line, sizeof line, f); n++) {
        line[strcspn(line, "\n")] = '\0';
        if (line[0] == '#' || strncmp(line, HEADER, strlen("scene\t")) == 0)
            continue;
        if (strncmp(line, "renderer\t", strlen("renderer\t")) == 0)
            snprintf(peer->renderer, sizeof peer->renderer, "%.*s", (int)sizeof peer->renderer - 1,
                     line + strlen("renderer\t"));
        else if (peer->count < SR_REPORT_SCENES && parse_row(line, &peer->rows[peer->count]))
            peer->count++;
        else
            ok = sr_error_set(err, "%s:%d: not a scene row (or more than %d rows)", path, n, SR_REPORT_SCENES);
    }
    fclose(f);
    return ok;
}

const sr_report_peer_row *sr_report_peer_find(const sr_report_peer *peer, const char *scene)
{
    for (int i = 0; i < peer->count; i++)
        if (strcmp(peer->rows[i].scene, scene) == 0)
            return &peer->rows[i];
    return NULL;
}
