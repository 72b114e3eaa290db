/* vt-view --wang shaders (vtv_wang_glsl.h). Keep TileTex in step with lib/store/vts_wang.c. */
#include "vtv_wang_glsl.h"

const char vtv_wang_vertex_glsl[] =
    "#version 330 core\n"
    "void main() {\n"
    "    vec2 p = vec2(float((gl_VertexID & 1) * 4 - 1), float((gl_VertexID & 2) * 2 - 1));\n"
    "    gl_Position = vec4(p, 0.0, 1.0);\n"
    "}\n";

/* Output coordinate: the frame covers `extent` tiles from tile `origin`, image rows downwards (row
 * 0 at the top). The origin enters as an integer (mod n): the floats only hold the position inside
 * the extent, so a frame a million tiles out is as precise as at 0,0. */
/* The hash and the pack slot (shared by the 2D view and the scene materials). */
const char vtv_wang_hash_glsl[] =
    "uniform usampler2D wang_perm;  /* the hash permutation: entry i at (i % 256, i / 256) */\n"
    "uniform uint wang_n, wang_kh, wang_kv;\n"
    "uint wang_fetch(usampler2D t, uint i) {\n"
    "    return texelFetch(t, ivec2(int(i & 255u), int(i >> 8)), 0).r;\n"
    "}\n"
    "uint wang_H(uint i) { return wang_fetch(wang_perm, i % wang_n); }\n"
    "uint wang_index1d(uint a, uint b) {\n"
    "    if (a < b) return 2u * a + b * b;\n"
    "    if (a > b && b > 0u) return a * a + 2u * b - 1u;\n"
    "    if (a == b && a > 0u) return (a + 1u) * (a + 1u) - 2u;\n"
    "    return a > 0u ? (a + 1u) * (a + 1u) - 1u : 0u;\n"
    "}\n"
    "uvec2 wang_edge_tile(uint x, uint y) {\n"
    "    uint column = wang_H(x), row = wang_H(2u * y);\n"
    "    uint nc = wang_H(column + y) % wang_kh, sc = wang_H(column + y + 1u) % wang_kh;\n"
    "    uint wc = wang_H(x + row) % wang_kv, ec = wang_H(x + 1u + row) % wang_kv;\n"
    "    return uvec2(wang_index1d(wc, ec), wang_index1d(nc, sc));\n"
    "}\n"
    "uvec2 wang_corner_tile(uint x, uint y) {\n"
    "    uint c0 = wang_H(x), c1 = wang_H(x + 1u), k2 = wang_kh * wang_kh;\n"
    "    uint top = wang_index1d(wang_H(c0 + y) % wang_kh, wang_H(c1 + y) % wang_kh);\n"
    "    uint bottom = wang_index1d(wang_H(c0 + y + 1u) % wang_kh, wang_H(c1 + y + 1u) % wang_kh);\n"
    "    uint j = (bottom + k2 - top) % k2;\n"
    "    uint shift = j == 0u ? 0u : (j * (j - 1u) / 2u) % k2;\n"
    "    return uvec2((top + k2 - shift) % k2, j);\n"
    "}\n";

/* Output coordinate: the frame covers `extent` tiles from tile `origin`, image rows downwards (row
 * 0 at the top). The origin enters as an integer (mod n): the floats only hold the position inside
 * the extent, so a frame a million tiles out is as precise as at 0,0. */
const char vtv_wang_tiletex_glsl[] =
    "uniform sampler2D pack;        /* the pack, sRGB, repeat, mipmapped */\n"
    "uniform usampler2D order;      /* a shuffled pack: slot of each canonical slot */\n"
    "uniform uint cols, rows;\n"
    "uniform bool corners, shuffled, use_map;\n"
    "uniform usampler2D tilemap;    /* use_map: the pack slot of tile (x, y) mod n, precomputed */\n"
    "uniform vec2 frame, extent;    /* frame in pixels, extent in tiles */\n"
    "uniform uvec2 origin;          /* the top-left tile, mod n */\n"
    "uniform vec2 shift;            /* and the position in it (a window's pan), in tiles */\n"
    "out vec4 colour;\n"
    "void main() {\n"
    "    vec2 uv = vec2(gl_FragCoord.x / frame.x, 1.0 - gl_FragCoord.y / frame.y);\n"
    "    vec2 p = uv * extent + shift;    /* output position in tiles from origin */\n"
    "    vec2 t = floor(p), f = p - t;    /* the tile and the offset inside it */\n"
    "    uint x = (origin.x + uint(t.x)) % wang_n, y = (origin.y + uint(t.y)) % wang_n;\n"
    "    uvec2 slot;\n"
    "    if (use_map) {\n"
    "        slot = texelFetch(tilemap, ivec2(int(x), int(y)), 0).rg;\n"
    "    } else {\n"
    "        slot = corners ? wang_corner_tile(x, y) : wang_edge_tile(x, y);\n"
    "    }\n"
    "    if (shuffled && !use_map) {\n"
    "        uint s = wang_fetch(order, slot.y * cols + slot.x);\n"
    "        slot = uvec2(s % cols, s / cols);\n"
    "    }\n"
    "    vec2 grid = vec2(float(cols), float(rows));\n"
    "    vec2 q = (vec2(slot) + f) / grid;\n"
    "    /* Wei, section 5: the level of detail from the continuous output coordinate */\n"
    "    colour = textureGrad(pack, q, dFdx(p) / grid, dFdy(p) / grid);\n"
    "}\n";

/* A scene material's diffuse (VTV_F_WANG, after vtv_wang_hash_glsl): TileTex at output position
 * (u, -v) * scale in tiles, from the texture coordinates v_uv = (u, 1 - v) of vtv_mesh. The tile
 * is taken mod n (the output's period) in float, exact while |u|, |v| * scale < 2^24. */
const char vtv_wang_material_glsl[] =
    "uniform sampler2D wang_pack;\n"
    "uniform usampler2D wang_order;\n"
    "uniform uint wang_cols, wang_rows;\n"
    "uniform bool wang_corners, wang_shuffled;\n"
    "uniform float wang_scale;\n"
    "vec4 wang_sample() {\n"
    "    vec2 p = vec2(v_uv.x, v_uv.y - 1.0) * wang_scale;\n"
    "    vec2 t = floor(p), f = p - t;\n"
    "    uint x = uint(mod(t.x, float(wang_n))), y = uint(mod(t.y, float(wang_n)));\n"
    "    uvec2 slot = wang_corners ? wang_corner_tile(x, y) : wang_edge_tile(x, y);\n"
    "    if (wang_shuffled) {\n"
    "        uint s = wang_fetch(wang_order, slot.y * wang_cols + slot.x);\n"
    "        slot = uvec2(s % wang_cols, s / wang_cols);\n"
    "    }\n"
    "    vec2 grid = vec2(float(wang_cols), float(wang_rows));\n"
    "    vec2 q = (vec2(slot) + f) / grid;\n"
    "    return textureGrad(wang_pack, q, dFdx(p) / grid, dFdy(p) / grid);\n"
    "}\n";

const char vtv_wang_reference_glsl[] =
    "#version 330 core\n"
    "uniform sampler2D image;       /* the output, assembled on the CPU, mipmapped */\n"
    "uniform vec2 frame;\n"
    "out vec4 colour;\n"
    "void main() {\n"
    "    vec2 uv = vec2(gl_FragCoord.x / frame.x, 1.0 - gl_FragCoord.y / frame.y);\n"
    "    colour = texture(image, uv);\n"
    "}\n";
