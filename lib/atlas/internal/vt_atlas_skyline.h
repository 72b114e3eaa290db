/* Whole-tile packing for vt-atlas (lib/atlas/vt_atlas_pack.c): items measured in tiles placed by a
 * bottom-left skyline over tile columns; the atlas width is chosen among several near-square
 * candidates and two orders to minimise the area. */
#ifndef VT_ATLAS_SKYLINE_H
#define VT_ATLAS_SKYLINE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "vt_error.h"

struct vt_atlas_tile_item {
    uint32_t w, h;  /* in tiles */
    uint32_t index; /* rect index, or sub-tile tile number when subtile */
    bool subtile;
    uint32_t x, y; /* out, in tiles */
};

/* Places the n items (x, y filled, in tiles) in an atlas of at most max_tiles x max_tiles tiles
 * (max_edge texels, for messages) and returns its size in tiles in *out_w, *out_h. Returns 0,
 * VTS_ERR_LIMIT (an item or the whole does not fit) or VTS_ERR_NOMEM. Reorders items. */
int vt_atlas_skyline_pack(struct vt_atlas_tile_item *items, size_t n, uint32_t max_tiles,
                          uint32_t max_edge, uint32_t *out_w, uint32_t *out_h,
                          struct vts_error *err);

#endif
