/* A cache of decoded native tiles shared by the workers reading one tiled image (tiled TIFF, tiled
 * EXR). Blocks of the pyramid overlap their neighbours by a few texels; without the cache each
 * native tile on a block edge would be decoded by every block that touches it. */
#ifndef VT_TILE_CACHE_H
#define VT_TILE_CACHE_H

#include <stddef.h>

#include "vt_error.h"
#include "vt_source.h"

struct vt_tile_cache;

/* Wraps n independent sources of one tiled image (info.tile_w and tile_h > 0) into n sources
 * (out[0..n-1]) that decode through their own handle but share decoded tiles, up to budget_bytes
 * (tiles of the highest rows are dropped first, since the blocks go down the image row by row; the
 * least recently used among a row's). Close the out sources, then destroy the cache;
 * the wrapped sources stay owned by the caller. Returns NULL and fills err on failure. */
struct vt_tile_cache *vt_tile_cache_create(struct vt_source *const *sources, unsigned n,
                                           size_t budget_bytes, struct vt_source *out,
                                           struct vts_error *err);

/* Tiles decoded and tiles served from the cache so far (for reports and tests). */
void vt_tile_cache_counts(struct vt_tile_cache *c, unsigned long long *decoded,
                          unsigned long long *hits);

void vt_tile_cache_destroy(struct vt_tile_cache *c);

#endif
