/* One BC4 block encoded and decoded (internal/vt_bc4_block.h): BC4 (RGTC1), each half of BC5
 * (RGTC2) and BC3's alpha half are this block.
 *
 * Encoder: the 8-value mode between max and min and the 6-value mode (explicit 0 and 255) between
 * the min and max of the other values, whichever has the smaller error; best refines both: least
 * squares on the index weights while the error falls, then +-1 on each endpoint while it falls.
 * With VT_BC4_BLOCK_EXTEND, best also starts from endpoints past the values: the min (or the max)
 * on an endpoint and the other extreme on the inner entry j of the palette's steps (j = 1 ..
 * steps - 1), the best of them refined the same way (a ramp of fewer levels than the palette
 * becomes exact).
 * Error: the sum of squared differences to the decoded palette (integer). The index of a value
 * is the nearest palette entry, the lowest index on a tie (one minimum over distance << 3 | k).
 *
 * SIMD: the error loop has an SSE2 path (x86-64's baseline); VT_BC_ENCODE_PORTABLE builds
 * without it, with the same integers. Float only in the least-squares division, compiled with
 * -ffp-contract=off (CMakeLists.txt). This is the code that was BC3's alpha encoder in
 * vt_bc_encode.c, moved here unchanged (BC3 bytes are the same). */
#include <stdbool.h>
#include <stdint.h>

#include "internal/vt_bc4_block.h"

#if defined(__SSE2__) && !defined(VT_BC_ENCODE_PORTABLE)
#define VT_BC4_BLOCK_SSE2 1
#include <emmintrin.h>
#endif

#define BC4_TEXELS 16
#define BC4_REFINE 4 /* least-squares rounds at most (best) */
#define BC4_SEARCH 8 /* +-1 endpoint search passes at most (best) */

#if !defined(VT_BC4_BLOCK_SSE2)
static int bc4_abs(int v)
{
    return v < 0 ? -v : v;
}
#endif

static int bc4_round_clamp(double v)
{
    if (!(v > 0))
        return 0;
    if (v >= 255)
        return 255;
    return (int)(v + 0.5);
}

void vt_bc4_block_palette(unsigned v0, unsigned v1, int pal[8])
{
    pal[0] = (int)v0;
    pal[1] = (int)v1;
    if (v0 > v1) {
        for (int i = 1; i <= 6; i++)
            pal[1 + i] = ((7 - i) * (int)v0 + i * (int)v1) / 7;
    } else {
        for (int i = 1; i <= 4; i++)
            pal[1 + i] = ((5 - i) * (int)v0 + i * (int)v1) / 5;
        pal[6] = 0;
        pal[7] = 255;
    }
}

struct bc4_values {
    _Alignas(16) uint8_t byte[BC4_TEXELS]; /* for the SSE2 error loop */
    int value[BC4_TEXELS];
};

struct bc4_candidate {
    unsigned a0, a1;
    uint64_t indices; /* 3 bits per texel */
    uint64_t error;
};

static uint64_t bc4_eval(const struct bc4_values *t, unsigned a0, unsigned a1, uint64_t bound,
                         uint64_t *indices)
{
    int pal[8];
    vt_bc4_block_palette(a0, a1, pal);
#if defined(VT_BC4_BLOCK_SSE2)
    /* key = |value - pal[k]| << 3 | k in 16-bit lanes (< 2048), one minimum gives both */
    const __m128i zero = _mm_setzero_si128();
    __m128i x = _mm_load_si128((const __m128i *)t->byte);
    __m128i m_lo = _mm_set1_epi16(INT16_MAX), m_hi = m_lo;
    for (int k = 0; k < 8; k++) {
        __m128i p = _mm_set1_epi8((char)pal[k]);
        __m128i d = _mm_or_si128(_mm_subs_epu8(x, p), _mm_subs_epu8(p, x));
        __m128i tag = _mm_set1_epi16((int16_t)k);
        m_lo =
            _mm_min_epi16(m_lo, _mm_or_si128(_mm_slli_epi16(_mm_unpacklo_epi8(d, zero), 3), tag));
        m_hi =
            _mm_min_epi16(m_hi, _mm_or_si128(_mm_slli_epi16(_mm_unpackhi_epi8(d, zero), 3), tag));
    }
    __m128i d_lo = _mm_srli_epi16(m_lo, 3), d_hi = _mm_srli_epi16(m_hi, 3);
    __m128i sq = _mm_add_epi32(_mm_madd_epi16(d_lo, d_lo), _mm_madd_epi16(d_hi, d_hi));
    sq = _mm_add_epi32(sq, _mm_shuffle_epi32(sq, _MM_SHUFFLE(1, 0, 3, 2)));
    sq = _mm_add_epi32(sq, _mm_shuffle_epi32(sq, _MM_SHUFFLE(2, 3, 0, 1)));
    uint64_t error = (uint32_t)_mm_cvtsi128_si32(sq);
    if (error >= bound)
        return UINT64_MAX;
    /* the 16 indices of 3 bits: bytes, then pairs (6 bits), fours (12), eights (24) */
    const __m128i seven = _mm_set1_epi16(7);
    __m128i b = _mm_packus_epi16(_mm_and_si128(m_lo, seven), _mm_and_si128(m_hi, seven));
    b = _mm_and_si128(_mm_or_si128(b, _mm_srli_epi16(b, 5)), _mm_set1_epi16(0x3f));
    b = _mm_and_si128(_mm_or_si128(b, _mm_srli_epi32(b, 10)), _mm_set1_epi32(0xfff));
    b = _mm_and_si128(_mm_or_si128(b, _mm_srli_epi64(b, 20)),
                      _mm_set_epi32(0, 0xffffff, 0, 0xffffff));
    _Alignas(16) uint64_t half[2];
    _mm_store_si128((__m128i *)half, b);
    *indices = half[0] | half[1] << 24;
    return error;
#else
    uint64_t error = 0, idx = 0;
    for (int i = 0; i < BC4_TEXELS; i++) {
        uint32_t m = UINT32_MAX; /* distance << 3 | index, branch-free minimum */
        for (int k = 0; k < 8; k++) {
            uint32_t key = (uint32_t)bc4_abs(t->value[i] - pal[k]) << 3 | (uint32_t)k;
            m = key < m ? key : m;
        }
        idx |= (uint64_t)(m & 7) << (3 * i);
        error += (uint64_t)(m >> 3) * (m >> 3);
        if (error >= bound)
            return UINT64_MAX;
    }
    *indices = idx;
    return error;
#endif
}

/* (a0, a1) in the 6-value mode (six: a0 <= a1) or the 8-value mode (a0 > a1), ordered so. */
static bool bc4_try(const struct bc4_values *t, unsigned a0, unsigned a1, bool six,
                    struct bc4_candidate *cand)
{
    if (six ? a0 > a1 : a0 < a1) {
        unsigned s = a0;
        a0 = a1;
        a1 = s;
    }
    uint64_t idx;
    uint64_t error = bc4_eval(t, a0, a1, cand->error, &idx);
    if (error >= cand->error)
        return false;
    *cand = (struct bc4_candidate){a0, a1, idx, error};
    return true;
}

static bool bc4_solve(const struct bc4_values *t, const struct bc4_candidate *c, bool six,
                      unsigned *a0, unsigned *a1)
{
    const int64_t scale = six ? 5 : 7;
    int64_t aa = 0, ab = 0, bb = 0, ax = 0, bx = 0;
    for (int i = 0; i < BC4_TEXELS; i++) {
        unsigned k = (unsigned)(c->indices >> (3 * i) & 7);
        if (six && k >= 6)
            continue; /* the explicit 0 and 255 */
        int64_t a = k == 0 ? scale : k == 1 ? 0 : scale - (k - 1), b = scale - a;
        aa += a * a;
        ab += a * b;
        bb += b * b;
        ax += a * t->value[i];
        bx += b * t->value[i];
    }
    int64_t det = aa * bb - ab * ab;
    if (det == 0)
        return false;
    *a0 = (unsigned)bc4_round_clamp((double)(scale * (bb * ax - ab * bx)) / (double)det);
    *a1 = (unsigned)bc4_round_clamp((double)(scale * (aa * bx - ab * ax)) / (double)det);
    return true;
}

static void bc4_refine(const struct bc4_values *t, unsigned a0, unsigned a1, bool six,
                       struct bc4_candidate *best)
{
    struct bc4_candidate chain = {0, 0, 0, UINT64_MAX};
    bc4_try(t, a0, a1, six, &chain);
    for (int r = 0; r < BC4_REFINE && chain.error > 0; r++) {
        unsigned n0, n1;
        if (!bc4_solve(t, &chain, six, &n0, &n1) || !bc4_try(t, n0, n1, six, &chain))
            break;
    }
    for (int pass = 0; pass < BC4_SEARCH && chain.error > 0; pass++) {
        bool improved = false;
        for (int d = -1; d <= 1; d += 2) {
            int v0 = (int)chain.a0 + d, v1 = (int)chain.a1 + d;
            if (v0 >= 0 && v0 <= 255)
                improved |= bc4_try(t, (unsigned)v0, chain.a1, six, &chain);
            if (v1 >= 0 && v1 <= 255)
                improved |= bc4_try(t, chain.a0, (unsigned)v1, six, &chain);
        }
        if (!improved)
            break;
    }
    if (chain.error < best->error)
        *best = chain;
}

/* The starts past the values: [lo, hi] spans j of the mode's steps (7 or 5) from either end;
 * each evaluated, the best of them refined. */
static void bc4_extend(const struct bc4_values *t, int lo, int hi, bool six,
                       struct bc4_candidate *best)
{
    int steps = six ? 5 : 7;
    struct bc4_candidate start = {0, 0, 0, UINT64_MAX};
    for (int j = 1; j < steps; j++) {
        int far = (hi - lo) * steps / j;
        int up = lo + far > 255 ? 255 : lo + far, down = hi - far < 0 ? 0 : hi - far;
        bc4_try(t, (unsigned)lo, (unsigned)up, six, &start);
        bc4_try(t, (unsigned)down, (unsigned)hi, six, &start);
    }
    if (start.error < UINT64_MAX)
        bc4_refine(t, start.a0, start.a1, six, best);
}

void vt_bc4_block_encode(const unsigned char *values, size_t step, unsigned flags,
                         unsigned char *dst)
{
    struct bc4_values t;
    int lo = 255, hi = 0, lo6 = 255, hi6 = 0;
    for (int i = 0; i < BC4_TEXELS; i++) {
        int a = t.value[i] = t.byte[i] = values[(size_t)i * step];
        lo = a < lo ? a : lo;
        hi = a > hi ? a : hi;
        if (a != 0 && a != 255) {
            lo6 = a < lo6 ? a : lo6;
            hi6 = a > hi6 ? a : hi6;
        }
    }
    struct bc4_candidate best = {(unsigned)lo, (unsigned)lo, 0, 0};
    if (lo != hi) {
        best.error = UINT64_MAX;
        if (lo6 > hi6) /* only 0 and 255 */
            lo6 = hi6 = 0;
        if (flags & VT_BC4_BLOCK_BEST) {
            bc4_refine(&t, (unsigned)hi, (unsigned)lo, false, &best);
            bc4_refine(&t, (unsigned)lo6, (unsigned)hi6, true, &best);
            if (flags & VT_BC4_BLOCK_EXTEND) {
                bc4_extend(&t, lo, hi, false, &best);
                if (lo6 < hi6)
                    bc4_extend(&t, lo6, hi6, true, &best);
            }
        } else {
            bc4_try(&t, (unsigned)hi, (unsigned)lo, false, &best);
            bc4_try(&t, (unsigned)lo6, (unsigned)hi6, true, &best);
        }
    }
    dst[0] = (unsigned char)best.a0;
    dst[1] = (unsigned char)best.a1;
    for (int b = 0; b < 6; b++)
        dst[2 + b] = (unsigned char)(best.indices >> (8 * b));
}

void vt_bc4_block_decode(const unsigned char *block, unsigned char *values, size_t step)
{
    int pal[8];
    vt_bc4_block_palette(block[0], block[1], pal);
    uint64_t indices = 0;
    for (int b = 0; b < 6; b++)
        indices |= (uint64_t)block[2 + b] << (8 * b);
    for (int i = 0; i < BC4_TEXELS; i++)
        values[(size_t)i * step] = (unsigned char)pal[(indices >> (3 * i)) & 7];
}
