/* Atlas compositing (see vt_atlas_build.h and docs/atlas-build.md). */
#include "vt_atlas_build.h"

#include <assert.h>
#include <stdlib.h>
#include <string.h>

#include "internal/vt_atlas_build_impl.h"
#include "vt_checked.h"
#include "vt_error.h"
#include "vt_pool.h"
#include "vts.h"

static uint32_t ceil_shift(uint32_t v, uint32_t k)
{
    return k >= 32 ? 1 : (uint32_t)(((uint64_t)v + (1ull << k) - 1) >> k);
}

static uint32_t log2_u32(uint32_t v)
{
    uint32_t l = 0;
    while (l < 31 && (1u << (l + 1)) <= v)
        l++;
    return l;
}

/* ---- tiles ---- */

/* Tiles are handed out in quadtree post-order: the four children of a tile (one level finer)
 * before the tile itself, children in Z order. Neighbouring tiles and the coarser tiles above them
 * follow each other, so the textures they read are still in the cache. */
struct frame {
    uint32_t level, tx, ty, child;
};

struct tile_run {
    struct vt_atlas_build *b;
    vt_atlas_emit_fn emit;
    void *user;
    uint64_t total, done;
    struct frame stack[VTS_MAX_LEVELS + 1];
    uint32_t depth;
    uint64_t root; /* next tile of the coarsest level to start */
};

/* Job number of a tile: its place in the index (level by level, row-major). */
static void job_tile(const struct vt_atlas_build *b, uint64_t job, uint32_t *L, uint32_t *tx,
                     uint32_t *ty)
{
    uint32_t l = 0;
    while (job >= b->first[l + 1])
        l++;
    uint64_t i = job - b->first[l];
    *L = l;
    *tx = (uint32_t)(i % b->tx[l]);
    *ty = (uint32_t)(i / b->tx[l]);
}

static bool tile_next(void *ctx, uint64_t *job)
{
    struct tile_run *r = ctx;
    const struct vt_atlas_build *b = r->b;
    uint32_t top = b->level_count - 1;
    for (;;) {
        if (r->depth == 0) {
            if (r->root >= (uint64_t)b->tx[top] * b->ty[top])
                return false;
            r->stack[r->depth++] = (struct frame){top, (uint32_t)(r->root % b->tx[top]),
                                                  (uint32_t)(r->root / b->tx[top]), 0};
            r->root++;
        }
        struct frame *f = &r->stack[r->depth - 1];
        if (f->level == 0 || f->child == 4) {
            *job = b->first[f->level] + (uint64_t)f->ty * b->tx[f->level] + f->tx;
            r->depth--;
            return true;
        }
        uint32_t d = f->child++, cx = 2 * f->tx + (d & 1), cy = 2 * f->ty + (d >> 1);
        if (cx < b->tx[f->level - 1] && cy < b->ty[f->level - 1])
            r->stack[r->depth++] = (struct frame){f->level - 1, cx, cy, 0};
    }
}

static int tile_do(void *ctx, unsigned worker, uint64_t job, struct vts_error *err)
{
    struct tile_run *r = ctx;
    struct vt_atlas_build *b = r->b;
    struct vt_atlas_tile_worker *w = &b->workers[worker];
    uint32_t L, tx, ty;
    job_tile(b, job, &L, &tx, &ty);
    if (!vt_atlas_shard_emits(b, L, tx, ty)) { /* another shard's, or the merge's */
        __atomic_fetch_add(&r->done, 1, __ATOMIC_RELAXED);
        return 0;
    }
    uint32_t cx0 = tx * b->t.content, cy0 = ty * b->t.content;
    uint32_t cw = b->t.lw[L] - cx0 < b->t.content ? b->t.lw[L] - cx0 : b->t.content;
    uint32_t chh = b->t.lh[L] - cy0 < b->t.content ? b->t.lh[L] - cy0 : b->t.content;
    int rc = 0;
    bool any = vt_atlas_tile_classify_content(&b->t, w, L, cx0, cy0, cw, chh);
    if (!any)
        __atomic_fetch_add(&b->tiles_empty, 1, __ATOMIC_RELAXED);
    for (uint32_t s = 0; s < b->t.nslots && rc == 0; s++) {
        if (any)
            rc = vt_atlas_tile_fill_payload(&b->t, w, s, L, cx0, cy0, cw, chh, err);
        if (rc == 0)
            rc = r->emit(r->user, worker, s, L, tx, ty, any ? &w->payload[s] : NULL, err);
    }
    vt_atlas_tile_unpin(&b->t, w);
    __atomic_fetch_add(&r->done, 1, __ATOMIC_RELAXED);
    return rc;
}

static int tile_progress(void *ctx)
{
    struct tile_run *r = ctx;
    if (!r->b->o.progress)
        return 0;
    return r->b->o.progress(r->b->o.progress_user, __atomic_load_n(&r->done, __ATOMIC_RELAXED),
                            r->total);
}

int vt_atlas_build_tiles(struct vt_atlas_build *b, vt_atlas_emit_fn emit, void *user,
                         struct vts_error *err)
{
    struct tile_run r = {.b = b, .emit = emit, .user = user, .total = b->first[b->level_count]};
    struct vt_pool_fns fns = {tile_next, tile_do, tile_progress};
    return vt_pool_run(b->o.threads, &fns, &r, err);
}

int vt_atlas_build_render(struct vt_atlas_build *b, uint32_t s, uint32_t L, uint32_t x, uint32_t y,
                          struct vt_image *dst, struct vts_error *err)
{
    if (s >= b->t.nslots || L >= b->level_count || dst->sample != b->t.slots[s].fmt.sample ||
        dst->channels != b->t.slots[s].fmt.channels || (uint64_t)x + dst->width > b->t.lw[L] ||
        (uint64_t)y + dst->height > b->t.lh[L])
        return vt_error_set(err, VTS_ERR_ARG, "render: bad region or image");
    struct vt_atlas_tile_worker *w = &b->workers[b->o.threads];
    int rc = 0;
    for (uint32_t j = 0; j < dst->height && rc == 0; j++) {
        uint8_t *o = vt_image_at(dst, 0, j);
        for (uint32_t i = 0; i < dst->width && rc == 0;) {
            uint32_t run = 0;
            int32_t k = vt_atlas_tile_classify(&b->t, L, x + i, y + j, &run);
            uint32_t end = k >= 0 ? run - x : i + 1;
            end = end < dst->width ? end : dst->width;
            for (; i < end && rc == 0; i++)
                rc = vt_atlas_tile_texel(&b->t, w, s, L, x + i, y + j, k,
                                         o + (size_t)i * b->t.slots[s].texel_bytes, err);
        }
    }
    vt_atlas_tile_unpin(&b->t, w);
    return rc;
}

static void geometry(struct vt_atlas_build *b)
{
    const struct vt_layout *lay = b->t.lay;
    b->t.content = lay->tile_content;
    b->t.border = lay->border;
    b->t.payload = b->t.content + 2 * b->t.border;
    uint32_t full = vts_full_level_count(lay->width, lay->height, b->t.content);
    b->level_count = b->o.level_count && b->o.level_count < full ? b->o.level_count : full;
    if (b->level_count > VTS_MAX_LEVELS)
        b->level_count = VTS_MAX_LEVELS;
    b->first[0] = 0;
    uint32_t n = b->level_count; /* a local: the stores below may alias b->level_count */
    for (uint32_t l = 0; l < n; l++) {
        b->t.lw[l] = ceil_shift(lay->width, l);
        b->t.lh[l] = ceil_shift(lay->height, l);
        b->tx[l] = b->t.lw[l] / b->t.content + (b->t.lw[l] % b->t.content != 0);
        b->ty[l] = b->t.lh[l] / b->t.content + (b->t.lh[l] % b->t.content != 0);
        b->first[l + 1] = b->first[l] + (uint64_t)b->tx[l] * b->ty[l];
    }
}

static int alloc_tables(struct vt_atlas_build *b, struct vts_error *err)
{
    size_t n;
    uint32_t ne = b->t.lay->entry_count;
    if (!vt_size_mul(ne ? ne : 1, b->t.nslots, &n))
        return vt_error_set(err, VTS_ERR_LIMIT, "too many entries");
    (void)n;
    b->t.lmax = calloc(ne ? ne : 1, 1);
    b->workers = calloc((size_t)b->o.threads + 1, sizeof *b->workers);
    if (!b->t.lmax || !b->workers)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory for the atlas tables");
    for (uint32_t e = 0; e < ne; e++)
        b->t.lmax[e] = (uint8_t)log2_u32(b->t.lay->entries[e].alignment);
    for (unsigned t = 0; t <= b->o.threads; t++) {
        struct vt_atlas_tile_worker *w = &b->workers[t];
        w->cls = malloc((size_t)b->t.content * b->t.content * sizeof *w->cls);
        if (!w->cls)
            return vt_error_set(err, VTS_ERR_NOMEM, "out of memory for tile buffers");
    }
    return 0;
}

static int alloc_payloads(struct vt_atlas_build *b, struct vts_error *err)
{
    for (unsigned t = 0; t < b->o.threads; t++)
        for (uint32_t s = 0; s < b->t.nslots; s++) {
            int rc = vt_image_alloc(&b->workers[t].payload[s], b->t.payload, b->t.payload,
                                    b->t.slots[s].fmt.channels, b->t.slots[s].fmt.sample, err);
            if (rc)
                return rc;
        }
    return 0;
}

struct vt_atlas_build *vt_atlas_build_create(const struct vt_atlas_build_options *o,
                                             struct vts_error *err)
{
    if (!o->layout || !o->open || o->layer_count < 1 || o->layer_count > VT_LAYOUT_MAX_LAYERS ||
        o->threads < 1 || o->threads > 256) {
        vt_error_set(err, VTS_ERR_ARG, "atlas build: bad options");
        return NULL;
    }
    struct vt_atlas_build *b = calloc(1, sizeof *b);
    if (!b) {
        vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
        return NULL;
    }
    b->o = *o;
    b->t.lay = o->layout;
    b->t.nslots = o->layer_count;
    if (!b->o.max_pixels)
        b->o.max_pixels = 1ull << 34;
    for (uint32_t s = 0; s < b->t.nslots; s++) {
        if (o->layers[s] >= b->t.lay->layer_count) {
            vt_error_set(err, VTS_ERR_ARG, "atlas build: layer %u out of range", o->layers[s]);
            goto fail;
        }
        b->t.slots[s].layer = o->layers[s];
    }
    geometry(b);
    if (alloc_tables(b, err) || vt_atlas_tile_build_grid(&b->t, err))
        goto fail;
    if (o->part.count && vt_atlas_shard_prepare(b, err))
        goto fail;
    if (!o->part.merge && vt_atlas_chains_build(&b->t, &b->o, b->level_count, &b->decodes, err))
        goto fail;
    if (alloc_payloads(b, err))
        goto fail;
    return b;
fail:
    vt_atlas_build_destroy(b);
    return NULL;
}

void vt_atlas_build_format(const struct vt_atlas_build *b, uint32_t slot,
                           struct vt_atlas_layer_format *out)
{
    *out = b->t.slots[slot].fmt;
}

uint32_t vt_atlas_build_level_count(const struct vt_atlas_build *b)
{
    return b->level_count;
}

uint64_t vt_atlas_build_tile_count(const struct vt_atlas_build *b)
{
    return b->first[b->level_count];
}

void vt_atlas_build_stats(const struct vt_atlas_build *b, struct vt_atlas_build_stats *out)
{
    struct vt_block_cache_stats cs = {0};
    if (b->t.blocks)
        vt_block_cache_stats(b->t.blocks, &cs);
    *out = (struct vt_atlas_build_stats){b->decodes,       cs.peak,    cs.budget,
                                         cs.peak_reserved, cs.spilled, b->tiles_empty,
                                         b->t.texels_mixed};
}

void vt_atlas_build_destroy(struct vt_atlas_build *b)
{
    if (!b)
        return;
    if (b->workers) {
        for (unsigned t = 0; t <= b->o.threads; t++) {
            vt_atlas_tile_unpin(&b->t, &b->workers[t]);
            free(b->workers[t].cls);
            for (uint32_t s = 0; s < VT_LAYOUT_MAX_LAYERS; s++)
                vt_image_release(&b->workers[t].payload[s]);
        }
    }
    vt_block_cache_destroy(b->t.blocks);
    free(b->t.chains);
    free(b->workers);
    free(b->t.lmax);
    vt_atlas_tile_release_grid(&b->t);
    free(b->need);
    for (uint32_t s = 0; s < VT_LAYOUT_MAX_LAYERS; s++)
        free(b->t.carried[s]);
    free(b);
}
