/* include/vts/vts_wang.h: TileIndex_1D and the pack positions exhaustively for every colour count
 * up to 8 (Wei's three requirements of section 4.4: a bijection, adjacent packed tiles share the
 * edge colour, across the wrap too), the corner packing likewise, and the hash's edge consistency
 * over a 256 x 256 output. Each checker is also run on a deliberately broken packing to show it
 * fails. */
#include <stdbool.h>
#include <stdlib.h>

#include "vt_test.h"
#include "vts_wang.h"

/* A packing under test: edges of the tile at (col, row) of a cols x rows pack. */
typedef void (*edges_fn)(uint32_t col, uint32_t row, struct vts_wang_edges *e);

static void swapped_edges(uint32_t col, uint32_t row, struct vts_wang_edges *e)
{
    /* a wrong packing: columns 1 and 2 exchanged */
    vts_wang_tile_edges(col == 1 ? 2 : col == 2 ? 1 : col, row, e);
}

/* Every (n, e, s, w) with n, s < kh and w, e < kv exactly once, and every pair of neighbours
 * (wrapping) sharing its edge. Returns the number of violations. */
static unsigned check_edge_pack(edges_fn fn, uint32_t kh, uint32_t kv)
{
    uint32_t cols = kv * kv, rows = kh * kh;
    unsigned bad = 0;
    unsigned char *seen = calloc((size_t)cols * rows, 1);
    for (uint32_t row = 0; row < rows; row++)
        for (uint32_t col = 0; col < cols; col++) {
            struct vts_wang_edges t, right, below;
            fn(col, row, &t);
            fn((col + 1) % cols, row, &right);
            fn(col, (row + 1) % rows, &below);
            if (t.n >= kh || t.s >= kh || t.w >= kv || t.e >= kv) {
                bad++;
                continue;
            }
            size_t id = (((size_t)t.n * kh + t.s) * kv + t.w) * kv + t.e;
            bad += seen[id]++ != 0;
            bad += t.e != right.w;
            bad += t.s != below.n;
        }
    free(seen);
    return bad;
}

static void index_1d_is_a_chained_bijection(void)
{
    for (uint32_t k = 1; k <= 8; k++) {
        uint32_t n = k * k;
        unsigned char seen[64] = {0};
        for (uint32_t a = 0; a < k; a++)
            for (uint32_t b = 0; b < k; b++) {
                uint32_t i = vts_wang_index_1d(a, b), e1, e2;
                VT_CHECK(i < n);
                if (i >= n)
                    continue;
                seen[i]++;
                vts_wang_pair_1d(i, &e1, &e2);
                VT_CHECK(e1 == a && e2 == b);
            }
        for (uint32_t i = 0; i < n; i++) {
            uint32_t a1, a2, b1, b2;
            VT_CHECK_INT_EQ(seen[i], 1);
            vts_wang_pair_1d(i, &a1, &a2);
            vts_wang_pair_1d((i + 1) % n, &b1, &b2);
            VT_CHECK_INT_EQ(a2, b1); /* adjacent indices share the colour, n - 1 -> 0 too */
        }
    }
    /* the pinned values of the formula */
    VT_CHECK_INT_EQ(vts_wang_index_1d(0, 0), 0);
    VT_CHECK_INT_EQ(vts_wang_index_1d(0, 1), 1);
    VT_CHECK_INT_EQ(vts_wang_index_1d(1, 1), 2);
    VT_CHECK_INT_EQ(vts_wang_index_1d(1, 0), 3);
    VT_CHECK_INT_EQ(vts_wang_index_1d(2, 1), 5);
    VT_CHECK_INT_EQ(vts_wang_index_1d(7, 0), 63);
}

static void pack_of_every_colour_count_shares_edges(void)
{
    for (uint32_t kh = 1; kh <= 8; kh++)
        for (uint32_t kv = 1; kv <= 8; kv++)
            VT_CHECK_INT_EQ(check_edge_pack(vts_wang_tile_edges, kh, kv), 0);
    for (uint32_t row = 0; row < 64; row++)
        for (uint32_t col = 0; col < 64; col++) {
            struct vts_wang_edges e;
            uint32_t c, r;
            vts_wang_tile_edges(col, row, &e);
            vts_wang_tile_position(&e, &c, &r);
            VT_CHECK(c == col && r == row);
        }
    /* the checker catches a wrong packing */
    VT_CHECK(check_edge_pack(swapped_edges, 2, 2) > 0);
}

/* Corner packs: every tile once (odd k) or twice (even k), neighbours sharing two corners each,
 * CornerIndex finding the first occurrence. shift_col breaks the packing (0: none). */
static unsigned check_corner_pack(uint32_t k, uint32_t shift_col)
{
    uint32_t cols = k * k, rows = vts_wang_corner_rows(k), copies = k % 2 ? 1 : 2;
    unsigned bad = 0;
    unsigned char *seen = calloc((size_t)cols * cols, 1);
    for (uint32_t row = 0; row < rows; row++)
        for (uint32_t col = 0; col < cols; col++) {
            struct vts_wang_corners t, right, below;
            uint32_t tc = shift_col && col == shift_col ? col + 1 : col;
            bad += vts_wang_corner_colours(k, tc % cols, row, &t) != VTS_OK;
            vts_wang_corner_colours(k, (col + 1) % cols, row, &right);
            vts_wang_corner_colours(k, col, (row + 1) % rows, &below);
            bad += t.ne != right.nw || t.se != right.sw;
            bad += t.sw != below.nw || t.se != below.ne;
            seen[((t.nw * k + t.ne) * k + t.sw) * k + t.se]++;
            uint32_t c, r;
            bad += vts_wang_corner_position(k, &t, &c, &r) != VTS_OK;
            struct vts_wang_corners back;
            vts_wang_corner_colours(k, c, r, &back);
            bad += back.nw != t.nw || back.ne != t.ne || back.sw != t.sw || back.se != t.se;
            bad += r >= cols; /* the first copy */
        }
    for (uint32_t i = 0; i < cols * cols; i++)
        bad += seen[i] != copies;
    free(seen);
    return bad;
}

static void corner_pack_of_every_colour_count_shares_corners(void)
{
    for (uint32_t k = 1; k <= 8; k++) {
        VT_CHECK_INT_EQ(vts_wang_corner_rows(k), k % 2 ? k * k : 2 * k * k);
        VT_CHECK_INT_EQ(check_corner_pack(k, 0), 0);
    }
    VT_CHECK(check_corner_pack(3, 2) > 0); /* a wrong packing fails */
    VT_CHECK_INT_EQ(vts_wang_corner_rows(0), 0);
    VT_CHECK_INT_EQ(vts_wang_corner_rows(VTS_WANG_MAX_COLOURS + 1), 0);
    struct vts_wang_corners c = {0, 0, 2, 0}, out;
    uint32_t col = 9, row = 9;
    VT_CHECK_INT_EQ(vts_wang_corner_position(2, &c, &col, &row), VTS_ERR_RANGE);
    VT_CHECK(col == 0 && row == 0);
    VT_CHECK_INT_EQ(vts_wang_corner_colours(2, 4, 0, &out), VTS_ERR_RANGE);
    VT_CHECK_INT_EQ(vts_wang_corner_colours(2, 0, 8, &out), VTS_ERR_RANGE);
}

static void permutation_is_a_permutation_and_pinned(void)
{
    static uint32_t perm[VTS_WANG_MAX_HASH], again[VTS_WANG_MAX_HASH];
    static unsigned char seen[VTS_WANG_MAX_HASH];
    VT_CHECK_INT_EQ(vts_wang_permutation(7, VTS_WANG_MAX_HASH, perm), VTS_OK);
    for (uint32_t i = 0; i < VTS_WANG_MAX_HASH; i++)
        seen[perm[i]]++;
    unsigned fixed = 0;
    for (uint32_t i = 0; i < VTS_WANG_MAX_HASH; i++) {
        VT_CHECK_INT_EQ(seen[i], 1);
        fixed += perm[i] == i;
    }
    VT_CHECK(fixed < 16); /* shuffled, not the identity */
    vts_wang_permutation(7, 256, perm);
    vts_wang_permutation(7, 256, again);
    VT_CHECK(memcmp(perm, again, 256 * sizeof *perm) == 0);
    vts_wang_permutation(8, 256, again);
    VT_CHECK(memcmp(perm, again, 256 * sizeof *perm) != 0);
    VT_CHECK_INT_EQ(vts_wang_permutation(1, 0, perm), VTS_ERR_RANGE);
    VT_CHECK_INT_EQ(vts_wang_permutation(1, VTS_WANG_MAX_HASH + 1, perm), VTS_ERR_RANGE);
}

/* Edge consistency of the hash over a 256 x 256 output (and across its wrap). A broken hash (the
 * east colour from the wrong row) fails. Returns violations. */
static unsigned check_hash(const struct vts_wang_hash *h, bool broken, unsigned *kinds_seen)
{
    unsigned bad = 0;
    unsigned char seen[16 * 16 * 16 * 16] = {0};
    for (uint32_t y = 0; y < 256; y++)
        for (uint32_t x = 0; x < 256; x++) {
            struct vts_wang_edges t, east, north;
            vts_wang_hash_edges(h, x, y, &t);
            vts_wang_hash_edges(h, x + 1, y + broken, &east);
            vts_wang_hash_edges(h, x, (y + 255) % 256, &north);
            bad += t.e != east.w;
            bad += t.n != north.s;
            bad += t.n >= h->kh || t.s >= h->kh || t.w >= h->kv || t.e >= h->kv;
            seen[(((t.n * 16 + t.s) * 16 + t.w) * 16 + t.e) & 0xffff] = 1;
        }
    *kinds_seen = 0;
    for (size_t i = 0; i < sizeof seen; i++)
        *kinds_seen += seen[i];
    return bad;
}

static void hash_edges_agree_with_neighbours(void)
{
    uint32_t perm[256];
    vts_wang_permutation(1, 256, perm);
    const uint32_t ks[][2] = {{2, 2}, {3, 4}, {1, 5}, {8, 8}};
    for (size_t i = 0; i < sizeof ks / sizeof ks[0]; i++) {
        struct vts_wang_hash h = {perm, 256, ks[i][0], ks[i][1]};
        unsigned kinds;
        VT_CHECK_INT_EQ(check_hash(&h, false, &kinds), 0);
        /* every tile of a small set is used: the hash is not degenerate */
        uint32_t all = ks[i][0] * ks[i][0] * ks[i][1] * ks[i][1];
        if (all <= 256)
            VT_CHECK_INT_EQ(kinds, all);
        VT_CHECK(check_hash(&h, true, &kinds) > 0);
    }
    /* corners: node colours shared by the four tiles around a node */
    struct vts_wang_hash h = {perm, 256, 3, 3};
    unsigned bad = 0;
    for (uint32_t y = 0; y < 256; y++)
        for (uint32_t x = 0; x < 256; x++) {
            struct vts_wang_corners t, e, s;
            vts_wang_hash_corners(&h, x, y, &t);
            vts_wang_hash_corners(&h, (x + 1) % 256, y, &e);
            vts_wang_hash_corners(&h, x, (y + 1) % 256, &s);
            bad += t.ne != e.nw || t.se != e.sw || t.sw != s.nw || t.se != s.ne;
        }
    VT_CHECK_INT_EQ(bad, 0);
}

int main(void)
{
    VT_RUN(index_1d_is_a_chained_bijection);
    VT_RUN(pack_of_every_colour_count_shares_edges);
    VT_RUN(corner_pack_of_every_colour_count_shares_corners);
    VT_RUN(permutation_is_a_permutation_and_pinned);
    VT_RUN(hash_edges_agree_with_neighbours);
    return vt_test_main_result();
}
