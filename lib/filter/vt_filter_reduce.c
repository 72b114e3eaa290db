/* Mip filtering: the separable 2:1 reduction of a float region, or of stored texels converted
 * row by row (vt_filter.h; kernels in vt_filter.c, conversions in vt_filter_convert.c).
 *
 * Numerics: the reduction sums floats in a fixed tap order (first tap times its weight, then each
 * next tap added), in every code path, so that an output texel has the same bits whichever region
 * split, edge path or vector path computed it. The build uses -std=c11, so GCC does not contract
 * a*b+c into fused multiply-adds behind our back. */
#include "vt_filter.h"

#include <string.h>

#include "internal/vt_filter_impl.h"
#include "vt_checked.h"
#include "vt_error.h"
#include "vts.h"

/* ---- reduction ---- */

typedef float v4f __attribute__((vector_size(16)));

static inline v4f load4(const float *p)
{
    v4f v;
    memcpy(&v, p, sizeof v);
    return v;
}

static inline void store4(float *p, v4f v)
{
    memcpy(p, &v, sizeof v);
}

/* One axis of a reduction: maps a coarser position and a tap to a finer position. */
struct axis {
    int64_t dst0;   /* first coarser position of the dst region */
    uint32_t dst_n; /* coarser positions in the dst region */
    int64_t src0;   /* first finer position held by src */
    uint32_t src_n; /* finer positions held by src */
    uint32_t level; /* finer level size */
    bool wrap;
    int first, count;
};

static inline int64_t clamp_i64(int64_t v, int64_t lo, int64_t hi)
{
    return v < lo ? lo : (v > hi ? hi : v);
}

/* Finer position read by tap t of coarser position X (level coordinates). */
static inline int64_t tap_pos(const struct axis *a, int64_t X, int t)
{
    if (a->wrap)
        return 2 * X + a->first + t;
    X = clamp_i64(X, 0, ((int64_t)a->level + 1) / 2 - 1);
    return clamp_i64(2 * X + a->first + t, 0, (int64_t)a->level - 1);
}

/* True when every position read lies inside src (positions grow with X and t). */
static bool axis_covered(const struct axis *a)
{
    int64_t lo = tap_pos(a, a->dst0, 0), hi = tap_pos(a, a->dst0 + a->dst_n - 1, a->count - 1);
    return lo >= a->src0 && hi < a->src0 + (int64_t)a->src_n;
}

/* The dst indices [*begin, *end) whose taps need no clamping: 2X + first + t for all t. */
static void axis_interior(const struct axis *a, uint32_t *begin, uint32_t *end)
{
    if (a->wrap) {
        *begin = 0;
        *end = a->dst_n;
        return;
    }
    /* X >= 0, 2X + first >= 0, 2X + first + count - 1 <= level - 1, X < ceil(level / 2) */
    int64_t lo = (-a->first + 1) / 2, hi = ((int64_t)a->level - a->first - a->count) / 2;
    int64_t coarse_last = ((int64_t)a->level + 1) / 2 - 1;
    lo = lo < 0 ? 0 : lo;
    hi = hi < coarse_last ? hi : coarse_last;
    if ((int64_t)a->level < a->count + a->first) /* no interior at all */
        hi = lo - 1;
    int64_t b = clamp_i64(lo - a->dst0, 0, a->dst_n), e = clamp_i64(hi + 1 - a->dst0, 0, a->dst_n);
    *begin = (uint32_t)b;
    *end = (uint32_t)(e > b ? e : b);
}

/* Call sites pass constant tap and channel counts to these always-inlined loops, and the tap
 * loops are unrolled (GCC's -O2 leaves a 12-iteration loop rolled, with the weights in memory). */
#define ALWAYS_INLINE inline __attribute__((always_inline))
#define UNROLL_TAPS   _Pragma("GCC unroll 16")

/* Horizontal sums of n interior dst texels: texel x reads taps row[2x..2x+count-1] (texels of ch
 * floats). */
static ALWAYS_INLINE void h_interior(const float *row, float *out, const float *w, int count,
                                     uint32_t ch, size_t n)
{
    if (ch == 4) {
        v4f wv[VT_KERNEL_MAX_TAPS];
        for (int t = 0; t < count; t++)
            wv[t] = (v4f){w[t], w[t], w[t], w[t]};
        for (size_t x = 0; x < n; x++) {
            const float *p = row + 8 * x;
            v4f acc = wv[0] * load4(p);
            UNROLL_TAPS
            for (int t = 1; t < count; t++)
                acc += wv[t] * load4(p + 4 * t);
            store4(out + 4 * x, acc);
        }
        return;
    }
    size_t x = 0;
    if (ch == 3 && n > 1) {
        /* 4-float loads whose lane 3 (the next texel's first channel) is discarded; store4 spills
         * into the next texel, which is written after. The last texel is left to the scalar loop
         * so that no load reads past its last tap. */
        v4f wv[VT_KERNEL_MAX_TAPS];
        for (int t = 0; t < count; t++)
            wv[t] = (v4f){w[t], w[t], w[t], w[t]};
        for (; x + 1 < n; x++) {
            const float *p = row + 6 * x;
            v4f acc = wv[0] * load4(p);
            UNROLL_TAPS
            for (int t = 1; t < count; t++)
                acc += wv[t] * load4(p + 3 * t);
            store4(out + 3 * x, acc);
        }
    }
    for (; x < n; x++) {
        const float *p = row + 2 * ch * x;
        for (uint32_t c = 0; c < ch; c++) {
            float acc = w[0] * p[c];
            for (int t = 1; t < count; t++)
                acc += w[t] * p[t * ch + c];
            out[ch * x + c] = acc;
        }
    }
}

/* One dst texel whose taps are clamped: same order of operations as h_interior. */
static void h_edge(const struct axis *a, const float *src_row, float *out, const float *w,
                   uint32_t ch, uint32_t x)
{
    const float *p[VT_KERNEL_MAX_TAPS];
    for (int t = 0; t < a->count; t++)
        p[t] = src_row + (size_t)(tap_pos(a, a->dst0 + x, t) - a->src0) * ch;
    for (uint32_t c = 0; c < ch; c++) {
        float acc = w[0] * p[0][c];
        for (int t = 1; t < a->count; t++)
            acc += w[t] * p[t][c];
        out[(size_t)x * ch + c] = acc;
    }
}

/* The dst indices from which on every texel lies past the coarser level's last texel (clamped
 * edges): they read the same taps as that texel, so they are copies of the first of them (or of
 * texel rep - 1 when it is the edge texel). dst_n when there are none (or with wrap). */
static uint32_t axis_replicas(const struct axis *a)
{
    if (a->wrap)
        return a->dst_n;
    int64_t coarse_last = ((int64_t)a->level + 1) / 2 - 1;
    return (uint32_t)clamp_i64(coarse_last + 1 - a->dst0, 1, a->dst_n);
}

/* Horizontal pass of one finer row: edge texels [0, ib) and [ie, rep), interior [ib, ie), copies
 * of texel rep - 1 from rep on (ib <= ie <= rep). */
static void h_row(const struct axis *a, const float *w, uint32_t ch, uint32_t ib, uint32_t ie,
                  uint32_t rep, const float *src_row, float *out)
{
    for (uint32_t x = 0; x < ib; x++)
        h_edge(a, src_row, out, w, ch, x);
    if (ib < ie) {
        /* texels ib.. read consecutive taps from their first one on; output starts at ib */
        const float *row = src_row + (size_t)(2 * (a->dst0 + ib) + a->first - a->src0) * ch;
        float *o = out + (size_t)ib * ch;
        size_t n = ie - ib;
        int taps = a->count;
        if (taps == 2 && ch == 4)
            h_interior(row, o, w, 2, 4, n);
        else if (taps == 4 && ch == 4)
            h_interior(row, o, w, 4, 4, n);
        else if (taps == 12 && ch == 4)
            h_interior(row, o, w, 12, 4, n);
        else if (taps == 4 && ch == 3)
            h_interior(row, o, w, 4, 3, n);
        else if (taps == 2 && ch == 3)
            h_interior(row, o, w, 2, 3, n);
        else if (taps == 12 && ch == 3)
            h_interior(row, o, w, 12, 3, n);
        else
            h_interior(row, o, w, taps, ch, n);
    }
    for (uint32_t x = ie; x < rep; x++)
        h_edge(a, src_row, out, w, ch, x);
    for (uint32_t x = rep; x < a->dst_n; x++)
        memcpy(out + (size_t)x * ch, out + (size_t)(rep - 1) * ch, ch * sizeof(float));
}

/* The horizontal pass of one stored 8-bit row with the box kernel, every texel before rep
 * interior: one table load per sample gives w[0] * t[a] + w[1] * t[b] for its two taps (the
 * conversion and the sum h_interior would compute); copies of texel rep - 1 from rep on. */
static void h_row_pairs(const struct axis *a, const float *pairs, uint32_t ch, uint32_t rep,
                        const uint8_t *src_row, float *out)
{
    const uint8_t *p = src_row + (size_t)(2 * a->dst0 + a->first - a->src0) * ch;
    if (ch == 3) {
        for (uint32_t x = 0; x < rep; x++, p += 6) {
            float r = pairs[p[0] << 8 | p[3]], g = pairs[p[1] << 8 | p[4]];
            float b = pairs[p[2] << 8 | p[5]];
            out[3 * x] = r, out[3 * x + 1] = g, out[3 * x + 2] = b;
        }
    } else {
        for (uint32_t x = 0; x < rep; x++, p += 2 * ch)
            for (uint32_t c = 0; c < ch; c++)
                out[(size_t)x * ch + c] = pairs[p[c] << 8 | p[ch + c]];
    }
    for (uint32_t x = rep; x < a->dst_n; x++)
        memcpy(out + (size_t)x * ch, out + (size_t)(rep - 1) * ch, ch * sizeof(float));
}

/* out[i] = w[0] * rows[0][i] + w[1] * rows[1][i] + ... in that order. */
static ALWAYS_INLINE void v_row(const float *const *rows, const float *w, int count, float *out,
                                size_t n)
{
    v4f wv[VT_KERNEL_MAX_TAPS];
    for (int t = 0; t < count; t++)
        wv[t] = (v4f){w[t], w[t], w[t], w[t]};
    size_t i = 0;
    for (; i + 4 <= n; i += 4) {
        v4f acc = wv[0] * load4(rows[0] + i);
        UNROLL_TAPS
        for (int t = 1; t < count; t++)
            acc += wv[t] * load4(rows[t] + i);
        store4(out + i, acc);
    }
    for (; i < n; i++) {
        float acc = w[0] * rows[0][i];
        for (int t = 1; t < count; t++)
            acc += w[t] * rows[t][i];
        out[i] = acc;
    }
}

static size_t scratch_rows(const struct vt_kernel *k, const struct vt_fregion *src,
                           const struct vt_fregion *dst)
{
    uint64_t rows = 2 * (uint64_t)dst->height + (uint64_t)k->count - 2;
    return (size_t)(rows < src->height ? rows : src->height);
}

size_t vt_filter_reduce_scratch(const struct vt_kernel *k, const struct vt_fregion *src,
                                const struct vt_fregion *dst)
{
    size_t n;
    if (dst->width == 0 || dst->height == 0)
        return 0;
    if (!vt_size_mul3(scratch_rows(k, src, dst), dst->width, dst->channels, &n))
        return SIZE_MAX;
    return n;
}

static int check_reduce_args(const struct vt_kernel *k, const struct vt_edges *edges,
                             const struct vt_fregion *src, const struct vt_fregion *dst,
                             const struct axis *ax, const struct axis *ay, size_t scratch_floats,
                             struct vts_error *err)
{
    if (src->channels != dst->channels || src->channels < 1 || src->channels > 4)
        return vt_error_set(err, VTS_ERR_ARG, "reduce: %u source channels, %u destination",
                            src->channels, dst->channels);
    if (edges->level_w == 0 || edges->level_h == 0 || k->count < 1 || k->count > VT_KERNEL_MAX_TAPS)
        return vt_error_set(err, VTS_ERR_ARG, "reduce: empty level or bad kernel");
    if (!axis_covered(ax) || !axis_covered(ay))
        return vt_error_set(
            err, VTS_ERR_ARG,
            "reduce: source %ux%u at (%lld,%lld) does not cover the %s taps of %ux%u at (%lld,%lld)",
            src->width, src->height, (long long)src->x0, (long long)src->y0,
            vt_filter_name(k->kind), dst->width, dst->height, (long long)dst->x0,
            (long long)dst->y0);
    if (!vt_filter_is_selection(k->kind) && scratch_floats < vt_filter_reduce_scratch(k, src, dst))
        return vt_error_set(err, VTS_ERR_ARG, "reduce: scratch of %zu floats is too small",
                            scratch_floats);
    return 0;
}

/* Where the finer rows of a reduction come from: a float region, or stored samples converted
 * to the working space row by row (into the last row of scratch) just before their horizontal
 * pass. */
struct row_source {
    const struct vt_fregion *src;
    const struct vt_stored_rows *stored; /* NULL: src->px holds working floats */
    float *row;                          /* stored: one converted row */
};

/* Finer row y; a stored row is converted in the texels [x0, x1) the horizontal pass reads. */
static const float *source_row(const struct row_source *rs, int64_t y, uint32_t x0, uint32_t x1)
{
    const struct vt_fregion *src = rs->src;
    size_t r = (size_t)(y - src->y0);
    if (!rs->stored)
        return src->px + r * src->width * src->channels;
    const struct vt_stored_rows *st = rs->stored;
    size_t texel = vts_sample_bytes(st->sample) * src->channels;
    vt_filter_to_working(st->mode, st->sample,
                         (const unsigned char *)st->px + r * st->stride + x0 * texel,
                         rs->row + (size_t)x0 * src->channels, x1 - x0);
    return rs->row;
}

/* ---- selections (nearest, mode, min, max) ---- */

/* Texel t of a 2x2 footprint, in the order top-left, top-right, bottom-left, bottom-right. */
struct footprint {
    const float *p[4];
};

static ALWAYS_INLINE void select_nearest(const struct footprint *f, uint32_t ch, float *out)
{
    for (uint32_t c = 0; c < ch; c++)
        out[c] = f->p[0][c];
}

/* The most frequent texel (whole texels compared bit for bit, so -0 and 0 differ and a NaN
 * equals the same NaN); ties go to the first in footprint order. */
static ALWAYS_INLINE void select_mode(const struct footprint *f, uint32_t ch, float *out)
{
    uint32_t bits[4][4];
    for (int i = 0; i < 4; i++)
        for (uint32_t c = 0; c < ch; c++)
            memcpy(&bits[i][c], f->p[i] + c, sizeof(float));
    int count[4] = {1, 1, 1, 1};
    for (int i = 0; i < 4; i++)
        for (int j = i + 1; j < 4; j++) {
            bool same = true;
            for (uint32_t c = 0; c < ch; c++)
                same &= bits[i][c] == bits[j][c];
            count[i] += same;
            count[j] += same;
        }
    int best = 0;
    for (int i = 1; i < 4; i++)
        if (count[i] > count[best])
            best = i;
    for (uint32_t c = 0; c < ch; c++)
        out[c] = f->p[best][c];
}

/* Per channel, the smallest (or largest) value; a NaN is passed over unless all four are NaN
 * (then the last one's bits). Equal values (0 and -0) keep the first in footprint order. */
static ALWAYS_INLINE void select_extreme(const struct footprint *f, uint32_t ch, bool max,
                                         float *out)
{
    for (uint32_t c = 0; c < ch; c++) {
        float v = f->p[0][c];
        for (int t = 1; t < 4; t++) {
            float u = f->p[t][c];
            if (v != v || (max ? u > v : u < v))
                v = u;
        }
        out[c] = v;
    }
}

/* A finer row of a selection: src's own floats, or stored samples converted in [x0, x1) into
 * buf (src->width texels). */
static const float *select_row(const struct vt_fregion *src, const struct vt_stored_rows *stored,
                               int64_t y, uint32_t x0, uint32_t x1, float *buf)
{
    size_t r = (size_t)(y - src->y0);
    if (!stored)
        return src->px + r * src->width * src->channels;
    size_t texel = vts_sample_bytes(stored->sample) * src->channels;
    vt_filter_to_working(stored->mode, stored->sample,
                         (const unsigned char *)stored->px + r * stored->stride + x0 * texel,
                         buf + (size_t)x0 * src->channels, x1 - x0);
    return buf;
}

/* One output row of a selection from finer rows top and bottom: texels [0, rep) computed, the
 * ones after copies of texel rep - 1 (past the coarser level's edge). Called with a constant ch
 * (select_out_row), so that the channel loops unroll. */
static ALWAYS_INLINE void select_out_row_ch(enum vt_filter_kind kind, const struct axis *ax,
                                            uint32_t ch, uint32_t rep, const float *top,
                                            const float *bottom, float *out)
{
    for (uint32_t x = 0; x < rep; x++) {
        size_t a = (size_t)(tap_pos(ax, ax->dst0 + x, 0) - ax->src0) * ch;
        size_t b = (size_t)(tap_pos(ax, ax->dst0 + x, 1) - ax->src0) * ch;
        struct footprint f = {{top + a, top + b, bottom + a, bottom + b}};
        float *o = out + (size_t)x * ch;
        if (kind == VT_FILTER_NEAREST)
            select_nearest(&f, ch, o);
        else if (kind == VT_FILTER_MODE)
            select_mode(&f, ch, o);
        else
            select_extreme(&f, ch, kind == VT_FILTER_MAX, o);
    }
    for (uint32_t x = rep; x < ax->dst_n; x++)
        memcpy(out + (size_t)x * ch, out + (size_t)(rep - 1) * ch, ch * sizeof(float));
}

static void select_out_row(enum vt_filter_kind kind, const struct axis *ax, uint32_t ch,
                           uint32_t rep, const float *top, const float *bottom, float *out)
{
    if (ch == 1)
        select_out_row_ch(kind, ax, 1, rep, top, bottom, out);
    else if (ch == 2)
        select_out_row_ch(kind, ax, 2, rep, top, bottom, out);
    else if (ch == 3)
        select_out_row_ch(kind, ax, 3, rep, top, bottom, out);
    else
        select_out_row_ch(kind, ax, 4, rep, top, bottom, out);
}

/* A selection: every coarser texel from the 2x2 finer texels the box would read (the same
 * clamped or wrapped positions), no weights. Stored rows are converted two at a time into
 * scratch (2 * src->width texels). */
static int select_reduce(const struct vt_kernel *k, const struct axis *ax, const struct axis *ay,
                         const struct vt_fregion *src, const struct vt_stored_rows *stored,
                         struct vt_fregion *dst, float *scratch, size_t scratch_floats,
                         struct vts_error *err)
{
    uint32_t ch = src->channels, rep_x = axis_replicas(ax), rep_y = axis_replicas(ay);
    size_t row_floats = (size_t)src->width * ch, out_floats = (size_t)dst->width * ch;
    if (k->first != 0 || k->count != 2)
        return vt_error_set(err, VTS_ERR_ARG, "reduce: a selection reads 2x2 texels");
    if (stored && scratch_floats / 2 < row_floats)
        return vt_error_set(err, VTS_ERR_ARG, "reduce: scratch of %zu floats is too small",
                            scratch_floats);
    uint32_t read0 = (uint32_t)(tap_pos(ax, ax->dst0, 0) - ax->src0);
    uint32_t read1 = (uint32_t)(tap_pos(ax, ax->dst0 + rep_x - 1, 1) - ax->src0) + 1;
    for (uint32_t y = 0; y < dst->height; y++) {
        float *out = dst->px + (size_t)y * out_floats;
        if (y >= rep_y) {
            memcpy(out, out - out_floats, out_floats * sizeof(float));
            continue;
        }
        int64_t ya = tap_pos(ay, ay->dst0 + y, 0), yb = tap_pos(ay, ay->dst0 + y, 1);
        const float *top = select_row(src, stored, ya, read0, read1, scratch);
        const float *bottom =
            yb == ya ? top : select_row(src, stored, yb, read0, read1, scratch + row_floats);
        select_out_row(k->kind, ax, ch, rep_x, top, bottom, out);
    }
    return 0;
}

/* ---- the reduction ---- */

static int reduce(const struct vt_kernel *k, const struct vt_edges *edges,
                  const struct vt_fregion *src, const struct vt_stored_rows *stored,
                  struct vt_fregion *dst, float *scratch, size_t scratch_floats,
                  struct vts_error *err)
{
    if (dst->width == 0 || dst->height == 0)
        return 0;
    struct axis ax = {dst->x0,        dst->width,    src->x0,  src->width,
                      edges->level_w, edges->wrap_x, k->first, k->count};
    struct axis ay = {dst->y0,        dst->height,   src->y0,  src->height,
                      edges->level_h, edges->wrap_y, k->first, k->count};
    if (vt_filter_is_selection(k->kind)) {
        int rc = check_reduce_args(k, edges, src, dst, &ax, &ay, scratch_floats, err);
        if (rc == 0 && stored &&
            (stored->mode->channels != src->channels || stored->sample < VTS_SAMPLE_U8 ||
             stored->sample > VTS_SAMPLE_F32))
            rc = vt_error_set(err, VTS_ERR_ARG, "reduce: stored rows of %u channels, region %u",
                              stored->mode->channels, src->channels);
        return rc ? rc : select_reduce(k, &ax, &ay, src, stored, dst, scratch, scratch_floats, err);
    }
    size_t row_extra = stored ? (size_t)src->width * src->channels : 0;
    if (scratch_floats < row_extra)
        return vt_error_set(err, VTS_ERR_ARG, "reduce: scratch of %zu floats is too small",
                            scratch_floats);
    int rc = check_reduce_args(k, edges, src, dst, &ax, &ay, scratch_floats - row_extra, err);
    if (rc < 0)
        return rc;
    if (stored && (stored->mode->channels != src->channels || stored->sample < VTS_SAMPLE_U8 ||
                   stored->sample > VTS_SAMPLE_F32))
        return vt_error_set(err, VTS_ERR_ARG, "reduce: stored rows of %u channels, region %u",
                            stored->mode->channels, src->channels);

    uint32_t ch = src->channels, ib, ie, rep_x = axis_replicas(&ax), rep_y = axis_replicas(&ay);
    axis_interior(&ax, &ib, &ie);
    size_t row_floats = (size_t)dst->width * ch;
    struct row_source rs = {src, stored, scratch + (scratch_floats - row_extra)};
    /* the finer texels the horizontal pass reads (positions grow with X and t) */
    uint32_t read0 = (uint32_t)(tap_pos(&ax, ax.dst0, 0) - ax.src0);
    uint32_t read1 = (uint32_t)(tap_pos(&ax, ax.dst0 + rep_x - 1, k->count - 1) - ax.src0) + 1;
    /* Scratch row r holds the horizontal pass of finer row row0 + r. Rows are filled lazily,
     * in increasing order, just before the first output row that needs them, so the rows in
     * use stay in cache (and each stored row is converted once). Output rows from rep_y on are
     * copies of row rep_y - 1 (past the coarser level's edge). */
    int64_t row0 = tap_pos(&ay, ay.dst0, 0), filled = row0;
    /* 8-bit rows, box kernel, no clamped texel: table pairs instead of convert + sum */
    const float *pairs =
        stored && stored->sample == VTS_SAMPLE_U8 && k->count == 2 && ib == 0 && ie == rep_x
            ? vt_filter_u8_pair_table(stored->mode, k->weights)
            : NULL;
    for (uint32_t y = 0; y < dst->height; y++) {
        const float *rows[VT_KERNEL_MAX_TAPS];
        float *out = dst->px + (size_t)y * row_floats;
        if (y >= rep_y) {
            memcpy(out, out - row_floats, row_floats * sizeof(float));
            continue;
        }
        int64_t last = tap_pos(&ay, ay.dst0 + y, k->count - 1);
        for (; filled <= last; filled++) {
            float *h = scratch + (size_t)(filled - row0) * row_floats;
            if (pairs)
                h_row_pairs(
                    &ax, pairs, ch, rep_x,
                    (const uint8_t *)stored->px + (size_t)(filled - src->y0) * stored->stride, h);
            else
                h_row(&ax, k->weights, ch, ib, ie, rep_x, source_row(&rs, filled, read0, read1), h);
        }
        for (int t = 0; t < k->count; t++)
            rows[t] = scratch + (size_t)(tap_pos(&ay, ay.dst0 + y, t) - row0) * row_floats;
        if (k->count == 2)
            v_row(rows, k->weights, 2, out, row_floats);
        else if (k->count == 4)
            v_row(rows, k->weights, 4, out, row_floats);
        else if (k->count == 12)
            v_row(rows, k->weights, 12, out, row_floats);
        else
            v_row(rows, k->weights, k->count, out, row_floats);
    }
    return 0;
}

int vt_filter_reduce(const struct vt_kernel *k, const struct vt_edges *edges,
                     const struct vt_fregion *src, struct vt_fregion *dst, float *scratch,
                     size_t scratch_floats, struct vts_error *err)
{
    return reduce(k, edges, src, NULL, dst, scratch, scratch_floats, err);
}

int vt_filter_reduce_stored(const struct vt_kernel *k, const struct vt_edges *edges,
                            const struct vt_fregion *src, const struct vt_stored_rows *stored,
                            struct vt_fregion *dst, float *scratch, size_t scratch_floats,
                            struct vts_error *err)
{
    return reduce(k, edges, src, stored, dst, scratch, scratch_floats, err);
}

size_t vt_filter_reduce_stored_scratch(const struct vt_kernel *k, const struct vt_fregion *src,
                                       const struct vt_fregion *dst)
{
    size_t n = vt_filter_reduce_scratch(k, src, dst), row;
    if (!vt_size_mul(src->width, src->channels, &row) || n > SIZE_MAX - row)
        return SIZE_MAX;
    if (vt_filter_is_selection(k->kind)) /* two converted rows (select_reduce) */
        return row > SIZE_MAX / 2 ? SIZE_MAX : 2 * row;
    return n + row;
}
