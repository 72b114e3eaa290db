/* BC4 (RGTC1) and BC5 (RGTC2) tile payloads, unsigned: the 4x4 blocks of the tile, row-major,
 * 8 bytes (BC4) or 16 bytes (BC5: the red block, then the green block) each, exactly what
 * glCompressedTexImage2D takes for GL_COMPRESSED_RED_RGTC1 / GL_COMPRESSED_RG_RGTC2 (core since
 * GL 3.0; DXGI BC4_UNORM / BC5_UNORM). The tile edge must be a multiple of 4.
 *
 * BC4 stores one channel (masks, heights, data). BC5 stores two: a 2-channel layer is its R and G;
 * a 3-channel layer is a normal map (colour "normal", xyz mapped from [-1,1] to 0..255 as every
 * normal layer): BC5 keeps x and y, and the decoder rebuilds z = sqrt(max(0, 1 - x^2 - y^2)) with
 * x = 2 r / 255 - 1, y = 2 g / 255 - 1, stored as round((z + 1) / 2 * 255) (double precision), so
 * every reader of a 3-channel layer gets xyz as from any other codec; a renderer that samples the
 * RG blocks itself rebuilds z the same way in its shader (vt-view does).
 *
 * Encoders (params->effort, enum vt_codec_bc_effort; the references 16, 17 are BC1/BC3 only):
 *   0 fast: each channel's block between its min and max, the 8-value and the 6-value mode,
 *           whichever has the smaller squared error;
 *   1 best: both modes refined by least squares and a +-1 search of the endpoints, also from
 *           endpoints past the values (ramps of fewer levels than the palette's).
 *   (vt_bc4_block.c; BC3's alpha block is the same code.)
 * Decoder: vt_bc4_block_decode(), the integer formulas of docs/codecs.md (truncating, as BC3's
 * alpha and Mesa's RGTC decoder). */
#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <string.h>

#include "internal/vt_bc4_block.h"
#include "internal/vt_block_tile.h"
#include "internal/vt_codec_impl.h"
#include "vt_codec.h"
#include "vt_error.h"

#define RGTC_BLOCK_PX VT_BLOCK_TILE_PX

/* What tells bc4 from bc5. */
struct rgtc_format {
    struct vt_block_format block; /* name, block bytes (8 or 16), channel counts */
    uint32_t planes;              /* BC4 blocks per block: 1 or 2 */
};

static const struct rgtc_format bc4_format = {
    {"bc4", 8, 1, 1, "1 channel",
     "use bc5 for two channels or a normal map, bc1 or bc3 for colour"},
    1};
static const struct rgtc_format bc5_format = {{"bc5", 16, 2, 3,
                                               "2 channels or a 3-channel normal map",
                                               "use bc4 for one channel, bc1 or bc3 for colour"},
                                              2};

/* ---- encoding ---- */

/* Channel c of the 4x4 block at texel (x0, y0) of src into 16 values. */
static void rgtc_gather_plane(const struct vt_image *src, uint32_t x0, uint32_t y0, uint32_t c,
                              unsigned char values[16])
{
    for (uint32_t y = 0; y < RGTC_BLOCK_PX; y++) {
        const unsigned char *texel = (const unsigned char *)src->pixels +
                                     (size_t)(y0 + y) * src->stride + (size_t)x0 * src->channels +
                                     c;
        for (uint32_t x = 0; x < RGTC_BLOCK_PX; x++)
            values[4 * y + x] = texel[(size_t)x * src->channels];
    }
}

static int rgtc_encode(const struct rgtc_format *fmt, const struct vt_image *src,
                       const struct vt_codec_params *params, void *dst, size_t dst_capacity,
                       size_t *out_len, struct vts_error *err)
{
    size_t payload_bytes;
    *out_len = 0;
    int effort = params ? params->effort : VT_CODEC_BC_FAST;
    bool effort_valid = effort == VT_CODEC_BC_FAST || effort == VT_CODEC_BC_BEST;
    int rc = vt_block_tile_encode_check(&fmt->block, src, effort, effort_valid, dst_capacity,
                                        &payload_bytes, err);
    if (rc < 0)
        return rc;
    unsigned flags = effort == VT_CODEC_BC_BEST ? VT_BC4_BLOCK_BEST | VT_BC4_BLOCK_EXTEND : 0;
    unsigned char *out = dst, values[16];
    for (uint32_t y0 = 0; y0 < src->height; y0 += RGTC_BLOCK_PX) {
        for (uint32_t x0 = 0; x0 < src->width; x0 += RGTC_BLOCK_PX) {
            for (uint32_t c = 0; c < fmt->planes; c++, out += 8) {
                rgtc_gather_plane(src, x0, y0, c, values);
                vt_bc4_block_encode(values, 1, flags, out);
            }
        }
    }
    *out_len = payload_bytes;
    return 0;
}

/* ---- decoding ---- */

/* z of a unit normal from its stored x and y (0..255 for [-1,1]), stored the same way. */
static unsigned char rgtc_normal_z(unsigned char r, unsigned char g)
{
    double x = r * (2.0 / 255.0) - 1.0, y = g * (2.0 / 255.0) - 1.0;
    double zz = 1.0 - x * x - y * y;
    double z = zz > 0.0 ? sqrt(zz) : 0.0;
    return (unsigned char)floor((z + 1.0) * 127.5 + 0.5);
}

static int rgtc_decode(const struct rgtc_format *fmt, const void *src, size_t src_len,
                       struct vt_image *dst, struct vts_error *err)
{
    int rc = vt_block_tile_decode_check(&fmt->block, src_len, dst, err);
    if (rc < 0)
        return rc;
    const unsigned char *block = src;
    unsigned char texels[16][3];
    uint32_t ch = dst->channels;
    for (uint32_t y0 = 0; y0 < dst->height; y0 += RGTC_BLOCK_PX) {
        for (uint32_t x0 = 0; x0 < dst->width;
             x0 += RGTC_BLOCK_PX, block += fmt->block.block_bytes) {
            for (uint32_t c = 0; c < fmt->planes; c++)
                vt_bc4_block_decode(block + 8 * c, &texels[0][c], 3);
            if (ch == 3)
                for (int i = 0; i < 16; i++)
                    texels[i][2] = rgtc_normal_z(texels[i][0], texels[i][1]);
            for (uint32_t y = 0; y < RGTC_BLOCK_PX; y++) {
                unsigned char *row =
                    (unsigned char *)dst->pixels + (size_t)(y0 + y) * dst->stride + (size_t)x0 * ch;
                for (uint32_t x = 0; x < RGTC_BLOCK_PX; x++)
                    memcpy(row + (size_t)x * ch, texels[4 * y + x], ch);
            }
        }
    }
    return 0;
}

/* ---- the two table entries ---- */

static int bc4_check(uint32_t tile_px, uint32_t channels, uint32_t sample, struct vts_error *err)
{
    return vt_block_tile_check(&bc4_format.block, tile_px, channels, sample, err);
}

static size_t bc4_encoded_bound(uint32_t width, uint32_t height, uint32_t channels, uint32_t sample)
{
    return vt_block_tile_encoded_bound(&bc4_format.block, width, height, channels, sample);
}

static int bc4_encode(const struct vt_image *src, const struct vt_codec_params *params, void *dst,
                      size_t dst_capacity, size_t *out_len, struct vts_error *err)
{
    return rgtc_encode(&bc4_format, src, params, dst, dst_capacity, out_len, err);
}

static int bc4_decode(const void *src, size_t src_len, struct vt_image *dst, struct vts_error *err)
{
    return rgtc_decode(&bc4_format, src, src_len, dst, err);
}

static int bc5_check(uint32_t tile_px, uint32_t channels, uint32_t sample, struct vts_error *err)
{
    return vt_block_tile_check(&bc5_format.block, tile_px, channels, sample, err);
}

static size_t bc5_encoded_bound(uint32_t width, uint32_t height, uint32_t channels, uint32_t sample)
{
    return vt_block_tile_encoded_bound(&bc5_format.block, width, height, channels, sample);
}

static int bc5_encode(const struct vt_image *src, const struct vt_codec_params *params, void *dst,
                      size_t dst_capacity, size_t *out_len, struct vts_error *err)
{
    return rgtc_encode(&bc5_format, src, params, dst, dst_capacity, out_len, err);
}

static int bc5_decode(const void *src, size_t src_len, struct vt_image *dst, struct vts_error *err)
{
    return rgtc_decode(&bc5_format, src, src_len, dst, err);
}

const struct vt_codec vt_codec_bc4 = {
    .name = "bc4",
    .fourcc = VTS_CODEC_BC4,
    .summary = "BC4/RGTC1 blocks (4 bpp), one channel, 8-bit; effort 0 fast, 1 best",
    .lossless = false,
    .check = bc4_check,
    .encoded_bound = bc4_encoded_bound,
    .encode = bc4_encode,
    .decode = bc4_decode,
};

const struct vt_codec vt_codec_bc5 = {
    .name = "bc5",
    .fourcc = VTS_CODEC_BC5,
    .summary =
        "BC5/RGTC2 blocks (8 bpp), two channels or a normal map (z rebuilt), 8-bit; effort 0 "
        "fast, 1 best",
    .lossless = false,
    .check = bc5_check,
    .encoded_bound = bc5_encoded_bound,
    .encode = bc5_encode,
    .decode = bc5_decode,
};
