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

/* fn(ctx, t), and the CPU time the calling thread spent in it when timed. */
static double timed_call(void (*fn)(void *ctx, int t), void *ctx, int t, bool timed)
{
    double start = timed ? sr_clock_ms(CLOCK_THREAD_CPUTIME_ID) : 0.0;
    fn(ctx, t);
    return timed ? sr_clock_ms(CLOCK_THREAD_CPUTIME_ID) - start : 0.0;
}

/* A worker sleeps on its own condition variable until it is handed a phase
 * or the pool stops; the loop around the wait absorbs spurious wakeups. The
 * lock orders everything: the phase's fn and ctx are written under it before
 * has_work, and the worker's results under it before pending drops, so the
 * caller that sees pending at 0 sees every write fn made. */
static void *worker_run(void *arg)
{
    sr_worker *w = arg;
    sr_pool *pool = w->pool;
    pthread_mutex_lock(&pool->lock);
    for (;;) {
        while (!w->has_work && !pool->stopping)
            pthread_cond_wait(&w->wake, &pool->lock);
        if (!w->has_work) /* stopping: never set while a phase runs */
            break;
        void (*fn)(void *, int) = pool->fn;
        void *ctx = pool->ctx;
        bool timed = pool->timed;
        pthread_mutex_unlock(&pool->lock);
        double cpu_ms = timed_call(fn, ctx, w->t, timed);
        pthread_mutex_lock(&pool->lock);
        w->cpu_ms = cpu_ms;
        w->has_work = false;
        if (--pool->pending == 0)
            pthread_cond_signal(&pool->done);
    }
    pthread_mutex_unlock(&pool->lock);
    return NULL;
}

static bool pool_ready(sr_pool *pool)
{
    if (pool->ready)
        return true;
    if (pthread_mutex_init(&pool->lock, NULL) != 0)
        return false;
    if (pthread_cond_init(&pool->done, NULL) != 0) {
        pthread_mutex_destroy(&pool->lock);
        return false;
    }
    pool->ready = true;
    pool->started = 1;
    return true;
}

/* Starts workers until the pool has `threads` threads, the caller counted,
 * and returns how many it has: fewer when one cannot start. */
static int pool_grow(sr_pool *pool, int threads)
{
    if (!pool_ready(pool))
        return 1;
    while (pool->started < threads) {
        sr_worker *w = &pool->workers[pool->started];
        *w = (sr_worker){ .pool = pool, .t = pool->started };
        if (pthread_cond_init(&w->wake, NULL) != 0)
            break;
        if (pthread_create(&w->id, NULL, worker_run, w) != 0) {
            pthread_cond_destroy(&w->wake);
            break;
        }
        pool->started++;
    }
    return pool->started;
}

/* Threads 1 .. pooled-1 run on the pool's workers; a share whose thread
 * cannot start runs on the caller after its own, as before the pool. Only
 * the workspace's one user thread reaches here (softrast.h), so `started`
 * is the caller's alone. */
void sr_parallel_run(sr_pool *pool, int threads, void (*fn)(void *ctx, int t), void *ctx, sr_phase_time *time)
{
    double start = time ? sr_now_ms() : 0.0;
    int pooled = threads > 1 ? pool_grow(pool, threads) : 1;
    if (pooled > threads)
        pooled = threads;
    if (pooled > 1) {
        pthread_mutex_lock(&pool->lock);
        pool->fn = fn;
        pool->ctx = ctx;
        pool->timed = time != NULL;
        pool->pending = pooled - 1;
        for (int t = 1; t < pooled; t++)
            pool->workers[t].has_work = true;
        pthread_mutex_unlock(&pool->lock);
        for (int t = 1; t < pooled; t++)
            pthread_cond_signal(&pool->workers[t].wake);
    }
    double cpu_ms = timed_call(fn, ctx, 0, time != NULL);
    for (int t = pooled; t < threads; t++)
        cpu_ms += timed_call(fn, ctx, t, time != NULL);
    if (pooled > 1) {
        pthread_mutex_lock(&pool->lock);
        while (pool->pending > 0)
            pthread_cond_wait(&pool->done, &pool->lock);
        for (int t = 1; t < pooled; t++)
            cpu_ms += pool->workers[t].cpu_ms;
        pthread_mutex_unlock(&pool->lock);
    }
    if (!time)
        return;
    time->wall += sr_now_ms() - start;
    time->cpu += cpu_ms;
}

void sr_pool_stop(sr_pool *pool)
{
    if (!pool->ready)
        return;
    pthread_mutex_lock(&pool->lock);
    pool->stopping = true;
    pthread_mutex_unlock(&pool->lock);
    for (int t = 1; t < pool->started; t++)
        pthread_cond_signal(&pool->workers[t].wake);
    for (int t = 1; t < pool->started; t++) {
        pthread_join(pool->workers[t].id, NULL);
        pthread_cond_destroy(&pool->workers[t].wake);
    }
    pthread_cond_destroy(&pool->done);
    pthread_mutex_destroy(&pool->lock);
    *pool = (sr_pool){ 0 };
}
