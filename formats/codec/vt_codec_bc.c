/* BC1 (DXT1) and BC3 (DXT5) tile payloads: the 4x4 blocks of the tile, row-major (left to right,
 * then top to bottom), 8 bytes (BC1) or 16 bytes (BC3) each, exactly what glCompressedTexImage2D
 * takes for a tile of that size. The tile edge must be a multiple of 4; the encoder never pads.
 *
 * Encoders (params->effort, enum vt_codec_bc_effort), both ours (vt_bc_encode.c):
 *   0 fast: principal axis, endpoints at the extreme projections (inset 1/16), one least-squares
 *           step; the BC3 alpha between the block's min and max in the 8- or 6-value mode,
 *           whichever has the smaller error. Above stb_dxt's PSNR at a higher speed.
 *   1 best: iterated least squares from several starts along the principal axis, both colour
 *           modes (BC1), +-1 search of the 565 endpoints; for BC3 colour error weighted by alpha
 *           (it counts where the texel shows), alpha refined in both modes. Above libsquish's
 *           cluster fit at more than 10x its speed.
 *   Both measured against the references in docs/accuracy.md (scripts/bench/bc-encoders).
 *   16, 17: the references, for the benchmark and the tests only: stb_dxt 1.12 (STB_DXT_NORMAL,
 *           what fast was, with libsquish's range fit for BC1 blocks holding a texel of alpha
 *           < 128) and libsquish 1.15's cluster fit (what best was).
 * BC1 keeps alpha as one bit: a 4-channel texel with alpha < 128 is stored as the transparent
 * black (0, 0, 0, 0) of the 3-colour mode, every other texel decodes with alpha 255. BC3 stores
 * alpha in its own block (fast: the 8-alpha mode; best: 8- or 6-alpha, whichever fits better).
 *
 * Decoder (our own, for GL without S3TC, verification and transcoding), exact integer formulas on
 * the 8-bit endpoints, truncating like libsquish's decoder (bit for bit: tested); the GL and D3D
 * specs allow other roundings, and GPU or llvmpipe decoders may differ by 1 on some texels:
 *   RGB565 -> RGB888 by bit replication: r8 = r5 << 3 | r5 >> 2, g8 = g6 << 2 | g6 >> 4;
 *   colour c0 > c1 (always in BC3): c2 = (2 c0 + c1) / 3, c3 = (c0 + 2 c1) / 3, alpha 255;
 *   colour c0 <= c1 (BC1 only):     c2 = (c0 + c1) / 2, c3 = transparent black (0, 0, 0, 0);
 *   alpha a0 > a1:  a[1 + i] = ((7 - i) a0 + i a1) / 7 for i = 1..6;
 *   alpha a0 <= a1: a[1 + i] = ((5 - i) a0 + i a1) / 5 for i = 1..4, a6 = 0, a7 = 255.
 * Texel i = 4 y + x of a block takes colour index bits 2i..2i+1 of the little-endian 32-bit word
 * at byte 4 (of the colour block) and alpha index bits 3i..3i+2 of the 48-bit word at byte 2. */
#include <stdbool.h>
#include <stdint.h>
#include <string.h>

#define STB_DXT_STATIC
#define STB_DXT_IMPLEMENTATION
#include <stb/stb_dxt.h>

#include "internal/vt_bc4_block.h"
#include "internal/vt_bc_encode.h"
#include "internal/vt_block_tile.h"
#include "internal/vt_codec_impl.h"
#include "internal/vt_squish_shim.h"
#include "vt_codec.h"
#include "vt_error.h"

#define BC_BLOCK_PX     VT_BLOCK_TILE_PX
#define BC_ALPHA_OPAQUE 128 /* BC1: alpha below this is stored as transparent */

/* What tells bc1 from bc3. */
struct bc_format {
    struct vt_block_format block; /* name, block bytes (8 or 16), channel counts */
    bool has_alpha_block;         /* bc3 */
};

static const struct bc_format bc1_format = {
    {"bc1", 8, 3, 4, "3 or 4 channels (RGB or RGBA)", "use png or raw for grey or grey+alpha"},
    false};
static const struct bc_format bc3_format = {
    {"bc3", 16, 4, 4, "4 channels (RGBA)",
     "use bc1 for RGB (half the size), png or raw for grey or grey+alpha"},
    true};

/* ---- encoding ---- */

/* Copies the 4x4 block at texel (x0, y0) of src into 16 RGBA texels (alpha 255 for RGB). */
static void bc_gather_block(const struct vt_image *src, uint32_t x0, uint32_t y0,
                            unsigned char *rgba)
{
    for (uint32_t y = 0; y < BC_BLOCK_PX; y++, rgba += 16) {
        const unsigned char *row =
            (const unsigned char *)src->pixels + (size_t)(y0 + y) * src->stride;
        if (src->channels == 4) {
            memcpy(rgba, row + (size_t)x0 * 4, 16);
            continue;
        }
        const unsigned char *texel = row + (size_t)x0 * 3;
        for (uint32_t x = 0; x < BC_BLOCK_PX; x++) {
            rgba[4 * x] = texel[3 * x];
            rgba[4 * x + 1] = texel[3 * x + 1];
            rgba[4 * x + 2] = texel[3 * x + 2];
            rgba[4 * x + 3] = 255;
        }
    }
}

static bool bc_block_has_transparent_texel(const unsigned char *rgba)
{
    for (int i = 0; i < 16; i++)
        if (rgba[4 * i + 3] < BC_ALPHA_OPAQUE)
            return true;
    return false;
}

/* Encodes one gathered block; returns 0, or -1 when libsquish (a reference encoder) failed. */
static int bc_encode_block(const struct bc_format *fmt, const unsigned char *rgba, int effort,
                           bool rgba_source, unsigned char *dst)
{
    unsigned squish_flags = fmt->has_alpha_block ? VT_SQUISH_SHIM_BC3 : 0;
    switch (effort) {
    case VT_CODEC_BC_REF_SQUISH:
        if (fmt->has_alpha_block) /* colour error counts where it shows */
            squish_flags |= VT_SQUISH_SHIM_WEIGHT_BY_ALPHA;
        return vt_squish_shim_compress_block(rgba, squish_flags | VT_SQUISH_SHIM_CLUSTER_FIT, dst);
    case VT_CODEC_BC_REF_STB_DXT:
        if (!fmt->has_alpha_block && rgba_source && bc_block_has_transparent_texel(rgba))
            return vt_squish_shim_compress_block(rgba, squish_flags, dst); /* range fit */
        stb_compress_dxt_block(dst, rgba, fmt->has_alpha_block, STB_DXT_NORMAL);
        return 0;
    default: {
        unsigned flags = effort == VT_CODEC_BC_BEST ? VT_BC_ENCODE_BEST : 0;
        if (!fmt->has_alpha_block) {
            vt_bc_encode_colour_block(rgba, flags, dst);
            return 0;
        }
        flags |= VT_BC_ENCODE_FOUR_COLOUR_ONLY;
        if (effort == VT_CODEC_BC_BEST)
            flags |= VT_BC_ENCODE_WEIGHT_BY_ALPHA;
        vt_bc4_block_encode(rgba + 3, 4, effort == VT_CODEC_BC_BEST ? VT_BC4_BLOCK_BEST : 0, dst);
        vt_bc_encode_colour_block(rgba, flags, dst + 8);
        return 0;
    }
    }
}

static int bc_encode(const struct bc_format *fmt, const struct vt_image *src,
                     const struct vt_codec_params *params, void *dst, size_t dst_capacity,
                     size_t *out_len, struct vts_error *err)
{
    size_t payload_bytes;
    *out_len = 0;
    int effort = params ? params->effort : VT_CODEC_BC_FAST;
    bool effort_valid = effort == VT_CODEC_BC_FAST || effort == VT_CODEC_BC_BEST ||
                        effort == VT_CODEC_BC_REF_STB_DXT || effort == VT_CODEC_BC_REF_SQUISH;
    int rc = vt_block_tile_encode_check(&fmt->block, src, effort, effort_valid, dst_capacity,
                                        &payload_bytes, err);
    if (rc < 0)
        return rc;
    unsigned char *out = dst;
    _Alignas(16) unsigned char rgba[64]; /* stb_dxt reads the texels as 32-bit words */
    for (uint32_t y0 = 0; y0 < src->height; y0 += BC_BLOCK_PX) {
        for (uint32_t x0 = 0; x0 < src->width; x0 += BC_BLOCK_PX, out += fmt->block.block_bytes) {
            bc_gather_block(src, x0, y0, rgba);
            if (bc_encode_block(fmt, rgba, effort, src->channels == 4, out) < 0)
                return vt_error_set(err, VTS_ERR_NOMEM,
                                    "%s encode: libsquish failed at block (%u, %u)",
                                    fmt->block.name, x0 / BC_BLOCK_PX, y0 / BC_BLOCK_PX);
        }
    }
    *out_len = payload_bytes;
    return 0;
}

/* ---- decoding ---- */

/* RGB565 -> RGBA8 by bit replication, alpha 255. */
static void bc_rgb565_expand(unsigned packed, unsigned char *rgba)
{
    unsigned r5 = packed >> 11, g6 = (packed >> 5) & 63, b5 = packed & 31;
    rgba[0] = (unsigned char)(r5 << 3 | r5 >> 2);
    rgba[1] = (unsigned char)(g6 << 2 | g6 >> 4);
    rgba[2] = (unsigned char)(b5 << 3 | b5 >> 2);
    rgba[3] = 255;
}

/* Decodes an 8-byte colour block into 16 RGBA texels; four_colour_only for BC3's colour half. */
static void bc_decode_colour_block(const unsigned char *block, bool four_colour_only,
                                   unsigned char texels[16][4])
{
    unsigned c0 = block[0] | (unsigned)block[1] << 8, c1 = block[2] | (unsigned)block[3] << 8;
    unsigned char palette[4][4];
    bc_rgb565_expand(c0, palette[0]);
    bc_rgb565_expand(c1, palette[1]);
    if (c0 > c1 || four_colour_only) {
        for (int k = 0; k < 3; k++) {
            palette[2][k] = (unsigned char)((2 * palette[0][k] + palette[1][k]) / 3);
            palette[3][k] = (unsigned char)((palette[0][k] + 2 * palette[1][k]) / 3);
        }
        palette[2][3] = palette[3][3] = 255;
    } else {
        for (int k = 0; k < 3; k++)
            palette[2][k] = (unsigned char)((palette[0][k] + palette[1][k]) / 2);
        palette[2][3] = 255;
        memset(palette[3], 0, 4);
    }
    uint32_t indices =
        block[4] | (uint32_t)block[5] << 8 | (uint32_t)block[6] << 16 | (uint32_t)block[7] << 24;
    for (int i = 0; i < 16; i++)
        memcpy(texels[i], palette[(indices >> (2 * i)) & 3], 4);
}

/* Writes the 16 decoded texels of a block at texel (x0, y0) of dst (3 or 4 channels; RGB drops
 * alpha). Fixed-size copies: this loop is most of the decoder's time. */
static void bc_scatter_block(unsigned char texels[16][4], struct vt_image *dst, uint32_t x0,
                             uint32_t y0)
{
    for (uint32_t y = 0; y < BC_BLOCK_PX; y++) {
        unsigned char *row = (unsigned char *)dst->pixels + (size_t)(y0 + y) * dst->stride;
        if (dst->channels == 4) {
            memcpy(row + (size_t)x0 * 4, texels[4 * y], 16);
            continue;
        }
        for (uint32_t x = 0; x < BC_BLOCK_PX; x++)
            memcpy(row + (size_t)(x0 + x) * 3, texels[4 * y + x], 3);
    }
}

static int bc_decode(const struct bc_format *fmt, const void *src, size_t src_len,
                     struct vt_image *dst, struct vts_error *err)
{
    int rc = vt_block_tile_decode_check(&fmt->block, src_len, dst, err);
    if (rc < 0)
        return rc;
    const unsigned char *block = src;
    unsigned char texels[16][4];
    for (uint32_t y0 = 0; y0 < dst->height; y0 += BC_BLOCK_PX) {
        for (uint32_t x0 = 0; x0 < dst->width; x0 += BC_BLOCK_PX, block += fmt->block.block_bytes) {
            if (fmt->has_alpha_block) {
                bc_decode_colour_block(block + 8, true, texels);
                vt_bc4_block_decode(block, &texels[0][3], 4);
            } else {
                bc_decode_colour_block(block, false, texels);
            }
            bc_scatter_block(texels, dst, x0, y0);
        }
    }
    return 0;
}

/* ---- the two table entries ---- */

static int bc1_check(uint32_t tile_px, uint32_t channels, uint32_t sample, struct vts_error *err)
{
    return vt_block_tile_check(&bc1_format.block, tile_px, channels, sample, err);
}

static size_t bc1_encoded_bound(uint32_t width, uint32_t height, uint32_t channels, uint32_t sample)
{
    return vt_block_tile_encoded_bound(&bc1_format.block, width, height, channels, sample);
}

static int bc1_encode(const struct vt_image *src, const struct vt_codec_params *params, void *dst,
                      size_t dst_capacity, size_t *out_len, struct vts_error *err)
{
    return bc_encode(&bc1_format, src, params, dst, dst_capacity, out_len, err);
}

static int bc1_decode(const void *src, size_t src_len, struct vt_image *dst, struct vts_error *err)
{
    return bc_decode(&bc1_format, src, src_len, dst, err);
}

static int bc3_check(uint32_t tile_px, uint32_t channels, uint32_t sample, struct vts_error *err)
{
    return vt_block_tile_check(&bc3_format.block, tile_px, channels, sample, err);
}

static size_t bc3_encoded_bound(uint32_t width, uint32_t height, uint32_t channels, uint32_t sample)
{
    return vt_block_tile_encoded_bound(&bc3_format.block, width, height, channels, sample);
}

static int bc3_encode(const struct vt_image *src, const struct vt_codec_params *params, void *dst,
                      size_t dst_capacity, size_t *out_len, struct vts_error *err)
{
    return bc_encode(&bc3_format, src, params, dst, dst_capacity, out_len, err);
}

static int bc3_decode(const void *src, size_t src_len, struct vt_image *dst, struct vts_error *err)
{
    return bc_decode(&bc3_format, src, src_len, dst, err);
}

const struct vt_codec vt_codec_bc1 = {
    .name = "bc1",
    .fourcc = VTS_CODEC_BC1,
    .summary =
        "BC1/DXT1 blocks (4 bpp), RGB or RGBA with 1-bit alpha, 8-bit; effort 0 fast, 1 best",
    .lossless = false,
    .check = bc1_check,
    .encoded_bound = bc1_encoded_bound,
    .encode = bc1_encode,
    .decode = bc1_decode,
};

const struct vt_codec vt_codec_bc3 = {
    .name = "bc3",
    .fourcc = VTS_CODEC_BC3,
    .summary = "BC3/DXT5 blocks (8 bpp), RGBA, 8-bit; effort 0 fast, 1 best",
    .lossless = false,
    .check = bc3_check,
    .encoded_bound = bc3_encoded_bound,
    .encode = bc3_encode,
    .decode = bc3_decode,
};
