/* Blocks of a mip pyramid pass: scratch, tiles, reduction, next-pass store (see
 * internal/vt_pyramid_block.h). */
#include "internal/vt_pyramid_block.h"

#include <stdlib.h>
#include <string.h>

#include "internal/vt_float_file.h"
#include "internal/vt_pyramid_read.h"
#include "vt_checked.h"
#include "vt_error.h"

/* ---- scratch ---- */

/* Largest region of relative level r over all blocks: a full block plus margins. */
static void max_region(const struct vt_pyramid_pass *p, uint32_t r, struct vt_fregion *out)
{
    uint32_t m = p->margin[r];
    uint64_t s = p->block >> r;
    out->x0 = out->y0 = 0;
    out->width = out->height = (uint32_t)s + 2 * m;
    out->channels = p->channels;
}

int vt_pyramid_block_scratch_alloc(const struct vt_pyramid_pass *p,
                                   struct vt_pyramid_block_scratch *s, struct vts_error *err)
{
    const struct vt_pyramid_options *o = p->o;
    uint32_t pp = o->tile_content_px + 2 * o->border_px;
    struct vt_fregion big;
    max_region(p, 0, &big);
    int rc = vt_image_alloc(&s->in, big.width, big.height, p->channels, p->sample, err);
    if (rc == 0)
        rc = vt_image_alloc(&s->tile_full, pp, pp, p->channels, o->out_sample, err);
    if (rc == 0)
        rc = vt_image_alloc(&s->tile, pp, pp, o->out_channels, o->out_sample, err);
    if (rc)
        return rc;
    bool ok = vt_pyramid_read_scratch_alloc(&s->read, big.width) == 0;
    size_t floats = 0;
    for (uint32_t r = 1; ok && r <= p->depth; r++) {
        struct vt_fregion reg, fine;
        max_region(p, r, &reg);
        max_region(p, r - 1, &fine);
        size_t n;
        ok = vt_size_mul3(reg.width, reg.height, p->channels, &n) &&
             (s->w[r].px = malloc(n * sizeof(float))) != NULL;
        /* level 1 of a stored source is reduced from the stored texels, a row at a time */
        size_t need = r == 1 && !p->source_is_working
                          ? vt_filter_reduce_stored_scratch(&p->kernel, &fine, &reg)
                          : vt_filter_reduce_scratch(&p->kernel, &fine, &reg);
        floats = need > floats ? need : floats;
    }
    ok = ok && floats != SIZE_MAX;
    s->reduce_floats = floats;
    if (ok && floats)
        ok = (s->reduce_scratch = malloc(floats * sizeof(float))) != NULL;
    if (!ok)
        return vt_error_set(err, VTS_ERR_NOMEM,
                            "out of memory for the working blocks of %ux%u texels", big.width,
                            big.height);
    return 0;
}

void vt_pyramid_block_scratch_release(const struct vt_pyramid_pass *p,
                                      struct vt_pyramid_block_scratch *s)
{
    (void)p;
    vt_image_release(&s->in);
    /* w[0] is a view of in (vt_pyramid_block_run) */
    for (uint32_t r = 1; r <= VT_PYRAMID_MAX_LEVELS; r++)
        free(s->w[r].px);
    free(s->reduce_scratch);
    vt_image_release(&s->tile_full);
    vt_image_release(&s->tile);
    vt_pyramid_read_scratch_release(&s->read);
}

/* ---- tiles ---- */

static bool all_transparent(const struct vt_image *t)
{
    if (t->channels != 2 && t->channels != 4)
        return false;
    size_t sb = vts_sample_bytes(t->sample), tb = vt_image_texel_bytes(t);
    for (uint32_t y = 0; y < t->height; y++)
        for (uint32_t x = 0; x < t->width; x++) {
            const unsigned char *a = (const unsigned char *)vt_image_at(t, x, y) + tb - sb;
            for (size_t i = 0; i < sb; i++)
                if (a[i])
                    return false;
        }
    return true;
}

/* Copies the first `channels` channels of every texel of src into dst (same sample type). */
static void copy_channels(const struct vt_image *src, struct vt_image *dst)
{
    size_t sb = vts_sample_bytes(src->sample);
    size_t stb = vt_image_texel_bytes(src), dtb = vt_image_texel_bytes(dst);
    for (uint32_t y = 0; y < dst->height; y++) {
        const unsigned char *s = vt_image_at(src, 0, y);
        unsigned char *d = vt_image_at(dst, 0, y);
        if (stb == dtb) {
            memcpy(d, s, dtb * dst->width);
            continue;
        }
        for (uint32_t x = 0; x < dst->width; x++)
            memcpy(d + x * dtb, s + x * stb, sb * dst->channels);
    }
}

/* Emits t, or the payload scratch when t is NULL (its out channels). */
static int emit_tile(const struct vt_pyramid_pass *p, unsigned worker,
                     struct vt_pyramid_block_scratch *s, const struct vt_image *t, uint32_t level,
                     uint32_t tx, uint32_t ty, struct vts_error *err)
{
    const struct vt_pyramid_options *o = p->o;
    if (!t)
        t = o->out_channels == p->channels ? &s->tile_full : &s->tile;
    /* a data layer of 2 or 4 bands (GDAL input) has no alpha: its zeros are texels */
    bool empty = p->has_alpha && all_transparent(t);
    int rc = o->emit(o->user, worker, level, tx, ty, empty ? NULL : t, err);
    if (rc == 0)
        __atomic_add_fetch(p->done, 1, __ATOMIC_RELAXED);
    return rc;
}

/* Payload of tile (tx, ty) of the pass's base level, straight from the source texels: a view of
 * the block when they are the payload's samples and channels, no copy. */
static int emit_base_tile(const struct vt_pyramid_pass *p, unsigned worker,
                          struct vt_pyramid_block_scratch *s, int64_t rx0, int64_t ry0, uint32_t tx,
                          uint32_t ty, struct vts_error *err)
{
    const struct vt_pyramid_options *o = p->o;
    uint32_t pp = o->tile_content_px + 2 * o->border_px;
    int64_t x = (int64_t)tx * o->tile_content_px - o->border_px - rx0;
    int64_t y = (int64_t)ty * o->tile_content_px - o->border_px - ry0;
    struct vt_image v = vt_pyramid_view(&s->block, x, y, pp, pp);
    if (o->out_sample == p->sample) {
        if (o->out_channels == p->channels)
            return emit_tile(p, worker, s, &v, p->base, tx, ty, err);
        copy_channels(&v, &s->tile);
        return emit_tile(p, worker, s, NULL, p->base, tx, ty, err);
    } else {
        float row[4 * 1024];
        for (uint32_t r = 0; r < pp; r++)
            for (uint32_t c0 = 0; c0 < pp; c0 += 1024) {
                uint32_t n = pp - c0 < 1024 ? pp - c0 : 1024;
                vt_filter_to_working(&p->mode, p->sample, vt_image_at(&v, c0, r), row, n);
                vt_filter_from_working(&p->mode, o->out_sample, row,
                                       vt_image_at(&s->tile_full, c0, r), n);
            }
    }
    if (o->out_channels != p->channels)
        copy_channels(&s->tile_full, &s->tile);
    return emit_tile(p, worker, s, NULL, p->base, tx, ty, err);
}

/* Payload of tile (tx, ty) of a reduced level from its working region. */
static int emit_working_tile(const struct vt_pyramid_pass *p, unsigned worker,
                             struct vt_pyramid_block_scratch *s, const struct vt_fregion *w,
                             uint32_t level, uint32_t tx, uint32_t ty, struct vts_error *err)
{
    const struct vt_pyramid_options *o = p->o;
    uint32_t pp = o->tile_content_px + 2 * o->border_px;
    int64_t x = (int64_t)tx * o->tile_content_px - o->border_px - w->x0;
    int64_t y = (int64_t)ty * o->tile_content_px - o->border_px - w->y0;
    for (uint32_t r = 0; r < pp; r++) {
        const float *src = w->px + ((size_t)(y + r) * w->width + (size_t)x) * w->channels;
        vt_filter_from_working(&p->mode, o->out_sample, src, vt_image_at(&s->tile_full, 0, r), pp);
    }
    if (o->out_channels != p->channels)
        copy_channels(&s->tile_full, &s->tile);
    return emit_tile(p, worker, s, NULL, level, tx, ty, err);
}

/* ---- blocks ---- */

struct span {
    int64_t c0;    /* first texel the block owns at this level */
    int64_t c1;    /* end of its whole tiles (past the level's edge for the last tiles) */
    int64_t inner; /* end of the texels it owns inside the level */
};

static struct span block_span(const struct vt_pyramid_pass *p, uint32_t b, uint32_t r,
                              uint32_t size)
{
    uint64_t s = p->block >> r, c = p->o->tile_content_px;
    uint64_t extent = vt_pyramid_level_extent(size, r), tiles_end = (extent + c - 1) / c * c;
    uint64_t end = (uint64_t)(b + 1) * s;
    return (struct span){(int64_t)((uint64_t)b * s), (int64_t)(end < tiles_end ? end : tiles_end),
                         (int64_t)(end < extent ? end : extent)};
}

static int emit_level_tiles(const struct vt_pyramid_pass *p, unsigned worker,
                            struct vt_pyramid_block_scratch *s, uint32_t r, uint32_t bx,
                            uint32_t by, int64_t rx0, int64_t ry0, struct vts_error *err)
{
    uint32_t c = p->o->tile_content_px, level = p->base + r;
    struct span sx = block_span(p, bx, r, p->w), sy = block_span(p, by, r, p->h);
    int rc = 0;
    for (uint32_t ty = (uint32_t)(sy.c0 / c); rc == 0 && (int64_t)ty * c < sy.c1; ty++)
        for (uint32_t tx = (uint32_t)(sx.c0 / c); rc == 0 && (int64_t)tx * c < sx.c1; tx++)
            rc = r == 0 ? emit_base_tile(p, worker, s, rx0, ry0, tx, ty, err)
                        : emit_working_tile(p, worker, s, &s->w[r], level, tx, ty, err);
    return rc;
}

static int store_next_pass(const struct vt_pyramid_pass *p, unsigned worker,
                           struct vt_pyramid_block_scratch *s, uint32_t bx, uint32_t by,
                           struct vts_error *err)
{
    const struct vt_fregion *w = &s->w[p->depth];
    struct span sx = block_span(p, bx, p->depth, p->w), sy = block_span(p, by, p->depth, p->h);
    if (p->carry) {
        if (sx.inner <= sx.c0 || sy.inner <= sy.c0)
            return 0;
        const float *first =
            w->px + ((size_t)(sy.c0 - w->y0) * w->width + (size_t)(sx.c0 - w->x0)) * w->channels;
        return p->o->carry(p->o->user, worker, (uint32_t)sx.c0, (uint32_t)sy.c0,
                           (uint32_t)(sx.inner - sx.c0), (uint32_t)(sy.inner - sy.c0), w->channels,
                           first, (size_t)w->width * w->channels, err);
    }
    if (sx.inner <= sx.c0 || sy.inner <= sy.c0)
        return 0;
    const float *first =
        w->px + ((size_t)(sy.c0 - w->y0) * w->width + (size_t)(sx.c0 - w->x0)) * w->channels;
    return vt_float_file_write(p->next, (uint32_t)sx.c0, (uint32_t)sy.c0,
                               (uint32_t)(sx.inner - sx.c0), (uint32_t)(sy.inner - sy.c0), first,
                               (size_t)w->width * w->channels, err);
}

/* End of the texels relative level r must hold: its whole tiles, and at least twice the end of
 * level r + 1 (with --wrap, coarser tiles past the edge are computed from finer texels past it). */
static int64_t region_end(const struct vt_pyramid_pass *p, uint32_t b, uint32_t r, uint32_t size)
{
    int64_t end = block_span(p, b, r, size).c1;
    if (r < p->depth) {
        int64_t coarser = 2 * region_end(p, b, r + 1, size);
        end = coarser > end ? coarser : end;
    }
    return end;
}

void vt_pyramid_block_region(const struct vt_pyramid_pass *p, uint32_t bx, uint32_t by, uint32_t r,
                             struct vt_fregion *out)
{
    struct span sx = block_span(p, bx, r, p->w), sy = block_span(p, by, r, p->h);
    uint32_t m = p->margin[r];
    out->x0 = sx.c0 - m;
    out->y0 = sy.c0 - m;
    out->width = (uint32_t)(region_end(p, bx, r, p->w) - sx.c0) + 2 * m;
    out->height = (uint32_t)(region_end(p, by, r, p->h) - sy.c0) + 2 * m;
    out->channels = p->channels;
}

int vt_pyramid_block_run(const struct vt_pyramid_pass *p, struct vt_pyramid_block_scratch *s,
                         struct vt_source *src, unsigned worker, uint32_t bx, uint32_t by,
                         struct vts_error *err)
{
    struct vt_fregion r0;
    vt_pyramid_block_region(p, bx, by, 0, &r0);
    struct vt_image *in = &s->block;
    *in = s->in;
    in->width = r0.width;
    in->height = r0.height;
    in->stride = r0.width * vt_image_texel_bytes(in); /* tight: it may double as working region */
    int rc = vt_pyramid_read_region(src, p->w, p->h, p->o->wrap, &s->read, r0.x0, r0.y0, in, err);
    if (rc == 0 && p->emit_base)
        rc = emit_level_tiles(p, worker, s, 0, bx, by, r0.x0, r0.y0, err);
    if (rc || (p->depth == 0 && !p->next && !p->carry))
        return rc;
    /* pass images are already in the working space; a stored block is read through stored */
    s->w[0] = (struct vt_fregion){r0.x0,     r0.y0,       r0.width,
                                  r0.height, p->channels, p->source_is_working ? in->pixels : NULL};
    struct vt_stored_rows stored = {in->pixels, in->stride, p->sample, &p->mode};
    for (uint32_t r = 1; rc == 0 && r <= p->depth; r++) {
        float *px = s->w[r].px;
        vt_pyramid_block_region(p, bx, by, r, &s->w[r]);
        s->w[r].px = px;
        struct vt_edges edges = {vt_pyramid_level_extent(p->w, r - 1),
                                 vt_pyramid_level_extent(p->h, r - 1), p->o->wrap, p->o->wrap};
        if (r == 1 && !p->source_is_working)
            rc = vt_filter_reduce_stored(&p->kernel, &edges, &s->w[0], &stored, &s->w[1],
                                         s->reduce_scratch, s->reduce_floats, err);
        else
            rc = vt_filter_reduce(&p->kernel, &edges, &s->w[r - 1], &s->w[r], s->reduce_scratch,
                                  s->reduce_floats, err);
        if (rc == 0 && p->o->colour == VTS_COLOUR_NORMAL)
            vt_filter_renormalize(&s->w[r]);
        if (rc == 0)
            rc = emit_level_tiles(p, worker, s, r, bx, by, 0, 0, err);
    }
    if (rc == 0 && (p->next || p->carry))
        rc = store_next_pass(p, worker, s, bx, by, err);
    return rc;
}
