/* Sharded builds (docs/sharding.md): what `vt-tiles --shard I/N` writes beside its tiles and what
 * vt-merge reads back to finish the build.
 *
 * A shard store has the single build's geometry, its layer, and one extra last layer named
 * VT_SHARD_LAYER_NAME (RAW, F32, the input's channel count) that holds the float texels the merge
 * needs from the shard: without wrap (carry=seams), the rectangles along the seams between parts
 * at every level from levels_per_pass up (vt_shard_seams.h); with wrap (carry=level), every
 * texel the shard's first-pass blocks computed of level levels_per_pass, one tile per block. Each
 * payload holds the texels of one rectangle inside its tile's content area, rows top to bottom,
 * little-endian, nothing else (the merge derives the rectangle from the geometry): it is not a
 * RAW tile of payload size. Its metadata is the single build's plus VT_SHARD_KEY=I/N,
 * VT_SHARD_BUILD_KEY (what the remaining levels need) and VT_SHARD_INPUT_KEY (size and time of
 * the input, to refuse shards of another build). A merge of the complete set drops the extra
 * layer and the shard keys. */
#ifndef VT_SHARD_H
#define VT_SHARD_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "vt_error.h"

#define VT_SHARD_KEY        "shard"       /* I/N */
#define VT_SHARD_BUILD_KEY  "shard.build" /* vt_shard_build_format() */
#define VT_SHARD_INPUT_KEY  "shard.input" /* size=BYTES mtime=SECONDS */
#define VT_SHARD_RANGE_KEY  "shard.range" /* an atlas shard's part of the "range" key */
#define VT_SHARD_LAYER_NAME "shard.carry"
#define VT_SHARD_MAX_COUNT  4096u

/* What the passes after the first need that the store's layer and metadata do not say. */
struct vt_shard_build {
    uint32_t levels_per_pass; /* the carried level */
    uint32_t channels;        /* of the input (the carried texels) */
    bool has_alpha, premultiplied;
    uint32_t subsampling; /* jpeg chroma subsampling: 420 or 444 */
    uint32_t effort;      /* codec effort (png level, bc mode) */
    bool seams;           /* carry=seams (no wrap: the shards built the levels above their first
                             pass but along the seams), else carry=level */
};

/* Parses "I/N" (1 <= I <= N, N a power of two up to VT_SHARD_MAX_COUNT). Returns 0 or -1. */
int vt_shard_parse(const char *text, uint32_t *index, uint32_t *count);

/* Formats/parses the VT_SHARD_BUILD_KEY value. Parse returns 0, or -1 when malformed. */
void vt_shard_build_format(const struct vt_shard_build *b, char *out, size_t cap);
int vt_shard_build_parse(const char *text, struct vt_shard_build *out);

/* Packs width x height texels of `channels` floats (rows `stride` floats apart) into a carried
 * payload: width * height * channels little-endian floats. */
void vt_shard_pack(unsigned char *payload, const float *texels, uint32_t width, uint32_t height,
                   uint32_t channels, size_t stride);

/* Unpacks row `row` of such a payload of rows `width` texels wide into out. */
void vt_shard_unpack_row(const unsigned char *payload, uint32_t width, uint32_t channels,
                         uint32_t row, float *out);

#endif
