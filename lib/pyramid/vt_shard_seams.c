/* The levels above a sharded build's first pass, computed by the shards and, along the seams, by
 * the merge (see internal/vt_shard_seams.h). */
#include "internal/vt_shard_seams.h"

#include <stdlib.h>
#include <string.h>

#include "internal/vt_float_file.h"
#include "internal/vt_pyramid_impl.h"
#include "internal/vt_pyramid_read.h"
#include "vt_checked.h"
#include "vt_error.h"
#include "vt_pool.h"
#include "vts.h"

#define GRID_MAX      64u /* parts per axis: 4096 shards are 64 x 64 */
#define LIST_CAP      (4u * GRID_MAX + 16u)
#define LEVEL_MEM_MAX ((size_t)64 << 20) /* levels in memory: bounded whatever the image size */
#define BAND_ROWS     32u /* coarser rows reduced per job (one read of the finer level) */

struct ival {
    int64_t a, b; /* [a, b) */
};

/* Sorted disjoint intervals; an interval that does not fit widens the last one (a superset is
 * always safe: it only carries more). */
struct ilist {
    uint32_t n;
    struct ival v[LIST_CAP];
};

/* One axis of the build: level extents, the interval each part column (row) computes exactly at
 * each level, and the texels of each level the merge needs. */
struct axis {
    uint32_t parts;
    int64_t ext[VTS_MAX_LEVELS];
    struct ival r[VTS_MAX_LEVELS][GRID_MAX];
    struct ilist need[VTS_MAX_LEVELS];
};

struct vt_seams {
    const struct vt_pyramid_options *o;
    struct vt_kernel kernel;
    struct vt_pixel_mode mode;
    uint32_t k, levels, c, border, channels;
    bool has_alpha;    /* tiles of alpha 0 are left empty only then (as vt_pyramid_block.c) */
    size_t mem_max;    /* bytes of a level held in memory, else in a file (LEVEL_MEM_MAX) */
    struct axis ax[2]; /* x, y */
};

static int64_t floor_div2(int64_t v)
{
    return v >= 0 ? v / 2 : -((-v + 1) / 2);
}

static int64_t clamp64(int64_t v, int64_t lo, int64_t hi)
{
    return v < lo ? lo : (v > hi ? hi : v);
}

static void list_add(struct ilist *l, int64_t a, int64_t b)
{
    if (a >= b)
        return;
    if (l->n < LIST_CAP) {
        l->v[l->n++] = (struct ival){a, b};
        return;
    }
    struct ival *last = &l->v[l->n - 1];
    last->a = a < last->a ? a : last->a;
    last->b = b > last->b ? b : last->b;
}

static int cmp_ival(const void *pa, const void *pb)
{
    const struct ival *a = pa, *b = pb;
    return a->a < b->a ? -1 : (a->a > b->a ? 1 : 0);
}

static void list_normalize(struct ilist *l)
{
    qsort(l->v, l->n, sizeof l->v[0], cmp_ival);
    uint32_t n = 0;
    for (uint32_t i = 0; i < l->n; i++) {
        if (n > 0 && l->v[i].a <= l->v[n - 1].b) {
            if (l->v[i].b > l->v[n - 1].b)
                l->v[n - 1].b = l->v[i].b;
        } else {
            l->v[n++] = l->v[i];
        }
    }
    l->n = n;
}

/* Hull of the part of l inside [a, b) (empty: a >= b). */
static struct ival list_hull_in(const struct ilist *l, int64_t a, int64_t b)
{
    struct ival h = {INT64_MAX, INT64_MIN};
    for (uint32_t i = 0; i < l->n; i++) {
        int64_t lo = l->v[i].a > a ? l->v[i].a : a, hi = l->v[i].b < b ? l->v[i].b : b;
        if (lo < hi) {
            h.a = lo < h.a ? lo : h.a;
            h.b = hi > h.b ? hi : h.b;
        }
    }
    return h.a < h.b ? h : (struct ival){0, 0};
}

/* Finer texels (clamped to [0, fine)) that coarser texels [a, b) read. */
static struct ival window(const struct vt_kernel *k, int64_t a, int64_t b, int64_t fine)
{
    return (struct ival){clamp64(2 * a + k->first, 0, fine - 1),
                         clamp64(2 * (b - 1) + k->first + k->count - 1, 0, fine - 1) + 1};
}

/* Coarser texels of [0, coarse) whose window lies inside [a, b) of the finer level. */
static struct ival inside(const struct vt_kernel *k, struct ival f, int64_t fine, int64_t coarse)
{
    if (f.a >= f.b)
        return (struct ival){0, 0};
    int64_t lo = f.a == 0 ? 0 : -floor_div2(-(f.a - k->first));
    int64_t hi = f.b == fine ? coarse : floor_div2(f.b - k->first - k->count) + 1;
    lo = lo < 0 ? 0 : lo;
    hi = hi > coarse ? coarse : hi;
    return lo < hi ? (struct ival){lo, hi} : (struct ival){0, 0};
}

/* Part index whose interval holds the (clamped) payload of tile t at level l, or -1. */
static int tile_owner(const struct vt_seams *s, const struct axis *x, uint32_t l, int64_t t)
{
    int64_t lo = clamp64(t * s->c - s->border, 0, x->ext[l]);
    int64_t hi = clamp64((t + 1) * s->c + s->border, 0, x->ext[l]);
    for (uint32_t i = 0; i < x->parts; i++)
        if (x->r[l][i].a <= lo && hi <= x->r[l][i].b && x->r[l][i].a < x->r[l][i].b)
            return (int)i;
    return -1;
}

static int64_t tiles_of(const struct vt_seams *s, const struct axis *x, uint32_t l)
{
    return (x->ext[l] + s->c - 1) / s->c;
}

/* Intervals of [0, ext) no part computes at level l, into g. */
static void gaps(const struct axis *x, uint32_t l, struct ilist *g)
{
    int64_t at = 0;
    g->n = 0;
    for (uint32_t i = 0; i < x->parts; i++) {
        if (x->r[l][i].a >= x->r[l][i].b)
            continue;
        list_add(g, at, x->r[l][i].a);
        at = x->r[l][i].b;
    }
    list_add(g, at, x->ext[l]);
}

static void axis_init(struct vt_seams *s, struct axis *x, uint32_t size, const uint32_t *cuts,
                      uint32_t parts)
{
    x->parts = parts;
    for (uint32_t l = 0; l < s->levels; l++)
        x->ext[l] = vt_pyramid_level_extent(size, l);
    for (uint32_t i = 0; i < parts; i++) {
        int64_t a = (int64_t)cuts[i] * s->c, b = (int64_t)cuts[i + 1] * s->c;
        x->r[s->k][i] =
            (struct ival){a < x->ext[s->k] ? a : x->ext[s->k], b < x->ext[s->k] ? b : x->ext[s->k]};
        for (uint32_t l = s->k + 1; l < s->levels; l++)
            x->r[l][i] = inside(&s->kernel, x->r[l - 1][i], x->ext[l - 1], x->ext[l]);
    }
    /* what the merge reads, from the top down: the payloads of the tiles no part can emit, and
     * the windows of the texels no part can compute at the next level */
    struct ilist g;
    for (uint32_t l = s->levels; l-- > s->k;) {
        struct ilist *n = &x->need[l];
        n->n = 0;
        for (int64_t t = 0; l > s->k && t < tiles_of(s, x, l); t++)
            if (tile_owner(s, x, l, t) < 0)
                list_add(n, clamp64(t * s->c - s->border, 0, x->ext[l]),
                         clamp64((t + 1) * s->c + s->border, 0, x->ext[l]));
        if (l + 1 < s->levels) {
            gaps(x, l + 1, &g);
            for (uint32_t i = 0; i < g.n; i++) {
                struct ival w = window(&s->kernel, g.v[i].a, g.v[i].b, x->ext[l]);
                list_add(n, w.a, w.b);
            }
        }
        list_normalize(n);
    }
}

struct vt_seams *vt_seams_create(const struct vt_pyramid_options *o,
                                 const struct vt_source_info *in, const uint32_t *xcuts,
                                 uint32_t gx, const uint32_t *ycuts, uint32_t gy,
                                 struct vts_error *err)
{
    if (o->wrap || gx < 1 || gx > GRID_MAX || gy < 1 || gy > GRID_MAX ||
        o->level_count > VTS_MAX_LEVELS || o->tile_content_px == 0) {
        vt_error_set(err, VTS_ERR_ARG, "invalid options for the seams of a sharded build");
        return NULL;
    }
    struct vt_seams *s = calloc(1, sizeof *s);
    if (!s) {
        vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
        return NULL;
    }
    s->o = o;
    s->k = vt_pyramid_resolved_k(o);
    s->levels = o->level_count;
    s->c = o->tile_content_px;
    s->border = o->border_px;
    s->channels = in->channels;
    s->has_alpha = in->has_alpha;
    s->mem_max = LEVEL_MEM_MAX;
    vt_kernel_init(&s->kernel, o->filter);
    s->mode =
        (struct vt_pixel_mode){in->channels, o->colour,
                               in->has_alpha && !in->premultiplied && o->colour != VTS_COLOUR_DATA};
    if (s->levels > s->k + 1) {
        axis_init(s, &s->ax[0], o->width, xcuts, gx);
        axis_init(s, &s->ax[1], o->height, ycuts, gy);
    }
    return s;
}

void vt_seams_set_memory(struct vt_seams *s, size_t bytes)
{
    s->mem_max = bytes;
}

void vt_seams_destroy(struct vt_seams *s)
{
    free(s);
}

/* The carried interval of part i in tile t of level l along one axis, and whether the merge needs
 * any of it along this axis (*hull: those texels, else the whole of *in). */
static struct ival axis_carry(const struct vt_seams *s, const struct axis *x, uint32_t i,
                              uint32_t l, int64_t t, struct ival *hull)
{
    int64_t a = t * s->c, b = (t + 1) * s->c < x->ext[l] ? (t + 1) * s->c : x->ext[l];
    struct ival r = x->r[l][i];
    struct ival in = {a > r.a ? a : r.a, b < r.b ? b : r.b};
    if (in.a >= in.b)
        in = (struct ival){0, 0};
    *hull = in.a < in.b ? list_hull_in(&x->need[l], in.a, in.b) : in;
    return in;
}

bool vt_seams_carry_rect(const struct vt_seams *s, uint32_t col, uint32_t row, uint32_t level,
                         uint32_t tx, uint32_t ty, struct vt_seams_rect *out)
{
    if (level < s->k || level >= s->levels || s->levels <= s->k + 1)
        return false;
    struct ival hx, hy;
    struct ival ix = axis_carry(s, &s->ax[0], col, level, tx, &hx);
    struct ival iy = axis_carry(s, &s->ax[1], row, level, ty, &hy);
    if (ix.a >= ix.b || iy.a >= iy.b || (hx.a >= hx.b && hy.a >= hy.b))
        return false;
    if (hx.a < hx.b && hy.a >= hy.b)
        ix = hx;
    else if (hy.a < hy.b && hx.a >= hx.b)
        iy = hy;
    *out = (struct vt_seams_rect){(uint32_t)ix.a, (uint32_t)iy.a, (uint32_t)(ix.b - ix.a),
                                  (uint32_t)(iy.b - iy.a)};
    return true;
}

uint64_t vt_seams_tile_count(const struct vt_seams *s, uint32_t col, uint32_t row)
{
    uint64_t n = 0;
    bool merge = col == UINT32_MAX;
    for (uint32_t l = s->k + 1; l < s->levels; l++)
        for (int64_t ty = 0; ty < tiles_of(s, &s->ax[1], l); ty++) {
            int oy = tile_owner(s, &s->ax[1], l, ty);
            for (int64_t tx = 0; tx < tiles_of(s, &s->ax[0], l); tx++) {
                int ox = tile_owner(s, &s->ax[0], l, tx);
                n += merge ? (ox < 0 || oy < 0) : (ox == (int)col && oy == (int)row);
            }
        }
    return n;
}

/* ---- levels in float files ---- */

/* A level's texels: in memory (calloc: pages never written cost nothing) up to s->mem_max bytes
 * of the whole level, else in an unlinked float file; either way read through src. */

struct level_io {
    struct vt_float_file *file;
    float *mem;
    size_t row_floats; /* mem: floats per row */
    struct vt_source src;
    bool open;
};

static int mem_read_region(void *ctx, uint32_t x, uint32_t y, struct vt_image *dst,
                           struct vts_error *err)
{
    const struct level_io *io = ctx;
    size_t channels = dst->channels, bytes = (size_t)dst->width * channels * sizeof(float);
    (void)err;
    for (uint32_t r = 0; r < dst->height; r++)
        memcpy((char *)dst->pixels + (size_t)r * dst->stride,
               io->mem + (size_t)(y + r) * io->row_floats + (size_t)x * channels, bytes);
    return 0;
}

static void mem_close(void *ctx)
{
    (void)ctx; /* the memory belongs to the level_io */
}

static const struct vt_source_ops mem_ops = {mem_read_region, mem_close};

static int level_open(struct vt_seams *s, uint32_t l, struct level_io *io, struct vts_error *err)
{
    uint32_t w = (uint32_t)s->ax[0].ext[l], h = (uint32_t)s->ax[1].ext[l];
    size_t floats;
    io->open = true;
    if (vt_size_mul3(w, h, s->channels, &floats) && floats <= s->mem_max / sizeof(float) &&
        (io->mem = calloc(floats, sizeof(float))) != NULL) {
        io->row_floats = (size_t)w * s->channels;
        io->src = (struct vt_source){.info = {.width = w,
                                              .height = h,
                                              .channels = s->channels,
                                              .sample = VTS_SAMPLE_F32,
                                              .colour = s->o->colour},
                                     .ops = &mem_ops,
                                     .ctx = io,
                                     .name = "(seam level)"};
        return 0;
    }
    io->file = vt_float_file_create(s->o->temp_dir, w, h, s->channels, s->c, err);
    if (!io->file)
        return err ? err->status : VTS_ERR_IO;
    return vt_float_file_source(io->file, s->o->colour, false, &io->src, err);
}

static void level_close(struct level_io *io)
{
    if (!io->open)
        return;
    vt_source_close(&io->src);
    vt_float_file_destroy(io->file);
    free(io->mem);
    *io = (struct level_io){0};
}

/* Moves level `from` to `to` (its source reads through the struct: it points at the new place). */
static void level_move(struct level_io *to, struct level_io *from)
{
    *to = *from;
    if (to->mem)
        to->src.ctx = to;
    *from = (struct level_io){0};
}

static int write_rect(struct level_io *io, const struct vt_seams_rect *r, const float *texels,
                      size_t stride, struct vts_error *err)
{
    size_t row_floats = (size_t)r->width * io->src.info.channels;
    if (!io->mem)
        return vt_float_file_write(io->file, r->x, r->y, r->width, r->height, texels, stride, err);
    for (uint32_t y = 0; y < r->height; y++)
        memcpy(io->mem + (size_t)(r->y + y) * io->row_floats + (size_t)r->x * io->src.info.channels,
               texels + y * stride, row_floats * sizeof(float));
    return 0;
}

static int read_rect(struct vt_seams *s, struct level_io *io, const struct vt_seams_rect *r,
                     float *texels, struct vts_error *err)
{
    struct vt_image img = {r->width,
                           r->height,
                           s->channels,
                           VTS_SAMPLE_F32,
                           (size_t)r->width * s->channels * sizeof(float),
                           texels};
    return vt_source_read(&io->src, r->x, r->y, &img, err);
}

/* ---- tiles ---- */

struct tile_buf {
    struct vt_image work, full, out; /* payload in working floats, out sample, out channels */
    struct vt_pyramid_read_scratch read;
};

static int tile_buf_alloc(struct vt_seams *s, struct tile_buf *t, struct vts_error *err)
{
    uint32_t pp = s->c + 2 * s->border;
    int rc = vt_image_alloc(&t->work, pp, pp, s->channels, VTS_SAMPLE_F32, err);
    if (rc == 0)
        rc = vt_image_alloc(&t->full, pp, pp, s->channels, s->o->out_sample, err);
    if (rc == 0)
        rc = vt_image_alloc(&t->out, pp, pp, s->o->out_channels, s->o->out_sample, err);
    if (rc == 0 && vt_pyramid_read_scratch_alloc(&t->read, pp) != 0)
        rc = vt_error_set(err, VTS_ERR_NOMEM, "out of memory for a tile");
    return rc;
}

static void tile_buf_release(struct tile_buf *t)
{
    vt_image_release(&t->work);
    vt_image_release(&t->full);
    vt_image_release(&t->out);
    vt_pyramid_read_scratch_release(&t->read);
}

/* True when every alpha sample of t is zero (then the tile is empty). */
static bool transparent(const struct vt_image *t)
{
    if (t->channels != 2 && t->channels != 4)
        return false;
    size_t sb = vts_sample_bytes(t->sample), tb = vt_image_texel_bytes(t);
    for (uint32_t y = 0; y < t->height; y++) {
        const unsigned char *row = vt_image_at(t, 0, y);
        for (uint32_t x = 0; x < t->width; x++)
            for (size_t i = tb - sb; i < tb; i++)
                if (row[x * tb + i])
                    return false;
    }
    return true;
}

/* ---- work on the pool: bands of a rectangle to reduce, tiles to emit ---- */

struct worker {
    float *src, *dst, *scratch;
    size_t src_cap, dst_cap, scratch_cap; /* floats */
    struct tile_buf t;
};

struct work {
    struct vt_seams *s;
    struct worker *w;
    unsigned threads;
    uint64_t done, total; /* tiles emitted (atomic), of total */
    uint64_t next, count; /* jobs of the current run */
    /* a reduction: rectangle r of level l from `fine` into `out`, BAND_ROWS rows per job */
    uint32_t l;
    struct level_io *fine, *out;
    struct vt_seams_rect r;
    /* emission: tiles[2 * job], tiles[2 * job + 1] of level l from `out` */
    uint32_t *tiles;
    size_t tiles_cap;
    bool emitting;
};

static bool grow(float **p, size_t *cap, size_t need)
{
    if (need <= *cap)
        return true;
    float *q = realloc(*p, need * sizeof(float));
    if (!q)
        return false;
    *p = q;
    *cap = need;
    return true;
}

/* Rows [r.y + job * BAND_ROWS, + BAND_ROWS) of rectangle r of level l from level l - 1 (every
 * texel they read already there). */
static int reduce_band(struct work *wk, struct worker *w, uint64_t job, struct vts_error *err)
{
    struct vt_seams *s = wk->s;
    const struct axis *ax = &s->ax[0], *ay = &s->ax[1];
    const struct vt_seams_rect *r = &wk->r;
    uint32_t l = wk->l, y = (uint32_t)(job * BAND_ROWS);
    uint32_t rows = r->height - y < BAND_ROWS ? r->height - y : BAND_ROWS;
    struct ival wx = window(&s->kernel, r->x, (int64_t)r->x + r->width, ax->ext[l - 1]);
    struct ival wy =
        window(&s->kernel, (int64_t)r->y + y, (int64_t)r->y + y + rows, ay->ext[l - 1]);
    size_t src_floats, dst_floats;
    if (!vt_size_mul3((size_t)(wx.b - wx.a), (size_t)(wy.b - wy.a), s->channels, &src_floats) ||
        !vt_size_mul3(r->width, rows, s->channels, &dst_floats))
        return vt_error_set(err, VTS_ERR_LIMIT, "a seam strip of %u texels is too wide", r->width);
    if (!grow(&w->src, &w->src_cap, src_floats) || !grow(&w->dst, &w->dst_cap, dst_floats))
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory for a band of %u texels", r->width);
    struct vt_fregion fr = {wx.a,        wy.a,  (uint32_t)(wx.b - wx.a), (uint32_t)(wy.b - wy.a),
                            s->channels, w->src};
    struct vt_fregion dr = {r->x, (int64_t)r->y + y, r->width, rows, s->channels, w->dst};
    if (!grow(&w->scratch, &w->scratch_cap, vt_filter_reduce_scratch(&s->kernel, &fr, &dr)))
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory for a band of %u texels", r->width);
    struct vt_seams_rect sr = {(uint32_t)fr.x0, (uint32_t)fr.y0, fr.width, fr.height};
    struct vt_edges edges = {(uint32_t)ax->ext[l - 1], (uint32_t)ay->ext[l - 1], false, false};
    int rc = read_rect(s, wk->fine, &sr, w->src, err);
    if (rc == 0)
        rc = vt_filter_reduce(&s->kernel, &edges, &fr, &dr, w->scratch, w->scratch_cap, err);
    if (rc == 0 && s->o->colour == VTS_COLOUR_NORMAL)
        vt_filter_renormalize(&dr);
    struct vt_seams_rect band = {r->x, r->y + y, r->width, rows};
    return rc ? rc : write_rect(wk->out, &band, w->dst, (size_t)r->width * s->channels, err);
}

/* Tile (tx, ty) of level l from the level's texels (its payload, clamped at the level's edges). */
static int emit(struct vt_seams *s, unsigned worker, struct tile_buf *t, struct level_io *io,
                uint32_t l, uint32_t tx, uint32_t ty, struct vts_error *err)
{
    const struct vt_pyramid_options *o = s->o;
    int64_t x0 = (int64_t)tx * s->c - s->border, y0 = (int64_t)ty * s->c - s->border;
    int rc = vt_pyramid_read_region(&io->src, (uint32_t)s->ax[0].ext[l], (uint32_t)s->ax[1].ext[l],
                                    false, &t->read, x0, y0, &t->work, err);
    if (rc)
        return rc;
    for (uint32_t y = 0; y < t->work.height; y++)
        vt_filter_from_working(&s->mode, o->out_sample, vt_image_at(&t->work, 0, y),
                               vt_image_at(&t->full, 0, y), t->work.width);
    struct vt_image *payload = &t->full;
    if (o->out_channels != s->channels) {
        size_t sb = vts_sample_bytes(o->out_sample);
        for (uint32_t y = 0; y < t->full.height; y++)
            for (uint32_t x = 0; x < t->full.width; x++)
                memcpy((unsigned char *)vt_image_at(&t->out, x, y), vt_image_at(&t->full, x, y),
                       sb * o->out_channels);
        payload = &t->out;
    }
    bool empty = s->has_alpha && transparent(payload);
    return o->emit(o->user, worker, l, tx, ty, empty ? NULL : payload, err);
}

static bool work_next(void *ctx, uint64_t *job)
{
    struct work *wk = ctx;
    if (wk->next >= wk->count)
        return false;
    *job = wk->next++;
    return true;
}

static int work_do(void *ctx, unsigned worker, uint64_t job, struct vts_error *err)
{
    struct work *wk = ctx;
    struct worker *w = &wk->w[worker];
    if (!wk->emitting)
        return reduce_band(wk, w, job, err);
    int rc =
        emit(wk->s, worker, &w->t, wk->out, wk->l, wk->tiles[2 * job], wk->tiles[2 * job + 1], err);
    if (rc == 0)
        __atomic_add_fetch(&wk->done, 1, __ATOMIC_RELAXED);
    return rc;
}

static int work_progress(void *ctx)
{
    struct work *wk = ctx;
    const struct vt_pyramid_options *o = wk->s->o;
    return o->progress
               ? o->progress(o->user, __atomic_load_n(&wk->done, __ATOMIC_RELAXED), wk->total)
               : 0;
}

static const struct vt_pool_fns work_fns = {work_next, work_do, work_progress};

static int work_init(struct work *wk, struct vt_seams *s, uint64_t done, uint64_t total,
                     struct vts_error *err)
{
    unsigned threads = s->o->threads ? s->o->threads : 1;
    *wk = (struct work){.s = s, .threads = threads, .done = done, .total = total};
    if (!(wk->w = calloc(threads, sizeof *wk->w)))
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory for %u workers", threads);
    for (unsigned i = 0; i < threads; i++) {
        int rc = tile_buf_alloc(s, &wk->w[i].t, err);
        if (rc)
            return rc;
    }
    return 0;
}

static void work_release(struct work *wk)
{
    for (unsigned i = 0; wk->w && i < wk->threads; i++) {
        free(wk->w[i].src);
        free(wk->w[i].dst);
        free(wk->w[i].scratch);
        tile_buf_release(&wk->w[i].t);
    }
    free(wk->w);
    free(wk->tiles);
}

/* Computes rectangle r of level l from `fine` into `out` on the pool. */
static int work_reduce(struct work *wk, uint32_t l, struct level_io *fine, struct level_io *out,
                       const struct vt_seams_rect *r, struct vts_error *err)
{
    wk->emitting = false;
    wk->l = l;
    wk->fine = fine;
    wk->out = out;
    wk->r = *r;
    wk->next = 0;
    wk->count = (r->height + BAND_ROWS - 1) / BAND_ROWS;
    return vt_pool_run(wk->threads, &work_fns, wk, err);
}

/* Emits the tiles of level l (from `out`) that part (col, row) owns, or with col = UINT32_MAX
 * those no part owns, on the pool. */
static int work_emit(struct work *wk, uint32_t l, struct level_io *out, uint32_t col, uint32_t row,
                     struct vts_error *err)
{
    struct vt_seams *s = wk->s;
    bool merge = col == UINT32_MAX;
    wk->emitting = true;
    wk->l = l;
    wk->out = out;
    wk->next = wk->count = 0;
    for (int64_t ty = 0; ty < tiles_of(s, &s->ax[1], l); ty++) {
        int oy = tile_owner(s, &s->ax[1], l, ty);
        if (!merge && oy != (int)row)
            continue;
        for (int64_t tx = 0; tx < tiles_of(s, &s->ax[0], l); tx++) {
            int ox = tile_owner(s, &s->ax[0], l, tx);
            if (merge ? (ox >= 0 && oy >= 0) : ox != (int)col)
                continue;
            if (2 * wk->count + 2 > wk->tiles_cap) {
                size_t cap = wk->tiles_cap ? 2 * wk->tiles_cap : 256;
                uint32_t *t = realloc(wk->tiles, cap * sizeof *t);
                if (!t)
                    return vt_error_set(err, VTS_ERR_NOMEM, "out of memory for a tile list");
                wk->tiles = t;
                wk->tiles_cap = cap;
            }
            wk->tiles[2 * wk->count] = (uint32_t)tx;
            wk->tiles[2 * wk->count + 1] = (uint32_t)ty;
            wk->count++;
        }
    }
    return wk->count ? vt_pool_run(wk->threads, &work_fns, wk, err) : 0;
}

/* ---- the shard ---- */

static int shard_carry(struct vt_seams *s, uint32_t col, uint32_t row, uint32_t l,
                       struct level_io *io, float *buf, struct vts_error *err)
{
    int rc = 0;
    for (int64_t ty = 0; rc == 0 && ty < tiles_of(s, &s->ax[1], l); ty++)
        for (int64_t tx = 0; rc == 0 && tx < tiles_of(s, &s->ax[0], l); tx++) {
            struct vt_seams_rect r;
            if (!vt_seams_carry_rect(s, col, row, l, (uint32_t)tx, (uint32_t)ty, &r))
                continue;
            rc = read_rect(s, io, &r, buf, err);
            if (rc == 0)
                rc = s->o->seam_carry(s->o->user, l, r.x, r.y, r.width, r.height, s->channels, buf,
                                      (size_t)r.width * s->channels, err);
        }
    return rc;
}

int vt_seams_shard_run(struct vt_seams *s, uint32_t col, uint32_t row,
                       struct vt_float_file *level_k, uint64_t *done, struct vts_error *err)
{
    if (s->levels <= s->k + 1)
        return 0;
    struct level_io lv[2] = {{.file = level_k}, {.file = NULL}};
    int rc = vt_float_file_source(level_k, s->o->colour, false, &lv[0].src, err);
    struct work wk = {.s = NULL};
    if (rc == 0)
        rc = work_init(&wk, s, *done, *done + vt_seams_tile_count(s, col, row), err);
    float *buf = malloc((size_t)s->c * s->c * s->channels * sizeof(float));
    if (rc == 0 && !buf)
        rc = vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    if (rc == 0)
        rc = shard_carry(s, col, row, s->k, &lv[0], buf, err);
    for (uint32_t l = s->k + 1; rc == 0 && l < s->levels; l++) {
        struct ival rx = s->ax[0].r[l][col], ry = s->ax[1].r[l][row];
        if (rx.a >= rx.b || ry.a >= ry.b)
            break; /* nothing of this level or above is the shard's */
        struct vt_seams_rect r = {(uint32_t)rx.a, (uint32_t)ry.a, (uint32_t)(rx.b - rx.a),
                                  (uint32_t)(ry.b - ry.a)};
        rc = level_open(s, l, &lv[1], err);
        if (rc == 0)
            rc = work_reduce(&wk, l, &lv[0], &lv[1], &r, err);
        if (rc == 0)
            rc = work_emit(&wk, l, &lv[1], col, row, err);
        if (rc == 0)
            rc = shard_carry(s, col, row, l, &lv[1], buf, err);
        if (lv[0].file == level_k)
            vt_source_close(&lv[0].src); /* the caller's file */
        else
            level_close(&lv[0]);
        level_move(&lv[0], &lv[1]);
    }
    if (lv[0].file == level_k)
        vt_source_close(&lv[0].src);
    else
        level_close(&lv[0]);
    level_close(&lv[1]);
    *done = wk.done;
    work_release(&wk);
    free(buf);
    return rc;
}

/* ---- the merge ---- */

static int merge_carried(struct vt_seams *s, uint32_t l, struct level_io *io, vt_seams_read_fn read,
                         void *user, float *buf, struct vts_error *err)
{
    int rc = 0;
    for (uint32_t row = 0; row < s->ax[1].parts; row++)
        for (uint32_t col = 0; col < s->ax[0].parts; col++)
            for (int64_t ty = 0; rc == 0 && ty < tiles_of(s, &s->ax[1], l); ty++)
                for (int64_t tx = 0; rc == 0 && tx < tiles_of(s, &s->ax[0], l); tx++) {
                    struct vt_seams_rect r;
                    if (!vt_seams_carry_rect(s, col, row, l, (uint32_t)tx, (uint32_t)ty, &r))
                        continue;
                    size_t stride = (size_t)r.width * s->channels;
                    rc = read(user, col, row, l, (uint32_t)tx, (uint32_t)ty, &r, buf, stride, err);
                    if (rc == 0)
                        rc = write_rect(io, &r, buf, stride, err);
                }
    return rc;
}

/* The strips of level l no part computes: whole columns and whole rows of the level. */
static int merge_strips(struct work *wk, uint32_t l, struct level_io *fine, struct level_io *io,
                        struct vts_error *err)
{
    struct vt_seams *s = wk->s;
    struct ilist g;
    int rc = 0;
    for (int a = 0; a < 2 && rc == 0; a++) {
        gaps(&s->ax[a], l, &g);
        for (uint32_t i = 0; i < g.n && rc == 0; i++) {
            struct vt_seams_rect r = {0, 0, (uint32_t)s->ax[0].ext[l], (uint32_t)s->ax[1].ext[l]};
            if (a == 0)
                r.x = (uint32_t)g.v[i].a, r.width = (uint32_t)(g.v[i].b - g.v[i].a);
            else
                r.y = (uint32_t)g.v[i].a, r.height = (uint32_t)(g.v[i].b - g.v[i].a);
            rc = work_reduce(wk, l, fine, io, &r, err);
        }
    }
    return rc;
}

int vt_seams_merge_run(struct vt_seams *s, vt_seams_read_fn read, void *user, struct vts_error *err)
{
    if (s->levels <= s->k + 1)
        return 0;
    struct level_io lv[2] = {{.file = NULL}, {.file = NULL}};
    struct work wk = {.s = NULL};
    int rc = work_init(&wk, s, 0, vt_seams_tile_count(s, UINT32_MAX, UINT32_MAX), err);
    float *buf = malloc((size_t)s->c * s->c * s->channels * sizeof(float));
    if (rc == 0 && !buf)
        rc = vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    if (rc == 0)
        rc = level_open(s, s->k, &lv[0], err);
    if (rc == 0)
        rc = merge_carried(s, s->k, &lv[0], read, user, buf, err);
    for (uint32_t l = s->k + 1; rc == 0 && l < s->levels; l++) {
        rc = level_open(s, l, &lv[1], err);
        if (rc == 0)
            rc = merge_carried(s, l, &lv[1], read, user, buf, err);
        if (rc == 0)
            rc = merge_strips(&wk, l, &lv[0], &lv[1], err);
        if (rc == 0)
            rc = work_emit(&wk, l, &lv[1], UINT32_MAX, UINT32_MAX, err);
        level_close(&lv[0]);
        level_move(&lv[0], &lv[1]);
    }
    level_close(&lv[0]);
    level_close(&lv[1]);
    work_release(&wk);
    free(buf);
    return rc;
}
