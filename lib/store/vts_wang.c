/* Wang tile packing and hashing (include/vts/vts_wang.h, docs/wang.md). */
#include "vts_wang.h"

#include <string.h>

uint32_t vts_wang_index_1d(uint32_t e1, uint32_t e2)
{
    if (e1 < e2)
        return 2 * e1 + e2 * e2;
    if (e1 > e2 && e2 > 0)
        return e1 * e1 + 2 * e2 - 1;
    if (e1 == e2 && e1 > 0)
        return (e1 + 1) * (e1 + 1) - 2;
    return e1 > 0 ? (e1 + 1) * (e1 + 1) - 1 : 0;
}

/* floor(sqrt(v)) in integers. */
static uint32_t isqrt(uint32_t v)
{
    uint32_t r = 0;
    for (uint32_t bit = 1u << 15; bit; bit >>= 1)
        if ((uint64_t)(r | bit) * (r | bit) <= v)
            r |= bit;
    return r;
}

void vts_wang_pair_1d(uint32_t index, uint32_t *e1, uint32_t *e2)
{
    /* index = m^2 + r, 0 <= r <= 2m: the cases of vts_wang_index_1d() in order of r */
    uint32_t m = isqrt(index), r = index - m * m;
    if (r == 2 * m) { /* (m, 0), and (0, 0) for index 0 */
        *e1 = m;
        *e2 = 0;
    } else if (r == 2 * m - 1) {
        *e1 = m;
        *e2 = m;
    } else if (r % 2 == 0) {
        *e1 = r / 2;
        *e2 = m;
    } else {
        *e1 = m;
        *e2 = (r + 1) / 2;
    }
}

void vts_wang_tile_position(const struct vts_wang_edges *edges, uint32_t *col, uint32_t *row)
{
    *col = vts_wang_index_1d(edges->w, edges->e);
    *row = vts_wang_index_1d(edges->n, edges->s);
}

void vts_wang_tile_edges(uint32_t col, uint32_t row, struct vts_wang_edges *edges)
{
    vts_wang_pair_1d(col, &edges->w, &edges->e);
    vts_wang_pair_1d(row, &edges->n, &edges->s);
}

uint32_t vts_wang_corner_rows(uint32_t k)
{
    if (k < 1 || k > VTS_WANG_MAX_COLOURS)
        return 0;
    return k % 2 ? k * k : 2 * k * k;
}

/* f(j) = sum of (t mod k^2) for t < j, mod k^2: the shift of row j of the corner torus. */
static uint32_t corner_shift(uint32_t k, uint32_t j)
{
    uint32_t n = k * k, full = j / n, rest = j % n;
    uint64_t sum = (uint64_t)full * (n * (uint64_t)(n - 1) / 2) + (uint64_t)rest * (rest - 1) / 2;
    return (uint32_t)(sum % n);
}

/* The colour sequence of TileIndex_1D: s(i) = e1 of index i. */
static uint32_t corner_sequence(uint32_t i)
{
    uint32_t e1, e2;
    vts_wang_pair_1d(i, &e1, &e2);
    return e1;
}

int vts_wang_corner_colours(uint32_t k, uint32_t col, uint32_t row,
                            struct vts_wang_corners *corners)
{
    uint32_t rows = vts_wang_corner_rows(k);
    memset(corners, 0, sizeof *corners);
    if (!rows || col >= k * k || row >= rows)
        return VTS_ERR_RANGE;
    uint32_t n = k * k, top = (col + corner_shift(k, row)) % n;
    uint32_t bottom = (top + row % n) % n; /* f(row + 1) = f(row) + row mod k^2 */
    corners->nw = corner_sequence(top);
    corners->ne = corner_sequence((top + 1) % n);
    corners->sw = corner_sequence(bottom);
    corners->se = corner_sequence((bottom + 1) % n);
    return VTS_OK;
}

int vts_wang_corner_position(uint32_t k, const struct vts_wang_corners *corners, uint32_t *col,
                             uint32_t *row)
{
    *col = *row = 0;
    if (k < 1 || k > VTS_WANG_MAX_COLOURS || corners->nw >= k || corners->ne >= k ||
        corners->sw >= k || corners->se >= k)
        return VTS_ERR_RANGE;
    uint32_t n = k * k;
    uint32_t top = vts_wang_index_1d(corners->nw, corners->ne);
    uint32_t bottom = vts_wang_index_1d(corners->sw, corners->se);
    uint32_t j = (bottom + n - top) % n;
    *row = j;
    *col = (top + n - corner_shift(k, j)) % n;
    return VTS_OK;
}

static uint64_t splitmix64(uint64_t *state)
{
    uint64_t z = (*state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

int vts_wang_permutation(uint64_t seed, uint32_t n, uint32_t *perm)
{
    if (n < 1 || n > VTS_WANG_MAX_HASH)
        return VTS_ERR_RANGE;
    for (uint32_t i = 0; i < n; i++)
        perm[i] = i;
    uint64_t state = seed;
    for (uint32_t i = n - 1; i > 0; i--) {
        uint32_t j = (uint32_t)(splitmix64(&state) % (i + 1)); /* bias < 2^-47: irrelevant */
        uint32_t t = perm[i];
        perm[i] = perm[j];
        perm[j] = t;
    }
    return VTS_OK;
}

static uint32_t hash_at(const struct vts_wang_hash *h, uint64_t i)
{
    return h->perm[i % h->n];
}

void vts_wang_hash_edges(const struct vts_wang_hash *h, uint32_t x, uint32_t y,
                         struct vts_wang_edges *edges)
{
    uint64_t column = hash_at(h, x), row = hash_at(h, 2 * (uint64_t)y);
    edges->n = hash_at(h, column + y) % h->kh;
    edges->s = hash_at(h, column + y + 1) % h->kh;
    edges->w = hash_at(h, x + row) % h->kv;
    edges->e = hash_at(h, x + 1 + row) % h->kv;
}

void vts_wang_hash_corners(const struct vts_wang_hash *h, uint32_t x, uint32_t y,
                           struct vts_wang_corners *corners)
{
    uint64_t c0 = hash_at(h, x), c1 = hash_at(h, (uint64_t)x + 1);
    corners->nw = hash_at(h, c0 + y) % h->kh;
    corners->ne = hash_at(h, c1 + y) % h->kh;
    corners->sw = hash_at(h, c0 + y + 1) % h->kh;
    corners->se = hash_at(h, c1 + y + 1) % h->kh;
}
