/* vt-offset on a wrap entry (lib/offset/vt_offset_mesh.c with lib/chart): faces crossing integer
 * UV lines are cut, every piece lands in the entry's one copy, a neighbour face gets the cut's
 * points as corners, and the output mesh is read back with vt_obj (not with the rewriter's code)
 * and checked: every corner's atlas coordinate is its position's texture coordinate moved by a
 * whole repeat, no T-junction and no new boundary (each output edge is shared by as many faces as
 * the input edge it lies on), the same 3D area. A deliberately broken output fails the checks. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "offset_fixture.h"
#include "vt_obj.h"
#include "vt_test.h"

/* A mesh read back: positions, texcoords, faces as corner lists. */
struct mesh {
    double *pos, *uv;
    uint32_t npos, nuv;
    uint32_t *fv, *ft; /* corner v and vt (VT_OBJ_NONE without) */
    uint32_t *fstart;  /* face_count + 1 */
    uint32_t nface, ncorner, cap_face, cap_corner;
};

static int on_face(void *user, const struct vt_obj *obj, const struct vt_obj_face *f,
                   struct vts_error *err)
{
    (void)obj, (void)err;
    struct mesh *m = user;
    if (m->nface + 2 > m->cap_face) {
        m->cap_face = 2 * m->cap_face + 64;
        m->fstart = realloc(m->fstart, m->cap_face * sizeof *m->fstart);
    }
    if (m->ncorner + f->corner_count > m->cap_corner) {
        m->cap_corner = 2 * (m->cap_corner + f->corner_count) + 64;
        m->fv = realloc(m->fv, m->cap_corner * sizeof *m->fv);
        m->ft = realloc(m->ft, m->cap_corner * sizeof *m->ft);
    }
    if (m->nface == 0)
        m->fstart[0] = 0;
    for (uint32_t i = 0; i < f->corner_count; i++) {
        m->fv[m->ncorner] = f->corners[i].v;
        m->ft[m->ncorner++] = f->corners[i].vt;
    }
    m->fstart[++m->nface] = m->ncorner;
    return 0;
}

static void read_mesh(const char *text, struct mesh *m)
{
    memset(m, 0, sizeof *m);
    struct vt_obj *obj = vt_obj_create(NULL, NULL);
    struct vt_obj_callbacks cb = {.face = on_face, .user = m};
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(vt_obj_parse_memory(obj, text, strlen(text), "out.obj", &cb, &err), 0);
    VT_CHECK_STR_EQ(err.message, "");
    m->npos = vt_obj_position_count(obj);
    m->nuv = vt_obj_texcoord_count(obj);
    m->pos = malloc((m->npos + 1) * 3 * sizeof(double));
    m->uv = malloc((m->nuv + 1) * 3 * sizeof(double));
    memcpy(m->pos, vt_obj_positions(obj), m->npos * 3 * sizeof(double));
    memcpy(m->uv, vt_obj_texcoords(obj), m->nuv * 3 * sizeof(double));
    vt_obj_destroy(obj);
}

static void free_mesh(struct mesh *m)
{
    free(m->pos);
    free(m->uv);
    free(m->fv);
    free(m->ft);
    free(m->fstart);
}

static double face_area(const struct mesh *m, uint32_t f)
{
    double a = 0;
    const double *p0 = m->pos + 3 * m->fv[m->fstart[f]];
    for (uint32_t k = m->fstart[f] + 1; k + 1 < m->fstart[f + 1]; k++) {
        const double *p1 = m->pos + 3 * m->fv[k], *p2 = m->pos + 3 * m->fv[k + 1];
        double u[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
        double w[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
        double c[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2],
                       u[0] * w[1] - u[1] * w[0]};
        a += 0.5 * sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    }
    return a;
}

static double total_area(const struct mesh *m)
{
    double a = 0;
    for (uint32_t f = 0; f < m->nface; f++)
        a += face_area(m, f);
    return a;
}

/* True when point p lies on segment a-b (within 1e-9). */
static int on_segment(const double *p, const double *a, const double *b)
{
    double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double ap[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
    double l2 = ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2];
    double t = (ap[0] * ab[0] + ap[1] * ab[1] + ap[2] * ab[2]) / l2;
    if (t < -1e-9 || t > 1 + 1e-9)
        return 0;
    double d[3] = {ap[0] - t * ab[0], ap[1] - t * ab[1], ap[2] - t * ab[2]};
    return d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < 1e-18;
}

/* Faces using the undirected edge of positions (a, b), by position value (new vertices are new
 * indices at the same place as nothing else). */
static int edge_uses(const struct mesh *m, const double *a, const double *b)
{
    int n = 0;
    for (uint32_t f = 0; f < m->nface; f++)
        for (uint32_t k = m->fstart[f]; k < m->fstart[f + 1]; k++) {
            uint32_t k2 = k + 1 < m->fstart[f + 1] ? k + 1 : m->fstart[f];
            const double *p = m->pos + 3 * m->fv[k], *q = m->pos + 3 * m->fv[k2];
            if ((!memcmp(p, a, 24) && !memcmp(q, b, 24)) ||
                (!memcmp(p, b, 24) && !memcmp(q, a, 24)))
                n++;
        }
    return n;
}

/* The watertight check: every output edge is shared by as many output faces as the input edge
 * it lies on has input faces, or by 2 when it lies inside an input face. Returns the number of
 * offending edges. */
static int watertight_errors(const struct mesh *in, const struct mesh *out)
{
    int bad = 0;
    for (uint32_t f = 0; f < out->nface; f++)
        for (uint32_t k = out->fstart[f]; k < out->fstart[f + 1]; k++) {
            uint32_t k2 = k + 1 < out->fstart[f + 1] ? k + 1 : out->fstart[f];
            const double *p = out->pos + 3 * out->fv[k], *q = out->pos + 3 * out->fv[k2];
            int uses = edge_uses(out, p, q), want = 2;
            for (uint32_t g = 0; g < in->nface; g++)
                for (uint32_t j = in->fstart[g]; j < in->fstart[g + 1]; j++) {
                    uint32_t j2 = j + 1 < in->fstart[g + 1] ? j + 1 : in->fstart[g];
                    const double *a = in->pos + 3 * in->fv[j], *b = in->pos + 3 * in->fv[j2];
                    if (on_segment(p, a, b) && on_segment(q, a, b))
                        want = edge_uses(in, a, b);
                }
            if (uses != want) {
                if (bad < 5)
                    fprintf(stderr, "edge (%g %g)-(%g %g): %d faces, want %d\n", p[0], p[1], q[0],
                            q[1], uses, want);
                bad++;
            }
        }
    return bad;
}

/* The texcoord check on the strip: position x has material u = x + 0.5, y has v = y. Every
 * corner's atlas coordinate, taken back to the entry (64x64 at 32, 32 of a 128 atlas), must be
 * in [0,1] and differ from (x + 0.5, y) by whole repeats. Returns the offending corners. */
static int texcoord_errors(const struct mesh *m)
{
    int bad = 0;
    for (uint32_t k = 0; k < m->ncorner; k++) {
        if (m->ft[k] == VT_OBJ_NONE)
            continue;
        const double *p = m->pos + 3 * m->fv[k], *t = m->uv + 3 * m->ft[k];
        double mu = (t[0] * 128 - 32) / 64, mv = 1 - ((1 - t[1]) * 128 - 32) / 64;
        double du = mu - (p[0] + 0.5), dv = mv - p[1];
        if (mu < -1e-9 || mu > 1 + 1e-9 || mv < -1e-9 || mv > 1 + 1e-9 ||
            fabs(du - round(du)) > 1e-9 || fabs(dv - round(dv)) > 1e-9) {
            if (bad < 5)
                fprintf(stderr, "corner at (%g %g): material uv %.12g %.12g\n", p[0], p[1], mu, mv);
            bad++;
        }
    }
    return bad;
}

/* A strip x 0..3, y 0..1 of three quads (six triangles, shared v and vt) with u = x + 0.5, so
 * lines u = 1, 2, 3 cut it at x = 0.5, 1.5, 2.5; below it a triangle without texcoords shares the
 * strip's bottom edge from x 0 to 1. */
static const char strip[] = "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 3 0 0\n"
                            "v 0 1 0\nv 1 1 0\nv 2 1 0\nv 3 1 0\nv 0.5 -1 0\n"
                            "vt 0.5 0\nvt 1.5 0\nvt 2.5 0\nvt 3.5 0\n"
                            "vt 0.5 1\nvt 1.5 1\nvt 2.5 1\nvt 3.5 1\n"
                            "vn 0 0 1\n"
                            "usemtl road\n"
                            "f 1/1/1 2/2/1 6/6/1\nf 1/1/1 6/6/1 5/5/1\n"
                            "f 2/2/1 3/3/1 7/7/1\nf 2/2/1 7/7/1 6/6/1\n"
                            "f 3/3/1 4/4/1 8/8/1\nf 3/3/1 8/8/1 7/7/1\n"
                            "g below\nf 9 2 1\n";

static void cuts_a_strip_without_cracks(void)
{
    static const struct spec rects[] = {{"road", 32, 32, 64, 64, 1, 1, 0, 0}};
    struct vt_layout l;
    offset_fixture_layout(&l, 128, 128, rects, 1);
    l.entries[0].wrap = true;
    struct membuf out;
    struct vt_offset_stats s;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(offset_fixture_rewrite(strip, &l, 0, &out, &s, &err), 0);
    VT_CHECK_STR_EQ(err.message, "");
    /* each quad's diagonal and both triangles cross one line: all six are cut */
    VT_CHECK_INT_EQ(s.faces_cut, 6);
    VT_CHECK_INT_EQ(s.faces_split, 1); /* the triangle below */
    VT_CHECK(s.pieces >= 12);
    VT_CHECK(s.positions_added >= 6); /* 3 lines x 2 strip edges, plus the diagonals' points */
    VT_CHECK(strstr(out.data, "\ng below\n") != NULL); /* other lines are kept */
    struct mesh in, o;
    read_mesh(strip, &in);
    read_mesh(out.data, &o);
    VT_CHECK_INT_EQ(o.npos, in.npos + (uint32_t)s.positions_added);
    VT_CHECK(fabs(total_area(&o) - total_area(&in)) < 1e-12);
    VT_CHECK_INT_EQ(texcoord_errors(&o), 0);
    VT_CHECK_INT_EQ(watertight_errors(&in, &o), 0);
    /* the checks can fail: a piece dropped opens a hole, a vt moved by a texel is caught */
    struct mesh broken = o;
    broken.nface = o.nface - 1;
    VT_CHECK(watertight_errors(&in, &broken) > 0);
    VT_CHECK(fabs(total_area(&broken) - total_area(&in)) > 1e-6);
    o.uv[3 * o.ft[0]] += 1.0 / 128;
    VT_CHECK(texcoord_errors(&o) > 0);
    free_mesh(&in);
    free_mesh(&o);
    free(out.data);
    vt_layout_release(&l);
}

/* The same strip on a plain (non-wrap) entry of 4 copies: nothing is cut, the chart is moved by
 * nothing (it starts in [0,1)) and every position and normal index is kept. */
static void does_not_cut_without_wrap(void)
{
    static const struct spec rects[] = {{"road", 0, 0, 64, 64, 4, 1, 0, 0}};
    struct vt_layout l;
    offset_fixture_layout(&l, 256, 64, rects, 1);
    struct membuf out;
    struct vt_offset_stats s;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(offset_fixture_rewrite(strip, &l, 0, &out, &s, &err), 0);
    VT_CHECK_INT_EQ(s.faces_cut, 0);
    VT_CHECK_INT_EQ(s.faces_split, 0);
    VT_CHECK_INT_EQ(s.positions_added, 0);
    VT_CHECK(strstr(out.data, "f 1/1/1 2/2/1 6/6/1\n") != NULL);
    VT_CHECK(strstr(out.data, "f 9 2 1\n") != NULL);
    free(out.data);
    vt_layout_release(&l);
}

int main(void)
{
    VT_RUN(cuts_a_strip_without_cracks);
    VT_RUN(does_not_cut_without_wrap);
    return vt_test_main_result();
}
