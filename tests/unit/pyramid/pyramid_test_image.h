/* Shared by the pyramid tests (included by each, one copy per test program): a w x h RGBA u8 sRGB
 * image in memory with a fixed pattern (transparent for x < 40, so that some tiles are empty),
 * read through a random-access vt_source. */
#ifndef PYRAMID_TEST_IMAGE_H
#define PYRAMID_TEST_IMAGE_H

#include <stdio.h>
#include <string.h>

#include "vt_image.h"
#include "vt_source.h"

static int pyramid_test_read_region(void *ctx, uint32_t x, uint32_t y, struct vt_image *dst,
                                    struct vts_error *err)
{
    (void)err;
    const struct vt_image *img = ctx;
    for (uint32_t r = 0; r < dst->height; r++)
        memcpy((char *)dst->pixels + (size_t)r * dst->stride, vt_image_at(img, x, y + r),
               (size_t)dst->width * vt_image_texel_bytes(img));
    return 0;
}

static void pyramid_test_close(void *ctx)
{
    (void)ctx;
}

static const struct vt_source_ops pyramid_test_ops = {pyramid_test_read_region, pyramid_test_close};

/* (Re)fills *image with the pattern at w x h and points *source at it. */
static void pyramid_test_source(struct vt_image *image, struct vt_source *source, uint32_t w,
                                uint32_t h)
{
    vt_image_release(image);
    vt_image_alloc(image, w, h, 4, VTS_SAMPLE_U8, NULL);
    for (uint32_t y = 0; y < h; y++)
        for (uint32_t x = 0; x < w; x++) {
            unsigned char *p = vt_image_at(image, x, y);
            p[0] = (unsigned char)(x * 3 + y);
            p[1] = (unsigned char)((x ^ y) * 5);
            p[2] = (unsigned char)(y * 7 + (x >> 3));
            p[3] = (unsigned char)(x < 40 ? 0 : 128 + (x + y) % 128); /* some transparent tiles */
        }
    *source = (struct vt_source){.info = {.width = w,
                                          .height = h,
                                          .channels = 4,
                                          .sample = VTS_SAMPLE_U8,
                                          .colour = VTS_COLOUR_SRGB,
                                          .has_alpha = true},
                                 .ops = &pyramid_test_ops,
                                 .ctx = image};
    snprintf(source->name, sizeof source->name, "memory");
}

#endif
