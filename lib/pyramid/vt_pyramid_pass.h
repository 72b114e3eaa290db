/* One pass of the mip pyramid (private to lib/, see vt_pyramid.h): the state the block workers
 * share, their scratch buffers, and running a pass's blocks row by row on the worker pool. The
 * blocks themselves are in vt_pyramid_block.c, reading the source in vt_pyramid_read.c. */
#ifndef VT_PYRAMID_PASS_H
#define VT_PYRAMID_PASS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "vt_error.h"
#include "vt_filter.h"
#include "vt_image.h"
#include "vt_pyramid.h"
#include "vt_source.h"

struct vt_float_file;

#define VT_PYRAMID_PASS_DEFAULT_LEVELS 2
#define VT_PYRAMID_PASS_MAX_LEVELS     6
/* coarser rows reduced from one converted band of input rows */
#define VT_PYRAMID_PASS_BAND_ROWS 16

/* One stretch of a region along one axis: dst positions [dst, dst + len) read source positions
 * [src, src + len), or all repeat source position src when replicate (clamped edge). */
struct vt_pyramid_pass_segment {
    int64_t dst;
    uint32_t src, len;
    bool replicate;
};

struct vt_pyramid_pass_scratch {
    struct vt_image in;                                  /* allocation for block + margin */
    struct vt_image block;                               /* the current block: a tight view of in */
    struct vt_fregion w[VT_PYRAMID_PASS_MAX_LEVELS + 1]; /* working regions per relative level */
    float *reduce_scratch;
    size_t reduce_floats;
    uint32_t band_rows;              /* rows of the w[0] band buffer (native sources) */
    struct vt_image tile_full, tile; /* payload in out sample: source channels / out channels */
    struct vt_pyramid_pass_segment *xs, *ys;
    size_t seg_cap;
};

struct vt_pyramid_pass_band {
    struct vt_image img; /* full-width rows [y0, y0 + img.height) */
    int64_t y0;
    bool valid;
};

struct vt_pyramid_pass {
    const struct vt_pyramid_options *o;
    struct vt_source *const *sources;
    struct vt_source band_source; /* reads from band for sequential inputs */
    struct vt_pyramid_pass_band band;
    bool sequential;
    bool source_is_working;
    bool emit_base;
    bool carry;              /* a shard: the last level goes to o->carry instead of a next pass */
    uint32_t base, depth, k; /* base level, levels reduced here, levels per pass */
    uint32_t w, h, channels, sample;
    uint64_t block; /* S = content << k */
    uint32_t margin[VT_PYRAMID_PASS_MAX_LEVELS + 1];
    uint32_t blocks_x, blocks_y, row, next_bx;
    uint32_t bx0, bx1, by0, by1; /* the blocks this pass runs */
    struct vt_kernel kernel;
    struct vt_pixel_mode mode;
    struct vt_float_file *next;
    struct vt_pyramid_pass_scratch *scratch;
    unsigned threads;
    uint64_t *done, total;
};

static inline uint32_t vt_pyramid_pass_level_extent(uint32_t size, uint32_t level)
{
    return (uint32_t)(((uint64_t)size + (1ull << level) - 1) >> level);
}

/* Levels reduced per pass: o->levels_per_pass, or the default, at most VT_PYRAMID_PASS_MAX_LEVELS.
 */
static inline uint32_t vt_pyramid_pass_resolved_k(const struct vt_pyramid_options *o)
{
    uint32_t k = o->levels_per_pass ? o->levels_per_pass : VT_PYRAMID_PASS_DEFAULT_LEVELS;
    return k > VT_PYRAMID_PASS_MAX_LEVELS ? VT_PYRAMID_PASS_MAX_LEVELS : k;
}

/* A view of w x h texels of img at (x, y) (no copy; in bounds by contract). */
static inline struct vt_image vt_pyramid_pass_view(const struct vt_image *img, int64_t x, int64_t y,
                                                   uint32_t w, uint32_t h)
{
    struct vt_image v = *img;
    v.pixels = vt_image_at(img, (uint32_t)x, (uint32_t)y);
    v.width = w;
    v.height = h;
    return v;
}

/* Runs pass p (its base, depth, sources and next/carry set by the caller): computes margins and
 * the blocks to run, allocates per-worker scratch, runs every block row on the pool (moving the
 * band first for a sequential source) and frees the scratch. 0 or a negative status. */
int vt_pyramid_pass_run(struct vt_pyramid_pass *p, struct vts_error *err);

#endif
