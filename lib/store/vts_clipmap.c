/* Clipmap arithmetic over a store's pyramid (include/vts/vts_clipmap.h, docs/clipmap.md): snapped
 * windows, toroidal slots, the strips a move exposes, and each level's front (loaded) and back
 * (target) windows. Pure computation, libc only. */
#include "vts_clipmap.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vt_checked.h"
#include "vt_error.h"

static bool rect_empty(const struct vts_tile_rect *r)
{
    return r->x0 >= r->x1 || r->y0 >= r->y1;
}

static uint32_t max_u32(uint32_t a, uint32_t b)
{
    return a > b ? a : b;
}

static uint32_t min_u32(uint32_t a, uint32_t b)
{
    return a < b ? a : b;
}

/* a ∩ b, {0} when empty. */
static struct vts_tile_rect rect_intersect(const struct vts_tile_rect *a,
                                           const struct vts_tile_rect *b)
{
    struct vts_tile_rect r = {max_u32(a->x0, b->x0), max_u32(a->y0, b->y0), min_u32(a->x1, b->x1),
                              min_u32(a->y1, b->y1)};
    if (rect_empty(a) || rect_empty(b) || rect_empty(&r))
        memset(&r, 0, sizeof r);
    return r;
}

void vts_clipmap_free(struct vts_clipmap *c)
{
    if (!c)
        return;
    for (uint32_t l = 0; l < VTS_MAX_LEVELS; l++)
        free(c->levels[l].slot_tile);
    memset(c, 0, sizeof *c);
}

int vts_clipmap_init(struct vts_clipmap *c, const struct vts_geometry *g, uint32_t n,
                     struct vts_error *err)
{
    if (!c)
        return vt_error_set(err, VTS_ERR_ARG, "clipmap: no clipmap to set up");
    memset(c, 0, sizeof *c);
    if (!g)
        return vt_error_set(err, VTS_ERR_ARG, "clipmap: no store geometry");
    if (n < 1 || n > VTS_CLIPMAP_MAX_N)
        return vt_error_set(err, VTS_ERR_ARG, "clipmap: window of %u tiles is outside 1..%u", n,
                            VTS_CLIPMAP_MAX_N);
    struct vts_error gerr = {0};
    int rc = vts_geometry_check(g, &gerr);
    if (rc < 0)
        return vt_error_set(err, VTS_ERR_ARG, "clipmap: invalid store geometry: %s", gerr.message);
    size_t slots;
    if (!vt_size_mul(n, n, &slots) || !vt_size_mul(slots, sizeof(uint64_t), &slots))
        return vt_error_set(err, VTS_ERR_LIMIT, "clipmap: %u x %u slots overflow", n, n);
    c->n = n;
    c->content_px = g->tile_content_px;
    for (uint32_t l = 0; l < g->level_count; l++) {
        struct vts_level lv;
        vts_geometry_level(g, l, &lv);
        struct vts_clipmap_level *cl = &c->levels[l];
        cl->width = lv.width;
        cl->height = lv.height;
        cl->tiles_x = lv.tiles_x;
        cl->tiles_y = lv.tiles_y;
        cl->slot_tile = malloc(slots);
        if (!cl->slot_tile) {
            vts_clipmap_free(c);
            return vt_error_set(err, VTS_ERR_NOMEM, "clipmap: cannot allocate %zu bytes of slots",
                                slots);
        }
        /* all bits set = UINT64_MAX: every slot free */
        memset(cl->slot_tile, 0xff, slots);
        c->level_count = l + 1;
    }
    return 0;
}

/* The snapped window's first tile on one axis: floor(centre / C - n / 2 + 1/2) clamped to
 * 0 .. tiles - n (0 when the level has at most n tiles). */
static uint32_t window_start(double centre_px, uint32_t content_px, uint32_t n, uint32_t tiles)
{
    if (tiles <= n)
        return 0;
    if (!isfinite(centre_px))
        centre_px = 0;
    double start = centre_px / content_px - n / 2.0 + 0.5;
    uint32_t last = tiles - n;
    if (!(start > 0))
        return 0;
    if (start >= (double)last) /* floor(start) >= last, last being an integer */
        return last;
    return (uint32_t)start; /* 0 < start < 2^32: truncation is floor (and no libm) */
}

int vts_clipmap_window(const struct vts_clipmap *c, uint32_t level, double cx, double cy,
                       struct vts_tile_rect *out)
{
    memset(out, 0, sizeof *out);
    if (!c || level >= c->level_count)
        return VTS_ERR_RANGE;
    const struct vts_clipmap_level *cl = &c->levels[level];
    out->x0 = window_start(cx, c->content_px, c->n, cl->tiles_x);
    out->y0 = window_start(cy, c->content_px, c->n, cl->tiles_y);
    out->x1 = min_u32(out->x0 + c->n, cl->tiles_x);
    out->y1 = min_u32(out->y0 + c->n, cl->tiles_y);
    return 0;
}

void vts_clipmap_slot(const struct vts_clipmap *c, uint32_t x, uint32_t y, uint32_t *slot_x,
                      uint32_t *slot_y)
{
    *slot_x = c->n ? x % c->n : 0;
    *slot_y = c->n ? y % c->n : 0;
}

uint32_t vts_clipmap_strips(const struct vts_tile_rect *from, const struct vts_tile_rect *to,
                            struct vts_tile_rect out[4])
{
    if (rect_empty(to))
        return 0;
    struct vts_tile_rect in = rect_intersect(from, to);
    if (rect_empty(&in)) {
        out[0] = *to;
        return 1;
    }
    uint32_t count = 0;
    /* columns beside the intersection over its rows, then whole-width rows above and below it */
    if (to->x0 < in.x0)
        out[count++] = (struct vts_tile_rect){to->x0, in.y0, in.x0, in.y1};
    if (in.x1 < to->x1)
        out[count++] = (struct vts_tile_rect){in.x1, in.y0, to->x1, in.y1};
    if (to->y0 < in.y0)
        out[count++] = (struct vts_tile_rect){to->x0, to->y0, to->x1, in.y0};
    if (in.y1 < to->y1)
        out[count++] = (struct vts_tile_rect){to->x0, in.y1, to->x1, to->y1};
    return count;
}

static bool tile_in_slot(const struct vts_clipmap *c, const struct vts_clipmap_level *cl,
                         uint32_t x, uint32_t y)
{
    return cl->slot_tile[(size_t)(y % c->n) * c->n + x % c->n] == (uint64_t)y * cl->tiles_x + x;
}

/* Whether every tile of [x0, x1) x [y0, y1) is in its slot. */
static bool all_in_slots(const struct vts_clipmap *c, const struct vts_clipmap_level *cl,
                         uint32_t x0, uint32_t y0, uint32_t x1, uint32_t y1)
{
    for (uint32_t y = y0; y < y1; y++)
        for (uint32_t x = x0; x < x1; x++)
            if (!tile_in_slot(c, cl, x, y))
                return false;
    return true;
}

/* Grows the level's front by whole columns and rows of the target whose tiles are in their slots,
 * until none is left (an empty front first becomes the target's top-left tile if that is loaded).
 * At the fixpoint no column or row next to the front is complete, which vts_clipmap_loaded uses. */
static void grow_front(const struct vts_clipmap *c, struct vts_clipmap_level *cl)
{
    struct vts_tile_rect *f = &cl->front;
    const struct vts_tile_rect *b = &cl->back;
    if (rect_empty(b))
        return;
    if (rect_empty(f)) {
        if (!tile_in_slot(c, cl, b->x0, b->y0))
            return;
        *f = (struct vts_tile_rect){b->x0, b->y0, b->x0 + 1, b->y0 + 1};
    }
    for (bool grew = true; grew;) {
        grew = false;
        if (f->x0 > b->x0 && all_in_slots(c, cl, f->x0 - 1, f->y0, f->x0, f->y1))
            f->x0--, grew = true;
        if (f->x1 < b->x1 && all_in_slots(c, cl, f->x1, f->y0, f->x1 + 1, f->y1))
            f->x1++, grew = true;
        if (f->y0 > b->y0 && all_in_slots(c, cl, f->x0, f->y0 - 1, f->x1, f->y0))
            f->y0--, grew = true;
        if (f->y1 < b->y1 && all_in_slots(c, cl, f->x0, f->y1, f->x1, f->y1 + 1))
            f->y1++, grew = true;
    }
}

int vts_clipmap_move(struct vts_clipmap *c, uint32_t level, const struct vts_tile_rect *to)
{
    if (!c || !to || level >= c->level_count)
        return VTS_ERR_RANGE;
    struct vts_clipmap_level *cl = &c->levels[level];
    if (rect_empty(to)) {
        memset(&cl->back, 0, sizeof cl->back);
        memset(&cl->front, 0, sizeof cl->front);
        return 0;
    }
    if (to->x1 > cl->tiles_x || to->y1 > cl->tiles_y || to->x1 - to->x0 > c->n ||
        to->y1 - to->y0 > c->n)
        return VTS_ERR_RANGE;
    cl->back = *to;
    cl->front = rect_intersect(&cl->front, to);
    /* tiles of an earlier, unfinished target may already be in their slots next to the front */
    grow_front(c, cl);
    return 0;
}

/* Calls visit(tile) for each tile of level's target that is not in its slot, in plan order, until
 * visit returns false. Returns false when it was stopped. */
typedef bool (*visit_fn)(void *ctx, const struct vts_clipmap_tile *t);

static bool walk_level(const struct vts_clipmap *c, uint32_t level, visit_fn visit, void *ctx)
{
    const struct vts_clipmap_level *cl = &c->levels[level];
    struct vts_tile_rect strips[4];
    uint32_t count = vts_clipmap_strips(&cl->front, &cl->back, strips);
    for (uint32_t s = 0; s < count; s++)
        for (uint32_t y = strips[s].y0; y < strips[s].y1; y++)
            for (uint32_t x = strips[s].x0; x < strips[s].x1; x++) {
                if (tile_in_slot(c, cl, x, y))
                    continue;
                struct vts_clipmap_tile t = {level, x, y, x % c->n, y % c->n};
                if (!visit(ctx, &t))
                    return false;
            }
    return true;
}

struct plan_ctx {
    struct vts_clipmap_tile *out;
    uint32_t max, count;
};

static bool plan_visit(void *ctx, const struct vts_clipmap_tile *t)
{
    struct plan_ctx *p = ctx;
    if (p->count >= p->max)
        return false;
    p->out[p->count++] = *t;
    return true;
}

uint32_t vts_clipmap_plan(const struct vts_clipmap *c, struct vts_clipmap_tile *out, uint32_t max)
{
    struct plan_ctx p = {out, max, 0};
    if (!c || !out || max == 0)
        return 0;
    for (uint32_t l = c->level_count; l-- > 0;)
        if (!walk_level(c, l, plan_visit, &p))
            break;
    return p.count;
}

static bool count_visit(void *ctx, const struct vts_clipmap_tile *t)
{
    (void)t;
    (*(uint64_t *)ctx)++;
    return true;
}

uint64_t vts_clipmap_pending(const struct vts_clipmap *c)
{
    uint64_t count = 0;
    if (!c)
        return 0;
    for (uint32_t l = c->level_count; l-- > 0;)
        walk_level(c, l, count_visit, &count);
    return count;
}

/* Whether (x, y) lies on a column or row next to the front, within the front's extent: the only
 * lines whose completeness a load there can change. */
static bool next_to_front(const struct vts_tile_rect *f, uint32_t x, uint32_t y)
{
    bool in_rows = y >= f->y0 && y < f->y1, in_cols = x >= f->x0 && x < f->x1;
    return (in_rows && (x + 1 == f->x0 || x == f->x1)) ||
           (in_cols && (y + 1 == f->y0 || y == f->y1));
}

int vts_clipmap_loaded(struct vts_clipmap *c, const struct vts_clipmap_tile *t)
{
    if (!c || !t || t->level >= c->level_count)
        return VTS_ERR_RANGE;
    struct vts_clipmap_level *cl = &c->levels[t->level];
    const struct vts_tile_rect *b = &cl->back;
    if (t->x < b->x0 || t->x >= b->x1 || t->y < b->y0 || t->y >= b->y1)
        return VTS_ERR_RANGE;
    cl->slot_tile[(size_t)(t->y % c->n) * c->n + t->x % c->n] = (uint64_t)t->y * cl->tiles_x + t->x;
    /* grow_front leaves no complete line next to the front, so only a load on such a line (or
     * into an empty front) can let it grow */
    if (rect_empty(&cl->front) || next_to_front(&cl->front, t->x, t->y))
        grow_front(c, cl);
    return 0;
}

bool vts_clipmap_complete(const struct vts_clipmap *c, uint32_t level)
{
    if (!c || level >= c->level_count)
        return false;
    const struct vts_clipmap_level *cl = &c->levels[level];
    return !rect_empty(&cl->back) && memcmp(&cl->front, &cl->back, sizeof cl->front) == 0;
}

void vts_clipmap_valid(const struct vts_clipmap *c, uint32_t level, double inset, double *x0,
                       double *y0, double *x1, double *y1)
{
    *x0 = *y0 = *x1 = *y1 = 0;
    if (!c || level >= c->level_count)
        return;
    const struct vts_clipmap_level *cl = &c->levels[level];
    const struct vts_tile_rect *f = &cl->front;
    if (rect_empty(f))
        return;
    if (!(inset > 0)) /* negative or NaN: no inset */
        inset = 0;
    double px = c->content_px;
    double ax0 = f->x0 * px, ay0 = f->y0 * px;
    /* a partial last tile: the level ends inside it */
    double ax1 = f->x1 < cl->tiles_x ? f->x1 * px : cl->width;
    double ay1 = f->y1 < cl->tiles_y ? f->y1 * px : cl->height;
    /* inset only where the front ends inside the level; at its edges the sampler clamps */
    if (f->x0 > 0)
        ax0 += inset;
    if (f->y0 > 0)
        ay0 += inset;
    if (f->x1 < cl->tiles_x)
        ax1 -= inset;
    if (f->y1 < cl->tiles_y)
        ay1 -= inset;
    if (ax0 >= ax1 || ay0 >= ay1)
        return;
    *x0 = ax0, *y0 = ay0, *x1 = ax1, *y1 = ay1;
}
