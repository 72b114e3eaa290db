/* vt-sample-scene: writes the sample scene of vtpipe (a small city) into a directory:
 * scene.obj, scene.mtl and PNG textures in textures/. Every texture is generated here and carries
 * its name and size drawn with a built-in 5x7 bitmap font, so that a screenshot shows which texture
 * is where. The output is deterministic (no clock, no random seed). See samples/README.md for the
 * content. */
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "tool_common.h"
#include "vt_atomic_file.h"
#include "vt_error.h"
#include "vt_png_file.h"

/* ---- 5x7 bitmap font: 7 rows of 5 columns, '1' = ink ---- */

struct glyph {
    char c;
    const char *rows; /* 35 characters */
};

static const struct glyph font[] = {
    {'0', "01110100011001110101110011000101110"}, {'1', "00100011000010000100001000010001110"},
    {'2', "01110100010000100010001000100011111"}, {'3', "11111000100010000010000011000101110"},
    {'4', "00010001100101010010111110001000010"}, {'5', "11111100001111000001000011000101110"},
    {'6', "00110010001000011110100011000101110"}, {'7', "11111000010001000100010000100001000"},
    {'8', "01110100011000101110100011000101110"}, {'9', "01110100011000101111000010001001100"},
    {'A', "01110100011000111111100011000110001"}, {'B', "11110100011000111110100011000111110"},
    {'C', "01110100011000010000100001000101110"}, {'D', "11100100101000110001100011001011100"},
    {'E', "11111100001000011110100001000011111"}, {'F', "11111100001000011110100001000010000"},
    {'G', "01110100011000010111100011000101111"}, {'H', "10001100011000111111100011000110001"},
    {'I', "01110001000010000100001000010001110"}, {'J', "00111000100001000010000101001001100"},
    {'K', "10001100101010011000101001001010001"}, {'L', "10000100001000010000100001000011111"},
    {'M', "10001110111010110101100011000110001"}, {'N', "10001100011100110101100111000110001"},
    {'O', "01110100011000110001100011000101110"}, {'P', "11110100011000111110100001000010000"},
    {'Q', "01110100011000110001101011001001101"}, {'R', "11110100011000111110101001001010001"},
    {'S', "01111100001000001110000010000111110"}, {'T', "11111001000010000100001000010000100"},
    {'U', "10001100011000110001100011000101110"}, {'V', "10001100011000110001100010101000100"},
    {'W', "10001100011000110101101011010101010"}, {'X', "10001100010101000100010101000110001"},
    {'Y', "10001100010101000100001000010000100"}, {'Z', "11111000010001000100010001000011111"},
    {'-', "00000000000000011111000000000000000"}, {'_', "00000000000000000000000000000011111"},
    {'.', "00000000000000000000000000110001100"}, {' ', "00000000000000000000000000000000000"},
};

#define GLYPH_W       5
#define GLYPH_H       7
#define GLYPH_ADVANCE 6 /* one blank column between glyphs */

static const char *glyph_rows(char c)
{
    if (c >= 'a' && c <= 'z')
        c = (char)(c - 'a' + 'A');
    for (size_t i = 0; i < sizeof(font) / sizeof(font[0]); i++)
        if (font[i].c == c)
            return font[i].rows;
    return font[sizeof(font) / sizeof(font[0]) - 1].rows; /* unknown: blank */
}

/* ---- images ---- */

struct img {
    uint32_t w, h, ch;
    uint8_t *px;
};

static int img_alloc(struct img *im, uint32_t w, uint32_t h, uint32_t ch)
{
    im->w = w;
    im->h = h;
    im->ch = ch;
    im->px = calloc((size_t)w * h, ch); /* sizes are ours (at most 2000x1000x4) */
    return im->px ? 0 : -1;
}

static uint8_t *img_at(struct img *im, uint32_t x, uint32_t y)
{
    return im->px + ((size_t)y * im->w + x) * im->ch;
}

static void img_set(struct img *im, int64_t x, int64_t y, const uint8_t *value)
{
    if (x < 0 || y < 0 || x >= im->w || y >= im->h)
        return;
    memcpy(img_at(im, (uint32_t)x, (uint32_t)y), value, im->ch);
}

static void img_fill_rect(struct img *im, int64_t x0, int64_t y0, int64_t w, int64_t h,
                          const uint8_t *value)
{
    for (int64_t y = y0; y < y0 + h; y++)
        for (int64_t x = x0; x < x0 + w; x++)
            img_set(im, x, y, value);
}

static int64_t text_width(const char *text, int64_t scale)
{
    size_t n = strlen(text);
    return n ? (int64_t)(n * GLYPH_ADVANCE - 1) * scale : 0;
}

/* Draws text with its top-left corner at (x0, y0), each font pixel a scale x scale square. */
static void draw_text(struct img *im, int64_t x0, int64_t y0, int64_t scale, const char *text,
                      const uint8_t *value)
{
    for (size_t i = 0; text[i]; i++) {
        const char *rows = glyph_rows(text[i]);
        for (int gy = 0; gy < GLYPH_H; gy++)
            for (int gx = 0; gx < GLYPH_W; gx++)
                if (rows[gy * GLYPH_W + gx] == '1')
                    img_fill_rect(im, x0 + ((int64_t)i * GLYPH_ADVANCE + gx) * scale,
                                  y0 + gy * scale, scale, scale, value);
    }
}

/* The label: the texture's name in big letters, its size below in smaller ones, white on a dark
 * box in the middle of the image. ink/box are ch-channel values. With a mask image (1 channel),
 * only the box and the text are drawn into it as box_mask/ink_mask. */
struct label_box {
    int64_t x, y, w, h;
    int64_t scale1, scale2;
};

static struct label_box label_place(uint32_t w, uint32_t h, const char *line1, const char *line2)
{
    struct label_box b = {0};
    int64_t s1 = (int64_t)(0.6 * w) / (text_width(line1, 1) + 1);
    int64_t s1h = (int64_t)(0.3 * h) / GLYPH_H;
    if (s1h < s1)
        s1 = s1h;
    if (s1 < 1)
        s1 = 1;
    int64_t s2 = s1 / 2;
    int64_t s2w = (int64_t)(0.9 * w) / (text_width(line2, 1) + 1);
    if (s2w < s2)
        s2 = s2w;
    if (s2 < 1 && s1 >= 2)
        s2 = 1;
    b.scale1 = s1;
    b.scale2 = s2;
    int64_t pad = s1 > 2 ? s1 : 2;
    int64_t tw = text_width(line1, s1);
    if (s2 > 0 && text_width(line2, s2) > tw)
        tw = text_width(line2, s2);
    b.w = tw + 2 * pad;
    b.h = GLYPH_H * s1 + (s2 > 0 ? (GLYPH_H + 3) * s2 : 0) + 2 * pad;
    b.x = ((int64_t)w - b.w) / 2;
    b.y = ((int64_t)h - b.h) / 2;
    return b;
}

static void label_draw(struct img *im, const struct label_box *b, const char *line1,
                       const char *line2, const uint8_t *box, const uint8_t *ink)
{
    img_fill_rect(im, b->x, b->y, b->w, b->h, box);
    int64_t pad = b->scale1 > 2 ? b->scale1 : 2;
    draw_text(im, b->x + (b->w - text_width(line1, b->scale1)) / 2, b->y + pad, b->scale1, line1,
              ink);
    if (b->scale2 > 0)
        draw_text(im, b->x + (b->w - text_width(line2, b->scale2)) / 2,
                  b->y + pad + GLYPH_H * b->scale1 + 3 * b->scale2, b->scale2, line2, ink);
}

/* ---- texture content ---- */

enum tex_kind {
    TEX_FACADE, /* opaque RGB: wall with a window grid, frame and corner marks */
    TEX_ALPHA,  /* RGBA: a round cut-out (tree crown) with soft edges */
    TEX_MASK,   /* 1 channel: map_d fence mask with holes */
    TEX_NORMAL, /* RGB normal map (tangent space, +Y up) of rivets and the raised label */
    TEX_TILING, /* RGB paving that tiles seamlessly (used with UVs 0..8) */
};

struct tex_spec {
    const char *file; /* under textures/ */
    const char *label;
    uint32_t w, h;
    enum tex_kind kind;
};

/* 44 textures: t00..t40 colour (t36..t38 with alpha), n41 normal, g42 tiling, m43 alpha mask. */
static const struct tex_spec textures[] = {
    {"t00.png", "T00", 1024, 1024, TEX_FACADE},
    {"t01.png", "T01", 512, 256, TEX_FACADE},
    {"t02.png", "T02", 300, 200, TEX_FACADE},
    {"t03.png", "T03", 100, 60, TEX_FACADE},
    {"t04.png", "T04", 64, 64, TEX_FACADE},
    {"t05.png", "T05", 2000, 1000, TEX_FACADE},
    {"t06.png", "T06", 256, 256, TEX_FACADE},
    {"t07.png", "T07", 128, 128, TEX_FACADE},
    {"t08.png", "T08", 512, 512, TEX_FACADE},
    {"t09.png", "T09", 200, 300, TEX_FACADE},
    {"t10.png", "T10", 640, 480, TEX_FACADE},
    {"t11.png", "T11", 96, 96, TEX_FACADE},
    {"t12.png", "T12", 256, 128, TEX_FACADE},
    {"t13.png", "T13", 128, 256, TEX_FACADE},
    {"t14.png", "T14", 1000, 500, TEX_FACADE},
    {"t15.png", "T15", 333, 222, TEX_FACADE},
    {"t16.png", "T16", 150, 150, TEX_FACADE},
    {"t17.png", "T17", 80, 120, TEX_FACADE},
    {"t18.png", "T18", 512, 384, TEX_FACADE},
    {"t19.png", "T19", 64, 128, TEX_FACADE},
    {"t20.png", "T20", 720, 360, TEX_FACADE},
    {"t21.png", "T21", 240, 240, TEX_FACADE},
    {"t22.png", "T22", 48, 48, TEX_FACADE},
    {"t23.png", "T23", 400, 100, TEX_FACADE},
    {"t24.png", "T24", 100, 400, TEX_FACADE},
    {"t25.png", "T25", 257, 129, TEX_FACADE},
    {"t26.png", "T26", 160, 90, TEX_FACADE},
    {"t27.png", "T27", 384, 384, TEX_FACADE},
    {"t28.png", "T28", 192, 64, TEX_FACADE},
    {"t29.png", "T29", 200, 200, TEX_FACADE},
    {"t30.png", "T30", 768, 512, TEX_FACADE},
    {"t31.png", "T31", 64, 48, TEX_FACADE},
    {"t32.png", "T32", 120, 80, TEX_FACADE},
    {"t33.png", "T33", 256, 64, TEX_FACADE},
    {"t34.png", "T34", 500, 500, TEX_FACADE},
    {"t35.png", "T35", 350, 175, TEX_FACADE},
    {"t36_alpha.png", "T36", 256, 256, TEX_ALPHA},
    {"t37_alpha.png", "T37", 200, 300, TEX_ALPHA},
    {"t38_alpha.png", "T38", 128, 128, TEX_ALPHA},
    {"t39.png", "T39", 300, 150, TEX_FACADE},
    {"t40.png", "T40", 512, 512, TEX_FACADE},
    {"n41_normal.png", "N41", 512, 512, TEX_NORMAL},
    {"g42_tiling.png", "G42", 128, 128, TEX_TILING},
    {"m43_mask.png", "M43", 300, 150, TEX_MASK},
};
#define TEXTURE_COUNT (sizeof(textures) / sizeof(textures[0]))

static uint32_t hash32(uint32_t x)
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
static void paint_facade(struct img *im, uint32_t index)
{
    double rgb[3];
    base_colour(index, rgb);
    uint32_t m = im->w < im->h ? im->w : im->h;
    uint32_t cell = m / 6 > 8 ? m / 6 : 8;
    uint32_t frame = m / 64 > 1 ? m / 64 : 1;
    for (uint32_t y = 0; y < im->h; y++) {
        double shade = 0.75 + 0.25 * (double)y / im->h;
        for (uint32_t x = 0; x < im->w; x++) {
            uint8_t *p = img_at(im, x, y);
            uint32_t cx = x % cell, cy = y % cell;
            bool window =
                cx > cell / 4 && cx < cell - cell / 4 && cy > cell / 5 && cy < cell - cell / 3;
            double k =
                window ? 0.35 + 0.15 * (hash32(index * 7919u + (x / cell) * 131u + (y / cell)) & 1)
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
    img_fill_rect(im, frame, frame, mark, mark, red);
    img_fill_rect(im, (int64_t)im->w - frame - mark, (int64_t)im->h - frame - mark, mark, mark,
                  blue);
}

static void paint_alpha(struct img *im, uint32_t index)
{
    double rgb[3];
    base_colour(index, rgb);
    double cx = im->w / 2.0, cy = im->h / 2.0, rx = im->w * 0.48, ry = im->h * 0.48;
    for (uint32_t y = 0; y < im->h; y++)
        for (uint32_t x = 0; x < im->w; x++) {
            uint8_t *p = img_at(im, x, y);
            double dx = (x + 0.5 - cx) / rx, dy = (y + 0.5 - cy) / ry;
            double d = sqrt(dx * dx + dy * dy);                  /* 1 on the ellipse */
            double edge = (1.0 - d) * (rx < ry ? rx : ry) / 2.0; /* ~2 px soft edge */
            double leaf = 0.7 + 0.3 * ((hash32(index * 31u + (x / 6) * 977u + y / 6) & 3) / 3.0);
            for (int c = 0; c < 3; c++)
                p[c] = to_u8(rgb[c] * leaf);
            p[3] = to_u8(edge + 0.5);
        }
}

static void paint_mask(struct img *im)
{
    /* Diamond holes on a 20-pixel lattice: 0 in the holes, 255 on the wire. */
    uint32_t period = im->w / 15 > 8 ? im->w / 15 : 8;
    for (uint32_t y = 0; y < im->h; y++)
        for (uint32_t x = 0; x < im->w; x++) {
            int64_t dx = (int64_t)(x % period) - (int64_t)period / 2;
            int64_t dy = (int64_t)(y % period) - (int64_t)period / 2;
            bool hole = llabs(dx) + llabs(dy) < (int64_t)period * 2 / 5;
            img_at(im, x, y)[0] = hole ? 0 : 255;
        }
}

/* Seamless paving: rectangular stones (period = image size), grout lines, per-stone shade. */
static void paint_tiling(struct img *im, uint32_t index)
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
            double k = grout ? 0.35 : 0.8 + 0.2 * ((hash32(index + stone * 2654435761u) & 7) / 7.0);
            uint8_t *p = img_at(im, x, y);
            for (int c = 0; c < 3; c++)
                p[c] = to_u8(rgb[c] * k);
        }
    }
}

/* Normal map from a height field: rivets on a lattice plus the raised label, by central
 * differences (wrapping at the edges). +X right, +Y up (OpenGL convention), encoded n * 0.5 + 0.5.
 */
static int paint_normal(struct img *im, const char *line1, const char *line2)
{
    struct img height;
    if (img_alloc(&height, im->w, im->h, 1) < 0)
        return -1;
    uint32_t period = im->w / 8 > 8 ? im->w / 8 : 8;
    for (uint32_t y = 0; y < im->h; y++)
        for (uint32_t x = 0; x < im->w; x++) {
            double dx = (double)(x % period) - period / 2.0 + 0.5;
            double dy = (double)(y % period) - period / 2.0 + 0.5;
            double r = sqrt(dx * dx + dy * dy) / (period * 0.3);
            img_at(&height, x, y)[0] = r < 1 ? to_u8(sqrt(1 - r * r) * 0.6) : 0;
        }
    struct label_box b = label_place(im->w, im->h, line1, line2);
    uint8_t flat = 0, raised = 255;
    label_draw(&height, &b, line1, line2, &flat, &raised);
    const double strength = 4.0 / 255.0;
    for (uint32_t y = 0; y < im->h; y++)
        for (uint32_t x = 0; x < im->w; x++) {
            uint32_t xl = (x + im->w - 1) % im->w, xr = (x + 1) % im->w;
            uint32_t yu = (y + im->h - 1) % im->h, yd = (y + 1) % im->h;
            double dhx = (img_at(&height, xr, y)[0] - img_at(&height, xl, y)[0]) * strength / 2;
            /* rows go down, +Y goes up */
            double dhy = (img_at(&height, x, yu)[0] - img_at(&height, x, yd)[0]) * strength / 2;
            double nx = -dhx, ny = -dhy, nz = 1.0;
            double len = sqrt(nx * nx + ny * ny + nz * nz);
            uint8_t *p = img_at(im, x, y);
            p[0] = to_u8(nx / len * 0.5 + 0.5);
            p[1] = to_u8(ny / len * 0.5 + 0.5);
            p[2] = to_u8(nz / len * 0.5 + 0.5);
        }
    free(height.px);
    return 0;
}

static int write_png(const char *path, struct img *im, struct vt_error *err)
{
    struct vt_png_file_writer *w = vt_png_file_writer_create(path, im->w, im->h, im->ch, 8, err);
    if (!w)
        return err->status;
    int rc = vt_png_file_writer_rows(w, im->px, im->h, (size_t)im->w * im->ch, err);
    if (rc == 0)
        rc = vt_png_file_writer_finish(w, err);
    vt_png_file_writer_destroy(w);
    return rc;
}

static int make_texture(const char *dir, uint32_t index, uint32_t shrink, struct vt_error *err)
{
    const struct tex_spec *t = &textures[index];
    uint32_t w = t->w / shrink > 8 ? t->w / shrink : 8;
    uint32_t h = t->h / shrink > 8 ? t->h / shrink : 8;
    static const uint32_t channels[] = {3, 4, 1, 3, 3};
    struct img im;
    if (img_alloc(&im, w, h, channels[t->kind]) < 0)
        return vt_error_set(err, VT_ERR_NOMEM, "out of memory for texture '%s'", t->file);
    char size_text[32];
    snprintf(size_text, sizeof(size_text), "%uX%u", w, h);
    struct label_box b = label_place(w, h, t->label, size_text);
    uint8_t box[4] = {20, 20, 20, 255}, ink[4] = {255, 255, 255, 255};
    int rc = 0;
    switch (t->kind) {
    case TEX_FACADE:
        paint_facade(&im, index);
        label_draw(&im, &b, t->label, size_text, box, ink);
        break;
    case TEX_ALPHA:
        paint_alpha(&im, index);
        label_draw(&im, &b, t->label, size_text, box, ink);
        break;
    case TEX_MASK: {
        paint_mask(&im);
        uint8_t opaque = 255, hole = 0;
        label_draw(&im, &b, t->label, size_text, &opaque, &hole);
        break;
    }
    case TEX_NORMAL:
        if (paint_normal(&im, t->label, size_text) < 0)
            rc = vt_error_set(err, VT_ERR_NOMEM, "out of memory for texture '%s'", t->file);
        break;
    case TEX_TILING: {
        paint_tiling(&im, index);
        /* the label stays inside the image, so the edges still tile */
        struct label_box small = label_place(w, h, t->label, "TILES");
        label_draw(&im, &small, t->label, "TILES", box, ink);
        break;
    }
    }
    if (rc == 0) {
        char path[VT_PATH_MAX];
        snprintf(path, sizeof(path), "%s/textures/%s", dir, t->file);
        rc = write_png(path, &im, err);
    }
    free(im.px);
    return rc;
}

/* ---- text output ---- */

struct text {
    char *data;
    size_t len, cap;
    bool failed;
};

static void text_printf(struct text *t, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

static void text_printf(struct text *t, const char *fmt, ...)
{
    if (t->failed)
        return;
    for (;;) {
        va_list ap;
        va_start(ap, fmt);
        int n = vsnprintf(t->data ? t->data + t->len : NULL, t->cap - t->len, fmt, ap);
        va_end(ap);
        if (n < 0) {
            t->failed = true;
            return;
        }
        if (t->len + (size_t)n < t->cap) {
            t->len += (size_t)n;
            return;
        }
        size_t cap = (t->cap + (size_t)n + 1) * 2;
        char *d = realloc(t->data, cap);
        if (!d) {
            t->failed = true;
            return;
        }
        t->data = d;
        t->cap = cap;
    }
}

static int write_text(const char *path, const struct text *t, struct vt_error *err)
{
    if (t->failed)
        return vt_error_set(err, VT_ERR_NOMEM, "out of memory writing '%s'", path);
    struct vt_atomic_file f;
    int rc = vt_atomic_file_create(&f, path, "tmp", err);
    if (rc < 0)
        return rc;
    rc = vt_atomic_file_pwrite(&f, t->data, t->len, 0, err);
    if (rc == 0)
        rc = vt_atomic_file_commit(&f, err);
    else
        vt_atomic_file_abort(&f);
    return rc;
}

/* The MTL is written with CRLF line ends, as Windows exporters do (valid for every reader). */
#define EOL "\r\n"

static void mtl_material(struct text *m, const char *name, const char *comment)
{
    text_printf(m,
                EOL "# %s" EOL "newmtl %s" EOL "Ka 0.1 0.1 0.1" EOL "Kd 1 1 1" EOL
                    "Ks 0.05 0.05 0.05" EOL "Ns 10" EOL "illum 2" EOL,
                comment, name);
}

static void write_mtl(struct text *m)
{
    text_printf(m, "# vtpipe sample scene materials (generated by vt-sample-scene)" EOL);
    for (uint32_t i = 0; i < 36; i++) {
        char name[32];
        snprintf(name, sizeof(name), "bld_%02u", i);
        mtl_material(m, name, "building");
        text_printf(m, "map_Kd textures/%s" EOL, textures[i].file);
    }
    mtl_material(m, "kiosk", "shares t10.png with bld_10");
    text_printf(m, "map_Kd textures/%s" EOL, textures[10].file);
    for (uint32_t i = 36; i <= 38; i++) {
        char name[32];
        snprintf(name, sizeof(name), "tree_%u", i - 36);
        mtl_material(m, name, "alpha in the RGBA diffuse map");
        text_printf(m, "map_Kd textures/%s" EOL, textures[i].file);
    }
    mtl_material(m, "fence", "RGB diffuse map + a separate map_d alpha mask");
    text_printf(m, "map_Kd textures/%s" EOL "map_d textures/%s" EOL, textures[39].file,
                textures[43].file);
    mtl_material(m, "wall", "diffuse + tangent-space normal map");
    text_printf(m, "map_Kd textures/%s" EOL "norm textures/%s" EOL, textures[40].file,
                textures[41].file);
    mtl_material(m, "ground", "tiling texture, UVs 0..8");
    text_printf(m, "map_Kd textures/%s" EOL, textures[42].file);
    text_printf(m, EOL "# no texture: a constant colour" EOL "newmtl plain_grey" EOL
                       "Kd 0.5 0.5 0.5" EOL "illum 1" EOL);
}

struct obj_state {
    struct text *t;
    uint32_t v, vt; /* counts written so far */
};

/* Normals written once at the top: 1 +X, 2 -X, 3 +Y, 4 -Y, 5 +Z, 6 -Z. */
enum { N_PX = 1, N_NX, N_PY, N_NY, N_PZ, N_NZ };

/* A quad face with corners a..d (1-based absolute v and vt), normal n; relative (negative)
 * indices when rel. */
static void obj_face4(struct obj_state *s, const uint32_t v[4], const uint32_t vt[4], int n,
                      bool rel)
{
    text_printf(s->t, "f");
    for (int i = 0; i < 4; i++) {
        if (rel)
            text_printf(s->t, " %lld/%lld/%d", (long long)v[i] - (long long)s->v - 1,
                        (long long)vt[i] - (long long)s->vt - 1, n);
        else
            text_printf(s->t, " %u/%u/%d", v[i], vt[i], n);
    }
    text_printf(s->t, "\n");
}

static void obj_tri(struct obj_state *s, uint32_t a, uint32_t b, uint32_t c, uint32_t ta,
                    uint32_t tb, uint32_t tc, int n)
{
    text_printf(s->t, "f %u/%u/%d %u/%u/%d %u/%u/%d\n", a, ta, n, b, tb, n, c, tc, n);
}

/* A box on the ground with every side showing the whole texture: 8 v, 4 vt, 5 faces (no
 * bottom). style 0: absolute indices, 1: negative indices, 2: top split into two triangles. */
static void obj_box(struct obj_state *s, const char *name, const char *mtl, double x0, double z0,
                    double x1, double z1, double y0, double y1, int style)
{
    text_printf(s->t, "o %s\nusemtl %s\n", name, mtl);
    const double xs[2] = {x0, x1}, zs[2] = {z0, z1};
    /* p0 (x0,y0,z0) p1 (x1,y0,z0) p2 (x1,y0,z1) p3 (x0,y0,z1), p4..p7 the same at y1 */
    const int corner[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int level = 0; level < 2; level++)
        for (int i = 0; i < 4; i++)
            text_printf(s->t, "v %.4f %.4f %.4f\n", xs[corner[i][0]], level ? y1 : y0,
                        zs[corner[i][1]]);
    text_printf(s->t, "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n");
    uint32_t p = s->v + 1, t = s->vt + 1;
    s->v += 8;
    s->vt += 4;
    const uint32_t uv[4] = {t, t + 1, t + 2, t + 3};
    const uint32_t front[4] = {p + 3, p + 2, p + 6, p + 7}, right[4] = {p + 2, p + 1, p + 5, p + 6};
    const uint32_t back[4] = {p + 1, p + 0, p + 4, p + 5}, left[4] = {p + 0, p + 3, p + 7, p + 4};
    const uint32_t top[4] = {p + 7, p + 6, p + 5, p + 4};
    bool rel = style == 1;
    obj_face4(s, front, uv, N_PZ, rel);
    obj_face4(s, right, uv, N_PX, rel);
    obj_face4(s, back, uv, N_NZ, rel);
    obj_face4(s, left, uv, N_NX, rel);
    if (style == 2) {
        obj_tri(s, top[0], top[1], top[2], uv[0], uv[1], uv[2], N_PY);
        obj_tri(s, top[0], top[2], top[3], uv[0], uv[2], uv[3], N_PY);
    } else {
        obj_face4(s, top, uv, N_PY, rel);
    }
}

/* A vertical quad facing +Z (or +X when along_z), bottom edge centred on (cx, cz), UV [0,1]. */
static void obj_billboard(struct obj_state *s, double cx, double cz, double w, double h,
                          bool along_z, bool rel)
{
    double hw = w / 2;
    for (int i = 0; i < 4; i++) {
        double a = (i == 0 || i == 3) ? -hw : hw, y = i >= 2 ? h : 0;
        if (along_z)
            text_printf(s->t, "v %.4f %.4f %.4f\n", cx, y, cz - a);
        else
            text_printf(s->t, "v %.4f %.4f %.4f\n", cx + a, y, cz);
    }
    text_printf(s->t, "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n");
    uint32_t p = s->v + 1, t = s->vt + 1;
    s->v += 4;
    s->vt += 4;
    const uint32_t v[4] = {p, p + 1, p + 2, p + 3}, uv[4] = {t, t + 1, t + 2, t + 3};
    obj_face4(s, v, uv, along_z ? N_PX : N_PZ, rel);
}

#define GRID  6
#define BLOCK 10.0 /* city block: one repeat of the ground texture */

static void write_obj(struct text *o)
{
    struct obj_state s = {o, 0, 0};
    text_printf(o, "# vtpipe sample scene (generated by vt-sample-scene): a 6x6 city on tiled\n"
                   "# ground, trees with alpha, a fence with a map_d mask, a normal-mapped wall.\n"
                   "mtllib scene.mtl\n"
                   "vn 1 0 0\nvn -1 0 0\nvn 0 1 0\nvn 0 -1 0\nvn 0 0 1\nvn 0 0 -1\n");
    /* Ground: 3x3 vertices from -BLOCK to (GRID + 2) * BLOCK - BLOCK, UVs 0..8 (8 blocks). */
    text_printf(o, "o ground\nusemtl ground\n");
    const double g0 = -BLOCK, g1 = (GRID + 1) * BLOCK;
    for (int j = 0; j < 3; j++)
        for (int i = 0; i < 3; i++) {
            double x = g0 + (g1 - g0) * i / 2, z = g1 - (g1 - g0) * j / 2;
            text_printf(o, "v %.4f 0 %.4f\nvt %d %d\n", x, z, 4 * i, 4 * j);
        }
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 2; i++) {
            uint32_t a = (uint32_t)(j * 3 + i + 1);
            const uint32_t v[4] = {a, a + 1, a + 4, a + 3};
            obj_face4(&s, v, v, N_PY, false);
        }
    s.v = s.vt = 9;
    /* Buildings: one per grid cell, each its own object and material. */
    for (uint32_t i = 0; i < GRID * GRID; i++) {
        uint32_t gx = i % GRID, gz = i / GRID, h = hash32(i + 1000);
        double foot = 4.0 + (h & 3), height = 5.0 + ((h >> 4) % 26);
        double cx = gx * BLOCK + BLOCK / 2, cz = gz * BLOCK + BLOCK / 2;
        char name[32], mtl[32];
        snprintf(name, sizeof(name), "building_%02u", i);
        snprintf(mtl, sizeof(mtl), "bld_%02u", i);
        obj_box(&s, name, mtl, cx - foot / 2, cz - foot / 2, cx + foot / 2, cz + foot / 2, 0,
                height, (int)(i % 3));
    }
    /* Kiosk next to building 10, sharing its texture through another material. */
    obj_box(&s, "kiosk", "kiosk", 3 * BLOCK + 8.2, 1 * BLOCK + 0.5, 3 * BLOCK + 9.5,
            1 * BLOCK + 1.8, 0, 2.0, 1);
    /* Antenna on building 0: no texture. */
    obj_box(&s, "antenna", "plain_grey", 4.8, 4.8, 5.2, 5.2, 0, 40.0, 0);
    /* Trees: two crossed alpha quads each, negative indices. */
    for (int i = 0; i < 3; i++) {
        char name[32], mtl[32];
        snprintf(name, sizeof(name), "tree_%d", i);
        snprintf(mtl, sizeof(mtl), "tree_%d", i);
        text_printf(o, "o %s\nusemtl %s\n", name, mtl);
        double cx = BLOCK * (1 + 2 * i), cz = GRID * BLOCK + 3;
        obj_billboard(&s, cx, cz, 4, 6, false, true);
        obj_billboard(&s, cx, cz, 4, 6, true, true);
    }
    text_printf(o, "o fence\nusemtl fence\n");
    obj_billboard(&s, GRID * BLOCK / 2, -4, 20, 2.5, false, false);
    text_printf(o, "o wall\nusemtl wall\n");
    obj_billboard(&s, -5, GRID * BLOCK / 2, 12, 12, true, false);
}

/* ---- main ---- */

static void usage(FILE *f)
{
    fprintf(f,
            "usage: vt-sample-scene [--shrink N] [-q] OUTDIR\n"
            "Writes the vtpipe sample scene: OUTDIR/scene.obj, OUTDIR/scene.mtl and %u textures\n"
            "in OUTDIR/textures/ (PNG, each labelled with its name and size). Deterministic.\n"
            "  --shrink N   divide every texture edge by N (1..16, default 1; at least 8 px)\n"
            "  -q           print errors only\n",
            (unsigned)TEXTURE_COUNT);
}

/* mkdir -p: creates path and every missing parent. */
static int make_dir(const char *path)
{
    char buf[VT_PATH_MAX];
    snprintf(buf, sizeof(buf), "%s", path);
    for (char *p = buf + 1;; p++) {
        if (*p != '/' && *p != 0)
            continue;
        char saved = *p;
        *p = 0;
        if (mkdir(buf, 0777) != 0 && errno != EEXIST) {
            vt_log(VT_LOG_ERROR, "cannot create '%s': %s", buf, strerror(errno));
            return -1;
        }
        *p = saved;
        if (!saved)
            return 0;
    }
}

static int run(const char *dir, uint32_t shrink)
{
    struct vt_error err = {0};
    char path[VT_PATH_MAX];
    if (strlen(dir) > VT_PATH_MAX - 64) {
        vt_log(VT_LOG_ERROR, "output directory name too long");
        return VT_EXIT_USAGE;
    }
    snprintf(path, sizeof(path), "%s/textures", dir);
    if (make_dir(dir) < 0 || make_dir(path) < 0)
        return VT_EXIT_BAD_INPUT;
    uint64_t texels = 0;
    for (uint32_t i = 0; i < TEXTURE_COUNT; i++) {
        if (make_texture(dir, i, shrink, &err) < 0) {
            vt_log(VT_LOG_ERROR, "%s", err.message);
            return VT_EXIT_BAD_INPUT;
        }
        texels += (uint64_t)textures[i].w * textures[i].h;
    }
    struct text mtl = {0}, obj = {0};
    write_mtl(&mtl);
    write_obj(&obj);
    int rc = 0;
    snprintf(path, sizeof(path), "%s/scene.mtl", dir);
    if (write_text(path, &mtl, &err) < 0)
        rc = -1;
    snprintf(path, sizeof(path), "%s/scene.obj", dir); /* last: its presence means complete */
    if (rc == 0 && write_text(path, &obj, &err) < 0)
        rc = -1;
    free(mtl.data);
    free(obj.data);
    if (rc < 0) {
        vt_log(VT_LOG_ERROR, "%s", err.message);
        return VT_EXIT_BAD_INPUT;
    }
    vt_log(VT_LOG_INFO, "wrote '%s': %u textures (%.1f Mtexels before --shrink)", path,
           (unsigned)TEXTURE_COUNT, texels / 1e6);
    return VT_EXIT_OK;
}

int main(int argc, char **argv)
{
    vt_tool_init("vt-sample-scene");
    vt_atomic_file_cleanup_on_signals();
    vt_log_set_level(VT_LOG_INFO);
    static const struct option opts[] = {{"shrink", required_argument, NULL, 's'},
                                         {"quiet", no_argument, NULL, 'q'},
                                         {"help", no_argument, NULL, 'h'},
                                         {"version", no_argument, NULL, 'V'},
                                         {NULL, 0, NULL, 0}};
    uint32_t shrink = 1;
    opterr = 0;
    int c;
    while ((c = vt_getopt_long(argc, argv, ":qh", opts)) != -1) {
        switch (c) {
        case 's':
            if (vt_parse_u32(optarg, 1, 16, &shrink) < 0)
                return vt_usage_error("--shrink: expected an integer 1..16, got '%s'", optarg);
            break;
        case 'q':
            vt_log_set_level(VT_LOG_ERROR);
            break;
        case 'h':
            usage(stdout);
            return VT_EXIT_OK;
        case 'V':
            vt_print_version(stdout);
            return VT_EXIT_OK;
        default:
            return vt_usage_getopt_error(c, argv);
        }
    }
    if (optind != argc - 1)
        return vt_usage_error("expected one output directory");
    return run(argv[optind], shrink);
}
