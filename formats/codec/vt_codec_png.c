/* PNG tile payloads through libpng, encoded to and decoded from memory. 1..4 channels (gray,
 * gray+alpha, RGB, RGBA), u8 or u16 samples; 16-bit samples are big-endian inside the PNG and in
 * host order in a vt_image. libpng's setjmp/longjmp stays in this file. The functions that call
 * setjmp (png_*_run) change no local of their own after it: the work happens in a callee
 * (png_*_body) whose frame the longjmp discards, on objects the caller owns, so no local is left
 * indeterminate (C11 7.13.2.1).
 *
 * params->effort: 1..9 is the zlib level, 0 the default (2: fast, tiles are small). Levels 1..3 use
 * the SUB filter on every row (fast: ~30 MP/s at level 1); levels 4..9 let libpng pick a filter per
 * row. */
#include <png.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "internal/vt_codec_impl.h"
#include "vt_checked.h"
#include "vt_codec.h"
#include "vt_error.h"

#define PNG_DEFAULT_LEVEL  2
#define PNG_FAST_MAX_LEVEL 3
#define PNG_MAX_EDGE       0x7fffffffu /* PNG_UINT_31_MAX */

/* State shared with the libpng callbacks (through the io and error pointers). */
struct png_mem_ctx {
    const char *what;   /* "encode" or "payload", for messages */
    int default_status; /* status of an error libpng raises itself */
    unsigned char *dst; /* encode: output buffer */
    size_t dst_capacity;
    size_t dst_len;
    const unsigned char *src; /* decode: input payload */
    size_t src_len;
    size_t src_pos;
    int status; /* status to return once libpng stops (0: the default of the operation) */
    char message[VTS_ERROR_MESSAGE_MAX]; /* first error, already worded for the user */
};

#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
static int
png_ctx_fail(struct png_mem_ctx *ctx, int status, const char *fmt, ...)
{
    if (ctx->message[0] == '\0') {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(ctx->message, sizeof ctx->message, fmt, ap);
        va_end(ap);
        ctx->status = status;
    }
    return ctx->status;
}

static void png_mem_error(png_structp png, png_const_charp msg)
{
    struct png_mem_ctx *ctx = png_get_error_ptr(png);
    int status = strstr(msg, "memory") ? VTS_ERR_NOMEM : ctx->default_status;
    png_ctx_fail(ctx, status, "png %s: %s", ctx->what, msg);
    png_longjmp(png, 1);
}

static void png_mem_warning(png_structp png, png_const_charp msg)
{
    (void)png; /* warnings are about ancillary data we do not use */
    (void)msg;
}

static void png_mem_write(png_structp png, png_bytep data, size_t length)
{
    struct png_mem_ctx *ctx = png_get_io_ptr(png);
    if (length > ctx->dst_capacity - ctx->dst_len) {
        png_ctx_fail(ctx, VTS_ERR_LIMIT, "png encode: output exceeds the %zu-byte buffer",
                     ctx->dst_capacity);
        png_error(png, "output buffer full");
    }
    memcpy(ctx->dst + ctx->dst_len, data, length);
    ctx->dst_len += length;
}

static void png_mem_flush(png_structp png)
{
    (void)png;
}

static void png_mem_read(png_structp png, png_bytep data, size_t length)
{
    struct png_mem_ctx *ctx = png_get_io_ptr(png);
    if (length > ctx->src_len - ctx->src_pos) {
        png_ctx_fail(ctx, VTS_ERR_BAD_INPUT, "png payload: truncated at byte %zu", ctx->src_len);
        png_error(png, "truncated");
    }
    memcpy(data, ctx->src + ctx->src_pos, length);
    ctx->src_pos += length;
}

static int png_colour_type(uint32_t channels)
{
    static const int types[] = {PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB,
                                PNG_COLOR_TYPE_RGB_ALPHA};
    return types[channels - 1];
}

/* Row bytes of an image PNG can hold; VTS_ERR_UNSUPPORTED / VTS_ERR_ARG otherwise. */
static int png_image_layout(const struct vt_image *img, const char *role, size_t *row_bytes,
                            struct vts_error *err)
{
    if (img->sample != VTS_SAMPLE_U8 && img->sample != VTS_SAMPLE_U16)
        return vt_error_set(err, VTS_ERR_UNSUPPORTED,
                            "png codec: %s samples are not supported (8 or 16-bit only); use raw",
                            vts_sample_name(img->sample));
    if (!img->pixels || img->channels < 1 || img->channels > 4 || img->width == 0 ||
        img->height == 0 || img->width > PNG_MAX_EDGE || img->height > PNG_MAX_EDGE ||
        !vt_size_mul3(img->width, img->channels, vts_sample_bytes(img->sample), row_bytes))
        return vt_error_set(err, VTS_ERR_ARG, "png codec: invalid %s image %ux%u, %u channels",
                            role, img->width, img->height, img->channels);
    if (img->stride < *row_bytes)
        return vt_error_set(err, VTS_ERR_ARG, "png codec: %s stride %zu < row size %zu", role,
                            img->stride, *row_bytes);
    return 0;
}

static size_t png_encoded_bound(uint32_t width, uint32_t height, uint32_t channels, uint32_t sample)
{
    size_t row_bytes, filtered, deflated, chunks, total;
    if (width == 0 || height == 0 || width > PNG_MAX_EDGE || height > PNG_MAX_EDGE ||
        channels < 1 || channels > 4 || (sample != VTS_SAMPLE_U8 && sample != VTS_SAMPLE_U16))
        return 0;
    /* One filter byte per row; zlib's conservative bound for any window size is below
     * n + n/8 + n/64 + 64; libpng cuts IDAT chunks (12 bytes of framing) at 8 KiB; signature,
     * IHDR and IEND take 45 bytes. */
    if (!vt_size_mul3(width, channels, vts_sample_bytes(sample), &row_bytes) ||
        !vt_size_add(row_bytes, 1, &row_bytes) || !vt_size_mul(row_bytes, height, &filtered) ||
        !vt_size_add(filtered, filtered / 8 + filtered / 64 + 64, &deflated) ||
        !vt_size_mul(deflated / 1024 + 1, 12, &chunks) ||
        !vt_size_add(deflated, chunks + 256, &total))
        return 0;
    return total;
}

static int png_check(uint32_t tile_px, uint32_t channels, uint32_t sample, struct vts_error *err)
{
    if (channels < 1 || channels > 4)
        return vt_error_set(err, VTS_ERR_UNSUPPORTED, "png codec: %u channels (1 to 4 supported)",
                            channels);
    if (sample == VTS_SAMPLE_F16 || sample == VTS_SAMPLE_F32)
        return vt_error_set(err, VTS_ERR_UNSUPPORTED,
                            "png codec: %s samples are not supported (8 or 16-bit only); use raw",
                            vts_sample_name(sample));
    if (sample != VTS_SAMPLE_U8 && sample != VTS_SAMPLE_U16)
        return vt_error_set(err, VTS_ERR_UNSUPPORTED, "png codec: unknown sample type %u", sample);
    size_t bound = png_encoded_bound(tile_px, tile_px, channels, sample);
    if (bound == 0 || bound > UINT32_MAX)
        return vt_error_set(err, VTS_ERR_UNSUPPORTED,
                            "png codec: a %ux%u tile does not fit the 4 GiB payload limit", tile_px,
                            tile_px);
    return 0;
}

/* The encoding itself; a libpng error longjmps out of it to png_encode_run(). */
static void png_encode_body(png_structp png, png_infop info, const struct vt_image *src, int level,
                            struct png_mem_ctx *ctx)
{
    png_set_write_fn(png, ctx, png_mem_write, png_mem_flush);
    png_set_user_limits(png, PNG_MAX_EDGE, PNG_MAX_EDGE);
    png_set_compression_level(png, level);
    png_set_filter(png, PNG_FILTER_TYPE_BASE,
                   level <= PNG_FAST_MAX_LEVEL ? PNG_FILTER_SUB : PNG_ALL_FILTERS);
    int bit_depth = src->sample == VTS_SAMPLE_U16 ? 16 : 8;
    png_set_IHDR(png, info, src->width, src->height, bit_depth, png_colour_type(src->channels),
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_BASE, PNG_FILTER_TYPE_BASE);
    png_write_info(png, info);
    if (bit_depth == 16 && vt_host_is_little_endian())
        png_set_swap(png);
    for (uint32_t y = 0; y < src->height; y++)
        png_write_row(png, (const unsigned char *)src->pixels + (size_t)y * src->stride);
    png_write_end(png, NULL);
}

static int png_encode_run(png_structp png, png_infop info, const struct vt_image *src, int level,
                          struct png_mem_ctx *ctx)
{
    if (setjmp(png_jmpbuf(png)))
        return ctx->status ? ctx->status : ctx->default_status;
    png_encode_body(png, info, src, level, ctx);
    return 0;
}

static int png_encode(const struct vt_image *src, const struct vt_codec_params *params, void *dst,
                      size_t dst_capacity, size_t *out_len, struct vts_error *err)
{
    size_t row_bytes;
    *out_len = 0;
    int rc = png_image_layout(src, "source", &row_bytes, err);
    if (rc < 0)
        return rc;
    int effort = params ? params->effort : 0;
    if (effort < 0 || effort > 9)
        return vt_error_set(err, VTS_ERR_ARG, "png codec: effort %d outside 0..9", effort);
    struct png_mem_ctx ctx = {
        .what = "encode", .default_status = VTS_ERR_ARG, .dst = dst, .dst_capacity = dst_capacity};
    png_structp png =
        png_create_write_struct(PNG_LIBPNG_VER_STRING, &ctx, png_mem_error, png_mem_warning);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    if (!info) {
        png_destroy_write_struct(&png, NULL);
        return vt_error_set(err, VTS_ERR_NOMEM, "png encode: out of memory");
    }
    rc = png_encode_run(png, info, src, effort ? effort : PNG_DEFAULT_LEVEL, &ctx);
    png_destroy_write_struct(&png, &info);
    if (rc < 0)
        return vt_error_set(err, rc, "%s", ctx.message);
    *out_len = ctx.dst_len;
    return 0;
}

/* Compares the PNG's header with the tile dst; fills ctx's message on a mismatch. */
static int png_decode_match(png_structp png, png_infop info, const struct vt_image *dst,
                            struct png_mem_ctx *ctx)
{
    png_uint_32 width, height;
    int bit_depth, colour_type;
    png_get_IHDR(png, info, &width, &height, &bit_depth, &colour_type, NULL, NULL, NULL);
    if (width != dst->width)
        return png_ctx_fail(ctx, VTS_ERR_BAD_INPUT, "png payload: width %u != tile %u",
                            (unsigned)width, dst->width);
    if (height != dst->height)
        return png_ctx_fail(ctx, VTS_ERR_BAD_INPUT, "png payload: height %u != tile %u",
                            (unsigned)height, dst->height);
    if (colour_type == PNG_COLOR_TYPE_PALETTE)
        return png_ctx_fail(ctx, VTS_ERR_BAD_INPUT,
                            "png payload: palette image (tiles are gray, gray+alpha, RGB or RGBA)");
    unsigned channels = png_get_channels(png, info);
    if (channels != dst->channels)
        return png_ctx_fail(ctx, VTS_ERR_BAD_INPUT, "png payload: %u channels != tile %u", channels,
                            dst->channels);
    unsigned tile_depth = dst->sample == VTS_SAMPLE_U16 ? 16 : 8;
    if ((unsigned)bit_depth != tile_depth)
        return png_ctx_fail(ctx, VTS_ERR_BAD_INPUT, "png payload: bit depth %d != tile %u",
                            bit_depth, tile_depth);
    if (png_get_valid(png, info, PNG_INFO_tRNS))
        return png_ctx_fail(
            ctx, VTS_ERR_BAD_INPUT,
            "png payload: tRNS transparency chunk (tiles carry alpha as a channel)");
    return 0;
}

/* The decoding itself; a libpng error longjmps out of it to png_decode_run(). */
static int png_decode_body(png_structp png, png_infop info, struct vt_image *dst, size_t row_bytes,
                           struct png_mem_ctx *ctx)
{
    png_set_read_fn(png, ctx, png_mem_read);
    png_set_benign_errors(png, 0); /* strict: errors stay errors */
    png_set_keep_unknown_chunks(png, PNG_HANDLE_CHUNK_NEVER, NULL, -1); /* skip ancillary chunks */
    png_set_user_limits(png, PNG_MAX_EDGE, PNG_MAX_EDGE); /* we compare with the tile ourselves */
    png_read_info(png, info);
    int rc = png_decode_match(png, info, dst, ctx);
    if (rc < 0)
        return rc;
    if (dst->sample == VTS_SAMPLE_U16 && vt_host_is_little_endian())
        png_set_swap(png);
    int passes = png_set_interlace_handling(png);
    png_read_update_info(png, info);
    if (png_get_rowbytes(png, info) != row_bytes)
        return png_ctx_fail(ctx, VTS_ERR_BAD_INPUT, "png payload: row of %zu bytes != tile %zu",
                            (size_t)png_get_rowbytes(png, info), row_bytes);
    for (int pass = 0; pass < passes; pass++)
        for (uint32_t y = 0; y < dst->height; y++)
            png_read_row(png, (unsigned char *)dst->pixels + (size_t)y * dst->stride, NULL);
    png_read_end(png, NULL);
    if (ctx->src_pos != ctx->src_len)
        return png_ctx_fail(ctx, VTS_ERR_BAD_INPUT, "png payload: %zu bytes after IEND",
                            ctx->src_len - ctx->src_pos);
    return 0;
}

static int png_decode_run(png_structp png, png_infop info, struct vt_image *dst, size_t row_bytes,
                          struct png_mem_ctx *ctx)
{
    if (setjmp(png_jmpbuf(png)))
        return ctx->status ? ctx->status : ctx->default_status;
    return png_decode_body(png, info, dst, row_bytes, ctx);
}

static int png_decode(const void *src, size_t src_len, struct vt_image *dst, struct vts_error *err)
{
    size_t row_bytes;
    int rc = png_image_layout(dst, "destination", &row_bytes, err);
    if (rc < 0)
        return rc;
    if (src_len < 8 || png_sig_cmp(src, 0, 8) != 0)
        return vt_error_set(err, VTS_ERR_BAD_INPUT, "png payload: no PNG signature (%zu bytes)",
                            src_len);
    struct png_mem_ctx ctx = {
        .what = "payload", .default_status = VTS_ERR_BAD_INPUT, .src = src, .src_len = src_len};
    png_structp png =
        png_create_read_struct(PNG_LIBPNG_VER_STRING, &ctx, png_mem_error, png_mem_warning);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    if (!info) {
        png_destroy_read_struct(&png, NULL, NULL);
        return vt_error_set(err, VTS_ERR_NOMEM, "png payload: out of memory");
    }
    rc = png_decode_run(png, info, dst, row_bytes, &ctx);
    png_destroy_read_struct(&png, &info, NULL);
    if (rc < 0)
        return vt_error_set(err, rc, "%s", ctx.message);
    return 0;
}

const struct vt_codec vt_codec_png = {
    .name = "png",
    .fourcc = VTS_CODEC_PNG,
    .summary = "PNG (zlib), 8 or 16-bit, 1 to 4 channels (exact); effort 1..9 = zlib level",
    .lossless = true,
    .check = png_check,
    .encoded_bound = png_encoded_bound,
    .encode = png_encode,
    .decode = png_decode,
};
