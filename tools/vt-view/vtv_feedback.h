/* vt-view tile determination: reduces the read-back feedback buffer (x, y, level, 1 per pixel) to
 * the list of tiles to show, with the number of pixels that want each, plus every ancestor of
 * each such tile (its count is the sum of its descendants'), sorted by pixel count (highest first,
 * then coarser level first, then index: a deterministic order). */
#ifndef VTV_FEEDBACK_H
#define VTV_FEEDBACK_H

#include <stddef.h>
#include <stdint.h>

#include "vtv_cache.h"

struct vtv_request {
    uint64_t index; /* vtv_cache_index */
    uint64_t pixels;
    uint32_t level, x, y;
};

struct vtv_feedback {
    struct vtv_request *items;
    size_t count, capacity;
    uint64_t *keys; /* scratch */
    size_t keys_capacity;
    uint64_t direct; /* tiles asked for by pixels, before the ancestors */
};

/* pixels: n RGBA16UI texels. Returns 0 or VTS_ERR_NOMEM. */
int vtv_feedback_reduce(struct vtv_feedback *f, const struct vtv_cache *c, const uint16_t *pixels,
                        size_t n);
void vtv_feedback_free(struct vtv_feedback *f);

#endif
