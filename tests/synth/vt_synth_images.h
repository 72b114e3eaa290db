/* Seeded image-file generators for the image input tests: TIFF (tiled, striped, BigTIFF, separate
 * planes, 1/2/4-bit grey, palette, MINISWHITE; 8/16-bit, half and float), PNG (1..16 bits, grey,
 * grey + alpha, RGB(A), palette with tRNS, Adam7), JPEG (grey/RGB, 4:4:4/4:2:0, progressive),
 * OpenEXR (half/float, scanline/tiled, any channel names, data window origin) and TGA, written with
 * libtiff, libpng, libjpeg and OpenEXRCore (TGA by hand). Texel values are a function of (seed, x,
 * y, channel), so every region a reader returns can be compared with vt_synth_image_expected(). */
#ifndef VT_SYNTH_IMAGES_H
#define VT_SYNTH_IMAGES_H

#include <stdbool.h>
#include <stdint.h>

#include "vt_error.h"
#include "vt_image.h"

enum vt_synth_format {
    VT_SYNTH_TIFF = 1,
    VT_SYNTH_PNG = 2,
    VT_SYNTH_JPEG = 3,
    VT_SYNTH_EXR = 4,
    VT_SYNTH_TGA = 5,
};

/* libtiff COMPRESSION_* and OpenEXR exr_compression_t values, so that tests need neither header. */
enum vt_synth_compression {
    VT_SYNTH_TIFF_NONE = 1,
    VT_SYNTH_TIFF_LZW = 5,
    VT_SYNTH_TIFF_DEFLATE = 8,
    VT_SYNTH_TIFF_PACKBITS = 32773,
    VT_SYNTH_EXR_NONE = 0,
    VT_SYNTH_EXR_RLE = 1,
    VT_SYNTH_EXR_ZIPS = 2,
    VT_SYNTH_EXR_ZIP = 3,
    VT_SYNTH_EXR_PIZ = 4,
};

struct vt_synth_image_options {
    uint32_t format; /* enum vt_synth_format */
    uint32_t width, height;
    uint32_t channels; /* 1..4 as read back (palette: 3, or 4 for a PNG with tRNS) */
    uint32_t sample;   /* enum vts_sample as read back (JPEG, TGA, palette, low bits: U8) */
    uint32_t seed;
    uint32_t tile_w, tile_h; /* TIFF, EXR: tiled when non-zero (TIFF: multiples of 16) */
    uint32_t rows_per_strip; /* TIFF striped; 0 = 16 */
    uint32_t bits;           /* PNG/TIFF grey or palette index bits: 1, 2, 4 or 8 (0 = 8) */
    bool palette;            /* PNG/TIFF: indices into a palette (200 colours at 8 bits) */
    bool bigtiff;
    bool separate_planes;     /* TIFF PLANARCONFIG_SEPARATE */
    bool min_is_white;        /* TIFF grey stored inverted (read back as the pattern) */
    uint32_t extra_channels;  /* TIFF: more samples per texel than channels (to test refusals) */
    bool interlaced;          /* PNG Adam7 */
    uint32_t compression;     /* enum vt_synth_compression of the format */
    const char *exr_channels; /* EXR channel names, comma-separated ("B,G,R,A", "Y", "Y,A,Z");
                                 NULL = "R,G,B,A" cut to channels (1: "Y", 2: "Y,A") */
    int32_t exr_origin_x, exr_origin_y; /* EXR data window corner */
    uint32_t quality;                   /* JPEG quality 1..100 */
    bool jpeg_420;                      /* JPEG 4:2:0 chroma (else 4:4:4) */
    bool progressive;                   /* JPEG */
    uint32_t alpha_shape; /* enum vt_synth_alpha: the alpha channel (2 or 4 channels, u8 only) */
};

/* Shapes of the alpha channel (vt-atlas's cut-out detection); each texel's alpha in 0..1. */
enum vt_synth_alpha {
    VT_SYNTH_ALPHA_PATTERN, /* the seeded pattern, like the other channels */
    VT_SYNTH_ALPHA_CUTOUT,  /* a disc of radius 0.4 min(w, h): 1 inside, 0 outside, 0.5 on the
                               texels its edge crosses (an anti-aliased cut-out) */
    VT_SYNTH_ALPHA_SMOOTH,  /* (x + 0.5) / width: a smooth mask */
    VT_SYNTH_ALPHA_BINARY,  /* 0 in the left half, 1 in the right (a team-colour mask) */
    VT_SYNTH_ALPHA_OPAQUE,  /* 1 everywhere */
    VT_SYNTH_ALPHA_SPARSE,  /* 1 everywhere but texel (0, 0), which is 0 */
};

/* Defaults: 97x61 RGBA8 TIFF, seed 1, striped 16 rows, deflate/zip, JPEG quality 90. */
void vt_synth_image_defaults(struct vt_synth_image_options *o);

/* Writes the image file at path. Returns 0 or VTS_ERR_ARG/VTS_ERR_IO with a message. */
int vt_synth_image_write(const char *path, const struct vt_synth_image_options *o,
                         struct vts_error *err);

/* Fills dst (o->channels, o->sample, any size) with texels [x, x + dst->width) x [y, ...) as an
 * exact reader returns them. Not meaningful for JPEG (lossy): use vt_synth_jpeg_decode(). */
void vt_synth_image_expected(const struct vt_synth_image_options *o, uint32_t x, uint32_t y,
                             struct vt_image *dst);

/* Decodes a whole JPEG with libjpeg's defaults (grey or RGB, 8-bit) into *out (free with
 * vt_image_release()): the reference a region reader must match. */
int vt_synth_jpeg_decode(const char *path, struct vt_image *out, struct vts_error *err);

#endif
