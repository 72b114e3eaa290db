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
};

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
