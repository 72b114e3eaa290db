/* Meshes in memory and independent checkers of vt_cut() results (cut_fixture.h). */
#include "cut_fixture.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void *grow(void *p, uint64_t *cap, uint64_t need, size_t elem)
{
    if (need <= *cap)
        return p;
    uint64_t n = *cap ? *cap : 16;
    while (n < need)
        n *= 2;
    void *q = realloc(p, (size_t)(n * elem));
    if (!q)
        abort();
    *cap = n;
    return q;
}

void tmesh_init(struct tmesh *t)
{
    memset(t, 0, sizeof *t);
    t->face_start = grow(NULL, &t->cap[0], 1, sizeof *t->face_start);
    t->face_start[0] = 0;
}

void tmesh_release(struct tmesh *t)
{
    free(t->face_start);
    free(t->pos);
    free(t->tex);
    free(t->group);
    free(t->xyz);
    free(t->uv);
    free(t->wrap);
    free(t->shift);
    memset(t, 0, sizeof *t);
}

uint32_t tmesh_pos(struct tmesh *t, double x, double y, double z)
{
    t->xyz = grow(t->xyz, &t->cap[1], 3 * ((uint64_t)t->position_count + 1), sizeof *t->xyz);
    double *p = t->xyz + 3 * (size_t)t->position_count;
    p[0] = x;
    p[1] = y;
    p[2] = z;
    return t->position_count++;
}

uint32_t tmesh_tex(struct tmesh *t, double u, double v)
{
    t->uv = grow(t->uv, &t->cap[2], 2 * ((uint64_t)t->texcoord_count + 1), sizeof *t->uv);
    t->uv[2 * (size_t)t->texcoord_count] = u;
    t->uv[2 * (size_t)t->texcoord_count + 1] = v;
    return t->texcoord_count++;
}

uint32_t tmesh_face(struct tmesh *t, uint32_t group, uint32_t n, const uint32_t *pos,
                    const uint32_t *tex, bool wrap)
{
    uint64_t f = t->face_count, c = t->corner_count;
    t->face_start = grow(t->face_start, &t->cap[0], f + 2, sizeof *t->face_start);
    t->group = grow(t->group, &t->cap[3], f + 1, sizeof *t->group);
    t->wrap = grow(t->wrap, &t->cap[4], f + 1, sizeof *t->wrap);
    t->shift = grow(t->shift, &t->cap[5], 2 * (f + 1), sizeof *t->shift);
    t->pos = grow(t->pos, &t->cap[6], c + n, sizeof *t->pos);
    t->tex = grow(t->tex, &t->cap[7], c + n, sizeof *t->tex);
    for (uint32_t i = 0; i < n; i++) {
        t->pos[c + i] = pos[i];
        t->tex[c + i] = tex ? tex[i] : VT_CHART_NONE;
    }
    t->corner_count = c + n;
    t->face_start[f + 1] = t->corner_count;
    t->group[f] = group;
    t->wrap[f] = wrap;
    t->shift[2 * f] = t->shift[2 * f + 1] = 0;
    return t->face_count++;
}

struct vt_chart_mesh tmesh_view(const struct tmesh *t)
{
    return (struct vt_chart_mesh){
        t->face_count, t->face_start,     t->pos,           t->tex, NULL, t->group,
        t->uv,         t->position_count, t->texcoord_count};
}

uint32_t tmesh_shift_charts(struct tmesh *t)
{
    struct vt_chart_mesh m = tmesh_view(t);
    uint32_t *chart = malloc((t->face_count + 1) * sizeof *chart), count;
    if (!chart || vt_chart_label(&m, chart, &count, NULL))
        abort();
    struct vt_chart_box *boxes = malloc((count + 1) * sizeof *boxes);
    if (!boxes)
        abort();
    vt_chart_boxes(&m, chart, count, boxes);
    for (uint32_t f = 0; f < t->face_count; f++) {
        t->shift[2 * (size_t)f] = chart[f] == VT_CHART_NONE ? 0 : boxes[chart[f]].du;
        t->shift[2 * (size_t)f + 1] = chart[f] == VT_CHART_NONE ? 0 : boxes[chart[f]].dv;
    }
    free(boxes);
    free(chart);
    return count;
}

void cut_fixture_position(const struct tmesh *t, const struct vt_cut_result *r, uint32_t p,
                          double out[3])
{
    if (p < t->position_count) {
        memcpy(out, t->xyz + 3 * (size_t)p, 3 * sizeof *out);
        return;
    }
    const struct vt_cut_vertex *v = &r->vertices[p - t->position_count];
    out[0] = out[1] = out[2] = 0;
    for (int i = 0; i < 3; i++)
        if (v->pos[i] != VT_CHART_NONE)
            for (int a = 0; a < 3; a++)
                out[a] += v->w[i] * t->xyz[3 * (size_t)v->pos[i] + a];
}

/* ---- watertightness ---- */

struct pair {
    uint32_t a, b;
};

static int compare_pairs(const void *pa, const void *pb)
{
    const struct pair *x = pa, *y = pb;
    if (x->a != y->a)
        return x->a < y->a ? -1 : 1;
    return x->b < y->b ? -1 : x->b > y->b;
}

static struct pair make_pair(uint32_t a, uint32_t b)
{
    return a < b ? (struct pair){a, b} : (struct pair){b, a};
}

/* How many times p occurs in the sorted pairs. */
static uint64_t count_pair(const struct pair *pairs, uint64_t n, struct pair p)
{
    uint64_t lo = 0, hi = n;
    while (lo < hi) {
        uint64_t mid = lo + (hi - lo) / 2;
        if (compare_pairs(&pairs[mid], &p) < 0)
            lo = mid + 1;
        else
            hi = mid;
    }
    uint64_t c = 0;
    while (lo + c < n && compare_pairs(&pairs[lo + c], &p) == 0)
        c++;
    return c;
}

struct pairs {
    struct pair *p;
    uint64_t n, cap;
};

static void add_pair(struct pairs *ps, uint32_t a, uint32_t b)
{
    ps->p = grow(ps->p, &ps->cap, ps->n + 1, sizeof *ps->p);
    ps->p[ps->n++] = make_pair(a, b);
}

/* The input edge a new edge point lies on, or false for an input position or an inner point. */
static bool edge_of_point(const struct tmesh *t, const struct vt_cut_result *r, uint32_t p,
                          struct pair *e)
{
    if (p < t->position_count)
        return false;
    const struct vt_cut_vertex *v = &r->vertices[p - t->position_count];
    if (v->pos[1] == VT_CHART_NONE || v->pos[2] != VT_CHART_NONE)
        return false;
    *e = make_pair(v->pos[0], v->pos[1]);
    return true;
}

/* Output position p lies on input edge e: one of its ends, or a new point on it. */
static bool on_edge(const struct tmesh *t, const struct vt_cut_result *r, uint32_t p, struct pair e)
{
    struct pair pe;
    if (p < t->position_count)
        return p == e.a || p == e.b;
    return edge_of_point(t, r, p, &pe) && compare_pairs(&pe, &e) == 0;
}

/* The edge of input face f that output edge (a, b) lies on (both ends on it), or false. */
static bool own_edge(const struct tmesh *t, const struct vt_cut_result *r, uint32_t f, uint32_t a,
                     uint32_t b, struct pair *e)
{
    uint64_t c0 = t->face_start[f], n = t->face_start[f + 1] - c0;
    for (uint64_t i = 0; i < n; i++) {
        *e = make_pair(t->pos[c0 + i], t->pos[c0 + (i + 1) % n]);
        if (on_edge(t, r, a, *e) && on_edge(t, r, b, *e))
            return true;
    }
    return false;
}

/* One use of an output edge: the pair, and the input edge of its own face it lies on (on.a ==
 * VT_CHART_NONE: inside the face, then face says which). */
struct use {
    struct pair e, on;
    uint32_t face;
};

static int compare_uses(const void *pa, const void *pb)
{
    const struct use *x = pa, *y = pb;
    int c = compare_pairs(&x->e, &y->e);
    if (c)
        return c;
    if (x->on.a == VT_CHART_NONE || y->on.a == VT_CHART_NONE) {
        if ((x->on.a == VT_CHART_NONE) != (y->on.a == VT_CHART_NONE))
            return x->on.a == VT_CHART_NONE ? 1 : -1;
        return x->face < y->face ? -1 : x->face > y->face;
    }
    return 0;
}

struct uses {
    struct use *u;
    uint64_t n, cap;
};

static void add_use(const struct tmesh *t, const struct vt_cut_result *r, struct uses *us,
                    uint32_t f, uint32_t a, uint32_t b)
{
    if (a == b)
        return; /* zero length */
    us->u = grow(us->u, &us->cap, us->n + 1, sizeof *us->u);
    struct use *u = &us->u[us->n++];
    u->e = make_pair(a, b);
    u->face = f;
    if (!own_edge(t, r, f, a, b, &u->on))
        u->on = (struct pair){VT_CHART_NONE, VT_CHART_NONE};
}

/* Every edge of every output polygon (a kept face's own), with where it lies. */
static void output_uses(const struct tmesh *t, const struct vt_cut_result *r, struct uses *us)
{
    for (uint32_t f = 0; f < t->face_count; f++) {
        if (!r->changed[f]) {
            uint64_t c0 = t->face_start[f], n = t->face_start[f + 1] - c0;
            for (uint64_t i = 0; i < n; i++)
                add_use(t, r, us, f, t->pos[c0 + i], t->pos[c0 + (i + 1) % n]);
            continue;
        }
        for (uint64_t q = r->face_poly[f]; q < r->face_poly[f + 1]; q++) {
            uint64_t c0 = r->poly_start[q], n = r->poly_start[q + 1] - c0;
            for (uint64_t i = 0; i < n; i++)
                add_use(t, r, us, f, r->corners[c0 + i].pos, r->corners[c0 + (i + 1) % n].pos);
        }
    }
}

int cut_fixture_check_watertight(const struct tmesh *t, const struct vt_cut_result *r, bool closed,
                                 bool verbose)
{
    struct pairs in = {0};
    struct uses out = {0};
    for (uint32_t f = 0; f < t->face_count; f++) {
        uint64_t c0 = t->face_start[f], n = t->face_start[f + 1] - c0;
        /* a face that vanished (zero area, cut_fixture_check_pieces() checks) has no edges left */
        if (r->changed[f] && r->face_poly[f] == r->face_poly[f + 1])
            continue;
        for (uint64_t i = 0; i < n; i++)
            add_pair(&in, t->pos[c0 + i], t->pos[c0 + (i + 1) % n]);
    }
    output_uses(t, r, &out);
    if (in.n)
        qsort(in.p, (size_t)in.n, sizeof *in.p, compare_pairs);
    if (out.n)
        qsort(out.u, (size_t)out.n, sizeof *out.u, compare_uses);
    int bad = 0;
    for (uint64_t i = 0; i < out.n;) {
        uint64_t j = i;
        while (j < out.n && compare_uses(&out.u[j], &out.u[i]) == 0)
            j++;
        const struct use *u = &out.u[i];
        bool inside = u->on.a == VT_CHART_NONE;
        uint64_t want = inside ? 2 : count_pair(in.p, in.n, u->on);
        if (j - i != want || (closed && j - i < 2)) {
            if (verbose && bad < 5)
                fprintf(stderr, "watertight: edge %u-%u %s%u has %llu faces, %llu expected\n",
                        u->e.a, u->e.b, inside ? "inside face " : "on input edge ",
                        inside ? u->face : u->on.a, (unsigned long long)(j - i),
                        (unsigned long long)want);
            bad++;
        }
        i = j;
    }
    free(in.p);
    free(out.u);
    return bad;
}

/* ---- pieces ---- */

static double uv_area2(const double *u, const double *v, uint64_t n)
{
    double s = 0;
    for (uint64_t i = 1; i + 1 < n; i++)
        s += (u[i] - u[0]) * (v[i + 1] - v[0]) - (u[i + 1] - u[0]) * (v[i] - v[0]);
    return s;
}

/* Twice the vector area of the polygon of points xyz (3 per point). */
static void vec_area2(const double *xyz, uint64_t n, double out[3])
{
    out[0] = out[1] = out[2] = 0;
    for (uint64_t i = 1; i + 1 < n; i++) {
        double a[3], b[3];
        for (int k = 0; k < 3; k++) {
            a[k] = xyz[3 * i + k] - xyz[k];
            b[k] = xyz[3 * (i + 1) + k] - xyz[k];
        }
        out[0] += a[1] * b[2] - a[2] * b[1];
        out[1] += a[2] * b[0] - a[0] * b[2];
        out[2] += a[0] * b[1] - a[1] * b[0];
    }
}

static double norm3(const double *a)
{
    return sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
}

/* The input texcoord of output corner c of face f (its weights over the face's corners). */
static void input_uv(const struct tmesh *t, uint32_t f, const struct vt_cut_corner *c, double uv[2])
{
    uv[0] = uv[1] = 0;
    for (int i = 0; i < 3; i++) {
        if (c->src[i] == VT_CHART_NONE)
            continue;
        const double *in = t->uv + 2 * (size_t)t->tex[t->face_start[f] + c->src[i]];
        uv[0] += c->w[i] * in[0];
        uv[1] += c->w[i] * in[1];
    }
}

struct scratch {
    double *u, *v, *xyz;
    uint64_t cap_uv, cap_v, cap_xyz;
};

static int check_polygon_uv(const struct tmesh *t, const struct vt_cut_result *r, uint32_t f,
                            uint64_t q, double tol, bool verbose)
{
    int bad = 0;
    double n0[2] = {0, 0};
    for (uint64_t c = r->poly_start[q]; c < r->poly_start[q + 1]; c++) {
        const struct vt_cut_corner *k = &r->corners[c];
        double in[2], d[2] = {0, 0};
        input_uv(t, f, k, in);
        for (int a = 0; a < 2; a++) {
            double x = a ? k->v : k->u;
            d[a] = x - in[a];
            double slack = tol * (1 + fabs(in[a]));
            if (c == r->poly_start[q])
                n0[a] = round(d[a]);
            if (fabs(d[a] - n0[a]) > slack)
                bad++;
            if (t->wrap[f] && t->group[f] != VT_CHART_NONE && (x < 0 || x > 1))
                bad++;
        }
        if (bad && verbose)
            fprintf(stderr,
                    "pieces: face %u polygon %llu corner %llu: uv %.17g %.17g, input "
                    "%.17g %.17g\n",
                    f, (unsigned long long)q, (unsigned long long)c, k->u, k->v, in[0], in[1]);
        if (bad)
            return bad;
    }
    return 0;
}

/* Areas of face f and of its output polygons. */
static int check_face_area(const struct tmesh *t, const struct vt_cut_result *r, uint32_t f,
                           double tol, bool verbose, struct scratch *s)
{
    uint64_t c0 = t->face_start[f], n = t->face_start[f + 1] - c0;
    bool uv = true;
    s->u = grow(s->u, &s->cap_uv, n, sizeof *s->u);
    s->v = grow(s->v, &s->cap_v, n, sizeof *s->v);
    s->xyz = grow(s->xyz, &s->cap_xyz, 3 * n, sizeof *s->xyz);
    double umin = INFINITY, umax = -INFINITY, vmin = INFINITY, vmax = -INFINITY;
    for (uint64_t i = 0; i < n; i++) {
        uv &= t->tex[c0 + i] != VT_CHART_NONE;
        if (uv) {
            s->u[i] = t->uv[2 * (size_t)t->tex[c0 + i]];
            s->v[i] = t->uv[2 * (size_t)t->tex[c0 + i] + 1];
            umin = fmin(umin, s->u[i]), umax = fmax(umax, s->u[i]);
            vmin = fmin(vmin, s->v[i]), vmax = fmax(vmax, s->v[i]);
        }
        memcpy(s->xyz + 3 * i, t->xyz + 3 * (size_t)t->pos[c0 + i], 3 * sizeof(double));
    }
    double face_uv = uv ? uv_area2(s->u, s->v, n) : 0, face_3d[3], sum_uv = 0, sum_abs = 0;
    double sum_3d[3] = {0, 0, 0};
    vec_area2(s->xyz, n, face_3d);
    for (uint64_t q = r->face_poly[f]; q < r->face_poly[f + 1]; q++) {
        uint64_t p0 = r->poly_start[q], pn = r->poly_start[q + 1] - p0;
        s->u = grow(s->u, &s->cap_uv, pn, sizeof *s->u);
        s->v = grow(s->v, &s->cap_v, pn, sizeof *s->v);
        s->xyz = grow(s->xyz, &s->cap_xyz, 3 * pn, sizeof *s->xyz);
        for (uint64_t i = 0; i < pn; i++) {
            s->u[i] = r->corners[p0 + i].u;
            s->v[i] = r->corners[p0 + i].v;
            cut_fixture_position(t, r, r->corners[p0 + i].pos, s->xyz + 3 * i);
        }
        double a = uv ? uv_area2(s->u, s->v, pn) : 0, v3[3];
        sum_uv += a;
        sum_abs += fabs(a);
        vec_area2(s->xyz, pn, v3);
        for (int k = 0; k < 3; k++)
            sum_3d[k] += v3[k];
    }
    /* 3D: relative to the square of the face's size, which also holds for a face of no area */
    double box = (umax - umin) * (vmax - vmin), d3[3], size2 = 0, mag2 = 0;
    for (uint64_t i = 0; i < n; i++) {
        double d[3];
        const double *x = t->xyz + 3 * (size_t)t->pos[c0 + i];
        for (int k = 0; k < 3; k++)
            d[k] = x[k] - t->xyz[3 * (size_t)t->pos[c0] + k];
        size2 = fmax(size2, d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        mag2 = fmax(mag2, x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    }
    for (int k = 0; k < 3; k++)
        d3[k] = sum_3d[k] - face_3d[k];
    int bad = 0;
    /* the pieces of a triangle (convex) all have its orientation; those of an n-gon, which may
     * be concave or self-intersecting, sum to its signed area only */
    if (uv && (fabs(sum_uv - face_uv) > tol * (box + 1e-300) ||
               (n == 3 && fabs(sum_abs - fabs(face_uv)) > tol * (box + 1e-300))))
        bad++;
    if (n == 3 && norm3(d3) > tol * (norm3(face_3d) + size2) + 1e-13 * mag2)
        bad++;
    /* a face may vanish only when it has no area at all */
    if (r->face_poly[f] == r->face_poly[f + 1] && (norm3(face_3d) != 0 || face_uv != 0))
        bad++;
    if (bad && verbose)
        fprintf(stderr,
                "pieces: face %u: uv area %.17g (|%.17g|) for %.17g, 3D %.17g for "
                "%.17g\n",
                f, sum_uv / 2, sum_abs / 2, face_uv / 2, norm3(sum_3d) / 2, norm3(face_3d) / 2);
    return bad;
}

int cut_fixture_check_pieces(const struct tmesh *t, const struct vt_cut_result *r, double tol,
                             bool verbose)
{
    int bad = 0;
    struct scratch s = {0};
    for (uint32_t f = 0; f < t->face_count; f++) {
        uint64_t c0 = t->face_start[f], n = t->face_start[f + 1] - c0;
        bool uv = true;
        for (uint64_t i = 0; i < n; i++)
            uv &= t->tex[c0 + i] != VT_CHART_NONE;
        if (!r->changed[f]) {
            if (r->face_poly[f] != r->face_poly[f + 1])
                bad++;
            for (int a = 0; a < 2 && uv && t->wrap[f] && t->group[f] != VT_CHART_NONE; a++) {
                double sh = r->face_shift[2 * (size_t)f + a];
                if (sh != floor(sh))
                    bad++;
                for (uint64_t i = 0; i < n; i++) {
                    double x = t->uv[2 * (size_t)t->tex[c0 + i] + a] + sh;
                    if (x < -tol || x > 1 + tol)
                        bad++;
                }
            }
            continue;
        }
        for (uint64_t q = r->face_poly[f]; q < r->face_poly[f + 1] && uv; q++)
            bad += check_polygon_uv(t, r, f, q, tol, verbose);
        bad += check_face_area(t, r, f, tol, verbose, &s);
    }
    free(s.u);
    free(s.v);
    free(s.xyz);
    return bad;
}

/* ---- random points ---- */

static uint64_t next_random(uint64_t *state)
{
    uint64_t z = (*state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

static double random01(uint64_t *state)
{
    return (double)(next_random(state) >> 11) * 0x1p-53;
}

/* The position of triangle f at texcoord (u, v) of a polygon moved by (nu, nv) from the input,
 * false for a triangle of zero UV area. The triangle is moved (exactly, for whole repeats towards
 * 0), not the point back, so that far repeats keep the precision of the cut's own frame. *slack:
 * how far a position can be off only because texcoords of this magnitude are rounded (the
 * rounding of one ulp, through the triangle's conditioning: its UV size over its UV area). */
static bool triangle_at(const struct tmesh *t, uint32_t f, double u, double v, double nu, double nv,
                        double out[3], double *slack)
{
    uint64_t c0 = t->face_start[f];
    double q[3][2];
    for (int i = 0; i < 3; i++) {
        q[i][0] = t->uv[2 * (size_t)t->tex[c0 + i]] + nu;
        q[i][1] = t->uv[2 * (size_t)t->tex[c0 + i] + 1] + nv;
    }
    const double *t0 = q[0], *t1 = q[1], *t2 = q[2];
    double e1u = t1[0] - t0[0], e1v = t1[1] - t0[1], e2u = t2[0] - t0[0], e2v = t2[1] - t0[1];
    double det = e1u * e2v - e1v * e2u, pu = u - t0[0], pv = v - t0[1];
    if (det == 0)
        return false;
    double l1 = (pu * e2v - pv * e2u) / det, l2 = (e1u * pv - e1v * pu) / det, l0 = 1 - l1 - l2;
    const double *p0 = t->xyz + 3 * (size_t)t->pos[c0], *p1 = t->xyz + 3 * (size_t)t->pos[c0 + 1],
                 *p2 = t->xyz + 3 * (size_t)t->pos[c0 + 2];
    double mag = 0, uv_size = 0, size = 0;
    for (int k = 0; k < 3; k++) {
        out[k] = l0 * p0[k] + l1 * p1[k] + l2 * p2[k];
        mag = fmax(mag, fmax(fabs(q[k][0]), fabs(q[k][1])));
        const double *a = t->xyz + 3 * (size_t)t->pos[c0 + k],
                     *b = t->xyz + 3 * (size_t)t->pos[c0 + (k + 1) % 3];
        double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
        size = fmax(size, norm3(d));
        uv_size = fmax(uv_size, hypot(q[k][0] - q[(k + 1) % 3][0], q[k][1] - q[(k + 1) % 3][1]));
    }
    *slack = 16 * 0x1p-52 * fmax(mag, 1) * uv_size / fabs(det) * size;
    return true;
}

int cut_fixture_check_points(const struct tmesh *t, const struct vt_cut_result *r, uint64_t seed,
                             int points_per_polygon, double tol, bool verbose)
{
    int bad = 0;
    uint64_t state = seed;
    for (uint32_t f = 0; f < t->face_count; f++) {
        uint64_t c0 = t->face_start[f];
        if (!r->changed[f] || t->face_start[f + 1] - c0 != 3)
            continue;
        if (t->tex[c0] == VT_CHART_NONE || t->tex[c0 + 1] == VT_CHART_NONE ||
            t->tex[c0 + 2] == VT_CHART_NONE)
            continue;
        double scale = 1;
        for (int i = 0; i < 3; i++)
            scale = fmax(scale, norm3(t->xyz + 3 * (size_t)t->pos[c0 + i]));
        for (uint64_t q = r->face_poly[f]; q < r->face_poly[f + 1]; q++) {
            uint64_t p0 = r->poly_start[q], pn = r->poly_start[q + 1] - p0;
            const struct vt_cut_corner *k = &r->corners[p0];
            double in[2];
            input_uv(t, f, k, in);
            double nu = round(k->u - in[0]), nv = round(k->v - in[1]);
            for (int s = 0; s < points_per_polygon && pn >= 3; s++) {
                uint64_t i = 1 + next_random(&state) % (pn - 2);
                double a = random01(&state), b = random01(&state);
                if (a + b > 1)
                    a = 1 - a, b = 1 - b;
                double w[3] = {1 - a - b, a, b}, pos[3] = {0, 0, 0}, u = 0, v = 0;
                uint64_t idx[3] = {p0, p0 + i, p0 + i + 1};
                for (int j = 0; j < 3; j++) {
                    double x[3];
                    cut_fixture_position(t, r, r->corners[idx[j]].pos, x);
                    for (int d = 0; d < 3; d++)
                        pos[d] += w[j] * x[d];
                    u += w[j] * r->corners[idx[j]].u;
                    v += w[j] * r->corners[idx[j]].v;
                }
                double want[3], d[3], slack;
                if (!triangle_at(t, f, u, v, nu, nv, want, &slack))
                    break;
                for (int j = 0; j < 3; j++)
                    d[j] = pos[j] - want[j];
                if (norm3(d) > tol * scale + slack) {
                    if (verbose && bad < 5)
                        fprintf(stderr,
                                "points: face %u polygon %llu at uv %.17g %.17g: off by "
                                "%g\n",
                                f, (unsigned long long)q, u, v, norm3(d));
                    bad++;
                }
            }
        }
    }
    return bad;
}

static void *dup(const void *p, size_t bytes, size_t extra)
{
    void *q = malloc(bytes + extra ? bytes + extra : 1);
    if (!q)
        abort();
    if (bytes)
        memcpy(q, p, bytes);
    return q;
}

void cut_fixture_copy(const struct tmesh *t, const struct vt_cut_result *r, uint64_t extra,
                      struct vt_cut_result *copy)
{
    size_t faces = t->face_count;
    *copy = *r;
    copy->changed = dup(r->changed, faces, 0);
    copy->face_shift = dup(r->face_shift, 2 * faces * sizeof(double), 0);
    copy->face_poly = dup(r->face_poly, (faces + 1) * sizeof(uint64_t), 0);
    copy->poly_start = dup(r->poly_start, (size_t)(r->poly_count + 1) * sizeof(uint64_t), 0);
    copy->corners = dup(r->corners, (size_t)r->corner_count * sizeof *r->corners,
                        (size_t)extra * sizeof *r->corners);
    copy->vertices = dup(r->vertices, r->vertex_count * sizeof *r->vertices,
                         (size_t)extra * sizeof *r->vertices);
}
