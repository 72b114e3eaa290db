/* Our BC1 colour block encoder, also BC3's colour half (the format: docs/codecs.md and
 * vt_codec_bc.c's decoder formulas). BC3's alpha half is a BC4 block: vt_bc4_block.c.
 *
 * Colour (BC1, and BC3's colour half in the 4-colour mode only):
 *   1. A block whose opaque texels are all one colour takes the best endpoint pair per channel from
 *      a table (built once: for each 8-bit value, the 5- or 6-bit pair whose 2/3-1/3 or 1/2-1/2
 *      mix, as the decoder truncates it, is closest).
 *   2. Otherwise: weighted mean and covariance, principal axis by power iteration, texels
 *      projected on it; the extreme projections (inset by 1/16 of the range) are the start
 *      endpoints, quantised to RGB565 (nearest expanded value).
 *   3. Iterated: indices by the nearest palette colour (the palette the decoder computes), then
 *      the least-squares endpoints for those index weights (the 2x2 normal equations, integer
 *      sums, one division), requantised; kept while the block error falls.
 *   4. best: the same from four starts between the extremes (inset 0, 1/16, 1/8, 1/4 of the
 *      range), two starts from indices (the texels in three bins along the axis on the top or the
 *      bottom three palette entries: blocks of three clusters whose best endpoint lies outside
 *      the texels), the 3-colour mode from two starts as well (BC1), then a search of +-1 on each
 *      of the six 565 components around the best pair, kept while it improves, and a last
 *      least-squares step.
 * Error: the sum over texels of the squared RGB distance to the decoded palette colour (integer,
 * uniform weights as PSNR counts; times alpha + 1 with VT_BC_ENCODE_WEIGHT_BY_ALPHA). BC1
 * texels with alpha < 128 take index 3 of the 3-colour mode (transparent black) and count nothing.
 *
 * SIMD: the set-up, the error loops and the least-squares sums have SSE2 paths (x86-64's
 * baseline) and the colour error loop an AVX2 one picked at run time; VT_BC_ENCODE_NO_AVX2 and
 * VT_BC_ENCODE_PORTABLE (no SIMD) build without them. All give the same integers
 * (tests/unit/codec/test_vt_bc_encode_portable.c builds this file both ways against the library).
 *
 * Determinism: the error and every choice between candidates are integer; the float steps (axis,
 * projections, least-squares division) are plain IEEE arithmetic in a fixed order, compiled with
 * -ffp-contract=off (CMakeLists.txt) so that no platform fuses them differently. */
#include <pthread.h>
#include <stdbool.h>
#include <stdint.h>
#include <string.h>

#include "internal/vt_bc_encode.h"

#if defined(__SSE2__) && !defined(VT_BC_ENCODE_PORTABLE)
#define VT_BC_ENCODE_SSE2 1
#include <emmintrin.h>
/* The colour error loop in AVX2 as well, chosen at run time (GCC and clang on x86-64) */
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) &&                            \
    !defined(VT_BC_ENCODE_NO_AVX2)
#define VT_BC_ENCODE_AVX2 1
#include <immintrin.h>
#endif
#endif

#define BC_TEXELS        16
#define BC_ALPHA_OPAQUE  128 /* BC1: alpha below this is stored as transparent */
#define BC_POWER_FAST    4   /* power iterations for the principal axis */
#define BC_POWER_BEST    8
#define BC_REFINE_BEST   4 /* least-squares rounds per start (fast: 1) */
#define BC_SEARCH_PASSES 8 /* +-1 endpoint search passes at most (best) */

/* ---- tables, built once ---- */

struct bc_pair {
    uint8_t q0, q1; /* endpoint values of one channel, 5 or 6 bits */
};

static uint8_t bc_quant5[256], bc_quant6[256]; /* 8-bit value -> nearest 5/6-bit value */
static struct bc_pair bc_single4[2][256];      /* [0]: 5 bits, [1]: 6 bits; 4-colour, index 2 */
static struct bc_pair bc_single3[2][256];      /* 3-colour mode, index 2 (the half) */
static pthread_once_t bc_tables_once = PTHREAD_ONCE_INIT;
#if defined(VT_BC_ENCODE_AVX2)
static bool bc_use_avx2; /* the CPU has AVX2: set once with the tables */
#endif

static int bc_expand(unsigned q, int bits)
{
    return bits == 5 ? (int)(q << 3 | q >> 2) : (int)(q << 2 | q >> 4);
}

static int bc_abs(int v)
{
    return v < 0 ? -v : v;
}

static void bc_tables_init(void)
{
#if defined(VT_BC_ENCODE_AVX2)
    __builtin_cpu_init();
    bc_use_avx2 = __builtin_cpu_supports("avx2");
#endif
    for (int b = 0; b < 2; b++) {
        int bits = b ? 6 : 5, levels = 1 << bits;
        uint8_t *quant = b ? bc_quant6 : bc_quant5;
        for (int v = 0; v < 256; v++) {
            int best = 0, best_d = 256;
            for (int q = 0; q < levels; q++) {
                int d = bc_abs(bc_expand((unsigned)q, bits) - v);
                if (d < best_d)
                    best = q, best_d = d;
            }
            quant[v] = (uint8_t)best;
            /* single colour: the pair whose mix is closest; ties go to the closer endpoints */
            int best4 = 1 << 30, best3 = 1 << 30;
            for (int q0 = 0; q0 < levels; q0++) {
                for (int q1 = 0; q1 < levels; q1++) {
                    int e0 = bc_expand((unsigned)q0, bits), e1 = bc_expand((unsigned)q1, bits);
                    int spread = bc_abs(e0 - e1);
                    int s4 = bc_abs((2 * e0 + e1) / 3 - v) * 1024 + spread;
                    int s3 = bc_abs((e0 + e1) / 2 - v) * 1024 + spread;
                    if (s4 < best4)
                        best4 = s4, bc_single4[b][v] = (struct bc_pair){(uint8_t)q0, (uint8_t)q1};
                    if (s3 < best3)
                        best3 = s3, bc_single3[b][v] = (struct bc_pair){(uint8_t)q0, (uint8_t)q1};
                }
            }
        }
    }
}

/* ---- colour ---- */

#define BC_MEMO_BITS 6
#define BC_MEMO      (1 << BC_MEMO_BITS) /* slots of the memo of pairs tried in a block */

struct bc_memo {
    uint32_t key;     /* c0 << 16 | c1, as stored */
    uint32_t error;   /* exact: the error; else a lower bound of it */
    uint32_t indices; /* exact only */
    bool exact;
};

struct bc_colour_texels {
    _Alignas(16) int16_t plane[3][BC_TEXELS];  /* R, G, B planes for the SIMD error loop */
    _Alignas(16) uint16_t weight[BC_TEXELS];   /* 0 for a transparent texel */
    _Alignas(16) uint32_t count[BC_TEXELS];    /* ~0 for a texel of weight > 0, else 0 */
    _Alignas(16) uint32_t weight32[BC_TEXELS]; /* the weights again (non-uniform blocks) */
    uint32_t force;       /* 3 << 2i for a transparent texel i (index 3 of the 3-colour mode) */
    uint32_t transparent; /* bit i: texel i is stored as transparent */
    int32_t wsum, wx[3];  /* the sums of the weights and weighted R, G, B (set by the axis) */
    bool uniform;         /* every weight is 0 or one common value: the error counts texels */
    unsigned memo_len;    /* pairs in the memo */
    uint64_t memo_used;   /* bit h: slot h holds a pair */
    struct bc_memo memo[BC_MEMO];
    bool four_only;
};

struct bc_colour_candidate {
    unsigned c0, c1; /* RGB565 as stored */
    uint32_t indices;
    uint32_t error;
};

static void bc_unpack565(unsigned c, int rgb[3])
{
    rgb[0] = bc_expand(c >> 11, 5);
    rgb[1] = bc_expand((c >> 5) & 63, 6);
    rgb[2] = bc_expand(c & 31, 5);
}

/* The error of endpoints (c0, c1) as stored (their order picks the mode), with the nearest
 * palette index of every texel in *indices; UINT32_MAX (and *indices untouched) when it reaches
 * bound. The error is the sum of the squared RGB distances,
 * times the texel's weight unless the block is uniform (then a common factor left out):
 * < 16 * 195075 * 256 < 2^32. */
/* The palette the decoder computes for (c0, c1); returns true for the 4-colour mode. */
static bool bc_colour_palette(const struct bc_colour_texels *t, unsigned c0, unsigned c1,
                              int pal[4][3])
{
    bc_unpack565(c0, pal[0]);
    bc_unpack565(c1, pal[1]);
    bool four = t->four_only || c0 > c1;
    for (int k = 0; k < 3; k++) {
        if (four) {
            pal[2][k] = (2 * pal[0][k] + pal[1][k]) / 3;
            pal[3][k] = (pal[0][k] + 2 * pal[1][k]) / 3;
        } else {
            pal[2][k] = (pal[0][k] + pal[1][k]) / 2;
            pal[3][k] = 0;
        }
    }
    return four;
}

#if defined(VT_BC_ENCODE_SSE2)
/* 16 bytes of 0..3 (texel order) folded into the 32-bit index word, 2 bits each. */
static uint32_t bc_fold_indices(__m128i bytes)
{
    __m128i x = _mm_and_si128(_mm_or_si128(bytes, _mm_srli_epi16(bytes, 6)), _mm_set1_epi16(15));
    x = _mm_and_si128(_mm_or_si128(x, _mm_srli_epi32(x, 12)), _mm_set1_epi32(255));
    x = _mm_packus_epi16(_mm_packs_epi32(x, x), x);
    return (uint32_t)_mm_cvtsi128_si32(x);
}
#endif

static uint32_t bc_colour_eval(const struct bc_colour_texels *t, unsigned c0, unsigned c1,
                               uint32_t bound, uint32_t *indices)
{
    int pal[4][3];
    bool four = bc_colour_palette(t, c0, c1, pal);
    /* key = distance << 2 | index: one branch-free minimum gives both; the 3-colour mode has no
     * fourth colour for an opaque texel: key INT32_MAX never wins. Integer only: the SSE2 path
     * and the portable one give the same keys. */
    uint32_t error = 0;
#if defined(VT_BC_ENCODE_SSE2)
    const __m128i zero = _mm_setzero_si128();
    __m128i m[4];
    for (int half = 0; half < 2; half++) {
        __m128i r = _mm_load_si128((const __m128i *)&t->plane[0][8 * half]);
        __m128i g = _mm_load_si128((const __m128i *)&t->plane[1][8 * half]);
        __m128i b = _mm_load_si128((const __m128i *)&t->plane[2][8 * half]);
        __m128i m_lo = _mm_set1_epi32(INT32_MAX), m_hi = m_lo;
        for (int k = 0; k < 4; k++) {
            __m128i dr = _mm_sub_epi16(r, _mm_set1_epi16((int16_t)pal[k][0]));
            __m128i dg = _mm_sub_epi16(g, _mm_set1_epi16((int16_t)pal[k][1]));
            __m128i db = _mm_sub_epi16(b, _mm_set1_epi16((int16_t)pal[k][2]));
            __m128i rg_lo = _mm_unpacklo_epi16(dr, dg), rg_hi = _mm_unpackhi_epi16(dr, dg);
            __m128i b_lo = _mm_unpacklo_epi16(db, zero), b_hi = _mm_unpackhi_epi16(db, zero);
            __m128i d_lo = _mm_add_epi32(_mm_madd_epi16(rg_lo, rg_lo), _mm_madd_epi16(b_lo, b_lo));
            __m128i d_hi = _mm_add_epi32(_mm_madd_epi16(rg_hi, rg_hi), _mm_madd_epi16(b_hi, b_hi));
            __m128i tag = _mm_set1_epi32(k == 3 && !four ? INT32_MAX : k);
            d_lo = _mm_or_si128(_mm_slli_epi32(d_lo, 2), tag);
            d_hi = _mm_or_si128(_mm_slli_epi32(d_hi, 2), tag);
            __m128i lt_lo = _mm_cmplt_epi32(d_lo, m_lo), lt_hi = _mm_cmplt_epi32(d_hi, m_hi);
            m_lo = _mm_or_si128(_mm_and_si128(lt_lo, d_lo), _mm_andnot_si128(lt_lo, m_lo));
            m_hi = _mm_or_si128(_mm_and_si128(lt_hi, d_hi), _mm_andnot_si128(lt_hi, m_hi));
        }
        m[2 * half] = m_lo;
        m[2 * half + 1] = m_hi;
        if (t->uniform) { /* the error of these 8 texels; out as soon as it reaches bound */
            __m128i s = _mm_add_epi32(
                _mm_and_si128(_mm_srli_epi32(m_lo, 2),
                              _mm_load_si128((const __m128i *)&t->count[8 * half])),
                _mm_and_si128(_mm_srli_epi32(m_hi, 2),
                              _mm_load_si128((const __m128i *)&t->count[8 * half + 4])));
            s = _mm_add_epi32(s, _mm_shuffle_epi32(s, _MM_SHUFFLE(1, 0, 3, 2)));
            s = _mm_add_epi32(s, _mm_shuffle_epi32(s, _MM_SHUFFLE(2, 3, 0, 1)));
            error += (uint32_t)_mm_cvtsi128_si32(s);
        } else { /* distance (< 2^18) times weight (<= 256): 32 x 32 -> 64-bit products */
            __m128i w_lo = _mm_load_si128((const __m128i *)&t->weight32[8 * half]);
            __m128i w_hi = _mm_load_si128((const __m128i *)&t->weight32[8 * half + 4]);
            __m128i d_lo = _mm_srli_epi32(m_lo, 2), d_hi = _mm_srli_epi32(m_hi, 2);
            __m128i p = _mm_add_epi64(
                _mm_add_epi64(_mm_mul_epu32(d_lo, w_lo),
                              _mm_mul_epu32(_mm_srli_epi64(d_lo, 32), _mm_srli_epi64(w_lo, 32))),
                _mm_add_epi64(_mm_mul_epu32(d_hi, w_hi),
                              _mm_mul_epu32(_mm_srli_epi64(d_hi, 32), _mm_srli_epi64(w_hi, 32))));
            p = _mm_add_epi64(p, _mm_unpackhi_epi64(p, p));
            error += (uint32_t)_mm_cvtsi128_si32(p); /* the block's total is < 2^32 */
        }
        if (error >= bound)
            return UINT32_MAX;
    }
    {
        /* the indices: 16 bytes of 0..3 folded into 2 bits each */
        const __m128i three = _mm_set1_epi32(3);
        __m128i i01 = _mm_packs_epi32(_mm_and_si128(m[0], three), _mm_and_si128(m[1], three));
        __m128i i23 = _mm_packs_epi32(_mm_and_si128(m[2], three), _mm_and_si128(m[3], three));
        *indices = bc_fold_indices(_mm_packus_epi16(i01, i23)) | t->force;
        return error;
    }
#else
    uint32_t key[BC_TEXELS], idx = 0;
    for (int i = 0; i < BC_TEXELS; i++) {
        uint32_t m = INT32_MAX;
        for (int k = 0; k < 4; k++) {
            int32_t dr = t->plane[0][i] - pal[k][0], dg = t->plane[1][i] - pal[k][1],
                    db = t->plane[2][i] - pal[k][2];
            uint32_t d = (uint32_t)(dr * dr + dg * dg + db * db) << 2 | (uint32_t)k;
            d = k == 3 && !four ? INT32_MAX : d;
            m = d < m ? d : m;
        }
        key[i] = m;
    }
    for (int i = 0; i < BC_TEXELS; i++) {
        idx |= (key[i] & 3) << (2 * i);
        uint32_t w = t->uniform ? t->weight[i] != 0 : t->weight[i];
        error += (key[i] >> 2) * w;
    }
    if (error >= bound)
        return UINT32_MAX;
    *indices = idx | t->force;
    return error;
#endif
}

#if defined(VT_BC_ENCODE_AVX2)
/* bc_colour_eval with all 16 texels in one register per channel: the same keys, the same error
 * and indices (the unpacks work within 128-bit lanes: m_lo holds texels 0-3 and 8-11, m_hi 4-7
 * and 12-15; the masks and weights are loaded in that order). */
__attribute__((target("avx2"))) static uint32_t
bc_colour_eval_avx2(const struct bc_colour_texels *t, unsigned c0, unsigned c1, uint32_t bound,
                    uint32_t *indices)
{
    int pal[4][3];
    bool four = bc_colour_palette(t, c0, c1, pal);
    const __m256i zero = _mm256_setzero_si256();
    __m256i r = _mm256_loadu_si256((const __m256i *)t->plane[0]);
    __m256i g = _mm256_loadu_si256((const __m256i *)t->plane[1]);
    __m256i b = _mm256_loadu_si256((const __m256i *)t->plane[2]);
    __m256i m_lo = _mm256_set1_epi32(INT32_MAX), m_hi = m_lo;
    for (int k = 0; k < 4; k++) {
        __m256i dr = _mm256_sub_epi16(r, _mm256_set1_epi16((int16_t)pal[k][0]));
        __m256i dg = _mm256_sub_epi16(g, _mm256_set1_epi16((int16_t)pal[k][1]));
        __m256i db = _mm256_sub_epi16(b, _mm256_set1_epi16((int16_t)pal[k][2]));
        __m256i rg_lo = _mm256_unpacklo_epi16(dr, dg), rg_hi = _mm256_unpackhi_epi16(dr, dg);
        __m256i b_lo = _mm256_unpacklo_epi16(db, zero), b_hi = _mm256_unpackhi_epi16(db, zero);
        __m256i d_lo =
            _mm256_add_epi32(_mm256_madd_epi16(rg_lo, rg_lo), _mm256_madd_epi16(b_lo, b_lo));
        __m256i d_hi =
            _mm256_add_epi32(_mm256_madd_epi16(rg_hi, rg_hi), _mm256_madd_epi16(b_hi, b_hi));
        __m256i tag = _mm256_set1_epi32(k == 3 && !four ? INT32_MAX : k);
        m_lo = _mm256_min_epi32(m_lo, _mm256_or_si256(_mm256_slli_epi32(d_lo, 2), tag));
        m_hi = _mm256_min_epi32(m_hi, _mm256_or_si256(_mm256_slli_epi32(d_hi, 2), tag));
    }
    __m256i d_lo = _mm256_srli_epi32(m_lo, 2), d_hi = _mm256_srli_epi32(m_hi, 2);
    __m128i s;
    if (t->uniform) {
        __m256i c_lo = _mm256_setr_m128i(_mm_load_si128((const __m128i *)&t->count[0]),
                                         _mm_load_si128((const __m128i *)&t->count[8]));
        __m256i c_hi = _mm256_setr_m128i(_mm_load_si128((const __m128i *)&t->count[4]),
                                         _mm_load_si128((const __m128i *)&t->count[12]));
        __m256i e = _mm256_add_epi32(_mm256_and_si256(d_lo, c_lo), _mm256_and_si256(d_hi, c_hi));
        s = _mm_add_epi32(_mm256_castsi256_si128(e), _mm256_extracti128_si256(e, 1));
        s = _mm_add_epi32(s, _mm_shuffle_epi32(s, _MM_SHUFFLE(1, 0, 3, 2)));
        s = _mm_add_epi32(s, _mm_shuffle_epi32(s, _MM_SHUFFLE(2, 3, 0, 1)));
    } else { /* distance (< 2^18) times weight (<= 256) */
        __m256i w_lo = _mm256_setr_m128i(_mm_load_si128((const __m128i *)&t->weight32[0]),
                                         _mm_load_si128((const __m128i *)&t->weight32[8]));
        __m256i w_hi = _mm256_setr_m128i(_mm_load_si128((const __m128i *)&t->weight32[4]),
                                         _mm_load_si128((const __m128i *)&t->weight32[12]));
        __m256i e =
            _mm256_add_epi32(_mm256_mullo_epi32(d_lo, w_lo), _mm256_mullo_epi32(d_hi, w_hi));
        s = _mm_add_epi32(_mm256_castsi256_si128(e), _mm256_extracti128_si256(e, 1));
        s = _mm_add_epi32(s, _mm_shuffle_epi32(s, _MM_SHUFFLE(1, 0, 3, 2)));
        s = _mm_add_epi32(s, _mm_shuffle_epi32(s, _MM_SHUFFLE(2, 3, 0, 1)));
    }
    uint32_t error = (uint32_t)_mm_cvtsi128_si32(s); /* the block's total is < 2^32 */
    if (error >= bound)
        return UINT32_MAX;
    const __m256i three = _mm256_set1_epi32(3);
    __m256i i16 = _mm256_packs_epi32(_mm256_and_si256(m_lo, three), _mm256_and_si256(m_hi, three));
    __m128i bytes = _mm_packus_epi16(_mm256_castsi256_si128(i16), _mm256_extracti128_si256(i16, 1));
    *indices = bc_fold_indices(bytes) | t->force;
    return error;
}

#endif

/* Evaluates (c0, c1) in the 3-colour mode (three) or the 4-colour mode, ordering the pair as that
 * mode needs; *cand takes it when its error is smaller. Returns true when it did. A quarter of the
 * pairs a block tries were tried before (starts converging, the search stepping back): the memo
 * of the block answers them with the same result an evaluation would give. */
static bool bc_colour_try(struct bc_colour_texels *t, unsigned c0, unsigned c1, bool three,
                          struct bc_colour_candidate *cand)
{
    if (three ? c0 > c1 : c0 < c1) {
        unsigned s = c0;
        c0 = c1;
        c1 = s;
    }
    uint32_t key = c0 << 16 | c1, idx, error;
    struct bc_memo *m = NULL;
    unsigned h = (key * 0x9e3779b1u) >> (32 - BC_MEMO_BITS); /* open addressing */
    while (t->memo_used >> h & 1) {
        if (t->memo[h].key == key) {
            m = &t->memo[h];
            break;
        }
        h = (h + 1) & (BC_MEMO - 1);
    }
    if (m && m->exact) {
        error = m->error;
        idx = m->indices;
    } else if (m && cand->error <= m->error) {
        return false; /* its error is at least m->error */
    } else {
#if defined(VT_BC_ENCODE_AVX2)
        error = bc_use_avx2 ? bc_colour_eval_avx2(t, c0, c1, cand->error, &idx)
                            : bc_colour_eval(t, c0, c1, cand->error, &idx);
#else
        error = bc_colour_eval(t, c0, c1, cand->error, &idx);
#endif
        if (!m && t->memo_len < BC_MEMO / 2) { /* at most half full: short probes */
            m = &t->memo[h];
            t->memo_used |= (uint64_t)1 << h;
            t->memo_len++;
        }
        if (m)
            *m = error == UINT32_MAX ? (struct bc_memo){key, cand->error, 0, false}
                                     : (struct bc_memo){key, error, idx, true};
    }
    if (error >= cand->error)
        return false;
    *cand = (struct bc_colour_candidate){c0, c1, idx, error};
    return true;
}

static bool bc_colour_is_three(const struct bc_colour_texels *t,
                               const struct bc_colour_candidate *c)
{
    return !t->four_only && c->c0 <= c->c1;
}

static int bc_round_clamp(double v)
{
    if (!(v > 0))
        return 0;
    if (v >= 255)
        return 255;
    return (int)(v + 0.5);
}

static unsigned bc_pack565(const double e[3])
{
    return (unsigned)bc_quant5[bc_round_clamp(e[0])] << 11 |
           (unsigned)bc_quant6[bc_round_clamp(e[1])] << 5 | bc_quant5[bc_round_clamp(e[2])];
}

/* Least-squares endpoints for the index weights of cand (4-colour: 1, 0, 2/3, 1/3 of c0;
 * 3-colour: 1, 0, 1/2), quantised. With a_i the weight of c0 in texel i's palette entry (times
 * scale) and b_i = scale - a_i, the normal equations need only sums over a_i (sum a, a^2, a x)
 * and the block's moments (t->wsum, t->wx): all integer. False when the system is singular
 * (one index for all). */
static bool bc_colour_solve(const struct bc_colour_texels *t, const struct bc_colour_candidate *c,
                            bool three, unsigned *c0, unsigned *c1)
{
    const int64_t scale = three ? 2 : 3;
    int32_t sa = 0, saa = 0, sax[3] = {0, 0, 0};
#if defined(VT_BC_ENCODE_SSE2)
    {
        /* the 16 indices into 16-bit lanes (lane i: bits 2i..2i+1 moved to the top), then a_i */
        const __m128i up =
            _mm_setr_epi16(1 << 14, 1 << 12, 1 << 10, 1 << 8, 1 << 6, 1 << 4, 1 << 2, 1);
        const __m128i zero = _mm_setzero_si128(), ones = _mm_set1_epi16(1);
        __m128i acc_a = zero, acc_aa = zero, acc_r = zero, acc_g = zero, acc_b = zero;
        for (int half = 0; half < 2; half++) {
            __m128i k = _mm_set1_epi16((int16_t)(c->indices >> (16 * half) & 0xffff));
            k = _mm_srli_epi16(_mm_mullo_epi16(k, up), 14);
            __m128i is0 = _mm_cmpeq_epi16(k, zero), is2 = _mm_cmpeq_epi16(k, _mm_set1_epi16(2));
            __m128i a;
            if (three) {
                a = _mm_or_si128(_mm_and_si128(is0, _mm_set1_epi16(2)), _mm_and_si128(is2, ones));
            } else {
                __m128i is3 = _mm_cmpeq_epi16(k, _mm_set1_epi16(3));
                a = _mm_or_si128(_mm_or_si128(_mm_and_si128(is0, _mm_set1_epi16(3)),
                                              _mm_and_si128(is2, _mm_set1_epi16(2))),
                                 _mm_and_si128(is3, ones));
            }
            /* aw = a times the weight (uniform: 1, or 0 for a transparent texel; < 2^10) */
            __m128i w = _mm_load_si128((const __m128i *)&t->weight[8 * half]);
            __m128i aw =
                t->uniform ? _mm_andnot_si128(_mm_cmpeq_epi16(w, zero), a) : _mm_mullo_epi16(a, w);
            acc_a = _mm_add_epi32(acc_a, _mm_madd_epi16(aw, ones));
            acc_aa = _mm_add_epi32(acc_aa, _mm_madd_epi16(aw, a));
            acc_r = _mm_add_epi32(
                acc_r, _mm_madd_epi16(aw, _mm_load_si128((const __m128i *)&t->plane[0][8 * half])));
            acc_g = _mm_add_epi32(
                acc_g, _mm_madd_epi16(aw, _mm_load_si128((const __m128i *)&t->plane[1][8 * half])));
            acc_b = _mm_add_epi32(
                acc_b, _mm_madd_epi16(aw, _mm_load_si128((const __m128i *)&t->plane[2][8 * half])));
        }
        /* transpose-add: lane j of sum0 = the total of vector j */
        __m128i t0 =
            _mm_add_epi32(_mm_unpacklo_epi32(acc_a, acc_aa), _mm_unpackhi_epi32(acc_a, acc_aa));
        __m128i t1 =
            _mm_add_epi32(_mm_unpacklo_epi32(acc_r, acc_g), _mm_unpackhi_epi32(acc_r, acc_g));
        __m128i sum0 = _mm_add_epi32(_mm_unpacklo_epi64(t0, t1), _mm_unpackhi_epi64(t0, t1));
        __m128i sb = _mm_add_epi32(acc_b, _mm_shuffle_epi32(acc_b, _MM_SHUFFLE(1, 0, 3, 2)));
        sb = _mm_add_epi32(sb, _mm_shuffle_epi32(sb, _MM_SHUFFLE(2, 3, 0, 1)));
        _Alignas(16) int32_t sums[4];
        _mm_store_si128((__m128i *)sums, sum0);
        sa = sums[0];
        saa = sums[1];
        sax[0] = sums[2];
        sax[1] = sums[3];
        sax[2] = _mm_cvtsi128_si32(sb);
    }
#else
    {
        static const int weight4[4] = {3, 0, 2, 1}, weight3[4] = {2, 0, 1, 0};
        for (int i = 0; i < BC_TEXELS; i++) {
            unsigned k = c->indices >> (2 * i) & 3;
            int32_t w = t->uniform ? t->weight[i] != 0 : t->weight[i];
            int32_t a = (three ? weight3[k] : weight4[k]) * w;
            sa += a;
            saa += a * (three ? weight3[k] : weight4[k]);
            for (int ch = 0; ch < 3; ch++)
                sax[ch] += a * t->plane[ch][i];
        }
    }
#endif
    int64_t aa = saa, ab = scale * sa - saa, bb = scale * scale * t->wsum - 2 * scale * sa + saa;
    int64_t det = aa * bb - ab * ab;
    if (det == 0)
        return false;
    double e0[3], e1[3];
    for (int ch = 0; ch < 3; ch++) {
        int64_t ax = sax[ch], bx = scale * t->wx[ch] - sax[ch];
        e0[ch] = (double)(scale * (bb * ax - ab * bx)) / (double)det;
        e1[ch] = (double)(scale * (aa * bx - ab * ax)) / (double)det;
    }
    *c0 = bc_pack565(e0);
    *c1 = bc_pack565(e1);
    return true;
}

/* From (c0, c1): least-squares rounds while the error falls; the result goes into *best. */
static void bc_colour_refine(struct bc_colour_texels *t, unsigned c0, unsigned c1, bool three,
                             int rounds, struct bc_colour_candidate *best)
{
    struct bc_colour_candidate chain = {0, 0, 0, UINT32_MAX};
    bc_colour_try(t, c0, c1, three, &chain);
    for (int r = 0; r < rounds && chain.error > 0; r++) {
        unsigned n0, n1;
        if (!bc_colour_solve(t, &chain, three, &n0, &n1))
            break;
        if ((n0 == chain.c0 && n1 == chain.c1) || (n0 == chain.c1 && n1 == chain.c0))
            break; /* a fixed point */
        if (!bc_colour_try(t, n0, n1, three, &chain))
            break;
    }
    if (chain.error < best->error)
        *best = chain;
}

/* +-1 on each 565 component of the best pair, in its mode, while the error falls. */
static void bc_colour_search(struct bc_colour_texels *t, struct bc_colour_candidate *best)
{
    static const unsigned shift[3] = {11, 5, 0}, mask[3] = {31, 63, 31};
    bool three = bc_colour_is_three(t, best);
    for (int pass = 0; pass < BC_SEARCH_PASSES && best->error > 0; pass++) {
        bool improved = false;
        for (int e = 0; e < 2; e++) {
            for (int ch = 0; ch < 3; ch++) {
                for (int d = -1; d <= 1; d += 2) {
                    unsigned c = e ? best->c1 : best->c0;
                    int v = (int)(c >> shift[ch] & mask[ch]) + d;
                    if (v < 0 || v > (int)mask[ch])
                        continue;
                    c = (c & ~(mask[ch] << shift[ch])) | (unsigned)v << shift[ch];
                    improved |= e ? bc_colour_try(t, best->c0, c, three, best)
                                  : bc_colour_try(t, c, best->c1, three, best);
                }
            }
        }
        if (!improved)
            break;
    }
}

/* Principal axis of the opaque texels: the start endpoints at the extreme projections, moved in by
 * inset (a fraction of the range). */
struct bc_axis {
    double mean[3], dir[3]; /* endpoint = mean + dir * t */
    double tmin, tmax;
    double proj[BC_TEXELS]; /* the texels' projections (t of the texel, plus tmin) */
};

/* The block's integer moments: weights <= 256, so every sum < 2^31. */
struct bc_moments {
    int32_t sw, s[3], rr, rg, rb, gg, gb, bb;
};

static void bc_colour_moments(const struct bc_colour_texels *t, struct bc_moments *m)
{
    *m = (struct bc_moments){0};
    for (int i = 0; i < BC_TEXELS; i++) {
        int32_t w = t->uniform ? t->weight[i] != 0 : t->weight[i];
        int32_t r = t->plane[0][i], g = t->plane[1][i], b = t->plane[2][i];
        m->sw += w;
        m->s[0] += w * r;
        m->s[1] += w * g;
        m->s[2] += w * b;
        m->rr += w * r * r;
        m->rg += w * r * g;
        m->rb += w * r * b;
        m->gg += w * g * g;
        m->gb += w * g * b;
        m->bb += w * b * b;
    }
}

static void bc_colour_axis(struct bc_colour_texels *t, const struct bc_moments *m, int iterations,
                           struct bc_axis *ax)
{
    /* the covariance times sw^2, exactly */
    const int32_t sw = m->sw, *s = m->s, rr = m->rr, rg = m->rg, rb = m->rb, gg = m->gg, gb = m->gb,
                  bb = m->bb;
    t->wsum = sw;
    memcpy(t->wx, s, sizeof t->wx);
    double c00 = (double)((int64_t)sw * rr - (int64_t)s[0] * s[0]),
           c01 = (double)((int64_t)sw * rg - (int64_t)s[0] * s[1]),
           c02 = (double)((int64_t)sw * rb - (int64_t)s[0] * s[2]),
           c11 = (double)((int64_t)sw * gg - (int64_t)s[1] * s[1]),
           c12 = (double)((int64_t)sw * gb - (int64_t)s[1] * s[2]),
           c22 = (double)((int64_t)sw * bb - (int64_t)s[2] * s[2]);
    /* power iteration on C / trace(C) (the eigenvalues in (0, 1]: no renormalising in the
     * loop), from the column of the largest variance: C times it is never zero */
    double scale = 1 / (c00 + c11 + c22);
    c00 *= scale;
    c01 *= scale;
    c02 *= scale;
    c11 *= scale;
    c12 *= scale;
    c22 *= scale;
    double v0 = c00, v1 = c01, v2 = c02;
    if (c11 > c00 && c11 >= c22)
        v0 = c01, v1 = c11, v2 = c12;
    else if (c22 > c00 && c22 > c11)
        v0 = c02, v1 = c12, v2 = c22;
    for (int it = 0; it < iterations; it++) {
        double n0 = c00 * v0 + c01 * v1 + c02 * v2, n1 = c01 * v0 + c11 * v1 + c12 * v2,
               n2 = c02 * v0 + c12 * v1 + c22 * v2;
        v0 = n0;
        v1 = n1;
        v2 = n2;
    }
    double vv = v0 * v0 + v1 * v1 + v2 * v2;
    if (!(vv > 0)) {
        v0 = v1 = v2 = 1;
        vv = 3;
    }
    /* the projections in float (4 lanes; the portable loop does the same float operations in
     * the same order) */
    float f0 = (float)v0, f1 = (float)v1, f2 = (float)v2;
    _Alignas(16) float proj[BC_TEXELS];
#if defined(VT_BC_ENCODE_SSE2)
    const __m128i zero = _mm_setzero_si128();
    const __m128 w0 = _mm_set1_ps(f0), w1 = _mm_set1_ps(f1), w2 = _mm_set1_ps(f2);
    for (int half = 0; half < 2; half++) {
        __m128i r = _mm_load_si128((const __m128i *)&t->plane[0][8 * half]);
        __m128i g = _mm_load_si128((const __m128i *)&t->plane[1][8 * half]);
        __m128i b = _mm_load_si128((const __m128i *)&t->plane[2][8 * half]);
        for (int q = 0; q < 2; q++) {
            __m128i r32 = q ? _mm_unpackhi_epi16(r, zero) : _mm_unpacklo_epi16(r, zero);
            __m128i g32 = q ? _mm_unpackhi_epi16(g, zero) : _mm_unpacklo_epi16(g, zero);
            __m128i b32 = q ? _mm_unpackhi_epi16(b, zero) : _mm_unpacklo_epi16(b, zero);
            __m128 p = _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_cvtepi32_ps(r32), w0),
                                             _mm_mul_ps(_mm_cvtepi32_ps(g32), w1)),
                                  _mm_mul_ps(_mm_cvtepi32_ps(b32), w2));
            _mm_store_ps(&proj[8 * half + 4 * q], p);
        }
    }
#else
    for (int i = 0; i < BC_TEXELS; i++)
        proj[i] =
            ((float)t->plane[0][i] * f0 + (float)t->plane[1][i] * f1) + (float)t->plane[2][i] * f2;
#endif
    float tmin = 1e30f, tmax = -1e30f;
    for (int i = 0; i < BC_TEXELS; i++) {
        if (t->weight[i] == 0)
            continue;
        tmin = proj[i] < tmin ? proj[i] : tmin;
        tmax = proj[i] > tmax ? proj[i] : tmax;
    }
    v0 = f0;
    v1 = f1;
    v2 = f2;
    vv = v0 * v0 + v1 * v1 + v2 * v2;
    double inv_sw = 1.0 / sw;
    ax->mean[0] = s[0] * inv_sw;
    ax->mean[1] = s[1] * inv_sw;
    ax->mean[2] = s[2] * inv_sw;
    double pm = ax->mean[0] * v0 + ax->mean[1] * v1 + ax->mean[2] * v2;
    for (int i = 0; i < BC_TEXELS; i++)
        ax->proj[i] = (double)proj[i] - tmin;
    ax->tmin = tmin - pm;
    ax->tmax = tmax - pm;
    ax->dir[0] = v0 / vv;
    ax->dir[1] = v1 / vv;
    ax->dir[2] = v2 / vv;
}

static void bc_axis_endpoints(const struct bc_axis *ax, double inset, unsigned *c0, unsigned *c1)
{
    double range = ax->tmax - ax->tmin, hi = ax->tmax - range * inset,
           lo = ax->tmin + range * inset;
    double e0[3], e1[3];
    for (int ch = 0; ch < 3; ch++) {
        e0[ch] = ax->mean[ch] + ax->dir[ch] * hi;
        e1[ch] = ax->mean[ch] + ax->dir[ch] * lo;
    }
    *c0 = bc_pack565(e0);
    *c1 = bc_pack565(e1);
}

/* A 4-colour start from indices: the texels in three bins along the axis, put on three evenly
 * spaced palette entries (the top three: c0, c2, c3, or the bottom three: c2, c3, c1), the
 * endpoints solved for those and refined. The blocks of three clusters where one endpoint must
 * lie outside the texels, which starts between the extremes do not find. */
static void bc_colour_bins(struct bc_colour_texels *t, const struct bc_axis *ax, bool top,
                           struct bc_colour_candidate *best)
{
    static const unsigned index_top[3] = {3, 2, 0}, index_bottom[3] = {1, 3, 2};
    double range = ax->tmax - ax->tmin;
    struct bc_colour_candidate start = {0, 0, 0, UINT32_MAX};
    for (int i = 0; i < BC_TEXELS; i++) {
        int bin = (int)(ax->proj[i] * 2 / range + 0.5);
        bin = bin < 0 ? 0 : bin > 2 ? 2 : bin;
        start.indices |= (top ? index_top[bin] : index_bottom[bin]) << (2 * i);
    }
    unsigned c0, c1;
    if (bc_colour_solve(t, &start, false, &c0, &c1))
        bc_colour_refine(t, c0, c1, false, BC_REFINE_BEST, best);
}

/* A block whose opaque texels are one colour: the per-channel table pairs. */
static void bc_colour_single(struct bc_colour_texels *t, const int rgb[3], bool may_four,
                             bool may_three, struct bc_colour_candidate *best)
{
    static const int table_of_channel[3] = {0, 1, 0};
    static const unsigned shift[3] = {11, 5, 0};
    if (may_four) {
        unsigned c0 = 0, c1 = 0;
        for (int ch = 0; ch < 3; ch++) {
            struct bc_pair p = bc_single4[table_of_channel[ch]][rgb[ch]];
            c0 |= (unsigned)p.q0 << shift[ch];
            c1 |= (unsigned)p.q1 << shift[ch];
        }
        bc_colour_try(t, c0, c1, false, best);
    }
    if (may_three) {
        unsigned c0 = 0, c1 = 0;
        for (int ch = 0; ch < 3; ch++) {
            struct bc_pair p = bc_single3[table_of_channel[ch]][rgb[ch]];
            c0 |= (unsigned)p.q0 << shift[ch];
            c1 |= (unsigned)p.q1 << shift[ch];
        }
        bc_colour_try(t, c0, c1, true, best);
    }
}

static void bc_put_colour(const struct bc_colour_candidate *c, unsigned char *dst)
{
    dst[0] = (unsigned char)(c->c0 & 255);
    dst[1] = (unsigned char)(c->c0 >> 8);
    dst[2] = (unsigned char)(c->c1 & 255);
    dst[3] = (unsigned char)(c->c1 >> 8);
    for (int b = 0; b < 4; b++)
        dst[4 + b] = (unsigned char)(c->indices >> (8 * b));
}

/* The texels into t, the scalar way (any alpha, any weights); *single when every counted texel
 * has one colour (rgb). */
static void bc_colour_setup(const unsigned char *rgba, unsigned flags, struct bc_colour_texels *t,
                            bool *single, int rgb[3])
{
    t->four_only = (flags & VT_BC_ENCODE_FOUR_COLOUR_ONLY) != 0;
    t->memo_len = 0;
    t->memo_used = 0;
    t->transparent = 0;
    t->force = 0;
    bool by_alpha = (flags & VT_BC_ENCODE_WEIGHT_BY_ALPHA) != 0;
    unsigned any = 0, all = 255, lo[3] = {255, 255, 255}, hi[3] = {0, 0, 0};
    for (int i = 0; i < BC_TEXELS; i++) {
        const unsigned char *x = rgba + 4 * i;
        unsigned a = x[3];
        for (int ch = 0; ch < 3; ch++)
            t->plane[ch][i] = x[ch];
        t->weight[i] = (uint16_t)(by_alpha ? a + 1 : 1);
        t->weight32[i] = t->weight[i];
        t->count[i] = ~0u;
        any |= a;
        all &= a;
        if (!t->four_only && a < BC_ALPHA_OPAQUE) {
            t->transparent |= 1u << i;
            t->force |= 3u << (2 * i);
            t->weight[i] = 0;
            t->weight32[i] = 0;
            t->count[i] = 0;
            continue;
        }
        for (int ch = 0; ch < 3; ch++) {
            lo[ch] = x[ch] < lo[ch] ? x[ch] : lo[ch];
            hi[ch] = x[ch] > hi[ch] ? x[ch] : hi[ch];
        }
    }
    /* uniform: every weight 0 or the same (not by alpha, or one alpha value for all) */
    t->uniform = !by_alpha || any == all;
    *single = lo[0] == hi[0] && lo[1] == hi[1] && lo[2] == hi[2];
    for (int ch = 0; ch < 3; ch++)
        rgb[ch] = (int)lo[ch];
}

#if defined(VT_BC_ENCODE_SSE2)
/* The common block in SSE2: every texel counted with one weight (BC3's colour, or BC1 with no
 * alpha below 128; not by alpha, or one alpha for all). False (t untouched) for any other block.
 * Fills t, the moments and *single / rgb as bc_colour_setup and bc_colour_moments would (the
 * weights all 1: uniform). */
static bool bc_colour_setup_sse2(const unsigned char *rgba, unsigned flags,
                                 struct bc_colour_texels *t, struct bc_moments *m, bool *single,
                                 int rgb[3])
{
    __m128i v0 = _mm_loadu_si128((const __m128i *)rgba),
            v1 = _mm_loadu_si128((const __m128i *)(rgba + 16)),
            v2 = _mm_loadu_si128((const __m128i *)(rgba + 32)),
            v3 = _mm_loadu_si128((const __m128i *)(rgba + 48));
    /* transpose into R, G, B, A planes of 16 bytes */
    __m128i t0 = _mm_unpacklo_epi8(v0, v1), t1 = _mm_unpackhi_epi8(v0, v1);
    __m128i t2 = _mm_unpacklo_epi8(v2, v3), t3 = _mm_unpackhi_epi8(v2, v3);
    __m128i u0 = _mm_unpacklo_epi8(t0, t1), u1 = _mm_unpackhi_epi8(t0, t1);
    __m128i u2 = _mm_unpacklo_epi8(t2, t3), u3 = _mm_unpackhi_epi8(t2, t3);
    __m128i w0 = _mm_unpacklo_epi8(u0, u1), w1 = _mm_unpackhi_epi8(u0, u1); /* RG, BA 0..7 */
    __m128i w2 = _mm_unpacklo_epi8(u2, u3), w3 = _mm_unpackhi_epi8(u2, u3); /* 8..15 */
    __m128i r = _mm_unpacklo_epi64(w0, w2), g = _mm_unpackhi_epi64(w0, w2);
    __m128i b = _mm_unpacklo_epi64(w1, w3), a = _mm_unpackhi_epi64(w1, w3);
    bool four_only = (flags & VT_BC_ENCODE_FOUR_COLOUR_ONLY) != 0;
    if (!four_only && _mm_movemask_epi8(a) != 0xffff)
        return false; /* an alpha below 128 */
    if ((flags & VT_BC_ENCODE_WEIGHT_BY_ALPHA) &&
        _mm_movemask_epi8(_mm_cmpeq_epi8(a, _mm_set1_epi8((char)rgba[3]))) != 0xffff)
        return false; /* weights differ */
    t->four_only = four_only;
    t->memo_len = 0;
    t->memo_used = 0;
    t->transparent = 0;
    t->force = 0;
    t->uniform = true;
    const __m128i zero = _mm_setzero_si128();
    __m128i same = _mm_and_si128(_mm_cmpeq_epi8(r, _mm_set1_epi8((char)rgba[0])),
                                 _mm_cmpeq_epi8(g, _mm_set1_epi8((char)rgba[1])));
    same = _mm_and_si128(same, _mm_cmpeq_epi8(b, _mm_set1_epi8((char)rgba[2])));
    *single = _mm_movemask_epi8(same) == 0xffff;
    rgb[0] = rgba[0];
    rgb[1] = rgba[1];
    rgb[2] = rgba[2];
    __m128i r0 = _mm_unpacklo_epi8(r, zero), r1 = _mm_unpackhi_epi8(r, zero);
    __m128i g0 = _mm_unpacklo_epi8(g, zero), g1 = _mm_unpackhi_epi8(g, zero);
    __m128i b0 = _mm_unpacklo_epi8(b, zero), b1 = _mm_unpackhi_epi8(b, zero);
    _mm_store_si128((__m128i *)&t->plane[0][0], r0);
    _mm_store_si128((__m128i *)&t->plane[0][8], r1);
    _mm_store_si128((__m128i *)&t->plane[1][0], g0);
    _mm_store_si128((__m128i *)&t->plane[1][8], g1);
    _mm_store_si128((__m128i *)&t->plane[2][0], b0);
    _mm_store_si128((__m128i *)&t->plane[2][8], b1);
    const __m128i one16 = _mm_set1_epi16(1);
    _mm_store_si128((__m128i *)&t->weight[0], one16);
    _mm_store_si128((__m128i *)&t->weight[8], one16);
    const __m128i all = _mm_set1_epi32(-1);
    for (int q = 0; q < 4; q++)
        _mm_store_si128((__m128i *)&t->count[4 * q], all);
    if (*single)
        return true;
    /* moments: sums of bytes (sad), products (madd), all 16 texels of weight 1 */
    __m128i sr = _mm_sad_epu8(r, zero), sg = _mm_sad_epu8(g, zero), sb = _mm_sad_epu8(b, zero);
    __m128i prr = _mm_add_epi32(_mm_madd_epi16(r0, r0), _mm_madd_epi16(r1, r1));
    __m128i prg = _mm_add_epi32(_mm_madd_epi16(r0, g0), _mm_madd_epi16(r1, g1));
    __m128i prb = _mm_add_epi32(_mm_madd_epi16(r0, b0), _mm_madd_epi16(r1, b1));
    __m128i pgg = _mm_add_epi32(_mm_madd_epi16(g0, g0), _mm_madd_epi16(g1, g1));
    __m128i pgb = _mm_add_epi32(_mm_madd_epi16(g0, b0), _mm_madd_epi16(g1, b1));
    __m128i pbb = _mm_add_epi32(_mm_madd_epi16(b0, b0), _mm_madd_epi16(b1, b1));
    /* transpose-add: lane j of x = the total of the j-th vector */
    __m128i x0 = _mm_add_epi32(_mm_unpacklo_epi32(prr, prg), _mm_unpackhi_epi32(prr, prg));
    __m128i x1 = _mm_add_epi32(_mm_unpacklo_epi32(prb, pgg), _mm_unpackhi_epi32(prb, pgg));
    __m128i x = _mm_add_epi32(_mm_unpacklo_epi64(x0, x1), _mm_unpackhi_epi64(x0, x1));
    __m128i y = _mm_add_epi32(_mm_unpacklo_epi32(pgb, pbb), _mm_unpackhi_epi32(pgb, pbb));
    y = _mm_add_epi32(y, _mm_unpackhi_epi64(y, y));
    _Alignas(16) int32_t p[8];
    _mm_store_si128((__m128i *)p, x);
    _mm_store_si128((__m128i *)(p + 4), y);
    m->sw = BC_TEXELS;
    m->s[0] = _mm_cvtsi128_si32(sr) + _mm_cvtsi128_si32(_mm_unpackhi_epi64(sr, sr));
    m->s[1] = _mm_cvtsi128_si32(sg) + _mm_cvtsi128_si32(_mm_unpackhi_epi64(sg, sg));
    m->s[2] = _mm_cvtsi128_si32(sb) + _mm_cvtsi128_si32(_mm_unpackhi_epi64(sb, sb));
    m->rr = p[0];
    m->rg = p[1];
    m->rb = p[2];
    m->gg = p[3];
    m->gb = p[4];
    m->bb = p[5];
    return true;
}
#endif

void vt_bc_encode_colour_block(const unsigned char *rgba, unsigned flags, unsigned char *dst)
{
    pthread_once(&bc_tables_once, bc_tables_init);
    struct bc_colour_texels t;
    struct bc_moments mom = {0};
    bool single;
    int rgb[3];
#if defined(VT_BC_ENCODE_SSE2)
    if (!bc_colour_setup_sse2(rgba, flags, &t, &mom, &single, rgb))
#endif
    {
        bc_colour_setup(rgba, flags, &t, &single, rgb);
        if (!single)
            bc_colour_moments(&t, &mom);
    }
    struct bc_colour_candidate best = {0, 0, 0xffffffffu, UINT32_MAX};
    if (t.transparent == 0xffffu) { /* every texel transparent */
        best.error = 0;
        bc_put_colour(&best, dst);
        return;
    }
    bool is_best = (flags & VT_BC_ENCODE_BEST) != 0;
    bool may_four = t.transparent == 0, may_three = !t.four_only;
    if (single) {
        bc_colour_single(&t, rgb, may_four, may_three, &best);
        bc_put_colour(&best, dst);
        return;
    }
    struct bc_axis ax;
    bc_colour_axis(&t, &mom, is_best ? BC_POWER_BEST : BC_POWER_FAST, &ax);
    unsigned c0, c1;
    if (!is_best) {
        t.memo_len = BC_MEMO / 2; /* two pairs: no memo (a full one is never written) */
        bc_axis_endpoints(&ax, 1.0 / 16, &c0, &c1);
        bc_colour_refine(&t, c0, c1, !may_four, 1, &best);
        bc_put_colour(&best, dst);
        return;
    }
    /* the refinement has local minima: several starts along the axis, each refined a little */
    static const double insets[] = {0, 1.0 / 16, 1.0 / 8, 1.0 / 4};
    for (int mode = 0; mode < 2; mode++) {
        bool three = mode == 1;
        if (three ? !may_three : !may_four)
            continue;
        /* the 3-colour mode wins on few blocks of a photo: two starts */
        size_t starts = three ? 2 : 4;
        for (size_t s = 0; s < starts; s++) {
            bc_axis_endpoints(&ax, insets[s], &c0, &c1);
            bc_colour_refine(&t, c0, c1, three, BC_REFINE_BEST, &best);
        }
        if (!three) {
            bc_colour_bins(&t, &ax, true, &best);
            bc_colour_bins(&t, &ax, false, &best);
        }
    }
    bc_colour_search(&t, &best);
    unsigned n0, n1;
    bool three = bc_colour_is_three(&t, &best);
    if (best.error > 0 && bc_colour_solve(&t, &best, three, &n0, &n1) &&
        bc_colour_try(&t, n0, n1, three, &best))
        bc_colour_search(&t, &best);
    bc_put_colour(&best, dst);
}
