/* JPEG input through the libjpeg API of libjpeg-turbo: grey -> 1 channel, YCbCr/RGB -> RGB, 8-bit.
 * Texels equal a full decode with libjpeg's defaults. A decode session crops to the columns a
 * region needs plus one iMCU each side (jpeg_crop_scanline; whole width for full-width regions),
 * skips rows above it (jpeg_skip_scanlines) and keeps its position, so bands read top-down decode
 * each row once; a region above the current row or outside the session's columns restarts the
 * decode from the top of the file. A truncated file is an error (libjpeg would pad it with grey and
 * warn); other corrupt-data warnings are not.
 *
 * setjmp/longjmp stay in this file; the functions that call setjmp (*_run) change no local after
 * it (C11 7.13.2.1). */
#include <errno.h>
#include <setjmp.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <jerror.h>
#include <jpeglib.h>

#include "internal/vt_input_readers.h"
#include "internal/vt_input_util.h"
#include "vt_error.h"

/* Memory a decode may use before it is refused: a progressive JPEG keeps every coefficient of the
 * image (2 bytes per sample), so this admits progressive 4:2:0 images up to ~26k x 26k texels and
 * 4:4:4 ones up to ~18k x 18k; baseline JPEGs need a few rows only. */
#define JPEG_INPUT_MAX_MEMORY (2ull << 30)

struct jpeg_input;

struct jpeg_input_error {
    struct jpeg_error_mgr mgr; /* first: libjpeg sees this struct as a jpeg_error_mgr */
    struct jpeg_input *input;
    jmp_buf jump;
};

struct jpeg_input {
    FILE *file;
    struct jpeg_decompress_struct cinfo;
    struct jpeg_input_error jerr;
    bool created; /* jpeg_create_decompress() done */
    bool started; /* a decode session is running (jpeg_start_decompress() done) */
    bool in_rows; /* errors happen while decoding rows: name the row */
    char name[256];
    struct vts_error error; /* filled by the error handler */
    uint32_t width, height, channels;
    JDIMENSION crop_x; /* first column of the running session (output_width columns) */
    unsigned char *row;
};

/* Records the message (once per failure) and jumps back to the *_run function. */
static void jpeg_input_fail(j_common_ptr cinfo, bool truncated)
{
    int read_errno = errno; /* of the failed fread() when libjpeg's source stopped on one */
    struct jpeg_input_error *jerr = (struct jpeg_input_error *)cinfo->err;
    struct jpeg_input *t = jerr->input;
    if (t->error.status == VTS_OK) {
        char msg[JMSG_LENGTH_MAX];
        int code = cinfo->err->msg_code;
        int status = VTS_ERR_BAD_INPUT;
        /* libjpeg's stdio source takes a failed read for the end of the file ("Empty input
         * file", or padding with a warning that reads as truncated): the stream says which */
        if (ferror(t->file)) {
            snprintf(msg, sizeof msg, "%s", strerror(read_errno));
            status = VTS_ERR_IO;
        } else if (truncated)
            snprintf(msg, sizeof msg, "truncated");
        else if (code == JERR_NO_BACKING_STORE)
            snprintf(msg, sizeof msg, "decoding needs more than %llu MiB (progressive JPEG?)",
                     (unsigned long long)(JPEG_INPUT_MAX_MEMORY >> 20));
        else
            cinfo->err->format_message(cinfo, msg);
        if (code == JERR_OUT_OF_MEMORY)
            status = VTS_ERR_NOMEM;
        else if (code == JERR_BAD_PRECISION || code == JERR_NO_BACKING_STORE ||
                 code == JERR_CONVERSION_NOTIMPL)
            status = VTS_ERR_UNSUPPORTED;
        if (t->in_rows)
            vt_error_set(&t->error, status, "cannot read '%s': %s at row %u", t->name, msg,
                         (unsigned)t->cinfo.output_scanline);
        else
            vt_error_set(&t->error, status, "cannot read '%s': %s", t->name, msg);
    }
    longjmp(jerr->jump, 1);
}

static void jpeg_input_error_exit(j_common_ptr cinfo)
{
    jpeg_input_fail(cinfo, false);
}

static void jpeg_input_emit_message(j_common_ptr cinfo, int msg_level)
{
    int code = cinfo->err->msg_code;
    if (msg_level < 0 && (code == JWRN_JPEG_EOF || code == JWRN_HIT_MARKER))
        jpeg_input_fail(cinfo, true); /* the file ends early: do not return padded rows */
    if (msg_level < 0)
        cinfo->err->num_warnings++;
}

static void jpeg_input_output_message(j_common_ptr cinfo)
{
    (void)cinfo; /* libjpeg never prints */
}

/* The status of a run that libjpeg stopped; the session is over. */
static int jpeg_input_stopped(struct jpeg_input *t, struct vts_error *err)
{
    t->started = false;
    if (t->error.status == VTS_OK)
        vt_error_set(&t->error, VTS_ERR_BAD_INPUT, "cannot read '%s': libjpeg stopped", t->name);
    return vt_error_set(err, t->error.status, "%s", t->error.message);
}

static void jpeg_input_close(void *ctx)
{
    struct jpeg_input *t = ctx;
    if (!t)
        return;
    if (t->created)
        jpeg_destroy_decompress(&t->cinfo);
    if (t->file)
        fclose(t->file);
    free(t->row);
    free(t);
}

/* Rewinds and reads the header (the decompressor must be idle or aborted). */
static void jpeg_input_header_body(struct jpeg_input *t)
{
    if (!t->created) {
        jpeg_create_decompress(&t->cinfo);
        t->created = true;
        t->cinfo.mem->max_memory_to_use = (long)JPEG_INPUT_MAX_MEMORY;
    } else {
        jpeg_abort_decompress(&t->cinfo);
    }
    t->started = false;
    rewind(t->file);
    jpeg_stdio_src(&t->cinfo, t->file);
    jpeg_read_header(&t->cinfo, TRUE);
}

static int jpeg_input_header_run(struct jpeg_input *t)
{
    if (setjmp(t->jerr.jump))
        return -1;
    jpeg_input_header_body(t);
    return 0;
}

/* Starts a session that outputs at least columns [x, x + w). */
static void jpeg_input_start_body(struct jpeg_input *t, uint32_t x, uint32_t w)
{
    jpeg_input_header_body(t);
    t->cinfo.out_color_space = t->channels == 1 ? JCS_GRAYSCALE : JCS_RGB;
    jpeg_start_decompress(&t->cinfo);
    t->started = true;
    t->crop_x = 0;
    /* The upsampler treats the crop's edges as image edges, so that with fancy (smoothed) chroma
     * upsampling the edge columns differ from a full decode: crop one iMCU wider on each side. */
    uint32_t margin = (uint32_t)t->cinfo.max_h_samp_factor * DCTSIZE;
    uint32_t x0 = x > margin ? x - margin : 0;
    uint32_t x1 = t->width - (x + w) > margin ? x + w + margin : t->width;
    if (x0 != 0 || x1 != t->width) {
        JDIMENSION crop_x = x0, crop_w = x1 - x0;
        jpeg_crop_scanline(&t->cinfo, &crop_x, &crop_w); /* widens to whole iMCUs */
        t->crop_x = crop_x;
    }
}

static int jpeg_input_start_run(struct jpeg_input *t, uint32_t x, uint32_t w)
{
    if (setjmp(t->jerr.jump))
        return -1;
    jpeg_input_start_body(t, x, w);
    return 0;
}

static int jpeg_input_read_region(void *ctx, uint32_t x, uint32_t y, struct vt_image *dst,
                                  struct vts_error *err);

static const struct vt_source_ops jpeg_input_ops = {jpeg_input_read_region, jpeg_input_close};

/* Checks what jpeg_read_header() found. */
static int jpeg_input_check_header(struct jpeg_input *t, uint64_t max_pixels, struct vts_error *err)
{
    struct jpeg_decompress_struct *c = &t->cinfo;
    int rc = vt_input_check_size(t->name, c->image_width, c->image_height, max_pixels, err);
    if (rc < 0)
        return rc;
    t->width = c->image_width;
    t->height = c->image_height;
    if (c->jpeg_color_space == JCS_GRAYSCALE && c->num_components == 1)
        t->channels = 1;
    else if ((c->jpeg_color_space == JCS_YCbCr || c->jpeg_color_space == JCS_RGB) &&
             c->num_components == 3)
        t->channels = 3;
    else
        return vt_error_set(
            err, VTS_ERR_UNSUPPORTED,
            "cannot read '%s': JPEG colour space %d with %d components (grey and RGB/YCbCr are supported)",
            t->name, (int)c->jpeg_color_space, c->num_components);
    t->row = malloc((size_t)t->width * t->channels);
    if (!t->row)
        return vt_error_set(err, VTS_ERR_NOMEM, "cannot read '%s': out of memory", t->name);
    return 0;
}

static int jpeg_open(const char *path, uint64_t max_pixels, struct vt_source *out,
                     struct vts_error *err)
{
    struct jpeg_input *t = calloc(1, sizeof *t);
    if (!t)
        return vt_error_set(err, VTS_ERR_NOMEM, "cannot read '%s': out of memory", path);
    vt_input_copy_name(t->name, sizeof t->name, path);
    t->cinfo.err = jpeg_std_error(&t->jerr.mgr);
    t->jerr.mgr.error_exit = jpeg_input_error_exit;
    t->jerr.mgr.emit_message = jpeg_input_emit_message;
    t->jerr.mgr.output_message = jpeg_input_output_message;
    t->jerr.input = t;
    int rc;
    t->file = fopen(path, "rb");
    if (!t->file) {
        rc = vt_error_set(err, VTS_ERR_IO, "cannot open '%s': %s", path, strerror(errno));
        goto out_close;
    }
    if (jpeg_input_header_run(t) < 0) {
        rc = jpeg_input_stopped(t, err);
        goto out_close;
    }
    rc = jpeg_input_check_header(t, max_pixels, err);
    if (rc < 0)
        goto out_close;
    vt_input_set_info(&out->info, t->width, t->height, t->channels, VTS_SAMPLE_U8, true, 0, 0,
                      "jpeg");
    out->ops = &jpeg_input_ops;
    out->ctx = t;
    return 0;

out_close:
    jpeg_input_close(t);
    return rc;
}

/* ---- rows ---- */

static void jpeg_input_rows_body(struct jpeg_input *t, uint32_t x, uint32_t y, struct vt_image *dst)
{
    struct jpeg_decompress_struct *c = &t->cinfo;
    t->in_rows = true;
    if (y > c->output_scanline) {
        JDIMENSION skip = y - c->output_scanline;
        if (jpeg_skip_scanlines(c, skip) != skip)
            jpeg_input_fail((j_common_ptr)c, true);
    }
    size_t texel = t->channels;
    for (uint32_t r = 0; r < dst->height; r++) {
        JSAMPROW row = t->row;
        if (jpeg_read_scanlines(c, &row, 1) != 1)
            jpeg_input_fail((j_common_ptr)c, true);
        memcpy(vt_image_at(dst, 0, r), t->row + (x - t->crop_x) * texel,
               (size_t)dst->width * texel);
    }
    t->in_rows = false;
}

static int jpeg_input_rows_run(struct jpeg_input *t, uint32_t x, uint32_t y, struct vt_image *dst)
{
    if (setjmp(t->jerr.jump))
        return -1;
    jpeg_input_rows_body(t, x, y, dst);
    return 0;
}

static int jpeg_input_read_region(void *ctx, uint32_t x, uint32_t y, struct vt_image *dst,
                                  struct vts_error *err)
{
    struct jpeg_input *t = ctx;
    struct jpeg_decompress_struct *c = &t->cinfo;
    vt_error_clear(&t->error);
    t->in_rows = false;
    bool reuse = t->started && y >= c->output_scanline && x >= t->crop_x &&
                 x + dst->width <= t->crop_x + c->output_width;
    if (!reuse && jpeg_input_start_run(t, x, dst->width) < 0)
        return jpeg_input_stopped(t, err);
    if (c->output_components != (int)t->channels || t->crop_x > x ||
        x + dst->width > t->crop_x + c->output_width) {
        t->started = false;
        return vt_error_set(err, VTS_ERR_BAD_INPUT, "cannot read '%s': unexpected decoder output",
                            t->name);
    }
    if (jpeg_input_rows_run(t, x, y, dst) < 0)
        return jpeg_input_stopped(t, err);
    return 0;
}

/* SOI followed by the first marker's 0xff. */
static bool jpeg_sniff(const unsigned char *magic, size_t len)
{
    return len >= 3 && magic[0] == 0xff && magic[1] == 0xd8 && magic[2] == 0xff;
}

const struct vt_input_reader vt_input_reader_jpeg = {"jpeg", jpeg_sniff, jpeg_open};
