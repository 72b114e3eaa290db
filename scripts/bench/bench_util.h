/* Shared by the benchmark programs (each includes its own copy): fatal errors named after the
 * program (set bench_name first), allocation that cannot fail, a tight 8-bit RGB image, and
 * mirrored indices for sampling windows at image edges. */
#ifndef BENCH_UTIL_H
#define BENCH_UTIL_H

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "vt_error.h"

static const char *bench_name = "vt-bench";

static inline void die(const char *what, const struct vts_error *err)
{
    fprintf(stderr, "%s: %s: %s\n", bench_name, what, err ? err->message : "failed");
    exit(1);
}

static inline void *xmalloc(size_t n)
{
    void *p = malloc(n ? n : 1);
    if (!p) {
        fprintf(stderr, "%s: out of memory\n", bench_name);
        exit(1);
    }
    return p;
}

/* Tight 8-bit RGB image. */
struct rgb {
    uint32_t w, h;
    uint8_t *px;
};

/* Mirror index into [0, n) without repeating the edge texel (n >= 2). */
static inline uint32_t mirror(int64_t i, uint32_t n)
{
    int64_t period = 2 * (int64_t)n - 2;
    i %= period;
    if (i < 0)
        i += period;
    return (uint32_t)(i < n ? i : period - i);
}

#endif
