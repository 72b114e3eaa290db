/* Private state header of module vt_atlas_build: per-tile compositing (vt_atlas_tile.c, the part
 * of the build that makes one tile): which entry owns each texel of a level (the owner rule), the
 * coverage-weighted average of texels that several cells or empty space share (mixed texels), and
 * the payload of one tile with its borders. */
#ifndef VT_ATLAS_BUILD_IMPL_H
#define VT_ATLAS_BUILD_IMPL_H

#include <stdbool.h>
#include <stdint.h>

#include "vt_atlas_build.h"
#include "vt_block_cache.h"
#include "vts.h"

#define VT_ATLAS_TILE_EMPTY (-1) /* texel class: no entry covers it */
#define VT_ATLAS_TILE_MIXED (-2) /* texel class: covered in part, or by several entries */

/* One layer being built: its layout layer, pixel format and the value of empty texels. */
struct vt_atlas_tile_slot {
    uint32_t layer;
    struct vt_atlas_layer_format fmt;
    struct vt_pixel_mode mode;
    size_t texel_bytes; /* channels x the sample's bytes */
    bool srgb_source;   /* a float layer of an sRGB layout layer (vt_mip_chain_spec's) */
    uint8_t empty_px[16];
};

/* Scratch of one worker: its pinned chain blocks (the last one read kept at hand), the classes of
 * the current tile's content texels (content x content) and one payload image per slot. */
struct vt_atlas_tile_worker {
    struct vt_block_cache_pins pins;
    uint64_t last_id;
    const uint8_t *last_px; /* NULL: none */
    int32_t *cls;
    struct vt_image payload[VT_LAYOUT_MAX_LAYERS];
};

/* Where the chain of one (entry, slot) key lives in the block cache: level L is
 * ceil(w0 / 2^L) x ceil(h0 / 2^L) texels (1 x 1 for a constant fill) cut in blocks of
 * VT_BLOCK_CACHE_EDGE, row-major, ids from base[L]. */
struct vt_atlas_chain_info {
    uint32_t w0, h0, levels;
    bool fill;
    uint64_t base[VTS_MAX_LEVELS];
};

/* What the compositor reads: the layout, its level sizes, the entry grid and the chains' blocks
 * (keys entry * nslots + slot). Filled by vt_atlas_build.c, the grid by _build_grid, the chains
 * by vt_atlas_chains_build. */
struct vt_atlas_tile {
    const struct vt_layout *lay;
    struct vt_atlas_tile_slot slots[VT_LAYOUT_MAX_LAYERS];
    uint32_t nslots;
    uint32_t content, border, payload;
    uint32_t lw[VTS_MAX_LEVELS + 1],
        lh[VTS_MAX_LEVELS + 1]; /* + 1: keeps GCC's bounds check quiet */
    uint8_t *lmax;              /* per entry: log2(alignment) */
    /* grid over level 0: buckets of 2^gshift texels listing the entries whose cell meets them */
    uint32_t gshift, gw, gh;
    uint32_t *goff, *gidx, *gsat;
    struct vt_block_cache *blocks;
    struct vt_atlas_chain_info *chains; /* per key */
    uint64_t texels_mixed;              /* updated atomically */
    /* sharded builds (vt_atlas_shard.c): entries whose chains a shard builds (NULL: all), and
     * in the merge the carried level, whole: per slot, (value in the working space, coverage)
     * of each texel, channels + 1 floats; NULL in a shard and in a single build */
    const uint8_t *need;
    uint32_t carried_level;
    float *carried[VT_LAYOUT_MAX_LAYERS];
};

/* The build (vt_atlas_build.c), shared with the shard and merge parts (vt_atlas_shard.c). */
struct vt_atlas_build {
    struct vt_atlas_tile t; /* what the compositor reads, the chain cache included */
    struct vt_atlas_build_options o;
    uint32_t level_count;
    uint32_t tx[VTS_MAX_LEVELS + 1], ty[VTS_MAX_LEVELS + 1];
    uint64_t first[VTS_MAX_LEVELS + 1]; /* job number of each level's first tile */
    uint64_t tiles_empty, decodes;
    struct vt_atlas_tile_worker *workers; /* threads + 1 (the last for render) */
    /* a shard (part.count > 0, not merge): the tiles of levels 0..carried of its part; the merge
     * (part.merge): the levels above; vt_atlas_shard.c */
    struct vt_atlas_build_part part;
    uint32_t part_shift;     /* a part is 2^part_shift x 2^part_shift tiles of level 0 */
    uint32_t carried;        /* min(part_shift, level_count - 1) */
    uint32_t part_x, part_y; /* the shard's part: column and row */
    uint32_t parts_x;        /* parts per row of the grid */
    uint8_t *need;
};

/* Whether the build emits tile (L, tx, ty): every tile, or a shard's or the merge's
 * (vt_atlas_shard.c). */
bool vt_atlas_shard_emits(const struct vt_atlas_build *b, uint32_t L, uint32_t tx, uint32_t ty);

/* Shards: after geometry, the part's place and the entries it needs (b->need, t.need); the
 * merge: the chains' plan of the levels above the carried one and the slots' formats. 0 or the
 * first error. */
int vt_atlas_shard_prepare(struct vt_atlas_build *b, struct vts_error *err);

/* The working-space value and coverage (0: empty, 1: owned) of texel (X, Y) of level L, as a
 * mixed texel of level L + 1 reads it. */
int vt_atlas_tile_working(struct vt_atlas_tile *t, struct vt_atlas_tile_worker *w, uint32_t s,
                          uint32_t L, uint32_t X, uint32_t Y, float *v, float *cov,
                          struct vts_error *err);

/* Sets the slot's texel bytes, pixel mode and empty texel from its fmt (the chains' decision or,
 * in a merge, the shards'). */
void vt_atlas_slot_derive(struct vt_atlas_tile_slot *sl);

/* The texture pass (vt_atlas_chains.c): opens every texture of the built layers (checking its
 * size), decides the layer formats (t->slots[].fmt, mode, empty_px), then decodes each texture
 * file once and streams its chains into t->blocks (created here, o->cache_bytes of memory). Keys
 * are built on o->threads. *decodes receives the texture decodes. 0 or the first error. */
int vt_atlas_chains_build(struct vt_atlas_tile *t, const struct vt_atlas_build_options *o,
                          uint32_t level_count, uint64_t *decodes, struct vts_error *err);

/* Drops the worker's pins (and its last block). */
void vt_atlas_tile_unpin(struct vt_atlas_tile *t, struct vt_atlas_tile_worker *w);

/* Builds the entry grid of t->lay. 0 or VTS_ERR_NOMEM; free with vt_atlas_tile_release_grid. */
int vt_atlas_tile_build_grid(struct vt_atlas_tile *t, struct vts_error *err);

/* Frees the grid (NULL pointers allowed). */
void vt_atlas_tile_release_grid(struct vt_atlas_tile *t);

/* Class of texel (X, Y) of level L: the owning entry (>= 0), VT_ATLAS_TILE_EMPTY or
 * VT_ATLAS_TILE_MIXED. For an owned texel, *run_end is the first X of the row past the owner's
 * cell. Thread safe. */
int32_t vt_atlas_tile_classify(const struct vt_atlas_tile *t, uint32_t L, uint32_t X, uint32_t Y,
                               uint32_t *run_end);

/* Writes the value (slot s, its sample type) of texel (X, Y) of level L whose class is k into o. */
int vt_atlas_tile_texel(struct vt_atlas_tile *t, struct vt_atlas_tile_worker *w, uint32_t s,
                        uint32_t L, uint32_t X, uint32_t Y, int32_t k, uint8_t *o,
                        struct vts_error *err);

/* Classes of the content texels of the tile at (cx0, cy0), cw x chh, into w->cls; returns
 * whether any is not empty. */
bool vt_atlas_tile_classify_content(const struct vt_atlas_tile *t, struct vt_atlas_tile_worker *w,
                                    uint32_t L, uint32_t cx0, uint32_t cy0, uint32_t cw,
                                    uint32_t chh);

/* Fills w->payload[s] (content plus borders) of that tile, after _classify_content. */
int vt_atlas_tile_fill_payload(struct vt_atlas_tile *t, struct vt_atlas_tile_worker *w, uint32_t s,
                               uint32_t L, uint32_t cx0, uint32_t cy0, uint32_t cw, uint32_t chh,
                               struct vts_error *err);

#endif
