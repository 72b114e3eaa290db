/* lib/chart/vt_cut*.c: faces cut along the integer UV lines. Every case is checked by the
 * fixture's independent checkers (watertightness by edge counts, areas in UV and 3D, texcoords in
 * [0, 1]^2 and equal to the input's plus an integer vector, 3D positions at random points); a
 * corrupted result is shown to fail them. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cut_fixture.h"
#include "vt_test.h"

#define PI 3.14159265358979323846

/* Cuts t with its charts' moves; returns the status (err filled). */
static int run_cut(struct tmesh *t, struct vt_cut_result *r, struct vts_error *err)
{
    tmesh_shift_charts(t);
    struct vt_chart_mesh m = tmesh_view(t);
    return vt_cut(&m, t->wrap, t->shift, r, err);
}

/* All the fixture's checks on a successful result. */
static void check_result(const struct tmesh *t, const struct vt_cut_result *r, bool closed)
{
    VT_CHECK_INT_EQ(cut_fixture_check_watertight(t, r, closed, true), 0);
    VT_CHECK_INT_EQ(cut_fixture_check_pieces(t, r, 1e-9, true), 0);
    VT_CHECK_INT_EQ(cut_fixture_check_points(t, r, 42, 8, 1e-9, true), 0);
    /* weights: one source corner per input corner, two per edge point, three inside a face */
    for (uint64_t c = 0; c < r->corner_count; c++) {
        const struct vt_cut_corner *k = &r->corners[c];
        int used = 0;
        double sum = 0;
        for (int i = 0; i < 3; i++) {
            used += k->src[i] != VT_CHART_NONE;
            sum += k->src[i] != VT_CHART_NONE ? k->w[i] : 0;
        }
        VT_CHECK(fabs(sum - 1) < 1e-12);
        int want = k->pos < t->position_count                                        ? 1
                   : r->vertices[k->pos - t->position_count].pos[2] == VT_CHART_NONE ? 2
                                                                                     : 3;
        VT_CHECK(used == want || (want == 3 && used == 1)); /* 1: a flat face's fallback */
    }
}

/* Twice the UV area of output polygon q. */
static double poly_area2(const struct vt_cut_result *r, uint64_t q)
{
    uint64_t c0 = r->poly_start[q], n = r->poly_start[q + 1] - c0;
    double s = 0;
    const struct vt_cut_corner *k = r->corners + c0;
    for (uint64_t i = 1; i + 1 < n; i++)
        s += (k[i].u - k[0].u) * (k[i + 1].v - k[0].v) - (k[i + 1].u - k[0].u) * (k[i].v - k[0].v);
    return s;
}

/* The smallest UV area of the output polygons (every piece should have one). */
static double min_piece_area(const struct vt_cut_result *r)
{
    double mn = INFINITY;
    for (uint64_t q = 0; q < r->poly_count; q++)
        mn = fmin(mn, fabs(poly_area2(r, q)) / 2);
    return mn;
}

/* A roof 0..8 x 0..4 in UV (a plane in 3D), as two triangles sharing texcoords. */
static void roof(struct tmesh *t)
{
    tmesh_init(t);
    double uv[4][2] = {{0, 0}, {8, 0}, {8, 4}, {0, 4}};
    uint32_t p[4], tx[4];
    for (int i = 0; i < 4; i++) {
        p[i] = tmesh_pos(t, 1.5 * uv[i][0], 0.5 * uv[i][1], 0.8 * uv[i][1] + 0.1 * uv[i][0]);
        tx[i] = tmesh_tex(t, uv[i][0], uv[i][1]);
    }
    tmesh_face(t, 0, 3, (uint32_t[]){p[0], p[1], p[2]}, (uint32_t[]){tx[0], tx[1], tx[2]}, true);
    tmesh_face(t, 0, 3, (uint32_t[]){p[0], p[2], p[3]}, (uint32_t[]){tx[0], tx[2], tx[3]}, true);
}

static void cut_a_roof_of_8_by_4_repeats(void)
{
    struct tmesh t;
    struct vt_cut_result r;
    struct vts_error err = {0};
    roof(&t);
    VT_CHECK_INT_EQ(run_cut(&t, &r, &err), 0);
    VT_CHECK_INT_EQ(r.faces_cut, 2);
    VT_CHECK_INT_EQ(r.faces_split, 0);
    /* 32 cells; the diagonal v = u / 2 crosses 8 of them (through the grid points (2, 1), (4, 2),
     * (6, 3)), which get a piece of each triangle */
    VT_CHECK_INT_EQ(r.pieces, 40);
    VT_CHECK_INT_EQ(r.poly_count, 40);
    /* new positions: 20 on the outline, 7 on the diagonal (3 where a u and a v line meet on it),
     * 21 - 3 grid points inside */
    VT_CHECK_INT_EQ(r.vertex_count, 27 + 18);
    VT_CHECK(r.changed[0] && r.changed[1]);
    VT_CHECK(min_piece_area(&r) > 0.2);
    check_result(&t, &r, false);
    vt_cut_release(&r);
    vt_cut_release(&r); /* released twice: zeroed the first time */
    tmesh_release(&t);
}

static void broken_results_fail_the_checkers(void)
{
    struct tmesh t;
    struct vt_cut_result r, bad;
    struct vts_error err = {0};
    roof(&t);
    VT_CHECK_INT_EQ(run_cut(&t, &r, &err), 0);
    /* one piece dropped (the last of the last face) */
    cut_fixture_copy(&t, &r, 0, &bad);
    bad.poly_count--;
    bad.face_poly[t.face_count]--;
    VT_CHECK(cut_fixture_check_watertight(&t, &bad, false, false) > 0);
    VT_CHECK(cut_fixture_check_pieces(&t, &bad, 1e-9, false) > 0);
    vt_cut_release(&bad);
    /* one point of the shared diagonal (positions 0-2) not shared: face 0 gets its own copy */
    cut_fixture_copy(&t, &r, 1, &bad);
    uint32_t target = VT_CHART_NONE;
    for (uint32_t v = 0; v < r.vertex_count && target == VT_CHART_NONE; v++)
        if (r.vertices[v].pos[0] == 0 && r.vertices[v].pos[1] == 2 &&
            r.vertices[v].pos[2] == VT_CHART_NONE)
            target = t.position_count + v;
    VT_CHECK(target != VT_CHART_NONE);
    bad.vertices[bad.vertex_count] = r.vertices[target - t.position_count];
    uint32_t copy = t.position_count + bad.vertex_count++;
    for (uint64_t c = r.poly_start[r.face_poly[0]]; c < r.poly_start[r.face_poly[1]]; c++)
        if (bad.corners[c].pos == target)
            bad.corners[c].pos = copy;
    VT_CHECK(cut_fixture_check_watertight(&t, &bad, false, false) > 0);
    VT_CHECK_INT_EQ(cut_fixture_check_pieces(&t, &bad, 1e-9, false), 0); /* same geometry */
    vt_cut_release(&bad);
    /* a texcoord off by half a repeat, and one off by a whole repeat (out of [0, 1]) */
    cut_fixture_copy(&t, &r, 0, &bad);
    bad.corners[3].u = fmod(bad.corners[3].u + 0.5, 1.0);
    VT_CHECK(cut_fixture_check_pieces(&t, &bad, 1e-9, false) > 0);
    VT_CHECK(cut_fixture_check_points(&t, &bad, 1, 8, 1e-9, false) > 0);
    bad.corners[3].u = r.corners[3].u + 1;
    VT_CHECK(cut_fixture_check_pieces(&t, &bad, 1e-9, false) > 0);
    vt_cut_release(&bad);
    /* a new position moved along its edge */
    cut_fixture_copy(&t, &r, 0, &bad);
    bad.vertices[0].w[0] += 0.01;
    bad.vertices[0].w[1] -= 0.01;
    VT_CHECK(cut_fixture_check_points(&t, &bad, 1, 8, 1e-9, false) > 0);
    vt_cut_release(&bad);
    vt_cut_release(&r);
    tmesh_release(&t);
}

static void cut_a_strip_from_minus_700_to_2600(void)
{
    struct tmesh t;
    tmesh_init(&t);
    double us[5] = {-700.25, -10.5, 800, 1700.75, 2600.5};
    uint32_t lo[5], hi[5], tlo[5], thi[5];
    for (int i = 0; i < 5; i++) {
        lo[i] = tmesh_pos(&t, us[i] * 0.01, 0, 1e-7 * us[i] * us[i]);
        hi[i] = tmesh_pos(&t, us[i] * 0.01, 1, 1e-7 * us[i] * us[i]);
        tlo[i] = tmesh_tex(&t, us[i], 0.25);
        thi[i] = tmesh_tex(&t, us[i], 0.75);
    }
    for (int i = 0; i < 4; i++) {
        tmesh_face(&t, 0, 3, (uint32_t[]){lo[i], lo[i + 1], hi[i + 1]},
                   (uint32_t[]){tlo[i], tlo[i + 1], thi[i + 1]}, true);
        tmesh_face(&t, 0, 3, (uint32_t[]){lo[i], hi[i + 1], hi[i]},
                   (uint32_t[]){tlo[i], thi[i + 1], thi[i]}, true);
    }
    struct vt_cut_result r;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(run_cut(&t, &r, &err), 0);
    VT_CHECK_INT_EQ(t.shift[0], 701);
    VT_CHECK_INT_EQ(r.faces_cut, 8);
    /* every column -701 .. 2600 gets a piece of both triangles of its quad, and the columns at
     * the quads' inner boundaries a piece of each of four triangles */
    VT_CHECK(r.pieces >= 2 * 3301);
    check_result(&t, &r, false);
    /* the input corners keep their exact value minus a whole number of repeats */
    for (uint64_t c = 0; c < r.corner_count; c++) {
        const struct vt_cut_corner *k = &r.corners[c];
        if (k->pos >= t.position_count)
            continue;
        uint32_t f = 0;
        while (r.face_poly[f + 1] <= 0 || r.poly_start[r.face_poly[f + 1]] <= c)
            f++;
        double u = t.uv[2 * (size_t)t.tex[t.face_start[f] + k->src[0]]];
        VT_CHECK(k->u == u - floor(u) || (k->u == 1 && u == floor(u)) ||
                 (k->u == 0 && u == floor(u)));
    }
    vt_cut_release(&r);
    tmesh_release(&t);
}

static void cut_a_triangle_with_a_vertex_on_a_line(void)
{
    struct tmesh t;
    tmesh_init(&t);
    uint32_t p[3] = {tmesh_pos(&t, 0, 0, 0), tmesh_pos(&t, 1, 0, 0), tmesh_pos(&t, 0.5, 0.7, 0.2)};
    uint32_t tx[3] = {tmesh_tex(&t, 0.5, 0.2), tmesh_tex(&t, 1.5, 0.2), tmesh_tex(&t, 1.0, 0.9)};
    tmesh_face(&t, 0, 3, p, tx, true);
    /* a second triangle that only touches u = 2 with a vertex: not cut, moved into its cell */
    uint32_t q[3] = {tmesh_pos(&t, 5, 0, 0), tmesh_pos(&t, 6, 0, 0), tmesh_pos(&t, 5, 1, 0)};
    uint32_t tq[3] = {tmesh_tex(&t, 7.2, -3.8), tmesh_tex(&t, 8.0, -3.5), tmesh_tex(&t, 7.2, -3.2)};
    tmesh_face(&t, 1, 3, q, tq, true);
    struct vt_cut_result r;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(run_cut(&t, &r, &err), 0);
    VT_CHECK_INT_EQ(r.faces_cut, 1);
    VT_CHECK_INT_EQ(r.pieces, 2);
    VT_CHECK_INT_EQ(r.vertex_count, 1); /* on the bottom edge; the chord ends at the vertex */
    VT_CHECK_INT_EQ(r.poly_start[1], 3);
    VT_CHECK_INT_EQ(r.poly_start[2], 6);
    VT_CHECK(!r.changed[1]);
    VT_CHECK(r.face_shift[2] == -7 && r.face_shift[3] == 4);
    check_result(&t, &r, false);
    vt_cut_release(&r);
    tmesh_release(&t);
}

static void cut_a_face_with_an_edge_on_a_line(void)
{
    struct tmesh t;
    tmesh_init(&t);
    uint32_t p[4] = {tmesh_pos(&t, 1, 0.25, 0), tmesh_pos(&t, 2.5, 0.5, 0.3),
                     tmesh_pos(&t, 1, 2.75, 0), tmesh_pos(&t, 0.2, 1.5, -0.4)};
    uint32_t tx[4] = {tmesh_tex(&t, 1, 0.25), tmesh_tex(&t, 2.5, 0.5), tmesh_tex(&t, 1, 2.75),
                      tmesh_tex(&t, 0.2, 1.5)};
    /* both faces have the edge 0-2 on u = 1, on either side */
    tmesh_face(&t, 0, 3, (uint32_t[]){p[0], p[1], p[2]}, (uint32_t[]){tx[0], tx[1], tx[2]}, true);
    tmesh_face(&t, 0, 3, (uint32_t[]){p[2], p[3], p[0]}, (uint32_t[]){tx[2], tx[3], tx[0]}, true);
    struct vt_cut_result r;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(run_cut(&t, &r, &err), 0);
    VT_CHECK_INT_EQ(r.faces_cut, 2);
    VT_CHECK(min_piece_area(&r) > 1e-3); /* no sliver along u = 1 */
    /* the shared edge's points at v = 1 and v = 2 exist once */
    uint32_t on_edge = 0;
    for (uint32_t v = 0; v < r.vertex_count; v++)
        on_edge += r.vertices[v].pos[0] == p[0] && r.vertices[v].pos[1] == p[2];
    VT_CHECK_INT_EQ(on_edge, 2);
    check_result(&t, &r, false);
    vt_cut_release(&r);
    tmesh_release(&t);
}

static void cut_splits_a_neighbour_without_texcoords(void)
{
    struct tmesh t;
    tmesh_init(&t);
    uint32_t p[4] = {tmesh_pos(&t, 0, 0, 0), tmesh_pos(&t, 3, 0, 0), tmesh_pos(&t, 1.5, 2, 0),
                     tmesh_pos(&t, 1.5, -2, 1)};
    uint32_t tx[3] = {tmesh_tex(&t, 0.5, 0.5), tmesh_tex(&t, 3.5, 0.5), tmesh_tex(&t, 2, 2.5)};
    tmesh_face(&t, 0, 3, (uint32_t[]){p[0], p[1], p[2]}, tx, true);
    tmesh_face(&t, 1, 3, (uint32_t[]){p[1], p[0], p[3]}, NULL, false);
    struct vt_cut_result r;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(run_cut(&t, &r, &err), 0);
    VT_CHECK_INT_EQ(r.faces_cut, 1);
    VT_CHECK_INT_EQ(r.faces_split, 1);
    VT_CHECK(r.changed[1]);
    VT_CHECK_INT_EQ(r.face_poly[2] - r.face_poly[1], 1);
    uint64_t q = r.face_poly[1], c0 = r.poly_start[q];
    /* u = 1, 2, 3 cross the shared edge: three extra corners, from p1 to p0 */
    VT_CHECK_INT_EQ(r.poly_start[q + 1] - c0, 6);
    VT_CHECK_INT_EQ(r.corners[c0].pos, p[1]);
    VT_CHECK_INT_EQ(r.corners[c0 + 4].pos, p[0]);
    for (int i = 1; i <= 3; i++) {
        const struct vt_cut_corner *k = &r.corners[c0 + i];
        VT_CHECK(!k->has_uv && k->pos >= t.position_count);
        VT_CHECK(k->src[0] == 0 && k->src[1] == 1 && k->src[2] == VT_CHART_NONE);
        /* from p1 (x = 3) towards p0: u = 3, 2, 1 at x = 2.5, 1.5, 0.5 */
        double x[3];
        cut_fixture_position(&t, &r, k->pos, x);
        VT_CHECK(fabs(x[0] - (3.5 - i)) < 1e-12 && x[1] == 0 && x[2] == 0);
    }
    check_result(&t, &r, false);
    vt_cut_release(&r);
    tmesh_release(&t);
}

/* A torus of nu x nv quads (as quads, or each as two triangles) with texcoords 0..6 x 0..3 and a
 * seam at i = 0 and j = 0: a closed mesh. */
static void torus(struct tmesh *t, int nu, int nv, bool triangles)
{
    tmesh_init(t);
    for (int j = 0; j < nv; j++)
        for (int i = 0; i < nu; i++) {
            double a = 2 * PI * i / nu, b = 2 * PI * j / nv;
            tmesh_pos(t, (3 + cos(b)) * cos(a), (3 + cos(b)) * sin(a), sin(b));
        }
    for (int j = 0; j <= nv; j++)
        for (int i = 0; i <= nu; i++)
            tmesh_tex(t, 6.0 * i / nu, 3.0 * j / nv);
    for (int j = 0; j < nv; j++)
        for (int i = 0; i < nu; i++) {
            uint32_t p[4] = {(uint32_t)(j * nu + i), (uint32_t)(j * nu + (i + 1) % nu),
                             (uint32_t)((j + 1) % nv * nu + (i + 1) % nu),
                             (uint32_t)((j + 1) % nv * nu + i)};
            uint32_t w = (uint32_t)nu + 1;
            uint32_t tx[4] = {(uint32_t)j * w + (uint32_t)i, (uint32_t)j * w + (uint32_t)i + 1,
                              (uint32_t)(j + 1) * w + (uint32_t)i + 1,
                              (uint32_t)(j + 1) * w + (uint32_t)i};
            if (!triangles) {
                tmesh_face(t, 0, 4, p, tx, true);
                continue;
            }
            tmesh_face(t, 0, 3, (uint32_t[]){p[0], p[1], p[2]}, (uint32_t[]){tx[0], tx[1], tx[2]},
                       true);
            tmesh_face(t, 0, 3, (uint32_t[]){p[0], p[2], p[3]}, (uint32_t[]){tx[0], tx[2], tx[3]},
                       true);
        }
}

static void cut_keeps_a_closed_torus_watertight(void)
{
    for (int tri = 0; tri < 2; tri++) {
        struct tmesh t;
        torus(&t, 7, 5, tri);
        struct vt_cut_result r;
        struct vts_error err = {0};
        VT_CHECK_INT_EQ(run_cut(&t, &r, &err), 0);
        VT_CHECK(r.faces_cut > t.face_count / 2);
        check_result(&t, &r, true);
        vt_cut_release(&r);
        tmesh_release(&t);
    }
    /* a grid whose lines fall on the mesh's own edges (12 x 6: every edge on a line or between) */
    struct tmesh t;
    torus(&t, 12, 6, true);
    struct vt_cut_result r;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(run_cut(&t, &r, &err), 0);
    check_result(&t, &r, true);
    vt_cut_release(&r);
    tmesh_release(&t);
}

static void cut_convex_n_gons(void)
{
    struct tmesh t;
    tmesh_init(&t);
    uint32_t p[7], tx[7];
    for (int i = 0; i < 7; i++) {
        double a = 2 * PI * i / 7, u = 2.3 + 1.6 * cos(a), v = 1.7 + 1.6 * sin(a);
        p[i] = tmesh_pos(&t, u, v, 0.25 * u - 0.5 * v);
        tx[i] = tmesh_tex(&t, u, v);
    }
    tmesh_face(&t, 0, 7, p, tx, true);
    /* a quad neighbour of another chart across edge 0-1 */
    uint32_t q = tmesh_pos(&t, 5, 0, 0), tq[4] = {tmesh_tex(&t, 0.1, 0.1), tmesh_tex(&t, 0.9, 0.1),
                                                  tmesh_tex(&t, 0.9, 0.9), tmesh_tex(&t, 0.1, 0.9)};
    tmesh_face(&t, 1, 4, (uint32_t[]){p[1], p[0], q, p[2]}, tq, true);
    struct vt_cut_result r;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(run_cut(&t, &r, &err), 0);
    VT_CHECK_INT_EQ(r.faces_cut, 1);
    VT_CHECK_INT_EQ(r.faces_split, 1);
    VT_CHECK(min_piece_area(&r) > 0);
    check_result(&t, &r, false);
    vt_cut_release(&r);
    tmesh_release(&t);
}

static void cut_degenerate_faces(void)
{
    struct tmesh t;
    tmesh_init(&t);
    uint32_t p[5] = {tmesh_pos(&t, 0, 0, 0), tmesh_pos(&t, 2, 0, 0), tmesh_pos(&t, 1, 1, 0),
                     tmesh_pos(&t, 1, -1, 0), tmesh_pos(&t, 3, 1, 1)};
    /* zero area in UV (a line 0.5 .. 2.5 on the diagonal), not in 3D: its pieces stay */
    uint32_t tx[3] = {tmesh_tex(&t, 0.5, 0.5), tmesh_tex(&t, 2.5, 2.5), tmesh_tex(&t, 1.5, 1.5)};
    tmesh_face(&t, 0, 3, (uint32_t[]){p[0], p[1], p[2]}, tx, true);
    tmesh_face(&t, 1, 3, (uint32_t[]){p[1], p[0], p[3]}, NULL, false);
    /* a repeated position (edge 1-1 of zero length in 3D) and a repeated texcoord */
    uint32_t ty[4] = {tmesh_tex(&t, 4.5, 0.5), tmesh_tex(&t, 6.5, 0.5), tmesh_tex(&t, 6.5, 0.8),
                      tmesh_tex(&t, 5.5, 2.5)};
    tmesh_face(&t, 2, 4, (uint32_t[]){p[1], p[4], p[4], p[2]}, ty, true);
    tmesh_face(&t, 2, 4, (uint32_t[]){p[1], p[4], p[2], p[2]},
               (uint32_t[]){ty[0], ty[1], ty[3], ty[3]}, true);
    struct vt_cut_result r;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(run_cut(&t, &r, &err), 0);
    VT_CHECK_INT_EQ(r.faces_cut, 3);
    VT_CHECK(r.face_poly[1] - r.face_poly[0] >= 3); /* the flat triangle in (at least) 3 cells */
    VT_CHECK_INT_EQ(cut_fixture_check_watertight(&t, &r, false, true), 0);
    VT_CHECK_INT_EQ(cut_fixture_check_pieces(&t, &r, 1e-9, true), 0);
    vt_cut_release(&r);
    tmesh_release(&t);
}

static void cut_a_non_manifold_edge(void)
{
    struct tmesh t;
    tmesh_init(&t);
    uint32_t p[5] = {tmesh_pos(&t, 0, 0, 0), tmesh_pos(&t, 4, 0, 0), tmesh_pos(&t, 2, 1, 0),
                     tmesh_pos(&t, 2, 0, 1), tmesh_pos(&t, 2, -1, -1)};
    /* three faces on edge 0-1: two wrap ones of different charts (different u along it), one
     * without texcoords */
    tmesh_face(
        &t, 0, 3, (uint32_t[]){p[0], p[1], p[2]},
        (uint32_t[]){tmesh_tex(&t, 0.5, 0.5), tmesh_tex(&t, 3.5, 0.5), tmesh_tex(&t, 2, 1.5)},
        true);
    tmesh_face(
        &t, 0, 3, (uint32_t[]){p[1], p[0], p[3]},
        (uint32_t[]){tmesh_tex(&t, 10.25, 0.5), tmesh_tex(&t, 12.0, 0.5), tmesh_tex(&t, 11, 0.9)},
        true);
    tmesh_face(&t, 1, 3, (uint32_t[]){p[0], p[1], p[4]}, NULL, true);
    struct vt_cut_result r;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(run_cut(&t, &r, &err), 0);
    VT_CHECK_INT_EQ(r.faces_cut, 2);
    VT_CHECK_INT_EQ(r.faces_split, 1);
    /* u = 1, 2, 3 of the first face, u = 1 of the second (0.25 .. 2 from its lower end) */
    uint32_t on_edge = 0;
    for (uint32_t v = 0; v < r.vertex_count; v++)
        on_edge += r.vertices[v].pos[0] == p[0] && r.vertices[v].pos[1] == p[1] &&
                   r.vertices[v].pos[2] == VT_CHART_NONE;
    VT_CHECK_INT_EQ(on_edge, 4);
    VT_CHECK_INT_EQ(r.poly_start[r.face_poly[2] + 1] - r.poly_start[r.face_poly[2]], 3 + 4);
    check_result(&t, &r, false);
    vt_cut_release(&r);
    tmesh_release(&t);
}

static void cut_far_repeats_exactly(void)
{
    struct tmesh t;
    tmesh_init(&t);
    uint32_t p[3] = {tmesh_pos(&t, 0, 0, 0), tmesh_pos(&t, 1, 0, 0), tmesh_pos(&t, 0, 1, 0)};
    double uv[3][2] = {{10000.75, -9999.5}, {10003.25, -9999.5}, {10001.5, -9997.25}};
    uint32_t tx[3];
    for (int i = 0; i < 3; i++)
        tx[i] = tmesh_tex(&t, uv[i][0], uv[i][1]);
    tmesh_face(&t, 0, 3, p, tx, true);
    struct vt_cut_result r;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(run_cut(&t, &r, &err), 0);
    VT_CHECK(t.shift[0] == -10000 && t.shift[1] == 10000);
    check_result(&t, &r, false);
    for (uint64_t c = 0; c < r.corner_count; c++) {
        const struct vt_cut_corner *k = &r.corners[c];
        if (k->pos < t.position_count) {
            double u = uv[k->src[0]][0], v = uv[k->src[0]][1];
            VT_CHECK(k->u == u - floor(u) && k->v == v - floor(v));
        }
    }
    vt_cut_release(&r);
    tmesh_release(&t);
}

static void cut_a_face_over_300_repeats(void)
{
    struct tmesh t;
    tmesh_init(&t);
    uint32_t p[3] = {tmesh_pos(&t, 0, 0, 0), tmesh_pos(&t, 30, 0, 0), tmesh_pos(&t, 15, 1, 0)};
    uint32_t tx[3] = {tmesh_tex(&t, 0, 0.2), tmesh_tex(&t, 300, 0.3), tmesh_tex(&t, 150, 0.8)};
    tmesh_face(&t, 0, 3, p, tx, true);
    struct vt_cut_result r;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(run_cut(&t, &r, &err), 0);
    VT_CHECK_INT_EQ(r.pieces, 300);
    check_result(&t, &r, false);
    vt_cut_release(&r);
    tmesh_release(&t);
}

static void cut_refuses_too_many_cells_and_non_finite_texcoords(void)
{
    struct tmesh t;
    tmesh_init(&t);
    uint32_t p[3] = {tmesh_pos(&t, 0, 0, 0), tmesh_pos(&t, 1, 0, 0), tmesh_pos(&t, 0, 1, 0)};
    /* 1025 x 1024 cells: one more column than 2^20 cells allow */
    tmesh_face(
        &t, 0, 3, p,
        (uint32_t[]){tmesh_tex(&t, 0.5, 0.5), tmesh_tex(&t, 1024.5, 0.5), tmesh_tex(&t, 0.5, 1024)},
        true);
    struct vt_cut_result r;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(run_cut(&t, &r, &err), VTS_ERR_LIMIT);
    VT_CHECK_STR_CONTAINS(err.message, "face 0");
    VT_CHECK_STR_CONTAINS(err.message, "1025 x 1024 cells");
    VT_CHECK(!r.changed && !r.corners && r.poly_count == 0);
    vt_cut_release(&r);
    /* the same face without the wrap flag is not cut: fine */
    t.wrap[0] = 0;
    VT_CHECK_INT_EQ(run_cut(&t, &r, &err), 0);
    VT_CHECK(!r.changed[0]);
    vt_cut_release(&r);
    tmesh_release(&t);

    tmesh_init(&t);
    for (int i = 0; i < 3; i++)
        p[i] = tmesh_pos(&t, i, i & 1, 0);
    tmesh_face(
        &t, 0, 3, p,
        (uint32_t[]){tmesh_tex(&t, 0.5, 0.5), tmesh_tex(&t, INFINITY, 0.5), tmesh_tex(&t, 0.5, 2)},
        true);
    VT_CHECK_INT_EQ(run_cut(&t, &r, &err), VTS_ERR_LIMIT);
    VT_CHECK_STR_CONTAINS(err.message, "not finite");
    vt_cut_release(&r);
    tmesh_release(&t);
}

/* Field by field (the struct has padding). */
static bool vertices_equal(const struct vt_cut_vertex *a, const struct vt_cut_vertex *b, uint32_t n)
{
    for (uint32_t i = 0; i < n; i++)
        if (memcmp(a[i].pos, b[i].pos, sizeof a[i].pos) || memcmp(a[i].w, b[i].w, sizeof a[i].w))
            return false;
    return true;
}

static bool corners_equal(const struct vt_cut_corner *a, const struct vt_cut_corner *b)
{
    return a->pos == b->pos && a->has_uv == b->has_uv && a->u == b->u && a->v == b->v &&
           !memcmp(a->src, b->src, sizeof a->src) && !memcmp(a->w, b->w, sizeof a->w);
}

static void cut_is_deterministic(void)
{
    struct tmesh t;
    torus(&t, 7, 5, true);
    struct vt_cut_result a, b;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(run_cut(&t, &a, &err), 0);
    VT_CHECK_INT_EQ(run_cut(&t, &b, &err), 0);
    VT_CHECK(a.corner_count == b.corner_count && a.vertex_count == b.vertex_count &&
             a.poly_count == b.poly_count);
    bool same = !memcmp(a.poly_start, b.poly_start, (a.poly_count + 1) * sizeof *a.poly_start) &&
                vertices_equal(a.vertices, b.vertices, a.vertex_count);
    for (uint64_t c = 0; c < a.corner_count && same; c++)
        same = corners_equal(&a.corners[c], &b.corners[c]);
    VT_CHECK(same);
    vt_cut_release(&a);
    vt_cut_release(&b);
    tmesh_release(&t);
}

static void cut_an_empty_mesh_and_faces_kept(void)
{
    struct tmesh t;
    tmesh_init(&t);
    struct vt_cut_result r;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(run_cut(&t, &r, &err), 0);
    VT_CHECK(r.face_poly && r.face_poly[0] == 0 && r.poly_count == 0 && r.vertex_count == 0);
    vt_cut_release(&r);
    /* a face of no chart is never cut, even with the wrap flag; a non-wrap one keeps its move */
    uint32_t p[3] = {tmesh_pos(&t, 0, 0, 0), tmesh_pos(&t, 1, 0, 0), tmesh_pos(&t, 0, 1, 0)};
    uint32_t tx[3] = {tmesh_tex(&t, 0.5, 0.5), tmesh_tex(&t, 3.5, 0.5), tmesh_tex(&t, 0.5, 2)};
    tmesh_face(&t, VT_CHART_NONE, 3, p, tx, true);
    tmesh_face(&t, 0, 3, p, tx, false);
    VT_CHECK_INT_EQ(run_cut(&t, &r, &err), 0);
    VT_CHECK(!r.changed[0] && !r.changed[1] && r.poly_count == 0);
    VT_CHECK(r.face_shift[0] == 0 && r.face_shift[2] == 0 && r.face_shift[3] == 0);
    vt_cut_release(&r);
    vt_cut_release(NULL);
    tmesh_release(&t);
}

int main(void)
{
    VT_RUN(cut_a_roof_of_8_by_4_repeats);
    VT_RUN(broken_results_fail_the_checkers);
    VT_RUN(cut_a_strip_from_minus_700_to_2600);
    VT_RUN(cut_a_triangle_with_a_vertex_on_a_line);
    VT_RUN(cut_a_face_with_an_edge_on_a_line);
    VT_RUN(cut_splits_a_neighbour_without_texcoords);
    VT_RUN(cut_keeps_a_closed_torus_watertight);
    VT_RUN(cut_convex_n_gons);
    VT_RUN(cut_degenerate_faces);
    VT_RUN(cut_a_non_manifold_edge);
    VT_RUN(cut_far_repeats_exactly);
    VT_RUN(cut_a_face_over_300_repeats);
    VT_RUN(cut_refuses_too_many_cells_and_non_finite_texcoords);
    VT_RUN(cut_is_deterministic);
    VT_RUN(cut_an_empty_mesh_and_faces_kept);
    return vt_test_main_result();
}
