/* vt-view materials: what one material of a scene needs to be drawn (its constants, which maps it
 * has, its alpha mode), the feature set derived from it (one shader variant per distinct set) and
 * the GLSL #defines and names of a feature set. The same rules serve the virtual texture (the
 * .vt.mtl vt-offset writes) and the reference (the original MTL), so that both draw every
 * material with the same variant (docs/viewer.md, "Materials and shading"). */
#ifndef VTV_MATERIAL_H
#define VTV_MATERIAL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "vt_obj.h"

/* The maps a material can have, one physical texture (or reference texture) each. */
enum vtv_map {
    VTV_MAP_DIFFUSE,  /* map_Kd */
    VTV_MAP_NORMAL,   /* norm, bump (a tangent-space normal map, as vt-atlas reads both) */
    VTV_MAP_SPECULAR, /* map_Ks */
    VTV_MAP_ALPHA,    /* map_d (its first channel) */
    VTV_MAP_COUNT
};

/* A material's alpha mode (atlas.json "alpha"; docs/atlas-format.md, "Alpha modes"). */
enum vtv_alpha { VTV_ALPHA_NONE, VTV_ALPHA_TEST, VTV_ALPHA_BLEND };

/* Shader features: one program per distinct set present in the scene. */
enum vtv_feature {
    VTV_F_DIFFUSE_MAP = 1u << 0,  /* map_Kd sampled (else the constant Kd) */
    VTV_F_ALPHA_TEST = 1u << 1,   /* cut-out: discard where alpha < VTV_ALPHA_THRESHOLD */
    VTV_F_ALPHA_BLEND = 1u << 2,  /* d < 1: blended over what is behind */
    VTV_F_ALPHA_MAP = 1u << 3,    /* alpha from map_d (else, for a test, map_Kd's alpha) */
    VTV_F_LIT = 1u << 4,          /* illum >= 1: directional light plus ambient */
    VTV_F_NORMAL_MAP = 1u << 5,   /* tangent-space normal map (lit materials only) */
    VTV_F_SPECULAR_MAP = 1u << 6, /* Blinn-Phong from map_Ks (illum >= 2) */
    VTV_F_SPECULAR = 1u << 7,     /* Blinn-Phong from the constant Ks (illum >= 2, Ks not 0) */
    VTV_F_EMISSIVE = 1u << 8,     /* Ke added */
    VTV_F_RANGE = 1u << 9,        /* map_Kd's values mapped from --range to [0,1] (the view's) */
    VTV_F_RAMP = 1u << 10,        /* map_Kd's first channel through a colour ramp (the view's) */
    VTV_F_INDEX = 1u << 11,       /* map_Kd's first channel as a class: its colour (vtv_select.h) */
    VTV_F_WANG = 1u << 12, /* diffuse from a Wang pack through TileTex (vt_wang), not map_Kd */
    VTV_F_COUNT = 13
};

/* Alpha below this is cut out (a renderer's usual alpha test; vt-atlas's cut-out rule counts
 * texels at most 1/8 as clear and at least 7/8 as solid, so a cut-out texture has few texels near
 * it). */
#define VTV_ALPHA_THRESHOLD 0.5f

struct vtv_material {
    float kd[3], ks[3], ke[3]; /* as in the MTL (sRGB-encoded values) */
    float ns, d;
    int illum;
    unsigned alpha;   /* enum vtv_alpha */
    unsigned maps;    /* bit (1 << enum vtv_map): the material has that map */
    uint32_t wang;    /* 1 + the scene's pack (struct vtv_mesh wang_paths) of vt_wang, 0: none */
    float wang_scale; /* vt_wang's scale: output tiles per unit of texture coordinate */
};

/* The material's constants and alpha mode from an MTL block, with vt-atlas's defaults (Kd 1 with
 * a map_Kd else 0.8; Ks Ke 0; Ns 0; d from d, else 1 - Tr for 0 < Tr < 1, else 1; illum 2 when Ks
 * is not black, else 1; alpha: vt_alpha, else blend when d < 1, test with a map_d, test when
 * diffuse_cutout (map_Kd's alpha is a cut-out), else none). maps: the maps it has (bits). m may be
 * NULL (a material the MTL lacks: Kd 0.8, opaque, illum 1). */
void vtv_material_from_mtl(const struct vt_mtl_material *m, unsigned maps, bool diffuse_cutout,
                           struct vtv_material *out);

/* The plain material: the shown layer as it is (no lighting, no alpha). */
void vtv_material_plain(struct vtv_material *out);

/* The features of a material (enum vtv_feature bits). A material with a pack (wang != 0) draws its
 * diffuse through TileTex (VTV_F_WANG) instead of map_Kd. */
unsigned vtv_material_features(const struct vtv_material *m);

/* The name of feature bit k ("diffuse_map", "alpha_test", ...). */
const char *vtv_feature_name(unsigned k);

/* "#define F_DIFFUSE_MAP 1\n..." for features into buf (at most cap bytes, NUL-terminated). */
void vtv_feature_defines(unsigned features, char *buf, size_t cap);

#endif
