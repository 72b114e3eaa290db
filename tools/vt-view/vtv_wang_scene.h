/* vt-view: the Wang packs that the materials of a scene name (the .vt.mtl statement "vt_wang
 * PACK.vts [scale S]"; docs/wang.md, "Packs in scenes"): each pack opened once, uploaded once
 * (vtv_wang_load_pack) and shared by the materials that name it, which draw their diffuse with
 * TileTex (VTV_F_WANG, vtv_wang_material_glsl) on texture units VTV_WANG_UNIT.. +2. */
#ifndef VTV_WANG_SCENE_H
#define VTV_WANG_SCENE_H

#include <stdint.h>

#include "vt_error.h"
#include "vtv_material.h"
#include "vtv_wang_gl.h"

#define VTV_WANG_UNIT 5 /* pack, permutation, order (after the page table and 4 physical maps) */

struct vtv_wang_scene_pack {
    struct vts_store *store;
    struct vt_wang_info info;
    struct vtv_wang_gl gl;
};

struct vtv_wang_scene {
    struct vtv_wang_scene_pack *packs;
    uint32_t count;
    bool uploaded;
};

/* Opens the count packs at paths (before any GL: one plain error naming a file that is not a
 * pack). */
int vtv_wang_scene_open(struct vtv_wang_scene *s, char *const *paths, uint32_t count,
                        struct vts_error *err);

/* Uploads them (a current GL context). */
int vtv_wang_scene_upload(struct vtv_wang_scene *s, struct vts_error *err);

/* Binds material m's pack (m->wang != 0) and sets the uniforms of program prog for it. */
void vtv_wang_scene_bind(const struct vtv_wang_scene *s, unsigned prog,
                         const struct vtv_material *m);

/* Frees everything (the textures only when uploaded: the GL context must still be current). */
void vtv_wang_scene_free(struct vtv_wang_scene *s);

#endif
