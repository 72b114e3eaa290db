/* A map from fixed-size keys (1 to VT_KEYMAP_MAX_WORDS 64-bit words, the same for every key of one
 * map) to 64-bit values, for lib/chart: the charts' shared texcoords and edges (vt_chart.c), the
 * cut's edges and grid points (vt_cut*.c). Open addressing with linear probing, keys stored in the
 * table, at most 3/4 full. Deterministic: no random seed. */
#ifndef VT_KEYMAP_H
#define VT_KEYMAP_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#define VT_KEYMAP_MAX_WORDS 6

/* Set it up with vt_keymap_init(); free with vt_keymap_release(). */
struct vt_keymap {
    uint64_t *slots; /* capacity slots of key_words + 1 words: the key, then value + 1 (0: free) */
    size_t capacity; /* 0 or a power of two */
    size_t count;
    unsigned key_words;
};

/* An empty map for keys of key_words (1..VT_KEYMAP_MAX_WORDS) words; allocates nothing. */
void vt_keymap_init(struct vt_keymap *map, unsigned key_words);

/* Reserves room for count entries in all (avoids growing while they are put). Returns 0 or
 * VTS_ERR_NOMEM (the map unchanged). */
int vt_keymap_reserve(struct vt_keymap *map, size_t count);

/* Looks key up: when it is there, sets *value to its value and returns false; else stores
 * key -> value (value < UINT64_MAX) and returns true. *rc: 0, or VTS_ERR_NOMEM (nothing stored,
 * returns false). */
bool vt_keymap_put_new(struct vt_keymap *map, const uint64_t *key, uint64_t *value, int *rc);

/* The value of key in *value and true, or false when it is not in the map. */
bool vt_keymap_get(const struct vt_keymap *map, const uint64_t *key, uint64_t *value);

/* Frees the table and empties the map (its key size kept). Accepts NULL. */
void vt_keymap_release(struct vt_keymap *map);

#endif
