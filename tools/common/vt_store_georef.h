/* A store's georeferencing (docs/geospatial.md): what its metadata geo.transform, geo.crs_wkt and
 * nodata say, for the tools that show it or write it next to an image (vt-info). */
#ifndef VT_STORE_GEOREF_H
#define VT_STORE_GEOREF_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "vt_georef_file.h"
#include "vts.h"

/* Fills g from the store's metadata, with layer's channel count as its bands; the transform
 * (has_transform false when absent or malformed) is level 0's; crs_wkt and nodata point into the
 * store's metadata. Returns true when the store has a transform, a CRS or a nodata value. */
bool vt_store_georef(const struct vts_store *s, uint32_t layer, struct vt_georef *g);

/* The CRS's name: the first quoted string of its WKT ("(unnamed)" without one), into buf. */
void vt_store_crs_name(const char *wkt, char *buf, size_t size);

#endif
