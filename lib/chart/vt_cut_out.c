/* The cut's output arrays (internal/vt_cut_impl.h): corners, polygons, new positions. */
#include <stdlib.h>

#include "internal/vt_cut_impl.h"
#include "vt_checked.h"
#include "vt_error.h"

void *vt_cut_out_grow(void *p, uint64_t *cap, uint64_t need, size_t elem)
{
    if (need == 0)
        need = 1; /* never NULL for an empty array */
    if (need <= *cap)
        return p;
    uint64_t n = *cap > 8 ? *cap : 8, bytes;
    while (n < need)
        n = n > UINT64_MAX / 2 ? need : n * 2;
    if (!vt_u64_mul(n, elem, &bytes) || bytes > SIZE_MAX)
        return NULL;
    void *q = realloc(p, (size_t)bytes);
    if (q)
        *cap = n;
    return q;
}

int vt_cut_out_nomem(struct vt_cut_ctx *ctx)
{
    return vt_error_set(ctx->err, VTS_ERR_NOMEM,
                        "cannot cut %u faces along the UV grid: out of memory", ctx->m->face_count);
}

int vt_cut_out_corner(struct vt_cut_ctx *ctx, const struct vt_cut_corner *c)
{
    struct vt_cut_result *r = ctx->r;
    void *p = vt_cut_out_grow(r->corners, &ctx->corner_cap, r->corner_count + 1, sizeof *c);
    if (!p)
        return vt_cut_out_nomem(ctx);
    r->corners = p;
    r->corners[r->corner_count++] = *c;
    return 0;
}

int vt_cut_out_end_poly(struct vt_cut_ctx *ctx)
{
    struct vt_cut_result *r = ctx->r;
    void *p =
        vt_cut_out_grow(r->poly_start, &ctx->poly_cap, r->poly_count + 2, sizeof *r->poly_start);
    if (!p)
        return vt_cut_out_nomem(ctx);
    r->poly_start = p;
    r->poly_start[++r->poly_count] = r->corner_count;
    return 0;
}

int vt_cut_out_vertex(struct vt_cut_ctx *ctx, const struct vt_cut_vertex *v, uint32_t *pos)
{
    struct vt_cut_result *r = ctx->r;
    /* position indices stay below VT_CHART_NONE */
    if (r->vertex_count >= VT_CHART_NONE - ctx->m->position_count)
        return vt_error_set(ctx->err, VTS_ERR_LIMIT,
                            "cannot cut along the UV grid: more than %u new positions",
                            VT_CHART_NONE - ctx->m->position_count);
    void *p =
        vt_cut_out_grow(r->vertices, &ctx->vertex_cap, (uint64_t)r->vertex_count + 1, sizeof *v);
    if (!p)
        return vt_cut_out_nomem(ctx);
    r->vertices = p;
    *pos = ctx->m->position_count + r->vertex_count;
    r->vertices[r->vertex_count++] = *v;
    return 0;
}

static double clamp01(double x)
{
    return x < 0 ? 0 : x > 1 ? 1 : x;
}

void vt_cut_out_corner_of(const struct vt_cut_ctx *ctx, const struct vt_cut_face *fc,
                          const struct vt_cut_pt *p, int64_t a, int64_t b,
                          struct vt_cut_corner *out)
{
    const struct vt_chart_mesh *m = ctx->m;
    out->pos = p->pos;
    out->has_uv = fc->has_uv;
    out->u = out->v = 0;
    for (int i = 0; i < 3; i++) {
        out->src[i] = p->src[i];
        out->w[i] = p->w[i];
    }
    if (!fc->has_uv)
        return;
    if (p->kind == VT_CUT_PT_CORNER) {
        /* the input value plus one integer move: rounded once, as a kept face's corner */
        const double *uv = m->uv + 2 * (size_t)m->tex[fc->c0 + p->src[0]];
        out->u = uv[0] + (fc->shift[0] - (double)a);
        out->v = uv[1] + (fc->shift[1] - (double)b);
    } else {
        out->u = p->uv[0] - (double)a;
        out->v = p->uv[1] - (double)b;
    }
    if (fc->wrap) {
        /* the cell's move of a value that rounding put a hair outside the cell */
        out->u = clamp01(out->u);
        out->v = clamp01(out->v);
    }
}
