/* The reader never allocates much more than the file it opens: a tiny hostile file must not make
 * it ask for hundreds of megabytes (memory amplification, and allocation failures in a process
 * that opens many stores). Linked with -Wl,--wrap=malloc,--wrap=calloc,--wrap=realloc
 * (tests/robust/CMakeLists.txt), so every allocation of the reader is seen here; the largest single
 * request while opening must stay below the file size plus a small constant. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "internal/vts_format.h"
#include "robust/vts_fixture.h"
#include "vt_test.h"
#include "vts.h"

void *__real_malloc(size_t n);
void *__real_calloc(size_t n, size_t size);
void *__real_realloc(void *p, size_t n);
void *__wrap_malloc(size_t n);
void *__wrap_calloc(size_t n, size_t size);
void *__wrap_realloc(void *p, size_t n);

static size_t largest; /* largest request since the last reset */

static void note(size_t n)
{
    if (n > largest)
        largest = n;
}

void *__wrap_malloc(size_t n)
{
    note(n);
    return __real_malloc(n);
}

void *__wrap_calloc(size_t n, size_t size)
{
    note(n * size); /* a product that overflows is refused by calloc anyway */
    return __real_calloc(n, size);
}

void *__wrap_realloc(void *p, size_t n)
{
    note(n);
    return __real_realloc(p, n);
}

/* The store object itself (names, levels) is a few KiB whatever the file. */
#define SLACK 8192u

static char tmpdir[256];

/* Opens an image from memory; returns the largest allocation made by the open. */
static size_t largest_while_opening(const unsigned char *data, size_t size, int *status)
{
    struct vts_error err = {0};
    largest = 0;
    struct vts_store *s = vts_open_memory(data, size, "alloc", &err);
    size_t seen = largest;
    *status = s ? 0 : err.status;
    vts_close(s);
    return seen;
}

/* A store whose index entries are 4096 bytes apart (legal: a later minor version may widen them):
 * a 64 KiB index of 16 entries. Before the fix the reader read it through a 256 MiB buffer. */
static void wide_index_entries_do_not_inflate_the_index_buffer(void)
{
    size_t size;
    unsigned char *base = vts_fixture_bytes(tmpdir, VTS_FIXTURE_SMALL, &size);
    VT_CHECK(base != NULL);
    if (!base)
        return;
    uint64_t n = vts_load_u64(base + VTS_H_INDEX_COUNT),
             index_off = vts_load_u64(base + VTS_H_INDEX_OFFSET);
    for (uint32_t stride = 16; stride <= 4096; stride *= 4) {
        size_t total = size + n * stride;
        unsigned char *im = calloc(1, total);
        memcpy(im, base, size);
        for (uint64_t i = 0; i < n; i++)
            memcpy(im + size + i * stride, base + index_off + i * VTS_INDEX_ENTRY_SIZE,
                   VTS_INDEX_ENTRY_SIZE);
        vts_store_u64(im + VTS_H_INDEX_OFFSET, size);
        vts_store_u32(im + VTS_H_INDEX_ENTRY, stride);
        vts_reseal_all(im, total);
        int status;
        size_t seen = largest_while_opening(im, total, &status);
        VT_CHECK_INT_EQ(status, 0);
        VT_CHECK(seen <= total + SLACK);
        fprintf(stderr, "     stride %4u: file %zu bytes, largest allocation %zu\n", stride, total,
                seen);
        free(im);
    }
    free(base);
}

/* Every fixture and a few thousand re-sealed mutants of header fields. */
static void no_open_allocates_more_than_the_file(void)
{
    static const unsigned fields[] = {VTS_H_WIDTH,        VTS_H_HEIGHT,      VTS_H_CONTENT,
                                      VTS_H_LEVELS,       VTS_H_LAYERS,      VTS_H_LAYER_ENTRY,
                                      VTS_H_INDEX_ENTRY,  VTS_H_META_SIZE,   VTS_H_INDEX_COUNT,
                                      VTS_H_LAYER_OFFSET, VTS_H_INDEX_OFFSET};
    static const uint32_t values[] = {0,    1,    2,     16,         47,         48,
                                      4095, 4096, 65536, 0x7fffffff, 0xffffffff, 16 << 20};
    size_t worst = 0;
    int opened = 0, tried = 0;
    for (int which = 0; which < VTS_FIXTURE_COUNT; which++) {
        size_t size;
        unsigned char *base = vts_fixture_bytes(tmpdir, (enum vts_fixture)which, &size);
        VT_CHECK(base != NULL);
        if (!base)
            continue;
        for (size_t f = 0; f < sizeof fields / sizeof *fields; f++)
            for (size_t v = 0; v < sizeof values / sizeof *values; v++) {
                unsigned char *im = malloc(size);
                memcpy(im, base, size);
                vts_store_u32(im + fields[f], values[v]);
                vts_reseal_all(im, size);
                int status;
                size_t seen = largest_while_opening(im, size, &status);
                opened += status == 0;
                tried++;
                VT_CHECK(seen <= size + SLACK);
                if (seen > worst)
                    worst = seen;
                free(im);
            }
        free(base);
    }
    fprintf(stderr, "     %d variants (%d opened): largest allocation %zu bytes\n", tried, opened,
            worst);
}

int main(void)
{
    if (!vts_fixture_mkdtemp(tmpdir, sizeof tmpdir, "test_vts_open_alloc"))
        return 1;
    VT_RUN(wide_index_entries_do_not_inflate_the_index_buffer);
    VT_RUN(no_open_allocates_more_than_the_file);
    vts_fixture_rmdir_all(tmpdir);
    return vt_test_main_result();
}
