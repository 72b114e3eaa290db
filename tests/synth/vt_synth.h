/* Seeded generator of valid .vts stores for tests and the demo. Texel values are a function of
 * (layer, level, texel position, channel), so borders and stitched levels can be checked exactly.
 */
#ifndef VT_SYNTH_H
#define VT_SYNTH_H

#include <stdbool.h>
#include <stdint.h>

#include "vt_error.h"

struct vt_synth_options {
    uint32_t width, height; /* level 0, texels */
    uint32_t tile_content_px;
    uint32_t border_px;
    uint32_t layer_count;
    uint32_t codec;    /* VTS_CODEC_RAW or VTS_CODEC_PNG */
    uint32_t channels; /* 1..4 */
    uint32_t sample;   /* enum vts_sample */
    uint32_t seed;
    bool empty_tiles; /* level-0 tiles with (tx + 2 * ty) % 7 == 3 are empty */
    bool flat_left;   /* the left quarter of every level is one flat colour: dedup */
};

/* Default options: 300x200, 64 px content, border 2, one RGBA8 raw layer, seed 1. */
void vt_synth_defaults(struct vt_synth_options *o);

/* Texel value (as a double in [0,1]) that the generator stores; x/y are clamped to the level. */
double vt_synth_texel(const struct vt_synth_options *o, uint32_t layer, uint32_t level, int64_t x,
                      int64_t y, uint32_t channel);

/* True when the generator leaves tile (tx, ty) of level empty. */
bool vt_synth_tile_is_empty(const struct vt_synth_options *o, uint32_t level, uint32_t tx,
                            uint32_t ty);

/* Writes a complete store at path (metadata: generator=vt-synth, seed=<seed>). */
int vt_synth_store(const char *path, const struct vt_synth_options *o, struct vts_error *err);

#endif
