/* Shared by the BC codec tests (each includes its own copy): encode into an exactly sized
 * buffer, decode into a padded image or one 4x4 block, the PSNR of a round trip, and a seeded
 * stream of random numbers. */
#ifndef BC_TEST_UTIL_H
#define BC_TEST_UTIL_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "codec_test_util.h"
#include "vt_codec.h"
#include "vt_synth_photo.h"
#include "vt_test.h"
#include "vts.h"

static uint64_t rng_state;

/* splitmix64: a seeded stream, identical on every machine */
static inline uint64_t rng_next(void)
{
    uint64_t z = (rng_state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

/* Encodes img into a fresh buffer of exactly encoded_bound() bytes (BC payloads have no other
 * size); NULL (and a failed check) on error. */
static inline unsigned char *encode_alloc_exact(const struct vt_codec *codec,
                                                const struct vt_image *img, int effort, size_t *len)
{
    unsigned char *buf = encode_alloc(codec, img, effort, len);
    if (buf)
        VT_CHECK_INT_EQ(*len,
                        codec->encoded_bound(img->width, img->height, img->channels, img->sample));
    return buf;
}

/* Decodes payload into a fresh u8 image (stride padded by 5 bytes preset to 0xcd). */
static inline int decode_into(const struct vt_codec *codec, const void *payload, size_t len,
                              struct vt_image *dst, uint32_t w, uint32_t h, uint32_t channels,
                              struct vts_error *err)
{
    *dst = (struct vt_image){w, h, channels, VTS_SAMPLE_U8, (size_t)w * channels + 5, NULL};
    dst->pixels = malloc(dst->stride * h);
    memset(dst->pixels, 0xcd, dst->stride * h);
    return codec->decode(payload, len, dst, err);
}

/* Decodes one block (8 or 16 bytes) as a 4x4 RGBA tile into texels[16][4]; returns the status. */
static inline int decode_block(const char *codec_name, const unsigned char *block, size_t len,
                               unsigned char texels[16][4])
{
    struct vt_image dst = {4, 4, 4, VTS_SAMPLE_U8, 16, texels};
    struct vts_error err = {0};
    int rc = vt_codec_find(codec_name)->decode(block, len, &dst, &err);
    if (rc)
        fprintf(stderr, "  decode: %s\n", err.message);
    return rc;
}

/* Encodes and decodes img with codec at effort; returns the PSNR over every channel. */
static inline double round_trip_psnr(const char *codec_name, const struct vt_image *img, int effort)
{
    const struct vt_codec *codec = vt_codec_find(codec_name);
    size_t len = 0;
    unsigned char *payload = encode_alloc(codec, img, effort, &len);
    struct vt_image dst;
    struct vts_error err = {0};
    int rc = decode_into(codec, payload, len, &dst, img->width, img->height, img->channels, &err);
    VT_CHECK_INT_EQ(rc, 0);
    double psnr = rc ? 0 : vt_synth_psnr_u8(img, &dst);
    free(dst.pixels);
    free(payload);
    return psnr;
}

#endif
