/* The selections of lib/filter (nearest, mode, min, max; vt_filter.h, docs/filters.md
 * "Selections"): known 2x2 cases and the tie rule, odd sizes and the clamped edge, the bound of
 * min/max over every finer texel, the value set kept, stored rows against working floats, and
 * region splits. Negative controls: the box filter fails the subset and bound checks. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "filter_test_util.h"
#include "vt_filter.h"
#include "vt_test.h"
#include "vts.h"

/* Reduces a whole w x h level of ch-channel floats with kind (clamped, or wrapped) into out
 * (ceil(w/2) x ceil(h/2)). Wrapped odd sizes read past px: even sizes only. */
static int reduce_level(enum vt_filter_kind kind, float *px, uint32_t w, uint32_t h, uint32_t ch,
                        bool wrap, float *out)
{
    struct vt_kernel k;
    vt_kernel_init(&k, kind);
    struct vt_edges e = {w, h, wrap, wrap};
    struct vt_fregion src = {0, 0, w, h, ch, px};
    struct vt_fregion dst = {0, 0, (w + 1) / 2, (h + 1) / 2, ch, out};
    size_t n = vt_filter_reduce_scratch(&k, &src, &dst);
    float *scratch = malloc((n ? n : 1) * sizeof(float));
    struct vts_error err = {0};
    int rc = vt_filter_reduce(&k, &e, &src, &dst, scratch, n, &err);
    free(scratch);
    return rc;
}

/* Number of coarser texel values (per channel) not bounded by the finer texels each covers: a
 * coarser texel i covers finer texels 2i and 2i + 1 that exist. max: coarser >= finer. */
static size_t bound_violations(const float *fine, uint32_t w, uint32_t h, uint32_t ch,
                               const float *coarse, bool max)
{
    uint32_t cw = (w + 1) / 2;
    size_t bad = 0;
    for (uint32_t y = 0; y < h; y++)
        for (uint32_t x = 0; x < w; x++)
            for (uint32_t c = 0; c < ch; c++) {
                float f = fine[((size_t)y * w + x) * ch + c];
                float v = coarse[((size_t)(y / 2) * cw + x / 2) * ch + c];
                bad += max ? !(v >= f) : !(v <= f);
            }
    return bad;
}

/* Number of coarser texels that are not one of the finer texels they cover (whole texels). */
static size_t not_covered(const float *fine, uint32_t w, uint32_t h, uint32_t ch,
                          const float *coarse)
{
    uint32_t cw = (w + 1) / 2, chh = (h + 1) / 2;
    size_t bad = 0;
    for (uint32_t y = 0; y < chh; y++)
        for (uint32_t x = 0; x < cw; x++) {
            const float *v = coarse + ((size_t)y * cw + x) * ch;
            bool found = false;
            for (uint32_t dy = 0; dy < 2 && !found; dy++)
                for (uint32_t dx = 0; dx < 2 && !found; dx++) {
                    uint32_t fx = 2 * x + dx < w ? 2 * x + dx : w - 1;
                    uint32_t fy = 2 * y + dy < h ? 2 * y + dy : h - 1;
                    found = memcmp(v, fine + ((size_t)fy * w + fx) * ch, ch * sizeof(float)) == 0;
                }
            bad += !found;
        }
    return bad;
}

static void selection_names_parse_and_print(void)
{
    static const char *const names[] = {"nearest", "mode", "min", "max"};
    enum vt_filter_kind kind;
    for (int i = 0; i < 4; i++) {
        VT_CHECK_INT_EQ(vt_filter_parse(names[i], &kind), 0);
        VT_CHECK_INT_EQ(kind, VT_FILTER_NEAREST + i);
        VT_CHECK_STR_EQ(vt_filter_name(kind), names[i]);
        VT_CHECK(vt_filter_is_selection(kind));
        struct vt_kernel k;
        vt_kernel_init(&k, kind);
        VT_CHECK(k.first == 0 && k.count == 2 && vt_kernel_margin(&k) == 0);
    }
    VT_CHECK(!vt_filter_is_selection(VT_FILTER_BOX) && !vt_filter_is_selection(VT_FILTER_KAISER));
    VT_CHECK_INT_EQ(vt_filter_parse("Mode", &kind), VTS_ERR_ARG);
}

/* One 2x2 level -> one texel. */
static float one(enum vt_filter_kind kind, float tl, float tr, float bl, float br)
{
    float px[4] = {tl, tr, bl, br}, out = -1.0f;
    VT_CHECK_INT_EQ(reduce_level(kind, px, 2, 2, 1, false, &out), 0);
    return out;
}

static void mode_takes_the_majority_and_ties_go_to_the_first(void)
{
    VT_CHECK(one(VT_FILTER_MODE, 3, 7, 7, 7) == 7); /* 3-1: the majority, not the top-left */
    VT_CHECK(one(VT_FILTER_MODE, 12, 3, 12, 12) == 12);
    VT_CHECK(one(VT_FILTER_MODE, 3, 7, 12, 7) == 7);  /* 2-1-1 */
    VT_CHECK(one(VT_FILTER_MODE, 7, 3, 3, 7) == 7);   /* 2-2: the first in footprint order */
    VT_CHECK(one(VT_FILTER_MODE, 3, 7, 7, 3) == 3);   /* 2-2 the other way round */
    VT_CHECK(one(VT_FILTER_MODE, 12, 7, 3, 5) == 12); /* all different: the top-left */
    VT_CHECK(one(VT_FILTER_NEAREST, 3, 7, 7, 7) == 3);
    /* the box's mean is a value of none of them: the negative control of the tests below */
    VT_CHECK(one(VT_FILTER_BOX, 3, 7, 7, 7) == 6);
}

static void mode_compares_whole_texels(void)
{
    /* four different texels: the top-left; a mode per channel would make (1, 6), a texel that
     * is none of them */
    float px[8] = {1, 5, 2, 6, 1, 7, 3, 6};
    float out[2] = {0};
    VT_CHECK_INT_EQ(reduce_level(VT_FILTER_MODE, px, 2, 2, 2, false, out), 0);
    VT_CHECK(out[0] == 1 && out[1] == 5);
    /* texels compared bit for bit: -0 (twice) wins over 0 (once) */
    float z[4] = {0.0f, -0.0f, -0.0f, 1.0f};
    float o = 5.0f;
    VT_CHECK_INT_EQ(reduce_level(VT_FILTER_MODE, z, 2, 2, 1, false, &o), 0);
    VT_CHECK(o == 0.0f && signbit(o));
}

static void min_max_per_channel_and_nan(void)
{
    float px[8] = {4, -1, 2, 8, 3, 0.5f, 9, -7};
    float lo[2], hi[2];
    VT_CHECK_INT_EQ(reduce_level(VT_FILTER_MIN, px, 2, 2, 2, false, lo), 0);
    VT_CHECK_INT_EQ(reduce_level(VT_FILTER_MAX, px, 2, 2, 2, false, hi), 0);
    VT_CHECK(lo[0] == 2 && lo[1] == -7 && hi[0] == 9 && hi[1] == 8);
    VT_CHECK(one(VT_FILTER_MIN, NAN, 5, NAN, 2) == 2);
    VT_CHECK(one(VT_FILTER_MAX, 1, NAN, 6, NAN) == 6);
    VT_CHECK(isnan(one(VT_FILTER_MIN, NAN, NAN, NAN, NAN)));
    VT_CHECK(one(VT_FILTER_MAX, -INFINITY, -3, INFINITY, 0) == INFINITY);
}

/* A terrain-like float field: smooth hills, a ridge, sharp cliffs and some noise. */
static void terrain(float *px, uint32_t w, uint32_t h)
{
    for (uint32_t y = 0; y < h; y++)
        for (uint32_t x = 0; x < w; x++) {
            float v = 300.0f * sinf((float)x * 0.07f) * cosf((float)y * 0.05f) +
                      (x > w / 3 ? 120.0f : -40.0f) + 15.0f * (rng_unit() - 0.5f);
            px[(size_t)y * w + x] = v;
        }
}

static void min_max_bound_every_finer_texel_at_odd_sizes(void)
{
    static const uint32_t sizes[][2] = {{5, 3}, {1, 7}, {33, 1}, {97, 61}, {64, 65}, {2, 2}};
    for (size_t s = 0; s < sizeof sizes / sizeof sizes[0]; s++) {
        uint32_t w = sizes[s][0], h = sizes[s][1];
        /* the whole pyramid down to 1x1, each level from the previous one */
        float *lo = malloc((size_t)w * h * sizeof(float)), *hi = malloc((size_t)w * h * 4);
        float *box = malloc((size_t)w * h * sizeof(float));
        terrain(lo, w, h);
        memcpy(hi, lo, (size_t)w * h * sizeof(float));
        size_t box_bad = 0;
        while (w > 1 || h > 1) {
            uint32_t cw = (w + 1) / 2, chh = (h + 1) / 2;
            float *l2 = malloc((size_t)cw * chh * 4), *h2 = malloc((size_t)cw * chh * 4);
            float *b2 = malloc((size_t)cw * chh * 4);
            VT_CHECK_INT_EQ(reduce_level(VT_FILTER_MIN, lo, w, h, 1, false, l2), 0);
            VT_CHECK_INT_EQ(reduce_level(VT_FILTER_MAX, hi, w, h, 1, false, h2), 0);
            VT_CHECK_INT_EQ(reduce_level(VT_FILTER_BOX, lo, w, h, 1, false, b2), 0);
            VT_CHECK_INT_EQ(bound_violations(lo, w, h, 1, l2, false), 0);
            VT_CHECK_INT_EQ(bound_violations(hi, w, h, 1, h2, true), 0);
            VT_CHECK_INT_EQ(not_covered(lo, w, h, 1, l2), 0);
            box_bad += bound_violations(lo, w, h, 1, b2, false);
            free(lo), free(hi), free(box);
            lo = l2, hi = h2, box = b2;
            w = cw, h = chh;
        }
        /* negative control: a box-filtered level is above some finer texel it covers */
        VT_CHECK(box_bad > 0);
        free(lo), free(hi), free(box);
    }
}

/* Land classes with 1-texel roads and rivers: every coarser texel is a covered finer one. */
static void selections_keep_the_value_set(void)
{
    static const float classes[] = {3, 7, 12, 40, 41, 200};
    uint32_t w = 67, h = 45, ch = 1;
    float *px = malloc((size_t)w * h * sizeof(float));
    for (uint32_t y = 0; y < h; y++)
        for (uint32_t x = 0; x < w; x++) {
            float v = classes[((x / 9) + (y / 7) * 3) % 4];
            if (x == 20 || y == 31) /* a road */
                v = classes[4];
            if (x + y == 50) /* a diagonal river */
                v = classes[5];
            px[(size_t)y * w + x] = v;
        }
    float *out = malloc((size_t)((w + 1) / 2) * ((h + 1) / 2) * sizeof(float));
    static const enum vt_filter_kind kinds[] = {VT_FILTER_NEAREST, VT_FILTER_MODE, VT_FILTER_MIN,
                                                VT_FILTER_MAX};
    for (int i = 0; i < 4; i++) {
        VT_CHECK_INT_EQ(reduce_level(kinds[i], px, w, h, ch, false, out), 0);
        VT_CHECK_INT_EQ(not_covered(px, w, h, ch, out), 0);
    }
    /* the negative control: the box mixes classes at their boundaries */
    VT_CHECK_INT_EQ(reduce_level(VT_FILTER_BOX, px, w, h, ch, false, out), 0);
    VT_CHECK(not_covered(px, w, h, ch, out) > 0);
    free(px);
    free(out);
}

/* Stored rows of every sample type give the bits of converting first, and any split of the
 * output into regions gives the bits of the whole. */
static void stored_rows_and_splits_match_the_whole(void)
{
    static const uint32_t samples[] = {VTS_SAMPLE_U8, VTS_SAMPLE_U16, VTS_SAMPLE_F16,
                                       VTS_SAMPLE_F32};
    uint32_t w = 37, h = 23, ch = 3, cw = 19, chh = 12;
    struct vt_pixel_mode m = {ch, VTS_COLOUR_DATA, false};
    for (size_t s = 0; s < 4; s++) {
        size_t bytes = vts_sample_bytes(samples[s]);
        unsigned char *stored = malloc((size_t)w * h * ch * bytes);
        for (size_t i = 0; i < (size_t)w * h * ch * bytes; i++)
            stored[i] = (unsigned char)(rng_u32() % 5 * 17); /* few values, many repeats */
        if (samples[s] == VTS_SAMPLE_F16) /* no NaN payloads: exponent bits kept low */
            for (size_t i = 1; i < (size_t)w * h * ch * 2; i += 2)
                stored[i] &= 0x3f;
        if (samples[s] == VTS_SAMPLE_F32)
            for (size_t i = 3; i < (size_t)w * h * ch * 4; i += 4)
                stored[i] &= 0x3f;
        float *work = malloc((size_t)w * h * ch * sizeof(float));
        vt_filter_to_working(&m, samples[s], stored, work, (size_t)w * h);
        for (enum vt_filter_kind kind = VT_FILTER_NEAREST; kind <= VT_FILTER_MAX; kind++) {
            float *whole = malloc((size_t)cw * chh * ch * sizeof(float));
            float *part = malloc((size_t)cw * chh * ch * sizeof(float));
            VT_CHECK_INT_EQ(reduce_level(kind, work, w, h, ch, false, whole), 0);
            struct vt_kernel k;
            vt_kernel_init(&k, kind);
            struct vt_edges e = {w, h, false, false};
            /* regions of the coarser level, some past its edge (clamped copies) */
            static const int64_t regs[][4] = {{0, 0, 7, 5}, {7, 0, 12, 5}, {0, 5, 19, 7}};
            for (int r = 0; r < 3; r++) {
                struct vt_fregion dst = {regs[r][0],           regs[r][1], (uint32_t)regs[r][2],
                                         (uint32_t)regs[r][3], ch,         NULL};
                int64_t fx0 = 2 * dst.x0, fy0 = 2 * dst.y0;
                uint32_t fw = (uint32_t)(2 * dst.width < w - fx0 ? 2 * dst.width : w - fx0);
                uint32_t fh = (uint32_t)(2 * dst.height < h - fy0 ? 2 * dst.height : h - fy0);
                struct vt_fregion src = {fx0, fy0, fw, fh, ch, NULL};
                struct vt_stored_rows st = {stored + ((size_t)fy0 * w + (size_t)fx0) * ch * bytes,
                                            (size_t)w * ch * bytes, samples[s], &m};
                float out[19 * 12 * 3];
                dst.px = out;
                size_t n = vt_filter_reduce_stored_scratch(&k, &src, &dst);
                float *scratch = malloc(n * sizeof(float));
                struct vts_error err = {0};
                VT_CHECK_INT_EQ(vt_filter_reduce_stored(&k, &e, &src, &st, &dst, scratch, n, &err),
                                0);
                VT_CHECK_INT_EQ(
                    vt_filter_reduce_stored(&k, &e, &src, &st, &dst, scratch, n - 1, &err),
                    VTS_ERR_ARG); /* the scratch it asked for, not less */
                free(scratch);
                for (uint32_t y = 0; y < dst.height; y++)
                    memcpy(part + ((size_t)(dst.y0 + y) * cw + (size_t)dst.x0) * ch,
                           out + (size_t)y * dst.width * ch, dst.width * ch * sizeof(float));
            }
            VT_CHECK(memcmp(whole, part, (size_t)cw * chh * ch * sizeof(float)) == 0);
            /* and the stored values come back exactly */
            unsigned char *back = malloc((size_t)cw * chh * ch * bytes);
            vt_filter_from_working(&m, samples[s], whole, back, (size_t)cw * chh);
            float *again = malloc((size_t)cw * chh * ch * sizeof(float));
            vt_filter_to_working(&m, samples[s], back, again, (size_t)cw * chh);
            VT_CHECK(memcmp(whole, again, (size_t)cw * chh * ch * sizeof(float)) == 0);
            free(back), free(again), free(whole), free(part);
        }
        free(stored);
        free(work);
    }
}

static void source_must_cover_the_footprint(void)
{
    struct vt_kernel k;
    vt_kernel_init(&k, VT_FILTER_MODE);
    float src_px[4 * 4] = {0}, dst_px[4] = {0};
    struct vt_edges e = {8, 8, false, false};
    struct vt_fregion src = {0, 0, 4, 3, 1, src_px}; /* rows 0..2: texel (0,1) needs row 3 */
    struct vt_fregion dst = {0, 0, 2, 2, 1, dst_px};
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(vt_filter_reduce(&k, &e, &src, &dst, NULL, 0, &err), VTS_ERR_ARG);
    VT_CHECK_STR_CONTAINS(err.message, "mode taps");
}

int main(void)
{
    VT_RUN(selection_names_parse_and_print);
    VT_RUN(mode_takes_the_majority_and_ties_go_to_the_first);
    VT_RUN(mode_compares_whole_texels);
    VT_RUN(min_max_per_channel_and_nan);
    VT_RUN(min_max_bound_every_finer_texel_at_odd_sizes);
    VT_RUN(selections_keep_the_value_set);
    VT_RUN(stored_rows_and_splits_match_the_whole);
    VT_RUN(source_must_cover_the_footprint);
    return vt_test_main_result();
}
