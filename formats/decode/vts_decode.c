/* libvts-decode (include/vts/vts_decode.h): a tile or a rectangle of a level read with libvts and
 * decoded with the codec table of formats/codec. Stateless: each call owns its scratch (one payload
 * buffer, one decoded tile), so calls may run concurrently. */
#include "vts_decode.h"

#include <stdlib.h>
#include <string.h>

#include "vt_checked.h"
#include "vt_codec.h"
#include "vt_error.h"
#include "vt_image.h"

/* What one call reads and decodes tiles with. */
struct decode_scratch {
    const struct vts_store *store;
    uint32_t layer;
    const struct vt_codec *codec;
    unsigned char *payload;
    size_t payload_capacity;
    struct vt_image tile; /* tile_payload_px square, the layer's channels and sample */
};

unsigned vts_decode_version(void)
{
    return VTS_VERSION_NUMBER;
}

size_t vts_decode_texel_bytes(const struct vts_store *store, uint32_t layer)
{
    const struct vts_layer *l = vts_store_layer(store, layer);
    return l ? (size_t)l->channels * vts_sample_bytes(l->sample) : 0;
}

int vts_decode_check(const struct vts_store *store, uint32_t layer, struct vts_error *err)
{
    const struct vts_layer *l = vts_store_layer(store, layer);
    struct vts_error why = {0};
    char name[5];
    if (!l)
        return vt_error_set(err, VTS_ERR_RANGE, "'%s': no layer %u (the store has %u)",
                            vts_store_name(store), layer, vts_store_geometry(store)->layer_count);
    const struct vt_codec *codec = vt_codec_by_fourcc(l->codec);
    vts_codec_name(l->codec, name);
    if (!codec)
        return vt_error_set(err, VTS_ERR_UNSUPPORTED,
                            "'%s': layer %u uses codec '%s', which this build cannot decode",
                            vts_store_name(store), layer, name);
    int rc = codec->check(vts_store_geometry(store)->tile_payload_px, l->channels, l->sample, &why);
    if (rc != 0)
        return vt_error_set(err, rc, "'%s': layer %u: %s", vts_store_name(store), layer,
                            why.message);
    return 0;
}

static void scratch_release(struct decode_scratch *s)
{
    free(s->payload);
    vt_image_release(&s->tile);
}

static int scratch_init(struct decode_scratch *s, const struct vts_store *store, uint32_t layer,
                        struct vts_error *err)
{
    const struct vts_geometry *g = vts_store_geometry(store);
    const struct vts_layer *l = vts_store_layer(store, layer);
    int rc = vts_decode_check(store, layer, err);
    *s = (struct decode_scratch){.store = store, .layer = layer};
    if (rc != 0)
        return rc;
    s->codec = vt_codec_by_fourcc(l->codec);
    s->payload_capacity = (size_t)vts_store_max_payload(store) + 1;
    s->payload = malloc(s->payload_capacity);
    if (!s->payload)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory reading '%s'",
                            vts_store_name(store));
    rc = vt_image_alloc(&s->tile, g->tile_payload_px, g->tile_payload_px, l->channels, l->sample,
                        err);
    if (rc != 0)
        scratch_release(s);
    return rc;
}

/* Reads and decodes one tile into s->tile (zeros for an empty tile). */
static int scratch_read(struct decode_scratch *s, uint32_t level, uint32_t tx, uint32_t ty,
                        unsigned flags, struct vts_error *err)
{
    unsigned read_flags = (flags & VTS_DECODE_NO_CRC) ? VTS_READ_NO_CRC : 0;
    struct vts_error why = {0};
    size_t len = 0;
    int rc = vts_store_read(s->store, s->layer, level, tx, ty, s->payload, s->payload_capacity,
                            &len, read_flags, &why);
    if (rc == 0 && len == 0)
        memset(s->tile.pixels, 0, s->tile.stride * s->tile.height);
    else if (rc == 0)
        rc = s->codec->decode(s->payload, len, &s->tile, &why);
    if (rc == 0)
        return 0;
    return vt_error_set(err, rc, "'%s': layer %u level %u tile %u,%u: %s", vts_store_name(s->store),
                        s->layer, level, tx, ty,
                        rc == VTS_ERR_CHECKSUM ? "payload checksum mismatch" : why.message);
}

/* Checks the caller's buffer for a width x height image of texel_bytes texels. */
static int check_dst(const struct vts_store *store, const void *dst, size_t dst_stride,
                     size_t dst_capacity, uint32_t width, uint32_t height, size_t texel_bytes,
                     struct vts_error *err)
{
    size_t row_bytes, before_last, need;
    if (!dst)
        return vt_error_set(err, VTS_ERR_ARG, "'%s': no destination buffer", vts_store_name(store));
    if (width == 0 || height == 0)
        return vt_error_set(err, VTS_ERR_ARG, "'%s': empty rectangle %ux%u", vts_store_name(store),
                            width, height);
    if (!vt_size_mul(width, texel_bytes, &row_bytes) ||
        !vt_size_mul(height - 1, dst_stride, &before_last) ||
        !vt_size_add(before_last, row_bytes, &need))
        return vt_error_set(err, VTS_ERR_LIMIT,
                            "'%s': a %ux%u image with a stride of %zu bytes "
                            "overflows size_t",
                            vts_store_name(store), width, height, dst_stride);
    if (dst_stride < row_bytes)
        return vt_error_set(err, VTS_ERR_ARG, "'%s': stride %zu is less than a row of %zu bytes",
                            vts_store_name(store), dst_stride, row_bytes);
    if (dst_capacity < need)
        return vt_error_set(err, VTS_ERR_LIMIT,
                            "'%s': a %ux%u image needs %zu bytes, the buffer holds %zu",
                            vts_store_name(store), width, height, need, dst_capacity);
    return 0;
}

/* Checks layer and level; fills *L. */
static int check_layer_level(const struct vts_store *store, uint32_t layer, uint32_t level,
                             struct vts_level *L, struct vts_error *err)
{
    const struct vts_geometry *g = vts_store_geometry(store);
    if (layer >= g->layer_count)
        return vt_error_set(err, VTS_ERR_RANGE, "'%s': no layer %u (the store has %u)",
                            vts_store_name(store), layer, g->layer_count);
    if (vts_store_level(store, level, L) != 0)
        return vt_error_set(err, VTS_ERR_RANGE, "'%s': no level %u (the store has %u)",
                            vts_store_name(store), level, g->level_count);
    return 0;
}

/* Copies rows x cols texels from (x, y) of src to dst. */
static void copy_block(const struct vt_image *src, uint32_t x, uint32_t y, uint32_t cols,
                       uint32_t rows, unsigned char *dst, size_t dst_stride)
{
    size_t row_bytes = (size_t)cols * vt_image_texel_bytes(src);
    for (uint32_t r = 0; r < rows; r++)
        memcpy(dst + (size_t)r * dst_stride, vt_image_at(src, x, y + r), row_bytes);
}

int vts_decode_tile(const struct vts_store *store, uint32_t layer, uint32_t level, uint32_t tx,
                    uint32_t ty, unsigned flags, void *dst, size_t dst_stride, size_t dst_capacity,
                    struct vts_error *err)
{
    const struct vts_geometry *g = vts_store_geometry(store);
    bool no_border = flags & VTS_DECODE_NO_BORDER;
    uint32_t edge = no_border ? g->tile_content_px : g->tile_payload_px;
    uint32_t origin = no_border ? g->border_px : 0;
    struct decode_scratch s;
    struct vts_level L;
    int rc = check_layer_level(store, layer, level, &L, err);
    if (rc != 0)
        return rc;
    if (tx >= L.tiles_x || ty >= L.tiles_y)
        return vt_error_set(err, VTS_ERR_RANGE, "'%s': no tile %u,%u in level %u (%ux%u tiles)",
                            vts_store_name(store), tx, ty, level, L.tiles_x, L.tiles_y);
    rc = check_dst(store, dst, dst_stride, dst_capacity, edge, edge,
                   vts_decode_texel_bytes(store, layer), err);
    if (rc == 0)
        rc = scratch_init(&s, store, layer, err);
    if (rc != 0)
        return rc;
    rc = scratch_read(&s, level, tx, ty, flags, err);
    if (rc == 0)
        copy_block(&s.tile, origin, origin, edge, edge, dst, dst_stride);
    scratch_release(&s);
    return rc;
}

int vts_decode_region(const struct vts_store *store, uint32_t layer, uint32_t level, uint32_t x,
                      uint32_t y, uint32_t width, uint32_t height, unsigned flags, void *dst,
                      size_t dst_stride, size_t dst_capacity, struct vts_error *err)
{
    const struct vts_geometry *g = vts_store_geometry(store);
    uint32_t edge = g->tile_content_px, border = g->border_px;
    struct decode_scratch s;
    struct vts_level L;
    int rc = check_layer_level(store, layer, level, &L, err);
    if (rc != 0)
        return rc;
    if (x > L.width || width > L.width - x || y > L.height || height > L.height - y)
        return vt_error_set(err, VTS_ERR_RANGE,
                            "'%s': rectangle %ux%u at %u,%u is outside level %u (%ux%u)",
                            vts_store_name(store), width, height, x, y, level, L.width, L.height);
    size_t texel_bytes = vts_decode_texel_bytes(store, layer);
    rc = check_dst(store, dst, dst_stride, dst_capacity, width, height, texel_bytes, err);
    if (rc == 0)
        rc = scratch_init(&s, store, layer, err);
    if (rc != 0)
        return rc;
    /* 64-bit: x + width may reach 2^32 - 1 + tile edge. */
    uint64_t x_end = (uint64_t)x + width, y_end = (uint64_t)y + height;
    for (uint64_t ty = y / edge; rc == 0 && ty * edge < y_end; ty++) {
        uint64_t y0 = ty * edge > y ? ty * edge : y;
        uint64_t y1 = (ty + 1) * edge < y_end ? (ty + 1) * edge : y_end;
        for (uint64_t tx = x / edge; rc == 0 && tx * edge < x_end; tx++) {
            uint64_t x0 = tx * edge > x ? tx * edge : x;
            uint64_t x1 = (tx + 1) * edge < x_end ? (tx + 1) * edge : x_end;
            rc = scratch_read(&s, level, (uint32_t)tx, (uint32_t)ty, flags, err);
            if (rc != 0)
                break;
            unsigned char *out = (unsigned char *)dst + (size_t)(y0 - y) * dst_stride +
                                 (size_t)(x0 - x) * texel_bytes;
            copy_block(&s.tile, (uint32_t)(x0 - tx * edge) + border,
                       (uint32_t)(y0 - ty * edge) + border, (uint32_t)(x1 - x0),
                       (uint32_t)(y1 - y0), out, dst_stride);
        }
    }
    scratch_release(&s);
    return rc;
}
