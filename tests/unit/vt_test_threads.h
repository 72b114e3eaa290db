/* Helpers for unit tests of threaded code: waiting for a condition (never for a fixed time) and
 * telling whether another thread of this process is blocked (Linux: its state in
 * /proc/self/task/TID/stat is 'S'). A test that must know "the other threads are now waiting
 * inside the code under test" polls vt_test_thread_sleeping() instead of sleeping and hoping.
 * Include after defining _GNU_SOURCE (for syscall(SYS_gettid)). */
#ifndef VT_TEST_THREADS_H
#define VT_TEST_THREADS_H

#include <errno.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>
#include <sys/syscall.h>
#include <sys/types.h>
#include <time.h>
#include <unistd.h>

/* Generous: a condition that holds after a few microseconds on an idle machine still holds well
 * within this on one loaded by other builds (or run under ThreadSanitizer). */
#define VT_TEST_DEADLINE_S 120.0

static inline pid_t vt_test_tid(void)
{
    return (pid_t)syscall(SYS_gettid);
}

static inline double vt_test_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec / 1e9;
}

static inline void vt_test_sleep_ms(long ms)
{
    struct timespec ts = {ms / 1000, (ms % 1000) * 1000000L};
    while (nanosleep(&ts, &ts) != 0 && errno == EINTR)
        ;
}

/* The scheduler state of thread tid of this process ('R' running, 'S' sleeping in the kernel:
 * futex, nanosleep, read...), or '?' when it cannot be read. */
static inline char vt_test_thread_state(pid_t tid)
{
    char path[64], buf[512];
    snprintf(path, sizeof path, "/proc/self/task/%d/stat", (int)tid);
    FILE *f = fopen(path, "r");
    if (!f)
        return '?';
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    fclose(f);
    buf[n] = '\0';
    const char *paren = strrchr(buf, ')'); /* the name in parentheses may hold spaces */
    return paren && paren[1] == ' ' && paren[2] ? paren[2] : '?';
}

static inline bool vt_test_thread_sleeping(pid_t tid)
{
    return vt_test_thread_state(tid) == 'S';
}

#endif
