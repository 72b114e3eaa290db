/* Mip filtering: conversions between stored samples (u8, u16, f16, f32) and the float working
 * space (linear light, premultiplied alpha, normals in [-1,1]), with the sRGB tables built once
 * (vt_filter.h; kernels in vt_filter.c, the reduction in vt_filter_reduce.c). */
#include "vt_filter.h"

#include <assert.h>
#include <math.h>
#include <pthread.h>
#include <string.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "internal/vt_filter_impl.h"
#include "vts.h"

/* ---- half floats ---- */

static uint32_t float_bits(float f)
{
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    return u;
}

static float bits_float(uint32_t u)
{
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

static float half_to_float(uint16_t h)
{
    uint32_t sign = (uint32_t)(h & 0x8000) << 16, exp = (h >> 10) & 0x1f, mant = h & 0x3ff;
    if (exp == 0) { /* zero or subnormal: mant * 2^-24, exact in float */
        float f = (float)mant * 0x1p-24f;
        return bits_float(float_bits(f) | sign);
    }
    if (exp == 31) /* inf, or NaN keeping its payload */
        return bits_float(sign | 0x7f800000u | (mant << 13));
    return bits_float(sign | ((exp + 127 - 15) << 23) | (mant << 13));
}

/* Rounds to nearest, ties to even; overflows to inf; NaN stays NaN (quiet). */
static uint16_t float_to_half(float f)
{
    uint32_t u = float_bits(f), abs = u & 0x7fffffffu;
    uint16_t sign = (uint16_t)((u >> 16) & 0x8000);
    if (abs > 0x7f800000u)
        return (uint16_t)(sign | 0x7e00 | ((abs >> 13) & 0x3ff));
    if (abs >= 0x477ff000u) /* >= 65520: rounds to inf */
        return (uint16_t)(sign | 0x7c00);
    uint32_t e = abs >> 23;
    if (e < 113) { /* below 2^-14: a half subnormal (or zero), units of 2^-24 */
        uint32_t shift = 126 - e;
        if (e == 0 || shift > 24)
            return sign;
        uint32_t m = (abs & 0x7fffffu) | 0x800000u, r = m >> shift;
        uint32_t rem = m & ((1u << shift) - 1), half = 1u << (shift - 1);
        if (rem > half || (rem == half && (r & 1)))
            r++;
        return (uint16_t)(sign | r);
    }
    uint32_t h = (abs >> 13) - ((127u - 15u) << 10), rem = abs & 0x1fff;
    if (rem > 0x1000 || (rem == 0x1000 && (h & 1)))
        h++; /* a carry into the exponent is right */
    return (uint16_t)(sign | h);
}

/* ---- sRGB (IEC 61966-2-1) ---- */

static double srgb_to_linear(double s)
{
    return s <= 0.04045 ? s / 12.92 : pow((s + 0.055) / 1.055, 2.4);
}

static double linear_to_srgb(double v)
{
    return v <= 0.0031308 ? v * 12.92 : 1.055 * pow(v, 1.0 / 2.4) - 0.055;
}

/* Encoding linear -> sRGB code without pow: thr[k] is the linear value at which the code goes from
 * k to k + 1 (sRGB (k + 0.5) / max), rounded down to a float so that `v > thr[k]` for a float v
 * equals the comparison with the double; thr[max] = inf. A bucket table indexed by exponent and the
 * top mantissa bits of v gives the code at the bucket's lowest value; a few steps fix it up. */
#define U8_EMIN     (-13) /* 2^-13 < thr[0] = 0.5 / 255 / 12.92 */
#define U8_MBITS    8     /* at most one threshold per bucket (checked when built) */
#define U16_EMIN    (-21) /* 2^-21 < 0.5 / 65535 / 12.92 */
#define U16_MBITS   12    /* at most a few thresholds per bucket */
#define U8_BUCKETS  (-U8_EMIN << U8_MBITS)
#define U16_BUCKETS (-U16_EMIN << U16_MBITS)

static float lin_u8[256];   /* sRGB code -> linear */
static float unorm_u8[256]; /* code / 255 */
static float thr_u8[256];
static uint8_t bucket_u8[U8_BUCKETS];
static float bucket_thr_u8[U8_BUCKETS]; /* thr_u8[bucket_u8[i]]: no load waits for another */
static float lin_u16[65536];
static float thr_u16[65536];
static uint16_t bucket_u16[U16_BUCKETS];
static pthread_once_t once_u8 = PTHREAD_ONCE_INIT;
static pthread_once_t once_u16 = PTHREAD_ONCE_INIT;

static float float_at_or_below(double d)
{
    float f = (float)d;
    return (double)f > d ? nextafterf(f, -INFINITY) : f;
}

/* Fills thr[0..max] and the bucket table; returns the most codes one bucket spans. */
static unsigned build_encoder(float *thr, unsigned max, int emin, int mbits, void *buckets,
                              bool wide)
{
    for (unsigned k = 0; k < max; k++)
        thr[k] = float_at_or_below(srgb_to_linear((k + 0.5) / max));
    thr[max] = INFINITY;
    unsigned n = (unsigned)-emin << mbits, code = 0, span = 0;
    uint32_t lo_bits = (uint32_t)(127 + emin) << 23;
    for (unsigned i = 0; i < n; i++) {
        float lo = bits_float(lo_bits + (i << (23 - mbits)));
        float hi = bits_float(lo_bits + ((i + 1) << (23 - mbits)) - 1);
        while (lo > thr[code])
            code++;
        unsigned hi_code = code;
        while (hi > thr[hi_code])
            hi_code++;
        span = hi_code - code > span ? hi_code - code : span;
        if (wide)
            ((uint16_t *)buckets)[i] = (uint16_t)code;
        else
            ((uint8_t *)buckets)[i] = (uint8_t)code;
    }
    return span;
}

static void build_u8_tables(void)
{
    for (unsigned k = 0; k < 256; k++) {
        lin_u8[k] = (float)srgb_to_linear(k / 255.0);
        unorm_u8[k] = (float)k / 255.0f;
    }
    unsigned span = build_encoder(thr_u8, 255, U8_EMIN, U8_MBITS, bucket_u8, false);
    assert(span <= 1);
    (void)span;
    for (unsigned i = 0; i < U8_BUCKETS; i++)
        bucket_thr_u8[i] = thr_u8[bucket_u8[i]];
}

static void build_u16_tables(void)
{
    for (unsigned k = 0; k < 65536; k++)
        lin_u16[k] = (float)srgb_to_linear(k / 65535.0);
    build_encoder(thr_u16, 65535, U16_EMIN, U16_MBITS, bucket_u16, true);
}

/* encode_srgb_u8() without branches, for loops over many samples: the value is clamped to
 * [2^-13, 1 - 2^-24] first (NaN to the low end), which gives the same codes (0 below thr[0],
 * 255 above thr[254]). */
static inline uint8_t encode_srgb_u8_clamped(float v)
{
    v = v >= 0x1p-13f ? v : 0x1p-13f;
    v = v < 0x1.fffffep-1f ? v : 0x1.fffffep-1f;
    uint32_t i = (float_bits(v) >> (23 - U8_MBITS)) - ((uint32_t)(127 + U8_EMIN) << U8_MBITS);
    return (uint8_t)(bucket_u8[i] + (v > bucket_thr_u8[i]));
}

/* encode_srgb_u8_clamped() over count samples; four at a time with SSE2 (the index arithmetic,
 * clamps and comparison in vectors; the two table loads per sample stay scalar). */
static void encode_srgb_u8_run(const float *src, uint8_t *dst, size_t count)
{
    size_t i = 0;
#if defined(__SSE2__)
    const __m128 lo = _mm_set1_ps(0x1p-13f), hi = _mm_set1_ps(0x1.fffffep-1f);
    const __m128i first = _mm_set1_epi32((127 + U8_EMIN) << U8_MBITS);
    for (; i + 4 <= count; i += 4) {
        /* max(v, lo) is lo for a NaN v, as in the scalar version */
        __m128 v = _mm_min_ps(_mm_max_ps(_mm_loadu_ps(src + i), lo), hi);
        __m128i idx = _mm_sub_epi32(_mm_srli_epi32(_mm_castps_si128(v), 23 - U8_MBITS), first);
        uint32_t k[4];
        _mm_storeu_si128((__m128i *)k, idx);
        __m128 thr = _mm_setr_ps(bucket_thr_u8[k[0]], bucket_thr_u8[k[1]], bucket_thr_u8[k[2]],
                                 bucket_thr_u8[k[3]]);
        __m128i code =
            _mm_setr_epi32(bucket_u8[k[0]], bucket_u8[k[1]], bucket_u8[k[2]], bucket_u8[k[3]]);
        code = _mm_sub_epi32(code, _mm_castps_si128(_mm_cmpgt_ps(v, thr))); /* true is -1 */
        code = _mm_packs_epi32(code, code);
        code = _mm_packus_epi16(code, code);
        int32_t bytes = _mm_cvtsi128_si32(code);
        memcpy(dst + i, &bytes, 4);
    }
#endif
    for (; i < count; i++)
        dst[i] = encode_srgb_u8_clamped(src[i]);
}

static inline unsigned encode_srgb_u8(float v)
{
    if (!(v >= 0x1p-13f)) /* also NaN */
        return 0;
    if (v >= 1.0f)
        return 255;
    uint32_t i = (float_bits(v) >> (23 - U8_MBITS)) - ((uint32_t)(127 + U8_EMIN) << U8_MBITS);
    unsigned code = bucket_u8[i];
    return code + (v > thr_u8[code]);
}

static inline unsigned encode_srgb_u16(float v)
{
    if (!(v >= 0x1p-21f))
        return 0;
    if (v >= 1.0f)
        return 65535;
    uint32_t i = (float_bits(v) >> (23 - U16_MBITS)) - ((uint32_t)(127 + U16_EMIN) << U16_MBITS);
    unsigned code = bucket_u16[i];
    while (v > thr_u16[code])
        code++;
    return code;
}

/* ---- conversions ---- */

/* What each channel of a pixel mode means. */
struct mode_info {
    uint32_t channels;
    uint32_t colour_n; /* leading channels that are colour (all but alpha) */
    uint32_t normal_n; /* leading channels mapped [0,1] <-> [-1,1] */
    bool srgb;         /* colour channels are sRGB-encoded */
    bool premultiply;  /* colour channels are premultiplied by the last channel */
};

static struct mode_info mode_info(const struct vt_pixel_mode *m)
{
    struct mode_info mi = {.channels = m->channels};
    assert(m->channels >= 1 && m->channels <= 4);
    bool alpha = m->alpha && m->channels >= 2;
    mi.colour_n = alpha ? m->channels - 1 : m->channels;
    mi.srgb = m->colour == VTS_COLOUR_SRGB;
    if (m->colour == VTS_COLOUR_NORMAL)
        mi.normal_n = mi.colour_n < 3 ? mi.colour_n : 3;
    /* Normals are directions, renormalised after filtering: premultiplying them would leave
     * |n| = 1/alpha after unpremultiplying, so only colour is premultiplied. */
    mi.premultiply = alpha && (m->colour == VTS_COLOUR_SRGB || m->colour == VTS_COLOUR_LINEAR);
    return mi;
}

static inline float load_sample(uint32_t sample, const void *src, size_t i, bool srgb)
{
    switch (sample) {
    case VTS_SAMPLE_U8: {
        uint8_t v = ((const uint8_t *)src)[i];
        return srgb ? lin_u8[v] : unorm_u8[v];
    }
    case VTS_SAMPLE_U16: {
        uint16_t v;
        memcpy(&v, (const uint8_t *)src + 2 * i, 2);
        return srgb ? lin_u16[v] : (float)v / 65535.0f;
    }
    case VTS_SAMPLE_F16: {
        uint16_t v;
        memcpy(&v, (const uint8_t *)src + 2 * i, 2);
        float f = half_to_float(v);
        return srgb ? (float)srgb_to_linear(f) : f;
    }
    default: {
        float f;
        memcpy(&f, (const uint8_t *)src + 4 * i, 4);
        return srgb ? (float)srgb_to_linear(f) : f;
    }
    }
}

/* dst[i] = table[in[i]], unrolled: the loop is bound by its loads and stores. */
static void table_lookup(const float *table, const uint8_t *in, float *dst, size_t n)
{
    size_t i = 0;
    for (; i + 8 <= n; i += 8) {
        float a0 = table[in[i]], a1 = table[in[i + 1]], a2 = table[in[i + 2]];
        float a3 = table[in[i + 3]], a4 = table[in[i + 4]], a5 = table[in[i + 5]];
        float a6 = table[in[i + 6]], a7 = table[in[i + 7]];
        dst[i] = a0, dst[i + 1] = a1, dst[i + 2] = a2, dst[i + 3] = a3;
        dst[i + 4] = a4, dst[i + 5] = a5, dst[i + 6] = a6, dst[i + 7] = a7;
    }
    for (; i < n; i++)
        dst[i] = table[in[i]];
}

void vt_filter_to_working(const struct vt_pixel_mode *m, uint32_t sample, const void *src,
                          float *dst, size_t n)
{
    assert(sample >= VTS_SAMPLE_U8 && sample <= VTS_SAMPLE_F32);
    struct mode_info mi = mode_info(m);
    uint32_t ch = mi.channels;
    if (sample == VTS_SAMPLE_U8)
        pthread_once(&once_u8, build_u8_tables);
    else if (sample == VTS_SAMPLE_U16 && mi.srgb)
        pthread_once(&once_u16, build_u16_tables);
    if (sample == VTS_SAMPLE_U8 && !mi.premultiply && mi.normal_n == 0) {
        /* the common case (opaque 8-bit colour or data): one table lookup per sample */
        const float *colour = mi.srgb ? lin_u8 : unorm_u8;
        const uint8_t *in = src;
        if (mi.colour_n == ch || colour == unorm_u8) { /* one table for every channel */
            table_lookup(colour, in, dst, n * ch);
            return;
        }
        for (size_t i = 0; i < n; i++)
            for (uint32_t c = 0; c < ch; c++)
                dst[i * ch + c] = (c < mi.colour_n ? colour : unorm_u8)[in[i * ch + c]];
        return;
    }
    if (sample == VTS_SAMPLE_F32 && !mi.srgb && !mi.premultiply && mi.normal_n == 0) {
        memcpy(dst, src, n * ch * sizeof(float));
        return;
    }
    for (size_t i = 0; i < n; i++) {
        float *px = dst + i * ch;
        for (uint32_t c = 0; c < ch; c++)
            px[c] = load_sample(sample, src, i * ch + c, mi.srgb && c < mi.colour_n);
        for (uint32_t c = 0; c < mi.normal_n; c++)
            px[c] = px[c] * 2.0f - 1.0f;
        if (mi.premultiply) {
            float a = px[ch - 1];
            for (uint32_t c = 0; c < mi.colour_n; c++)
                px[c] *= a;
        }
    }
}

static inline float clamp01(float v)
{
    return v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f; /* NaN -> 0 */
}

static inline void store_sample(uint32_t sample, void *dst, size_t i, float v, bool srgb)
{
    switch (sample) {
    case VTS_SAMPLE_U8:
        ((uint8_t *)dst)[i] =
            (uint8_t)(srgb ? encode_srgb_u8(v) : (unsigned)(clamp01(v) * 255.0f + 0.5f));
        return;
    case VTS_SAMPLE_U16: {
        uint16_t u =
            (uint16_t)(srgb ? encode_srgb_u16(v) : (unsigned)(clamp01(v) * 65535.0f + 0.5f));
        memcpy((uint8_t *)dst + 2 * i, &u, 2);
        return;
    }
    case VTS_SAMPLE_F16: {
        uint16_t h = float_to_half(srgb ? (float)linear_to_srgb(v) : v);
        memcpy((uint8_t *)dst + 2 * i, &h, 2);
        return;
    }
    default: {
        float f = srgb ? (float)linear_to_srgb(v) : v;
        memcpy((uint8_t *)dst + 4 * i, &f, 4);
        return;
    }
    }
}

/* Copies one working texel into px, unpremultiplied and with normals mapped back to [0,1]. */
static inline void unpremultiply(const struct mode_info *mi, const float *src, float *px)
{
    uint32_t ch = mi->channels;
    memcpy(px, src, ch * sizeof(float));
    if (mi->premultiply) {
        float a = px[ch - 1];
        for (uint32_t c = 0; c < mi->colour_n; c++)
            px[c] = a > 0.0f ? px[c] / a : 0.0f;
    }
    for (uint32_t c = 0; c < mi->normal_n; c++)
        px[c] = (px[c] + 1.0f) * 0.5f;
}

/* ---- pairs of 8-bit samples, box-filtered ---- */

static float pair_lin_u8[65536], pair_unorm_u8[65536];
static pthread_once_t once_pair_lin = PTHREAD_ONCE_INIT;
static pthread_once_t once_pair_unorm = PTHREAD_ONCE_INIT;

static void build_pairs(float *pairs, const float *t)
{
    for (unsigned p = 0; p < 256; p++)
        for (unsigned q = 0; q < 256; q++) {
            float acc = 0.5f * t[p]; /* the reduction's order: first tap, then the next added */
            acc += 0.5f * t[q];
            pairs[p << 8 | q] = acc;
        }
}

static void build_pair_lin(void)
{
    pthread_once(&once_u8, build_u8_tables);
    build_pairs(pair_lin_u8, lin_u8);
}

static void build_pair_unorm(void)
{
    pthread_once(&once_u8, build_u8_tables);
    build_pairs(pair_unorm_u8, unorm_u8);
}

const float *vt_filter_u8_pair_table(const struct vt_pixel_mode *m, const float *w)
{
    struct mode_info mi = mode_info(m);
    if (w[0] != 0.5f || w[1] != 0.5f || mi.premultiply || mi.normal_n != 0)
        return NULL;
    if (!mi.srgb) { /* vt_filter_to_working: unorm_u8 for every channel */
        pthread_once(&once_pair_unorm, build_pair_unorm);
        return pair_unorm_u8;
    }
    if (mi.colour_n != mi.channels)
        return NULL;
    pthread_once(&once_pair_lin, build_pair_lin);
    return pair_lin_u8;
}

/* The common case, with the sample type hoisted out of the loop. */
static void from_working_u8(const struct mode_info *mi, const float *src, uint8_t *dst, size_t n)
{
    uint32_t ch = mi->channels, srgb_n = mi->srgb ? mi->colour_n : 0;
    if (!mi->premultiply && mi->normal_n == 0 && (srgb_n == ch || srgb_n == 0)) {
        /* opaque colour or data: every sample encoded alike, no per-texel work */
        size_t count = n * ch;
        if (srgb_n)
            encode_srgb_u8_run(src, dst, count);
        else
            for (size_t i = 0; i < count; i++)
                dst[i] = (uint8_t)(clamp01(src[i]) * 255.0f + 0.5f);
        return;
    }
    for (size_t i = 0; i < n; i++) {
        float px[4];
        unpremultiply(mi, src + i * ch, px);
        uint8_t *o = dst + i * ch;
        uint32_t c = 0;
        for (; c < srgb_n; c++)
            o[c] = (uint8_t)encode_srgb_u8(px[c]);
        for (; c < ch; c++)
            o[c] = (uint8_t)(clamp01(px[c]) * 255.0f + 0.5f);
    }
}

void vt_filter_from_working(const struct vt_pixel_mode *m, uint32_t sample, const float *src,
                            void *dst, size_t n)
{
    assert(sample >= VTS_SAMPLE_U8 && sample <= VTS_SAMPLE_F32);
    struct mode_info mi = mode_info(m);
    uint32_t ch = mi.channels;
    if (sample == VTS_SAMPLE_U8 && mi.srgb)
        pthread_once(&once_u8, build_u8_tables);
    else if (sample == VTS_SAMPLE_U16 && mi.srgb)
        pthread_once(&once_u16, build_u16_tables);
    if (sample == VTS_SAMPLE_F32 && !mi.srgb && !mi.premultiply && mi.normal_n == 0) {
        memcpy(dst, src, n * ch * sizeof(float));
        return;
    }
    if (sample == VTS_SAMPLE_U8) {
        from_working_u8(&mi, src, dst, n);
        return;
    }
    for (size_t i = 0; i < n; i++) {
        float px[4];
        unpremultiply(&mi, src + i * ch, px);
        for (uint32_t c = 0; c < ch; c++)
            store_sample(sample, dst, i * ch + c, px[c], mi.srgb && c < mi.colour_n);
    }
}
