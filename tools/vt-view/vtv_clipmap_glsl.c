/* GLSL of vt-view --clipmap (docs/viewer.md, "Clipmap mode"); it follows vtv_display_glsl (the
 * shown colour's range, ramp or index colours, as the page-table path shows them).
 *
 * Coordinates: t0 is the sample's level-0 texel position relative to a base (u_rel, the 2D view's
 * split coordinates: the level-0 tile u_origin's corner; else v_uv over the whole texture and the
 * base 0), so no float holds a 2^20 coordinate. Per level l (uniform arrays, computed on the CPU
 * in double): r = t0 / 2^l is the position in level-l texels relative to base / 2^l;
 * u_edge[l] is the level's clamp rectangle [0.5, w_l - 0.5]^2 relative to it, u_valid[l] the
 * level's valid rectangle (the front in texels less the inset) relative to it, u_off[l] the base
 * modulo the texture's edge S = n * C. The toroidal texture position is then (u_off[l] + r) / S
 * with GL_REPEAT: tile (x, y) of the level sits at slot (x mod n, y mod n).
 *
 * Level selection (equations 5-7 of the paper):
 *   (5) lambda = log2(max(|d t0/dx|, |d t0/dy|)) + lod bias (the footprint in level-0 texels);
 *   (6) clip = the finest level whose valid rectangle holds the sample;
 *   (7) used = max(level(lambda), clip), clamped to the store's levels, and then the first level
 *       from there whose valid rectangle holds the sample (the same unless a coarser level's
 *       front is smaller than a finer one's). Trilinear: floor(lambda) and floor(lambda) + 1, each
 *       so, blended by the fraction of lambda. A pixel drawn from a coarser level than lambda's
 *       counts as a fallback pixel (as in the page-table path).
 *
 * u_rebuild_z: the texture holds BC5 normal xy (RGTC2 uploaded as stored); z is rebuilt from the
 * filtered xy as the page-table shader's vt_rebuild_z does.
 *
 * With F_LIT (the terrain's lit material) the colour is shaded as the page-table pass's vt_shade
 * shades a lit material without maps: Kd * colour * (ambient + light * max(n . l, 0)). */
#include "vtv_clipmap_glsl.h"

const char vtv_clipmap_fs_glsl[] =
    "in vec2 v_uv;\n"
    "uniform sampler2DArray u_clip;\n"
    "uniform int u_levels;\n"
    "uniform vec2 u_virt;\n"
    "uniform int u_rel;\n"
    "uniform float u_size;\n"
    "uniform vec2 u_off[32];\n"
    "uniform vec4 u_edge[32];\n"
    "uniform vec4 u_valid[32];\n"
    "uniform int u_trilinear;\n"
    "uniform int u_nearest;\n"
    "uniform float u_lod_bias;\n"
    "uniform int u_debug;\n"
    "uniform int u_rebuild_z;\n"
    "#ifdef F_LIT\n"
    "in vec3 v_normal;\n"
    "uniform vec3 u_kd, u_light_dir, u_light_colour, u_ambient;\n"
    "#endif\n"
    "layout(location = 0) out vec4 o_color;\n"
    "layout(location = 1) out uint o_fallback;\n"
    "vec2 level_pos(int l, vec2 t0) { return t0 / exp2(float(l)); }\n"
    /* the position the fetch reads (clamped to the level's edge texels' centres): a sample on
       the texture's far edge (the terrain grid's u = 1) is held where its texel is */
    "bool holds(int l, vec2 t0) {\n"
    "    vec2 r = clamp(level_pos(l, t0), u_edge[l].xy, u_edge[l].zw);\n"
    "    vec4 v = u_valid[l];\n"
    "    return r.x >= v.x && r.y >= v.y && r.x < v.z && r.y < v.w;\n"
    "}\n"
    /* (6) and (7): the first level from `want` on whose valid rectangle holds t0; u_levels when
       none does */
    "int clip_from(int want, vec2 t0) {\n"
    "    for (int l = want; l < u_levels; l++)\n"
    "        if (holds(l, t0)) return l;\n"
    "    return u_levels;\n"
    "}\n"
    "vec4 fetch(int l, vec2 t0) {\n"
    "    if (l >= u_levels) return vec4(1.0, 0.0, 1.0, 1.0);\n"
    "    vec2 q = clamp(level_pos(l, t0), u_edge[l].xy, u_edge[l].zw);\n"
    "    return textureLod(u_clip, vec3((u_off[l] + q) / u_size, float(l)), 0.0);\n"
    "}\n"
    "int nearest_level(float lam) {\n"
    "    if (lam <= 0.5) return 0;\n"
    "    return min(int(ceil(lam + 0.5)) - 1, u_levels - 1);\n"
    "}\n"
    "void main() {\n"
    "    vec2 t0 = u_rel != 0 ? v_uv : v_uv * u_virt;\n"
    "    vec2 gx = dFdx(t0), gy = dFdy(t0);\n"
    /* (5) */
    "    float lam = 0.5 * log2(max(max(dot(gx, gx), dot(gy, gy)), 1e-20)) + u_lod_bias;\n"
    "    int want0, used0, used1 = 0;\n"
    "    bool fb;\n"
    "    vec4 c;\n"
    "    if (u_trilinear != 0 && u_nearest == 0) {\n"
    "        float l = clamp(lam, 0.0, float(u_levels - 1));\n"
    "        want0 = int(floor(l));\n"
    "        int want1 = min(want0 + 1, u_levels - 1);\n"
    "        float f = l - float(want0);\n"
    "        used0 = clip_from(want0, t0);\n"
    "        used1 = clip_from(want1, t0);\n"
    "        c = mix(fetch(used0, t0), fetch(used1, t0), f);\n"
    "        fb = used0 > want0 || (f > 0.0 && used1 > want1);\n"
    "    } else {\n"
    "        want0 = nearest_level(lam);\n"
    "        used0 = clip_from(want0, t0);\n"
    "        c = fetch(used0, t0);\n"
    "        fb = used0 > want0;\n"
    "    }\n"
    /* BC5 normal xy uploaded as stored: z from the filtered xy, as the page table's vt_rebuild_z */
    "    if (u_rebuild_z != 0) {\n"
    "        vec2 nx = c.xy * 2.0 - 1.0;\n"
    "        c = vec4(c.xy, sqrt(max(1.0 - dot(nx, nx), 0.0)) * 0.5 + 0.5, c.a);\n"
    "    }\n"
    "    c = vt_display(c);\n"
    /* a lit material (the terrain): the page-table pass's vt_shade without maps */
    "#ifdef F_LIT\n"
    "    vec3 n = normalize(v_normal);\n"
    "    if (!gl_FrontFacing) n = -n;\n"
    "    c.rgb = u_kd * c.rgb * (u_ambient + u_light_colour * max(dot(n, u_light_dir), 0.0));\n"
    "#endif\n"
    "    if (u_debug == 1) c = vec4(mix(level_colour(used0), c.rgb, 0.25), 1.0);\n"
    "    o_color = vec4(c.rgb, 1.0);\n"
    "    o_fallback = fb ? 1u : 0u;\n"
    "}\n";
