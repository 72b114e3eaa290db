/* Tests of the bc1 and bc3 tile codecs (formats/codec/vt_codec_bc.c,
 * formats/codec/vt_squish_shim.cpp): the decoder on hand-computed blocks and against libsquish, the
 * payload layout, round trips, refusals and threads. Our encoder's own tests are
 * test_vt_bc_encode.c. */
#include <dirent.h>
#include <math.h>
#include <pthread.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "bc_test_util.h"
#include "internal/vt_squish_shim.h"
#include "vt_codec.h"
#include "vt_synth_photo.h"
#include "vt_test.h"
#include "vts.h"

/* ---- helpers ---- */

/* Counts texels of a 16-texel block that differ from expect[index[i]]. */
static int block_mismatches(unsigned char texels[16][4], const unsigned char expect[][4],
                            const unsigned char index[16])
{
    int wrong = 0;
    for (int i = 0; i < 16; i++) {
        if (memcmp(texels[i], expect[index[i]], 4) != 0) {
            fprintf(stderr, "  texel %d: %u %u %u %u, expected %u %u %u %u\n", i, texels[i][0],
                    texels[i][1], texels[i][2], texels[i][3], expect[index[i]][0],
                    expect[index[i]][1], expect[index[i]][2], expect[index[i]][3]);
            wrong++;
        }
    }
    return wrong;
}

/* Copy of the first len bytes in a fresh allocation of exactly len, so ASan sees over-reads. */
static unsigned char *dup_prefix(const unsigned char *src, size_t len)
{
    unsigned char *p = malloc(len ? len : 1);
    memcpy(p, src, len);
    return p;
}

/* ---- hand-computed blocks ----
 * Endpoints used below, RGB565 -> RGB888 by bit replication (x5 << 3 | x5 >> 2, g6 << 2 | g6 >> 4):
 *   0xa505 = r 20, g 40, b 5  -> (165, 162, 41)
 *   0x193e = r 3,  g 9,  b 30 -> (24, 36, 247)
 * Colour indices bytes e4 1b 00 ff: texels 0..3 use 0,1,2,3; 4..7 use 3,2,1,0; 8..11 use 0;
 * 12..15 use 3 (2 bits per texel, texel 0 in the low bits of byte 4). */
static const unsigned char colour_index[16] = {0, 1, 2, 3, 3, 2, 1, 0, 0, 0, 0, 0, 3, 3, 3, 3};

static void bc1_decodes_four_colour_block_by_hand(void)
{
    /* c0 = 0xa505 > c1 = 0x193e: c2 = (2 c0 + c1) / 3, c3 = (c0 + 2 c1) / 3, truncated:
     * c2 = ((330 + 24) / 3, (324 + 36) / 3, (82 + 247) / 3) = (118, 120, 109)  [329/3 = 109.7]
     * c3 = ((165 + 48) / 3, (162 + 72) / 3, (41 + 494) / 3) = (71, 78, 178)   [535/3 = 178.3] */
    static const unsigned char block[8] = {0x05, 0xa5, 0x3e, 0x19, 0xe4, 0x1b, 0x00, 0xff};
    static const unsigned char expect[4][4] = {
        {165, 162, 41, 255}, {24, 36, 247, 255}, {118, 120, 109, 255}, {71, 78, 178, 255}};
    unsigned char texels[16][4];
    VT_CHECK_INT_EQ(decode_block("bc1", block, 8, texels), 0);
    VT_CHECK_INT_EQ(block_mismatches(texels, expect, colour_index), 0);
}

static void bc1_decodes_three_colour_transparent_block_by_hand(void)
{
    /* c0 = 0x193e <= c1 = 0xa505: c2 = (c0 + c1) / 2 truncated, c3 = transparent black:
     * c2 = ((24 + 165) / 2, (36 + 162) / 2, (247 + 41) / 2) = (94, 99, 144)  [189/2 = 94.5] */
    static const unsigned char block[8] = {0x3e, 0x19, 0x05, 0xa5, 0xe4, 0x1b, 0x00, 0xff};
    static const unsigned char expect[4][4] = {
        {24, 36, 247, 255}, {165, 162, 41, 255}, {94, 99, 144, 255}, {0, 0, 0, 0}};
    unsigned char texels[16][4];
    VT_CHECK_INT_EQ(decode_block("bc1", block, 8, texels), 0);
    VT_CHECK_INT_EQ(block_mismatches(texels, expect, colour_index), 0);
    /* c0 == c1 is the 3-colour mode too: index 3 is transparent */
    static const unsigned char equal[8] = {0x05, 0xa5, 0x05, 0xa5, 0xff, 0xff, 0xff, 0xff};
    VT_CHECK_INT_EQ(decode_block("bc1", equal, 8, texels), 0);
    static const unsigned char transparent[1][4] = {{0, 0, 0, 0}};
    static const unsigned char zeros[16] = {0};
    VT_CHECK_INT_EQ(block_mismatches(texels, transparent, zeros), 0);
    /* an RGB tile gets the black of the transparent texels */
    struct vt_image rgb;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(decode_into(vt_codec_find("bc1"), block, 8, &rgb, 4, 4, 3, &err), 0);
    const unsigned char *t = (const unsigned char *)rgb.pixels + 3 * rgb.stride + 3 * 3;
    VT_CHECK(t[0] == 0 && t[1] == 0 && t[2] == 0);
    t = (const unsigned char *)rgb.pixels + 0 * rgb.stride + 2 * 3;
    VT_CHECK(t[0] == 94 && t[1] == 99 && t[2] == 144);
    VT_CHECK(((unsigned char *)rgb.pixels)[12] == 0xcd); /* padding untouched */
    free(rgb.pixels);
}

static void bc3_decodes_eight_alpha_block_by_hand(void)
{
    /* a0 = 200 > a1 = 10: a[1 + i] = ((7 - i) a0 + i a1) / 7, truncated, i = 1..6:
     * 1210/7 = 172.9, 1020/7 = 145.7, 830/7 = 118.6, 640/7 = 91.4, 450/7 = 64.3, 260/7 = 37.1.
     * Alpha indices (3 bits per texel from byte 2): texel i uses i % 8.
     * The colour half has c0 = 0x193e < c1 = 0xa505 and must still decode in 4-colour mode:
     * c2 = (2 c0 + c1) / 3 = (71, 78, 178), c3 = (c0 + 2 c1) / 3 = (118, 120, 109). */
    static const unsigned char block[16] = {200,  10,   0x88, 0xc6, 0xfa, 0x88, 0xc6, 0xfa,
                                            0x3e, 0x19, 0x05, 0xa5, 0xe4, 0x1b, 0x00, 0xff};
    static const unsigned char alpha[8] = {200, 10, 172, 145, 118, 91, 64, 37};
    static const unsigned char rgb[4][3] = {
        {24, 36, 247}, {165, 162, 41}, {71, 78, 178}, {118, 120, 109}};
    unsigned char texels[16][4];
    VT_CHECK_INT_EQ(decode_block("bc3", block, 16, texels), 0);
    int wrong = 0;
    for (int i = 0; i < 16; i++)
        wrong += memcmp(texels[i], rgb[colour_index[i]], 3) != 0 || texels[i][3] != alpha[i % 8];
    VT_CHECK_INT_EQ(wrong, 0);
}

static void bc3_decodes_six_alpha_block_by_hand(void)
{
    /* a0 = 41 <= a1 = 243: a[1 + i] = ((5 - i) a0 + i a1) / 5, truncated, i = 1..4, a6 = 0,
     * a7 = 255: 407/5 = 81.4, 609/5 = 121.8, 811/5 = 162.2, 1013/5 = 202.6.
     * Alpha indices: texels 0..7 use 0..7, texels 8..15 use 7..0. */
    static const unsigned char block[16] = {41,   243,  0x88, 0xc6, 0xfa, 0x77, 0x39, 0x05,
                                            0x05, 0xa5, 0x3e, 0x19, 0xe4, 0x1b, 0x00, 0xff};
    static const unsigned char alpha[8] = {41, 243, 81, 121, 162, 202, 0, 255};
    static const unsigned char rgb[4][3] = {
        {165, 162, 41}, {24, 36, 247}, {118, 120, 109}, {71, 78, 178}};
    unsigned char texels[16][4];
    VT_CHECK_INT_EQ(decode_block("bc3", block, 16, texels), 0);
    int wrong = 0;
    for (int i = 0; i < 16; i++)
        wrong += memcmp(texels[i], rgb[colour_index[i]], 3) != 0 ||
                 texels[i][3] != alpha[i < 8 ? i : 15 - i];
    VT_CHECK_INT_EQ(wrong, 0);
}

static void bc_decoder_agrees_with_libsquish_on_random_blocks(void)
{
    rng_state = 41;
    int bc1_wrong = 0, bc3_wrong = 0;
    for (int n = 0; n < 20000; n++) {
        unsigned char block[16], ours[16][4], theirs[16][4];
        uint64_t a = rng_next(), b = rng_next();
        memcpy(block, &a, 8);
        memcpy(block + 8, &b, 8);
        if (n % 4 == 0) /* a0 == a1 and c0 == c1 now and then */
            block[1] = block[0], block[10] = block[8], block[11] = block[9];
        VT_CHECK_INT_EQ(decode_block("bc1", block, 8, ours), 0);
        VT_CHECK_INT_EQ(vt_squish_shim_decompress_block(block, 0, &theirs[0][0]), 0);
        bc1_wrong += memcmp(ours, theirs, sizeof ours) != 0;
        VT_CHECK_INT_EQ(decode_block("bc3", block, 16, ours), 0);
        VT_CHECK_INT_EQ(vt_squish_shim_decompress_block(block, VT_SQUISH_SHIM_BC3, &theirs[0][0]),
                        0);
        bc3_wrong += memcmp(ours, theirs, sizeof ours) != 0;
    }
    VT_CHECK_INT_EQ(bc1_wrong, 0);
    VT_CHECK_INT_EQ(bc3_wrong, 0);
}

/* ---- payload layout ---- */

static void bc_payload_is_blocks_row_major(void)
{
    /* a 12x8 tile whose 4x4 blocks are each one colour, all representable in RGB565 */
    struct vt_image src = {12, 8, 4, VTS_SAMPLE_U8, 12 * 4, malloc(12 * 8 * 4)};
    for (uint32_t y = 0; y < 8; y++)
        for (uint32_t x = 0; x < 12; x++) {
            unsigned k = (y / 4) * 3 + x / 4; /* block number, row-major */
            unsigned char *t = (unsigned char *)src.pixels + y * src.stride + x * 4;
            t[0] = (unsigned char)(k * 33); /* 33 = 4 << 3 | 4 >> 2: a 5-bit expansion */
            t[1] = 0;
            t[2] = 255;
            t[3] = (unsigned char)(200 - k);
        }
    static const char *const names[] = {"bc1", "bc3"};
    for (int c = 0; c < 2; c++) {
        const struct vt_codec *codec = vt_codec_find(names[c]);
        size_t block_bytes = c ? 16 : 8, len = 0;
        unsigned char *payload = encode_alloc_exact(codec, &src, 0, &len);
        VT_CHECK_INT_EQ(len, 6 * block_bytes);
        for (unsigned k = 0; payload && k < 6; k++) {
            unsigned char texels[16][4];
            VT_CHECK_INT_EQ(vt_squish_shim_decompress_block(payload + k * block_bytes,
                                                            c ? VT_SQUISH_SHIM_BC3 : 0,
                                                            &texels[0][0]),
                            0);
            VT_CHECK(texels[5][0] == k * 33 && texels[5][1] == 0 && texels[5][2] == 255);
            VT_CHECK(texels[5][3] == (c ? 200 - k : 255));
        }
        free(payload);
    }
    free(src.pixels);
}

/* ---- round trips ---- */

static void bc_round_trips_a_photo_like_image(void)
{
    struct vt_image rgb = vt_synth_photo(256, 256, 3, 1, 0.6),
                    rgba = vt_synth_photo(256, 256, 4, 1, 0.6);
    double bc1_fast = round_trip_psnr("bc1", &rgb, 0), bc1_best = round_trip_psnr("bc1", &rgb, 1);
    double bc3_fast = round_trip_psnr("bc3", &rgba, 0), bc3_best = round_trip_psnr("bc3", &rgba, 1);
    fprintf(stderr, "  bc1 fast %.2f dB, best %.2f dB; bc3 fast %.2f dB, best %.2f dB\n", bc1_fast,
            bc1_best, bc3_fast, bc3_best);
    VT_CHECK(bc1_fast >= 38.0);
    VT_CHECK(bc1_best >= 39.0);
    VT_CHECK(bc1_best >= bc1_fast);
    VT_CHECK(bc1_best >= bc1_fast + 0.25); /* what libsquish's cluster fit buys here (~0.5 dB) */
    VT_CHECK(bc3_fast >= 39.0);
    VT_CHECK(bc3_best >= 39.5);
    VT_CHECK(bc3_best >= bc3_fast);
    VT_CHECK(bc3_best >= bc3_fast + 0.25);
    free(rgba.pixels);
    free(rgb.pixels);
}

static void bc_round_trips_odd_shapes_and_strides(void)
{
    /* 4x4 (one block), 8x12 (not square), 264x264 (a 256 tile with border 4) */
    static const uint32_t sizes[][2] = {{4, 4}, {8, 12}, {264, 264}};
    for (size_t s = 0; s < 3; s++) {
        struct vt_image tight = vt_synth_photo(sizes[s][0], sizes[s][1], 4, 2, 0.6);
        struct vt_image padded = tight; /* the same texels with 7 bytes of padding per row */
        padded.stride = tight.stride + 7;
        padded.pixels = calloc(padded.stride, tight.height);
        for (uint32_t y = 0; y < tight.height; y++)
            memcpy((char *)padded.pixels + y * padded.stride,
                   (char *)tight.pixels + y * tight.stride, tight.stride);
        for (int effort = 0; effort <= 1; effort++) {
            size_t len_a = 0, len_b = 0;
            unsigned char *a = encode_alloc_exact(vt_codec_find("bc3"), &tight, effort, &len_a);
            unsigned char *b = encode_alloc_exact(vt_codec_find("bc3"), &padded, effort, &len_b);
            VT_CHECK(a && b && len_a == len_b && memcmp(a, b, len_a) == 0);
            free(a);
            free(b);
            VT_CHECK(round_trip_psnr("bc3", &padded, effort) > 30.0);
        }
        free(padded.pixels);
        free(tight.pixels);
    }
}

static void bc1_stores_alpha_as_one_bit(void)
{
    /* alpha: a cut-out pattern of 0, 127, 128 and 255 over a photo */
    struct vt_image img = vt_synth_photo(64, 64, 4, 3, 0.6);
    static const unsigned char levels[4] = {0, 127, 128, 255};
    for (uint32_t y = 0; y < 64; y++)
        for (uint32_t x = 0; x < 64; x++)
            ((unsigned char *)img.pixels)[y * img.stride + x * 4 + 3] =
                levels[((x / 3) ^ (y / 5)) % 4];
    for (int effort = 0; effort <= 1; effort++) {
        const struct vt_codec *bc1 = vt_codec_find("bc1");
        size_t len = 0;
        unsigned char *payload = encode_alloc_exact(bc1, &img, effort, &len);
        struct vt_image dst;
        struct vts_error err = {0};
        VT_CHECK_INT_EQ(decode_into(bc1, payload, len, &dst, 64, 64, 4, &err), 0);
        int wrong_alpha = 0, wrong_black = 0;
        double sum = 0;
        int opaque = 0;
        for (uint32_t y = 0; y < 64; y++)
            for (uint32_t x = 0; x < 64; x++) {
                const unsigned char *s = (const unsigned char *)img.pixels + y * img.stride + x * 4;
                const unsigned char *d = (const unsigned char *)dst.pixels + y * dst.stride + x * 4;
                wrong_alpha += d[3] != (s[3] < 128 ? 0 : 255);
                if (s[3] < 128) {
                    wrong_black += d[0] || d[1] || d[2];
                    continue;
                }
                for (int k = 0; k < 3; k++)
                    sum += (double)(s[k] - d[k]) * (s[k] - d[k]);
                opaque++;
            }
        VT_CHECK_INT_EQ(wrong_alpha, 0);
        VT_CHECK_INT_EQ(wrong_black, 0);
        double psnr = 10 * log10(255.0 * 255.0 / (sum / (3.0 * opaque)));
        VT_CHECK(psnr > 30.0); /* colour of the opaque texels survives */
        free(dst.pixels);
        free(payload);
    }
    free(img.pixels);
}

static void bc1_stores_fully_transparent_blocks(void)
{
    unsigned char texels[16][4], payload[8], decoded[16][4];
    for (int i = 0; i < 16; i++) {
        texels[i][0] = (unsigned char)(i * 16);
        texels[i][1] = 200;
        texels[i][2] = (unsigned char)(255 - i);
        texels[i][3] = (unsigned char)(i * 8); /* 0..120: all below 128 */
    }
    struct vt_image src = {4, 4, 4, VTS_SAMPLE_U8, 16, texels};
    static const unsigned char transparent[1][4] = {{0, 0, 0, 0}};
    static const unsigned char zeros[16] = {0};
    for (int effort = 0; effort <= 1; effort++) {
        struct vt_codec_params params = {.effort = effort};
        size_t len = 0;
        VT_CHECK_INT_EQ(vt_codec_find("bc1")->encode(&src, &params, payload, 8, &len, NULL), 0);
        VT_CHECK_INT_EQ(decode_block("bc1", payload, len, decoded), 0);
        VT_CHECK_INT_EQ(block_mismatches(decoded, transparent, zeros), 0);
    }
}

/* Encodes a 4x4 tile of one colour with codec_name at effort; true when it decodes exactly. */
static bool solid_block_is_exact(const char *codec_name, int effort, const unsigned char rgba[4])
{
    unsigned char texels[16][4], out[16];
    for (int i = 0; i < 16; i++)
        memcpy(texels[i], rgba, 4);
    struct vt_image src = {4, 4, 4, VTS_SAMPLE_U8, 16, texels};
    struct vt_codec_params params = {.effort = effort};
    size_t len = 0;
    const struct vt_codec *codec = vt_codec_find(codec_name);
    if (codec->encode(&src, &params, out, sizeof out, &len, NULL) != 0)
        return false;
    unsigned char decoded[16][4];
    if (decode_block(codec_name, out, len, decoded) != 0)
        return false;
    return memcmp(decoded, texels, sizeof texels) == 0;
}

static void bc_solid_colours_in_rgb565_decode_exactly(void)
{
    int bc1_wrong[2] = {0, 0}, bc3_wrong[2] = {0, 0};
    for (unsigned r5 = 0; r5 < 32; r5++)
        for (unsigned g6 = 0; g6 < 64; g6++)
            for (unsigned b5 = 0; b5 < 32; b5 += (r5 + g6) % 3 + 1) {
                unsigned char rgba[4] = {(unsigned char)(r5 << 3 | r5 >> 2),
                                         (unsigned char)(g6 << 2 | g6 >> 4),
                                         (unsigned char)(b5 << 3 | b5 >> 2), 255};
                for (int effort = 0; effort <= 1; effort++) {
                    bc1_wrong[effort] += !solid_block_is_exact("bc1", effort, rgba);
                    rgba[3] = (unsigned char)(r5 * 8 + b5); /* any constant alpha is exact */
                    bc3_wrong[effort] += !solid_block_is_exact("bc3", effort, rgba);
                    rgba[3] = 255;
                }
            }
    VT_CHECK_INT_EQ(bc1_wrong[0], 0);
    VT_CHECK_INT_EQ(bc1_wrong[1], 0);
    VT_CHECK_INT_EQ(bc3_wrong[0], 0);
    VT_CHECK_INT_EQ(bc3_wrong[1], 0);
}

/* ---- refusals ---- */

static void bc_check_refuses_what_it_cannot_store(void)
{
    const struct vt_codec *bc1 = vt_codec_find("bc1"), *bc3 = vt_codec_find("bc3");
    struct vts_error err = {0};
    VT_CHECK(bc1 && bc1->fourcc == VTS_CODEC_BC1 && !bc1->lossless);
    VT_CHECK(bc3 && bc3->fourcc == VTS_CODEC_BC3 && !bc3->lossless);
    VT_CHECK(vt_codec_by_fourcc(VTS_CODEC_BC1) == bc1 && vt_codec_by_fourcc(VTS_CODEC_BC3) == bc3);
    VT_CHECK_INT_EQ(bc1->check(256, 3, VTS_SAMPLE_U8, &err), 0);
    VT_CHECK_INT_EQ(bc1->check(264, 4, VTS_SAMPLE_U8, &err), 0);
    VT_CHECK_INT_EQ(bc3->check(264, 4, VTS_SAMPLE_U8, &err), 0);
    VT_CHECK_INT_EQ(bc1->check(258, 3, VTS_SAMPLE_U8, &err), VTS_ERR_UNSUPPORTED);
    VT_CHECK_STR_CONTAINS(err.message,
                          "bc1 needs a tile payload that is a multiple of 4 (got 258)");
    VT_CHECK_STR_CONTAINS(err.message, "--border 4");
    VT_CHECK_INT_EQ(bc3->check(130, 4, VTS_SAMPLE_U8, &err), VTS_ERR_UNSUPPORTED);
    VT_CHECK_STR_CONTAINS(err.message,
                          "bc3 needs a tile payload that is a multiple of 4 (got 130)");
    VT_CHECK_INT_EQ(bc1->check(256, 3, VTS_SAMPLE_U16, &err), VTS_ERR_UNSUPPORTED);
    VT_CHECK_STR_CONTAINS(err.message, "8-bit samples only (got u16)");
    VT_CHECK_INT_EQ(bc3->check(256, 4, VTS_SAMPLE_F32, &err), VTS_ERR_UNSUPPORTED);
    VT_CHECK_STR_CONTAINS(err.message, "use png or raw");
    VT_CHECK_INT_EQ(bc1->check(256, 2, VTS_SAMPLE_U8, &err), VTS_ERR_UNSUPPORTED);
    VT_CHECK_STR_CONTAINS(err.message, "bc1 needs 3 or 4 channels (RGB or RGBA), got 2");
    VT_CHECK_INT_EQ(bc1->check(256, 1, VTS_SAMPLE_U8, &err), VTS_ERR_UNSUPPORTED);
    VT_CHECK_INT_EQ(bc3->check(256, 3, VTS_SAMPLE_U8, &err), VTS_ERR_UNSUPPORTED);
    VT_CHECK_STR_CONTAINS(err.message, "bc3 needs 4 channels (RGBA), got 3: use bc1");
    VT_CHECK_INT_EQ(bc1->check(0, 3, VTS_SAMPLE_U8, &err), VTS_ERR_UNSUPPORTED);
    VT_CHECK_INT_EQ(bc1->encoded_bound(256, 256, 3, VTS_SAMPLE_U8), 256 * 256 / 2);
    VT_CHECK_INT_EQ(bc3->encoded_bound(264, 264, 4, VTS_SAMPLE_U8), 264 * 264);
    VT_CHECK_INT_EQ(bc1->encoded_bound(258, 258, 3, VTS_SAMPLE_U8), 0);
    VT_CHECK_INT_EQ(bc3->encoded_bound(256, 256, 3, VTS_SAMPLE_U8), 0);
    VT_CHECK_INT_EQ(bc1->encoded_bound(256, 256, 4, VTS_SAMPLE_U16), 0);
}

static void bc_encode_refuses_bad_effort_shape_and_small_buffer(void)
{
    const struct vt_codec *bc1 = vt_codec_find("bc1");
    struct vt_image img = vt_synth_photo(8, 8, 3, 4, 0.5);
    unsigned char buf[64];
    size_t len = 99;
    struct vts_error err = {0};
    struct vt_codec_params params = {.effort = 2};
    VT_CHECK_INT_EQ(bc1->encode(&img, &params, buf, sizeof buf, &len, &err), VTS_ERR_ARG);
    VT_CHECK_STR_CONTAINS(err.message, "effort 2");
    VT_CHECK_INT_EQ(len, 0);
    VT_CHECK_INT_EQ(bc1->encode(&img, NULL, buf, 31, &len, &err), VTS_ERR_LIMIT);
    VT_CHECK_INT_EQ(bc1->encode(&img, NULL, buf, 32, &len, &err), 0);
    VT_CHECK_INT_EQ(len, 32);
    img.width = 6; /* not a whole number of blocks */
    VT_CHECK_INT_EQ(bc1->encode(&img, NULL, buf, sizeof buf, &len, &err), VTS_ERR_UNSUPPORTED);
    VT_CHECK_STR_CONTAINS(err.message, "4x4 blocks");
    img.width = 8;
    img.channels = 2;
    VT_CHECK_INT_EQ(bc1->encode(&img, NULL, buf, sizeof buf, &len, &err), VTS_ERR_UNSUPPORTED);
    free(img.pixels);
}

static void bc_decode_rejects_payloads_of_wrong_length(void)
{
    static const char *const names[] = {"bc1", "bc3"};
    for (int c = 0; c < 2; c++) {
        const struct vt_codec *codec = vt_codec_find(names[c]);
        struct vt_image img = vt_synth_photo(16, 16, 4, 5, 0.5);
        size_t len = 0;
        unsigned char *payload = encode_alloc_exact(codec, &img, 0, &len);
        VT_CHECK_INT_EQ(len, c ? 256 : 128);
        struct vt_image dst;
        struct vts_error err = {0};
        unsigned char *short_one = dup_prefix(payload, len - 1);
        VT_CHECK_INT_EQ(decode_into(codec, short_one, len - 1, &dst, 16, 16, 4, &err),
                        VTS_ERR_BAD_INPUT);
        VT_CHECK_STR_CONTAINS(err.message,
                              c ? "bc3 payload: 255 bytes != 256" : "127 bytes != 128");
        free(dst.pixels);
        unsigned char *long_one = calloc(1, len + 1);
        memcpy(long_one, payload, len);
        VT_CHECK_INT_EQ(decode_into(codec, long_one, len + 1, &dst, 16, 16, 4, &err),
                        VTS_ERR_BAD_INPUT);
        free(dst.pixels);
        VT_CHECK_INT_EQ(decode_into(codec, NULL, 0, &dst, 16, 16, 4, &err), VTS_ERR_BAD_INPUT);
        free(dst.pixels);
        /* a tile of another size: the length tells */
        VT_CHECK_INT_EQ(decode_into(codec, payload, len, &dst, 16, 20, 4, &err), VTS_ERR_BAD_INPUT);
        free(dst.pixels);
        /* and a destination this codec does not produce is the caller's error */
        VT_CHECK_INT_EQ(decode_into(codec, payload, len, &dst, 16, 16, 2, &err),
                        VTS_ERR_UNSUPPORTED);
        free(dst.pixels);
        free(long_one);
        free(short_one);
        free(payload);
        free(img.pixels);
    }
}

/* ---- threads ---- */

struct encode_job {
    const struct vt_image *img;
    const char *codec_name;
    int effort;
    unsigned char *payload;
    size_t len;
};

static void *encode_job_run(void *arg)
{
    struct encode_job *job = arg;
    const struct vt_codec *codec = vt_codec_find(job->codec_name);
    job->len = codec->encoded_bound(job->img->width, job->img->height, job->img->channels,
                                    job->img->sample);
    job->payload = malloc(job->len);
    struct vt_codec_params params = {.effort = job->effort};
    if (codec->encode(job->img, &params, job->payload, job->len, &job->len, NULL) != 0)
        job->len = 0;
    return NULL;
}

/* Threads of this process (entries of /proc/self/task), or -1 when unknown. */
static int thread_count(void)
{
    DIR *dir = opendir("/proc/self/task");
    if (!dir)
        return -1;
    int n = 0;
    for (struct dirent *e; (e = readdir(dir));)
        n += e->d_name[0] != '.';
    closedir(dir);
    return n;
}

static int threads_at_start; /* thread_count() before any test ran */

static void bc_encodes_the_same_bytes_on_two_threads_without_openmp(void)
{
    struct vt_image img = vt_synth_photo(64, 64, 4, 6, 0.6);
    static const char *const names[] = {"bc1", "bc3"};
    for (int c = 0; c < 2; c++) {
        for (int effort = 0; effort <= 1; effort++) {
            struct encode_job alone = {&img, names[c], effort, NULL, 0}, jobs[2];
            encode_job_run(&alone);
            pthread_t threads[2];
            for (int t = 0; t < 2; t++) {
                jobs[t] = alone;
                VT_CHECK_INT_EQ(pthread_create(&threads[t], NULL, encode_job_run, &jobs[t]), 0);
            }
            for (int t = 0; t < 2; t++) {
                pthread_join(threads[t], NULL);
                VT_CHECK(jobs[t].len > 0 && jobs[t].len == alone.len &&
                         memcmp(jobs[t].payload, alone.payload, alone.len) == 0);
                free(jobs[t].payload);
            }
            free(alone.payload);
        }
    }
    /* libsquish ran here and in every test before: had it started an OpenMP team, its threads
     * would still be there */
    VT_CHECK(threads_at_start > 0);
    VT_CHECK_INT_EQ(thread_count(), threads_at_start);
    free(img.pixels);
}

static void *no_op(void *arg)
{
    return arg;
}

int main(void)
{
    /* one thread started and joined first, so that runtimes which start a helper thread with the
     * first pthread_create() (TSan) have done so before the baseline is taken */
    pthread_t warm_up;
    if (pthread_create(&warm_up, NULL, no_op, NULL) == 0)
        pthread_join(warm_up, NULL);
    threads_at_start = thread_count();
    VT_RUN(bc1_decodes_four_colour_block_by_hand);
    VT_RUN(bc1_decodes_three_colour_transparent_block_by_hand);
    VT_RUN(bc3_decodes_eight_alpha_block_by_hand);
    VT_RUN(bc3_decodes_six_alpha_block_by_hand);
    VT_RUN(bc_decoder_agrees_with_libsquish_on_random_blocks);
    VT_RUN(bc_payload_is_blocks_row_major);
    VT_RUN(bc_round_trips_a_photo_like_image);
    VT_RUN(bc_round_trips_odd_shapes_and_strides);
    VT_RUN(bc1_stores_alpha_as_one_bit);
    VT_RUN(bc1_stores_fully_transparent_blocks);
    VT_RUN(bc_solid_colours_in_rgb565_decode_exactly);
    VT_RUN(bc_check_refuses_what_it_cannot_store);
    VT_RUN(bc_encode_refuses_bad_effort_shape_and_small_buffer);
    VT_RUN(bc_decode_rejects_payloads_of_wrong_length);
    VT_RUN(bc_encodes_the_same_bytes_on_two_threads_without_openmp);
    return vt_test_main_result();
}
