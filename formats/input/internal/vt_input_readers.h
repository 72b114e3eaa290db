/* Private to formats/input: the readers the dispatcher (vt_image_input.c) hands a file to, in the
 * order it asks them. Each reader file defines one; adding a format = one reader file, one extern
 * here and one line in the dispatcher's table. Readers never call the dispatcher. */
#ifndef VT_INPUT_READERS_H
#define VT_INPUT_READERS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "vt_error.h"
#include "vt_source.h"

struct vt_input_reader {
    const char *name; /* "tiff", "png"... */
    /* True when the file's first len (<= 8) bytes are this format's magic. NULL for the fallback,
     * which takes whatever no other reader recognised. */
    bool (*sniff)(const unsigned char *magic, size_t len);
    /* Opens path (already known to be this reader's): fills out->info, out->ops and out->ctx (not
     * out->name) and returns 0, or a negative status with err naming path and leaves *out
     * untouched. max_pixels is the resolved limit (never 0). */
    int (*open)(const char *path, uint64_t max_pixels, struct vt_source *out,
                struct vts_error *err);
};

extern const struct vt_input_reader vt_input_reader_tiff; /* vt_input_tiff.c: libtiff */
/* How a TIFF is read (vt_input_tiff_route()). */
enum vt_tiff_route {
    VT_TIFF_NATIVE,     /* by vt_input_reader_tiff */
    VT_TIFF_GEO_NATIVE, /* a GeoTIFF this reader reads as GDAL would: pixels here, the rest GDAL */
    VT_TIFF_GDAL, /* GDAL: more than 4 samples, signed or 32-bit integer or 64-bit float samples,
                     3+ grey samples (bands of data), or a GeoTIFF of 2 or 4 samples whose last
                     one is not alpha */
};
/* vt_input_tiff.c: sets *route for the TIFF at path. Returns 0, or a negative status with err set
 * as the TIFF reader's open would (the file cannot be opened or read). */
int vt_input_tiff_route(const char *path, enum vt_tiff_route *route, struct vts_error *err);
extern const struct vt_input_reader vt_input_reader_png;  /* vt_input_png.c: libpng */
extern const struct vt_input_reader vt_input_reader_jpeg; /* vt_input_jpeg.c: libjpeg-turbo */
extern const struct vt_input_reader vt_input_reader_exr;  /* vt_input_exr.c: OpenEXRCore */
/* vt_input_oiio.c: the fallback, libvt_oiio.so loaded on first use (see there for where). */
extern const struct vt_input_reader vt_input_reader_oiio;

#endif
