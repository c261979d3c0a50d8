#include <pthread.h>

#include "draw_internal.h"

typedef struct job {
    void (*fn)(void *ctx, int t);
    void *ctx;
    int t;
} job;

static void *run_job(void *arg)
{
    job *j = arg;
    j->fn(j->ctx, j->t);
    return NULL;
}

/* Threads live for one phase of one draw: at two to a few phases a frame
 * their start-up (tens of microseconds) is noise next to a frame's work.
 * A thread that cannot start leaves its share to the calling thread. */
void sr_parallel_run(int threads, void (*fn)(void *ctx, int t), void *ctx)
{
    pthread_t ids[SR_MAX_THREADS];
    job jobs[SR_MAX_THREADS];
    bool started[SR_MAX_THREADS] = { false };
    for (int t = 1; t < threads; t++) {
        jobs[t] = (job){ fn, ctx, t };
        started[t] = pthread_create(&ids[t], NULL, run_job, &jobs[t]) == 0;
    }
    fn(ctx, 0);
    for (int t = 1; t < threads; t++) {
        if (started[t])
            pthread_join(ids[t], NULL);
        else
            fn(ctx, t);
    }
}
