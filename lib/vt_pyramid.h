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
                                  struct vt_error *err);

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
};

/* Builds the pyramid. sources[0 .. threads-1] are independent handles on the same image (so that
 * workers can decode in parallel); a sequential source needs only sources[0] (others may be
 * NULL). Returns 0 or the first error (lowest block) with its message. */
int vt_pyramid_build(struct vt_source *const *sources, const struct vt_pyramid_options *o,
                     struct vt_error *err);

/* Tiles per layer the build emits (for progress totals). */
uint64_t vt_pyramid_tile_count(const struct vt_pyramid_options *o);

#endif
