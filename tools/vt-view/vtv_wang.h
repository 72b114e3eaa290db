/* vt-view --wang PACK.vts: an arbitrarily large texture drawn from a Wang pack (vt-wang) with
 * TileTex (vtv_wang_glsl.h), or with --reference the same output assembled on the CPU into one
 * plain mipmapped texture (docs/wang.md, docs/cli/vt-view.md). The frame shows the extent (in
 * tiles) of the output from tile --origin (default its top-left corner), trilinear filtering; in a
 * window, dragging and the arrow keys pan it and +/- and the wheel zoom it (TileTex only). */
#ifndef VTV_WANG_H
#define VTV_WANG_H

#include "vt_wang_pack.h"
#include "vtv_app.h"

/* A pack as GL textures: the pack (sRGB, repeat, trilinear, its levels down to one texel per Wang
 * tile), the hash permutation and the shuffled order (R32UI, 256 columns; one 0 when unshuffled).
 */
struct vtv_wang_gl {
    unsigned pack, perm, order; /* GLuint */
    uint32_t levels;
};

/* Uploads the pack of store (its info read with vt_wang_pack_open) into *out (textures created even
 * on failure are in *out: delete them). Needs a current GL context. */
int vtv_wang_load_pack(struct vts_store *store, const struct vt_wang_info *info,
                       struct vtv_wang_gl *out, struct vts_error *err);

/* Runs the viewer on o->wang_path; returns the process exit status. */
int vtv_wang_run(const struct vtv_options *o);

#endif
