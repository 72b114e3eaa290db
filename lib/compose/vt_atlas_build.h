/* Atlas compositing for vt-tiles --layout: the tiles of every level of an atlas
 * (lib/layout/vt_layout.h) computed from the source textures on demand, without ever holding a
 * whole level.
 *
 * Each texture file is decoded once; each entry's texture (per layer) becomes a mip chain
 * (vt_mip_chain.h, streamed by vt_chain_stream.h where it can be) kept as blocks in a bounded
 * cache that spills to a temporary file (vt_block_cache.h), shared by the workers. A level-L texel
 * whose level-0 footprint lies inside one entry's cell, with the entry aligned at 2^L, is "owned":
 * it reads that entry's chain at level L (clamped into the chain's rectangle, so cell padding, the
 * gutter before x/y of a cell that starts before its texture, and borders on a texture's edge
 * repeat that texture's edge texels, and filtering never mixes textures; a wrap entry's chain is
 * read modulo its size instead, so they show the opposite edge). The chain holds the entry's crop
 * of its copies. A texel whose footprint touches no cell is empty. Any other texel (coarse levels
 * above an entry's alignment) is "mixed": the coverage-weighted average, in the working space, of
 * its four children one level down. A tile whose content texels are all empty is emitted as empty.
 * Output has the layer's sample type (8-bit unless a texture is wider: vt_atlas_layer_format);
 * the bytes do not depend on the number of threads or on the cache size. Details
 * in docs/atlas-build.md. */
#ifndef VT_ATLAS_BUILD_H
#define VT_ATLAS_BUILD_H

#include <stdbool.h>
#include <stdint.h>

#include "vt_error.h"
#include "vt_filter.h"
#include "vt_image.h"
#include "vt_layout.h"
#include "vt_source.h"

/* Opens the texture file at path (a layout texture's resolved path) as a source. lib/ does not
 * read image files itself: tools pass vt_image_input_open() through this. Called from worker
 * threads at once (each call opens an independent source). Fills err naming the file on failure. */
typedef int (*vt_atlas_open_fn)(void *user, const char *path, struct vt_source *out,
                                struct vts_error *err);

/* Receives the payload of one tile of one built layer (slot 0 .. layer_count-1), or NULL for an
 * empty tile. Called from worker threads, each (slot, level, tx, ty) exactly once. */
typedef int (*vt_atlas_emit_fn)(void *user, unsigned worker, uint32_t slot, uint32_t level,
                                uint32_t tx, uint32_t ty, const struct vt_image *payload,
                                struct vts_error *err);

/* Progress: tile positions done of total; non-zero cancels. Called on the calling thread. */
typedef int (*vt_atlas_progress_fn)(void *user, uint64_t done, uint64_t total);

#define VT_ATLAS_BUILD_CACHE (256ull << 20) /* default chain block budget, bytes */

struct vt_atlas_layer_format;

/* Sharded atlas builds (docs/sharding.md, "Atlas shards"). Level 0 is cut into a grid of
 * 2^a x 2^(m - a) parts (count = 2^m) of 2^P x 2^P tiles, numbered row by row: the grid with the
 * smallest P that covers the atlas (ties: a = ceil(m/2), as image shards). A shard (merge false)
 * emits the tiles of levels 0..K (K = min(P, level_count - 1)) of its part: level K's tile is the
 * part. The merge (merge true) emits the levels above K from what the shards carry
 * (vt_atlas_build_carry()): each texel of level K of their part in the working space, and the
 * chains above K of the entries whose cell starts in their part. Every tile has the single build's
 * bytes. */
struct vt_atlas_build_part {
    uint32_t index, count; /* part (0-based) of count (a power of two); count 0: the whole build */
    bool merge;            /* the merge of count parts (textures are not read) */
    const struct vt_atlas_layer_format *formats; /* merge: per slot, the shards' formats */
};

struct vt_atlas_build_options {
    const struct vt_layout *layout; /* read and checked (vt_layout_read); must outlive the build */
    const uint32_t *layers;         /* layout layer indices to build, in store order */
    uint32_t layer_count;           /* 1..VT_LAYOUT_MAX_LAYERS */
    uint32_t level_count;           /* 0 = every level (down to one tile) */
    enum vt_filter_kind filter;     /* mip filter of the textures' chains */
    unsigned threads;               /* 1..256 */
    uint64_t cache_bytes; /* decoded chain blocks kept in memory; 0 = VT_ATLAS_BUILD_CACHE */
    const char *temp_dir; /* where chain blocks over the budget spill; NULL = $TMPDIR or /tmp */
    uint64_t max_pixels;  /* per entry chain (its crop of the copies); 0 = 2^34 */
    vt_atlas_open_fn open;
    void *open_user;
    vt_atlas_progress_fn progress; /* optional, for the texture scan of create() too */
    void *progress_user;
    struct vt_atlas_build_part part; /* zero: the whole build */
};

/* Output format of one built layer: colour_channels (1 when every texture of the layer is grey,
 * else 3) plus alpha when some texture of the layer is not opaque. The sample type is the widest
 * its textures need: u8 when every texture is 8-bit; u16 when some is 16-bit and none is float;
 * with a float texture, f16 when every float texture is f16 and none is 16-bit, else f32 (a
 * 16-bit texture does not fit in f16's 11 bits). A float layer holds linear values: the layout's
 * sRGB colour becomes linear (8- and 16-bit sRGB textures are decoded into it). */
struct vt_atlas_layer_format {
    uint32_t channels;
    uint32_t colour_channels;
    bool alpha;
    uint32_t colour;      /* enum vts_colour: the layout layer's (linear for its sRGB in floats) */
    uint32_t sample;      /* enum vts_sample */
    uint32_t textures[4]; /* texture files of the layer by sample type (index sample - 1) */
    bool has_range;       /* f16/f32 layers and u16 layers not sRGB: range holds */
    float range[2];       /* the smallest and largest finite colour value (alpha excluded) of
                             the layer's level 0 over its entries (u16: normalised), empty space
                             excluded */
};

struct vt_atlas_build;

/* Opens every texture of the built layers once (in parallel): checks that it exists, that its
 * size is the one the layout records, and scans alpha channels to decide the layer formats.
 * Returns NULL and fills err ("'wood.png': ...") on failure. Free with vt_atlas_build_destroy(). */
struct vt_atlas_build *vt_atlas_build_create(const struct vt_atlas_build_options *o,
                                             struct vts_error *err);

void vt_atlas_build_format(const struct vt_atlas_build *b, uint32_t slot,
                           struct vt_atlas_layer_format *out);

/* Levels the build emits, and tile positions per layer (for progress). */
uint32_t vt_atlas_build_level_count(const struct vt_atlas_build *b);
uint64_t vt_atlas_build_tile_count(const struct vt_atlas_build *b);

/* Computes and emits every tile of every built layer, on the option's threads. Returns 0, the
 * first error (lowest tile) or VTS_ERR_CANCELLED. */
int vt_atlas_build_tiles(struct vt_atlas_build *b, vt_atlas_emit_fn emit, void *user,
                         struct vts_error *err);

/* Texels [x, x + dst->width) x [y, y + dst->height) of level `level` of slot into dst (the slot's
 * sample type and channels), as the tiles' content holds them (empty space: zero, a flat normal for
 * normal layers). Single-threaded; for --export-atlas. */
int vt_atlas_build_render(struct vt_atlas_build *b, uint32_t slot, uint32_t level, uint32_t x,
                          uint32_t y, struct vt_image *dst, struct vts_error *err);

struct vt_atlas_build_stats {
    uint64_t chains_built;  /* texture decodes: each file once, unless noted in atlas-build.md */
    uint64_t cache_peak;    /* most chain block bytes held in memory at once */
    uint64_t cache_budget;  /* the budget they were held to (unpinned blocks never exceed it) */
    uint64_t buffers_peak;  /* most bytes of texture-pass buffers counted in that budget at once */
    uint64_t spilled_bytes; /* chain block bytes written to the temporary file */
    uint64_t tiles_empty;   /* tile positions emitted empty (per layer) */
    uint64_t texels_mixed;  /* coarse texels computed from several cells */
};
void vt_atlas_build_stats(const struct vt_atlas_build *b, struct vt_atlas_build_stats *out);

/* Sharded builds: the carried level K, and whether the merge has levels to build (K is not the
 * top level). */
uint32_t vt_atlas_build_carried_level(const struct vt_atlas_build *b);
bool vt_atlas_build_carries(const struct vt_atlas_build *b);

/* The tile of level K that part `index` (0-based) is: (*px, *py); false when the part lies past
 * the atlas (no tile, nothing carried). */
bool vt_atlas_build_part_tile(const struct vt_atlas_build *b, uint32_t index, uint32_t *px,
                              uint32_t *py);

/* Shard: what the merge needs from this part (see vt_atlas_build_part), as one payload of
 * *len bytes (malloc'd into *payload; 0 bytes when the build carries nothing). Call after
 * vt_atlas_build_tiles(). Little-endian: per slot, the part's texels of level K row by row,
 * channels + 1 floats each (value in the working space, coverage); then a u32 count of entries
 * and per entry its u32 index and, per slot, its chain's levels K + 1.. as 8-bit texels. */
int vt_atlas_build_carry(struct vt_atlas_build *b, unsigned char **payload, size_t *len,
                         struct vts_error *err);

/* Merge: takes part `index`'s payload (from vt_atlas_build_carry()). Every part must be put
 * before vt_atlas_build_tiles(). VTS_ERR_BAD_INPUT when it is not such a payload. */
int vt_atlas_build_put_carry(struct vt_atlas_build *b, uint32_t index, const unsigned char *payload,
                             size_t len, struct vts_error *err);

/* Frees everything. Accepts NULL. */
void vt_atlas_build_destroy(struct vt_atlas_build *b);

#endif
