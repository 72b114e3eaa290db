/* A region reader over an image: a file (formats/input/vt_image_input.h), a temporary level of the
 * pyramid, an atlas layout or a store level. The pyramid only ever sees this interface. */
#ifndef VT_SOURCE_H
#define VT_SOURCE_H

#include <stdbool.h>
#include <stdint.h>

#include "vt_error.h"
#include "vt_image.h"

struct vt_source_info {
    uint32_t width, height; /* texels */
    uint32_t channels;      /* 1..4 as stored in the input (2 = grey + alpha, 4 = RGBA) */
    uint32_t sample;        /* enum vts_sample of read_region() output */
    uint32_t colour; /* enum vts_colour the input suggests (8/16-bit colour: srgb; float: linear) */
    bool has_alpha;  /* the last channel is alpha (channels 2 or 4) */
    bool premultiplied;      /* colour is already multiplied by alpha (OpenEXR's convention) */
    bool sequential;         /* regions are cheap only top-down in full-width bands (PNG, JPEG,
                                striped TIFF): read whole bands in increasing y */
    uint32_t tile_w, tile_h; /* native tile size of a tiled input, else 0 */
    char format[16];         /* "tiff", "png", "jpeg", "exr", "oiio:tga", "float-temp"... */
};

struct vt_source_ops {
    /* Reads texels [x, x + dst->width) x [y, y + dst->height) into dst, whose channels and sample
     * equal the source's (the caller allocates it). The region lies inside the image. Called by
     * one thread at a time. Returns 0 or a negative status with a message naming the file. */
    int (*read_region)(void *ctx, uint32_t x, uint32_t y, struct vt_image *dst,
                       struct vts_error *err);
    void (*close)(void *ctx); /* frees ctx */
};

struct vt_source {
    struct vt_source_info info;
    const struct vt_source_ops *ops;
    void *ctx;
    char name[256]; /* for messages: the file name */
};

/* Reads a region after checking it lies inside the image (VTS_ERR_RANGE otherwise) and that dst
 * has the source's channels and sample (VTS_ERR_ARG). */
int vt_source_read(struct vt_source *src, uint32_t x, uint32_t y, struct vt_image *dst,
                   struct vts_error *err);

/* Reads the whole image top-down in bands and sets *opaque to whether every alpha sample is at
 * its maximum (1.0 for floats). Sources without alpha are opaque. */
int vt_source_alpha_opaque(struct vt_source *src, bool *opaque, struct vts_error *err);

/* True when every alpha sample of img (its last channel) is at its maximum (1.0 for floats;
 * NaN is not). Call only for images with an alpha channel. */
bool vt_image_alpha_opaque(const struct vt_image *img);

/* Closes the source (ops->close) and zeroes it. Accepts NULL and an already closed source. */
void vt_source_close(struct vt_source *src);

#endif
