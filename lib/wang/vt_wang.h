/* Wang tile sets made from a sample texture and packed for hardware filtering (docs/wang.md).
 *
 * Edge tiles (Cohen, Shade, Hiller, Deussen 2003, "Wang Tiles for Image and Texture Generation"):
 * one sample patch per edge colour (a tile-sized square of the sample, the bounding box of the
 * colour's diamond, centred on the edge); a tile is the four half-diamonds of its edge colours
 * (N, E, S, W triangles meeting at the tile's centre), each pair of neighbouring triangles joined
 * along the minimum-error cut through their overlap (dynamic programming over the quadrant, the
 * cut kept near the diagonal so that every tile edge is its colour's patch alone). Tiles that share
 * an edge colour continue the same patch across the edge, so any tiling that matches colours is
 * seamless. Corner tiles (--corners): one patch per corner colour centred on the corner, the four
 * quadrants joined along minimum-error cuts near the midlines that meet the tile's edges at their
 * middle. The pack arranges the tiles by vts_wang_tile_position() / vts_wang_corner_colours()
 * (include/vts/vts_wang.h). Pure computation: libc, core and the store's vts_wang API. */
#ifndef VT_WANG_H
#define VT_WANG_H

#include <stdbool.h>
#include <stdint.h>

#include "vt_error.h"
#include "vt_image.h"
#include "vts_wang.h"

/* Metadata keys of a pack store (docs/wang.md, "The pack"). */
#define VT_WANG_KEY_KIND    "wang.kind"    /* "edge" or "corner" */
#define VT_WANG_KEY_COLOURS "wang.colours" /* "KhxKv" (corner packs: "KxK") */
#define VT_WANG_KEY_TILE    "wang.tile"    /* tile edge in texels at level 0 */
#define VT_WANG_KEY_GRID    "wang.grid"    /* "COLSxROWS": the pack in tiles */
#define VT_WANG_KEY_HASH    "wang.hash"    /* the permutation: n entries, space-separated */
#define VT_WANG_KEY_SEED    "wang.seed"    /* the seed of the patches and the permutation */
#define VT_WANG_KEY_ORDER   "wang.order"   /* only in a shuffled pack: slot of each tile */

/* The largest pack vt_wang_build makes (texels of level 0). */
#define VT_WANG_MAX_PACK_TEXELS (1ull << 30)

struct vt_wang_params {
    uint32_t tile_px; /* even, >= 8 */
    uint32_t kh, kv;  /* 1 .. VTS_WANG_MAX_COLOURS; corner packs: kh == kv */
    bool corners;
    uint64_t seed; /* patch positions */
    bool shuffle;  /* tiles in an arbitrary order (Wei's figure 5; tests) */
    uint64_t shuffle_seed;
};

/* The pack's geometry in tiles. */
void vt_wang_grid(const struct vt_wang_params *p, uint32_t *cols, uint32_t *rows);

/* Builds the pack image from sample (8-bit, 1..4 channels, at least tile_px on each side) into
 * *pack (allocated here: free with vt_image_release): cols * tile_px x rows * tile_px texels of
 * the sample's channels. With shuffle, order[] (cols * rows entries, may be NULL otherwise) gets
 * the slot (row * cols + col) where the tile of canonical slot i lies. Returns 0, VTS_ERR_ARG (a
 * bad parameter or a sample smaller than a tile: message says which) or VTS_ERR_LIMIT (a pack of
 * more than VT_WANG_MAX_PACK_TEXELS, or out of memory). */
int vt_wang_build(const struct vt_image *sample, const struct vt_wang_params *p,
                  struct vt_image *pack, uint32_t *order, struct vts_error *err);

/* One tile from its patches (vt_wang_tile.c). patches: for edge tiles n, e, s, w (patches of
 * tile_px square), for corner tiles nw, ne, sw, se (patches of tile_px + 2 * margin square, margin
 * = vt_wang_corner_margin(tile_px)). All 8-bit with the same channels as dst (tile_px square). */
void vt_wang_edge_tile(const struct vt_image *const patches[4], struct vt_image *dst);
void vt_wang_corner_tile(const struct vt_image *const patches[4], struct vt_image *dst);
uint32_t vt_wang_corner_margin(uint32_t tile_px);

/* A pack as recorded in a store's metadata (vt_wang_meta.c). */
struct vt_wang_info {
    bool corners;
    uint32_t kh, kv, tile_px, cols, rows;
    uint64_t seed;
    uint32_t hash_n;
    uint32_t *hash;  /* hash_n entries */
    uint32_t *order; /* cols * rows entries, or NULL (canonical order) */
};

/* Parses the pack metadata through get(user, key) (NULL for a missing key). Returns 0,
 * VTS_ERR_ARG with "not a Wang pack" when wang.kind is missing, or VTS_ERR_CORRUPT naming the bad
 * key. Release with vt_wang_info_release. */
int vt_wang_info_parse(const char *(*get)(void *user, const char *key), void *user,
                       struct vt_wang_info *info, struct vts_error *err);
void vt_wang_info_release(struct vt_wang_info *info);

/* The pack slot (col, row) that holds output tile (x, y) of a pack described by info. */
void vt_wang_info_locate(const struct vt_wang_info *info, uint32_t x, uint32_t y, uint32_t *col,
                         uint32_t *row);

/* Formats the hash table as the wang.hash value (space-separated); returns a malloc()ed string or
 * NULL (out of memory). */
char *vt_wang_hash_format(const uint32_t *perm, uint32_t n);

/* Assembles the region [x0, x0 + dst->width) x [y0, y0 + dst->height) of the virtual output (in
 * texels of level `level`, tile edge info->tile_px >> level) from the pack image of that level
 * (pack_level: cols * tile x rows * tile texels) into dst (same channels and sample). */
void vt_wang_assemble(const struct vt_wang_info *info, const struct vt_image *pack_level,
                      uint32_t level, uint64_t x0, uint64_t y0, struct vt_image *dst);

#endif
