/* A mip chain built from a stream of rows (see internal/vt_chain_stream.h). */
#include "internal/vt_chain_stream.h"

#include <assert.h>
#include <stdlib.h>
#include <string.h>

#include "vt_checked.h"
#include "vt_error.h"
#include "vts.h"

#define MAX_STAGES (2 * VTS_MAX_LEVELS + 32)

/* One 2:1 reduction: finer rows [row0, row0 + nrows) of a fw x fh level are buffered (working
 * floats) until the coarser rows that read them are made.
 *
 * With wrap-around edges (a wrap entry) the finer rows arrive rotated: rows rot .. fh - 1, then
 * 0 .. rot - 1 (row0 and nrows count positions in that stream). The coarser rows are made in the
 * order y0 .. dh - 1, 0 .. y0 - 1, y0 being the first whose taps start at or after row rot, so
 * that each one waits only for rows that come before it in the stream, except for the last few,
 * whose taps run past the stream's end into its first rows: those first nhead rows are kept
 * (head) until the end. The coarser level then streams out rotated by y0 (the next stage's rot);
 * y0 stays at about the kernel's margin. A small level (fewer rows than a few kernels) is held
 * whole (small) and reduced once its last row is in, in order (y0 = 0). Rows are stored padded
 * with the columns the wrapped taps read: pw texels from column `first`. */
struct stage {
    uint32_t fw, fh, dw, dh;
    float *buf;
    uint32_t row0, nrows, cap; /* cap: rows buf holds */
    uint32_t next;             /* coarser rows made (with wrap: in the stream's order) */
    int level;                 /* chain level it makes, or -1 before level 0 */
    bool wrap, small;
    uint32_t rot, y0, nhead, pw;
    float *head;
};

/* Rows of one chain level gathered until a row of blocks is complete. The rows arrive rotated
 * by rot (a wrap entry): the row of blocks holding row rot gets its first rows last, so it is
 * gathered apart (split) and emitted after the level's last row. */
struct level_acc {
    uint32_t w, h, y; /* y: rows of the level received */
    uint32_t rot;
    uint8_t *rows;  /* VT_CHAIN_STREAM_EDGE rows */
    uint8_t *split; /* the same for the row of blocks holding row rot, when rot % EDGE != 0 */
};

struct vt_chain_stream {
    struct vt_pixel_mode mode;
    struct vt_kernel kern;
    uint32_t ch, pre, nstages, nlevels;
    uint32_t sample; /* the layer's (enum vts_sample) */
    size_t tb;       /* bytes of a stored texel */
    struct stage st[MAX_STAGES];
    struct level_acc acc[VTS_MAX_LEVELS];
    float *out, *scratch, *conv; /* a band of coarser rows, the filter's scratch, converted rows */
    size_t out_n, scratch_n, conv_n;
    float *gather; /* the finer rows of a wrapped band, gathered in order */
    size_t gather_n;
    uint8_t *u8, *block; /* a band of stored rows (the layer's sample type); one block */
    size_t u8_n;
    size_t bytes; /* of every buffer above */
    vt_chain_stream_emit_fn emit;
    void *user;
};

static uint32_t ceil_shift(uint32_t v, uint32_t k)
{
    return k >= 32 ? 1 : (uint32_t)(((uint64_t)v + (1ull << k) - 1) >> k);
}

bool vt_chain_stream_fits(const struct vt_mip_chain_spec *s, uint32_t tw, uint32_t th,
                          uint32_t *pre)
{
    if (s->crop_x || s->crop_y || s->crop_width != s->width || s->crop_height != s->height)
        return false;
    for (uint32_t k = 0; k < 32 && ceil_shift(tw, k) >= s->width; k++)
        if (ceil_shift(tw, k) == s->width && ceil_shift(th, k) == s->height &&
            (k == 0 || tw > s->width)) {
            *pre = k;
            return true;
        }
    return false;
}

/* Grows *p (*cap elements) to hold n elements of elem bytes; *total counts the bytes. */
static int reserve(void **p, size_t *cap, size_t n, size_t elem, size_t *total,
                   struct vts_error *err)
{
    if (n <= *cap)
        return 0;
    size_t bytes;
    if (!vt_size_mul(n, elem, &bytes))
        return vt_error_set(err, VTS_ERR_LIMIT, "a texture row is too large");
    void *q = realloc(*p, bytes);
    if (!q)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory for a texture band");
    *p = q;
    *total += bytes - *cap * elem;
    *cap = n;
    return 0;
}

/* Reduces src into dst (dst.px unset: its rows go to cs->out, grown as needed, with the scratch
 * the reduction needs), renormalising normals. */
static int reduce_out(struct vt_chain_stream *cs, const struct vt_kernel *k,
                      const struct vt_edges *edges, const struct vt_fregion *src,
                      struct vt_fregion *dst, struct vts_error *err)
{
    int rc = reserve((void **)&cs->out, &cs->out_n, (size_t)dst->width * dst->height * cs->ch,
                     sizeof(float), &cs->bytes, err);
    size_t sn = vt_filter_reduce_scratch(k, src, dst);
    if (rc == 0)
        rc = reserve((void **)&cs->scratch, &cs->scratch_n, sn ? sn : 1, sizeof(float), &cs->bytes,
                     err);
    if (rc)
        return rc;
    dst->px = cs->out;
    if ((rc = vt_filter_reduce(k, edges, src, dst, cs->scratch, sn, err)) != 0)
        return rc;
    if (cs->mode.colour == VTS_COLOUR_NORMAL)
        vt_filter_renormalize(dst);
    return 0;
}

/* The next n rows of a level (stored texels, tight, w wide) into its accumulator; full rows of
 * blocks are emitted. */
static int level_rows(struct vt_chain_stream *cs, uint32_t l, const uint8_t *px, uint32_t n,
                      size_t stride, struct vts_error *err)
{
    struct level_acc *a = &cs->acc[l];
    size_t rb = (size_t)a->w * cs->tb;
    const uint32_t E = VT_CHAIN_STREAM_EDGE;
    for (uint32_t r = 0; r < n; r++) {
        assert(a->y < a->h);
        uint32_t y = (uint32_t)(((uint64_t)a->rot + a->y) % a->h);
        bool split = a->split && y / E == a->rot / E;
        uint8_t *band = split ? a->split : a->rows;
        memcpy(band + (y % E) * rb, px + r * stride, rb);
        a->y++;
        if (split ? a->y != a->h : y % E != E - 1 && y != a->h - 1)
            continue;
        uint32_t by = y / E, bh = a->h - by * E < E ? a->h - by * E : E;
        for (uint32_t bx = 0; bx * E < a->w; bx++) {
            uint32_t x0 = bx * E;
            uint32_t bw = a->w - x0 < E ? a->w - x0 : E;
            for (uint32_t j = 0; j < bh; j++)
                memcpy(cs->block + (size_t)j * bw * cs->tb, band + j * rb + (size_t)x0 * cs->tb,
                       (size_t)bw * cs->tb);
            int rc = cs->emit(cs->user, l, bx, by, cs->block, bw, bh, err);
            if (rc)
                return rc;
        }
    }
    return 0;
}

static int stage_feed(struct vt_chain_stream *cs, uint32_t i, const float *rows, uint32_t n,
                      struct vts_error *err);

/* ---- wrap-around stages ---- */

static uint32_t wrap_index(int64_t v, uint32_t n)
{
    int64_t r = v % (int64_t)n;
    return (uint32_t)(r < 0 ? r + n : r);
}

/* The coarser row made e-th (e < dh) by a wrapped stage. */
static uint32_t wrap_row(const struct stage *s, uint32_t e)
{
    return s->small ? e : (uint32_t)(((uint64_t)s->y0 + e) % s->dh);
}

/* Stream position of the first finer row that coarser row e reads (its taps run on from there,
 * past the stream's end into the head for the last rows). */
static uint32_t wrap_first(const struct stage *s, const struct vt_kernel *k, uint32_t e)
{
    return wrap_index(2 * (int64_t)wrap_row(s, e) + k->first - s->rot, s->fh);
}

static bool wrap_ready(const struct stage *s, const struct vt_kernel *k, uint32_t e)
{
    uint64_t last = (uint64_t)wrap_first(s, k, e) + (uint64_t)k->count - 1;
    uint32_t have = s->row0 + s->nrows;
    return s->small || last >= s->fh ? have == s->fh : last < have;
}

/* Plans a wrapped stage whose finer rows arrive rotated by rot: small or not, y0 and the head. */
static void wrap_plan(struct stage *s, const struct vt_kernel *k, uint32_t rot)
{
    s->wrap = true;
    s->rot = rot;
    s->pw = 2 * (s->dw - 1) + (uint32_t)k->count;
    s->small = (uint64_t)s->fh < 2 * ((uint64_t)k->count + rot) + 8;
    s->y0 = s->small ? 0 : (uint32_t)(((int64_t)rot - k->first + 1) / 2);
    s->nhead = 0;
    for (uint32_t e = 0; !s->small && e < s->dh; e++) {
        uint64_t end = (uint64_t)wrap_first(s, k, e) + (uint64_t)k->count;
        if (end > s->fh && end - s->fh > s->nhead)
            s->nhead = (uint32_t)(end - s->fh);
    }
    assert(s->small || (s->y0 < s->dh && s->nhead < s->fh));
}

/* Finer row at stream position p: in the buffer, or kept in the head. */
static const float *wrap_row_at(const struct stage *s, uint32_t p, size_t rf)
{
    if (p >= s->row0 && p < s->row0 + s->nrows)
        return s->buf + (size_t)(p - s->row0) * rf;
    assert(p < s->nhead);
    return s->head + (size_t)p * rf;
}

static int stage_output(struct vt_chain_stream *cs, uint32_t i, uint32_t n, struct vts_error *err);

/* Makes coarser rows e .. e + n - 1 (consecutive rows of the level) into cs->out. */
static int wrap_reduce(struct vt_chain_stream *cs, struct stage *s, uint32_t e, uint32_t n,
                       struct vts_error *err)
{
    const struct vt_kernel *k = &cs->kern;
    size_t rf = (size_t)s->pw * cs->ch;
    uint32_t ya = wrap_row(s, e), rows = 2 * (n - 1) + (uint32_t)k->count;
    uint32_t p0 = wrap_first(s, k, e);
    const float *px;
    if ((uint64_t)p0 + rows <= s->fh && p0 >= s->row0 && p0 + rows <= s->row0 + s->nrows) {
        px = s->buf + (size_t)(p0 - s->row0) * rf; /* contiguous in the buffer */
    } else {
        int rc =
            reserve((void **)&cs->gather, &cs->gather_n, rows * rf, sizeof(float), &cs->bytes, err);
        if (rc)
            return rc;
        for (uint32_t r = 0; r < rows; r++)
            memcpy(cs->gather + r * rf, wrap_row_at(s, wrap_index((int64_t)p0 + r, s->fh), rf),
                   rf * sizeof(float));
        px = cs->gather;
    }
    struct vt_fregion src = {k->first, 2 * (int64_t)ya + k->first, s->pw, rows,
                             cs->ch,   (float *)(uintptr_t)px};
    struct vt_fregion dst = {0, ya, s->dw, n, cs->ch, NULL};
    struct vt_edges edges = {s->fw, s->fh, true, true};
    return reduce_out(cs, k, &edges, &src, &dst, err);
}

/* Makes every coarser row of wrapped stage i that can be made, in the stream's order. */
static int wrap_run(struct vt_chain_stream *cs, uint32_t i, struct vts_error *err)
{
    struct stage *s = &cs->st[i];
    const struct vt_kernel *k = &cs->kern;
    size_t rf = (size_t)s->pw * cs->ch;
    while (s->next < s->dh && wrap_ready(s, k, s->next)) {
        uint32_t e = s->next, n = 1, ya = wrap_row(s, e);
        while (e + n < s->dh && ya + n < s->dh && wrap_ready(s, k, e + n))
            n++;
        int rc = wrap_reduce(cs, s, e, n, err);
        if (rc)
            return rc;
        s->next = e + n;
        /* drop the buffered rows no later coarser row reads (the head keeps the first ones) */
        uint32_t have = s->row0 + s->nrows;
        uint32_t keep = s->small ? s->row0 : s->next < s->dh ? wrap_first(s, k, s->next) : have;
        if (keep > s->row0) {
            uint32_t drop = keep - s->row0 < s->nrows ? keep - s->row0 : s->nrows;
            memmove(s->buf, s->buf + drop * rf, (s->nrows - drop) * rf * sizeof(float));
            s->row0 += drop;
            s->nrows -= drop;
        }
        if ((rc = stage_output(cs, i, n, err)) != 0)
            return rc;
    }
    return 0;
}

/* The next n finer rows (fw wide) into wrapped stage i, padded; the first ones also to its head. */
static int wrap_feed(struct vt_chain_stream *cs, uint32_t i, const float *rows, uint32_t n,
                     struct vts_error *err)
{
    struct stage *s = &cs->st[i];
    size_t rf = (size_t)s->pw * cs->ch, tf = cs->ch * sizeof(float);
    if (s->nrows + n > s->cap) {
        size_t cap = s->small ? s->fh : s->nrows + n + 8;
        if (reserve((void **)&s->buf, &(size_t){(size_t)s->cap * rf}, cap * rf, sizeof(float),
                    &cs->bytes, err))
            return err ? err->status : VTS_ERR_NOMEM;
        s->cap = (uint32_t)cap;
    }
    for (uint32_t r = 0; r < n; r++) {
        const float *in = rows + (size_t)r * s->fw * cs->ch;
        float *o = s->buf + (size_t)(s->nrows + r) * rf;
        uint32_t x = wrap_index(cs->kern.first, s->fw);
        for (uint32_t a = 0; a < s->pw;) {
            uint32_t run = s->fw - x < s->pw - a ? s->fw - x : s->pw - a;
            memcpy(o + (size_t)a * cs->ch, in + (size_t)x * cs->ch, run * tf);
            a += run;
            x = 0;
        }
        uint32_t p = s->row0 + s->nrows + r;
        if (p < s->nhead)
            memcpy(s->head + (size_t)p * rf, o, rf * sizeof(float));
    }
    s->nrows += n;
    return wrap_run(cs, i, err);
}

/* Coarser rows [y0, y0 + n) of stage i are made (cs->out): stored and/or passed on. */
static int stage_output(struct vt_chain_stream *cs, uint32_t i, uint32_t n, struct vts_error *err)
{
    struct stage *s = &cs->st[i];
    size_t nt = (size_t)s->dw * n;
    int rc = reserve((void **)&cs->u8, &cs->u8_n, nt * cs->tb, 1, &cs->bytes, err);
    if (rc)
        return rc;
    bool last_pre = s->level < 0 && i + 1 == cs->pre;
    if (s->level >= 0 || last_pre) {
        vt_filter_from_working(&cs->mode, cs->sample, cs->out, cs->u8, nt);
        rc = level_rows(cs, s->level >= 0 ? (uint32_t)s->level : 0, cs->u8, n,
                        (size_t)s->dw * cs->tb, err);
    }
    if (rc || i + 1 >= cs->nstages)
        return rc;
    if (!last_pre) /* the next reduction reads these floats as they are (build_levels) */
        return stage_feed(cs, i + 1, cs->out, n, err);
    /* level 0 from the texture's own mip level: reduced again from its stored texels */
    if ((rc = reserve((void **)&cs->conv, &cs->conv_n, nt * cs->ch, sizeof(float), &cs->bytes,
                      err)) != 0)
        return rc;
    vt_filter_to_working(&cs->mode, cs->sample, cs->u8, cs->conv, nt);
    return stage_feed(cs, i + 1, cs->conv, n, err);
}

static uint32_t clamp_row(int64_t y, uint32_t h)
{
    return y < 0 ? 0 : y >= h ? h - 1 : (uint32_t)y;
}

/* Makes every coarser row of stage i whose finer rows are all buffered. */
static int stage_run(struct vt_chain_stream *cs, uint32_t i, struct vts_error *err)
{
    struct stage *s = &cs->st[i];
    const struct vt_kernel *k = &cs->kern;
    uint32_t have = s->row0 + s->nrows; /* finer rows [0, have) seen */
    uint32_t y1 = s->next;
    while (y1 < s->dh && clamp_row(2 * (int64_t)y1 + k->first + k->count - 1, s->fh) < have)
        y1++;
    if (y1 == s->next)
        return 0;
    uint32_t n = y1 - s->next;
    uint32_t lo = clamp_row(2 * (int64_t)s->next + k->first, s->fh);
    uint32_t hi = clamp_row(2 * (int64_t)(y1 - 1) + k->first + k->count - 1, s->fh);
    assert(lo >= s->row0 && hi < have);
    size_t rf = (size_t)s->fw * cs->ch;
    struct vt_fregion src = {0, lo, s->fw, hi - lo + 1, cs->ch, s->buf + (lo - s->row0) * rf};
    struct vt_fregion dst = {0, s->next, s->dw, n, cs->ch, NULL};
    struct vt_edges edges = {s->fw, s->fh, false, false};
    int rc = reduce_out(cs, k, &edges, &src, &dst, err);
    if (rc)
        return rc;
    s->next = y1;
    /* drop the finer rows no later coarser row reads */
    uint32_t keep = s->next < s->dh ? clamp_row(2 * (int64_t)s->next + k->first, s->fh) : have;
    if (keep > s->row0) {
        uint32_t drop = keep - s->row0 < s->nrows ? keep - s->row0 : s->nrows;
        memmove(s->buf, s->buf + drop * rf, (s->nrows - drop) * rf * sizeof(float));
        s->row0 += drop;
        s->nrows -= drop;
    }
    return stage_output(cs, i, n, err);
}

static int stage_feed(struct vt_chain_stream *cs, uint32_t i, const float *rows, uint32_t n,
                      struct vts_error *err)
{
    struct stage *s = &cs->st[i];
    if (s->wrap)
        return wrap_feed(cs, i, rows, n, err);
    size_t rf = (size_t)s->fw * cs->ch;
    if (s->nrows + n > s->cap) {
        size_t cap = s->nrows + n + 8;
        if (reserve((void **)&s->buf, &(size_t){(size_t)s->cap * rf}, cap * rf, sizeof(float),
                    &cs->bytes, err))
            return err ? err->status : VTS_ERR_NOMEM;
        s->cap = (uint32_t)cap;
    }
    memcpy(s->buf + s->nrows * rf, rows, n * rf * sizeof(float));
    s->nrows += n;
    /* cs->out is reused by the next stage: this stage's output is consumed before it returns */
    return stage_run(cs, i, err);
}

int vt_chain_stream_push(struct vt_chain_stream *cs, const struct vt_image *rows,
                         struct vts_error *err)
{
    assert(rows->sample == cs->sample && rows->channels == cs->ch);
    int rc = 0;
    if (cs->pre == 0)
        rc = level_rows(cs, 0, rows->pixels, rows->height, rows->stride, err);
    if (rc || cs->nstages == 0)
        return rc;
    size_t nt = (size_t)rows->width * rows->height;
    if ((rc = reserve((void **)&cs->conv, &cs->conv_n, nt * cs->ch, sizeof(float), &cs->bytes,
                      err)) != 0)
        return rc;
    for (uint32_t y = 0; y < rows->height; y++)
        vt_filter_to_working(&cs->mode, cs->sample, vt_image_at(rows, 0, y),
                             cs->conv + (size_t)y * rows->width * cs->ch, rows->width);
    /* stage 0 copies the rows before it runs, so conv may be reused below it */
    float *conv = cs->conv;
    cs->conv = NULL;
    size_t conv_n = cs->conv_n;
    cs->conv_n = 0;
    rc = stage_feed(cs, 0, conv, rows->height, err);
    free(cs->conv);
    cs->conv = conv;
    cs->conv_n = conv_n;
    return rc;
}

struct vt_chain_stream *vt_chain_stream_create(const struct vt_mip_chain_spec *s, uint32_t tw,
                                               uint32_t th, vt_chain_stream_emit_fn emit,
                                               void *user, struct vts_error *err)
{
    uint32_t pre;
    if (!vt_chain_stream_fits(s, tw, th, &pre) || s->level_count < 1 ||
        s->level_count > VTS_MAX_LEVELS) {
        vt_error_set(err, VTS_ERR_ARG, "chain stream: unsupported spec");
        return NULL;
    }
    struct vt_chain_stream *cs = calloc(1, sizeof *cs);
    if (!cs) {
        vt_error_set(err, VTS_ERR_NOMEM, "out of memory for a texture chain");
        return NULL;
    }
    vt_mip_chain_mode(s, &cs->mode);
    vt_kernel_init(&cs->kern, s->filter);
    cs->ch = cs->mode.channels;
    cs->sample = vt_mip_chain_sample(s);
    cs->tb = (size_t)cs->ch * vts_sample_bytes(cs->sample);
    cs->pre = pre;
    cs->nlevels = s->level_count;
    cs->nstages = pre + s->level_count - 1;
    cs->emit = emit;
    cs->user = user;
    uint32_t w = tw, h = th, rot = 0;
    bool ok = true;
    for (uint32_t i = 0; i < cs->nstages; i++) {
        struct stage *st = &cs->st[i];
        *st = (struct stage){.fw = w,
                             .fh = h,
                             .dw = ceil_shift(w, 1),
                             .dh = ceil_shift(h, 1),
                             .level = i < pre ? -1 : (int)(i - pre + 1)};
        if (s->wrap) {
            wrap_plan(st, &cs->kern, rot);
            rot = st->y0;
            size_t hn = (size_t)st->nhead * st->pw * cs->ch;
            ok = ok && (hn == 0 || (st->head = malloc(hn * sizeof(float))));
            cs->bytes += hn * sizeof(float);
        }
        if (st->level >= 0)
            cs->acc[st->level].rot = rot;
        else if (i + 1 == pre)
            cs->acc[0].rot = rot;
        w = st->dw;
        h = st->dh;
    }
    ok = ok && (cs->block = malloc((size_t)VT_CHAIN_STREAM_EDGE * VT_CHAIN_STREAM_EDGE * cs->tb));
    cs->bytes += (size_t)VT_CHAIN_STREAM_EDGE * VT_CHAIN_STREAM_EDGE * cs->tb;
    for (uint32_t l = 0; ok && l < cs->nlevels && l < VTS_MAX_LEVELS; l++) {
        struct level_acc *a = &cs->acc[l];
        a->w = ceil_shift(s->width, l);
        a->h = ceil_shift(s->height, l);
        a->rot %= a->h;
        size_t band = (size_t)a->w * cs->tb * VT_CHAIN_STREAM_EDGE;
        ok = (a->rows = malloc(band));
        if (ok && a->rot % VT_CHAIN_STREAM_EDGE)
            ok = (a->split = malloc(band));
        cs->bytes += a->split ? 2 * band : band;
    }
    if (!ok) {
        vt_chain_stream_destroy(cs);
        vt_error_set(err, VTS_ERR_NOMEM, "out of memory for a texture chain");
        return NULL;
    }
    return cs;
}

size_t vt_chain_stream_bytes(const struct vt_chain_stream *cs)
{
    return cs->bytes;
}

void vt_chain_stream_destroy(struct vt_chain_stream *cs)
{
    if (!cs)
        return;
    for (uint32_t i = 0; i < cs->nstages; i++) {
        free(cs->st[i].buf);
        free(cs->st[i].head);
    }
    for (uint32_t l = 0; l < VTS_MAX_LEVELS; l++) {
        free(cs->acc[l].rows);
        free(cs->acc[l].split);
    }
    free(cs->gather);
    free(cs->out);
    free(cs->scratch);
    free(cs->conv);
    free(cs->u8);
    free(cs->block);
    free(cs);
}
