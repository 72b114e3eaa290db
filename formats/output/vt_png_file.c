/* PNG files on disk through libpng: a streaming writer over vt_atomic_file and a whole-image
 * reader. The functions that call setjmp (*_run) change no local of their own after it: the work
 * happens in callees (*_body) whose frames the longjmp discards, or through pointers to objects
 * the caller owns, so no local is left indeterminate (C11 7.13.2.1). */
#include "vt_png_file.h"

#include <errno.h>
#include <png.h>
#include <setjmp.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vt_atomic_file.h"
#include "vt_checked.h"
#include "vt_error.h"

#define PNG_FILE_MAX_EDGE     0x7fffffffu /* PNG_UINT_31_MAX */
#define PNG_FILE_BUFFER_BYTES (1u << 20)  /* output is written in pieces of this size */

struct vt_png_file_writer {
    struct vt_atomic_file file;
    bool file_open; /* the temporary file exists (create succeeded, commit not yet) */
    bool stopped;   /* libpng or a write failed: the png state is unusable */
    png_structp png;
    png_infop info;
    uint32_t width, height, channels, bit_depth;
    size_t row_bytes;
    uint32_t rows_written;
    unsigned char *buffer;       /* PNG_FILE_BUFFER_BYTES of output not yet written */
    size_t buffered;             /* bytes in buffer */
    unsigned long long file_pos; /* bytes written to the file before buffer */
    struct vts_error error;      /* first error raised inside a libpng callback */
};

/* The status to return after libpng or a callback stopped: the recorded one, else fallback (a
 * callee that failed without filling its error) with a generic message. */
static int png_file_stop_status(struct vts_error *error, int fallback)
{
    if (error->status == VTS_OK)
        vt_error_set(error, fallback, "libpng stopped without a message");
    return error->status;
}

/* ---- writer ---- */

static void png_file_ignore_warning(png_structp png, png_const_charp msg)
{
    (void)png; /* warnings concern ancillary data we neither write nor use */
    (void)msg;
}

static void png_file_writer_error(png_structp png, png_const_charp msg)
{
    struct vt_png_file_writer *w = png_get_error_ptr(png);
    if (w->error.status == VTS_OK)
        vt_error_set(&w->error, strstr(msg, "memory") ? VTS_ERR_NOMEM : VTS_ERR_ARG,
                     "cannot write '%s': %s", w->file.final_path, msg);
    png_longjmp(png, 1);
}

/* Writes the buffered bytes; false (w->error filled) on failure. */
static bool png_file_writer_flush_buffer(struct vt_png_file_writer *w)
{
    if (w->buffered == 0)
        return true;
    if (vt_atomic_file_pwrite(&w->file, w->buffer, w->buffered, w->file_pos, &w->error) < 0)
        return false;
    w->file_pos += w->buffered;
    w->buffered = 0;
    return true;
}

static void png_file_writer_write(png_structp png, png_bytep data, size_t length)
{
    struct vt_png_file_writer *w = png_get_io_ptr(png);
    while (length > 0) {
        if (w->buffered == PNG_FILE_BUFFER_BYTES && !png_file_writer_flush_buffer(w))
            png_error(png, "write failed");
        size_t n = PNG_FILE_BUFFER_BYTES - w->buffered;
        if (n > length)
            n = length;
        memcpy(w->buffer + w->buffered, data, n);
        w->buffered += n;
        data += n;
        length -= n;
    }
}

static void png_file_writer_flush(png_structp png)
{
    (void)png; /* the buffer is written when full and at the end */
}

static int png_file_writer_start_run(struct vt_png_file_writer *w)
{
    if (setjmp(png_jmpbuf(w->png)))
        return png_file_stop_status(&w->error, VTS_ERR_IO);
    png_set_write_fn(w->png, w, png_file_writer_write, png_file_writer_flush);
    png_set_user_limits(w->png, PNG_FILE_MAX_EDGE, PNG_FILE_MAX_EDGE);
    png_set_compression_level(w->png, VT_PNG_FILE_LEVEL);
    png_set_filter(w->png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
    static const int colour_types[] = {PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA,
                                       PNG_COLOR_TYPE_RGB, PNG_COLOR_TYPE_RGB_ALPHA};
    png_set_IHDR(w->png, w->info, w->width, w->height, (int)w->bit_depth,
                 colour_types[w->channels - 1], PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_BASE,
                 PNG_FILTER_TYPE_BASE);
    png_write_info(w->png, w->info);
    if (w->bit_depth == 16 && vt_host_is_little_endian())
        png_set_swap(w->png);
    return 0;
}

static void png_file_writer_rows_body(struct vt_png_file_writer *w, const unsigned char *rows,
                                      uint32_t row_count, size_t stride)
{
    for (uint32_t i = 0; i < row_count; i++) {
        png_write_row(w->png, rows + (size_t)i * stride);
        w->rows_written++;
    }
}

static int png_file_writer_rows_run(struct vt_png_file_writer *w, const unsigned char *rows,
                                    uint32_t row_count, size_t stride)
{
    if (setjmp(png_jmpbuf(w->png)))
        return png_file_stop_status(&w->error, VTS_ERR_IO);
    png_file_writer_rows_body(w, rows, row_count, stride);
    return 0;
}

static int png_file_writer_end_run(struct vt_png_file_writer *w)
{
    if (setjmp(png_jmpbuf(w->png)))
        return png_file_stop_status(&w->error, VTS_ERR_IO);
    png_write_end(w->png, NULL);
    if (!png_file_writer_flush_buffer(w))
        return png_file_stop_status(&w->error, VTS_ERR_IO);
    return 0;
}

/* Marks the writer stopped after a failed *_run and copies its error to err. */
static int png_file_writer_fail(struct vt_png_file_writer *w, struct vts_error *err)
{
    w->stopped = true;
    return vt_error_set(err, w->error.status, "%s", w->error.message);
}

static int png_file_writer_check_args(const char *path, uint32_t width, uint32_t height,
                                      uint32_t channels, uint32_t bit_depth, struct vts_error *err)
{
    if (!path || !path[0])
        return vt_error_set(err, VTS_ERR_ARG, "cannot write a PNG: empty path");
    if (width == 0 || height == 0 || width > PNG_FILE_MAX_EDGE || height > PNG_FILE_MAX_EDGE)
        return vt_error_set(err, VTS_ERR_ARG, "cannot write '%s': image size %ux%u", path, width,
                            height);
    if (channels < 1 || channels > 4 || (bit_depth != 8 && bit_depth != 16))
        return vt_error_set(err, VTS_ERR_ARG, "cannot write '%s': %u channels of %u bits", path,
                            channels, bit_depth);
    size_t row_bytes;
    if (!vt_size_mul3(width, channels, bit_depth / 8, &row_bytes))
        return vt_error_set(err, VTS_ERR_LIMIT, "cannot write '%s': rows of %u texels are too long",
                            path, width);
    return 0;
}

struct vt_png_file_writer *vt_png_file_writer_create(const char *path, uint32_t width,
                                                     uint32_t height, uint32_t channels,
                                                     uint32_t bit_depth, struct vts_error *err)
{
    if (png_file_writer_check_args(path, width, height, channels, bit_depth, err) < 0)
        return NULL;
    struct vt_png_file_writer *w = calloc(1, sizeof *w);
    if (!w) {
        vt_error_set(err, VTS_ERR_NOMEM, "cannot write '%s': out of memory", path);
        return NULL;
    }
    w->width = width;
    w->height = height;
    w->channels = channels;
    w->bit_depth = bit_depth;
    w->row_bytes = (size_t)width * channels * (bit_depth / 8); /* checked above */
    w->buffer = malloc(PNG_FILE_BUFFER_BYTES);
    w->png = png_create_write_struct(PNG_LIBPNG_VER_STRING, w, png_file_writer_error,
                                     png_file_ignore_warning);
    w->info = w->png ? png_create_info_struct(w->png) : NULL;
    if (!w->buffer || !w->info) {
        vt_error_set(err, VTS_ERR_NOMEM, "cannot write '%s': out of memory", path);
        goto out_destroy;
    }
    if (vt_atomic_file_create(&w->file, path, "tmp", VT_ATOMIC_FILE_SEQUENTIAL, err) < 0)
        goto out_destroy;
    w->file_open = true;
    if (png_file_writer_start_run(w) < 0) {
        png_file_writer_fail(w, err);
        goto out_destroy;
    }
    return w;

out_destroy:
    vt_png_file_writer_destroy(w);
    return NULL;
}

int vt_png_file_writer_rows(struct vt_png_file_writer *w, const void *rows, uint32_t row_count,
                            size_t stride, struct vts_error *err)
{
    if (w->stopped || !w->file_open)
        return vt_error_set(err, VTS_ERR_ARG, "cannot write '%s': the writer has stopped",
                            w->file.final_path);
    if (row_count > w->height - w->rows_written)
        return vt_error_set(err, VTS_ERR_ARG, "cannot write '%s': %u rows past row %u of %u",
                            w->file.final_path, row_count, w->rows_written, w->height);
    if (row_count > 1 && stride < w->row_bytes)
        return vt_error_set(err, VTS_ERR_ARG, "cannot write '%s': stride %zu < row size %zu",
                            w->file.final_path, stride, w->row_bytes);
    if (row_count == 0)
        return 0;
    if (png_file_writer_rows_run(w, rows, row_count, stride) < 0)
        return png_file_writer_fail(w, err);
    return 0;
}

int vt_png_file_writer_finish(struct vt_png_file_writer *w, struct vts_error *err)
{
    if (w->stopped || !w->file_open)
        return vt_error_set(err, VTS_ERR_ARG, "cannot write '%s': the writer has stopped",
                            w->file.final_path);
    if (w->rows_written != w->height)
        return vt_error_set(err, VTS_ERR_ARG, "cannot write '%s': %u of %u rows given",
                            w->file.final_path, w->rows_written, w->height);
    if (png_file_writer_end_run(w) < 0)
        return png_file_writer_fail(w, err);
    /* commit removes the temporary file itself when it fails */
    w->file_open = false;
    w->stopped = true;
    return vt_atomic_file_commit(&w->file, err);
}

void vt_png_file_writer_destroy(struct vt_png_file_writer *w)
{
    if (!w)
        return;
    if (w->png)
        png_destroy_write_struct(&w->png, &w->info);
    if (w->file_open)
        vt_atomic_file_abort(&w->file);
    free(w->buffer);
    free(w);
}

/* ---- reader ---- */

struct png_file_reader {
    const char *path;
    FILE *fp;
    unsigned long long pos; /* bytes read so far, for messages */
    struct vts_error error; /* first error raised inside a libpng callback */
};

static void png_file_reader_error(png_structp png, png_const_charp msg)
{
    struct png_file_reader *rd = png_get_error_ptr(png);
    if (rd->error.status == VTS_OK)
        vt_error_set(&rd->error, strstr(msg, "memory") ? VTS_ERR_NOMEM : VTS_ERR_BAD_INPUT,
                     "cannot read '%s': %s", rd->path, msg);
    png_longjmp(png, 1);
}

static void png_file_reader_read(png_structp png, png_bytep data, size_t length)
{
    struct png_file_reader *rd = png_get_io_ptr(png);
    size_t n = fread(data, 1, length, rd->fp);
    rd->pos += n;
    if (n == length)
        return;
    if (ferror(rd->fp))
        vt_error_set(&rd->error, VTS_ERR_IO, "cannot read '%s': %s", rd->path, strerror(errno));
    else
        vt_error_set(&rd->error, VTS_ERR_BAD_INPUT, "cannot read '%s': truncated at byte %llu",
                     rd->path, rd->pos);
    png_error(png, "read failed");
}

/* Sets up libpng's expansions for the image whose header was read; fills the output shape. */
static int png_file_reader_setup(png_structp png, png_infop info, struct png_file_reader *rd,
                                 uint32_t *channels, uint32_t *sample, int *passes)
{
    png_uint_32 width = png_get_image_width(png, info), height = png_get_image_height(png, info);
    if ((unsigned long long)width * height > VT_PNG_FILE_MAX_PIXELS)
        return vt_error_set(&rd->error, VTS_ERR_LIMIT,
                            "cannot read '%s': %ux%u texels exceed the limit of %llu", rd->path,
                            (unsigned)width, (unsigned)height, VT_PNG_FILE_MAX_PIXELS);
    png_set_expand(png); /* palette -> RGB(A), gray < 8 bits -> 8 bits, tRNS -> alpha */
    if (png_get_bit_depth(png, info) == 16 && vt_host_is_little_endian())
        png_set_swap(png);
    *passes = png_set_interlace_handling(png);
    png_read_update_info(png, info);
    *channels = png_get_channels(png, info);
    int depth = png_get_bit_depth(png, info);
    if (*channels < 1 || *channels > 4 || (depth != 8 && depth != 16))
        return vt_error_set(&rd->error, VTS_ERR_BAD_INPUT,
                            "cannot read '%s': %u channels of %d bits after expansion", rd->path,
                            *channels, depth);
    *sample = depth == 16 ? VTS_SAMPLE_U16 : VTS_SAMPLE_U8;
    return 0;
}

/* The reading itself; a libpng error longjmps out of it to png_file_reader_run(). */
static int png_file_reader_body(png_structp png, png_infop info, struct png_file_reader *rd,
                                struct vt_image *out)
{
    png_set_read_fn(png, rd, png_file_reader_read);
    png_set_sig_bytes(png, 8);
    png_set_user_limits(png, PNG_FILE_MAX_EDGE, PNG_FILE_MAX_EDGE); /* we limit the texel count */
    png_read_info(png, info);
    uint32_t channels = 0, sample = 0;
    int passes = 0;
    if (png_file_reader_setup(png, info, rd, &channels, &sample, &passes) < 0)
        return rd->error.status;
    struct vts_error alloc_error;
    if (vt_image_alloc(out, png_get_image_width(png, info), png_get_image_height(png, info),
                       channels, sample, &alloc_error) < 0)
        return vt_error_set(&rd->error, alloc_error.status, "cannot read '%s': %s", rd->path,
                            alloc_error.message);
    if (png_get_rowbytes(png, info) != out->stride)
        return vt_error_set(&rd->error, VTS_ERR_BAD_INPUT, "cannot read '%s': unexpected row size",
                            rd->path);
    for (int pass = 0; pass < passes; pass++)
        for (uint32_t y = 0; y < out->height; y++)
            png_read_row(png, (unsigned char *)out->pixels + (size_t)y * out->stride, NULL);
    png_read_end(png, NULL);
    return 0;
}

static int png_file_reader_run(png_structp png, png_infop info, struct png_file_reader *rd,
                               struct vt_image *out)
{
    if (setjmp(png_jmpbuf(png)))
        return png_file_stop_status(&rd->error, VTS_ERR_BAD_INPUT);
    return png_file_reader_body(png, info, rd, out);
}

int vt_png_file_read(const char *path, struct vt_image *out, struct vts_error *err)
{
    memset(out, 0, sizeof *out);
    struct png_file_reader rd = {.path = path};
    unsigned char signature[8];
    png_structp png = NULL;
    png_infop info = NULL;
    int rc = 0;
    rd.fp = fopen(path, "rb");
    if (!rd.fp)
        return vt_error_set(err, VTS_ERR_IO, "cannot read '%s': %s", path, strerror(errno));
    size_t n = fread(signature, 1, sizeof signature, rd.fp);
    if (n != sizeof signature && ferror(rd.fp)) {
        rc = vt_error_set(err, VTS_ERR_IO, "cannot read '%s': %s", path, strerror(errno));
        goto out_close;
    }
    if (n != sizeof signature || png_sig_cmp(signature, 0, sizeof signature) != 0) {
        rc = vt_error_set(err, VTS_ERR_BAD_INPUT, "cannot read '%s': not a PNG file", path);
        goto out_close;
    }
    png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &rd, png_file_reader_error,
                                 png_file_ignore_warning);
    info = png ? png_create_info_struct(png) : NULL;
    if (!info) {
        rc = vt_error_set(err, VTS_ERR_NOMEM, "cannot read '%s': out of memory", path);
        goto out_destroy;
    }
    rc = png_file_reader_run(png, info, &rd, out);
    if (rc < 0) {
        vt_image_release(out);
        vt_error_set(err, rc, "%s", rd.error.message);
    }
out_destroy:
    png_destroy_read_struct(&png, &info, NULL);
out_close:
    fclose(rd.fp);
    return rc;
}
