/* The georeferencing of an extracted image, written next to it as the sidecar files GDAL and GIS
 * tools read (docs/geospatial.md): IMAGE.aux.xml (GDAL's PAM: SRS as WKT, GeoTransform and every
 * band's NoDataValue) and a world file (x.png -> x.pgw, x.tif / x.tiff -> x.tfw, else
 * IMAGE.wld: the six numbers of the texel centres). Each file is written through a temporary file
 * and renamed when complete. */
#ifndef VT_GEOREF_FILE_H
#define VT_GEOREF_FILE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "vt_error.h"

struct vt_georef {
    bool has_transform;
    double transform[6]; /* GDAL's: x0, dx/dcol, dx/drow, y0, dy/dcol, dy/drow (texel corners) */
    const char *crs_wkt; /* NULL: none */
    const char *nodata;  /* the value as text, NULL: none */
    uint32_t bands;      /* of the image (PAM's per-band nodata) */
};

/* The transform of a region of level `level` starting at level texel (x, y) (which may be
 * negative: a tile's border), from level 0's. */
void vt_georef_region(const double level0[6], uint32_t level, int64_t x, int64_t y, double out[6]);

/* Writes IMAGE.aux.xml and, with a transform, the world file, for the image at image_path.
 * world_path (world_size bytes) gets the world file's name ("" without a transform). Returns 0 or
 * VTS_ERR_IO / VTS_ERR_ARG naming the file. Nothing is written when g has neither a transform nor
 * a CRS. */
int vt_georef_file_write(const char *image_path, const struct vt_georef *g, char *world_path,
                         size_t world_size, struct vts_error *err);

#endif
