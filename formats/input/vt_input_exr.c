/* OpenEXR input through the OpenEXRCore C API (3.1): part 0, level 0, scanline or tiled. Channels
 * are chosen by name: R,G,B (+A), else Y (+A), else all of them when there are at most 4 (in the
 * file's alphabetical order); other channels (Z, layers) are ignored. Samples stay half when every
 * chosen channel is half, else become float; uint channels are refused. Texel (0,0) is the data
 * window's corner.
 *
 * Each chunk is decoded planar, one plane per channel, and interleaved here: in 3.1.5 decoding
 * half channels straight into interleaved float RGBA puts them in the file's order (A,B,G,R), and
 * the chunk of a tile gives tile indices, not texels, in start_x/start_y (PLATFORM.md). The last
 * decoded chunk is kept, so bands that cross a chunk boundary decode it once. */
#include <errno.h>
#include <fcntl.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <OpenEXR/openexr.h>

#include "internal/vt_input_readers.h"
#include "internal/vt_input_util.h"
#include "vt_checked.h"
#include "vt_error.h"

struct exr_input {
    int fd;
    exr_context_t exr;
    char name[256];
    char message[160]; /* the last error OpenEXR reported */
    uint32_t width, height;
    int32_t x0, y0;      /* data window corner */
    uint32_t channels;   /* output channels */
    int file_channel[4]; /* output channel -> index in the file's channel list */
    uint32_t sample;     /* VTS_SAMPLE_F16 or VTS_SAMPLE_F32 */
    size_t sample_bytes;
    bool tiled;
    uint32_t chunk_w, chunk_h; /* tile size, or width x scanlines per chunk */
    exr_decode_pipeline_t decoder;
    bool decoder_ready;
    unsigned char *planes; /* channels planes of chunk_w * chunk_h samples */
    size_t plane_bytes;
    uint64_t cached;             /* 1 + index of the chunk in planes, 0 = none */
    uint32_t cached_w, cached_h; /* its size (edge chunks are smaller) */
};

/* Copies text from the file (channel and attribute names inside OpenEXR's messages) into dst with
 * control characters replaced by '?', so that messages stay on one line. */
static void exr_one_line(char *dst, size_t cap, const char *src)
{
    snprintf(dst, cap, "%s", src);
    for (unsigned char *p = (unsigned char *)dst; *p; p++)
        if (*p < 0x20 || *p == 0x7f)
            *p = '?';
}

static void exr_input_on_error(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
    void *user = NULL;
    if (!ctxt || exr_get_user_data(ctxt, &user) != EXR_ERR_SUCCESS || !user)
        return;
    struct exr_input *t = user;
    exr_one_line(t->message, sizeof t->message, msg ? msg : exr_get_default_error_message(code));
}

static int64_t exr_input_read(exr_const_context_t ctxt, void *user, void *buffer, uint64_t size,
                              uint64_t offset, exr_stream_error_func_ptr_t error_cb)
{
    struct exr_input *t = user;
    uint64_t done = 0;
    while (done < size) {
        ssize_t n = pread(t->fd, (char *)buffer + done, size - done, (off_t)(offset + done));
        if (n < 0 && errno == EINTR)
            continue;
        if (n < 0) {
            error_cb(ctxt, EXR_ERR_READ_IO, "read error: %s", strerror(errno));
            return -1;
        }
        if (n == 0)
            break; /* end of file: the caller reports the short read */
        done += (uint64_t)n;
    }
    return (int64_t)done;
}

static int64_t exr_input_size(exr_const_context_t ctxt, void *user)
{
    (void)ctxt;
    struct exr_input *t = user;
    struct stat st;
    return fstat(t->fd, &st) == 0 ? (int64_t)st.st_size : -1;
}

static void exr_input_close(void *ctx)
{
    struct exr_input *t = ctx;
    if (!t)
        return;
    if (t->decoder_ready)
        exr_decoding_destroy(t->exr, &t->decoder);
    if (t->exr)
        exr_finish(&t->exr);
    if (t->fd >= 0)
        close(t->fd);
    free(t->planes);
    free(t);
}

static int exr_input_status(exr_result_t rv)
{
    if (rv == EXR_ERR_OUT_OF_MEMORY)
        return VTS_ERR_NOMEM;
    if (rv == EXR_ERR_FEATURE_NOT_IMPLEMENTED)
        return VTS_ERR_UNSUPPORTED;
    return VTS_ERR_BAD_INPUT;
}

static const char *exr_input_message(const struct exr_input *t, exr_result_t rv)
{
    return t->message[0] ? t->message : exr_get_default_error_message(rv);
}

/* Index of the channel called name in list, or -1. */
static int exr_find_channel(const exr_attr_chlist_t *list, const char *name)
{
    for (int i = 0; i < list->num_channels; i++)
        if (list->entries[i].name.str && strcmp(list->entries[i].name.str, name) == 0)
            return i;
    return -1;
}

/* Chooses the output channels (t->file_channel) and the sample type; sets *has_alpha. */
static int exr_choose_channels(struct exr_input *t, const exr_attr_chlist_t *list, bool *has_alpha,
                               struct vts_error *err)
{
    int r = exr_find_channel(list, "R"), g = exr_find_channel(list, "G");
    int b = exr_find_channel(list, "B"), a = exr_find_channel(list, "A");
    int y = exr_find_channel(list, "Y");
    t->channels = 0;
    if (r >= 0 && g >= 0 && b >= 0) {
        t->file_channel[t->channels++] = r;
        t->file_channel[t->channels++] = g;
        t->file_channel[t->channels++] = b;
    } else if (y >= 0) {
        t->file_channel[t->channels++] = y;
    } else if (list->num_channels >= 1 && list->num_channels <= 4) {
        for (int i = 0; i < list->num_channels; i++)
            if (i != a)
                t->file_channel[t->channels++] = i;
    } else {
        return vt_error_set(
            err, VTS_ERR_UNSUPPORTED,
            "cannot read '%s': %d channels, none named R, G, B or Y (at most 4 unnamed channels are supported)",
            t->name, list->num_channels);
    }
    *has_alpha = a >= 0;
    if (a >= 0)
        t->file_channel[t->channels++] = a;
    bool all_half = true;
    for (uint32_t c = 0; c < t->channels; c++) {
        const exr_attr_chlist_entry_t *e = &list->entries[t->file_channel[c]];
        if (e->x_sampling != 1 || e->y_sampling != 1 ||
            (e->pixel_type != EXR_PIXEL_HALF && e->pixel_type != EXR_PIXEL_FLOAT)) {
            char name[64];
            exr_one_line(name, sizeof name, e->name.str ? e->name.str : "");
            return vt_error_set(err, VTS_ERR_UNSUPPORTED,
                                "cannot read '%s': channel '%s' is subsampled or not half/float",
                                t->name, name);
        }
        all_half = all_half && e->pixel_type == EXR_PIXEL_HALF;
    }
    t->sample = all_half ? VTS_SAMPLE_F16 : VTS_SAMPLE_F32;
    t->sample_bytes = all_half ? 2 : 4;
    return 0;
}

/* Reads the size, storage and chunk shape of part 0. */
static int exr_check_layout(struct exr_input *t, uint64_t max_pixels, struct vts_error *err)
{
    exr_attr_box2i_t dw;
    exr_storage_t storage;
    exr_result_t rv = exr_get_data_window(t->exr, 0, &dw);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_get_storage(t->exr, 0, &storage);
    if (rv != EXR_ERR_SUCCESS)
        return vt_error_set(err, exr_input_status(rv), "cannot read '%s': %s", t->name,
                            exr_input_message(t, rv));
    int64_t w = (int64_t)dw.max.x - dw.min.x + 1, h = (int64_t)dw.max.y - dw.min.y + 1;
    int rc = vt_input_check_size(t->name, w > 0 ? (uint64_t)w : 0, h > 0 ? (uint64_t)h : 0,
                                 max_pixels, err);
    if (rc < 0)
        return rc;
    t->width = (uint32_t)w;
    t->height = (uint32_t)h;
    t->x0 = dw.min.x;
    t->y0 = dw.min.y;
    if (storage == EXR_STORAGE_TILED) {
        uint32_t tw = 0, th = 0;
        exr_tile_level_mode_t level_mode;
        exr_tile_round_mode_t round_mode;
        rv = exr_get_tile_descriptor(t->exr, 0, &tw, &th, &level_mode, &round_mode);
        if (rv != EXR_ERR_SUCCESS || tw == 0 || th == 0)
            return vt_error_set(err, VTS_ERR_BAD_INPUT, "cannot read '%s': bad tile description",
                                t->name);
        t->tiled = true;
        t->chunk_w = tw;
        t->chunk_h = th;
    } else if (storage == EXR_STORAGE_SCANLINE) {
        int32_t lines = 0;
        rv = exr_get_scanlines_per_chunk(t->exr, 0, &lines);
        if (rv != EXR_ERR_SUCCESS || lines <= 0)
            return vt_error_set(err, VTS_ERR_BAD_INPUT, "cannot read '%s': bad chunk description",
                                t->name);
        t->chunk_w = t->width;
        t->chunk_h = (uint32_t)lines;
    } else {
        return vt_error_set(err, VTS_ERR_UNSUPPORTED, "cannot read '%s': deep images", t->name);
    }
    return 0;
}

static int exr_input_read_region(void *ctx, uint32_t x, uint32_t y, struct vt_image *dst,
                                 struct vts_error *err);

static const struct vt_source_ops exr_input_ops = {exr_input_read_region, exr_input_close};

/* Everything after the file is open: header, channels, buffers. */
static int exr_input_setup(struct exr_input *t, uint64_t max_pixels, bool *has_alpha,
                           struct vts_error *err)
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = exr_input_on_error;
    init.user_data = t;
    init.read_fn = exr_input_read;
    init.size_fn = exr_input_size;
    exr_result_t rv = exr_start_read(&t->exr, t->name, &init);
    if (rv != EXR_ERR_SUCCESS)
        return vt_error_set(err, exr_input_status(rv), "cannot read '%s': %s", t->name,
                            exr_input_message(t, rv));
    int rc = exr_check_layout(t, max_pixels, err);
    if (rc < 0)
        return rc;
    const exr_attr_chlist_t *list = NULL;
    rv = exr_get_channels(t->exr, 0, &list);
    if (rv != EXR_ERR_SUCCESS || !list || list->num_channels <= 0)
        return vt_error_set(err, VTS_ERR_BAD_INPUT, "cannot read '%s': no channels", t->name);
    rc = exr_choose_channels(t, list, has_alpha, err);
    if (rc < 0)
        return rc;
    size_t all; /* a chunk never exceeds the image */
    uint32_t buf_w = t->chunk_w < t->width ? t->chunk_w : t->width;
    uint32_t buf_h = t->chunk_h < t->height ? t->chunk_h : t->height;
    if (!vt_size_mul3(buf_w, buf_h, t->sample_bytes, &t->plane_bytes) ||
        !vt_size_mul(t->plane_bytes, t->channels, &all) || all > VT_INPUT_MAX_BUFFER_BYTES)
        return vt_error_set(err, VTS_ERR_BAD_INPUT, "cannot read '%s': chunks of %ux%u texels",
                            t->name, t->chunk_w, t->chunk_h);
    t->planes = malloc(all);
    if (!t->planes)
        return vt_error_set(err, VTS_ERR_NOMEM, "cannot read '%s': out of memory", t->name);
    return 0;
}

static int exr_open(const char *path, uint64_t max_pixels, struct vt_source *out,
                    struct vts_error *err)
{
    struct exr_input *t = calloc(1, sizeof *t);
    if (!t)
        return vt_error_set(err, VTS_ERR_NOMEM, "cannot read '%s': out of memory", path);
    vt_input_copy_name(t->name, sizeof t->name, path);
    int rc;
    t->fd = open(path, O_RDONLY | O_CLOEXEC);
    if (t->fd < 0) {
        rc = vt_error_set(err, VTS_ERR_IO, "cannot open '%s': %s", path, strerror(errno));
        goto out_close;
    }
    bool has_alpha = false;
    rc = exr_input_setup(t, max_pixels, &has_alpha, err);
    if (rc < 0)
        goto out_close;
    vt_input_set_info(&out->info, t->width, t->height, t->channels, t->sample, !t->tiled,
                      t->tiled ? t->chunk_w : 0, t->tiled ? t->chunk_h : 0, "exr");
    out->info.has_alpha = has_alpha;
    out->info.premultiplied = has_alpha; /* OpenEXR stores associated (premultiplied) alpha */
    out->ops = &exr_input_ops;
    out->ctx = t;
    return 0;

out_close:
    exr_input_close(t);
    return rc;
}

/* ---- pixels ---- */

/* Finds the chunk (cx, cy) and checks its shape against the part's. */
static exr_result_t exr_chunk_info(struct exr_input *t, uint32_t cx, uint32_t cy,
                                   exr_chunk_info_t *ci)
{
    exr_result_t rv;
    if (t->tiled)
        rv = exr_read_tile_chunk_info(t->exr, 0, (int)cx, (int)cy, 0, 0, ci);
    else
        rv = exr_read_scanline_chunk_info(t->exr, 0, (int)(t->y0 + (int64_t)cy * t->chunk_h), ci);
    if (rv != EXR_ERR_SUCCESS)
        return rv;
    /* tiles: start_x/start_y are tile indices (OpenEXR 3.1.5) */
    int64_t sx = t->tiled ? (int64_t)ci->start_x * t->chunk_w : (int64_t)ci->start_x - t->x0;
    int64_t sy = t->tiled ? (int64_t)ci->start_y * t->chunk_h : (int64_t)ci->start_y - t->y0;
    uint32_t want_w =
        t->width - cx * t->chunk_w < t->chunk_w ? t->width - cx * t->chunk_w : t->chunk_w;
    uint32_t want_h =
        t->height - cy * t->chunk_h < t->chunk_h ? t->height - cy * t->chunk_h : t->chunk_h;
    if (sx != (int64_t)cx * t->chunk_w || sy != (int64_t)cy * t->chunk_h ||
        ci->width != (int32_t)want_w || ci->height != (int32_t)want_h) {
        snprintf(t->message, sizeof t->message, "chunk table does not match the image");
        return EXR_ERR_BAD_CHUNK_LEADER;
    }
    return EXR_ERR_SUCCESS;
}

/* Points the decoder's chosen channels at their planes, the others at nothing. */
static exr_result_t exr_set_outputs(struct exr_input *t, const exr_chunk_info_t *ci)
{
    exr_decode_pipeline_t *d = &t->decoder;
    for (int i = 0; i < d->channel_count; i++)
        d->channels[i].decode_to_ptr = NULL;
    for (uint32_t c = 0; c < t->channels; c++) {
        int i = t->file_channel[c];
        if (i >= d->channel_count || d->channels[i].width != ci->width ||
            d->channels[i].height != ci->height)
            return EXR_ERR_BAD_CHUNK_LEADER;
        exr_coding_channel_info_t *ch = &d->channels[i];
        ch->decode_to_ptr = t->planes + c * t->plane_bytes;
        ch->user_pixel_stride = (int32_t)t->sample_bytes;
        ch->user_line_stride = (int32_t)(t->sample_bytes * (size_t)ci->width);
        ch->user_bytes_per_element = (int16_t)t->sample_bytes;
        ch->user_data_type = t->sample == VTS_SAMPLE_F16 ? EXR_PIXEL_HALF : EXR_PIXEL_FLOAT;
    }
    return EXR_ERR_SUCCESS;
}

/* Decodes chunk (cx, cy) into t->planes unless it is already there. */
static int exr_load_chunk(struct exr_input *t, uint32_t cx, uint32_t cy, struct vts_error *err)
{
    uint64_t index = (uint64_t)cy * ((t->width - 1) / t->chunk_w + 1) + cx;
    if (t->cached == index + 1)
        return 0;
    t->cached = 0;
    t->message[0] = '\0';
    exr_chunk_info_t ci;
    exr_result_t rv = exr_chunk_info(t, cx, cy, &ci);
    if (rv == EXR_ERR_SUCCESS) {
        if (!t->decoder_ready) {
            rv = exr_decoding_initialize(t->exr, 0, &ci, &t->decoder);
            t->decoder_ready = rv == EXR_ERR_SUCCESS;
        } else {
            rv = exr_decoding_update(t->exr, 0, &ci, &t->decoder);
        }
    }
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_set_outputs(t, &ci);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_decoding_choose_default_routines(t->exr, 0, &t->decoder);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_decoding_run(t->exr, 0, &t->decoder);
    if (rv != EXR_ERR_SUCCESS)
        return vt_error_set(err, exr_input_status(rv), "cannot read '%s': %s at %u,%u: %s", t->name,
                            t->tiled ? "tile" : "chunk", cx * t->chunk_w, cy * t->chunk_h,
                            exr_input_message(t, rv));
    t->cached = index + 1;
    t->cached_w = (uint32_t)ci.width;
    t->cached_h = (uint32_t)ci.height;
    return 0;
}

/* Interleaves rows [r0, r1) x columns [c0, c1) of the decoded chunk at (px, py) into dst. */
static void exr_copy_chunk(const struct exr_input *t, uint32_t px, uint32_t py, uint32_t c0,
                           uint32_t c1, uint32_t r0, uint32_t r1, uint32_t x, uint32_t y,
                           struct vt_image *dst)
{
    size_t sb = t->sample_bytes;
    for (uint32_t r = r0; r < r1; r++) {
        unsigned char *out = vt_image_at(dst, px + c0 - x, py + r - y);
        for (uint32_t c = 0; c < t->channels; c++) {
            const unsigned char *plane =
                t->planes + c * t->plane_bytes + ((size_t)r * t->cached_w + c0) * sb;
            for (uint32_t i = 0; i < c1 - c0; i++)
                memcpy(out + (i * t->channels + c) * sb, plane + i * sb, sb);
        }
    }
}

static int exr_input_read_region(void *ctx, uint32_t x, uint32_t y, struct vt_image *dst,
                                 struct vts_error *err)
{
    struct exr_input *t = ctx;
    uint32_t x_end = x + dst->width, y_end = y + dst->height;
    for (uint32_t cy = y / t->chunk_h; cy <= (y_end - 1) / t->chunk_h; cy++) {
        uint32_t py = cy * t->chunk_h;
        uint32_t r0 = y > py ? y - py : 0;
        uint32_t r1 = y_end - py < t->chunk_h ? y_end - py : t->chunk_h;
        for (uint32_t cx = x / t->chunk_w; cx <= (x_end - 1) / t->chunk_w; cx++) {
            uint32_t px = cx * t->chunk_w;
            uint32_t c0 = x > px ? x - px : 0;
            uint32_t c1 = x_end - px < t->chunk_w ? x_end - px : t->chunk_w;
            int rc = exr_load_chunk(t, cx, cy, err);
            if (rc < 0)
                return rc;
            exr_copy_chunk(t, px, py, c0, c1, r0, r1, x, y, dst);
        }
    }
    return 0;
}

static bool exr_sniff(const unsigned char *magic, size_t len)
{
    static const unsigned char exr[4] = {0x76, 0x2f, 0x31, 0x01};
    return len >= 4 && memcmp(magic, exr, 4) == 0;
}

const struct vt_input_reader vt_input_reader_exr = {"exr", exr_sniff, exr_open};
