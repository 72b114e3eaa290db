/* Tile-aware rectangle packing: sub-tile power-of-two cells inside shared tiles (guillotine split
 * of aligned power-of-two blocks), larger cells in whole tiles by a skyline over tile columns. */
#include "vt_atlas_pack.h"

#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "internal/vt_atlas_skyline.h"
#include "vt_checked.h"
#include "vt_error.h"

#define LOG2_MAX 17 /* tile content up to 2^16: block edges 2^0..2^16 */

uint32_t vt_atlas_next_pow2(uint32_t v)
{
    uint32_t p = 1;
    while (p < v)
        p <<= 1;
    return p;
}

static unsigned log2_u32(uint32_t v)
{
    unsigned l = 0;
    while ((1u << l) < v)
        l++;
    return l;
}

/* ---- sub-tile cells: free blocks bucketed by (log2 width, log2 height) ---- */

struct block {
    uint32_t tile; /* index of the sub-tile tile */
    uint32_t x, y; /* inside the tile */
};

struct bucket {
    struct block *items;
    size_t count, capacity;
};

struct buddy {
    struct bucket buckets[LOG2_MAX][LOG2_MAX];
    unsigned tile_log2;
    uint32_t tile_count;
};

static int bucket_push(struct bucket *b, struct block blk)
{
    if (b->count == b->capacity) {
        size_t cap = b->capacity ? b->capacity * 2 : 16;
        struct block *n = realloc(b->items, cap * sizeof *n);
        if (!n)
            return VTS_ERR_NOMEM;
        b->items = n;
        b->capacity = cap;
    }
    b->items[b->count++] = blk;
    return 0;
}

static void buddy_release(struct buddy *bd)
{
    for (unsigned i = 0; i < LOG2_MAX; i++)
        for (unsigned j = 0; j < LOG2_MAX; j++)
            free(bd->buckets[i][j].items);
}

/* Takes a free block of at least 2^lw x 2^lh (the smallest such one; a new tile when none is
 * left), places the cell at its corner and returns the rest as aligned power-of-two blocks. */
static int buddy_alloc(struct buddy *bd, unsigned lw, unsigned lh, struct block *out)
{
    unsigned best_w = 0, best_h = 0;
    bool found = false;
    for (unsigned w = lw; w <= bd->tile_log2; w++)
        for (unsigned h = lh; h <= bd->tile_log2; h++)
            if (bd->buckets[w][h].count &&
                (!found || w + h < best_w + best_h || (w + h == best_w + best_h && h < best_h))) {
                best_w = w;
                best_h = h;
                found = true;
            }
    struct block blk;
    if (found) {
        struct bucket *b = &bd->buckets[best_w][best_h];
        blk = b->items[--b->count];
    } else {
        blk = (struct block){.tile = bd->tile_count++, .x = 0, .y = 0};
        best_w = best_h = bd->tile_log2;
    }
    *out = blk;
    /* Right of the cell, the cell's height: widths 2^lw .. 2^(best_w-1) at x + 2^k. */
    for (unsigned k = lw; k < best_w; k++) {
        struct block r = {blk.tile, blk.x + (1u << k), blk.y};
        if (bucket_push(&bd->buckets[k][lh], r))
            return VTS_ERR_NOMEM;
    }
    /* Below the cell, the block's full width: heights 2^lh .. 2^(best_h-1) at y + 2^k. */
    for (unsigned k = lh; k < best_h; k++) {
        struct block r = {blk.tile, blk.x, blk.y + (1u << k)};
        if (bucket_push(&bd->buckets[best_w][k], r))
            return VTS_ERR_NOMEM;
    }
    return 0;
}

struct small_ref {
    uint32_t index;
    uint8_t lw, lh;
    uint32_t gx, gy; /* gutter before the content in x and y */
};

/* Cell edge (log2) and gutter of one axis of a sub-tile rectangle of edge e. */
static void small_axis(uint32_t e, uint32_t T, uint32_t G, uint8_t *lg, uint32_t *g)
{
    if ((uint64_t)e + 2ull * G <= T) {
        *lg = (uint8_t)log2_u32(e + 2 * G);
        *g = G;
    } else {
        *lg = (uint8_t)log2_u32(T);
        *g = 0;
    }
}

static int cmp_small_ref(const void *a, const void *b)
{
    const struct small_ref *p = a, *q = b;
    if (p->lh != q->lh)
        return p->lh > q->lh ? -1 : 1;
    if (p->lw != q->lw)
        return p->lw > q->lw ? -1 : 1;
    return p->index < q->index ? -1 : p->index > q->index;
}

static int check_args(const struct vt_atlas_rect *rects, uint32_t count,
                      const struct vt_atlas_pack_options *o, struct vts_error *err)
{
    uint32_t T = o->tile_content;
    if (T == 0 || T > (1u << (LOG2_MAX - 1)) || (T & (T - 1)))
        return vt_error_set(err, VTS_ERR_ARG, "tile content %u is not a power of two 1..65536", T);
    if (o->max_edge < T)
        return vt_error_set(err, VTS_ERR_ARG, "atlas size limit %u is below the tile content %u",
                            o->max_edge, T);
    if (o->gutter && ((o->gutter & (o->gutter - 1)) || o->gutter >= T))
        return vt_error_set(err, VTS_ERR_ARG,
                            "gutter %u is not 0 or a power of two below the tile content %u",
                            o->gutter, T);
    if (count == 0)
        return vt_error_set(err, VTS_ERR_ARG, "no texture to pack");
    for (uint32_t i = 0; i < count; i++)
        if (rects[i].width == 0 || rects[i].height == 0)
            return vt_error_set(err, VTS_ERR_ARG, "texture %u has a zero size", i);
    return 0;
}

/* Largest power of two (up to T) dividing every value of v[0..n). */
static uint32_t common_alignment(const uint32_t *v, size_t n, uint32_t T)
{
    uint32_t a = T;
    for (size_t i = 0; i < n; i++)
        while (a > 1 && v[i] % a)
            a >>= 1;
    return a;
}

/* ---- sub-tile cells with a gutter: shelves inside tiles ---- */

struct shelf {
    uint32_t tile, y, h, used;
};

struct shelf_ref {
    uint32_t index;
    uint32_t cw, ch; /* cell size, multiples of the gutter */
    uint32_t gx, gy;
};

static int cmp_shelf_ref(const void *a, const void *b)
{
    const struct shelf_ref *p = a, *q = b;
    if (p->ch != q->ch)
        return p->ch > q->ch ? -1 : 1;
    if (p->cw != q->cw)
        return p->cw > q->cw ? -1 : 1;
    return p->index < q->index ? -1 : p->index > q->index;
}

/* Cell edge and gutter of one axis with gutter G: edge + 2G rounded up to a multiple of G, or a
 * whole tile without gutter when that exceeds T (the sides are then tile edges). */
static void shelf_axis(uint32_t e, uint32_t T, uint32_t G, uint32_t *cell, uint32_t *g)
{
    if ((uint64_t)e + 2ull * G <= T) {
        *cell = (e + 2 * G + G - 1) & ~(G - 1);
        *g = G;
    } else {
        *cell = T;
        *g = 0;
    }
}

/* With a gutter the content sits at a multiple of G whatever the cell, so power-of-two cells
 * would buy no alignment: cells are edge + 2G rounded up to G, placed on shelves (tallest first;
 * each cell takes the lowest shelf that fits it, else opens a shelf in the first tile with room,
 * else a new tile). Every position and size is a multiple of G. */
static int pack_shelves(struct vt_atlas_rect *rects, uint32_t count, uint32_t T, uint32_t G,
                        uint32_t *small_tiles, uint32_t *tile_of, struct vts_error *err)
{
    size_t n = 0;
    for (uint32_t i = 0; i < count; i++)
        n += rects[i].width <= T && rects[i].height <= T;
    struct shelf_ref *refs = malloc((n ? n : 1) * sizeof *refs);
    struct shelf *shelves = malloc((n ? n : 1) * sizeof *shelves);
    uint32_t *tile_top = malloc((n ? n : 1) * sizeof *tile_top);
    size_t nshelves = 0;
    uint32_t ntiles = 0;
    int rc = 0;
    if (!refs || !shelves || !tile_top) {
        rc = vt_error_set(err, VTS_ERR_NOMEM, "out of memory packing %zu cells", n);
        goto out;
    }
    n = 0;
    for (uint32_t i = 0; i < count; i++)
        if (rects[i].width <= T && rects[i].height <= T) {
            struct shelf_ref *f = &refs[n++];
            f->index = i;
            shelf_axis(rects[i].width, T, G, &f->cw, &f->gx);
            shelf_axis(rects[i].height, T, G, &f->ch, &f->gy);
        }
    qsort(refs, n, sizeof *refs, cmp_shelf_ref);
    for (size_t k = 0; k < n; k++) {
        const struct shelf_ref *f = &refs[k];
        size_t best = SIZE_MAX;
        for (size_t j = 0; j < nshelves; j++)
            if (shelves[j].h >= f->ch && T - shelves[j].used >= f->cw &&
                (best == SIZE_MAX || shelves[j].h < shelves[best].h))
                best = j;
        if (best == SIZE_MAX) {
            uint32_t t = 0;
            while (t < ntiles && T - tile_top[t] < f->ch)
                t++;
            if (t == ntiles)
                tile_top[ntiles++] = 0;
            shelves[nshelves] = (struct shelf){t, tile_top[t], f->ch, 0};
            tile_top[t] += f->ch;
            best = nshelves++;
        }
        struct shelf *sh = &shelves[best];
        struct vt_atlas_rect *r = &rects[f->index];
        r->cell_x = sh->used;
        r->cell_y = sh->y;
        r->x = r->cell_x + f->gx;
        r->y = r->cell_y + f->gy;
        r->cell_width = f->cw;
        r->cell_height = f->ch;
        uint32_t v[6] = {r->x, r->y, r->cell_x, r->cell_y, f->cw, f->ch};
        r->alignment = common_alignment(v, 6, T);
        sh->used += f->cw;
        tile_of[f->index] = sh->tile;
        if (T - sh->used < 3 * G) /* no cell fits any more: stop scanning it */
            shelves[best] = shelves[--nshelves];
    }
    *small_tiles = ntiles;
out:
    free(refs);
    free(shelves);
    free(tile_top);
    return rc;
}

/* Places the sub-tile cells inside numbered tiles (x, y relative to the tile; tile number kept
 * in alignment until the tiles are placed). */
static int pack_small(struct vt_atlas_rect *rects, uint32_t count, uint32_t T, uint32_t G,
                      uint32_t *small_tiles, uint32_t *tile_of, struct vts_error *err)
{
    size_t n = 0;
    for (uint32_t i = 0; i < count; i++)
        n += rects[i].width <= T && rects[i].height <= T;
    struct small_ref *refs = malloc((n ? n : 1) * sizeof *refs);
    struct buddy *bd = calloc(1, sizeof *bd);
    int rc = 0;
    if (!refs || !bd) {
        rc = vt_error_set(err, VTS_ERR_NOMEM, "out of memory packing %zu cells", n);
        goto out;
    }
    n = 0;
    for (uint32_t i = 0; i < count; i++)
        if (rects[i].width <= T && rects[i].height <= T) {
            struct small_ref *f = &refs[n++];
            f->index = i;
            small_axis(rects[i].width, T, G, &f->lw, &f->gx);
            small_axis(rects[i].height, T, G, &f->lh, &f->gy);
        }
    qsort(refs, n, sizeof *refs, cmp_small_ref);
    bd->tile_log2 = log2_u32(T);
    for (size_t k = 0; k < n; k++) {
        struct block blk;
        if (buddy_alloc(bd, refs[k].lw, refs[k].lh, &blk)) {
            rc = vt_error_set(err, VTS_ERR_NOMEM, "out of memory packing %zu cells", n);
            goto out;
        }
        struct vt_atlas_rect *r = &rects[refs[k].index];
        r->cell_x = blk.x;
        r->cell_y = blk.y;
        r->x = blk.x + refs[k].gx;
        r->y = blk.y + refs[k].gy;
        r->cell_width = 1u << refs[k].lw;
        r->cell_height = 1u << refs[k].lh;
        uint32_t a = r->cell_width < r->cell_height ? r->cell_width : r->cell_height;
        if (refs[k].gx && refs[k].gx < a)
            a = refs[k].gx;
        if (refs[k].gy && refs[k].gy < a)
            a = refs[k].gy;
        r->alignment = a;
        tile_of[refs[k].index] = blk.tile;
    }
    *small_tiles = bd->tile_count;
out:
    if (bd)
        buddy_release(bd);
    free(bd);
    free(refs);
    return rc;
}

static void fill_stats(const struct vt_atlas_rect *rects, uint32_t count, uint32_t T,
                       struct vt_atlas_pack_stats *s)
{
    s->content_area = 0;
    s->cell_area = 0;
    s->base_cell_area = 0;
    for (uint32_t i = 0; i < count; i++) {
        const struct vt_atlas_rect *r = &rects[i];
        s->content_area += (uint64_t)r->width * r->height;
        s->cell_area += (uint64_t)r->cell_width * r->cell_height;
        if (r->width <= T && r->height <= T)
            s->base_cell_area +=
                (uint64_t)vt_atlas_next_pow2(r->width) * vt_atlas_next_pow2(r->height);
        else
            s->base_cell_area += (uint64_t)r->cell_width * r->cell_height;
    }
    s->tiles_x = (s->width + T - 1) / T;
    s->tiles_y = (s->height + T - 1) / T;
    s->tiles_empty = (uint64_t)s->tiles_x * s->tiles_y - s->tiles_used;
    double atlas = (double)s->width * s->height;
    s->fill_ratio = (double)s->content_area / atlas;
    s->area_over_cells = atlas / (double)s->cell_area;
    s->area_over_base = atlas / (double)s->base_cell_area;
}

int vt_atlas_pack(struct vt_atlas_rect *rects, uint32_t count,
                  const struct vt_atlas_pack_options *options, struct vt_atlas_pack_stats *stats,
                  struct vts_error *err)
{
    int rc = check_args(rects, count, options, err);
    if (rc)
        return rc;
    const uint32_t T = options->tile_content;
    const uint32_t max_tiles = options->max_edge / T;
    uint32_t *tile_of = malloc((size_t)count * sizeof *tile_of);
    struct vt_atlas_tile_item *items = NULL;
    uint32_t small_tiles = 0;
    if (!tile_of) {
        rc = vt_error_set(err, VTS_ERR_NOMEM, "out of memory packing %u cells", count);
        goto out;
    }
    if (options->gutter)
        rc = pack_shelves(rects, count, T, options->gutter, &small_tiles, tile_of, err);
    else
        rc = pack_small(rects, count, T, 0, &small_tiles, tile_of, err);
    if (rc)
        goto out;
    size_t n = 0;
    for (uint32_t i = 0; i < count; i++)
        n += !(rects[i].width <= T && rects[i].height <= T);
    size_t total = n + small_tiles;
    items = malloc(total * sizeof *items);
    if (!items) {
        rc = vt_error_set(err, VTS_ERR_NOMEM, "out of memory packing %u cells", count);
        goto out;
    }
    n = 0;
    uint64_t used = 0;
    for (uint32_t i = 0; i < count; i++)
        if (!(rects[i].width <= T && rects[i].height <= T)) {
            uint32_t tw = (uint32_t)(((uint64_t)rects[i].width + T - 1) / T);
            uint32_t th = (uint32_t)(((uint64_t)rects[i].height + T - 1) / T);
            items[n++] = (struct vt_atlas_tile_item){.w = tw, .h = th, .index = i};
            used += (uint64_t)tw * th;
        }
    for (uint32_t t = 0; t < small_tiles; t++)
        items[n++] = (struct vt_atlas_tile_item){.w = 1, .h = 1, .index = t, .subtile = true};
    used += small_tiles;
    uint32_t W = 0, H = 0;
    rc = vt_atlas_skyline_pack(items, total, max_tiles, options->max_edge, &W, &H, err);
    if (rc)
        goto out;
    /* Sub-tile tile t sits at tile (small_pos[2t], small_pos[2t + 1]). */
    uint32_t *small_pos = calloc((size_t)small_tiles * 2 + 1, sizeof *small_pos);
    if (!small_pos) {
        rc = vt_error_set(err, VTS_ERR_NOMEM, "out of memory packing %u cells", count);
        goto out;
    }
    for (size_t k = 0; k < total; k++) {
        const struct vt_atlas_tile_item *it = &items[k];
        if (it->subtile) {
            small_pos[2 * it->index] = it->x;
            small_pos[2 * it->index + 1] = it->y;
        } else {
            struct vt_atlas_rect *r = &rects[it->index];
            r->x = r->cell_x = it->x * T;
            r->y = r->cell_y = it->y * T;
            r->cell_width = it->w * T;
            r->cell_height = it->h * T;
            r->alignment = T;
        }
    }
    uint32_t width = W * T, height = H * T;
    if (W == 1 && H == 1)
        width = height = 0; /* one tile: shrink to the used corner */
    for (uint32_t i = 0; i < count; i++)
        if (rects[i].width <= T && rects[i].height <= T) {
            uint32_t dx = small_pos[2 * tile_of[i]] * T, dy = small_pos[2 * tile_of[i] + 1] * T;
            rects[i].x += dx;
            rects[i].y += dy;
            rects[i].cell_x += dx;
            rects[i].cell_y += dy;
        }
    if (W == 1 && H == 1)
        for (uint32_t i = 0; i < count; i++) {
            if (rects[i].cell_x + rects[i].cell_width > width)
                width = rects[i].cell_x + rects[i].cell_width;
            if (rects[i].cell_y + rects[i].cell_height > height)
                height = rects[i].cell_y + rects[i].cell_height;
        }
    if (W == 1 && H == 1) {
        width = vt_atlas_next_pow2(width);
        height = vt_atlas_next_pow2(height);
    }
    free(small_pos);
    if (stats) {
        memset(stats, 0, sizeof *stats);
        stats->width = width;
        stats->height = height;
        stats->tiles_used = used;
        stats->subtile_tiles = small_tiles;
        fill_stats(rects, count, T, stats);
    }
out:
    free(items);
    free(tile_of);
    return rc;
}
