/* lib/chart/vt_chart.c: chart labels (shared texcoord indices, shared edges with equal
 * texcoords, groups, seams, numbering) and the boxes and moves of charts, exact for far repeats. */
#include <math.h>
#include <stdlib.h>

#include "cut_fixture.h"
#include "vt_test.h"

/* Labels t's faces into labels[] (face_count entries); returns the chart count. */
static uint32_t label(const struct tmesh *t, uint32_t *labels)
{
    struct vt_chart_mesh m = tmesh_view(t);
    uint32_t count = 12345;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(vt_chart_label(&m, labels, &count, &err), 0);
    return count;
}

/* A triangle of group g at positions p0..p2 with new texcoords (u, v) + the given offsets. */
static uint32_t triangle(struct tmesh *t, uint32_t g, const uint32_t p[3], const double uv[6])
{
    uint32_t tex[3];
    for (int i = 0; i < 3; i++)
        tex[i] = tmesh_tex(t, uv[2 * i], uv[2 * i + 1]);
    return tmesh_face(t, g, 3, p, tex, false);
}

static void labels_join_faces_sharing_a_texcoord_index(void)
{
    struct tmesh t;
    tmesh_init(&t);
    for (int i = 0; i < 6; i++)
        tmesh_pos(&t, i, i * i, 0);
    uint32_t tx[4] = {tmesh_tex(&t, 0, 0), tmesh_tex(&t, 1, 0), tmesh_tex(&t, 0, 1),
                      tmesh_tex(&t, 1, 1)};
    /* no position in common: only texcoord index 1 joins them */
    tmesh_face(&t, 0, 3, (uint32_t[]){0, 1, 2}, (uint32_t[]){tx[0], tx[1], tx[2]}, false);
    tmesh_face(&t, 0, 3, (uint32_t[]){3, 4, 5}, (uint32_t[]){tx[1], tx[3], tx[2]}, false);
    uint32_t labels[2];
    VT_CHECK_INT_EQ(label(&t, labels), 1);
    VT_CHECK_INT_EQ(labels[0], 0);
    VT_CHECK_INT_EQ(labels[1], 0);
    tmesh_release(&t);
}

static void labels_join_faces_sharing_an_edge_with_equal_texcoords(void)
{
    struct tmesh t;
    tmesh_init(&t);
    for (int i = 0; i < 4; i++)
        tmesh_pos(&t, i, i * i, 1);
    /* one texcoord per corner (as some exporters write); edge 1-2 has the same values on both
     * faces, walked in opposite directions */
    triangle(&t, 7, (uint32_t[]){0, 1, 2}, (double[]){0.1, 0.1, 0.9, 0.2, 0.5, 0.8});
    triangle(&t, 7, (uint32_t[]){2, 1, 3}, (double[]){0.5, 0.8, 0.9, 0.2, 1.3, 0.9});
    uint32_t labels[2];
    VT_CHECK_INT_EQ(label(&t, labels), 1);
    VT_CHECK_INT_EQ(labels[1], 0);
    tmesh_release(&t);
}

static void labels_never_join_different_groups(void)
{
    struct tmesh t;
    tmesh_init(&t);
    for (int i = 0; i < 4; i++)
        tmesh_pos(&t, i, i * i, 1);
    uint32_t tx[4] = {tmesh_tex(&t, 0, 0), tmesh_tex(&t, 1, 0), tmesh_tex(&t, 0, 1),
                      tmesh_tex(&t, 1, 1)};
    /* the same texcoord indices and the same edge (same values), different materials */
    tmesh_face(&t, 0, 3, (uint32_t[]){0, 1, 2}, (uint32_t[]){tx[0], tx[1], tx[2]}, false);
    tmesh_face(&t, 1, 3, (uint32_t[]){2, 1, 3}, (uint32_t[]){tx[2], tx[1], tx[3]}, false);
    /* a third face of group 1 joins the second through index 3, not the first */
    tmesh_face(&t, 1, 3, (uint32_t[]){0, 1, 3}, (uint32_t[]){tx[0], tx[1], tx[3]}, false);
    uint32_t labels[3];
    VT_CHECK_INT_EQ(label(&t, labels), 2);
    VT_CHECK_INT_EQ(labels[0], 0);
    VT_CHECK_INT_EQ(labels[1], 1);
    VT_CHECK_INT_EQ(labels[2], 1);
    tmesh_release(&t);
}

static void labels_split_an_edge_with_different_texcoords(void)
{
    struct tmesh t;
    tmesh_init(&t);
    for (int i = 0; i < 4; i++)
        tmesh_pos(&t, i, i * i, 1);
    /* edge 1-2: the same positions, texcoords differing in one bit on one end (a seam) */
    triangle(&t, 0, (uint32_t[]){0, 1, 2}, (double[]){0.1, 0.1, 0.9, 0.2, 0.5, 0.8});
    triangle(&t, 0, (uint32_t[]){2, 1, 3}, (double[]){0.5, nextafter(0.8, 1), 0.9, 0.2, 1.3, 0.9});
    /* and -0.0 is not 0.0 (bitwise) */
    triangle(&t, 0, (uint32_t[]){1, 2, 3}, (double[]){0.0, 0.0, 1, 1, 0, 1});
    triangle(&t, 0, (uint32_t[]){2, 1, 0}, (double[]){1, 1, -0.0, 0.0, 5, 5});
    uint32_t labels[4];
    VT_CHECK_INT_EQ(label(&t, labels), 4);
    for (uint32_t f = 0; f < 4; f++)
        VT_CHECK_INT_EQ(labels[f], f);
    tmesh_release(&t);
}

static void labels_number_charts_in_order_of_their_first_face(void)
{
    struct tmesh t;
    tmesh_init(&t);
    for (int i = 0; i < 3; i++)
        tmesh_pos(&t, i, 0, 0);
    uint32_t p[3] = {0, 1, 2}, tx[12];
    for (int i = 0; i < 12; i++)
        tx[i] = tmesh_tex(&t, i, i);
    tmesh_face(&t, 0, 3, p, (uint32_t[]){tx[0], tx[1], tx[2]}, false);             /* A */
    tmesh_face(&t, 0, 3, p, (uint32_t[]){tx[3], tx[4], tx[5]}, false);             /* B */
    tmesh_face(&t, VT_CHART_NONE, 3, p, (uint32_t[]){tx[0], tx[1], tx[2]}, false); /* none */
    tmesh_face(&t, 0, 3, p, NULL, false);                                          /* none */
    tmesh_face(&t, 0, 3, p, (uint32_t[]){tx[6], tx[7], tx[8]}, false);             /* C */
    /* joins B and A: the merged chart keeps A's number, C becomes 1 */
    tmesh_face(&t, 0, 3, p, (uint32_t[]){tx[5], tx[9], tx[0]}, false);
    /* one corner without texcoord: in a chart through its other corners (C) */
    tmesh_face(&t, 0, 3, p, (uint32_t[]){VT_CHART_NONE, tx[6], tx[10]}, false);
    uint32_t labels[7];
    VT_CHECK_INT_EQ(label(&t, labels), 2);
    uint32_t want[7] = {0, 0, VT_CHART_NONE, VT_CHART_NONE, 1, 0, 1};
    for (int f = 0; f < 7; f++)
        VT_CHECK_INT_EQ(labels[f], want[f]);
    struct vt_chart_box boxes[2];
    struct vt_chart_mesh m = tmesh_view(&t);
    vt_chart_boxes(&m, labels, 2, boxes);
    VT_CHECK_INT_EQ(boxes[0].faces, 3);
    VT_CHECK_INT_EQ(boxes[1].faces, 2);
    VT_CHECK(boxes[0].umin == 0 && boxes[0].umax == 9 && boxes[1].umin == 6 && boxes[1].umax == 10);
    tmesh_release(&t);
}

static void labels_of_an_empty_mesh(void)
{
    struct tmesh t;
    tmesh_init(&t);
    uint32_t labels[1];
    VT_CHECK_INT_EQ(label(&t, labels), 0);
    tmesh_release(&t);
}

/* One chart of a triangle with these u and v; checks its box and move, exact. */
static void check_move(const double u[3], const double v[3])
{
    struct tmesh t;
    tmesh_init(&t);
    uint32_t p[3], tx[3];
    for (int i = 0; i < 3; i++) {
        p[i] = tmesh_pos(&t, i, 0, 0);
        tx[i] = tmesh_tex(&t, u[i], v[i]);
    }
    tmesh_face(&t, 3, 3, p, tx, false);
    uint32_t labels[1];
    VT_CHECK_INT_EQ(label(&t, labels), 1);
    struct vt_chart_box b;
    struct vt_chart_mesh m = tmesh_view(&t);
    vt_chart_boxes(&m, labels, 1, &b);
    double umin = fmin(u[0], fmin(u[1], u[2])), vmin = fmin(v[0], fmin(v[1], v[2]));
    VT_CHECK(b.group == 3 && b.faces == 1 && b.umin == umin && b.vmin == vmin);
    VT_CHECK(b.umax == fmax(u[0], fmax(u[1], u[2])) && b.vmax == fmax(v[0], fmax(v[1], v[2])));
    VT_CHECK(b.du == -floor(umin) && b.dv == -floor(vmin));
    VT_CHECK(!signbit(b.du) || b.du != 0);
    /* the box starts in [0, 1), at exactly u - floor(u), and the move is undone exactly */
    VT_CHECK(umin + b.du == umin - floor(umin) && umin + b.du >= 0 && umin + b.du < 1);
    VT_CHECK(vmin + b.dv == vmin - floor(vmin) && vmin + b.dv >= 0 && vmin + b.dv < 1);
    for (int i = 0; i < 3; i++) {
        VT_CHECK((u[i] + b.du) - b.du == u[i]);
        VT_CHECK((v[i] + b.dv) - b.dv == v[i]);
    }
    tmesh_release(&t);
}

static void boxes_and_moves_are_exact_for_far_repeats(void)
{
    check_move((double[]){2600.3, 2601.2, 2600.9}, (double[]){-675.25, -674.5, -675.0});
    check_move((double[]){-675.25, -674.1, -675.0}, (double[]){2600.3, 2600.31, 2600.7});
    /* 1e4 repeats, and 1e4 + a fraction that is not a short binary one */
    check_move((double[]){1e4, 1e4 + 0.7, 10000.3}, (double[]){-1e4 + 0.1, -9999.9, -1e4});
    check_move((double[]){0.0, 0.5, 0.25}, (double[]){-0.0, 0.5, 0.25}); /* du = +0 */
    /* one chart spanning -700 .. 2600: the move of its box */
    check_move((double[]){-700.0, 2600.0, 12.5}, (double[]){0.25, 0.5, 0.75});
}

int main(void)
{
    VT_RUN(labels_join_faces_sharing_a_texcoord_index);
    VT_RUN(labels_join_faces_sharing_an_edge_with_equal_texcoords);
    VT_RUN(labels_never_join_different_groups);
    VT_RUN(labels_split_an_edge_with_different_texcoords);
    VT_RUN(labels_number_charts_in_order_of_their_first_face);
    VT_RUN(labels_of_an_empty_mesh);
    VT_RUN(boxes_and_moves_are_exact_for_far_repeats);
    return vt_test_main_result();
}
