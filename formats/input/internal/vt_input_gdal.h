/* Private to formats/input: the GDAL reader (vt_input_gdal.c), which the dispatcher calls directly
 * (it takes band groups and describes georeferencing, which the reader table does not). */
#ifndef VT_INPUT_GDAL_H
#define VT_INPUT_GDAL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "vt_error.h"
#include "vt_input_raster.h"
#include "vt_source.h"

/* True for the magic bytes of the formats sent to GDAL whatever their content: a VRT
 * ("<VRTDataset") and JPEG 2000 (a JP2 box or a raw codestream). */
bool vt_input_gdal_sniff(const unsigned char *magic, size_t len);

/* True when libvt_gdal.so can be loaded (why filled otherwise). */
bool vt_input_gdal_available(char *why, size_t why_size);

/* Opens bands [first, first + count) of path (count 0: all, at most 4); see
 * vt_image_input_open_bands(). */
int vt_input_gdal_open(const char *path, uint64_t max_pixels, uint32_t first, uint32_t count,
                       struct vt_source *out, struct vts_error *err);

/* Fills *out (already zeroed) from the file through GDAL. */
int vt_input_gdal_describe(const char *path, uint64_t max_pixels, struct vt_input_raster *out,
                           struct vts_error *err);

#endif
