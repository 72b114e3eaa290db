/* TIFF and BigTIFF input through libtiff 4.5. The image is read in "chunks": tiles (random
 * access), strips (TIFFReadEncodedStrip; the last strip of each plane is kept decoded so that bands
 * crossing a strip boundary decode it once), or single rows (TIFFReadScanline) when a strip is too
 * big to decode at once. Both planar configurations; 1/2/4-bit grey is scaled to 8 bits, palettes
 * become RGB, MINISWHITE is inverted, YCbCr JPEG-in-TIFF is converted to RGB by libtiff. The first
 * image directory is read; the Orientation tag is ignored (texels come in stored order).
 * libtiff's messages go to the source's own handler (TIFFOpenOptions), never to stderr. libtiff
 * reads through this file's procedures (TIFFClientOpenExt), so that a failed read() is reported
 * with its reason ("Input/output error") as VTS_ERR_IO, not as libtiff's "Read error at scanline
 * 160; got -1 bytes" or "IO error during reading of ..." as a corrupt file. */
#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <tiffio.h>
#include <unistd.h>

#include "internal/vt_input_readers.h"
#include "internal/vt_input_util.h"
#include "vt_checked.h"
#include "vt_error.h"

enum tiff_layout { TIFF_TILES, TIFF_STRIPS, TIFF_SCANLINES };

/* How stored samples become output samples. */
enum tiff_convert {
    TIFF_COPY,    /* 8/16/32-bit samples as stored */
    TIFF_BITS,    /* 1/2/4-bit grey scaled to 8 bits */
    TIFF_PALETTE, /* 1..8-bit indices to RGB */
};

struct tiff_input {
    TIFF *tif;
    int fd;         /* the file libtiff reads through tiff_io_*; -1 when closed */
    int read_errno; /* errno of the first failed read, 0 if none */
    char name[256];
    char message[160]; /* the last error libtiff reported */
    uint32_t width, height;
    uint32_t channels; /* output channels */
    uint32_t bps;      /* stored bits per sample */
    uint32_t sample_bytes;
    enum tiff_layout layout;
    enum tiff_convert convert;
    bool separate; /* PLANARCONFIG_SEPARATE: one plane per channel */
    bool min_is_white;
    uint32_t chunk_w, chunk_h; /* tile size, or full width x rows per strip (1 for scanlines) */
    size_t chunk_bytes;        /* bytes of one decoded chunk of one plane */
    size_t row_bytes;          /* bytes of one row of a chunk of one plane */
    unsigned char *chunk[4];   /* per plane: the last decoded chunk */
    uint64_t cached[4];        /* per plane: 1 + index of the chunk held in chunk[], 0 = none */
    uint8_t palette[256][3];
};

static int tiff_on_error(TIFF *tif, void *user_data, const char *module, const char *fmt,
                         va_list ap) __attribute__((format(printf, 4, 0)));

static int tiff_on_error(TIFF *tif, void *user_data, const char *module, const char *fmt,
                         va_list ap)
{
    (void)tif;
    (void)module;
    struct tiff_input *t = user_data;
    vsnprintf(t->message, sizeof t->message, fmt, ap);
    for (char *p = t->message; *p; p++) /* messages stay one line */
        if (*p == '\n' || *p == '\r')
            *p = ' ';
    return 1; /* handled: libtiff must not print */
}

static int tiff_on_warning(TIFF *tif, void *user_data, const char *module, const char *fmt,
                           va_list ap)
{
    (void)tif, (void)user_data, (void)module, (void)fmt, (void)ap;
    return 1; /* warnings concern tags we do not use or are followed by an error */
}

/* Why libtiff failed: a failed read of the file (its errno), else libtiff's last message. */
static const char *tiff_message(const struct tiff_input *t)
{
    if (t->read_errno)
        return strerror(t->read_errno);
    return t->message[0] ? t->message : "corrupt data";
}

static int tiff_status(const struct tiff_input *t)
{
    return t->read_errno ? VTS_ERR_IO : VTS_ERR_BAD_INPUT;
}

/* ---- libtiff's I/O on t->fd ---- */

/* A failed read returns the bytes read so far, never -1: libtiff 4.5's TIFFReadAndRealloc adds
 * the result to its offset and clears the rest of its buffer from there (a write one byte before
 * the buffer after -1, seen by ASan in tool_eio.sh). A short read fails the same way, and
 * read_errno says why. */
static tmsize_t tiff_io_read(thandle_t h, void *buf, tmsize_t size)
{
    struct tiff_input *t = h;
    size_t done = 0;
    while (done < (size_t)size) {
        ssize_t n = read(t->fd, (char *)buf + done, (size_t)size - done);
        if (n < 0 && errno == EINTR)
            continue;
        if (n < 0 && !t->read_errno)
            t->read_errno = errno;
        if (n <= 0)
            break; /* an error, or the end of the file: libtiff reports the short read */
        done += (size_t)n;
    }
    return (tmsize_t)done;
}

static tmsize_t tiff_io_write(thandle_t h, void *buf, tmsize_t size)
{
    (void)h, (void)buf, (void)size;
    errno = EBADF; /* opened for reading */
    return -1;
}

static toff_t tiff_io_seek(thandle_t h, toff_t off, int whence)
{
    struct tiff_input *t = h;
    return (toff_t)lseek(t->fd, (off_t)off, whence);
}

static int tiff_io_close(thandle_t h)
{
    (void)h; /* tiff_close() closes t->fd */
    return 0;
}

static toff_t tiff_io_size(thandle_t h)
{
    struct tiff_input *t = h;
    struct stat st;
    return fstat(t->fd, &st) == 0 ? (toff_t)st.st_size : 0;
}

static int tiff_io_map(thandle_t h, void **base, toff_t *size)
{
    (void)h, (void)base, (void)size;
    return 0; /* never mapped (mode "m") */
}

static void tiff_io_unmap(thandle_t h, void *base, toff_t size)
{
    (void)h, (void)base, (void)size;
}

static void tiff_close(void *ctx)
{
    struct tiff_input *t = ctx;
    if (!t)
        return;
    if (t->tif)
        TIFFClose(t->tif);
    if (t->fd >= 0)
        close(t->fd);
    for (int i = 0; i < 4; i++)
        free(t->chunk[i]);
    free(t);
}

/* ---- header ---- */

static uint16_t tiff_get16(TIFF *tif, ttag_t tag, uint16_t fallback)
{
    uint16_t v;
    return TIFFGetField(tif, tag, &v) ? v : fallback;
}

/* Reads the colormap; old writers store 8-bit values, the standard says 16-bit. */
static void tiff_load_palette(struct tiff_input *t, const uint16_t *r, const uint16_t *g,
                              const uint16_t *b)
{
    uint32_t count = 1u << t->bps;
    bool eight_bit = true;
    for (uint32_t i = 0; i < count; i++)
        if (r[i] > 255 || g[i] > 255 || b[i] > 255)
            eight_bit = false;
    int shift = eight_bit ? 0 : 8;
    for (uint32_t i = 0; i < count; i++) {
        t->palette[i][0] = (uint8_t)(r[i] >> shift);
        t->palette[i][1] = (uint8_t)(g[i] >> shift);
        t->palette[i][2] = (uint8_t)(b[i] >> shift);
    }
}

/* Decides channels, output sample and conversion from the photometric interpretation and the
 * sample layout; fills *sample. */
static int tiff_check_pixels(struct tiff_input *t, uint32_t *sample, struct vts_error *err)
{
    TIFF *tif = t->tif;
    uint16_t spp = tiff_get16(tif, TIFFTAG_SAMPLESPERPIXEL, 1);
    uint16_t format = tiff_get16(tif, TIFFTAG_SAMPLEFORMAT, SAMPLEFORMAT_UINT);
    uint16_t photometric =
        tiff_get16(tif, TIFFTAG_PHOTOMETRIC, spp >= 3 ? PHOTOMETRIC_RGB : PHOTOMETRIC_MINISBLACK);
    uint16_t compression = tiff_get16(tif, TIFFTAG_COMPRESSION, COMPRESSION_NONE);
    t->bps = tiff_get16(tif, TIFFTAG_BITSPERSAMPLE, 1);
    t->separate =
        spp > 1 && /* one sample per texel: the same layout either way */
        tiff_get16(tif, TIFFTAG_PLANARCONFIG, PLANARCONFIG_CONTIG) == PLANARCONFIG_SEPARATE;
    t->channels = spp;
    if (photometric == PHOTOMETRIC_YCBCR && compression == COMPRESSION_JPEG) {
        if (!TIFFSetField(tif, TIFFTAG_JPEGCOLORMODE, JPEGCOLORMODE_RGB))
            return vt_error_set(err, tiff_status(t), "cannot read '%s': %s", t->name,
                                tiff_message(t));
        photometric = PHOTOMETRIC_RGB;
    }
    if (spp < 1 || spp > 4)
        return vt_error_set(err, VTS_ERR_UNSUPPORTED,
                            "cannot read '%s': %u channels (1 to 4 are supported)", t->name, spp);
    bool grey = photometric == PHOTOMETRIC_MINISBLACK || photometric == PHOTOMETRIC_MINISWHITE;
    if (!(grey && spp <= 2) && !(photometric == PHOTOMETRIC_RGB && spp >= 3) &&
        !(photometric == PHOTOMETRIC_PALETTE && spp == 1))
        return vt_error_set(
            err, VTS_ERR_UNSUPPORTED,
            "cannot read '%s': photometric interpretation %u with %u channels (grey, RGB and palette images are supported)",
            t->name, photometric, spp);
    t->min_is_white = photometric == PHOTOMETRIC_MINISWHITE;
    if (format == SAMPLEFORMAT_UINT && (t->bps == 8 || t->bps == 16)) {
        *sample = t->bps == 8 ? VTS_SAMPLE_U8 : VTS_SAMPLE_U16;
    } else if (format == SAMPLEFORMAT_IEEEFP && (t->bps == 16 || t->bps == 32) &&
               !t->min_is_white) {
        *sample = t->bps == 16 ? VTS_SAMPLE_F16 : VTS_SAMPLE_F32;
    } else if (format == SAMPLEFORMAT_UINT && spp == 1 &&
               (t->bps == 1 || t->bps == 2 || t->bps == 4)) {
        *sample = VTS_SAMPLE_U8;
    } else {
        return vt_error_set(
            err, VTS_ERR_UNSUPPORTED,
            "cannot read '%s': %u-bit samples of format %u (8/16-bit unsigned and 16/32-bit float are supported)",
            t->name, t->bps, format);
    }
    t->sample_bytes = t->bps >= 8 ? t->bps / 8 : 1;
    t->convert = t->bps < 8 ? TIFF_BITS : TIFF_COPY;
    if (photometric == PHOTOMETRIC_PALETTE) {
        uint16_t *r, *g, *b;
        if (t->bps > 8 || !TIFFGetField(tif, TIFFTAG_COLORMAP, &r, &g, &b))
            return vt_error_set(err, VTS_ERR_UNSUPPORTED, "cannot read '%s': %u-bit palette image",
                                t->name, t->bps);
        tiff_load_palette(t, r, g, b);
        t->convert = TIFF_PALETTE;
        t->channels = 3;
    }
    return 0;
}

/* Chooses tiles, strips or scanlines and checks the chunk sizes libtiff computes. */
static int tiff_check_layout(struct tiff_input *t, struct vts_error *err)
{
    TIFF *tif = t->tif;
    uint64_t chunk_bytes, row_bytes;
    if (TIFFIsTiled(tif)) {
        uint32_t tw = 0, th = 0;
        TIFFGetField(tif, TIFFTAG_TILEWIDTH, &tw);
        TIFFGetField(tif, TIFFTAG_TILELENGTH, &th);
        if (tw == 0 || th == 0)
            return vt_error_set(err, VTS_ERR_BAD_INPUT, "cannot read '%s': tile size %ux%u",
                                t->name, tw, th);
        t->layout = TIFF_TILES;
        t->chunk_w = tw;
        t->chunk_h = th;
        chunk_bytes = TIFFTileSize64(tif);
        row_bytes = TIFFTileRowSize64(tif);
    } else {
        uint32_t rps = t->height;
        TIFFGetField(tif, TIFFTAG_ROWSPERSTRIP, &rps);
        if (rps == 0 || rps > t->height)
            rps = t->height;
        t->layout = TIFF_STRIPS;
        t->chunk_w = t->width;
        t->chunk_h = rps;
        row_bytes = TIFFScanlineSize64(tif);
        chunk_bytes = TIFFStripSize64(tif);
        if (chunk_bytes > VT_INPUT_MAX_BUFFER_BYTES / 4 && rps > 1) {
            t->layout = TIFF_SCANLINES; /* decode a huge strip row by row */
            t->chunk_h = 1;
            chunk_bytes = row_bytes;
        }
    }
    uint64_t texel_bits =
        (uint64_t)t->bps * (t->separate ? 1 : (t->convert == TIFF_PALETTE ? 1 : t->channels));
    uint64_t need_row, need_chunk;
    uint32_t planes = t->separate ? t->channels : 1;
    if (row_bytes == 0 || chunk_bytes == 0 || chunk_bytes > VT_INPUT_MAX_BUFFER_BYTES / planes ||
        !vt_u64_mul(t->chunk_w, texel_bits, &need_row) || (need_row + 7) / 8 > row_bytes ||
        !vt_u64_mul(row_bytes, t->chunk_h, &need_chunk) || need_chunk > chunk_bytes)
        return vt_error_set(err, VTS_ERR_BAD_INPUT,
                            "cannot read '%s': unusable %s size %ux%u (%llu bytes)", t->name,
                            t->layout == TIFF_TILES ? "tile" : "strip", t->chunk_w, t->chunk_h,
                            (unsigned long long)chunk_bytes);
    t->chunk_bytes = (size_t)chunk_bytes;
    t->row_bytes = (size_t)row_bytes;
    for (uint32_t s = 0; s < planes; s++) {
        t->chunk[s] = malloc(t->chunk_bytes);
        if (!t->chunk[s])
            return vt_error_set(err, VTS_ERR_NOMEM, "cannot read '%s': out of memory", t->name);
    }
    return 0;
}

static int tiff_read_region(void *ctx, uint32_t x, uint32_t y, struct vt_image *dst,
                            struct vts_error *err);

static const struct vt_source_ops tiff_ops = {tiff_read_region, tiff_close};

/* Opens path through libtiff (the first directory read): *out to tiff_close(), or a negative
 * status with err set ("cannot read 'x.tif': Input/output error"). */
static int tiff_open_file(const char *path, struct tiff_input **out, struct vts_error *err)
{
    *out = NULL;
    struct tiff_input *t = calloc(1, sizeof *t);
    if (!t)
        return vt_error_set(err, VTS_ERR_NOMEM, "cannot read '%s': out of memory", path);
    vt_input_copy_name(t->name, sizeof t->name, path);
    int rc;
    t->fd = open(path, O_RDONLY | O_CLOEXEC);
    if (t->fd < 0) {
        rc = vt_error_set(err, VTS_ERR_IO, "cannot open '%s': %s", path, strerror(errno));
        goto out_free;
    }
    rc = VTS_ERR_NOMEM;
    TIFFOpenOptions *opts = TIFFOpenOptionsAlloc();
    if (!opts) {
        vt_error_set(err, rc, "cannot read '%s': out of memory", path);
        goto out_free;
    }
    TIFFOpenOptionsSetErrorHandlerExtR(opts, tiff_on_error, t);
    TIFFOpenOptionsSetWarningHandlerExtR(opts, tiff_on_warning, t);
    TIFFOpenOptionsSetMaxSingleMemAlloc(opts, (tmsize_t)VT_INPUT_MAX_BUFFER_BYTES);
    /* "m": no mmap, or every page read counts as RSS */
    t->tif = TIFFClientOpenExt(path, "rm", t, tiff_io_read, tiff_io_write, tiff_io_seek,
                               tiff_io_close, tiff_io_size, tiff_io_map, tiff_io_unmap, opts);
    TIFFOpenOptionsFree(opts);
    /* libtiff goes on after some failed reads of the directory (a tag left out): not here */
    if (!t->tif || t->read_errno) {
        rc = vt_error_set(err, tiff_status(t), "cannot read '%s': %s", path, tiff_message(t));
        goto out_free;
    }
    *out = t;
    return 0;

out_free:
    tiff_close(t);
    return rc;
}

static int tiff_open(const char *path, uint64_t max_pixels, struct vt_source *out,
                     struct vts_error *err)
{
    struct tiff_input *t;
    int rc = tiff_open_file(path, &t, err);
    if (rc < 0)
        return rc;
    uint32_t sample = 0;
    if (!TIFFGetField(t->tif, TIFFTAG_IMAGEWIDTH, &t->width) ||
        !TIFFGetField(t->tif, TIFFTAG_IMAGELENGTH, &t->height)) {
        rc = vt_error_set(err, VTS_ERR_BAD_INPUT, "cannot read '%s': no image size", path);
        goto out_free;
    }
    rc = vt_input_check_size(path, t->width, t->height, max_pixels, err);
    if (rc == 0)
        rc = tiff_check_pixels(t, &sample, err);
    if (rc == 0)
        rc = tiff_check_layout(t, err);
    if (rc < 0)
        goto out_free;
    bool tiled = t->layout == TIFF_TILES;
    vt_input_set_info(&out->info, t->width, t->height, t->channels, sample, !tiled,
                      tiled ? t->chunk_w : 0, tiled ? t->chunk_h : 0,
                      TIFFIsBigTIFF(t->tif) ? "bigtiff" : "tiff");
    out->ops = &tiff_ops;
    out->ctx = t;
    return 0;

out_free:
    tiff_close(t);
    return rc;
}

/* ---- pixels ---- */

/* Decodes chunk (cx, cy) of plane s into t->chunk[s] unless it is already there. */
static int tiff_load_chunk(struct tiff_input *t, uint32_t cx, uint32_t cy, uint16_t s,
                           struct vts_error *err)
{
    uint32_t px = cx * t->chunk_w, py = cy * t->chunk_h;
    uint64_t index;
    if (t->layout == TIFF_TILES)
        index = TIFFComputeTile(t->tif, px, py, 0, s);
    else if (t->layout == TIFF_STRIPS)
        index = (uint64_t)s * ((t->height - 1) / t->chunk_h + 1) + cy;
    else
        index = (uint64_t)s * t->height + py;
    if (t->cached[s] == index + 1)
        return 0;
    t->cached[s] = 0;
    t->message[0] = '\0';
    bool ok;
    if (t->layout == TIFF_TILES) {
        ok = TIFFReadEncodedTile(t->tif, (uint32_t)index, t->chunk[s], (tmsize_t)t->chunk_bytes) ==
             (tmsize_t)t->chunk_bytes;
    } else if (t->layout == TIFF_STRIPS) {
        uint32_t rows = t->height - py < t->chunk_h ? t->height - py : t->chunk_h;
        tmsize_t n =
            TIFFReadEncodedStrip(t->tif, (uint32_t)index, t->chunk[s], (tmsize_t)t->chunk_bytes);
        ok = n >= 0 && (uint64_t)n >= (uint64_t)rows * t->row_bytes;
    } else {
        ok = TIFFReadScanline(t->tif, t->chunk[s], py, s) == 1;
    }
    if (!ok) {
        if (t->layout == TIFF_TILES)
            return vt_error_set(err, tiff_status(t), "cannot read '%s': tile at %u,%u: %s", t->name,
                                px, py, tiff_message(t));
        return vt_error_set(err, tiff_status(t), "cannot read '%s': %s at row %u: %s", t->name,
                            t->layout == TIFF_STRIPS ? "strip" : "scanline", py, tiff_message(t));
    }
    t->cached[s] = index + 1;
    return 0;
}

/* Converts n texels of a stored row (plane s), starting at texel c0, into the output row. */
static void tiff_convert_row(const struct tiff_input *t, const unsigned char *src, uint32_t c0,
                             uint32_t n, uint32_t s, unsigned char *dst)
{
    size_t sb = t->sample_bytes;
    size_t texel = (size_t)t->channels * sb;
    if (t->convert == TIFF_COPY && !t->separate) {
        memcpy(dst, src + (size_t)c0 * texel, (size_t)n * texel);
    } else if (t->convert == TIFF_COPY) {
        for (uint32_t i = 0; i < n; i++)
            memcpy(dst + i * texel + s * sb, src + (size_t)(c0 + i) * sb, sb);
    } else {
        uint32_t bps = t->bps, max = (1u << bps) - 1;
        for (uint32_t i = 0; i < n; i++) {
            uint64_t bit = (uint64_t)(c0 + i) * bps;
            uint32_t v = (src[bit / 8] >> (8 - bps - bit % 8)) & max;
            if (t->convert == TIFF_PALETTE)
                memcpy(dst + i * 3, t->palette[v], 3);
            else
                dst[i] = (uint8_t)(v * 255 / max);
        }
    }
    if (t->min_is_white && s == 0) { /* invert grey, not alpha */
        for (uint32_t i = 0; i < n; i++) {
            if (sb == 1) {
                dst[i * texel] = (uint8_t)(255 - dst[i * texel]);
            } else {
                uint16_t v;
                memcpy(&v, dst + i * texel, 2);
                v = (uint16_t)(65535 - v);
                memcpy(dst + i * texel, &v, 2);
            }
        }
    }
}

/* True when dst is exactly the tile at (x, y), with rows as libtiff decodes them: the tile can be
 * decoded straight into dst, without the chunk buffer and its copy. */
static bool whole_tile(const struct tiff_input *t, uint32_t x, uint32_t y,
                       const struct vt_image *dst)
{
    return t->layout == TIFF_TILES && !t->separate && t->convert == TIFF_COPY && !t->min_is_white &&
           x % t->chunk_w == 0 && y % t->chunk_h == 0 && dst->width == t->chunk_w &&
           dst->height == t->chunk_h && dst->stride == t->row_bytes &&
           t->row_bytes * t->chunk_h == t->chunk_bytes;
}

static int tiff_decode_tile(struct tiff_input *t, uint32_t x, uint32_t y, void *pixels,
                            struct vts_error *err)
{
    t->message[0] = '\0';
    uint32_t index = TIFFComputeTile(t->tif, x, y, 0, 0);
    if (TIFFReadEncodedTile(t->tif, index, pixels, (tmsize_t)t->chunk_bytes) !=
        (tmsize_t)t->chunk_bytes)
        return vt_error_set(err, tiff_status(t), "cannot read '%s': tile at %u,%u: %s", t->name, x,
                            y, tiff_message(t));
    return 0;
}

static int tiff_read_region(void *ctx, uint32_t x, uint32_t y, struct vt_image *dst,
                            struct vts_error *err)
{
    struct tiff_input *t = ctx;
    size_t texel = vt_image_texel_bytes(dst);
    if (whole_tile(t, x, y, dst)) /* decoded where it goes (the tile cache's reads) */
        return tiff_decode_tile(t, x, y, dst->pixels, err);
    uint32_t planes = t->separate ? t->channels : 1;
    uint32_t x_end = x + dst->width, y_end = y + dst->height;
    for (uint32_t cy = y / t->chunk_h; cy <= (y_end - 1) / t->chunk_h; cy++) {
        uint32_t py = cy * t->chunk_h;
        uint32_t r0 = y > py ? y - py : 0;
        uint32_t r1 = y_end - py < t->chunk_h ? y_end - py : t->chunk_h;
        for (uint32_t cx = x / t->chunk_w; cx <= (x_end - 1) / t->chunk_w; cx++) {
            uint32_t px = cx * t->chunk_w;
            uint32_t c0 = x > px ? x - px : 0;
            uint32_t c1 = x_end - px < t->chunk_w ? x_end - px : t->chunk_w;
            for (uint32_t s = 0; s < planes; s++) {
                int rc = tiff_load_chunk(t, cx, cy, (uint16_t)s, err);
                if (rc < 0)
                    return rc;
                for (uint32_t r = r0; r < r1; r++) {
                    unsigned char *out = (unsigned char *)vt_image_at(dst, 0, py + r - y) +
                                         (size_t)(px + c0 - x) * texel;
                    tiff_convert_row(t, t->chunk[s] + (size_t)r * t->row_bytes, c0, c1 - c0, s,
                                     out);
                }
            }
        }
    }
    return 0;
}

/* "II*\0" / "MM\0*" (classic TIFF) and "II+\0" / "MM\0+" (BigTIFF). */
static bool tiff_sniff(const unsigned char *magic, size_t len)
{
    return len >= 4 && ((magic[0] == 'I' && magic[1] == 'I' && magic[3] == 0 &&
                         (magic[2] == 42 || magic[2] == 43)) ||
                        (magic[0] == 'M' && magic[1] == 'M' && magic[2] == 0 &&
                         (magic[3] == 42 || magic[3] == 43)));
}

const struct vt_input_reader vt_input_reader_tiff = {"tiff", tiff_sniff, tiff_open};

int vt_input_tiff_route(const char *path, enum vt_tiff_route *route, struct vts_error *err)
{
    *route = VT_TIFF_NATIVE;
    struct tiff_input *t;
    int rc = tiff_open_file(path, &t, err);
    if (rc < 0)
        return rc;
    TIFF *tif = t->tif;
    uint16_t spp = tiff_get16(tif, TIFFTAG_SAMPLESPERPIXEL, 1);
    uint16_t format = tiff_get16(tif, TIFFTAG_SAMPLEFORMAT, SAMPLEFORMAT_UINT);
    uint16_t bps = tiff_get16(tif, TIFFTAG_BITSPERSAMPLE, 1);
    uint16_t photometric =
        tiff_get16(tif, TIFFTAG_PHOTOMETRIC, spp >= 3 ? PHOTOMETRIC_RGB : PHOTOMETRIC_MINISBLACK);
    uint16_t extra_count = 0, *extra = NULL;
    bool alpha = TIFFGetField(tif, TIFFTAG_EXTRASAMPLES, &extra_count, &extra) && extra_count &&
                 (extra[extra_count - 1] == EXTRASAMPLE_ASSOCALPHA ||
                  extra[extra_count - 1] == EXTRASAMPLE_UNASSALPHA);
    /* GeoTIFF: ModelPixelScale, ModelTiepoint, ModelTransformation, GeoKeyDirectory; libtiff
     * keeps them as anonymous fields, known only when this file has them */
    static const uint32_t geo_tags[] = {33550, 33922, 34264, 34735};
    bool geo = false;
    for (size_t i = 0; i < sizeof geo_tags / sizeof geo_tags[0]; i++) {
        uint32_t count = 0;
        void *data = NULL;
        if (TIFFFindField(tif, geo_tags[i], TIFF_ANY) &&
            TIFFGetField(tif, geo_tags[i], &count, &data))
            geo = true;
    }
    tiff_close(t);
    /* what this reader refuses but GDAL reads as bands of data */
    bool gdal = spp > 4 || format == SAMPLEFORMAT_INT ||
                (format == SAMPLEFORMAT_UINT && bps == 32) ||
                (format == SAMPLEFORMAT_IEEEFP && bps == 64) ||
                (spp >= 3 &&
                 (photometric == PHOTOMETRIC_MINISBLACK || photometric == PHOTOMETRIC_MINISWHITE));
    /* a GeoTIFF's 2nd / 4th band is alpha only when it says so (else: RGBN, data) */
    if (geo && (spp == 2 || spp == 4) && !alpha)
        gdal = true;
    *route = gdal ? VT_TIFF_GDAL : geo ? VT_TIFF_GEO_NATIVE : VT_TIFF_NATIVE;
    return 0;
}
