/* TIFF files on disk through libtiff: a streaming 8-bit writer over vt_atomic_file (see
 * vt_tiff_file.h). libtiff reports errors through the handlers given to TIFFFdOpenExt(), which
 * keep the first message in the writer: nothing is printed. */
#include "vt_tiff_file.h"

#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <tiffio.h>
#include <unistd.h>

#include "vt_atomic_file.h"
#include "vt_error.h"

#define TIFF_FILE_BIGTIFF_BYTES (1ull << 31) /* classic TIFF offsets are 32-bit */

struct vt_tiff_file_writer {
    struct vt_atomic_file file; /* fd -1 and no temp_path once committed or aborted */
    TIFF *tif;                  /* writes through a dup of file.fd; NULL once closed */
    bool stopped;               /* a write failed: the TIFF state is unusable */
    uint32_t width, height, rows_written;
    unsigned libtiff_errors; /* errors libtiff reported (message: the first) */
    char message[200];
};

static int tiff_file_on_error(TIFF *tif, void *user_data, const char *module, const char *fmt,
                              va_list ap) __attribute__((format(printf, 4, 0)));

static int tiff_file_on_error(TIFF *tif, void *user_data, const char *module, const char *fmt,
                              va_list ap)
{
    (void)tif;
    (void)module;
    struct vt_tiff_file_writer *w = user_data;
    if (w->libtiff_errors++ == 0) {
        vsnprintf(w->message, sizeof w->message, fmt, ap);
        for (char *p = w->message; *p; p++) /* messages stay one line */
            if (*p == '\n' || *p == '\r')
                *p = ' ';
    }
    return 1; /* handled: libtiff must not print */
}

static int tiff_file_on_warning(TIFF *tif, void *user_data, const char *module, const char *fmt,
                                va_list ap)
{
    (void)tif, (void)user_data, (void)module, (void)fmt, (void)ap;
    return 1; /* warnings concern tags we do not write, or come before an error */
}

static int tiff_file_fail(struct vt_tiff_file_writer *w, struct vts_error *err)
{
    w->stopped = true;
    return vt_error_set(err, VTS_ERR_IO, "cannot write '%s': %s", w->file.final_path,
                        w->message[0] ? w->message : "libtiff failed");
}

/* Opens the TIFF over a duplicate of the temporary file's descriptor (TIFFClose closes it). */
static int tiff_file_open(struct vt_tiff_file_writer *w, uint32_t channels, uint32_t sample,
                          struct vts_error *err)
{
    TIFFOpenOptions *opts = TIFFOpenOptionsAlloc();
    if (!opts)
        return vt_error_set(err, VTS_ERR_NOMEM, "cannot write '%s': out of memory",
                            w->file.final_path);
    TIFFOpenOptionsSetErrorHandlerExtR(opts, tiff_file_on_error, w);
    TIFFOpenOptionsSetWarningHandlerExtR(opts, tiff_file_on_warning, w);
    uint32_t bits = sample == VTS_SAMPLE_U8 ? 8 : sample == VTS_SAMPLE_U16 ? 16 : 32;
    bool big = (uint64_t)w->width * w->height * channels * (bits / 8) > TIFF_FILE_BIGTIFF_BYTES;
    int fd = dup(w->file.fd);
    if (fd >= 0 && !(w->tif = TIFFFdOpenExt(fd, w->file.final_path, big ? "w8" : "w", opts)))
        close(fd);
    TIFFOpenOptionsFree(opts);
    if (!w->tif)
        return tiff_file_fail(w, err);
    uint16_t extra = EXTRASAMPLE_UNASSALPHA;
    TIFFSetField(w->tif, TIFFTAG_IMAGEWIDTH, w->width);
    TIFFSetField(w->tif, TIFFTAG_IMAGELENGTH, w->height);
    TIFFSetField(w->tif, TIFFTAG_SAMPLESPERPIXEL, (uint16_t)channels);
    TIFFSetField(w->tif, TIFFTAG_BITSPERSAMPLE, (uint16_t)bits);
    TIFFSetField(w->tif, TIFFTAG_SAMPLEFORMAT,
                 (uint16_t)(bits == 32 ? SAMPLEFORMAT_IEEEFP : SAMPLEFORMAT_UINT));
    TIFFSetField(w->tif, TIFFTAG_PHOTOMETRIC,
                 channels >= 3 ? PHOTOMETRIC_RGB : PHOTOMETRIC_MINISBLACK);
    TIFFSetField(w->tif, TIFFTAG_PLANARCONFIG, PLANARCONFIG_CONTIG);
    TIFFSetField(w->tif, TIFFTAG_COMPRESSION, COMPRESSION_ADOBE_DEFLATE);
    TIFFSetField(w->tif, TIFFTAG_ROWSPERSTRIP, VT_TIFF_FILE_ROWS_PER_STRIP);
    if (channels == 2 || channels == 4)
        TIFFSetField(w->tif, TIFFTAG_EXTRASAMPLES, (uint16_t)1, &extra);
    return w->libtiff_errors ? tiff_file_fail(w, err) : 0;
}

struct vt_tiff_file_writer *vt_tiff_file_writer_create(const char *path, uint32_t width,
                                                       uint32_t height, uint32_t channels,
                                                       struct vts_error *err)
{
    return vt_tiff_file_writer_create_sample(path, width, height, channels, VTS_SAMPLE_U8, err);
}

struct vt_tiff_file_writer *vt_tiff_file_writer_create_sample(const char *path, uint32_t width,
                                                              uint32_t height, uint32_t channels,
                                                              uint32_t sample,
                                                              struct vts_error *err)
{
    if (!path || width == 0 || height == 0 || channels < 1 || channels > 4 ||
        (sample != VTS_SAMPLE_U8 && sample != VTS_SAMPLE_U16 && sample != VTS_SAMPLE_F32)) {
        vt_error_set(err, VTS_ERR_ARG, "cannot write '%s': %ux%u texels of %u channels (%s)",
                     path ? path : "(null)", width, height, channels, vts_sample_name(sample));
        return NULL;
    }
    struct vt_tiff_file_writer *w = calloc(1, sizeof *w);
    if (!w) {
        vt_error_set(err, VTS_ERR_NOMEM, "cannot write '%s': out of memory", path);
        return NULL;
    }
    w->width = width;
    w->height = height;
    if (vt_atomic_file_create(&w->file, path, "tmp", 0, err) != 0)
        goto out_free;
    if (tiff_file_open(w, channels, sample, err) != 0)
        goto out_destroy;
    return w;

out_destroy:
    vt_tiff_file_writer_destroy(w);
    return NULL;
out_free:
    free(w);
    return NULL;
}

int vt_tiff_file_writer_rows(struct vt_tiff_file_writer *w, const void *rows, uint32_t row_count,
                             size_t stride, struct vts_error *err)
{
    if (w->stopped || !w->tif)
        return vt_error_set(err, VTS_ERR_IO, "cannot write '%s': the writer stopped earlier",
                            w->file.final_path);
    if (row_count > w->height - w->rows_written)
        return vt_error_set(err, VTS_ERR_ARG, "cannot write '%s': %u rows past its height %u",
                            w->file.final_path, row_count, w->height);
    const char *row = rows;
    for (uint32_t i = 0; i < row_count; i++, row += stride) {
        /* libtiff takes a non-const buffer but only reads it for uncompressed-order contiguous
         * rows (no byte swapping: we write the host's order, which the header records) */
        if (TIFFWriteScanline(w->tif, (void *)(uintptr_t)row, w->rows_written, 0) < 0)
            return tiff_file_fail(w, err);
        w->rows_written++;
    }
    return 0;
}

int vt_tiff_file_writer_finish(struct vt_tiff_file_writer *w, struct vts_error *err)
{
    if (w->stopped || !w->tif)
        return vt_error_set(err, VTS_ERR_IO, "cannot write '%s': the writer stopped earlier",
                            w->file.final_path);
    if (w->rows_written != w->height)
        return vt_error_set(err, VTS_ERR_ARG, "cannot write '%s': %u of %u rows given",
                            w->file.final_path, w->rows_written, w->height);
    TIFFClose(w->tif); /* writes the directory; errors come through the handler */
    w->tif = NULL;
    if (w->libtiff_errors) {
        int rc = tiff_file_fail(w, err);
        vt_atomic_file_abort(&w->file);
        return rc;
    }
    return vt_atomic_file_commit(&w->file, err);
}

void vt_tiff_file_writer_destroy(struct vt_tiff_file_writer *w)
{
    if (!w)
        return;
    if (w->tif)
        TIFFClose(w->tif);
    vt_atomic_file_abort(&w->file);
    free(w);
}
