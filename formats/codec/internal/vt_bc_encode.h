/* Private to formats/codec: our BC1 colour block encoder (vt_bc_encode.c), used by vt_codec_bc.c
 * (BC1, and BC3's colour half; BC3's alpha half is a BC4 block, internal/vt_bc4_block.h).
 * One 4x4 block per call, no allocation, no global state written after the first call's one-time
 * table set-up (pthread_once): thread-safe. The bytes depend only on the texels and the flags
 * (integer error metric, float math in a fixed order built without FMA contraction). */
#ifndef VT_BC_ENCODE_H
#define VT_BC_ENCODE_H

enum vt_bc_encode_flags {
    VT_BC_ENCODE_BEST = 1 << 0,             /* refinement and endpoint search; else one pass */
    VT_BC_ENCODE_FOUR_COLOUR_ONLY = 1 << 1, /* BC3's colour half: never the 3-colour mode */
    VT_BC_ENCODE_WEIGHT_BY_ALPHA = 1 << 2,  /* colour error of a texel weighted by alpha + 1 */
};

/* Encodes the colour of 16 RGBA texels (64 bytes, row-major) into an 8-byte BC1 colour block.
 * Without VT_BC_ENCODE_FOUR_COLOUR_ONLY a texel with alpha < 128 is stored as the transparent
 * black of the 3-colour mode, and the 3-colour mode is also tried for opaque blocks. */
void vt_bc_encode_colour_block(const unsigned char *rgba, unsigned flags, unsigned char *dst);

#endif
