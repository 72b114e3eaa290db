/* Shared cache of decoded texture mip chains for the atlas compositor (private to lib/compose).
 * Chains are keyed by a dense index (entry * slots + slot), built on first use by a callback,
 * shared between workers with reference counts, and freed least recently used first while the
 * cache holds more than its byte budget. A chain being built by one worker is waited for by the
 * others. Thread safe: every function may be called from several workers at once, except
 * init/release. */
#ifndef VT_ATLAS_CACHE_H
#define VT_ATLAS_CACHE_H

#include <pthread.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "vt_error.h"
#include "vt_mip_chain.h"

#define VT_ATLAS_CACHE_PINS 8 /* chains a worker holds at once */

/* Builds the chain for key into *out (called without the cache lock). 0 or a negative status. */
typedef int (*vt_atlas_cache_build_fn)(void *user, uint64_t key, struct vt_mip_chain *out,
                                       struct vts_error *err);

struct vt_atlas_cache_node; /* private to vt_atlas_cache.c */

/* The chains one worker holds referenced (zero-initialise; empty it with _unpin_all). */
struct vt_atlas_cache_pins {
    struct {
        uint64_t key;
        struct vt_atlas_cache_node *node;
    } pins[VT_ATLAS_CACHE_PINS];
    uint32_t count, next;
};

struct vt_atlas_cache {
    pthread_mutex_t mu;
    pthread_cond_t cv;
    bool sync_ok;
    struct vt_atlas_cache_node **table; /* key_count slots */
    size_t key_count;
    struct vt_atlas_cache_node *lru_head, *lru_tail; /* unreferenced ready chains */
    uint64_t bytes, peak, built, budget;
    vt_atlas_cache_build_fn build;
    void *build_user;
};

/* Sets up an empty cache for keys 0..key_count-1 holding about budget_bytes of unreferenced
 * chains. 0 or VTS_ERR_NOMEM; on failure c may still be passed to vt_atlas_cache_release. */
int vt_atlas_cache_init(struct vt_atlas_cache *c, size_t key_count, uint64_t budget_bytes,
                        vt_atlas_cache_build_fn build, void *build_user, struct vts_error *err);

/* Frees every chain and the cache's own memory. Every pin must be released first. NULL-safe. */
void vt_atlas_cache_release(struct vt_atlas_cache *c);

/* The chain of key, pinned in p until vt_atlas_cache_unpin_all (or until VT_ATLAS_CACHE_PINS
 * other chains are pinned in p). 0 or the status of the build callback / VTS_ERR_NOMEM. */
int vt_atlas_cache_get(struct vt_atlas_cache *c, struct vt_atlas_cache_pins *p, uint64_t key,
                       const struct vt_mip_chain **out, struct vts_error *err);

/* Releases every chain pinned in p. */
void vt_atlas_cache_unpin_all(struct vt_atlas_cache *c, struct vt_atlas_cache_pins *p);

#endif
