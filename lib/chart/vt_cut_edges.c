/* Points on mesh edges (internal/vt_cut_impl.h): where a cut face's edges cross its integer
 * lines, shared by every face on the edge, and the polygon of a face with those points inserted. */
#include <assert.h>
#include <stdlib.h>

#include "internal/vt_cut_impl.h"
#include "vt_error.h"

/* Corner i of the face is the end an edge i -> j is measured from: the lower position index, or,
 * for an edge between two corners at one position, the lower moved texcoord (u, then v), so that
 * faces with the same texcoords on the edge agree whatever their winding. */
static bool edge_from_i(const struct vt_cut_ctx *ctx, const struct vt_cut_face *fc, uint32_t i,
                        uint32_t j)
{
    uint32_t pi = ctx->m->pos[fc->c0 + i], pj = ctx->m->pos[fc->c0 + j];
    if (pi != pj || !fc->has_uv)
        return pi <= pj;
    double ui = vt_cut_face_uv(ctx, fc, i, 0), uj = vt_cut_face_uv(ctx, fc, j, 0);
    if (ui != uj)
        return ui < uj;
    return vt_cut_face_uv(ctx, fc, i, 1) <= vt_cut_face_uv(ctx, fc, j, 1);
}

static uint64_t edge_key(uint32_t lo, uint32_t hi)
{
    return (uint64_t)lo << 32 | hi;
}

int vt_cut_edges_register(struct vt_cut_ctx *ctx, const struct vt_cut_face *fc)
{
    const struct vt_chart_mesh *m = ctx->m;
    for (uint32_t i = 0; i < fc->n; i++) {
        uint32_t j = (i + 1) % fc->n;
        uint32_t lo = edge_from_i(ctx, fc, i, j) ? i : j, hi = lo == i ? j : i;
        for (int a = 0; a < 2; a++) {
            double x0 = vt_cut_face_uv(ctx, fc, lo, a), x1 = vt_cut_face_uv(ctx, fc, hi, a), k0,
                   step;
            uint64_t count = vt_cut_lines(x0, x1, &k0, &step);
            void *p = vt_cut_out_grow(ctx->recs, &ctx->rec_cap, ctx->rec_count + count,
                                      sizeof *ctx->recs);
            if (!p)
                return vt_cut_out_nomem(ctx);
            ctx->recs = p;
            for (uint64_t q = 0; q < count; q++)
                ctx->recs[ctx->rec_count++] =
                    (struct vt_cut_rec){m->pos[fc->c0 + lo], m->pos[fc->c0 + hi],
                                        vt_cut_line_t(x0, x1, k0 + (double)q * step)};
        }
    }
    return 0;
}

static int compare_recs(const void *pa, const void *pb)
{
    const struct vt_cut_rec *a = pa, *b = pb;
    if (a->lo != b->lo)
        return a->lo < b->lo ? -1 : 1;
    if (a->hi != b->hi)
        return a->hi < b->hi ? -1 : 1;
    return a->t < b->t ? -1 : a->t > b->t;
}

int vt_cut_edges_finish(struct vt_cut_ctx *ctx)
{
    struct vt_cut_rec *recs = ctx->recs;
    if (!ctx->rec_count)
        return 0;
    qsort(recs, (size_t)ctx->rec_count, sizeof *recs, compare_recs);
    /* one point per (edge, t): faces with the same texcoords on an edge computed the same bits */
    uint64_t n = 1, edges = 1;
    for (uint64_t i = 1; i < ctx->rec_count; i++) {
        if (compare_recs(&recs[i], &recs[n - 1]) == 0)
            continue;
        edges += recs[i].lo != recs[n - 1].lo || recs[i].hi != recs[n - 1].hi;
        recs[n++] = recs[i];
    }
    ctx->rec_count = n;
    if (vt_keymap_reserve(&ctx->edges, (size_t)edges))
        return vt_cut_out_nomem(ctx);
    for (uint64_t i = 0; i < n; i++) {
        const struct vt_cut_rec *e = &recs[i];
        struct vt_cut_vertex v = {{e->lo, e->hi, VT_CHART_NONE}, {1 - e->t, e->t, 0}};
        uint32_t pos;
        int rc = vt_cut_out_vertex(ctx, &v, &pos);
        if (rc)
            return rc;
        assert(pos == ctx->m->position_count + i);
        if (i == 0 || e->lo != recs[i - 1].lo || e->hi != recs[i - 1].hi) {
            uint64_t key = edge_key(e->lo, e->hi), first = i;
            if (!vt_keymap_put_new(&ctx->edges, &key, &first, &rc) && rc)
                return vt_cut_out_nomem(ctx);
        }
    }
    return 0;
}

/* The first record of the edge between corners i and j of the face, or false when it has none. */
static bool edge_first(const struct vt_cut_ctx *ctx, const struct vt_cut_face *fc, uint32_t i,
                       uint32_t j, uint64_t *first)
{
    uint32_t pi = ctx->m->pos[fc->c0 + i], pj = ctx->m->pos[fc->c0 + j];
    uint64_t key = pi <= pj ? edge_key(pi, pj) : edge_key(pj, pi);
    return vt_keymap_get(&ctx->edges, &key, first);
}

bool vt_cut_edges_touch(const struct vt_cut_ctx *ctx, const struct vt_cut_face *fc)
{
    uint64_t first;
    for (uint32_t i = 0; i < fc->n; i++)
        if (edge_first(ctx, fc, i, (i + 1) % fc->n, &first))
            return true;
    return false;
}

static bool is_integer(double x)
{
    return floor(x) == x;
}

/* x kept between the values f1 and f2 that the points before and after it on its edge have on
 * this axis. For a cut face (strict) it also stays off every integer line it does not cross
 * there: a point between two of the edge's crossings lies strictly between their lines, so that
 * no piece of an edge between two of its points crosses a line, and none runs along one unless
 * the whole edge does. */
static double keep_between(double x, double f1, double f2, bool strict)
{
    if (f1 == f2)
        return f1;
    double lo = fmin(f1, f2), hi = fmax(f1, f2);
    if (strict && is_integer(lo))
        lo = nextafter(lo, hi);
    if (strict && is_integer(hi))
        hi = nextafter(hi, lo);
    return x < lo ? lo : x > hi ? hi : x;
}

/* One axis of an edge walked from its measured end x0 to x1: its crossings of the face's own
 * lines (a cut face's) and the last fixed value passed (x0, then each crossing's integer). */
struct axis_walk {
    double x0, x1, k0, step, prev;
    uint64_t count, next;
};

static void walk_start(struct axis_walk *w, double x0, double x1, bool cut)
{
    w->x0 = x0;
    w->x1 = x1;
    w->prev = x0;
    w->next = 0;
    w->count = cut ? vt_cut_lines(x0, x1, &w->k0, &w->step) : 0;
}

/* The coordinate of the point at t on this axis; sets *tagged when it is one of the crossings. */
static double walk_point(struct axis_walk *w, double t, bool strict, bool *tagged)
{
    *tagged = false;
    double k = w->next < w->count ? w->k0 + (double)w->next * w->step : w->x1;
    if (w->next < w->count) {
        double tk = vt_cut_line_t(w->x0, w->x1, k);
        assert(t <= tk); /* every crossing of a cut face was registered */
        if (t == tk) {
            *tagged = true;
            w->prev = k;
            w->next++;
            return k;
        }
    }
    return keep_between(w->x0 + t * (w->x1 - w->x0), w->prev, k, strict);
}

/* Appends the points of edge i -> j of the face to ctx->poly, in order from corner i. */
static int append_edge_points(struct vt_cut_ctx *ctx, struct vt_cut_face *fc, uint32_t i,
                              uint32_t j)
{
    uint64_t r;
    if (!edge_first(ctx, fc, i, j, &r))
        return 0;
    bool from_i = edge_from_i(ctx, fc, i, j);
    uint32_t lo = from_i ? i : j, hi = from_i ? j : i;
    struct axis_walk walk[2];
    for (int a = 0; a < 2 && fc->has_uv; a++)
        walk_start(&walk[a], vt_cut_face_uv(ctx, fc, lo, a), vt_cut_face_uv(ctx, fc, hi, a),
                   fc->cut);
    uint64_t start = fc->poly_n;
    const struct vt_cut_rec *e = &ctx->recs[r];
    for (; r < ctx->rec_count && ctx->recs[r].lo == e->lo && ctx->recs[r].hi == e->hi; r++) {
        double t = ctx->recs[r].t;
        void *p = vt_cut_out_grow(ctx->poly, &ctx->poly_cap_pts, fc->poly_n + 1, sizeof *ctx->poly);
        if (!p)
            return vt_cut_out_nomem(ctx);
        ctx->poly = p;
        struct vt_cut_pt *pt = &ctx->poly[fc->poly_n++];
        *pt = (struct vt_cut_pt){ctx->m->position_count + (uint32_t)r,
                                 i,
                                 VT_CUT_PT_EDGE,
                                 0,
                                 {0, 0},
                                 {i, j, VT_CHART_NONE},
                                 {from_i ? 1 - t : t, from_i ? t : 1 - t, 0}};
        for (int a = 0; a < 2 && fc->has_uv; a++) {
            bool tagged;
            pt->uv[a] = walk_point(&walk[a], t, fc->cut, &tagged);
            pt->tags |= (uint8_t)(tagged << a);
        }
    }
    assert(!fc->cut || !fc->has_uv ||
           (walk[0].next == walk[0].count && walk[1].next == walk[1].count));
    if (!from_i) /* walked from corner j: reverse into the face's order */
        for (uint64_t a = start, b = fc->poly_n - 1; a < b; a++, b--) {
            struct vt_cut_pt t = ctx->poly[a];
            ctx->poly[a] = ctx->poly[b];
            ctx->poly[b] = t;
        }
    return 0;
}

int vt_cut_edges_polygon(struct vt_cut_ctx *ctx, struct vt_cut_face *fc)
{
    void *p = vt_cut_out_grow(ctx->corner_at, &ctx->corner_at_cap, fc->n, sizeof *ctx->corner_at);
    if (!p)
        return vt_cut_out_nomem(ctx);
    ctx->corner_at = p;
    fc->poly_n = 0;
    for (uint32_t i = 0; i < fc->n; i++) {
        p = vt_cut_out_grow(ctx->poly, &ctx->poly_cap_pts, fc->poly_n + 1, sizeof *ctx->poly);
        if (!p)
            return vt_cut_out_nomem(ctx);
        ctx->poly = p;
        ctx->corner_at[i] = fc->poly_n;
        struct vt_cut_pt *pt = &ctx->poly[fc->poly_n++];
        *pt = (struct vt_cut_pt){
            ctx->m->pos[fc->c0 + i],           i,        VT_CUT_PT_CORNER, 0, {0, 0},
            {i, VT_CHART_NONE, VT_CHART_NONE}, {1, 0, 0}};
        if (fc->has_uv) {
            pt->uv[0] = vt_cut_face_uv(ctx, fc, i, 0);
            pt->uv[1] = vt_cut_face_uv(ctx, fc, i, 1);
        }
        int rc = append_edge_points(ctx, fc, i, (i + 1) % fc->n);
        if (rc)
            return rc;
    }
    return 0;
}
