/* Running one pass of the mip pyramid (see vt_pyramid_pass.h). */
#include "vt_pyramid_pass.h"

#include <stdlib.h>

#include "vt_checked.h"
#include "vt_error.h"
#include "vt_pool.h"
#include "vt_pyramid_block.h"
#include "vt_pyramid_read.h"

static void scratch_free(struct vt_pyramid_pass *p)
{
    for (unsigned i = 0; p->scratch && i < p->threads; i++) {
        struct vt_pyramid_pass_scratch *s = &p->scratch[i];
        vt_image_release(&s->in);
        for (uint32_t r = p->source_is_working ? 1 : 0; r <= VT_PYRAMID_PASS_MAX_LEVELS; r++)
            free(s->w[r].px);
        free(s->reduce_scratch);
        vt_image_release(&s->tile_full);
        vt_image_release(&s->tile);
        free(s->xs);
        free(s->ys);
    }
    free(p->scratch);
    p->scratch = NULL;
}

/* Largest region of relative level r over all blocks: a full block plus margins. */
static void max_region(const struct vt_pyramid_pass *p, uint32_t r, struct vt_fregion *out)
{
    uint32_t m = p->margin[r];
    uint64_t s = p->block >> r;
    out->x0 = out->y0 = 0;
    out->width = out->height = (uint32_t)s + 2 * m;
    out->channels = p->channels;
}

static int scratch_alloc(struct vt_pyramid_pass *p, struct vts_error *err)
{
    const struct vt_pyramid_options *o = p->o;
    uint32_t pp = o->tile_content_px + 2 * o->border_px;
    p->scratch = calloc(p->threads, sizeof *p->scratch);
    if (!p->scratch)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory for %u workers", p->threads);
    struct vt_fregion big;
    max_region(p, 0, &big);
    for (unsigned i = 0; i < p->threads; i++) {
        struct vt_pyramid_pass_scratch *s = &p->scratch[i];
        int rc = vt_image_alloc(&s->in, big.width, big.height, p->channels, p->sample, err);
        if (rc == 0)
            rc = vt_image_alloc(&s->tile_full, pp, pp, p->channels, o->out_sample, err);
        if (rc == 0)
            rc = vt_image_alloc(&s->tile, pp, pp, o->out_channels, o->out_sample, err);
        if (rc)
            return rc;
        s->seg_cap = (size_t)big.width + 4;
        s->xs = calloc(s->seg_cap, sizeof *s->xs);
        s->ys = calloc(s->seg_cap, sizeof *s->ys);
        bool ok = s->xs && s->ys;
        size_t floats = 0;
        for (uint32_t r = 0; ok && r <= p->depth; r++) {
            struct vt_fregion reg;
            max_region(p, r, &reg);
            if (r == 0 && !p->source_is_working) /* a band of rows, see reduce_from_native */
                reg.height = s->band_rows =
                    2 * VT_PYRAMID_PASS_BAND_ROWS + (uint32_t)p->kernel.count;
            if (r > 0 || !p->source_is_working) {
                size_t n;
                ok = vt_size_mul3(reg.width, reg.height, p->channels, &n) &&
                     (s->w[r].px = malloc(n * sizeof(float))) != NULL;
            }
            if (r > 0) {
                struct vt_fregion fine;
                max_region(p, r - 1, &fine);
                size_t need = vt_filter_reduce_scratch(&p->kernel, &fine, &reg);
                floats = need > floats ? need : floats;
            }
        }
        s->reduce_floats = floats;
        if (ok && floats)
            ok = (s->reduce_scratch = malloc(floats * sizeof(float))) != NULL;
        if (!ok)
            return vt_error_set(err, VTS_ERR_NOMEM,
                                "out of memory for the working blocks of %ux%u texels", big.width,
                                big.height);
    }
    return 0;
}

static bool next_block(void *ctx, uint64_t *job)
{
    struct vt_pyramid_pass *p = ctx;
    if (p->next_bx >= p->bx1)
        return false;
    *job = p->next_bx++;
    return true;
}

static int run_block(void *ctx, unsigned worker, uint64_t job, struct vts_error *err)
{
    struct vt_pyramid_pass *p = ctx;
    return vt_pyramid_block_run(p, worker, (uint32_t)job, p->row, err);
}

static int report_progress(void *ctx)
{
    struct vt_pyramid_pass *p = ctx;
    if (!p->o->progress)
        return 0;
    return p->o->progress(p->o->user, __atomic_load_n(p->done, __ATOMIC_RELAXED), p->total);
}

int vt_pyramid_pass_run(struct vt_pyramid_pass *p, struct vts_error *err)
{
    const struct vt_pyramid_options *o = p->o;
    uint32_t km = vt_kernel_margin(&p->kernel);
    p->margin[p->depth] = o->border_px;
    for (uint32_t r = p->depth; r-- > 0;) {
        uint32_t m = 2 * p->margin[r + 1] + km;
        p->margin[r] = m > o->border_px ? m : o->border_px;
    }
    p->blocks_x = (uint32_t)((p->w + p->block - 1) / p->block);
    p->blocks_y = (uint32_t)((p->h + p->block - 1) / p->block);
    bool part = o->part && p->base == 0 && !o->resume_input;
    p->bx0 = part ? o->part_x0 : 0;
    p->bx1 = part ? (o->part_x1 < p->blocks_x ? o->part_x1 : p->blocks_x) : p->blocks_x;
    p->by0 = part ? o->part_y0 : 0;
    p->by1 = part ? (o->part_y1 < p->blocks_y ? o->part_y1 : p->blocks_y) : p->blocks_y;
    if (p->bx0 >= p->bx1 || p->by0 >= p->by1) /* an empty part */
        return 0;
    int rc = scratch_alloc(p, err);
    static const struct vt_pool_fns fns = {next_block, run_block, report_progress};
    for (uint32_t by = p->by0; rc == 0 && by < p->by1; by++) {
        if (p->sequential) {
            struct vt_fregion r0;
            vt_pyramid_block_region(p, 0, by, 0, &r0);
            int64_t a = r0.y0, b = r0.y0 + r0.height;
            if (o->wrap && (a < 0 || b > p->h))
                a = 0, b = p->h; /* wrapped rows come from both ends: hold the whole image */
            a = a < 0 ? 0 : a;
            b = b > p->h ? p->h : b;
            rc = vt_pyramid_read_band_move(p, a, b, err);
        }
        p->row = by;
        p->next_bx = p->bx0;
        if (rc == 0)
            rc = vt_pool_run(p->threads, &fns, p, err);
    }
    scratch_free(p);
    vt_image_release(&p->band.img);
    p->band.valid = false;
    return rc;
}
