/* Region and band reads of the mip pyramid (see internal/vt_pyramid_read.h). */
#include "internal/vt_pyramid_read.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "internal/vt_pyramid_impl.h"
#include "vt_error.h"

int vt_pyramid_read_scratch_alloc(struct vt_pyramid_read_scratch *s, uint32_t max_edge)
{
    s->cap = (size_t)max_edge + 4;
    s->xs = calloc(s->cap, sizeof *s->xs);
    s->ys = calloc(s->cap, sizeof *s->ys);
    return s->xs && s->ys ? 0 : VTS_ERR_NOMEM;
}

void vt_pyramid_read_scratch_release(struct vt_pyramid_read_scratch *s)
{
    free(s->xs);
    free(s->ys);
    s->xs = s->ys = NULL;
}

/* Splits [a, b) of an axis of size n into read runs and clamped (replicated) edges, or wrapped
 * runs. Returns the number of segments (at most cap). */
static size_t make_segments(int64_t a, int64_t b, uint32_t n, bool wrap,
                            struct vt_pyramid_read_segment *seg, size_t cap)
{
    size_t k = 0;
    if (!wrap) {
        if (a < 0)
            seg[k++] =
                (struct vt_pyramid_read_segment){0, 0, (uint32_t)((b < 0 ? b : 0) - a), true};
        int64_t lo = a < 0 ? 0 : a, hi = b > n ? n : b;
        if (lo < hi)
            seg[k++] =
                (struct vt_pyramid_read_segment){lo - a, (uint32_t)lo, (uint32_t)(hi - lo), false};
        if (b > n)
            seg[k++] = (struct vt_pyramid_read_segment){(a > n ? a : n) - a, n - 1,
                                                        (uint32_t)(b - (a > n ? a : n)), true};
        return k;
    }
    for (int64_t p = a; p < b && k < cap;) {
        int64_t s = ((p % n) + n) % n;
        int64_t len = b - p < (int64_t)n - s ? b - p : (int64_t)n - s;
        seg[k++] = (struct vt_pyramid_read_segment){p - a, (uint32_t)s, (uint32_t)len, false};
        p += len;
    }
    return k;
}

/* Fills n texels of tb bytes at d with a copy of the texel at e (outside them), doubling the
 * copied run each step: a few memcpy calls instead of one per texel. */
static void fill_texels(unsigned char *d, const unsigned char *e, size_t tb, size_t n)
{
    if (n == 0)
        return;
    memcpy(d, e, tb);
    for (size_t done = 1; done < n;) {
        size_t k = done < n - done ? done : n - done;
        memcpy(d + done * tb, d, k * tb);
        done += k;
    }
}

int vt_pyramid_read_region(struct vt_source *src, uint32_t width, uint32_t height, bool wrap,
                           struct vt_pyramid_read_scratch *s, int64_t x0, int64_t y0,
                           struct vt_image *dst, struct vts_error *err)
{
    size_t nx = make_segments(x0, x0 + dst->width, width, wrap, s->xs, s->cap);
    size_t ny = make_segments(y0, y0 + dst->height, height, wrap, s->ys, s->cap);
    size_t tb = vt_image_texel_bytes(dst);
    for (size_t j = 0; j < ny; j++) {
        if (s->ys[j].replicate)
            continue;
        for (size_t i = 0; i < nx; i++) {
            if (s->xs[i].replicate)
                continue;
            struct vt_image v =
                vt_pyramid_view(dst, s->xs[i].dst, s->ys[j].dst, s->xs[i].len, s->ys[j].len);
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
                fill_texels(vt_image_at(dst, (uint32_t)s->xs[i].dst, y),
                            vt_image_at(dst, (uint32_t)edge, y), tb, s->xs[i].len);
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
                            struct vts_error *err)
{
    const struct vt_pyramid_read_band *b = ctx;
    if ((int64_t)y < b->y0 || (int64_t)y + dst->height > b->y0 + b->img.height)
        return vt_error_set(err, VTS_ERR_ARG, "rows %u..%u are outside the band", y,
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

int vt_pyramid_read_band_move(struct vt_pyramid_read_band *b, struct vt_source *src, int64_t a,
                              int64_t end, struct vts_error *err)
{
    const struct vt_source_info *in = &src->info;
    struct vt_pyramid_read_band nb = {.y0 = a, .valid = true};
    int rc = vt_image_alloc(&nb.img, in->width, (uint32_t)(end - a), in->channels, in->sample, err);
    if (rc)
        return rc;
    /* bands move down: rows [a, keep_hi) are already in the old band, the rest is read */
    int64_t old_end = b->valid ? b->y0 + b->img.height : a;
    bool can_keep = b->valid && a >= b->y0 && a < old_end;
    int64_t keep_hi = can_keep ? (old_end < end ? old_end : end) : a;
    for (int64_t y = a; y < keep_hi; y++)
        memcpy(vt_image_at(&nb.img, 0, (uint32_t)(y - a)),
               vt_image_at(&b->img, 0, (uint32_t)(y - b->y0)),
               vt_image_texel_bytes(&nb.img) * in->width);
    if (keep_hi < end) {
        struct vt_image v =
            vt_pyramid_view(&nb.img, 0, keep_hi - a, in->width, (uint32_t)(end - keep_hi));
        rc = vt_source_read(src, 0, (uint32_t)keep_hi, &v, err);
    }
    vt_image_release(&b->img);
    b->img = nb.img;
    b->y0 = nb.y0;
    b->valid = true;
    if (rc)
        vt_pyramid_read_band_release(b);
    return rc;
}

void vt_pyramid_read_band_init(struct vt_pyramid_read_band *b, const struct vt_source *of)
{
    *b = (struct vt_pyramid_read_band){.valid = false};
    b->source = (struct vt_source){.info = of->info, .ops = &band_ops, .ctx = b};
    snprintf(b->source.name, sizeof b->source.name, "%s", of->name);
}

void vt_pyramid_read_band_release(struct vt_pyramid_read_band *b)
{
    vt_image_release(&b->img);
    b->valid = false;
}
