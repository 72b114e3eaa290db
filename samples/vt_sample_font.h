/* The built-in 5x7 bitmap font of the sample scene generator (samples/gen_scene.c) and the labels
 * drawn with it: each texture carries its name and size, so that a screenshot shows which texture
 * is where. */
#ifndef VT_SAMPLE_FONT_H
#define VT_SAMPLE_FONT_H

#include <stdint.h>

#include "vt_sample_image.h"

#define VT_SAMPLE_FONT_GLYPH_W       5
#define VT_SAMPLE_FONT_GLYPH_H       7
#define VT_SAMPLE_FONT_GLYPH_ADVANCE 6 /* one blank column between glyphs */

/* The width of text drawn at scale (font pixels of scale x scale), 0 for "". */
int64_t vt_sample_font_text_width(const char *text, int64_t scale);

/* Draws text with its top-left corner at (x0, y0), each font pixel a scale x scale square. */
void vt_sample_font_draw_text(struct vt_sample_image *im, int64_t x0, int64_t y0, int64_t scale,
                              const char *text, const uint8_t *value);

/* The label: the texture's name in big letters, its size below in smaller ones, white on a dark
 * box in the middle of the image. ink/box are ch-channel values. With a mask image (1 channel),
 * only the box and the text are drawn into it as box_mask/ink_mask. */
struct vt_sample_font_label {
    int64_t x, y, w, h;
    int64_t scale1, scale2;
};

/* Places the label of line1 over line2 in a w x h image. */
struct vt_sample_font_label vt_sample_font_label_place(uint32_t w, uint32_t h, const char *line1,
                                                       const char *line2);

/* Draws the label: box b filled with box, the two lines in ink (ch-channel values). */
void vt_sample_font_label_draw(struct vt_sample_image *im, const struct vt_sample_font_label *b,
                               const char *line1, const char *line2, const uint8_t *box,
                               const uint8_t *ink);

#endif
