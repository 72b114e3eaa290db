/* Checks of vt-view's material rules and tangent frames without GL (tools/vt-view/vtv_material.c,
 * vtv_tangent.c; docs/viewer.md, "Materials and shading"), its colour ramps and the formats of
 * 16-bit and float layers (vtv_ramp.c, vtv_wide.c; "Ranges and ramps"), and the index colours
 * (vtv_select.c; "Categorical and min/max layers"). Prints one line per failed check and exits 1
 * when any failed. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "vtv_material.h"
#include "vtv_ramp.h"
#include "vtv_select.h"
#include "vtv_tangent.h"
#include "vtv_wide.h"

static int failures;

#define CHECK(cond)                                                                                \
    do {                                                                                           \
        if (!(cond)) {                                                                             \
            printf("FAIL %s:%d: %s\n", __FILE__, __LINE__, #cond);                                 \
            failures++;                                                                            \
        }                                                                                          \
    } while (0)

static const unsigned KD = 1u << VTV_MAP_DIFFUSE, NORM = 1u << VTV_MAP_NORMAL,
                      KS = 1u << VTV_MAP_SPECULAR, D = 1u << VTV_MAP_ALPHA;

static unsigned features_of(const struct vt_mtl_material *m, unsigned maps, bool cutout)
{
    struct vtv_material mat;
    vtv_material_from_mtl(m, maps, cutout, &mat);
    return vtv_material_features(&mat);
}

static void material_rules(void)
{
    struct vtv_material mat;
    struct vt_mtl_material m;
    memset(&m, 0, sizeof(m));
    m.d = 1;
    /* defaults as vt-atlas's: Kd 1 with a map, else 0.8; illum 1 without Ks, 2 with one */
    vtv_material_from_mtl(&m, KD, false, &mat);
    CHECK(mat.kd[0] == 1.0f && mat.illum == 1 && mat.d == 1.0f && mat.alpha == VTV_ALPHA_NONE);
    vtv_material_from_mtl(&m, 0, false, &mat);
    CHECK(fabsf(mat.kd[1] - 0.8f) < 1e-6f);
    m.flags = VT_MTL_HAS_KS;
    m.ks[0] = 0.5;
    vtv_material_from_mtl(&m, KD, false, &mat);
    CHECK(mat.illum == 2);
    CHECK(vtv_material_features(&mat) == (VTV_F_DIFFUSE_MAP | VTV_F_LIT | VTV_F_SPECULAR));
    /* d: from Tr strictly between 0 and 1 (a lone Tr 1 is MeshLab's opaque) */
    memset(&m, 0, sizeof(m));
    m.d = 1;
    m.flags = VT_MTL_HAS_TR;
    m.tr = 1.0;
    vtv_material_from_mtl(&m, KD, false, &mat);
    CHECK(mat.d == 1.0f && mat.alpha == VTV_ALPHA_NONE);
    m.tr = 0.25;
    vtv_material_from_mtl(&m, KD, false, &mat);
    CHECK(fabsf(mat.d - 0.75f) < 1e-6f && mat.alpha == VTV_ALPHA_BLEND);
    /* alpha order: vt_alpha, then d < 1, then map_d, then a cut-out in map_Kd */
    memset(&m, 0, sizeof(m));
    m.d = 1;
    CHECK(features_of(&m, KD | D, false) ==
          (VTV_F_DIFFUSE_MAP | VTV_F_ALPHA_TEST | VTV_F_ALPHA_MAP | VTV_F_LIT));
    CHECK(features_of(&m, KD, true) == (VTV_F_DIFFUSE_MAP | VTV_F_ALPHA_TEST | VTV_F_LIT));
    CHECK(features_of(&m, KD, false) == (VTV_F_DIFFUSE_MAP | VTV_F_LIT));
    m.alpha = VT_MTL_ALPHA_NONE; /* a mask: never cut out, map_d or not */
    CHECK(features_of(&m, KD, true) == (VTV_F_DIFFUSE_MAP | VTV_F_LIT));
    CHECK(features_of(&m, KD | D, true) == (VTV_F_DIFFUSE_MAP | VTV_F_LIT));
    m.alpha = VT_MTL_ALPHA_AUTO;
    m.flags = VT_MTL_HAS_D;
    m.d = 0.5;
    CHECK(features_of(&m, KD | D, true) ==
          (VTV_F_DIFFUSE_MAP | VTV_F_ALPHA_BLEND | VTV_F_ALPHA_MAP | VTV_F_LIT));
    /* a test needs coverage: no map_d and no map_Kd, no test */
    memset(&m, 0, sizeof(m));
    m.d = 1;
    m.alpha = VT_MTL_ALPHA_TEST;
    CHECK(features_of(&m, 0, false) == VTV_F_LIT);
    /* illum 0: unlit, so no normal map and no specular; illum 1: no specular */
    m.alpha = VT_MTL_ALPHA_AUTO;
    m.flags = VT_MTL_HAS_ILLUM | VT_MTL_HAS_KS | VT_MTL_HAS_KE;
    m.ks[1] = 1;
    m.ke[2] = 0.5;
    m.illum = 0;
    CHECK(features_of(&m, KD | NORM | KS, false) == (VTV_F_DIFFUSE_MAP | VTV_F_EMISSIVE));
    m.illum = 1;
    CHECK(features_of(&m, KD | NORM | KS, false) ==
          (VTV_F_DIFFUSE_MAP | VTV_F_LIT | VTV_F_NORMAL_MAP | VTV_F_EMISSIVE));
    m.illum = 2;
    CHECK(features_of(&m, KD | NORM | KS, false) ==
          (VTV_F_DIFFUSE_MAP | VTV_F_LIT | VTV_F_NORMAL_MAP | VTV_F_SPECULAR_MAP | VTV_F_EMISSIVE));
    /* the plain material: the layer as it is */
    vtv_material_plain(&mat);
    CHECK(vtv_material_features(&mat) == VTV_F_DIFFUSE_MAP);
    char defines[512];
    vtv_feature_defines(VTV_F_ALPHA_TEST | VTV_F_LIT, defines, sizeof(defines));
    CHECK(strcmp(defines, "#define F_ALPHA_TEST 1\n#define F_LIT 1\n") == 0);
    CHECK(strcmp(vtv_feature_name(5), "normal_map") == 0);
}

/* A unit quad in the z = 0 plane as two triangles, drawn UVs (v flipped) from OBJ corner UVs. */
static void quad(float *v, uint32_t *keys, const double uv[4][2], bool with_normal)
{
    static const double p[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    static const int tri[6] = {0, 1, 2, 0, 2, 3};
    memset(v, 0, 6 * VTV_VERTEX_FLOATS * sizeof(float));
    for (int i = 0; i < 6; i++) {
        float *o = v + i * VTV_VERTEX_FLOATS;
        int c = tri[i];
        o[0] = (float)p[c][0];
        o[1] = (float)p[c][1];
        o[3] = (float)uv[c][0];
        o[4] = (float)(1.0 - uv[c][1]);
        o[7] = with_normal ? 1.0f : 0.0f;
        keys[i * 3] = keys[i * 3 + 1] = (uint32_t)c;
        keys[i * 3 + 2] = with_normal ? 0 : UINT32_MAX;
    }
}

static bool near3(const float *a, double x, double y, double z)
{
    return fabs(a[0] - x) < 1e-5 && fabs(a[1] - y) < 1e-5 && fabs(a[2] - z) < 1e-5;
}

static void tangents(void)
{
    static const double laid[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    static const double umirror[4][2] = {{1, 0}, {0, 0}, {0, 1}, {1, 1}};
    static const double vmirror[4][2] = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
    static const double turned[4][2] = {{0, 1}, {0, 0}, {1, 0}, {1, 1}}; /* u along +y */
    float v[6 * VTV_VERTEX_FLOATS];
    uint32_t keys[18];
    quad(v, keys, laid, false);
    CHECK(vtv_tangents(v, keys, 6) == 0);
    for (int i = 0; i < 6; i++) {
        const float *o = v + i * VTV_VERTEX_FLOATS;
        CHECK(near3(o + 5, 0, 0, 1)); /* the face normal filled in */
        CHECK(near3(o + 8, 1, 0, 0) && o[11] == 1.0f);
    }
    quad(v, keys, umirror, true);
    CHECK(vtv_tangents(v, keys, 6) == 0);
    for (int i = 0; i < 6; i++) /* T along -x; N x T = -y, B = +y: w = -1 */
        CHECK(near3(v + i * VTV_VERTEX_FLOATS + 8, -1, 0, 0) &&
              v[i * VTV_VERTEX_FLOATS + 11] == -1.0f);
    quad(v, keys, vmirror, true);
    CHECK(vtv_tangents(v, keys, 6) == 0);
    for (int i = 0; i < 6; i++) /* T along +x, B along -y: w = -1 */
        CHECK(near3(v + i * VTV_VERTEX_FLOATS + 8, 1, 0, 0) &&
              v[i * VTV_VERTEX_FLOATS + 11] == -1.0f);
    quad(v, keys, turned, true);
    CHECK(vtv_tangents(v, keys, 6) == 0);
    for (int i = 0; i < 6; i++) /* T along +y, B along -x = N x T: w = +1 */
        CHECK(near3(v + i * VTV_VERTEX_FLOATS + 8, 0, 1, 0) &&
              v[i * VTV_VERTEX_FLOATS + 11] == 1.0f);
    /* UVs without area: some tangent perpendicular to the normal, of unit length */
    static const double flat[4][2] = {{0.5, 0.5}, {0.5, 0.5}, {0.5, 0.5}, {0.5, 0.5}};
    quad(v, keys, flat, true);
    CHECK(vtv_tangents(v, keys, 6) == 0);
    for (int i = 0; i < 6; i++) {
        const float *t = v + i * VTV_VERTEX_FLOATS + 8;
        CHECK(fabs(t[0] * t[0] + t[1] * t[1] + t[2] * t[2] - 1) < 1e-5 && fabs(t[2]) < 1e-5);
    }
    /* a tilted vertex normal: T made orthogonal to it (Gram-Schmidt) */
    quad(v, keys, laid, true);
    for (int i = 0; i < 6; i++) {
        float *n = v + i * VTV_VERTEX_FLOATS + 5;
        n[0] = 0.6f;
        n[2] = 0.8f;
    }
    CHECK(vtv_tangents(v, keys, 6) == 0);
    const float *t = v + 8;
    CHECK(fabs(t[0] * 0.6 + t[2] * 0.8) < 1e-5 && near3(t, 0.8, 0, -0.6));
}

static bool close3(const float a[3], const float b[3], float tol)
{
    return fabsf(a[0] - b[0]) <= tol && fabsf(a[1] - b[1]) <= tol && fabsf(a[2] - b[2]) <= tol;
}

static void ramps(void)
{
    enum vtv_ramp_kind k;
    CHECK(vtv_ramp_parse("dusk", &k) && k == VTV_RAMP_DUSK);
    CHECK(vtv_ramp_parse("none", &k) && k == VTV_RAMP_NONE && !vtv_ramp_table(k));
    CHECK(!vtv_ramp_parse("rainbow", &k));
    for (int r = VTV_RAMP_DUSK; r < VTV_RAMP_COUNT; r++) {
        const float(*t)[3] = vtv_ramp_table((enum vtv_ramp_kind)r);
        float c[3], mid[3];
        /* the control colours at i/8, linear in between, the ends beyond [0,1] and for NaN */
        for (int i = 0; i < VTV_RAMP_POINTS; i++) {
            vtv_ramp_at((enum vtv_ramp_kind)r, (float)i / 8, c);
            CHECK(close3(c, t[i], 1e-6f));
        }
        vtv_ramp_at((enum vtv_ramp_kind)r, 3.0f / 16, c);
        for (int j = 0; j < 3; j++)
            mid[j] = (t[1][j] + t[2][j]) / 2;
        CHECK(close3(c, mid, 1e-6f));
        CHECK(!close3(c, t[1], 1e-3f) || !close3(c, t[2], 1e-3f)); /* a wrong index fails */
        vtv_ramp_at((enum vtv_ramp_kind)r, -5.0f, c);
        CHECK(close3(c, t[0], 0));
        vtv_ramp_at((enum vtv_ramp_kind)r, 7.0f, c);
        CHECK(close3(c, t[8], 0));
        vtv_ramp_at((enum vtv_ramp_kind)r, NAN, c);
        CHECK(close3(c, t[0], 0));
        /* every ramp runs dark to light: its lightness (Rec. 709 luma) rises */
        for (int i = 1; i < VTV_RAMP_POINTS; i++)
            CHECK(0.2126f * t[i][0] + 0.7152f * t[i][1] + 0.0722f * t[i][2] >
                  0.2126f * t[i - 1][0] + 0.7152f * t[i - 1][1] + 0.0722f * t[i - 1][2]);
    }
}

static void wide_formats(void)
{
    struct vtv_texel_format f;
    struct vts_layer l = {VTS_CODEC_PNG, 1, VTS_SAMPLE_U8, VTS_COLOUR_DATA, 0, 0, {0}};
    vtv_wide_format(&l, &f);
    CHECK(f.sample == VTS_SAMPLE_U8 && f.channels == 4 && vtv_wide_texel_bytes(&f) == 4);
    l.sample = VTS_SAMPLE_U16;
    vtv_wide_format(&l, &f);
    CHECK(f.sample == VTS_SAMPLE_U16 && f.channels == 1 && vtv_wide_texel_bytes(&f) == 2);
    l.channels = 3, l.colour = VTS_COLOUR_SRGB; /* no 16-bit sRGB in GL: linear floats */
    vtv_wide_format(&l, &f);
    CHECK(f.sample == VTS_SAMPLE_F32 && f.channels == 3 && vtv_wide_texel_bytes(&f) == 12);
    l.sample = VTS_SAMPLE_F16, l.channels = 4, l.colour = VTS_COLOUR_LINEAR;
    vtv_wide_format(&l, &f);
    CHECK(f.sample == VTS_SAMPLE_F16 && f.channels == 4 && vtv_wide_texel_bytes(&f) == 8);
}

/* The index colours (vtv_select.h): pinned values, as documented; all 256 u8 values distinct. */
static void index_colours(void)
{
    uint8_t c[256][3];
    for (uint32_t v = 0; v < 256; v++) {
        vtv_index_colour(v, c[v]);
        for (int k = 0; k < 3; k++)
            CHECK(c[v][k] >= 48);
        for (uint32_t u = 0; u < v; u++)
            CHECK(memcmp(c[u], c[v], 3) != 0);
    }
    CHECK(c[0][0] == 150 && c[0][1] == 178 && c[0][2] == 57);
    CHECK(c[3][0] == 240 && c[3][1] == 207 && c[3][2] == 118);
    CHECK(c[200][0] == 78 && c[200][1] == 61 && c[200][2] == 191);
    uint8_t top[3];
    vtv_index_colour(65535, top);
    CHECK(top[0] == 164 && top[1] == 56 && top[2] == 186);
}

int main(void)
{
    material_rules();
    tangents();
    ramps();
    wide_formats();
    index_colours();
    printf("%s\n", failures ? "vtv_unit: failures" : "vtv_unit: all checks passed");
    return failures ? 1 : 0;
}
