/* The state of one vt_cut() run, shared by the cut's parts: vt_cut.c (the driver: faces, kept and
 * split faces), vt_cut_edges.c (points on mesh edges: registration, the polygon of a face with its
 * edge points), vt_cut_clip.c (a cut face clipped into unit cells) and vt_cut_out.c (the growing
 * output arrays). docs/real-scenes.md, "Charts and cuts", states the rules. */
#ifndef VT_CUT_IMPL_H
#define VT_CUT_IMPL_H

#include <math.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "vt_cut.h"
#include "vt_keymap.h"

/* At most this many unit cells per cut face (the header's limit). */
#define VT_CUT_MAX_CELLS (1u << 20)
/* Moved texcoords of a wrap face must stay below this magnitude, where every integer and every
 * cell index is exact in double precision. */
#define VT_CUT_MAX_UV 4503599627370496.0 /* 2^52 */

/* A point registered on a mesh edge: at t from the edge's lower position index lo to hi. After
 * sorting and deduplication, record i is the new position position_count + i. */
struct vt_cut_rec {
    uint32_t lo, hi;
    double t;
};

enum vt_cut_pt_kind { VT_CUT_PT_CORNER, VT_CUT_PT_EDGE, VT_CUT_PT_GRID };

/* A corner of a polygon being clipped (in the face's moved texcoords, before any cell's move). */
struct vt_cut_pt {
    uint32_t pos;  /* position index: input, or position_count + new vertex */
    uint32_t edge; /* CORNER: its corner index c (it lies on edges c - 1 and c); EDGE: the face's
                      edge (corner edge -> edge + 1) it lies on; GRID: unused */
    uint8_t kind;  /* enum vt_cut_pt_kind */
    uint8_t tags;  /* bit a: the point is where this face's edge crosses its own integer line on
                      axis a (0: u, 1: v), and uv[a] is that integer exactly */
    double uv[2];
    uint32_t src[3]; /* as struct vt_cut_corner */
    double w[3];
};

/* The face being processed. */
struct vt_cut_face {
    uint32_t f;
    uint64_t c0;     /* its first corner */
    uint32_t n;      /* its corner count */
    bool has_uv;     /* a texcoord at every corner */
    bool wrap;       /* a wrap face: moved into its cell(s) */
    bool cut;        /* a wrap face that lines cut */
    bool flat;       /* zero area in UV (its fan determinants sum to exactly 0) */
    double shift[2]; /* its move (du, dv); 0 without texcoords */
    int64_t cell[4]; /* wrap faces: the cells a0..a1 x b0..b1 of its moved box */
    uint64_t poly_n; /* its polygon with the edge points: ctx->poly[0 .. poly_n) */
};

struct vt_cut_ctx {
    const struct vt_chart_mesh *m;
    const uint8_t *wrap;
    const double *shift;
    struct vt_cut_result *r;
    struct vts_error *err;
    /* points on mesh edges, sorted by (lo, hi, t) */
    struct vt_cut_rec *recs;
    uint64_t rec_count, rec_cap;
    struct vt_keymap edges; /* lo << 32 | hi -> its first record */
    struct vt_keymap grid;  /* (face, k_u, k_v) -> new vertex at that grid point inside the face */
    /* output capacities */
    uint64_t poly_cap, corner_cap, vertex_cap;
    /* the current face's polygon with its edge points, and where each corner i sits in it */
    struct vt_cut_pt *poly;
    uint64_t poly_cap_pts;
    uint64_t *corner_at;
    uint64_t corner_at_cap;
    /* the clipper's stack of polygons */
    struct vt_cut_pt *stack;
    uint64_t stack_top, stack_cap;
};

/* The moved texcoord of corner i of the face (texcoord + shift), on axis a. */
static inline double vt_cut_face_uv(const struct vt_cut_ctx *ctx, const struct vt_cut_face *fc,
                                    uint32_t i, int a)
{
    const struct vt_chart_mesh *m = ctx->m;
    return m->uv[2 * (size_t)m->tex[fc->c0 + i] + (size_t)a] + fc->shift[a];
}

/* The integers strictly between x0 and x1, in order from x0: returns how many, with the first in
 * *k0 and the *step (+1 or -1) to the next. |x0|, |x1| < VT_CUT_MAX_UV. */
static inline uint64_t vt_cut_lines(double x0, double x1, double *k0, double *step)
{
    if (x0 < x1) {
        double first = floor(x0) + 1, last = ceil(x1) - 1;
        *k0 = first;
        *step = 1;
        return last >= first ? (uint64_t)(last - first) + 1 : 0;
    }
    if (x0 > x1) {
        double first = ceil(x0) - 1, last = floor(x1) + 1;
        *k0 = first;
        *step = -1;
        return first >= last ? (uint64_t)(first - last) + 1 : 0;
    }
    *k0 = x0;
    *step = 0;
    return 0;
}

/* t of the crossing of integer k on the segment x0 -> x1 (x0 != x1), measured from x0. Every part
 * computes it with this one expression, so the same texcoords give the same bits. */
static inline double vt_cut_line_t(double x0, double x1, double k)
{
    return (k - x0) / (x1 - x0);
}

/* vt_cut_out.c: the output arrays. Each returns 0 or a negative status (error filled). */
int vt_cut_out_corner(struct vt_cut_ctx *ctx, const struct vt_cut_corner *c);
int vt_cut_out_end_poly(struct vt_cut_ctx *ctx); /* closes the polygon of the corners since */
int vt_cut_out_vertex(struct vt_cut_ctx *ctx, const struct vt_cut_vertex *v, uint32_t *pos);
/* The array p (of *cap elements of elem bytes) with room for need elements (at least 1): p itself,
 * or a larger block (its capacity in *cap), or NULL when that cannot be allocated (p unchanged,
 * still the caller's). */
void *vt_cut_out_grow(void *p, uint64_t *cap, uint64_t need, size_t elem);
/* Fills ctx->err for running out of memory and returns VTS_ERR_NOMEM. */
int vt_cut_out_nomem(struct vt_cut_ctx *ctx);
/* The output corner of polygon point p of face fc, moved by (-a, -b) (a wrap face's cell). */
void vt_cut_out_corner_of(const struct vt_cut_ctx *ctx, const struct vt_cut_face *fc,
                          const struct vt_cut_pt *p, int64_t a, int64_t b,
                          struct vt_cut_corner *out);

/* vt_cut_edges.c */
/* Registers the points where face fc's edges cross its lines (fc->cut). */
int vt_cut_edges_register(struct vt_cut_ctx *ctx, const struct vt_cut_face *fc);
/* Sorts and deduplicates the points, makes their new positions and the edge map. */
int vt_cut_edges_finish(struct vt_cut_ctx *ctx);
/* True when one of face fc's edges has registered points. */
bool vt_cut_edges_touch(const struct vt_cut_ctx *ctx, const struct vt_cut_face *fc);
/* Builds fc's polygon with its edge points in ctx->poly (sets fc->poly_n, ctx->corner_at). */
int vt_cut_edges_polygon(struct vt_cut_ctx *ctx, struct vt_cut_face *fc);

/* vt_cut_clip.c: clips fc's polygon (ctx->poly) to its cells and writes the pieces; *pieces gets
 * their count. */
int vt_cut_clip_face(struct vt_cut_ctx *ctx, const struct vt_cut_face *fc, uint64_t *pieces);

#endif
