#include "vt_synth.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vt_codec.h"
#include "vt_error.h"
#include "vt_image.h"
#include "vts_writer.h"

void vt_synth_defaults(struct vt_synth_options *o)
{
    *o = (struct vt_synth_options){.width = 300,
                                   .height = 200,
                                   .tile_content_px = 64,
                                   .border_px = 2,
                                   .layer_count = 1,
                                   .codec = VTS_CODEC_RAW,
                                   .channels = 4,
                                   .sample = VTS_SAMPLE_U8,
                                   .seed = 1};
}

static uint32_t hash32(uint32_t v)
{
    v ^= v >> 16;
    v *= 0x7feb352dU;
    v ^= v >> 15;
    v *= 0x846ca68bU;
    v ^= v >> 16;
    return v;
}

double vt_synth_texel(const struct vt_synth_options *o, uint32_t layer, uint32_t level, int64_t x,
                      int64_t y, uint32_t channel)
{
    uint32_t w = (uint32_t)(((uint64_t)o->width + (1ull << level) - 1) >> level);
    uint32_t h = (uint32_t)(((uint64_t)o->height + (1ull << level) - 1) >> level);
    x = x < 0 ? 0 : (x >= w ? w - 1 : x);
    y = y < 0 ? 0 : (y >= h ? h - 1 : y);
    if (o->flat_left && (uint64_t)x < w / 4)
        return channel == 3 ? 1.0 : 0.25 + 0.1 * channel;
    uint32_t v =
        hash32(o->seed * 0x9e3779b9u ^ hash32((uint32_t)x * 73856093u ^ (uint32_t)y * 19349663u ^
                                              level * 83492791u ^ layer * 2654435761u ^ channel));
    return (v & 0xffff) / 65535.0;
}

bool vt_synth_tile_is_empty(const struct vt_synth_options *o, uint32_t level, uint32_t tx,
                            uint32_t ty)
{
    return o->empty_tiles && level == 0 && (tx + 2 * ty) % 7 == 3;
}

static void fill_tile(const struct vt_synth_options *o, struct vt_image *img, uint32_t layer,
                      uint32_t level, uint32_t tx, uint32_t ty)
{
    int64_t x0 = (int64_t)tx * o->tile_content_px - o->border_px;
    int64_t y0 = (int64_t)ty * o->tile_content_px - o->border_px;
    for (uint32_t y = 0; y < img->height; y++)
        for (uint32_t x = 0; x < img->width; x++)
            for (uint32_t c = 0; c < img->channels; c++) {
                double v = vt_synth_texel(o, layer, level, x0 + x, y0 + y, c);
                unsigned char *p = (unsigned char *)vt_image_at(img, x, y);
                if (img->sample == VTS_SAMPLE_U8) {
                    p[c] = (unsigned char)(v * 255.0 + 0.5);
                } else if (img->sample == VTS_SAMPLE_U16) {
                    uint16_t s = (uint16_t)(v * 65535.0 + 0.5);
                    memcpy(p + 2 * c, &s, 2);
                } else if (img->sample == VTS_SAMPLE_F32) {
                    float f = (float)v;
                    memcpy(p + 4 * c, &f, 4);
                } else { /* f16: v in [0,1] with 10 mantissa bits, exponent 14 or below */
                    uint16_t half = (uint16_t)(0x3800 + (uint16_t)(v * 1023.0)); /* 0.5..~1 */
                    memcpy(p + 2 * c, &half, 2);
                }
            }
}

int vt_synth_store(const char *path, const struct vt_synth_options *o, struct vts_error *err)
{
    const struct vt_codec *codec = vt_codec_by_fourcc(o->codec);
    if (!codec)
        return vt_error_set(err, VTS_ERR_UNSUPPORTED, "vt-synth: unknown codec");
    struct vts_geometry g = {o->width,
                             o->height,
                             o->tile_content_px,
                             o->border_px,
                             o->tile_content_px + 2 * o->border_px,
                             0,
                             o->layer_count,
                             0};
    g.level_count = vts_full_level_count(g.width, g.height, g.tile_content_px);
    struct vts_layer layers[VTS_MAX_LAYERS];
    memset(layers, 0, sizeof layers);
    for (uint32_t i = 0; i < o->layer_count && i < VTS_MAX_LAYERS; i++) {
        layers[i] = (struct vts_layer){
            o->codec, (uint8_t)o->channels, (uint8_t)o->sample, VTS_COLOUR_SRGB, 0, 0, {0}};
        snprintf(layers[i].name, sizeof layers[i].name, i == 0 ? "diffuse" : "layer%u", i);
    }
    int rc = codec->check(g.tile_payload_px, o->channels, o->sample, err);
    if (rc)
        return rc;
    struct vts_writer *w = vts_writer_create(path, &g, layers, err);
    if (!w)
        return err ? err->status : VTS_ERR_IO;
    struct vt_image img = {0};
    size_t cap = codec->encoded_bound(g.tile_payload_px, g.tile_payload_px, o->channels, o->sample);
    unsigned char *buf = malloc(cap ? cap : 1);
    rc = vt_image_alloc(&img, g.tile_payload_px, g.tile_payload_px, o->channels, o->sample, err);
    if (!buf && rc == 0)
        rc = vt_error_set(err, VTS_ERR_NOMEM, "vt-synth: out of memory");
    struct vt_codec_params params = {0};
    for (uint32_t layer = 0; rc == 0 && layer < g.layer_count; layer++)
        for (uint32_t level = 0; rc == 0 && level < g.level_count; level++) {
            struct vts_level L;
            vts_geometry_level(&g, level, &L);
            for (uint32_t ty = 0; rc == 0 && ty < L.tiles_y; ty++)
                for (uint32_t tx = 0; rc == 0 && tx < L.tiles_x; tx++) {
                    size_t len = 0;
                    if (!vt_synth_tile_is_empty(o, level, tx, ty)) {
                        fill_tile(o, &img, layer, level, tx, ty);
                        rc = codec->encode(&img, &params, buf, cap, &len, err);
                    }
                    if (rc == 0)
                        rc = vts_writer_put(w, layer, level, tx, ty, buf, len, err);
                }
        }
    char seed[16];
    snprintf(seed, sizeof seed, "%u", o->seed);
    if (rc == 0)
        rc = vts_writer_set_meta(w, "generator", "vt-synth", err);
    if (rc == 0)
        rc = vts_writer_set_meta(w, "seed", seed, err);
    if (rc == 0)
        rc = vts_writer_finish(w, err);
    vts_writer_destroy(w);
    vt_image_release(&img);
    free(buf);
    return rc;
}
