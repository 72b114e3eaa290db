/* PNG tile payloads, 1..4 channels (gray, gray+alpha, RGB, RGBA), u8 or u16 samples; 16-bit
 * samples are big-endian inside the PNG and in host order in a vt_image.
 *
 * Encoding writes the PNG container itself (signature, IHDR, IDAT, IEND; PNG spec 1.2 / ISO 15948)
 * around libdeflate's zlib stream: the rows are filtered into one buffer and deflated in one call,
 * several times faster than libpng -> zlib at a smaller size (docs/codecs.md#png has the table).
 * Each thread keeps its compressors and filter buffer (png_thread_scratch).
 * params->effort: 1..9 is libdeflate's level (its 10..12 are far slower for a few % less) and
 * picks the filter: 1..3 UP on every row (fast), 4..9 a filter per row by the PNG spec's
 * minimum-sum-of-absolute-differences heuristic; 0 is the default, 1.
 *
 * Decoding goes through libpng; its setjmp/longjmp stays in this file. The functions that call
 * setjmp (png_*_run) change no local of their own after it: the work happens in a callee
 * (png_*_body) whose frame the longjmp discards, on objects the caller owns, so no local is left
 * indeterminate (C11 7.13.2.1). */
#include <libdeflate.h>
#include <png.h>
#include <pthread.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "internal/vt_codec_impl.h"
#include "vt_checked.h"
#include "vt_codec.h"
#include "vt_error.h"

#define PNG_DEFAULT_EFFORT  1
#define PNG_FAST_MAX_EFFORT 3
#define PNG_MAX_EDGE        0x7fffffffu        /* PNG_UINT_31_MAX */
#define PNG_IDAT_MAX        ((size_t)1 << 18)  /* zlib stream bytes per IDAT chunk */
#define PNG_HEAD_BYTES      41                 /* signature, IHDR, first IDAT's length and type */
#define PNG_SCRATCH_KEEP    ((size_t)16 << 20) /* larger filter buffers are freed after use */

/* State shared with the libpng callbacks (through the io and error pointers). */
struct png_mem_ctx {
    const char *what;         /* "payload", for messages */
    int default_status;       /* status of an error libpng raises itself */
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
    size_t row_bytes, filtered, chunks, total;
    if (width == 0 || height == 0 || width > PNG_MAX_EDGE || height > PNG_MAX_EDGE ||
        channels < 1 || channels > 4 || (sample != VTS_SAMPLE_U8 && sample != VTS_SAMPLE_U16))
        return 0;
    /* One filter byte per row; libdeflate's bound for any compressor; IDAT chunks of
     * PNG_IDAT_MAX bytes with 12 bytes of framing each; signature, IHDR and IEND: 45 bytes. */
    if (!vt_size_mul3(width, channels, vts_sample_bytes(sample), &row_bytes) ||
        !vt_size_add(row_bytes, 1, &row_bytes) || !vt_size_mul(row_bytes, height, &filtered))
        return 0;
    size_t deflated = libdeflate_zlib_compress_bound(NULL, filtered);
    if (deflated < filtered || !vt_size_mul(deflated / PNG_IDAT_MAX + 1, 12, &chunks) ||
        !vt_size_add(deflated, chunks + 45, &total))
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

/* ---- encoding: per-thread scratch ---- */

/* What one thread keeps between encodes: a compressor per effort (made on first use) and the
 * buffer the filtered rows go to (kept up to PNG_SCRATCH_KEEP bytes). */
struct png_scratch {
    struct libdeflate_compressor *deflate[10];
    unsigned char *buf;
    size_t capacity;
};

static pthread_once_t png_key_once = PTHREAD_ONCE_INIT;
static pthread_key_t png_key;
static int png_key_error; /* written once, inside pthread_once */

static void png_scratch_destroy(void *value)
{
    struct png_scratch *s = value;
    for (size_t i = 0; i < sizeof s->deflate / sizeof s->deflate[0]; i++)
        libdeflate_free_compressor(s->deflate[i]);
    free(s->buf);
    free(s);
}

static void png_key_create(void)
{
    png_key_error = pthread_key_create(&png_key, png_scratch_destroy);
}

/* The calling thread's scratch, with the compressor of effort (1..9) and a buffer of at least
 * bytes; NULL when out of memory (err filled). Belongs to the thread. */
static struct png_scratch *png_thread_scratch(int effort, size_t bytes, struct vts_error *err)
{
    pthread_once(&png_key_once, png_key_create);
    if (png_key_error) {
        vt_error_set(err, VTS_ERR_NOMEM, "png encode: cannot create a thread key");
        return NULL;
    }
    struct png_scratch *s = pthread_getspecific(png_key);
    if (!s) {
        s = calloc(1, sizeof *s);
        if (!s || pthread_setspecific(png_key, s) != 0) {
            free(s);
            vt_error_set(err, VTS_ERR_NOMEM, "png encode: out of memory");
            return NULL;
        }
    }
    if (!s->deflate[effort])
        s->deflate[effort] = libdeflate_alloc_compressor(effort);
    if (s->capacity < bytes) {
        free(s->buf);
        s->capacity = 0;
        if ((s->buf = malloc(bytes)) != NULL)
            s->capacity = bytes;
    }
    if (!s->deflate[effort] || !s->buf) {
        vt_error_set(err, VTS_ERR_NOMEM, "png encode: out of memory");
        return NULL;
    }
    return s;
}

/* Frees a buffer too big to keep (a huge tile's) once the encode is done. */
static void png_scratch_trim(struct png_scratch *s)
{
    if (s->capacity > PNG_SCRATCH_KEEP) {
        free(s->buf);
        s->buf = NULL;
        s->capacity = 0;
    }
}

/* ---- encoding: filters (PNG spec 1.2 section 6) ---- */

enum { PNG_F_NONE, PNG_F_SUB, PNG_F_UP, PNG_F_AVG, PNG_F_PAETH, PNG_F_COUNT };

static unsigned png_paeth(unsigned a, unsigned b, unsigned c)
{
    int p = (int)a + (int)b - (int)c;
    int pa = abs(p - (int)a), pb = abs(p - (int)b), pc = abs(p - (int)c);
    return pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
}

/* Writes the filter byte f and row filtered with it into out (n + 1 bytes); prev is the row above
 * (all zero for the first row); bpp bytes per pixel. */
static void png_filter_row(int f, const unsigned char *restrict row,
                           const unsigned char *restrict prev, size_t n, size_t bpp,
                           unsigned char *restrict out)
{
    *out++ = (unsigned char)f;
    size_t i = 0;
    switch (f) {
    case PNG_F_NONE:
        memcpy(out, row, n);
        break;
    case PNG_F_SUB:
        memcpy(out, row, bpp);
        for (i = bpp; i < n; i++)
            out[i] = (unsigned char)(row[i] - row[i - bpp]);
        break;
    case PNG_F_UP:
        for (; i < n; i++)
            out[i] = (unsigned char)(row[i] - prev[i]);
        break;
    case PNG_F_AVG:
        for (; i < bpp; i++)
            out[i] = (unsigned char)(row[i] - (prev[i] >> 1));
        for (; i < n; i++)
            out[i] = (unsigned char)(row[i] - ((row[i - bpp] + prev[i]) >> 1));
        break;
    default:
        for (; i < bpp; i++)
            out[i] = (unsigned char)(row[i] - prev[i]);
        for (; i < n; i++)
            out[i] = (unsigned char)(row[i] - png_paeth(row[i - bpp], prev[i], prev[i - bpp]));
        break;
    }
}

/* Sum of the filtered bytes as signed magnitudes: the PNG spec's filter choice heuristic. */
static uint64_t png_row_cost(const unsigned char *filtered, size_t n)
{
    uint64_t sum = 0;
    for (size_t i = 0; i < n; i++)
        sum += (uint64_t)abs((int)(signed char)filtered[i]);
    return sum;
}

/* Filters every row of src into out (height x (row_bytes + 1) bytes). rows is scratch for two
 * big-endian copies of 16-bit rows (2 x row_bytes) and cand for the adaptive choice's candidates
 * (PNG_F_COUNT x (row_bytes + 1)). */
static void png_filter_image(const struct vt_image *src, size_t row_bytes, bool adaptive,
                             unsigned char *out, unsigned char *rows, unsigned char *cand)
{
    size_t bpp = (size_t)src->channels * vts_sample_bytes(src->sample);
    bool swap = src->sample == VTS_SAMPLE_U16 && vt_host_is_little_endian();
    memset(rows, 0, row_bytes); /* the row above the first */
    const unsigned char *prev = rows;
    for (uint32_t y = 0; y < src->height; y++) {
        const unsigned char *row = (const unsigned char *)src->pixels + (size_t)y * src->stride;
        if (swap) {
            unsigned char *be = rows + (y % 2 ? 0 : row_bytes);
            for (size_t i = 0; i < row_bytes; i += 2) {
                be[i] = row[i + 1];
                be[i + 1] = row[i];
            }
            row = be;
        }
        unsigned char *o = out + (size_t)y * (row_bytes + 1);
        if (!adaptive) {
            png_filter_row(PNG_F_UP, row, prev, row_bytes, bpp, o);
        } else {
            int best = 0;
            uint64_t best_cost = UINT64_MAX;
            for (int f = 0; f < PNG_F_COUNT; f++) {
                unsigned char *c = cand + (size_t)f * (row_bytes + 1);
                png_filter_row(f, row, prev, row_bytes, bpp, c);
                uint64_t cost = png_row_cost(c + 1, row_bytes);
                if (cost < best_cost) {
                    best = f;
                    best_cost = cost;
                }
            }
            memcpy(o, cand + (size_t)best * (row_bytes + 1), row_bytes + 1);
        }
        prev = row;
    }
}

/* ---- encoding: the container ---- */

static void png_put_u32(unsigned char *p, uint32_t v)
{
    p[0] = (unsigned char)(v >> 24);
    p[1] = (unsigned char)(v >> 16);
    p[2] = (unsigned char)(v >> 8);
    p[3] = (unsigned char)v;
}

/* Writes a chunk's length and type before data (at p + 8) and its CRC after it. */
static void png_put_chunk(unsigned char *p, const char type[4], size_t len)
{
    png_put_u32(p, (uint32_t)len);
    memcpy(p + 4, type, 4);
    png_put_u32(p + 8 + len, (uint32_t)libdeflate_crc32(0, p + 4, len + 4));
}

/* Signature and IHDR (33 bytes). */
static void png_put_header(unsigned char *p, const struct vt_image *src)
{
    static const unsigned char sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    memcpy(p, sig, 8);
    unsigned char *d = p + 16;
    png_put_u32(d, src->width);
    png_put_u32(d + 4, src->height);
    d[8] = src->sample == VTS_SAMPLE_U16 ? 16 : 8;
    d[9] = (unsigned char)png_colour_type(src->channels);
    d[10] = d[11] = d[12] = 0; /* deflate, adaptive filtering, not interlaced */
    png_put_chunk(p + 8, "IHDR", 13);
}

/* The zlib stream (z bytes at dst + PNG_HEAD_BYTES) cut into IDAT chunks of PNG_IDAT_MAX bytes,
 * then IEND; returns the PNG's size, or 0 when it does not fit dst_capacity. */
static size_t png_put_idat(unsigned char *dst, size_t dst_capacity, size_t z)
{
    size_t k = (z + PNG_IDAT_MAX - 1) / PNG_IDAT_MAX, total = 33 + z + 12 * k + 12;
    if (total > dst_capacity)
        return 0;
    for (size_t i = k; i-- > 1;) /* later pieces move right by 12 bytes per chunk before them */
        memmove(dst + PNG_HEAD_BYTES + i * (PNG_IDAT_MAX + 12),
                dst + PNG_HEAD_BYTES + i * PNG_IDAT_MAX,
                i + 1 < k ? PNG_IDAT_MAX : z - i * PNG_IDAT_MAX);
    for (size_t i = 0; i < k; i++)
        png_put_chunk(dst + 33 + i * (PNG_IDAT_MAX + 12), "IDAT",
                      i + 1 < k ? PNG_IDAT_MAX : z - i * PNG_IDAT_MAX);
    png_put_chunk(dst + total - 12, "IEND", 0);
    return total;
}

static int png_encode(const struct vt_image *src, const struct vt_codec_params *params, void *dst,
                      size_t dst_capacity, size_t *out_len, struct vts_error *err)
{
    size_t row_bytes = 0, filtered, scratch;
    *out_len = 0;
    int rc = png_image_layout(src, "source", &row_bytes, err);
    if (rc < 0)
        return rc;
    int effort = params ? params->effort : 0;
    if (effort < 0 || effort > 9)
        return vt_error_set(err, VTS_ERR_ARG, "png codec: effort %d outside 0..9", effort);
    effort = effort ? effort : PNG_DEFAULT_EFFORT;
    if (!vt_size_mul(row_bytes + 1, src->height, &filtered) ||
        !vt_size_mul(row_bytes + 1, 2 + PNG_F_COUNT, &scratch) ||
        !vt_size_add(filtered, scratch, &scratch))
        return vt_error_set(err, VTS_ERR_LIMIT, "png encode: %ux%u image too large", src->width,
                            src->height);
    struct png_scratch *s = png_thread_scratch(effort, scratch, err);
    if (!s)
        return VTS_ERR_NOMEM;
    unsigned char *rows = s->buf + filtered;
    png_filter_image(src, row_bytes, effort > PNG_FAST_MAX_EFFORT, s->buf, rows,
                     rows + 2 * (row_bytes + 1));
    size_t z = 0, total = 0;
    if (dst_capacity > PNG_HEAD_BYTES + 16)
        z = libdeflate_zlib_compress(s->deflate[effort], s->buf, filtered,
                                     (unsigned char *)dst + PNG_HEAD_BYTES,
                                     dst_capacity - PNG_HEAD_BYTES - 16);
    png_scratch_trim(s);
    if (z)
        total = png_put_idat(dst, dst_capacity, z);
    if (!total)
        return vt_error_set(err, VTS_ERR_LIMIT, "png encode: output exceeds the %zu-byte buffer",
                            dst_capacity);
    png_put_header(dst, src);
    *out_len = total;
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
    size_t row_bytes = 0;
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
    .summary = "PNG (deflate), 8 or 16-bit, 1 to 4 channels (exact); effort 1..9 = deflate level",
    .lossless = true,
    .check = png_check,
    .encoded_bound = png_encoded_bound,
    .encode = png_encode,
    .decode = png_decode,
};
