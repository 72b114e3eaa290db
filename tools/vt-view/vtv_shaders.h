/* GLSL 330 core sources of vt-view (string literals in vtv_shaders.c). A fragment shader is
 * assembled from pieces: the version, the feature #defines of its variant (vtv_material.h), the
 * shared parts and the body of its kind. */
#ifndef VTV_SHADERS_H
#define VTV_SHADERS_H

#include <stddef.h>

enum vtv_program_kind {
    VTV_PROG_VT,        /* virtual texture: page table + physical textures, shaded */
    VTV_PROG_FEEDBACK,  /* tile determination: (x, y, level, 1) per pixel, cut-outs discarded */
    VTV_PROG_REFERENCE, /* plain mipmapped GL textures, shaded the same way */
    VTV_PROG_KINDS
};

#define VTV_SHADER_PIECES 9

extern const char vtv_vs_source[]; /* shared vertex shader: position, uv, normal, tangent */
/* The shown colour's display, vec4 vt_display(vec4) (range, ramp, index colours: F_RANGE, F_RAMP,
 * F_INDEX; uniforms set by vtv_render_material_uniforms). */
extern const char vtv_display_glsl[];
/* vec3 level_colour(int level): the --debug levels tint (after vtv_display_glsl). */
extern const char vtv_level_colour_glsl[];

/* The pieces of the fragment shader of kind for features (enum vtv_feature bits); defines is the
 * caller's buffer for the #define lines (cap bytes, 512 is enough). Returns the piece count. */
int vtv_shader_fragment(enum vtv_program_kind kind, unsigned features, char *defines, size_t cap,
                        const char *pieces[VTV_SHADER_PIECES]);

#endif
