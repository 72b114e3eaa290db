/* GLSL 330 core sources of vt-view. Coordinates: v_uv in [0,1]^2 over the virtual texture (v = 0 is
 * the first row of the store); t0 = v_uv * u_virt is in level-0 texels (in the 2D view, t0 = v_uv
 * relative to a level-0 tile u_origin: split coordinates, see vt_texel). The level-of-detail comes
 * from the gradients of t0 (the virtual texture), not from the physical texture, and the physical
 * lookups get those gradients scaled to the level used (corrected gradients). Every layer of a
 * tile sits in the same slot of its own physical texture, so one page-table lookup addresses all
 * of them. Shading (docs/viewer.md, "Materials and shading"): one directional light plus ambient,
 * tangent-space normal maps, Blinn-Phong specular, in linear light when the frame is sRGB. */
#include "vtv_shaders.h"

#include "vtv_material.h"
#include "vtv_wang_glsl.h"

const char vtv_vs_source[] = "#version 330 core\n"
                             "layout(location = 0) in vec3 a_pos;\n"
                             "layout(location = 1) in vec2 a_uv;\n"
                             "layout(location = 2) in vec3 a_normal;\n"
                             "layout(location = 3) in vec4 a_tangent;\n"
                             "uniform mat4 u_mvp;\n"
                             "uniform vec2 u_jitter;\n"
                             "out vec2 v_uv;\n"
                             "out vec3 v_pos;\n"
                             "out vec3 v_normal;\n"
                             "out vec4 v_tangent;\n"
                             "void main() {\n"
                             "    gl_Position = u_mvp * vec4(a_pos, 1.0);\n"
                             "    gl_Position.xy += u_jitter * gl_Position.w;\n"
                             "    v_uv = a_uv;\n"
                             "    v_pos = a_pos;\n"
                             "    v_normal = a_normal;\n"
                             "    v_tangent = a_tangent;\n"
                             "}\n";

static const char version[] = "#version 330 core\n#define ALPHA_THRESHOLD 0.5\n";

/* Page-table addressing, shared by the main and the tile-determination passes. */
static const char vt_common[] =
    "in vec2 v_uv;\n"
    "uniform usampler2D u_pt;\n"
    "uniform vec2 u_virt;\n"
    "uniform float u_content;\n"
    "uniform int u_max_level;\n"
    "uniform ivec2 u_pt_tiles[32];\n"
    "uniform int u_pt_row[32];\n"
    "uniform int u_trilinear;\n"
    "uniform float u_lod_bias;\n"
    "uniform sampler2D u_phys_kd, u_phys_norm, u_phys_ks, u_phys_d;\n"
    "uniform vec2 u_phys_size;\n"
    "uniform float u_border;\n"
    "uniform float u_payload;\n"
    "uniform int u_aniso;\n"
    /* Split coordinates (u_rel != 0, the 2D view): v_uv is in level-0 texels relative to the
       corner of level-0 tile u_origin, so that the float coordinates stay small however large
       the virtual texture; otherwise v_uv is in [0,1] over it and u_origin is 0. */
    "uniform int u_rel;\n"
    "uniform ivec2 u_origin;\n"
    "vec2 vt_texel() { return u_rel != 0 ? v_uv : v_uv * u_virt; }\n"
    /* Anisotropic filtering (u_aniso > 1): the footprint's major axis over its minor one, at most
       u_aniso, is the number of taps along the major axis; the level is chosen for the major
       axis divided by it (docs/viewer.md, "Anisotropic filtering"). */
    "int vt_taps(vec2 gx, vec2 gy) {\n"
    "    if (u_aniso <= 1) return 1;\n"
    "    float a = dot(gx, gx), b = dot(gy, gy);\n"
    "    float r = sqrt(max(a, b) / max(min(a, b), 1e-20));\n"
    "    return int(clamp(ceil(r - 1e-3), 1.0, float(u_aniso)));\n"
    "}\n"
    "float vt_lambda(vec2 gx, vec2 gy) {\n"
    "    return 0.5 * log2(max(max(dot(gx, gx), dot(gy, gy)), 1e-20))\n"
    "           - log2(float(vt_taps(gx, gy))) + u_lod_bias;\n"
    "}\n"
    "int vt_nearest_level(float lam) {\n"
    "    if (lam <= 0.5) return 0;\n"
    "    return min(int(ceil(lam + 0.5)) - 1, u_max_level);\n"
    "}\n"
    "ivec2 vt_tile(int level, vec2 t0) {\n"
    "    ivec2 tc;\n"
    "    if (u_rel != 0) {\n"
    "        ivec2 m = ivec2((1 << level) - 1);\n"
    "        vec2 f = (vec2(u_origin & m) + t0 / u_content) / exp2(float(level));\n"
    "        tc = (u_origin >> level) + ivec2(floor(f));\n"
    "    } else {\n"
    "        tc = ivec2(floor(t0 / (u_content * exp2(float(level)))));\n"
    "    }\n"
    "    return clamp(tc, ivec2(0), u_pt_tiles[level] - 1);\n"
    "}\n"
    "struct vt_addr { vec2 p; vec2 gx; vec2 gy; vec2 ax; vec2 lo; vec2 hi; int n; };\n"
    /* The physical position of t0 at level want (or its resident ancestor): false when the
       page table has no entry. */
    "bool vt_address(int want, vec2 t0, vec2 gx, vec2 gy, out vt_addr a, out int used,\n"
    "                out vec2 in_tile) {\n"
    "    ivec2 tc = vt_tile(want, t0);\n"
    "    uvec4 e = texelFetch(u_pt, ivec2(tc.x, tc.y + u_pt_row[want]), 0);\n"
    "    a.p = vec2(0.0); a.gx = vec2(0.0); a.gy = vec2(0.0); a.ax = vec2(0.0);\n"
    "    a.lo = vec2(0.0); a.hi = vec2(0.0); a.n = 1;\n"
    "    if (e.a == 0u) { used = 99; in_tile = vec2(0.0); return false; }\n"
    "    used = int(e.b);\n"
    "    ivec2 tl = tc >> (used - want);\n"
    "    float s = exp2(float(used));\n"
    "    vec2 t = u_rel != 0 ? (vec2(u_origin - (tl << used)) * u_content + t0) / s\n"
    "                        : t0 / s - vec2(tl) * u_content;\n"
    "    in_tile = clamp(t, vec2(0.5 - u_border), vec2(u_content + u_border - 0.5));\n"
    "    vec2 org = vec2(e.rg) * u_payload;\n"
    "    a.p = (org + u_border + in_tile) / u_phys_size;\n"
    "    vec2 k = 1.0 / (s * u_phys_size);\n"
    "    a.gx = gx * k; a.gy = gy * k;\n"
    "    a.n = vt_taps(gx, gy);\n"
    "    a.ax = (dot(gx, gx) >= dot(gy, gy) ? gx : gy) * k;\n"
    "    a.lo = (org + 0.5) / u_phys_size;\n"
    "    a.hi = (org + u_payload - 0.5) / u_phys_size;\n"
    "    return true;\n"
    "}\n"
    /* n bilinear taps spread evenly over the major axis, each kept inside the slot's payload
       (content and borders): a border of n/2 texels holds them (the option is clamped to it). */
    "vec4 vt_at(sampler2D s, vt_addr a) {\n"
    "    if (a.n <= 1) return textureGrad(s, a.p, a.gx, a.gy);\n"
    "    vec4 c = vec4(0.0);\n"
    "    float n = float(a.n);\n"
    "    for (int i = 0; i < a.n; i++) {\n"
    "        vec2 q = clamp(a.p + a.ax * ((float(i) + 0.5) / n - 0.5), a.lo, a.hi);\n"
    "        c += textureGrad(s, q, a.gx / n, a.gy / n);\n"
    "    }\n"
    "    return c / n;\n"
    "}\n";

/* The material and the light, shared by the main pass and the reference. map_sample(k) is the
 * kind's: k is enum vtv_map (0 map_Kd, 1 normal, 2 map_Ks, 3 map_d). */
static const char shading[] =
    "in vec3 v_pos;\n"
    "in vec3 v_normal;\n"
    "in vec4 v_tangent;\n"
    "uniform vec3 u_kd, u_ks, u_ke;\n"
    "uniform float u_ns, u_d;\n"
    "uniform vec3 u_light_dir, u_light_colour, u_ambient, u_eye;\n"
    "vec4 map_sample(int k);\n"
    "#ifdef F_WANG\n"
    "vec4 wang_sample();\n"
    "#endif\n"
    "vec3 vt_shade(vec3 diffuse, vec3 ntex, vec3 spec) {\n"
    "    vec3 c = diffuse;\n"
    "#ifdef F_LIT\n"
    "    vec3 n0 = normalize(v_normal);\n"
    "    vec3 n = n0;\n"
    "#ifdef F_NORMAL_MAP\n"
    "    vec3 t = v_tangent.xyz - n0 * dot(n0, v_tangent.xyz);\n"
    "    t = dot(t, t) > 1e-12 ? normalize(t) : vec3(1.0, 0.0, 0.0);\n"
    "    vec3 b = cross(n0, t) * v_tangent.w;\n"
    "    n = normalize(t * ntex.x + b * ntex.y + n0 * ntex.z);\n"
    "#endif\n"
    "    if (!gl_FrontFacing) n = -n;\n"
    "    float ndl = max(dot(n, u_light_dir), 0.0);\n"
    "    c = diffuse * (u_ambient + u_light_colour * ndl);\n"
    "#if defined(F_SPECULAR) || defined(F_SPECULAR_MAP)\n"
    "    vec3 h = normalize(u_light_dir + normalize(u_eye - v_pos));\n"
    "    float s = ndl > 0.0 ? pow(max(dot(n, h), 0.0), max(u_ns, 1.0)) : 0.0;\n"
    "    c += spec * u_light_colour * s;\n"
    "#endif\n"
    "#endif\n"
    "#ifdef F_EMISSIVE\n"
    "    c += u_ke;\n"
    "#endif\n"
    "    return c;\n"
    "}\n"
    "vec4 vt_material() {\n"
    "    vec4 base = vec4(u_kd, 1.0);\n"
    "#if defined(F_WANG)\n"
    "    vec4 dt = wang_sample();\n"
    "    base = vec4(u_kd * dt.rgb, dt.a);\n"
    "#elif defined(F_DIFFUSE_MAP)\n"
    "    vec4 dt = map_sample(0);\n"
    "    base = vec4(u_kd * dt.rgb, dt.a);\n"
    "#endif\n"
    "    float a = 1.0;\n"
    "#if defined(F_ALPHA_MAP)\n"
    "    a = map_sample(3).r;\n"
    "#elif defined(F_ALPHA_TEST)\n"
    "    a = base.a;\n"
    "#endif\n"
    "#ifdef F_ALPHA_TEST\n"
    "    if (a < ALPHA_THRESHOLD) discard;\n"
    "#endif\n"
    "    vec3 nt = vec3(0.0, 0.0, 1.0);\n"
    "#ifdef F_NORMAL_MAP\n"
    "    nt = map_sample(1).rgb * 2.0 - 1.0;\n"
    "#endif\n"
    "    vec3 sp = u_ks;\n"
    "#ifdef F_SPECULAR_MAP\n"
    "    sp = u_ks * map_sample(2).rgb;\n"
    "#endif\n"
    "    vec3 c = vt_shade(base.rgb, nt, sp);\n"
    "#ifdef F_ALPHA_BLEND\n"
    "    return vec4(c, u_d * a);\n"
    "#else\n"
    "    return vec4(c, 1.0);\n"
    "#endif\n"
    "}\n";

/* The shown colour's display (docs/viewer.md, "Ranges and ramps"): map_Kd's values mapped from
 * [min, max] to [0,1] (u_range: min, 1 / (max - min)), then its first channel through the ramp
 * (u_ramp: VTV_RAMP_POINTS colours at 0, 1/8, ..., 1, linear in between; as vtv_ramp_at()).
 * Without F_RANGE and F_RAMP it is the identity. */
const char vtv_display_glsl[] =
    "uniform vec2 u_range;\n"
    "uniform float u_index_scale;\n"
    "uniform vec3 u_ramp[9];\n"
    "vec4 vt_display(vec4 c) {\n"
    "#ifdef F_RANGE\n"
    "    c.rgb = (c.rgb - u_range.x) * u_range.y;\n"
    "#endif\n"
    "#ifdef F_RAMP\n"
    "    float s = clamp(c.r, 0.0, 1.0) * 8.0;\n"
    "    int i = min(int(s), 7);\n"
    "    c.rgb = mix(u_ramp[i], u_ramp[i + 1], s - float(i));\n"
    "#endif\n"
    "#ifdef F_INDEX\n" /* as vtv_index_colour() */
    "    uint h = (uint(c.r * u_index_scale + 0.5) + 1u) * 0x9E3779B1u;\n"
    "    h ^= h >> 16u;\n"
    "    h *= 0x85EBCA6Bu;\n"
    "    h ^= h >> 13u;\n"
    "    c.rgb = vec3(48u + (((uvec3(h, h >> 8u, h >> 16u) & 255u) * 208u) >> 8u)) / 255.0;\n"
    "#endif\n"
    "    return c;\n"
    "}\n";

/* --debug levels: the tint of the level a pixel uses (the page-table and clipmap passes). */
const char vtv_level_colour_glsl[] =
    "vec3 level_colour(int l) {\n"
    "    vec3 c[8] = vec3[8](vec3(1,0,0), vec3(1,0.5,0), vec3(1,1,0), vec3(0,1,0),\n"
    "                        vec3(0,1,1), vec3(0,0,1), vec3(0.6,0,1), vec3(1,0,1));\n"
    "    return c[clamp(l, 0, 7)];\n"
    "}\n";

static const char vt_body[] =
    "uniform int u_debug;\n"
    "layout(location = 0) out vec4 o_color;\n"
    "layout(location = 1) out uint o_fallback;\n"
    "vt_addr A0, A1;\n"
    "bool OK0, OK1, TRI;\n"
    "float F;\n"
    "vec4 vt_layer(sampler2D s) {\n"
    "    vec4 c0 = OK0 ? vt_at(s, A0) : vec4(1.0, 0.0, 1.0, 1.0);\n"
    "    if (!TRI) return c0;\n"
    "    vec4 c1 = OK1 ? vt_at(s, A1) : vec4(1.0, 0.0, 1.0, 1.0);\n"
    "    return mix(c0, c1, F);\n"
    "}\n"
    "uniform int u_rebuild_z;\n"
    "vec4 vt_rebuild_z(vec4 c, int k) {\n" /* bc5 normal xy (RGTC2): z from the filtered xy */
    "    if (((u_rebuild_z >> k) & 1) == 0) return c;\n"
    "    vec2 n = c.xy * 2.0 - 1.0;\n"
    "    return vec4(c.xy, sqrt(max(1.0 - dot(n, n), 0.0)) * 0.5 + 0.5, c.a);\n"
    "}\n"
    "vec4 map_sample(int k) {\n"
    "    if (k == 0) return vt_display(vt_rebuild_z(vt_layer(u_phys_kd), 0));\n"
    "    if (k == 1) return vt_rebuild_z(vt_layer(u_phys_norm), 1);\n"
    "    if (k == 2) return vt_rebuild_z(vt_layer(u_phys_ks), 2);\n"
    "    return vt_rebuild_z(vt_layer(u_phys_d), 3);\n"
    "}\n"
    "void main() {\n"
    "    vec2 t0 = vt_texel();\n"
    "    vec2 gx = dFdx(t0), gy = dFdy(t0);\n"
    "    float lam = vt_lambda(gx, gy);\n"
    "    float texels_per_px = exp2(lam - u_lod_bias);\n"
    "    int used0, used1 = 0; vec2 it0, it1;\n"
    "    int want0; bool fb;\n"
    "    TRI = u_trilinear != 0;\n"
    "    F = 0.0;\n"
    "    if (TRI) {\n"
    "        float l = clamp(lam, 0.0, float(u_max_level));\n"
    "        want0 = int(floor(l));\n"
    "        int want1 = min(want0 + 1, u_max_level);\n"
    "        F = l - float(want0);\n"
    "        OK0 = vt_address(want0, t0, gx, gy, A0, used0, it0);\n"
    "        OK1 = vt_address(want1, t0, gx, gy, A1, used1, it1);\n"
    "        fb = used0 > want0 || (F > 0.0 && used1 > want1);\n"
    "    } else {\n"
    "        want0 = vt_nearest_level(lam);\n"
    "        OK0 = vt_address(want0, t0, gx, gy, A0, used0, it0);\n"
    "        OK1 = false;\n"
    "        fb = used0 > want0;\n"
    "    }\n"
    "#if !defined(F_DIFFUSE_MAP) && !defined(F_NORMAL_MAP) && !defined(F_SPECULAR_MAP) && "
    "!defined(F_ALPHA_MAP)\n"
    "    fb = false; /* a constant: no tile wanted, none missing */\n"
    "#endif\n"
    "    vec4 c = vt_material();\n"
    "    if (u_debug == 1) {\n"
    "        c = vec4(mix(level_colour(used0), c.rgb, 0.25), 1.0);\n"
    "    } else if (u_debug == 2) {\n"
    "        vec2 d = min(it0, vec2(u_content) - it0);\n"
    "        float px = texels_per_px / exp2(float(used0));\n"
    "        if (min(d.x, d.y) < 1.5 * px) c = fb ? vec4(1.0, 0.0, 0.0, 1.0) : vec4(0.0, 1.0, 0.0, 1.0);\n"
    "    }\n"
    "    o_color = c;\n"
    "    o_fallback = fb ? 1u : 0u;\n"
    "}\n";

/* Tile determination: the level the main pass wants; cut-outs are discarded with the coverage
 * read through the page table (the wanted tile or its resident ancestor), so that nothing behind
 * a hole is hidden and no tile is asked for where nothing is drawn. A material without any map
 * asks for no tile (it still occludes, unless it is blended: then it leaves what is behind). */
static const char feedback_body[] =
    "layout(location = 0) out uvec4 o_request;\n"
    "void main() {\n"
    "    vec2 t0 = vt_texel();\n"
    "    vec2 gx = dFdx(t0), gy = dFdy(t0);\n"
    "    float lam = vt_lambda(gx, gy);\n"
    "    int want = u_trilinear != 0 ? int(floor(clamp(lam, 0.0, float(u_max_level))))\n"
    "                                : vt_nearest_level(lam);\n"
    "#ifdef F_ALPHA_TEST\n"
    "    vt_addr a; int used; vec2 it;\n"
    "    if (vt_address(want, t0, gx, gy, a, used, it)) {\n"
    "#ifdef F_ALPHA_MAP\n"
    "        float al = vt_at(u_phys_d, a).r;\n"
    "#else\n"
    "        float al = vt_at(u_phys_kd, a).a;\n"
    "#endif\n"
    "        if (al < ALPHA_THRESHOLD) discard;\n"
    "    }\n"
    "#endif\n"
    "    ivec2 tc = vt_tile(want, t0);\n"
    "#if defined(F_DIFFUSE_MAP) || defined(F_NORMAL_MAP) || defined(F_SPECULAR_MAP) || "
    "defined(F_ALPHA_MAP)\n"
    "    o_request = uvec4(uint(tc.x), uint(tc.y), uint(want), 1u);\n"
    "#elif defined(F_ALPHA_BLEND)\n"
    "    discard;\n"
    "#else\n"
    "    o_request = uvec4(0u);\n"
    "#endif\n"
    "}\n";

/* The reference: the material's own textures as GL samples them (their addressing, filtering and
 * level of detail), each map's texcoords scaled and offset by its -s and -o (u_st: scale, offset,
 * on the drawn texcoords). */
static const char reference_body[] = "in vec2 v_uv;\n"
                                     "uniform sampler2D u_tex_kd, u_tex_norm, u_tex_ks, u_tex_d;\n"
                                     "uniform vec4 u_st[4];\n"
                                     "layout(location = 0) out vec4 o_color;\n"
                                     "layout(location = 1) out uint o_fallback;\n"
                                     "vec4 map_sample(int k) {\n"
                                     "    vec2 uv = v_uv * u_st[k].xy + u_st[k].zw;\n"
                                     "    if (k == 0) return vt_display(texture(u_tex_kd, uv));\n"
                                     "    if (k == 1) return texture(u_tex_norm, uv);\n"
                                     "    if (k == 2) return texture(u_tex_ks, uv);\n"
                                     "    return texture(u_tex_d, uv);\n"
                                     "}\n"
                                     "void main() {\n"
                                     "    o_color = vt_material();\n"
                                     "    o_fallback = 0u;\n"
                                     "}\n";

int vtv_shader_fragment(enum vtv_program_kind kind, unsigned features, char *defines, size_t cap,
                        const char *pieces[VTV_SHADER_PIECES])
{
    int n = 0;
    vtv_feature_defines(features, defines, cap);
    pieces[n++] = version;
    pieces[n++] = defines;
    switch (kind) {
    case VTV_PROG_VT:
        pieces[n++] = vt_common;
        if (features & VTV_F_WANG) { /* a material names a Wang pack (vt_wang) */
            pieces[n++] = vtv_wang_hash_glsl;
            pieces[n++] = vtv_wang_material_glsl;
        }
        pieces[n++] = shading;
        pieces[n++] = vtv_display_glsl;
        pieces[n++] = vtv_level_colour_glsl;
        pieces[n++] = vt_body;
        break;
    case VTV_PROG_FEEDBACK:
        pieces[n++] = vt_common;
        pieces[n++] = feedback_body;
        break;
    default:
        pieces[n++] = shading;
        pieces[n++] = vtv_display_glsl;
        pieces[n++] = reference_body;
        break;
    }
    return n;
}
