/* Texel statistics of a store's level (vt-info --stats): per channel the minimum, maximum, mean
 * and standard deviation of the level's texels (tile contents inside the level, borders left
 * out), as gdalinfo -stats reports them for a raster band. u8 and u16 samples count as their
 * integer codes, f16 and f32 as their values; NaNs are counted apart, not in the moments; empty
 * tiles are zeros (what a reader of the store gets for them) and are counted. */
#ifndef VT_LEVEL_STATS_H
#define VT_LEVEL_STATS_H

#include <stdint.h>

#include "vt_error.h"
#include "vt_tile_reader.h"

struct vt_channel_stats {
    double min, max, mean, stddev; /* over the texels that are not NaN (all 0 when none) */
    uint64_t nan;                  /* NaN samples */
};

struct vt_level_stats {
    uint64_t texels;      /* width x height of the level */
    uint64_t empty_tiles; /* tiles without a payload (zeros) */
    uint32_t channels;
    struct vt_channel_stats ch[4];
};

/* Computes the statistics of level (< level count) of the reader's layer, reading every tile of
 * the level once. Returns 0, or the status of a tile read with its message (vt_tile_reader_read).
 */
int vt_level_stats_compute(struct vt_tile_reader *r, uint32_t level, struct vt_level_stats *out,
                           struct vts_error *err);

#endif
