#include "internal/vt_tile_cache.h"
#include "vt_error.h"

#include <pthread.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

struct entry {
    long long key; /* ty * tiles_x + tx, -1 when free */
    struct vt_image img;
    unsigned pins;
    bool ready; /* decoded; until then other readers of the key wait */
    unsigned long long last_use;
};

struct worker {
    struct vt_tile_cache *cache;
    unsigned index;
    struct vt_image spare; /* decode target when every slot is pinned */
};

struct vt_tile_cache {
    pthread_mutex_t lock;
    pthread_cond_t loaded;
    struct vt_source *const *sources;
    struct worker *workers;
    unsigned n;
    struct entry *entries;
    size_t capacity;
    uint32_t tw, th, tiles_x;
    unsigned long long clock, decoded, hits;
};

/* Returns a pinned entry holding tile (tx, ty), decoding it through the worker's own source when
 * absent, or NULL with *img set to the worker's spare buffer when no slot is free. */
static int get_tile(struct worker *w, uint32_t tx, uint32_t ty, struct entry **out,
                    struct vt_image **img, struct vts_error *err)
{
    struct vt_tile_cache *c = w->cache;
    const struct vt_source_info *in = &c->sources[w->index]->info;
    long long key = (long long)ty * c->tiles_x + tx;
    *out = NULL;
    pthread_mutex_lock(&c->lock);
    struct entry *victim;
lookup:
    victim = NULL;
    for (size_t i = 0; i < c->capacity; i++) {
        struct entry *e = &c->entries[i];
        if (e->key == key) {
            e->pins++;
            while (!e->ready && e->key == key)
                pthread_cond_wait(&c->loaded, &c->lock);
            if (e->key != key) { /* its decode failed: try again */
                e->pins--;
                goto lookup;
            }
            e->last_use = ++c->clock;
            c->hits++;
            pthread_mutex_unlock(&c->lock);
            *out = e;
            *img = &e->img;
            return 0;
        }
        /* blocks go down row by row: a tile in a higher row is less likely to be needed again */
        if (e->pins == 0 &&
            (!victim || e->key < 0 ||
             (victim->key >= 0 && (e->key / c->tiles_x < victim->key / c->tiles_x ||
                                   (e->key / c->tiles_x == victim->key / c->tiles_x &&
                                    e->last_use < victim->last_use)))))
            victim = e;
    }
    if (victim) { /* claim the slot now; other readers of the key wait until it is ready */
        victim->key = key;
        victim->pins = 1;
        victim->ready = false;
        victim->last_use = ++c->clock;
    }
    c->decoded++;
    pthread_mutex_unlock(&c->lock);
    struct vt_image *dst = victim ? &victim->img : &w->spare;
    uint32_t x = tx * c->tw, y = ty * c->th;
    struct vt_image v = *dst;
    v.width = in->width - x < c->tw ? in->width - x : c->tw;
    v.height = in->height - y < c->th ? in->height - y : c->th;
    int rc = vt_source_read(c->sources[w->index], x, y, &v, err);
    if (victim) {
        pthread_mutex_lock(&c->lock);
        if (rc) {
            victim->key = -1;
            victim->pins--;
        }
        victim->ready = rc == 0;
        pthread_cond_broadcast(&c->loaded);
        pthread_mutex_unlock(&c->lock);
        if (rc)
            return rc;
    }
    *out = victim;
    *img = dst;
    return rc;
}

static void unpin(struct vt_tile_cache *c, struct entry *e)
{
    if (!e)
        return;
    pthread_mutex_lock(&c->lock);
    e->pins--;
    pthread_mutex_unlock(&c->lock);
}

static int cached_read_region(void *ctx, uint32_t x, uint32_t y, struct vt_image *dst,
                              struct vts_error *err)
{
    struct worker *w = ctx;
    struct vt_tile_cache *c = w->cache;
    size_t tb = vt_image_texel_bytes(dst);
    for (uint32_t ty = y / c->th; ty * c->th < y + dst->height; ty++)
        for (uint32_t tx = x / c->tw; tx * c->tw < x + dst->width; tx++) {
            struct entry *e;
            struct vt_image *img;
            int rc = get_tile(w, tx, ty, &e, &img, err);
            if (rc)
                return rc;
            /* the part of this tile inside the region */
            uint32_t x0 = tx * c->tw > x ? tx * c->tw : x;
            uint32_t y0 = ty * c->th > y ? ty * c->th : y;
            uint32_t x1 = (tx + 1) * c->tw < x + dst->width ? (tx + 1) * c->tw : x + dst->width;
            uint32_t y1 = (ty + 1) * c->th < y + dst->height ? (ty + 1) * c->th : y + dst->height;
            for (uint32_t r = y0; r < y1; r++)
                memcpy(vt_image_at(dst, x0 - x, r - y),
                       vt_image_at(img, x0 - tx * c->tw, r - ty * c->th), (x1 - x0) * tb);
            unpin(c, e);
        }
    return 0;
}

static void cached_close(void *ctx)
{
    (void)ctx; /* workers belong to the cache */
}

static const struct vt_source_ops cached_ops = {cached_read_region, cached_close};

struct vt_tile_cache *vt_tile_cache_create(struct vt_source *const *sources, unsigned n,
                                           size_t budget_bytes, struct vt_source *out,
                                           struct vts_error *err)
{
    const struct vt_source_info *in = &sources[0]->info;
    struct vt_tile_cache *c = calloc(1, sizeof *c);
    if (!c) {
        vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
        return NULL;
    }
    pthread_mutex_init(&c->lock, NULL);
    pthread_cond_init(&c->loaded, NULL);
    c->sources = sources;
    c->n = n;
    c->tw = in->tile_w;
    c->th = in->tile_h;
    c->tiles_x = (in->width + c->tw - 1) / c->tw;
    size_t tile_bytes = (size_t)c->tw * c->th * in->channels * vts_sample_bytes(in->sample);
    c->capacity = budget_bytes / (tile_bytes ? tile_bytes : 1);
    if (c->capacity < 4 * (size_t)n)
        c->capacity = 4 * (size_t)n;
    c->entries = calloc(c->capacity, sizeof *c->entries);
    c->workers = calloc(n, sizeof *c->workers);
    bool ok = c->entries && c->workers;
    for (size_t i = 0; ok && i < c->capacity; i++) {
        c->entries[i].key = -1;
        ok = vt_image_alloc(&c->entries[i].img, c->tw, c->th, in->channels, in->sample, err) == 0;
    }
    for (unsigned i = 0; ok && i < n; i++) {
        c->workers[i] = (struct worker){c, i, {0}};
        ok = vt_image_alloc(&c->workers[i].spare, c->tw, c->th, in->channels, in->sample, err) == 0;
        out[i] = *sources[i];
        out[i].ops = &cached_ops;
        out[i].ctx = &c->workers[i];
    }
    if (!ok) {
        vt_error_set(err, VTS_ERR_NOMEM, "out of memory for the input tile cache");
        vt_tile_cache_destroy(c);
        return NULL;
    }
    return c;
}

void vt_tile_cache_counts(struct vt_tile_cache *c, unsigned long long *decoded,
                          unsigned long long *hits)
{
    pthread_mutex_lock(&c->lock);
    *decoded = c->decoded;
    *hits = c->hits;
    pthread_mutex_unlock(&c->lock);
}

void vt_tile_cache_destroy(struct vt_tile_cache *c)
{
    if (!c)
        return;
    for (size_t i = 0; c->entries && i < c->capacity; i++)
        vt_image_release(&c->entries[i].img);
    for (unsigned i = 0; c->workers && i < c->n; i++)
        vt_image_release(&c->workers[i].spare);
    free(c->entries);
    free(c->workers);
    pthread_cond_destroy(&c->loaded);
    pthread_mutex_destroy(&c->lock);
    free(c);
}
