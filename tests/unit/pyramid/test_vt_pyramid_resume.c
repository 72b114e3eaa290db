/* Tests of the pyramid resumed from a level (lib/pyramid/vt_pyramid_resume.c), without tools or
 * stores: an image in memory is built whole, and again as parts that carry their texels of level
 * k; the resume from the assembled carried texels must emit every tile above k with the single
 * build's bytes. */
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pyramid_test_image.h"
#include "vt_pyramid.h"
#include "vt_pyramid_resume.h"
#include "vt_test.h"

enum { W = 300, H = 200, CH = 4, CONTENT = 16, BORDER = 2, K = 2, THREADS = 2 };

/* ---- an image in memory as a random-access source (pyramid_test_image.h) ---- */

static struct vt_image image;
static struct vt_source source;

static void make_source(void)
{
    pyramid_test_source(&image, &source, W, H);
}

/* ---- what a build emits: tiles (one slot per level, tx, ty) and carried texels of level K ---- */

struct build {
    uint32_t first[17], tiles_x[16];
    size_t tile_bytes;
    unsigned char *bytes; /* tile_bytes per slot */
    unsigned char *state; /* 0 not emitted, 1 empty, 2 with texels; more: emitted twice */
    uint32_t carry_w, carry_h;
    float *carried; /* carry_w x carry_h x CH, from carry() */
    int fail_at;    /* read_level() fails at this call (-1: never) */
    int reads;
};

static uint32_t extent(uint32_t size, uint32_t level)
{
    return (uint32_t)(((uint64_t)size + (1u << level) - 1) >> level);
}

static struct vt_pyramid_options base_options(struct build *b)
{
    const char *tmp = getenv("TMPDIR");
    return (struct vt_pyramid_options){.width = W,
                                       .height = H,
                                       .tile_content_px = CONTENT,
                                       .border_px = BORDER,
                                       .level_count = vts_full_level_count(W, H, CONTENT),
                                       .filter = VT_FILTER_LANCZOS3,
                                       .colour = VTS_COLOUR_SRGB,
                                       .out_channels = CH,
                                       .out_sample = VTS_SAMPLE_U8,
                                       .threads = THREADS,
                                       .levels_per_pass = K,
                                       .temp_dir = tmp && *tmp ? tmp : "/tmp",
                                       .user = b};
}

static void build_init(struct build *b)
{
    struct vt_pyramid_options o = base_options(b);
    struct vt_pyramid_plan plan;
    vt_pyramid_plan(&o, &plan);
    *b = (struct build){.carry_w = plan.carry_width, .carry_h = plan.carry_height, .fail_at = -1};
    uint32_t n = 0;
    for (uint32_t l = 0; l < o.level_count; l++) {
        b->first[l] = n;
        b->tiles_x[l] = (extent(W, l) + CONTENT - 1) / CONTENT;
        n += b->tiles_x[l] * ((extent(H, l) + CONTENT - 1) / CONTENT);
    }
    b->first[o.level_count] = n;
    b->tile_bytes = (size_t)(CONTENT + 2 * BORDER) * (CONTENT + 2 * BORDER) * CH;
    b->bytes = calloc(n, b->tile_bytes);
    b->state = calloc(n, 1);
    b->carried = calloc((size_t)b->carry_w * b->carry_h * CH, sizeof(float));
}

static void build_release(struct build *b)
{
    free(b->bytes);
    free(b->state);
    free(b->carried);
}

/* Distinct tiles go to distinct slots: safe from the worker threads without a lock. */
static int emit(void *user, unsigned worker, uint32_t level, uint32_t tx, uint32_t ty,
                const struct vt_image *payload, struct vts_error *err)
{
    (void)worker;
    (void)err;
    struct build *b = user;
    size_t slot = b->first[level] + (size_t)ty * b->tiles_x[level] + tx;
    b->state[slot] = (unsigned char)(b->state[slot] + (payload ? 2 : 1));
    for (uint32_t y = 0; payload && y < payload->height; y++)
        memcpy(b->bytes + slot * b->tile_bytes + (size_t)y * payload->width * CH,
               vt_image_at(payload, 0, y), (size_t)payload->width * CH);
    return 0;
}

/* Blocks own disjoint texels: safe from the worker threads without a lock. */
static int carry(void *user, unsigned worker, uint32_t x, uint32_t y, uint32_t width,
                 uint32_t height, uint32_t channels, const float *texels, size_t stride,
                 struct vts_error *err)
{
    (void)worker;
    (void)err;
    struct build *b = user;
    for (uint32_t r = 0; r < height; r++)
        memcpy(b->carried + ((size_t)(y + r) * b->carry_w + x) * CH, texels + r * stride,
               (size_t)width * channels * sizeof(float));
    return 0;
}

/* vt_pyramid_level_fn over another build's carried texels. */
static int read_level(void *user, uint32_t tx, uint32_t ty, uint32_t width, uint32_t height,
                      float *texels, size_t stride, struct vts_error *err)
{
    struct build *b = user;
    if (b->reads++ == b->fail_at)
        return vt_error_set(err, VTS_ERR_BAD_INPUT, "no texels for tile %u,%u", tx, ty);
    for (uint32_t r = 0; r < height; r++)
        memcpy(texels + r * stride,
               b->carried + ((size_t)(ty * CONTENT + r) * b->carry_w + tx * CONTENT) * CH,
               (size_t)width * CH * sizeof(float));
    return 0;
}

/* ---- tests ---- */

static struct vt_source *sources[THREADS] = {&source, &source};

/* The first pass in `parts` parts (vt_pyramid_part), each carrying its texels of level K. */
static void build_parts(struct build *b, uint32_t parts)
{
    struct vt_pyramid_options o = base_options(b);
    struct vt_pyramid_plan plan;
    vt_pyramid_plan(&o, &plan);
    o.emit = emit;
    o.part = true;
    o.carry = carry;
    struct vts_error err = {0};
    for (uint32_t i = 0; i < parts; i++) {
        VT_CHECK(vt_pyramid_part(&plan, i, parts, &o.part_x0, &o.part_y0, &o.part_x1, &o.part_y1));
        VT_CHECK_INT_EQ(vt_pyramid_build(sources, &o, &err), 0);
    }
}

/* Counts the tiles of levels [from, to) not emitted exactly once, and those that differ from ref
 * (emptiness or bytes). */
static void compare_levels(const struct build *b, const struct build *ref, uint32_t from,
                           uint32_t to, int *missing, int *different)
{
    *missing = *different = 0;
    for (uint32_t i = b->first[from]; i < b->first[to]; i++) {
        *missing += b->state[i] == 0 || b->state[i] > 2;
        *different += b->state[i] != ref->state[i] ||
                      memcmp(b->bytes + i * b->tile_bytes, ref->bytes + i * b->tile_bytes,
                             b->tile_bytes) != 0;
    }
}

static void resume_emits_the_single_builds_tiles(void)
{
    struct build single, parts, resumed;
    build_init(&single);
    build_init(&parts);
    build_init(&resumed);
    struct vts_error err = {0};
    struct vt_pyramid_options o = base_options(&single);
    o.emit = emit;
    VT_CHECK_INT_EQ(vt_pyramid_build(sources, &o, &err), 0);
    build_parts(&parts, 4);
    int missing, different;
    compare_levels(&parts, &single, 0, K + 1, &missing, &different); /* the parts' own levels */
    VT_CHECK_INT_EQ(missing, 0);
    VT_CHECK_INT_EQ(different, 0);

    struct vt_source_info input = source.info;
    struct vt_pyramid_options ro = base_options(&resumed);
    ro.emit = emit;
    ro.resume_input = &input;
    struct vt_pyramid_resume *r = vt_pyramid_resume_create(&ro, read_level, &parts, &err);
    VT_CHECK(r != NULL);
    VT_CHECK_INT_EQ(parts.reads, (int)(((parts.carry_w + CONTENT - 1) / CONTENT) *
                                       ((parts.carry_h + CONTENT - 1) / CONTENT)));
    VT_CHECK_INT_EQ(r ? vt_pyramid_resume_run(r, &err) : -1, 0);
    vt_pyramid_resume_destroy(r);
    compare_levels(&resumed, &single, K + 1, ro.level_count, &missing, &different);
    VT_CHECK_INT_EQ(missing, 0);
    VT_CHECK_INT_EQ(different, 0);
    int again = 0; /* tiles of levels 0..K emitted by the resume: none */
    for (uint32_t i = 0; i < resumed.first[K + 1]; i++)
        again += resumed.state[i] != 0;
    VT_CHECK_INT_EQ(again, 0);
    uint64_t emitted = resumed.first[ro.level_count] - resumed.first[K + 1];
    VT_CHECK_INT_EQ(vt_pyramid_tile_count(&ro), emitted);
    build_release(&single);
    build_release(&parts);
    build_release(&resumed);
}

static void resume_stops_at_the_first_failed_read(void)
{
    struct build parts, resumed;
    build_init(&parts);
    build_init(&resumed);
    build_parts(&parts, 1);
    parts.fail_at = 3;
    struct vt_source_info input = source.info;
    struct vt_pyramid_options ro = base_options(&resumed);
    ro.emit = emit;
    ro.resume_input = &input;
    struct vts_error err = {0};
    VT_CHECK(vt_pyramid_resume_create(&ro, read_level, &parts, &err) == NULL);
    VT_CHECK_INT_EQ(err.status, VTS_ERR_BAD_INPUT);
    VT_CHECK_STR_CONTAINS(err.message, "no texels for tile ");
    VT_CHECK_INT_EQ(parts.reads, 4);
    build_release(&parts);
    build_release(&resumed);
}

static void resume_refuses_a_build_without_levels_above_k(void)
{
    struct build b;
    build_init(&b);
    struct vt_source_info input = source.info;
    struct vt_pyramid_options o = base_options(&b);
    o.emit = emit;
    o.resume_input = &input;
    o.level_count = K + 1; /* the first pass makes every level */
    struct vts_error err = {0};
    VT_CHECK(vt_pyramid_resume_create(&o, read_level, &b, &err) == NULL);
    VT_CHECK_INT_EQ(err.status, VTS_ERR_ARG);
    o.level_count = vts_full_level_count(W, H, CONTENT);
    o.resume_input = NULL;
    VT_CHECK(vt_pyramid_resume_create(&o, read_level, &b, &err) == NULL);
    VT_CHECK_INT_EQ(err.status, VTS_ERR_ARG);
    VT_CHECK_INT_EQ(b.reads, 0);
    vt_pyramid_resume_destroy(NULL);
    build_release(&b);
}

int main(void)
{
    make_source();
    VT_RUN(resume_emits_the_single_builds_tiles);
    VT_RUN(resume_stops_at_the_first_failed_read);
    VT_RUN(resume_refuses_a_build_without_levels_above_k);
    vt_image_release(&image);
    return vt_test_main_result();
}
