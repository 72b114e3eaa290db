/* Our BC1/BC3 block encoder (the format: docs/codecs.md and vt_codec_bc.c's decoder formulas).
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
 *   4. best: the same from the un-inset extremes, the 3-colour mode as well (BC1), then a search
 *      of +-1 on each of the six 565 components around the best pair, kept while it improves,
 *      and a last least-squares step.
 * Error: the sum over texels of the squared RGB distance to the decoded palette colour (integer,
 * uniform weights as PSNR counts; times alpha + 1 with VT_BC_ENCODE_WEIGHT_BY_ALPHA). BC1
 * texels with alpha < 128 take index 3 of the 3-colour mode (transparent black) and count nothing.
 *
 * Alpha (BC3): the 8-value mode between max and min; best refines it (least squares, +-1 search)
 * and tries the 6-value mode (explicit 0 and 255) between the min and max of the other values.
 *
 * Determinism: the error and every choice between candidates are integer; the float steps (axis,
 * least-squares division) are plain double arithmetic in a fixed order, compiled with
 * -ffp-contract=off (CMakeLists.txt) so that no platform fuses them differently. */
#include <pthread.h>
#include <stdbool.h>
#include <stdint.h>
#include <string.h>

#include "internal/vt_bc_encode.h"

#if defined(__SSE2__) && !defined(VT_BC_ENCODE_PORTABLE)
#define VT_BC_ENCODE_SSE2 1
#include <emmintrin.h>
#endif

#define BC_TEXELS        16
#define BC_ALPHA_OPAQUE  128 /* BC1: alpha below this is stored as transparent */
#define BC_POWER_FAST    4   /* power iterations for the principal axis */
#define BC_POWER_BEST    8
#define BC_REFINE_BEST   4 /* least-squares rounds per start (fast: 1) */
#define BC_SEARCH_PASSES 8 /* +-1 endpoint search passes at most (best) */
#define BC_ALPHA_REFINE  4
#define BC_ALPHA_SEARCH  8

/* ---- tables, built once ---- */

struct bc_pair {
    uint8_t q0, q1; /* endpoint values of one channel, 5 or 6 bits */
};

static uint8_t bc_quant5[256], bc_quant6[256]; /* 8-bit value -> nearest 5/6-bit value */
static struct bc_pair bc_single4[2][256];      /* [0]: 5 bits, [1]: 6 bits; 4-colour, index 2 */
static struct bc_pair bc_single3[2][256];      /* 3-colour mode, index 2 (the half) */
static pthread_once_t bc_tables_once = PTHREAD_ONCE_INIT;

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

struct bc_colour_texels {
    int rgb[BC_TEXELS][3];
    uint32_t weight[BC_TEXELS];
    /* the same, laid out for the error loop: channel planes, weight 0 and index 3 forced for
     * transparent texels */
    _Alignas(16) int16_t plane[3][BC_TEXELS];
    uint32_t eval_weight[BC_TEXELS], eval_force[BC_TEXELS];
    uint32_t transparent; /* bit i: texel i is stored as transparent (index 3, 3-colour mode) */
    bool four_only;
};

struct bc_colour_candidate {
    unsigned c0, c1; /* RGB565 as stored */
    uint32_t indices;
    uint64_t error;
};

static void bc_unpack565(unsigned c, int rgb[3])
{
    rgb[0] = bc_expand(c >> 11, 5);
    rgb[1] = bc_expand((c >> 5) & 63, 6);
    rgb[2] = bc_expand(c & 31, 5);
}

/* The error of endpoints (c0, c1) as stored (their order picks the mode), with the nearest
 * palette index of every texel in *indices; UINT64_MAX as soon as it reaches bound. */
static uint64_t bc_colour_eval(const struct bc_colour_texels *t, unsigned c0, unsigned c1,
                               uint64_t bound, uint32_t *indices)
{
    int pal[4][3];
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
    /* the 3-colour mode has no fourth colour for an opaque texel: key INT32_MAX never wins */
    _Alignas(16) uint32_t key[BC_TEXELS];
    /* key = distance << 2 | index: one branch-free minimum gives both. Integer only: the SSE2
     * path and the portable one give the same keys. */
#if defined(VT_BC_ENCODE_SSE2)
    const __m128i zero = _mm_setzero_si128();
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
        _mm_store_si128((__m128i *)&key[8 * half], m_lo);
        _mm_store_si128((__m128i *)&key[8 * half + 4], m_hi);
    }
#else
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
#endif
    uint32_t error = 0, idx = 0;
    for (int i = 0; i < BC_TEXELS; i++) {
        idx |= ((key[i] & 3) | t->eval_force[i]) << (2 * i);
        error += (key[i] >> 2) * t->eval_weight[i]; /* < 16 * 195075 * 256 < 2^32 */
    }
    if (error >= bound)
        return UINT64_MAX;
    *indices = idx;
    return error;
}

/* Evaluates (c0, c1) in the 3-colour mode (three) or the 4-colour mode, ordering the pair as that
 * mode needs; *cand takes it when its error is smaller. Returns true when it did. */
static bool bc_colour_try(const struct bc_colour_texels *t, unsigned c0, unsigned c1, bool three,
                          struct bc_colour_candidate *cand)
{
    if (three ? c0 > c1 : c0 < c1) {
        unsigned s = c0;
        c0 = c1;
        c1 = s;
    }
    uint32_t idx;
    uint64_t error = bc_colour_eval(t, c0, c1, cand->error, &idx);
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
 * 3-colour: 1, 0, 1/2), quantised. False when the system is singular (one index for all). */
static bool bc_colour_solve(const struct bc_colour_texels *t, const struct bc_colour_candidate *c,
                            bool three, unsigned *c0, unsigned *c1)
{
    static const int weight4[4] = {3, 0, 2, 1}, weight3[4] = {2, 0, 1, 0};
    const int scale = three ? 2 : 3;
    int64_t aa = 0, ab = 0, bb = 0, ax[3] = {0, 0, 0}, bx[3] = {0, 0, 0};
    for (int i = 0; i < BC_TEXELS; i++) {
        if (t->transparent >> i & 1)
            continue;
        unsigned k = c->indices >> (2 * i) & 3;
        int64_t a = three ? weight3[k] : weight4[k], b = scale - a, w = t->weight[i];
        aa += w * a * a;
        ab += w * a * b;
        bb += w * b * b;
        for (int ch = 0; ch < 3; ch++) {
            ax[ch] += w * a * t->rgb[i][ch];
            bx[ch] += w * b * t->rgb[i][ch];
        }
    }
    int64_t det = aa * bb - ab * ab;
    if (det == 0)
        return false;
    double e0[3], e1[3];
    for (int ch = 0; ch < 3; ch++) {
        e0[ch] = (double)(scale * (bb * ax[ch] - ab * bx[ch])) / (double)det;
        e1[ch] = (double)(scale * (aa * bx[ch] - ab * ax[ch])) / (double)det;
    }
    *c0 = bc_pack565(e0);
    *c1 = bc_pack565(e1);
    return true;
}

/* From (c0, c1): least-squares rounds while the error falls; the result goes into *best. */
static void bc_colour_refine(const struct bc_colour_texels *t, unsigned c0, unsigned c1, bool three,
                             int rounds, struct bc_colour_candidate *best)
{
    struct bc_colour_candidate chain = {0, 0, 0, UINT64_MAX};
    bc_colour_try(t, c0, c1, three, &chain);
    for (int r = 0; r < rounds && chain.error > 0; r++) {
        unsigned n0, n1;
        if (!bc_colour_solve(t, &chain, three, &n0, &n1))
            break;
        if (!bc_colour_try(t, n0, n1, three, &chain))
            break;
    }
    if (chain.error < best->error)
        *best = chain;
}

/* +-1 on each 565 component of the best pair, in its mode, while the error falls. */
static void bc_colour_search(const struct bc_colour_texels *t, struct bc_colour_candidate *best)
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
        /* both endpoints of one channel together (a shift of the line) */
        for (int ch = 0; ch < 3; ch++) {
            for (int d = -1; d <= 1; d += 2) {
                int v0 = (int)(best->c0 >> shift[ch] & mask[ch]) + d;
                int v1 = (int)(best->c1 >> shift[ch] & mask[ch]) + d;
                if (v0 < 0 || v0 > (int)mask[ch] || v1 < 0 || v1 > (int)mask[ch])
                    continue;
                unsigned n0 = (best->c0 & ~(mask[ch] << shift[ch])) | (unsigned)v0 << shift[ch];
                unsigned n1 = (best->c1 & ~(mask[ch] << shift[ch])) | (unsigned)v1 << shift[ch];
                improved |= bc_colour_try(t, n0, n1, three, best);
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
};

static void bc_colour_axis(const struct bc_colour_texels *t, int iterations, struct bc_axis *ax)
{
    double wsum = 0, m[3] = {0, 0, 0};
    for (int i = 0; i < BC_TEXELS; i++) {
        if (t->transparent >> i & 1)
            continue;
        double w = t->weight[i];
        wsum += w;
        for (int ch = 0; ch < 3; ch++)
            m[ch] += w * t->rgb[i][ch];
    }
    for (int ch = 0; ch < 3; ch++)
        m[ch] /= wsum;
    double cov[3][3] = {{0}};
    for (int i = 0; i < BC_TEXELS; i++) {
        if (t->transparent >> i & 1)
            continue;
        double w = t->weight[i], d[3];
        for (int ch = 0; ch < 3; ch++)
            d[ch] = t->rgb[i][ch] - m[ch];
        for (int r = 0; r < 3; r++)
            for (int c = r; c < 3; c++)
                cov[r][c] += w * d[r] * d[c];
    }
    cov[1][0] = cov[0][1];
    cov[2][0] = cov[0][2];
    cov[2][1] = cov[1][2];
    /* start from the column of the largest variance: C times it is never zero */
    int k = 0;
    for (int ch = 1; ch < 3; ch++)
        if (cov[ch][ch] > cov[k][k])
            k = ch;
    double v[3] = {cov[0][k], cov[1][k], cov[2][k]};
    for (int it = 0; it < iterations; it++) {
        double n[3], big = 0;
        for (int r = 0; r < 3; r++) {
            n[r] = cov[r][0] * v[0] + cov[r][1] * v[1] + cov[r][2] * v[2];
            double a = n[r] < 0 ? -n[r] : n[r];
            if (a > big)
                big = a;
        }
        if (!(big > 0))
            break;
        for (int r = 0; r < 3; r++)
            v[r] = n[r] / big;
    }
    double vv = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    if (!(vv > 0)) {
        v[0] = v[1] = v[2] = 1;
        vv = 3;
    }
    ax->tmin = 1e300;
    ax->tmax = -1e300;
    for (int i = 0; i < BC_TEXELS; i++) {
        if (t->transparent >> i & 1)
            continue;
        double p = 0;
        for (int ch = 0; ch < 3; ch++)
            p += (t->rgb[i][ch] - m[ch]) * v[ch];
        if (p < ax->tmin)
            ax->tmin = p;
        if (p > ax->tmax)
            ax->tmax = p;
    }
    for (int ch = 0; ch < 3; ch++) {
        ax->mean[ch] = m[ch];
        ax->dir[ch] = v[ch] / vv;
    }
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

/* A block whose opaque texels are one colour: the per-channel table pairs. */
static void bc_colour_single(const struct bc_colour_texels *t, const int rgb[3], bool may_four,
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

void vt_bc_encode_colour_block(const unsigned char *rgba, unsigned flags, unsigned char *dst)
{
    pthread_once(&bc_tables_once, bc_tables_init);
    struct bc_colour_texels t;
    t.four_only = (flags & VT_BC_ENCODE_FOUR_COLOUR_ONLY) != 0;
    t.transparent = 0;
    int first = -1;
    bool single = true;
    for (int i = 0; i < BC_TEXELS; i++) {
        const unsigned char *x = rgba + 4 * i;
        for (int ch = 0; ch < 3; ch++)
            t.rgb[i][ch] = x[ch];
        t.weight[i] = (flags & VT_BC_ENCODE_WEIGHT_BY_ALPHA) ? x[3] + 1u : 1u;
        for (int ch = 0; ch < 3; ch++)
            t.plane[ch][i] = x[ch];
        t.eval_weight[i] = t.weight[i];
        t.eval_force[i] = 0;
        if (!t.four_only && x[3] < BC_ALPHA_OPAQUE) {
            t.transparent |= 1u << i;
            t.eval_weight[i] = 0;
            t.eval_force[i] = 3;
            continue;
        }
        if (first < 0)
            first = i;
        else if (memcmp(t.rgb[i], t.rgb[first], sizeof t.rgb[i]) != 0)
            single = false;
    }
    struct bc_colour_candidate best = {0, 0, 0xffffffffu, UINT64_MAX};
    if (first < 0) { /* every texel transparent */
        best.error = 0;
        bc_put_colour(&best, dst);
        return;
    }
    bool is_best = (flags & VT_BC_ENCODE_BEST) != 0;
    bool may_four = t.transparent == 0, may_three = !t.four_only;
    if (single) {
        bc_colour_single(&t, t.rgb[first], may_four, may_three, &best);
        bc_put_colour(&best, dst);
        return;
    }
    struct bc_axis ax;
    bc_colour_axis(&t, is_best ? BC_POWER_BEST : BC_POWER_FAST, &ax);
    unsigned c0, c1;
    bc_axis_endpoints(&ax, 1.0 / 16, &c0, &c1);
    if (!is_best) {
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
        /* the 3-colour mode wins on few blocks of a photo: two starts (more 4-colour starts for
         * BC3 measured -0.003 dB closer to libsquish for 20% of the speed: not taken) */
        size_t starts = three ? 2 : 4;
        for (size_t s = 0; s < starts; s++) {
            bc_axis_endpoints(&ax, insets[s], &c0, &c1);
            bc_colour_refine(&t, c0, c1, three, BC_REFINE_BEST, &best);
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

/* ---- alpha ---- */

struct bc_alpha_candidate {
    unsigned a0, a1;
    uint64_t indices; /* 3 bits per texel */
    uint64_t error;
};

static uint64_t bc_alpha_eval(const int *alpha, unsigned a0, unsigned a1, uint64_t bound,
                              uint64_t *indices)
{
    int pal[8] = {(int)a0, (int)a1};
    if (a0 > a1) {
        for (int i = 1; i <= 6; i++)
            pal[1 + i] = ((7 - i) * (int)a0 + i * (int)a1) / 7;
    } else {
        for (int i = 1; i <= 4; i++)
            pal[1 + i] = ((5 - i) * (int)a0 + i * (int)a1) / 5;
        pal[6] = 0;
        pal[7] = 255;
    }
    uint64_t error = 0, idx = 0;
    for (int i = 0; i < BC_TEXELS; i++) {
        uint32_t m = UINT32_MAX; /* distance << 3 | index, branch-free minimum */
        for (int k = 0; k < 8; k++) {
            uint32_t key = (uint32_t)bc_abs(alpha[i] - pal[k]) << 3 | (uint32_t)k;
            m = key < m ? key : m;
        }
        idx |= (uint64_t)(m & 7) << (3 * i);
        error += (uint64_t)(m >> 3) * (m >> 3);
        if (error >= bound)
            return UINT64_MAX;
    }
    *indices = idx;
    return error;
}

/* (a0, a1) in the 6-value mode (six: a0 <= a1) or the 8-value mode (a0 > a1), ordered so. */
static bool bc_alpha_try(const int *alpha, unsigned a0, unsigned a1, bool six,
                         struct bc_alpha_candidate *cand)
{
    if (six ? a0 > a1 : a0 < a1) {
        unsigned s = a0;
        a0 = a1;
        a1 = s;
    }
    uint64_t idx;
    uint64_t error = bc_alpha_eval(alpha, a0, a1, cand->error, &idx);
    if (error >= cand->error)
        return false;
    *cand = (struct bc_alpha_candidate){a0, a1, idx, error};
    return true;
}

static bool bc_alpha_solve(const int *alpha, const struct bc_alpha_candidate *c, bool six,
                           unsigned *a0, unsigned *a1)
{
    const int64_t scale = six ? 5 : 7;
    int64_t aa = 0, ab = 0, bb = 0, ax = 0, bx = 0;
    for (int i = 0; i < BC_TEXELS; i++) {
        unsigned k = (unsigned)(c->indices >> (3 * i) & 7);
        if (six && k >= 6)
            continue; /* the explicit 0 and 255 */
        int64_t a = k == 0 ? scale : k == 1 ? 0 : scale - (k - 1), b = scale - a;
        aa += a * a;
        ab += a * b;
        bb += b * b;
        ax += a * alpha[i];
        bx += b * alpha[i];
    }
    int64_t det = aa * bb - ab * ab;
    if (det == 0)
        return false;
    *a0 = (unsigned)bc_round_clamp((double)(scale * (bb * ax - ab * bx)) / (double)det);
    *a1 = (unsigned)bc_round_clamp((double)(scale * (aa * bx - ab * ax)) / (double)det);
    return true;
}

static void bc_alpha_refine(const int *alpha, unsigned a0, unsigned a1, bool six,
                            struct bc_alpha_candidate *best)
{
    struct bc_alpha_candidate chain = {0, 0, 0, UINT64_MAX};
    bc_alpha_try(alpha, a0, a1, six, &chain);
    for (int r = 0; r < BC_ALPHA_REFINE && chain.error > 0; r++) {
        unsigned n0, n1;
        if (!bc_alpha_solve(alpha, &chain, six, &n0, &n1) ||
            !bc_alpha_try(alpha, n0, n1, six, &chain))
            break;
    }
    for (int pass = 0; pass < BC_ALPHA_SEARCH && chain.error > 0; pass++) {
        bool improved = false;
        for (int d = -1; d <= 1; d += 2) {
            int v0 = (int)chain.a0 + d, v1 = (int)chain.a1 + d;
            if (v0 >= 0 && v0 <= 255)
                improved |= bc_alpha_try(alpha, (unsigned)v0, chain.a1, six, &chain);
            if (v1 >= 0 && v1 <= 255)
                improved |= bc_alpha_try(alpha, chain.a0, (unsigned)v1, six, &chain);
        }
        if (!improved)
            break;
    }
    if (chain.error < best->error)
        *best = chain;
}

void vt_bc_encode_alpha_block(const unsigned char *rgba, unsigned flags, unsigned char *dst)
{
    int alpha[BC_TEXELS], lo = 255, hi = 0, lo6 = 255, hi6 = 0;
    for (int i = 0; i < BC_TEXELS; i++) {
        int a = alpha[i] = rgba[4 * i + 3];
        lo = a < lo ? a : lo;
        hi = a > hi ? a : hi;
        if (a != 0 && a != 255) {
            lo6 = a < lo6 ? a : lo6;
            hi6 = a > hi6 ? a : hi6;
        }
    }
    struct bc_alpha_candidate best = {(unsigned)lo, (unsigned)lo, 0, 0};
    if (lo != hi) {
        best.error = UINT64_MAX;
        if (lo6 > hi6) /* only 0 and 255 */
            lo6 = hi6 = 0;
        if (flags & VT_BC_ENCODE_BEST) {
            bc_alpha_refine(alpha, (unsigned)hi, (unsigned)lo, false, &best);
            bc_alpha_refine(alpha, (unsigned)lo6, (unsigned)hi6, true, &best);
        } else {
            bc_alpha_try(alpha, (unsigned)hi, (unsigned)lo, false, &best);
            bc_alpha_try(alpha, (unsigned)lo6, (unsigned)hi6, true, &best);
        }
    }
    dst[0] = (unsigned char)best.a0;
    dst[1] = (unsigned char)best.a1;
    for (int b = 0; b < 6; b++)
        dst[2 + b] = (unsigned char)(best.indices >> (8 * b));
}
