/* vt-view --wang: the fragment shader of TileTex (Wei 2004), the GLSL mirror of libvts's
 * vts_wang API (include/vts/vts_wang.h): the hash of equation 2 from a permutation texture,
 * TileIndex_1D / CornerIndex to the pack position, the offset inside the tile, and one fetch from
 * the pack with explicit derivatives of the continuous output coordinate (so the jump of the pack
 * coordinate at tile edges does not select the coarsest level). tests/e2e/view's wang cases check
 * it against the CPU assembly that uses the C API. */
#ifndef VTV_WANG_GLSL_H
#define VTV_WANG_GLSL_H

/* The vertex shader (a full-screen triangle from gl_VertexID) and the two fragment shaders: TileTex
 * is "#version 330 core\n", vtv_wang_hash_glsl, then vtv_wang_tiletex_glsl. */
extern const char vtv_wang_vertex_glsl[];
extern const char vtv_wang_hash_glsl[];      /* the hash and TileIndex / CornerIndex; uniforms */
extern const char vtv_wang_tiletex_glsl[];   /* uniforms: see the source */
extern const char vtv_wang_reference_glsl[]; /* one texture over the extent */
/* A scene material's TileTex, wang_sample() (after vtv_wang_hash_glsl and a v_uv input). */
extern const char vtv_wang_material_glsl[];

#endif
