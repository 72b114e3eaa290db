/* Tests of the seams of a sharded build without wrap (lib/pyramid/vt_shard_seams.c), without tools
 * or stores: an image in memory is built whole, then as N parts that build their levels above the
 * first pass and carry their seam texels, then merged from those carried texels; every tile of
 * every level must be emitted exactly once with the single build's bytes, over odd sizes, several
 * part counts, levels per pass, filters, borders, a dropped alpha channel, and the merge's levels
 * in memory or in temporary files. */
#include <pthread.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "internal/vt_shard_seams.h"
#include "pyramid_test_image.h"
#include "vt_pyramid.h"
#include "vt_test.h"

enum { CH = 4, THREADS = 2 };

/* ---- an image in memory as a random-access source (pyramid_test_image.h) ---- */

static struct vt_image image;
static struct vt_source source;

static void make_source(uint32_t w, uint32_t h)
{
    pyramid_test_source(&image, &source, w, h);
}

/* ---- one case ---- */

struct params {
    uint32_t w, h, content, border, k;
    enum vt_filter_kind filter;
    uint32_t out_channels;
    bool compact; /* large enough that the seams carry less than the first pass's last level */
    bool files;   /* the merge keeps its levels in temporary files, not in memory */
};

/* A carried rectangle, as a part handed it over. */
struct carried {
    uint32_t part, level, tx, ty;
    struct vt_seams_rect r;
    float *texels;
};

/* What builds emit: tiles (one slot per level, tx, ty), and the parts' carried rectangles. */
struct build {
    const struct params *p;
    uint32_t first[33], tiles_x[32], levels;
    size_t tile_bytes;
    unsigned char *bytes; /* tile_bytes per slot */
    unsigned char *state; /* 0 not emitted, 1 empty, 2 with texels; more: emitted twice */
    struct carried *carried;
    size_t carried_count, carried_cap, carried_texels;
    uint32_t part, gx; /* the part running; the grid's columns (parts are numbered by rows) */
    int reads, fail_at;
};

static uint32_t extent(uint32_t size, uint32_t level)
{
    return (uint32_t)(((uint64_t)size + (1u << level) - 1) >> level);
}

static int emit(void *user, unsigned worker, uint32_t level, uint32_t tx, uint32_t ty,
                const struct vt_image *payload, struct vts_error *err);

static struct vt_pyramid_options options(struct build *b)
{
    const char *tmp = getenv("TMPDIR");
    const struct params *p = b->p;
    return (struct vt_pyramid_options){.width = p->w,
                                       .height = p->h,
                                       .tile_content_px = p->content,
                                       .border_px = p->border,
                                       .level_count = b->levels,
                                       .filter = p->filter,
                                       .colour = VTS_COLOUR_SRGB,
                                       .out_channels = p->out_channels,
                                       .out_sample = VTS_SAMPLE_U8,
                                       .threads = THREADS,
                                       .levels_per_pass = p->k,
                                       .temp_dir = tmp && *tmp ? tmp : "/tmp",
                                       .emit = emit,
                                       .user = b};
}

static void build_init(struct build *b, const struct params *p)
{
    *b = (struct build){.p = p, .fail_at = -1};
    b->levels = vts_full_level_count(p->w, p->h, p->content);
    uint32_t n = 0;
    for (uint32_t l = 0; l < b->levels; l++) {
        b->first[l] = n;
        b->tiles_x[l] = (extent(p->w, l) + p->content - 1) / p->content;
        n += b->tiles_x[l] * ((extent(p->h, l) + p->content - 1) / p->content);
    }
    b->first[b->levels] = n;
    uint32_t pp = p->content + 2 * p->border;
    b->tile_bytes = (size_t)pp * pp * p->out_channels;
    b->bytes = calloc(n, b->tile_bytes);
    b->state = calloc(n, 1);
}

static void build_release(struct build *b)
{
    for (size_t i = 0; i < b->carried_count; i++)
        free(b->carried[i].texels);
    free(b->carried);
    free(b->bytes);
    free(b->state);
}

static pthread_mutex_t emit_lock = PTHREAD_MUTEX_INITIALIZER;

static int emit(void *user, unsigned worker, uint32_t level, uint32_t tx, uint32_t ty,
                const struct vt_image *payload, struct vts_error *err)
{
    (void)worker;
    (void)err;
    struct build *b = user;
    size_t slot = b->first[level] + (size_t)ty * b->tiles_x[level] + tx;
    pthread_mutex_lock(&emit_lock); /* a slot may be emitted twice (a bug this test finds) */
    b->state[slot] = (unsigned char)(b->state[slot] + (payload ? 2 : 1));
    for (uint32_t y = 0; payload && y < payload->height; y++)
        memcpy(b->bytes + slot * b->tile_bytes + (size_t)y * payload->width * payload->channels,
               vt_image_at(payload, 0, y), (size_t)payload->width * payload->channels);
    pthread_mutex_unlock(&emit_lock);
    return 0;
}

/* vt_pyramid_seam_fn: keeps a copy (called on the calling thread). */
static int carry(void *user, uint32_t level, uint32_t x, uint32_t y, uint32_t width,
                 uint32_t height, uint32_t channels, const float *texels, size_t stride,
                 struct vts_error *err)
{
    (void)err;
    struct build *b = user;
    if (b->carried_count == b->carried_cap) {
        b->carried_cap = b->carried_cap ? 2 * b->carried_cap : 64;
        b->carried = realloc(b->carried, b->carried_cap * sizeof *b->carried);
    }
    struct carried *c = &b->carried[b->carried_count++];
    uint32_t content = b->p->content;
    *c = (struct carried){b->part,
                          level,
                          x / content,
                          y / content,
                          {x, y, width, height},
                          malloc((size_t)width * height * channels * sizeof(float))};
    for (uint32_t r = 0; r < height; r++)
        memcpy(c->texels + (size_t)r * width * channels, texels + r * stride,
               (size_t)width * channels * sizeof(float));
    b->carried_texels += (size_t)width * height;
    return 0;
}

/* vt_seams_read_fn over the carried rectangles: the same rectangle must have been carried. */
static int read_carried(void *user, uint32_t col, uint32_t row, uint32_t level, uint32_t tx,
                        uint32_t ty, const struct vt_seams_rect *r, float *texels, size_t stride,
                        struct vts_error *err)
{
    struct build *b = user;
    if (b->reads++ == b->fail_at)
        return vt_error_set(err, VTS_ERR_BAD_INPUT, "read %d fails", b->fail_at);
    for (size_t i = 0; i < b->carried_count; i++) {
        const struct carried *c = &b->carried[i];
        if (c->level != level || c->tx != tx || c->ty != ty || c->part != row * b->gx + col)
            continue;
        if (c->r.x != r->x || c->r.y != r->y || c->r.width != r->width || c->r.height != r->height)
            return vt_error_set(err, VTS_ERR_BAD_INPUT,
                                "part %u,%u level %u tile %u,%u: rectangle differs", col, row,
                                level, tx, ty);
        for (uint32_t y = 0; y < r->height; y++)
            memcpy(texels + y * stride, c->texels + (size_t)y * r->width * CH,
                   (size_t)r->width * CH * sizeof(float));
        return 0;
    }
    return vt_error_set(err, VTS_ERR_BAD_INPUT, "part %u,%u level %u tile %u,%u: not carried", col,
                        row, level, tx, ty);
}

static struct vt_source *sources[THREADS] = {&source, &source};

/* The seams of the build in `count` parts (merge side: the original input). */
static struct vt_seams *seams_of(const struct vt_pyramid_options *o, uint32_t count)
{
    struct vt_pyramid_plan plan;
    uint32_t xcuts[65], ycuts[65], gx, gy;
    vt_pyramid_plan(o, &plan);
    VT_CHECK(vt_pyramid_part_cuts(&plan, count, xcuts, &gx, ycuts, &gy));
    return vt_seams_create(o, &source.info, xcuts, gx, ycuts, gy, NULL);
}

/* Builds the parts of a `count`-part build and merges them into b; 0 or the merge's status. */
static int build_sharded(struct build *b, uint32_t count, struct vts_error *err)
{
    struct vt_pyramid_options o = options(b);
    struct vt_pyramid_plan plan;
    vt_pyramid_plan(&o, &plan);
    o.part = true;
    o.part_count = count;
    o.seam_carry = carry;
    for (uint32_t i = 0; i < count; i++) {
        VT_CHECK(vt_pyramid_part(&plan, i, count, &o.part_x0, &o.part_y0, &o.part_x1, &o.part_y1));
        o.part_index = i;
        b->part = i;
        VT_CHECK(vt_pyramid_part_seams(&o) == (b->levels > plan.levels_per_pass + 1));
        VT_CHECK_INT_EQ(vt_pyramid_build(sources, &o, err), 0);
    }
    struct vt_pyramid_options mo = options(b);
    mo.resume_input = &source.info;
    uint32_t xcuts[65], ycuts[65], gy;
    VT_CHECK(vt_pyramid_part_cuts(&plan, count, xcuts, &b->gx, ycuts, &gy));
    struct vt_seams *s = seams_of(&mo, count);
    VT_CHECK(s != NULL);
    if (s && b->p->files)
        vt_seams_set_memory(s, 0);
    int rc = s ? vt_seams_merge_run(s, read_carried, b, err) : -1;
    vt_seams_destroy(s);
    return rc;
}

/* Tiles not emitted exactly once, and those that differ from ref (emptiness or bytes). */
static void compare(const struct build *b, const struct build *ref, int *missing, int *different)
{
    *missing = *different = 0;
    for (uint32_t i = 0; i < b->first[b->levels]; i++) {
        *missing += b->state[i] == 0 || b->state[i] > 2;
        *different += b->state[i] != ref->state[i] ||
                      memcmp(b->bytes + i * b->tile_bytes, ref->bytes + i * b->tile_bytes,
                             b->tile_bytes) != 0;
    }
}

static void check_case(const struct params *p, const uint32_t *counts, size_t ncounts)
{
    make_source(p->w, p->h);
    struct build single;
    build_init(&single, p);
    struct vts_error err = {0};
    struct vt_pyramid_options o = options(&single);
    VT_CHECK_INT_EQ(vt_pyramid_build(sources, &o, &err), 0);
    for (size_t i = 0; i < ncounts; i++) {
        struct build sharded;
        build_init(&sharded, p);
        VT_CHECK_INT_EQ(build_sharded(&sharded, counts[i], &err), 0);
        int missing, different;
        compare(&sharded, &single, &missing, &different);
        if (getenv("VT_TEST_VERBOSE"))
            fprintf(stderr, "%ux%u, %u parts: %zu texels carried, %llu in level %u\n", p->w, p->h,
                    counts[i], sharded.carried_texels,
                    (unsigned long long)extent(p->w, p->k) * extent(p->h, p->k), p->k);
        if (missing || different)
            fprintf(stderr,
                    "%ux%u content %u border %u k %u filter %d, %u parts: %d missing, %d "
                    "different\n",
                    p->w, p->h, p->content, p->border, p->k, (int)p->filter, counts[i], missing,
                    different);
        VT_CHECK_INT_EQ(missing, 0);
        VT_CHECK_INT_EQ(different, 0);
        /* the seams are thin: far fewer texels carried than the first pass's last level has */
        uint64_t level_k = (uint64_t)extent(p->w, p->k) * extent(p->h, p->k);
        if (counts[i] == 1)
            VT_CHECK_INT_EQ((int)sharded.carried_texels, 0);
        else if (single.levels > p->k + 1)
            VT_CHECK(sharded.carried_texels < level_k || !p->compact);
        build_release(&sharded);
    }
    build_release(&single);
}

static void shards_and_merge_equal_the_single_build(void)
{
    static const uint32_t many[] = {1, 2, 4, 8, 16}, some[] = {2, 4, 16}, few[] = {4, 8};
    const struct params cases[] = {
        {300, 200, 16, 2, 2, VT_FILTER_LANCZOS3, 4, false, false},
        {1001, 777, 30, 1, 1, VT_FILTER_BOX, 4, true, true},
        {513, 1025, 14, 3, 3, VT_FILTER_KAISER, 3, false, false},
        {777, 301, 12, 2, 2, VT_FILTER_TRIANGLE, 4, false, false},
        {2000, 1500, 30, 2, 2, VT_FILTER_LANCZOS3, 4, true, true},
        {97, 61, 8, 1, 1, VT_FILTER_LANCZOS3, 4, false, false},
    };
    check_case(&cases[0], many, 5);
    check_case(&cases[1], some, 3);
    check_case(&cases[2], few, 2);
    check_case(&cases[3], many, 5);
    check_case(&cases[4], few, 2);
    check_case(&cases[5], many, 5);
}

/* A wrong carried rectangle (another size than the merge expects) or a failed read is an error. */
static void merge_stops_at_a_failed_read(void)
{
    const struct params p = {300, 200, 16, 2, 2, VT_FILTER_LANCZOS3, 4, false, false};
    make_source(p.w, p.h);
    struct build b;
    build_init(&b, &p);
    b.fail_at = 5;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(build_sharded(&b, 4, &err), VTS_ERR_BAD_INPUT);
    VT_CHECK_STR_CONTAINS(err.message, "read 5 fails");
    VT_CHECK_INT_EQ(b.reads, 6);
    build_release(&b);

    build_init(&b, &p);
    struct vt_pyramid_options o = options(&b);
    o.resume_input = &source.info;
    o.wrap = true; /* wrapped builds carry their level instead */
    struct vt_pyramid_plan plan;
    uint32_t xcuts[65], ycuts[65], gx, gy;
    vt_pyramid_plan(&o, &plan);
    VT_CHECK(vt_pyramid_part_cuts(&plan, 4, xcuts, &gx, ycuts, &gy));
    VT_CHECK(vt_seams_create(&o, &source.info, xcuts, gx, ycuts, gy, &err) == NULL);
    VT_CHECK_INT_EQ(err.status, VTS_ERR_ARG);
    o.part_count = 4;
    o.part = true;
    VT_CHECK(!vt_pyramid_part_seams(&o));
    vt_seams_destroy(NULL);
    build_release(&b);
}

int main(void)
{
    VT_RUN(shards_and_merge_equal_the_single_build);
    VT_RUN(merge_stops_at_a_failed_read);
    vt_image_release(&image);
    return vt_test_main_result();
}
