/* vt-view --clipmap: the fragment shader that samples the clipmap's texture array (one layer per
 * level, toroidal addressing) with the level selection of Ephanov & Coleman's equations 5-7
 * (docs/viewer.md, "Clipmap mode"). Its vertex shader is vtv_vs_source (vtv_shaders.h): any
 * struct vtv_mesh drawn with any struct vtv_view camera, the clipmap addressed from the vertex
 * texcoords. */
#ifndef VTV_CLIPMAP_GLSL_H
#define VTV_CLIPMAP_GLSL_H

/* The fragment shader's body, after "#version 330 core", the display's #defines and
 * vtv_display_glsl (vtv_shaders.h); its uniforms are set by vtv_clipmap_gl.c. */
extern const char vtv_clipmap_fs_glsl[];

#endif
