/* Private to formats/codec: one BC4 block (RGTC1 unsigned; also BC3's alpha half and each half of
 * BC5), encoded and decoded (vt_bc4_block.c), used by vt_codec_bc.c (BC3) and vt_codec_rgtc.c
 * (BC4, BC5). A block is 8 bytes: value endpoints v0, v1, then 16 indices of 3 bits (texel
 * i = 4 y + x takes bits 3i..3i+2 of the little-endian 48-bit word at byte 2).
 * No allocation, no global state: thread-safe. The bytes depend only on the values and the flags
 * (integer error, float only in the least-squares step, built without FMA contraction). */
#ifndef VT_BC4_BLOCK_H
#define VT_BC4_BLOCK_H

#include <stddef.h>

enum vt_bc4_block_flags {
    VT_BC4_BLOCK_BEST = 1 << 0, /* least-squares refinement and +-1 search of both modes */
    /* with BEST: also the starts whose endpoints lie past the values (the values' min and max on
     * inner palette entries: ramps of fewer steps than the palette's); BC4 and BC5 best, not
     * BC3's (its bytes are pinned, and 3x slower there for +0.002 dB on RGBA photos) */
    VT_BC4_BLOCK_EXTEND = 1 << 1,
};

/* Encodes 16 values (values[i * step], i = 4 y + x) into an 8-byte block. Fast: the 8-value mode
 * between the block's max and min and the 6-value mode (explicit 0 and 255) between the min and
 * max of the other values, whichever has the smaller squared error; VT_BC4_BLOCK_BEST refines
 * both from there. A block of one value is exact. */
void vt_bc4_block_encode(const unsigned char *values, size_t step, unsigned flags,
                         unsigned char *dst);

/* Decodes an 8-byte block into 16 values (values[i * step]) with the integer formulas of
 * docs/codecs.md (truncating division, as libsquish's and Mesa's decoders):
 *   v0 > v1:  v[1 + i] = ((7 - i) v0 + i v1) / 7, i = 1..6;
 *   v0 <= v1: v[1 + i] = ((5 - i) v0 + i v1) / 5, i = 1..4; v6 = 0, v7 = 255. */
void vt_bc4_block_decode(const unsigned char *block, unsigned char *values, size_t step);

/* The decoded palette of endpoints (v0, v1), as vt_bc4_block_decode() uses it (for the tests'
 * exhaustive searches). */
void vt_bc4_block_palette(unsigned v0, unsigned v1, int palette[8]);

#endif
