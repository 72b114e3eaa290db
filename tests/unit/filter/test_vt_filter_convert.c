/* Mip filtering: conversions between stored samples and the working space (lib/filter
 * vt_filter_convert.c): exact round trips of u8, u16 and finite f16, correctly rounded sRGB
 * encoding (the thresholds, their neighbours, special values), premultiplied alpha. */
#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "filter_test_util.h"
#include "vt_filter.h"
#include "vt_test.h"
#include "vts.h"

static void u8_round_trips_are_exact(void)
{
    static const uint32_t colours[] = {VTS_COLOUR_SRGB, VTS_COLOUR_LINEAR, VTS_COLOUR_NORMAL,
                                       VTS_COLOUR_DATA};
    for (int ci = 0; ci < 4; ci++)
        for (uint32_t ch = 1; ch <= 4; ch++)
            for (int alpha = 0; alpha < 2; alpha++) {
                struct vt_pixel_mode m = {ch, colours[ci], alpha && ch >= 2};
                uint8_t in[256 * 4], back[256 * 4];
                float work[256 * 4];
                for (uint32_t i = 0; i < 256; i++)
                    for (uint32_t c = 0; c < ch; c++)
                        in[i * ch + c] = m.alpha && c == ch - 1 ? 255 : (uint8_t)(i + 17 * c);
                vt_filter_to_working(&m, VTS_SAMPLE_U8, in, work, 256);
                vt_filter_from_working(&m, VTS_SAMPLE_U8, work, back, 256);
                VT_CHECK(memcmp(in, back, 256 * ch) == 0);
            }
    /* the linearisation itself */
    struct vt_pixel_mode m = {1, VTS_COLOUR_SRGB, false};
    uint8_t codes[256];
    float lin[256];
    for (int i = 0; i < 256; i++)
        codes[i] = (uint8_t)i;
    vt_filter_to_working(&m, VTS_SAMPLE_U8, codes, lin, 256);
    int off = 0;
    for (int i = 0; i < 256; i++)
        off += lin[i] != (float)ref_srgb_to_linear(i / 255.0);
    VT_CHECK_INT_EQ(off, 0);
    VT_CHECK(lin[255] == 1.0f && lin[0] == 0.0f);
}

static void u16_round_trips_are_exact(void)
{
    uint16_t *in = malloc(65536 * 2), *back = malloc(65536 * 2);
    float *work = malloc(65536 * sizeof(float));
    for (uint32_t i = 0; i < 65536; i++)
        in[i] = (uint16_t)i;
    for (int srgb = 0; srgb < 2; srgb++) {
        struct vt_pixel_mode m = {1, srgb ? VTS_COLOUR_SRGB : VTS_COLOUR_LINEAR, false};
        memset(back, 0, 65536 * 2);
        vt_filter_to_working(&m, VTS_SAMPLE_U16, in, work, 65536);
        vt_filter_from_working(&m, VTS_SAMPLE_U16, work, back, 65536);
        VT_CHECK(memcmp(in, back, 65536 * 2) == 0);
    }
    free(in);
    free(back);
    free(work);
}

static void f16_round_trip_is_exact_for_finite_halves(void)
{
    uint16_t *in = malloc(65536 * 2), *back = malloc(65536 * 2);
    float *work = malloc(65536 * sizeof(float));
    for (uint32_t i = 0; i < 65536; i++)
        in[i] = (uint16_t)i;
    struct vt_pixel_mode m = {1, VTS_COLOUR_DATA, false};
    vt_filter_to_working(&m, VTS_SAMPLE_F16, in, work, 65536);
    vt_filter_from_working(&m, VTS_SAMPLE_F16, work, back, 65536);
    int bad = 0, nan_ok = 1;
    for (uint32_t i = 0; i < 65536; i++) {
        bool finite = (i & 0x7c00) != 0x7c00;
        if (finite || (i & 0x3ff) == 0)
            bad += back[i] != in[i]; /* finite values and the infinities */
        else
            nan_ok &= isnan(work[i]) && (back[i] & 0x7c00) == 0x7c00 && (back[i] & 0x3ff);
    }
    VT_CHECK_INT_EQ(bad, 0);
    VT_CHECK(nan_ok);
    VT_CHECK(work[0x0001] == 0x1p-24f); /* smallest subnormal */
    VT_CHECK(work[0x3c00] == 1.0f && work[0xc000] == -2.0f && work[0x7bff] == 65504.0f);
    VT_CHECK(isinf(work[0x7c00]) && work[0xfc00] < 0);

    /* rounding from float: ties to even, overflow, underflow */
    const float f[] = {1.0f + 0x1p-11f, 1.0f + 3 * 0x1p-11f, 65519.0f, 65520.0f, 0x1p-25f,
                       0x1.000002p-25f, 3 * 0x1p-25f,        -0.0f,    1e-30f,   1e30f,
                       0x1.ffep-15f};
    const uint16_t want[] = {0x3c00, 0x3c02, 0x7bff, 0x7c00, 0x0000, 0x0001,
                             0x0002, 0x8000, 0x0000, 0x7c00, 0x0400};
    uint16_t got[11];
    vt_filter_from_working(&m, VTS_SAMPLE_F16, f, got, 11);
    for (int i = 0; i < 11; i++)
        VT_CHECK_INT_EQ(got[i], want[i]);
    free(in);
    free(back);
    free(work);
}

static void srgb_u8_encoding_is_correctly_rounded(void)
{
    enum { N = 100000 + 255 * 3 + 8 };
    float *v = malloc(N * sizeof(float));
    uint8_t *out = malloc(N);
    size_t n = 0;
    for (int i = 0; i < 50000; i++)
        v[n++] = rng_unit();
    for (int i = 0; i < 50000; i++) /* log-uniform over [1e-6, 1]: the dark codes */
        v[n++] = (float)pow(10.0, -6.0 * rng_unit());
    for (int k = 0; k < 255; k++) { /* floats around each decision threshold */
        float t = (float)ref_srgb_to_linear((k + 0.5) / 255.0);
        v[n++] = nextafterf(t, 0.0f);
        v[n++] = t;
        v[n++] = nextafterf(t, 2.0f);
    }
    const float special[] = {0.0f, -0.0f, -1.0f, 1.0f, 2.0f, INFINITY, -INFINITY, NAN};
    for (int i = 0; i < 8; i++)
        v[n++] = special[i];
    struct vt_pixel_mode m = {1, VTS_COLOUR_SRGB, false};
    vt_filter_from_working(&m, VTS_SAMPLE_U8, v, out, n);
    int bad = 0;
    for (size_t i = 0; i < n; i++)
        bad += out[i] != ref_srgb_code(v[i], 255);
    VT_CHECK_INT_EQ(bad, 0);
    VT_CHECK_INT_EQ(out[n - 1], 0);   /* NaN */
    VT_CHECK_INT_EQ(out[n - 3], 255); /* inf */
    free(v);
    free(out);
}

static void srgb_u16_encoding_is_correctly_rounded(void)
{
    enum { N = 100000 };
    float *v = malloc(N * sizeof(float));
    uint16_t *out = malloc(N * 2);
    for (int i = 0; i < N; i++)
        v[i] = i % 2 ? rng_unit() : (float)pow(10.0, -7.0 * rng_unit());
    struct vt_pixel_mode m = {1, VTS_COLOUR_SRGB, false};
    vt_filter_from_working(&m, VTS_SAMPLE_U16, v, out, N);
    int bad = 0;
    for (int i = 0; i < N; i++)
        bad += out[i] != ref_srgb_code(v[i], 65535);
    VT_CHECK_INT_EQ(bad, 0);
    free(v);
    free(out);
}

static void premultiplied_round_trip_and_zero_alpha(void)
{
    struct vt_pixel_mode m = {4, VTS_COLOUR_LINEAR, true};
    const uint8_t in[8] = {200, 100, 50, 128, 200, 100, 50, 0};
    float w[8];
    uint8_t back[8];
    vt_filter_to_working(&m, VTS_SAMPLE_U8, in, w, 2);
    VT_CHECK(fabsf(w[0] - 200.0f / 255 * 128.0f / 255) < 1e-6f);
    VT_CHECK(w[4] == 0.0f && w[7] == 0.0f);
    vt_filter_from_working(&m, VTS_SAMPLE_U8, w, back, 2);
    VT_CHECK(memcmp(back, in, 4) == 0);
    VT_CHECK(back[4] == 0 && back[5] == 0 && back[6] == 0 && back[7] == 0);
    /* data with alpha is not premultiplied */
    struct vt_pixel_mode d = {4, VTS_COLOUR_DATA, true};
    vt_filter_to_working(&d, VTS_SAMPLE_U8, in, w, 2);
    VT_CHECK(w[4] == 200.0f / 255);
}

int main(void)
{
    VT_RUN(u8_round_trips_are_exact);
    VT_RUN(u16_round_trips_are_exact);
    VT_RUN(f16_round_trip_is_exact_for_finite_halves);
    VT_RUN(srgb_u8_encoding_is_correctly_rounded);
    VT_RUN(srgb_u16_encoding_is_correctly_rounded);
    VT_RUN(premultiplied_round_trip_and_zero_alpha);
    return vt_test_main_result();
}
