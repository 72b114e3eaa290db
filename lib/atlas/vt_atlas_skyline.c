/* Whole-tile packing for vt-atlas: a bottom-left skyline over tile columns, tried at several
 * atlas widths and two orders (vt_atlas_skyline.h). */
#include "internal/vt_atlas_skyline.h"
#include "vt_error.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static int cmp_tile_item(const void *a, const void *b)
{
    const struct vt_atlas_tile_item *p = a, *q = b;
    if (p->h != q->h)
        return p->h > q->h ? -1 : 1;
    if (p->w != q->w)
        return p->w > q->w ? -1 : 1;
    if (p->subtile != q->subtile)
        return p->subtile ? 1 : -1;
    return p->index < q->index ? -1 : p->index > q->index;
}

/* Skyline bottom-left at width W tiles; returns the height in tiles, or UINT32_MAX when an item
 * is wider than W or the height passes max_h. heights and window are scratch of W entries. */
static uint32_t skyline(struct vt_atlas_tile_item *items, size_t n, uint32_t W, uint32_t max_h,
                        uint32_t *heights, uint32_t *deque, uint64_t *prefix)
{
    uint32_t top = 0;
    memset(heights, 0, W * sizeof *heights);
    for (size_t i = 0; i < n; i++) {
        struct vt_atlas_tile_item *it = &items[i];
        if (it->w > W)
            return UINT32_MAX;
        prefix[0] = 0;
        for (uint32_t c = 0; c < W; c++)
            prefix[c + 1] = prefix[c] + heights[c];
        /* Sliding-window maximum over windows of it->w columns (monotonic deque). */
        size_t head = 0, tail = 0;
        uint32_t best_x = 0, best_y = UINT32_MAX;
        uint64_t best_waste = UINT64_MAX;
        for (uint32_t c = 0; c < W; c++) {
            while (tail > head && heights[deque[tail - 1]] <= heights[c])
                tail--;
            deque[tail++] = c;
            if (c + 1 < it->w)
                continue;
            uint32_t x = c + 1 - it->w;
            while (deque[head] < x)
                head++;
            uint32_t y = heights[deque[head]];
            uint64_t waste = (uint64_t)y * it->w - (prefix[x + it->w] - prefix[x]);
            if (y < best_y || (y == best_y && waste < best_waste)) {
                best_y = y;
                best_x = x;
                best_waste = waste;
            }
        }
        if ((uint64_t)best_y + it->h > max_h)
            return UINT32_MAX;
        it->x = best_x;
        it->y = best_y;
        for (uint32_t c = best_x; c < best_x + it->w; c++)
            heights[c] = best_y + it->h;
        if (best_y + it->h > top)
            top = best_y + it->h;
    }
    return top;
}

static int cmp_tile_item_wide(const void *a, const void *b)
{
    const struct vt_atlas_tile_item *p = a, *q = b;
    if (p->w != q->w)
        return p->w > q->w ? -1 : 1;
    return cmp_tile_item(a, b);
}

/* One trial: an atlas width in tiles and an item order (0: tallest first, 1: widest first). */
struct trial {
    uint32_t w, h;
    int order;
};

static void sort_items(struct vt_atlas_tile_item *items, size_t n, int order)
{
    qsort(items, n, sizeof *items, order ? cmp_tile_item_wide : cmp_tile_item);
}

/* The trial widths: every width from the widest item to twice the square root of the area when
 * that is a short range (small atlases), else near-square factors of the square root. */
static size_t trial_widths(double side, uint32_t min_w, uint32_t max_tiles, uint32_t *w, size_t cap)
{
    static const double factors[] = {0.85, 0.90, 0.95, 1.00, 1.05, 1.10, 1.15, 1.20};
    size_t k = 0;
    double top = ceil(2 * side) + 1;
    if (top - min_w < 32) {
        for (double x = min_w; x <= top && x <= max_tiles && k < cap; x++)
            w[k++] = (uint32_t)x;
        return k;
    }
    w[k++] = min_w;
    for (size_t f = 0; f < sizeof factors / sizeof factors[0] && k < cap; f++) {
        double x = ceil(side * factors[f]);
        uint32_t W = x > max_tiles ? max_tiles : (uint32_t)x;
        W = W < min_w ? min_w : W;
        if (W != w[k - 1])
            w[k++] = W;
    }
    return k;
}

/* Keeps the smallest area, and among areas within 1% of it the squarest. */
static struct trial pick_trial(const struct trial *t, size_t n)
{
    uint64_t min_a = UINT64_MAX;
    for (size_t i = 0; i < n; i++)
        if (t[i].h != UINT32_MAX && (uint64_t)t[i].w * t[i].h < min_a)
            min_a = (uint64_t)t[i].w * t[i].h;
    struct trial best = {0, 0, 0};
    uint32_t best_d = UINT32_MAX;
    for (size_t i = 0; i < n; i++) {
        uint64_t a = (uint64_t)t[i].w * t[i].h;
        uint32_t d = t[i].w > t[i].h ? t[i].w - t[i].h : t[i].h - t[i].w;
        if (t[i].h != UINT32_MAX && (double)a <= (double)min_a * 1.01 && d < best_d) {
            best = t[i];
            best_d = d;
        }
    }
    return best;
}

/* Packs the tile items at several widths and two orders, keeps the best (see pick_trial) and
 * leaves its placement in items. */
int vt_atlas_skyline_pack(struct vt_atlas_tile_item *items, size_t n, uint32_t max_tiles,
                          uint32_t max_edge, uint32_t *out_w, uint32_t *out_h,
                          struct vts_error *err)
{
    uint64_t area = 0;
    uint32_t min_w = 1, min_h = 1;
    for (size_t i = 0; i < n; i++) {
        area += (uint64_t)items[i].w * items[i].h;
        min_w = items[i].w > min_w ? items[i].w : min_w;
        min_h = items[i].h > min_h ? items[i].h : min_h;
    }
    if (min_w > max_tiles || min_h > max_tiles)
        return vt_error_set(err, VTS_ERR_LIMIT,
                            "a texture is %u tiles %s, more than the atlas size limit %u allows",
                            min_w > max_tiles ? min_w : min_h, min_w > max_tiles ? "wide" : "tall",
                            max_edge);
    uint32_t *heights = malloc(max_tiles * sizeof *heights);
    uint32_t *deque = malloc(max_tiles * sizeof *deque);
    uint64_t *prefix = malloc(((size_t)max_tiles + 1) * sizeof *prefix);
    int rc = 0;
    if (!heights || !deque || !prefix) {
        rc = vt_error_set(err, VTS_ERR_NOMEM, "out of memory packing %zu cells", n);
        goto out;
    }
    double side = sqrt((double)area);
    uint32_t widths[40];
    size_t nw = trial_widths(side, min_w, max_tiles, widths, 40);
    struct trial trials[80];
    size_t nt = 0;
    /* Widest-first only helps small atlases (holes under wide items); it doubles the time. */
    int orders = n <= 4096 ? 2 : 1;
    for (int order = 0; order < orders; order++) {
        sort_items(items, n, order);
        for (size_t i = 0; i < nw; i++) {
            uint32_t h = skyline(items, n, widths[i], max_tiles, heights, deque, prefix);
            trials[nt++] = (struct trial){widths[i], h, order};
        }
    }
    struct trial best = pick_trial(trials, nt);
    /* Nothing fits under the height limit: wider atlases, doubling up to the limit. */
    sort_items(items, n, 0);
    for (double w = ceil(side * 1.4); !best.w; w *= 2) {
        uint32_t W = w > max_tiles ? max_tiles : (uint32_t)w;
        uint32_t H = skyline(items, n, W, max_tiles, heights, deque, prefix);
        if (H != UINT32_MAX)
            best = (struct trial){W, H, 0};
        if (W == max_tiles)
            break;
    }
    if (!best.w) {
        rc = vt_error_set(
            err, VTS_ERR_LIMIT,
            "the textures (%llu tiles) do not fit in the atlas size limit %u (%u x %u tiles)",
            (unsigned long long)area, max_edge, max_tiles, max_tiles);
        goto out;
    }
    sort_items(items, n, best.order);
    skyline(items, n, best.w, max_tiles, heights, deque, prefix); /* redo the best */
    *out_w = best.w;
    *out_h = best.h;
out:
    free(heights);
    free(deque);
    free(prefix);
    return rc;
}
