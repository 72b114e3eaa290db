/* Running one pass of the mip pyramid (see internal/vt_pyramid_pass.h). */
#include "internal/vt_pyramid_pass.h"

#include <stdlib.h>

#include "internal/vt_pyramid_block.h"
#include "internal/vt_pyramid_read.h"
#include "vt_error.h"
#include "vt_pool.h"

/* What running the pass takes beyond its description: the pool's jobs and the workers' memory. */
struct pass_run {
    const struct vt_pyramid_pass *p;
    struct vt_source *const *sources;
    bool sequential;
    struct vt_pyramid_read_band band; /* sequential sources: the rows the current block row reads */
    struct vt_pyramid_block_scratch *scratch; /* one per worker */
    unsigned threads;
    uint64_t total;
    uint32_t row, row1;         /* the block row of the next job, the end of the rows run */
    uint32_t next_bx, bx0, bx1; /* the next job's block in its row, the blocks of a row */
};

static void scratch_free(struct pass_run *run)
{
    for (unsigned i = 0; run->scratch && i < run->threads; i++)
        vt_pyramid_block_scratch_release(run->p, &run->scratch[i]);
    free(run->scratch);
    run->scratch = NULL;
}

static int scratch_alloc(struct pass_run *run, struct vts_error *err)
{
    run->scratch = calloc(run->threads, sizeof *run->scratch);
    if (!run->scratch)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory for %u workers", run->threads);
    for (unsigned i = 0; i < run->threads; i++) {
        int rc = vt_pyramid_block_scratch_alloc(run->p, &run->scratch[i], err);
        if (rc)
            return rc;
    }
    return 0;
}

/* Jobs are blocks in row-major order: of one block row for a sequential source (the band holds
 * that row's texels), of all rows [row, row1) otherwise (no wait at the end of each row). */
static bool next_block(void *ctx, uint64_t *job)
{
    struct pass_run *run = ctx;
    if (run->next_bx >= run->bx1) {
        if (run->row + 1 >= run->row1)
            return false;
        run->row++;
        run->next_bx = run->bx0;
    }
    *job = (uint64_t)run->row << 32 | run->next_bx++;
    return true;
}

static int run_block(void *ctx, unsigned worker, uint64_t job, struct vts_error *err)
{
    struct pass_run *run = ctx;
    struct vt_source *src = run->sequential ? &run->band.source : run->sources[worker];
    return vt_pyramid_block_run(run->p, &run->scratch[worker], src, worker, (uint32_t)job,
                                (uint32_t)(job >> 32), err);
}

static int report_progress(void *ctx)
{
    struct pass_run *run = ctx;
    const struct vt_pyramid_options *o = run->p->o;
    if (!o->progress)
        return 0;
    return o->progress(o->user, __atomic_load_n(run->p->done, __ATOMIC_RELAXED), run->total);
}

/* Moves the band down to the rows block row `by` reads (all of them with wrap at an edge). */
static int move_band(struct pass_run *run, uint32_t by, struct vts_error *err)
{
    const struct vt_pyramid_pass *p = run->p;
    struct vt_fregion r0;
    vt_pyramid_block_region(p, 0, by, 0, &r0);
    int64_t a = r0.y0, b = r0.y0 + r0.height;
    if (p->o->wrap && (a < 0 || b > p->h))
        a = 0, b = p->h; /* wrapped rows come from both ends: hold the whole image */
    a = a < 0 ? 0 : a;
    b = b > p->h ? p->h : b;
    return vt_pyramid_read_band_move(&run->band, run->sources[0], a, b, err);
}

int vt_pyramid_pass_run(struct vt_pyramid_pass *p, struct vt_source *const *sources,
                        bool sequential, unsigned threads, uint64_t total, struct vts_error *err)
{
    const struct vt_pyramid_options *o = p->o;
    uint32_t km = vt_kernel_margin(&p->kernel);
    p->margin[p->depth] = o->border_px;
    for (uint32_t r = p->depth; r-- > 0;) {
        uint32_t m = 2 * p->margin[r + 1] + km;
        p->margin[r] = m > o->border_px ? m : o->border_px;
    }
    uint32_t blocks_x = (uint32_t)((p->w + p->block - 1) / p->block);
    uint32_t blocks_y = (uint32_t)((p->h + p->block - 1) / p->block);
    bool part = o->part && p->base == 0 && !o->resume_input;
    struct pass_run run = {.p = p,
                           .sources = sources,
                           .sequential = sequential,
                           .threads = threads,
                           .total = total,
                           .bx0 = part ? o->part_x0 : 0,
                           .bx1 =
                               part ? (o->part_x1 < blocks_x ? o->part_x1 : blocks_x) : blocks_x};
    uint32_t by0 = part ? o->part_y0 : 0;
    uint32_t by1 = part ? (o->part_y1 < blocks_y ? o->part_y1 : blocks_y) : blocks_y;
    if (run.bx0 >= run.bx1 || by0 >= by1) /* an empty part */
        return 0;
    if (sequential)
        vt_pyramid_read_band_init(&run.band, sources[0]);
    int rc = scratch_alloc(&run, err);
    static const struct vt_pool_fns fns = {next_block, run_block, report_progress};
    /* a sequential source: one pool run per block row, the band moved down between them */
    for (uint32_t by = by0; rc == 0 && by < by1; by = sequential ? by + 1 : by1) {
        if (sequential)
            rc = move_band(&run, by, err);
        run.row = by;
        run.row1 = sequential ? by + 1 : by1;
        run.next_bx = run.bx0;
        if (rc == 0)
            rc = vt_pool_run(threads, &fns, &run, err);
    }
    scratch_free(&run);
    vt_pyramid_read_band_release(&run.band);
    return rc;
}
