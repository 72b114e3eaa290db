/* Tile payload codecs behind one small table: encode a tile to bytes, decode bytes to a tile. */
#ifndef VT_CODEC_H
#define VT_CODEC_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "vt_error.h"
#include "vt_image.h"

/* Encoder settings; zero-initialise for defaults. */
struct vt_codec_params {
    int quality;     /* lossy codecs: 1..100, 0 = codec default */
    int effort;      /* png: 1..9 = deflate level, 0 = default (1; 1..3 use the fast UP filter);
                        bc: enum vt_codec_bc_effort */
    int subsampling; /* jpeg: 420 or 444; 0 = default (420) */
};

/* bc1 and bc3 effort. The reference encoders are an explicit option for the benchmark
 * (scripts/bench/bc-encoders) and the tests, which compare ours with them on the same texels
 * through this table; the tools never ask for them (--mode gives 0 or 1). */
enum vt_codec_bc_effort {
    VT_CODEC_BC_FAST = 0,         /* ours: principal axis, one least-squares step */
    VT_CODEC_BC_BEST = 1,         /* ours, several starts, refinement + endpoint search */
    VT_CODEC_BC_REF_STB_DXT = 16, /* stb_dxt 1.12 (libsquish range fit for BC1 cut-outs) */
    VT_CODEC_BC_REF_SQUISH = 17,  /* libsquish 1.15 cluster fit (BC3: colour by alpha) */
};

struct vt_codec {
    const char *name;    /* lowercase CLI name: "raw", "png" */
    uint32_t fourcc;     /* VTS_CODEC_* stored in the layer table */
    const char *summary; /* one line for --help */
    bool lossless;
    /* 0 when the codec can store tiles of edge tile_px with this many channels and sample type;
     * else VTS_ERR_UNSUPPORTED and a message that says why and what to use instead (including a
     * payload that could not fit the index's 32-bit length). */
    int (*check)(uint32_t tile_px, uint32_t channels, uint32_t sample, struct vts_error *err);
    /* Largest payload encode() can produce for such a tile (0 = shape not supported). */
    size_t (*encoded_bound)(uint32_t width, uint32_t height, uint32_t channels, uint32_t sample);
    /* Encodes src into dst (dst_capacity bytes, at least encoded_bound()); *out_len = bytes
     * written. Thread-safe. Returns 0, VTS_ERR_LIMIT when dst_capacity is too small, or another
     * negative status with a message. */
    int (*encode)(const struct vt_image *src, const struct vt_codec_params *params, void *dst,
                  size_t dst_capacity, size_t *out_len, struct vts_error *err);
    /* Decodes src into dst, which the caller allocated with the width, height, channels and sample
     * the store's layer declares. A payload of another shape, or malformed, gives VTS_ERR_BAD_INPUT
     * (never a crash, never a read outside src). Thread-safe. */
    int (*decode)(const void *src, size_t src_len, struct vt_image *dst, struct vts_error *err);
};

/* Lookup in the registry of codecs compiled into this build; NULL when unknown. */
const struct vt_codec *vt_codec_find(const char *name);
const struct vt_codec *vt_codec_by_fourcc(uint32_t fourcc);

/* All codecs of this build, in a stable order; *count receives their number. */
const struct vt_codec *const *vt_codec_list(size_t *count);

#endif
