/* Cutting faces along the integer UV lines (vt_cut.h): the driver. Pass 1 classifies the faces and
 * registers the points where the cut faces' edges cross their lines (vt_cut_edges.c); pass 2
 * writes each face: kept as it is, split (its polygon with the points of its edges) or cut into
 * the pieces of its cells (vt_cut_clip.c). */
#include <stdlib.h>
#include <string.h>

#include "internal/vt_cut_impl.h"
#include "vt_checked.h"
#include "vt_error.h"

/* The cells a0..a1 of the moved texcoords x over [lo, hi] on one axis. */
static void cell_range(double lo, double hi, int64_t *a0, int64_t *a1)
{
    *a0 = (int64_t)floor(lo);
    *a1 = hi > lo ? (int64_t)ceil(hi) - 1 : *a0;
}

/* Zero area in UV: the signed area (the sum of its fan triangles' determinants) is exactly 0. So
 * for a collinear face (each determinant 0, exactly so along a grid line), and for one folded over
 * itself so that it encloses nothing, whose pieces would all lie on lines. */
static bool face_is_flat(const struct vt_cut_ctx *ctx, const struct vt_cut_face *fc)
{
    double u0 = vt_cut_face_uv(ctx, fc, 0, 0), v0 = vt_cut_face_uv(ctx, fc, 0, 1), sum = 0;
    for (uint32_t i = 1; i + 1 < fc->n; i++) {
        double e1u = vt_cut_face_uv(ctx, fc, i, 0) - u0, e1v = vt_cut_face_uv(ctx, fc, i, 1) - v0;
        double e2u = vt_cut_face_uv(ctx, fc, i + 1, 0) - u0;
        double e2v = vt_cut_face_uv(ctx, fc, i + 1, 1) - v0;
        sum += e1u * e2v - e1v * e2u;
    }
    return sum == 0;
}

/* The box and cells of a wrap face's moved texcoords; VTS_ERR_LIMIT for a value that is not
 * finite or too large for exact cells, or too many cells. */
static int wrap_cells(struct vt_cut_ctx *ctx, struct vt_cut_face *fc)
{
    double box[4] = {INFINITY, -INFINITY, INFINITY, -INFINITY};
    for (uint32_t i = 0; i < fc->n; i++)
        for (int a = 0; a < 2; a++) {
            double x = vt_cut_face_uv(ctx, fc, i, a);
            if (!(fabs(x) < VT_CUT_MAX_UV))
                return vt_error_set(ctx->err, VTS_ERR_LIMIT,
                                    "cannot cut face %u along the UV grid: moved texcoord %g is "
                                    "not finite or beyond 2^52",
                                    fc->f, x);
            box[2 * a] = fmin(box[2 * a], x);
            box[2 * a + 1] = fmax(box[2 * a + 1], x);
        }
    cell_range(box[0], box[1], &fc->cell[0], &fc->cell[1]);
    cell_range(box[2], box[3], &fc->cell[2], &fc->cell[3]);
    uint64_t nu = (uint64_t)(fc->cell[1] - fc->cell[0]) + 1,
             nv = (uint64_t)(fc->cell[3] - fc->cell[2]) + 1;
    if (nu > VT_CUT_MAX_CELLS || nv > VT_CUT_MAX_CELLS || nu * nv > VT_CUT_MAX_CELLS)
        return vt_error_set(ctx->err, VTS_ERR_LIMIT,
                            "cannot cut face %u along the UV grid: it spans %llu x %llu cells "
                            "(at most %u)",
                            fc->f, (unsigned long long)nu, (unsigned long long)nv,
                            VT_CUT_MAX_CELLS);
    fc->cut = nu > 1 || nv > 1;
    return 0;
}

/* What face f is: its corners, texcoords, move, whether it wraps and whether lines cut it. */
static int face_setup(struct vt_cut_ctx *ctx, uint32_t f, struct vt_cut_face *fc)
{
    const struct vt_chart_mesh *m = ctx->m;
    memset(fc, 0, sizeof *fc);
    fc->f = f;
    fc->c0 = m->face_start[f];
    uint64_t n = m->face_start[f + 1] - fc->c0;
    if (n >= VT_CHART_NONE)
        return vt_error_set(ctx->err, VTS_ERR_LIMIT, "cannot cut face %u: %llu corners", f,
                            (unsigned long long)n);
    fc->n = (uint32_t)n;
    bool any_uv = false;
    fc->has_uv = n > 0;
    for (uint32_t i = 0; i < fc->n; i++) {
        any_uv |= m->tex[fc->c0 + i] != VT_CHART_NONE;
        fc->has_uv &= m->tex[fc->c0 + i] != VT_CHART_NONE;
    }
    if (any_uv) {
        fc->shift[0] = ctx->shift[2 * (size_t)f];
        fc->shift[1] = ctx->shift[2 * (size_t)f + 1];
    }
    fc->wrap = fc->has_uv && fc->n >= 3 && ctx->wrap[f] && m->group[f] != VT_CHART_NONE;
    if (!fc->wrap)
        return 0;
    int rc = wrap_cells(ctx, fc);
    if (rc)
        return rc;
    fc->flat = fc->cut && face_is_flat(ctx, fc);
    return 0;
}

/* Writes the face's polygon with its edge points as one polygon (a split face). */
static int write_split(struct vt_cut_ctx *ctx, const struct vt_cut_face *fc)
{
    int64_t a = fc->wrap ? fc->cell[0] : 0, b = fc->wrap ? fc->cell[2] : 0;
    for (uint64_t i = 0; i < fc->poly_n; i++) {
        struct vt_cut_corner c;
        vt_cut_out_corner_of(ctx, fc, &ctx->poly[i], a, b, &c);
        int rc = vt_cut_out_corner(ctx, &c);
        if (rc)
            return rc;
    }
    return vt_cut_out_end_poly(ctx);
}

/* Pass 2 for face f. */
static int write_face(struct vt_cut_ctx *ctx, uint32_t f)
{
    struct vt_cut_result *r = ctx->r;
    struct vt_cut_face fc;
    int rc = face_setup(ctx, f, &fc);
    if (rc)
        return rc;
    r->face_poly[f] = r->poly_count;
    r->face_shift[2 * (size_t)f] = fc.shift[0] - (fc.wrap && !fc.cut ? (double)fc.cell[0] : 0);
    r->face_shift[2 * (size_t)f + 1] = fc.shift[1] - (fc.wrap && !fc.cut ? (double)fc.cell[2] : 0);
    r->changed[f] = fc.n >= 3 && (fc.cut || vt_cut_edges_touch(ctx, &fc));
    if (!r->changed[f])
        return 0;
    rc = vt_cut_edges_polygon(ctx, &fc);
    if (rc)
        return rc;
    if (!fc.cut) {
        r->faces_split++;
        return write_split(ctx, &fc);
    }
    uint64_t pieces;
    rc = vt_cut_clip_face(ctx, &fc, &pieces);
    r->faces_cut++;
    r->pieces += pieces;
    return rc;
}

static int alloc_result(struct vt_cut_ctx *ctx)
{
    struct vt_cut_result *r = ctx->r;
    size_t faces = ctx->m->face_count;
    r->changed = malloc(faces + 1);
    r->face_shift = malloc((2 * faces + 1) * sizeof *r->face_shift);
    r->face_poly = malloc((faces + 1) * sizeof *r->face_poly);
    r->poly_start = malloc(sizeof *r->poly_start);
    if (!r->changed || !r->face_shift || !r->face_poly || !r->poly_start)
        return vt_cut_out_nomem(ctx);
    ctx->poly_cap = 1;
    r->poly_start[0] = 0;
    return 0;
}

int vt_cut(const struct vt_chart_mesh *m, const uint8_t *wrap, const double *shift,
           struct vt_cut_result *r, struct vts_error *err)
{
    memset(r, 0, sizeof *r);
    struct vt_cut_ctx ctx = {.m = m, .wrap = wrap, .shift = shift, .r = r, .err = err};
    vt_keymap_init(&ctx.edges, 1);
    vt_keymap_init(&ctx.grid, 3);
    int rc = alloc_result(&ctx);
    for (uint32_t f = 0; f < m->face_count && !rc; f++) {
        struct vt_cut_face fc;
        rc = face_setup(&ctx, f, &fc);
        if (!rc && fc.cut)
            rc = vt_cut_edges_register(&ctx, &fc);
    }
    if (!rc)
        rc = vt_cut_edges_finish(&ctx);
    for (uint32_t f = 0; f < m->face_count && !rc; f++)
        rc = write_face(&ctx, f);
    if (!rc)
        r->face_poly[m->face_count] = r->poly_count;
    free(ctx.recs);
    free(ctx.poly);
    free(ctx.corner_at);
    free(ctx.stack);
    vt_keymap_release(&ctx.edges);
    vt_keymap_release(&ctx.grid);
    if (rc)
        vt_cut_release(r);
    return rc;
}

void vt_cut_release(struct vt_cut_result *r)
{
    if (!r)
        return;
    free(r->changed);
    free(r->face_shift);
    free(r->face_poly);
    free(r->poly_start);
    free(r->corners);
    free(r->vertices);
    memset(r, 0, sizeof *r);
}
