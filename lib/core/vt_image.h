/* Pixel buffers: size, channels, sample type, row stride. */
#ifndef VT_IMAGE_H
#define VT_IMAGE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "vt_error.h"
#include "vts.h"

/* Bytes per sample of an enum vts_sample, 0 if unknown (what libvts's vts_sample_bytes() returns;
 * here so that core needs nothing of the store). */
static inline unsigned vt_sample_bytes(uint32_t sample)
{
    switch (sample) {
    case VTS_SAMPLE_U8:
        return 1;
    case VTS_SAMPLE_U16:
    case VTS_SAMPLE_F16:
        return 2;
    case VTS_SAMPLE_F32:
        return 4;
    default:
        return 0;
    }
}

/* Interleaved channels; samples in host order (little-endian on every supported machine). */
struct vt_image {
    uint32_t width, height; /* texels */
    uint32_t channels;      /* 1..4 */
    uint32_t sample;        /* enum vts_sample */
    size_t stride;          /* bytes from one row to the next (>= width * texel bytes) */
    void *pixels;           /* owned when allocated by vt_image_alloc() */
};

/* Allocates a zeroed width x height image with a tight stride. Checks the byte count for overflow
 * (VTS_ERR_LIMIT). Free with vt_image_release(). */
int vt_image_alloc(struct vt_image *img, uint32_t width, uint32_t height, uint32_t channels,
                   uint32_t sample, struct vts_error *err);

/* Frees pixels allocated by vt_image_alloc() and zeroes the struct. Accepts NULL. */
void vt_image_release(struct vt_image *img);

/* Bytes of one texel (channels * sample bytes). */
size_t vt_image_texel_bytes(const struct vt_image *img);

/* True on a little-endian host (vt_image samples and payload samples are in host order:
 * little-endian there). */
static inline bool vt_host_is_little_endian(void)
{
    const uint16_t one = 1;
    unsigned char first;
    memcpy(&first, &one, 1);
    return first == 1;
}

/* Pointer to texel (x, y). */
static inline void *vt_image_at(const struct vt_image *img, uint32_t x, uint32_t y)
{
    return (unsigned char *)img->pixels + (size_t)y * img->stride +
           (size_t)x * vt_image_texel_bytes(img);
}

#endif
