/* Clipmap arithmetic over a store's pyramid (docs/clipmap.md): the clipmap-style runtime of
 * Ephanov & Coleman, "Virtual Texture: A Large Area Raster Resource for the GPU" (2006), in which
 * every level keeps a window of n x n tiles around a paging centre, each tile in the toroidal slot
 * (x mod n, y mod n) of that level's texture, and a move of the centre loads only the strips of
 * tiles it newly exposes. Levels are copied from the prebuilt pyramid, never generated at run time.
 *
 * Pure computation: libc only, no I/O, no GL. A struct vts_clipmap is one thread's (no locking).
 *
 * Terms, per level l (0 = finest) with C = the store's tile_content_px:
 * - window: the tiles the level should hold, [x0, x1) x [y0, y1) in the level's tile grid.
 *   vts_clipmap_window() snaps a paging centre to the level's tile grid, so that a move of the
 *   centre by less than the snapping step leaves the window (and every texel the level shows)
 *   where it was.
 * - slot: tile (x, y) lives in slot (x mod n, y mod n): any n x n window of tiles has distinct
 *   slots, and tiles that stay in the window when it moves keep their slot (no copy).
 * - front: the rectangle of tiles a renderer may sample, every one of them loaded in its slot
 *   (a subset of the window). back: the window being loaded (the target). The two make the
 *   level's window double-buffered: when the target moves, the front shrinks to its intersection
 *   with the new target (the tiles that stay, whose slots are never written while they are in the
 *   target) and grows back strip by strip as the newly exposed tiles arrive; the renderer draws
 *   from the front and falls back to a coarser level outside it.
 * - strips: the new target minus the front, as at most four disjoint rectangles: first the
 *   column strips beside the front over the front's rows, then the row strips above and below it
 *   over the target's whole width. Loading them in that order keeps the front a rectangle that
 *   grows after every completed strip.
 */
#ifndef VTS_CLIPMAP_H
#define VTS_CLIPMAP_H

#include <stdbool.h>
#include <stdint.h>

#include "vts.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Window edge in tiles: 1 .. VTS_CLIPMAP_MAX_N. */
#define VTS_CLIPMAP_MAX_N 256

/* Tiles x0 <= x < x1, y0 <= y < y1 of one level (empty when x0 >= x1 or y0 >= y1). */
struct vts_tile_rect {
    uint32_t x0, y0, x1, y1;
};

/* One tile to load: level, position in the level's grid, and its toroidal slot. */
struct vts_clipmap_tile {
    uint32_t level, x, y;
    uint32_t slot_x, slot_y; /* x mod n, y mod n */
};

struct vts_clipmap_level {
    uint32_t width, height; /* texels (as struct vts_level) */
    uint32_t tiles_x, tiles_y;
    struct vts_tile_rect back;  /* target window (empty until the first vts_clipmap_move) */
    struct vts_tile_rect front; /* loaded rectangle the renderer may use (subset of back) */
    /* per slot (slot_y * n + slot_x): the tile it holds as y * tiles_x + x, or UINT64_MAX */
    uint64_t *slot_tile;
};

struct vts_clipmap {
    uint32_t n;          /* window edge, tiles */
    uint32_t content_px; /* C */
    uint32_t level_count;
    struct vts_clipmap_level levels[VTS_MAX_LEVELS];
};

/* Sets up a clipmap of n x n tile windows over the levels of a checked geometry (every level;
 * those of at most n x n tiles are held whole). All windows start empty, every slot free.
 * Returns 0, VTS_ERR_ARG (n out of 1 .. VTS_CLIPMAP_MAX_N, NULL geometry) or VTS_ERR_NOMEM, with
 * a message in err. Free with vts_clipmap_free (which accepts a zeroed or freed struct). */
VTS_API int vts_clipmap_init(struct vts_clipmap *c, const struct vts_geometry *g, uint32_t n,
                             struct vts_error *err);
VTS_API void vts_clipmap_free(struct vts_clipmap *c);

/* The window of level for a paging centre (cx, cy) given in that level's texels (level-0 texels
 * divided by 2^level; each level may have its own centre). Snapped to the tile grid:
 *   x0 = floor(cx / C - n / 2 + 1/2)   (n even: the tile corner nearest the centre is the
 *                                       window's middle; n odd: the tile under the centre is)
 * then clamped to 0 .. tiles_x - n (a level of at most n tiles across: the whole level), and
 * x1 = min(x0 + n, tiles_x); likewise y. Non-finite centres count as 0. Returns VTS_ERR_RANGE
 * (and an empty rect) for a level outside the clipmap, else 0. */
VTS_API int vts_clipmap_window(const struct vts_clipmap *c, uint32_t level, double cx, double cy,
                               struct vts_tile_rect *out);

/* Toroidal slot of tile (x, y): (x mod n, y mod n). */
VTS_API void vts_clipmap_slot(const struct vts_clipmap *c, uint32_t x, uint32_t y, uint32_t *slot_x,
                              uint32_t *slot_y);

/* Disjoint rectangles covering `to` minus `from` (both of at most n x n tiles of one level), in
 * loading order: column strips left and right of `from` over the rows `from` and `to` share,
 * then row strips above and below over `to`'s whole width; no empty rectangle. Returns the count
 * (0 .. 4); `to` whole (1) when they do not overlap. */
VTS_API uint32_t vts_clipmap_strips(const struct vts_tile_rect *from,
                                    const struct vts_tile_rect *to, struct vts_tile_rect out[4]);

/* Sets level's target window (from vts_clipmap_window). The front becomes its intersection with
 * the target, then grows as in vts_clipmap_loaded over the columns and rows already in their
 * slots (tiles an earlier, unfinished target loaded); slots are not touched (a tile still in its
 * slot is not loaded again). An empty target empties the level's windows. Returns
 * VTS_ERR_RANGE for a level outside the clipmap or a target wider than n or outside the level,
 * else 0. */
VTS_API int vts_clipmap_move(struct vts_clipmap *c, uint32_t level, const struct vts_tile_rect *to);

/* The tiles to load next, at most max: coarsest level first; within a level the strips of its
 * target minus its front in vts_clipmap_strips order, each strip row by row, skipping tiles their
 * slot already holds. Does not change the clipmap: call vts_clipmap_loaded for each tile that was
 * uploaded. Returns the count written to out. */
VTS_API uint32_t vts_clipmap_plan(const struct vts_clipmap *c, struct vts_clipmap_tile *out,
                                  uint32_t max);

/* The tiles vts_clipmap_plan would list with no limit: how many loads the targets still need. */
VTS_API uint64_t vts_clipmap_pending(const struct vts_clipmap *c);

/* Records that tile t (one vts_clipmap_plan listed) is now in its slot, replacing what the slot
 * held, and grows the level's front: a column or row next to the front, within the target, whose
 * tiles over the front's extent are all in their slots joins it, repeatedly (an empty front starts
 * as the target's top-left tile once that is in its slot). Returns
 * VTS_ERR_RANGE when t is outside its level's target, else 0. */
VTS_API int vts_clipmap_loaded(struct vts_clipmap *c, const struct vts_clipmap_tile *t);

/* True when level's front equals its target (the level is complete); false while the target is
 * empty (before the level's first vts_clipmap_move) and for a level outside the clipmap. */
VTS_API bool vts_clipmap_complete(const struct vts_clipmap *c, uint32_t level);

/* The texels of level the renderer may sample with a filter reaching `inset` texels around the
 * sample position: the front in texels, [x0, x1) x [y0, y1), clipped to the level's size, shrunk
 * by inset on each side that is not an edge of the level (at a level's edge the sampler clamps).
 * Empty (x0 >= x1) when nothing is usable. */
VTS_API void vts_clipmap_valid(const struct vts_clipmap *c, uint32_t level, double inset,
                               double *x0, double *y0, double *x1, double *y1);

#ifdef __cplusplus
}
#endif

#endif
