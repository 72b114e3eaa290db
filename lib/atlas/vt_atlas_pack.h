/* Tile-aware rectangle packing for atlases (vt-atlas): pure computation, no I/O. See
 * docs/atlas-packing.md.
 *
 * Rules. With T the tile content edge (a power of two):
 * - a rectangle with both edges <= T (sub-tile) shares tiles only with other sub-tile cells.
 *   With a gutter G > 0 its cell edge is edge + 2G rounded up to a multiple of G, the content
 *   sits G texels in (x = cell_x + G), cells go on shelves inside the tiles and alignment = G
 *   (every position and size is a multiple of G); an axis where edge + 2G exceeds T gets a
 *   T-wide cell without gutter (its sides are tile edges, which tile borders clamp). Without
 *   gutter the cell edges are the next powers of two of the edges, at a multiple of the cell
 *   size (a guillotine split of power-of-two blocks, i.e. a 2D buddy; alignment = the smaller
 *   cell edge) and x = cell_x;
 * - a larger rectangle gets a cell rounded up to whole tiles, at a tile corner (alignment T);
 * - tiles are packed at tile granularity (skyline, tallest first) into an atlas of whole tiles
 *   whose width is chosen among near-square candidates to minimise the area; when everything fits
 *   in one tile the atlas shrinks to the used power-of-two corner of it.
 * Cells never overlap and free space outside the sub-tile tiles is whole tiles. */
#ifndef VT_ATLAS_PACK_H
#define VT_ATLAS_PACK_H

#include <stdint.h>

#include "vt_error.h"

#ifdef __cplusplus
extern "C" {
#endif

/* One rectangle to place. */
struct vt_atlas_rect {
    uint32_t width, height;           /* in: texels needed (all copies), >= 1 */
    uint32_t x, y;                    /* out: top-left texel of the content */
    uint32_t cell_x, cell_y;          /* out: top-left texel of the cell (<= x, y: the gutter) */
    uint32_t cell_width, cell_height; /* out: the exclusive cell, >= gutter + width, height */
    uint32_t alignment; /* out: power of two dividing x, y, the cell corner and edges */
};

/* The default gutter of vt-atlas (--gutter): see docs/atlas-packing.md for its cost. */
#ifndef VT_ATLAS_DEFAULT_GUTTER
#define VT_ATLAS_DEFAULT_GUTTER 4
#endif

struct vt_atlas_pack_options {
    uint32_t tile_content; /* tile content edge, a power of two 1..2^16 */
    uint32_t max_edge;     /* largest atlas width or height in texels (>= tile_content) */
    uint32_t gutter;       /* texels reserved on each side of a sub-tile rectangle inside its cell
                              (0 or a power of two below tile_content); an axis where the
                              rectangle plus two gutters exceeds the tile gets a tile-wide cell
                              and no gutter (its sides are tile edges) */
};

/* What the packing achieved. */
struct vt_atlas_pack_stats {
    uint32_t width, height;    /* atlas level-0 size in texels */
    uint32_t tiles_x, tiles_y; /* atlas size in tiles (rounded up) */
    uint64_t tiles_used;       /* tiles holding at least one cell */
    uint64_t tiles_empty;      /* tiles_x * tiles_y - tiles_used */
    uint64_t subtile_tiles;    /* tiles holding sub-tile cells */
    uint64_t content_area;     /* sum of width * height */
    uint64_t cell_area;        /* sum of cell areas (tile-rounded or power-of-two) */
    uint64_t base_cell_area;   /* the same without gutter: next powers of two of the sub-tile
                                  rectangles' edges, large ones rounded up to whole tiles */
    double fill_ratio;         /* content_area / (width * height) */
    double area_over_cells;    /* width * height / cell_area (1 = no packing loss) */
    double area_over_base;     /* width * height / base_cell_area (packing and gutter cost) */
};

/* Places the count rectangles (fills x, y, cell_width, cell_height, alignment of each) and fills
 * *stats (may be NULL). Deterministic: the same input gives the same placement. Returns 0,
 * VTS_ERR_ARG (tile_content not a power of two, a zero-sized rectangle, count 0), VTS_ERR_LIMIT
 * ("the atlas needs 70000 x 70000 texels, more than --max-size 65536") or VTS_ERR_NOMEM. */
int vt_atlas_pack(struct vt_atlas_rect *rects, uint32_t count,
                  const struct vt_atlas_pack_options *options, struct vt_atlas_pack_stats *stats,
                  struct vts_error *err);

/* Smallest power of two >= v (v in 1..2^31). */
uint32_t vt_atlas_next_pow2(uint32_t v);

#ifdef __cplusplus
}
#endif
#endif
