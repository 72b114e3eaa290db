#include "vt_tile_reader.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tool_common.h"
#include "vt_checked.h"
#include "vt_error.h"
#include "vt_png_file.h"
#include "vt_tiff_file.h"

int vt_tile_reader_init(struct vt_tile_reader *r, const struct vts_store *store, uint32_t layer,
                        struct vts_error *err)
{
    const struct vts_geometry *g = vts_store_geometry(store);
    const struct vts_layer *l = vts_store_layer(store, layer);
    char codec[5];
    assert(l);
    *r = (struct vt_tile_reader){.store = store, .layer = layer};
    r->codec = vt_codec_by_fourcc(l->codec);
    if (!r->codec) {
        vts_codec_name(l->codec, codec);
        return vt_error_set(err, VTS_ERR_UNSUPPORTED,
                            "'%s': layer %u uses codec '%s', which this build cannot decode",
                            vts_store_name(store), layer, codec);
    }
    r->payload = malloc((size_t)vts_store_max_payload(store) + 1);
    if (!r->payload)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory reading '%s'",
                            vts_store_name(store));
    return vt_image_alloc(&r->img, g->tile_payload_px, g->tile_payload_px, l->channels, l->sample,
                          err);
}

void vt_tile_reader_release(struct vt_tile_reader *r)
{
    if (!r)
        return;
    free(r->payload);
    r->payload = NULL;
    vt_image_release(&r->img);
}

/* An empty tile: zeros, or r->fill where the sample type holds it. */
static void tile_reader_fill_empty(struct vt_tile_reader *r)
{
    struct vt_image *img = &r->img;
    memset(img->pixels, 0, img->stride * img->height);
    double v = r->fill;
    bool integral = v == floor(v);
    if (!r->has_fill || v == 0)
        return;
    size_t n = (size_t)img->width * img->channels;
    for (uint32_t y = 0; y < img->height; y++) {
        unsigned char *row = (unsigned char *)img->pixels + y * img->stride;
        for (size_t i = 0; i < n; i++) {
            if (img->sample == VTS_SAMPLE_U8 && integral && v >= 0 && v <= 255)
                row[i] = (unsigned char)v;
            else if (img->sample == VTS_SAMPLE_U16 && integral && v >= 0 && v <= 65535)
                ((uint16_t *)(void *)row)[i] = (uint16_t)v;
            else if (img->sample == VTS_SAMPLE_F32)
                ((float *)(void *)row)[i] = (float)v;
        }
    }
}

int vt_tile_reader_read(struct vt_tile_reader *r, uint32_t level, uint32_t tx, uint32_t ty,
                        bool *stored, struct vts_error *err)
{
    struct vts_error why = {0};
    size_t len = 0;
    int rc = vts_store_read(r->store, r->layer, level, tx, ty, r->payload,
                            vts_store_max_payload(r->store), &len, 0, &why);
    if (rc == 0 && len == 0)
        tile_reader_fill_empty(r);
    else if (rc == 0 && !r->crc_only)
        rc = r->codec->decode(r->payload, len, &r->img, &why);
    *stored = len > 0;
    if (rc == 0)
        return 0;
    return vt_error_set(err, rc, "'%s': layer %u level %u tile %u,%u: %s", vts_store_name(r->store),
                        r->layer, level, tx, ty,
                        rc == VTS_ERR_CHECKSUM ? "payload checksum mismatch" : why.message);
}

uint32_t vt_tile_reader_png_depth(const struct vt_tile_reader *r)
{
    return r->img.sample == VTS_SAMPLE_U8 ? 8 : 16;
}

static float half_to_float(uint16_t h)
{
    int exponent = (h >> 10) & 31;
    float mantissa = (float)(h & 1023);
    float v = exponent == 0    ? ldexpf(mantissa, -24)
              : exponent == 31 ? (mantissa != 0 ? NAN : INFINITY)
                               : ldexpf(mantissa + 1024.0f, exponent - 25);
    return (h & 0x8000) ? -v : v;
}

static uint16_t unit_to_u16(float v)
{
    if (!(v > 0.0f)) /* negative, zero or NaN */
        return 0;
    return v >= 1.0f ? 65535 : (uint16_t)(v * 65535.0f + 0.5f);
}

void vt_tile_reader_png_row(const struct vt_tile_reader *r, uint32_t x, uint32_t y, uint32_t count,
                            void *dst)
{
    const unsigned char *src = vt_image_at(&r->img, x, y);
    size_t samples = (size_t)count * r->img.channels;
    assert(x + count <= r->img.width && y < r->img.height);
    if (r->img.sample == VTS_SAMPLE_U8 || r->img.sample == VTS_SAMPLE_U16) {
        memcpy(dst, src, samples * vts_sample_bytes(r->img.sample));
        return;
    }
    for (size_t i = 0; i < samples; i++) {
        uint16_t half, out;
        float f;
        if (r->img.sample == VTS_SAMPLE_F16) {
            memcpy(&half, src + 2 * i, 2);
            f = half_to_float(half);
        } else {
            memcpy(&f, src + 4 * i, 4);
        }
        out = unit_to_u16(f);
        memcpy((unsigned char *)dst + 2 * i, &out, 2);
    }
}

/* TIFF samples of the layer: u8 and u16 as they are, f16 and f32 as 32-bit floats. */
static uint32_t tiff_sample(const struct vt_tile_reader *r)
{
    return r->img.sample == VTS_SAMPLE_U8 || r->img.sample == VTS_SAMPLE_U16 ? r->img.sample
                                                                             : VTS_SAMPLE_F32;
}

/* Where extracted rows go: a PNG or a TIFF writer, and how a row of texels is converted. */
struct image_sink {
    struct vt_png_file_writer *png;
    struct vt_tiff_file_writer *tiff;
};

static void sink_row(const struct image_sink *k, const struct vt_tile_reader *r, uint32_t x,
                     uint32_t y, uint32_t count, void *dst)
{
    if (k->png || r->img.sample != VTS_SAMPLE_F16) {
        if (k->png || r->img.sample == VTS_SAMPLE_U8 || r->img.sample == VTS_SAMPLE_U16)
            vt_tile_reader_png_row(r, x, y, count, dst);
        else /* f32 into a float TIFF: the values */
            memcpy(dst, vt_image_at(&r->img, x, y), (size_t)count * r->img.channels * 4);
        return;
    }
    const unsigned char *src = vt_image_at(&r->img, x, y);
    for (size_t i = 0; i < (size_t)count * r->img.channels; i++) { /* f16: exact as floats */
        uint16_t half;
        memcpy(&half, src + 2 * i, 2);
        float f = half_to_float(half);
        memcpy((unsigned char *)dst + 4 * i, &f, 4);
    }
}

static int sink_rows(const struct image_sink *k, const void *rows, uint32_t count, size_t stride,
                     struct vts_error *err)
{
    return k->png ? vt_png_file_writer_rows(k->png, rows, count, stride, err)
                  : vt_tiff_file_writer_rows(k->tiff, rows, count, stride, err);
}

/* Writes tile (tx, ty) whole, one row at a time through row (row_bytes). */
static int write_tile_rows(struct vt_tile_reader *r, uint32_t level, uint32_t tx, uint32_t ty,
                           const struct image_sink *k, unsigned char *row, size_t row_bytes,
                           struct vts_error *err)
{
    bool stored;
    int rc = vt_tile_reader_read(r, level, tx, ty, &stored, err);
    for (uint32_t y = 0; rc == 0 && y < r->img.height; y++) {
        sink_row(k, r, 0, y, r->img.width, row);
        rc = sink_rows(k, row, 1, row_bytes, err);
    }
    return rc;
}

/* Writes the contents of every tile of level, one row of tiles (tile content rows) at a time. */
static int write_level_rows(struct vt_tile_reader *r, uint32_t level, const struct image_sink *k,
                            unsigned char *band, size_t row_bytes, struct vts_error *err)
{
    const struct vts_geometry *g = vts_store_geometry(r->store);
    uint32_t edge = g->tile_content_px, border = g->border_px;
    struct vt_progress progress;
    struct vts_level L;
    bool stored;
    int rc = 0;
    vts_store_level(r->store, level, &L);
    size_t texel_bytes = row_bytes / L.width;
    vt_progress_start(&progress, "extracting", "tiles", (uint64_t)L.tiles_x * L.tiles_y);
    for (uint32_t ty = 0; ty < L.tiles_y && rc == 0; ty++) {
        uint32_t rows = L.height - ty * edge < edge ? L.height - ty * edge : edge;
        for (uint32_t tx = 0; tx < L.tiles_x && rc == 0; tx++) {
            uint32_t cols = L.width - tx * edge < edge ? L.width - tx * edge : edge;
            unsigned char *dst = band + (size_t)tx * edge * texel_bytes;
            rc = vt_tile_reader_read(r, level, tx, ty, &stored, err);
            for (uint32_t y = 0; rc == 0 && y < rows; y++)
                sink_row(k, r, border, border + y, cols, dst + y * row_bytes);
            vt_progress_update(&progress, (uint64_t)ty * L.tiles_x + tx + 1);
        }
        if (rc == 0)
            rc = sink_rows(k, band, rows, row_bytes, err);
    }
    vt_progress_end(&progress);
    return rc;
}

int vt_tile_reader_write_image(struct vt_tile_reader *r, uint32_t level, bool one_tile, uint32_t tx,
                               uint32_t ty, const char *path, bool tiff, struct vts_error *err)
{
    const struct vts_geometry *g = vts_store_geometry(r->store);
    struct vts_level L;
    vts_store_level(r->store, level, &L);
    uint32_t width = one_tile ? r->img.width : L.width;
    uint32_t height = one_tile ? r->img.height : L.height;
    uint32_t band_rows = one_tile ? 1 : height < g->tile_content_px ? height : g->tile_content_px;
    uint32_t depth = vt_tile_reader_png_depth(r);
    size_t sample_bytes = tiff ? vts_sample_bytes(tiff_sample(r)) : depth / 8;
    size_t row_bytes, band_bytes;
    unsigned char *band = NULL;
    if (!vt_size_mul3(width, r->img.channels, sample_bytes, &row_bytes) ||
        !vt_size_mul(row_bytes, band_rows, &band_bytes) || !(band = malloc(band_bytes)))
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory for %u rows of %u texels", band_rows,
                            width);
    struct image_sink k = {0};
    if (tiff)
        k.tiff = vt_tiff_file_writer_create_sample(path, width, height, r->img.channels,
                                                   tiff_sample(r), err);
    else
        k.png = vt_png_file_writer_create(path, width, height, r->img.channels, depth, err);
    int rc = !k.png && !k.tiff ? (err ? err->status : VTS_ERR_IO)
             : one_tile        ? write_tile_rows(r, level, tx, ty, &k, band, row_bytes, err)
                               : write_level_rows(r, level, &k, band, row_bytes, err);
    if (rc == 0)
        rc =
            k.png ? vt_png_file_writer_finish(k.png, err) : vt_tiff_file_writer_finish(k.tiff, err);
    vt_png_file_writer_destroy(k.png);
    vt_tiff_file_writer_destroy(k.tiff);
    free(band);
    return rc;
}

int vt_tile_reader_write_png(struct vt_tile_reader *r, uint32_t level, bool one_tile, uint32_t tx,
                             uint32_t ty, const char *path, struct vts_error *err)
{
    return vt_tile_reader_write_image(r, level, one_tile, tx, ty, path, false, err);
}
