/* Tool-side tile access: reads one layer's tiles from a store, checks their CRC, decodes them
 * with the layer's codec, converts decoded rows to PNG samples and writes a tile or level as PNG.
 * Shared by the tools that read stores (vt-info; later vt-convert, vt-merge). Messages name the
 * store, layer, level and tile. */
#ifndef VT_TILE_READER_H
#define VT_TILE_READER_H

#include <stdbool.h>
#include <stdint.h>

#include "vt_codec.h"
#include "vt_error.h"
#include "vt_image.h"
#include "vts.h"

struct vt_tile_reader {
    const struct vts_store *store; /* not owned */
    uint32_t layer;
    const struct vt_codec *codec;
    unsigned char *payload; /* vts_store_max_payload() bytes */
    struct vt_image img;    /* the last tile read: payload edge square, the layer's shape */
    bool crc_only;          /* set by the caller: reads check the CRC and do not decode */
    /* Set by the caller: empty tiles hold `fill` in every sample (a store's nodata,
     * docs/geospatial.md) instead of zeros: u8/u16 when it is an integer in range, f32 always,
     * f16 never (zeros). */
    bool has_fill;
    double fill;
};

/* Prepares to read tiles of layer (< layer count) of store. Returns 0, or VTS_ERR_UNSUPPORTED (no
 * decoder for the layer's codec in this build) or VTS_ERR_NOMEM with a message naming the store.
 * Release with vt_tile_reader_release() either way. */
int vt_tile_reader_init(struct vt_tile_reader *r, const struct vts_store *store, uint32_t layer,
                        struct vts_error *err);

/* Frees the buffers. Accepts NULL and a reader whose init failed; may be called twice. */
void vt_tile_reader_release(struct vt_tile_reader *r);

/* Reads tile (tx, ty) of level into r->img: decoded, or all zero (or r->fill) when the tile is
 * empty (*stored false). Returns 0, or the status of the read (VTS_ERR_CHECKSUM, VTS_ERR_IO...) or
 * of the decoder (VTS_ERR_BAD_INPUT) with the message "'<store>': layer L level V tile X,Y:
 * <reason>". */
int vt_tile_reader_read(struct vt_tile_reader *r, uint32_t level, uint32_t tx, uint32_t ty,
                        bool *stored, struct vts_error *err);

/* PNG bit depth for the layer's samples: 8 for u8, 16 for the others. */
uint32_t vt_tile_reader_png_depth(const struct vt_tile_reader *r);

/* Converts count texels of row y of r->img, from column x, into PNG samples of
 * vt_tile_reader_png_depth() bits (16-bit ones in host order): u8 and u16 are copied, f16 and f32
 * are clamped to [0,1] and scaled to 0..65535 (NaN -> 0). */
void vt_tile_reader_png_row(const struct vt_tile_reader *r, uint32_t x, uint32_t y, uint32_t count,
                            void *dst);

/* Writes level (< level count) of the reader's layer as a PNG at path (vt_png_file writer: nothing
 * appears under path unless it succeeds): with one_tile, tile (tx, ty) whole, border included;
 * else the whole level stitched from tile contents without borders, one row of tiles at a time
 * (memory: one tile row). Empty tiles are zero. Samples as vt_tile_reader_png_row(). Shows a
 * progress line (tool_common) for a whole level. Returns 0, or a negative status with a message
 * (a bad tile is named as by vt_tile_reader_read()). */
int vt_tile_reader_write_png(struct vt_tile_reader *r, uint32_t level, bool one_tile, uint32_t tx,
                             uint32_t ty, const char *path, struct vts_error *err);

/* The same as a PNG (tiff false) or as a TIFF (deflate; vt_tiff_file): u8 and u16 samples as they
 * are, f16 and f32 as 32-bit floats holding their exact values (no clamping). */
int vt_tile_reader_write_image(struct vt_tile_reader *r, uint32_t level, bool one_tile, uint32_t tx,
                               uint32_t ty, const char *path, bool tiff, struct vts_error *err);

#endif
