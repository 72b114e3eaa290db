/* Atlas layer kinds: names, MTL statements and colour spaces (vt_atlas_kind.h). */
#include "vt_atlas_kind.h"

#include "vts.h"

static const char *const kind_names[VT_ATLAS_KIND_COUNT] = {"diffuse", "normal",  "specular",
                                                            "alpha",   "ambient", "displacement"};
static const char *const kind_maps[VT_ATLAS_KIND_COUNT] = {"map_Kd", "norm",   "map_Ks",
                                                           "map_d",  "map_Ka", "disp"};

const char *vt_atlas_kind_name(unsigned kind)
{
    return kind < VT_ATLAS_KIND_COUNT ? kind_names[kind] : "?";
}

const char *vt_atlas_kind_map(unsigned kind)
{
    return kind < VT_ATLAS_KIND_COUNT ? kind_maps[kind] : "?";
}

uint32_t vt_atlas_kind_colour(unsigned kind)
{
    switch (kind) {
    case VT_ATLAS_NORMAL:
        return VTS_COLOUR_NORMAL;
    case VT_ATLAS_ALPHA:
    case VT_ATLAS_DISP:
        return VTS_COLOUR_DATA;
    default:
        return VTS_COLOUR_SRGB;
    }
}
