/* vt-view terrain (--terrain, docs/viewer.md "Terrain"): a regular grid of G x G vertices over the
 * whole extent of the colour store, each displaced by an elevation layer (bilinear from one level
 * of it, read and decoded once here), draped with the colour store (texcoords in [0,1]^2 over the
 * virtual texture, v = 0 its first row: the convention of the .vt.obj scenes, so the virtual
 * texture's programs draw it unchanged) and lit with the normals of the displaced grid (central
 * differences). The result is an indexed struct vtv_mesh (G^2 vertices, three indices a triangle)
 * of one lit material that any renderer can draw.
 *
 * World space: y up; x along the texture's rows (u), z down its columns (v); x and z relative to
 * the extent's centre, y = exaggeration * elevation. Horizontal unit: one level-0 texel of the
 * colour store, or, when the elevation store has a geo.transform, the CRS's unit (the extent is
 * then elevation width * |dx| by elevation height * |dy|). When both stores have a north-up
 * geo.transform, the grid covers the colour store's extent (colour width * |dx| by height * |dy|)
 * and each vertex samples the elevation where the transforms place it (clamped past its edges);
 * else both are taken to cover the same extent. Elevations: float layers as stored, times
 * layer.N.scale plus layer.N.offset when the store has them; u8/u16 layers need them (stored *
 * scale + offset). Texels equal to the store's nodata (or not finite) take the lowest valid
 * elevation. */
#ifndef VTV_TERRAIN_H
#define VTV_TERRAIN_H

#include <stdbool.h>
#include <stdint.h>

#include "vt_error.h"
#include "vts.h"
#include "vtv_mesh.h"

#define VTV_TERRAIN_GRID_DEFAULT 512u
#define VTV_TERRAIN_GRID_MAX     4096u

struct vtv_terrain_options {
    const char *spec; /* --terrain: "ELEVATION.vts", "ELEVATION.vts:LAYER" or ":LAYER" */
    uint32_t grid;    /* G, 2..VTV_TERRAIN_GRID_MAX */
    double exaggeration;
};

/* What vt-view reports of the terrain it drew (the stats' "terrain" object). */
struct vtv_terrain_info {
    char store[1024]; /* the elevation store's path (the colour store's for ":LAYER") */
    char layer[64];   /* its layer's name */
    uint32_t grid;    /* G */
    uint32_t level;   /* the elevation level read */
    uint32_t level_width, level_height;
    double scale, offset;          /* applied to the stored values */
    double min_height, max_height; /* elevations over the level's valid texels (before
                                      exaggeration) */
    uint64_t nodata_texels;        /* texels given the lowest valid elevation */
    double exaggeration;
    double unit_per_texel; /* world units per level-0 texel of the colour store */
    bool geo;              /* units from the elevation store's geo.transform */
    bool mapped;           /* both stores georeferenced: the grid covers the colour store's extent,
                              placed on the elevation by the two transforms */
    double window[4]; /* the grid's corners in level-0 texels of the elevation store: x0, y0, x1,
                         y1 */
    double extent[2]; /* the grid's world size along x and z (centred on 0) */
    uint32_t colour_width, colour_height; /* the colour store's level 0, texels */
};

/* The colour store's level-0 texel position (tx, ty) under world point (x, z) (any y): the
 * inverse of the grid's placement, not clamped. */
void vtv_terrain_texel(const struct vtv_terrain_info *info, double x, double z, double *tx,
                       double *ty);

/* Splits spec into the elevation store's path (NULL: the colour store) and layer (NULL: the
 * default) in place; a spec naming an existing file is a path whole. */
void vtv_terrain_parse(char *spec, const char **path, const char **layer);

/* Builds the terrain mesh over the colour store (open, at colour_path) from the elevation layer o
 * names. Returns 0, or VTS_ERR_BAD_INPUT / VTS_ERR_IO / ... with a one-line message (a missing
 * store or layer, a layer of more than one channel, a u8/u16 layer without layer.N.scale, an
 * unreadable tile, no valid elevation). m is released on failure. */
int vtv_terrain_build(const struct vts_store *colour, const char *colour_path,
                      const struct vtv_terrain_options *o, struct vtv_mesh *m,
                      struct vtv_terrain_info *info, struct vts_error *err);

#endif
