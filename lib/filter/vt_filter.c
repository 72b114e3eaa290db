/* Mip filtering: kernels, sample <-> working-space conversions, separable 2:1 reduction.
 *
 * Numerics: kernel weights are computed and normalised in double, then stored as float. The
 * reduction sums floats in a fixed tap order (first tap times its weight, then each next tap
 * added), in every code path, so that an output texel has the same bits whichever region split,
 * edge path or vector path computed it. The build uses -std=c11, so GCC does not contract a*b+c
 * into fused multiply-adds behind our back. */
#include "vt_filter.h"

#include <assert.h>
#include <math.h>
#include <pthread.h>
#include <string.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "vt_checked.h"
#include "vt_error.h"
#include "vts.h"

/* ---- names ---- */

static const char *const filter_names[] = {"box", "triangle", "lanczos3", "kaiser"};

int vt_filter_parse(const char *name, enum vt_filter_kind *out)
{
    for (size_t i = 0; name && i < sizeof filter_names / sizeof filter_names[0]; i++) {
        if (strcmp(name, filter_names[i]) == 0) {
            *out = (enum vt_filter_kind)i;
            return 0;
        }
    }
    return VTS_ERR_ARG;
}

const char *vt_filter_name(enum vt_filter_kind kind)
{
    if ((unsigned)kind < sizeof filter_names / sizeof filter_names[0])
        return filter_names[kind];
    return "?";
}

/* ---- kernels ---- */

#define PI           3.14159265358979323846
#define KAISER_ALPHA 4.0
#define SINC_RADIUS  3.0

static double sinc(double x)
{
    if (x == 0.0)
        return 1.0;
    double px = PI * x;
    return sin(px) / px;
}

/* Modified Bessel function of the first kind, order 0, by its power series (converges fast for
 * the arguments we use, |x| <= KAISER_ALPHA). */
static double bessel_i0(double x)
{
    double sum = 1.0, term = 1.0, q = x * x / 4.0;
    for (int k = 1; k < 50; k++) {
        term *= q / ((double)k * k);
        sum += term;
        if (term < sum * 1e-17)
            break;
    }
    return sum;
}

/* The kernel K(x), x in coarser-texel units. */
static double kernel_eval(enum vt_filter_kind kind, double x)
{
    double ax = fabs(x);
    switch (kind) {
    case VT_FILTER_BOX:
        return ax <= 0.5 ? 1.0 : 0.0;
    case VT_FILTER_TRIANGLE:
        return ax < 1.0 ? 1.0 - ax : 0.0;
    case VT_FILTER_LANCZOS3:
        return ax < SINC_RADIUS ? sinc(ax) * sinc(ax / SINC_RADIUS) : 0.0;
    case VT_FILTER_KAISER: {
        if (ax >= SINC_RADIUS)
            return 0.0;
        double r = ax / SINC_RADIUS;
        return sinc(ax) * bessel_i0(KAISER_ALPHA * sqrt(1.0 - r * r)) / bessel_i0(KAISER_ALPHA);
    }
    }
    return 0.0;
}

void vt_kernel_init(struct vt_kernel *k, enum vt_filter_kind kind)
{
    static const int firsts[] = {0, -1, -5, -5};
    static const int counts[] = {2, 4, 12, 12};
    assert((unsigned)kind < 4);
    memset(k, 0, sizeof *k);
    k->kind = kind;
    k->first = firsts[kind];
    k->count = counts[kind];
    assert(k->count <= VT_KERNEL_MAX_TAPS);

    /* Tap t is finer texel j = 2i + first + t, whose centre lies (j + 0.5) - (2i + 1) finer
     * texels from the output centre, i.e. half that in coarser texels. */
    double w[VT_KERNEL_MAX_TAPS], sum = 0.0;
    for (int t = 0; t < k->count; t++) {
        w[t] = kernel_eval(kind, ((double)(k->first + t) - 0.5) / 2.0);
        sum += w[t];
    }
    for (int t = 0; t < k->count; t++)
        k->weights[t] = (float)(w[t] / sum);
}

uint32_t vt_kernel_margin(const struct vt_kernel *k)
{
    int left = -k->first, right = k->first + k->count - 2;
    int m = left > right ? left : right;
    return m > 0 ? (uint32_t)m : 0;
}

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
    if (scratch_floats < vt_filter_reduce_scratch(k, src, dst))
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
    for (uint32_t y = 0; y < dst->height; y++) {
        const float *rows[VT_KERNEL_MAX_TAPS];
        float *out = dst->px + (size_t)y * row_floats;
        if (y >= rep_y) {
            memcpy(out, out - row_floats, row_floats * sizeof(float));
            continue;
        }
        int64_t last = tap_pos(&ay, ay.dst0 + y, k->count - 1);
        for (; filled <= last; filled++)
            h_row(&ax, k->weights, ch, ib, ie, rep_x, source_row(&rs, filled, read0, read1),
                  scratch + (size_t)(filled - row0) * row_floats);
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
    return n + row;
}

void vt_filter_renormalize(struct vt_fregion *r)
{
    uint32_t ch = r->channels;
    if (ch < 3)
        return;
    size_t n = (size_t)r->width * r->height;
    for (size_t i = 0; i < n; i++) {
        float *p = r->px + i * ch;
        float len2 = p[0] * p[0] + p[1] * p[1] + p[2] * p[2];
        if (len2 > 0.0f && len2 < INFINITY) {
            float inv = 1.0f / sqrtf(len2);
            p[0] *= inv;
            p[1] *= inv;
            p[2] *= inv;
        } else {
            p[0] = 0.0f;
            p[1] = 0.0f;
            p[2] = 1.0f;
        }
    }
}
