/* lib/pyramid's native tile cache (vt_tile_cache): regions read through it hold the source's
 * texels, a tile read twice is decoded once (a hit), the cache holds no more tiles than its byte
 * budget allows and drops tiles of the highest rows first, least recently used first within a row,
 * readers of one tile on several threads decode it once, and a failed decode is reported and
 * retried. The wrapped source counts its decodes per tile, independently of the cache's counts. */
#define _GNU_SOURCE /* syscall(SYS_gettid) in vt_test_threads.h */
#include <pthread.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "internal/vt_tile_cache.h"
#include "unit/vt_test_threads.h"
#include "vt_error.h"
#include "vt_image.h"
#include "vt_source.h"
#include "vt_test.h"

#define MAX_TILES   4096
#define MAX_READERS 8

/* One tiled image, shared by the per-thread sources that wrap it. */
struct image {
    uint32_t width, height, tile;
    atomic_int decodes[MAX_TILES]; /* region reads of the underlying source, by tile */
    atomic_int fail_next;          /* the next read of tile fail_tile fails */
    int fail_tile;
    /* gate: a decode of gate_tile waits until the other readers are blocked in the cache */
    int gate_tile;
    pid_t reader_tids[MAX_READERS];
    atomic_int reading[MAX_READERS]; /* reader i has started its read */
    atomic_int done[MAX_READERS];    /* reader i has finished it */
    unsigned readers;
    atomic_int gate_timed_out;
};

static uint8_t texel(uint32_t x, uint32_t y, uint32_t c)
{
    return (uint8_t)(x * 7 + y * 13 + c * 101 + (x >> 3) * (y >> 2));
}

static bool all_other_readers_sleeping(const struct image *im)
{
    pid_t self = vt_test_tid();
    for (unsigned i = 0; i < im->readers; i++)
        if (im->reader_tids[i] != self && !atomic_load(&im->done[i]) &&
            !(atomic_load(&im->reading[i]) && vt_test_thread_sleeping(im->reader_tids[i])))
            return false;
    return true;
}

/* The underlying source: one native tile per read (the cache reads whole tiles), 2 channels. */
static int image_read(void *ctx, uint32_t x, uint32_t y, struct vt_image *dst,
                      struct vts_error *err)
{
    struct image *im = ctx;
    int t = (int)((y / im->tile) * ((im->width + im->tile - 1) / im->tile) + x / im->tile);
    if (x % im->tile || y % im->tile || t >= MAX_TILES)
        return vt_error_set(err, VTS_ERR_ARG, "read at %u,%u is not a native tile", x, y);
    atomic_fetch_add(&im->decodes[t], 1);
    if (t == im->gate_tile) {
        double until = vt_test_now() + VT_TEST_DEADLINE_S;
        while (!all_other_readers_sleeping(im) && vt_test_now() < until)
            vt_test_sleep_ms(1);
        if (vt_test_now() >= until)
            atomic_store(&im->gate_timed_out, 1);
    }
    if (t == im->fail_tile && atomic_exchange(&im->fail_next, 0))
        return vt_error_set(err, VTS_ERR_IO, "'tiled.tif': cannot decode tile %d", t);
    for (uint32_t r = 0; r < dst->height; r++)
        for (uint32_t c = 0; c < dst->width; c++) {
            uint8_t *p = vt_image_at(dst, c, r);
            p[0] = texel(x + c, y + r, 0);
            p[1] = texel(x + c, y + r, 1);
        }
    return 0;
}

static void image_close(void *ctx)
{
    (void)ctx; /* the image belongs to the test */
}

static const struct vt_source_ops image_ops = {image_read, image_close};

static struct image *image_new(uint32_t width, uint32_t height, uint32_t tile)
{
    struct image *im = calloc(1, sizeof *im);
    im->width = width;
    im->height = height;
    im->tile = tile;
    im->fail_tile = -1;
    im->gate_tile = -1;
    return im;
}

static struct vt_source image_source(struct image *im)
{
    struct vt_source s = {{0}, &image_ops, im, "tiled.tif"};
    s.info.width = im->width;
    s.info.height = im->height;
    s.info.channels = 2;
    s.info.sample = VTS_SAMPLE_U8;
    s.info.tile_w = s.info.tile_h = im->tile;
    snprintf(s.info.format, sizeof s.info.format, "tiff");
    return s;
}

static int decodes_of(struct image *im, uint32_t tx, uint32_t ty)
{
    return atomic_load(&im->decodes[ty * ((im->width + im->tile - 1) / im->tile) + tx]);
}

static int total_decodes(struct image *im)
{
    int n = 0;
    for (int i = 0; i < MAX_TILES; i++)
        n += atomic_load(&im->decodes[i]);
    return n;
}

/* Index of the first texel of region (x, y, img) that differs from the image, or -1. */
static long first_wrong_texel(const struct vt_image *img, uint32_t x, uint32_t y)
{
    for (uint32_t r = 0; r < img->height; r++)
        for (uint32_t c = 0; c < img->width; c++) {
            const uint8_t *p = vt_image_at(img, c, r);
            if (p[0] != texel(x + c, y + r, 0) || p[1] != texel(x + c, y + r, 1))
                return (long)r * img->width + c;
        }
    return -1;
}

/* Reads region (x, y, w, h) through src; -1 on a read error, else first_wrong_texel. */
static long read_check(struct vt_source *src, uint32_t x, uint32_t y, uint32_t w, uint32_t h)
{
    struct vt_image img;
    if (vt_image_alloc(&img, w, h, 2, VTS_SAMPLE_U8, NULL) != 0)
        return -2;
    struct vts_error err = {0};
    long bad = vt_source_read(src, x, y, &img, &err) != 0 ? -3 : first_wrong_texel(&img, x, y);
    vt_image_release(&img);
    return bad;
}

static void counts(struct vt_tile_cache *c, unsigned long long *decoded, unsigned long long *hits)
{
    vt_tile_cache_counts(c, decoded, hits);
}

static void the_texel_check_catches_a_wrong_value(void)
{
    struct vt_image img;
    VT_CHECK_INT_EQ(vt_image_alloc(&img, 5, 3, 2, VTS_SAMPLE_U8, NULL), 0);
    for (uint32_t r = 0; r < 3; r++)
        for (uint32_t c = 0; c < 5; c++) {
            uint8_t *p = vt_image_at(&img, c, r);
            p[0] = texel(10 + c, 20 + r, 0);
            p[1] = texel(10 + c, 20 + r, 1);
        }
    VT_CHECK_INT_EQ(first_wrong_texel(&img, 10, 20), -1);
    VT_CHECK(first_wrong_texel(&img, 11, 20) >= 0); /* the right texels at the wrong place */
    ((uint8_t *)vt_image_at(&img, 3, 2))[1] ^= 1;   /* one sample off by one */
    VT_CHECK_INT_EQ(first_wrong_texel(&img, 10, 20), 2 * 5 + 3);
    vt_image_release(&img);
}

static void a_second_read_of_a_tile_is_a_hit(void)
{
    struct image *im = image_new(100, 70, 16); /* 7 x 5 tiles, partial ones at the edges */
    struct vt_source src = image_source(im), out;
    struct vt_source *srcs[1] = {&src};
    struct vts_error err = {0};
    struct vt_tile_cache *c = vt_tile_cache_create(srcs, 1, 1 << 20, &out, &err);
    VT_CHECK(c != NULL);
    if (!c)
        return;
    unsigned long long decoded, hits;
    VT_CHECK_INT_EQ(read_check(&out, 3, 2, 10, 10), -1); /* inside tile 0,0 */
    counts(c, &decoded, &hits);
    VT_CHECK_INT_EQ(decoded, 1);
    VT_CHECK_INT_EQ(hits, 0);
    VT_CHECK_INT_EQ(read_check(&out, 0, 0, 16, 16), -1); /* the same tile again */
    counts(c, &decoded, &hits);
    VT_CHECK_INT_EQ(decoded, 1);
    VT_CHECK_INT_EQ(hits, 1);
    VT_CHECK_INT_EQ(decodes_of(im, 0, 0), 1);
    /* a region across four tiles, one of them cached: three decodes, one hit */
    VT_CHECK_INT_EQ(read_check(&out, 8, 8, 16, 16), -1);
    counts(c, &decoded, &hits);
    VT_CHECK_INT_EQ(decoded, 4);
    VT_CHECK_INT_EQ(hits, 2);
    VT_CHECK_INT_EQ(total_decodes(im), 4);
    /* the whole image (every edge tile partial): each of the 35 tiles decoded once */
    VT_CHECK_INT_EQ(read_check(&out, 0, 0, 100, 70), -1);
    VT_CHECK_INT_EQ(total_decodes(im), 35);
    VT_CHECK_INT_EQ(decodes_of(im, 6, 4), 1);
    counts(c, &decoded, &hits);
    VT_CHECK_INT_EQ(decoded, 35);
    VT_CHECK_INT_EQ(hits, 2 + 4);
    /* the last texel alone */
    VT_CHECK_INT_EQ(read_check(&out, 99, 69, 1, 1), -1);
    VT_CHECK_INT_EQ(total_decodes(im), 35);
    vt_source_close(&out);
    vt_tile_cache_destroy(c);
    free(im);
}

/* A 16x16 tile of 2 channels is 512 bytes: a budget of 4.9 tiles holds 4 (at least 4 per reader
 * in any case). */
static void the_cache_holds_what_its_budget_allows_highest_rows_dropped_first(void)
{
    struct image *im = image_new(128, 128, 16); /* 8 x 8 tiles */
    struct vt_source src = image_source(im), out;
    struct vt_source *srcs[1] = {&src};
    struct vt_tile_cache *c = vt_tile_cache_create(srcs, 1, 4 * 512 + 500, &out, NULL);
    VT_CHECK(c != NULL);
    if (!c)
        return;
    /* row 0: tiles A B C D fill the cache; E evicts A, the least recently used */
    for (uint32_t tx = 0; tx < 5; tx++)
        VT_CHECK_INT_EQ(read_check(&out, tx * 16, 0, 16, 16), -1);
    VT_CHECK_INT_EQ(total_decodes(im), 5);
    for (uint32_t tx = 1; tx < 5; tx++) /* B..E: cached */
        VT_CHECK_INT_EQ(read_check(&out, tx * 16, 0, 16, 16), -1);
    VT_CHECK_INT_EQ(total_decodes(im), 5);
    VT_CHECK_INT_EQ(read_check(&out, 0, 0, 16, 16), -1); /* A again: decoded again, evicts B */
    VT_CHECK_INT_EQ(decodes_of(im, 0, 0), 2);
    VT_CHECK_INT_EQ(read_check(&out, 16, 0, 16, 16), -1); /* B: evicted, evicts C */
    VT_CHECK_INT_EQ(decodes_of(im, 1, 0), 2);
    /* now D E A B are cached; C is not: the cache holds 4 tiles, never 5 */
    unsigned long long decoded, hits;
    counts(c, &decoded, &hits);
    VT_CHECK_INT_EQ(decoded, 7);
    for (uint32_t tx = 3; tx < 5; tx++)
        VT_CHECK_INT_EQ(read_check(&out, tx * 16, 0, 16, 16), -1);
    VT_CHECK_INT_EQ(read_check(&out, 0, 0, 16, 16), -1);
    VT_CHECK_INT_EQ(read_check(&out, 16, 0, 16, 16), -1);
    VT_CHECK_INT_EQ(total_decodes(im), 7);
    /* rows: blocks go down, so a tile of row 1 is kept over row 0 tiles used after it */
    VT_CHECK_INT_EQ(read_check(&out, 0, 16, 16, 16), -1);     /* F (row 1) evicts D (row 0) */
    VT_CHECK_INT_EQ(read_check(&out, 4 * 16, 0, 16, 16), -1); /* E, A, B: hits, used after F */
    VT_CHECK_INT_EQ(read_check(&out, 0, 0, 16, 16), -1);
    VT_CHECK_INT_EQ(read_check(&out, 16, 0, 16, 16), -1);
    VT_CHECK_INT_EQ(total_decodes(im), 8);
    VT_CHECK_INT_EQ(read_check(&out, 16, 16, 16, 16), -1); /* G (row 1) evicts E, not F */
    VT_CHECK_INT_EQ(read_check(&out, 0, 16, 16, 16), -1);  /* F: still there */
    VT_CHECK_INT_EQ(decodes_of(im, 0, 1), 1);
    VT_CHECK_INT_EQ(total_decodes(im), 9);
    vt_source_close(&out);
    vt_tile_cache_destroy(c);
    free(im);
}

static void a_failed_decode_is_reported_and_retried(void)
{
    struct image *im = image_new(64, 64, 16);
    im->fail_tile = 5; /* tile 1,1 */
    atomic_store(&im->fail_next, 1);
    struct vt_source src = image_source(im), out;
    struct vt_source *srcs[1] = {&src};
    struct vt_tile_cache *c = vt_tile_cache_create(srcs, 1, 1 << 20, &out, NULL);
    VT_CHECK(c != NULL);
    if (!c)
        return;
    struct vt_image img;
    VT_CHECK_INT_EQ(vt_image_alloc(&img, 32, 32, 2, VTS_SAMPLE_U8, NULL), 0);
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(vt_source_read(&out, 0, 0, &img, &err), VTS_ERR_IO);
    VT_CHECK_STR_CONTAINS(err.message, "cannot decode tile 5");
    VT_CHECK_INT_EQ(vt_source_read(&out, 0, 0, &img, &err), 0); /* decoded again, now fine */
    VT_CHECK_INT_EQ(first_wrong_texel(&img, 0, 0), -1);
    VT_CHECK_INT_EQ(decodes_of(im, 1, 1), 2);
    VT_CHECK_INT_EQ(decodes_of(im, 0, 0), 1); /* tiles read before the failure stayed cached */
    vt_image_release(&img);
    vt_source_close(&out);
    vt_tile_cache_destroy(c);
    free(im);
}

struct reader {
    struct image *im;
    struct vt_source *src;
    unsigned index;
    atomic_int *registered;
    uint32_t x, y, w, h;
    unsigned rounds;
    uint64_t seed;
    long bad;
};

/* Registers its thread id, waits until every reader has (so that all of them read at once),
 * then reads its region (or `rounds` random regions). */
static void *reader_main(void *arg)
{
    struct reader *r = arg;
    r->im->reader_tids[r->index] = vt_test_tid();
    atomic_fetch_add(r->registered, 1);
    double until = vt_test_now() + VT_TEST_DEADLINE_S;
    while (atomic_load(r->registered) < (int)r->im->readers && vt_test_now() < until)
        vt_test_sleep_ms(1);
    r->bad = -1;
    atomic_store(&r->im->reading[r->index], 1);
    if (!r->rounds) {
        r->bad = read_check(r->src, r->x, r->y, r->w, r->h);
        atomic_store(&r->im->done[r->index], 1);
        return NULL;
    }
    for (unsigned i = 0; i < r->rounds && r->bad == -1; i++) {
        r->seed = r->seed * 6364136223846793005ull + 1442695040888963407ull;
        uint32_t w = 1 + (uint32_t)(r->seed >> 33) % 40, h = 1 + (uint32_t)(r->seed >> 45) % 40;
        uint32_t x = (uint32_t)(r->seed >> 20) % (r->im->width - w + 1);
        uint32_t y = (uint32_t)(r->seed >> 8) % (r->im->height - h + 1);
        r->bad = read_check(r->src, x, y, w, h);
    }
    atomic_store(&r->im->done[r->index], 1);
    return NULL;
}

static void concurrent_readers_of_one_tile_decode_it_once(void)
{
    static const unsigned counts_[] = {2, 4, 8};
    for (size_t k = 0; k < sizeof counts_ / sizeof counts_[0]; k++) {
        unsigned n = counts_[k];
        struct image *im = image_new(64, 64, 32);
        im->readers = n;
        im->gate_tile = 3; /* tile 1,1: its decoder waits until the other readers block */
        struct vt_source src[MAX_READERS], out[MAX_READERS];
        struct vt_source *srcs[MAX_READERS];
        for (unsigned i = 0; i < n; i++) {
            src[i] = image_source(im);
            srcs[i] = &src[i];
        }
        struct vt_tile_cache *c = vt_tile_cache_create(srcs, n, 1 << 20, out, NULL);
        VT_CHECK(c != NULL);
        if (!c)
            return;
        atomic_int registered = 0;
        struct reader r[MAX_READERS];
        pthread_t th[MAX_READERS];
        for (unsigned i = 0; i < n; i++) {
            r[i] = (struct reader){im, &out[i], i, &registered, 40, 36, 20, 20, 0, 0, 0};
            pthread_create(&th[i], NULL, reader_main, &r[i]);
        }
        for (unsigned i = 0; i < n; i++) {
            pthread_join(th[i], NULL);
            VT_CHECK_INT_EQ(r[i].bad, -1);
        }
        VT_CHECK_INT_EQ(atomic_load(&im->gate_timed_out), 0);
        VT_CHECK_INT_EQ(decodes_of(im, 1, 1), 1);
        unsigned long long decoded, hits;
        counts(c, &decoded, &hits);
        VT_CHECK_INT_EQ(decoded, 1);
        VT_CHECK_INT_EQ(hits, n - 1);
        for (unsigned i = 0; i < n; i++)
            vt_source_close(&out[i]);
        vt_tile_cache_destroy(c);
        free(im);
    }
}

/* Many readers, random regions, a cache of 4 tiles per reader: every texel right (run under
 * ThreadSanitizer by scripts/test). */
static void many_readers_with_a_small_cache_read_the_right_texels(void)
{
    const unsigned n = 4;
    struct image *im = image_new(300, 200, 16);
    im->readers = n;
    struct vt_source src[MAX_READERS], out[MAX_READERS];
    struct vt_source *srcs[MAX_READERS];
    for (unsigned i = 0; i < n; i++) {
        src[i] = image_source(im);
        srcs[i] = &src[i];
    }
    struct vt_tile_cache *c = vt_tile_cache_create(srcs, n, 1, out, NULL);
    VT_CHECK(c != NULL);
    if (!c)
        return;
    atomic_int registered = 0;
    struct reader r[MAX_READERS];
    pthread_t th[MAX_READERS];
    for (unsigned i = 0; i < n; i++) {
        r[i] = (struct reader){im, &out[i], i, &registered, 0, 0, 0, 0, 300, 1000 + i, 0};
        pthread_create(&th[i], NULL, reader_main, &r[i]);
    }
    for (unsigned i = 0; i < n; i++) {
        pthread_join(th[i], NULL);
        VT_CHECK_INT_EQ(r[i].bad, -1);
    }
    unsigned long long decoded, hits;
    counts(c, &decoded, &hits);
    VT_CHECK_INT_EQ(decoded, (unsigned long long)total_decodes(im));
    VT_CHECK(decoded > 19 * 13); /* more than once each: 16 slots cannot hold 247 tiles */
    VT_CHECK(hits > 0);
    for (unsigned i = 0; i < n; i++)
        vt_source_close(&out[i]);
    vt_tile_cache_destroy(c);
    free(im);
}

int main(void)
{
    VT_RUN(the_texel_check_catches_a_wrong_value);
    VT_RUN(a_second_read_of_a_tile_is_a_hit);
    VT_RUN(the_cache_holds_what_its_budget_allows_highest_rows_dropped_first);
    VT_RUN(a_failed_decode_is_reported_and_retried);
    VT_RUN(concurrent_readers_of_one_tile_decode_it_once);
    VT_RUN(many_readers_with_a_small_cache_read_the_right_texels);
    return vt_test_main_result();
}
