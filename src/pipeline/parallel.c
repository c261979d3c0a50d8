#include <pthread.h>

#include "core/clock.h"
#include "draw_internal.h"

void sr_chunks_init(sr_chunks *c, uint32_t count, uint32_t size)
{
    atomic_init(&c->next, 0);
    c->count = count;
    c->size = size;
}

bool sr_chunks_take(sr_chunks *c, uint32_t *first, uint32_t *end)
{
    uint64_t start = (uint64_t)atomic_fetch_add(&c->next, 1) * c->size;
    if (start >= c->count)
        return false;
    *first = (uint32_t)start;
    *end = start + c->size < c->count ? (uint32_t)(start + c->size) : c->count;
    return true;
}

typedef struct job {
    void (*fn)(void *ctx, int t);
    void *ctx;
    int t;
    bool timed;
    double cpu_ms; /* the thread's CPU time in fn, when timed */
} job;

static void *run_job(void *arg)
{
    job *j = arg;
    double start = j->timed ? sr_clock_ms(CLOCK_THREAD_CPUTIME_ID) : 0.0;
    j->fn(j->ctx, j->t);
    if (j->timed)
        j->cpu_ms = sr_clock_ms(CLOCK_THREAD_CPUTIME_ID) - start;
    return NULL;
}

/* Threads live for one phase of one draw: at two to a few phases a frame
 * their start-up (tens of microseconds) is noise next to a frame's work.
 * A thread that cannot start leaves its share to the calling thread. */
void sr_parallel_run(int threads, void (*fn)(void *ctx, int t), void *ctx, sr_phase_time *time)
{
    pthread_t ids[SR_MAX_THREADS];
    job jobs[SR_MAX_THREADS];
    bool started[SR_MAX_THREADS] = { false };
    double start = time ? sr_now_ms() : 0.0;
    for (int t = 0; t < threads; t++)
        jobs[t] = (job){ fn, ctx, t, time != NULL, 0.0 };
    for (int t = 1; t < threads; t++)
        started[t] = pthread_create(&ids[t], NULL, run_job, &jobs[t]) == 0;
    run_job(&jobs[0]);
    for (int t = 1; t < threads; t++) {
        if (started[t])
            pthread_join(ids[t], NULL);
        else
            run_job(&jobs[t]);
    }
    if (!time)
        return;
    time->wall += sr_now_ms() - start;
    for (int t = 0; t < threads; t++)
        time->cpu += jobs[t].cpu_ms;
}
