/* Sharded builds (docs/sharding.md): what `vt-tiles --shard I/N` writes beside its tiles and what
 * vt-merge reads back to finish the build.
 *
 * A shard store has the single build's geometry, its layer, and one extra last layer named
 * VT_SHARD_LAYER_NAME (RAW, F32, the input's channel count) that holds, at level levels_per_pass
 * only, the float texels the shard's first-pass blocks computed of that level: one tile per block,
 * the texels in the tile's content area (border and texels past the level's edge are 0). Its
 * metadata is the single build's plus VT_SHARD_KEY=I/N, VT_SHARD_BUILD_KEY (what the remaining
 * passes need) and VT_SHARD_INPUT_KEY (size and time of the input, to refuse shards of another
 * build). A merge of the complete set drops the extra layer and the shard keys. */
#ifndef VT_SHARD_H
#define VT_SHARD_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "vt_error.h"

#define VT_SHARD_KEY        "shard"       /* I/N */
#define VT_SHARD_BUILD_KEY  "shard.build" /* vt_shard_build_format() */
#define VT_SHARD_INPUT_KEY  "shard.input" /* size=BYTES mtime=SECONDS */
#define VT_SHARD_LAYER_NAME "shard.carry"
#define VT_SHARD_MAX_COUNT  4096u

/* What the passes after the first need that the store's layer and metadata do not say. */
struct vt_shard_build {
    uint32_t levels_per_pass; /* the carried level */
    uint32_t channels;        /* of the input (the carried texels) */
    bool has_alpha, premultiplied;
    uint32_t subsampling; /* jpeg chroma subsampling: 420 or 444 */
    uint32_t effort;      /* codec effort (png level, bc mode) */
};

/* Parses "I/N" (1 <= I <= N, N a power of two up to VT_SHARD_MAX_COUNT). Returns 0 or -1. */
int vt_shard_parse(const char *text, uint32_t *index, uint32_t *count);

/* Formats/parses the VT_SHARD_BUILD_KEY value. Parse returns 0, or -1 when malformed. */
void vt_shard_build_format(const struct vt_shard_build *b, char *out, size_t cap);
int vt_shard_build_parse(const char *text, struct vt_shard_build *out);

/* Packs width x height texels of `channels` floats (rows `stride` floats apart) into a RAW F32
 * payload of payload_px square texels at (border, border), little-endian, zeros elsewhere. */
void vt_shard_pack(unsigned char *payload, uint32_t payload_px, uint32_t border,
                   const float *texels, uint32_t width, uint32_t height, uint32_t channels,
                   size_t stride);

/* Unpacks `count` texels of row `row` of the content area of such a payload into out. */
void vt_shard_unpack_row(const unsigned char *payload, uint32_t payload_px, uint32_t border,
                         uint32_t channels, uint32_t row, uint32_t count, float *out);

#endif
