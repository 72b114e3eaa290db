/* The textures of the sample scene (see vt_sample_textures.h). */
#include "vt_sample_textures.h"

#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>

#include "vt_atomic_file.h"
#include "vt_error.h"
#include "vt_sample_font.h"
#include "vt_sample_image.h"

/* 44 textures: t00..t40 colour (t36..t38 with alpha), n41 normal, g42 tiling, m43 alpha mask. */
const struct vt_sample_textures_spec vt_sample_textures[] = {
    {"t00.png", "T00", 1024, 1024, VT_SAMPLE_TEXTURES_FACADE},
    {"t01.png", "T01", 512, 256, VT_SAMPLE_TEXTURES_FACADE},
    {"t02.png", "T02", 300, 200, VT_SAMPLE_TEXTURES_FACADE},
    {"t03.png", "T03", 100, 60, VT_SAMPLE_TEXTURES_FACADE},
    {"t04.png", "T04", 64, 64, VT_SAMPLE_TEXTURES_FACADE},
    {"t05.png", "T05", 2000, 1000, VT_SAMPLE_TEXTURES_FACADE},
    {"t06.png", "T06", 256, 256, VT_SAMPLE_TEXTURES_FACADE},
    {"t07.png", "T07", 128, 128, VT_SAMPLE_TEXTURES_FACADE},
    {"t08.png", "T08", 512, 512, VT_SAMPLE_TEXTURES_FACADE},
    {"t09.png", "T09", 200, 300, VT_SAMPLE_TEXTURES_FACADE},
    {"t10.png", "T10", 640, 480, VT_SAMPLE_TEXTURES_FACADE},
    {"t11.png", "T11", 96, 96, VT_SAMPLE_TEXTURES_FACADE},
    {"t12.png", "T12", 256, 128, VT_SAMPLE_TEXTURES_FACADE},
    {"t13.png", "T13", 128, 256, VT_SAMPLE_TEXTURES_FACADE},
    {"t14.png", "T14", 1000, 500, VT_SAMPLE_TEXTURES_FACADE},
    {"t15.png", "T15", 333, 222, VT_SAMPLE_TEXTURES_FACADE},
    {"t16.png", "T16", 150, 150, VT_SAMPLE_TEXTURES_FACADE},
    {"t17.png", "T17", 80, 120, VT_SAMPLE_TEXTURES_FACADE},
    {"t18.png", "T18", 512, 384, VT_SAMPLE_TEXTURES_FACADE},
    {"t19.png", "T19", 64, 128, VT_SAMPLE_TEXTURES_FACADE},
    {"t20.png", "T20", 720, 360, VT_SAMPLE_TEXTURES_FACADE},
    {"t21.png", "T21", 240, 240, VT_SAMPLE_TEXTURES_FACADE},
    {"t22.png", "T22", 48, 48, VT_SAMPLE_TEXTURES_FACADE},
    {"t23.png", "T23", 400, 100, VT_SAMPLE_TEXTURES_FACADE},
    {"t24.png", "T24", 100, 400, VT_SAMPLE_TEXTURES_FACADE},
    {"t25.png", "T25", 257, 129, VT_SAMPLE_TEXTURES_FACADE},
    {"t26.png", "T26", 160, 90, VT_SAMPLE_TEXTURES_FACADE},
    {"t27.png", "T27", 384, 384, VT_SAMPLE_TEXTURES_FACADE},
    {"t28.png", "T28", 192, 64, VT_SAMPLE_TEXTURES_FACADE},
    {"t29.png", "T29", 200, 200, VT_SAMPLE_TEXTURES_FACADE},
    {"t30.png", "T30", 768, 512, VT_SAMPLE_TEXTURES_FACADE},
    {"t31.png", "T31", 64, 48, VT_SAMPLE_TEXTURES_FACADE},
    {"t32.png", "T32", 120, 80, VT_SAMPLE_TEXTURES_FACADE},
    {"t33.png", "T33", 256, 64, VT_SAMPLE_TEXTURES_FACADE},
    {"t34.png", "T34", 500, 500, VT_SAMPLE_TEXTURES_FACADE},
    {"t35.png", "T35", 350, 175, VT_SAMPLE_TEXTURES_FACADE},
    {"t36_alpha.png", "T36", 256, 256, VT_SAMPLE_TEXTURES_ALPHA},
    {"t37_alpha.png", "T37", 200, 300, VT_SAMPLE_TEXTURES_ALPHA},
    {"t38_alpha.png", "T38", 128, 128, VT_SAMPLE_TEXTURES_ALPHA},
    {"t39.png", "T39", 300, 150, VT_SAMPLE_TEXTURES_FACADE},
    {"t40.png", "T40", 512, 512, VT_SAMPLE_TEXTURES_FACADE},
    {"n41_normal.png", "N41", 512, 512, VT_SAMPLE_TEXTURES_NORMAL},
    {"g42_tiling.png", "G42", 128, 128, VT_SAMPLE_TEXTURES_TILING},
    {"m43_mask.png", "M43", 300, 150, VT_SAMPLE_TEXTURES_MASK},
};
_Static_assert(sizeof(vt_sample_textures) / sizeof(vt_sample_textures[0]) ==
                   VT_SAMPLE_TEXTURES_COUNT,
               "VT_SAMPLE_TEXTURES_COUNT");

uint32_t vt_sample_textures_hash32(uint32_t x)
{
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return x;
}

/* A saturated colour for texture index i (hues spread by the golden ratio). */
static void base_colour(uint32_t i, double rgb[3])
{
    double hue = fmod(i * 0.6180339887, 1.0) * 6.0;
    double f = hue - floor(hue);
    double v = 0.85, s = 0.65;
    double p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
    switch ((int)hue) {
    case 0:
        rgb[0] = v, rgb[1] = t, rgb[2] = p;
        break;
    case 1:
        rgb[0] = q, rgb[1] = v, rgb[2] = p;
        break;
    case 2:
        rgb[0] = p, rgb[1] = v, rgb[2] = t;
        break;
    case 3:
        rgb[0] = p, rgb[1] = q, rgb[2] = v;
        break;
    case 4:
        rgb[0] = t, rgb[1] = p, rgb[2] = v;
        break;
    default:
        rgb[0] = v, rgb[1] = p, rgb[2] = q;
        break;
    }
}

static uint8_t to_u8(double v)
{
    if (v <= 0)
        return 0;
    if (v >= 1)
        return 255;
    return (uint8_t)(v * 255.0 + 0.5);
}

/* Facade: gradient background, a grid of windows, a light frame, red mark at the top-left corner
 * and blue at the bottom-right (orientation checks), then the label. ch is 3 or 4. */
static void paint_facade(struct vt_sample_image *im, uint32_t index)
{
    double rgb[3];
    base_colour(index, rgb);
    uint32_t m = im->w < im->h ? im->w : im->h;
    uint32_t cell = m / 6 > 8 ? m / 6 : 8;
    uint32_t frame = m / 64 > 1 ? m / 64 : 1;
    for (uint32_t y = 0; y < im->h; y++) {
        double shade = 0.75 + 0.25 * (double)y / im->h;
        for (uint32_t x = 0; x < im->w; x++) {
            uint8_t *p = vt_sample_image_at(im, x, y);
            uint32_t cx = x % cell, cy = y % cell;
            bool window =
                cx > cell / 4 && cx < cell - cell / 4 && cy > cell / 5 && cy < cell - cell / 3;
            double k = window ? 0.35 + 0.15 * (vt_sample_textures_hash32(
                                                   index * 7919u + (x / cell) * 131u + (y / cell)) &
                                               1)
                              : shade;
            for (int c = 0; c < 3; c++)
                p[c] = to_u8(rgb[c] * k);
            if (im->ch == 4)
                p[3] = 255;
            if (x < frame || y < frame || x >= im->w - frame || y >= im->h - frame)
                p[0] = p[1] = p[2] = 235;
        }
    }
    uint8_t red[4] = {220, 30, 30, 255}, blue[4] = {30, 30, 220, 255};
    int64_t mark = m / 10 > 2 ? m / 10 : 2;
    vt_sample_image_fill_rect(im, frame, frame, mark, mark, red);
    vt_sample_image_fill_rect(im, (int64_t)im->w - frame - mark, (int64_t)im->h - frame - mark,
                              mark, mark, blue);
}

static void paint_alpha(struct vt_sample_image *im, uint32_t index)
{
    double rgb[3];
    base_colour(index, rgb);
    double cx = im->w / 2.0, cy = im->h / 2.0, rx = im->w * 0.48, ry = im->h * 0.48;
    for (uint32_t y = 0; y < im->h; y++)
        for (uint32_t x = 0; x < im->w; x++) {
            uint8_t *p = vt_sample_image_at(im, x, y);
            double dx = (x + 0.5 - cx) / rx, dy = (y + 0.5 - cy) / ry;
            double d = sqrt(dx * dx + dy * dy);                  /* 1 on the ellipse */
            double edge = (1.0 - d) * (rx < ry ? rx : ry) / 2.0; /* ~2 px soft edge */
            double leaf =
                0.7 +
                0.3 * ((vt_sample_textures_hash32(index * 31u + (x / 6) * 977u + y / 6) & 3) / 3.0);
            for (int c = 0; c < 3; c++)
                p[c] = to_u8(rgb[c] * leaf);
            p[3] = to_u8(edge + 0.5);
        }
}

static void paint_mask(struct vt_sample_image *im)
{
    /* Diamond holes on a 20-pixel lattice: 0 in the holes, 255 on the wire. */
    uint32_t period = im->w / 15 > 8 ? im->w / 15 : 8;
    for (uint32_t y = 0; y < im->h; y++)
        for (uint32_t x = 0; x < im->w; x++) {
            int64_t dx = (int64_t)(x % period) - (int64_t)period / 2;
            int64_t dy = (int64_t)(y % period) - (int64_t)period / 2;
            bool hole = llabs(dx) + llabs(dy) < (int64_t)period * 2 / 5;
            vt_sample_image_at(im, x, y)[0] = hole ? 0 : 255;
        }
}

/* Seamless paving: rectangular stones (period = image size), grout lines, per-stone shade. */
static void paint_tiling(struct vt_sample_image *im, uint32_t index)
{
    double rgb[3] = {0.62, 0.58, 0.50};
    uint32_t sx = im->w / 4, sy = im->h / 8;
    if (sx < 2)
        sx = 2;
    if (sy < 2)
        sy = 2;
    for (uint32_t y = 0; y < im->h; y++) {
        uint32_t row = y / sy;
        uint32_t off = (row & 1) ? sx / 2 : 0; /* running bond; w is a multiple of sx */
        for (uint32_t x = 0; x < im->w; x++) {
            uint32_t xs = (x + off) % im->w;
            uint32_t stone = (xs / sx) + 16 * row;
            bool grout = xs % sx == 0 || y % sy == 0;
            double k =
                grout ? 0.35
                      : 0.8 + 0.2 * ((vt_sample_textures_hash32(index + stone * 2654435761u) & 7) /
                                     7.0);
            uint8_t *p = vt_sample_image_at(im, x, y);
            for (int c = 0; c < 3; c++)
                p[c] = to_u8(rgb[c] * k);
        }
    }
}

/* Normal map from a height field: rivets on a lattice plus the raised label, by central
 * differences (wrapping at the edges). +X right, +Y up (OpenGL convention), encoded n * 0.5 + 0.5.
 */
static int paint_normal(struct vt_sample_image *im, const char *line1, const char *line2)
{
    struct vt_sample_image height;
    if (vt_sample_image_alloc(&height, im->w, im->h, 1) < 0)
        return -1;
    uint32_t period = im->w / 8 > 8 ? im->w / 8 : 8;
    for (uint32_t y = 0; y < im->h; y++)
        for (uint32_t x = 0; x < im->w; x++) {
            double dx = (double)(x % period) - period / 2.0 + 0.5;
            double dy = (double)(y % period) - period / 2.0 + 0.5;
            double r = sqrt(dx * dx + dy * dy) / (period * 0.3);
            vt_sample_image_at(&height, x, y)[0] = r < 1 ? to_u8(sqrt(1 - r * r) * 0.6) : 0;
        }
    struct vt_sample_font_label b = vt_sample_font_label_place(im->w, im->h, line1, line2);
    uint8_t flat = 0, raised = 255;
    vt_sample_font_label_draw(&height, &b, line1, line2, &flat, &raised);
    const double strength = 4.0 / 255.0;
    for (uint32_t y = 0; y < im->h; y++)
        for (uint32_t x = 0; x < im->w; x++) {
            uint32_t xl = (x + im->w - 1) % im->w, xr = (x + 1) % im->w;
            uint32_t yu = (y + im->h - 1) % im->h, yd = (y + 1) % im->h;
            double dhx =
                (vt_sample_image_at(&height, xr, y)[0] - vt_sample_image_at(&height, xl, y)[0]) *
                strength / 2;
            /* rows go down, +Y goes up */
            double dhy =
                (vt_sample_image_at(&height, x, yu)[0] - vt_sample_image_at(&height, x, yd)[0]) *
                strength / 2;
            double nx = -dhx, ny = -dhy, nz = 1.0;
            double len = sqrt(nx * nx + ny * ny + nz * nz);
            uint8_t *p = vt_sample_image_at(im, x, y);
            p[0] = to_u8(nx / len * 0.5 + 0.5);
            p[1] = to_u8(ny / len * 0.5 + 0.5);
            p[2] = to_u8(nz / len * 0.5 + 0.5);
        }
    free(height.px);
    return 0;
}

int vt_sample_textures_make(const char *dir, uint32_t index, uint32_t shrink, struct vts_error *err)
{
    const struct vt_sample_textures_spec *t = &vt_sample_textures[index];
    uint32_t w = t->w / shrink > 8 ? t->w / shrink : 8;
    uint32_t h = t->h / shrink > 8 ? t->h / shrink : 8;
    static const uint32_t channels[] = {3, 4, 1, 3, 3};
    struct vt_sample_image im;
    if (vt_sample_image_alloc(&im, w, h, channels[t->kind]) < 0)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory for texture '%s'", t->file);
    char size_text[32];
    snprintf(size_text, sizeof(size_text), "%uX%u", w, h);
    struct vt_sample_font_label b = vt_sample_font_label_place(w, h, t->label, size_text);
    uint8_t box[4] = {20, 20, 20, 255}, ink[4] = {255, 255, 255, 255};
    int rc = 0;
    switch (t->kind) {
    case VT_SAMPLE_TEXTURES_FACADE:
        paint_facade(&im, index);
        vt_sample_font_label_draw(&im, &b, t->label, size_text, box, ink);
        break;
    case VT_SAMPLE_TEXTURES_ALPHA:
        paint_alpha(&im, index);
        vt_sample_font_label_draw(&im, &b, t->label, size_text, box, ink);
        break;
    case VT_SAMPLE_TEXTURES_MASK: {
        paint_mask(&im);
        uint8_t opaque = 255, hole = 0;
        vt_sample_font_label_draw(&im, &b, t->label, size_text, &opaque, &hole);
        break;
    }
    case VT_SAMPLE_TEXTURES_NORMAL:
        if (paint_normal(&im, t->label, size_text) < 0)
            rc = vt_error_set(err, VTS_ERR_NOMEM, "out of memory for texture '%s'", t->file);
        break;
    case VT_SAMPLE_TEXTURES_TILING: {
        paint_tiling(&im, index);
        /* the label stays inside the image, so the edges still tile */
        struct vt_sample_font_label small = vt_sample_font_label_place(w, h, t->label, "TILES");
        vt_sample_font_label_draw(&im, &small, t->label, "TILES", box, ink);
        break;
    }
    }
    if (rc == 0) {
        char path[VT_PATH_MAX];
        snprintf(path, sizeof(path), "%s/textures/%s", dir, t->file);
        rc = vt_sample_image_write_png(path, &im, err);
    }
    free(im.px);
    return rc;
}
