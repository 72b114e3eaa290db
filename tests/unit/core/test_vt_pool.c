/* lib/core/vt_pool: every job runs exactly once whatever the thread count, results written by job
 * number do not depend on it, on_progress runs on the calling thread, a non-zero on_progress
 * cancels (and no job is handed out afterwards), and the failure of the lowest-numbered failing
 * job reaches the caller. Waits are for conditions (a flag, another thread blocked in the pool),
 * never for a fixed time, so a loaded machine only makes the test slower. */
#define _GNU_SOURCE /* syscall(SYS_gettid) in vt_test_threads.h */
#include <pthread.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "unit/vt_test_threads.h"
#include "vt_error.h"
#include "vt_pool.h"
#include "vt_test.h"

#define MAX_THREADS 256
#define SCRATCH     64

static const unsigned thread_counts[] = {1, 2, 8};

struct jobs {
    uint64_t count;  /* jobs to hand out */
    uint64_t next;   /* next job number: next_job runs under the pool's lock */
    uint64_t handed; /* jobs handed out */
    unsigned threads;
    atomic_uint *runs;            /* per job: how many times do_job ran it */
    uint64_t *results;            /* per job, written by do_job at its index */
    atomic_int busy[MAX_THREADS]; /* per worker: inside do_job */
    atomic_int worker_errors;     /* worker numbers out of range, or one worker in two jobs */
    unsigned char scratch[MAX_THREADS][SCRATCH];
    /* progress */
    pthread_t caller;
    pid_t caller_tid;
    atomic_int progress_calls, progress_off_thread;
    /* cancel and failure cases */
    atomic_int started, finished;
    atomic_int cancelled;         /* on_progress decided to cancel */
    uint64_t handed_after_cancel; /* jobs handed out once the cancel was decided */
    atomic_int deadline_missed;
    atomic_int fail_worker_tid; /* the thread that ran the failing job 7, once it failed */
    atomic_int job_after_own_failure;
};

static uint64_t mix(uint64_t z)
{
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

static bool next_job(void *ctx, uint64_t *job)
{
    struct jobs *j = ctx;
    if (j->next >= j->count)
        return false;
    *job = j->next++;
    j->handed++;
    if (atomic_load(&j->cancelled))
        j->handed_after_cancel++;
    return true;
}

/* Marks the worker busy (a worker never runs two jobs at once), checks its number. */
static void enter(struct jobs *j, unsigned worker)
{
    if (worker >= j->threads || atomic_exchange(&j->busy[worker], 1) != 0)
        atomic_fetch_add(&j->worker_errors, 1);
}

static void leave(struct jobs *j, unsigned worker)
{
    if (worker < j->threads)
        atomic_store(&j->busy[worker], 0);
}

/* Result of a job: a hash computed through the worker's own scratch buffer. */
static uint64_t compute(struct jobs *j, unsigned worker, uint64_t job)
{
    unsigned char *s = j->scratch[worker < MAX_THREADS ? worker : 0];
    for (unsigned i = 0; i < SCRATCH; i++)
        s[i] = (unsigned char)mix(job * SCRATCH + i);
    uint64_t h = 1469598103934665603ull;
    for (unsigned i = 0; i < SCRATCH; i++)
        h = (h ^ s[i]) * 1099511628211ull;
    return h;
}

static int plain_job(void *ctx, unsigned worker, uint64_t job, struct vts_error *err)
{
    (void)err;
    struct jobs *j = ctx;
    enter(j, worker);
    atomic_fetch_add(&j->runs[job], 1);
    j->results[job] = compute(j, worker, job);
    leave(j, worker);
    return 0;
}

static void jobs_init(struct jobs *j, uint64_t count, unsigned threads)
{
    memset(j, 0, sizeof *j);
    j->count = count;
    j->threads = threads;
    j->runs = calloc(count ? count : 1, sizeof *j->runs);
    j->results = calloc(count ? count : 1, sizeof *j->results);
    j->caller = pthread_self();
    j->caller_tid = vt_test_tid();
}

static void jobs_free(struct jobs *j)
{
    free(j->runs);
    free(j->results);
}

/* Index of the first job that did not run exactly once, or -1. */
static long first_job_not_run_once(const atomic_uint *runs, uint64_t n)
{
    for (uint64_t i = 0; i < n; i++)
        if (atomic_load(&runs[i]) != 1)
            return (long)i;
    return -1;
}

static bool same_results(const uint64_t *a, const uint64_t *b, uint64_t n)
{
    return n == 0 || memcmp(a, b, n * sizeof *a) == 0;
}

static void the_checks_catch_wrong_values(void)
{
    atomic_uint runs[4];
    for (int i = 0; i < 4; i++)
        atomic_init(&runs[i], 1);
    VT_CHECK_INT_EQ(first_job_not_run_once(runs, 4), -1);
    atomic_store(&runs[2], 2); /* a job run twice */
    VT_CHECK_INT_EQ(first_job_not_run_once(runs, 4), 2);
    atomic_store(&runs[2], 1);
    atomic_store(&runs[3], 0); /* a job never run */
    VT_CHECK_INT_EQ(first_job_not_run_once(runs, 4), 3);
    uint64_t a[3] = {1, 2, 3}, b[3] = {1, 2, 3};
    VT_CHECK(same_results(a, b, 3));
    b[1] ^= 1; /* one result off by one bit */
    VT_CHECK(!same_results(a, b, 3));
}

static void every_job_runs_exactly_once_for_1_2_and_8_threads(void)
{
    static const uint64_t job_counts[] = {0, 1, 5000};
    for (size_t t = 0; t < sizeof thread_counts / sizeof thread_counts[0]; t++)
        for (size_t k = 0; k < sizeof job_counts / sizeof job_counts[0]; k++) {
            struct jobs *j = malloc(sizeof *j);
            jobs_init(j, job_counts[k], thread_counts[t]);
            struct vt_pool_fns fns = {next_job, plain_job, NULL};
            struct vts_error err = {0};
            VT_CHECK_INT_EQ(vt_pool_run(thread_counts[t], &fns, j, &err), 0);
            VT_CHECK_INT_EQ(j->handed, job_counts[k]);
            VT_CHECK_INT_EQ(first_job_not_run_once(j->runs, job_counts[k]), -1);
            VT_CHECK_INT_EQ(atomic_load(&j->worker_errors), 0);
            if (j->handed != job_counts[k] || first_job_not_run_once(j->runs, job_counts[k]) >= 0)
                fprintf(stderr, "  %u threads, %llu jobs\n", thread_counts[t],
                        (unsigned long long)job_counts[k]);
            jobs_free(j);
            free(j);
        }
}

static void results_in_job_order_do_not_depend_on_the_thread_count(void)
{
    const uint64_t n = 20000;
    uint64_t *first = NULL;
    for (size_t t = 0; t < sizeof thread_counts / sizeof thread_counts[0]; t++) {
        struct jobs *j = malloc(sizeof *j);
        jobs_init(j, n, thread_counts[t]);
        struct vt_pool_fns fns = {next_job, plain_job, NULL};
        VT_CHECK_INT_EQ(vt_pool_run(thread_counts[t], &fns, j, NULL), 0);
        if (!first) {
            first = j->results;
            j->results = NULL;
            /* the single-threaded run against the formula itself */
            bool formula = true;
            for (uint64_t i = 0; i < n && formula; i++)
                formula = first[i] == compute(j, 0, i);
            VT_CHECK(formula);
        } else {
            VT_CHECK(same_results(first, j->results, n));
        }
        jobs_free(j);
        free(j);
    }
    free(first);
}

static void the_thread_count_must_be_1_to_256(void)
{
    struct jobs *j = malloc(sizeof *j);
    jobs_init(j, 10, 1);
    struct vt_pool_fns fns = {next_job, plain_job, NULL};
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(vt_pool_run(0, &fns, j, &err), VTS_ERR_ARG);
    VT_CHECK_STR_CONTAINS(err.message, "thread count 0");
    VT_CHECK_INT_EQ(vt_pool_run(257, &fns, j, &err), VTS_ERR_ARG);
    VT_CHECK_STR_CONTAINS(err.message, "257");
    VT_CHECK_INT_EQ(j->handed, 0); /* refused before any job */
    jobs_free(j);
    jobs_init(j, 1000, 256);
    VT_CHECK_INT_EQ(vt_pool_run(256, &fns, j, &err), 0);
    VT_CHECK_INT_EQ(first_job_not_run_once(j->runs, 1000), -1);
    VT_CHECK_INT_EQ(atomic_load(&j->worker_errors), 0);
    jobs_free(j);
    free(j);
}

static int count_progress(void *ctx)
{
    struct jobs *j = ctx;
    if (!pthread_equal(pthread_self(), j->caller))
        atomic_fetch_add(&j->progress_off_thread, 1);
    atomic_fetch_add(&j->progress_calls, 1);
    return 0;
}

/* Job 0 waits until on_progress has run while the workers are busy (the pool calls it about five
 * times a second), so the check sees calls during the run, not only the final one. */
static int job_waiting_for_progress(void *ctx, unsigned worker, uint64_t job, struct vts_error *err)
{
    struct jobs *j = ctx;
    if (job == 0) {
        double until = vt_test_now() + VT_TEST_DEADLINE_S;
        while (atomic_load(&j->progress_calls) == 0 && vt_test_now() < until)
            vt_test_sleep_ms(1);
        if (atomic_load(&j->progress_calls) == 0)
            atomic_store(&j->deadline_missed, 1);
    }
    return plain_job(ctx, worker, job, err);
}

static void on_progress_runs_on_the_calling_thread(void)
{
    for (size_t t = 0; t < sizeof thread_counts / sizeof thread_counts[0]; t++) {
        struct jobs *j = malloc(sizeof *j);
        jobs_init(j, 200, thread_counts[t]);
        struct vt_pool_fns fns = {next_job, job_waiting_for_progress, count_progress};
        VT_CHECK_INT_EQ(vt_pool_run(thread_counts[t], &fns, j, NULL), 0);
        VT_CHECK_INT_EQ(atomic_load(&j->deadline_missed), 0);
        VT_CHECK(atomic_load(&j->progress_calls) >= 2); /* during the run, and once at the end */
        VT_CHECK_INT_EQ(atomic_load(&j->progress_off_thread), 0);
        VT_CHECK_INT_EQ(first_job_not_run_once(j->runs, 200), -1);
        jobs_free(j);
        /* no job at all: still the final call */
        jobs_init(j, 0, thread_counts[t]);
        fns.do_job = plain_job;
        VT_CHECK_INT_EQ(vt_pool_run(thread_counts[t], &fns, j, NULL), 0);
        VT_CHECK(atomic_load(&j->progress_calls) >= 1);
        VT_CHECK_INT_EQ(atomic_load(&j->progress_off_thread), 0);
        jobs_free(j);
        free(j);
    }
}

/* Cancels once every worker is inside a job, so that the jobs handed out are exactly one per
 * worker and none can be handed out between the decision and the pool's stop. */
static int cancel_when_all_busy(void *ctx)
{
    struct jobs *j = ctx;
    count_progress(ctx);
    uint64_t busy = j->count < j->threads ? j->count : j->threads;
    if ((uint64_t)atomic_load(&j->started) < busy)
        return 0;
    atomic_store(&j->cancelled, 1);
    return 1;
}

/* Blocks until the cancel is decided and the calling thread is asleep again in the pool (it has
 * then taken the pool's lock and marked the run stopped), then finishes. */
static int job_held_until_cancelled(void *ctx, unsigned worker, uint64_t job, struct vts_error *err)
{
    struct jobs *j = ctx;
    atomic_fetch_add(&j->started, 1);
    double until = vt_test_now() + VT_TEST_DEADLINE_S;
    while (!(atomic_load(&j->cancelled) && vt_test_thread_sleeping(j->caller_tid)) &&
           vt_test_now() < until)
        vt_test_sleep_ms(1);
    if (vt_test_now() >= until)
        atomic_store(&j->deadline_missed, 1);
    int rc = plain_job(ctx, worker, job, err);
    atomic_fetch_add(&j->finished, 1);
    return rc;
}

static void a_progress_callback_returning_non_zero_cancels(void)
{
    for (size_t t = 0; t < sizeof thread_counts / sizeof thread_counts[0]; t++) {
        unsigned threads = thread_counts[t];
        struct jobs *j = malloc(sizeof *j);
        jobs_init(j, 1000, threads);
        struct vt_pool_fns fns = {next_job, job_held_until_cancelled, cancel_when_all_busy};
        struct vts_error err = {0};
        VT_CHECK_INT_EQ(vt_pool_run(threads, &fns, j, &err), VTS_ERR_CANCELLED);
        VT_CHECK_INT_EQ(err.status, VTS_ERR_CANCELLED);
        VT_CHECK_STR_CONTAINS(err.message, "cancelled");
        VT_CHECK_INT_EQ(atomic_load(&j->deadline_missed), 0);
        VT_CHECK_INT_EQ(j->handed, threads);                 /* the jobs in flight, nothing more */
        VT_CHECK_INT_EQ(j->handed_after_cancel, 0);          /* no job starts after the cancel */
        VT_CHECK_INT_EQ(atomic_load(&j->finished), threads); /* jobs in flight complete */
        VT_CHECK_INT_EQ(atomic_load(&j->progress_off_thread), 0);
        jobs_free(j);
        free(j);
    }
}

static bool thread_has_exited(pid_t tid)
{
    char s = vt_test_thread_state(tid);
    return s == '?' || s == 'X' || s == 'Z';
}

/* Jobs handed out after job 7 wait until job 7 failed and its worker left the pool (it records
 * the failure and sees the stop before it exits); job 3 (with fail3) fails only then, so the
 * pool has already recorded job 7's failure and must replace it by job 3's, the lower one. */
static int failing_jobs(struct jobs *j, unsigned worker, uint64_t job, struct vts_error *err,
                        bool fail3)
{
    atomic_fetch_add(&j->started, 1);
    if (job == 7) {
        plain_job(j, worker, job, err);
        atomic_store(&j->fail_worker_tid, (int)vt_test_tid());
        return vt_error_set(err, VTS_ERR_IO, "job 7: cannot write 'x.vts': disk full");
    }
    if (job > 7 || (fail3 && job == 3)) {
        double until = vt_test_now() + VT_TEST_DEADLINE_S;
        pid_t tid;
        while (!((tid = (pid_t)atomic_load(&j->fail_worker_tid)) != 0 && thread_has_exited(tid)) &&
               vt_test_now() < until) {
            if (tid == vt_test_tid()) { /* this worker got a job after its own job failed */
                atomic_fetch_add(&j->job_after_own_failure, 1);
                break;
            }
            vt_test_sleep_ms(1);
        }
        if (vt_test_now() >= until)
            atomic_store(&j->deadline_missed, 1);
    }
    plain_job(j, worker, job, err);
    if (fail3 && job == 3)
        return vt_error_set(err, VTS_ERR_RANGE, "job 3: tile 9,9 is outside the level");
    return 0;
}

static int job_7_fails(void *ctx, unsigned worker, uint64_t job, struct vts_error *err)
{
    return failing_jobs(ctx, worker, job, err, false);
}

static int jobs_3_and_7_fail(void *ctx, unsigned worker, uint64_t job, struct vts_error *err)
{
    return failing_jobs(ctx, worker, job, err, true);
}

static void a_failing_job_stops_the_pool_and_its_error_reaches_the_caller(void)
{
    for (size_t t = 0; t < sizeof thread_counts / sizeof thread_counts[0]; t++) {
        unsigned threads = thread_counts[t];
        struct jobs *j = malloc(sizeof *j);
        jobs_init(j, 1000, threads);
        struct vt_pool_fns fns = {next_job, job_7_fails, NULL};
        struct vts_error err = {0};
        VT_CHECK_INT_EQ(vt_pool_run(threads, &fns, j, &err), VTS_ERR_IO);
        VT_CHECK_INT_EQ(err.status, VTS_ERR_IO);
        VT_CHECK_STR_CONTAINS(err.message, "job 7: cannot write 'x.vts': disk full");
        VT_CHECK_INT_EQ(atomic_load(&j->deadline_missed), 0);
        /* jobs 0..7 and at most one more per other worker (held until the failure is recorded) */
        VT_CHECK(j->handed >= 8 && j->handed <= 7 + (uint64_t)threads);
        VT_CHECK_INT_EQ(atomic_load(&j->started), j->handed); /* no job was skipped */
        VT_CHECK_INT_EQ(atomic_load(&j->job_after_own_failure), 0);
        jobs_free(j);
        free(j);
    }
}

static void the_lowest_failing_job_wins(void)
{
    static const unsigned counts[] = {2, 8}; /* job 3 waits for job 7: needs a second worker */
    for (size_t t = 0; t < sizeof counts / sizeof counts[0]; t++) {
        struct jobs *j = malloc(sizeof *j);
        jobs_init(j, 1000, counts[t]);
        struct vt_pool_fns fns = {next_job, jobs_3_and_7_fail, NULL};
        struct vts_error err = {0};
        VT_CHECK_INT_EQ(vt_pool_run(counts[t], &fns, j, &err), VTS_ERR_RANGE);
        VT_CHECK_INT_EQ(err.status, VTS_ERR_RANGE);
        VT_CHECK_STR_CONTAINS(err.message, "job 3: tile 9,9 is outside the level");
        VT_CHECK_INT_EQ(atomic_load(&j->deadline_missed), 0);
        jobs_free(j);
        free(j);
    }
}

static void the_cpu_count_is_at_least_one(void)
{
    unsigned n = vt_pool_cpu_count();
    VT_CHECK(n >= 1 && n <= 256);
}

int main(void)
{
    VT_RUN(the_checks_catch_wrong_values);
    VT_RUN(every_job_runs_exactly_once_for_1_2_and_8_threads);
    VT_RUN(results_in_job_order_do_not_depend_on_the_thread_count);
    VT_RUN(the_thread_count_must_be_1_to_256);
    VT_RUN(on_progress_runs_on_the_calling_thread);
    VT_RUN(a_progress_callback_returning_non_zero_cancels);
    VT_RUN(a_failing_job_stops_the_pool_and_its_error_reaches_the_caller);
    VT_RUN(the_lowest_failing_job_wins);
    VT_RUN(the_cpu_count_is_at_least_one);
    return vt_test_main_result();
}
