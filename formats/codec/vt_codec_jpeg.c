/* JPEG tile payloads through the TurboJPEG 2.x API (libjpeg-turbo 2.1: tjCompress2/tjDecompress2,
 * no tj3*): 1 channel -> greyscale JPEG, 3 channels -> YCbCr JPEG of RGB texels; 8-bit samples
 * only; no alpha (check() says what to use instead). A payload is one complete baseline JFIF
 * stream.
 *
 * params->quality: 1..100, 0 = 85. params->subsampling: 420 (default), 422 or 444 chroma
 * subsampling for RGB (ignored for grey). TurboJPEG's defaults otherwise: standard Huffman tables,
 * the fast integer DCT to encode below quality 96 (the accurate one from 96), the accurate DCT to
 * decode.
 *
 * Decoding is strict: the header must give the tile's width and height and grey for a 1-channel
 * tile, colour for a 3-channel one. libjpeg's warnings are errors: on a truncated or corrupt
 * stream libjpeg only warns and fills the missing rows with grey, which must not pass for a tile.
 * TurboJPEG 2.1 returns -1 after a warning anyway; TJFLAG_STOPONWARNING makes it stop at the first
 * one instead of decoding the rest. Progressive streams are limited to 500 scans
 * (TJFLAG_LIMITSCANS). Bytes after the EOI marker are ignored, as libjpeg does.
 *
 * Each thread keeps one compress and one decompress handle (created on first use, destroyed by a
 * pthread key destructor when the thread exits), so a worker encodes tile after tile without
 * allocating. TurboJPEG's error text lives in the handle; it leaves this file as a vt_error. */
#include <limits.h>
#include <pthread.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <turbojpeg.h>

#include "internal/vt_codec_impl.h"
#include "vt_codec.h"
#include "vt_error.h"

#define JPG_DEFAULT_QUALITY 85
#define JPG_MAX_EDGE        65500 /* JPEG_MAX_DIMENSION of libjpeg */

/* ---- per-thread TurboJPEG handles ---- */

struct jpg_handles {
    tjhandle compress;
    tjhandle decompress;
};

static pthread_once_t jpg_key_once = PTHREAD_ONCE_INIT;
static pthread_key_t jpg_key;
static int jpg_key_error; /* written once, inside pthread_once */

static void jpg_handles_destroy(void *value)
{
    struct jpg_handles *handles = value;
    if (handles->compress)
        tjDestroy(handles->compress);
    if (handles->decompress)
        tjDestroy(handles->decompress);
    free(handles);
}

static void jpg_key_create(void)
{
    jpg_key_error = pthread_key_create(&jpg_key, jpg_handles_destroy);
}

/* The calling thread's handle (compress or decompress), created on first use; NULL when out of
 * memory (err filled). The handle belongs to the thread: never pass it to another one. */
static tjhandle jpg_thread_handle(bool compress, struct vts_error *err)
{
    pthread_once(&jpg_key_once, jpg_key_create);
    if (jpg_key_error) {
        vt_error_set(err, VTS_ERR_NOMEM, "jpeg codec: cannot create a thread key");
        return NULL;
    }
    struct jpg_handles *handles = pthread_getspecific(jpg_key);
    if (!handles) {
        handles = calloc(1, sizeof *handles);
        if (!handles || pthread_setspecific(jpg_key, handles) != 0) {
            free(handles);
            vt_error_set(err, VTS_ERR_NOMEM, "jpeg codec: out of memory");
            return NULL;
        }
    }
    tjhandle *slot = compress ? &handles->compress : &handles->decompress;
    if (!*slot)
        *slot = compress ? tjInitCompress() : tjInitDecompress();
    if (!*slot)
        vt_error_set(err, VTS_ERR_NOMEM, "jpeg codec: cannot create a TurboJPEG handle: %s",
                     tjGetErrorStr2(NULL));
    return *slot;
}

/* Destroys the calling thread's handle after TurboJPEG failed with it: libjpeg-turbo 2.1.5's
 * tjDecompressHeader3() returns from an error without aborting the decompressor, and the next
 * header read on that handle resumes mid-marker ("Bogus marker length") on a valid stream. A fresh
 * handle is cheap next to a corrupt tile being noticed. */
static void jpg_thread_handle_discard(bool compress)
{
    struct jpg_handles *handles = pthread_getspecific(jpg_key);
    tjhandle *slot = compress ? &handles->compress : &handles->decompress;
    tjDestroy(*slot);
    *slot = NULL;
}

/* Fills err with TurboJPEG's message for handle, then discards the handle; returns status. */
static int jpg_fail(bool compress, tjhandle handle, int status, const char *what,
                    struct vts_error *err)
{
    vt_error_set(err, status, "jpeg %s: %s", what, tjGetErrorStr2(handle));
    jpg_thread_handle_discard(compress);
    return status;
}

/* ---- shapes ---- */

static int jpg_check_channels_and_sample(uint32_t channels, uint32_t sample, struct vts_error *err)
{
    if (sample != VTS_SAMPLE_U8)
        return vt_error_set(err, VTS_ERR_UNSUPPORTED,
                            "jpeg stores 8-bit samples only (got %s); use png or raw",
                            vts_sample_name(sample));
    if (channels == 2 || channels == 4)
        return vt_error_set(
            err, VTS_ERR_UNSUPPORTED,
            "jpeg cannot store alpha: use png, bc3 or raw (vt-tiles drops an alpha that is opaque everywhere)");
    if (channels != 1 && channels != 3)
        return vt_error_set(err, VTS_ERR_UNSUPPORTED,
                            "jpeg codec: %u channels (1 grey or 3 RGB supported)", channels);
    return 0;
}

static size_t jpg_encoded_bound(uint32_t width, uint32_t height, uint32_t channels, uint32_t sample)
{
    if (sample != VTS_SAMPLE_U8 || (channels != 1 && channels != 3) || width == 0 || height == 0 ||
        width > JPG_MAX_EDGE || height > JPG_MAX_EDGE)
        return 0;
    if (channels == 1)
        return (size_t)tjBufSize((int)width, (int)height, TJSAMP_GRAY);
    /* the largest of the subsamplings an RGB tile may use (4:4:4 for most sizes, but 4:2:0 pads
     * to 16x16 MCUs: 2816 bytes for a 1x1 tile against 2432 for 4:4:4) */
    static const int subsamplings[] = {TJSAMP_420, TJSAMP_422, TJSAMP_444};
    size_t bound = 0;
    for (size_t i = 0; i < sizeof subsamplings / sizeof subsamplings[0]; i++) {
        unsigned long b = tjBufSize((int)width, (int)height, subsamplings[i]);
        if (b > bound)
            bound = (size_t)b;
    }
    return bound;
}

static int jpg_check(uint32_t tile_px, uint32_t channels, uint32_t sample, struct vts_error *err)
{
    int rc = jpg_check_channels_and_sample(channels, sample, err);
    if (rc < 0)
        return rc;
    if (tile_px == 0 || tile_px > JPG_MAX_EDGE)
        return vt_error_set(err, VTS_ERR_UNSUPPORTED,
                            "jpeg codec: tile edge %u outside JPEG's 1..%u", tile_px, JPG_MAX_EDGE);
    if (jpg_encoded_bound(tile_px, tile_px, channels, sample) > UINT32_MAX)
        return vt_error_set(err, VTS_ERR_UNSUPPORTED,
                            "jpeg codec: a %ux%u tile does not fit the 4 GiB payload limit",
                            tile_px, tile_px);
    return 0;
}

/* Checks that img is a tile JPEG can hold (also the range of TurboJPEG's int arguments). */
static int jpg_image_layout(const struct vt_image *img, const char *role, struct vts_error *err)
{
    int rc = jpg_check_channels_and_sample(img->channels, img->sample, err);
    if (rc < 0)
        return rc;
    if (!img->pixels || img->width == 0 || img->height == 0 || img->width > JPG_MAX_EDGE ||
        img->height > JPG_MAX_EDGE || img->stride < (size_t)img->width * img->channels ||
        img->stride > INT_MAX)
        return vt_error_set(err, VTS_ERR_ARG, "jpeg codec: invalid %s image %ux%u, stride %zu",
                            role, img->width, img->height, img->stride);
    return 0;
}

/* ---- encoding ---- */

/* TurboJPEG's subsampling for params (grey: TJSAMP_GRAY); -1 with err filled when invalid. */
static int jpg_subsampling(const struct vt_image *src, int subsampling, struct vts_error *err)
{
    if (src->channels == 1)
        return TJSAMP_GRAY;
    switch (subsampling) {
    case 0:
    case 420:
        return TJSAMP_420;
    case 422:
        return TJSAMP_422;
    case 444:
        return TJSAMP_444;
    default:
        vt_error_set(err, VTS_ERR_ARG, "jpeg codec: subsampling %d is not 420, 422 or 444",
                     subsampling);
        return -1;
    }
}

static int jpg_encode(const struct vt_image *src, const struct vt_codec_params *params, void *dst,
                      size_t dst_capacity, size_t *out_len, struct vts_error *err)
{
    *out_len = 0;
    int rc = jpg_image_layout(src, "source", err);
    if (rc < 0)
        return rc;
    int quality = params && params->quality ? params->quality : JPG_DEFAULT_QUALITY;
    if (quality < 1 || quality > 100)
        return vt_error_set(err, VTS_ERR_ARG, "jpeg codec: quality %d outside 1..100", quality);
    int subsamp = jpg_subsampling(src, params ? params->subsampling : 0, err);
    if (subsamp < 0)
        return VTS_ERR_ARG;
    /* With TJFLAG_NOREALLOC TurboJPEG assumes a buffer of tjBufSize() bytes: make sure it is. */
    unsigned long needed = tjBufSize((int)src->width, (int)src->height, subsamp);
    if (needed == (unsigned long)-1 || dst_capacity < needed)
        return vt_error_set(err, VTS_ERR_LIMIT, "jpeg encode: output buffer of %zu bytes < %lu",
                            dst_capacity, needed);
    tjhandle handle = jpg_thread_handle(true, err);
    if (!handle)
        return VTS_ERR_NOMEM;
    unsigned char *out = dst;
    unsigned long out_size = (unsigned long)dst_capacity;
    if (tjCompress2(handle, src->pixels, (int)src->width, (int)src->stride, (int)src->height,
                    src->channels == 1 ? TJPF_GRAY : TJPF_RGB, &out, &out_size, subsamp, quality,
                    TJFLAG_NOREALLOC) != 0)
        return jpg_fail(true, handle, VTS_ERR_ARG, "encode", err);
    *out_len = out_size;
    return 0;
}

/* ---- decoding ---- */

/* Compares the JPEG header with the tile dst. */
static int jpg_decode_match(int width, int height, int subsamp, int colourspace,
                            const struct vt_image *dst, struct vts_error *err)
{
    if ((uint32_t)width != dst->width)
        return vt_error_set(err, VTS_ERR_BAD_INPUT, "jpeg payload: width %d != tile %u", width,
                            dst->width);
    if ((uint32_t)height != dst->height)
        return vt_error_set(err, VTS_ERR_BAD_INPUT, "jpeg payload: height %d != tile %u", height,
                            dst->height);
    if (colourspace == TJCS_CMYK || colourspace == TJCS_YCCK)
        return vt_error_set(err, VTS_ERR_BAD_INPUT,
                            "jpeg payload: CMYK JPEG (tiles are grey or RGB)");
    bool grey = colourspace == TJCS_GRAY || subsamp == TJSAMP_GRAY;
    if (grey && dst->channels != 1)
        return vt_error_set(err, VTS_ERR_BAD_INPUT,
                            "jpeg payload: greyscale JPEG for a %u-channel tile", dst->channels);
    if (!grey && dst->channels != 3)
        return vt_error_set(err, VTS_ERR_BAD_INPUT,
                            "jpeg payload: colour JPEG for a greyscale tile");
    return 0;
}

static int jpg_decode(const void *src, size_t src_len, struct vt_image *dst, struct vts_error *err)
{
    int rc = jpg_image_layout(dst, "destination", err);
    if (rc < 0)
        return rc;
    const unsigned char *bytes = src;
    if (src_len < 4 || bytes[0] != 0xff || bytes[1] != 0xd8)
        return vt_error_set(err, VTS_ERR_BAD_INPUT, "jpeg payload: no SOI marker (%zu bytes)",
                            src_len);
    tjhandle handle = jpg_thread_handle(false, err);
    if (!handle)
        return VTS_ERR_NOMEM;
    int width, height, subsamp, colourspace;
    if (tjDecompressHeader3(handle, bytes, (unsigned long)src_len, &width, &height, &subsamp,
                            &colourspace) != 0)
        return jpg_fail(false, handle, VTS_ERR_BAD_INPUT, "payload", err);
    rc = jpg_decode_match(width, height, subsamp, colourspace, dst, err);
    if (rc < 0)
        return rc;
    if (tjDecompress2(handle, bytes, (unsigned long)src_len, dst->pixels, width, (int)dst->stride,
                      height, dst->channels == 1 ? TJPF_GRAY : TJPF_RGB,
                      TJFLAG_STOPONWARNING | TJFLAG_LIMITSCANS) != 0)
        return jpg_fail(false, handle, VTS_ERR_BAD_INPUT, "payload", err);
    return 0;
}

const struct vt_codec vt_codec_jpeg = {
    .name = "jpeg",
    .fourcc = VTS_CODEC_JPEG,
    .summary = "JPEG (TurboJPEG), grey or RGB, 8-bit; quality 1..100 (85), 4:2:0 or 4:4:4",
    .lossless = false,
    .check = jpg_check,
    .encoded_bound = jpg_encoded_bound,
    .encode = jpg_encode,
    .decode = jpg_decode,
};
