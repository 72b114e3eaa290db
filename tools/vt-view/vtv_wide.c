/* vt-view: layers of 16-bit and float samples (see vtv_wide.h). */
#include "vtv_wide.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vt_codec.h"
#include "vt_filter.h"

void vtv_wide_format(const struct vts_layer *info, struct vtv_texel_format *out)
{
    if (info->sample == VTS_SAMPLE_U8)
        *out = (struct vtv_texel_format){VTS_SAMPLE_U8, 4};
    else if (info->sample == VTS_SAMPLE_U16 && info->colour == VTS_COLOUR_SRGB)
        *out = (struct vtv_texel_format){VTS_SAMPLE_F32, info->channels};
    else
        *out = (struct vtv_texel_format){info->sample, info->channels};
}

size_t vtv_wide_texel_bytes(const struct vtv_texel_format *f)
{
    return (size_t)f->channels * vts_sample_bytes(f->sample);
}

void vtv_wide_convert(const struct vt_image *img, const struct vts_layer *info, void *dst)
{
    struct vtv_texel_format f;
    vtv_wide_format(info, &f);
    size_t row = (size_t)img->width * vtv_wide_texel_bytes(&f);
    uint8_t *o = dst;
    if (f.sample == img->sample) {
        for (uint32_t y = 0; y < img->height; y++)
            memcpy(o + y * row, vt_image_at(img, 0, y), row);
        return;
    }
    /* sRGB u16 -> linear f32: colour channels decoded, alpha (2 or 4 channels) as it is */
    uint32_t ch = img->channels;
    bool alpha = ch == 2 || ch == 4;
    struct vt_pixel_mode srgb = {ch, VTS_COLOUR_SRGB, false}, plain = {ch, VTS_COLOUR_DATA, false};
    for (uint32_t y = 0; y < img->height; y++) {
        float *r = (float *)(void *)(o + y * row);
        vt_filter_to_working(&srgb, img->sample, vt_image_at(img, 0, y), r, img->width);
        if (!alpha)
            continue;
        for (uint32_t x = 0; x < img->width; x++) {
            float a[4];
            vt_filter_to_working(&plain, img->sample, (const uint8_t *)vt_image_at(img, x, y), a,
                                 1);
            r[(size_t)x * ch + ch - 1] = a[ch - 1];
        }
    }
}

int vtv_wide_estimate_range(const struct vts_store *s, uint32_t layer, float range[2],
                            struct vts_error *err)
{
    const struct vts_geometry *g = vts_store_geometry(s);
    const struct vts_layer *info = vts_store_layer(s, layer);
    const struct vt_codec *codec = vt_codec_by_fourcc(info->codec);
    uint32_t L = g->level_count - 1;
    uint32_t c = g->tile_content_px, b = g->border_px;
    uint32_t lw = (uint32_t)(((uint64_t)g->width + (1ull << L) - 1) >> L);
    uint32_t lh = (uint32_t)(((uint64_t)g->height + (1ull << L) - 1) >> L);
    float lo = INFINITY, hi = -INFINITY;
    size_t cap = vts_store_max_payload(s) + 1;
    void *buf = malloc(cap);
    struct vt_image img = {0};
    int rc = buf ? 0 : vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    if (rc == 0 && !codec)
        rc = vt_error_set(err, VTS_ERR_UNSUPPORTED, "%s: layer '%s': unknown codec",
                          vts_store_name(s), info->name);
    if (rc == 0)
        rc = vt_image_alloc(&img, g->tile_payload_px, g->tile_payload_px, info->channels,
                            info->sample, err);
    uint32_t cc = info->channels == 2 || info->channels == 4 ? info->channels - 1 : info->channels;
    struct vt_pixel_mode plain = {info->channels, VTS_COLOUR_DATA, false};
    float px[4];
    for (uint32_t ty = 0; rc == 0 && ty * c < lh; ty++)
        for (uint32_t tx = 0; rc == 0 && tx * c < lw; tx++) {
            size_t len = 0;
            rc = vts_store_read(s, layer, L, tx, ty, buf, cap, &len, 0, err);
            if (rc || len == 0)
                continue;
            if ((rc = codec->decode(buf, len, &img, err)) != 0)
                break;
            uint32_t w = lw - tx * c < c ? lw - tx * c : c, h = lh - ty * c < c ? lh - ty * c : c;
            for (uint32_t y = 0; y < h; y++)
                for (uint32_t x = 0; x < w; x++) {
                    vt_filter_to_working(&plain, info->sample, vt_image_at(&img, b + x, b + y), px,
                                         1);
                    for (uint32_t k = 0; k < cc; k++)
                        if (isfinite(px[k])) {
                            lo = px[k] < lo ? px[k] : lo;
                            hi = px[k] > hi ? px[k] : hi;
                        }
                }
        }
    free(buf);
    vt_image_release(&img);
    if (!(lo <= hi))
        lo = 0.0f, hi = 1.0f;
    range[0] = lo;
    range[1] = hi;
    return rc;
}
