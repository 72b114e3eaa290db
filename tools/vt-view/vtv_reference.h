/* vt-view --reference-scene: the original scene (the OBJ before vt-offset, with its MTL files)
 * drawn the way an engine draws it, shaded like the virtual texture (vtv_material.h, the same
 * shader variants): one plain GL texture per map file (map_Kd, norm or bump, map_Ks, map_d), read
 * through formats/input/vt_image_input.h (8/16-bit samples, shown as 8 bits; sRGB colour maps as
 * GL_SRGB8_ALPHA8 when the frame is sRGB), mip levels made on the CPU like the store's
 * (vtv_mipmap.h: box in linear light, normals renormalised). The material's constants, alpha mode
 * and illumination follow vt-atlas's rules on the original MTL (vtv_material_from_mtl, with the
 * cut-out rule of lib/atlas on map_Kd's alpha). Addressing is GL_REPEAT on both axes, or
 * GL_CLAMP_TO_EDGE when the map statement says -clamp on; each map's -s and -o scale and offset
 * its texcoords; filtering follows the view's (bilinear: GL_LINEAR_MIPMAP_NEAREST, trilinear:
 * GL_LINEAR_MIPMAP_LINEAR). A repeating material's texcoords are drawn minus the floor of their
 * face's smallest u and v (subtracted in double per face), so that UVs far from 0 keep float
 * precision. Needs a current GL 3.3 core context and an initialised struct vtv_render. */
#ifndef VTV_REFERENCE_H
#define VTV_REFERENCE_H

#include <stdbool.h>
#include <stdint.h>

#include <epoxy/gl.h>

#include "vt_error.h"
#include "vtv_material.h"
#include "vtv_render.h"

struct vtv_reference_map {
    GLuint tex;  /* 0: the material has no such map */
    bool clamp;  /* -clamp on: GL_CLAMP_TO_EDGE, else GL_REPEAT */
    float st[4]; /* -s u v, -o u v as applied to the drawn texcoords (v flipped) */
};

struct vtv_reference_part {
    uint32_t first, count; /* vertices in the scene's buffer */
    struct vtv_material mat;
    unsigned features;
    bool clamp; /* texcoords as read (a clamped map_Kd); else shifted per face */
    struct vtv_reference_map maps[VTV_MAP_COUNT];
};

struct vtv_reference_scene {
    GLuint vao, vbo;
    struct vtv_reference_part *parts; /* in draw order: opaque feature sets, then blended */
    uint32_t part_count;
    GLuint *textures; /* distinct (file, kind) textures */
    uint32_t texture_count;
    double lo[3], hi[3]; /* bounding box */
};

/* Reads obj_path and its MTL files, loads the textures (srgb: the frame is sRGB-encoded, so sRGB
 * colour maps decode to linear light) and compiles the variants in r (their face counts are
 * added). Returns 0 or a negative status naming the file. */
int vtv_reference_scene_load(struct vtv_reference_scene *s, struct vtv_render *r,
                             const char *obj_path, bool srgb, struct vts_error *err);
/* Draws the scene into the main framebuffer with the view's camera, filtering and light. */
void vtv_reference_scene_draw(struct vtv_render *r, const struct vtv_reference_scene *s,
                              const struct vtv_view *v);
void vtv_reference_scene_free(struct vtv_reference_scene *s);

#endif
