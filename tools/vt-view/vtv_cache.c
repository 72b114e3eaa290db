/* vt-view tile cache: residency, LRU slots, page table with fallback entries. */
#include "vtv_cache.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vt_checked.h"
#include "vt_error.h"

int vtv_cache_init(struct vtv_cache *c, const struct vts_store *store, uint32_t slots,
                   struct vts_error *err)
{
    const struct vts_geometry *g = vts_store_geometry(store);
    memset(c, 0, sizeof(*c));
    c->level_count = g->level_count;
    for (uint32_t l = 0; l < g->level_count; l++)
        vts_store_level(store, l, &c->levels[l]);
    c->tile_count = vts_geometry_tiles_per_layer(g);
    if (slots < 1 || slots > 65536) {
        vt_error_set(err, VTS_ERR_ARG, "cache of %u tiles: must be 1..65536", slots);
        return VTS_ERR_ARG;
    }
    c->slots = slots;
    c->slots_x = (uint32_t)ceil(sqrt((double)slots));
    c->slots_y = (slots + c->slots_x - 1) / c->slots_x;
    c->pt_width = c->levels[0].tiles_x;
    for (uint32_t l = 0; l < c->level_count; l++) {
        c->pt_row[l] = c->pt_height;
        c->pt_height += c->levels[l].tiles_y;
    }
    if (c->pt_width > 16384 || c->pt_height > 16384 || c->tile_count > (1ull << 28)) {
        vt_error_set(err, VTS_ERR_LIMIT, "%s: %llu tiles per layer is too many for the page table",
                     vts_store_name(store), (unsigned long long)c->tile_count);
        return VTS_ERR_LIMIT;
    }
    size_t n = (size_t)c->tile_count;
    c->state = calloc(n, 1);
    c->slot_of = malloc(n * sizeof(*c->slot_of));
    c->slot_tile = malloc(slots * sizeof(*c->slot_tile));
    c->slot_stamp = calloc(slots, sizeof(*c->slot_stamp));
    c->pt = calloc((size_t)c->pt_width * c->pt_height, 4);
    c->changes = malloc(VTV_CACHE_MAX_CHANGES * sizeof(*c->changes));
    if (!c->state || !c->slot_of || !c->slot_tile || !c->slot_stamp || !c->pt || !c->changes) {
        vtv_cache_free(c);
        vt_error_set(err, VTS_ERR_NOMEM, "out of memory for the tile cache");
        return VTS_ERR_NOMEM;
    }
    for (size_t i = 0; i < n; i++)
        c->slot_of[i] = VTV_NO_SLOT;
    for (uint32_t s = 0; s < slots; s++)
        c->slot_tile[s] = UINT64_MAX;
    c->pt_full = true;
    vtv_cache_page_table_clean(c);
    return 0;
}

void vtv_cache_free(struct vtv_cache *c)
{
    free(c->state);
    free(c->slot_of);
    free(c->slot_tile);
    free(c->slot_stamp);
    free(c->pt);
    free(c->changes);
    memset(c, 0, sizeof(*c));
}

uint64_t vtv_cache_index(const struct vtv_cache *c, uint32_t level, uint32_t x, uint32_t y)
{
    const struct vts_level *lv = &c->levels[level];
    return lv->first_tile + (uint64_t)y * lv->tiles_x + x;
}

void vtv_cache_coords(const struct vtv_cache *c, uint64_t index, uint32_t *level, uint32_t *x,
                      uint32_t *y)
{
    uint32_t l = c->level_count - 1;
    while (l > 0 && c->levels[l].first_tile > index)
        l--;
    uint64_t r = index - c->levels[l].first_tile;
    *level = l;
    *x = (uint32_t)(r % c->levels[l].tiles_x);
    *y = (uint32_t)(r / c->levels[l].tiles_x);
}

static void changed(struct vtv_cache *c, uint64_t index)
{
    if (c->change_count < VTV_CACHE_MAX_CHANGES)
        c->changes[c->change_count++] = index;
    else
        c->pt_full = true;
}

void vtv_cache_touch(struct vtv_cache *c, uint64_t index, uint64_t stamp)
{
    uint32_t s = c->slot_of[index];
    if (s != VTV_NO_SLOT && c->slot_stamp[s] < stamp)
        c->slot_stamp[s] = stamp;
}

uint32_t vtv_cache_alloc(struct vtv_cache *c, uint64_t protect)
{
    uint32_t best = VTV_NO_SLOT;
    uint64_t best_stamp = UINT64_MAX;
    uint64_t coarsest = c->levels[c->level_count - 1].first_tile;
    for (uint32_t s = 0; s < c->slots; s++) {
        if (c->slot_tile[s] == UINT64_MAX)
            return s;
        if (c->slot_tile[s] >= coarsest || c->slot_stamp[s] >= protect)
            continue;
        if (c->slot_stamp[s] < best_stamp) {
            best_stamp = c->slot_stamp[s];
            best = s;
        }
    }
    if (best != VTV_NO_SLOT) {
        uint64_t old = c->slot_tile[best];
        c->state[old] = VTV_TILE_ABSENT;
        c->slot_of[old] = VTV_NO_SLOT;
        c->slot_tile[best] = UINT64_MAX;
        c->resident--;
        changed(c, old);
    }
    return best;
}

void vtv_cache_assign(struct vtv_cache *c, uint32_t slot, uint64_t index, uint64_t stamp)
{
    c->slot_tile[slot] = index;
    c->slot_stamp[slot] = stamp;
    c->slot_of[index] = slot;
    c->state[index] = VTV_TILE_RESIDENT;
    c->resident++;
    changed(c, index);
}

void vtv_cache_set_state(struct vtv_cache *c, uint64_t index, enum vtv_tile_state s)
{
    c->state[index] = (uint8_t)s;
}

static uint8_t *pt_at(const struct vtv_cache *c, uint32_t l, uint32_t x, uint32_t y)
{
    return c->pt + ((size_t)(c->pt_row[l] + y) * c->pt_width + x) * 4;
}

/* Entry of one tile: its own slot when resident, else its parent's entry (nearest resident
 * ancestor), invalid above the coarsest level. */
static void pt_entry(struct vtv_cache *c, uint32_t l, uint32_t x, uint32_t y)
{
    uint8_t *e = pt_at(c, l, x, y);
    uint32_t s = c->slot_of[vtv_cache_index(c, l, x, y)];
    if (s != VTV_NO_SLOT) {
        e[0] = (uint8_t)(s % c->slots_x);
        e[1] = (uint8_t)(s / c->slots_x);
        e[2] = (uint8_t)l;
        e[3] = 1;
    } else if (l + 1 < c->level_count) {
        memcpy(e, pt_at(c, l + 1, x / 2, y / 2), 4);
    } else {
        memset(e, 0, 4);
    }
}

static void mark_dirty(struct vtv_cache *c, uint32_t l, uint32_t x0, uint32_t y0, uint32_t x1,
                       uint32_t y1)
{
    if (c->dirty_x0[l] >= c->dirty_x1[l]) {
        c->dirty_x0[l] = x0;
        c->dirty_y0[l] = y0;
        c->dirty_x1[l] = x1;
        c->dirty_y1[l] = y1;
        return;
    }
    c->dirty_x0[l] = x0 < c->dirty_x0[l] ? x0 : c->dirty_x0[l];
    c->dirty_y0[l] = y0 < c->dirty_y0[l] ? y0 : c->dirty_y0[l];
    c->dirty_x1[l] = x1 > c->dirty_x1[l] ? x1 : c->dirty_x1[l];
    c->dirty_y1[l] = y1 > c->dirty_y1[l] ? y1 : c->dirty_y1[l];
}

/* Recomputes the entries of tile (l, x, y) and of all its descendants, coarse to fine. */
static void update_subtree(struct vtv_cache *c, uint32_t l, uint32_t x, uint32_t y)
{
    for (uint32_t k = l + 1; k-- > 0;) {
        const struct vts_level *lv = &c->levels[k];
        uint32_t sh = l - k;
        uint64_t x0 = (uint64_t)x << sh, y0 = (uint64_t)y << sh;
        uint64_t x1 = ((uint64_t)x + 1) << sh, y1 = ((uint64_t)y + 1) << sh;
        if (x0 >= lv->tiles_x || y0 >= lv->tiles_y)
            break;
        x1 = x1 < lv->tiles_x ? x1 : lv->tiles_x;
        y1 = y1 < lv->tiles_y ? y1 : lv->tiles_y;
        for (uint64_t ty = y0; ty < y1; ty++)
            for (uint64_t tx = x0; tx < x1; tx++)
                pt_entry(c, k, (uint32_t)tx, (uint32_t)ty);
        mark_dirty(c, k, (uint32_t)x0, (uint32_t)y0, (uint32_t)x1, (uint32_t)y1);
    }
}

bool vtv_cache_update_page_table(struct vtv_cache *c)
{
    if (c->pt_full) {
        uint32_t top = c->level_count - 1;
        for (uint32_t y = 0; y < c->levels[top].tiles_y; y++)
            for (uint32_t x = 0; x < c->levels[top].tiles_x; x++)
                update_subtree(c, top, x, y);
        c->pt_full = false;
        c->change_count = 0;
        return true;
    }
    for (uint32_t i = 0; i < c->change_count; i++) {
        uint32_t l, x, y;
        vtv_cache_coords(c, c->changes[i], &l, &x, &y);
        update_subtree(c, l, x, y);
    }
    bool any = c->change_count > 0;
    c->change_count = 0;
    return any;
}

void vtv_cache_page_table_clean(struct vtv_cache *c)
{
    for (uint32_t l = 0; l < VTS_MAX_LEVELS; l++)
        c->dirty_x0[l] = c->dirty_y0[l] = c->dirty_x1[l] = c->dirty_y1[l] = 0;
}
