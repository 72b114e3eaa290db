/* One Wang tile from its sample patches, the patches joined along minimum-error cuts (vt_wang.h).
 */
#include <assert.h>
#include <limits.h>
#include <stdlib.h>

#include "vt_wang.h"

/* A source of texels for one side of a cut: the patch, and where tile texel (0, 0) lies in it. */
struct side {
    const struct vt_image *patch;
    int32_t dx, dy;
};

static const uint8_t *texel(const struct side *s, uint32_t x, uint32_t y)
{
    return vt_image_at(s->patch, (uint32_t)((int32_t)x + s->dx), (uint32_t)((int32_t)y + s->dy));
}

static uint32_t error_at(const struct side *a, const struct side *b, uint32_t x, uint32_t y,
                         uint32_t channels)
{
    const uint8_t *p = texel(a, x, y), *q = texel(b, x, y);
    uint32_t e = 0;
    for (uint32_t c = 0; c < channels; c++) {
        int d = (int)p[c] - (int)q[c];
        e += (uint32_t)(d * d);
    }
    return e;
}

static void copy_texel(struct vt_image *dst, uint32_t x, uint32_t y, const struct side *s)
{
    uint8_t *out = vt_image_at(dst, x, y);
    const uint8_t *in = texel(s, x, y);
    for (uint32_t c = 0; c < dst->channels; c++)
        out[c] = in[c];
}

/* Quadrant-local (u, v) to tile (x, y): u runs along the A edge away from the corner, v away from
 * the A edge; flip_x / flip_y pick the quadrant. */
static void to_tile(uint32_t t, bool flip_x, bool flip_y, uint32_t u, uint32_t v, uint32_t *x,
                    uint32_t *y)
{
    *x = flip_x ? t - 1 - u : u;
    *y = flip_y ? t - 1 - v : v;
}

/* Minimum-error cut of one quadrant of an edge tile between A (the patch of the horizontal edge,
 * row v = 0 of the quadrant) and B (the vertical edge, column u = 0): in row v the texels u < c(v)
 * come from B, the rest from A. c(0) = 0 (the edge row is A's), c(v) >= 1 below it (the edge
 * column is B's), |c(v) - c(v - 1)| <= 1, within min(v, h - v) / 3 of the diagonal (so that near
 * the tile's corner and centre the cut is the diagonal: there tiles of other edge colours meet, and
 * a cut that strays from the diagonal there brings them into what filtering across an edge reads):
 * the path of least summed
 * error over its texels, by dynamic programming. */
static void edge_quadrant(const struct side *a, const struct side *b, bool flip_x, bool flip_y,
                          struct vt_image *dst, uint32_t *cost, uint8_t *from)
{
    uint32_t t = dst->width, h = t / 2, ch = dst->channels;
    const uint32_t inf = UINT32_MAX / 2;
    /* cost[v * (h + 1) + c]: least error of a path ending at c in row v */
    for (uint32_t i = 0; i < (h + 1) * h; i++)
        cost[i] = inf;
    cost[0] = 0;
    for (uint32_t v = 1; v < h; v++) {
        uint32_t band = (v < h - v ? v : h - v) / 3;
        uint32_t lo = v > band + 1 ? v - band : 1, hi = v + band < h ? v + band : h;
        for (uint32_t c = lo; c <= hi; c++) {
            uint32_t best = inf;
            uint8_t step = 0;
            for (int d = -1; d <= 1; d++) {
                int64_t pc = (int64_t)c + d;
                if (pc < 0 || pc > (int64_t)h)
                    continue;
                uint32_t prev = cost[(v - 1) * (h + 1) + (uint32_t)pc];
                if (prev < best) {
                    best = prev;
                    step = (uint8_t)(d + 1);
                }
            }
            if (best >= inf)
                continue;
            uint32_t x, y, e = 0;
            if (c < h) { /* the texel at the cut, where A meets B */
                to_tile(t, flip_x, flip_y, c, v, &x, &y);
                e = error_at(a, b, x, y, ch);
            }
            cost[v * (h + 1) + c] = best + e;
            from[v * (h + 1) + c] = step;
        }
    }
    uint32_t c = 1;
    for (uint32_t k = 1; k <= h; k++)
        if (cost[(h - 1) * (h + 1) + k] < cost[(h - 1) * (h + 1) + c])
            c = k;
    for (uint32_t v = h; v-- > 0;) {
        for (uint32_t u = 0; u < h; u++) {
            uint32_t x, y;
            to_tile(t, flip_x, flip_y, u, v, &x, &y);
            copy_texel(dst, x, y, u < c ? b : a);
        }
        if (v > 0)
            c = (uint32_t)((int32_t)c + from[v * (h + 1) + c] - 1);
    }
    assert(c == 0);
}

void vt_wang_edge_tile(const struct vt_image *const patches[4], struct vt_image *dst)
{
    int32_t t = (int32_t)dst->width, h = t / 2;
    /* the patch of each edge is centred on it: N's row h is the tile's row 0, and so on */
    struct side n = {patches[0], 0, h}, e = {patches[1], -h, 0};
    struct side s = {patches[2], 0, -h}, w = {patches[3], h, 0};
    size_t cells = (size_t)(h + 1) * (size_t)h;
    uint32_t *cost = malloc(cells * sizeof *cost);
    uint8_t *from = malloc(cells);
    if (!cost || !from) { /* a quadrant split on the diagonals instead of the cuts */
        for (int32_t y = 0; y < t; y++)
            for (int32_t x = 0; x < t; x++) {
                int32_t u = x < h ? x : t - 1 - x, v = y < h ? y : t - 1 - y;
                const struct side *hs = y < h ? &n : &s, *vs = x < h ? &w : &e;
                copy_texel(dst, (uint32_t)x, (uint32_t)y, u < v ? vs : hs);
            }
    } else {
        edge_quadrant(&n, &w, false, false, dst, cost, from);
        edge_quadrant(&n, &e, true, false, dst, cost, from);
        edge_quadrant(&s, &w, false, true, dst, cost, from);
        edge_quadrant(&s, &e, true, true, dst, cost, from);
    }
    free(cost);
    free(from);
}

uint32_t vt_wang_corner_margin(uint32_t tile_px)
{
    return tile_px / 8;
}

/* Minimum-error cut between `first` (texels before the cut) and `second` along a line of `len`
 * texels (rows when vertical, columns otherwise) within [mid - m, mid + m]; at the line's ends
 * (the tile's edges) the cut is at mid. cut[i] receives the first texel of `second`. */
static void line_cut(const struct side *first, const struct side *second, bool vertical,
                     uint32_t len, uint32_t from, uint32_t mid, uint32_t m, uint32_t ch,
                     uint32_t edge_len, uint32_t *cut, uint32_t *cost, uint8_t *step)
{
    uint32_t w = 2 * m + 1;
    const uint32_t inf = UINT32_MAX / 2;
    for (uint32_t i = 0; i < len; i++) {
        uint32_t along = from + i;
        bool at_edge = along == 0 || along == edge_len - 1;
        for (uint32_t k = 0; k < w; k++) {
            uint32_t c = mid - m + k, best = inf;
            uint8_t st = 1;
            if (at_edge && c != mid) {
                cost[i * w + k] = inf;
                continue;
            }
            if (i == 0)
                best = 0;
            for (int d = -1; i > 0 && d <= 1; d++) {
                int32_t pk = (int32_t)k + d;
                if (pk >= 0 && pk < (int32_t)w && cost[(i - 1) * w + (uint32_t)pk] < best) {
                    best = cost[(i - 1) * w + (uint32_t)pk];
                    st = (uint8_t)(d + 1);
                }
            }
            uint32_t x = vertical ? c : along, y = vertical ? along : c;
            cost[i * w + k] = best >= inf ? inf : best + error_at(first, second, x, y, ch);
            step[i * w + k] = st;
        }
    }
    uint32_t k = m;
    for (uint32_t j = 0; j < w; j++)
        if (cost[(len - 1) * w + j] < cost[(len - 1) * w + k])
            k = j;
    for (uint32_t i = len; i-- > 0;) {
        cut[i] = mid - m + k;
        if (i > 0)
            k = (uint32_t)((int32_t)k + step[i * w + k] - 1);
    }
}

void vt_wang_corner_tile(const struct vt_image *const patches[4], struct vt_image *dst)
{
    uint32_t t = dst->width, h = t / 2, m = vt_wang_corner_margin(t), ch = dst->channels;
    int32_t o = (int32_t)(h + m);
    /* the patch of each corner is centred on it, with a margin of m around */
    struct side nw = {patches[0], o, o}, ne = {patches[1], o - (int32_t)t, o};
    struct side sw = {patches[2], o, o - (int32_t)t},
                se = {patches[3], o - (int32_t)t, o - (int32_t)t};
    uint32_t w = 2 * m + 1;
    uint32_t *cost = malloc((size_t)t * w * sizeof *cost), *cuts = malloc(4 * (size_t)t * 4);
    uint8_t *step = malloc((size_t)t * w);
    if (!cost || !cuts || !step || m == 0) { /* quadrants as they are */
        for (uint32_t y = 0; y < t; y++)
            for (uint32_t x = 0; x < t; x++)
                copy_texel(dst, x, y, y < h ? (x < h ? &nw : &ne) : (x < h ? &sw : &se));
        goto out;
    }
    /* vertical cuts of the upper rows (nw | ne) and the lower rows (sw | se), each reaching
     * past the middle by m; horizontal cuts of the left (nw / sw) and right (ne / se) columns */
    uint32_t *up = cuts, *down = cuts + t, *left = cuts + 2 * t, *right = cuts + 3 * t;
    line_cut(&nw, &ne, true, h + m, 0, h, m, ch, t, up, cost, step);
    line_cut(&sw, &se, true, h + m, h - m, h, m, ch, t, down + (h - m), cost, step);
    line_cut(&nw, &sw, false, h + m, 0, h, m, ch, t, left, cost, step);
    line_cut(&ne, &se, false, h + m, h - m, h, m, ch, t, right + (h - m), cost, step);
    for (uint32_t y = 0; y < t; y++)
        for (uint32_t x = 0; x < t; x++) {
            /* upper or lower from the horizontal cut of the column's half, then left or right
             * from the vertical cut of that half (clamped to the rows it covers) */
            uint32_t hc = x < h ? left[x < h + m ? x : h + m - 1] : right[x >= h - m ? x : h - m];
            bool upper = y < hc;
            uint32_t vr = upper ? (y < h + m ? y : h + m - 1) : (y >= h - m ? y : h - m);
            uint32_t vc = upper ? up[vr] : down[vr];
            const struct side *s = upper ? (x < vc ? &nw : &ne) : (x < vc ? &sw : &se);
            copy_texel(dst, x, y, s);
        }
out:
    free(cost);
    free(cuts);
    free(step);
}
