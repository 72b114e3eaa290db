/* The 44 textures of the sample scene (samples/gen_scene.c): their files, sizes and kinds, and
 * the painter that writes each one (deterministic: no clock, no random seed). */
#ifndef VT_SAMPLE_TEXTURES_H
#define VT_SAMPLE_TEXTURES_H

#include <stdint.h>

#include "vt_error.h"

enum vt_sample_textures_kind {
    VT_SAMPLE_TEXTURES_FACADE, /* opaque RGB: wall with a window grid, frame and corner marks */
    VT_SAMPLE_TEXTURES_ALPHA,  /* RGBA: a round cut-out (tree crown) with soft edges */
    VT_SAMPLE_TEXTURES_MASK,   /* 1 channel: map_d fence mask with holes */
    VT_SAMPLE_TEXTURES_NORMAL, /* RGB normal map (tangent space, +Y up) of rivets and the raised
                                  label */
    VT_SAMPLE_TEXTURES_TILING, /* RGB paving that tiles seamlessly (used with UVs 0..8) */
};

struct vt_sample_textures_spec {
    const char *file; /* under textures/ */
    const char *label;
    uint32_t w, h;
    enum vt_sample_textures_kind kind;
};

#define VT_SAMPLE_TEXTURES_COUNT 44
/* t00..t40 colour (t36..t38 with alpha), n41 normal, g42 tiling, m43 alpha mask. */
extern const struct vt_sample_textures_spec vt_sample_textures[];

/* A well-mixed 32-bit hash (for deterministic variation). */
uint32_t vt_sample_textures_hash32(uint32_t x);

/* Paints texture index (edges divided by shrink, at least 8 px) and writes it to
 * dir/textures/<file>. Returns 0 or a negative status with err filled. */
int vt_sample_textures_make(const char *dir, uint32_t index, uint32_t shrink,
                            struct vts_error *err);

#endif
