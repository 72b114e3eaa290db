/* The mip pyramid resumed from a level: the passes of vt_pyramid_build() after its first one, fed
 * with the texels that first pass would have left of its last level (level k = levels_per_pass).
 * That is how vt-merge finishes a sharded build (docs/sharding.md): the shards computed level k
 * in parts and carried its texels; the resume assembles them and emits every level above k, byte
 * for byte the tiles of the single build. */
#ifndef VT_PYRAMID_RESUME_H
#define VT_PYRAMID_RESUME_H

#include <stddef.h>
#include <stdint.h>

#include "vt_error.h"
#include "vt_pyramid.h"

/* Fills texels with tile (tx, ty) of level k as the first pass computed it: the part of the
 * tile's content inside the level, width x height texels of the input's channel count
 * (o->resume_input->channels) floats in working space, rows `stride` floats apart. Called on the
 * calling thread, once per tile of level k, in row-major order. 0 or a negative status. */
typedef int (*vt_pyramid_level_fn)(void *user, uint32_t tx, uint32_t ty, uint32_t width,
                                   uint32_t height, float *texels, size_t stride,
                                   struct vts_error *err);

struct vt_pyramid_resume;

/* Assembles level k of the build *o describes into a temporary float image in o->temp_dir,
 * reading it through read_level. o->resume_input must be set (the original input: channels,
 * has_alpha, premultiplied) and the build must have levels above k (vt_pyramid_plan(): has_next;
 * VTS_ERR_ARG otherwise). *o is used again by vt_pyramid_resume_run(): it must outlive the
 * handle. Returns NULL and fills err (read_level's error, VTS_ERR_IO, VTS_ERR_NOMEM) on failure.
 * Free with vt_pyramid_resume_destroy(). */
struct vt_pyramid_resume *vt_pyramid_resume_create(const struct vt_pyramid_options *o,
                                                   vt_pyramid_level_fn read_level, void *user,
                                                   struct vts_error *err);

/* Builds the levels above k from the assembled level and hands their tiles to o->emit (worker
 * threads, each tile once; progress through o->progress), as vt_pyramid_build() does. Call once.
 * Returns 0 or the first error. */
int vt_pyramid_resume_run(struct vt_pyramid_resume *r, struct vts_error *err);

/* Frees the handle and its temporary image. Accepts NULL. */
void vt_pyramid_resume_destroy(struct vt_pyramid_resume *r);

#endif
