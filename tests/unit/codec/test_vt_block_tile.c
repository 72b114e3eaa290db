/* The 4x4-block tile geometry and checks that bc1, bc3, bc4 and bc5 share (vt_block_tile.c),
 * through the codec table: the payload size of a tile shape, the 4 GiB payload limit, and every
 * refusal's message, whole, for each format (these were four copies of the same code; the
 * messages are pinned to what the copies said). */
#include <stdint.h>
#include <string.h>

#include "vt_codec.h"
#include "vt_test.h"

static const struct vt_codec *codec(const char *name)
{
    const struct vt_codec *c = vt_codec_find(name);
    VT_CHECK(c != NULL);
    return c;
}

/* check(): channel counts, sample type, tile edge, the 4 GiB limit. */
static void check_refuses_with_each_formats_message(void)
{
    struct vts_error err = {0};
    const struct vt_codec *bc1 = codec("bc1"), *bc3 = codec("bc3"), *bc4 = codec("bc4"),
                          *bc5 = codec("bc5");
    VT_CHECK_INT_EQ(bc1->check(256, 3, VTS_SAMPLE_U8, &err), 0);
    VT_CHECK_INT_EQ(bc1->check(256, 4, VTS_SAMPLE_U8, &err), 0);
    VT_CHECK_INT_EQ(bc1->check(256, 2, VTS_SAMPLE_U8, &err), VTS_ERR_UNSUPPORTED);
    VT_CHECK_STR_EQ(err.message, "bc1 needs 3 or 4 channels (RGB or RGBA), got 2: use png or raw "
                                 "for grey or grey+alpha");
    VT_CHECK_INT_EQ(bc3->check(256, 3, VTS_SAMPLE_U8, &err), VTS_ERR_UNSUPPORTED);
    VT_CHECK_STR_EQ(err.message, "bc3 needs 4 channels (RGBA), got 3: use bc1 for RGB (half the "
                                 "size), png or raw for grey or grey+alpha");
    VT_CHECK_INT_EQ(bc4->check(256, 2, VTS_SAMPLE_U8, &err), VTS_ERR_UNSUPPORTED);
    VT_CHECK_STR_EQ(err.message, "bc4 needs 1 channel, got 2: use bc5 for two channels or a normal "
                                 "map, bc1 or bc3 for colour");
    VT_CHECK_INT_EQ(bc5->check(256, 1, VTS_SAMPLE_U8, &err), VTS_ERR_UNSUPPORTED);
    VT_CHECK_STR_EQ(err.message, "bc5 needs 2 channels or a 3-channel normal map, got 1: use bc4 "
                                 "for one channel, bc1 or bc3 for colour");
    VT_CHECK_INT_EQ(bc5->check(256, 2, VTS_SAMPLE_U16, &err), VTS_ERR_UNSUPPORTED);
    VT_CHECK_STR_EQ(err.message, "bc5 stores 8-bit samples only (got u16); use png or raw");
    VT_CHECK_INT_EQ(bc4->check(130, 1, VTS_SAMPLE_U8, &err), VTS_ERR_UNSUPPORTED);
    VT_CHECK_STR_EQ(err.message, "bc4 needs a tile payload that is a multiple of 4 (got 130): use "
                                 "--tile-size 256 with --border 4 or --keep payload");
    VT_CHECK_INT_EQ(bc1->check(0, 3, VTS_SAMPLE_U8, &err), VTS_ERR_UNSUPPORTED);
    /* 16384^2 blocks: 2 GiB of bc1 fits, 4 GiB of bc3 (16 bytes a block) does not */
    VT_CHECK_INT_EQ(bc1->check(65536, 3, VTS_SAMPLE_U8, &err), 0);
    VT_CHECK_INT_EQ(bc3->check(65532, 4, VTS_SAMPLE_U8, &err), 0);
    VT_CHECK_INT_EQ(bc3->check(65536, 4, VTS_SAMPLE_U8, &err), VTS_ERR_UNSUPPORTED);
    VT_CHECK_STR_EQ(err.message, "bc3: a 65536x65536 tile exceeds the 4 GiB payload limit");
    /* the comparison can fail: a message off by one word is not equal */
    VT_CHECK(strcmp(err.message, "bc3: a 65536x65536 tile exceeds the 4 GiB payload limits") != 0);
}

/* encoded_bound(): whole blocks of 8 or 16 bytes, 0 for a shape or sample not stored. */
static void encoded_bound_counts_whole_blocks(void)
{
    const struct vt_codec *bc1 = codec("bc1"), *bc3 = codec("bc3"), *bc4 = codec("bc4"),
                          *bc5 = codec("bc5");
    VT_CHECK_INT_EQ(bc1->encoded_bound(8, 4, 3, VTS_SAMPLE_U8), 16);
    VT_CHECK_INT_EQ(bc3->encoded_bound(8, 12, 4, VTS_SAMPLE_U8), 96);
    VT_CHECK_INT_EQ(bc4->encoded_bound(256, 128, 1, VTS_SAMPLE_U8), 64 * 32 * 8);
    VT_CHECK_INT_EQ(bc5->encoded_bound(4, 4, 3, VTS_SAMPLE_U8), 16);
    VT_CHECK_INT_EQ(bc1->encoded_bound(6, 4, 3, VTS_SAMPLE_U8), 0);
    VT_CHECK_INT_EQ(bc1->encoded_bound(4, 0, 3, VTS_SAMPLE_U8), 0);
    VT_CHECK_INT_EQ(bc5->encoded_bound(4, 4, 4, VTS_SAMPLE_U8), 0);
    VT_CHECK_INT_EQ(bc3->encoded_bound(4, 4, 4, VTS_SAMPLE_F32), 0);
    VT_CHECK(bc1->encoded_bound(8, 4, 3, VTS_SAMPLE_U8) != 17); /* a wrong size fails */
}

/* encode() and decode(): the image, the effort, the output buffer and the payload length. */
static void encode_and_decode_refuse_with_each_formats_message(void)
{
    struct vts_error err = {0};
    const struct vt_codec *bc1 = codec("bc1"), *bc3 = codec("bc3"), *bc4 = codec("bc4"),
                          *bc5 = codec("bc5");
    unsigned char px[16 * 4 * 6] = {0}, out[64];
    size_t len = 1;
    struct vt_image rgb = {4, 4, 3, VTS_SAMPLE_U8, 12, px};
    struct vt_codec_params params = {.effort = 16}; /* a BC1/BC3 reference, not BC4/BC5's */
    VT_CHECK_INT_EQ(bc1->encode(&rgb, NULL, out, 7, &len, &err), VTS_ERR_LIMIT);
    VT_CHECK_STR_EQ(err.message, "bc1 encode: output buffer of 7 bytes < 8");
    VT_CHECK_INT_EQ(len, 0);
    VT_CHECK_INT_EQ(bc1->encode(&rgb, NULL, out, 8, &len, &err), 0);
    VT_CHECK_INT_EQ(len, 8);
    struct vt_image rgba = {6, 4, 4, VTS_SAMPLE_U8, 24, px};
    VT_CHECK_INT_EQ(bc3->encode(&rgba, NULL, out, sizeof out, &len, &err), VTS_ERR_UNSUPPORTED);
    VT_CHECK_STR_EQ(err.message, "bc3: a 6x4 source image is not a whole number of 4x4 blocks");
    struct vt_image grey = {4, 4, 1, VTS_SAMPLE_U8, 4, px};
    VT_CHECK_INT_EQ(bc4->encode(&grey, &params, out, sizeof out, &len, &err), VTS_ERR_ARG);
    VT_CHECK_STR_EQ(err.message, "bc4 codec: effort 16 is neither 0 (fast) nor 1 (best)");
    params.effort = 2;
    VT_CHECK_INT_EQ(bc1->encode(&rgb, &params, out, sizeof out, &len, &err), VTS_ERR_ARG);
    VT_CHECK_STR_EQ(err.message, "bc1 codec: effort 2 is neither 0 (fast) nor 1 (best)");
    params.effort = 16;
    VT_CHECK_INT_EQ(bc1->encode(&rgb, &params, out, sizeof out, &len, &err), 0);
    struct vt_image rg = {4, 4, 2, VTS_SAMPLE_U8, 4, px}; /* stride < 4 x 2 */
    VT_CHECK_INT_EQ(bc5->encode(&rg, NULL, out, sizeof out, &len, &err), VTS_ERR_ARG);
    VT_CHECK_STR_EQ(err.message, "bc5 codec: invalid source image (stride 4, 4x4)");
    VT_CHECK_INT_EQ(bc1->decode(out, 7, &rgb, &err), VTS_ERR_BAD_INPUT);
    VT_CHECK_STR_EQ(err.message,
                    "bc1 payload: 7 bytes != 8 expected for a 4x4 tile (1 blocks of 8 bytes)");
    struct vt_image grey_tall = {4, 6, 1, VTS_SAMPLE_U8, 4, px};
    VT_CHECK_INT_EQ(bc4->decode(out, 8, &grey_tall, &err), VTS_ERR_UNSUPPORTED);
    VT_CHECK_STR_EQ(err.message,
                    "bc4: a 4x6 destination image is not a whole number of 4x4 blocks");
    struct vt_image rgba8 = {8, 4, 4, VTS_SAMPLE_U8, 32, px};
    VT_CHECK_INT_EQ(bc3->decode(out, 16, &rgba8, &err), VTS_ERR_BAD_INPUT);
    VT_CHECK_STR_EQ(err.message,
                    "bc3 payload: 16 bytes != 32 expected for a 8x4 tile (2 blocks of 16 bytes)");
    struct vt_image no_pixels = {4, 4, 3, VTS_SAMPLE_U8, 12, NULL};
    VT_CHECK_INT_EQ(bc1->decode(out, 8, &no_pixels, &err), VTS_ERR_ARG);
    VT_CHECK_STR_EQ(err.message, "bc1 codec: invalid destination image (stride 12, 4x4)");
}

int main(void)
{
    VT_RUN(check_refuses_with_each_formats_message);
    VT_RUN(encoded_bound_counts_whole_blocks);
    VT_RUN(encode_and_decode_refuse_with_each_formats_message);
    return vt_test_main_result();
}
