/* Texture-chain cache of the atlas compositor (see vt_atlas_cache.h). */
#include "internal/vt_atlas_cache.h"
#include "vt_error.h"

#include <stdlib.h>

enum chain_state { CHAIN_LOADING, CHAIN_READY };

struct vt_atlas_cache_node {
    struct vt_mip_chain c;
    uint64_t key;
    int refs;
    enum chain_state state;
    struct vt_atlas_cache_node *prev, *next; /* LRU list of unreferenced ready chains */
};

static void lru_unlink(struct vt_atlas_cache *c, struct vt_atlas_cache_node *n)
{
    if (n->prev)
        n->prev->next = n->next;
    else
        c->lru_head = n->next;
    if (n->next)
        n->next->prev = n->prev;
    else
        c->lru_tail = n->prev;
    n->prev = n->next = NULL;
}

static void lru_push(struct vt_atlas_cache *c, struct vt_atlas_cache_node *n)
{
    n->prev = c->lru_tail;
    n->next = NULL;
    if (c->lru_tail)
        c->lru_tail->next = n;
    else
        c->lru_head = n;
    c->lru_tail = n;
}

/* Frees unreferenced chains, oldest first, while over budget. Under the lock. */
static void evict(struct vt_atlas_cache *c)
{
    while (c->bytes > c->budget && c->lru_head) {
        struct vt_atlas_cache_node *n = c->lru_head;
        lru_unlink(c, n);
        c->table[n->key] = NULL;
        c->bytes -= n->c.bytes;
        vt_mip_chain_release(&n->c);
        free(n);
    }
}

/* The chain of key, referenced (release with chain_release). */
static int chain_acquire(struct vt_atlas_cache *c, uint64_t key, struct vt_atlas_cache_node **out,
                         struct vts_error *err)
{
    pthread_mutex_lock(&c->mu);
    for (;;) {
        struct vt_atlas_cache_node *n = c->table[key];
        if (!n)
            break;
        if (n->state == CHAIN_READY) {
            if (n->refs++ == 0)
                lru_unlink(c, n);
            pthread_mutex_unlock(&c->mu);
            *out = n;
            return 0;
        }
        pthread_cond_wait(&c->cv, &c->mu); /* another worker is decoding it */
    }
    struct vt_atlas_cache_node *n = calloc(1, sizeof *n);
    if (!n) {
        pthread_mutex_unlock(&c->mu);
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory for a texture chain");
    }
    n->key = key;
    n->state = CHAIN_LOADING;
    n->refs = 1;
    c->table[key] = n;
    pthread_mutex_unlock(&c->mu);

    int rc = c->build(c->build_user, key, &n->c, err);

    pthread_mutex_lock(&c->mu);
    if (rc) {
        c->table[key] = NULL;
        free(n);
        n = NULL;
    } else {
        n->state = CHAIN_READY;
        c->bytes += n->c.bytes;
        c->built++;
        if (c->bytes > c->peak)
            c->peak = c->bytes;
        evict(c);
    }
    pthread_cond_broadcast(&c->cv);
    pthread_mutex_unlock(&c->mu);
    *out = n;
    return rc;
}

static void chain_release(struct vt_atlas_cache *c, struct vt_atlas_cache_node *n)
{
    pthread_mutex_lock(&c->mu);
    if (--n->refs == 0) {
        lru_push(c, n);
        evict(c);
    }
    pthread_mutex_unlock(&c->mu);
}

void vt_atlas_cache_unpin_all(struct vt_atlas_cache *c, struct vt_atlas_cache_pins *p)
{
    for (uint32_t i = 0; i < p->count; i++)
        chain_release(c, p->pins[i].node);
    p->count = 0;
    p->next = 0;
}

int vt_atlas_cache_get(struct vt_atlas_cache *c, struct vt_atlas_cache_pins *p, uint64_t key,
                       const struct vt_mip_chain **out, struct vts_error *err)
{
    for (uint32_t i = 0; i < p->count; i++)
        if (p->pins[i].key == key) {
            *out = &p->pins[i].node->c;
            return 0;
        }
    struct vt_atlas_cache_node *n = NULL;
    int rc = chain_acquire(c, key, &n, err);
    if (rc)
        return rc;
    uint32_t i;
    if (p->count < VT_ATLAS_CACHE_PINS) {
        i = p->count++;
    } else { /* drop the oldest pin; texel pointers into it are not kept across calls */
        i = p->next;
        p->next = (p->next + 1) % VT_ATLAS_CACHE_PINS;
        chain_release(c, p->pins[i].node);
    }
    p->pins[i].key = key;
    p->pins[i].node = n;
    *out = &n->c;
    return 0;
}

int vt_atlas_cache_init(struct vt_atlas_cache *c, size_t key_count, uint64_t budget_bytes,
                        vt_atlas_cache_build_fn build, void *build_user, struct vts_error *err)
{
    *c = (struct vt_atlas_cache){.budget = budget_bytes, .build = build, .build_user = build_user};
    if (pthread_mutex_init(&c->mu, NULL))
        return vt_error_set(err, VTS_ERR_NOMEM, "cannot create a mutex");
    if (pthread_cond_init(&c->cv, NULL)) {
        pthread_mutex_destroy(&c->mu);
        return vt_error_set(err, VTS_ERR_NOMEM, "cannot create a condition variable");
    }
    c->sync_ok = true;
    c->table = calloc(key_count, sizeof *c->table);
    if (!c->table)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory for the atlas tables");
    c->key_count = key_count;
    return 0;
}

void vt_atlas_cache_release(struct vt_atlas_cache *c)
{
    if (!c)
        return;
    if (c->table) {
        for (size_t i = 0; i < c->key_count; i++)
            if (c->table[i]) {
                vt_mip_chain_release(&c->table[i]->c);
                free(c->table[i]);
            }
    }
    if (c->sync_ok) {
        pthread_mutex_destroy(&c->mu);
        pthread_cond_destroy(&c->cv);
    }
    free(c->table);
    c->table = NULL;
    c->sync_ok = false;
}
