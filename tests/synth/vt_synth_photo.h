/* Photo-like test images for codec tests: smooth gradients, texture, hard edges and grain. */
#ifndef VT_SYNTH_PHOTO_H
#define VT_SYNTH_PHOTO_H

#include <stdint.h>

#include "vt_image.h"

/* A w x h image (1, 3 or 4 channels, u8, tight stride, pixels from malloc: free them) from seed;
 * chroma scales how colourful it is (0 = grey); alpha (4 channels) is a smooth field with one
 * hard-edged hole. */
struct vt_image vt_synth_photo(uint32_t w, uint32_t h, uint32_t channels, uint32_t seed,
                               double chroma);

/* PSNR in dB over every sample of two u8 images of one shape (99 when identical). */
double vt_synth_psnr_u8(const struct vt_image *a, const struct vt_image *b);

#endif
