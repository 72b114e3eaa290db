/* The layers an atlas can have, in layout order, with the MTL statement each comes from. A scene
 * gets only the layers its used materials have textures for (vt_atlas_place.h). */
#ifndef VT_ATLAS_KIND_H
#define VT_ATLAS_KIND_H

#include <stdint.h>

enum vt_atlas_kind {
    VT_ATLAS_DIFFUSE,  /* map_Kd */
    VT_ATLAS_NORMAL,   /* norm, map_Bump, bump */
    VT_ATLAS_SPECULAR, /* map_Ks */
    VT_ATLAS_ALPHA,    /* map_d */
    VT_ATLAS_AMBIENT,  /* map_Ka */
    VT_ATLAS_DISP,     /* disp */
    VT_ATLAS_KIND_COUNT
};

/* The layer name of kind ("diffuse"), as atlas.json and the stores call it; "?" out of range. */
const char *vt_atlas_kind_name(unsigned kind);

/* The MTL statement of kind ("map_Kd"; "norm" for normals), as atlas.json records it; "?" out of
 * range. */
const char *vt_atlas_kind_map(unsigned kind);

/* The enum vts_colour of kind's layer: normal for normals, data for alpha and displacement, sRGB
 * for the colours. */
uint32_t vt_atlas_kind_colour(unsigned kind);

#endif
