/* vt-view tile streaming: loads -> uploads -> page table; feedback -> loader queue. */
#include "vtv_stream.h"

#include <stdlib.h>
#include <string.h>

#include "tool_common.h"
#include "vt_codec.h"
#include "vt_error.h"
#include "vtv_wide.h"

/* Uploads a decoded payload of tile index into a slot. Returns false when no slot could be
 * freed (the tile stays absent). */
static bool upload(struct vtv_stream *s, uint64_t index, const uint8_t *data, size_t bytes,
                   struct vtv_frame_stats *st)
{
    struct vtv_cache *c = &s->cache;
    uint32_t slot = vtv_cache_alloc(c, s->stamp);
    if (slot == VTV_NO_SLOT) {
        vtv_cache_set_state(c, index, VTV_TILE_ABSENT);
        return false;
    }
    vtv_render_upload_tile(s->render, c, slot, data, bytes);
    vtv_cache_assign(c, slot, index, s->stamp);
    st->uploads++;
    return true;
}

/* Puts one finished load into the cache (a decoded payload also into the RAM cache). A tile that
 * is no longer wanted (a prefetch, or a request the camera left) goes to the RAM cache only.
 * Returns false when no slot could be freed. */
static bool apply(struct vtv_stream *s, struct vtv_load *r, struct vtv_frame_stats *st)
{
    struct vtv_cache *c = &s->cache;
    if (r->status != 0) {
        vt_log(VT_LOG_WARN, "%s (its ancestor is shown)", r->error);
        vtv_cache_set_state(c, r->index, VTV_TILE_FAILED);
        s->failed++;
        st->loaded++;
        return true;
    }
    if (r->empty) {
        vtv_cache_set_state(c, r->index, VTV_TILE_EMPTY);
        s->empty++;
        st->loaded++;
        return true;
    }
    if (s->ram)
        vtv_ramcache_put(s->ram, r->index, r->rgba, r->bytes);
    if (s->wanted && !s->wanted[r->index]) {
        vtv_cache_set_state(c, r->index, VTV_TILE_ABSENT);
        return true;
    }
    if (!upload(s, r->index, r->rgba, r->bytes, st))
        return false;
    st->loaded++;
    return true;
}

/* Uploads tile index from the RAM cache when it is there; false when it is not, or no slot. */
static bool upload_from_ram(struct vtv_stream *s, uint64_t index, struct vtv_frame_stats *st)
{
    size_t bytes = 0;
    const uint8_t *p = s->ram ? vtv_ramcache_get(s->ram, index, &bytes) : NULL;
    if (!p || !upload(s, index, p, bytes, st))
        return false;
    st->ram_hits++;
    return true;
}

/* Adds tile (l, x, y) to the prefetch candidates unless it is outside the level, in the cache,
 * wanted, in the RAM cache or already a candidate. */
static void add_ahead(struct vtv_stream *s, int64_t l, int64_t x, int64_t y)
{
    struct vtv_cache *c = &s->cache;
    if (s->ahead_count >= s->ahead_cap || l < 0 || x < 0 || y < 0 || x >= c->levels[l].tiles_x ||
        y >= c->levels[l].tiles_y)
        return;
    uint64_t idx = vtv_cache_index(c, (uint32_t)l, (uint32_t)x, (uint32_t)y);
    if (c->state[idx] != VTV_TILE_ABSENT || s->wanted[idx] || vtv_ramcache_has(s->ram, idx))
        return;
    for (uint32_t j = 0; j < s->ahead_count; j++)
        if (s->ahead[j] == idx)
            return;
    s->ahead[s->ahead_count] = idx;
    s->ahead_lxy[s->ahead_count * 3] = (uint32_t)l;
    s->ahead_lxy[s->ahead_count * 3 + 1] = (uint32_t)x;
    s->ahead_lxy[s->ahead_count * 3 + 2] = (uint32_t)y;
    s->ahead_count++;
}

/* Prefetch candidates of the latest request, at most ahead_cap, in this order: the four
 * neighbours of the wanted tiles of the finest level asked for (where a moving camera goes
 * next), then the four children of those tiles (where a zoom goes next), each in the request's
 * order (most pixels first). Coarser wanted tiles are ancestors or far away: not read ahead. */
static void collect_ahead(struct vtv_stream *s)
{
    s->ahead_count = 0;
    if (!s->opt.prefetch || !s->ram || s->feedback.count == 0)
        return;
    uint32_t finest = UINT32_MAX;
    for (size_t i = 0; i < s->feedback.count; i++)
        finest = s->feedback.items[i].level < finest ? s->feedback.items[i].level : finest;
    for (int pass = 0; pass < 2; pass++)
        for (size_t i = 0; i < s->feedback.count && s->ahead_count < s->ahead_cap; i++) {
            const struct vtv_request *q = &s->feedback.items[i];
            int64_t l = q->level, x = q->x, y = q->y;
            if (q->level != finest)
                continue;
            if (pass == 0) {
                add_ahead(s, l, x - 1, y);
                add_ahead(s, l, x + 1, y);
                add_ahead(s, l, x, y - 1);
                add_ahead(s, l, x, y + 1);
            } else {
                for (int k = 0; k < 4; k++)
                    add_ahead(s, l - 1, 2 * x + (k & 1), 2 * y + (k >> 1));
            }
        }
}

int vtv_stream_init(struct vtv_stream *s, const struct vts_store *store, const uint32_t *layers,
                    uint32_t slots, uint32_t threads, bool sync, uint32_t budget, bool bc_upload,
                    const struct vtv_stream_options *opt, struct vtv_render *render,
                    struct vts_error *err)
{
    memset(s, 0, sizeof(*s));
    s->opt = *opt;
    s->render = render;
    render->lod_bias = opt->auto_lod ? 0.0f : opt->lod_bias;
    s->sync = sync;
    s->budget = budget;
    s->stamp = 1;
    int st = vtv_cache_init(&s->cache, store, slots, err);
    if (st != 0)
        return st;
    const struct vts_level *top = &s->cache.levels[s->cache.level_count - 1];
    if ((uint64_t)top->tiles_x * top->tiles_y > slots / 2)
        return vt_error_set(err, VTS_ERR_ARG,
                            "--cache %u is too small: the coarsest level alone has %u tiles", slots,
                            top->tiles_x * top->tiles_y);
    /* one physical texture per map kind in use, one loader reading all of them per tile */
    struct vtv_phys_layer phys[VTV_MAP_COUNT];
    uint32_t order[VTV_LOADER_MAX_LAYERS], n = 0;
    unsigned compressed = 0;
    uint32_t pp = vts_store_geometry(store)->tile_payload_px;
    memset(phys, 0, sizeof(phys));
    for (int k = 0; k < VTV_MAP_COUNT; k++) {
        if (layers[k] == UINT32_MAX)
            continue;
        if (layers[k] >= vts_store_geometry(store)->layer_count)
            return vt_error_set(err, VTS_ERR_ARG, "%s: no layer %u", vts_store_name(store),
                                layers[k]);
        const struct vts_layer *info = vts_store_layer(store, layers[k]);
        phys[k].used = true;
        phys[k].srgb = info->colour == VTS_COLOUR_SRGB;
        vtv_wide_format(info, &phys[k].texels);
        if (bc_upload && vtv_render_bc_format(render, info->codec, phys[k].srgb, pp)) {
            phys[k].bc_codec = info->codec;
            phys[k].rebuild_z = info->codec == VTS_CODEC_BC5 && info->channels == 3;
            vt_log(VT_LOG_INFO, "layer '%s': %s blocks uploaded compressed%s", info->name,
                   vt_codec_by_fourcc(info->codec)->name,
                   phys[k].rebuild_z ? " (normal xy, z rebuilt in the shader)" : "");
            compressed |= 1u << n;
        }
        order[n++] = layers[k];
    }
    if (n == 0)
        return vt_error_set(err, VTS_ERR_ARG, "no layer to show");
    st = vtv_render_set_cache(render, &s->cache, vts_store_geometry(store), phys, err);
    if (st != 0)
        return st;
    s->loader = vtv_loader_create_layers(store, order, n, sync ? 0 : threads, compressed, err);
    if (!s->loader)
        return err->status;
    render->slice_bytes = vtv_loader_slice_bytes(s->loader);
    uint32_t cap = vtv_loader_queue_capacity(s->loader);
    s->pending = malloc(cap * sizeof(*s->pending));
    s->pending_lxy = malloc(cap * 3 * sizeof(*s->pending_lxy));
    s->dropped = malloc(cap * sizeof(*s->dropped));
    s->ahead_cap = budget < cap / 2 ? budget : cap / 2;
    s->ahead = malloc((s->ahead_cap + 1) * sizeof(*s->ahead));
    s->ahead_lxy = malloc((s->ahead_cap + 1) * 3 * sizeof(*s->ahead_lxy));
    s->ready = malloc(cap * sizeof(*s->ready));
    s->wanted = calloc(s->cache.tile_count, 1);
    s->ram = opt->ram_tiles ? vtv_ramcache_create(opt->ram_tiles) : NULL;
    if (!s->pending || !s->pending_lxy || !s->dropped || !s->ahead || !s->ahead_lxy || !s->ready ||
        !s->wanted || (opt->ram_tiles && !s->ram))
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    struct vtv_frame_stats dummy = {0};
    uint32_t top_level = s->cache.level_count - 1;
    for (uint32_t y = 0; y < top->tiles_y; y++) {
        for (uint32_t x = 0; x < top->tiles_x; x++) {
            uint64_t idx = vtv_cache_index(&s->cache, top_level, x, y);
            s->wanted[idx] = 1; /* pinned: always shown */
            struct vtv_load *r = vtv_loader_load_now(s->loader, idx, top_level, x, y);
            if (!r)
                return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
            if (r->status != 0) {
                st = vt_error_set(err, r->status, "%s", r->error);
                vtv_load_free(r);
                return st;
            }
            apply(s, r, &dummy);
            vtv_load_free(r);
        }
    }
    if (vtv_cache_update_page_table(&s->cache))
        vtv_render_upload_page_table(render, &s->cache);
    vtv_cache_page_table_clean(&s->cache);
    return 0;
}

void vtv_stream_free(struct vtv_stream *s)
{
    vtv_loader_destroy(s->loader);
    vtv_cache_free(&s->cache);
    vtv_feedback_free(&s->feedback);
    free(s->pending);
    free(s->pending_lxy);
    free(s->dropped);
    free(s->ahead);
    free(s->ahead_lxy);
    free(s->ready);
    free(s->wanted);
    vtv_ramcache_destroy(s->ram);
    memset(s, 0, sizeof(*s));
}

/* --sync: the pending tiles in request order (from the RAM cache, else read while the read
 * budget lasts), up to the upload budget; then, with reads to spare, the prefetch candidates
 * into the RAM cache. */
static void update_sync(struct vtv_stream *s, struct vtv_frame_stats *st)
{
    struct vtv_cache *c = &s->cache;
    uint32_t reads = 0, max_reads = s->opt.reads ? s->opt.reads : UINT32_MAX;
    for (uint32_t i = 0; i < s->pending_count && st->uploads < s->budget; i++) {
        uint64_t idx = s->pending[i];
        if (c->state[idx] != VTV_TILE_ABSENT)
            continue;
        if (vtv_ramcache_has(s->ram, idx)) {
            if (!upload_from_ram(s, idx, st))
                break;
            continue;
        }
        if (reads >= max_reads)
            continue;
        struct vtv_load *r =
            vtv_loader_load_now(s->loader, idx, s->pending_lxy[i * 3], s->pending_lxy[i * 3 + 1],
                                s->pending_lxy[i * 3 + 2]);
        if (!r)
            break;
        reads++;
        bool ok = apply(s, r, st);
        vtv_loader_release(s->loader, r);
        if (!ok)
            break;
    }
    s->pending_count = 0;
    /* read ahead with the reads left (at most the upload budget's worth a frame) */
    for (uint32_t i = 0; i < s->ahead_count && reads < max_reads && st->prefetched < s->budget;
         i++) {
        uint64_t idx = s->ahead[i];
        if (c->state[idx] != VTV_TILE_ABSENT || vtv_ramcache_has(s->ram, idx))
            continue;
        struct vtv_load *r = vtv_loader_load_now(s->loader, idx, s->ahead_lxy[i * 3],
                                                 s->ahead_lxy[i * 3 + 1], s->ahead_lxy[i * 3 + 2]);
        if (!r)
            break;
        reads++;
        st->prefetched += r->status == 0 && !r->empty;
        apply(s, r, st); /* not wanted: into the RAM cache (or marked empty or failed) */
        vtv_loader_release(s->loader, r);
    }
    s->ahead_count = 0;
    st->reads = reads;
}

/* Loader threads: the wanted tiles the RAM cache holds first, then the finished loads. */
static void update_async(struct vtv_stream *s, struct vtv_frame_stats *st)
{
    struct vtv_cache *c = &s->cache;
    uint32_t i = 0;
    for (; i < s->ready_count && st->uploads < s->budget; i++) {
        uint64_t idx = s->ready[i];
        if (c->state[idx] == VTV_TILE_QUEUED) /* queued for the RAM cache: not the loader */
            c->state[idx] = VTV_TILE_ABSENT;
        if (c->state[idx] == VTV_TILE_ABSENT && s->wanted[idx] && !upload_from_ram(s, idx, st))
            break;
    }
    for (; i < s->ready_count; i++) /* no budget left: asked for again next frame */
        if (c->state[s->ready[i]] == VTV_TILE_QUEUED)
            c->state[s->ready[i]] = VTV_TILE_ABSENT;
    s->ready_count = 0;
    uint32_t left = s->budget > st->uploads ? s->budget - (uint32_t)st->uploads : 0;
    struct vtv_load *list = left ? vtv_loader_take(s->loader, left) : NULL;
    for (struct vtv_load *r = list; r; r = r->next) {
        bool was_wanted = s->wanted[r->index];
        apply(s, r, st);
        st->prefetched += !was_wanted && r->status == 0 && !r->empty;
    }
    vtv_loader_release(s->loader, list);
}

void vtv_stream_update(struct vtv_stream *s, struct vtv_frame_stats *st)
{
    struct vtv_cache *c = &s->cache;
    if (s->sync)
        update_sync(s, st);
    else
        update_async(s, st);
    if (vtv_cache_update_page_table(c))
        vtv_render_upload_page_table(s->render, c);
    vtv_cache_page_table_clean(c);
    st->resident = c->resident;
    st->lod_bias = s->render->lod_bias;
    st->empty = s->empty;
    st->failed = s->failed;
    /* the quality of this frame: wanted tiles (of the latest determination) still missing */
    st->levels = c->level_count;
    for (size_t i = 0; i < s->feedback.count; i++) {
        const struct vtv_request *q = &s->feedback.items[i];
        uint8_t state = c->state[q->index];
        st->missed[q->level] += state != VTV_TILE_RESIDENT && state != VTV_TILE_EMPTY;
    }
}

/* The automatic level-of-detail bias (docs/viewer.md, "Over-committed cache"): when the tiles the
 * latest determination wants (the pinned coarsest level aside) are more than the slots that can
 * hold them, the next frames want one level coarser; when one level finer would still fit (it
 * wants at most 4 times the tiles of the finest level asked for, plus these tiles as ancestors),
 * one level finer again. So a view that needs more tiles than the cache holds degrades in
 * resolution instead of evicting what it shows. */
static void adjust_bias(struct vtv_stream *s)
{
    const struct vtv_cache *c = &s->cache;
    if (!s->opt.auto_lod)
        return;
    uint32_t top = c->level_count - 1, pinned = c->levels[top].tiles_x * c->levels[top].tiles_y;
    uint64_t need = 0, finest_count = 0;
    uint32_t finest = top;
    for (size_t i = 0; i < s->feedback.count; i++) {
        const struct vtv_request *q = &s->feedback.items[i];
        need += q->level != top;
        finest = q->level < finest ? q->level : finest;
    }
    for (size_t i = 0; i < s->feedback.count; i++)
        finest_count += s->feedback.items[i].level == finest && finest != top;
    uint64_t room = c->slots - pinned;
    float bias = s->render->lod_bias;
    if (need > room && bias < (float)top)
        bias += 1.0f;
    else if (bias >= 1.0f && finest > 0 && 4 * finest_count + need <= room)
        bias -= 1.0f;
    s->render->lod_bias = bias;
}

int vtv_stream_request(struct vtv_stream *s, const uint16_t *pixels, size_t n,
                       struct vtv_frame_stats *st)
{
    struct vtv_cache *c = &s->cache;
    s->stamp++;
    for (size_t i = 0; i < s->feedback.count; i++) /* forget the previous determination */
        s->wanted[s->feedback.items[i].index] = 0;
    if (vtv_feedback_reduce(&s->feedback, c, pixels, n) != 0)
        return VTS_ERR_NOMEM;
    st->requested = s->feedback.count;
    adjust_bias(s);
    for (size_t i = 0; i < s->feedback.count; i++)
        s->wanted[s->feedback.items[i].index] = 1;
    for (uint32_t y = 0, top = c->level_count - 1; y < c->levels[top].tiles_y; y++)
        for (uint32_t x = 0; x < c->levels[top].tiles_x; x++) /* pinned tiles stay wanted */
            s->wanted[vtv_cache_index(c, top, x, y)] = 1;
    if (!s->sync) { /* take back what no thread started on */
        uint32_t nd = vtv_loader_submit(s->loader, NULL, NULL, 0, s->dropped);
        for (uint32_t i = 0; i < nd; i++)
            if (c->state[s->dropped[i]] == VTV_TILE_QUEUED)
                c->state[s->dropped[i]] = VTV_TILE_ABSENT;
    }
    uint32_t cap = vtv_loader_queue_capacity(s->loader);
    s->pending_count = 0;
    for (size_t i = 0; i < s->feedback.count; i++) {
        const struct vtv_request *r = &s->feedback.items[i];
        vtv_cache_touch(c, r->index, s->stamp);
        if (c->state[r->index] != VTV_TILE_ABSENT || s->pending_count >= cap)
            continue;
        s->pending[s->pending_count] = r->index;
        s->pending_lxy[s->pending_count * 3] = r->level;
        s->pending_lxy[s->pending_count * 3 + 1] = r->x;
        s->pending_lxy[s->pending_count * 3 + 2] = r->y;
        s->pending_count++;
    }
    collect_ahead(s);
    if (!s->sync) {
        /* wanted tiles held in RAM are uploaded from there; the others, then the prefetch
         * candidates (lower priority), go to the loader */
        uint32_t keep = 0;
        s->ready_count = 0;
        for (uint32_t i = 0; i < s->pending_count; i++) {
            uint64_t idx = s->pending[i];
            c->state[idx] = VTV_TILE_QUEUED;
            if (vtv_ramcache_has(s->ram, idx)) {
                s->ready[s->ready_count++] = idx;
                continue;
            }
            s->pending[keep] = idx;
            memmove(&s->pending_lxy[keep * 3], &s->pending_lxy[i * 3], 3 * sizeof(uint32_t));
            keep++;
        }
        for (uint32_t i = 0; i < s->ahead_count && keep < cap; i++) {
            c->state[s->ahead[i]] = VTV_TILE_QUEUED;
            s->pending[keep] = s->ahead[i];
            memcpy(&s->pending_lxy[keep * 3], &s->ahead_lxy[i * 3], 3 * sizeof(uint32_t));
            keep++;
        }
        s->ahead_count = 0;
        vtv_loader_submit(s->loader, s->pending, s->pending_lxy, keep, s->dropped);
        s->pending_count = 0;
    }
    return 0;
}

uint8_t *vtv_stream_level0(const struct vts_store *store, uint32_t layer, struct vts_error *err)
{
    const struct vts_geometry *g = vts_store_geometry(store);
    struct vts_level lv;
    vts_store_level(store, 0, &lv);
    if ((uint64_t)g->width * g->height > (1ull << 28)) {
        vt_error_set(err, VTS_ERR_LIMIT, "--reference: level 0 is too large (%ux%u)", g->width,
                     g->height);
        return NULL;
    }
    const struct vts_layer *info = vts_store_layer(store, layer);
    if (info && info->sample != VTS_SAMPLE_U8) {
        vt_error_set(err, VTS_ERR_UNSUPPORTED,
                     "--reference draws 8-bit layers; layer '%s' of %s holds %s samples",
                     info->name, vts_store_name(store), vts_sample_name(info->sample));
        return NULL;
    }
    struct vtv_loader *l = vtv_loader_create(store, layer, 0, 0, err);
    uint8_t *img = l ? calloc((size_t)g->width * g->height, 4) : NULL;
    if (l && !img)
        vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    uint32_t cp = g->tile_content_px, pp = g->tile_payload_px;
    for (uint32_t ty = 0; img && ty < lv.tiles_y; ty++) {
        for (uint32_t tx = 0; img && tx < lv.tiles_x; tx++) {
            struct vtv_load *r = vtv_loader_load_now(l, 0, 0, tx, ty);
            if (!r || r->status != 0) {
                vt_error_set(err, r ? r->status : VTS_ERR_NOMEM, "%s", r ? r->error : "no memory");
                vtv_load_free(r);
                free(img);
                img = NULL;
                break;
            }
            for (uint32_t y = 0; r->rgba && y < cp && ty * cp + y < g->height; y++) {
                uint32_t w = tx * cp + cp <= g->width ? cp : g->width - tx * cp;
                memcpy(img + (((size_t)ty * cp + y) * g->width + (size_t)tx * cp) * 4,
                       r->rgba + (((size_t)y + g->border_px) * pp + g->border_px) * 4,
                       (size_t)w * 4);
            }
            vtv_load_free(r);
        }
    }
    vtv_loader_destroy(l);
    return img;
}
