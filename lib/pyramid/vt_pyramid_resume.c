/* The pyramid resumed from level k (see vt_pyramid_resume.h): the level is assembled tile by tile
 * into a float pass image, which is then the source of vt_pyramid_build()'s resume path. */
#include "vt_pyramid_resume.h"

#include <stdlib.h>

#include "internal/vt_float_file.h"
#include "vt_checked.h"
#include "vt_error.h"

struct vt_pyramid_resume {
    const struct vt_pyramid_options *o;
    struct vt_float_file *level; /* level k, F32 working texels */
    struct vt_source source;     /* reads level; shared by every worker (pread) */
};

/* Reads every tile of level k through read_level into r->level, one tile buffer at a time. */
static int resume_assemble(struct vt_pyramid_resume *r, const struct vt_pyramid_plan *plan,
                           vt_pyramid_level_fn read_level, void *user, struct vts_error *err)
{
    uint32_t c = r->o->tile_content_px, channels = r->o->resume_input->channels;
    size_t floats;
    float *tile = NULL;
    if (!vt_size_mul3(c, c, channels, &floats) || !(tile = malloc(floats * sizeof *tile)))
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    int rc = 0;
    for (uint32_t ty = 0; rc == 0 && (uint64_t)ty * c < plan->carry_height; ty++)
        for (uint32_t tx = 0; rc == 0 && (uint64_t)tx * c < plan->carry_width; tx++) {
            uint32_t w = plan->carry_width - tx * c < c ? plan->carry_width - tx * c : c;
            uint32_t h = plan->carry_height - ty * c < c ? plan->carry_height - ty * c : c;
            size_t stride = (size_t)c * channels;
            rc = read_level(user, tx, ty, w, h, tile, stride, err);
            if (rc == 0)
                rc = vt_float_file_write(r->level, tx * c, ty * c, w, h, tile, stride, err);
        }
    free(tile);
    return rc;
}

struct vt_pyramid_resume *vt_pyramid_resume_create(const struct vt_pyramid_options *o,
                                                   vt_pyramid_level_fn read_level, void *user,
                                                   struct vts_error *err)
{
    struct vt_pyramid_plan plan;
    vt_pyramid_plan(o, &plan);
    if (!o->resume_input || o->part || !plan.has_next || !read_level || o->tile_content_px == 0) {
        vt_error_set(err, VTS_ERR_ARG, "invalid options to resume a pyramid");
        return NULL;
    }
    struct vt_pyramid_resume *r = calloc(1, sizeof *r);
    if (!r) {
        vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
        return NULL;
    }
    r->o = o;
    const struct vt_source_info *in = o->resume_input;
    r->level = vt_float_file_create(o->temp_dir, plan.carry_width, plan.carry_height, in->channels,
                                    o->tile_content_px, err);
    if (!r->level)
        goto out_destroy;
    if (resume_assemble(r, &plan, read_level, user, err) != 0)
        goto out_destroy;
    if (vt_float_file_source(r->level, o->colour, in->has_alpha, &r->source, err) != 0)
        goto out_destroy;
    return r;

out_destroy:
    vt_pyramid_resume_destroy(r);
    return NULL;
}

int vt_pyramid_resume_run(struct vt_pyramid_resume *r, struct vts_error *err)
{
    unsigned threads = r->o->threads;
    struct vt_source **sources = calloc(threads ? threads : 1, sizeof *sources);
    if (!sources)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    for (unsigned i = 0; i < threads; i++)
        sources[i] = &r->source;
    int rc = vt_pyramid_build(sources, r->o, err);
    free(sources);
    return rc;
}

void vt_pyramid_resume_destroy(struct vt_pyramid_resume *r)
{
    if (!r)
        return;
    vt_source_close(&r->source);
    vt_float_file_destroy(r->level);
    free(r);
}
