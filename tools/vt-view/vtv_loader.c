/* vt-view tile loader: read + decode + convert to RGBA8 (16-bit and float layers: their own
 * format, vtv_wide.h), synchronously or on threads. */
#include "vtv_loader.h"

#include <assert.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vt_codec.h"
#include "vt_error.h"
#include "vt_image.h"
#include "vtv_wide.h"

#define VTV_QUEUE_MAX 1024u
#define VTV_POOL_MAX  256u

/* Per-thread buffers, reused for every tile: allocating them per tile in a thread's malloc arena
 * made glibc trim and fault the pages back in each time (5x slower streaming). */
struct scratch {
    void *payload;
    size_t capacity;
    struct vt_image img[VTV_LOADER_MAX_LAYERS];
};

/* One layer the loader reads. */
struct loader_layer {
    uint32_t index;
    const struct vt_codec *codec;
    struct vts_layer info;
    size_t bc_bytes;             /* > 0: hand over BC blocks of this size instead of decoding */
    struct vtv_texel_format fmt; /* what a tile holds for it (RGBA8 unless 16-bit or float) */
};

struct vtv_loader {
    const struct vts_store *store;
    struct loader_layer layers[VTV_LOADER_MAX_LAYERS];
    uint32_t layer_count;
    uint32_t payload_px;
    uint32_t max_payload;
    size_t stride; /* bytes of one layer in a result: payload_px^2 * the widest texel (>= 4) */
    /* threads */
    pthread_t *threads;
    uint32_t thread_count;
    pthread_mutex_t mu;
    pthread_cond_t wake, idle;
    bool stop;
    uint64_t queue[VTV_QUEUE_MAX];
    uint32_t queue_lxy[VTV_QUEUE_MAX * 3];
    uint32_t queue_head, queue_len, busy;
    struct vtv_load *done_head, *done_tail;
    struct vtv_load *pool; /* released results with their rgba buffers */
    uint32_t pool_count;
    struct scratch sync_scratch;
};

static void to_rgba8(const struct vt_image *img, uint8_t *dst)
{
    if (img->sample == VTS_SAMPLE_U8 && (img->channels == 3 || img->channels == 4)) {
        for (uint32_t y = 0; y < img->height; y++) {
            const uint8_t *s = (const uint8_t *)img->pixels + (size_t)y * img->stride;
            uint8_t *d = dst + (size_t)y * img->width * 4;
            if (img->channels == 4) {
                memcpy(d, s, (size_t)img->width * 4);
                continue;
            }
            for (uint32_t x = 0; x < img->width; x++, s += 3, d += 4) {
                d[0] = s[0];
                d[1] = s[1];
                d[2] = s[2];
                d[3] = 255;
            }
        }
        return;
    }
    for (uint32_t y = 0; y < img->height; y++) {
        for (uint32_t x = 0; x < img->width; x++) {
            uint8_t v[4] = {0, 0, 0, 255};
            const uint8_t *p8 = vt_image_at(img, x, y);
            for (uint32_t ch = 0; ch < img->channels; ch++) {
                if (img->sample == VTS_SAMPLE_U16) {
                    uint16_t s;
                    memcpy(&s, p8 + ch * 2, 2);
                    v[ch] = (uint8_t)((s + 128u) / 257u);
                } else {
                    v[ch] = p8[ch];
                }
            }
            if (img->channels == 1 || img->channels == 2) {
                v[3] = img->channels == 2 ? v[1] : 255;
                v[1] = v[2] = v[0];
            }
            memcpy(dst + ((size_t)y * img->width + x) * 4, v, 4);
        }
    }
}

static struct vtv_load *new_result(struct vtv_loader *l)
{
    pthread_mutex_lock(&l->mu);
    struct vtv_load *r = l->pool;
    if (r) {
        l->pool = r->next;
        l->pool_count--;
    }
    pthread_mutex_unlock(&l->mu);
    uint8_t *rgba = r ? r->rgba : NULL;
    if (!r && !(r = calloc(1, sizeof(*r))))
        return NULL;
    memset(r, 0, sizeof(*r));
    r->rgba = rgba ? rgba : malloc(l->stride * l->layer_count);
    if (!r->rgba) {
        free(r);
        return NULL;
    }
    return r;
}

/* Reads and decodes layer k of tile (level, x, y) into dst (one layer's slice of a result);
 * *empty when it is stored empty. Returns 0 or a status with the message in err. */
static int load_layer(struct vtv_loader *l, struct scratch *sc, uint32_t k, uint32_t level,
                      uint32_t x, uint32_t y, uint8_t *dst, bool *empty, size_t *read,
                      struct vts_error *err)
{
    const struct loader_layer *ly = &l->layers[k];
    size_t len = 0;
    int st = 0;
    if (!sc->img[k].pixels)
        st = vt_image_alloc(&sc->img[k], l->payload_px, l->payload_px, ly->info.channels,
                            ly->info.sample, err);
    if (st == 0)
        st = vts_store_read(l->store, ly->index, level, x, y, sc->payload, sc->capacity, &len, 0,
                            err);
    *empty = st == 0 && len == 0;
    *read += len;
    if (st != 0 || len == 0)
        return st;
    if (ly->bc_bytes) {
        if (len != ly->bc_bytes)
            return vt_error_set(
                err, VTS_ERR_BAD_INPUT,
                "'%s': tile %u,%u of level %u: %zu bytes of BC blocks, expected %zu",
                vts_store_name(l->store), x, y, level, len, ly->bc_bytes);
        memcpy(dst, sc->payload, len);
        return 0;
    }
    struct vts_error e = {0};
    st = ly->codec->decode(sc->payload, len, &sc->img[k], &e);
    if (st != 0) /* the codec's message does not say which tile */
        return vt_error_set(err, st, "'%s': tile %u,%u of level %u: %s", vts_store_name(l->store),
                            x, y, level, e.message);
    if (ly->fmt.sample == VTS_SAMPLE_U8)
        to_rgba8(&sc->img[k], dst);
    else
        vtv_wide_convert(&sc->img[k], &ly->info, dst);
    return 0;
}

/* What a layer stored empty shows when other layers of the tile are not: a flat normal, else
 * transparent black (BC blocks of zeros). A bc5 normal layer's flat normal: blocks of x = y = 128
 * (two BC4 blocks of endpoints 128, indices 0; the shader rebuilds z). */
static void fill_empty(const struct vtv_loader *l, uint32_t k, uint8_t *dst)
{
    memset(dst, 0, l->stride);
    if (l->layers[k].info.colour != VTS_COLOUR_NORMAL || l->layers[k].fmt.sample != VTS_SAMPLE_U8)
        return;
    if (l->layers[k].bc_bytes) {
        for (size_t i = 0; l->layers[k].info.codec == VTS_CODEC_BC5 && i < l->layers[k].bc_bytes;
             i += 8)
            dst[i] = dst[i + 1] = 128;
        return;
    }
    for (size_t i = 0; i < l->stride; i += 4) {
        dst[i] = dst[i + 1] = 128;
        dst[i + 2] = dst[i + 3] = 255;
    }
}

static struct vtv_load *load(struct vtv_loader *l, struct scratch *sc, uint64_t index,
                             uint32_t level, uint32_t x, uint32_t y)
{
    struct vtv_load *r = new_result(l);
    if (!r)
        return NULL;
    r->index = index;
    r->level = level;
    r->x = x;
    r->y = y;
    struct vts_error err = {0};
    size_t need = l->max_payload ? l->max_payload : 1;
    int st = 0;
    if (sc->capacity < need) {
        free(sc->payload);
        sc->capacity = 0;
        if (!(sc->payload = malloc(need)))
            st = vt_error_set(&err, VTS_ERR_NOMEM, "out of memory reading a tile");
        else
            sc->capacity = need;
    }
    bool empty[VTV_LOADER_MAX_LAYERS] = {false}, all_empty = true;
    for (uint32_t k = 0; k < l->layer_count && st == 0; k++) {
        st = load_layer(l, sc, k, level, x, y, r->rgba + k * l->stride, &empty[k], &r->bytes_read,
                        &err);
        all_empty &= empty[k];
    }
    r->empty = st == 0 && all_empty;
    for (uint32_t k = 0; k < l->layer_count && st == 0 && !r->empty; k++)
        if (empty[k])
            fill_empty(l, k, r->rgba + k * l->stride);
    r->bytes = l->stride * l->layer_count;
    r->status = st;
    if (st != 0)
        snprintf(r->error, sizeof(r->error), "%s", err.message);
    if (st != 0 || r->empty) {
        free(r->rgba);
        r->rgba = NULL;
    }
    return r;
}

static void scratch_free(struct scratch *sc)
{
    free(sc->payload);
    for (uint32_t k = 0; k < VTV_LOADER_MAX_LAYERS; k++)
        vt_image_release(&sc->img[k]);
    memset(sc, 0, sizeof(*sc));
}

struct vtv_load *vtv_loader_load_now(struct vtv_loader *l, uint64_t index, uint32_t level,
                                     uint32_t x, uint32_t y)
{
    return load(l, &l->sync_scratch, index, level, x, y);
}

void vtv_loader_release(struct vtv_loader *l, struct vtv_load *list)
{
    while (list) {
        struct vtv_load *n = list->next;
        pthread_mutex_lock(&l->mu);
        bool keep = list->rgba && l->pool_count < VTV_POOL_MAX;
        if (keep) {
            list->next = l->pool;
            l->pool = list;
            l->pool_count++;
        }
        pthread_mutex_unlock(&l->mu);
        if (!keep) {
            list->next = NULL;
            vtv_load_free(list);
        }
        list = n;
    }
}

void vtv_load_free(struct vtv_load *r)
{
    while (r) {
        struct vtv_load *n = r->next;
        free(r->rgba);
        free(r);
        r = n;
    }
}

static void *worker(void *arg)
{
    struct vtv_loader *l = arg;
    struct scratch sc = {0};
    pthread_mutex_lock(&l->mu);
    for (;;) {
        while (!l->stop && l->queue_len == 0)
            pthread_cond_wait(&l->wake, &l->mu);
        if (l->stop)
            break;
        uint32_t q = l->queue_head;
        uint64_t index = l->queue[q];
        uint32_t lv = l->queue_lxy[q * 3], x = l->queue_lxy[q * 3 + 1], y = l->queue_lxy[q * 3 + 2];
        l->queue_head = (q + 1) % VTV_QUEUE_MAX;
        l->queue_len--;
        l->busy++;
        pthread_mutex_unlock(&l->mu);
        struct vtv_load *r = load(l, &sc, index, lv, x, y);
        pthread_mutex_lock(&l->mu);
        l->busy--;
        if (r) {
            if (l->done_tail)
                l->done_tail->next = r;
            else
                l->done_head = r;
            l->done_tail = r;
        }
        if (l->busy == 0 && l->queue_len == 0)
            pthread_cond_broadcast(&l->idle);
    }
    pthread_mutex_unlock(&l->mu);
    scratch_free(&sc);
    return NULL;
}

/* Checks layer index of store and fills ly; NULL error otherwise. */
static int setup_layer(const struct vts_store *store, uint32_t index, bool compressed,
                       uint32_t payload_px, struct loader_layer *ly, struct vts_error *err)
{
    const struct vts_geometry *g = vts_store_geometry(store);
    if (index >= g->layer_count)
        return vt_error_set(err, VTS_ERR_ARG, "%s: no layer %u (the store has %u)",
                            vts_store_name(store), index, g->layer_count);
    const struct vts_layer *info = vts_store_layer(store, index);
    const struct vt_codec *codec = vt_codec_by_fourcc(info->codec);
    if (!codec) {
        char name[5];
        vts_codec_name(info->codec, name);
        return vt_error_set(err, VTS_ERR_UNSUPPORTED, "%s: codec '%s' is not built into vt-view",
                            vts_store_name(store), name);
    }
    ly->index = index;
    vtv_wide_format(info, &ly->fmt);
    ly->codec = codec;
    ly->info = *info;
    ly->bc_bytes = 0;
    bool eight = info->codec == VTS_CODEC_BC1 || info->codec == VTS_CODEC_BC4;
    if (compressed && (eight || info->codec == VTS_CODEC_BC3 || info->codec == VTS_CODEC_BC5))
        ly->bc_bytes = (size_t)(payload_px / 4) * (payload_px / 4) * (eight ? 8u : 16u);
    return 0;
}

struct vtv_loader *vtv_loader_create(const struct vts_store *store, uint32_t layer,
                                     uint32_t threads, unsigned flags, struct vts_error *err)
{
    return vtv_loader_create_layers(store, &layer, 1, threads,
                                    (flags & VTV_LOADER_COMPRESSED) ? 1u : 0u, err);
}

struct vtv_loader *vtv_loader_create_layers(const struct vts_store *store, const uint32_t *layers,
                                            uint32_t layer_count, uint32_t threads,
                                            unsigned compressed_mask, struct vts_error *err)
{
    const struct vts_geometry *g = vts_store_geometry(store);
    struct vtv_loader *l = calloc(1, sizeof(*l));
    if (!l) {
        vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
        return NULL;
    }
    assert(layer_count >= 1 && layer_count <= VTV_LOADER_MAX_LAYERS);
    l->store = store;
    l->payload_px = g->tile_payload_px;
    l->stride = (size_t)l->payload_px * l->payload_px * 4;
    l->max_payload = vts_store_max_payload(store);
    for (uint32_t k = 0; k < layer_count; k++) {
        if (setup_layer(store, layers[k], (compressed_mask >> k) & 1u, l->payload_px, &l->layers[k],
                        err) != 0) {
            free(l);
            return NULL;
        }
        size_t tb = vtv_wide_texel_bytes(&l->layers[k].fmt);
        size_t slice = (size_t)l->payload_px * l->payload_px * tb;
        l->stride = slice > l->stride ? slice : l->stride;
    }
    l->layer_count = layer_count;
    pthread_mutex_init(&l->mu, NULL);
    pthread_cond_init(&l->wake, NULL);
    pthread_cond_init(&l->idle, NULL);
    if (threads > 0) {
        l->threads = calloc(threads, sizeof(*l->threads));
        if (!l->threads) {
            vtv_loader_destroy(l);
            vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
            return NULL;
        }
        for (uint32_t i = 0; i < threads; i++) {
            if (pthread_create(&l->threads[i], NULL, worker, l) != 0) {
                vtv_loader_destroy(l);
                vt_error_set(err, VTS_ERR_NOMEM, "cannot start a loader thread");
                return NULL;
            }
            l->thread_count++;
        }
    }
    return l;
}

void vtv_loader_destroy(struct vtv_loader *l)
{
    if (!l)
        return;
    pthread_mutex_lock(&l->mu);
    l->stop = true;
    pthread_cond_broadcast(&l->wake);
    pthread_mutex_unlock(&l->mu);
    for (uint32_t i = 0; i < l->thread_count; i++)
        pthread_join(l->threads[i], NULL);
    free(l->threads);
    vtv_load_free(l->done_head);
    vtv_load_free(l->pool);
    scratch_free(&l->sync_scratch);
    pthread_mutex_destroy(&l->mu);
    pthread_cond_destroy(&l->wake);
    pthread_cond_destroy(&l->idle);
    free(l);
}

uint32_t vtv_loader_queue_capacity(const struct vtv_loader *l)
{
    (void)l;
    return VTV_QUEUE_MAX;
}

uint32_t vtv_loader_submit(struct vtv_loader *l, const uint64_t *index, const uint32_t *lxy,
                           uint32_t n, uint64_t *dropped)
{
    pthread_mutex_lock(&l->mu);
    uint32_t nd = 0;
    for (uint32_t i = 0; i < l->queue_len; i++)
        dropped[nd++] = l->queue[(l->queue_head + i) % VTV_QUEUE_MAX];
    l->queue_head = 0;
    l->queue_len = n < VTV_QUEUE_MAX ? n : VTV_QUEUE_MAX;
    if (l->queue_len) {
        memcpy(l->queue, index, l->queue_len * sizeof(*index));
        memcpy(l->queue_lxy, lxy, l->queue_len * 3 * sizeof(*lxy));
        pthread_cond_broadcast(&l->wake);
    }
    pthread_mutex_unlock(&l->mu);
    return nd;
}

struct vtv_load *vtv_loader_take(struct vtv_loader *l, uint32_t max)
{
    pthread_mutex_lock(&l->mu);
    struct vtv_load *head = l->done_head, *tail = NULL, *r = head;
    uint32_t n = 0;
    while (r && n < max) {
        tail = r;
        r = r->next;
        n++;
    }
    if (!tail) {
        pthread_mutex_unlock(&l->mu);
        return NULL;
    }
    l->done_head = r;
    if (!r)
        l->done_tail = NULL;
    tail->next = NULL;
    pthread_mutex_unlock(&l->mu);
    return head;
}

void vtv_loader_wait_idle(struct vtv_loader *l)
{
    pthread_mutex_lock(&l->mu);
    while (l->thread_count > 0 && (l->busy > 0 || l->queue_len > 0))
        pthread_cond_wait(&l->idle, &l->mu);
    pthread_mutex_unlock(&l->mu);
}

size_t vtv_loader_slice_bytes(const struct vtv_loader *l)
{
    return l->stride;
}
