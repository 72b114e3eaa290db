/* Unit tests of lib/offset/vt_offset.c (the vt-offset rewriter), rewriting: exact output text,
 * shared vt duplication with faces renumbered, untouched lines byte-identical (CRLF, continuations,
 * comments), the V-axis convention, wrapped copies and constant cells. Numerics, bad input and
 * random scenes: test_vt_offset_numerics.c. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "offset_fixture.h"
#include "vt_test.h"

static const struct spec two_halves[] = {{"a", 0, 0, 512, 512, 1, 1, 0, 0},
                                         {"b", 512, 0, 512, 512, 1, 1, 0, 0}};

/* ---- rewriting ---- */

static void rewrites_vt_and_material_lines(void)
{
    struct vt_layout l;
    offset_fixture_layout(&l, 1024, 1024, two_halves, 2);
    struct vt_offset_stats s;
    VT_CHECK(offset_fixture_expect_output("mtllib scene.mtl\n"
                                          "v 0 0 0\nv 1 0 0\nv 1 1 0\n"
                                          "vt 0 0\nvt 1 0\nvt 1 1\nvt 0.25 0.75\n"
                                          "usemtl a\n"
                                          "f 1/1 2/2 3/3\n",
                                          &l, 0,
                                          "mtllib out.mtl\n"
                                          "v 0 0 0\nv 1 0 0\nv 1 1 0\n"
                                          "vt 0 0.5\nvt 0.5 0.5\nvt 0.5 1\nvt 0.25 0.75\n"
                                          "usemtl vt_atlas\n"
                                          "f 1/1 2/2 3/3\n",
                                          &s));
    VT_CHECK_INT_EQ(s.vt_lines, 4);
    VT_CHECK_INT_EQ(s.vt_rewritten, 3);
    VT_CHECK_INT_EQ(s.vt_unused, 1); /* vt 4: no face uses it, copied as is */
    VT_CHECK_INT_EQ(s.vt_duplicated, 0);
    VT_CHECK_INT_EQ(s.faces, 1);
    VT_CHECK_INT_EQ(s.faces_rewritten, 0);
    VT_CHECK_INT_EQ(s.digits, 7); /* 0.5e-7 * 1024 <= 1e-4 texel */
    VT_CHECK_INT_EQ(s.lines, 10);
    VT_CHECK(s.max_error == 0);
    /* material b: u shifts by half the atlas */
    VT_CHECK(offset_fixture_expect_output(
        "v 0 0 0\nvt 0.5 0.5\nusemtl b\nf 1/1 1/1 1/1\n", &l, 0,
        "mtllib out.mtl\nv 0 0 0\nvt 0.75 0.75\nusemtl vt_atlas\nf 1/1 1/1 1/1\n", &s));
    vt_layout_release(&l);
}

static void duplicates_shared_vt_and_renumbers_faces(void)
{
    struct vt_layout l;
    offset_fixture_layout(&l, 1024, 1024, two_halves, 2);
    struct vt_offset_stats s;
    /* vt 3 is used by a and b: a second line follows it for b, and vt 4 moves to 5 */
    VT_CHECK(offset_fixture_expect_output("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\n"
                                          "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                                          "usemtl a\n"
                                          "f 1/1/1 2/2/1 3/3/1\n"
                                          "usemtl b\n"
                                          "f 1/3/1 3/3/1 4/4/1\n"
                                          "f -4/-2/-1 -3/-1/-1 -2/-1/-1\n"
                                          "usemtl a\n"
                                          "f -4/-2/-1 -3/-3/-1 -2/+1/-1\n"
                                          "f 1//1 2//1 3//1\n"
                                          "f 1 2 3\n",
                                          &l, 0,
                                          "mtllib out.mtl\n"
                                          "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\n"
                                          "vt 0 0.5\nvt 0.5 0.5\nvt 0.5 1\nvt 1 1\nvt 0.5 1\n"
                                          "usemtl vt_atlas\n"
                                          "f 1/1/1 2/2/1 3/3/1\n"
                                          "usemtl vt_atlas\n"
                                          "f 1/4/1 3/4/1 4/5/1\n"
                                          "f -4/-2/-1 -3/-1/-1 -2/-1/-1\n"
                                          "usemtl vt_atlas\n"
                                          "f -4/-3/-1 -3/-4/-1 -2/+1/-1\n"
                                          "f 1//1 2//1 3//1\n"
                                          "f 1 2 3\n",
                                          &s));
    VT_CHECK_INT_EQ(s.vt_rewritten, 4);
    VT_CHECK_INT_EQ(s.vt_duplicated, 1);
    VT_CHECK_INT_EQ(s.faces, 6);
    VT_CHECK_INT_EQ(s.faces_rewritten, 2);
    VT_CHECK_INT_EQ(s.faces_without_vt, 2);
    vt_layout_release(&l);
}

static void keeps_other_lines_byte_identical(void)
{
    struct vt_layout l;
    offset_fixture_layout(&l, 1024, 1024, two_halves, 2);
    struct vt_offset_stats s;
    /* CRLF, tabs, comments, unknown statements, groups, a 3-component vt (w kept as written), a
     * 1-component vt (v = 0), continuation lines, a second mtllib turned into a comment, l lines
     * renumbered to the first copy, no newline at the end */
    VT_CHECK(offset_fixture_expect_output("# exported\r\n"
                                          "mtllib a.mtl\r\n"
                                          "mtllib b.mtl\r\n"
                                          "o thing  \r\n"
                                          "v\t0 0 0\r\nv 1 0 0 # note\r\nv 1 1 0\r\n"
                                          "vt 0.5 0.5 0.125\r\n"
                                          "vt  1\t # one component\r\n"
                                          "vt 0.5 \\\r\n 0.25\r\n"
                                          "cstype bezier\r\n"
                                          "g  left right\r\n"
                                          "s off\r\n"
                                          "  usemtl b\r\n"
                                          "f 1/1 2/2 3/3 # first\r\n"
                                          "usemtl a\r\n"
                                          "f 1/1 2/2 \\\r\n 3/3\r\n"
                                          "l 1/1 2/2 3/3\r\n"
                                          "l 1 2\r\n"
                                          "f 1/3 2/3 3/3",
                                          &l, 0,
                                          "# exported\r\n"
                                          "mtllib out.mtl\r\n"
                                          "# mtllib b.mtl\r\n"
                                          "o thing  \r\n"
                                          "v\t0 0 0\r\nv 1 0 0 # note\r\nv 1 1 0\r\n"
                                          "vt 0.75 0.75 0.125\r\n"
                                          "vt 0.25 0.75 0.125\r\n"
                                          "vt  1 0.5\t # one component\r\n"
                                          "vt 0.5 0.5\r\n"
                                          "vt 0.75 0.625\r\n"
                                          "vt 0.25 0.625\r\n"
                                          "cstype bezier\r\n"
                                          "g  left right\r\n"
                                          "s off\r\n"
                                          "  usemtl vt_atlas\r\n"
                                          "f 1/1 2/3 3/5 # first\r\n"
                                          "usemtl vt_atlas\r\n"
                                          "f 1/2 2/4 \\\r\n 3/6\r\n"
                                          "l 1/1 2/3 3/5\r\n"
                                          "l 1 2\r\n"
                                          "f 1/6 2/6 3/6",
                                          &s));
    VT_CHECK_INT_EQ(s.vt_duplicated, 3);
    VT_CHECK_INT_EQ(s.faces_rewritten, 4);
    VT_CHECK_INT_EQ(s.lines, 22);
    vt_layout_release(&l);
}

/* V is up in OBJ and down in the atlas: texel (i, j) of a texture, j counted from its top row, has
 * its centre at u = (i + 0.5) / w, v = 1 - (j + 0.5) / h and lands on the centre of atlas texel
 * (x + i, y + j), y counted from the atlas' top row. */
static void follows_the_v_axis_convention(void)
{
    static const struct spec rect[] = {{"t", 16, 8, 16, 8, 1, 1, 0, 0}};
    struct vt_layout l;
    offset_fixture_layout(&l, 64, 64, rect, 1);
    struct membuf out;
    struct vt_offset_stats s;
    struct vts_error err;
    /* texel (3, 0): top row; texel (3, 7): bottom row; the top-left and bottom-right corners */
    int rc = offset_fixture_rewrite("v 0 0 0\n"
                                    "vt 0.21875 0.9375\n"
                                    "vt 0.21875 0.0625\n"
                                    "vt 0 1\n"
                                    "vt 1 0\n"
                                    "usemtl t\nf 1/1 1/2 1/3 1/4\n",
                                    &l, 0, &out, &s, &err);
    VT_CHECK_INT_EQ(rc, 0);
    double u, v;
    VT_CHECK(offset_fixture_nth_vt(out.data, 0, &u, &v));
    /* 6 decimals: within 1e-4 texel */
    VT_CHECK(fabs(u * 64 - 19.5) < 1e-4 && fabs((1 - v) * 64 - 8.5) < 1e-4); /* top row: row 8 */
    VT_CHECK(offset_fixture_nth_vt(out.data, 1, &u, &v));
    VT_CHECK(fabs(u * 64 - 19.5) < 1e-4 && fabs((1 - v) * 64 - 15.5) < 1e-4); /* bottom: 15 */
    VT_CHECK(offset_fixture_nth_vt(out.data, 2, &u, &v));
    VT_CHECK(u * 64 == 16 && (1 - v) * 64 == 8); /* (0, 1) is the rect's top-left corner */
    VT_CHECK(offset_fixture_nth_vt(out.data, 3, &u, &v));
    VT_CHECK(u * 64 == 32 && (1 - v) * 64 == 16); /* (1, 0) its bottom-right corner */
    free(out.data);
    vt_layout_release(&l);
}

/* With wrap replication the copies lie side by side from (x, y) and the material's UV range
 * [origin, origin + repeat] covers them all. */
static void maps_repeated_copies(void)
{
    static const struct spec rect[] = {{"w", 0, 0, 16, 16, 2, 3, -1, 0}};
    struct vt_layout l;
    offset_fixture_layout(&l, 64, 64, rect, 1);
    struct vt_offset_stats s;
    /* u -1..1 spans the two copies (32 texels), v 0..3 the three copies (48 rows, v up) */
    VT_CHECK(offset_fixture_expect_output(
        "v 0 0 0\nvt -1 0\nvt 1 3\nvt 0 1.5\nusemtl w\nf 1/1 1/2 1/3\n", &l, 0,
        "mtllib out.mtl\nv 0 0 0\nvt 0 0.25\nvt 0.5 1\nvt 0.25 0.625\n"
        "usemtl vt_atlas\nf 1/1 1/2 1/3\n",
        &s));
    vt_layout_release(&l);
}

/* A material without textures has a constant cell: every one of its coordinates, whatever it
 * is (even outside [0,1]), goes to the centre of the cell, so that filtering stays inside it. */
static void maps_constant_materials_to_the_cell_centre(void)
{
    static const struct spec rects[] = {{"a", 0, 0, 32, 32, 1, 1, 0, 0},
                                        {"const_kd", 32, 0, 4, 4, 1, 1, 0, 0}};
    struct vt_layout l;
    offset_fixture_layout(&l, 64, 64, rects, 2);
    struct vt_offset_stats s;
    VT_CHECK(offset_fixture_expect_output(
        "v 0 0 0\nvt 0 0\nvt 5 -2\nusemtl const_kd\nf 1/1 1/2 1/1\n", &l, 0,
        "mtllib out.mtl\nv 0 0 0\nvt 0.53125 0.96875\nvt 0.53125 0.96875\n"
        "usemtl vt_atlas\nf 1/1 1/2 1/1\n",
        &s));
    vt_layout_release(&l);
}

int main(void)
{
    VT_RUN(rewrites_vt_and_material_lines);
    VT_RUN(duplicates_shared_vt_and_renumbers_faces);
    VT_RUN(keeps_other_lines_byte_identical);
    VT_RUN(follows_the_v_axis_convention);
    VT_RUN(maps_repeated_copies);
    VT_RUN(maps_constant_materials_to_the_cell_centre);
    return vt_test_main_result();
}
