/* Wang tile packs (docs/wang.md): the tile index of Wei, "Tile-Based Texture Mapping on Graphics
 * Hardware" (Graphics Hardware 2004), that packs every edge-colour combination into one texture so
 * that hardware filtering across tile edges reads the texels the virtual texture has there, a
 * corner-colour variant of it, and the hash of the tile position that assigns edge colours to an
 * arbitrarily large output without storing it. Pure functions of their arguments (no state, no
 * allocation, thread-safe); vt-view's shader (tools/vt-view/vtv_wang_glsl.c) computes the same.
 *
 * Conventions: tile positions (x, y) with y growing downwards (image rows): the north edge of tile
 * (x, y) is the south edge of tile (x, y - 1); the east edge of (x, y) is the west edge of
 * (x + 1, y). Edge colours of north and south edges ("horizontal" edges) are 0 .. kh - 1, of west
 * and east edges 0 .. kv - 1. A pack is kv^2 tiles wide and kh^2 tiles high. */
#ifndef VTS_WANG_H
#define VTS_WANG_H

#include <stdint.h>

#include "vts.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Colours per edge kind (and corner colours) supported: 1 .. VTS_WANG_MAX_COLOURS. */
#define VTS_WANG_MAX_COLOURS 16
/* Entries of a hash permutation table: 1 .. VTS_WANG_MAX_HASH. */
#define VTS_WANG_MAX_HASH 65536

/* TileIndex_1D(e1, e2) (Wei, section 4.4): a bijection of the colour pairs of 0 .. k - 1 onto
 * 0 .. k^2 - 1 for every k, in which consecutive indices i, i + 1 (and k^2 - 1, 0) satisfy
 * e2(i) == e1(i + 1). Independent of k:
 *   e1 < e2:          2 e1 + e2^2          e1 > e2 > 0:      e1^2 + 2 e2 - 1
 *   e1 == e2 > 0:     (e1 + 1)^2 - 2       e1 > 0, e2 == 0:  (e1 + 1)^2 - 1      (0, 0): 0
 * Colours at most 65535. */
VTS_API uint32_t vts_wang_index_1d(uint32_t e1, uint32_t e2);

/* The inverse of vts_wang_index_1d: the pair of index (index < 2^32 - 2^17). */
VTS_API void vts_wang_pair_1d(uint32_t index, uint32_t *e1, uint32_t *e2);

/* The edge colours of one tile. */
struct vts_wang_edges {
    uint32_t n, e, s, w;
};

/* TileIndex_2D: the pack column TileIndex_1D(w, e) and row TileIndex_1D(n, s) of the tile with
 * these edges (horizontally adjacent pack tiles share an edge colour, and so do vertically
 * adjacent ones; the pack wraps). */
VTS_API void vts_wang_tile_position(const struct vts_wang_edges *edges, uint32_t *col,
                                    uint32_t *row);

/* The edges of the tile at pack column col (< kv^2) and row row (< kh^2). */
VTS_API void vts_wang_tile_edges(uint32_t col, uint32_t row, struct vts_wang_edges *edges);

/* Corner tiles (colours on the four corners, k of them, k^4 tiles): the pack is k^2 columns by
 * vts_wang_corner_rows(k) rows, a torus of corner colours g(i, j) = s((i + f(j)) mod k^2) where s
 * is the colour sequence of TileIndex_1D (s(i) = e1 of index i) and f(j) = sum of (t mod k^2) for
 * t < j: every 2x2 window of corner colours, that is every tile, appears once (odd k: k^2 rows)
 * or twice (even k: 2 k^2 rows, the second half a shifted copy that closes the torus), and
 * adjacent pack tiles share their corners, across the pack's wrap too. Returns the rows, or 0 for
 * k out of 1 .. VTS_WANG_MAX_COLOURS. */
VTS_API uint32_t vts_wang_corner_rows(uint32_t k);

/* The corner colours of one tile (north-west, north-east, south-west, south-east). */
struct vts_wang_corners {
    uint32_t nw, ne, sw, se;
};

/* CornerIndex: the pack position (first occurrence) of the corner tile with these corners (each
 * < k). Returns VTS_OK, or VTS_ERR_RANGE (zeroed outputs) for k or a colour out of range. */
VTS_API int vts_wang_corner_position(uint32_t k, const struct vts_wang_corners *corners,
                                     uint32_t *col, uint32_t *row);

/* The corners of the tile at pack column col (< k^2) and row (< vts_wang_corner_rows(k)).
 * Returns VTS_OK or VTS_ERR_RANGE (zeroed output). */
VTS_API int vts_wang_corner_colours(uint32_t k, uint32_t col, uint32_t row,
                                    struct vts_wang_corners *corners);

/* The hash of equation 2: H(i) = perm[i mod n] over a permutation perm of 0 .. n - 1, and
 *   S(x, y) = H(H(x) + y + 1) mod kh    N(x, y) = H(H(x) + y) mod kh
 *   W(x, y) = H(x + H(2 y)) mod kv      E(x, y) = H(x + 1 + H(2 y)) mod kv
 * so that N(x, y) == S(x, y - 1) and E(x, y) == W(x + 1, y) by construction; the output repeats
 * every n tiles in x and y (choose n >= the extent in tiles). Corner tiles: the corner colour of
 * grid node (x, y) is H(H(x) + y) mod kh. */
struct vts_wang_hash {
    const uint32_t *perm; /* n entries, a permutation of 0 .. n - 1 */
    uint32_t n;           /* 1 .. VTS_WANG_MAX_HASH */
    uint32_t kh, kv;      /* 1 .. VTS_WANG_MAX_COLOURS */
};

/* Fills perm[0 .. n - 1] with the permutation of seed (a Fisher-Yates shuffle driven by
 * SplitMix64; the same on every machine). Returns VTS_OK or VTS_ERR_RANGE for n out of
 * 1 .. VTS_WANG_MAX_HASH. */
VTS_API int vts_wang_permutation(uint64_t seed, uint32_t n, uint32_t *perm);

/* The edge colours of output tile (x, y). */
VTS_API void vts_wang_hash_edges(const struct vts_wang_hash *h, uint32_t x, uint32_t y,
                                 struct vts_wang_edges *edges);

/* The corner colours of output tile (x, y) (corner packs: kh colours). */
VTS_API void vts_wang_hash_corners(const struct vts_wang_hash *h, uint32_t x, uint32_t y,
                                   struct vts_wang_corners *corners);

#ifdef __cplusplus
}
#endif

#endif
