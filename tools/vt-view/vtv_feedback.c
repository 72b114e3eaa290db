/* vt-view tile determination: feedback buffer -> sorted request list with ancestors. */
#include "vtv_feedback.h"

#include <stdlib.h>
#include <string.h>

static int cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

static int cmp_index(const void *a, const void *b)
{
    const struct vtv_request *x = a, *y = b;
    return x->index < y->index ? -1 : x->index > y->index;
}

static int cmp_priority(const void *a, const void *b)
{
    const struct vtv_request *x = a, *y = b;
    if (x->pixels != y->pixels)
        return x->pixels > y->pixels ? -1 : 1;
    if (x->level != y->level)
        return x->level > y->level ? -1 : 1;
    return x->index < y->index ? -1 : x->index > y->index;
}

static int reserve(struct vtv_feedback *f, size_t n)
{
    if (n <= f->capacity)
        return 0;
    size_t cap = f->capacity ? f->capacity : 256;
    while (cap < n)
        cap *= 2;
    struct vtv_request *p = realloc(f->items, cap * sizeof(*p));
    if (!p)
        return VTS_ERR_NOMEM;
    f->items = p;
    f->capacity = cap;
    return 0;
}

int vtv_feedback_reduce(struct vtv_feedback *f, const struct vtv_cache *c, const uint16_t *pixels,
                        size_t n)
{
    f->count = 0;
    f->direct = 0;
    if (n > f->keys_capacity) {
        uint64_t *k = realloc(f->keys, n * sizeof(*k));
        if (!k)
            return VTS_ERR_NOMEM;
        f->keys = k;
        f->keys_capacity = n;
    }
    size_t nk = 0;
    for (size_t i = 0; i < n; i++) {
        const uint16_t *p = pixels + i * 4;
        if (p[3] == 0 || p[2] >= c->level_count)
            continue;
        const struct vts_level *lv = &c->levels[p[2]];
        if (p[0] >= lv->tiles_x || p[1] >= lv->tiles_y)
            continue;
        f->keys[nk++] = vtv_cache_index(c, p[2], p[0], p[1]);
    }
    if (nk) /* keys is NULL until pixels ask for a tile */
        qsort(f->keys, nk, sizeof(*f->keys), cmp_u64);
    for (size_t i = 0; i < nk;) {
        size_t j = i;
        while (j < nk && f->keys[j] == f->keys[i])
            j++;
        if (reserve(f, f->count + c->level_count) != 0)
            return VTS_ERR_NOMEM;
        struct vtv_request r = {.index = f->keys[i], .pixels = j - i};
        vtv_cache_coords(c, r.index, &r.level, &r.x, &r.y);
        f->items[f->count++] = r;
        f->direct++;
        /* ancestors */
        for (uint32_t l = r.level + 1; l < c->level_count; l++) {
            struct vtv_request a = {.pixels = r.pixels,
                                    .level = l,
                                    .x = r.x >> (l - r.level),
                                    .y = r.y >> (l - r.level)};
            a.index = vtv_cache_index(c, a.level, a.x, a.y);
            f->items[f->count++] = a;
        }
        i = j;
    }
    if (f->count) /* items is NULL until pixels ask for a tile */
        qsort(f->items, f->count, sizeof(*f->items), cmp_index);
    size_t out = 0;
    for (size_t i = 0; i < f->count; i++) {
        if (out > 0 && f->items[out - 1].index == f->items[i].index)
            f->items[out - 1].pixels += f->items[i].pixels;
        else
            f->items[out++] = f->items[i];
    }
    f->count = out;
    if (f->count)
        qsort(f->items, f->count, sizeof(*f->items), cmp_priority);
    return 0;
}

void vtv_feedback_free(struct vtv_feedback *f)
{
    free(f->items);
    free(f->keys);
    memset(f, 0, sizeof(*f));
}
