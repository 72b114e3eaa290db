/* Fixed-size key -> value map of lib/chart (internal/vt_keymap.h). */
#include "internal/vt_keymap.h"

#include <assert.h>
#include <stdlib.h>
#include <string.h>

#include "vt_checked.h"
#include "vt_error.h"

/* A 64-bit mix of the key's words (multiply-xorshift rounds, the finaliser of MurmurHash3). */
static uint64_t hash_key(const uint64_t *key, unsigned words)
{
    uint64_t h = 0x9e3779b97f4a7c15ull * (words + 1);
    for (unsigned i = 0; i < words; i++) {
        h ^= key[i];
        h *= 0xff51afd7ed558ccdull;
        h ^= h >> 32;
    }
    h ^= h >> 33;
    h *= 0xc4ceb9fe1a85ec53ull;
    h ^= h >> 33;
    return h;
}

/* The offset (in words) of the slot holding key, or of the free slot where it would go. The table
 * is never full, so the probe ends. */
static size_t find_slot(const uint64_t *slots, size_t capacity, unsigned words, const uint64_t *key)
{
    size_t mask = capacity - 1, stride = (size_t)words + 1;
    size_t i = (size_t)hash_key(key, words) & mask;
    for (;;) {
        const uint64_t *s = slots + i * stride;
        if (!s[words] || memcmp(s, key, words * sizeof *key) == 0)
            return i * stride;
        i = (i + 1) & mask;
    }
}

void vt_keymap_init(struct vt_keymap *map, unsigned key_words)
{
    assert(key_words >= 1 && key_words <= VT_KEYMAP_MAX_WORDS);
    memset(map, 0, sizeof *map);
    map->key_words = key_words;
}

/* Moves every entry into a table of capacity slots (a power of two above count * 4 / 3). */
static int rehash(struct vt_keymap *map, size_t capacity)
{
    unsigned words = map->key_words;
    size_t stride = (size_t)words + 1, bytes;
    if (!vt_size_mul(capacity, stride * sizeof(uint64_t), &bytes))
        return VTS_ERR_NOMEM;
    uint64_t *slots = calloc(1, bytes);
    if (!slots)
        return VTS_ERR_NOMEM;
    for (size_t i = 0; i < map->capacity; i++) {
        const uint64_t *s = map->slots + i * stride;
        if (s[words])
            memcpy(slots + find_slot(slots, capacity, words, s), s, stride * sizeof *s);
    }
    free(map->slots);
    map->slots = slots;
    map->capacity = capacity;
    return 0;
}

int vt_keymap_reserve(struct vt_keymap *map, size_t count)
{
    size_t capacity = map->capacity ? map->capacity : 16;
    /* at most 3/4 full: count <= capacity - capacity / 4 */
    while (count > capacity - capacity / 4) {
        if (capacity > SIZE_MAX / 2)
            return VTS_ERR_NOMEM;
        capacity *= 2;
    }
    return capacity == map->capacity ? 0 : rehash(map, capacity);
}

bool vt_keymap_put_new(struct vt_keymap *map, const uint64_t *key, uint64_t *value, int *rc)
{
    assert(*value < UINT64_MAX);
    *rc = 0;
    if (map->count + 1 > map->capacity - map->capacity / 4) {
        *rc = vt_keymap_reserve(map, map->count + 1);
        if (*rc)
            return false;
    }
    unsigned words = map->key_words;
    uint64_t *s = map->slots + find_slot(map->slots, map->capacity, words, key);
    if (s[words]) {
        *value = s[words] - 1;
        return false;
    }
    memcpy(s, key, words * sizeof *key);
    s[words] = *value + 1;
    map->count++;
    return true;
}

bool vt_keymap_get(const struct vt_keymap *map, const uint64_t *key, uint64_t *value)
{
    if (!map->capacity)
        return false;
    const uint64_t *s = map->slots + find_slot(map->slots, map->capacity, map->key_words, key);
    if (!s[map->key_words])
        return false;
    *value = s[map->key_words] - 1;
    return true;
}

void vt_keymap_release(struct vt_keymap *map)
{
    if (!map)
        return;
    free(map->slots);
    unsigned words = map->key_words;
    memset(map, 0, sizeof *map);
    map->key_words = words;
}
