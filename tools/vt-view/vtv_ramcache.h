/* vt-view RAM cache: decoded tile payloads (RGBA8 texels or BC blocks, as uploaded) kept in main
 * memory beyond the physical texture, least recently used first out. A tile evicted from the
 * physical texture and asked for again is uploaded from here, without a read or a decode; the
 * prefetch (vtv_stream) fills it ahead of demand. Single-threaded (the render thread). */
#ifndef VTV_RAMCACHE_H
#define VTV_RAMCACHE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

struct vtv_ramcache;

/* A cache of at most `tiles` payloads (0: a cache that holds nothing). NULL when out of memory. */
struct vtv_ramcache *vtv_ramcache_create(uint32_t tiles);
void vtv_ramcache_destroy(struct vtv_ramcache *c);

/* The payload of tile index (made most recently used), or NULL; *bytes its size. c may be NULL
 * (no cache), here and in vtv_ramcache_has(). */
const uint8_t *vtv_ramcache_get(struct vtv_ramcache *c, uint64_t index, size_t *bytes);

/* True when tile index is held (does not change the order). */
bool vtv_ramcache_has(const struct vtv_ramcache *c, uint64_t index);

/* Keeps a copy of a payload of tile index (replacing the least recently used one when full).
 * Returns false when out of memory (nothing kept). */
bool vtv_ramcache_put(struct vtv_ramcache *c, uint64_t index, const uint8_t *data, size_t bytes);

/* Tiles held. */
uint32_t vtv_ramcache_count(const struct vtv_ramcache *c);

#endif
