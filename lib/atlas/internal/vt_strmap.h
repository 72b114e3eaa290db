/* A string -> uint32_t map for the scene scan (lib/atlas/vt_atlas_scene.c): material names, texture
 * paths, file identities and dependencies to their array index. Open addressing with linear
 * probing, FNV-1a hashes, at most half full. Keys are not copied: each must stay alive and
 * unchanged while the map holds it (the scan points them at the strings its arrays own). */
#ifndef VT_STRMAP_H
#define VT_STRMAP_H

#include <stddef.h>
#include <stdint.h>

/* Zero it to get an empty map; free with vt_strmap_release(). */
struct vt_strmap {
    const char **keys; /* capacity slots, NULL when free */
    uint32_t *values;
    size_t capacity, count; /* capacity: 0 or a power of two */
};

/* The value stored for key, or -1 when it is not in the map. */
int64_t vt_strmap_get(const struct vt_strmap *map, const char *key);

/* Stores key -> value; key must not be in the map yet (look it up first). Returns 0, or
 * VTS_ERR_NOMEM with the map unchanged. */
int vt_strmap_put(struct vt_strmap *map, const char *key, uint32_t value);

/* Frees the tables (not the keys) and zeroes the map. Accepts NULL. */
void vt_strmap_release(struct vt_strmap *map);

#endif
