/* Mip filtering: kernel weights, reductions (of floats and of stored texels, in linear light, with
 * premultiplied alpha, normals, clamped and wrapped edges) against double-precision references;
 * the conversions alone are test_vt_filter_convert.c. `test_vt_filter --bench` prints throughput
 * figures instead (docs/filters.md). */
#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "filter_test_util.h"
#include "vt_filter.h"
#include "vt_test.h"
#include "vts.h"

static float *region_alloc(struct vt_fregion *r, int64_t x0, int64_t y0, uint32_t w, uint32_t h,
                           uint32_t ch)
{
    *r = (struct vt_fregion){x0, y0, w, h, ch, calloc((size_t)w * h * ch, sizeof(float))};
    return r->px;
}

/* Reduces src into dst with a freshly allocated scratch of the advertised size. */
static int reduce(const struct vt_kernel *k, const struct vt_edges *e, const struct vt_fregion *src,
                  struct vt_fregion *dst)
{
    size_t n = vt_filter_reduce_scratch(k, src, dst);
    float *scratch = malloc((n ? n : 1) * sizeof(float));
    int rc = vt_filter_reduce(k, e, src, dst, scratch, n, NULL);
    free(scratch);
    return rc;
}

/* ---- kernels ---- */

static void filter_names_parse_and_print(void)
{
    enum vt_filter_kind kind;
    for (int i = 0; i < 4; i++) {
        VT_CHECK_INT_EQ(vt_filter_parse(vt_filter_name((enum vt_filter_kind)i), &kind), 0);
        VT_CHECK_INT_EQ(kind, i);
    }
    VT_CHECK(strcmp(vt_filter_name(VT_FILTER_LANCZOS3), "lanczos3") == 0);
    VT_CHECK_INT_EQ(vt_filter_parse("Box", &kind), VTS_ERR_ARG);
    VT_CHECK_INT_EQ(vt_filter_parse("", &kind), VTS_ERR_ARG);
    VT_CHECK_INT_EQ(vt_filter_parse(NULL, &kind), VTS_ERR_ARG);
    VT_CHECK(strcmp(vt_filter_name((enum vt_filter_kind)9), "?") == 0);
}

static void kernel_weights_sum_to_one(void)
{
    for (int i = 0; i < 4; i++) {
        struct vt_kernel k;
        vt_kernel_init(&k, (enum vt_filter_kind)i);
        double sum = 0.0;
        for (int t = 0; t < k.count; t++)
            sum += k.weights[t];
        VT_CHECK(fabs(sum - 1.0) < 1e-6);
        for (int t = k.count; t < VT_KERNEL_MAX_TAPS; t++)
            VT_CHECK(k.weights[t] == 0.0f);
    }
}

static void box_and_triangle_weights_are_exact(void)
{
    struct vt_kernel k;
    vt_kernel_init(&k, VT_FILTER_BOX);
    VT_CHECK_INT_EQ(k.first, 0);
    VT_CHECK_INT_EQ(k.count, 2);
    VT_CHECK(k.weights[0] == 0.5f && k.weights[1] == 0.5f);
    vt_kernel_init(&k, VT_FILTER_TRIANGLE);
    VT_CHECK_INT_EQ(k.first, -1);
    VT_CHECK_INT_EQ(k.count, 4);
    VT_CHECK(k.weights[0] == 0.125f && k.weights[1] == 0.375f);
    VT_CHECK(k.weights[2] == 0.375f && k.weights[3] == 0.125f);
}

static void sinc_kernels_are_symmetric_with_negative_lobes(void)
{
    for (int i = VT_FILTER_LANCZOS3; i <= VT_FILTER_KAISER; i++) {
        struct vt_kernel k;
        vt_kernel_init(&k, (enum vt_filter_kind)i);
        VT_CHECK_INT_EQ(k.first, -5);
        VT_CHECK_INT_EQ(k.count, 12);
        for (int t = 0; t < 6; t++)
            VT_CHECK(k.weights[t] == k.weights[11 - t]);
        /* centre taps dominate; the first lobe outside is negative */
        VT_CHECK(k.weights[5] > 0.3f && k.weights[5] < 0.5f);
        VT_CHECK(k.weights[3] < 0.0f && k.weights[8] < 0.0f);
        VT_CHECK(k.weights[5] > k.weights[4] && k.weights[4] > k.weights[3]);
    }
    /* Lanczos-3 at x = 0.25 (tap 5): sinc(0.25) sinc(1/12), before normalisation */
    struct vt_kernel l, ka;
    vt_kernel_init(&l, VT_FILTER_LANCZOS3);
    vt_kernel_init(&ka, VT_FILTER_KAISER);
    VT_CHECK(l.weights[0] != ka.weights[0]);
    double pi = 3.14159265358979323846, raw[12], sum = 0;
    for (int t = 0; t < 12; t++) {
        double x = fabs((t - 5 - 0.5) / 2.0);
        raw[t] = sin(pi * x) / (pi * x) * sin(pi * x / 3) / (pi * x / 3);
        sum += raw[t];
    }
    for (int t = 0; t < 12; t++)
        VT_CHECK(fabs(l.weights[t] - raw[t] / sum) < 1e-7);
}

static void kernel_margins_cover_the_taps(void)
{
    static const uint32_t want[] = {0, 1, 5, 5};
    for (int i = 0; i < 4; i++) {
        struct vt_kernel k;
        vt_kernel_init(&k, (enum vt_filter_kind)i);
        uint32_t m = vt_kernel_margin(&k);
        VT_CHECK_INT_EQ(m, want[i]);
        /* block [a, b) reads [2a - m, 2b + m): first tap of a and last tap of b - 1 */
        VT_CHECK_INT_EQ(2 * 3 + k.first, 2 * 3 - (int)m);
        VT_CHECK_INT_EQ(2 * (7 - 1) + k.first + k.count - 1, 2 * 7 + (int)m - 1);
    }
}

/* ---- box reduction against a double reference ---- */

/* Mean of the 2x2 finer texels of coarser (X, Y), clamped at the level edges. */
static double box_ref(const float *level, uint32_t w, uint32_t h, uint32_t ch, int64_t X, int64_t Y,
                      uint32_t c)
{
    int64_t cx = X < 0 ? 0 : (X > (w + 1) / 2 - 1 ? (w + 1) / 2 - 1 : X);
    int64_t cy = Y < 0 ? 0 : (Y > (h + 1) / 2 - 1 ? (h + 1) / 2 - 1 : Y);
    int64_t x0 = 2 * cx, x1 = 2 * cx + 1 < w ? 2 * cx + 1 : w - 1;
    int64_t y0 = 2 * cy, y1 = 2 * cy + 1 < h ? 2 * cy + 1 : h - 1;
    double s = (double)level[(y0 * w + x0) * ch + c] + level[(y0 * w + x1) * ch + c] +
               level[(y1 * w + x0) * ch + c] + level[(y1 * w + x1) * ch + c];
    return s / 4.0;
}

static void box_reduce_one_size(uint32_t w, uint32_t h, uint32_t ch)
{
    struct vt_kernel k;
    vt_kernel_init(&k, VT_FILTER_BOX);
    struct vt_edges e = {w, h, false, false};
    struct vt_fregion src, dst, left, right, top, bottom;
    float *px = region_alloc(&src, 0, 0, w, h, ch);
    for (size_t i = 0; i < (size_t)w * h * ch; i++)
        px[i] = rng_unit() * 2.0f - 0.5f;
    /* dst extends 2 texels past every edge of the coarser level: clamped positions */
    uint32_t cw = (w + 1) / 2, chh = (h + 1) / 2, dw = cw + 4, dh = chh + 4;
    region_alloc(&dst, -2, -2, dw, dh, ch);
    VT_CHECK_INT_EQ(reduce(&k, &e, &src, &dst), 0);
    int bad = 0;
    for (uint32_t y = 0; y < dh; y++)
        for (uint32_t x = 0; x < dw; x++)
            for (uint32_t c = 0; c < ch; c++) {
                double ref = box_ref(px, w, h, ch, (int64_t)x - 2, (int64_t)y - 2, c);
                bad += fabs(dst.px[((size_t)y * dw + x) * ch + c] - ref) > 1e-6;
            }
    VT_CHECK_INT_EQ(bad, 0);

    /* halves (split at an odd column/row) give the same bits as the whole */
    uint32_t sx = dw / 2 + 1, sy = dh / 2 + 1;
    region_alloc(&left, -2, -2, sx, dh, ch);
    region_alloc(&right, -2 + sx, -2, dw - sx, dh, ch);
    region_alloc(&top, -2, -2, dw, sy, ch);
    region_alloc(&bottom, -2, -2 + sy, dw, dh - sy, ch);
    VT_CHECK_INT_EQ(reduce(&k, &e, &src, &left), 0);
    VT_CHECK_INT_EQ(reduce(&k, &e, &src, &right), 0);
    VT_CHECK_INT_EQ(reduce(&k, &e, &src, &top), 0);
    VT_CHECK_INT_EQ(reduce(&k, &e, &src, &bottom), 0);
    int diff = 0;
    for (uint32_t y = 0; y < dh; y++) {
        const float *row = dst.px + (size_t)y * dw * ch;
        diff += memcmp(row, left.px + (size_t)y * sx * ch, sx * ch * sizeof(float)) != 0;
        diff += memcmp(row + sx * ch, right.px + (size_t)y * (dw - sx) * ch,
                       (dw - sx) * ch * sizeof(float)) != 0;
    }
    diff += memcmp(dst.px, top.px, (size_t)sy * dw * ch * sizeof(float)) != 0;
    diff += memcmp(dst.px + (size_t)sy * dw * ch, bottom.px,
                   (size_t)(dh - sy) * dw * ch * sizeof(float)) != 0;
    VT_CHECK_INT_EQ(diff, 0);
    free(src.px);
    free(dst.px);
    free(left.px);
    free(right.px);
    free(top.px);
    free(bottom.px);
}

static void box_reduce_matches_double_reference(void)
{
    for (uint32_t ch = 1; ch <= 4; ch++) {
        box_reduce_one_size(16, 12, ch);
        box_reduce_one_size(5, 7, ch);
        box_reduce_one_size(33, 1, ch);
        box_reduce_one_size(1, 1, ch);
    }
}

static void odd_level_edge_texel_repeats_the_last_finer_texel(void)
{
    struct vt_kernel k;
    vt_kernel_init(&k, VT_FILTER_BOX);
    struct vt_edges e = {5, 1, false, false};
    float px[5] = {0.1f, 0.2f, 0.3f, 0.4f, 0.7f}, out[3];
    struct vt_fregion src = {0, 0, 5, 1, 1, px}, dst = {0, 0, 3, 1, 1, out};
    VT_CHECK_INT_EQ(reduce(&k, &e, &src, &dst), 0);
    VT_CHECK(out[2] == 0.7f);
    VT_CHECK(out[0] == 0.5f * 0.1f + 0.5f * 0.2f);
}

/* Any kernel, any channel count, clamped at every edge: the separable float sums stay within
 * 1e-5 of the 2-D sum computed in double. */
static void every_kernel_matches_a_double_reference(void)
{
    const uint32_t w = 29, h = 18;
    for (uint32_t ch = 1; ch <= 4; ch++) {
        struct vt_fregion src, dst;
        float *px = region_alloc(&src, 0, 0, w, h, ch);
        for (size_t i = 0; i < (size_t)w * h * ch; i++)
            px[i] = rng_unit();
        uint32_t cw = (w + 1) / 2, chh = (h + 1) / 2;
        region_alloc(&dst, -1, -1, cw + 2, chh + 2, ch);
        for (int kind = 0; kind < 4; kind++) {
            struct vt_kernel k;
            vt_kernel_init(&k, (enum vt_filter_kind)kind);
            struct vt_edges e = {w, h, false, false};
            VT_CHECK_INT_EQ(reduce(&k, &e, &src, &dst), 0);
            int bad = 0;
            for (uint32_t y = 0; y < dst.height; y++)
                for (uint32_t x = 0; x < dst.width; x++) {
                    int64_t X = dst.x0 + x, Y = dst.y0 + y;
                    X = X < 0 ? 0 : (X >= cw ? cw - 1 : X);
                    Y = Y < 0 ? 0 : (Y >= chh ? chh - 1 : Y);
                    for (uint32_t c = 0; c < ch; c++) {
                        double sum = 0;
                        for (int ty = 0; ty < k.count; ty++)
                            for (int tx = 0; tx < k.count; tx++) {
                                int64_t fx = 2 * X + k.first + tx, fy = 2 * Y + k.first + ty;
                                fx = fx < 0 ? 0 : (fx >= w ? w - 1 : fx);
                                fy = fy < 0 ? 0 : (fy >= h ? h - 1 : fy);
                                sum += (double)k.weights[tx] * k.weights[ty] *
                                       px[((size_t)fy * w + (size_t)fx) * ch + c];
                            }
                        float got = dst.px[((size_t)y * dst.width + x) * ch + c];
                        bad += fabs(got - sum) > 1e-5;
                    }
                }
            VT_CHECK_INT_EQ(bad, 0);
        }
        free(src.px);
        free(dst.px);
    }
}

/* Splits a coarser region into 5x4 blocks, each reduced from just the src it needs. */
static void kernels_split_identically(uint32_t ch)
{
    const uint32_t w = 37, h = 23;
    struct vt_fregion level;
    float *px = region_alloc(&level, 0, 0, w, h, ch);
    for (size_t i = 0; i < (size_t)w * h * ch; i++)
        px[i] = rng_unit();
    for (int kind = 0; kind < 4; kind++) {
        struct vt_kernel k;
        vt_kernel_init(&k, (enum vt_filter_kind)kind);
        struct vt_edges e = {w, h, false, false};
        struct vt_fregion whole, part;
        region_alloc(&whole, 0, 0, 19, 12, ch);
        VT_CHECK_INT_EQ(reduce(&k, &e, &level, &whole), 0);
        int diff = 0;
        for (uint32_t bx = 0; bx < 19; bx += 5)
            for (uint32_t by = 0; by < 12; by += 4) {
                uint32_t pw = bx + 5 <= 19 ? 5 : 19 - bx, ph = 4;
                region_alloc(&part, bx, by, pw, ph, ch);
                /* a src holding just [2a - m, 2b + m) clamped to the level */
                int64_t m = vt_kernel_margin(&k);
                int64_t x0 = 2 * (int64_t)bx - m, x1 = 2 * (int64_t)(bx + pw) + m;
                int64_t y0 = 2 * (int64_t)by - m, y1 = 2 * (int64_t)(by + ph) + m;
                x0 = x0 < 0 ? 0 : x0, y0 = y0 < 0 ? 0 : y0;
                x1 = x1 > w ? w : x1, y1 = y1 > h ? h : y1;
                struct vt_fregion sub;
                region_alloc(&sub, x0, y0, (uint32_t)(x1 - x0), (uint32_t)(y1 - y0), ch);
                for (int64_t y = y0; y < y1; y++)
                    memcpy(sub.px + (size_t)(y - y0) * sub.width * ch,
                           px + ((size_t)y * w + (size_t)x0) * ch, sub.width * ch * sizeof(float));
                VT_CHECK_INT_EQ(reduce(&k, &e, &sub, &part), 0);
                for (uint32_t y = 0; y < ph; y++)
                    diff += memcmp(part.px + (size_t)y * pw * ch,
                                   whole.px + ((size_t)(by + y) * 19 + bx) * ch,
                                   pw * ch * sizeof(float)) != 0;
                free(sub.px);
                free(part.px);
            }
        VT_CHECK_INT_EQ(diff, 0);
        free(whole.px);
    }
    free(px);
}

/* Any kernel: splitting the dst region (and giving each part only the src it needs) gives the
 * same bits as one call. */
static void every_kernel_is_independent_of_the_region_split(void)
{
    for (uint32_t ch = 3; ch <= 4; ch++)
        kernels_split_identically(ch);
}

/* ---- reductions from stored texels ---- */

/* Random stored samples of a sample type (u16 and f16 bit patterns of finite values in [0, 1]). */
static void fill_stored(uint32_t sample, unsigned char *p, size_t count)
{
    for (size_t i = 0; i < count; i++) {
        if (sample == VTS_SAMPLE_U8) {
            p[i] = (unsigned char)rng_u32();
        } else if (sample == VTS_SAMPLE_U16) {
            uint16_t v = (uint16_t)rng_u32();
            memcpy(p + 2 * i, &v, 2);
        } else if (sample == VTS_SAMPLE_F16) {
            uint16_t v = (uint16_t)(rng_u32() % 0x3c01); /* +0 .. 1.0 */
            memcpy(p + 2 * i, &v, 2);
        } else {
            float v = rng_unit();
            memcpy(p + 4 * i, &v, 4);
        }
    }
}

/* One case: a w x h level of stored samples at (sx0, sy0) (the region the reduction reads: the
 * whole level, or with wrap a larger window), reduced into dst at (dx0, dy0) of dw x dh, through
 * vt_filter_reduce_stored and through vt_filter_to_working + vt_filter_reduce. Returns the number
 * of differing bytes; *bad_check gets the same comparison against a wrong kernel (must differ). */
static size_t stored_case(const struct vt_pixel_mode *m, uint32_t sample, enum vt_filter_kind kind,
                          bool wrap, uint32_t w, uint32_t h, int64_t dx0, int64_t dy0, uint32_t dw,
                          uint32_t dh, size_t *wrong)
{
    struct vt_kernel k, other;
    vt_kernel_init(&k, kind);
    vt_kernel_init(&other, kind == VT_FILTER_BOX ? VT_FILTER_TRIANGLE : VT_FILTER_BOX);
    uint32_t ch = m->channels, m_src = vt_kernel_margin(&k) + 2;
    /* the source window: all the level (clamped), or the level and a margin read modulo it */
    int64_t sx0 = wrap ? 2 * dx0 - m_src : 0, sy0 = wrap ? 2 * dy0 - m_src : 0;
    uint32_t sw = wrap ? 2 * dw + 2 * m_src : w, sh = wrap ? 2 * dh + 2 * m_src : h;
    size_t sb = vts_sample_bytes(sample), texel = sb * ch;
    unsigned char *level = malloc((size_t)w * h * texel);
    unsigned char *win = malloc((size_t)sw * sh * texel);
    fill_stored(sample, level, (size_t)w * h * ch);
    for (uint32_t y = 0; y < sh; y++)
        for (uint32_t x = 0; x < sw; x++) {
            int64_t X = ((sx0 + x) % w + w) % w, Y = ((sy0 + y) % h + h) % h;
            memcpy(win + ((size_t)y * sw + x) * texel, level + ((size_t)Y * w + (size_t)X) * texel,
                   texel);
        }
    struct vt_fregion src, ref_dst, got_dst, bad_dst;
    float *conv = region_alloc(&src, sx0, sy0, sw, sh, ch);
    vt_filter_to_working(m, sample, win, conv, (size_t)sw * sh);
    region_alloc(&ref_dst, dx0, dy0, dw, dh, ch);
    region_alloc(&got_dst, dx0, dy0, dw, dh, ch);
    region_alloc(&bad_dst, dx0, dy0, dw, dh, ch);
    struct vt_edges e = {w, h, wrap, wrap};
    VT_CHECK_INT_EQ(reduce(&k, &e, &src, &ref_dst), 0);
    VT_CHECK_INT_EQ(reduce(&other, &e, &src, &bad_dst), 0);
    struct vt_stored_rows st = {win, (size_t)sw * texel, sample, m};
    size_t n = vt_filter_reduce_stored_scratch(&k, &src, &got_dst);
    VT_CHECK(n >= vt_filter_reduce_scratch(&k, &src, &got_dst) + (size_t)sw * ch);
    float *scratch = malloc(n * sizeof(float));
    struct vt_fregion geometry = src;
    geometry.px = NULL; /* not read */
    VT_CHECK_INT_EQ(vt_filter_reduce_stored(&k, &e, &geometry, &st, &got_dst, scratch, n, NULL), 0);
    /* one float short of the scratch it needs is refused */
    VT_CHECK_INT_EQ(vt_filter_reduce_stored(&k, &e, &geometry, &st, &got_dst, scratch, n - 1, NULL),
                    VTS_ERR_ARG);
    size_t bytes = (size_t)dw * dh * ch * sizeof(float), diff = 0;
    const unsigned char *a = (const void *)ref_dst.px, *b = (const void *)got_dst.px,
                        *c = (const void *)bad_dst.px;
    *wrong = 0;
    for (size_t i = 0; i < bytes; i++) {
        diff += a[i] != b[i];
        *wrong += a[i] != c[i];
    }
    free(level);
    free(win);
    free(scratch);
    free(src.px);
    free(ref_dst.px);
    free(got_dst.px);
    free(bad_dst.px);
    return diff;
}

/* vt_filter_reduce_stored gives the bits of converting first, for every sample type, colour
 * mode, kernel and edge rule, with dst regions inside, across and wholly past the level's edges
 * (texels past a clamped edge repeat the edge texel). A wrong kernel fails the same comparison. */
static void stored_reduce_gives_the_bits_of_convert_then_reduce(void)
{
    const struct vt_pixel_mode modes[] = {
        {3, VTS_COLOUR_SRGB, false},
        {4, VTS_COLOUR_SRGB, true},
        {1, VTS_COLOUR_DATA, false},
        {2, VTS_COLOUR_LINEAR, true},
        {3, VTS_COLOUR_NORMAL, false},
        {4, VTS_COLOUR_SRGB, false}, /* 4 colour channels, no alpha */
    };
    const uint32_t samples[] = {VTS_SAMPLE_U8, VTS_SAMPLE_U16, VTS_SAMPLE_F16, VTS_SAMPLE_F32};
    const uint32_t w = 37, h = 22, cw = (w + 1) / 2, chh = (h + 1) / 2;
    /* dst regions: the whole coarser level; inside; across every edge by far; wholly past */
    const int64_t regions[][4] = {
        {0, 0, cw, chh}, {3, 2, 7, 5}, {-5, -4, cw + 14, chh + 11}, {cw + 2, chh + 1, 6, 4}};
    size_t diff = 0, wrong_cases = 0, cases = 0;
    for (size_t mi = 0; mi < sizeof modes / sizeof modes[0]; mi++)
        for (size_t si = 0; si < 4; si++)
            for (int kind = 0; kind < 4; kind++)
                for (int wrap = 0; wrap < 2; wrap++)
                    for (size_t r = 0; r < 4; r++) {
                        size_t wrong = 0;
                        diff +=
                            stored_case(&modes[mi], samples[si], (enum vt_filter_kind)kind, wrap, w,
                                        h, regions[r][0], regions[r][1], (uint32_t)regions[r][2],
                                        (uint32_t)regions[r][3], &wrong);
                        wrong_cases += wrong == 0;
                        cases++;
                    }
    VT_CHECK_INT_EQ(diff, 0);
    VT_CHECK_INT_EQ(wrong_cases, 0); /* a wrong kernel always shows */
    VT_CHECK_INT_EQ(cases, 6 * 4 * 4 * 2 * 4);
}

/* Clamped edges: every texel of a region past the coarser level's edge equals the edge texel
 * (here against the double reference: the copies are the texel, not a recomputation). */
static void texels_past_a_clamped_edge_repeat_the_edge_texel(void)
{
    const uint32_t w = 11, h = 9, ch = 3;
    struct vt_fregion src, dst, edge;
    float *px = region_alloc(&src, 0, 0, w, h, ch);
    for (size_t i = 0; i < (size_t)w * h * ch; i++)
        px[i] = rng_unit();
    struct vt_kernel k;
    vt_kernel_init(&k, VT_FILTER_LANCZOS3);
    struct vt_edges e = {w, h, false, false};
    region_alloc(&dst, 4, 3, 9, 7, ch);  /* from inside to far past the 6 x 5 coarser level */
    region_alloc(&edge, 5, 4, 1, 1, ch); /* its last texel */
    VT_CHECK_INT_EQ(reduce(&k, &e, &src, &dst), 0);
    VT_CHECK_INT_EQ(reduce(&k, &e, &src, &edge), 0);
    int bad = 0;
    for (uint32_t y = 1; y < dst.height; y++)
        for (uint32_t x = 1; x < dst.width; x++)
            bad +=
                memcmp(dst.px + ((size_t)y * dst.width + x) * ch, edge.px, ch * sizeof(float)) != 0;
    VT_CHECK_INT_EQ(bad, 0);
    /* and the texels at x = 4 (inside) differ from the edge's column */
    VT_CHECK(memcmp(dst.px + (size_t)1 * dst.width * ch, edge.px, ch * sizeof(float)) != 0);
    free(px);
    free(dst.px);
    free(edge.px);
}

/* ---- colour ---- */

static void srgb_checkerboard_reduces_to_188(void)
{
    struct vt_pixel_mode m = {3, VTS_COLOUR_SRGB, false};
    uint8_t img[8 * 8 * 3], out[4 * 4 * 3];
    for (int i = 0; i < 64; i++)
        memset(img + 3 * i, ((i % 8) + (i / 8)) % 2 ? 255 : 0, 3);
    struct vt_fregion src, dst;
    region_alloc(&src, 0, 0, 8, 8, 3);
    region_alloc(&dst, 0, 0, 4, 4, 3);
    vt_filter_to_working(&m, VTS_SAMPLE_U8, img, src.px, 64);
    struct vt_kernel k;
    vt_kernel_init(&k, VT_FILTER_BOX);
    struct vt_edges e = {8, 8, false, false};
    VT_CHECK_INT_EQ(reduce(&k, &e, &src, &dst), 0);
    vt_filter_from_working(&m, VTS_SAMPLE_U8, dst.px, out, 16);
    int not188 = 0;
    for (int i = 0; i < 48; i++)
        not188 += out[i] != 188;
    VT_CHECK_INT_EQ(not188, 0);
    VT_CHECK_INT_EQ(out[0], 188);
    free(src.px);
    free(dst.px);
}

static void transparent_half_leaves_no_dark_fringe(void)
{
    struct vt_pixel_mode m = {4, VTS_COLOUR_SRGB, true};
    for (int white = 0; white < 2; white++)
        for (int kind = 0; kind < 4; kind++) {
            uint8_t img[10 * 4 * 4], out[5 * 2 * 4];
            for (int i = 0; i < 40; i++) {
                static const uint8_t red[4] = {255, 0, 0, 255};
                uint8_t clear[4] = {0, 0, 0, 0};
                memset(clear, white ? 255 : 0, 3);
                memcpy(img + 4 * i, i % 10 < 5 ? red : clear, 4);
            }
            struct vt_fregion src, dst;
            region_alloc(&src, 0, 0, 10, 4, 4);
            region_alloc(&dst, 0, 0, 5, 2, 4);
            vt_filter_to_working(&m, VTS_SAMPLE_U8, img, src.px, 40);
            struct vt_kernel k;
            vt_kernel_init(&k, (enum vt_filter_kind)kind);
            struct vt_edges e = {10, 4, false, false};
            VT_CHECK_INT_EQ(reduce(&k, &e, &src, &dst), 0);
            vt_filter_from_working(&m, VTS_SAMPLE_U8, dst.px, out, 10);
            int fringe = 0;
            for (int i = 0; i < 10; i++) {
                const uint8_t *p = out + 4 * i;
                if (p[3] > 0)
                    fringe += p[0] != 255 || p[1] != 0 || p[2] != 0;
            }
            VT_CHECK_INT_EQ(fringe, 0);
            if (kind == VT_FILTER_BOX) { /* texel 2 straddles the boundary: finer 4 and 5 */
                VT_CHECK_INT_EQ(out[8], 255);
                VT_CHECK_INT_EQ(out[9], 0);
                VT_CHECK_INT_EQ(out[10], 0);
                VT_CHECK_INT_EQ(out[11], 128);
                VT_CHECK_INT_EQ(out[15], 0);
                VT_CHECK_INT_EQ(out[3], 255);
            }
            free(src.px);
            free(dst.px);
        }
}

/* ---- normals ---- */

static void normal_map_stays_unit_after_lanczos3_and_renormalize(void)
{
    const uint32_t n = 32;
    struct vt_pixel_mode m = {3, VTS_COLOUR_NORMAL, false};
    uint8_t img[32 * 32 * 3], out[16 * 16 * 3];
    for (uint32_t i = 0; i < n * n; i++) {
        double x = rng_unit() * 2 - 1, y = rng_unit() * 2 - 1, z = rng_unit() + 0.05;
        double len = sqrt(x * x + y * y + z * z), v[3] = {x / len, y / len, z / len};
        for (int c = 0; c < 3; c++)
            img[3 * i + c] = (uint8_t)floor((v[c] + 1) / 2 * 255 + 0.5);
    }
    struct vt_fregion src, dst;
    region_alloc(&src, 0, 0, n, n, 3);
    region_alloc(&dst, 0, 0, n / 2, n / 2, 3);
    vt_filter_to_working(&m, VTS_SAMPLE_U8, img, src.px, n * n);
    VT_CHECK(src.px[0] >= -1.0f && src.px[0] <= 1.0f);
    struct vt_kernel k;
    vt_kernel_init(&k, VT_FILTER_LANCZOS3);
    struct vt_edges e = {n, n, false, false};
    VT_CHECK_INT_EQ(reduce(&k, &e, &src, &dst), 0);
    int short_before = 0;
    for (uint32_t i = 0; i < n * n / 4; i++) {
        const float *p = dst.px + 3 * i;
        short_before += fabs(sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) - 1) > 0.01;
    }
    VT_CHECK(short_before > 0); /* random normals average to shorter vectors */
    vt_filter_renormalize(&dst);
    vt_filter_from_working(&m, VTS_SAMPLE_U8, dst.px, out, n * n / 4);
    int off = 0;
    for (uint32_t i = 0; i < n * n / 4; i++) {
        double s = 0;
        for (int c = 0; c < 3; c++) {
            double d = out[3 * i + c] / 255.0 * 2 - 1;
            s += d * d;
        }
        off += fabs(sqrt(s) - 1) > 0.01;
    }
    VT_CHECK_INT_EQ(off, 0);

    float zero[4] = {0, 0, 0, 0.5f};
    struct vt_fregion z = {0, 0, 1, 1, 4, zero};
    vt_filter_renormalize(&z);
    VT_CHECK(zero[0] == 0 && zero[1] == 0 && zero[2] == 1 && zero[3] == 0.5f);
    free(src.px);
    free(dst.px);
}

/* ---- edges ---- */

/* The triangle's weighted sum, in the reduction's order of operations. */
static float triangle_sum(float a, float b, float c, float d)
{
    float acc = 0.125f * a;
    acc += 0.375f * b;
    acc += 0.375f * c;
    acc += 0.125f * d;
    return acc;
}

static void wrap_reads_positions_across_the_edge(void)
{
    /* level 8x8; src holds unwrapped columns -1..8 with value 100 + position, so a texel shows
     * which positions it read */
    struct vt_kernel k;
    vt_kernel_init(&k, VT_FILTER_TRIANGLE);
    struct vt_fregion src, dst;
    float *px = region_alloc(&src, -1, 0, 10, 8, 1);
    for (uint32_t y = 0; y < 8; y++)
        for (uint32_t x = 0; x < 10; x++)
            px[y * 10 + x] = 100.0f + (float)x - 1.0f;
    region_alloc(&dst, 0, 0, 4, 4, 1);
    struct vt_edges wrap = {8, 8, true, false};
    VT_CHECK_INT_EQ(reduce(&k, &wrap, &src, &dst), 0);
    /* texel 0 reads -1, 0, 1, 2; texel 3 reads 5..8; every row holds the same values */
    float t0 = triangle_sum(99.0f, 100.0f, 101.0f, 102.0f);
    float t3 = triangle_sum(105.0f, 106.0f, 107.0f, 108.0f);
    VT_CHECK(dst.px[0] == triangle_sum(t0, t0, t0, t0));
    VT_CHECK(dst.px[3] == triangle_sum(t3, t3, t3, t3));
    VT_CHECK(dst.px[3 * 4] == dst.px[0]); /* the last row clamps at the bottom edge */
    /* clamp instead: texel 0 reads 0, 0, 1, 2 */
    struct vt_edges clamp = {8, 8, false, false};
    VT_CHECK_INT_EQ(reduce(&k, &clamp, &src, &dst), 0);
    float c0 = triangle_sum(100.0f, 100.0f, 101.0f, 102.0f);
    VT_CHECK(dst.px[0] == triangle_sum(c0, c0, c0, c0));
    /* wrap needs -1: a src starting at 0 does not cover it */
    struct vt_fregion narrow = {0, 0, 9, 8, 1, px + 1};
    VT_CHECK_INT_EQ(reduce(&k, &wrap, &narrow, &dst), VTS_ERR_ARG);
    free(src.px);
    free(dst.px);
}

static void reduce_rejects_src_that_does_not_cover_the_taps(void)
{
    struct vt_kernel k;
    vt_kernel_init(&k, VT_FILTER_TRIANGLE);
    struct vt_edges e = {64, 64, false, false};
    struct vt_fregion src, dst;
    /* dst [4, 8) x [4, 8) needs finer [7, 17) on both axes */
    region_alloc(&src, 7, 7, 10, 10, 2);
    region_alloc(&dst, 4, 4, 4, 4, 2);
    struct vts_error err = {0};
    size_t n = vt_filter_reduce_scratch(&k, &src, &dst);
    float *scratch = malloc(n * sizeof(float));
    VT_CHECK_INT_EQ(vt_filter_reduce(&k, &e, &src, &dst, scratch, n, &err), 0);
    struct vt_fregion s = src;
    s.x0 = 8;
    VT_CHECK_INT_EQ(vt_filter_reduce(&k, &e, &s, &dst, scratch, n, &err), VTS_ERR_ARG);
    VT_CHECK_STR_CONTAINS(err.message, "does not cover");
    s = src;
    s.height = 9;
    VT_CHECK_INT_EQ(vt_filter_reduce(&k, &e, &s, &dst, scratch, n, &err), VTS_ERR_ARG);
    s = src;
    s.y0 = 6;
    VT_CHECK_INT_EQ(vt_filter_reduce(&k, &e, &s, &dst, scratch, n, &err), VTS_ERR_ARG);
    VT_CHECK_INT_EQ(vt_filter_reduce(&k, &e, &src, &dst, scratch, n - 1, &err), VTS_ERR_ARG);
    s = src;
    s.channels = 3;
    VT_CHECK_INT_EQ(vt_filter_reduce(&k, &e, &s, &dst, scratch, n, &err), VTS_ERR_ARG);
    /* at the level edge the clamped taps need less: dst [30, 32) of 64 reads [59, 64) */
    struct vt_fregion edge_src = {59, 59, 5, 5, 2, src.px}, edge_dst = {30, 30, 2, 2, 2, dst.px};
    VT_CHECK_INT_EQ(reduce(&k, &e, &edge_src, &edge_dst), 0);
    edge_src.width = 4;
    VT_CHECK_INT_EQ(reduce(&k, &e, &edge_src, &edge_dst), VTS_ERR_ARG);
    free(scratch);
    free(src.px);
    free(dst.px);
}

/* ---- benchmark ---- */

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
}

/* Reduces a 256x256 output region (tile-sized, as the pyramid does) repeatedly. */
static void bench_reduce(uint32_t ch)
{
    const uint32_t out = 256;
    for (int kind = 0; kind <= VT_FILTER_MAX; kind++) {
        struct vt_kernel k;
        vt_kernel_init(&k, (enum vt_filter_kind)kind);
        uint32_t m = vt_kernel_margin(&k), fine = 2 * out + 2 * m;
        struct vt_fregion src, dst;
        float *px = region_alloc(&src, -(int64_t)m, -(int64_t)m, fine, fine, ch);
        for (size_t i = 0; i < (size_t)fine * fine * ch; i++)
            px[i] = rng_unit();
        region_alloc(&dst, 0, 0, out, out, ch);
        struct vt_edges e = {1u << 20, 1u << 20, false, false};
        size_t n = vt_filter_reduce_scratch(&k, &src, &dst);
        float *scratch = malloc(n * sizeof(float));
        double best = 0; /* best of 5 runs of 0.2 s: the machine is shared */
        for (int run = 0; run < 5; run++) {
            int reps = 0;
            double t0 = now_s(), t;
            do {
                vt_filter_reduce(&k, &e, &src, &dst, scratch, n, NULL);
                reps++;
            } while ((t = now_s() - t0) < 0.2);
            best = reps / t > best ? reps / t : best;
        }
        double texels = best * out * out;
        printf("reduce %-8s %u ch float: %7.1f M output texels/s  %7.1f M output values/s\n",
               vt_filter_name(k.kind), ch, texels / 1e6, texels * ch / 1e6);
        free(scratch);
        free(px);
        free(dst.px);
    }
}

static void bench_convert(void)
{
    enum { N = 1 << 20 };
    float *w = malloc(N * 4 * sizeof(float));
    uint8_t *b = malloc(N * 4);
    for (size_t i = 0; i < (size_t)N * 4; i++)
        b[i] = (uint8_t)rng_u32();
    struct vt_pixel_mode modes[] = {{4, VTS_COLOUR_SRGB, true}, {3, VTS_COLOUR_SRGB, false}};
    for (int mi = 0; mi < 2; mi++) {
        const struct vt_pixel_mode *m = &modes[mi];
        double best_to = 0, best_from = 0;
        for (int run = 0; run < 5; run++) {
            double t0 = now_s();
            vt_filter_to_working(m, VTS_SAMPLE_U8, b, w, N);
            double t1 = now_s();
            vt_filter_from_working(m, VTS_SAMPLE_U8, w, b, N);
            double t2 = now_s(), to = N / (t1 - t0), from = N / (t2 - t1);
            best_to = to > best_to ? to : best_to;
            best_from = from > best_from ? from : best_from;
        }
        printf("to_working   u8 srgb %u ch%s: %7.1f M values/s\n", m->channels,
               m->alpha ? "+alpha" : "      ", best_to * m->channels / 1e6);
        printf("from_working u8 srgb %u ch%s: %7.1f M values/s\n", m->channels,
               m->alpha ? "+alpha" : "      ", best_from * m->channels / 1e6);
    }
    free(w);
    free(b);
}

/* Frequency response of each kernel at f cycles per finer texel: 0.125 is half the coarser
 * Nyquist (detail that should stay), 0.375 aliases onto 0.125 after the 2:1 decimation. */
static void print_responses(void)
{
    for (int kind = 0; kind < 4; kind++) {
        struct vt_kernel k;
        vt_kernel_init(&k, (enum vt_filter_kind)kind);
        printf("response %-8s", vt_filter_name(k.kind));
        const double f[] = {0.125, 0.25, 0.375, 0.5};
        for (int i = 0; i < 4; i++) {
            double h = 0;
            for (int t = 0; t < k.count; t++)
                h += k.weights[t] * cos(2 * 3.14159265358979323846 * f[i] * (k.first + t - 0.5));
            printf("  H(%.3f) = %+.3f", f[i], h);
        }
        printf("\n");
    }
}

int main(int argc, char **argv)
{
    if (argc > 1 && strcmp(argv[1], "--bench") == 0) {
        bench_reduce(4);
        bench_reduce(3);
        bench_reduce(1);
        bench_convert();
        print_responses();
        return 0;
    }
    VT_RUN(filter_names_parse_and_print);
    VT_RUN(kernel_weights_sum_to_one);
    VT_RUN(box_and_triangle_weights_are_exact);
    VT_RUN(sinc_kernels_are_symmetric_with_negative_lobes);
    VT_RUN(kernel_margins_cover_the_taps);
    VT_RUN(box_reduce_matches_double_reference);
    VT_RUN(odd_level_edge_texel_repeats_the_last_finer_texel);
    VT_RUN(every_kernel_matches_a_double_reference);
    VT_RUN(every_kernel_is_independent_of_the_region_split);
    VT_RUN(stored_reduce_gives_the_bits_of_convert_then_reduce);
    VT_RUN(texels_past_a_clamped_edge_repeat_the_edge_texel);
    VT_RUN(srgb_checkerboard_reduces_to_188);
    VT_RUN(transparent_half_leaves_no_dark_fringe);
    VT_RUN(normal_map_stays_unit_after_lanczos3_and_renormalize);
    VT_RUN(wrap_reads_positions_across_the_edge);
    VT_RUN(reduce_rejects_src_that_does_not_cover_the_taps);
    return vt_test_main_result();
}
