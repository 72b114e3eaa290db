/* String -> index map of the scene scan (internal/vt_strmap.h). */
#include "internal/vt_strmap.h"

#include <assert.h>
#include <stdlib.h>
#include <string.h>

#include "vt_error.h"

static uint64_t hash_str(const char *s)
{
    uint64_t h = 1469598103934665603ull; /* FNV-1a, 64-bit */
    for (; *s; s++)
        h = (h ^ (unsigned char)*s) * 1099511628211ull;
    return h;
}

/* The slot holding key, or the free slot where it would go. capacity is a non-zero power of two
 * and the table is never full, so the probe ends. */
static size_t find_slot(const char *const *keys, size_t capacity, const char *key)
{
    size_t mask = capacity - 1;
    size_t i = (size_t)hash_str(key) & mask;
    while (keys[i] && strcmp(keys[i], key) != 0)
        i = (i + 1) & mask;
    return i;
}

int64_t vt_strmap_get(const struct vt_strmap *map, const char *key)
{
    if (!map->capacity)
        return -1;
    size_t i = find_slot(map->keys, map->capacity, key);
    return map->keys[i] ? (int64_t)map->values[i] : -1;
}

/* Moves every entry into tables of twice the capacity (64 for an empty map). */
static int grow(struct vt_strmap *map)
{
    size_t capacity = map->capacity ? map->capacity * 2 : 64;
    if (capacity < map->capacity)
        return VTS_ERR_NOMEM;
    const char **keys = calloc(capacity, sizeof *keys);
    uint32_t *values = calloc(capacity, sizeof *values);
    if (!keys || !values)
        goto out_nomem;
    for (size_t i = 0; i < map->capacity; i++) {
        if (!map->keys[i])
            continue;
        size_t j = find_slot(keys, capacity, map->keys[i]);
        keys[j] = map->keys[i];
        values[j] = map->values[i];
    }
    free(map->keys);
    free(map->values);
    map->keys = keys;
    map->values = values;
    map->capacity = capacity;
    return 0;
out_nomem:
    free(keys);
    free(values);
    return VTS_ERR_NOMEM;
}

int vt_strmap_put(struct vt_strmap *map, const char *key, uint32_t value)
{
    /* At most half full: count + 1 <= capacity / 2 (count < capacity, so no overflow). */
    if (map->count + 1 > map->capacity / 2) {
        int rc = grow(map);
        if (rc)
            return rc;
    }
    size_t i = find_slot(map->keys, map->capacity, key);
    assert(!map->keys[i]); /* the caller looks the key up first */
    map->keys[i] = key;
    map->values[i] = value;
    map->count++;
    return 0;
}

void vt_strmap_release(struct vt_strmap *map)
{
    if (!map)
        return;
    free(map->keys);
    free(map->values);
    memset(map, 0, sizeof *map);
}
