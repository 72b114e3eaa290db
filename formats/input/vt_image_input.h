/* Image file input: opens TIFF/BigTIFF, PNG, JPEG and OpenEXR files as a region reader
 * (struct vt_source), recognising the format by its magic bytes, not the file name. Any other
 * format goes to OpenImageIO through a module that is dlopen()ed only when such a file is met
 * (libvt_oiio.so), so that processes reading only the native formats never load OpenImageIO.
 *
 * What comes out of read_region(): 1..4 interleaved channels (grey, grey + alpha, RGB, RGBA;
 * palettes expanded to RGB or RGBA, 1/2/4-bit grey scaled to 8 bits) in the sample type the file
 * stores (u8, u16, f16, f32), samples in host order. Details per format in vt_input_*.c. */
#ifndef VT_IMAGE_INPUT_H
#define VT_IMAGE_INPUT_H

#include <stdint.h>

#include "vt_error.h"
#include "vt_input_raster.h"
#include "vt_source.h"

/* Default of vt_input_limits.max_pixels: 2^34 texels (128k x 128k). */
#define VT_INPUT_DEFAULT_MAX_PIXELS (1ull << 34)

/* Limits checked from the header, before any pixel buffer is allocated. */
struct vt_input_limits {
    uint64_t max_pixels; /* width * height above this: VTS_ERR_LIMIT; 0 = the default */
};

/* Opens the image at path and fills *out (info, ops, ctx, name = path). Returns 0, or a negative
 * status with a one-line message naming the file: VTS_ERR_IO (cannot open or read),
 * VTS_ERR_BAD_INPUT (truncated, corrupt, zero size), VTS_ERR_LIMIT (more texels than
 * limits->max_pixels; limits may be NULL for the defaults), VTS_ERR_UNSUPPORTED (a variant no
 * reader handles: more than 4 channels, CMYK, signed or 32-bit integer samples, a format
 * OpenImageIO does not know or a build without it), VTS_ERR_NOMEM; *out is then zeroed. Close with
 * vt_source_close().
 *
 * The source is read by one thread at a time (the caller serialises); different sources may be
 * used from different threads at once. Sources with info.sequential (PNG, JPEG, striped TIFF,
 * scanline EXR, scanline files through OpenImageIO) are fastest read in full-width bands in
 * increasing y; a PNG or JPEG region above the previous one restarts the decode from the top. */
int vt_image_input_open(const char *path, const struct vt_input_limits *limits,
                        struct vt_source *out, struct vts_error *err);

/* ---- Multi-band and georeferenced rasters (GDAL input, docs/geospatial.md) ----
 * Files that need GDAL go to libvt_gdal.so (vt_gdal_module.c, dlopen()ed when such a file is
 * met): VRT mosaics, JPEG 2000, and TIFFs with GeoTIFF tags, more than 4 samples or samples the
 * native reader does not take (signed, 32-bit integers, 64-bit floats: read as 32-bit float). */

/* Fills *out for the image at path (zeroed first). Native formats: band_count = channels, no
 * georeferencing; files that go to GDAL: their bands, band descriptions, geotransform, CRS and
 * nodata. Errors as vt_image_input_open(), except that more than 4 bands is not one (more than
 * VT_INPUT_MAX_BANDS is). Release with vt_input_raster_release() (vt_input_raster.h). */
int vt_image_input_describe(const char *path, const struct vt_input_limits *limits,
                            struct vt_input_raster *out, struct vts_error *err);

/* As vt_image_input_open(), but reads only bands [first, first + count) (0-based; 1 <= count <= 4)
 * of the file: channels = count; has_alpha only when the group ends with an alpha band of a 2- or
 * 4-band group; colour data for bands that are not grey or RGB. count 0: every band (at most 4). */
int vt_image_input_open_bands(const char *path, const struct vt_input_limits *limits,
                              uint32_t first, uint32_t count, struct vt_source *out,
                              struct vts_error *err);

#endif
