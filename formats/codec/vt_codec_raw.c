/* The reference codec: a payload is the tile's rows tightly packed, top row first, channels
 * interleaved, samples little-endian. Exact for every channel count and sample type; it anchors
 * the golden hashes of the end-to-end tests. */
#include <stdbool.h>
#include <stdint.h>
#include <string.h>

#include "internal/vt_codec_impl.h"
#include "vt_checked.h"
#include "vt_codec.h"
#include "vt_error.h"

/* Payload bytes of a width x height tile, or false when the shape is invalid or too large. */
static bool raw_payload_bytes(uint32_t width, uint32_t height, uint32_t channels, uint32_t sample,
                              size_t *row_bytes, size_t *total_bytes)
{
    unsigned sample_bytes = vts_sample_bytes(sample);
    if (width == 0 || height == 0 || channels < 1 || channels > 4 || sample_bytes == 0)
        return false;
    return vt_size_mul3(width, channels, sample_bytes, row_bytes) &&
           vt_size_mul(*row_bytes, height, total_bytes);
}

/* Copies sample_count samples between host order and little-endian (the same on LE hosts). */
static void raw_copy_samples(unsigned char *dst, const unsigned char *src, size_t sample_count,
                             unsigned sample_bytes)
{
    if (sample_bytes == 1 || vt_host_is_little_endian()) {
        memcpy(dst, src, sample_count * sample_bytes);
        return;
    }
    for (size_t i = 0; i < sample_count; i++, dst += sample_bytes, src += sample_bytes)
        for (unsigned b = 0; b < sample_bytes; b++)
            dst[b] = src[sample_bytes - 1 - b];
}

static int raw_check(uint32_t tile_px, uint32_t channels, uint32_t sample, struct vts_error *err)
{
    size_t row_bytes, total_bytes;
    if (channels < 1 || channels > 4)
        return vt_error_set(err, VTS_ERR_UNSUPPORTED, "raw codec: %u channels (1 to 4 supported)",
                            channels);
    if (vts_sample_bytes(sample) == 0)
        return vt_error_set(err, VTS_ERR_UNSUPPORTED, "raw codec: unknown sample type %u", sample);
    if (tile_px == 0)
        return vt_error_set(err, VTS_ERR_UNSUPPORTED, "raw codec: tile size 0");
    if (!raw_payload_bytes(tile_px, tile_px, channels, sample, &row_bytes, &total_bytes) ||
        total_bytes > UINT32_MAX)
        return vt_error_set(err, VTS_ERR_UNSUPPORTED,
                            "raw codec: a %ux%u tile of %u x %s exceeds the 4 GiB payload limit",
                            tile_px, tile_px, channels, vts_sample_name(sample));
    return 0;
}

static size_t raw_encoded_bound(uint32_t width, uint32_t height, uint32_t channels, uint32_t sample)
{
    size_t row_bytes, total_bytes;
    if (!raw_payload_bytes(width, height, channels, sample, &row_bytes, &total_bytes))
        return 0;
    return total_bytes;
}

/* Shape of img as a raw payload; VTS_ERR_ARG when img is not a valid image (a caller's bug). */
static int raw_image_layout(const struct vt_image *img, const char *role, size_t *row_bytes,
                            size_t *total_bytes, struct vts_error *err)
{
    if (!img->pixels || !raw_payload_bytes(img->width, img->height, img->channels, img->sample,
                                           row_bytes, total_bytes))
        return vt_error_set(err, VTS_ERR_ARG, "raw codec: invalid %s image %ux%u, %u x sample %u",
                            role, img->width, img->height, img->channels, img->sample);
    if (img->stride < *row_bytes)
        return vt_error_set(err, VTS_ERR_ARG, "raw codec: %s stride %zu < row size %zu", role,
                            img->stride, *row_bytes);
    return 0;
}

static int raw_encode(const struct vt_image *src, const struct vt_codec_params *params, void *dst,
                      size_t dst_capacity, size_t *out_len, struct vts_error *err)
{
    size_t row_bytes, total_bytes;
    (void)params; /* nothing to tune */
    *out_len = 0;
    int rc = raw_image_layout(src, "source", &row_bytes, &total_bytes, err);
    if (rc < 0)
        return rc;
    if (dst_capacity < total_bytes)
        return vt_error_set(err, VTS_ERR_LIMIT, "raw codec: output buffer of %zu bytes < %zu",
                            dst_capacity, total_bytes);
    unsigned sample_bytes = vts_sample_bytes(src->sample);
    size_t row_samples = (size_t)src->width * src->channels;
    for (uint32_t y = 0; y < src->height; y++)
        raw_copy_samples((unsigned char *)dst + (size_t)y * row_bytes,
                         (const unsigned char *)src->pixels + (size_t)y * src->stride, row_samples,
                         sample_bytes);
    *out_len = total_bytes;
    return 0;
}

static int raw_decode(const void *src, size_t src_len, struct vt_image *dst, struct vts_error *err)
{
    size_t row_bytes, total_bytes;
    int rc = raw_image_layout(dst, "destination", &row_bytes, &total_bytes, err);
    if (rc < 0)
        return rc;
    if (src_len != total_bytes)
        return vt_error_set(err, VTS_ERR_BAD_INPUT,
                            "raw payload: %zu bytes != %zu expected for a %ux%u tile of %u x %s",
                            src_len, total_bytes, dst->width, dst->height, dst->channels,
                            vts_sample_name(dst->sample));
    unsigned sample_bytes = vts_sample_bytes(dst->sample);
    size_t row_samples = (size_t)dst->width * dst->channels;
    for (uint32_t y = 0; y < dst->height; y++)
        raw_copy_samples((unsigned char *)dst->pixels + (size_t)y * dst->stride,
                         (const unsigned char *)src + (size_t)y * row_bytes, row_samples,
                         sample_bytes);
    return 0;
}

const struct vt_codec vt_codec_raw = {
    .name = "raw",
    .fourcc = VTS_CODEC_RAW,
    .summary = "uncompressed rows, any channel count and sample type (exact)",
    .lossless = true,
    .check = raw_check,
    .encoded_bound = raw_encoded_bound,
    .encode = raw_encode,
    .decode = raw_decode,
};
