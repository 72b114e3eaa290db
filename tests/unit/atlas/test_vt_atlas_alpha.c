/* Cut-out detection (vt_atlas_alpha.h): the thresholds, every sample type, bounded bands, the
 * early stop, and sources without alpha. The source computes its texels from a shape, so that
 * a wide image costs no memory here. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "vt_atlas_alpha.h"
#include "vt_test.h"
#include "vts.h"

enum shape { DISC, RAMP, LEVELS, HALF };

struct fake {
    enum shape shape;
    const double *levels; /* LEVELS: alpha of texel i (row-major) is levels[i % level_count] */
    uint32_t level_count;
    uint32_t reads, max_rows, min_width;
    uint64_t rows_read;
};

static double alpha_at(const struct fake *f, const struct vt_source_info *in, uint32_t x,
                       uint32_t y)
{
    switch (f->shape) {
    case DISC: {
        double dx = x + 0.5 - in->width / 2.0, dy = y + 0.5 - in->height / 2.0;
        return dx * dx + dy * dy < 0.16 * in->width * in->width ? 1 : 0;
    }
    case RAMP:
        return (x + 0.5) / in->width;
    case LEVELS:
        return f->levels[((uint64_t)y * in->width + x) % f->level_count];
    default:
        return x < in->width / 2 ? 0 : 1;
    }
}

/* IEEE half of a value in 0..1 that a half holds exactly (0, 0.5, 1 and the like). */
static uint16_t to_half(double v)
{
    if (v == 0)
        return 0;
    int e;
    double m = frexp(v, &e); /* v = m 2^e, m in [0.5, 1) */
    return (uint16_t)((e - 1 + 15) << 10 | (uint16_t)((m * 2 - 1) * 1024));
}

struct source {
    struct vt_source_info info;
    struct fake *fake;
};

static struct vt_source_info *info_of(void *ctx)
{
    return &((struct source *)ctx)->info;
}

static int fake_read(void *ctx, uint32_t x0, uint32_t y0, struct vt_image *dst,
                     struct vts_error *err)
{
    (void)err;
    struct source *s = ctx;
    struct fake *f = s->fake;
    const struct vt_source_info *in = info_of(ctx);
    f->reads++;
    f->rows_read += dst->height;
    f->max_rows = dst->height > f->max_rows ? dst->height : f->max_rows;
    f->min_width = !f->min_width || dst->width < f->min_width ? dst->width : f->min_width;
    size_t tb = vt_image_texel_bytes(dst), sb = vt_sample_bytes(dst->sample);
    for (uint32_t y = 0; y < dst->height; y++)
        for (uint32_t x = 0; x < dst->width; x++) {
            unsigned char *p = (unsigned char *)vt_image_at(dst, x, y) + tb - sb;
            double a = alpha_at(f, in, x0 + x, y0 + y);
            uint16_t u16 = dst->sample == VTS_SAMPLE_U16 ? (uint16_t)lround(a * 65535) : to_half(a);
            float f32 = (float)a;
            if (dst->sample == VTS_SAMPLE_U8)
                p[0] = (unsigned char)lround(a * 255);
            else if (dst->sample == VTS_SAMPLE_F32)
                memcpy(p, &f32, 4);
            else
                memcpy(p, &u16, 2);
        }
    return 0;
}

static void fake_close(void *ctx)
{
    (void)ctx;
}

static const struct vt_source_ops fake_ops = {fake_read, fake_close};

static int scan(struct fake *f, uint32_t w, uint32_t h, uint32_t channels, uint32_t sample,
                struct vt_atlas_alpha_counts *c)
{
    struct source s = {.fake = f};
    s.info.width = w, s.info.height = h, s.info.channels = channels, s.info.sample = sample;
    s.info.has_alpha = channels == 2 || channels == 4;
    struct vt_source src = {.info = s.info, .ops = &fake_ops, .ctx = &s};
    snprintf(src.name, sizeof src.name, "fake");
    struct vts_error err;
    int rc = vt_atlas_alpha_scan(&src, c, &err);
    VT_CHECK_INT_EQ(rc, 0);
    return rc;
}

static void thresholds_split_clear_partial_and_solid(void)
{
    /* 8-bit: 31 is clear (0.1216 <= 1/8), 32 and 223 partial, 224 solid (0.878 >= 7/8) */
    static const double levels[] = {31 / 255.0, 32 / 255.0, 223 / 255.0, 224 / 255.0};
    struct fake f = {.shape = LEVELS, .levels = levels, .level_count = 4};
    struct vt_atlas_alpha_counts c;
    scan(&f, 8, 8, 4, VTS_SAMPLE_U8, &c);
    VT_CHECK_INT_EQ(c.texels, 64);
    VT_CHECK_INT_EQ(c.read, 64);
    VT_CHECK_INT_EQ(c.clear, 16);
    VT_CHECK_INT_EQ(c.partial, 32);
    VT_CHECK(!vt_atlas_alpha_is_cutout(&c));
}

static void cutout_needs_few_partial_and_some_clear_texels(void)
{
    struct vt_atlas_alpha_counts c = {.texels = 1000, .read = 1000, .clear = 1, .partial = 100};
    VT_CHECK(vt_atlas_alpha_is_cutout(&c)); /* 10% partial, 0.1% clear: both bounds included */
    c.partial = 101;
    VT_CHECK(!vt_atlas_alpha_is_cutout(&c));
    c.partial = 0, c.clear = 0;
    VT_CHECK(!vt_atlas_alpha_is_cutout(&c)); /* opaque */
    c.texels = c.read = 1001, c.clear = 1;
    VT_CHECK(!vt_atlas_alpha_is_cutout(&c)); /* one clear texel in 1001: a stray */
    c.texels = 0;
    VT_CHECK(!vt_atlas_alpha_is_cutout(&c));
}

static void every_sample_type_reads_the_same_disc(void)
{
    static const uint32_t samples[] = {VTS_SAMPLE_U8, VTS_SAMPLE_U16, VTS_SAMPLE_F16,
                                       VTS_SAMPLE_F32};
    struct vt_atlas_alpha_counts first = {0};
    for (int i = 0; i < 4; i++) {
        struct fake f = {.shape = DISC};
        struct vt_atlas_alpha_counts c;
        scan(&f, 40, 40, i % 2 ? 2 : 4, samples[i], &c);
        VT_CHECK(vt_atlas_alpha_is_cutout(&c));
        VT_CHECK_INT_EQ(c.partial, 0);
        VT_CHECK(c.clear > 0 && c.clear < 1600 && c.read == 1600);
        if (i == 0)
            first = c;
        VT_CHECK_INT_EQ(c.clear, first.clear);
    }
    /* a half and a float in the middle are partial */
    static const double mid[] = {0.5};
    for (int i = 2; i < 4; i++) {
        struct fake f = {.shape = LEVELS, .levels = mid, .level_count = 1};
        struct vt_atlas_alpha_counts c;
        scan(&f, 4, 4, 4, samples[i], &c);
        VT_CHECK(c.partial > 0 && c.clear == 0);
    }
}

static void smooth_masks_stop_early_and_are_not_cutouts(void)
{
    struct fake f = {.shape = RAMP};
    struct vt_atlas_alpha_counts c;
    scan(&f, 256, 1024, 4, VTS_SAMPLE_U8, &c);
    VT_CHECK(!vt_atlas_alpha_is_cutout(&c));
    /* 75% of each band is partial: after 3 bands of 64 rows (48 rows' worth) more than 10% of
     * the 1024 rows are */
    VT_CHECK_INT_EQ(f.reads, 3);
    VT_CHECK_INT_EQ(c.read, 3 * 64 * 256);
    /* a binary mask is a cut-out by its texels (the MTL's vt_alpha none overrides that) */
    struct fake g = {.shape = HALF};
    scan(&g, 64, 64, 2, VTS_SAMPLE_U8, &c);
    VT_CHECK(vt_atlas_alpha_is_cutout(&c));
    VT_CHECK_INT_EQ(c.clear, 64 * 32);
}

static void bands_are_bounded_by_rows_and_bytes(void)
{
    /* 1000 x 300 RGBA8: bands of 64 rows, full width */
    struct fake f = {.shape = HALF};
    struct vt_atlas_alpha_counts c;
    scan(&f, 1000, 300, 4, VTS_SAMPLE_U8, &c);
    VT_CHECK_INT_EQ(f.max_rows, 64);
    VT_CHECK_INT_EQ(f.min_width, 1000);
    VT_CHECK_INT_EQ(f.rows_read, 300);
    /* 2^17 x 5 RGBA float: 2 MiB a row, so 8 rows fit 16 MiB: bands of 5 rows (the height) */
    struct fake g = {.shape = HALF};
    scan(&g, 1u << 17, 5, 4, VTS_SAMPLE_F32, &c);
    VT_CHECK_INT_EQ(g.max_rows, 5);
    /* 2^20 x 3 RGBA float: 16 MiB a row: one row per band */
    struct fake h = {.shape = HALF};
    scan(&h, 1u << 20, 3, 4, VTS_SAMPLE_F32, &c);
    VT_CHECK_INT_EQ(h.max_rows, 1);
    VT_CHECK_INT_EQ(h.reads, 3);
    VT_CHECK(vt_atlas_alpha_is_cutout(&c));
}

static void sources_without_alpha_are_not_read(void)
{
    struct fake f = {.shape = HALF};
    struct vt_atlas_alpha_counts c;
    scan(&f, 16, 16, 3, VTS_SAMPLE_U8, &c);
    VT_CHECK_INT_EQ(f.reads, 0);
    VT_CHECK_INT_EQ(c.texels, 256);
    VT_CHECK(!vt_atlas_alpha_is_cutout(&c));
}

int main(void)
{
    VT_RUN(thresholds_split_clear_partial_and_solid);
    VT_RUN(cutout_needs_few_partial_and_some_clear_texels);
    VT_RUN(every_sample_type_reads_the_same_disc);
    VT_RUN(smooth_masks_stop_early_and_are_not_cutouts);
    VT_RUN(bands_are_bounded_by_rows_and_bytes);
    VT_RUN(sources_without_alpha_are_not_read);
    return vt_test_main_result();
}
