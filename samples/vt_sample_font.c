/* The 5x7 bitmap font and texture labels of the sample scene generator (see vt_sample_font.h). */
#include "vt_sample_font.h"

#include <string.h>

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

static const char *glyph_rows(char c)
{
    if (c >= 'a' && c <= 'z')
        c = (char)(c - 'a' + 'A');
    for (size_t i = 0; i < sizeof(font) / sizeof(font[0]); i++)
        if (font[i].c == c)
            return font[i].rows;
    return font[sizeof(font) / sizeof(font[0]) - 1].rows; /* unknown: blank */
}

int64_t vt_sample_font_text_width(const char *text, int64_t scale)
{
    size_t n = strlen(text);
    return n ? (int64_t)(n * VT_SAMPLE_FONT_GLYPH_ADVANCE - 1) * scale : 0;
}

/* Draws text with its top-left corner at (x0, y0), each font pixel a scale x scale square. */
void vt_sample_font_draw_text(struct vt_sample_image *im, int64_t x0, int64_t y0, int64_t scale,
                              const char *text, const uint8_t *value)
{
    for (size_t i = 0; text[i]; i++) {
        const char *rows = glyph_rows(text[i]);
        for (int gy = 0; gy < VT_SAMPLE_FONT_GLYPH_H; gy++)
            for (int gx = 0; gx < VT_SAMPLE_FONT_GLYPH_W; gx++)
                if (rows[gy * VT_SAMPLE_FONT_GLYPH_W + gx] == '1')
                    vt_sample_image_fill_rect(
                        im, x0 + ((int64_t)i * VT_SAMPLE_FONT_GLYPH_ADVANCE + gx) * scale,
                        y0 + gy * scale, scale, scale, value);
    }
}
struct vt_sample_font_label vt_sample_font_label_place(uint32_t w, uint32_t h, const char *line1,
                                                       const char *line2)
{
    struct vt_sample_font_label b = {0};
    int64_t s1 = (int64_t)(0.6 * w) / (vt_sample_font_text_width(line1, 1) + 1);
    int64_t s1h = (int64_t)(0.3 * h) / VT_SAMPLE_FONT_GLYPH_H;
    if (s1h < s1)
        s1 = s1h;
    if (s1 < 1)
        s1 = 1;
    int64_t s2 = s1 / 2;
    int64_t s2w = (int64_t)(0.9 * w) / (vt_sample_font_text_width(line2, 1) + 1);
    if (s2w < s2)
        s2 = s2w;
    if (s2 < 1 && s1 >= 2)
        s2 = 1;
    b.scale1 = s1;
    b.scale2 = s2;
    int64_t pad = s1 > 2 ? s1 : 2;
    int64_t tw = vt_sample_font_text_width(line1, s1);
    if (s2 > 0 && vt_sample_font_text_width(line2, s2) > tw)
        tw = vt_sample_font_text_width(line2, s2);
    b.w = tw + 2 * pad;
    b.h = VT_SAMPLE_FONT_GLYPH_H * s1 + (s2 > 0 ? (VT_SAMPLE_FONT_GLYPH_H + 3) * s2 : 0) + 2 * pad;
    b.x = ((int64_t)w - b.w) / 2;
    b.y = ((int64_t)h - b.h) / 2;
    return b;
}

void vt_sample_font_label_draw(struct vt_sample_image *im, const struct vt_sample_font_label *b,
                               const char *line1, const char *line2, const uint8_t *box,
                               const uint8_t *ink)
{
    vt_sample_image_fill_rect(im, b->x, b->y, b->w, b->h, box);
    int64_t pad = b->scale1 > 2 ? b->scale1 : 2;
    vt_sample_font_draw_text(im, b->x + (b->w - vt_sample_font_text_width(line1, b->scale1)) / 2,
                             b->y + pad, b->scale1, line1, ink);
    if (b->scale2 > 0)
        vt_sample_font_draw_text(
            im, b->x + (b->w - vt_sample_font_text_width(line2, b->scale2)) / 2,
            b->y + pad + VT_SAMPLE_FONT_GLYPH_H * b->scale1 + 3 * b->scale2, b->scale2, line2, ink);
}
