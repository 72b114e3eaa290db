/* libvts-decode (vts_decode.h), linked as the shared library: tiles with and without their border,
 * regions stitched from tiles' content, empty tiles as zeros, every argument check, a malformed
 * payload and an unknown codec. Stores are written through libvts's writer with raw payloads whose
 * texels are a function of their position in the level, so every decoded texel has a known value.
 */
#define _POSIX_C_SOURCE 200809L
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "vt_test.h"
#include "vts.h"
#include "vts_decode.h"
#include "vts_writer.h"

static char tmpdir[256];

/* 300x200, content 64 + border 2: level 0 is 5x4 tiles. Layer 0 u8 x 3, layer 1 u16 x 1. */
static const struct vts_geometry geo = {300, 200, 64, 2, 68, 4, 2, 0};

/* Value of channel c of texel (x, y) of level, layer 0 (u8) or layer 1 (u16). */
static uint32_t texel_value(uint32_t layer, uint32_t level, uint32_t x, uint32_t y, uint32_t c)
{
    uint32_t v = x * 7u + y * 131u + level * 1000u + c * 50u;
    return layer == 0 ? v % 251u : (v * 37u) % 65521u;
}

static bool tile_is_empty(uint32_t level, uint32_t tx, uint32_t ty)
{
    return level == 0 && (tx + 2 * ty) % 7 == 3;
}

/* Raw payload of a tile: each payload texel is the level's texel at its position, clamped. */
static size_t make_payload(uint32_t layer, uint32_t level, uint32_t tx, uint32_t ty,
                           unsigned char *buf)
{
    struct vts_level L;
    vts_geometry_level(&geo, level, &L);
    uint32_t channels = layer == 0 ? 3 : 1, bytes = layer == 0 ? 1 : 2;
    size_t n = 0;
    for (uint32_t py = 0; py < geo.tile_payload_px; py++)
        for (uint32_t px = 0; px < geo.tile_payload_px; px++) {
            int64_t gx = (int64_t)tx * geo.tile_content_px + px - geo.border_px;
            int64_t gy = (int64_t)ty * geo.tile_content_px + py - geo.border_px;
            gx = gx < 0 ? 0 : gx >= L.width ? L.width - 1 : gx;
            gy = gy < 0 ? 0 : gy >= L.height ? L.height - 1 : gy;
            for (uint32_t c = 0; c < channels; c++) {
                uint32_t v = texel_value(layer, level, (uint32_t)gx, (uint32_t)gy, c);
                buf[n++] = (unsigned char)v;
                if (bytes == 2)
                    buf[n++] = (unsigned char)(v >> 8);
            }
        }
    return n;
}

/* Writes the store; layer 1's codec is codec1 (an unknown fourcc tests VTS_ERR_UNSUPPORTED). When
 * bad_tile, level 1 tile 0,0 of layer 0 holds a truncated payload. */
static struct vts_store *make_store(const char *name, uint32_t codec1, bool bad_tile)
{
    struct vts_layer layers[2] = {
        {VTS_CODEC_RAW, 3, VTS_SAMPLE_U8, VTS_COLOUR_SRGB, 0, 0, "diffuse"},
        {codec1, 1, VTS_SAMPLE_U16, VTS_COLOUR_DATA, 0, 0, "height"},
    };
    char path[300];
    struct vts_error err;
    snprintf(path, sizeof path, "%s/%s", tmpdir, name);
    unsigned char *buf = malloc(68 * 68 * 3);
    struct vts_writer *w = vts_writer_create(path, &geo, layers, &err);
    VT_CHECK(w != NULL);
    for (uint32_t layer = 0; w && layer < 2; layer++)
        for (uint32_t level = 0; level < geo.level_count; level++) {
            struct vts_level L;
            vts_geometry_level(&geo, level, &L);
            for (uint32_t ty = 0; ty < L.tiles_y; ty++)
                for (uint32_t tx = 0; tx < L.tiles_x; tx++) {
                    size_t len =
                        tile_is_empty(level, tx, ty) ? 0 : make_payload(layer, level, tx, ty, buf);
                    if (bad_tile && layer == 0 && level == 1 && tx == 0 && ty == 0)
                        len = 100;
                    VT_CHECK_INT_EQ(vts_writer_put(w, layer, level, tx, ty, buf, len, &err), 0);
                }
        }
    VT_CHECK_INT_EQ(vts_writer_finish(w, &err), 0);
    vts_writer_destroy(w);
    free(buf);
    struct vts_store *s = vts_open(path, &err);
    VT_CHECK(s != NULL);
    return s;
}

/* Number of texels of the w x h image at img (stride bytes) that differ from the level's values
 * at (x0, y0) + their position; empty tiles' texels must be 0. */
static long count_wrong(const unsigned char *img, size_t stride, uint32_t layer, uint32_t level,
                        uint32_t x0, uint32_t y0, uint32_t w, uint32_t h)
{
    uint32_t channels = layer == 0 ? 3 : 1, bytes = layer == 0 ? 1 : 2;
    long wrong = 0;
    for (uint32_t y = 0; y < h; y++)
        for (uint32_t x = 0; x < w; x++)
            for (uint32_t c = 0; c < channels; c++) {
                uint32_t gx = x0 + x, gy = y0 + y, got;
                const unsigned char *p = img + y * stride + ((size_t)x * channels + c) * bytes;
                if (bytes == 1) {
                    got = *p;
                } else {
                    uint16_t v;
                    memcpy(&v, p, 2);
                    got = v;
                }
                bool empty = tile_is_empty(level, gx / 64, gy / 64);
                wrong += got != (empty ? 0 : texel_value(layer, level, gx, gy, c));
            }
    return wrong;
}

static struct vts_store *store;

static void tile_with_border_is_the_payload(void)
{
    unsigned char buf[68 * 68 * 3], want[68 * 68 * 3];
    struct vts_error err;
    VT_CHECK_INT_EQ(vts_decode_texel_bytes(store, 0), 3);
    VT_CHECK_INT_EQ(vts_decode_texel_bytes(store, 1), 2);
    for (uint32_t level = 0; level < 4; level++) {
        VT_CHECK_INT_EQ(vts_decode_tile(store, 0, level, 0, 0, 0, buf, 68 * 3, sizeof buf, &err),
                        0);
        make_payload(0, level, 0, 0, want);
        VT_CHECK(memcmp(buf, want, sizeof want) == 0);
    }
    VT_CHECK_INT_EQ(vts_decode_tile(store, 1, 0, 4, 2, 0, buf, 68 * 2, sizeof buf, &err), 0);
    make_payload(1, 0, 4, 2, want);
    VT_CHECK(memcmp(buf, want, 68 * 68 * 2) == 0);
}

static void tile_without_border_is_the_content(void)
{
    size_t stride = 64 * 3 + 5; /* a stride longer than a row: the gaps stay untouched */
    unsigned char *buf = malloc(stride * 64);
    struct vts_error err;
    memset(buf, 0xEE, stride * 64);
    VT_CHECK_INT_EQ(vts_decode_tile(store, 0, 0, 1, 2, VTS_DECODE_NO_BORDER, buf, stride,
                                    stride * 63 + 64 * 3, &err),
                    0);
    VT_CHECK_INT_EQ(count_wrong(buf, stride, 0, 0, 64, 128, 64, 64), 0);
    VT_CHECK_INT_EQ(buf[64 * 3], 0xEE);
    /* The right edge tile of level 0 (300 = 4 * 64 + 44): past the edge, clamped copies. */
    VT_CHECK_INT_EQ(
        vts_decode_tile(store, 0, 0, 4, 0, VTS_DECODE_NO_BORDER, buf, stride, stride * 64, &err),
        0);
    VT_CHECK_INT_EQ(count_wrong(buf, stride, 0, 0, 256, 0, 44, 64), 0);
    VT_CHECK_INT_EQ(buf[50 * 3], texel_value(0, 0, 299, 0, 0));
    free(buf);
}

static void empty_tiles_decode_as_zeros(void)
{
    unsigned char buf[68 * 68 * 3];
    struct vts_error err;
    memset(buf, 0xEE, sizeof buf);
    VT_CHECK(tile_is_empty(0, 3, 0));
    VT_CHECK_INT_EQ(vts_decode_tile(store, 0, 0, 3, 0, 0, buf, 68 * 3, sizeof buf, &err), 0);
    bool all_zero = true;
    for (size_t i = 0; i < sizeof buf; i++)
        all_zero &= buf[i] == 0;
    VT_CHECK(all_zero);
}

static void region_is_stitched_from_tiles(void)
{
    /* Rectangles across tile edges, on edges, one texel, the last column, whole levels. */
    static const uint32_t rects[][5] = {
        {0, 0, 0, 300, 200}, {0, 63, 63, 2, 2}, {0, 10, 5, 250, 190}, {0, 299, 199, 1, 1},
        {1, 0, 0, 150, 100}, {2, 3, 7, 70, 43}, {3, 0, 0, 38, 25},    {0, 128, 64, 64, 64}};
    struct vts_error err;
    for (uint32_t layer = 0; layer < 2; layer++)
        for (size_t i = 0; i < sizeof rects / sizeof rects[0]; i++) {
            const uint32_t *r = rects[i];
            size_t stride = (size_t)r[3] * (layer == 0 ? 3 : 2) + 3;
            unsigned char *buf = malloc(stride * r[4]);
            int rc = vts_decode_region(store, layer, r[0], r[1], r[2], r[3], r[4], 0, buf, stride,
                                       stride * r[4], &err);
            VT_CHECK_INT_EQ(rc, 0);
            if (rc == 0)
                VT_CHECK_INT_EQ(count_wrong(buf, stride, layer, r[0], r[1], r[2], r[3], r[4]), 0);
            free(buf);
        }
}

/* The check itself: a region decoded one texel off does not pass. */
static void a_shifted_region_is_caught(void)
{
    unsigned char buf[20 * 20 * 3];
    struct vts_error err;
    VT_CHECK_INT_EQ(vts_decode_region(store, 0, 0, 61, 61, 20, 20, 0, buf, 60, sizeof buf, &err),
                    0);
    VT_CHECK(count_wrong(buf, 60, 0, 0, 62, 61, 20, 20) > 0);
}

static void out_of_range_is_refused_and_dst_untouched(void)
{
    unsigned char buf[68 * 68 * 3];
    struct vts_error err;
    memset(buf, 0xEE, sizeof buf);
    VT_CHECK_INT_EQ(vts_decode_tile(store, 2, 0, 0, 0, 0, buf, 68 * 3, sizeof buf, &err),
                    VTS_ERR_RANGE);
    VT_CHECK_STR_CONTAINS(err.message, "no layer 2");
    VT_CHECK_INT_EQ(vts_decode_tile(store, 0, 4, 0, 0, 0, buf, 68 * 3, sizeof buf, &err),
                    VTS_ERR_RANGE);
    VT_CHECK_STR_CONTAINS(err.message, "no level 4 (the store has 4)");
    VT_CHECK_INT_EQ(vts_decode_tile(store, 0, 0, 5, 0, 0, buf, 68 * 3, sizeof buf, &err),
                    VTS_ERR_RANGE);
    VT_CHECK_INT_EQ(vts_decode_region(store, 0, 0, 290, 0, 11, 1, 0, buf, 33, sizeof buf, &err),
                    VTS_ERR_RANGE);
    VT_CHECK_STR_CONTAINS(err.message, "outside level 0 (300x200)");
    VT_CHECK_INT_EQ(
        vts_decode_region(store, 0, 1, 0, UINT32_MAX, 1, 2, 0, buf, 3, sizeof buf, &err),
        VTS_ERR_RANGE);
    VT_CHECK_INT_EQ(buf[0], 0xEE);
    VT_CHECK_INT_EQ(vts_decode_texel_bytes(store, 2), 0);
}

static void bad_buffers_are_refused(void)
{
    unsigned char buf[68 * 68 * 3];
    struct vts_error err;
    VT_CHECK_INT_EQ(vts_decode_tile(store, 0, 0, 0, 0, 0, NULL, 68 * 3, sizeof buf, &err),
                    VTS_ERR_ARG);
    VT_CHECK_INT_EQ(vts_decode_tile(store, 0, 0, 0, 0, 0, buf, 68 * 3 - 1, sizeof buf, &err),
                    VTS_ERR_ARG);
    VT_CHECK_STR_CONTAINS(err.message, "less than a row of 204 bytes");
    VT_CHECK_INT_EQ(vts_decode_tile(store, 0, 0, 0, 0, 0, buf, 68 * 3, sizeof buf - 1, &err),
                    VTS_ERR_LIMIT);
    VT_CHECK_STR_CONTAINS(err.message, "needs 13872 bytes, the buffer holds 13871");
    VT_CHECK_INT_EQ(vts_decode_region(store, 0, 0, 0, 0, 0, 1, 0, buf, 3, sizeof buf, &err),
                    VTS_ERR_ARG);
    VT_CHECK_INT_EQ(
        vts_decode_region(store, 0, 0, 0, 0, 1, 3, 0, buf, SIZE_MAX / 2, SIZE_MAX, &err),
        VTS_ERR_LIMIT);
    VT_CHECK_STR_CONTAINS(err.message, "overflows size_t");
    VT_CHECK_INT_EQ(vts_decode_tile(store, 0, 0, 0, 0, 0, buf, 68 * 3, sizeof buf, NULL), 0);
}

static void a_malformed_payload_names_its_tile(void)
{
    struct vts_store *bad = make_store("bad.vts", VTS_CODEC_RAW, true);
    unsigned char buf[68 * 68 * 3];
    struct vts_error err;
    VT_CHECK_INT_EQ(vts_decode_tile(bad, 0, 1, 0, 0, 0, buf, 68 * 3, sizeof buf, &err),
                    VTS_ERR_BAD_INPUT);
    VT_CHECK_STR_CONTAINS(err.message, "bad.vts': layer 0 level 1 tile 0,0: ");
    VT_CHECK_INT_EQ(vts_decode_region(bad, 0, 1, 60, 0, 10, 10, 0, buf, 30, sizeof buf, &err),
                    VTS_ERR_BAD_INPUT);
    VT_CHECK_INT_EQ(vts_decode_tile(bad, 0, 1, 1, 0, 0, buf, 68 * 3, sizeof buf, &err), 0);
    vts_close(bad);
}

static void an_unknown_codec_is_unsupported(void)
{
    struct vts_store *odd = make_store("odd.vts", VTS_FOURCC('W', 'E', 'B', 'P'), false);
    unsigned char buf[68 * 68 * 2];
    struct vts_error err;
    VT_CHECK_INT_EQ(vts_decode_check(odd, 0, &err), 0);
    VT_CHECK_INT_EQ(vts_decode_check(odd, 1, &err), VTS_ERR_UNSUPPORTED);
    VT_CHECK_STR_CONTAINS(err.message, "layer 1 uses codec 'webp'");
    VT_CHECK_INT_EQ(vts_decode_tile(odd, 1, 0, 0, 0, 0, buf, 68 * 2, sizeof buf, &err),
                    VTS_ERR_UNSUPPORTED);
    VT_CHECK_INT_EQ(vts_decode_check(odd, 2, &err), VTS_ERR_RANGE);
    vts_close(odd);
}

static void version_is_the_projects(void)
{
    VT_CHECK_INT_EQ(vts_decode_version(), VTS_VERSION_NUMBER);
    VT_CHECK_INT_EQ(vts_decode_version(), vts_version());
}

int main(void)
{
    char cmd[300];
    snprintf(tmpdir, sizeof tmpdir, "%s/vts_decode_XXXXXX",
             getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
    if (!mkdtemp(tmpdir))
        return 1;
    store = make_store("s.vts", VTS_CODEC_RAW, false);
    if (store) {
        VT_RUN(tile_with_border_is_the_payload);
        VT_RUN(tile_without_border_is_the_content);
        VT_RUN(empty_tiles_decode_as_zeros);
        VT_RUN(region_is_stitched_from_tiles);
        VT_RUN(a_shifted_region_is_caught);
        VT_RUN(out_of_range_is_refused_and_dst_untouched);
        VT_RUN(bad_buffers_are_refused);
    }
    VT_RUN(a_malformed_payload_names_its_tile);
    VT_RUN(an_unknown_codec_is_unsupported);
    VT_RUN(version_is_the_projects);
    vts_close(store);
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmpdir);
    if (system(cmd) != 0)
        return 1;
    return vt_test_main_result();
}
