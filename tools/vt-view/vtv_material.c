/* vt-view materials: constants, alpha mode and shader features. */
#include "vtv_material.h"

#include <stdio.h>
#include <string.h>

static const char *const feature_names[VTV_F_COUNT] = {
    "diffuse_map", "alpha_test", "alpha_blend", "alpha_map", "lit",   "normal_map", "specular_map",
    "specular",    "emissive",   "range",       "ramp",      "index", "wang"};
static const char *const feature_defines[VTV_F_COUNT] = {
    "F_DIFFUSE_MAP", "F_ALPHA_TEST",   "F_ALPHA_BLEND", "F_ALPHA_MAP", "F_LIT",
    "F_NORMAL_MAP",  "F_SPECULAR_MAP", "F_SPECULAR",    "F_EMISSIVE",  "F_RANGE",
    "F_RAMP",        "F_INDEX",        "F_WANG"};

static void copy3(float *dst, const double *src)
{
    for (int k = 0; k < 3; k++)
        dst[k] = (float)src[k];
}

static bool black(const float *c)
{
    return c[0] <= 0.0f && c[1] <= 0.0f && c[2] <= 0.0f;
}

void vtv_material_from_mtl(const struct vt_mtl_material *m, unsigned maps, bool diffuse_cutout,
                           struct vtv_material *out)
{
    memset(out, 0, sizeof(*out));
    out->maps = maps;
    float kd = (maps & (1u << VTV_MAP_DIFFUSE)) ? 1.0f : 0.8f;
    out->kd[0] = out->kd[1] = out->kd[2] = kd;
    out->d = 1.0f;
    if (!m) {
        out->illum = 1;
        return;
    }
    if (m->flags & VT_MTL_HAS_KD)
        copy3(out->kd, m->kd);
    if (m->flags & VT_MTL_HAS_KS)
        copy3(out->ks, m->ks);
    if (m->flags & VT_MTL_HAS_KE)
        copy3(out->ke, m->ke);
    out->ns = (m->flags & VT_MTL_HAS_NS) ? (float)m->ns : 0.0f;
    if (m->flags & VT_MTL_HAS_D)
        out->d = (float)m->d;
    else if ((m->flags & VT_MTL_HAS_TR) && m->tr > 0.0 && m->tr < 1.0)
        out->d = (float)(1.0 - m->tr);
    out->d = out->d < 0.0f ? 0.0f : out->d > 1.0f ? 1.0f : out->d;
    out->illum = (m->flags & VT_MTL_HAS_ILLUM) ? m->illum : black(out->ks) ? 1 : 2;
    switch (m->alpha) {
    case VT_MTL_ALPHA_NONE:
        out->alpha = VTV_ALPHA_NONE;
        break;
    case VT_MTL_ALPHA_TEST:
        out->alpha = VTV_ALPHA_TEST;
        break;
    case VT_MTL_ALPHA_BLEND:
        out->alpha = VTV_ALPHA_BLEND;
        break;
    default:
        out->alpha = out->d < 1.0f                    ? VTV_ALPHA_BLEND
                     : (maps & (1u << VTV_MAP_ALPHA)) ? VTV_ALPHA_TEST
                     : diffuse_cutout                 ? VTV_ALPHA_TEST
                                                      : VTV_ALPHA_NONE;
    }
}

void vtv_material_plain(struct vtv_material *out)
{
    memset(out, 0, sizeof(*out));
    out->kd[0] = out->kd[1] = out->kd[2] = 1.0f;
    out->d = 1.0f;
    out->illum = 0;
    out->maps = 1u << VTV_MAP_DIFFUSE;
}

unsigned vtv_material_features(const struct vtv_material *m)
{
    unsigned f = 0;
    bool has_alpha_map = m->maps & (1u << VTV_MAP_ALPHA);
    if (m->wang)
        f |= VTV_F_WANG;
    else if (m->maps & (1u << VTV_MAP_DIFFUSE))
        f |= VTV_F_DIFFUSE_MAP;
    /* a test needs coverage: map_d, else map_Kd's alpha */
    if (m->alpha == VTV_ALPHA_TEST && (has_alpha_map || (f & VTV_F_DIFFUSE_MAP)))
        f |= VTV_F_ALPHA_TEST;
    if (m->alpha == VTV_ALPHA_BLEND)
        f |= VTV_F_ALPHA_BLEND;
    if (has_alpha_map && (f & (VTV_F_ALPHA_TEST | VTV_F_ALPHA_BLEND)))
        f |= VTV_F_ALPHA_MAP;
    if (m->illum >= 1) {
        f |= VTV_F_LIT;
        if (m->maps & (1u << VTV_MAP_NORMAL))
            f |= VTV_F_NORMAL_MAP;
        if (m->illum >= 2 && (m->maps & (1u << VTV_MAP_SPECULAR)))
            f |= VTV_F_SPECULAR_MAP;
        else if (m->illum >= 2 && !black(m->ks))
            f |= VTV_F_SPECULAR;
    }
    if (!black(m->ke))
        f |= VTV_F_EMISSIVE;
    return f;
}

const char *vtv_feature_name(unsigned k)
{
    return k < VTV_F_COUNT ? feature_names[k] : "?";
}

void vtv_feature_defines(unsigned features, char *buf, size_t cap)
{
    size_t n = 0;
    buf[0] = '\0';
    for (unsigned k = 0; k < VTV_F_COUNT && n < cap; k++)
        if (features & (1u << k)) {
            int w = snprintf(buf + n, cap - n, "#define %s 1\n", feature_defines[k]);
            if (w < 0)
                break;
            n += (size_t)w;
        }
}
