/* A cut face clipped into the unit cells of the UV grid (internal/vt_cut_impl.h). The face's
 * polygon, with its edge points, is split in two at a middle line of its remaining cell range,
 * first along u and then, in each column, along v, each half by Sutherland-Hodgman (a point on
 * the line belongs to both halves; a segment is cut only where its ends lie strictly on both
 * sides), until one cell is left: the same pieces as clipping to every cell, in O(n log cells). */
#include <assert.h>
#include <stdlib.h>
#include <string.h>

#include "internal/vt_cut_impl.h"
#include "vt_error.h"

/* The face's edge that both points lie on, or VT_CHART_NONE. */
static uint32_t shared_edge(const struct vt_cut_face *fc, const struct vt_cut_pt *s,
                            const struct vt_cut_pt *e)
{
    uint32_t es[2], ee[2], ns = 0, ne = 0;
    if (s->kind == VT_CUT_PT_CORNER) {
        es[ns++] = (s->edge + fc->n - 1) % fc->n;
        es[ns++] = s->edge;
    } else if (s->kind == VT_CUT_PT_EDGE) {
        es[ns++] = s->edge;
    }
    if (e->kind == VT_CUT_PT_CORNER) {
        ee[ne++] = (e->edge + fc->n - 1) % fc->n;
        ee[ne++] = e->edge;
    } else if (e->kind == VT_CUT_PT_EDGE) {
        ee[ne++] = e->edge;
    }
    for (uint32_t a = 0; a < ns; a++)
        for (uint32_t b = 0; b < ne; b++)
            if (es[a] == ee[b])
                return es[a];
    return VT_CHART_NONE;
}

/* The registered point of edge j where it crosses this face's line x[axis] = k, or NULL. */
static const struct vt_cut_pt *edge_crossing(const struct vt_cut_ctx *ctx,
                                             const struct vt_cut_face *fc, uint32_t j, int axis,
                                             double k)
{
    uint64_t end = j + 1 < fc->n ? ctx->corner_at[j + 1] : fc->poly_n;
    for (uint64_t q = ctx->corner_at[j] + 1; q < end; q++) {
        const struct vt_cut_pt *p = &ctx->poly[q];
        if ((p->tags >> axis & 1) && p->uv[axis] == k)
            return p;
    }
    return NULL;
}

/* Barycentric coordinates of (x, y) in a fan triangle (b, b + i, b + i + 1) of the face: the first
 * that contains it, else the one it is nearest to outside (by its lowest coordinate). The fan
 * starts at corner 0; at the next corners only while every triangle so far has zero area (a face
 * with repeated texcoords). Texcoords are taken relative to the fan's corner, which keeps the
 * precision of large repeats. Without any triangle of non-zero area: corner 0, weight 1. */
static void fan_weights(const struct vt_cut_ctx *ctx, const struct vt_cut_face *fc, double x,
                        double y, uint32_t src[3], double w[3])
{
    double best = -INFINITY;
    src[0] = 0;
    src[1] = src[2] = VT_CHART_NONE;
    w[0] = 1;
    w[1] = w[2] = 0;
    for (uint32_t b = 0; b < fc->n && best == -INFINITY; b++) {
        double u0 = vt_cut_face_uv(ctx, fc, b, 0), v0 = vt_cut_face_uv(ctx, fc, b, 1);
        for (uint32_t i = 1; i + 1 < fc->n && best < 0; i++) {
            uint32_t c1 = (b + i) % fc->n, c2 = (b + i + 1) % fc->n;
            double e1u = vt_cut_face_uv(ctx, fc, c1, 0) - u0;
            double e1v = vt_cut_face_uv(ctx, fc, c1, 1) - v0;
            double e2u = vt_cut_face_uv(ctx, fc, c2, 0) - u0;
            double e2v = vt_cut_face_uv(ctx, fc, c2, 1) - v0;
            double pu = x - u0, pv = y - v0, det = e1u * e2v - e1v * e2u;
            if (det == 0)
                continue;
            double l1 = (pu * e2v - pv * e2u) / det, l2 = (e1u * pv - e1v * pu) / det;
            double l0 = 1 - l1 - l2, low = fmin(l0, fmin(l1, l2));
            if (low > best) {
                best = low;
                src[0] = b;
                src[1] = c1;
                src[2] = c2;
                w[0] = l0;
                w[1] = l1;
                w[2] = l2;
            }
        }
    }
}

/* The point at (x, y) inside the face, where a segment inside it (on a grid line) crosses another
 * grid line: one new position per face and grid point (shared), shared by all the face's pieces;
 * unshared for a point off the grid (a case the rules exclude; kept for robustness). */
static int inner_point(struct vt_cut_ctx *ctx, const struct vt_cut_face *fc, double x, double y,
                       bool shared, struct vt_cut_pt *out)
{
    const struct vt_chart_mesh *m = ctx->m;
    *out = (struct vt_cut_pt){0, VT_CHART_NONE, VT_CUT_PT_GRID, 0, {x, y}, {0}, {0}};
    fan_weights(ctx, fc, x, y, out->src, out->w);
    uint64_t key[3] = {fc->f, (uint64_t)(int64_t)x, (uint64_t)(int64_t)y}, vertex;
    if (shared && vt_keymap_get(&ctx->grid, key, &vertex)) {
        out->pos = (uint32_t)vertex;
        return 0;
    }
    struct vt_cut_vertex v = {{VT_CHART_NONE, VT_CHART_NONE, VT_CHART_NONE}, {0, 0, 0}};
    for (int i = 0; i < 3; i++) {
        if (out->src[i] != VT_CHART_NONE)
            v.pos[i] = m->pos[fc->c0 + out->src[i]];
        v.w[i] = out->w[i];
    }
    int rc = vt_cut_out_vertex(ctx, &v, &out->pos);
    if (rc || !shared)
        return rc;
    vertex = out->pos;
    if (!vt_keymap_put_new(&ctx->grid, key, &vertex, &rc) && rc)
        return vt_cut_out_nomem(ctx);
    return 0;
}

/* Where the segment s -> e (ends strictly on both sides) crosses the line x[axis] = k. */
static int crossing(struct vt_cut_ctx *ctx, const struct vt_cut_face *fc, const struct vt_cut_pt *s,
                    const struct vt_cut_pt *e, int axis, double k, struct vt_cut_pt *out)
{
    uint32_t j = shared_edge(fc, s, e);
    if (j != VT_CHART_NONE) {
        const struct vt_cut_pt *p = edge_crossing(ctx, fc, j, axis, k);
        assert(p);
        if (p) {
            *out = *p;
            return 0;
        }
    }
    int other = 1 - axis;
    double o = s->uv[other];
    bool on_grid = e->uv[other] == o && floor(o) == o;
    assert(on_grid);
    if (!on_grid)
        o += (k - s->uv[axis]) / (e->uv[axis] - s->uv[axis]) * (e->uv[other] - o);
    return axis == 0 ? inner_point(ctx, fc, k, o, on_grid, out)
                     : inner_point(ctx, fc, o, k, on_grid, out);
}

static int side_of(const struct vt_cut_pt *p, int axis, double k)
{
    return p->uv[axis] < k ? -1 : p->uv[axis] > k;
}

/* Sutherland-Hodgman: the n points at stack[in] clipped to the side keep (-1: x[axis] <= k,
 * +1: x[axis] >= k) of the line, written from stack[ctx->stack_top]; *out_n gets their count. */
static int clip_half(struct vt_cut_ctx *ctx, const struct vt_cut_face *fc, uint64_t in, uint64_t n,
                     int axis, double k, int keep, uint64_t *out_n)
{
    uint64_t out = ctx->stack_top, count = 0;
    /* every segment adds at most two points */
    void *p = vt_cut_out_grow(ctx->stack, &ctx->stack_cap, out + 2 * n, sizeof *ctx->stack);
    if (!p)
        return vt_cut_out_nomem(ctx);
    ctx->stack = p;
    for (uint64_t i = 0; i < n; i++) {
        const struct vt_cut_pt *s = &ctx->stack[in + (i + n - 1) % n], *e = &ctx->stack[in + i];
        int ss = side_of(s, axis, k), se = side_of(e, axis, k);
        if (ss * se < 0) {
            int rc = crossing(ctx, fc, s, e, axis, k, &ctx->stack[out + count++]);
            if (rc)
                return rc;
        }
        if (se == 0 || se == keep)
            ctx->stack[out + count++] = *e;
    }
    *out_n = count;
    return 0;
}

/* All n points on one side line of cell (a, b) that lies inside the face's cells: what clipping
 * leaves on the far side of a line that a face only touches, or that one of its edges lies on. A
 * piece on the outer line of the face's cells is kept: no cell beyond holds that part of the face
 * (a face folded over itself in UV can have an area in 3D there). */
static bool on_one_side_line(const struct vt_cut_face *fc, const struct vt_cut_pt *p, uint64_t n,
                             int64_t a, int64_t b)
{
    const double line[4] = {(double)a, (double)a + 1, (double)b, (double)b + 1};
    const bool inside[4] = {(a > fc->cell[0]), (a < fc->cell[1]), (b > fc->cell[2]),
                            (b < fc->cell[3])};
    for (int s = 0; s < 4; s++) {
        uint64_t i = 0;
        if (!inside[s])
            continue;
        while (i < n && p[i].uv[s / 2] == line[s])
            i++;
        if (i == n)
            return true;
    }
    return false;
}

static bool all_at_one_point(const struct vt_cut_pt *p, uint64_t n)
{
    for (uint64_t i = 1; i < n; i++)
        if (p[i].uv[0] != p[0].uv[0] || p[i].uv[1] != p[0].uv[1])
            return false;
    return true;
}

/* The same point twice (position and texcoord), as a degenerate piece can hold in a row. */
static bool same_point(const struct vt_cut_pt *a, const struct vt_cut_pt *b)
{
    return a->pos == b->pos && a->uv[0] == b->uv[0] && a->uv[1] == b->uv[1];
}

/* Writes the piece of cell (a, b) (the n points at stack[at]), unless it is degenerate: fewer
 * than 3 corners once repeated points in a row are merged, or all on one side line of the cell
 * that is not the outer line of the face's cells (for a convex face: exactly the pieces of zero
 * area). A face of zero area in UV (collinear, or folded so that it encloses nothing: its pieces
 * lie on lines, and it may well have an area in 3D) keeps the pieces that are not a single point.
 * Pieces of zero area that are neither (from a face folded over itself in UV) are kept: vt_cut
 * sees no positions, and dropping them could leave a hole in 3D. */
static int emit_piece(struct vt_cut_ctx *ctx, const struct vt_cut_face *fc, uint64_t at, uint64_t n,
                      int64_t a, int64_t b, uint64_t *pieces)
{
    struct vt_cut_pt *p = &ctx->stack[at];
    uint64_t kept = 0;
    for (uint64_t i = 0; i < n; i++)
        if (!kept || !same_point(&p[i], &p[kept - 1]))
            p[kept++] = p[i];
    while (kept > 1 && same_point(&p[kept - 1], &p[0]))
        kept--;
    if (kept < 3)
        return 0;
    if (fc->flat ? all_at_one_point(p, kept) : on_one_side_line(fc, p, kept, a, b))
        return 0;
    for (uint64_t i = 0; i < kept; i++) {
        struct vt_cut_corner c;
        vt_cut_out_corner_of(ctx, fc, &p[i], a, b, &c);
        int rc = vt_cut_out_corner(ctx, &c);
        if (rc)
            return rc;
    }
    (*pieces)++;
    return vt_cut_out_end_poly(ctx);
}

static int64_t clamp64(int64_t x, int64_t lo, int64_t hi)
{
    return x < lo ? lo : x > hi ? hi : x;
}

/* Splits the n points at stack[at] along axis over the cells lo..hi (their column a once axis
 * is 1) down to single cells, and writes the pieces. */
static int split(struct vt_cut_ctx *ctx, const struct vt_cut_face *fc, uint64_t at, uint64_t n,
                 int axis, int64_t lo, int64_t hi, int64_t a, uint64_t *pieces)
{
    if (n < 3)
        return 0;
    /* only the cells the points reach */
    double mn = INFINITY, mx = -INFINITY;
    for (uint64_t i = 0; i < n; i++) {
        mn = fmin(mn, ctx->stack[at + i].uv[axis]);
        mx = fmax(mx, ctx->stack[at + i].uv[axis]);
    }
    int64_t l2 = clamp64((int64_t)floor(mn), lo, hi), h2 = clamp64((int64_t)ceil(mx) - 1, lo, hi);
    if (h2 < l2)
        h2 = l2;
    if (l2 == h2)
        return axis == 0 ? split(ctx, fc, at, n, 1, fc->cell[2], fc->cell[3], l2, pieces)
                         : emit_piece(ctx, fc, at, n, a, l2, pieces);
    int64_t k = l2 + (h2 - l2 + 1) / 2; /* the line between cells k - 1 and k */
    uint64_t top = ctx->stack_top, half = 0;
    for (int keep = -1; keep <= 1; keep += 2) {
        int rc = clip_half(ctx, fc, at, n, axis, (double)k, keep, &half);
        if (!rc) {
            ctx->stack_top = top + half;
            rc = keep < 0 ? split(ctx, fc, top, half, axis, l2, k - 1, a, pieces)
                          : split(ctx, fc, top, half, axis, k, h2, a, pieces);
        }
        ctx->stack_top = top;
        if (rc)
            return rc;
    }
    return 0;
}

int vt_cut_clip_face(struct vt_cut_ctx *ctx, const struct vt_cut_face *fc, uint64_t *pieces)
{
    *pieces = 0;
    void *p = vt_cut_out_grow(ctx->stack, &ctx->stack_cap, fc->poly_n, sizeof *ctx->stack);
    if (!p)
        return vt_cut_out_nomem(ctx);
    ctx->stack = p;
    memcpy(ctx->stack, ctx->poly, (size_t)fc->poly_n * sizeof *ctx->stack);
    ctx->stack_top = fc->poly_n;
    return split(ctx, fc, 0, fc->poly_n, 0, fc->cell[0], fc->cell[1], 0, pieces);
}
