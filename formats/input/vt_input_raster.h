/* What a raster file holds beyond the pixels of one source: its bands, their descriptions and its
 * georeferencing (filled by vt_image_input_describe(), vt_image_input.h; docs/geospatial.md). */
#ifndef VT_INPUT_RASTER_H
#define VT_INPUT_RASTER_H

#include <stdbool.h>
#include <stdint.h>

#include "vts.h"

#define VT_INPUT_MAX_BANDS VTS_MAX_LAYERS

/* What vt_image_input_describe() tells about a file beyond its first source's info. */
struct vt_input_raster {
    uint32_t band_count; /* bands (channels) of the file, 1..VT_INPUT_MAX_BANDS */
    char band_names[VT_INPUT_MAX_BANDS][VTS_LAYER_NAME_BYTES]; /* descriptions; "" for none */
    bool has_geotransform;
    double geotransform[6]; /* GDAL's: x0, dx/dcol, dx/drow, y0, dy/dcol, dy/drow */
    char *crs_wkt;          /* the CRS as WKT (malloc'ed), or NULL */
    bool has_nodata;
    double nodata;        /* of the first band, in the file's units */
    bool has_scale;       /* the first band has a scale or offset (GDAL's band scale/offset) */
    double scale, offset; /* its value = stored * scale + offset */
    bool geo_unread;      /* a GeoTIFF read natively: the GDAL module could not be loaded */
    char why[160];        /* with geo_unread: why the module could not be loaded */
};

/* Frees what r holds (and leaves it without); accepts NULL. */
void vt_input_raster_release(struct vt_input_raster *r);

#endif
