/* Our BC encoders (formats/codec/vt_bc_encode.c, vt_bc4_block.c) built a second time here, against
 * the library's build (which picks its AVX2 error loop at run time when the CPU has AVX2, else
 * SSE2): the same bytes for every flag on photo-like, noisy, cut-out, alpha-weighted, two-colour
 * and solid blocks. Two executables from this file: test_vt_bc_encode_portable
 * (VT_BC_ENCODE_PORTABLE: no SIMD at all) and test_vt_bc_encode_sse2 (VT_BC_ENCODE_TEST_SSE2: SSE2
 * without AVX2). The SIMD paths (set-up, error loops, least squares) only reorder integer sums, so
 * any difference is a bug in one of them. */
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#if defined(VT_BC_ENCODE_TEST_SSE2)
#define VT_BC_ENCODE_NO_AVX2 1
#else
#define VT_BC_ENCODE_PORTABLE 1
#endif
#define vt_bc_encode_colour_block portable_colour_block
#define vt_bc4_block_encode       portable_bc4_encode
#define vt_bc4_block_decode       portable_bc4_decode
#define vt_bc4_block_palette      portable_bc4_palette
#include "vt_bc4_block.c"
#include "vt_bc_encode.c"
#undef vt_bc_encode_colour_block
#undef vt_bc4_block_encode
#undef vt_bc4_block_decode
#undef vt_bc4_block_palette

#include "bc_test_util.h"
#include "vt_synth_photo.h"
#include "vt_test.h"

/* the library's build (internal/vt_bc_encode.h was read above under the portable names) */
void vt_bc_encode_colour_block(const unsigned char *rgba, unsigned flags, unsigned char *dst);
void vt_bc4_block_encode(const unsigned char *values, size_t step, unsigned flags,
                         unsigned char *dst);

/* Counts the blocks whose bytes differ between the two builds, over every flag combination. */
static int mismatches(const unsigned char rgba[64])
{
    int bad = 0;
    for (unsigned flags = 0; flags < 8; flags++) {
        unsigned char a[8], b[8];
        vt_bc_encode_colour_block(rgba, flags, a);
        portable_colour_block(rgba, flags, b);
        bad += memcmp(a, b, 8) != 0;
        /* the BC4 block (BC3's alpha; BC4/BC5 best adds the starts past the values) */
        static const unsigned bc4_flags[4] = {0, VT_BC4_BLOCK_BEST, 0,
                                              VT_BC4_BLOCK_BEST | VT_BC4_BLOCK_EXTEND};
        vt_bc4_block_encode(rgba + 3, 4, bc4_flags[flags & 3], a);
        portable_bc4_encode(rgba + 3, 4, bc4_flags[flags & 3], b);
        bad += memcmp(a, b, 8) != 0;
    }
    return bad;
}

/* The 4x4 block at (x0, y0) of a 4-channel image. */
static void block_of(const struct vt_image *img, uint32_t x0, uint32_t y0, unsigned char rgba[64])
{
    for (uint32_t y = 0; y < 4; y++)
        memcpy(rgba + 16 * y, (const unsigned char *)img->pixels + (y0 + y) * img->stride + x0 * 4,
               16);
}

static void bc_encode_portable_and_sse2_give_the_same_bytes(void)
{
    int bad = 0, blocks = 0;
    /* photo-like texels, opaque and with their own alpha (smooth, cut-outs) */
    struct vt_image photo = vt_synth_photo(128, 128, 4, 5, 0.6);
    for (uint32_t y = 0; y < 128; y += 4)
        for (uint32_t x = 0; x < 128; x += 4) {
            unsigned char rgba[64];
            block_of(&photo, x, y, rgba);
            bad += mismatches(rgba);
            for (int i = 0; i < 16; i++)
                rgba[4 * i + 3] = 255;
            bad += mismatches(rgba);
            blocks += 2;
        }
    free(photo.pixels);
    /* noise, noise with random alpha, two colours, solid colours, one alpha below 128 */
    rng_state = 29;
    for (int n = 0; n < 4000; n++) {
        unsigned char rgba[64];
        uint64_t r = rng_next();
        for (int i = 0; i < 64; i += 8) {
            uint64_t q = rng_next();
            memcpy(rgba + i, &q, 8);
        }
        int kind = n % 5;
        for (int i = 0; i < 16; i++) {
            if (kind == 0 || kind == 2 || kind == 3)
                rgba[4 * i + 3] = 255;
            if (kind == 2) /* two colours */
                memcpy(rgba + 4 * i, rgba + ((r >> i) & 1 ? 0 : 4), 3);
            if (kind == 3) /* one colour */
                memcpy(rgba + 4 * i, rgba, 3);
            if (kind == 4) /* cut-out: alpha 0 or 255, one texel below 128 */
                rgba[4 * i + 3] = (r >> (i + 16)) & 1 ? 255 : 0;
        }
        if (kind == 4)
            rgba[4 * (n % 16) + 3] = 100;
        bad += mismatches(rgba);
        blocks++;
    }
    fprintf(stderr, "  %d blocks x 8 flag sets: %d differ\n", blocks, bad);
    VT_CHECK_INT_EQ(bad, 0);
    /* the comparison sees a difference: one bit of the portable build's output flipped */
    unsigned char rgba[64], a[8], b[8];
    memset(rgba, 77, sizeof rgba);
    rgba[5] = 200;
    vt_bc_encode_colour_block(rgba, VT_BC_ENCODE_BEST, a);
    portable_colour_block(rgba, VT_BC_ENCODE_BEST, b);
    VT_CHECK(memcmp(a, b, 8) == 0);
    b[6] ^= 4;
    VT_CHECK(memcmp(a, b, 8) != 0);
}

int main(void)
{
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
    fprintf(stderr, "  the library's colour error loop on this CPU: %s\n",
            __builtin_cpu_supports("avx2") ? "AVX2" : "SSE2");
#endif
    VT_RUN(bc_encode_portable_and_sse2_give_the_same_bytes);
    return vt_test_main_result();
}
