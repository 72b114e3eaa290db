/* Bounded store of the blocks of decoded texture mip chains for the atlas compositor (private to
 * lib/compose). A block is a small rectangle of one level of one chain (at most
 * VT_BLOCK_CACHE_EDGE texels a side), named by a dense id. Blocks are put once, then read many
 * times; the bytes of blocks held in memory never exceed the budget: before a block is put or
 * read back, unreferenced blocks are written to an unlinked temporary file (once each: blocks do
 * not change) and freed, least recently used first. Readers pin blocks (reference counts) while
 * they use them; only pinned blocks may take the memory over the budget (a reader needs the one it
 * reads), at most VT_BLOCK_CACHE_PINS per reader. Thread safe, except create/destroy; the file
 * is written and read outside the cache's lock (a block being written stays counted in memory
 * until it is freed). */
#ifndef VT_BLOCK_CACHE_H
#define VT_BLOCK_CACHE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "vt_error.h"

#define VT_BLOCK_CACHE_SHIFT 6
#define VT_BLOCK_CACHE_EDGE  (1u << VT_BLOCK_CACHE_SHIFT) /* texels: 64 */
#define VT_BLOCK_CACHE_PINS  8                            /* blocks a reader holds at once */

struct vt_block_cache;
struct vt_block_cache_node; /* private to vt_block_cache.c */

/* The blocks one reader holds referenced (zero-initialise; empty it with _unpin_all). */
struct vt_block_cache_pins {
    struct {
        uint64_t id;
        struct vt_block_cache_node *node;
    } pins[VT_BLOCK_CACHE_PINS];
    uint32_t count, next;
};

struct vt_block_cache_stats {
    uint64_t budget;        /* bytes */
    uint64_t bytes;         /* block bytes in memory now */
    uint64_t peak;          /* most block bytes in memory at once (those being written included) */
    uint64_t peak_unpinned; /* most at once that no reader needed (this one never exceeds budget) */
    uint64_t spilled;       /* bytes written to the temporary file */
    uint64_t reloads;       /* blocks read back from it */
    uint64_t peak_reserved; /* most bytes reserved at once (vt_block_cache_reserve) */
};

/* An empty cache for block ids 0..block_count-1 keeping at most budget_bytes in memory; the
 * temporary file is created in temp_dir (NULL: $TMPDIR or /tmp) when the first block spills.
 * Returns NULL and fills err (VTS_ERR_NOMEM). Free with vt_block_cache_destroy(). */
struct vt_block_cache *vt_block_cache_create(uint64_t block_count, uint64_t budget_bytes,
                                             const char *temp_dir, struct vts_error *err);

/* Frees every block, closes the file. Every pin must be released first. Accepts NULL. */
void vt_block_cache_destroy(struct vt_block_cache *c);

/* Stores block id (bytes bytes, copied; id not put before). 0, VTS_ERR_NOMEM or VTS_ERR_IO. */
int vt_block_cache_put(struct vt_block_cache *c, uint64_t id, const void *data, size_t bytes,
                       struct vts_error *err);

/* Forgets block id (put before, not pinned): its memory is freed, its file bytes unused. */
void vt_block_cache_drop(struct vt_block_cache *c, uint64_t id);

/* The bytes of block id (put before), pinned in p until vt_block_cache_unpin_all (or until
 * VT_BLOCK_CACHE_PINS other blocks are pinned in p). 0, VTS_ERR_NOMEM or VTS_ERR_IO. */
int vt_block_cache_get(struct vt_block_cache *c, struct vt_block_cache_pins *p, uint64_t id,
                       const uint8_t **out, struct vts_error *err);

/* Releases every block pinned in p. */
void vt_block_cache_unpin_all(struct vt_block_cache *c, struct vt_block_cache_pins *p);

/* Counts bytes of the caller's own buffers (a texture stream's) against the budget until
 * vt_block_cache_unreserve: unreferenced blocks are spilled to make room. With first set (the
 * caller reserves nothing yet), waits while others hold reservations and this one would take
 * them over half the budget, so that workers' buffers cannot crowd out the blocks whatever
 * their number. 0 or VTS_ERR_IO (a spill failed; the bytes are reserved all the same). */
int vt_block_cache_reserve(struct vt_block_cache *c, uint64_t bytes, bool first,
                           struct vts_error *err);

/* Gives back bytes reserved before. */
void vt_block_cache_unreserve(struct vt_block_cache *c, uint64_t bytes);

void vt_block_cache_stats(struct vt_block_cache *c, struct vt_block_cache_stats *out);

#endif
