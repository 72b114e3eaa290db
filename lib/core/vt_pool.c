#include "vt_pool.h"
#include "vt_error.h"

#include <errno.h>
#include <pthread.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#define PROGRESS_INTERVAL_NS 200000000L

struct pool {
    const struct vt_pool_fns *fns;
    void *ctx;
    pthread_mutex_t lock;
    pthread_cond_t done_cond;
    unsigned running;
    bool stop;
    int status; /* of the failed job with the lowest number */
    uint64_t failed_job;
    struct vts_error error;
};

struct worker {
    struct pool *pool;
    unsigned index;
};

static void record_failure(struct pool *p, uint64_t job, int status, const struct vts_error *err)
{
    if (p->status == 0 || job < p->failed_job) {
        p->status = status;
        p->failed_job = job;
        p->error = *err;
        p->error.status = status;
    }
    p->stop = true;
}

static void *worker_main(void *arg)
{
    struct worker *w = arg;
    struct pool *p = w->pool;
    for (;;) {
        uint64_t job;
        pthread_mutex_lock(&p->lock);
        bool have = !p->stop && p->fns->next_job(p->ctx, &job);
        pthread_mutex_unlock(&p->lock);
        if (!have)
            break;
        struct vts_error err = {0};
        int rc = p->fns->do_job(p->ctx, w->index, job, &err);
        if (rc < 0) {
            pthread_mutex_lock(&p->lock);
            record_failure(p, job, rc, &err);
            pthread_mutex_unlock(&p->lock);
        }
    }
    pthread_mutex_lock(&p->lock);
    p->running--;
    pthread_cond_signal(&p->done_cond);
    pthread_mutex_unlock(&p->lock);
    return NULL;
}

static void wait_with_progress(struct pool *p)
{
    pthread_mutex_lock(&p->lock);
    while (p->running > 0) {
        struct timespec until;
        clock_gettime(CLOCK_REALTIME, &until);
        until.tv_nsec += PROGRESS_INTERVAL_NS;
        if (until.tv_nsec >= 1000000000L) {
            until.tv_sec++;
            until.tv_nsec -= 1000000000L;
        }
        int rc = pthread_cond_timedwait(&p->done_cond, &p->lock, &until);
        if (rc == ETIMEDOUT && p->fns->on_progress && !p->stop) {
            pthread_mutex_unlock(&p->lock);
            int cancel = p->fns->on_progress(p->ctx);
            pthread_mutex_lock(&p->lock);
            if (cancel && p->status == 0) {
                p->status = VTS_ERR_CANCELLED;
                vt_error_set(&p->error, VTS_ERR_CANCELLED, "cancelled");
                p->stop = true;
            }
        }
    }
    pthread_mutex_unlock(&p->lock);
}

int vt_pool_run(unsigned threads, const struct vt_pool_fns *fns, void *ctx, struct vts_error *err)
{
    if (threads < 1 || threads > 256)
        return vt_error_set(err, VTS_ERR_ARG, "thread count %u is outside 1..256", threads);
    struct pool p = {.fns = fns, .ctx = ctx};
    pthread_mutex_init(&p.lock, NULL);
    pthread_cond_init(&p.done_cond, NULL);
    pthread_t *tids = calloc(threads, sizeof *tids);
    struct worker *workers = calloc(threads, sizeof *workers);
    int rc = 0;
    if (!tids || !workers) {
        rc = vt_error_set(err, VTS_ERR_NOMEM, "out of memory starting %u threads", threads);
        goto out;
    }
    /* Workers leave SIGINT, SIGTERM and SIGHUP to the other threads (they inherit this mask): the
     * atomic-file cleanup handler then never runs in a worker while the thread creating an output
     * file has them blocked (vt_atomic_file.c). */
    sigset_t block, old_mask;
    sigemptyset(&block);
    sigaddset(&block, SIGINT);
    sigaddset(&block, SIGTERM);
    sigaddset(&block, SIGHUP);
    pthread_sigmask(SIG_BLOCK, &block, &old_mask);
    unsigned started = 0;
    for (; started < threads; started++) {
        workers[started] = (struct worker){&p, started};
        pthread_mutex_lock(&p.lock);
        p.running++;
        pthread_mutex_unlock(&p.lock);
        if (pthread_create(&tids[started], NULL, worker_main, &workers[started]) != 0) {
            pthread_mutex_lock(&p.lock);
            p.running--;
            pthread_mutex_unlock(&p.lock);
            if (started == 0)
                rc = vt_error_set(err, VTS_ERR_NOMEM, "cannot start a worker thread");
            break; /* run with the workers that did start */
        }
    }
    pthread_sigmask(SIG_SETMASK, &old_mask, NULL);
    wait_with_progress(&p);
    for (unsigned i = 0; i < started; i++)
        pthread_join(tids[i], NULL);
    if (fns->on_progress && rc == 0 && p.status == 0 && fns->on_progress(ctx))
        p.status = vt_error_set(&p.error, VTS_ERR_CANCELLED, "cancelled");
    if (rc == 0 && p.status != 0) {
        rc = p.status;
        if (err)
            *err = p.error;
    }
out:
    free(tids);
    free(workers);
    pthread_cond_destroy(&p.done_cond);
    pthread_mutex_destroy(&p.lock);
    return rc;
}

unsigned vt_pool_cpu_count(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : (n > 256 ? 256 : (unsigned)n);
}
