/* vt-view tile cache: the residency state of every tile of the store, the slots of the physical
 * texture with LRU replacement (the coarsest level is pinned, never evicted), and the CPU side of
 * the page table (each tile's entry points at itself when resident, else at its nearest resident
 * ancestor: the fallback). */
#ifndef VTV_CACHE_H
#define VTV_CACHE_H

#include <stdbool.h>
#include <stdint.h>

#include "vt_error.h"
#include "vts.h"

enum vtv_tile_state {
    VTV_TILE_ABSENT = 0,   /* not in the cache, not asked for */
    VTV_TILE_QUEUED = 1,   /* handed to the loader */
    VTV_TILE_RESIDENT = 2, /* in a slot of the physical texture */
    VTV_TILE_EMPTY = 3,    /* stored with length 0: its ancestor is shown */
    VTV_TILE_FAILED = 4,   /* could not be read or decoded (reported once) */
};

#define VTV_NO_SLOT UINT32_MAX

struct vtv_cache {
    uint32_t level_count;
    struct vts_level levels[VTS_MAX_LEVELS];
    uint64_t tile_count; /* tiles of one layer, all levels */
    uint8_t *state;      /* per tile: enum vtv_tile_state */
    uint32_t *slot_of;   /* per tile: slot or VTV_NO_SLOT */
    uint32_t slots, slots_x, slots_y;
    uint64_t *slot_tile;  /* per slot: tile index or UINT64_MAX */
    uint64_t *slot_stamp; /* per slot: last frame the tile was requested */
    uint32_t resident;
    /* Page table: level l occupies rows pt_row[l] .. pt_row[l] + tiles_y(l) - 1 of a pt_width x
     * pt_height RGBA8 texture; each texel is (slot x, slot y, level used, 1 when valid). */
    uint32_t pt_width, pt_height;
    uint32_t pt_row[VTS_MAX_LEVELS];
    uint8_t *pt; /* pt_width * pt_height * 4 bytes */
    /* Tiles that came or went since the last update (their subtrees are recomputed), or a full
     * rebuild when there were more than VTV_CACHE_MAX_CHANGES. */
    uint64_t *changes;
    uint32_t change_count;
    bool pt_full;
    /* Per level, the rectangle of entries changed since vtv_cache_page_table_clean() (x0 >= x1:
     * none), for partial uploads. */
    uint32_t dirty_x0[VTS_MAX_LEVELS], dirty_y0[VTS_MAX_LEVELS];
    uint32_t dirty_x1[VTS_MAX_LEVELS], dirty_y1[VTS_MAX_LEVELS];
};

#define VTV_CACHE_MAX_CHANGES 4096u

/* Sets up the state of every tile of store and a cache of `slots` physical slots (a near-square
 * grid). Returns 0 or VTS_ERR_NOMEM / VTS_ERR_LIMIT with a message. */
int vtv_cache_init(struct vtv_cache *c, const struct vts_store *store, uint32_t slots,
                   struct vts_error *err);
void vtv_cache_free(struct vtv_cache *c);

/* Index of tile (level, x, y) in the state arrays, and back. */
uint64_t vtv_cache_index(const struct vtv_cache *c, uint32_t level, uint32_t x, uint32_t y);
void vtv_cache_coords(const struct vtv_cache *c, uint64_t index, uint32_t *level, uint32_t *x,
                      uint32_t *y);

/* Marks a resident tile as used in frame `stamp` (LRU). */
void vtv_cache_touch(struct vtv_cache *c, uint64_t index, uint64_t stamp);

/* A slot for a new tile: a free one, else the least recently used tile whose stamp is below
 * `protect` and which is not on the coarsest level (evicted: its state becomes ABSENT). Returns
 * VTV_NO_SLOT when every slot is protected. */
uint32_t vtv_cache_alloc(struct vtv_cache *c, uint64_t protect);

/* Puts tile index into slot (from vtv_cache_alloc) as resident, stamped `stamp`. */
void vtv_cache_assign(struct vtv_cache *c, uint32_t slot, uint64_t index, uint64_t stamp);

/* Records a tile that is stored empty (its ancestor stays in use). */
void vtv_cache_set_state(struct vtv_cache *c, uint64_t index, enum vtv_tile_state s);

/* Brings the page table entries up to date after tiles came or went (only the subtrees of the
 * changed tiles are recomputed); returns true when entries changed (see the dirty rectangles). */
bool vtv_cache_update_page_table(struct vtv_cache *c);

/* Forgets the dirty rectangles (after the page table was uploaded). */
void vtv_cache_page_table_clean(struct vtv_cache *c);

#endif
