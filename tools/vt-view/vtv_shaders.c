/* GLSL 330 core sources of vt-view. Coordinates: v_uv in [0,1]^2 over the virtual texture (v = 0 is
 * the first row of the store); t0 = v_uv * u_virt is in level-0 texels. The level-of-detail comes
 * from the gradients of t0 (the virtual texture), not from the physical texture, and the physical
 * lookups get those gradients scaled to the level used (corrected gradients). */
#include "vtv_shaders.h"

const char vtv_vs_source[] = "#version 330 core\n"
                             "layout(location = 0) in vec3 a_pos;\n"
                             "layout(location = 1) in vec2 a_uv;\n"
                             "uniform mat4 u_mvp;\n"
                             "uniform vec2 u_jitter;\n"
                             "out vec2 v_uv;\n"
                             "void main() {\n"
                             "    gl_Position = u_mvp * vec4(a_pos, 1.0);\n"
                             "    gl_Position.xy += u_jitter * gl_Position.w;\n"
                             "    v_uv = a_uv;\n"
                             "}\n";

#define VTV_COMMON                                                                                 \
    "#version 330 core\n"                                                                          \
    "in vec2 v_uv;\n"                                                                              \
    "uniform usampler2D u_pt;\n"                                                                   \
    "uniform vec2 u_virt;\n"                                                                       \
    "uniform float u_content;\n"                                                                   \
    "uniform int u_max_level;\n"                                                                   \
    "uniform ivec2 u_pt_tiles[32];\n"                                                              \
    "uniform int u_pt_row[32];\n"                                                                  \
    "uniform int u_trilinear;\n"                                                                   \
    "uniform float u_lod_bias;\n"                                                                  \
    "float vt_lambda(vec2 gx, vec2 gy) {\n"                                                        \
    "    return 0.5 * log2(max(max(dot(gx, gx), dot(gy, gy)), 1e-20)) + u_lod_bias;\n"             \
    "}\n"                                                                                          \
    "int vt_nearest_level(float lam) {\n"                                                          \
    "    if (lam <= 0.5) return 0;\n"                                                              \
    "    return min(int(ceil(lam + 0.5)) - 1, u_max_level);\n"                                     \
    "}\n"                                                                                          \
    "ivec2 vt_tile(int level, vec2 t0) {\n"                                                        \
    "    ivec2 tc = ivec2(floor(t0 / (u_content * exp2(float(level)))));\n"                        \
    "    return clamp(tc, ivec2(0), u_pt_tiles[level] - 1);\n"                                     \
    "}\n"

const char vtv_fs_vt_source[] = VTV_COMMON
    "uniform sampler2D u_phys;\n"
    "uniform vec2 u_phys_size;\n"
    "uniform float u_border;\n"
    "uniform float u_payload;\n"
    "uniform int u_debug;\n"
    "uniform float u_alpha_test;\n"
    "layout(location = 0) out vec4 o_color;\n"
    "layout(location = 1) out uint o_fallback;\n"
    "vec4 vt_sample(int want, vec2 t0, vec2 gx, vec2 gy, out int used, out vec2 in_tile) {\n"
    "    ivec2 tc = vt_tile(want, t0);\n"
    "    uvec4 e = texelFetch(u_pt, ivec2(tc.x, tc.y + u_pt_row[want]), 0);\n"
    "    if (e.a == 0u) { used = 99; in_tile = vec2(0.0); return vec4(1.0, 0.0, 1.0, 1.0); }\n"
    "    used = int(e.b);\n"
    "    ivec2 tl = tc >> (used - want);\n"
    "    float s = exp2(float(used));\n"
    "    vec2 t = t0 / s - vec2(tl) * u_content;\n"
    "    in_tile = clamp(t, vec2(0.5 - u_border), vec2(u_content + u_border - 0.5));\n"
    "    vec2 p = (vec2(e.rg) * u_payload + u_border + in_tile) / u_phys_size;\n"
    "    vec2 k = 1.0 / (s * u_phys_size);\n"
    "    return textureGrad(u_phys, p, gx * k, gy * k);\n"
    "}\n"
    "vec3 level_colour(int l) {\n"
    "    vec3 c[8] = vec3[8](vec3(1,0,0), vec3(1,0.5,0), vec3(1,1,0), vec3(0,1,0),\n"
    "                        vec3(0,1,1), vec3(0,0,1), vec3(0.6,0,1), vec3(1,0,1));\n"
    "    return c[clamp(l, 0, 7)];\n"
    "}\n"
    "void main() {\n"
    "    vec2 t0 = v_uv * u_virt;\n"
    "    vec2 gx = dFdx(t0), gy = dFdy(t0);\n"
    "    float lam = vt_lambda(gx, gy);\n"
    "    float texels_per_px = exp2(lam - u_lod_bias);\n"
    "    int used0, used1; vec2 it0, it1;\n"
    "    int want0; vec4 c; bool fb;\n"
    "    if (u_trilinear != 0) {\n"
    "        float l = clamp(lam, 0.0, float(u_max_level));\n"
    "        want0 = int(floor(l));\n"
    "        int want1 = min(want0 + 1, u_max_level);\n"
    "        float f = l - float(want0);\n"
    "        vec4 c0 = vt_sample(want0, t0, gx, gy, used0, it0);\n"
    "        vec4 c1 = vt_sample(want1, t0, gx, gy, used1, it1);\n"
    "        c = mix(c0, c1, f);\n"
    "        fb = used0 > want0 || (f > 0.0 && used1 > want1);\n"
    "    } else {\n"
    "        want0 = vt_nearest_level(lam);\n"
    "        c = vt_sample(want0, t0, gx, gy, used0, it0);\n"
    "        fb = used0 > want0;\n"
    "    }\n"
    "    if (u_debug == 1) {\n"
    "        c = vec4(mix(level_colour(used0), c.rgb, 0.25), 1.0);\n"
    "    } else if (u_debug == 2) {\n"
    "        vec2 d = min(it0, vec2(u_content) - it0);\n"
    "        float px = texels_per_px / exp2(float(used0));\n"
    "        if (min(d.x, d.y) < 1.5 * px) c = fb ? vec4(1.0, 0.0, 0.0, 1.0) : vec4(0.0, 1.0, 0.0, 1.0);\n"
    "    }\n"
    "    if (c.a < u_alpha_test) discard;\n"
    "    o_color = c;\n"
    "    o_fallback = fb ? 1u : 0u;\n"
    "}\n";

const char vtv_fs_feedback_source[] =
    VTV_COMMON "layout(location = 0) out uvec4 o_request;\n"
               "void main() {\n"
               "    vec2 t0 = v_uv * u_virt;\n"
               "    float lam = vt_lambda(dFdx(t0), dFdy(t0));\n"
               "    int want = u_trilinear != 0 ? int(floor(clamp(lam, 0.0, float(u_max_level))))\n"
               "                                : vt_nearest_level(lam);\n"
               "    ivec2 tc = vt_tile(want, t0);\n"
               "    o_request = uvec4(uint(tc.x), uint(tc.y), uint(want), 1u);\n"
               "}\n";

/* The reference: u_mode 0 the colour u_kd, 1 the texture as GL samples it (its own addressing,
 * filtering and level of detail). */
const char vtv_fs_reference_source[] = "#version 330 core\n"
                                       "in vec2 v_uv;\n"
                                       "uniform sampler2D u_tex;\n"
                                       "uniform int u_mode;\n"
                                       "uniform vec4 u_kd;\n"
                                       "uniform float u_alpha_test;\n"
                                       "layout(location = 0) out vec4 o_color;\n"
                                       "layout(location = 1) out uint o_fallback;\n"
                                       "void main() {\n"
                                       "    vec4 c = u_mode == 0 ? u_kd : texture(u_tex, v_uv);\n"
                                       "    if (c.a < u_alpha_test) discard;\n"
                                       "    o_color = c;\n"
                                       "    o_fallback = 0u;\n"
                                       "}\n";
