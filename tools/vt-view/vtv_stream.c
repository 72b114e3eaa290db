/* vt-view tile streaming: loads -> uploads -> page table; feedback -> loader queue. */
#include "vtv_stream.h"

#include <stdlib.h>
#include <string.h>

#include "tool_common.h"
#include "vt_error.h"

/* Puts one finished load into the cache. Returns false when no slot could be freed. */
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
    uint32_t slot = vtv_cache_alloc(c, s->stamp);
    if (slot == VTV_NO_SLOT) {
        vtv_cache_set_state(c, r->index, VTV_TILE_ABSENT);
        return false;
    }
    vtv_render_upload_tile(s->render, c, slot, r->rgba, r->bytes);
    vtv_cache_assign(c, slot, r->index, s->stamp);
    st->loaded++;
    st->uploads++;
    return true;
}

int vtv_stream_init(struct vtv_stream *s, const struct vts_store *store, uint32_t layer,
                    uint32_t slots, uint32_t threads, bool sync, uint32_t budget, bool bc_upload,
                    struct vtv_render *render, struct vts_error *err)
{
    memset(s, 0, sizeof(*s));
    s->render = render;
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
    if (layer >= vts_store_geometry(store)->layer_count)
        return vt_error_set(err, VTS_ERR_ARG, "%s: no layer %u", vts_store_name(store), layer);
    const struct vts_layer *info = vts_store_layer(store, layer);
    bool srgb = info->colour == VTS_COLOUR_SRGB;
    uint32_t pp = vts_store_geometry(store)->tile_payload_px;
    uint32_t bc =
        bc_upload && vtv_render_bc_format(render, info->codec, srgb, pp) ? info->codec : 0;
    st = vtv_render_set_cache(render, &s->cache, vts_store_geometry(store), srgb, bc, err);
    if (st != 0)
        return st;
    s->loader =
        vtv_loader_create(store, layer, sync ? 0 : threads, bc ? VTV_LOADER_COMPRESSED : 0, err);
    if (!s->loader)
        return err->status;
    uint32_t cap = vtv_loader_queue_capacity(s->loader);
    s->pending = malloc(cap * sizeof(*s->pending));
    s->pending_lxy = malloc(cap * 3 * sizeof(*s->pending_lxy));
    s->dropped = malloc(cap * sizeof(*s->dropped));
    if (!s->pending || !s->pending_lxy || !s->dropped)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    struct vtv_frame_stats dummy = {0};
    uint32_t top_level = s->cache.level_count - 1;
    for (uint32_t y = 0; y < top->tiles_y; y++) {
        for (uint32_t x = 0; x < top->tiles_x; x++) {
            uint64_t idx = vtv_cache_index(&s->cache, top_level, x, y);
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
    memset(s, 0, sizeof(*s));
}

void vtv_stream_update(struct vtv_stream *s, struct vtv_frame_stats *st)
{
    struct vtv_cache *c = &s->cache;
    if (s->sync) {
        for (uint32_t i = 0; i < s->pending_count && st->uploads < s->budget; i++) {
            uint64_t idx = s->pending[i];
            if (c->state[idx] != VTV_TILE_ABSENT)
                continue;
            struct vtv_load *r =
                vtv_loader_load_now(s->loader, idx, s->pending_lxy[i * 3],
                                    s->pending_lxy[i * 3 + 1], s->pending_lxy[i * 3 + 2]);
            if (!r)
                break;
            bool ok = apply(s, r, st);
            vtv_loader_release(s->loader, r);
            if (!ok)
                break;
        }
        s->pending_count = 0;
    } else {
        struct vtv_load *list = vtv_loader_take(s->loader, s->budget);
        for (struct vtv_load *r = list; r; r = r->next)
            apply(s, r, st);
        vtv_loader_release(s->loader, list);
    }
    if (vtv_cache_update_page_table(c))
        vtv_render_upload_page_table(s->render, c);
    vtv_cache_page_table_clean(c);
    st->resident = c->resident;
    st->empty = s->empty;
    st->failed = s->failed;
}

int vtv_stream_request(struct vtv_stream *s, const uint16_t *pixels, size_t n,
                       struct vtv_frame_stats *st)
{
    struct vtv_cache *c = &s->cache;
    s->stamp++;
    if (vtv_feedback_reduce(&s->feedback, c, pixels, n) != 0)
        return VTS_ERR_NOMEM;
    st->requested = s->feedback.count;
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
    if (!s->sync) {
        for (uint32_t i = 0; i < s->pending_count; i++)
            c->state[s->pending[i]] = VTV_TILE_QUEUED;
        vtv_loader_submit(s->loader, s->pending, s->pending_lxy, s->pending_count, s->dropped);
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
