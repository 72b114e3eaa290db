/* Tile counts and sizes of a store, per layer and level: stored, empty and shared tiles, unique
 * payload bytes, raw size, bits per texel and compression ratio. What vt-info prints; any tool
 * that reports on a store it wrote or read can use it. */
#ifndef VT_STORE_STATS_H
#define VT_STORE_STATS_H

#include <stdint.h>

#include "vt_error.h"
#include "vts.h"

/* Counts of one level of one layer, or sums of them. */
struct vt_tile_counts {
    uint64_t tiles;  /* index entries */
    uint64_t stored; /* entries with a payload */
    uint64_t empty;  /* entries without one */
    uint64_t shared; /* stored entries whose payload offset an earlier entry (index order) uses */
    uint64_t bytes;  /* payload bytes, each shared payload counted once */
    uint64_t raw_bytes; /* decoded size of the stored tiles: payload edge^2 * channels * sample */
};

struct vt_store_stats {
    uint32_t layer_count, level_count;
    struct vt_tile_counts
        *counts;                 /* level_count + 1 per layer, layer-major; the last: layer total */
    struct vt_tile_counts total; /* every layer and level */
    double bits_per_texel;    /* 8 * total.bytes / (total.stored * payload edge^2); NAN if none */
    double compression_ratio; /* total.raw_bytes / total.bytes; NAN when no payload byte */
};

/* Counts every index entry of store (no payload is read). Returns 0, or VTS_ERR_NOMEM with a
 * message. Release with vt_store_stats_release() either way. */
int vt_store_stats_init(struct vt_store_stats *st, const struct vts_store *store,
                        struct vts_error *err);

/* Frees the counts. Accepts NULL. */
void vt_store_stats_release(struct vt_store_stats *st);

/* Counts of level (< level_count) of layer, or the layer's total when level == level_count. */
const struct vt_tile_counts *vt_store_stats_at(const struct vt_store_stats *st, uint32_t layer,
                                               uint32_t level);

#endif
