/* Test helper for vt-view's precision at full size (item 7 of issue 16): a sparse virtual texture
 * of SIZE x SIZE texels (default 2^20) whose level-0 tiles are stored only in the K x K corner
 * at the far end (bottom right), every other tile of every level stored empty (length 0). The
 * texels are a function of their integer position (sines with periods of 5 to 11 texels: a
 * sub-texel error of the coordinates shows), layer colour 'data', borders from the same function
 * (clamped at the texture's edge).
 *   vtv_make_sparse OUT.vts [--size N] [--tile N] [--border N] [--corner K]
 * and the CPU reference of a 2D view of it, in double precision: pixel (i, j) of a W x H frame
 * (rows from the top) with camera (CX, CY, SCALE) looks at level-0 texel coordinate
 * (CX + (i + 0.5 - W / 2) / SCALE, CY + (j + 0.5 - H / 2) / SCALE), sampled bilinearly (texel
 * centres at + 0.5, clamped to the edge); SHIFT (default 0) moves the camera by that many texels
 * in x and y (the negative control: a sub-texel error must fail the comparison).
 *   vtv_make_sparse --reference OUT.png CX CY SCALE W H [--size N] [--shift T] */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vt_codec.h"
#include "vt_png_file.h"
#include "vts_writer.h"

static const double pi = 3.14159265358979;

static double texel(long x, long y, long size, int c)
{
    x = x < 0 ? 0 : x >= size ? size - 1 : x;
    y = y < 0 ? 0 : y >= size ? size - 1 : y;
    double fx = (double)(x % 4620), fy = (double)(y % 4620); /* periods divide 4620 */
    switch (c) {
    case 0:
        return 128 + 80 * sin(2 * pi * fx / 7.0) + 40 * cos(2 * pi * fy / 11.0);
    case 1:
        return 128 + 90 * sin(2 * pi * (fx + fy) / 5.0);
    default:
        return 128 + 60 * cos(2 * pi * fy / 7.0) + 60 * sin(2 * pi * fx / 11.0);
    }
}

static unsigned char u8(double v)
{
    return (unsigned char)(v < 0 ? 0 : v > 255 ? 255 : lround(v));
}

static int reference(int argc, char **argv)
{
    if (argc < 8)
        return 2;
    const char *out = argv[2];
    double cx = atof(argv[3]), cy = atof(argv[4]), scale = atof(argv[5]), shift = 0;
    unsigned w = (unsigned)atoi(argv[6]), h = (unsigned)atoi(argv[7]);
    long size = 1L << 20;
    for (int i = 8; i + 1 < argc; i += 2) {
        if (!strcmp(argv[i], "--size"))
            size = atol(argv[i + 1]);
        else if (!strcmp(argv[i], "--shift"))
            shift = atof(argv[i + 1]);
        else
            return 2;
    }
    if (w < 1 || h < 1 || w > 4096 || h > 4096 || scale <= 0)
        return 2;
    struct vts_error err;
    struct vt_png_file_writer *pw = vt_png_file_writer_create(out, w, h, 3, 8, &err);
    unsigned char *row = malloc((size_t)w * 3);
    int st = pw && row ? 0 : -1;
    for (unsigned j = 0; st == 0 && j < h; j++) {
        for (unsigned i = 0; i < w; i++) {
            double tx = cx + shift + (i + 0.5 - w / 2.0) / scale - 0.5;
            double ty = cy + shift + (j + 0.5 - h / 2.0) / scale - 0.5;
            double x0 = floor(tx), y0 = floor(ty), fx = tx - x0, fy = ty - y0;
            long xi = (long)x0, yi = (long)y0;
            for (int c = 0; c < 3; c++) {
                /* the stored texels are 8-bit: interpolate those */
                double a = u8(texel(xi, yi, size, c)), b = u8(texel(xi + 1, yi, size, c));
                double d = u8(texel(xi, yi + 1, size, c)), e = u8(texel(xi + 1, yi + 1, size, c));
                row[i * 3 + c] =
                    u8((a * (1 - fx) + b * fx) * (1 - fy) + (d * (1 - fx) + e * fx) * fy);
            }
        }
        st = vt_png_file_writer_rows(pw, row, 1, 0, &err);
    }
    if (st == 0)
        st = vt_png_file_writer_finish(pw, &err);
    if (st != 0)
        fprintf(stderr, "vtv_make_sparse: %s\n", pw ? err.message : "cannot write");
    vt_png_file_writer_destroy(pw);
    free(row);
    return st ? 1 : 0;
}

int main(int argc, char **argv)
{
    if (argc >= 2 && !strcmp(argv[1], "--reference"))
        return reference(argc, argv);
    const char *out = NULL;
    uint32_t size = 1u << 20, tile = 1016, border = 4, corner = 2;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--size") && i + 1 < argc)
            size = (uint32_t)atol(argv[++i]);
        else if (!strcmp(argv[i], "--tile") && i + 1 < argc)
            tile = (uint32_t)atoi(argv[++i]);
        else if (!strcmp(argv[i], "--border") && i + 1 < argc)
            border = (uint32_t)atoi(argv[++i]);
        else if (!strcmp(argv[i], "--corner") && i + 1 < argc)
            corner = (uint32_t)atoi(argv[++i]);
        else if (!out && argv[i][0] != '-')
            out = argv[i];
        else {
            fprintf(stderr, "vtv_make_sparse: bad argument '%s'\n", argv[i]);
            return 2;
        }
    }
    if (!out || size < 1 || tile < 1)
        return 2;
    struct vts_error err = {0};
    const struct vt_codec *codec = vt_codec_find("png");
    struct vts_geometry g = {.width = size,
                             .height = size,
                             .tile_content_px = tile,
                             .border_px = border,
                             .tile_payload_px = tile + 2 * border,
                             .layer_count = 1};
    g.level_count = vts_full_level_count(size, size, tile);
    struct vts_layer layer = {
        .codec = codec->fourcc, .channels = 3, .sample = VTS_SAMPLE_U8, .colour = VTS_COLOUR_DATA};
    strcpy(layer.name, "diffuse");
    struct vts_writer *w = vts_writer_create(out, &g, &layer, &err);
    if (!w) {
        fprintf(stderr, "vtv_make_sparse: %s\n", err.message);
        return 1;
    }
    uint32_t pp = g.tile_payload_px;
    struct vt_image img;
    vt_image_alloc(&img, pp, pp, 3, VTS_SAMPLE_U8, &err);
    size_t cap = codec->encoded_bound(pp, pp, 3, VTS_SAMPLE_U8);
    uint8_t *buf = malloc(cap);
    struct vt_codec_params params = {.quality = 95};
    int st = buf ? 0 : -1;
    for (uint32_t l = 0; st == 0 && l < g.level_count; l++) {
        struct vts_level lv;
        vts_geometry_level(&g, l, &lv);
        for (uint32_t ty = 0; st == 0 && ty < lv.tiles_y; ty++)
            for (uint32_t tx = 0; st == 0 && tx < lv.tiles_x; tx++) {
                size_t len = 0;
                if (l == 0 && tx + corner >= lv.tiles_x && ty + corner >= lv.tiles_y) {
                    for (uint32_t j = 0; j < pp; j++)
                        for (uint32_t i = 0; i < pp; i++) {
                            long x = (long)tx * tile + i - border, y = (long)ty * tile + j - border;
                            uint8_t *d = vt_image_at(&img, i, j);
                            for (int c = 0; c < 3; c++)
                                d[c] = u8(texel(x, y, size, c));
                        }
                    st = codec->encode(&img, &params, buf, cap, &len, &err);
                }
                if (st == 0)
                    st = vts_writer_put(w, 0, l, tx, ty, buf, len, &err);
            }
    }
    if (st == 0)
        st = vts_writer_finish(w, &err);
    if (st != 0)
        fprintf(stderr, "vtv_make_sparse: %s\n", err.message);
    vts_writer_destroy(w);
    vt_image_release(&img);
    free(buf);
    return st ? 1 : 0;
}
