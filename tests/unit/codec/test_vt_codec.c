/* Tests of the codec registry, the raw codec and the PNG codec (formats/vt_codec*.c). */
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "codec_test_util.h"
#include "vt_codec.h"
#include "vt_test.h"
#include "vts.h"

/* ---- helpers ---- */

static uint64_t rng_state;

static void rng_seed(uint64_t seed)
{
    rng_state = seed;
}

/* splitmix64: a seeded stream, identical on every machine */
static uint64_t rng_next(void)
{
    uint64_t z = (rng_state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

static void rng_fill(void *buf, size_t len)
{
    unsigned char *p = buf;
    for (size_t i = 0; i < len; i++)
        p[i] = (unsigned char)rng_next();
}

/* An image with stride = tight row + pad bytes, every byte (padding too) pseudo-random. */
static struct vt_image image_make(uint32_t w, uint32_t h, uint32_t channels, uint32_t sample,
                                  size_t pad)
{
    size_t row = (size_t)w * channels * vts_sample_bytes(sample);
    struct vt_image img = {w, h, channels, sample, row + pad, NULL};
    img.pixels = malloc(img.stride * h);
    rng_fill(img.pixels, img.stride * h);
    return img;
}

static size_t image_row_bytes(const struct vt_image *img)
{
    return (size_t)img->width * img->channels * vts_sample_bytes(img->sample);
}

/* True when the texels (not the padding) of a and b are equal. */
static bool image_equal(const struct vt_image *a, const struct vt_image *b)
{
    if (a->width != b->width || a->height != b->height || a->channels != b->channels ||
        a->sample != b->sample)
        return false;
    for (uint32_t y = 0; y < a->height; y++)
        if (memcmp((const char *)a->pixels + y * a->stride, (const char *)b->pixels + y * b->stride,
                   image_row_bytes(a)) != 0)
            return false;
    return true;
}

/* Decodes payload into a fresh image of the given shape (pad bytes of padding, preset to 0xcd). */
static int decode_into(const struct vt_codec *codec, const void *payload, size_t len,
                       struct vt_image *dst, uint32_t w, uint32_t h, uint32_t channels,
                       uint32_t sample, struct vts_error *err)
{
    size_t row = (size_t)w * channels * vts_sample_bytes(sample);
    *dst = (struct vt_image){w, h, channels, sample, row + 5, NULL};
    dst->pixels = malloc(dst->stride * h);
    memset(dst->pixels, 0xcd, dst->stride * h);
    return codec->decode(payload, len, dst, err);
}

/* Copy of the first len bytes in a fresh allocation of exactly len, so ASan sees over-reads. */
static unsigned char *dup_prefix(const unsigned char *src, size_t len)
{
    unsigned char *p = malloc(len ? len : 1);
    memcpy(p, src, len);
    return p;
}

/* ---- registry ---- */

static void registry_finds_codecs_by_name_and_fourcc(void)
{
    const struct vt_codec *raw = vt_codec_find("raw"), *png = vt_codec_find("png");
    VT_CHECK(raw && raw->fourcc == VTS_CODEC_RAW && raw->lossless);
    VT_CHECK(png && png->fourcc == VTS_CODEC_PNG && png->lossless);
    VT_CHECK(vt_codec_by_fourcc(VTS_CODEC_RAW) == raw);
    VT_CHECK(vt_codec_by_fourcc(VTS_CODEC_PNG) == png);
    VT_CHECK(vt_codec_find("nope") == NULL);
    VT_CHECK(vt_codec_find("RAW") == NULL);
    VT_CHECK(vt_codec_find("") == NULL);
    VT_CHECK(vt_codec_find(NULL) == NULL);
    VT_CHECK(vt_codec_by_fourcc(VTS_FOURCC('Z', 'Z', 'Z', 'Z')) == NULL);
    VT_CHECK(vt_codec_by_fourcc(0) == NULL);
}

static void registry_lists_each_codec_once(void)
{
    size_t count = 0;
    const struct vt_codec *const *list = vt_codec_list(&count);
    VT_CHECK(count >= 2);
    VT_CHECK(list[0] == vt_codec_find("raw"));
    for (size_t i = 0; i < count; i++) {
        VT_CHECK(vt_codec_find(list[i]->name) == list[i]);
        VT_CHECK(vt_codec_by_fourcc(list[i]->fourcc) == list[i]);
        VT_CHECK(list[i]->summary && list[i]->check && list[i]->encoded_bound && list[i]->encode &&
                 list[i]->decode);
        for (size_t j = 0; j < i; j++)
            VT_CHECK(list[j]->fourcc != list[i]->fourcc);
    }
}

/* ---- raw ---- */

static void raw_round_trips_every_channel_count_and_sample(void)
{
    const struct vt_codec *raw = vt_codec_find("raw");
    rng_seed(1);
    for (uint32_t channels = 1; channels <= 4; channels++) {
        for (uint32_t sample = VTS_SAMPLE_U8; sample <= VTS_SAMPLE_F32; sample++) {
            struct vts_error err = {0};
            VT_CHECK_INT_EQ(raw->check(264, channels, sample, &err), 0);
            struct vt_image src = image_make(7, 5, channels, sample, 13);
            size_t row = image_row_bytes(&src), len = 0;
            VT_CHECK_INT_EQ(raw->encoded_bound(7, 5, channels, sample), row * 5);
            unsigned char *payload = encode_alloc(raw, &src, 0, &len);
            VT_CHECK_INT_EQ(len, row * 5);
            /* the payload is the rows, tight, top first (samples little-endian on this host) */
            for (uint32_t y = 0; payload && y < 5; y++)
                VT_CHECK(memcmp(payload + y * row, (char *)src.pixels + y * src.stride, row) == 0);
            struct vt_image dst;
            VT_CHECK_INT_EQ(decode_into(raw, payload, len, &dst, 7, 5, channels, sample, &err), 0);
            VT_CHECK(image_equal(&src, &dst));
            for (uint32_t y = 0; y < 5; y++) /* the padding of dst is left alone */
                VT_CHECK(((unsigned char *)dst.pixels)[y * dst.stride + row] == 0xcd);
            free(payload);
            free(dst.pixels);
            free(src.pixels);
        }
    }
}

static void raw_stores_samples_little_endian(void)
{
    const struct vt_codec *raw = vt_codec_find("raw");
    uint16_t texels[2] = {0x0102, 0xa0b0};
    struct vt_image src = {2, 1, 1, VTS_SAMPLE_U16, sizeof texels, texels};
    unsigned char payload[4];
    size_t len = 0;
    VT_CHECK_INT_EQ(raw->encode(&src, NULL, payload, sizeof payload, &len, NULL), 0);
    VT_CHECK_INT_EQ(len, 4);
    VT_CHECK(payload[0] == 0x02 && payload[1] == 0x01 && payload[2] == 0xb0 && payload[3] == 0xa0);
}

static void raw_rejects_payload_of_wrong_size(void)
{
    const struct vt_codec *raw = vt_codec_find("raw");
    rng_seed(2);
    struct vt_image src = image_make(16, 16, 4, VTS_SAMPLE_U8, 0);
    size_t len = 0;
    unsigned char *payload = encode_alloc(raw, &src, 0, &len);
    struct vts_error err = {0};
    struct vt_image dst;
    VT_CHECK_INT_EQ(decode_into(raw, payload, len - 1, &dst, 16, 16, 4, VTS_SAMPLE_U8, &err),
                    VTS_ERR_BAD_INPUT);
    VT_CHECK_STR_CONTAINS(err.message, "1023");
    VT_CHECK_STR_CONTAINS(err.message, "1024");
    free(dst.pixels);
    unsigned char *longer = calloc(1, len + 1);
    VT_CHECK_INT_EQ(decode_into(raw, longer, len + 1, &dst, 16, 16, 4, VTS_SAMPLE_U8, &err),
                    VTS_ERR_BAD_INPUT);
    VT_CHECK_STR_CONTAINS(err.message, "1025");
    free(dst.pixels);
    VT_CHECK_INT_EQ(decode_into(raw, payload, len, &dst, 16, 16, 3, VTS_SAMPLE_U8, &err),
                    VTS_ERR_BAD_INPUT);
    free(dst.pixels);
    VT_CHECK_INT_EQ(decode_into(raw, NULL, 0, &dst, 16, 16, 4, VTS_SAMPLE_U8, &err),
                    VTS_ERR_BAD_INPUT);
    free(dst.pixels);
    free(longer);
    free(payload);
    free(src.pixels);
}

static void raw_refuses_bad_shapes_and_small_buffers(void)
{
    const struct vt_codec *raw = vt_codec_find("raw");
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(raw->check(256, 0, VTS_SAMPLE_U8, &err), VTS_ERR_UNSUPPORTED);
    VT_CHECK_INT_EQ(raw->check(256, 5, VTS_SAMPLE_U8, &err), VTS_ERR_UNSUPPORTED);
    VT_CHECK_INT_EQ(raw->check(256, 4, 0, &err), VTS_ERR_UNSUPPORTED);
    VT_CHECK_INT_EQ(raw->check(256, 4, 9, &err), VTS_ERR_UNSUPPORTED);
    VT_CHECK_INT_EQ(raw->check(16384, 4, VTS_SAMPLE_F32, &err), VTS_ERR_UNSUPPORTED); /* 4 GiB */
    VT_CHECK_INT_EQ(raw->check(16384, 4, VTS_SAMPLE_F16, &err), 0);
    VT_CHECK_INT_EQ(raw->encoded_bound(8, 8, 5, VTS_SAMPLE_U8), 0);
    VT_CHECK_INT_EQ(raw->encoded_bound(0, 8, 4, VTS_SAMPLE_U8), 0);
    rng_seed(3);
    struct vt_image src = image_make(8, 8, 2, VTS_SAMPLE_F16, 0);
    unsigned char buf[8 * 8 * 4];
    size_t len = 99;
    VT_CHECK_INT_EQ(raw->encode(&src, NULL, buf, sizeof buf - 1, &len, &err), VTS_ERR_LIMIT);
    VT_CHECK_INT_EQ(len, 0);
    src.stride = 8 * 4 - 1;
    VT_CHECK_INT_EQ(raw->encode(&src, NULL, buf, sizeof buf, &len, &err), VTS_ERR_ARG);
    free(src.pixels);
}

/* ---- png ---- */

static void png_round_trips_exactly(void)
{
    static const uint32_t sizes[][2] = {{1, 1}, {3, 5}, {264, 264}};
    const struct vt_codec *png = vt_codec_find("png");
    rng_seed(4);
    for (size_t s = 0; s < sizeof sizes / sizeof sizes[0]; s++) {
        for (uint32_t channels = 1; channels <= 4; channels++) {
            for (uint32_t sample = VTS_SAMPLE_U8; sample <= VTS_SAMPLE_U16; sample++) {
                uint32_t w = sizes[s][0], h = sizes[s][1];
                struct vts_error err = {0};
                VT_CHECK_INT_EQ(png->check(w, channels, sample, &err), 0);
                struct vt_image src = image_make(w, h, channels, sample, 3);
                size_t len = 0;
                unsigned char *payload = encode_alloc(png, &src, (int)(s + channels) % 10, &len);
                struct vt_image dst;
                int rc = decode_into(png, payload, len, &dst, w, h, channels, sample, &err);
                VT_CHECK_INT_EQ(rc, 0);
                if (rc)
                    fprintf(stderr, "  %ux%u x%u %s: %s\n", w, h, channels, vts_sample_name(sample),
                            err.message);
                VT_CHECK(image_equal(&src, &dst));
                free(dst.pixels);
                free(payload);
                free(src.pixels);
            }
        }
    }
}

static void png_noise_fits_the_bound_at_every_effort(void)
{
    const struct vt_codec *png = vt_codec_find("png");
    rng_seed(5);
    struct vt_image src = image_make(264, 264, 4, VTS_SAMPLE_U16, 0);
    for (int effort = 0; effort <= 9; effort++) {
        size_t len = 0;
        unsigned char *payload = encode_alloc(png, &src, effort, &len);
        struct vt_image dst;
        struct vts_error err = {0};
        VT_CHECK_INT_EQ(decode_into(png, payload, len, &dst, 264, 264, 4, VTS_SAMPLE_U16, &err), 0);
        VT_CHECK(image_equal(&src, &dst));
        free(dst.pixels);
        free(payload);
    }
    free(src.pixels);
}

static void png_encode_refuses_small_buffer_and_bad_effort(void)
{
    const struct vt_codec *png = vt_codec_find("png");
    rng_seed(6);
    struct vt_image src = image_make(33, 17, 3, VTS_SAMPLE_U8, 0);
    size_t len = 0, len2 = 99;
    unsigned char *payload = encode_alloc(png, &src, 1, &len);
    struct vts_error err = {0};
    unsigned char *small = malloc(len - 1);
    VT_CHECK_INT_EQ(png->encode(&src, NULL, small, len - 1, &len2, &err), VTS_ERR_LIMIT);
    VT_CHECK_INT_EQ(len2, 0);
    VT_CHECK_STR_CONTAINS(err.message, "png encode");
    VT_CHECK_INT_EQ(png->encode(&src, NULL, small, 0, &len2, &err), VTS_ERR_LIMIT);
    struct vt_codec_params params = {.effort = 10};
    VT_CHECK_INT_EQ(png->encode(&src, &params, payload, len, &len2, &err), VTS_ERR_ARG);
    params.effort = -1;
    VT_CHECK_INT_EQ(png->encode(&src, &params, payload, len, &len2, &err), VTS_ERR_ARG);
    free(small);
    free(payload);
    free(src.pixels);
}

static void png_refuses_float_samples(void)
{
    const struct vt_codec *png = vt_codec_find("png");
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(png->check(256, 4, VTS_SAMPLE_F16, &err), VTS_ERR_UNSUPPORTED);
    VT_CHECK_STR_CONTAINS(err.message, "f16");
    VT_CHECK_STR_CONTAINS(err.message, "use raw");
    VT_CHECK_INT_EQ(png->check(256, 1, VTS_SAMPLE_F32, &err), VTS_ERR_UNSUPPORTED);
    VT_CHECK_STR_CONTAINS(err.message, "use raw");
    VT_CHECK_INT_EQ(png->check(256, 5, VTS_SAMPLE_U8, &err), VTS_ERR_UNSUPPORTED);
    VT_CHECK_INT_EQ(png->check(256, 0, VTS_SAMPLE_U8, &err), VTS_ERR_UNSUPPORTED);
    VT_CHECK_INT_EQ(png->encoded_bound(256, 256, 4, VTS_SAMPLE_F32), 0);
    rng_seed(7);
    struct vt_image src = image_make(4, 4, 4, VTS_SAMPLE_F16, 0);
    unsigned char buf[4096];
    size_t len;
    VT_CHECK_INT_EQ(png->encode(&src, NULL, buf, sizeof buf, &len, &err), VTS_ERR_UNSUPPORTED);
    VT_CHECK_INT_EQ(png->decode(buf, sizeof buf, &src, &err), VTS_ERR_UNSUPPORTED);
    free(src.pixels);
}

/* Decodes the first cut bytes of payload (a fresh allocation); true when it fails cleanly. */
static bool png_prefix_fails_cleanly(const unsigned char *payload, size_t cut, size_t len)
{
    unsigned char *prefix = dup_prefix(payload, cut);
    struct vt_image dst;
    struct vts_error err = {0};
    int rc = decode_into(vt_codec_find("png"), prefix, cut, &dst, 33, 17, 4, VTS_SAMPLE_U16, &err);
    bool clean = rc == VTS_ERR_BAD_INPUT && strncmp(err.message, "png payload: ", 13) == 0;
    if (!clean)
        fprintf(stderr, "  cut %zu of %zu: rc %d '%s'\n", cut, len, rc, err.message);
    free(dst.pixels);
    free(prefix);
    return clean;
}

static void png_decode_rejects_truncated_payloads(void)
{
    rng_seed(8);
    struct vt_image src = image_make(33, 17, 4, VTS_SAMPLE_U16, 0);
    size_t len = 0;
    unsigned char *payload = encode_alloc(vt_codec_find("png"), &src, 1, &len);
    int failures = 0;
    for (size_t cut = 0; cut < len; cut += 7)
        failures += !png_prefix_fails_cleanly(payload, cut, len);
    for (size_t cut = len - 12; cut < len; cut++) /* inside IEND */
        failures += !png_prefix_fails_cleanly(payload, cut, len);
    VT_CHECK_INT_EQ(failures, 0);
    free(payload);
    free(src.pixels);
}

/* Encodes a w x h tile and decodes it as a tile of another shape: must fail with expect. */
static void check_shape_mismatch(uint32_t w, uint32_t h, uint32_t channels, uint32_t sample,
                                 uint32_t tw, uint32_t th, uint32_t tchannels, uint32_t tsample,
                                 const char *expect)
{
    const struct vt_codec *png = vt_codec_find("png");
    struct vt_image src = image_make(w, h, channels, sample, 0);
    size_t len = 0;
    unsigned char *payload = encode_alloc(png, &src, 1, &len);
    struct vt_image dst;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(decode_into(png, payload, len, &dst, tw, th, tchannels, tsample, &err),
                    VTS_ERR_BAD_INPUT);
    VT_CHECK_STR_CONTAINS(err.message, expect);
    free(dst.pixels);
    free(payload);
    free(src.pixels);
}

static void png_decode_rejects_other_shapes(void)
{
    rng_seed(9);
    check_shape_mismatch(300, 264, 4, VTS_SAMPLE_U8, 264, 264, 4, VTS_SAMPLE_U8,
                         "png payload: width 300 != tile 264");
    check_shape_mismatch(8, 9, 4, VTS_SAMPLE_U8, 8, 8, 4, VTS_SAMPLE_U8, "height 9 != tile 8");
    check_shape_mismatch(8, 8, 3, VTS_SAMPLE_U8, 8, 8, 4, VTS_SAMPLE_U8, "3 channels != tile 4");
    check_shape_mismatch(8, 8, 2, VTS_SAMPLE_U16, 8, 8, 2, VTS_SAMPLE_U8, "bit depth 16 != tile 8");
}

static void png_decode_rejects_garbage_and_trailing_bytes(void)
{
    const struct vt_codec *png = vt_codec_find("png");
    static const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    rng_seed(10);
    int failures = 0;
    for (size_t len = 0; len < 400; len += 3) {
        unsigned char *junk = malloc(len + 1);
        rng_fill(junk, len);
        if (len >= 8 && len % 2) /* half of them get past the signature check */
            memcpy(junk, signature, 8);
        struct vt_image dst;
        struct vts_error err = {0};
        if (decode_into(png, junk, len, &dst, 8, 8, 4, VTS_SAMPLE_U8, &err) != VTS_ERR_BAD_INPUT)
            failures++;
        free(dst.pixels);
        free(junk);
    }
    VT_CHECK_INT_EQ(failures, 0);
    struct vt_image src = image_make(8, 8, 1, VTS_SAMPLE_U8, 0);
    size_t len = 0;
    unsigned char *payload = encode_alloc(png, &src, 1, &len);
    unsigned char *longer = calloc(1, len + 1);
    memcpy(longer, payload, len);
    struct vt_image dst;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(decode_into(png, longer, len + 1, &dst, 8, 8, 1, VTS_SAMPLE_U8, &err),
                    VTS_ERR_BAD_INPUT);
    VT_CHECK_STR_CONTAINS(err.message, "1 bytes after IEND");
    free(dst.pixels);
    free(longer);
    free(payload);
    free(src.pixels);
}

static uint32_t crc32_png(const unsigned char *p, size_t len)
{
    uint32_t crc = 0xffffffffu;
    for (size_t i = 0; i < len; i++) {
        crc ^= p[i];
        for (int k = 0; k < 8; k++)
            crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1)));
    }
    return ~crc;
}

/* Rewrites the CRC of every chunk whose length stays inside the buffer. */
static void png_fix_crcs(unsigned char *p, size_t len)
{
    size_t pos = 8;
    while (pos + 12 <= len) {
        uint32_t n =
            (uint32_t)p[pos] << 24 | (uint32_t)p[pos + 1] << 16 | p[pos + 2] << 8 | p[pos + 3];
        if (n > len - pos - 12)
            return;
        uint32_t crc = crc32_png(p + pos + 4, n + 4);
        for (int b = 0; b < 4; b++)
            p[pos + 8 + n + b] = (unsigned char)(crc >> (24 - 8 * b));
        pos += 12 + (size_t)n;
    }
}

static void png_decode_survives_mutations_with_valid_crcs(void)
{
    const struct vt_codec *png = vt_codec_find("png");
    rng_seed(11);
    struct vt_image src = image_make(20, 12, 2, VTS_SAMPLE_U8, 0);
    size_t len = 0;
    unsigned char *payload = encode_alloc(png, &src, 1, &len);
    int bad_status = 0, decoded = 0;
    for (int i = 0; i < 3000; i++) {
        unsigned char *copy = dup_prefix(payload, len);
        for (int flips = 1 + i % 3; flips > 0; flips--)
            copy[8 + rng_next() % (len - 8)] ^= (unsigned char)(1u << (rng_next() % 8));
        png_fix_crcs(copy, len);
        struct vt_image dst;
        struct vts_error err = {0};
        int rc = decode_into(png, copy, len, &dst, 20, 12, 2, VTS_SAMPLE_U8, &err);
        decoded += rc == 0;
        bad_status += rc != 0 && rc != VTS_ERR_BAD_INPUT;
        free(dst.pixels);
        free(copy);
    }
    VT_CHECK_INT_EQ(bad_status, 0);
    VT_CHECK(decoded < 3000); /* the mutations were noticed at least sometimes */
    free(payload);
    free(src.pixels);
}

static uint32_t be32(const unsigned char *p)
{
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

/* Walks the chunks of payload: counts IDATs (each at most 256 KiB) and bad CRCs; true when it is
 * signature, IHDR (w x h, depth, colour type, no interlace), IDAT..., IEND, nothing after. */
static bool png_chunks_valid(const unsigned char *p, size_t len, uint32_t w, uint32_t h,
                             unsigned depth, unsigned colour_type, int *idats, int *bad_crcs)
{
    static const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    *idats = *bad_crcs = 0;
    if (len < 8 + 25 + 12 || memcmp(p, signature, 8) != 0 || be32(p + 8) != 13 ||
        memcmp(p + 12, "IHDR", 4) != 0 || be32(p + 16) != w || be32(p + 20) != h ||
        p[24] != depth || p[25] != colour_type || p[26] || p[27] || p[28])
        return false;
    size_t pos = 8;
    bool iend = false;
    while (pos + 12 <= len && !iend) {
        uint32_t n = be32(p + pos);
        if (n > len - pos - 12)
            return false;
        *bad_crcs += crc32_png(p + pos + 4, n + 4) != be32(p + pos + 8 + n);
        if (memcmp(p + pos + 4, "IDAT", 4) == 0)
            *idats += n <= (1u << 18) ? 1 : 1000;
        iend = memcmp(p + pos + 4, "IEND", 4) == 0 && n == 0;
        pos += 12 + (size_t)n;
    }
    return iend && pos == len;
}

static void png_payload_is_a_plain_png_with_idats_cut_at_256k(void)
{
    const struct vt_codec *png = vt_codec_find("png");
    rng_seed(12);
    struct vt_image src = image_make(264, 264, 4, VTS_SAMPLE_U16, 0); /* 558 KB, incompressible */
    int idats = 0, bad_crcs = 0;
    for (int effort = 1; effort <= 9; effort += 8) {
        size_t len = 0;
        unsigned char *payload = encode_alloc(png, &src, effort, &len);
        VT_CHECK(png_chunks_valid(payload, len, 264, 264, 16, 6, &idats, &bad_crcs));
        VT_CHECK_INT_EQ(idats, 3);
        VT_CHECK_INT_EQ(bad_crcs, 0);
        /* a byte changed in the middle IDAT: the walk and the decoder both notice */
        payload[8 + 25 + 12 + (1u << 18) + 100] ^= 0x10;
        VT_CHECK(png_chunks_valid(payload, len, 264, 264, 16, 6, &idats, &bad_crcs));
        VT_CHECK_INT_EQ(bad_crcs, 1);
        struct vt_image dst;
        struct vts_error err = {0};
        VT_CHECK_INT_EQ(decode_into(png, payload, len, &dst, 264, 264, 4, VTS_SAMPLE_U16, &err),
                        VTS_ERR_BAD_INPUT);
        free(dst.pixels);
        free(payload);
    }
    free(src.pixels);
    struct vt_image grey = image_make(5, 3, 1, VTS_SAMPLE_U8, 2);
    size_t len = 0;
    unsigned char *payload = encode_alloc(png, &grey, 0, &len);
    VT_CHECK(png_chunks_valid(payload, len, 5, 3, 8, 0, &idats, &bad_crcs));
    VT_CHECK(idats == 1 && bad_crcs == 0);
    VT_CHECK(!png_chunks_valid(payload, len, 5, 3, 8, 2, &idats, &bad_crcs)); /* not RGB */
    free(payload);
    free(grey.pixels);
}

/* 2x1 16-bit gray, samples 0x0102 and 0xa0b0 (written by a Python script, not by libpng). */
static const unsigned char fixture_gray16_2x1[] = {
    0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48,
    0x44, 0x52, 0x00, 0x00, 0x00, 0x02, 0x00, 0x00, 0x00, 0x01, 0x10, 0x00, 0x00, 0x00,
    0x00, 0x81, 0xd9, 0xfc, 0x15, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x44, 0x41, 0x54, 0x78,
    0x9c, 0x63, 0x60, 0x64, 0x5a, 0xb0, 0x01, 0x00, 0x01, 0xff, 0x01, 0x54, 0x8e, 0x7d,
    0x8e, 0x40, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};

/* 5x5 RGB8, Adam7-interlaced; texel (x, y) = (40x + 7y, 50y, x + y). */
static const unsigned char fixture_adam7_rgb8_5x5[] = {
    0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44, 0x52,
    0x00, 0x00, 0x00, 0x05, 0x00, 0x00, 0x00, 0x05, 0x08, 0x02, 0x00, 0x00, 0x01, 0x75, 0x0a, 0x81,
    0x24, 0x00, 0x00, 0x00, 0x5e, 0x49, 0x44, 0x41, 0x54, 0x78, 0x9c, 0x63, 0x60, 0x00, 0x82, 0x05,
    0x0c, 0x2c, 0x0c, 0x32, 0x27, 0x58, 0xf6, 0x9c, 0xe0, 0x60, 0x08, 0x60, 0x60, 0x62, 0xc8, 0x39,
    0xc1, 0xc6, 0xc0, 0x97, 0xc2, 0x14, 0x97, 0xc2, 0xb2, 0x2e, 0x85, 0x8d, 0x41, 0x83, 0x81, 0xb1,
    0x82, 0x81, 0x99, 0xc1, 0x2c, 0x85, 0xb9, 0x2d, 0x85, 0x95, 0xc1, 0xe5, 0x04, 0xeb, 0x94, 0x13,
    0xec, 0x0c, 0xec, 0x46, 0x8c, 0xfa, 0x46, 0x4c, 0xe1, 0x46, 0xcc, 0xf5, 0x46, 0x2c, 0xcb, 0x8d,
    0x58, 0x19, 0x44, 0xa7, 0x31, 0xdb, 0x4e, 0x63, 0x49, 0x9d, 0xc6, 0xda, 0x3b, 0x8d, 0x6d, 0xeb,
    0x34, 0x76, 0x00, 0xf3, 0xe3, 0x13, 0x57, 0xd0, 0x9e, 0x24, 0x75, 0x00, 0x00, 0x00, 0x00, 0x49,
    0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};

static void png_decodes_foreign_16bit_and_interlaced_payloads(void)
{
    const struct vt_codec *png = vt_codec_find("png");
    struct vt_image dst;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(decode_into(png, fixture_gray16_2x1, sizeof fixture_gray16_2x1, &dst, 2, 1, 1,
                                VTS_SAMPLE_U16, &err),
                    0);
    const uint16_t *gray = dst.pixels;
    VT_CHECK(gray[0] == 0x0102 && gray[1] == 0xa0b0); /* host order */
    free(dst.pixels);
    VT_CHECK_INT_EQ(decode_into(png, fixture_adam7_rgb8_5x5, sizeof fixture_adam7_rgb8_5x5, &dst, 5,
                                5, 3, VTS_SAMPLE_U8, &err),
                    0);
    int wrong = 0;
    for (uint32_t y = 0; y < 5; y++)
        for (uint32_t x = 0; x < 5; x++) {
            const unsigned char *t = (const unsigned char *)dst.pixels + y * dst.stride + x * 3;
            wrong += t[0] != 40 * x + 7 * y || t[1] != 50 * y || t[2] != x + y;
        }
    VT_CHECK_INT_EQ(wrong, 0);
    free(dst.pixels);
}

int main(void)
{
    VT_RUN(registry_finds_codecs_by_name_and_fourcc);
    VT_RUN(registry_lists_each_codec_once);
    VT_RUN(raw_round_trips_every_channel_count_and_sample);
    VT_RUN(raw_stores_samples_little_endian);
    VT_RUN(raw_rejects_payload_of_wrong_size);
    VT_RUN(raw_refuses_bad_shapes_and_small_buffers);
    VT_RUN(png_round_trips_exactly);
    VT_RUN(png_noise_fits_the_bound_at_every_effort);
    VT_RUN(png_encode_refuses_small_buffer_and_bad_effort);
    VT_RUN(png_refuses_float_samples);
    VT_RUN(png_decode_rejects_truncated_payloads);
    VT_RUN(png_decode_rejects_other_shapes);
    VT_RUN(png_decode_rejects_garbage_and_trailing_bytes);
    VT_RUN(png_decode_survives_mutations_with_valid_crcs);
    VT_RUN(png_payload_is_a_plain_png_with_idats_cut_at_256k);
    VT_RUN(png_decodes_foreign_16bit_and_interlaced_payloads);
    return vt_test_main_result();
}
