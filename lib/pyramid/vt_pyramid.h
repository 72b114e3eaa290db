/* Out-of-core mip pyramid with bordered tiles (the heart of vt-tiles).
 *
 * The image is processed in square blocks of tile_content_px << levels_per_pass texels. A block
 * reads its texels plus a margin from the source, emits the level-0 tiles it owns, reduces itself
 * levels_per_pass times (in float working space) and emits the tiles it owns at each level; its
 * last level is written to a temporary float image that is the source of the next pass. Memory is
 * bounded by the block size, the number of workers and (for sequential inputs such as PNG) one
 * band of block rows; never by the image area. Every texel is computed from the same finer texels
 * in the same order whatever the block split or thread count, so output bytes do not depend on -j.
 */
#ifndef VT_PYRAMID_H
#define VT_PYRAMID_H

#include <stdbool.h>
#include <stdint.h>

#include "vt_error.h"
#include "vt_filter.h"
#include "vt_image.h"
#include "vt_source.h"

/* Receives each tile's payload texels (tile_payload_px square, the output channels and sample),
 * or NULL for a tile whose texels are all transparent (empty). Called from worker threads
 * (worker = 0..threads-1) in no particular order; each tile exactly once. */
typedef int (*vt_pyramid_emit_fn)(void *user, unsigned worker, uint32_t level, uint32_t tx,
                                  uint32_t ty, const struct vt_image *payload,
                                  struct vts_error *err);

/* Sharded builds (docs/sharding.md): receives the texels a first-pass block computed of the pass's
 * last level (relative level levels_per_pass): width x height texels of `channels` floats in the
 * working space at (x, y) of that level, rows `stride` floats apart. Called from worker threads,
 * once per block. */
typedef int (*vt_pyramid_carry_fn)(void *user, unsigned worker, uint32_t x, uint32_t y,
                                   uint32_t width, uint32_t height, uint32_t channels,
                                   const float *texels, size_t stride, struct vts_error *err);

/* Sharded builds without wrap (docs/sharding.md, "Seams"): receives a rectangle of texels of
 * level `level` (levels_per_pass or above) that the merge needs from this shard, width x height
 * texels of `channels` working floats at (x, y), inside one tile of that level, rows `stride`
 * floats apart. Called on the calling thread. */
typedef int (*vt_pyramid_seam_fn)(void *user, uint32_t level, uint32_t x, uint32_t y,
                                  uint32_t width, uint32_t height, uint32_t channels,
                                  const float *texels, size_t stride, struct vts_error *err);

/* Progress: tiles done of total; a non-zero return cancels. Called on the calling thread. */
typedef int (*vt_pyramid_progress_fn)(void *user, uint64_t done, uint64_t total);

struct vt_pyramid_options {
    uint32_t width, height;   /* must equal the source's */
    uint32_t tile_content_px; /* content edge */
    uint32_t border_px;       /* border on each side */
    uint32_t level_count;     /* levels to emit: 1 .. full count */
    enum vt_filter_kind filter;
    uint32_t colour;          /* enum vts_colour of the output */
    bool wrap;                /* borders and filters wrap (tiling texture) */
    uint32_t out_channels;    /* source channels, or one fewer to drop an (opaque) alpha */
    uint32_t out_sample;      /* enum vts_sample of payloads */
    unsigned threads;         /* workers, >= 1 */
    uint32_t levels_per_pass; /* 1..6; 0 = default (2) */
    const char *temp_dir;     /* where pass images go (unlinked at once); NULL = "." */
    vt_pyramid_emit_fn emit;
    vt_pyramid_progress_fn progress;
    void *user;
    /* Shard (part of level 0): when part is set, only the first pass runs, on the blocks
     * [part_x0, part_x1) x [part_y0, part_y1) (see vt_pyramid_part()); it emits their tiles of
     * levels 0 .. levels_per_pass and hands their texels of the last one to carry (when a next
     * pass exists). Reads still use the whole source (margins), so these tiles are exact. */
    bool part;
    uint32_t part_x0, part_y0, part_x1, part_y1; /* may be empty: nothing is emitted */
    vt_pyramid_carry_fn carry;
    /* With part_count set (the part is part_index of vt_pyramid_part(..., part_count)) and without
     * wrap, the shard goes on above its first pass instead: it builds every texel of the levels
     * above that it can compute exactly, emits the tiles that lie inside them and hands
     * seam_carry the texels along the seams between parts that the merge needs (carry is then
     * not called). */
    uint32_t part_index, part_count;
    vt_pyramid_seam_fn seam_carry;
    /* Resume (merging shards): when set, the first pass is skipped; sources[] read the first
     * pass's last level (F32 working texels of resume_input->channels, level levels_per_pass)
     * assembled from the carried parts, and the build emits the levels above it. resume_input
     * describes the original input (channels, has_alpha, premultiplied). */
    const struct vt_source_info *resume_input;
};

/* The first pass of a build: levels per pass (k, resolved), whether a next pass exists (then the
 * carried level is k and every block carries one tile of it), the block edge and the blocks. */
struct vt_pyramid_plan {
    uint32_t levels_per_pass;
    bool has_next;
    uint64_t block;
    uint32_t blocks_x, blocks_y;
    uint32_t carry_width, carry_height; /* size of level k when has_next */
};
void vt_pyramid_plan(const struct vt_pyramid_options *o, struct vt_pyramid_plan *out);

/* Part index (0 .. count-1, count a power of two) of a split of level 0 into a grid of
 * 2^ceil(log2(count)/2) x 2^floor(log2(count)/2) parts, row-major, each ceil(blocks/grid) blocks
 * (the last ones smaller, possibly empty). Returns false for a bad index or count. */
bool vt_pyramid_part(const struct vt_pyramid_plan *plan, uint32_t index, uint32_t count,
                     uint32_t *x0, uint32_t *y0, uint32_t *x1, uint32_t *y1);

/* The part grid of vt_pyramid_part(plan, ..., count): *gx columns and *gy rows, the first-pass
 * block where each begins and ends in xcuts[0 .. *gx] and ycuts[0 .. *gy] (at most 65 each).
 * Returns false for a bad count. */
bool vt_pyramid_part_cuts(const struct vt_pyramid_plan *plan, uint32_t count, uint32_t *xcuts,
                          uint32_t *gx, uint32_t *ycuts, uint32_t *gy);

/* True when the shards of build *o continue above their first pass (part_count set, no wrap,
 * levels above the first pass): their seam texels go to seam_carry, see vt_shard_seams. */
bool vt_pyramid_part_seams(const struct vt_pyramid_options *o);

/* Builds the pyramid. sources[0 .. threads-1] are independent handles on the same image (so that
 * workers can decode in parallel); a sequential source needs only sources[0] (others may be
 * NULL). Returns 0 or the first error (lowest block) with its message. */
int vt_pyramid_build(struct vt_source *const *sources, const struct vt_pyramid_options *o,
                     struct vts_error *err);

/* Tiles per layer the build emits (for progress totals; a shard's or a resumed build's own). */
uint64_t vt_pyramid_tile_count(const struct vt_pyramid_options *o);

#endif
