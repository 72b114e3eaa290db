/* Private to formats/codec: what the 4x4-block codecs (bc1, bc3 in vt_codec_bc.c; bc4, bc5 in
 * vt_codec_rgtc.c) share: the tile geometry (a whole number of 4x4 blocks, row-major, block_bytes
 * each), its bounds (the 4 GiB payload limit) and the checks of a tile's shape, sample type and
 * channel count, with the same messages for every format (vt_block_tile.c). The block loops stay
 * in each codec (their inner work differs). No allocation, no global state: thread-safe. */
#ifndef VT_BLOCK_TILE_H
#define VT_BLOCK_TILE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "vt_error.h"
#include "vt_image.h"

#define VT_BLOCK_TILE_PX 4 /* texels on a block's edge */

/* One block format: its name, block size and the channel counts it stores. */
struct vt_block_format {
    const char *name;      /* "bc1" ... */
    uint32_t block_bytes;  /* 8 or 16 */
    uint32_t min_channels; /* accepted channel counts */
    uint32_t max_channels;
    /* the message for another channel count: "<name> needs <needs>, got N: <instead>" */
    const char *needs;
    const char *instead;
};

/* 0 when fmt stores channels x sample (8-bit only), else VTS_ERR_UNSUPPORTED with a message. */
int vt_block_tile_check_channels_and_sample(const struct vt_block_format *fmt, uint32_t channels,
                                            uint32_t sample, struct vts_error *err);

/* The codec's check(): channels and sample, an edge of tile_px a multiple of 4, a payload under
 * 4 GiB. */
int vt_block_tile_check(const struct vt_block_format *fmt, uint32_t tile_px, uint32_t channels,
                        uint32_t sample, struct vts_error *err);

/* Payload bytes of a width x height tile, or 0 when the shape is not a whole number of blocks
 * (or its size overflows). */
size_t vt_block_tile_payload_bytes(const struct vt_block_format *fmt, uint32_t width,
                                   uint32_t height);

/* The codec's encoded_bound(): the payload bytes, 0 for a shape or sample fmt does not store. */
size_t vt_block_tile_encoded_bound(const struct vt_block_format *fmt, uint32_t width,
                                   uint32_t height, uint32_t channels, uint32_t sample);

/* The checks before an encode: src is a tile fmt stores, effort_valid (else the effort's
 * message), dst_capacity holds its payload; *payload_bytes receives the payload's size. */
int vt_block_tile_encode_check(const struct vt_block_format *fmt, const struct vt_image *src,
                               int effort, bool effort_valid, size_t dst_capacity,
                               size_t *payload_bytes, struct vts_error *err);

/* The checks before a decode: dst is a tile fmt stores and src_len its payload size. */
int vt_block_tile_decode_check(const struct vt_block_format *fmt, size_t src_len,
                               const struct vt_image *dst, struct vts_error *err);

#endif
