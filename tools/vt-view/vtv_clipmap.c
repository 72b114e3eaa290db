/* vt-view --clipmap: the clipmap's state, its loads within the budget, and its statistics. */
#include "vtv_clipmap.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vt_checked.h"
#include "vtv_wide.h"

int vtv_clipmap_init(struct vtv_clipmap *c, const struct vts_store *store, uint32_t layer,
                     const struct vtv_clipmap_options *opt, unsigned display_features,
                     struct vts_error *err)
{
    memset(c, 0, sizeof(*c));
    c->store = store;
    c->layer = layer;
    c->opt = *opt;
    const struct vts_geometry *g = vts_store_geometry(store);
    const struct vts_layer *info = vts_store_layer(store, layer);
    struct vtv_texel_format texels;
    vtv_wide_format(info, &texels); /* what vtv_loader hands over (BC decoded on the CPU unless
                                       opt->bc_format) */
    int st = vts_clipmap_init(&c->cm, g, opt->n, err);
    if (st == 0 && opt->bc_format) /* the blocks as stored */
        st = vtv_clipmap_gl_init_bc(&c->gl, opt->n, g->tile_content_px, c->cm.level_count,
                                    (GLenum)opt->bc_format, opt->rebuild_z, display_features, err);
    else if (st == 0)
        st = vtv_clipmap_gl_init(&c->gl, opt->n, g->tile_content_px, c->cm.level_count, &texels,
                                 info->colour == VTS_COLOUR_SRGB, display_features, err);
    if (st != 0)
        return st;
    uint64_t tile_bytes = c->gl.tile_bytes;
    if (opt->budget < tile_bytes)
        return vt_error_set(err, VTS_ERR_ARG,
                            "--budget %llu: below one tile's upload (%llu bytes: %u x %u texels%s)",
                            (unsigned long long)opt->budget, (unsigned long long)tile_bytes,
                            g->tile_content_px, g->tile_content_px,
                            opt->bc_format ? ", BC blocks" : "");
    uint64_t max = opt->budget / tile_bytes;
    c->max_tiles = max > (1u << 20) ? 1u << 20 : (uint32_t)max;
    c->loader = vtv_loader_create(store, layer, opt->sync ? 0 : opt->threads,
                                  opt->bc_format ? VTV_LOADER_COMPRESSED : 0u, err);
    if (!c->loader)
        return err->status;
    uint32_t qcap = vtv_loader_queue_capacity(c->loader);
    c->plan_cap = opt->sync ? c->max_tiles : qcap;
    c->plan = calloc(c->plan_cap, sizeof(*c->plan));
    c->queue_index = calloc(qcap, sizeof(*c->queue_index));
    c->queue_lxy = calloc((size_t)qcap * 3, sizeof(*c->queue_lxy));
    c->dropped = calloc(qcap, sizeof(*c->dropped));
    c->zero = calloc((size_t)tile_bytes, 1);
    c->frames = calloc(opt->frames_cap ? opt->frames_cap : 1, sizeof(*c->frames));
    if (!c->plan || !c->queue_index || !c->queue_lxy || !c->dropped || !c->zero || !c->frames)
        return vt_error_set(err, VTS_ERR_NOMEM, "out of memory");
    return 0;
}

void vtv_clipmap_free(struct vtv_clipmap *c)
{
    vtv_loader_destroy(c->loader);
    vtv_clipmap_gl_free(&c->gl);
    vts_clipmap_free(&c->cm);
    free(c->plan);
    free(c->queue_index);
    free(c->queue_lxy);
    free(c->dropped);
    free(c->zero);
    free(c->frames);
    free(c->list);
    memset(c, 0, sizeof(*c));
}

static bool in_rect(const struct vts_tile_rect *r, uint32_t x, uint32_t y)
{
    return x >= r->x0 && x < r->x1 && y >= r->y0 && y < r->y1;
}

/* True when slot of tile (x, y) of level holds it. */
static bool in_slot(const struct vts_clipmap *cm, uint32_t level, uint32_t x, uint32_t y)
{
    const struct vts_clipmap_level *lv = &cm->levels[level];
    uint32_t sx, sy;
    vts_clipmap_slot(cm, x, y, &sx, &sy);
    return lv->slot_tile[(size_t)sy * cm->n + sx] == (uint64_t)y * lv->tiles_x + x;
}

static uint64_t tile_id(uint32_t level, uint32_t x, uint32_t y)
{
    return (uint64_t)level << 56 | (uint64_t)y << 28 | x;
}

/* Uploads a finished load into its slot and records it; 0 or VTS_ERR_NOMEM. */
static int apply(struct vtv_clipmap *c, struct vtv_load *ld, struct vtv_clipmap_frame *f)
{
    const struct vts_geometry *g = vts_store_geometry(c->store);
    struct vts_clipmap_tile t = {.level = ld->level, .x = ld->x, .y = ld->y};
    vts_clipmap_slot(&c->cm, t.x, t.y, &t.slot_x, &t.slot_y);
    if (ld->status != 0) { /* shown as zeros, counted, not read again */
        if (!c->failed++)
            snprintf(c->error, sizeof(c->error), "%s", ld->error);
    }
    const uint8_t *px = ld->status == 0 && !ld->empty ? ld->rgba : NULL;
    vtv_clipmap_gl_upload(&c->gl, t.level, t.slot_x, t.slot_y, px, g->tile_payload_px, g->border_px,
                          c->zero);
    vts_clipmap_loaded(&c->cm, &t);
    f->tiles++;
    f->bytes += c->gl.tile_bytes;
    if (c->frame_count >= c->opt.frames_cap)
        return 0; /* past the frames whose statistics are kept (a window: none) */
    if (!vt_array_grow((void **)&c->list, &c->list_cap, c->list_count + 1, sizeof(*c->list), 1024))
        return VTS_ERR_NOMEM;
    uint32_t *e = c->list[c->list_count++];
    e[0] = t.level;
    e[1] = t.x;
    e[2] = t.y;
    return 0;
}

static int load_sync(struct vtv_clipmap *c, struct vtv_clipmap_frame *f)
{
    uint32_t n = vts_clipmap_plan(&c->cm, c->plan, c->max_tiles);
    for (uint32_t i = 0; i < n; i++) {
        const struct vts_clipmap_tile *t = &c->plan[i];
        struct vtv_load *ld =
            vtv_loader_load_now(c->loader, tile_id(t->level, t->x, t->y), t->level, t->x, t->y);
        if (!ld)
            return VTS_ERR_NOMEM;
        f->reads++;
        int st = apply(c, ld, f);
        vtv_loader_release(c->loader, ld);
        if (st != 0)
            return st;
    }
    return 0;
}

/* Loader threads: finished loads still wanted (in their target, slot not yet holding them) are
 * uploaded, at most max_tiles per frame; then the plan replaces the loader's queue. */
static int load_async(struct vtv_clipmap *c, struct vtv_clipmap_frame *f)
{
    struct vtv_load *done = vtv_loader_take(c->loader, UINT32_MAX);
    int st = 0;
    for (struct vtv_load *ld = done; ld && st == 0; ld = ld->next) {
        f->reads++;
        bool wanted = ld->level < c->cm.level_count &&
                      in_rect(&c->cm.levels[ld->level].back, ld->x, ld->y) &&
                      !in_slot(&c->cm, ld->level, ld->x, ld->y);
        if (wanted && f->tiles < c->max_tiles)
            st = apply(c, ld, f);
    }
    vtv_loader_release(c->loader, done);
    if (st != 0)
        return st;
    uint32_t n = vts_clipmap_plan(&c->cm, c->plan, c->plan_cap);
    for (uint32_t i = 0; i < n; i++) {
        c->queue_index[i] = tile_id(c->plan[i].level, c->plan[i].x, c->plan[i].y);
        c->queue_lxy[3 * i] = c->plan[i].level;
        c->queue_lxy[3 * i + 1] = c->plan[i].x;
        c->queue_lxy[3 * i + 2] = c->plan[i].y;
    }
    vtv_loader_submit(c->loader, c->queue_index, c->queue_lxy, n, c->dropped);
    return 0;
}

int vtv_clipmap_update(struct vtv_clipmap *c, double cx, double cy, struct vtv_clipmap_frame *out)
{
    struct vtv_clipmap_frame f = {0};
    if (c->opt.centre_fixed) {
        cx = c->opt.centre[0];
        cy = c->opt.centre[1];
    }
    f.centre[0] = cx;
    f.centre[1] = cy;
    f.first = c->list_count;
    /* the paging centre, the same for every level in its texels (scaled by 2^-l) */
    for (uint32_t l = 0; l < c->cm.level_count; l++) {
        struct vts_tile_rect w;
        double k = ldexp(1.0, -(int)l);
        vts_clipmap_window(&c->cm, l, cx * k, cy * k, &w);
        vts_clipmap_move(&c->cm, l, &w);
    }
    struct vts_tile_rect strips[VTS_MAX_LEVELS][4];
    uint32_t strip_count[VTS_MAX_LEVELS];
    for (uint32_t l = 0; l < c->cm.level_count; l++)
        strip_count[l] =
            vts_clipmap_strips(&c->cm.levels[l].front, &c->cm.levels[l].back, strips[l]);
    int st = c->opt.sync ? load_sync(c, &f) : load_async(c, &f);
    if (st != 0)
        return st;
    for (uint32_t l = 0; l < c->cm.level_count; l++) {
        for (uint32_t s = 0; s < strip_count[l]; s++) {
            const struct vts_tile_rect *r = &strips[l][s];
            bool whole = true;
            for (uint32_t y = r->y0; y < r->y1 && whole; y++)
                for (uint32_t x = r->x0; x < r->x1 && whole; x++)
                    whole = in_slot(&c->cm, l, x, y);
            f.strips += whole;
        }
        f.levels_complete += vts_clipmap_complete(&c->cm, l);
        f.front[l] = c->cm.levels[l].front;
    }
    if (c->frame_count < c->opt.frames_cap)
        c->frames[c->frame_count++] = f;
    *out = f;
    return 0;
}
