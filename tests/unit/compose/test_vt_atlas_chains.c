/* lib/compose's out-of-core texture pass: a chain streamed from rows holds the texels of the whole
 * chain bit for bit; the block cache keeps its memory within the budget and gives back what was
 * spilled; an atlas build decodes each texture file once (both layers from one decode) and holds
 * its budget. */
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "internal/vt_atlas_build_impl.h"
#include "internal/vt_block_cache.h"
#include "internal/vt_chain_stream.h"
#include "internal/vt_mip_chain.h"
#include "vt_atlas_build.h"
#include "vt_layout.h"
#include "vt_test.h"

#define NTEX 4
#include "compose_test_util.h"

/* ---- the stream against the whole chain ---- */

struct got {
    struct vt_image levels[VTS_MAX_LEVELS];
    uint32_t blocks;
};

static int got_block(void *user, uint32_t level, uint32_t bx, uint32_t by, const uint8_t *px,
                     uint32_t w, uint32_t h, struct vts_error *err)
{
    struct got *g = user;
    struct vt_image *lv = &g->levels[level];
    size_t tb = vt_image_texel_bytes(lv);
    (void)err;
    for (uint32_t j = 0; j < h; j++)
        memcpy(vt_image_at(lv, bx * VT_CHAIN_STREAM_EDGE, by * VT_CHAIN_STREAM_EDGE + j),
               px + j * w * tb, w * tb);
    g->blocks++;
    return 0;
}

/* Streams tex (tw x th) into the chain of an entry of ew x eh texels, band heights varying, and
 * compares every level with vt_mip_chain_from_image's. Returns the texels that differ. */
static uint64_t stream_vs_whole_wrap(uint32_t tw, uint32_t th, uint32_t ew, uint32_t eh,
                                     uint32_t ch, uint32_t colour, enum vt_filter_kind filter,
                                     uint32_t levels, bool wrap)
{
    struct vt_image tex;
    fill_texture(&tex, tw, th, ch, tw + th, 15);
    struct vt_source_info in = {tw, th, ch, VTS_SAMPLE_U8, colour, ch == 4, false, true, 0, 0, ""};
    struct vt_mip_chain_spec s = {ew,
                                  eh,
                                  0,
                                  0,
                                  ew,
                                  eh,
                                  wrap,
                                  levels,
                                  ch == 4 ? 3 : ch,
                                  ch == 4,
                                  colour,
                                  filter,
                                  1ull << 30,
                                  VTS_SAMPLE_U8,
                                  false};
    struct vt_mip_chain whole;
    VT_CHECK_INT_EQ(vt_mip_chain_from_image(&whole, &s, &in, &tex, NULL), 0);
    struct got g = {0};
    for (uint32_t l = 0; l < whole.level_count; l++)
        vt_image_alloc(&g.levels[l], whole.levels[l].width, whole.levels[l].height, ch,
                       VTS_SAMPLE_U8, NULL);
    uint32_t pre = 99;
    VT_CHECK(vt_chain_stream_fits(&s, tw, th, &pre));
    struct vt_chain_stream *cs = vt_chain_stream_create(&s, tw, th, got_block, &g, NULL);
    VT_CHECK(cs != NULL);
    for (uint32_t y = 0, n = 1; cs && y < th; y += n, n = n % 13 + 5) {
        struct vt_image band = tex;
        band.pixels = (uint8_t *)tex.pixels + y * tex.stride;
        band.height = th - y < n ? th - y : n;
        VT_CHECK_INT_EQ(vt_chain_stream_push(cs, &band, NULL), 0);
    }
    vt_chain_stream_destroy(cs);
    uint64_t diff = 0;
    for (uint32_t l = 0; l < whole.level_count; l++) {
        const struct vt_image *a = &whole.levels[l], *b = &g.levels[l];
        for (uint32_t y = 0; y < a->height; y++)
            diff += memcmp(vt_image_at(a, 0, y), vt_image_at(b, 0, y), a->width * ch) != 0;
        vt_image_release(&g.levels[l]);
    }
    VT_CHECK(g.blocks > 0);
    vt_mip_chain_release(&whole);
    vt_image_release(&tex);
    return diff;
}

static uint64_t stream_vs_whole(uint32_t tw, uint32_t th, uint32_t ew, uint32_t eh, uint32_t ch,
                                uint32_t colour, enum vt_filter_kind filter, uint32_t levels)
{
    return stream_vs_whole_wrap(tw, th, ew, eh, ch, colour, filter, levels, false);
}

static void a_streamed_chain_equals_the_whole_chain(void)
{
    VT_CHECK_INT_EQ(stream_vs_whole(131, 77, 131, 77, 3, VTS_COLOUR_SRGB, VT_FILTER_BOX, 8), 0);
    VT_CHECK_INT_EQ(stream_vs_whole(200, 150, 200, 150, 4, VTS_COLOUR_SRGB, VT_FILTER_LANCZOS3, 6),
                    0);
    VT_CHECK_INT_EQ(stream_vs_whole(97, 130, 97, 130, 3, VTS_COLOUR_NORMAL, VT_FILTER_KAISER, 5),
                    0);
    VT_CHECK_INT_EQ(stream_vs_whole(70, 64, 70, 64, 1, VTS_COLOUR_DATA, VT_FILTER_TRIANGLE, 1), 0);
    /* the texture's own mip level 2 (scale 1/4), then the chain */
    VT_CHECK_INT_EQ(stream_vs_whole(259, 130, 65, 33, 4, VTS_COLOUR_SRGB, VT_FILTER_LANCZOS3, 4),
                    0);
}

/* Wrap entries: the first rows of each level wait for the last ones (the rotated stream), odd
 * sizes straddle the seam, small levels are held whole; every filter. */
static void a_streamed_wrap_chain_equals_the_whole_chain(void)
{
    static const enum vt_filter_kind f[4] = {VT_FILTER_BOX, VT_FILTER_TRIANGLE, VT_FILTER_LANCZOS3,
                                             VT_FILTER_KAISER};
    for (int i = 0; i < 4; i++) {
        VT_CHECK_INT_EQ(stream_vs_whole_wrap(131, 77, 131, 77, 3, VTS_COLOUR_SRGB, f[i], 8, true),
                        0);
        VT_CHECK_INT_EQ(stream_vs_whole_wrap(200, 301, 200, 301, 4, VTS_COLOUR_SRGB, f[i], 9, true),
                        0);
        VT_CHECK_INT_EQ(stream_vs_whole_wrap(64, 256, 64, 256, 1, VTS_COLOUR_DATA, f[i], 9, true),
                        0);
        VT_CHECK_INT_EQ(stream_vs_whole_wrap(5, 3, 5, 3, 3, VTS_COLOUR_LINEAR, f[i], 3, true), 0);
    }
    VT_CHECK_INT_EQ(
        stream_vs_whole_wrap(97, 330, 97, 330, 3, VTS_COLOUR_NORMAL, VT_FILTER_KAISER, 5, true), 0);
    /* the texture's own mip level 2, wrapped, then the chain */
    VT_CHECK_INT_EQ(
        stream_vs_whole_wrap(259, 530, 65, 133, 4, VTS_COLOUR_SRGB, VT_FILTER_LANCZOS3, 6, true),
        0);
    VT_CHECK_INT_EQ(
        stream_vs_whole_wrap(256, 256, 128, 128, 3, VTS_COLOUR_SRGB, VT_FILTER_BOX, 8, true), 0);
}

static void a_wrong_texel_is_caught(void)
{
    /* the comparison can fail: a chain of another filter differs */
    struct vt_image tex;
    fill_texture(&tex, 64, 64, 3, 1, 15);
    struct vt_source_info in = {64, 64, 3, VTS_SAMPLE_U8, VTS_COLOUR_SRGB, false, false, true,
                                0,  0,  ""};
    struct vt_mip_chain_spec s = {64,
                                  64,
                                  0,
                                  0,
                                  64,
                                  64,
                                  false,
                                  3,
                                  3,
                                  false,
                                  VTS_COLOUR_SRGB,
                                  VT_FILTER_BOX,
                                  1ull << 30,
                                  VTS_SAMPLE_U8,
                                  false};
    struct vt_mip_chain a, b;
    vt_mip_chain_from_image(&a, &s, &in, &tex, NULL);
    s.filter = VT_FILTER_LANCZOS3;
    vt_mip_chain_from_image(&b, &s, &in, &tex, NULL);
    VT_CHECK(memcmp(a.levels[1].pixels, b.levels[1].pixels, 32 * 32 * 3) != 0);
    vt_mip_chain_release(&a);
    vt_mip_chain_release(&b);
    vt_image_release(&tex);
    uint32_t pre;
    s.crop_x = 3; /* a crop is not streamed: built whole */
    s.crop_width = 61;
    VT_CHECK(!vt_chain_stream_fits(&s, 64, 64, &pre));
}

/* ---- the block cache ---- */

static void the_block_cache_holds_its_budget_and_reads_back_what_spilled(void)
{
    enum { N = 40, BYTES = 1000 };
    struct vt_block_cache *c = vt_block_cache_create(N, 5 * BYTES, NULL, NULL);
    VT_CHECK(c != NULL);
    uint8_t buf[BYTES];
    struct vt_block_cache_stats st;
    for (int i = 0; i < N; i++) {
        memset(buf, i, sizeof buf);
        VT_CHECK_INT_EQ(vt_block_cache_put(c, (uint64_t)i, buf, sizeof buf, NULL), 0);
        vt_block_cache_stats(c, &st);
        VT_CHECK(st.bytes <= 5 * BYTES);
    }
    VT_CHECK_INT_EQ(st.spilled, (N - 5) * BYTES);
    struct vt_block_cache_pins pins = {0};
    for (int round = 0; round < 2; round++)
        for (int i = N - 1; i >= 0; i--) {
            const uint8_t *px = NULL;
            VT_CHECK_INT_EQ(vt_block_cache_get(c, &pins, (uint64_t)i, &px, NULL), 0);
            VT_CHECK(px && px[0] == i && px[BYTES - 1] == i);
            vt_block_cache_stats(c, &st);
            VT_CHECK(st.bytes - 0 <= 5 * BYTES + VT_BLOCK_CACHE_PINS * BYTES);
        }
    vt_block_cache_unpin_all(c, &pins);
    vt_block_cache_stats(c, &st);
    VT_CHECK(st.peak_unpinned <= 5 * BYTES);
    VT_CHECK(st.peak <= 5 * BYTES + VT_BLOCK_CACHE_PINS * BYTES);
    VT_CHECK(st.reloads > 0);
    VT_CHECK_INT_EQ(st.spilled, N * BYTES); /* each block written once at most */
    vt_block_cache_destroy(c);
}

static void reserved_bytes_push_blocks_out_of_the_budget(void)
{
    enum { N = 12, BYTES = 1000 };
    struct vt_block_cache *c = vt_block_cache_create(N, 5 * BYTES, NULL, NULL);
    uint8_t buf[BYTES];
    struct vt_block_cache_stats st;
    for (int i = 0; i < 5; i++) {
        memset(buf, i, sizeof buf);
        VT_CHECK_INT_EQ(vt_block_cache_put(c, (uint64_t)i, buf, sizeof buf, NULL), 0);
    }
    vt_block_cache_stats(c, &st);
    VT_CHECK(st.bytes == 5 * BYTES && st.spilled == 0);
    VT_CHECK_INT_EQ(vt_block_cache_reserve(c, 2 * BYTES + 1, true, NULL), 0);
    vt_block_cache_stats(c, &st);
    VT_CHECK_INT_EQ(st.bytes, 2 * BYTES); /* 3 blocks made room for the reservation */
    VT_CHECK_INT_EQ(st.spilled, 3 * BYTES);
    memset(buf, 5, sizeof buf);
    VT_CHECK_INT_EQ(vt_block_cache_put(c, 5, buf, sizeof buf, NULL), 0);
    vt_block_cache_stats(c, &st);
    VT_CHECK(st.bytes <= 2 * BYTES && st.peak_reserved == 2 * BYTES + 1);
    vt_block_cache_unreserve(c, 2 * BYTES + 1);
    for (int i = 6; i < 9; i++) {
        memset(buf, i, sizeof buf);
        VT_CHECK_INT_EQ(vt_block_cache_put(c, (uint64_t)i, buf, sizeof buf, NULL), 0);
    }
    vt_block_cache_stats(c, &st);
    VT_CHECK_INT_EQ(st.bytes, 5 * BYTES); /* the whole budget again, nothing more spilled */
    VT_CHECK_INT_EQ(st.spilled, 4 * BYTES);
    struct vt_block_cache_pins pins = {0};
    for (int i = 0; i < 9; i++) {
        const uint8_t *px = NULL;
        VT_CHECK_INT_EQ(vt_block_cache_get(c, &pins, (uint64_t)i, &px, NULL), 0);
        VT_CHECK(px && px[0] == i && px[BYTES - 1] == i);
        vt_block_cache_unpin_all(c, &pins);
    }
    vt_block_cache_destroy(c);
}

struct reserver {
    struct vt_block_cache *c;
    int released; /* set (atomically) by the first reserver just before it unreserves */
    int seen;     /* what the second one saw when its reservation returned */
};

static void *second_reserver(void *arg)
{
    struct reserver *r = arg;
    VT_CHECK_INT_EQ(vt_block_cache_reserve(r->c, 1000, true, NULL), 0);
    r->seen = __atomic_load_n(&r->released, __ATOMIC_SEQ_CST);
    vt_block_cache_unreserve(r->c, 1000);
    return NULL;
}

static void a_first_reservation_waits_for_others_over_half_the_budget(void)
{
    struct reserver r = {vt_block_cache_create(4, 10000, NULL, NULL), 0, -1};
    VT_CHECK_INT_EQ(vt_block_cache_reserve(r.c, 4500, true, NULL), 0);
    pthread_t th;
    VT_CHECK_INT_EQ(pthread_create(&th, NULL, second_reserver, &r), 0);
    nanosleep(&(struct timespec){0, 50 * 1000 * 1000},
              NULL); /* give it time to try (not a check) */
    __atomic_store_n(&r.released, 1, __ATOMIC_SEQ_CST);
    vt_block_cache_unreserve(r.c, 4500);
    pthread_join(th, NULL);
    VT_CHECK_INT_EQ(r.seen, 1); /* 4500 + 1000 > 10000 / 2: it waited */
    /* a reservation that is not the caller's first never waits */
    VT_CHECK_INT_EQ(vt_block_cache_reserve(r.c, 4500, true, NULL), 0);
    VT_CHECK_INT_EQ(vt_block_cache_reserve(r.c, 4500, false, NULL), 0);
    vt_block_cache_unreserve(r.c, 9000);
    vt_block_cache_destroy(r.c);
}

/* ---- a build: decodes counted through the open callback ---- */

static const uint32_t tex_w[NTEX] = {300, 170, 256, 90}, tex_h[NTEX] = {200, 260, 256, 40};

static int count_tiles(void *user, unsigned worker, uint32_t slot, uint32_t level, uint32_t tx,
                       uint32_t ty, const struct vt_image *payload, struct vts_error *err)
{
    (void)worker, (void)slot, (void)level, (void)tx, (void)ty, (void)payload, (void)err;
    __atomic_fetch_add((uint64_t *)user, 1, __ATOMIC_RELAXED);
    return 0;
}

static void a_build_decodes_each_file_once_within_its_budget(void)
{
    char json[4096];
    int n = snprintf(json, sizeof json,
                     "{\"format\": \"vtpipe-atlas\", \"version\": 1, \"width\": 2048, \"height\": "
                     "512, \"tile_content\": 64, \"border\": 4, \"layers\": [{\"name\": \"d\", "
                     "\"map\": \"map_Kd\", \"colour\": \"srgb\"}, {\"name\": \"a\", \"map\": "
                     "\"map_d\", \"colour\": \"data\"}], \"entries\": [");
    for (int i = 0; i < NTEX; i++) {
        fill_texture(&textures[i], tex_w[i], tex_h[i], i == 1 ? 4 : 3, (uint32_t)i, 15);
        n += snprintf(json + n, sizeof json - (size_t)n,
                      "%s{\"name\": \"e%d\", \"x\": %d, \"y\": 0, \"width\": %u, \"height\": %u, "
                      "\"cell_width\": 512, \"cell_height\": 512, \"alignment\": 4, %s"
                      "\"textures\": [{\"path\": \"%d.png\", \"width\": %u, \"height\": %u}, "
                      "{\"path\": \"%d.png\", \"width\": %u, \"height\": %u}]}",
                      i ? ", " : "", i, i * 512, tex_w[i], tex_h[i],
                      i % 2 == 0 ? "\"wrap\": true, " : "", i, tex_w[i], tex_h[i], i, tex_w[i],
                      tex_h[i]);
    }
    snprintf(json + n, sizeof json - (size_t)n, "]}");
    struct vt_layout lay;
    VT_CHECK_INT_EQ(vt_layout_parse_memory(json, strlen(json), "/m/atlas.json", NULL, &lay, NULL),
                    0);
    uint32_t layers[2] = {0, 1};
    struct vt_atlas_build_options o = {.layout = &lay,
                                       .layers = layers,
                                       .layer_count = 2,
                                       .threads = 2,
                                       .filter = VT_FILTER_LANCZOS3, /* wrap rows rotated */
                                       .cache_bytes = 200000,        /* a fraction of the chains */
                                       .open = open_mem};
    struct vts_error err = {0};
    struct vt_atlas_build *b = vt_atlas_build_create(&o, &err);
    VT_CHECK(b != NULL);
    uint64_t tiles = 0;
    VT_CHECK_INT_EQ(b ? vt_atlas_build_tiles(b, count_tiles, &tiles, &err) : -1, 0);
    struct vt_atlas_build_stats st = {0};
    if (b)
        vt_atlas_build_stats(b, &st);
    VT_CHECK_INT_EQ(st.chains_built, NTEX); /* one decode per file, for both layers */
    for (int i = 0; i < NTEX; i++)
        VT_CHECK_INT_EQ(rows_read[i], tex_h[i]); /* every row decoded once */
    VT_CHECK(st.spilled_bytes > 0);
    VT_CHECK(st.cache_peak <= 200000 + 3 * VT_BLOCK_CACHE_PINS * 64 * 64 * 4);
    VT_CHECK(st.buffers_peak > 0); /* the texture streams' buffers were counted */
    VT_CHECK_INT_EQ(tiles, 2 * vt_atlas_build_tile_count(b));
    struct vt_atlas_layer_format f;
    vt_atlas_build_format(b, 0, &f);
    VT_CHECK(f.alpha); /* texture 1's alpha is not opaque */
    /* the streamed wrap entries (0 and 2) hold the texels of their whole chains */
    for (int i = 0; b && i < NTEX; i += 2) {
        struct vt_source_info in = {
            tex_w[i], tex_h[i], 3, VTS_SAMPLE_U8, VTS_COLOUR_SRGB, false, false, true, 0, 0, ""};
        struct vt_mip_chain_spec s = {tex_w[i],
                                      tex_h[i],
                                      0,
                                      0,
                                      tex_w[i],
                                      tex_h[i],
                                      true,
                                      3,
                                      3,
                                      true,
                                      VTS_COLOUR_SRGB,
                                      VT_FILTER_LANCZOS3,
                                      1ull << 30,
                                      VTS_SAMPLE_U8,
                                      false};
        struct vt_mip_chain whole;
        VT_CHECK_INT_EQ(vt_mip_chain_from_image(&whole, &s, &in, &textures[i], NULL), 0);
        for (uint32_t l = 0; l < whole.level_count; l++) {
            const struct vt_image *lv = &whole.levels[l];
            struct vt_image got;
            vt_image_alloc(&got, lv->width, lv->height, 4, VTS_SAMPLE_U8, NULL);
            VT_CHECK_INT_EQ(vt_atlas_build_render(b, 0, l, (uint32_t)(i * 512) >> l, 0, &got, &err),
                            0);
            uint64_t diff = 0;
            for (uint32_t y = 0; y < lv->height; y++)
                diff += memcmp(vt_image_at(lv, 0, y), vt_image_at(&got, 0, y), lv->width * 4) != 0;
            VT_CHECK_INT_EQ(diff, 0);
            vt_image_release(&got);
        }
        vt_mip_chain_release(&whole);
    }
    vt_atlas_build_destroy(b);
    vt_layout_release(&lay);
    for (int i = 0; i < NTEX; i++)
        vt_image_release(&textures[i]);
}

/* Workers put their own blocks and read everyone's while the others put, under a budget of a few
 * blocks: spills are written outside the cache's lock while other workers evict, reload, pin and
 * drop. Every block read holds its own bytes (a block reloaded from the wrong file range, or freed
 * while being written, fails it), the unpinned bytes never exceed the budget, and no block is
 * written twice. Failures are counted per worker and checked on the main thread. */
enum { SPILL_WORKERS = 4, SPILL_PER_WORKER = 48, SPILL_BYTES = 1500, SPILL_BUDGET = 6 };

struct spill_worker {
    struct vt_block_cache *c;
    int index;
    int errors, wrong;
};

static uint8_t spill_byte(uint64_t id, size_t i)
{
    return (uint8_t)(id * 131u + i * 7u + (i >> 8));
}

static void *spill_worker_run(void *arg)
{
    struct spill_worker *w = arg;
    uint8_t buf[SPILL_BYTES];
    struct vt_block_cache_pins pins = {0};
    for (int k = 0; k < SPILL_PER_WORKER; k++) {
        uint64_t id = (uint64_t)k * SPILL_WORKERS + (uint64_t)w->index;
        for (size_t i = 0; i < sizeof buf; i++)
            buf[i] = spill_byte(id, i);
        if (vt_block_cache_put(w->c, id, buf, sizeof buf, NULL))
            w->errors++;
        /* read back the newest blocks of this worker */
        for (int j = k; j >= 0 && j > k - 3; j--) {
            uint64_t rid = (uint64_t)j * SPILL_WORKERS + (uint64_t)w->index;
            const uint8_t *px = NULL;
            if (vt_block_cache_get(w->c, &pins, rid, &px, NULL) || !px) {
                w->errors++;
                continue;
            }
            for (size_t i = 0; i < SPILL_BYTES; i += 97)
                w->wrong += px[i] != spill_byte(rid, i);
        }
        /* and an older one, spilled by now (a reload) */
        const uint8_t *px = NULL;
        uint64_t old = (uint64_t)(k / 2) * SPILL_WORKERS + (uint64_t)w->index;
        if (vt_block_cache_get(w->c, &pins, old, &px, NULL) || !px)
            w->errors++;
        else
            for (size_t i = 0; i < SPILL_BYTES; i += 13)
                w->wrong += px[i] != spill_byte(old, i);
        vt_block_cache_unpin_all(w->c, &pins);
    }
    /* drop every third block of its own: the others' reads must not see it go */
    for (int k = 2; k < SPILL_PER_WORKER; k += 3)
        vt_block_cache_drop(w->c, (uint64_t)k * SPILL_WORKERS + (uint64_t)w->index);
    return NULL;
}

static void concurrent_spills_keep_every_block_and_the_budget(void)
{
    uint64_t n = (uint64_t)SPILL_WORKERS * SPILL_PER_WORKER;
    struct vt_block_cache *c =
        vt_block_cache_create(n, (uint64_t)SPILL_BUDGET * SPILL_BYTES, NULL, NULL);
    VT_CHECK(c != NULL);
    if (!c)
        return;
    struct spill_worker w[SPILL_WORKERS];
    pthread_t th[SPILL_WORKERS];
    for (int i = 0; i < SPILL_WORKERS; i++) {
        w[i] = (struct spill_worker){c, i, 0, 0};
        VT_CHECK_INT_EQ(pthread_create(&th[i], NULL, spill_worker_run, &w[i]), 0);
    }
    for (int i = 0; i < SPILL_WORKERS; i++) {
        pthread_join(th[i], NULL);
        VT_CHECK_INT_EQ(w[i].errors, 0);
        VT_CHECK_INT_EQ(w[i].wrong, 0);
    }
    struct vt_block_cache_stats st;
    vt_block_cache_stats(c, &st);
    VT_CHECK(st.spilled > 0 && st.reloads > 0); /* the budget did force spills and reloads */
    VT_CHECK(st.peak_unpinned <= (uint64_t)SPILL_BUDGET * SPILL_BYTES);
    VT_CHECK(st.spilled <= n * SPILL_BYTES); /* each block written once at most */
    /* every block not dropped still reads back whole, after all the workers are gone */
    struct vt_block_cache_pins pins = {0};
    int wrong = 0, errors = 0;
    for (uint64_t id = 0; id < n; id++) {
        if ((id / SPILL_WORKERS) % 3 == 2 && id / SPILL_WORKERS >= 2)
            continue;
        const uint8_t *px = NULL;
        if (vt_block_cache_get(c, &pins, id, &px, NULL) || !px) {
            errors++;
            continue;
        }
        for (size_t i = 0; i < SPILL_BYTES; i++)
            wrong += px[i] != spill_byte(id, i);
        vt_block_cache_unpin_all(c, &pins);
    }
    VT_CHECK_INT_EQ(errors, 0);
    VT_CHECK_INT_EQ(wrong, 0);
    vt_block_cache_destroy(c);
}

int main(void)
{
    VT_RUN(a_streamed_chain_equals_the_whole_chain);
    VT_RUN(a_streamed_wrap_chain_equals_the_whole_chain);
    VT_RUN(a_wrong_texel_is_caught);
    VT_RUN(the_block_cache_holds_its_budget_and_reads_back_what_spilled);
    VT_RUN(reserved_bytes_push_blocks_out_of_the_budget);
    VT_RUN(a_first_reservation_waits_for_others_over_half_the_budget);
    VT_RUN(concurrent_spills_keep_every_block_and_the_budget);
    VT_RUN(a_build_decodes_each_file_once_within_its_budget);
    return vt_test_main_result();
}
