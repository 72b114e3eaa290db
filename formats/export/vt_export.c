/* The run of an export: blocks of output tiles, each made one row of tiles at a time from a band
 * of the store's texels that rolls down the block (each store tile the block touches decoded
 * once; a worker holds one band, never a whole level); the levels coarser than the store's made
 * in memory from its coarsest one; every tile encoded with the codec table and written. */
#include <assert.h>
#include <stdlib.h>
#include <string.h>

#include "internal/vt_export_impl.h"
#include "vt_checked.h"
#include "vt_filter.h"
#include "vt_image.h"
#include "vt_pool.h"

/* Output tiles per block edge: blocks of about 4096 texels square. A block decodes the store
 * tiles around it too (for the overlap, and where the grids differ): about 1/8 more per side at
 * 4096, 1/4 at 2048 (measured: 2048-texel blocks decoded 1.56x the store's tiles of a level with
 * overlap 1). */
#define BLOCK_TEXELS 4096u

struct worker {
    unsigned char *payload; /* one stored payload */
    struct vt_image tile;   /* one decoded store tile (payload edge) */
    unsigned char *band;    /* rows [band_y0, band_y0 + band_rows) of the block's columns */
    uint32_t band_y0, band_rows, band_cap; /* band_cap: rows it can hold */
    struct vt_image out;                   /* one output tile after conversion / padding */
    unsigned char *encoded;                /* its encoded bytes */
    size_t encoded_cap;
};

struct job_level {
    uint32_t j, blocks_x, blocks_y;
    uint64_t first_job;
};

struct run {
    const struct vts_store *store;
    const struct vt_export_params *p;
    struct vt_export_plan plan;
    const char *dir;
    const struct vts_layer *layer;
    const struct vt_codec *decoder; /* the store layer's codec */
    uint32_t store_levels, block_tiles;
    size_t texel_bytes;
    uint32_t out_sample;        /* u8, or u16 for 16-bit PNG */
    struct vt_image coarse[33]; /* levels j >= store_levels, made in memory */
    struct job_level levels[33];
    uint64_t job_count, next_job, done, total; /* done: atomic */
    struct worker *workers;
};

/* ---- reading texels of a level ---- */

/* Copies the texels of store tile (tx, ty) of level j that lie in rect into dst (rect's origin). */
static int read_store_tile(struct run *r, struct worker *w, uint32_t j, uint32_t tx, uint32_t ty,
                           struct vt_export_rect rect, unsigned char *dst, size_t stride,
                           struct vts_error *err)
{
    const struct vts_geometry *g = vts_store_geometry(r->store);
    uint64_t edge = g->tile_content_px;
    uint64_t x0 = tx * edge > rect.x0 ? tx * edge : rect.x0;
    uint64_t y0 = ty * edge > rect.y0 ? ty * edge : rect.y0;
    uint64_t x1 = (tx + 1) * edge < rect.x1 ? (tx + 1) * edge : rect.x1;
    uint64_t y1 = (ty + 1) * edge < rect.y1 ? (ty + 1) * edge : rect.y1;
    struct vts_error why = {0};
    size_t len = 0;
    int rc = vts_store_read(r->store, r->p->layer, j, tx, ty, w->payload,
                            (size_t)vts_store_max_payload(r->store) + 1, &len, 0, &why);
    if (rc == 0 && len > 0)
        rc = r->decoder->decode(w->payload, len, &w->tile, &why);
    if (rc != 0)
        return vt_error_set(err, rc, "'%s': layer %u level %u tile %u,%u: %s",
                            vts_store_name(r->store), r->p->layer, j, tx, ty,
                            rc == VTS_ERR_CHECKSUM ? "payload checksum mismatch" : why.message);
    size_t row_bytes = (size_t)(x1 - x0) * r->texel_bytes;
    for (uint64_t y = y0; y < y1; y++) {
        unsigned char *out = dst + (size_t)(y - rect.y0) * stride + (x0 - rect.x0) * r->texel_bytes;
        if (len == 0)
            memset(out, 0, row_bytes);
        else
            memcpy(out,
                   vt_image_at(&w->tile, (uint32_t)(x0 - tx * edge) + g->border_px,
                               (uint32_t)(y - ty * edge) + g->border_px),
                   row_bytes);
    }
    return 0;
}

/* Reads rect of level j into dst (rows stride bytes apart): from the store's tiles, each read and
 * decoded once, or from the in-memory coarse level. */
static int read_rect(struct run *r, struct worker *w, uint32_t j, struct vt_export_rect rect,
                     unsigned char *dst, size_t stride, struct vts_error *err)
{
    if (j >= r->store_levels) {
        const struct vt_image *c = &r->coarse[j];
        for (uint32_t y = rect.y0; y < rect.y1; y++)
            memcpy(dst + (size_t)(y - rect.y0) * stride, vt_image_at(c, rect.x0, y),
                   (size_t)(rect.x1 - rect.x0) * r->texel_bytes);
        return 0;
    }
    uint32_t edge = vts_store_geometry(r->store)->tile_content_px;
    for (uint32_t ty = rect.y0 / edge; (uint64_t)ty * edge < rect.y1; ty++)
        for (uint32_t tx = rect.x0 / edge; (uint64_t)tx * edge < rect.x1; tx++) {
            int rc = read_store_tile(r, w, j, tx, ty, rect, dst, stride, err);
            if (rc != 0)
                return rc;
        }
    return 0;
}

/* ---- the levels coarser than the store's ---- */

/* Box 2:1 reduction in the layer's working space (linear light for sRGB, premultiplied alpha,
 * renormalised normals), clamped or wrapped as the store: what the store's own box levels are; or
 * the store's selection (docs/filters.md, "Selections"). */
static int reduce_level(struct run *r, const struct vt_image *src, struct vt_image *dst,
                        struct vts_error *err)
{
    const struct vts_layer *l = r->layer;
    bool colour = l->colour == VTS_COLOUR_SRGB || l->colour == VTS_COLOUR_LINEAR;
    struct vt_pixel_mode mode = {.channels = l->channels,
                                 .colour = l->colour,
                                 .alpha = colour && (l->channels == 2 || l->channels == 4) &&
                                          !(l->flags & VTS_LAYER_PREMULTIPLIED)};
    uint32_t flags = vts_store_geometry(r->store)->flags;
    struct vt_edges edges = {src->width, src->height, flags & VTS_STORE_WRAP_X,
                             flags & VTS_STORE_WRAP_Y};
    /* a store reduced by a selection (filter=mode, min...) goes on with it: its levels hold
     * values of level 0 only */
    enum vt_filter_kind kind;
    if (vt_filter_parse(vts_store_meta_find(r->store, "filter"), &kind) != 0 ||
        !vt_filter_is_selection(kind))
        kind = VT_FILTER_BOX;
    struct vt_kernel k;
    vt_kernel_init(&k, kind);
    uint32_t w = (src->width + 1) / 2, h = (src->height + 1) / 2;
    int rc = vt_image_alloc(dst, w, h, l->channels, l->sample, err);
    if (rc != 0)
        return rc;
    struct vt_fregion sreg = {0, 0, src->width, src->height, l->channels, NULL};
    struct vt_fregion dreg = {0, 0, w, h, l->channels, NULL};
    struct vt_stored_rows stored = {src->pixels, src->stride, l->sample, &mode};
    size_t scratch_n = vt_filter_reduce_stored_scratch(&k, &sreg, &dreg);
    float *scratch = malloc(scratch_n * sizeof(float));
    dreg.px = malloc((size_t)w * h * l->channels * sizeof(float));
    if (!scratch || !dreg.px)
        rc = vt_error_set(err, VTS_ERR_NOMEM, "out of memory reducing '%s'",
                          vts_store_name(r->store));
    if (rc == 0)
        rc = vt_filter_reduce_stored(&k, &edges, &sreg, &stored, &dreg, scratch, scratch_n, err);
    if (rc == 0 && l->colour == VTS_COLOUR_NORMAL)
        vt_filter_renormalize(&dreg);
    for (uint32_t y = 0; rc == 0 && y < h; y++)
        vt_filter_from_working(&mode, l->sample, dreg.px + (size_t)y * w * l->channels,
                               vt_image_at(dst, 0, y), w);
    free(scratch);
    free(dreg.px);
    return rc;
}

/* Reads the store's coarsest level whole and reduces it down to the export's last level. */
static int make_coarse_levels(struct run *r, struct vts_error *err)
{
    uint32_t last = r->store_levels - 1;
    if (r->plan.level_count <= r->store_levels)
        return 0;
    struct vts_level L;
    struct vt_image top = {0};
    vts_store_level(r->store, last, &L);
    int rc = vt_image_alloc(&top, L.width, L.height, r->layer->channels, r->layer->sample, err);
    if (rc == 0)
        rc = read_rect(r, &r->workers[0], last, (struct vt_export_rect){0, 0, L.width, L.height},
                       top.pixels, top.stride, err);
    const struct vt_image *src = &top;
    for (uint32_t j = last + 1; rc == 0 && j < r->plan.level_count; j++) {
        rc = reduce_level(r, src, &r->coarse[j], err);
        src = &r->coarse[j];
    }
    vt_image_release(&top);
    return rc;
}

/* ---- tiles: convert, encode, write ---- */

/* Converts tile rect (texels at src) into w->out: u16 -> u8 for JPEG (rounded), padded with zeros
 * to the full tile edge for XYZ. */
static void convert_tile(struct run *r, struct worker *w, const unsigned char *src, size_t stride,
                         uint32_t width, uint32_t height)
{
    struct vt_image *o = &w->out;
    uint32_t ch = r->layer->channels;
    o->width = r->plan.layout == VT_EXPORT_XYZ ? r->plan.tile_px : width;
    o->height = r->plan.layout == VT_EXPORT_XYZ ? r->plan.tile_px : height;
    o->stride = (size_t)o->width * vt_image_texel_bytes(o);
    memset(o->pixels, 0, o->stride * o->height);
    for (uint32_t y = 0; y < height; y++) {
        const unsigned char *s = src + (size_t)y * stride;
        unsigned char *d = (unsigned char *)o->pixels + (size_t)y * o->stride;
        if (r->layer->sample == r->out_sample) {
            memcpy(d, s, (size_t)width * r->texel_bytes);
            continue;
        }
        for (size_t i = 0; i < (size_t)width * ch; i++) {
            uint16_t v;
            memcpy(&v, s + 2 * i, 2);
            d[i] = (unsigned char)(((uint32_t)v * 255 + 32767) / 65535);
        }
    }
}

static int write_tile(struct run *r, struct worker *w, uint32_t j, uint32_t c, uint32_t row,
                      unsigned char *band, size_t stride, struct vt_export_rect brect,
                      struct vts_error *err)
{
    struct vt_export_rect t = vt_export_tile_rect(&r->plan, j, c, row);
    unsigned char *src =
        band + (size_t)(t.y0 - brect.y0) * stride + (size_t)(t.x0 - brect.x0) * r->texel_bytes;
    struct vt_image view = {t.x1 - t.x0,      t.y1 - t.y0, r->layer->channels,
                            r->layer->sample, stride,      src};
    const struct vt_image *img = &view;
    if (r->plan.layout == VT_EXPORT_XYZ || r->layer->sample != r->out_sample) {
        convert_tile(r, w, src, stride, view.width, view.height);
        img = &w->out;
    }
    char rel[512];
    size_t len = 0;
    if (vt_export_tile_path(&r->plan, r->p->name, j, c, row, rel, sizeof rel) < 0)
        return vt_error_set(err, VTS_ERR_ARG, "export name too long");
    int rc = r->p->codec->encode(img, &r->p->codec_params, w->encoded, w->encoded_cap, &len, err);
    if (rc == 0)
        rc = vt_export_write_file(r->dir, rel, w->encoded, len, err);
    if (rc == 0)
        __atomic_add_fetch(&r->done, 1, __ATOMIC_RELAXED);
    return rc;
}

/* ---- the pool ---- */

static bool next_job(void *ctx, uint64_t *job)
{
    struct run *r = ctx;
    if (r->next_job >= r->job_count)
        return false;
    *job = r->next_job++;
    return true;
}

/* Drops the band's rows above y (rows the next tiles do not use). */
static void band_drop(struct worker *w, uint32_t y, size_t stride)
{
    if (y <= w->band_y0)
        return;
    uint32_t k = y - w->band_y0 < w->band_rows ? y - w->band_y0 : w->band_rows;
    memmove(w->band, w->band + (size_t)k * stride, (size_t)(w->band_rows - k) * stride);
    w->band_rows -= k;
    w->band_y0 = y;
}

/* Extends the band down to row y_end (exclusive) of level j, columns [x0, x1): from the store a
 * whole store-tile row at a time, so that each store tile is decoded once per block. */
static int band_fill(struct run *r, struct worker *w, uint32_t j, uint32_t x0, uint32_t x1,
                     uint32_t y_end, size_t stride, struct vts_error *err)
{
    uint32_t edge = vts_store_geometry(r->store)->tile_content_px;
    uint32_t level_h = vt_export_level_height(&r->plan, j);
    while (w->band_y0 + w->band_rows < y_end) {
        uint32_t end = w->band_y0 + w->band_rows, next = y_end;
        if (j < r->store_levels) {
            uint64_t boundary = ((uint64_t)end / edge + 1) * edge;
            next = boundary < level_h ? (uint32_t)boundary : level_h;
        }
        assert(w->band_rows + (next - end) <= w->band_cap);
        int rc = read_rect(r, w, j, (struct vt_export_rect){x0, end, x1, next},
                           w->band + (size_t)w->band_rows * stride, stride, err);
        if (rc != 0)
            return rc;
        w->band_rows += next - end;
    }
    return 0;
}

static int do_job(void *ctx, unsigned worker, uint64_t job, struct vts_error *err)
{
    struct run *r = ctx;
    struct worker *w = &r->workers[worker];
    uint32_t li = 0;
    while (li + 1 < r->plan.level_count && r->levels[li + 1].first_job <= job)
        li++;
    const struct job_level *jl = &r->levels[li];
    uint64_t b = job - jl->first_job;
    uint32_t bx = (uint32_t)(b % jl->blocks_x), by = (uint32_t)(b / jl->blocks_x);
    uint32_t c0 = bx * r->block_tiles, r0 = by * r->block_tiles;
    uint32_t c1 = c0 + r->block_tiles, r1 = r0 + r->block_tiles;
    if (c1 > vt_export_tiles_x(&r->plan, jl->j))
        c1 = vt_export_tiles_x(&r->plan, jl->j);
    if (r1 > vt_export_tiles_y(&r->plan, jl->j))
        r1 = vt_export_tiles_y(&r->plan, jl->j);
    uint32_t x0 = vt_export_tile_rect(&r->plan, jl->j, c0, r0).x0;
    uint32_t x1 = vt_export_tile_rect(&r->plan, jl->j, c1 - 1, r0).x1;
    size_t stride = (size_t)(x1 - x0) * r->texel_bytes;
    int rc = 0;
    w->band_y0 = vt_export_tile_rect(&r->plan, jl->j, c0, r0).y0;
    w->band_rows = 0;
    for (uint32_t row = r0; rc == 0 && row < r1; row++) {
        struct vt_export_rect t = vt_export_tile_rect(&r->plan, jl->j, c0, row);
        band_drop(w, t.y0, stride);
        rc = band_fill(r, w, jl->j, x0, x1, t.y1, stride, err);
        struct vt_export_rect brect = {x0, w->band_y0, x1, w->band_y0 + w->band_rows};
        for (uint32_t c = c0; rc == 0 && c < c1; c++)
            rc = write_tile(r, w, jl->j, c, row, w->band, stride, brect, err);
    }
    return rc;
}

static int on_progress(void *ctx)
{
    struct run *r = ctx;
    if (!r->p->progress)
        return 0;
    return r->p->progress(r->p->progress_ctx, __atomic_load_n(&r->done, __ATOMIC_RELAXED),
                          r->total);
}

/* ---- setup ---- */

static int alloc_worker(struct run *r, struct worker *w, struct vts_error *err)
{
    const struct vts_geometry *g = vts_store_geometry(r->store);
    uint32_t ch = r->layer->channels, t = r->plan.tile_px + 2 * r->plan.overlap_px;
    uint64_t block_width = (uint64_t)r->block_tiles * r->plan.tile_px + 2 * r->plan.overlap_px;
    size_t band_bytes;
    /* One row of tiles with its overlap, and the rest of the last store-tile row it reaches. */
    w->band_cap = t + g->tile_content_px;
    w->payload = malloc((size_t)vts_store_max_payload(r->store) + 1);
    w->encoded_cap = r->p->codec->encoded_bound(t, t, ch, r->out_sample);
    w->encoded = w->encoded_cap ? malloc(w->encoded_cap) : NULL;
    if (!vt_size_mul3((size_t)block_width, w->band_cap, r->texel_bytes, &band_bytes) ||
        !w->payload || !w->encoded || !(w->band = malloc(band_bytes)))
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory exporting '%s'",
                            vts_store_name(r->store));
    int rc =
        vt_image_alloc(&w->tile, g->tile_payload_px, g->tile_payload_px, ch, r->layer->sample, err);
    if (rc == 0)
        rc = vt_image_alloc(&w->out, t, t, ch, r->out_sample, err);
    return rc;
}

static void free_workers(struct run *r, unsigned n)
{
    for (unsigned i = 0; r->workers && i < n; i++) {
        free(r->workers[i].payload);
        free(r->workers[i].band);
        free(r->workers[i].encoded);
        vt_image_release(&r->workers[i].tile);
        vt_image_release(&r->workers[i].out);
    }
    free(r->workers);
    for (int j = 0; j < 33; j++)
        vt_image_release(&r->coarse[j]);
}

static void plan_jobs(struct run *r)
{
    uint64_t first = 0;
    uint32_t bt = r->block_tiles;
    for (uint32_t j = 0; j < r->plan.level_count; j++) {
        struct job_level *jl = &r->levels[j];
        jl->j = j;
        jl->blocks_x = (vt_export_tiles_x(&r->plan, j) + bt - 1) / bt;
        jl->blocks_y = (vt_export_tiles_y(&r->plan, j) + bt - 1) / bt;
        jl->first_job = first;
        first += (uint64_t)jl->blocks_x * jl->blocks_y;
    }
    r->job_count = first;
}

int vt_export_run(const struct vts_store *store, const struct vt_export_params *p, const char *dir,
                  struct vts_error *err)
{
    struct run r = {.store = store, .p = p, .dir = dir};
    int rc = vt_export_check(store, p, err);
    if (rc != 0)
        return rc;
    vt_export_plan_init(&r.plan, store, p);
    r.layer = vts_store_layer(store, p->layer);
    r.decoder = vt_codec_by_fourcc(r.layer->codec);
    if (!r.decoder)
        return vt_error_set(err, VTS_ERR_UNSUPPORTED, "'%s': layer %u: unknown codec",
                            vts_store_name(store), p->layer);
    r.store_levels = vts_store_geometry(store)->level_count;
    r.texel_bytes = (size_t)r.layer->channels * vt_sample_bytes(r.layer->sample);
    r.out_sample = p->codec->fourcc == VTS_CODEC_JPEG ? VTS_SAMPLE_U8 : r.layer->sample;
    r.block_tiles = p->tile_px >= BLOCK_TEXELS ? 1 : BLOCK_TEXELS / p->tile_px;
    r.total = vt_export_tile_count(store, p);
    plan_jobs(&r);
    unsigned n = p->threads ? p->threads : 1;
    r.workers = calloc(n, sizeof *r.workers);
    if (!r.workers)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    for (unsigned i = 0; rc == 0 && i < n; i++)
        rc = alloc_worker(&r, &r.workers[i], err);
    if (rc == 0)
        rc = make_coarse_levels(&r, err);
    if (rc == 0)
        rc = vt_export_write_descriptor(&r.plan, p, dir, err);
    if (rc == 0) {
        struct vt_pool_fns fns = {next_job, do_job, on_progress};
        rc = vt_pool_run(n, &fns, &r, err);
    }
    free_workers(&r, n);
    return rc;
}
