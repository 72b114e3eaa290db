/* The mip pyramid driver: plans, shard parts, option checks and the pass loop (see vt_pyramid.h;
 * a pass runs in vt_pyramid_pass.c, its blocks in vt_pyramid_block.c: internal/vt_pyramid_impl.h).
 */
#include "vt_pyramid.h"

#include <stdlib.h>

#include "internal/vt_float_file.h"
#include "internal/vt_pyramid_impl.h"
#include "internal/vt_pyramid_pass.h"
#include "internal/vt_shard_seams.h"
#include "internal/vt_tile_cache.h"
#include "vt_error.h"

#define INPUT_CACHE_BYTES (48u << 20) /* decoded input tiles shared by the workers */

void vt_pyramid_plan(const struct vt_pyramid_options *o, struct vt_pyramid_plan *out)
{
    uint32_t k = vt_pyramid_resolved_k(o);
    uint64_t block = (uint64_t)o->tile_content_px << k;
    *out = (struct vt_pyramid_plan){.levels_per_pass = k,
                                    .has_next = o->level_count > k + 1,
                                    .block = block,
                                    .blocks_x = (uint32_t)((o->width + block - 1) / block),
                                    .blocks_y = (uint32_t)((o->height + block - 1) / block)};
    if (out->has_next) {
        out->carry_width = vt_pyramid_level_extent(o->width, k);
        out->carry_height = vt_pyramid_level_extent(o->height, k);
    }
}

bool vt_pyramid_part(const struct vt_pyramid_plan *plan, uint32_t index, uint32_t count,
                     uint32_t *x0, uint32_t *y0, uint32_t *x1, uint32_t *y1)
{
    if (count == 0 || (count & (count - 1)) != 0 || index >= count)
        return false;
    uint32_t m = 0;
    while ((1u << m) < count)
        m++;
    uint32_t gx = 1u << ((m + 1) / 2), gy = 1u << (m / 2);
    uint32_t px = (plan->blocks_x + gx - 1) / gx, py = (plan->blocks_y + gy - 1) / gy;
    uint32_t col = index % gx, row = index / gx;
    uint64_t a = (uint64_t)col * px, b = (uint64_t)(col + 1) * px;
    *x0 = (uint32_t)(a < plan->blocks_x ? a : plan->blocks_x);
    *x1 = (uint32_t)(b < plan->blocks_x ? b : plan->blocks_x);
    a = (uint64_t)row * py, b = (uint64_t)(row + 1) * py;
    *y0 = (uint32_t)(a < plan->blocks_y ? a : plan->blocks_y);
    *y1 = (uint32_t)(b < plan->blocks_y ? b : plan->blocks_y);
    return true;
}

bool vt_pyramid_part_cuts(const struct vt_pyramid_plan *plan, uint32_t count, uint32_t *xcuts,
                          uint32_t *gx, uint32_t *ycuts, uint32_t *gy)
{
    uint32_t x0, y0, x1, y1, m = 0;
    if (count == 0 || (count & (count - 1)) != 0 || count > 4096)
        return false;
    while ((1u << m) < count)
        m++;
    *gx = 1u << ((m + 1) / 2);
    *gy = 1u << (m / 2);
    for (uint32_t i = 0; i < *gx; i++) {
        vt_pyramid_part(plan, i, count, &x0, &y0, &x1, &y1);
        xcuts[i] = x0;
        xcuts[i + 1] = x1;
    }
    for (uint32_t j = 0; j < *gy; j++) {
        vt_pyramid_part(plan, j * *gx, count, &x0, &y0, &x1, &y1);
        ycuts[j] = y0;
        ycuts[j + 1] = y1;
    }
    return true;
}

bool vt_pyramid_part_seams(const struct vt_pyramid_options *o)
{
    return o->part_count > 0 && !o->wrap && o->level_count > vt_pyramid_resolved_k(o) + 1;
}

/* The seams of a shard's build (vt_shard_seams.h) and its column and row in the part grid. */
static struct vt_seams *part_seams(const struct vt_pyramid_options *o,
                                   const struct vt_source_info *in, uint32_t *col, uint32_t *row,
                                   struct vts_error *err)
{
    struct vt_pyramid_plan plan;
    uint32_t xcuts[65], ycuts[65], gx, gy;
    vt_pyramid_plan(o, &plan);
    if (!vt_pyramid_part_cuts(&plan, o->part_count, xcuts, &gx, ycuts, &gy) ||
        o->part_index >= o->part_count) {
        vt_error_set(err, VTS_ERR_ARG, "invalid shard part %u of %u", o->part_index, o->part_count);
        return NULL;
    }
    *col = o->part_index % gx;
    *row = o->part_index / gx;
    return vt_seams_create(o, in, xcuts, gx, ycuts, gy, err);
}

/* Tiles of a level-r axis that blocks [b0, b1) own (the whole axis: 0 .. blocks). */
static uint64_t part_tiles(uint32_t size, uint32_t r, uint64_t block, uint32_t c, uint32_t b0,
                           uint32_t b1)
{
    uint64_t s = block >> r, extent = vt_pyramid_level_extent(size, r);
    uint64_t tiles_end = (extent + c - 1) / c * c, c0 = (uint64_t)b0 * s, c1 = (uint64_t)b1 * s;
    c1 = c1 < tiles_end ? c1 : tiles_end;
    return c0 < c1 ? (c1 - c0 + c - 1) / c : 0;
}

uint64_t vt_pyramid_tile_count(const struct vt_pyramid_options *o)
{
    struct vt_pyramid_plan plan;
    vt_pyramid_plan(o, &plan);
    uint32_t k = plan.levels_per_pass, first = o->resume_input ? k + 1 : 0;
    uint64_t n = 0;
    for (uint32_t l = first; l < o->level_count; l++) {
        uint64_t tx =
            (vt_pyramid_level_extent(o->width, l) + o->tile_content_px - 1) / o->tile_content_px;
        uint64_t ty =
            (vt_pyramid_level_extent(o->height, l) + o->tile_content_px - 1) / o->tile_content_px;
        if (o->part) {
            if (l > k)
                break;
            tx = part_tiles(o->width, l, plan.block, o->tile_content_px, o->part_x0, o->part_x1);
            ty = part_tiles(o->height, l, plan.block, o->tile_content_px, o->part_y0, o->part_y1);
        }
        n += tx * ty;
    }
    uint32_t col, row;
    struct vt_source_info info = {.channels = 1};
    struct vt_seams *seams =
        o->part && vt_pyramid_part_seams(o) ? part_seams(o, &info, &col, &row, NULL) : NULL;
    if (seams)
        n += vt_seams_tile_count(seams, col, row);
    vt_seams_destroy(seams);
    return n;
}

static int check_options(struct vt_source *const *sources, const struct vt_pyramid_options *o,
                         struct vts_error *err)
{
    const struct vt_source_info *in = o->resume_input ? o->resume_input : &sources[0]->info;
    uint32_t full = vts_full_level_count(o->width, o->height, o->tile_content_px);
    if (!o->emit || o->threads < 1 || o->tile_content_px == 0 || o->level_count == 0 ||
        o->level_count > full ||
        (!o->resume_input && (in->width != o->width || in->height != o->height)) ||
        vts_sample_bytes(o->out_sample) == 0 || in->channels < 1 || in->channels > 4 ||
        (o->part && o->resume_input) ||
        (o->part && o->level_count > vt_pyramid_resolved_k(o) + 1 &&
         !(vt_pyramid_part_seams(o) ? o->seam_carry != NULL : o->carry != NULL)) ||
        (o->part_count && o->part_index >= o->part_count))
        return vt_error_set(err, VTS_ERR_ARG, "invalid pyramid options");
    if (o->resume_input) {
        struct vt_pyramid_plan plan;
        vt_pyramid_plan(o, &plan);
        const struct vt_source_info *r = &sources[0]->info;
        if (!plan.has_next || r->width != plan.carry_width || r->height != plan.carry_height ||
            r->channels != in->channels || r->sample != VTS_SAMPLE_F32)
            return vt_error_set(
                err, VTS_ERR_ARG,
                "'%s': %ux%u texels of %u channels, %s, cannot resume a %ux%u build of %u channels at level %u",
                sources[0]->name, r->width, r->height, r->channels, vts_sample_name(r->sample),
                o->width, o->height, in->channels, plan.levels_per_pass);
        for (unsigned i = 0; i < o->threads; i++)
            if (!sources[i])
                return vt_error_set(err, VTS_ERR_ARG, "resuming needs one source per worker");
    }
    if (o->out_channels != in->channels && !(in->has_alpha && o->out_channels == in->channels - 1))
        return vt_error_set(err, VTS_ERR_ARG, "cannot make %u channels from %u", o->out_channels,
                            in->channels);
    if (o->tile_content_px + 2ull * o->border_px > VTS_MAX_PAYLOAD_PX)
        return vt_error_set(err, VTS_ERR_LIMIT, "tile payload is larger than %u px",
                            VTS_MAX_PAYLOAD_PX);
    for (unsigned i = 0; !in->sequential && i < o->threads; i++)
        if (!sources[i])
            return vt_error_set(err, VTS_ERR_ARG,
                                "a random-access input needs one source per worker");
    return 0;
}

/* The first pass's description: from the input, or as after the first pass when resuming (its
 * last level, in working space, is the source). */
static void first_pass(const struct vt_pyramid_options *o, const struct vt_source_info *in,
                       uint64_t *done, struct vt_pyramid_pass *p)
{
    uint32_t k = vt_pyramid_resolved_k(o);
    *p = (struct vt_pyramid_pass){.o = o,
                                  .emit_base = true,
                                  .w = o->width,
                                  .h = o->height,
                                  .channels = in->channels,
                                  .sample = in->sample,
                                  .has_alpha = in->has_alpha,
                                  .block = (uint64_t)o->tile_content_px << k,
                                  .done = done};
    /* premultiply while filtering, unless the input already is (then it is filtered and stored
     * premultiplied, and the layer says so) */
    p->mode =
        (struct vt_pixel_mode){in->channels, o->colour,
                               in->has_alpha && !in->premultiplied && o->colour != VTS_COLOUR_DATA};
    vt_kernel_init(&p->kernel, o->filter);
    if (o->resume_input) {
        p->source_is_working = true;
        p->emit_base = false;
        p->base = k;
        p->w = vt_pyramid_level_extent(o->width, k);
        p->h = vt_pyramid_level_extent(o->height, k);
        p->sample = VTS_SAMPLE_F32;
    }
}

/* A shard's levels above its first pass, from its texels of the first pass's last level. */
static int shard_seams(const struct vt_pyramid_options *o, const struct vt_source_info *in,
                       struct vt_float_file *level_k, uint64_t *done, struct vts_error *err)
{
    uint32_t col, row;
    struct vt_seams *s = part_seams(o, in, &col, &row, err);
    if (!s)
        return err ? err->status : VTS_ERR_NOMEM;
    int rc = vt_seams_shard_run(s, col, row, level_k, done, err);
    vt_seams_destroy(s);
    return rc;
}

int vt_pyramid_build(struct vt_source *const *sources, const struct vt_pyramid_options *o,
                     struct vts_error *err)
{
    int rc = check_options(sources, o, err);
    if (rc)
        return rc;
    const struct vt_source_info *in = o->resume_input ? o->resume_input : &sources[0]->info;
    uint32_t k = vt_pyramid_resolved_k(o);
    uint64_t done = 0, total = vt_pyramid_tile_count(o);
    struct vt_pyramid_pass p;
    first_pass(o, in, &done, &p);
    bool sequential = in->sequential && !o->resume_input;
    bool seams = o->part && vt_pyramid_part_seams(o);
    struct vt_source *const *pass_sources = sources;
    struct vt_float_file *prev = NULL;
    struct vt_source temp_source = {0};
    struct vt_source **temp_sources = NULL;
    /* tiled inputs: workers share decoded tiles, so block margins do not decode tiles twice */
    struct vt_source cached[256], *cached_ptrs[256];
    struct vt_tile_cache *cache = NULL;
    if (!o->resume_input && !in->sequential && in->tile_w && in->tile_h && o->threads <= 256) {
        cache = vt_tile_cache_create(sources, o->threads, INPUT_CACHE_BYTES, cached, err);
        if (!cache)
            return err ? err->status : VTS_ERR_NOMEM;
        for (unsigned i = 0; i < o->threads; i++)
            cached_ptrs[i] = &cached[i];
        pass_sources = cached_ptrs;
    }
    for (;;) {
        uint32_t left = o->level_count - 1 - p.base;
        p.depth = left < k ? left : k;
        p.next = NULL;
        p.carry = o->part && !seams && p.depth < left;
        if (p.depth < left && (!o->part || seams)) {
            p.next = vt_float_file_create(o->temp_dir, vt_pyramid_level_extent(p.w, p.depth),
                                          vt_pyramid_level_extent(p.h, p.depth), p.channels,
                                          o->tile_content_px, err);
            if (!p.next) {
                rc = err ? err->status : VTS_ERR_IO;
                break;
            }
        }
        rc = vt_pyramid_pass_run(&p, pass_sources, sequential, o->threads, total, err);
        vt_tile_cache_destroy(cache); /* only pass 0 reads the input */
        cache = NULL;
        vt_source_close(&temp_source);
        vt_float_file_destroy(prev);
        prev = p.next;
        if (rc == 0 && seams && p.next)
            rc = shard_seams(o, in, p.next, &done, err);
        if (rc || !p.next || o->part) /* a shard stops after its first pass (and its seams) */
            break;
        /* the next pass reads this pass's last level, already in working space */
        free(temp_sources);
        temp_sources = calloc(o->threads, sizeof *temp_sources);
        if (!temp_sources) {
            rc = vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
            break;
        }
        vt_float_file_source(p.next, o->colour, in->has_alpha, &temp_source, err);
        for (unsigned i = 0; i < o->threads; i++)
            temp_sources[i] = &temp_source;
        pass_sources = temp_sources;
        sequential = false;
        p.source_is_working = true;
        p.emit_base = false;
        p.base += p.depth;
        p.w = vt_pyramid_level_extent(p.w, p.depth);
        p.h = vt_pyramid_level_extent(p.h, p.depth);
        p.sample = VTS_SAMPLE_F32;
    }
    vt_tile_cache_destroy(cache);
    vt_source_close(&temp_source);
    vt_float_file_destroy(prev);
    free(temp_sources);
    return rc;
}
