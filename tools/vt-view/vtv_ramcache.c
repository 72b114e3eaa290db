/* vt-view RAM cache of tile payloads (see vtv_ramcache.h): entries in an array, found through an
 * open-addressing hash of tile indices, ordered by a doubly linked LRU list. */
#include "vtv_ramcache.h"

#include <stdlib.h>
#include <string.h>

#define NONE UINT32_MAX

struct entry {
    uint64_t index;
    uint8_t *data;
    size_t bytes, capacity;
    uint32_t prev, next; /* LRU list: head most recent */
};

struct vtv_ramcache {
    struct entry *e;
    uint32_t cap, count, head, tail;
    uint32_t *hash; /* entry of each bucket or NONE; linear probing, deletion by re-insertion */
    uint32_t mask;
};

static uint32_t bucket(const struct vtv_ramcache *c, uint64_t index)
{
    index *= 0x9e3779b97f4a7c15ull;
    return (uint32_t)(index >> 32) & c->mask;
}

static uint32_t find(const struct vtv_ramcache *c, uint64_t index, uint32_t *slot)
{
    for (uint32_t b = bucket(c, index);; b = (b + 1) & c->mask) {
        uint32_t k = c->hash[b];
        if (k == NONE || c->e[k].index == index) {
            if (slot)
                *slot = b;
            return k;
        }
    }
}

static void unlink_lru(struct vtv_ramcache *c, uint32_t k)
{
    struct entry *e = &c->e[k];
    if (e->prev != NONE)
        c->e[e->prev].next = e->next;
    else
        c->head = e->next;
    if (e->next != NONE)
        c->e[e->next].prev = e->prev;
    else
        c->tail = e->prev;
    e->prev = e->next = NONE;
}

static void push_front(struct vtv_ramcache *c, uint32_t k)
{
    struct entry *e = &c->e[k];
    e->prev = NONE;
    e->next = c->head;
    if (c->head != NONE)
        c->e[c->head].prev = k;
    c->head = k;
    if (c->tail == NONE)
        c->tail = k;
}

/* Removes the hash bucket b and re-inserts the run of buckets after it (linear probing). */
static void hash_remove(struct vtv_ramcache *c, uint32_t b)
{
    c->hash[b] = NONE;
    for (uint32_t i = (b + 1) & c->mask; c->hash[i] != NONE; i = (i + 1) & c->mask) {
        uint32_t k = c->hash[i], s;
        c->hash[i] = NONE;
        find(c, c->e[k].index, &s);
        c->hash[s] = k;
    }
}

struct vtv_ramcache *vtv_ramcache_create(uint32_t tiles)
{
    struct vtv_ramcache *c = calloc(1, sizeof *c);
    if (!c)
        return NULL;
    c->cap = tiles;
    c->head = c->tail = NONE;
    uint32_t buckets = 16;
    while (buckets < 2 * (uint64_t)tiles && buckets < (1u << 31))
        buckets *= 2;
    c->mask = buckets - 1;
    c->e = calloc(tiles ? tiles : 1, sizeof *c->e);
    c->hash = malloc(buckets * sizeof *c->hash);
    if (!c->e || !c->hash) {
        vtv_ramcache_destroy(c);
        return NULL;
    }
    memset(c->hash, 0xff, buckets * sizeof *c->hash);
    return c;
}

void vtv_ramcache_destroy(struct vtv_ramcache *c)
{
    if (!c)
        return;
    for (uint32_t i = 0; c->e && i < c->count; i++)
        free(c->e[i].data);
    free(c->e);
    free(c->hash);
    free(c);
}

const uint8_t *vtv_ramcache_get(struct vtv_ramcache *c, uint64_t index, size_t *bytes)
{
    if (!c || c->count == 0)
        return NULL;
    uint32_t k = find(c, index, NULL);
    if (k == NONE || c->e[k].bytes == 0) /* bytes 0: a put that ran out of memory */
        return NULL;
    unlink_lru(c, k);
    push_front(c, k);
    *bytes = c->e[k].bytes;
    return c->e[k].data;
}

bool vtv_ramcache_has(const struct vtv_ramcache *c, uint64_t index)
{
    uint32_t k = c && c->count ? find(c, index, NULL) : NONE;
    return k != NONE && c->e[k].bytes > 0;
}

bool vtv_ramcache_put(struct vtv_ramcache *c, uint64_t index, const uint8_t *data, size_t bytes)
{
    if (c->cap == 0)
        return true;
    uint32_t b, k = find(c, index, &b);
    if (k == NONE) {
        if (c->count < c->cap) {
            k = c->count++;
            c->e[k] = (struct entry){.prev = NONE, .next = NONE};
        } else { /* reuse the least recently used entry */
            k = c->tail;
            uint32_t old;
            find(c, c->e[k].index, &old);
            hash_remove(c, old);
            unlink_lru(c, k);
            find(c, index, &b); /* the bucket may have moved */
        }
        c->e[k].index = index;
        c->hash[b] = k;
    } else {
        unlink_lru(c, k);
    }
    struct entry *e = &c->e[k];
    if (e->capacity < bytes) {
        uint8_t *p = realloc(e->data, bytes);
        if (!p) { /* forget the entry: its old payload is of another tile now */
            e->bytes = 0;
            push_front(c, k);
            return false;
        }
        e->data = p;
        e->capacity = bytes;
    }
    memcpy(e->data, data, bytes);
    e->bytes = bytes;
    push_front(c, k);
    return true;
}

uint32_t vtv_ramcache_count(const struct vtv_ramcache *c)
{
    return c->count;
}
