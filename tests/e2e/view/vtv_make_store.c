/* Test helper for vt-view: writes a small RGB store through vts_writer from a smooth synthetic
 * image, with mip levels made by 2x2 box averaging (as glGenerateMipmap does) and borders copied
 * from the neighbours (edge texels clamped). --bad-borders writes borders that are NOT copied from
 * the neighbours (each sample pushed to the far end: 255 below 128, else 0, at least 128 away from
 * the right value) so that the renderer's comparison must fail clearly; --empty TX,TY
 * stores level-0 tile (TX, TY) with length 0. The layer is colour 'data' (mips averaged on the
 * stored values, like glGenerateMipmap on RGBA8), or 'srgb' with --srgb (the same values).
 * usage: vtv_make_store OUT.vts [--size N] [--tile N] [--border N] [--codec png|raw|jpeg]
 *                       [--bad-borders] [--empty TX,TY]... [--srgb] */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vt_codec.h"
#include "vts_writer.h"

static uint8_t clamp8(double v)
{
    return (uint8_t)(v < 0 ? 0 : v > 255 ? 255 : lround(v));
}

static int fail(const struct vts_error *err)
{
    fprintf(stderr, "vtv_make_store: %s\n", err->message);
    return 1;
}

int main(int argc, char **argv)
{
    const char *out = NULL, *codec_name = "png";
    uint32_t size = 512, tile = 64, border = 4, empty[16][2], n_empty = 0;
    int bad = 0, srgb = 0;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--size") && i + 1 < argc)
            size = (uint32_t)atoi(argv[++i]);
        else if (!strcmp(argv[i], "--tile") && i + 1 < argc)
            tile = (uint32_t)atoi(argv[++i]);
        else if (!strcmp(argv[i], "--border") && i + 1 < argc)
            border = (uint32_t)atoi(argv[++i]);
        else if (!strcmp(argv[i], "--codec") && i + 1 < argc)
            codec_name = argv[++i];
        else if (!strcmp(argv[i], "--srgb"))
            srgb = 1;
        else if (!strcmp(argv[i], "--bad-borders"))
            bad = 1;
        else if (!strcmp(argv[i], "--empty") && i + 1 < argc && n_empty < 16) {
            if (sscanf(argv[++i], "%u,%u", &empty[n_empty][0], &empty[n_empty][1]) != 2)
                return 2;
            n_empty++;
        } else if (!out && argv[i][0] != '-')
            out = argv[i];
        else {
            fprintf(stderr, "vtv_make_store: bad argument '%s'\n", argv[i]);
            return 2;
        }
    }
    if (!out || size < 1 || tile < 1)
        return 2;
    struct vts_error err = {0};
    const struct vt_codec *codec = vt_codec_find(codec_name);
    if (!codec)
        return 2;
    struct vts_geometry g = {.width = size,
                             .height = size,
                             .tile_content_px = tile,
                             .border_px = border,
                             .tile_payload_px = tile + 2 * border,
                             .layer_count = 1};
    g.level_count = vts_full_level_count(size, size, tile);
    struct vts_layer layer = {.codec = codec->fourcc,
                              .channels = 3,
                              .sample = VTS_SAMPLE_U8,
                              .colour = srgb ? VTS_COLOUR_SRGB : VTS_COLOUR_DATA,
                              .codec_param = 0};
    strcpy(layer.name, "diffuse");
    struct vts_writer *w = vts_writer_create(out, &g, &layer, &err);
    if (!w)
        return fail(&err);
    /* level 0: smooth sinusoids (periods 20..160 texels) */
    uint32_t lw = size;
    uint8_t *img = malloc((size_t)size * size * 3);
    for (uint32_t y = 0; y < size; y++)
        for (uint32_t x = 0; x < size; x++) {
            double fx = x, fy = y;
            uint8_t *p = img + ((size_t)y * size + x) * 3;
            p[0] = clamp8(128 + 70 * sin(fx / 9.0) + 40 * cos(fy / 23.0 + fx / 50.0));
            p[1] = clamp8(128 + 60 * sin((fx + fy) / 13.0) + 50 * sin(fy / 31.0));
            p[2] = clamp8(128 + 90 * cos(hypot(fx - 200, fy - 300) / 11.0));
        }
    uint32_t pp = g.tile_payload_px;
    struct vt_image tile_img;
    vt_image_alloc(&tile_img, pp, pp, 3, VTS_SAMPLE_U8, &err);
    size_t cap = codec->encoded_bound(pp, pp, 3, VTS_SAMPLE_U8);
    uint8_t *buf = malloc(cap);
    struct vt_codec_params params = {.quality = 95};
    for (uint32_t l = 0; l < g.level_count; l++) {
        struct vts_level lv;
        vts_geometry_level(&g, l, &lv);
        for (uint32_t ty = 0; ty < lv.tiles_y; ty++)
            for (uint32_t tx = 0; tx < lv.tiles_x; tx++) {
                int is_empty = 0;
                for (uint32_t e = 0; l == 0 && e < n_empty; e++)
                    is_empty |= empty[e][0] == tx && empty[e][1] == ty;
                size_t len = 0;
                if (!is_empty) {
                    for (uint32_t j = 0; j < pp; j++)
                        for (uint32_t i = 0; i < pp; i++) {
                            long sx = (long)(tx * tile + i) - (long)border;
                            long sy = (long)(ty * tile + j) - (long)border;
                            int outside = i < border || j < border || i >= border + tile ||
                                          j >= border + tile;
                            sx = sx < 0 ? 0 : sx >= (long)lw ? (long)lw - 1 : sx;
                            sy = sy < 0 ? 0 : sy >= (long)lw ? (long)lw - 1 : sy;
                            const uint8_t *s = img + ((size_t)sy * lw + (size_t)sx) * 3;
                            uint8_t *d = vt_image_at(&tile_img, i, j);
                            for (int c = 0; c < 3; c++)
                                d[c] = (uint8_t)(bad && outside ? (s[c] < 128 ? 255 : 0) : s[c]);
                        }
                    if (codec->encode(&tile_img, &params, buf, cap, &len, &err) != 0)
                        return fail(&err);
                }
                if (vts_writer_put(w, 0, l, tx, ty, buf, len, &err) != 0)
                    return fail(&err);
            }
        /* next level: 2x2 box average */
        uint32_t nw = (lw + 1) / 2;
        uint8_t *next = malloc((size_t)nw * nw * 3);
        for (uint32_t y = 0; y < nw; y++)
            for (uint32_t x = 0; x < nw; x++)
                for (int c = 0; c < 3; c++) {
                    uint32_t x1 = 2 * x + 1 < lw ? 2 * x + 1 : lw - 1;
                    uint32_t y1 = 2 * y + 1 < lw ? 2 * y + 1 : lw - 1;
                    unsigned s = img[((size_t)2 * y * lw + 2 * x) * 3 + c] +
                                 img[((size_t)2 * y * lw + x1) * 3 + c] +
                                 img[((size_t)y1 * lw + 2 * x) * 3 + c] +
                                 img[((size_t)y1 * lw + x1) * 3 + c];
                    next[((size_t)y * nw + x) * 3 + c] = (uint8_t)((s + 2) / 4);
                }
        free(img);
        img = next;
        lw = nw;
    }
    free(img);
    free(buf);
    vt_image_release(&tile_img);
    if (vts_writer_finish(w, &err) != 0)
        return fail(&err);
    vts_writer_destroy(w);
    return 0;
}
