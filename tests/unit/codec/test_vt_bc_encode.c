/* Our BC1/BC3 encoder (formats/codec/vt_bc_encode.c) through the codec table: two-colour and
 * constant blocks exact, gradients bounded, cut-outs in the three-colour mode, solid, one-channel
 * and alpha blocks against exhaustive searches of every endpoint pair (with wrong encoders shown
 * to fail), pinned output bytes, and `best` against libsquish's cluster fit (`fast` against
 * stb_dxt) on a photo. The SIMD paths against the portable code: test_vt_bc_encode_portable.c. */
#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "bc_test_util.h"
#include "vt_codec.h"
#include "vt_synth_photo.h"
#include "vt_test.h"
#include "vts.h"

/* Encodes one 4x4 RGBA block with codec_name at effort and decodes it into decoded. */
static void block_round_trip(const char *codec_name, int effort, unsigned char texels[16][4],
                             unsigned char decoded[16][4])
{
    struct vt_image src = {4, 4, 4, VTS_SAMPLE_U8, 16, texels};
    struct vt_codec_params params = {.effort = effort};
    unsigned char out[16];
    size_t len = 0;
    VT_CHECK_INT_EQ(vt_codec_find(codec_name)->encode(&src, &params, out, sizeof out, &len, NULL),
                    0);
    VT_CHECK_INT_EQ(decode_block(codec_name, out, len, decoded), 0);
}

static void bc_ours_two_colour_blocks_decode_exactly(void)
{
    /* two RGB565 colours anywhere in the block: the endpoints themselves are the answer */
    rng_state = 7;
    static const int efforts[] = {VT_CODEC_BC_BEST, VT_CODEC_BC_FAST};
    int wrong[2][2] = {{0, 0}, {0, 0}};
    for (int n = 0; n < 2000; n++) {
        uint64_t r = rng_next();
        unsigned char colour[2][4];
        for (int c = 0; c < 2; c++) {
            unsigned packed = (unsigned)(r >> (16 * c)) & 0xffff, r5 = packed >> 11,
                     g6 = (packed >> 5) & 63, b5 = packed & 31;
            colour[c][0] = (unsigned char)(r5 << 3 | r5 >> 2);
            colour[c][1] = (unsigned char)(g6 << 2 | g6 >> 4);
            colour[c][2] = (unsigned char)(b5 << 3 | b5 >> 2);
            colour[c][3] = 255;
        }
        unsigned char texels[16][4], decoded[16][4];
        for (int i = 0; i < 16; i++)
            memcpy(texels[i], colour[(r >> (32 + i)) & 1], 4);
        for (int e = 0; e < 2; e++) {
            block_round_trip("bc1", efforts[e], texels, decoded);
            wrong[0][e] += memcmp(texels, decoded, sizeof texels) != 0;
            block_round_trip("bc3", efforts[e], texels, decoded);
            wrong[1][e] += memcmp(texels, decoded, sizeof texels) != 0;
        }
    }
    fprintf(stderr, "  two-colour blocks not exact: bc1 best %d fast %d, bc3 best %d fast %d\n",
            wrong[0][0], wrong[0][1], wrong[1][0], wrong[1][1]);
    VT_CHECK_INT_EQ(wrong[0][0], 0);
    VT_CHECK_INT_EQ(wrong[1][0], 0);
}

static void bc_ours_constant_blocks_are_optimal(void)
{
    /* any constant colour (not only RGB565 ones): within 2 of it in every channel (the table of
     * endpoint pairs), exact for RGB565 colours (bc_solid_colours_in_rgb565_decode_exactly) */
    rng_state = 11;
    int worst = 0;
    for (int n = 0; n < 3000; n++) {
        uint64_t r = rng_next();
        unsigned char texels[16][4], decoded[16][4];
        for (int i = 0; i < 16; i++)
            for (int c = 0; c < 4; c++)
                texels[i][c] = c == 3 ? 255 : (unsigned char)(r >> (8 * c));
        for (int f = 0; f < 2; f++) {
            block_round_trip(f ? "bc3" : "bc1", VT_CODEC_BC_BEST, texels, decoded);
            for (int i = 0; i < 16; i++)
                for (int c = 0; c < 4; c++) {
                    int d = abs(texels[i][c] - decoded[i][c]);
                    worst = d > worst ? d : worst;
                }
        }
    }
    fprintf(stderr, "  constant blocks: worst channel error %d\n", worst);
    VT_CHECK(worst <= 2);
}

static void bc_ours_gradients_stay_within_a_bound(void)
{
    /* a ramp across the block in each direction, of several slopes: every texel within 6 */
    int worst = 0;
    for (int slope = 1; slope <= 24; slope += 5)
        for (int dir = 0; dir < 2; dir++) {
            unsigned char texels[16][4], decoded[16][4];
            for (int i = 0; i < 16; i++) {
                int s = dir ? i % 4 : i / 4;
                texels[i][0] = (unsigned char)(40 + slope * s);
                texels[i][1] = (unsigned char)(200 - slope * s);
                texels[i][2] = (unsigned char)(90 + slope * s / 2);
                texels[i][3] = 255;
            }
            for (int f = 0; f < 2; f++) {
                block_round_trip(f ? "bc3" : "bc1", VT_CODEC_BC_BEST, texels, decoded);
                for (int i = 0; i < 16; i++)
                    for (int c = 0; c < 3; c++) {
                        int d = abs(texels[i][c] - decoded[i][c]);
                        worst = d > worst ? d : worst;
                    }
            }
        }
    fprintf(stderr, "  gradients: worst channel error %d\n", worst);
    VT_CHECK(worst <= 6);
}

static void bc3_ours_two_alpha_values_decode_exactly(void)
{
    rng_state = 13;
    static const int efforts[] = {VT_CODEC_BC_BEST, VT_CODEC_BC_FAST};
    int wrong = 0;
    for (int n = 0; n < 2000; n++) {
        uint64_t r = rng_next();
        unsigned char a[2] = {(unsigned char)r, (unsigned char)(r >> 8)};
        if (n % 5 == 0)
            a[n % 2] = n % 3 ? 0 : 255; /* with the extremes of the 6-value mode too */
        unsigned char texels[16][4], decoded[16][4];
        for (int i = 0; i < 16; i++) {
            texels[i][0] = texels[i][1] = texels[i][2] = 99;
            texels[i][3] = a[(r >> (16 + i)) & 1];
        }
        for (int e = 0; e < 2; e++) {
            block_round_trip("bc3", efforts[e], texels, decoded);
            for (int i = 0; i < 16; i++)
                wrong += decoded[i][3] != texels[i][3];
        }
    }
    VT_CHECK_INT_EQ(wrong, 0);
}

static void bc1_ours_stores_cut_outs_in_the_three_colour_mode(void)
{
    /* some texels below alpha 128: the block must be 3-colour (c0 <= c1), those texels index 3 */
    rng_state = 17;
    int bad = 0;
    for (int n = 0; n < 500; n++) {
        uint64_t r = rng_next();
        unsigned char texels[16][4], out[8];
        for (int i = 0; i < 16; i++) {
            texels[i][0] = (unsigned char)(r >> (i % 8 * 8));
            texels[i][1] = (unsigned char)(i * 13 + n);
            texels[i][2] = (unsigned char)(255 - i * 7);
            texels[i][3] = (r >> (i + 40)) & 1 ? 255 : (unsigned char)(n % 128);
        }
        texels[n % 16][3] = 0;
        struct vt_image src = {4, 4, 4, VTS_SAMPLE_U8, 16, texels};
        static const int efforts[] = {VT_CODEC_BC_FAST, VT_CODEC_BC_BEST};
        for (int e = 0; e < 2; e++) {
            struct vt_codec_params params = {.effort = efforts[e]};
            size_t len = 0;
            VT_CHECK_INT_EQ(vt_codec_find("bc1")->encode(&src, &params, out, 8, &len, NULL), 0);
            unsigned c0 = out[0] | out[1] << 8, c1 = out[2] | out[3] << 8;
            unsigned char decoded[16][4];
            VT_CHECK_INT_EQ(decode_block("bc1", out, 8, decoded), 0);
            bad += c0 > c1;
            for (int i = 0; i < 16; i++) {
                if (texels[i][3] < 128)
                    bad += decoded[i][0] || decoded[i][1] || decoded[i][2] || decoded[i][3];
                else
                    bad += decoded[i][3] != 255;
            }
        }
    }
    VT_CHECK_INT_EQ(bad, 0);
}

/* ---- against exhaustive searches ---- */

static int expand_bits(unsigned q, int bits)
{
    return bits == 5 ? (int)(q << 3 | q >> 2) : (int)(q << 2 | q >> 4);
}

/* The smallest squared error of one channel's values x[0..15] over every endpoint pair of that
 * channel (bits 5 or 6) with the decoder's palette: the 4-colour mode when q0 > q1 (and always
 * with four_only), else the 3-colour mode (c2 = the half, c3 = the opaque texel's black: never
 * near, see the callers). The other channels equal in both endpoints, so the pair's order in
 * this channel picks the mode. */
static long channel_optimum(const int x[16], int bits, bool four_only)
{
    long best = -1;
    for (unsigned q0 = 0; q0 < (1u << bits); q0++)
        for (unsigned q1 = 0; q1 < (1u << bits); q1++) {
            int e0 = expand_bits(q0, bits), e1 = expand_bits(q1, bits), pal[4], n = 4;
            pal[0] = e0;
            pal[1] = e1;
            if (four_only || q0 > q1) {
                pal[2] = (2 * e0 + e1) / 3;
                pal[3] = (e0 + 2 * e1) / 3;
            } else {
                pal[2] = (e0 + e1) / 2;
                n = 3;
            }
            long err = 0;
            for (int i = 0; i < 16; i++) {
                long m = 1L << 30;
                for (int k = 0; k < n; k++) {
                    long d = (long)(x[i] - pal[k]) * (x[i] - pal[k]);
                    m = d < m ? d : m;
                }
                err += m;
            }
            if (best < 0 || err < best)
                best = err;
        }
    return best;
}

/* The squared RGB error of decoded against texels. */
static long block_error(unsigned char texels[16][4], unsigned char decoded[16][4])
{
    long err = 0;
    for (int i = 0; i < 16; i++)
        for (int c = 0; c < 3; c++)
            err += (long)(texels[i][c] - decoded[i][c]) * (texels[i][c] - decoded[i][c]);
    return err;
}

/* A block with the values x in channel ch and 255 (exact in RGB565) in the two others: black,
 * the 3-colour mode's fourth entry, is then never the nearest colour. */
static void one_channel_block(const int x[16], int ch, unsigned char texels[16][4])
{
    for (int i = 0; i < 16; i++) {
        texels[i][0] = texels[i][1] = texels[i][2] = texels[i][3] = 255;
        texels[i][ch] = (unsigned char)x[i];
    }
}

static void bc_ours_solid_blocks_reach_the_exhaustive_optimum(void)
{
    /* every 8-bit value in each channel: both efforts reach the best pair's error exactly (the
     * single-colour table); a wrong encoder (the endpoints swapped: the other mode) does not */
    static const int efforts[] = {VT_CODEC_BC_FAST, VT_CODEC_BC_BEST};
    int wrong[2][2] = {{0, 0}, {0, 0}}, swapped_wrong = 0;
    for (int ch = 0; ch < 3; ch++)
        for (int v = 0; v < 256; v++) {
            int x[16];
            for (int i = 0; i < 16; i++)
                x[i] = v;
            unsigned char texels[16][4], decoded[16][4], out[16];
            one_channel_block(x, ch, texels);
            for (int f = 0; f < 2; f++) {
                const char *name = f ? "bc3" : "bc1";
                long optimum = channel_optimum(x, ch == 1 ? 6 : 5, f == 1);
                for (int e = 0; e < 2; e++) {
                    struct vt_image src = {4, 4, 4, VTS_SAMPLE_U8, 16, texels};
                    struct vt_codec_params params = {.effort = efforts[e]};
                    size_t len = 0;
                    VT_CHECK_INT_EQ(
                        vt_codec_find(name)->encode(&src, &params, out, sizeof out, &len, NULL), 0);
                    VT_CHECK_INT_EQ(decode_block(name, out, len, decoded), 0);
                    wrong[f][e] += block_error(texels, decoded) != optimum;
                    if (f == 0 && e == 1) {
                        unsigned char c[8];
                        memcpy(c, out, 8);
                        memcpy(c, out + 2, 2);
                        memcpy(c + 2, out, 2);
                        VT_CHECK_INT_EQ(decode_block(name, c, 8, decoded), 0);
                        swapped_wrong += block_error(texels, decoded) != optimum;
                    }
                }
            }
        }
    fprintf(stderr, "  solid blocks off the optimum: bc1 %d %d, bc3 %d %d; swapped endpoints %d\n",
            wrong[0][0], wrong[0][1], wrong[1][0], wrong[1][1], swapped_wrong);
    VT_CHECK_INT_EQ(wrong[0][0] + wrong[0][1] + wrong[1][0] + wrong[1][1], 0);
    VT_CHECK(swapped_wrong > 100); /* the check sees a wrong block */
}

static void bc_ours_one_channel_blocks_near_the_exhaustive_optimum(void)
{
    /* 16 values in one channel (a random range, clusters and ramps), the others exact: the
     * optimum is the best pair of that channel, searched exhaustively. best reaches it on most
     * blocks and stays within 2% in total; fast within 25%; an encoder whose
     * indices are off by one does not. */
    rng_state = 23;
    long total_opt[2] = {0, 0}, total_best[2] = {0, 0}, total_fast[2] = {0, 0},
         total_off[2] = {0, 0};
    int exact_best[2] = {0, 0}, below[2] = {0, 0}, blocks = 300;
    for (int n = 0; n < blocks; n++) {
        uint64_t r = rng_next();
        int ch = n % 3, lo = (int)(r & 255), span = (int)(r >> 8 & 255) % (256 - lo) + 1;
        int clusters = 1 + (int)(r >> 16 & 3), x[16];
        for (int i = 0; i < 16; i++) {
            uint64_t q = rng_next();
            int centre = lo + span * (int)(q % (unsigned)(clusters + 1)) / (clusters + 1);
            int v = n % 2 ? centre + (int)(q >> 8 & 7) - 3 : lo + (int)(q >> 8) % span;
            x[i] = v < 0 ? 0 : v > 255 ? 255 : v;
        }
        unsigned char texels[16][4], decoded[16][4], out[16];
        one_channel_block(x, ch, texels);
        for (int f = 0; f < 2; f++) {
            const char *name = f ? "bc3" : "bc1";
            long optimum = channel_optimum(x, ch == 1 ? 6 : 5, f == 1);
            total_opt[f] += optimum;
            block_round_trip(name, VT_CODEC_BC_BEST, texels, decoded);
            long e_best = block_error(texels, decoded);
            total_best[f] += e_best;
            exact_best[f] += e_best == optimum;
            below[f] += e_best < optimum; /* impossible unless the reference is wrong */
            block_round_trip(name, VT_CODEC_BC_FAST, texels, decoded);
            total_fast[f] += block_error(texels, decoded);
            /* the wrong encoder: best's block with every colour index + 1 (mod 4) */
            struct vt_image src = {4, 4, 4, VTS_SAMPLE_U8, 16, texels};
            struct vt_codec_params params = {.effort = VT_CODEC_BC_BEST};
            size_t len = 0;
            VT_CHECK_INT_EQ(vt_codec_find(name)->encode(&src, &params, out, sizeof out, &len, NULL),
                            0);
            unsigned char *colour = out + (f ? 8 : 0);
            for (int b = 4; b < 8; b++) {
                unsigned v = colour[b], w = 0;
                for (int k = 0; k < 4; k++)
                    w |= (((v >> (2 * k)) + 1) & 3) << (2 * k);
                colour[b] = (unsigned char)w;
            }
            VT_CHECK_INT_EQ(decode_block(name, out, len, decoded), 0);
            total_off[f] += block_error(texels, decoded);
        }
    }
    for (int f = 0; f < 2; f++) {
        fprintf(
            stderr,
            "  %s one-channel blocks: optimum %ld, best %ld (%d of %d exact), fast %ld, indices "
            "off by one %ld\n",
            f ? "bc3" : "bc1", total_opt[f], total_best[f], exact_best[f], blocks, total_fast[f],
            total_off[f]);
        VT_CHECK_INT_EQ(below[f], 0);
        VT_CHECK(exact_best[f] >= blocks * 9 / 10);
        VT_CHECK(total_best[f] <= total_opt[f] + total_opt[f] / 50); /* within 2% */
        VT_CHECK(total_fast[f] <= total_opt[f] + total_opt[f] / 4);  /* within 25% */
        VT_CHECK(total_off[f] > 2 * total_opt[f]);                   /* the check sees it */
    }
}

/* The smallest squared error of 16 alpha values over every (a0, a1) pair of BC3's alpha block in
 * both modes (the decoder's palettes), by exhaustive search. */
static long alpha_optimum(const int a[16])
{
    long best = -1;
    for (int a0 = 0; a0 < 256; a0++)
        for (int a1 = 0; a1 < 256; a1++) {
            int pal[8] = {a0, a1};
            if (a0 > a1) {
                for (int i = 1; i <= 6; i++)
                    pal[1 + i] = ((7 - i) * a0 + i * a1) / 7;
            } else {
                for (int i = 1; i <= 4; i++)
                    pal[1 + i] = ((5 - i) * a0 + i * a1) / 5;
                pal[6] = 0;
                pal[7] = 255;
            }
            long err = 0;
            for (int i = 0; i < 16 && (best < 0 || err < best); i++) {
                long m = 1L << 30;
                for (int k = 0; k < 8; k++) {
                    long d = (long)(a[i] - pal[k]) * (a[i] - pal[k]);
                    m = d < m ? d : m;
                }
                err += m;
            }
            if (best < 0 || err < best)
                best = err;
        }
    return best;
}

static void bc3_ours_alpha_blocks_near_the_exhaustive_optimum(void)
{
    /* random alpha blocks (spreads, clusters, with and without 0 and 255: harder than real alpha)
     * against the exhaustive optimum of the alpha block. Measured: best exact on 29 of 60, 38%
     * above the optimum in total; fast (min/max endpoints in both modes) 2.05x the optimum. The
     * gap is blocks whose best palette puts an endpoint past the values; starts from binned
     * indices closed it to 5% (47 exact) but made bc3 best 3x slower on the benchmark's RGBA
     * image for +0.002 dB, so they are not in. Indices off by one fail. */
    rng_state = 31;
    long total_opt = 0, total_best = 0, total_fast = 0, total_off = 0;
    int exact_best = 0, below = 0, blocks = 60;
    for (int n = 0; n < blocks; n++) {
        uint64_t r = rng_next();
        int lo = (int)(r & 255), span = (int)(r >> 8 & 255) % (256 - lo) + 1, a[16];
        for (int i = 0; i < 16; i++) {
            uint64_t q = rng_next();
            a[i] = n % 3 == 0 ? lo + (int)(q % 4) * (span - 1) / 3 /* four clusters */
                              : lo + (int)(q % (unsigned)span);
            if (n % 4 == 1 && i < 3)
                a[i] = i == 0 ? 0 : 255; /* the 6-value mode's extremes */
        }
        unsigned char texels[16][4], decoded[16][4], out[16];
        for (int i = 0; i < 16; i++) {
            texels[i][0] = texels[i][1] = texels[i][2] = 128;
            texels[i][3] = (unsigned char)a[i];
        }
        long optimum = alpha_optimum(a), err[2];
        static const int efforts[2] = {VT_CODEC_BC_BEST, VT_CODEC_BC_FAST};
        for (int e = 0; e < 2; e++) {
            block_round_trip("bc3", efforts[e], texels, decoded);
            err[e] = 0;
            for (int i = 0; i < 16; i++)
                err[e] += (long)(a[i] - decoded[i][3]) * (a[i] - decoded[i][3]);
        }
        total_opt += optimum;
        total_best += err[0];
        total_fast += err[1];
        exact_best += err[0] == optimum;
        below += err[0] < optimum || err[1] < optimum;
        /* the wrong encoder: best's alpha indices + 1 (mod 8) */
        struct vt_image src = {4, 4, 4, VTS_SAMPLE_U8, 16, texels};
        struct vt_codec_params params = {.effort = VT_CODEC_BC_BEST};
        size_t len = 0;
        VT_CHECK_INT_EQ(vt_codec_find("bc3")->encode(&src, &params, out, sizeof out, &len, NULL),
                        0);
        uint64_t idx = 0;
        for (int b = 0; b < 6; b++)
            idx |= (uint64_t)out[2 + b] << (8 * b);
        uint64_t wrong = 0;
        for (int i = 0; i < 16; i++)
            wrong |= (((idx >> (3 * i)) + 1) & 7) << (3 * i);
        for (int b = 0; b < 6; b++)
            out[2 + b] = (unsigned char)(wrong >> (8 * b));
        VT_CHECK_INT_EQ(decode_block("bc3", out, len, decoded), 0);
        for (int i = 0; i < 16; i++)
            total_off += (long)(a[i] - decoded[i][3]) * (a[i] - decoded[i][3]);
    }
    fprintf(stderr,
            "  bc3 alpha blocks: optimum %ld, best %ld (%d of %d exact), fast %ld, indices off by "
            "one %ld\n",
            total_opt, total_best, exact_best, blocks, total_fast, total_off);
    VT_CHECK_INT_EQ(below, 0);
    VT_CHECK(exact_best >= 25);
    VT_CHECK(total_best <= total_opt + total_opt * 45 / 100);
    VT_CHECK(total_fast <= total_opt * 21 / 10);
    VT_CHECK(total_best < total_fast); /* the refinement pays */
    VT_CHECK(total_off > 100 * total_opt);
}

/* FNV-1a of a payload */
static uint64_t fnv1a(const unsigned char *p, size_t n)
{
    uint64_t h = 0xcbf29ce484222325ull;
    for (size_t i = 0; i < n; i++)
        h = (h ^ p[i]) * 0x100000001b3ull;
    return h;
}

static void bc_ours_is_deterministic(void)
{
    /* the same bytes twice, and the bytes pinned: a compiler, flag or platform that changes them
     * (float contraction, another rounding) fails here. Changing the encoder on purpose: print
     * the new values and update them with a note in the commit. */
    struct vt_image rgb = vt_synth_photo(64, 64, 3, 9, 0.6),
                    rgba = vt_synth_photo(64, 64, 4, 9, 0.6);
    const struct vt_image *imgs[2] = {&rgb, &rgba};
    static const char *const names[2] = {"bc1", "bc3"};
    static const int efforts[2] = {VT_CODEC_BC_BEST, VT_CODEC_BC_FAST};
    static const uint64_t pinned[2][2] = {
        {0x890d13c9e8747c69ull, 0x497e9ac31e2deeefull},
        {0xffb9c69947dc5337ull, 0xbc01234a146963c4ull},
    };
    for (int c = 0; c < 2; c++)
        for (int e = 0; e < 2; e++) {
            size_t la = 0, lb = 0;
            unsigned char *a =
                encode_alloc_exact(vt_codec_find(names[c]), imgs[c], efforts[e], &la);
            unsigned char *b =
                encode_alloc_exact(vt_codec_find(names[c]), imgs[c], efforts[e], &lb);
            VT_CHECK(a && b && la == lb && memcmp(a, b, la) == 0);
            uint64_t h = a ? fnv1a(a, la) : 0;
            fprintf(stderr, "  %s effort %d: 0x%016llxull\n", names[c], efforts[e],
                    (unsigned long long)h);
            VT_CHECK(h == pinned[c][e]);
            free(a);
            free(b);
        }
    free(rgb.pixels);
    free(rgba.pixels);
}

static void bc_ours_best_matches_libsquish_cluster_fit(void)
{
    struct vt_image rgb = vt_synth_photo(256, 256, 3, 1, 0.6),
                    rgba = vt_synth_photo(256, 256, 4, 1, 0.6);
    double bc1_ours = round_trip_psnr("bc1", &rgb, VT_CODEC_BC_BEST),
           bc1_squish = round_trip_psnr("bc1", &rgb, VT_CODEC_BC_REF_SQUISH);
    double bc3_ours = round_trip_psnr("bc3", &rgba, VT_CODEC_BC_BEST),
           bc3_squish = round_trip_psnr("bc3", &rgba, VT_CODEC_BC_REF_SQUISH);
    double bc1_fast = round_trip_psnr("bc1", &rgb, VT_CODEC_BC_FAST),
           bc1_stb = round_trip_psnr("bc1", &rgb, VT_CODEC_BC_REF_STB_DXT);
    fprintf(
        stderr,
        "  bc1 best %.3f dB vs libsquish %.3f; bc3 best %.3f vs %.3f; ours fast %.3f vs stb_dxt %.3f\n",
        bc1_ours, bc1_squish, bc3_ours, bc3_squish, bc1_fast, bc1_stb);
    /* over all channels, alpha included for bc3: at least the cluster fit's (measured +0.14 and
     * +0.11 dB here) */
    VT_CHECK(bc1_ours >= bc1_squish);
    VT_CHECK(bc3_ours >= bc3_squish);
    VT_CHECK(bc1_fast >= bc1_stb);
    free(rgb.pixels);
    free(rgba.pixels);
}

int main(void)
{
    VT_RUN(bc_ours_two_colour_blocks_decode_exactly);
    VT_RUN(bc_ours_constant_blocks_are_optimal);
    VT_RUN(bc_ours_gradients_stay_within_a_bound);
    VT_RUN(bc3_ours_two_alpha_values_decode_exactly);
    VT_RUN(bc1_ours_stores_cut_outs_in_the_three_colour_mode);
    VT_RUN(bc_ours_solid_blocks_reach_the_exhaustive_optimum);
    VT_RUN(bc_ours_one_channel_blocks_near_the_exhaustive_optimum);
    VT_RUN(bc3_ours_alpha_blocks_near_the_exhaustive_optimum);
    VT_RUN(bc_ours_is_deterministic);
    VT_RUN(bc_ours_best_matches_libsquish_cluster_fit);
    return vt_test_main_result();
}
