/* libFuzzer target for the tile payload decoders (formats/vt_codec_*.c, scripts/fuzz). The first
 * input byte picks the codec (raw, png, jpeg, bc1, bc3: byte % 5) and, among the tile shapes that
 * codec's check() accepts (edge 1, 4, 8, 16, 64 or 260; 1..4 channels; u8, u16, f16 or f32), the
 * shape number byte / 5 (modulo their count); bytes 232..255 pick bc4 (even) and bc5 (odd), shape
 * (byte - 232) / 2 (the codecs added later: the bytes below 232 keep their meaning, and so do the
 * kept findings); the rest is the payload, copied into an exact-size
 * allocation (ASan sees any read past it) and decoded into a vt_image of that shape.
 * Invariants, not only crashes: decode returns 0 or a negative status with a non-empty one-line
 * message; a payload that decodes is encoded again and that must decode too (lossless codecs: to
 * the same texels). The round trip is skipped for 260 px tiles: re-encoding 4225 BC blocks under
 * the sanitizers took ~80 ms and would have held the whole run to a few hundred executions/s.
 *
 * Built with -DVT_FUZZ_NO_ENTRY, the file gives fuzz_codec_shape() and fuzz_codec_decode_one() to
 * the seed writer and to the regression test (tests/robust/test_fuzz_regressions.c). */
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "vt_codec.h"
#include "vts.h"

/* Also declared by make_codec_seeds.c and test_fuzz_regressions.c, which compile this file. */
#define FUZZ_CODEC_COUNT 5 /* raw, png, jpeg, bc1, bc3 */
/* The codec and tile shape an input's first byte selects; -1 when that codec is not built in. */
int fuzz_codec_shape(uint8_t selector, const struct vt_codec **codec, uint32_t *edge,
                     uint32_t *channels, uint32_t *sample);
/* Runs one input; returns the decode status (0 or negative, err filled). Aborts on a defect. */
int fuzz_codec_decode_one(const uint8_t *data, size_t size, struct vts_error *err);

static const char *const codec_names[FUZZ_CODEC_COUNT] = {"raw", "png", "jpeg", "bc1", "bc3"};
#define FUZZ_RGTC_FIRST 232 /* selectors from here: bc4, bc5 */
static const uint32_t edges[6] = {1, 4, 8, 16, 64, 260};

/* Shape number i of the 96 (edge, channels, sample) combinations, in an order where the first 52
 * (what one byte can pick) already hold every edge, channel count and sample type. */
static void shape_of(unsigned i, uint32_t *edge, uint32_t *channels, uint32_t *sample)
{
    *edge = edges[i % 6];
    *channels = (i / 6) % 4 + 1;
    *sample = (i / 24 + i) % 4 + 1;
}

int fuzz_codec_shape(uint8_t selector, const struct vt_codec **codec, uint32_t *edge,
                     uint32_t *channels, uint32_t *sample)
{
    bool rgtc = selector >= FUZZ_RGTC_FIRST;
    const struct vt_codec *c = vt_codec_find(rgtc ? (selector % 2 ? "bc5" : "bc4")
                                                  : codec_names[selector % FUZZ_CODEC_COUNT]);
    if (!c)
        return -1;
    unsigned accepted[96], n = 0;
    for (unsigned i = 0; i < 96; i++) {
        uint32_t e, ch, s;
        shape_of(i, &e, &ch, &s);
        struct vts_error err = {0};
        if (c->check(e, ch, s, &err) == 0)
            accepted[n++] = i;
    }
    if (n == 0)
        return -1;
    *codec = c;
    unsigned pick = rgtc ? (selector - FUZZ_RGTC_FIRST) / 2u : selector / FUZZ_CODEC_COUNT;
    shape_of(accepted[pick % n], edge, channels, sample);
    return 0;
}

static void check_failure(int rc, const struct vts_error *err)
{
    if (rc >= 0 || err->message[0] == '\0' || strchr(err->message, '\n'))
        abort();
}

static int same_texels(const struct vt_image *a, const struct vt_image *b)
{
    size_t row = (size_t)a->width * vt_image_texel_bytes(a);
    for (uint32_t y = 0; y < a->height; y++)
        if (memcmp(vt_image_at(a, 0, y), vt_image_at(b, 0, y), row) != 0)
            return 0;
    return 1;
}

/* Encodes the decoded tile again and decodes that; any failure is a defect (abort). */
static void round_trip(const struct vt_codec *c, const struct vt_image *img)
{
    struct vts_error err = {0};
    size_t bound = c->encoded_bound(img->width, img->height, img->channels, img->sample), len = 0;
    unsigned char *buf = malloc(bound ? bound : 1);
    struct vt_image again = {0};
    if (bound == 0 || !buf ||
        c->encode(img, &(struct vt_codec_params){0}, buf, bound, &len, &err) || len > bound ||
        vt_image_alloc(&again, img->width, img->height, img->channels, img->sample, &err) ||
        c->decode(buf, len, &again, &err) != 0 || (c->lossless && !same_texels(img, &again)))
        abort();
    vt_image_release(&again);
    free(buf);
}

int fuzz_codec_decode_one(const uint8_t *data, size_t size, struct vts_error *err)
{
    const struct vt_codec *c;
    uint32_t edge, channels, sample;
    if (size < 1 || fuzz_codec_shape(data[0], &c, &edge, &channels, &sample) != 0)
        return 0;
    size_t len = size - 1;
    unsigned char *payload = malloc(len ? len : 1);
    struct vt_image img = {0};
    if (!payload || vt_image_alloc(&img, edge, edge, channels, sample, err) != 0)
        abort();
    if (len)
        memcpy(payload, data + 1, len);
    /* exactly len bytes: a zero-length payload is a pointer to nothing readable */
    int rc = c->decode(payload, len, &img, err);
    free(payload);
    if (rc != 0)
        check_failure(rc, err);
    else if (edge <= 64)
        round_trip(c, &img);
    vt_image_release(&img);
    return rc;
}

#ifndef VT_FUZZ_NO_ENTRY
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    struct vts_error err = {0};
    fuzz_codec_decode_one(data, size, &err);
    return 0;
}
#endif
