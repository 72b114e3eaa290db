/* Private to lib/pyramid: the constants and helpers of the mip pyramid, and the description of one
 * pass. Data flows one way through the pyramid's files, each including this header and the
 * headers of the files below it only:
 *   vt_pyramid.c (the driver: plans the passes, fills struct vt_pyramid_pass for each)
 *   -> vt_pyramid_pass.c (runs one pass: margins, the blocks of each row on the pool, the band)
 *   -> vt_pyramid_block.c (one block: tiles, reductions, the next pass's texels)
 *   -> vt_pyramid_read.c (regions of a source with clamped or wrapped edges; bands of rows).
 * No file calls a function of a file above it. Beside them, vt_shard_seams.c (the levels of a
 * sharded build above its first pass, without wrap) is called by vt_pyramid.c and
 * vt_shard_merge.c and calls vt_pyramid_read.c and the float pass files only. */
#ifndef VT_PYRAMID_IMPL_H
#define VT_PYRAMID_IMPL_H

#include <stdbool.h>
#include <stdint.h>

#include "vt_filter.h"
#include "vt_image.h"
#include "vt_pyramid.h"

struct vt_float_file;

#define VT_PYRAMID_DEFAULT_LEVELS 2
#define VT_PYRAMID_MAX_LEVELS     6
/* coarser rows reduced from one converted band of input rows */
#define VT_PYRAMID_BAND_ROWS 16

/* One pass as its blocks see it: filled by the driver, completed (margin) by
 * vt_pyramid_pass_run() before any block runs, then only read (blocks get it const). */
struct vt_pyramid_pass {
    const struct vt_pyramid_options *o;
    struct vt_kernel kernel;
    struct vt_pixel_mode mode;
    bool source_is_working;          /* the source holds working-space floats (pass images) */
    bool emit_base;                  /* emit the base level's tiles (the first pass only) */
    bool carry;                      /* a shard: the last level goes to o->carry, not to next */
    bool has_alpha;                  /* last channel alpha: alpha-0 tiles are left empty */
    uint32_t base, depth;            /* base level, levels reduced in this pass */
    uint32_t w, h, channels, sample; /* the base level's size; the source's channels and sample */
    uint64_t block;                  /* block edge at the base level: content << levels per pass */
    struct vt_float_file *next;      /* the next pass's source (its last level), or NULL */
    uint64_t *done;                  /* tiles emitted so far (atomic) */
    uint32_t margin[VT_PYRAMID_MAX_LEVELS + 1]; /* per relative level (vt_pyramid_pass_run) */
};

static inline uint32_t vt_pyramid_level_extent(uint32_t size, uint32_t level)
{
    return (uint32_t)(((uint64_t)size + (1ull << level) - 1) >> level);
}

/* Levels reduced per pass: o->levels_per_pass, or the default, at most VT_PYRAMID_MAX_LEVELS. */
static inline uint32_t vt_pyramid_resolved_k(const struct vt_pyramid_options *o)
{
    uint32_t k = o->levels_per_pass ? o->levels_per_pass : VT_PYRAMID_DEFAULT_LEVELS;
    return k > VT_PYRAMID_MAX_LEVELS ? VT_PYRAMID_MAX_LEVELS : k;
}

/* A view of w x h texels of img at (x, y) (no copy; in bounds by contract). */
static inline struct vt_image vt_pyramid_view(const struct vt_image *img, int64_t x, int64_t y,
                                              uint32_t w, uint32_t h)
{
    struct vt_image v = *img;
    v.pixels = vt_image_at(img, (uint32_t)x, (uint32_t)y);
    v.width = w;
    v.height = h;
    return v;
}

#endif
