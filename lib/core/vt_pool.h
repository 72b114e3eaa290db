/* A small worker pool with three roles: next_job hands out job numbers under the pool's lock,
 * do_job runs concurrently on workers (each with its own scratch, by worker number), on_progress
 * runs on the calling thread about five times a second. */
#ifndef VT_POOL_H
#define VT_POOL_H

#include <stdbool.h>
#include <stdint.h>

#include "vt_error.h"

struct vt_pool_fns {
    /* Called under the pool's lock: stores the next job in *job and returns true, or returns
     * false when every job has been handed out. */
    bool (*next_job)(void *ctx, uint64_t *job);
    /* Runs one job on worker 0..threads-1. A negative return (with err filled) stops the pool:
     * no further job starts. */
    int (*do_job)(void *ctx, unsigned worker, uint64_t job, struct vts_error *err);
    /* Optional. Called on the calling thread while workers run (without the pool's lock, so jobs
     * may still be handed out while it runs), and once at the end. A non-zero return cancels the
     * run (VTS_ERR_CANCELLED): no job starts after it has returned. */
    int (*on_progress)(void *ctx);
};

/* Runs jobs on `threads` workers (1..256) until next_job says none are left or a job fails.
 * Returns 0, the status of the failed job with the lowest job number (its message in err), or
 * VTS_ERR_CANCELLED. */
int vt_pool_run(unsigned threads, const struct vt_pool_fns *fns, void *ctx, struct vts_error *err);

/* Number of online processors (at least 1). */
unsigned vt_pool_cpu_count(void);

#endif
