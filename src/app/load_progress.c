/* Loading a mesh with a word on progress: a load that takes longer than a
 * moment says what it is doing, then how long it took. */
#include <pthread.h>
#include <stdio.h>
#include <sys/stat.h>
#include <time.h>

#include "load_progress.h"
#include "core/clock.h"

typedef struct mesh_load {
    const char *path;
    sr_mesh *mesh;
    sr_texture *texture;
    sr_load_report *report;
    sr_error *err;
    bool ok, done;
    pthread_mutex_t lock;
    pthread_cond_t finished;
} mesh_load;

static void *load_in_thread(void *p)
{
    mesh_load *l = p;
    bool ok = sr_mesh_load_report(l->mesh, l->texture, l->path, l->report, l->err);
    pthread_mutex_lock(&l->lock);
    l->ok = ok;
    l->done = true;
    pthread_cond_signal(&l->finished);
    pthread_mutex_unlock(&l->lock);
    return NULL;
}

/* Waits up to ms for the load; true when it is done. */
static bool wait_done(mesh_load *l, double ms)
{
    struct timespec until;
    clock_gettime(CLOCK_REALTIME, &until);
    long long ns = until.tv_nsec + (long long)(ms * 1e6);
    until.tv_sec += (time_t)(ns / 1000000000);
    until.tv_nsec = (long)(ns % 1000000000);
    pthread_mutex_lock(&l->lock);
    while (!l->done && pthread_cond_timedwait(&l->finished, &l->lock, &until) == 0)
        ;
    bool done = l->done;
    pthread_mutex_unlock(&l->lock);
    return done;
}

bool sr_app_load_mesh(const char *path, sr_mesh *mesh, sr_texture *texture, double quiet_ms, sr_error *err)
{
    return sr_app_load_mesh_report(path, mesh, texture, NULL, quiet_ms, err);
}

bool sr_app_load_mesh_report(const char *path, sr_mesh *mesh, sr_texture *texture, sr_load_report *report,
                             double quiet_ms, sr_error *err)
{
    mesh_load l = { path,  mesh,  texture, report, err, false, false, PTHREAD_MUTEX_INITIALIZER,
                    PTHREAD_COND_INITIALIZER };
    double start = sr_now_ms();
    pthread_t thread;
    if (pthread_create(&thread, NULL, load_in_thread, &l) != 0)
        return sr_mesh_load_report(mesh, texture, path, report, err);
    bool quiet = wait_done(&l, quiet_ms);
    if (!quiet) {
        struct stat st;
        double mb = stat(path, &st) == 0 ? (double)st.st_size / 1e6 : 0.0;
        fprintf(stderr, "softrast: loading %s (%.1f MB)...\n", path, mb);
    }
    pthread_join(thread, NULL);
    if (!quiet && l.ok)
        fprintf(stderr, "softrast: loaded %s in %.1f s: %u vertices, %u triangles\n", path,
                (sr_now_ms() - start) / 1e3, mesh->vertex_count, sr_mesh_triangle_slots(mesh));
    return l.ok;
}
