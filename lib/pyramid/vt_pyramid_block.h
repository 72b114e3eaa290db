/* One block of a mip pyramid pass (private to lib/): reads the block plus its margin, emits the
 * tiles it owns at the pass's base level, reduces it level by level in float working space
 * (emitting each level's tiles) and stores its last level for the next pass or a shard's carry. */
#ifndef VT_PYRAMID_BLOCK_H
#define VT_PYRAMID_BLOCK_H

#include <stdint.h>

#include "vt_pyramid_pass.h"

/* Region of relative level r (texels, with its margin) that block (bx, by) computes. */
void vt_pyramid_block_region(const struct vt_pyramid_pass *p, uint32_t bx, uint32_t by, uint32_t r,
                             struct vt_fregion *out);

/* Runs block (bx, by) of pass p on worker `worker` (its scratch p->scratch[worker]). 0 or the
 * status of a read, a reduction, the emit or the store. */
int vt_pyramid_block_run(struct vt_pyramid_pass *p, unsigned worker, uint32_t bx, uint32_t by,
                         struct vts_error *err);

#endif
