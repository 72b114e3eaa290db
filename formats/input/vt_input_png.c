/* PNG input through libpng, read row by row: the decoder keeps its position, so bands read top-down
 * decode each row once; a region that starts above the current row restarts the decode from the
 * top of the file (callers read bands in increasing y). Palette -> RGB(A), tRNS -> alpha, 1/2/4-bit
 * grey -> 8 bits, 16-bit samples in host order. Interlaced (Adam7) images are de-interlaced whole
 * into memory on the first read, up to VT_INPUT_MAX_BUFFER_BYTES.
 *
 * setjmp/longjmp stay in this file. The functions that call setjmp (*_run) change no local after
 * it: the work happens in callees (*_body) or through the struct, so no local is left
 * indeterminate (C11 7.13.2.1). */
#include <errno.h>
#include <png.h>
#include <setjmp.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "internal/vt_input_readers.h"
#include "internal/vt_input_util.h"
#include "vt_checked.h"
#include "vt_error.h"

#define PNG_INPUT_MAX_EDGE 0x7fffffffu /* PNG_UINT_31_MAX */

struct png_input {
    FILE *file;
    png_structp png;
    png_infop info;
    char name[256];
    struct vts_error error;  /* filled by the libpng callbacks */
    bool in_rows;            /* errors happen while decoding rows: name the row */
    bool broken;             /* the decoder stopped on an error: restart before the next read */
    bool read_failed;        /* the error is a failed read of the file (VTS_ERR_IO) */
    uint32_t width, height;  /* from IHDR */
    uint32_t channels;       /* after the transforms */
    uint32_t bit_depth;      /* after the transforms: 8 or 16 */
    size_t row_bytes;        /* of a transformed row */
    uint32_t next_row;       /* the row the next png_read_row() returns */
    bool interlaced;         /* Adam7: the whole image is decoded into image */
    unsigned char *row;      /* one transformed row */
    unsigned char *image;    /* de-interlaced image (interlaced files only) */
    png_bytep *row_pointers; /* into image, while it is decoded */
};

static void png_input_on_error(png_structp png, png_const_charp msg)
{
    struct png_input *t = png_get_error_ptr(png);
    if (t->error.status == VTS_OK) {
        int status = t->read_failed          ? VTS_ERR_IO
                     : strstr(msg, "memory") ? VTS_ERR_NOMEM
                                             : VTS_ERR_BAD_INPUT;
        if (t->in_rows)
            vt_error_set(&t->error, status, "cannot read '%s': %s at row %u", t->name, msg,
                         t->next_row);
        else
            vt_error_set(&t->error, status, "cannot read '%s': %s", t->name, msg);
    }
    png_longjmp(png, 1);
}

static void png_input_on_warning(png_structp png, png_const_charp msg)
{
    (void)png; /* warnings concern ancillary chunks, which are not used */
    (void)msg;
}

static void png_input_on_read(png_structp png, png_bytep data, size_t length)
{
    struct png_input *t = png_get_io_ptr(png);
    if (fread(data, 1, length, t->file) == length)
        return;
    if (!ferror(t->file))
        png_error(png, "truncated");
    t->read_failed = true; /* the message is the reason, "Input/output error" */
    png_error(png, strerror(errno));
}

/* The status of a run that libpng stopped; the decoder is unusable until restarted. */
static int png_input_stopped(struct png_input *t)
{
    t->broken = true;
    if (t->error.status == VTS_OK)
        vt_error_set(&t->error, VTS_ERR_BAD_INPUT, "cannot read '%s': libpng stopped", t->name);
    return t->error.status;
}

static void png_input_destroy_decoder(struct png_input *t)
{
    if (t->png)
        png_destroy_read_struct(&t->png, t->info ? &t->info : NULL, NULL);
    t->png = NULL;
    t->info = NULL;
}

static void png_input_close(void *ctx)
{
    struct png_input *t = ctx;
    if (!t)
        return;
    png_input_destroy_decoder(t);
    if (t->file)
        fclose(t->file);
    free(t->row);
    free(t->image);
    free(t->row_pointers);
    free(t);
}

/* Reads the header and sets up the transforms; leaves the decoder at row 0. */
static void png_input_start_body(struct png_input *t)
{
    png_structp png = t->png;
    png_infop info = t->info;
    png_set_read_fn(png, t, png_input_on_read);
    png_set_user_limits(png, PNG_INPUT_MAX_EDGE, PNG_INPUT_MAX_EDGE);
    png_read_info(png, info);
    int colour_type = png_get_color_type(png, info);
    int bit_depth = png_get_bit_depth(png, info);
    if (colour_type == PNG_COLOR_TYPE_PALETTE)
        png_set_palette_to_rgb(png);
    if (colour_type == PNG_COLOR_TYPE_GRAY && bit_depth < 8)
        png_set_expand_gray_1_2_4_to_8(png);
    if (png_get_valid(png, info, PNG_INFO_tRNS))
        png_set_tRNS_to_alpha(png);
    if (bit_depth == 16) {
        const uint16_t one = 1;
        unsigned char first;
        memcpy(&first, &one, 1);
        if (first == 1)
            png_set_swap(png); /* PNG is big-endian */
    }
    t->interlaced = png_get_interlace_type(png, info) != PNG_INTERLACE_NONE;
    if (t->interlaced)
        png_set_interlace_handling(png);
    png_read_update_info(png, info);
    t->width = png_get_image_width(png, info);
    t->height = png_get_image_height(png, info);
    t->channels = png_get_channels(png, info);
    t->bit_depth = png_get_bit_depth(png, info);
    t->row_bytes = png_get_rowbytes(png, info);
}

static int png_input_start_run(struct png_input *t)
{
    if (setjmp(png_jmpbuf(t->png)))
        return png_input_stopped(t);
    png_input_start_body(t);
    return 0;
}

/* (Re)creates the decoder at the start of the file and reads the header. */
static int png_input_start(struct png_input *t, struct vts_error *err)
{
    png_input_destroy_decoder(t);
    vt_error_clear(&t->error);
    t->read_failed = false;
    t->in_rows = false;
    t->next_row = 0;
    if (fseek(t->file, 0, SEEK_SET) != 0)
        return vt_error_set(err, VTS_ERR_IO, "cannot read '%s': %s", t->name, strerror(errno));
    clearerr(t->file);
    t->png =
        png_create_read_struct(PNG_LIBPNG_VER_STRING, t, png_input_on_error, png_input_on_warning);
    t->info = t->png ? png_create_info_struct(t->png) : NULL;
    if (!t->info)
        return vt_error_set(err, VTS_ERR_NOMEM, "cannot read '%s': out of memory", t->name);
    if (png_input_start_run(t) < 0)
        return vt_error_set(err, t->error.status, "%s", t->error.message);
    t->broken = false;
    return 0;
}

/* Reads the size from IHDR before libpng allocates anything, so that the limit comes first. */
static int png_input_check_header(struct png_input *t, uint64_t max_pixels, struct vts_error *err)
{
    unsigned char h[24];
    if (fread(h, 1, sizeof h, t->file) != sizeof h)
        return vt_error_set(err, VTS_ERR_BAD_INPUT, "cannot read '%s': truncated header", t->name);
    if (memcmp(h + 12, "IHDR", 4) != 0)
        return vt_error_set(err, VTS_ERR_BAD_INPUT, "cannot read '%s': no IHDR chunk", t->name);
    uint32_t w = (uint32_t)h[16] << 24 | (uint32_t)h[17] << 16 | (uint32_t)h[18] << 8 | h[19];
    uint32_t ht = (uint32_t)h[20] << 24 | (uint32_t)h[21] << 16 | (uint32_t)h[22] << 8 | h[23];
    int rc = vt_input_check_size(t->name, w, ht, max_pixels, err);
    if (rc == 0 && (uint64_t)w * 8 > VT_INPUT_MAX_BUFFER_BYTES) /* RGBA16 rows, before libpng's */
        rc = vt_error_set(err, VTS_ERR_LIMIT, "'%s': rows of %u texels are too long", t->name, w);
    return rc;
}

static int png_input_read_region(void *ctx, uint32_t x, uint32_t y, struct vt_image *dst,
                                 struct vts_error *err);

static const struct vt_source_ops png_input_ops = {png_input_read_region, png_input_close};

static int png_open(const char *path, uint64_t max_pixels, struct vt_source *out,
                    struct vts_error *err)
{
    struct png_input *t = calloc(1, sizeof *t);
    if (!t)
        return vt_error_set(err, VTS_ERR_NOMEM, "cannot read '%s': out of memory", path);
    vt_input_copy_name(t->name, sizeof t->name, path);
    int rc;
    t->file = fopen(path, "rb");
    if (!t->file) {
        rc = vt_error_set(err, VTS_ERR_IO, "cannot open '%s': %s", path, strerror(errno));
        goto out_close;
    }
    rc = png_input_check_header(t, max_pixels, err);
    if (rc == 0)
        rc = png_input_start(t, err);
    if (rc < 0)
        goto out_close;
    size_t sb = t->bit_depth / 8;
    if (t->channels < 1 || t->channels > 4 || (sb != 1 && sb != 2) ||
        t->row_bytes != (size_t)t->width * t->channels * sb) {
        rc = vt_error_set(err, VTS_ERR_UNSUPPORTED,
                          "cannot read '%s': %u channels of %u bits in %zu-byte rows", path,
                          t->channels, t->bit_depth, t->row_bytes);
        goto out_close;
    }
    t->row = malloc(t->row_bytes);
    if (!t->row) {
        rc = vt_error_set(err, VTS_ERR_NOMEM, "cannot read '%s': out of memory", path);
        goto out_close;
    }
    vt_input_set_info(&out->info, t->width, t->height, t->channels,
                      sb == 2 ? VTS_SAMPLE_U16 : VTS_SAMPLE_U8, true, 0, 0, "png");
    out->ops = &png_input_ops;
    out->ctx = t;
    return 0;

out_close:
    png_input_close(t);
    return rc;
}

/* ---- rows ---- */

static void png_input_rows_body(struct png_input *t, uint32_t x, uint32_t y, struct vt_image *dst)
{
    size_t texel = vt_image_texel_bytes(dst);
    t->in_rows = true;
    while (t->next_row < y) {
        png_read_row(t->png, t->row, NULL);
        t->next_row++;
    }
    for (uint32_t r = 0; r < dst->height; r++) {
        png_read_row(t->png, t->row, NULL);
        t->next_row++;
        memcpy(vt_image_at(dst, 0, r), t->row + (size_t)x * texel, (size_t)dst->width * texel);
    }
}

static int png_input_rows_run(struct png_input *t, uint32_t x, uint32_t y, struct vt_image *dst)
{
    if (setjmp(png_jmpbuf(t->png)))
        return png_input_stopped(t);
    png_input_rows_body(t, x, y, dst);
    return 0;
}

static int png_input_deinterlace_run(struct png_input *t)
{
    if (setjmp(png_jmpbuf(t->png)))
        return png_input_stopped(t);
    t->in_rows = true;
    png_read_image(t->png, t->row_pointers);
    return 0;
}

/* Decodes the whole interlaced image into t->image once. */
static int png_input_deinterlace(struct png_input *t, struct vts_error *err)
{
    size_t bytes;
    if (!vt_size_mul(t->row_bytes, t->height, &bytes) || bytes > VT_INPUT_MAX_BUFFER_BYTES)
        return vt_error_set(
            err, VTS_ERR_UNSUPPORTED,
            "cannot read '%s': interlaced PNG of %ux%u texels is too big to de-interlace (save it non-interlaced)",
            t->name, t->width, t->height);
    t->image = malloc(bytes);
    t->row_pointers = malloc(sizeof *t->row_pointers * t->height);
    if (!t->image || !t->row_pointers)
        return vt_error_set(err, VTS_ERR_NOMEM, "cannot read '%s': out of memory", t->name);
    for (uint32_t r = 0; r < t->height; r++)
        t->row_pointers[r] = t->image + (size_t)r * t->row_bytes;
    int rc = png_input_deinterlace_run(t);
    free(t->row_pointers);
    t->row_pointers = NULL;
    if (rc < 0) {
        free(t->image);
        t->image = NULL;
        return vt_error_set(err, t->error.status, "%s", t->error.message);
    }
    png_input_destroy_decoder(t); /* everything is in memory now */
    return 0;
}

static int png_input_read_region(void *ctx, uint32_t x, uint32_t y, struct vt_image *dst,
                                 struct vts_error *err)
{
    struct png_input *t = ctx;
    int rc;
    if (t->interlaced) {
        if (!t->image) {
            if ((t->broken || !t->png) && (rc = png_input_start(t, err)) < 0)
                return rc;
            if ((rc = png_input_deinterlace(t, err)) < 0)
                return rc;
        }
        size_t texel = vt_image_texel_bytes(dst);
        for (uint32_t r = 0; r < dst->height; r++)
            memcpy(vt_image_at(dst, 0, r), t->image + (size_t)(y + r) * t->row_bytes + x * texel,
                   (size_t)dst->width * texel);
        return 0;
    }
    if ((t->broken || y < t->next_row) && (rc = png_input_start(t, err)) < 0)
        return rc;
    if (png_input_rows_run(t, x, y, dst) < 0)
        return vt_error_set(err, t->error.status, "%s", t->error.message);
    return 0;
}

static bool png_sniff(const unsigned char *magic, size_t len)
{
    static const unsigned char png[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    return len >= 8 && memcmp(magic, png, 8) == 0;
}

const struct vt_input_reader vt_input_reader_png = {"png", png_sniff, png_open};
