/* One block of a mip pyramid pass (private to lib/pyramid; see vt_pyramid_impl.h): reads the block
 * plus its margin, emits the tiles it owns at the pass's base level, reduces it level by level in
 * float working space (emitting each level's tiles) and stores its last level for the next pass or
 * a shard's carry. Also the per-worker scratch memory that takes. */
#ifndef VT_PYRAMID_BLOCK_H
#define VT_PYRAMID_BLOCK_H

#include <stddef.h>
#include <stdint.h>

#include "vt_error.h"
#include "vt_filter.h"
#include "vt_image.h"
#include "vt_pyramid_impl.h"
#include "vt_pyramid_read.h"
#include "vt_source.h"

/* One worker's buffers, sized for the largest block of a pass. */
struct vt_pyramid_block_scratch {
    struct vt_image in;                             /* allocation for block + margin */
    struct vt_image block;                          /* the current block: a tight view of in */
    struct vt_fregion w[VT_PYRAMID_MAX_LEVELS + 1]; /* working regions per relative level (w[0]:
                                                       geometry of the block, a view of in) */
    float *reduce_scratch;
    size_t reduce_floats;
    struct vt_image tile_full, tile; /* payload in out sample: source channels / out channels */
    struct vt_pyramid_read_scratch read;
};

/* Allocates s (zeroed by the caller) for the blocks of pass p (margins set). 0 or VTS_ERR_NOMEM;
 * release s either way. */
int vt_pyramid_block_scratch_alloc(const struct vt_pyramid_pass *p,
                                   struct vt_pyramid_block_scratch *s, struct vts_error *err);
void vt_pyramid_block_scratch_release(const struct vt_pyramid_pass *p,
                                      struct vt_pyramid_block_scratch *s);

/* Region of relative level r (texels, with its margin) that block (bx, by) computes. */
void vt_pyramid_block_region(const struct vt_pyramid_pass *p, uint32_t bx, uint32_t by, uint32_t r,
                             struct vt_fregion *out);

/* Runs block (bx, by) of pass p, reading src, with worker `worker`'s scratch s (the worker number
 * goes to o->emit and o->carry). 0 or the status of a read, a reduction, the emit or the store. */
int vt_pyramid_block_run(const struct vt_pyramid_pass *p, struct vt_pyramid_block_scratch *s,
                         struct vt_source *src, unsigned worker, uint32_t bx, uint32_t by,
                         struct vts_error *err);

#endif
