/* vt-view: a Wang pack (vt-wang) uploaded as GL textures, shared by --wang (vtv_wang.h) and the
 * scene materials that name a pack (vtv_wang_scene.h). */
#ifndef VTV_WANG_GL_H
#define VTV_WANG_GL_H

#include <stdint.h>

#include "vt_error.h"
#include "vt_wang_pack.h"

/* A pack as GL textures: the pack (sRGB, repeat, trilinear, its levels down to one texel per
 * Wang tile), the hash permutation and the shuffled order (R32UI, 256 columns; one 0 when the
 * pack is not shuffled). */
struct vtv_wang_gl {
    unsigned pack, perm, order; /* GLuint */
    uint32_t levels;
};

/* Uploads the pack of store (its info read with vt_wang_pack_open) into *out (textures created even
 * on failure are in *out: delete them). Needs a current GL context. */
int vtv_wang_load_pack(struct vts_store *store, const struct vt_wang_info *info,
                       struct vtv_wang_gl *out, struct vts_error *err);

#endif
