/* libvts-decode: tiles and regions of a .vts store decoded to pixels (the companion of libvts).
 * Reading stays libvts's (vts.h: open a store with vts_open()); this library adds the payload
 * codecs (raw, png, jpeg, bc1, bc3) and so links libpng, TurboJPEG and libsquish, which libvts
 * itself never does. Guide: docs/decode-api.md.
 *
 * Conventions (those of vts.h):
 * - Every name is vts_decode_* / VTS_DECODE_*; only those symbols are exported from
 *   libvts-decode.so.
 * - Actions return 0 (VTS_OK) or a negative enum vts_status and fill the caller's struct vts_error
 *   (which may be NULL) with a one-line message naming the store, layer, level and tile.
 * - Out-of-range arguments (a layer, level, tile or rectangle the store does not hold) give
 *   VTS_ERR_RANGE, never clamping; a NULL dst, a zero width or height, or a stride smaller than a
 *   row give VTS_ERR_ARG; a dst_capacity smaller than the image gives VTS_ERR_LIMIT, and so does a
 *   size that overflows size_t. In all these cases nothing is written to dst. A failure while
 *   decoding (VTS_ERR_IO, VTS_ERR_CHECKSUM, VTS_ERR_BAD_INPUT, VTS_ERR_NOMEM) may leave dst
 *   partially written.
 * - Thread safety: every function may be called from many threads at once, on one store or many:
 *   the functions keep no state between calls (each call allocates its own scratch buffers).
 *
 * What a decoded texel is: the layer's channels (vts_layer.channels, interleaved, in stored order)
 * and its sample type exactly as stored, in host byte order (little-endian on every supported
 * machine):
 *   VTS_SAMPLE_U8  -> uint8_t        VTS_SAMPLE_U16 -> uint16_t
 *   VTS_SAMPLE_F16 -> uint16_t holding the IEEE half-float bits (not converted)
 *   VTS_SAMPLE_F32 -> float
 * A texel is vts_decode_texel_bytes() bytes; rows are dst_stride bytes apart (the caller's choice,
 * at least width * texel bytes); an image of h rows needs (h - 1) * dst_stride + width * texel
 * bytes of dst. Empty tiles (index length 0) decode as zeros. */
#ifndef VTS_DECODE_H
#define VTS_DECODE_H

#include <stddef.h>
#include <stdint.h>

#include "vts.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Version of the libvts-decode actually loaded, as VTS_VERSION_NUMBER (the project's version: the
 * same as libvts's). */
VTS_API unsigned vts_decode_version(void);

enum vts_decode_flags {
    VTS_DECODE_NO_BORDER = 1u << 0, /* vts_decode_tile(): the content square only, without the
                                       border (tile_content_px instead of tile_payload_px) */
    VTS_DECODE_NO_CRC = 1u << 1,    /* skip the CRC-32C check of each payload (VTS_READ_NO_CRC) */
};

/* Bytes of one decoded texel of layer: channels * sample bytes; 0 when layer is out of range. */
VTS_API size_t vts_decode_texel_bytes(const struct vts_store *store, uint32_t layer);

/* Whether this build can decode layer's codec. Returns 0, VTS_ERR_RANGE (no such layer) or
 * VTS_ERR_UNSUPPORTED (an unknown codec fourcc, or a channel count / sample type the codec does
 * not store) with a message. */
VTS_API int vts_decode_check(const struct vts_store *store, uint32_t layer, struct vts_error *err);

/* Decodes tile (tx, ty) of level of layer into dst: tile_payload_px x tile_payload_px texels with
 * its border, or tile_content_px x tile_content_px without it (flags VTS_DECODE_NO_BORDER; texel
 * (0, 0) is then the payload's (border_px, border_px)). A tile of the right or bottom edge of a
 * level is decoded whole: its texels past the level's edge are what the store holds there (the
 * builder's clamped or wrapped copies). flags: enum vts_decode_flags. Returns 0 or a negative
 * status (see the conventions above). */
VTS_API int vts_decode_tile(const struct vts_store *store, uint32_t layer, uint32_t level,
                            uint32_t tx, uint32_t ty, unsigned flags, void *dst, size_t dst_stride,
                            size_t dst_capacity, struct vts_error *err);

/* Decodes the rectangle (x, y, width, height) of level of layer, in that level's texels, into
 * dst: each texel comes from the content of the tile that owns it (borders are never read), empty
 * tiles give zeros. The rectangle must lie inside the level (x + width <= level width, y + height
 * <= level height): VTS_ERR_RANGE otherwise. A whole level is (0, 0, level width, level height)
 * (see vts_store_level()). Each tile the rectangle touches is read and decoded once. flags:
 * VTS_DECODE_NO_CRC (VTS_DECODE_NO_BORDER has no effect here). Returns 0 or a negative status. */
VTS_API int vts_decode_region(const struct vts_store *store, uint32_t layer, uint32_t level,
                              uint32_t x, uint32_t y, uint32_t width, uint32_t height,
                              unsigned flags, void *dst, size_t dst_stride, size_t dst_capacity,
                              struct vts_error *err);

#ifdef __cplusplus
}
#endif
#endif
