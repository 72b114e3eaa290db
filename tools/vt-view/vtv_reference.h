/* vt-view --reference-scene: the original scene (the OBJ before vt-offset, with its MTL files)
 * drawn the way an engine draws it, with one plain GL texture per material's map_Kd, read through
 * formats/input/vt_image_input.h (8/16-bit samples, shown as 8 bits; sRGB textures as
 * GL_SRGB8_ALPHA8 when the frame is sRGB), mip levels made on the CPU like the store's
 * (vtv_mipmap.h: box in linear light). Addressing is GL_REPEAT on both axes, or GL_CLAMP_TO_EDGE
 * when the map_Kd statement says -clamp on; filtering follows the view's (bilinear:
 * GL_LINEAR_MIPMAP_NEAREST, trilinear: GL_LINEAR_MIPMAP_LINEAR). A repeating material's texcoords
 * are drawn minus the floor of their face's smallest u and v (subtracted in double per face), so
 * that UVs far from 0 keep float precision. Materials without map_Kd are drawn with their Kd (0.8
 * grey without one), taken as sRGB-encoded like vt-atlas's constant cells. Needs a current GL 3.3
 * core context and an initialised struct vtv_render. */
#ifndef VTV_REFERENCE_H
#define VTV_REFERENCE_H

#include <stdbool.h>
#include <stdint.h>

#include <epoxy/gl.h>

#include "vt_error.h"
#include "vtv_render.h"

struct vtv_reference_part {
    uint32_t first, count; /* vertices in the scene's buffer */
    GLuint tex;            /* 0: the constant kd */
    float kd[4];           /* linear when the frame is sRGB-encoded */
    bool clamp;            /* map_Kd -clamp on: GL_CLAMP_TO_EDGE, texcoords as read; else
                              GL_REPEAT, texcoords shifted per face */
};

struct vtv_reference_scene {
    GLuint vao, vbo;
    struct vtv_reference_part *parts;
    uint32_t part_count;
    GLuint *textures; /* distinct map_Kd files */
    uint32_t texture_count;
    double lo[3], hi[3]; /* bounding box */
};

/* Reads obj_path and its MTL files, loads the textures (srgb: the frame is sRGB-encoded, so sRGB
 * textures decode to linear light). Returns 0 or a negative status naming the file. */
int vtv_reference_scene_load(struct vtv_reference_scene *s, const char *obj_path, bool srgb,
                             struct vts_error *err);
/* Draws the scene into the main framebuffer with the view's camera and filtering. */
void vtv_reference_scene_draw(struct vtv_render *r, const struct vtv_reference_scene *s,
                              const struct vtv_view *v);
void vtv_reference_scene_free(struct vtv_reference_scene *s);

#endif
