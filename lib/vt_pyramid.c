#include "vt_pyramid.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vt_checked.h"
#include "vt_float_file.h"
#include "vt_pool.h"
#include "vt_tile_cache.h"

#define DEFAULT_LEVELS_PER_PASS 2
#define MAX_LEVELS_PER_PASS     6
#define BAND_ROWS               16 /* coarser rows reduced from one converted band of input rows */
#define INPUT_CACHE_BYTES       (48u << 20) /* decoded input tiles shared by the workers */

/* One stretch of a region along one axis: dst positions [dst, dst + len) read source positions
 * [src, src + len), or all repeat source position src when replicate (clamped edge). */
struct segment {
    int64_t dst;
    uint32_t src, len;
    bool replicate;
};

struct scratch {
    struct vt_image in;                           /* allocation for block + margin */
    struct vt_image block;                        /* the current block: a tight view of in */
    struct vt_fregion w[MAX_LEVELS_PER_PASS + 1]; /* working regions per relative level */
    float *reduce_scratch;
    size_t reduce_floats;
    uint32_t band_rows;              /* rows of the w[0] band buffer (native sources) */
    struct vt_image tile_full, tile; /* payload in out sample: source channels / out channels */
    struct segment *xs, *ys;
    size_t seg_cap;
};

struct band {
    struct vt_image img; /* full-width rows [y0, y0 + img.height) */
    int64_t y0;
    bool valid;
};

struct pass {
    const struct vt_pyramid_options *o;
    struct vt_source *const *sources;
    struct vt_source band_source; /* reads from band for sequential inputs */
    struct band band;
    bool sequential;
    bool source_is_working;
    bool emit_base;
    bool carry;              /* a shard: the last level goes to o->carry instead of a next pass */
    uint32_t base, depth, k; /* base level, levels reduced here, levels per pass */
    uint32_t w, h, channels, sample;
    uint64_t block; /* S = content << k */
    uint32_t margin[MAX_LEVELS_PER_PASS + 1];
    uint32_t blocks_x, blocks_y, row, next_bx;
    uint32_t bx0, bx1, by0, by1; /* the blocks this pass runs */
    struct vt_kernel kernel;
    struct vt_pixel_mode mode;
    struct vt_float_file *next;
    struct scratch *scratch;
    unsigned threads;
    uint64_t *done, total;
};

static uint32_t level_extent(uint32_t size, uint32_t level)
{
    return (uint32_t)(((uint64_t)size + (1ull << level) - 1) >> level);
}

static uint32_t resolved_levels_per_pass(const struct vt_pyramid_options *o)
{
    uint32_t k = o->levels_per_pass ? o->levels_per_pass : DEFAULT_LEVELS_PER_PASS;
    return k > MAX_LEVELS_PER_PASS ? MAX_LEVELS_PER_PASS : k;
}

void vt_pyramid_plan(const struct vt_pyramid_options *o, struct vt_pyramid_plan *out)
{
    uint32_t k = resolved_levels_per_pass(o);
    uint64_t block = (uint64_t)o->tile_content_px << k;
    *out = (struct vt_pyramid_plan){.levels_per_pass = k,
                                    .has_next = o->level_count > k + 1,
                                    .block = block,
                                    .blocks_x = (uint32_t)((o->width + block - 1) / block),
                                    .blocks_y = (uint32_t)((o->height + block - 1) / block)};
    if (out->has_next) {
        out->carry_width = level_extent(o->width, k);
        out->carry_height = level_extent(o->height, k);
    }
}

bool vt_pyramid_part(const struct vt_pyramid_plan *plan, uint32_t index, uint32_t count,
                     uint32_t *x0, uint32_t *y0, uint32_t *x1, uint32_t *y1)
{
    if (count == 0 || (count & (count - 1)) != 0 || index >= count)
        return false;
    uint32_t m = 0;
    while ((1u << m) < count)
        m++;
    uint32_t gx = 1u << ((m + 1) / 2), gy = 1u << (m / 2);
    uint32_t px = (plan->blocks_x + gx - 1) / gx, py = (plan->blocks_y + gy - 1) / gy;
    uint32_t col = index % gx, row = index / gx;
    uint64_t a = (uint64_t)col * px, b = (uint64_t)(col + 1) * px;
    *x0 = (uint32_t)(a < plan->blocks_x ? a : plan->blocks_x);
    *x1 = (uint32_t)(b < plan->blocks_x ? b : plan->blocks_x);
    a = (uint64_t)row * py, b = (uint64_t)(row + 1) * py;
    *y0 = (uint32_t)(a < plan->blocks_y ? a : plan->blocks_y);
    *y1 = (uint32_t)(b < plan->blocks_y ? b : plan->blocks_y);
    return true;
}

/* Tiles of a level-r axis that blocks [b0, b1) own (the whole axis: 0 .. blocks). */
static uint64_t part_tiles(uint32_t size, uint32_t r, uint64_t block, uint32_t c, uint32_t b0,
                           uint32_t b1)
{
    uint64_t s = block >> r, extent = level_extent(size, r);
    uint64_t tiles_end = (extent + c - 1) / c * c, c0 = (uint64_t)b0 * s, c1 = (uint64_t)b1 * s;
    c1 = c1 < tiles_end ? c1 : tiles_end;
    return c0 < c1 ? (c1 - c0 + c - 1) / c : 0;
}

uint64_t vt_pyramid_tile_count(const struct vt_pyramid_options *o)
{
    struct vt_pyramid_plan plan;
    vt_pyramid_plan(o, &plan);
    uint32_t k = plan.levels_per_pass, first = o->resume_input ? k + 1 : 0;
    uint64_t n = 0;
    for (uint32_t l = first; l < o->level_count; l++) {
        uint64_t tx = (level_extent(o->width, l) + o->tile_content_px - 1) / o->tile_content_px;
        uint64_t ty = (level_extent(o->height, l) + o->tile_content_px - 1) / o->tile_content_px;
        if (o->part) {
            if (l > k)
                break;
            tx = part_tiles(o->width, l, plan.block, o->tile_content_px, o->part_x0, o->part_x1);
            ty = part_tiles(o->height, l, plan.block, o->tile_content_px, o->part_y0, o->part_y1);
        }
        n += tx * ty;
    }
    return n;
}

/* Splits [a, b) of an axis of size n into read runs and clamped (replicated) edges, or wrapped
 * runs. Returns the number of segments (at most cap). */
static size_t make_segments(int64_t a, int64_t b, uint32_t n, bool wrap, struct segment *seg,
                            size_t cap)
{
    size_t k = 0;
    if (!wrap) {
        if (a < 0)
            seg[k++] = (struct segment){0, 0, (uint32_t)((b < 0 ? b : 0) - a), true};
        int64_t lo = a < 0 ? 0 : a, hi = b > n ? n : b;
        if (lo < hi)
            seg[k++] = (struct segment){lo - a, (uint32_t)lo, (uint32_t)(hi - lo), false};
        if (b > n)
            seg[k++] =
                (struct segment){(a > n ? a : n) - a, n - 1, (uint32_t)(b - (a > n ? a : n)), true};
        return k;
    }
    for (int64_t p = a; p < b && k < cap;) {
        int64_t s = ((p % n) + n) % n;
        int64_t len = b - p < (int64_t)n - s ? b - p : (int64_t)n - s;
        seg[k++] = (struct segment){p - a, (uint32_t)s, (uint32_t)len, false};
        p += len;
    }
    return k;
}

static struct vt_image view_of(const struct vt_image *img, int64_t x, int64_t y, uint32_t w,
                               uint32_t h)
{
    struct vt_image v = *img;
    v.pixels = vt_image_at(img, (uint32_t)x, (uint32_t)y);
    v.width = w;
    v.height = h;
    return v;
}

/* Reads positions [x0, x0 + dst.width) x [y0, ...) of the pass source into dst, clamping or
 * wrapping positions outside the image. */
static int read_region(struct pass *p, struct scratch *s, struct vt_source *src, int64_t x0,
                       int64_t y0, struct vt_image *dst, struct vt_error *err)
{
    bool wrap = p->o->wrap;
    size_t nx = make_segments(x0, x0 + dst->width, p->w, wrap, s->xs, s->seg_cap);
    size_t ny = make_segments(y0, y0 + dst->height, p->h, wrap, s->ys, s->seg_cap);
    size_t tb = vt_image_texel_bytes(dst);
    for (size_t j = 0; j < ny; j++) {
        if (s->ys[j].replicate)
            continue;
        for (size_t i = 0; i < nx; i++) {
            if (s->xs[i].replicate)
                continue;
            struct vt_image v =
                view_of(dst, s->xs[i].dst, s->ys[j].dst, s->xs[i].len, s->ys[j].len);
            int rc = vt_source_read(src, s->xs[i].src, s->ys[j].src, &v, err);
            if (rc)
                return rc;
        }
    }
    if (wrap)
        return 0;
    /* clamp: replicate the edge column into x margins, then the edge row into y margins */
    for (size_t j = 0; j < ny; j++) {
        if (s->ys[j].replicate)
            continue;
        for (uint32_t r = 0; r < s->ys[j].len; r++) {
            uint32_t y = (uint32_t)s->ys[j].dst + r;
            for (size_t i = 0; i < nx; i++) {
                if (!s->xs[i].replicate)
                    continue;
                int64_t edge = s->xs[i].dst == 0 ? s->xs[i].len : s->xs[i].dst - 1;
                const unsigned char *e = vt_image_at(dst, (uint32_t)edge, y);
                for (uint32_t c = 0; c < s->xs[i].len; c++)
                    memcpy(vt_image_at(dst, (uint32_t)s->xs[i].dst + c, y), e, tb);
            }
        }
    }
    for (size_t j = 0; j < ny; j++) {
        if (!s->ys[j].replicate)
            continue;
        int64_t edge = s->ys[j].dst == 0 ? s->ys[j].len : s->ys[j].dst - 1;
        for (uint32_t r = 0; r < s->ys[j].len; r++)
            memcpy(vt_image_at(dst, 0, (uint32_t)s->ys[j].dst + r),
                   vt_image_at(dst, 0, (uint32_t)edge), tb * dst->width);
    }
    return 0;
}

/* ---- bands: full-width rows of a sequential source, moved down without re-reading ---- */

static int band_read_region(void *ctx, uint32_t x, uint32_t y, struct vt_image *dst,
                            struct vt_error *err)
{
    const struct band *b = ctx;
    if ((int64_t)y < b->y0 || (int64_t)y + dst->height > b->y0 + b->img.height)
        return vt_error_set(err, VT_ERR_ARG, "rows %u..%u are outside the band", y,
                            y + dst->height);
    size_t row = vt_image_texel_bytes(dst) * dst->width;
    for (uint32_t r = 0; r < dst->height; r++)
        memcpy((char *)dst->pixels + (size_t)r * dst->stride,
               vt_image_at(&b->img, x, (uint32_t)(y - b->y0) + r), row);
    return 0;
}

static void band_close(void *ctx)
{
    (void)ctx;
}

static const struct vt_source_ops band_ops = {band_read_region, band_close};

/* Makes the band hold source rows [a, b): keeps the rows it already has, reads the rest in one
 * top-down region read. */
static int band_move(struct pass *p, int64_t a, int64_t b, struct vt_error *err)
{
    struct band *old = &p->band, nb = {.y0 = a, .valid = true};
    int rc = vt_image_alloc(&nb.img, p->w, (uint32_t)(b - a), p->channels, p->sample, err);
    if (rc)
        return rc;
    /* bands move down: rows [a, keep_hi) are already in the old band, the rest is read */
    int64_t old_end = old->valid ? old->y0 + old->img.height : a;
    bool can_keep = old->valid && a >= old->y0 && a < old_end;
    int64_t keep_hi = can_keep ? (old_end < b ? old_end : b) : a;
    for (int64_t y = a; y < keep_hi; y++)
        memcpy(vt_image_at(&nb.img, 0, (uint32_t)(y - a)),
               vt_image_at(&old->img, 0, (uint32_t)(y - old->y0)),
               vt_image_texel_bytes(&nb.img) * p->w);
    if (keep_hi < b) {
        struct vt_image v = view_of(&nb.img, 0, keep_hi - a, p->w, (uint32_t)(b - keep_hi));
        rc = vt_source_read(p->sources[0], 0, (uint32_t)keep_hi, &v, err);
    }
    vt_image_release(&old->img);
    *old = nb;
    if (rc) {
        vt_image_release(&old->img);
        old->valid = false;
    }
    return rc;
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

static int emit_tile(struct pass *p, unsigned worker, struct scratch *s, uint32_t level,
                     uint32_t tx, uint32_t ty, struct vt_error *err)
{
    const struct vt_pyramid_options *o = p->o;
    struct vt_image *t = o->out_channels == p->channels ? &s->tile_full : &s->tile;
    int rc = o->emit(o->user, worker, level, tx, ty, all_transparent(t) ? NULL : t, err);
    if (rc == 0)
        __atomic_add_fetch(p->done, 1, __ATOMIC_RELAXED);
    return rc;
}

/* Payload of tile (tx, ty) of the pass's base level, straight from the source texels. */
static int emit_base_tile(struct pass *p, unsigned worker, struct scratch *s, int64_t rx0,
                          int64_t ry0, uint32_t tx, uint32_t ty, struct vt_error *err)
{
    const struct vt_pyramid_options *o = p->o;
    uint32_t pp = o->tile_content_px + 2 * o->border_px;
    int64_t x = (int64_t)tx * o->tile_content_px - o->border_px - rx0;
    int64_t y = (int64_t)ty * o->tile_content_px - o->border_px - ry0;
    struct vt_image v = view_of(&s->block, x, y, pp, pp);
    if (o->out_sample == p->sample) {
        copy_channels(&v, &s->tile_full);
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
    return emit_tile(p, worker, s, p->base, tx, ty, err);
}

/* Payload of tile (tx, ty) of a reduced level from its working region. */
static int emit_working_tile(struct pass *p, unsigned worker, struct scratch *s,
                             const struct vt_fregion *w, uint32_t level, uint32_t tx, uint32_t ty,
                             struct vt_error *err)
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
    return emit_tile(p, worker, s, level, tx, ty, err);
}

/* ---- blocks ---- */

struct span {
    int64_t c0;    /* first texel the block owns at this level */
    int64_t c1;    /* end of its whole tiles (past the level's edge for the last tiles) */
    int64_t inner; /* end of the texels it owns inside the level */
};

static struct span block_span(const struct pass *p, uint32_t b, uint32_t r, uint32_t size)
{
    uint64_t s = p->block >> r, c = p->o->tile_content_px;
    uint64_t extent = level_extent(size, r), tiles_end = (extent + c - 1) / c * c;
    uint64_t end = (uint64_t)(b + 1) * s;
    return (struct span){(int64_t)((uint64_t)b * s), (int64_t)(end < tiles_end ? end : tiles_end),
                         (int64_t)(end < extent ? end : extent)};
}

static int emit_level_tiles(struct pass *p, unsigned worker, struct scratch *s, uint32_t r,
                            uint32_t bx, uint32_t by, int64_t rx0, int64_t ry0,
                            struct vt_error *err)
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

static int store_next_pass(struct pass *p, unsigned worker, struct scratch *s, uint32_t bx,
                           uint32_t by, struct vt_error *err)
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
    for (int64_t y = sy.c0; y < sy.inner; y++) {
        const float *row =
            w->px + ((size_t)(y - w->y0) * w->width + (size_t)(sx.c0 - w->x0)) * w->channels;
        int rc = vt_float_file_write(p->next, (uint32_t)sx.c0, (uint32_t)y, row,
                                     (uint32_t)(sx.inner - sx.c0), err);
        if (rc)
            return rc;
    }
    return 0;
}

/* End of the texels relative level r must hold: its whole tiles, and at least twice the end of
 * level r + 1 (with --wrap, coarser tiles past the edge are computed from finer texels past it). */
static int64_t region_end(const struct pass *p, uint32_t b, uint32_t r, uint32_t size)
{
    int64_t end = block_span(p, b, r, size).c1;
    if (r < p->depth) {
        int64_t coarser = 2 * region_end(p, b, r + 1, size);
        end = coarser > end ? coarser : end;
    }
    return end;
}

static void region_at(const struct pass *p, uint32_t bx, uint32_t by, uint32_t r,
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

static int64_t clamp_to(int64_t v, int64_t size, bool wrap)
{
    return wrap ? v : (v < 0 ? 0 : (v >= size ? size - 1 : v));
}

/* Reduces the native block `in` (region r0 of the base level) into s->w[1], converting to the
 * working space only the rows each band of BAND_ROWS coarser rows reads. Gives the same bits as
 * converting the whole block first (the reduction does not depend on how it is split), with a
 * working buffer of a few rows instead of the whole block. */
static int reduce_from_native(struct pass *p, struct scratch *s, const struct vt_image *in,
                              const struct vt_fregion *r0, const struct vt_edges *edges,
                              struct vt_error *err)
{
    const struct vt_kernel *k = &p->kernel;
    struct vt_fregion *dst = &s->w[1];
    int64_t coarse_h = level_extent(p->h, 1);
    for (uint32_t row = 0; row < dst->height; row += BAND_ROWS) {
        uint32_t rows = dst->height - row < BAND_ROWS ? dst->height - row : BAND_ROWS;
        int64_t a = dst->y0 + row, b = a + rows; /* coarser rows [a, b) */
        int64_t lo = clamp_to(2 * clamp_to(a, coarse_h, edges->wrap_y) + k->first, edges->level_h,
                              edges->wrap_y);
        int64_t hi =
            clamp_to(2 * clamp_to(b - 1, coarse_h, edges->wrap_y) + k->first + k->count - 1,
                     edges->level_h, edges->wrap_y) +
            1;
        if (lo < r0->y0 || hi > r0->y0 + r0->height || hi - lo > (int64_t)s->band_rows)
            return vt_error_set(err, VT_ERR_ARG, "band rows %lld..%lld outside the block",
                                (long long)lo, (long long)hi);
        struct vt_fregion band = {r0->x0,      lo,        r0->width, (uint32_t)(hi - lo),
                                  p->channels, s->w[0].px};
        vt_filter_to_working(&p->mode, p->sample, vt_image_at(in, 0, (uint32_t)(lo - r0->y0)),
                             band.px, (size_t)band.width * band.height);
        struct vt_fregion out = {dst->x0,       a,
                                 dst->width,    rows,
                                 dst->channels, dst->px + (size_t)row * dst->width * dst->channels};
        int rc = vt_filter_reduce(k, edges, &band, &out, s->reduce_scratch, s->reduce_floats, err);
        if (rc)
            return rc;
    }
    return 0;
}

static int do_block(struct pass *p, unsigned worker, uint32_t bx, uint32_t by, struct vt_error *err)
{
    struct scratch *s = &p->scratch[worker];
    struct vt_fregion r0;
    region_at(p, bx, by, 0, &r0);
    struct vt_image *in = &s->block;
    *in = s->in;
    in->width = r0.width;
    in->height = r0.height;
    in->stride = r0.width * vt_image_texel_bytes(in); /* tight: it may double as working region */
    struct vt_source *src = p->sequential ? &p->band_source : p->sources[worker];
    int rc = read_region(p, s, src, r0.x0, r0.y0, in, err);
    if (rc == 0 && p->emit_base)
        rc = emit_level_tiles(p, worker, s, 0, bx, by, r0.x0, r0.y0, err);
    if (rc || (p->depth == 0 && !p->next && !p->carry))
        return rc;
    if (p->source_is_working) /* pass images are already in the working space */
        s->w[0] = (struct vt_fregion){r0.x0, r0.y0, r0.width, r0.height, p->channels, in->pixels};
    for (uint32_t r = 1; rc == 0 && r <= p->depth; r++) {
        float *px = s->w[r].px;
        region_at(p, bx, by, r, &s->w[r]);
        s->w[r].px = px;
        struct vt_edges edges = {level_extent(p->w, r - 1), level_extent(p->h, r - 1), p->o->wrap,
                                 p->o->wrap};
        if (r == 1 && !p->source_is_working)
            rc = reduce_from_native(p, s, in, &r0, &edges, err);
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

/* ---- passes ---- */

static void scratch_free(struct pass *p)
{
    for (unsigned i = 0; p->scratch && i < p->threads; i++) {
        struct scratch *s = &p->scratch[i];
        vt_image_release(&s->in);
        for (uint32_t r = p->source_is_working ? 1 : 0; r <= MAX_LEVELS_PER_PASS; r++)
            free(s->w[r].px);
        free(s->reduce_scratch);
        vt_image_release(&s->tile_full);
        vt_image_release(&s->tile);
        free(s->xs);
        free(s->ys);
    }
    free(p->scratch);
    p->scratch = NULL;
}

/* Largest region of relative level r over all blocks: a full block plus margins. */
static void max_region(const struct pass *p, uint32_t r, struct vt_fregion *out)
{
    uint32_t m = p->margin[r];
    uint64_t s = p->block >> r;
    out->x0 = out->y0 = 0;
    out->width = out->height = (uint32_t)s + 2 * m;
    out->channels = p->channels;
}

static int scratch_alloc(struct pass *p, struct vt_error *err)
{
    const struct vt_pyramid_options *o = p->o;
    uint32_t pp = o->tile_content_px + 2 * o->border_px;
    p->scratch = calloc(p->threads, sizeof *p->scratch);
    if (!p->scratch)
        return vt_error_set(err, VT_ERR_NOMEM, "out of memory for %u workers", p->threads);
    struct vt_fregion big;
    max_region(p, 0, &big);
    for (unsigned i = 0; i < p->threads; i++) {
        struct scratch *s = &p->scratch[i];
        int rc = vt_image_alloc(&s->in, big.width, big.height, p->channels, p->sample, err);
        if (rc == 0)
            rc = vt_image_alloc(&s->tile_full, pp, pp, p->channels, o->out_sample, err);
        if (rc == 0)
            rc = vt_image_alloc(&s->tile, pp, pp, o->out_channels, o->out_sample, err);
        if (rc)
            return rc;
        s->seg_cap = (size_t)big.width + 4;
        s->xs = calloc(s->seg_cap, sizeof *s->xs);
        s->ys = calloc(s->seg_cap, sizeof *s->ys);
        bool ok = s->xs && s->ys;
        size_t floats = 0;
        for (uint32_t r = 0; ok && r <= p->depth; r++) {
            struct vt_fregion reg;
            max_region(p, r, &reg);
            if (r == 0 && !p->source_is_working) /* a band of rows, see reduce_from_native */
                reg.height = s->band_rows = 2 * BAND_ROWS + (uint32_t)p->kernel.count;
            if (r > 0 || !p->source_is_working) {
                size_t n;
                ok = vt_size_mul3(reg.width, reg.height, p->channels, &n) &&
                     (s->w[r].px = malloc(n * sizeof(float))) != NULL;
            }
            if (r > 0) {
                struct vt_fregion fine;
                max_region(p, r - 1, &fine);
                size_t need = vt_filter_reduce_scratch(&p->kernel, &fine, &reg);
                floats = need > floats ? need : floats;
            }
        }
        s->reduce_floats = floats;
        if (ok && floats)
            ok = (s->reduce_scratch = malloc(floats * sizeof(float))) != NULL;
        if (!ok)
            return vt_error_set(err, VT_ERR_NOMEM,
                                "out of memory for the working blocks of %ux%u "
                                "texels",
                                big.width, big.height);
    }
    return 0;
}

static bool next_block(void *ctx, uint64_t *job)
{
    struct pass *p = ctx;
    if (p->next_bx >= p->bx1)
        return false;
    *job = p->next_bx++;
    return true;
}

static int run_block(void *ctx, unsigned worker, uint64_t job, struct vt_error *err)
{
    struct pass *p = ctx;
    return do_block(p, worker, (uint32_t)job, p->row, err);
}

static int report_progress(void *ctx)
{
    struct pass *p = ctx;
    if (!p->o->progress)
        return 0;
    return p->o->progress(p->o->user, __atomic_load_n(p->done, __ATOMIC_RELAXED), p->total);
}

static int run_pass(struct pass *p, struct vt_error *err)
{
    const struct vt_pyramid_options *o = p->o;
    uint32_t km = vt_kernel_margin(&p->kernel);
    p->margin[p->depth] = o->border_px;
    for (uint32_t r = p->depth; r-- > 0;) {
        uint32_t m = 2 * p->margin[r + 1] + km;
        p->margin[r] = m > o->border_px ? m : o->border_px;
    }
    p->blocks_x = (uint32_t)((p->w + p->block - 1) / p->block);
    p->blocks_y = (uint32_t)((p->h + p->block - 1) / p->block);
    bool part = o->part && p->base == 0 && !o->resume_input;
    p->bx0 = part ? o->part_x0 : 0;
    p->bx1 = part ? (o->part_x1 < p->blocks_x ? o->part_x1 : p->blocks_x) : p->blocks_x;
    p->by0 = part ? o->part_y0 : 0;
    p->by1 = part ? (o->part_y1 < p->blocks_y ? o->part_y1 : p->blocks_y) : p->blocks_y;
    if (p->bx0 >= p->bx1 || p->by0 >= p->by1) /* an empty part */
        return 0;
    int rc = scratch_alloc(p, err);
    static const struct vt_pool_fns fns = {next_block, run_block, report_progress};
    for (uint32_t by = p->by0; rc == 0 && by < p->by1; by++) {
        if (p->sequential) {
            struct vt_fregion r0;
            region_at(p, 0, by, 0, &r0);
            int64_t a = r0.y0, b = r0.y0 + r0.height;
            if (o->wrap && (a < 0 || b > p->h))
                a = 0, b = p->h; /* wrapped rows come from both ends: hold the whole image */
            a = a < 0 ? 0 : a;
            b = b > p->h ? p->h : b;
            rc = band_move(p, a, b, err);
        }
        p->row = by;
        p->next_bx = p->bx0;
        if (rc == 0)
            rc = vt_pool_run(p->threads, &fns, p, err);
    }
    scratch_free(p);
    vt_image_release(&p->band.img);
    p->band.valid = false;
    return rc;
}

static int check_options(struct vt_source *const *sources, const struct vt_pyramid_options *o,
                         struct vt_error *err)
{
    const struct vt_source_info *in = o->resume_input ? o->resume_input : &sources[0]->info;
    uint32_t full = vts_full_level_count(o->width, o->height, o->tile_content_px);
    if (!o->emit || o->threads < 1 || o->tile_content_px == 0 || o->level_count == 0 ||
        o->level_count > full ||
        (!o->resume_input && (in->width != o->width || in->height != o->height)) ||
        vts_sample_bytes(o->out_sample) == 0 || in->channels < 1 || in->channels > 4 ||
        (o->part && o->resume_input) ||
        (o->part && o->level_count > resolved_levels_per_pass(o) + 1 && !o->carry))
        return vt_error_set(err, VT_ERR_ARG, "invalid pyramid options");
    if (o->resume_input) {
        struct vt_pyramid_plan plan;
        vt_pyramid_plan(o, &plan);
        const struct vt_source_info *r = &sources[0]->info;
        if (!plan.has_next || r->width != plan.carry_width || r->height != plan.carry_height ||
            r->channels != in->channels || r->sample != VTS_SAMPLE_F32)
            return vt_error_set(err, VT_ERR_ARG,
                                "'%s': %ux%u texels of %u channels, %s, cannot resume a "
                                "%ux%u build of %u channels at level %u",
                                sources[0]->name, r->width, r->height, r->channels,
                                vts_sample_name(r->sample), o->width, o->height, in->channels,
                                plan.levels_per_pass);
        for (unsigned i = 0; i < o->threads; i++)
            if (!sources[i])
                return vt_error_set(err, VT_ERR_ARG, "resuming needs one source per worker");
    }
    if (o->out_channels != in->channels && !(in->has_alpha && o->out_channels == in->channels - 1))
        return vt_error_set(err, VT_ERR_ARG, "cannot make %u channels from %u", o->out_channels,
                            in->channels);
    if (o->tile_content_px + 2ull * o->border_px > VTS_MAX_PAYLOAD_PX)
        return vt_error_set(err, VT_ERR_LIMIT, "tile payload is larger than %u px",
                            VTS_MAX_PAYLOAD_PX);
    for (unsigned i = 0; !in->sequential && i < o->threads; i++)
        if (!sources[i])
            return vt_error_set(err, VT_ERR_ARG,
                                "a random-access input needs one source per "
                                "worker");
    return 0;
}

int vt_pyramid_build(struct vt_source *const *sources, const struct vt_pyramid_options *o,
                     struct vt_error *err)
{
    int rc = check_options(sources, o, err);
    if (rc)
        return rc;
    const struct vt_source_info *in = o->resume_input ? o->resume_input : &sources[0]->info;
    uint32_t k = resolved_levels_per_pass(o);
    uint64_t done = 0;
    struct pass p = {.o = o,
                     .sources = sources,
                     .sequential = in->sequential,
                     .emit_base = true,
                     .k = k,
                     .w = o->width,
                     .h = o->height,
                     .channels = in->channels,
                     .sample = in->sample,
                     .block = (uint64_t)o->tile_content_px << k,
                     .threads = o->threads,
                     .done = &done,
                     .total = vt_pyramid_tile_count(o)};
    /* premultiply while filtering, unless the input already is (then it is filtered and stored
     * premultiplied, and the layer says so) */
    p.mode =
        (struct vt_pixel_mode){in->channels, o->colour,
                               in->has_alpha && !in->premultiplied && o->colour != VTS_COLOUR_DATA};
    vt_kernel_init(&p.kernel, o->filter);
    if (o->resume_input) { /* as after the first pass: read its last level, in working space */
        p.sequential = false;
        p.source_is_working = true;
        p.emit_base = false;
        p.base = k;
        p.w = level_extent(o->width, k);
        p.h = level_extent(o->height, k);
        p.sample = VTS_SAMPLE_F32;
    }
    p.band_source = (struct vt_source){.info = *in, .ops = &band_ops, .ctx = &p.band};
    snprintf(p.band_source.name, sizeof p.band_source.name, "%s", sources[0]->name);
    struct vt_float_file *prev = NULL;
    struct vt_source temp_source = {0};
    struct vt_source **temp_sources = NULL;
    /* tiled inputs: workers share decoded tiles, so block margins do not decode tiles twice */
    struct vt_source cached[256], *cached_ptrs[256];
    struct vt_tile_cache *cache = NULL;
    if (!o->resume_input && !in->sequential && in->tile_w && in->tile_h && o->threads <= 256) {
        cache = vt_tile_cache_create(sources, o->threads, INPUT_CACHE_BYTES, cached, err);
        if (!cache)
            return err ? err->status : VT_ERR_NOMEM;
        for (unsigned i = 0; i < o->threads; i++)
            cached_ptrs[i] = &cached[i];
        p.sources = cached_ptrs;
    }
    for (;;) {
        uint32_t left = o->level_count - 1 - p.base;
        p.depth = left < k ? left : k;
        p.next = NULL;
        p.carry = o->part && p.depth < left;
        if (p.depth < left && !o->part) {
            p.next = vt_float_file_create(o->temp_dir, level_extent(p.w, p.depth),
                                          level_extent(p.h, p.depth), p.channels, err);
            if (!p.next) {
                rc = err ? err->status : VT_ERR_IO;
                break;
            }
        }
        rc = run_pass(&p, err);
        vt_tile_cache_destroy(cache); /* only pass 0 reads the input */
        cache = NULL;
        vt_source_close(&temp_source);
        vt_float_file_destroy(prev);
        prev = p.next;
        if (rc || !p.next) /* a shard (o->part) stops after its first pass */
            break;
        /* the next pass reads this pass's last level, already in working space */
        free(temp_sources);
        temp_sources = calloc(o->threads, sizeof *temp_sources);
        if (!temp_sources) {
            rc = vt_error_set(err, VT_ERR_NOMEM, "out of memory");
            break;
        }
        vt_float_file_source(p.next, o->colour, in->has_alpha, &temp_source, err);
        for (unsigned i = 0; i < o->threads; i++)
            temp_sources[i] = &temp_source;
        p.sources = temp_sources;
        p.sequential = false;
        p.source_is_working = true;
        p.emit_base = false;
        p.base += p.depth;
        p.w = level_extent(p.w, p.depth);
        p.h = level_extent(p.h, p.depth);
        p.sample = VTS_SAMPLE_F32;
    }
    vt_tile_cache_destroy(cache);
    vt_source_close(&temp_source);
    vt_float_file_destroy(prev);
    free(temp_sources);
    return rc;
}
