/* Tests of the tile sink (formats/codec/vt_tile_sink.c): the auto codec rule, the --mode effort,
 * and tiles put through it into a store and read back. */
#include <errno.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "vt_codec.h"
#include "vt_test.h"
#include "vt_tile_sink.h"
#include "vts.h"
#include "vts_writer.h"

static char test_dir[256]; /* a fresh directory under $TMPDIR (or /tmp) */

static const char *test_path(const char *name)
{
    static char path[512];
    snprintf(path, sizeof path, "%s/%s", test_dir, name);
    return path;
}

/* A tile whose texels depend on (seed, x, y, c) only. */
static struct vt_image tile_make(uint32_t px, uint32_t channels, uint32_t sample, unsigned seed)
{
    struct vt_image img;
    if (vt_image_alloc(&img, px, px, channels, sample, NULL) != 0)
        return (struct vt_image){0};
    unsigned char *p = img.pixels;
    for (size_t i = 0; i < img.stride * px; i++)
        p[i] = (unsigned char)(i * 7u + seed * 31u + (i >> 9));
    return img;
}

static void auto_rule_follows_the_table(void)
{
    static const struct {
        uint32_t sample;
        bool alpha;
        uint32_t colour;
        const char *codec;
    } rows[] = {
        {VTS_SAMPLE_U8, false, VTS_COLOUR_SRGB, "jpeg"},
        {VTS_SAMPLE_U8, false, VTS_COLOUR_LINEAR, "jpeg"},
        {VTS_SAMPLE_U8, true, VTS_COLOUR_SRGB, "png"},
        {VTS_SAMPLE_U8, false, VTS_COLOUR_NORMAL, "png"},
        {VTS_SAMPLE_U8, false, VTS_COLOUR_DATA, "png"},
        {VTS_SAMPLE_U16, false, VTS_COLOUR_SRGB, "png"},
        {VTS_SAMPLE_U16, true, VTS_COLOUR_LINEAR, "png"},
        {VTS_SAMPLE_F16, false, VTS_COLOUR_LINEAR, "raw"},
        {VTS_SAMPLE_F32, true, VTS_COLOUR_SRGB, "raw"},
        {VTS_SAMPLE_F32, false, VTS_COLOUR_NORMAL, "raw"},
    };
    for (size_t i = 0; i < sizeof rows / sizeof rows[0]; i++) {
        const char *got = vt_tile_sink_auto_codec(rows[i].sample, rows[i].alpha, rows[i].colour);
        if (strcmp(got, rows[i].codec) != 0)
            fprintf(stderr, "  row %zu: %s, not %s\n", i, got, rows[i].codec);
        VT_CHECK(strcmp(got, rows[i].codec) == 0);
        VT_CHECK(vt_codec_find(got) != NULL);
    }
}

static void codec_name_resolves_auto_only(void)
{
    VT_CHECK(strcmp(vt_tile_sink_codec_name("auto", VTS_SAMPLE_U8, false, VTS_COLOUR_SRGB),
                    "jpeg") == 0);
    /* an atlas layer of converted 16-bit textures is 8-bit: jpeg; the same input alone: png */
    VT_CHECK(strcmp(vt_tile_sink_codec_name("auto", VTS_SAMPLE_U16, false, VTS_COLOUR_SRGB),
                    "png") == 0);
    VT_CHECK(strcmp(vt_tile_sink_codec_name("bc1", VTS_SAMPLE_U16, true, VTS_COLOUR_DATA), "bc1") ==
             0);
    VT_CHECK(strcmp(vt_tile_sink_codec_name("nope", VTS_SAMPLE_U8, false, VTS_COLOUR_SRGB),
                    "nope") == 0);
}

static void gpu_rule_picks_bc5_for_normals_and_bc4_for_one_channel(void)
{
    static const struct {
        uint32_t channels;
        bool alpha;
        uint32_t colour;
        const char *codec;
    } rows[] = {
        {3, false, VTS_COLOUR_NORMAL, "bc5"}, {2, false, VTS_COLOUR_DATA, "bc5"},
        {2, true, VTS_COLOUR_SRGB, "bc5"},    {1, false, VTS_COLOUR_DATA, "bc4"},
        {1, false, VTS_COLOUR_SRGB, "bc4"},   {3, false, VTS_COLOUR_SRGB, "bc1"},
        {3, false, VTS_COLOUR_DATA, "bc1"},   {4, true, VTS_COLOUR_SRGB, "bc3"},
        {4, true, VTS_COLOUR_NORMAL, "bc3"},
    };
    int wrong = 0;
    for (size_t i = 0; i < sizeof rows / sizeof rows[0]; i++) {
        const char *got = vt_tile_sink_layer_codec_name("gpu", VTS_SAMPLE_U8, rows[i].channels,
                                                        rows[i].alpha, rows[i].colour);
        if (strcmp(got, rows[i].codec) != 0)
            fprintf(stderr, "  row %zu: %s, not %s\n", i, got, rows[i].codec);
        wrong += strcmp(got, rows[i].codec) != 0;
        /* the codec picked stores that layer */
        const struct vt_codec *c = vt_codec_find(got);
        VT_CHECK(c && c->check(256, rows[i].channels, VTS_SAMPLE_U8, NULL) == 0);
    }
    VT_CHECK_INT_EQ(wrong, 0);
    /* other names pass through to the auto rule */
    VT_CHECK_STR_EQ(
        vt_tile_sink_layer_codec_name("auto", VTS_SAMPLE_U8, 3, false, VTS_COLOUR_NORMAL), "png");
    VT_CHECK_STR_EQ(
        vt_tile_sink_layer_codec_name("bc1", VTS_SAMPLE_U8, 3, false, VTS_COLOUR_NORMAL), "bc1");
}

static void best_effort_maps_per_codec(void)
{
    static const struct {
        const char *codec;
        int fast, best;
    } rows[] = {{"raw", 0, 1}, {"png", 0, 9}, {"jpeg", 0, 1}, {"bc1", 0, 1}, {"bc3", 0, 1}};
    for (size_t i = 0; i < sizeof rows / sizeof rows[0]; i++) {
        const struct vt_codec *c = vt_codec_find(rows[i].codec);
        VT_CHECK(c != NULL);
        if (!c)
            continue;
        VT_CHECK_INT_EQ(vt_tile_sink_effort(c, false), rows[i].fast);
        VT_CHECK_INT_EQ(vt_tile_sink_effort(c, true), rows[i].best);
    }
}

/* Two layers (png RGBA8, raw u16 grey) and a third the caller fills itself, from two workers;
 * read back: png and raw give the texels, empty tiles are empty, the caller's bytes are kept. */
static void put_round_trips_through_a_store(void)
{
    enum { PX = 16 };
    const char *path = test_path("sink.vts");
    struct vts_geometry g = {40, 24, PX - 4, 2, PX, 0, 3, 0};
    g.level_count = vts_full_level_count(g.width, g.height, g.tile_content_px);
    struct vts_layer layers[3] = {{VTS_CODEC_PNG, 4, VTS_SAMPLE_U8, VTS_COLOUR_SRGB, 0, 0, "c"},
                                  {VTS_CODEC_RAW, 1, VTS_SAMPLE_U16, VTS_COLOUR_DATA, 0, 0, "d"},
                                  {VTS_CODEC_RAW, 1, VTS_SAMPLE_U8, VTS_COLOUR_DATA, 0, 0, "own"}};
    struct vts_error err = {0};
    struct vts_writer *w = vts_writer_create(path, &g, layers, &err);
    VT_CHECK(w != NULL);
    if (!w)
        return;
    const struct vt_codec *png = vt_codec_find("png"), *raw = vt_codec_find("raw");
    struct vt_tile_sink_layer sl[3] = {{png, {0, vt_tile_sink_effort(png, true), 0}, 4, 0},
                                       {raw, {0}, 1, VTS_SAMPLE_U16},
                                       {NULL, {0}, 0, 0}};
    struct vt_tile_sink *s = vt_tile_sink_create(w, PX, sl, 3, 2, 1000, &err);
    VT_CHECK(s != NULL);
    size_t cap = 0;
    unsigned char *own = s ? vt_tile_sink_scratch(s, 1, &cap) : NULL;
    VT_CHECK(own != NULL && cap >= 1000);
    VT_CHECK(s == NULL || vt_tile_sink_scratch(s, 2, NULL) == NULL);
    struct vt_image c0 = tile_make(PX, 4, VTS_SAMPLE_U8, 1);
    struct vt_image c1 = tile_make(PX, 4, VTS_SAMPLE_U8, 2);
    struct vt_image d0 = tile_make(PX, 1, VTS_SAMPLE_U16, 3);
    VT_CHECK_INT_EQ(vt_tile_sink_put(s, 0, 0, 0, 0, 0, &c0, &err), 0);
    VT_CHECK_INT_EQ(vt_tile_sink_put(s, 1, 0, 0, 1, 1, &c1, &err), 0);
    VT_CHECK_INT_EQ(vt_tile_sink_put(s, 1, 0, 0, 2, 0, NULL, &err), 0);
    VT_CHECK_INT_EQ(vt_tile_sink_put(s, 0, 1, 1, 0, 0, &d0, &err), 0);
    VT_CHECK_INT_EQ(vt_tile_sink_put(s, 0, 2, 0, 0, 0, &c0, &err), VTS_ERR_ARG); /* no codec */
    VT_CHECK_INT_EQ(vt_tile_sink_put(s, 2, 0, 0, 0, 1, &c0, &err), VTS_ERR_ARG); /* no worker */
    for (int i = 0; own && i < 5; i++)
        own[i] = (unsigned char)(0xa0 + i);
    VT_CHECK_INT_EQ(vts_writer_put(w, 2, 0, 1, 0, own, 5, &err), 0);
    VT_CHECK_INT_EQ(vts_writer_finish(w, &err), 0);
    vt_tile_sink_destroy(s);
    vts_writer_destroy(w);

    struct vts_store *st = vts_open(path, &err);
    VT_CHECK(st != NULL);
    unsigned char buf[8192];
    size_t len = 0;
    struct vt_image back = {0};
    vt_image_alloc(&back, PX, PX, 4, VTS_SAMPLE_U8, NULL);
    VT_CHECK_INT_EQ(vts_store_read(st, 0, 0, 1, 1, buf, sizeof buf, &len, 0, &err), 0);
    VT_CHECK_INT_EQ(png->decode(buf, len, &back, &err), 0);
    VT_CHECK(memcmp(back.pixels, c1.pixels, c1.stride * PX) == 0);
    VT_CHECK_INT_EQ(vts_store_read(st, 0, 0, 2, 0, buf, sizeof buf, &len, 0, &err), 0);
    VT_CHECK_INT_EQ(len, 0);
    VT_CHECK_INT_EQ(vts_store_read(st, 1, 1, 0, 0, buf, sizeof buf, &len, 0, &err), 0);
    VT_CHECK_INT_EQ(len, d0.stride * PX);
    VT_CHECK(memcmp(buf, d0.pixels, d0.stride * PX) == 0);
    VT_CHECK_INT_EQ(vts_store_read(st, 2, 0, 1, 0, buf, sizeof buf, &len, 0, &err), 0);
    VT_CHECK(len == 5 && buf[0] == 0xa0 && buf[4] == 0xa4);
    vts_close(st);
    vt_image_release(&back);
    vt_image_release(&c0);
    vt_image_release(&c1);
    vt_image_release(&d0);
    unlink(path);
}

/* A tile the codec refuses: the codec's reason, prefixed with the tile and level. */
static void put_names_the_tile_an_encoder_refuses(void)
{
    enum { PX = 16 };
    const char *path = test_path("refused.vts");
    struct vts_geometry g = {16, 16, PX - 4, 2, PX, 1, 1, 0};
    struct vts_layer layer = {VTS_CODEC_JPEG, 3, VTS_SAMPLE_U8, VTS_COLOUR_SRGB, 0, 85, "c"};
    struct vts_error err = {0};
    struct vts_writer *w = vts_writer_create(path, &g, &layer, &err);
    const struct vt_codec *jpeg = vt_codec_find("jpeg");
    struct vt_tile_sink_layer sl = {jpeg, {85, 0, 420}, 3, VTS_SAMPLE_U8};
    struct vt_tile_sink *s = w ? vt_tile_sink_create(w, PX, &sl, 1, 1, 0, &err) : NULL;
    VT_CHECK(s != NULL);
    struct vt_image rgba = tile_make(PX, 4, VTS_SAMPLE_U8, 5); /* jpeg has no alpha */
    int rc = s ? vt_tile_sink_put(s, 0, 0, 0, 0, 0, &rgba, &err) : 0;
    VT_CHECK(rc < 0);
    VT_CHECK_STR_CONTAINS(err.message, "cannot encode tile 0,0 of level 0: ");
    vt_image_release(&rgba);
    vt_tile_sink_destroy(s);
    vts_writer_destroy(w);
    VT_CHECK(access(path, F_OK) != 0);
}

static void create_refuses_bad_arguments(void)
{
    struct vts_error err = {0};
    VT_CHECK(vt_tile_sink_create(NULL, 16, NULL, 0, 1, 0, &err) == NULL);
    VT_CHECK_INT_EQ(err.status, VTS_ERR_ARG);
    vt_tile_sink_destroy(NULL);
}

int main(void)
{
    const char *tmp = getenv("TMPDIR");
    snprintf(test_dir, sizeof test_dir, "%s/test_vt_tile_sink.XXXXXX", tmp && *tmp ? tmp : "/tmp");
    if (!mkdtemp(test_dir)) {
        perror("mkdtemp");
        return 1;
    }
    VT_RUN(auto_rule_follows_the_table);
    VT_RUN(codec_name_resolves_auto_only);
    VT_RUN(gpu_rule_picks_bc5_for_normals_and_bc4_for_one_channel);
    VT_RUN(best_effort_maps_per_codec);
    VT_RUN(put_round_trips_through_a_store);
    VT_RUN(put_names_the_tile_an_encoder_refuses);
    VT_RUN(create_refuses_bad_arguments);
    if (rmdir(test_dir) != 0)
        fprintf(stderr, "cannot remove %s: %s\n", test_dir, strerror(errno));
    return vt_test_main_result();
}
