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
 * floats) until the coarser rows that read them are made. */
struct stage {
    uint32_t fw, fh, dw, dh;
    float *buf;
    uint32_t row0, nrows, cap; /* cap: rows buf holds */
    uint32_t next;             /* next coarser row to make */
    int level;                 /* chain level it makes, or -1 before level 0 */
};

/* Rows of one chain level gathered until a row of blocks is complete. */
struct level_acc {
    uint32_t w, h, y; /* y: rows of the level done */
    uint8_t *rows;    /* VT_CHAIN_STREAM_EDGE rows */
};

struct vt_chain_stream {
    struct vt_pixel_mode mode;
    struct vt_kernel kern;
    uint32_t ch, pre, nstages, nlevels;
    struct stage st[MAX_STAGES];
    struct level_acc acc[VTS_MAX_LEVELS];
    float *out, *scratch, *conv; /* a band of coarser rows, the filter's scratch, converted rows */
    size_t out_n, scratch_n, conv_n;
    uint8_t *u8, *block; /* a band of 8-bit rows; one block */
    size_t u8_n;
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
    if (s->wrap || s->crop_x || s->crop_y || s->crop_width != s->width ||
        s->crop_height != s->height)
        return false;
    for (uint32_t k = 0; k < 32 && ceil_shift(tw, k) >= s->width; k++)
        if (ceil_shift(tw, k) == s->width && ceil_shift(th, k) == s->height &&
            (k == 0 || tw > s->width)) {
            *pre = k;
            return true;
        }
    return false;
}

/* Grows *p to hold n floats (bytes for the u8 variant). */
static int reserve(void **p, size_t *cap, size_t n, size_t elem, struct vts_error *err)
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
    *cap = n;
    return 0;
}

/* Rows [y, y + n) of a level (8-bit, tight, w wide) into its accumulator; full rows of blocks are
 * emitted. */
static int level_rows(struct vt_chain_stream *cs, uint32_t l, const uint8_t *px, uint32_t n,
                      size_t stride, struct vts_error *err)
{
    struct level_acc *a = &cs->acc[l];
    size_t rb = (size_t)a->w * cs->ch;
    for (uint32_t r = 0; r < n; r++) {
        uint32_t in_band = a->y % VT_CHAIN_STREAM_EDGE;
        memcpy(a->rows + in_band * rb, px + r * stride, rb);
        a->y++;
        if (a->y % VT_CHAIN_STREAM_EDGE != 0 && a->y != a->h)
            continue;
        uint32_t by = (a->y - 1) / VT_CHAIN_STREAM_EDGE, bh = in_band + 1;
        for (uint32_t bx = 0; bx * VT_CHAIN_STREAM_EDGE < a->w; bx++) {
            uint32_t x0 = bx * VT_CHAIN_STREAM_EDGE;
            uint32_t bw = a->w - x0 < VT_CHAIN_STREAM_EDGE ? a->w - x0 : VT_CHAIN_STREAM_EDGE;
            for (uint32_t j = 0; j < bh; j++)
                memcpy(cs->block + (size_t)j * bw * cs->ch, a->rows + j * rb + (size_t)x0 * cs->ch,
                       (size_t)bw * cs->ch);
            int rc = cs->emit(cs->user, l, bx, by, cs->block, bw, bh, err);
            if (rc)
                return rc;
        }
    }
    return 0;
}

static int stage_feed(struct vt_chain_stream *cs, uint32_t i, const float *rows, uint32_t n,
                      struct vts_error *err);

/* Coarser rows [y0, y0 + n) of stage i are made (cs->out): stored and/or passed on. */
static int stage_output(struct vt_chain_stream *cs, uint32_t i, uint32_t n, struct vts_error *err)
{
    struct stage *s = &cs->st[i];
    size_t nt = (size_t)s->dw * n;
    int rc = reserve((void **)&cs->u8, &cs->u8_n, nt * cs->ch, 1, err);
    if (rc)
        return rc;
    bool last_pre = s->level < 0 && i + 1 == cs->pre;
    if (s->level >= 0 || last_pre) {
        vt_filter_from_working(&cs->mode, VTS_SAMPLE_U8, cs->out, cs->u8, nt);
        rc = level_rows(cs, s->level >= 0 ? (uint32_t)s->level : 0, cs->u8, n,
                        (size_t)s->dw * cs->ch, err);
    }
    if (rc || i + 1 >= cs->nstages)
        return rc;
    if (!last_pre) /* the next reduction reads these floats as they are (build_levels) */
        return stage_feed(cs, i + 1, cs->out, n, err);
    /* level 0 from the texture's own mip level: reduced again from its 8-bit texels */
    if ((rc = reserve((void **)&cs->conv, &cs->conv_n, nt * cs->ch, sizeof(float), err)) != 0)
        return rc;
    vt_filter_to_working(&cs->mode, VTS_SAMPLE_U8, cs->u8, cs->conv, nt);
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
    int rc = reserve((void **)&cs->out, &cs->out_n, (size_t)s->dw * n * cs->ch, sizeof(float), err);
    size_t sn = vt_filter_reduce_scratch(k, &src, &dst);
    if (rc == 0)
        rc = reserve((void **)&cs->scratch, &cs->scratch_n, sn ? sn : 1, sizeof(float), err);
    if (rc)
        return rc;
    dst.px = cs->out;
    if ((rc = vt_filter_reduce(k, &edges, &src, &dst, cs->scratch, sn, err)) != 0)
        return rc;
    if (cs->mode.colour == VTS_COLOUR_NORMAL)
        vt_filter_renormalize(&dst);
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
    size_t rf = (size_t)s->fw * cs->ch;
    if (s->nrows + n > s->cap) {
        size_t cap = s->nrows + n + 8;
        if (reserve((void **)&s->buf, &(size_t){0}, cap * rf, sizeof(float), err))
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
    assert(rows->sample == VTS_SAMPLE_U8 && rows->channels == cs->ch);
    int rc = 0;
    if (cs->pre == 0)
        rc = level_rows(cs, 0, rows->pixels, rows->height, rows->stride, err);
    if (rc || cs->nstages == 0)
        return rc;
    size_t nt = (size_t)rows->width * rows->height;
    if ((rc = reserve((void **)&cs->conv, &cs->conv_n, nt * cs->ch, sizeof(float), err)) != 0)
        return rc;
    for (uint32_t y = 0; y < rows->height; y++)
        vt_filter_to_working(&cs->mode, VTS_SAMPLE_U8, vt_image_at(rows, 0, y),
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
    cs->pre = pre;
    cs->nlevels = s->level_count;
    cs->nstages = pre + s->level_count - 1;
    cs->emit = emit;
    cs->user = user;
    uint32_t w = tw, h = th;
    for (uint32_t i = 0; i < cs->nstages; i++) {
        cs->st[i] = (struct stage){w,
                                   h,
                                   ceil_shift(w, 1),
                                   ceil_shift(h, 1),
                                   NULL,
                                   0,
                                   0,
                                   0,
                                   0,
                                   i < pre ? -1 : (int)(i - pre + 1)};
        w = ceil_shift(w, 1);
        h = ceil_shift(h, 1);
    }
    bool ok = (cs->block = malloc((size_t)VT_CHAIN_STREAM_EDGE * VT_CHAIN_STREAM_EDGE * cs->ch));
    for (uint32_t l = 0; ok && l < cs->nlevels && l < VTS_MAX_LEVELS; l++) {
        struct level_acc *a = &cs->acc[l];
        a->w = ceil_shift(s->width, l);
        a->h = ceil_shift(s->height, l);
        ok = (a->rows = malloc((size_t)a->w * cs->ch * VT_CHAIN_STREAM_EDGE));
    }
    if (!ok) {
        vt_chain_stream_destroy(cs);
        vt_error_set(err, VTS_ERR_NOMEM, "out of memory for a texture chain");
        return NULL;
    }
    return cs;
}

void vt_chain_stream_destroy(struct vt_chain_stream *cs)
{
    if (!cs)
        return;
    for (uint32_t i = 0; i < cs->nstages; i++)
        free(cs->st[i].buf);
    for (uint32_t l = 0; l < VTS_MAX_LEVELS; l++)
        free(cs->acc[l].rows);
    free(cs->out);
    free(cs->scratch);
    free(cs->conv);
    free(cs->u8);
    free(cs->block);
    free(cs);
}
