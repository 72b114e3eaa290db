/* A minimal test harness: checks report file:line and keep going; vt_test_main() sums up and sets
 * the exit status. Each test file defines test functions and calls them from main via VT_RUN. */
#ifndef VT_TEST_H
#define VT_TEST_H

#include <inttypes.h>
#include <stdatomic.h>
#include <stdio.h>
#include <string.h>

/* Atomic: checks may run on worker threads (e.g. readers tested from several threads). */
static _Atomic int vt_test_failures;
static _Atomic int vt_test_checks;

#define VT_CHECK(cond)                                                                             \
    do {                                                                                           \
        vt_test_checks++;                                                                          \
        if (!(cond)) {                                                                             \
            vt_test_failures++;                                                                    \
            fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__, #cond);               \
        }                                                                                          \
    } while (0)

#define VT_CHECK_INT_EQ(a, b)                                                                      \
    do {                                                                                           \
        long long vt_a_ = (long long)(a), vt_b_ = (long long)(b);                                  \
        vt_test_checks++;                                                                          \
        if (vt_a_ != vt_b_) {                                                                      \
            vt_test_failures++;                                                                    \
            fprintf(stderr, "%s:%d: %s == %s failed: %lld != %lld\n", __FILE__, __LINE__, #a, #b,  \
                    vt_a_, vt_b_);                                                                 \
        }                                                                                          \
    } while (0)

/* Strings equal; a NULL actual value fails. */
#define VT_CHECK_STR_EQ(a, b)                                                                      \
    do {                                                                                           \
        const char *vt_a_ = (a), *vt_b_ = (b);                                                     \
        vt_test_checks++;                                                                          \
        if (!vt_a_ || strcmp(vt_a_, vt_b_) != 0) {                                                 \
            vt_test_failures++;                                                                    \
            fprintf(stderr, "%s:%d: %s is '%s', not '%s'\n", __FILE__, __LINE__, #a,               \
                    vt_a_ ? vt_a_ : "(null)", vt_b_);                                              \
        }                                                                                          \
    } while (0)

#define VT_CHECK_STR_CONTAINS(haystack, needle)                                                    \
    do {                                                                                           \
        const char *vt_h_ = (haystack), *vt_n_ = (needle);                                         \
        vt_test_checks++;                                                                          \
        if (!vt_h_ || !strstr(vt_h_, vt_n_)) {                                                     \
            vt_test_failures++;                                                                    \
            fprintf(stderr, "%s:%d: '%s' does not contain '%s'\n", __FILE__, __LINE__,             \
                    vt_h_ ? vt_h_ : "(null)", vt_n_);                                              \
        }                                                                                          \
    } while (0)

#define VT_RUN(test_fn)                                                                            \
    do {                                                                                           \
        int vt_before_ = vt_test_failures;                                                         \
        test_fn();                                                                                 \
        fprintf(stderr, "%s %s\n", vt_test_failures == vt_before_ ? "ok  " : "FAIL", #test_fn);    \
    } while (0)

static inline int vt_test_main_result(void)
{
    fprintf(stderr, "%d checks, %d failed\n", atomic_load(&vt_test_checks),
            atomic_load(&vt_test_failures));
    return vt_test_failures ? 1 : 0;
}

#endif
