#include <pthread.h>

#include "core/clock.h"
#include "draw_state.h"

void sr_chunks_init(sr_chunks *c, uint32_t count, uint32_t size)
{
    atomic_init(&c->next, 0);
    c->count = count;
    c->size = size;
}

/* A 64-bit counter: each thread takes one past the last chunk at most
 * once, so it cannot wrap. */
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

/* How long a waiting thread polls before it sleeps: the phases of a frame
 * follow each other sooner than a sleeper wakes, and an idle viewer's
 * threads should not spin. */
#define SPIN_MS 0.05

/* Polls f(arg) for up to SPIN_MS: true once it holds, false when time ran out. */
static bool spin_until(bool (*f)(void *arg), void *arg)
{
    double deadline = sr_now_ms() + SPIN_MS;
    while (!f(arg))
        if (sr_now_ms() > deadline)
            return false;
    return true;
}

static bool worker_handed_phase(void *arg)
{
    sr_worker *w = arg;
    return atomic_load_explicit(&w->go, memory_order_acquire) != w->seen;
}

static bool phase_done(void *arg)
{
    sr_pool *pool = arg;
    return atomic_load_explicit(&pool->pending, memory_order_acquire) == 0;
}

/* Waits for the next phase; false when the pool stops instead. A worker
 * sleeps under the lock only after checking go under it, and the caller
 * moves go on before it takes the lock to wake sleepers, so no wakeup is
 * lost; the loop around the wait absorbs spurious ones. */
static bool worker_wait(sr_worker *w)
{
    if (spin_until(worker_handed_phase, w))
        return true;
    sr_pool *pool = w->pool;
    pthread_mutex_lock(&pool->lock);
    while (!worker_handed_phase(w) && !pool->stopping) {
        w->sleeping = true;
        pthread_cond_wait(&w->wake, &pool->lock);
        w->sleeping = false;
    }
    bool handed = worker_handed_phase(w); /* stopping is never set while a phase runs */
    pthread_mutex_unlock(&pool->lock);
    return handed;
}

/* The phase's fn and ctx are written before go moves on (release) and read
 * after go is seen (acquire); a worker's writes come before its decrement
 * of pending, which the caller reads (acquire) before it goes on. */
static void *worker_run(void *arg)
{
    sr_worker *w = arg;
    sr_pool *pool = w->pool;
    while (worker_wait(w)) {
        w->seen = atomic_load_explicit(&w->go, memory_order_relaxed);
        w->cpu_ms = timed_call(pool->fn, pool->ctx, w->t, pool->timed);
        if (atomic_fetch_sub_explicit(&pool->pending, 1, memory_order_acq_rel) == 1) {
            pthread_mutex_lock(&pool->lock);
            if (pool->caller_sleeping)
                pthread_cond_signal(&pool->done);
            pthread_mutex_unlock(&pool->lock);
        }
    }
    return NULL;
}

static bool pool_ready(sr_pool *pool)
{
    if (pool->started > 0)
        return true;
    if (pthread_mutex_init(&pool->lock, NULL) != 0)
        return false;
    if (pthread_cond_init(&pool->done, NULL) != 0) {
        pthread_mutex_destroy(&pool->lock);
        return false;
    }
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
        *w = (sr_worker){ .pool = pool, .t = pool->started, .seen = pool->phase };
        atomic_init(&w->go, pool->phase);
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

static void pool_hand_out(sr_pool *pool, int pooled, void (*fn)(void *ctx, int t), void *ctx, bool timed)
{
    pool->fn = fn;
    pool->ctx = ctx;
    pool->timed = timed;
    pool->phase++;
    atomic_store_explicit(&pool->pending, pooled - 1, memory_order_relaxed);
    for (int t = 1; t < pooled; t++)
        atomic_store_explicit(&pool->workers[t].go, pool->phase, memory_order_release);
    pthread_mutex_lock(&pool->lock);
    for (int t = 1; t < pooled; t++)
        if (pool->workers[t].sleeping)
            pthread_cond_signal(&pool->workers[t].wake);
    pthread_mutex_unlock(&pool->lock);
}

static void pool_wait(sr_pool *pool)
{
    if (spin_until(phase_done, pool))
        return;
    pthread_mutex_lock(&pool->lock);
    while (!phase_done(pool)) {
        pool->caller_sleeping = true;
        pthread_cond_wait(&pool->done, &pool->lock);
        pool->caller_sleeping = false;
    }
    pthread_mutex_unlock(&pool->lock);
}

/* Threads 1 .. pooled-1 run on the pool's workers; a share whose thread
 * cannot start runs on the caller after its own, as before the pool. Only
 * the workspace's one user thread reaches here (softrast.h), so the fields
 * marked the caller's need no lock. */
void sr_parallel_run(sr_pool *pool, int threads, void (*fn)(void *ctx, int t), void *ctx, sr_phase_time *time)
{
    double start = time ? sr_now_ms() : 0.0;
    int pooled = threads > 1 ? pool_grow(pool, threads) : 1;
    if (pooled > threads)
        pooled = threads;
    if (pooled > 1)
        pool_hand_out(pool, pooled, fn, ctx, time != NULL);
    double cpu_ms = timed_call(fn, ctx, 0, time != NULL);
    for (int t = pooled; t < threads; t++)
        cpu_ms += timed_call(fn, ctx, t, time != NULL);
    if (pooled > 1)
        pool_wait(pool);
    for (int t = 1; t < pooled; t++)
        cpu_ms += pool->workers[t].cpu_ms;
    if (!time)
        return;
    time->wall += sr_now_ms() - start;
    time->cpu += cpu_ms;
}

void sr_pool_stop(sr_pool *pool)
{
    if (pool->started == 0)
        return;
    pthread_mutex_lock(&pool->lock);
    pool->stopping = true;
    for (int t = 1; t < pool->started; t++)
        pthread_cond_signal(&pool->workers[t].wake);
    pthread_mutex_unlock(&pool->lock);
    for (int t = 1; t < pool->started; t++) {
        pthread_join(pool->workers[t].id, NULL);
        pthread_cond_destroy(&pool->workers[t].wake);
    }
    pthread_cond_destroy(&pool->done);
    pthread_mutex_destroy(&pool->lock);
    *pool = (sr_pool){ 0 };
}
