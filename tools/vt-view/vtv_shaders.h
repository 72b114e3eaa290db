/* GLSL 330 core sources of vt-view (string literals in vtv_shaders.c). */
#ifndef VTV_SHADERS_H
#define VTV_SHADERS_H

extern const char vtv_vs_source[];           /* shared vertex shader: position, uv, MVP, jitter */
extern const char vtv_fs_vt_source[];        /* virtual texture: page table + physical texture */
extern const char vtv_fs_feedback_source[];  /* tile determination: (x, y, level, 1) per pixel */
extern const char vtv_fs_reference_source[]; /* plain mipmapped GL texture */

#endif
