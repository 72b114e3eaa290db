/* Pixel buffers of the sample scene generator (samples/gen_scene.c): 8-bit images of 1..4
 * channels, written as PNG. */
#ifndef VT_SAMPLE_IMAGE_H
#define VT_SAMPLE_IMAGE_H

#include <stdint.h>

#include "vt_error.h"

struct vt_sample_image {
    uint32_t w, h, ch;
    uint8_t *px;
};

/* Allocates w x h pixels of ch channels, zeroed (free im->px). Returns 0 or -1 (out of memory). */
int vt_sample_image_alloc(struct vt_sample_image *im, uint32_t w, uint32_t h, uint32_t ch);

/* The pixel at (x, y), which must be inside the image. */
uint8_t *vt_sample_image_at(struct vt_sample_image *im, uint32_t x, uint32_t y);

/* Sets the pixel at (x, y) to value (ch bytes); pixels outside the image are ignored. */
void vt_sample_image_set(struct vt_sample_image *im, int64_t x, int64_t y, const uint8_t *value);

/* Sets the pixels of a rectangle (clipped to the image) to value (ch bytes). */
void vt_sample_image_fill_rect(struct vt_sample_image *im, int64_t x0, int64_t y0, int64_t w,
                               int64_t h, const uint8_t *value);

/* Writes the image to path as an 8-bit PNG. Returns 0 or a negative status with err filled. */
int vt_sample_image_write_png(const char *path, struct vt_sample_image *im, struct vts_error *err);

#endif
