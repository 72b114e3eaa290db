/* The 4x4-block tile geometry and checks shared by the block codecs (bc1, bc3, bc4, bc5). */
#include "internal/vt_block_tile.h"

#include "vt_checked.h"
#include "vt_error.h"

int vt_block_tile_check_channels_and_sample(const struct vt_block_format *fmt, uint32_t channels,
                                            uint32_t sample, struct vts_error *err)
{
    if (sample != VTS_SAMPLE_U8)
        return vt_error_set(err, VTS_ERR_UNSUPPORTED,
                            "%s stores 8-bit samples only (got %s); use png or raw", fmt->name,
                            vts_sample_name(sample));
    if (channels < fmt->min_channels || channels > fmt->max_channels)
        return vt_error_set(err, VTS_ERR_UNSUPPORTED, "%s needs %s, got %u: %s", fmt->name,
                            fmt->needs, channels, fmt->instead);
    return 0;
}

int vt_block_tile_check(const struct vt_block_format *fmt, uint32_t tile_px, uint32_t channels,
                        uint32_t sample, struct vts_error *err)
{
    int rc = vt_block_tile_check_channels_and_sample(fmt, channels, sample, err);
    if (rc < 0)
        return rc;
    if (tile_px == 0 || tile_px % VT_BLOCK_TILE_PX != 0)
        return vt_error_set(
            err, VTS_ERR_UNSUPPORTED,
            "%s needs a tile payload that is a multiple of 4 (got %u): use --tile-size 256 with --border 4 or --keep payload",
            fmt->name, tile_px);
    uint64_t blocks = (uint64_t)(tile_px / VT_BLOCK_TILE_PX) * (tile_px / VT_BLOCK_TILE_PX);
    if (blocks * fmt->block_bytes > UINT32_MAX)
        return vt_error_set(err, VTS_ERR_UNSUPPORTED,
                            "%s: a %ux%u tile exceeds the 4 GiB payload limit", fmt->name, tile_px,
                            tile_px);
    return 0;
}

size_t vt_block_tile_payload_bytes(const struct vt_block_format *fmt, uint32_t width,
                                   uint32_t height)
{
    size_t total;
    if (width == 0 || height == 0 || width % VT_BLOCK_TILE_PX || height % VT_BLOCK_TILE_PX ||
        !vt_size_mul3(width / VT_BLOCK_TILE_PX, height / VT_BLOCK_TILE_PX, fmt->block_bytes,
                      &total))
        return 0;
    return total;
}

size_t vt_block_tile_encoded_bound(const struct vt_block_format *fmt, uint32_t width,
                                   uint32_t height, uint32_t channels, uint32_t sample)
{
    if (sample != VTS_SAMPLE_U8 || channels < fmt->min_channels || channels > fmt->max_channels)
        return 0;
    return vt_block_tile_payload_bytes(fmt, width, height);
}

/* Checks that img is a tile fmt stores; *payload_bytes receives its encoded size. */
static int block_tile_image_layout(const struct vt_block_format *fmt, const struct vt_image *img,
                                   const char *role, size_t *payload_bytes, struct vts_error *err)
{
    int rc = vt_block_tile_check_channels_and_sample(fmt, img->channels, img->sample, err);
    if (rc < 0)
        return rc;
    *payload_bytes = vt_block_tile_payload_bytes(fmt, img->width, img->height);
    if (*payload_bytes == 0)
        return vt_error_set(err, VTS_ERR_UNSUPPORTED,
                            "%s: a %ux%u %s image is not a whole number of 4x4 blocks", fmt->name,
                            img->width, img->height, role);
    if (!img->pixels || img->stride < (size_t)img->width * img->channels)
        return vt_error_set(err, VTS_ERR_ARG, "%s codec: invalid %s image (stride %zu, %ux%u)",
                            fmt->name, role, img->stride, img->width, img->height);
    return 0;
}

int vt_block_tile_encode_check(const struct vt_block_format *fmt, const struct vt_image *src,
                               int effort, bool effort_valid, size_t dst_capacity,
                               size_t *payload_bytes, struct vts_error *err)
{
    int rc = block_tile_image_layout(fmt, src, "source", payload_bytes, err);
    if (rc < 0)
        return rc;
    if (!effort_valid)
        return vt_error_set(err, VTS_ERR_ARG,
                            "%s codec: effort %d is neither 0 (fast) nor 1 (best)", fmt->name,
                            effort);
    if (dst_capacity < *payload_bytes)
        return vt_error_set(err, VTS_ERR_LIMIT, "%s encode: output buffer of %zu bytes < %zu",
                            fmt->name, dst_capacity, *payload_bytes);
    return 0;
}

int vt_block_tile_decode_check(const struct vt_block_format *fmt, size_t src_len,
                               const struct vt_image *dst, struct vts_error *err)
{
    size_t payload_bytes;
    int rc = block_tile_image_layout(fmt, dst, "destination", &payload_bytes, err);
    if (rc < 0)
        return rc;
    if (src_len != payload_bytes)
        return vt_error_set(
            err, VTS_ERR_BAD_INPUT,
            "%s payload: %zu bytes != %zu expected for a %ux%u tile (%u blocks of %u bytes)",
            fmt->name, src_len, payload_bytes, dst->width, dst->height,
            (unsigned)(payload_bytes / fmt->block_bytes), fmt->block_bytes);
    return 0;
}
