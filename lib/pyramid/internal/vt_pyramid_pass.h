/* One pass of the mip pyramid (private to lib/pyramid; see vt_pyramid_impl.h): the blocks of a
 * pass run row by row on the worker pool, each worker with its own scratch, with a band of rows
 * standing in for a sequential source. */
#ifndef VT_PYRAMID_PASS_H
#define VT_PYRAMID_PASS_H

#include <stdbool.h>
#include <stdint.h>

#include "vt_error.h"
#include "vt_pyramid_impl.h"
#include "vt_source.h"

/* Runs pass p (everything but margin set by the caller; this sets margin first): the blocks of the
 * pass (all, or a shard's part of level 0), reading sources[worker] (sequential: sources[0] only,
 * through a band of rows that moves down with the block rows), on `threads` workers; progress
 * through p->o->progress with `total` tiles. 0 or a negative status. */
int vt_pyramid_pass_run(struct vt_pyramid_pass *p, struct vt_source *const *sources,
                        bool sequential, unsigned threads, uint64_t total, struct vts_error *err);

#endif
