/* Unit tests of lib/offset/vt_offset.c (the vt-offset rewriter), numerics and robustness: precision
 * on a 2^20 atlas, the float32 warning threshold, bad input (nothing written), randomised scenes
 * checked against vt_obj's reader, files read in blocks against memory. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "offset_fixture.h"
#include "vt_obj.h"
#include "vt_test.h"
#include "vts.h"

static const struct spec two_halves[] = {{"a", 0, 0, 512, 512, 1, 1, 0, 0},
                                         {"b", 512, 0, 512, 512, 1, 1, 0, 0}};

/* ---- numerics ---- */

/* Coordinates at 0, 1, texel centres and texel edges of a 2^20 atlas survive the written text
 * with an error under 1e-3 texel; float32 stays under 1/8 texel there (no warning). */
static void keeps_texel_precision_on_a_2_20_atlas(void)
{
    const uint32_t size = 1u << 20;
    static const struct spec rects[] = {
        {"whole", 0, 0, 1u << 20, 1u << 19, 1, 1, 0, 0},
        {"odd", 300001, 600001, 4099, 2053, 1, 1, 0, 0},
        {"corner", (1u << 20) - 1, (1u << 20) - 1, 1, 1, 1, 1, 0, 0}};
    struct vt_layout l;
    offset_fixture_layout(&l, size, size, rects, 3);
    size_t cap = 1 << 20, len = 0;
    char *text = malloc(cap);
    len += (size_t)snprintf(text + len, cap - len, "v 0 0 0\n");
    int count = 0;
    /* whole: u at texel edges and centres across the atlas, v edges and centres of its 2^19 rows */
    for (uint32_t i = 0; i <= size; i += 4099, count += 2) {
        len += (size_t)snprintf(text + len, cap - len, "vt %.17g %.17g\n", (double)i / size,
                                (double)(i / 2) / (size / 2));
        len += (size_t)snprintf(text + len, cap - len, "vt %.17g %.17g\n", (i + 0.5) / size,
                                (i / 2 + 0.5) / (size / 2));
    }
    len += (size_t)snprintf(text + len, cap - len, "vt 0 0\nvt 1 1\nvt 1 0\nvt 0 1\n");
    count += 4;
    int whole_count = count;
    for (uint32_t i = 0; i <= 4099; i += 7, count += 2) {
        len += (size_t)snprintf(text + len, cap - len, "vt %.17g %.17g\n", (double)i / 4099,
                                (double)(i % 2054) / 2053);
        len += (size_t)snprintf(text + len, cap - len, "vt %.17g %.17g\n", (i + 0.5) / 4100,
                                (i % 2053 + 0.5) / 2053);
    }
    int odd_count = count - whole_count;
    len += (size_t)snprintf(text + len, cap - len, "vt 0 0\nvt 1 1\nvt 0.5 0.5\n");
    count += 3;
    len += (size_t)snprintf(text + len, cap - len, "usemtl whole\n");
    for (int i = 0; i < whole_count; i++)
        len += (size_t)snprintf(text + len, cap - len, "f 1/%d 1/%d 1/%d\n", i + 1, i + 1, i + 1);
    len += (size_t)snprintf(text + len, cap - len, "usemtl odd\n");
    for (int i = whole_count; i < whole_count + odd_count; i++)
        len += (size_t)snprintf(text + len, cap - len, "f 1/%d 1/%d 1/%d\n", i + 1, i + 1, i + 1);
    len += (size_t)snprintf(text + len, cap - len, "usemtl corner\nf 1/-1 1/-2 1/-3\n");
    VT_CHECK(len < cap);

    struct membuf out;
    struct vt_offset_stats s;
    struct vts_error err;
    int rc = offset_fixture_rewrite(text, &l, 0, &out, &s, &err);
    VT_CHECK_INT_EQ(rc, 0);
    VT_CHECK_INT_EQ(s.digits, 10);
    VT_CHECK_INT_EQ(s.vt_rewritten, count);
    /* read the written text back with strtod and compare with the exact double mapping */
    double worst = 0, worst32 = 0;
    int bad = 0;
    for (int i = 0; i < count; i++) {
        double in_u, in_v, u, v, au, av;
        const struct vt_layout_entry *e = &l.entries[i < whole_count               ? 0
                                                     : i < whole_count + odd_count ? 1
                                                                                   : 2];
        if (!offset_fixture_nth_vt(text, i, &in_u, &in_v) ||
            !offset_fixture_nth_vt(out.data, i, &u, &v)) {
            bad++;
            continue;
        }
        vt_layout_map_uv(&l, e, in_u, in_v, &au, &av);
        double eu = fabs(u - au) * size, ev = fabs(v - av) * size;
        double eu32 = fabs((double)(float)u - au) * size, ev32 = fabs((double)(float)v - av) * size;
        worst = fmax(worst, fmax(eu, ev));
        worst32 = fmax(worst32, fmax(eu32, ev32));
    }
    VT_CHECK_INT_EQ(bad, 0);
    VT_CHECK(worst < 1e-3);
    VT_CHECK(worst <= 0.5e-10 * size * 1.0001); /* half a unit of the 10th decimal */
    VT_CHECK(s.max_error == worst);             /* the rewriter measured the same */
    VT_CHECK(s.max_error_f32 == worst32);
    VT_CHECK(worst32 <= 1.0 / 32 + 1e-4); /* float32 spacing 2^-24 below 1: 1/16 texel */
    VT_CHECK(!vt_offset_f32_warning(&s));
    /* 0 and 1 are written exactly */
    double u, v;
    VT_CHECK(offset_fixture_nth_vt(out.data, whole_count - 4, &u, &v) && u == 0 && v == 0.5);
    VT_CHECK(offset_fixture_nth_vt(out.data, whole_count - 3, &u, &v) && u == 1 && v == 1);
    /* the 1x1 entry in the last atlas texel: its corners */
    VT_CHECK(offset_fixture_nth_vt(out.data, count - 3, &u, &v) &&
             fabs(u * size - (size - 1)) < 1e-3 && v == 0);
    VT_CHECK(offset_fixture_nth_vt(out.data, count - 2, &u, &v) && u == 1 &&
             fabs(v * size - 1) < 1e-3);
    VT_CHECK(strstr(out.data, "\nvt 0 0.5\n") && strstr(out.data, "\nvt 1 1\n"));
    free(out.data);
    free(text);
    vt_layout_release(&l);
}

/* Charts 10^4 repeats away (u 10000.x, v -9999.x) are moved by whole repeats exactly: on a 2^20
 * atlas every written coordinate is within 1e-3 texel of the exact mapping of the moved value;
 * a chart straddling nothing keeps one copy of the texture. */
static void moves_charts_of_ten_thousand_repeats_exactly(void)
{
    const uint32_t size = 1u << 20;
    static const struct spec rects[] = {{"far", 300000, 500000, 4096, 4096, 1, 1, 0, 0}};
    struct vt_layout l;
    offset_fixture_layout(&l, size, size, rects, 1);
    size_t cap = 1 << 20, len = 0;
    char *text = malloc(cap);
    len += (size_t)snprintf(text + len, cap - len, "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl far\n");
    double us[300], vs[300];
    int n = 0;
    for (int c = 0; c < 100; c++) { /* 100 charts of one triangle, each at its own repeat */
        double base_u = 10000 + c, base_v = -9999 - 2 * c;
        for (int k = 0; k < 3; k++, n++) {
            us[n] = base_u + (0.1 + 0.8 * ((c * 7 + k * 13) % 97) / 97.0);
            vs[n] = base_v + (0.1 + 0.8 * ((c * 5 + k * 31) % 89) / 89.0);
            len += (size_t)snprintf(text + len, cap - len, "vt %.17g %.17g\n", us[n], vs[n]);
        }
        len += (size_t)snprintf(text + len, cap - len, "f 1/-3 2/-2 3/-1\n");
    }
    VT_CHECK(len < cap);
    struct membuf out;
    struct vt_offset_stats s;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(offset_fixture_rewrite(text, &l, 0, &out, &s, &err), 0);
    VT_CHECK_STR_EQ(err.message, "");
    VT_CHECK_INT_EQ(s.charts, 100);
    VT_CHECK_INT_EQ(s.charts_moved, 100);
    VT_CHECK_INT_EQ(s.faces_cut, 0);
    double worst = 0;
    for (int i = 0; i < n; i++) {
        double u, v, au, av;
        VT_CHECK(offset_fixture_nth_vt(out.data, i, &u, &v));
        double mu = us[i] - floor(us[i]), mv = vs[i] - floor(vs[i]); /* exact in double */
        vt_layout_map_uv(&l, &l.entries[0], mu, mv, &au, &av);
        worst = fmax(worst, fmax(fabs(u - au), fabs(v - av)) * size);
    }
    printf("10^4 repeats on a 2^20 atlas: worst error %.3g texel\n", worst);
    VT_CHECK(worst < 1e-3);
    free(out.data);
    free(text);
    vt_layout_release(&l);
}

/* Maps u to an atlas coordinate t texels from the left of a 2^23-wide atlas and returns the
 * rewriter's stats. */
static struct vt_offset_stats stats_at_texel(double t)
{
    static const struct spec rect[] = {{"a", 0, 0, 1u << 23, 256, 1, 1, 0, 0}};
    struct vt_layout l;
    offset_fixture_layout(&l, 1u << 23, 256, rect, 1);
    char text[256];
    snprintf(text, sizeof text, "v 0 0 0\nvt %.17g 0.5\nusemtl a\nf 1/1 1/1 1/1\n", t / (1u << 23));
    struct membuf out;
    struct vt_offset_stats s;
    struct vts_error err;
    int rc = offset_fixture_rewrite(text, &l, 0, &out, &s, &err);
    VT_CHECK_INT_EQ(rc, 0);
    free(out.data);
    vt_layout_release(&l);
    return s;
}

/* float32 has 24 bits: between 2^22 and 2^23 texels it holds every half texel, so a coordinate
 * 0.12 texel past a half texel loses 0.12 texel (no warning) and one 0.13 past loses 0.13 (more
 * than 1/8: warning). Below 2^22 texels float32 is four times finer. */
static void warns_exactly_when_float32_loses_an_eighth_of_a_texel(void)
{
    struct vt_offset_stats s = stats_at_texel(4194304 + 1000.5 + 0.12);
    VT_CHECK(fabs(s.max_error_f32 - 0.12) < 1e-3);
    VT_CHECK(!vt_offset_f32_warning(&s));
    VT_CHECK(s.max_error < 1e-3);
    s = stats_at_texel(4194304 + 1000.5 + 0.13);
    VT_CHECK(fabs(s.max_error_f32 - 0.13) < 1e-3);
    VT_CHECK(vt_offset_f32_warning(&s));
    VT_CHECK_INT_EQ(s.max_error_f32_line, 2);
    s = stats_at_texel(4194304 + 1000.5 - 0.13); /* below the grid point: also 0.13 */
    VT_CHECK(vt_offset_f32_warning(&s));
    s = stats_at_texel(4194304 + 1000.25); /* the worst case: a quarter texel */
    VT_CHECK(fabs(s.max_error_f32 - 0.25) < 1e-3 && vt_offset_f32_warning(&s));
    s = stats_at_texel(1000000.13); /* spacing 1/8 texel here: at most 1/16 lost */
    VT_CHECK(s.max_error_f32 <= 0.0626 && !vt_offset_f32_warning(&s));
}

/* ---- bad input: nothing written, file:line messages ---- */

static void rejects_bad_input_before_writing(void)
{
    struct vt_layout l;
    offset_fixture_layout(&l, 1024, 1024, two_halves, 2);
    VT_CHECK(offset_fixture_expect_error(
        "v 0 0 0\nvt 0 0\nvt 1 1\nusemtl a\nf 1/1 1/3 1/2\n", &l, VTS_ERR_BAD_INPUT,
        "'s.obj':5: texture index 3 in '1/3' out of range (2 texcoords defined)"));
    VT_CHECK(offset_fixture_expect_error(
        "v 0 0 0\nvt 0 0\nusemtl a\nf 1/1 1/-2 1/1\n", &l, VTS_ERR_BAD_INPUT,
        "'s.obj':4: texture index -2 in '1/-2' out of range (1 texcoords defined)"));
    VT_CHECK(offset_fixture_expect_error(
        "v 0 0 0\nvt 0 0\nusemtl a\nf 2/1 1/1 1/1\n", &l, VTS_ERR_BAD_INPUT,
        "'s.obj':4: vertex index 2 in '2/1' out of range (1 vertices defined)"));
    VT_CHECK(offset_fixture_expect_error(
        "v 0 0 0\nvt 0 0\nusemtl a\nf 1/0 1/1 1/1\n", &l, VTS_ERR_BAD_INPUT,
        "'s.obj':4: texture index 0 in '1/0' (OBJ indices start at 1)"));
    VT_CHECK(offset_fixture_expect_error("v 0 0 0\nvt 0 0\nusemtl a\nf 1/x 1/1 1/1\n", &l,
                                         VTS_ERR_BAD_INPUT, "'s.obj':4: bad texture index '1/x'"));
    VT_CHECK(offset_fixture_expect_error("v 0 0 0\nvt 0.5 nan\n", &l, VTS_ERR_BAD_INPUT,
                                         "'s.obj':2: bad number 'nan' in 'vt'"));
    VT_CHECK(offset_fixture_expect_error("v 0 0 0\nvt 0.5 \\\n inf\n", &l, VTS_ERR_BAD_INPUT,
                                         "'s.obj':2: bad number 'inf' in 'vt'"));
    VT_CHECK(offset_fixture_expect_error("vt 1e999 0\n", &l, VTS_ERR_BAD_INPUT,
                                         "'s.obj':1: bad number '1e999' in 'vt'"));
    VT_CHECK(offset_fixture_expect_error("vt 0 0 0 0\n", &l, VTS_ERR_BAD_INPUT,
                                         "'s.obj':1: 'vt' needs 1 to 3 numbers"));
    VT_CHECK(offset_fixture_expect_error("vt\n", &l, VTS_ERR_BAD_INPUT,
                                         "'s.obj':1: 'vt' needs 1 to 3 numbers"));
    VT_CHECK(offset_fixture_expect_error(
        "v 0 0 0\nvt 0 0\nusemtl a\nusemtl zz top\nf 1/1 1/1 1/1\n", &l, VTS_ERR_BAD_INPUT,
        "'s.obj':5: material 'zz top' (usemtl on line 4) is not in 'atlas.json'"));
    VT_CHECK(
        offset_fixture_expect_error("v 0 0 0\nvt 0 0\nf 1/1 1/1 1/1\n", &l, VTS_ERR_BAD_INPUT,
                                    "'s.obj':3: face with texture coordinates before any usemtl"));
    VT_CHECK(offset_fixture_expect_error(
        "v 0 0 0\nvt 0 0\nvt 1.5 0.25\nusemtl b\nf 1/1 1/1 1/2\n", &l, VTS_ERR_BAD_INPUT,
        "'s.obj':5: vt 2 (1.5 0.25) is outside the UV range of material 'b' in 'atlas.json' (u 0..1, v 0..1): rebuild the atlas from this OBJ"));
    /* a chart one repeat down is moved (valid); one across v = 0 leaves the entry's one copy */
    VT_CHECK(offset_fixture_expect_error(
        "v 0 0 0\nvt 0 -0.001\nvt 0 0.5\nusemtl a\nf 1/1 1/1 1/2\n", &l, VTS_ERR_BAD_INPUT,
        "'s.obj':5: vt 2 (0 0.5, moved by 0 1) is outside the UV range of material 'a' in 'atlas.json' (u 0..1, v 0..1): rebuild the atlas from this OBJ"));
    VT_CHECK(offset_fixture_expect_error("v 0 0 0\nf 1 1\n", &l, VTS_ERR_BAD_INPUT,
                                         "'s.obj':2: face with 2 corners (needs 3)"));
    VT_CHECK(offset_fixture_expect_error("v 0 0 0\nmtllib\n", &l, VTS_ERR_BAD_INPUT,
                                         "'s.obj':2: mtllib without a file name"));
    struct membuf out = {0};
    struct vts_error err;
    struct vt_offset_options opt;
    vt_offset_options_default(&opt);
    struct vt_offset_sink sink = {offset_fixture_write, &out};
    static const char nul_text[] = "v 0 0 0\n# a \\\nb\0c\n";
    int rc = vt_offset_rewrite_memory(nul_text, sizeof nul_text - 1, "n.obj", &l, &opt, &sink, NULL,
                                      &err);
    VT_CHECK_INT_EQ(rc, VTS_ERR_BAD_INPUT);
    VT_CHECK(strcmp(err.message, "'n.obj':3: NUL byte in a text line") == 0);
    VT_CHECK_INT_EQ(out.len, 0);
    rc = vt_offset_rewrite("/nonexistent/s.obj", &l, &opt, &sink, NULL, &err);
    VT_CHECK_INT_EQ(rc, VTS_ERR_IO);
    VT_CHECK(strcmp(err.message, "cannot open '/nonexistent/s.obj': No such file or directory") ==
             0);
    /* a line over the limit */
    opt.limits.max_line_bytes = 16;
    rc = vt_offset_rewrite_memory("v 0 0 0\nvt 0.5 0.5 # a long comment\n", 38, "l.obj", &l, &opt,
                                  &sink, NULL, &err);
    VT_CHECK_INT_EQ(rc, VTS_ERR_LIMIT);
    VT_CHECK(strcmp(err.message, "'l.obj':2: line longer than the limit of 16 bytes") == 0);
    free(out.data);
    vt_layout_release(&l);
}

/* ---- end to end against vt_obj's reader ---- */

struct face_list {
    uint32_t *corners; /* v, vt, vn per corner */
    uint32_t *mat;     /* entry index per corner, or NONE */
    size_t count, cap;
    const struct vt_layout *layout;
};

static int collect_face(void *user, const struct vt_obj *obj, const struct vt_obj_face *face,
                        struct vts_error *err)
{
    struct face_list *f = user;
    (void)obj, (void)err;
    if (f->count + face->corner_count > f->cap) {
        f->cap = (f->count + face->corner_count) * 2;
        f->corners = realloc(f->corners, f->cap * 3 * sizeof *f->corners);
        f->mat = realloc(f->mat, f->cap * sizeof *f->mat);
    }
    const struct vt_layout_entry *e = vt_layout_find(f->layout, face->material);
    for (uint32_t i = 0; i < face->corner_count; i++, f->count++) {
        f->corners[3 * f->count] = face->corners[i].v;
        f->corners[3 * f->count + 1] = face->corners[i].vt;
        f->corners[3 * f->count + 2] = face->corners[i].vn;
        f->mat[f->count] = e ? (uint32_t)(e - f->layout->entries) : UINT32_MAX;
    }
    return 0;
}

/* Random scenes (shared vt, negative and positive indices, CRLF, continuations, w components):
 * every face corner of the output must name the same v and vn, and a vt whose value is the
 * input's vt mapped for the face's material. */
static void random_scenes_agree_with_the_obj_reader(void)
{
    static const struct spec rects[] = {{"m0", 0, 0, 256, 256, 1, 1, 0, 0},
                                        {"m1", 256, 0, 128, 512, 1, 1, 0, 0},
                                        {"m2", 512, 512, 64, 32, 2, 2, -1, 0},
                                        {"m3", 0, 768, 1024, 256, 1, 1, 0, 0}};
    struct vt_layout l;
    offset_fixture_layout(&l, 1024, 1024, rects, 4);
    uint64_t seed = 12345, duplicated = 0, renumbered = 0;
    int bad = 0;
    for (int round = 0; round < 40 && bad == 0; round++) {
        size_t cap = 1 << 18, len = 0;
        char *text = malloc(cap);
        int nv = 0, nvt = 0;
        bool crlf = round % 3 == 1;
        const char *eol = crlf ? "\r\n" : "\n";
        for (int k = 0; k < 300 && len < cap - 256; k++) {
            seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
            unsigned r = (unsigned)(seed >> 33);
            if (r % 7 == 0 || nv == 0) {
                len += (size_t)snprintf(text + len, cap - len, "v %u 0 0%s", r % 10, eol);
                nv++;
            } else if (r % 7 <= 2) {
                double u = (r >> 4) % 1000 / 999.0, v = (r >> 14) % 1000 / 999.0;
                if (r % 5 == 0)
                    len += (size_t)snprintf(text + len, cap - len, "vt %.6f \\%s%.6f 0.5%s", u, eol,
                                            v, eol);
                else
                    len += (size_t)snprintf(text + len, cap - len, "vt %.6f %.6f%s", u, v, eol);
                nvt++;
            } else if (r % 7 == 3) {
                len += (size_t)snprintf(text + len, cap - len, "usemtl m%u%s", (r >> 5) % 4, eol);
            } else if (nvt > 0) {
                if (!strstr(text, "usemtl"))
                    len += (size_t)snprintf(text + len, cap - len, "usemtl m0%s", eol);
                len += (size_t)snprintf(text + len, cap - len, "f");
                for (int c = 0; c < 3 + (int)(r % 3); c++) {
                    seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
                    unsigned q = (unsigned)(seed >> 33);
                    int vi = (int)(q % (unsigned)nv), ti = (int)((q >> 10) % (unsigned)nvt);
                    if (q % 2)
                        len += (size_t)snprintf(text + len, cap - len, " %d/%d", vi + 1, ti + 1);
                    else
                        len += (size_t)snprintf(text + len, cap - len, " %d/%d", vi - nv, ti - nvt);
                }
                len += (size_t)snprintf(text + len, cap - len, "%s", eol);
            }
        }
        struct membuf out;
        struct vt_offset_stats s;
        struct vts_error err;
        int rc = offset_fixture_rewrite(text, &l, 12, &out, &s, &err);
        if (rc != 0) {
            fprintf(stderr, "round %d: %s\n", round, err.message);
            bad++;
            free(text);
            continue;
        }
        duplicated += s.vt_duplicated;
        renumbered += s.faces_rewritten;
        struct face_list in_faces = {.layout = &l}, out_faces = {.layout = &l};
        struct vt_obj_callbacks cb_in = {NULL, NULL, collect_face, &in_faces};
        struct vt_obj_callbacks cb_out = {NULL, NULL, collect_face, &out_faces};
        struct vt_obj *in = vt_obj_create(NULL, &err), *outobj = vt_obj_create(NULL, &err);
        VT_CHECK_INT_EQ(vt_obj_parse_memory(in, text, len, "in", &cb_in, &err), 0);
        VT_CHECK_INT_EQ(vt_obj_parse_memory(outobj, out.data, out.len, "out", &cb_out, &err), 0);
        VT_CHECK_INT_EQ(in_faces.count, out_faces.count);
        VT_CHECK_INT_EQ(vt_obj_texcoord_count(outobj), s.vt_lines + s.vt_duplicated);
        const double *tin = vt_obj_texcoords(in), *tout = vt_obj_texcoords(outobj);
        for (size_t c = 0; c < in_faces.count && c < out_faces.count; c++) {
            uint32_t *a = &in_faces.corners[3 * c], *b = &out_faces.corners[3 * c];
            if (a[0] != b[0] || a[2] != b[2] || (a[1] == UINT32_MAX) != (b[1] == UINT32_MAX)) {
                bad++;
                continue;
            }
            double au, av;
            vt_layout_map_uv(&l, &l.entries[in_faces.mat[c]], tin[3 * a[1]], tin[3 * a[1] + 1], &au,
                             &av);
            if (fabs(tout[3 * b[1]] - au) > 1e-12 || fabs(tout[3 * b[1] + 1] - av) > 1e-12 ||
                tout[3 * b[1] + 2] != tin[3 * a[1] + 2])
                bad++;
        }
        vt_obj_destroy(in);
        vt_obj_destroy(outobj);
        free(in_faces.corners);
        free(in_faces.mat);
        free(out_faces.corners);
        free(out_faces.mat);
        free(out.data);
        free(text);
    }
    VT_CHECK_INT_EQ(bad, 0);
    VT_CHECK(duplicated > 1000 && renumbered > 1000); /* the scenes did share vt */
    vt_layout_release(&l);
}

/* Reading a file in 1 MiB blocks (lines across block ends, a 900 KB line, continuations across
 * block ends) gives the same bytes as reading memory; a line over the limit is refused. */
static void file_and_memory_agree(void)
{
    struct vt_layout l;
    offset_fixture_layout(&l, 1024, 1024, two_halves, 2);
    size_t cap = 6u << 20, len = 0;
    char *text = malloc(cap);
    uint64_t seed = 99;
    for (int block = 0; len < cap - (1u << 20) - 4096; block++) {
        seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
        size_t pad = block == 40 ? 900000 : (size_t)(seed >> 33) % 3000;
        len += (size_t)snprintf(text + len, cap - len, "# c ");
        memset(text + len, 'x', pad);
        len += pad;
        len += (size_t)snprintf(text + len, cap - len,
                                "\r\nv 0 0 0\r\nvt 0.25 0.5\r\nvt 0.5 \\\r\n 0.75 0.1\r\n"
                                "usemtl a\r\nf -1/-1 -1/-2 \\\n-1/-1\r\nusemtl b\r\nf -1/-2 "
                                "-1/-2 -1/-1\n");
    }
    char path[] = "/tmp/test_vt_offset_XXXXXX";
    int fd = mkstemp(path);
    VT_CHECK(fd >= 0);
    FILE *f = fdopen(fd, "wb");
    VT_CHECK(f && fwrite(text, 1, len, f) == len);
    fclose(f);
    struct vt_offset_options opt;
    vt_offset_options_default(&opt);
    struct membuf a = {0}, b = {0};
    struct vt_offset_sink sa = {offset_fixture_write, &a}, sb = {offset_fixture_write, &b};
    struct vt_offset_stats st_a, st_b;
    struct vts_error err;
    VT_CHECK_INT_EQ(vt_offset_rewrite(path, &l, &opt, &sa, &st_a, &err), 0);
    VT_CHECK_INT_EQ(vt_offset_rewrite_memory(text, len, path, &l, &opt, &sb, &st_b, &err), 0);
    VT_CHECK(a.len == b.len && a.len > len && memcmp(a.data, b.data, a.len) == 0);
    VT_CHECK(st_a.lines == st_b.lines && st_a.vt_duplicated == st_b.vt_duplicated &&
             st_a.vt_duplicated > 1000);
    /* a 1.5 MiB line in a file */
    f = fopen(path, "wb");
    fputs("v 0 0 0\n# ", f);
    for (int i = 0; i < 3 << 19; i++)
        fputc('y', f);
    fputs("\nvt 0 0\n", f);
    fclose(f);
    free(a.data);
    a = (struct membuf){0};
    VT_CHECK_INT_EQ(vt_offset_rewrite(path, &l, &opt, &sa, NULL, &err), VTS_ERR_LIMIT);
    char want[256];
    snprintf(want, sizeof want, "'%s':2: line longer than the limit of 1048576 bytes", path);
    VT_CHECK(strcmp(err.message, want) == 0);
    VT_CHECK_INT_EQ(a.len, 0);
    remove(path);
    free(a.data);
    free(b.data);
    free(text);
    vt_layout_release(&l);
}

int main(void)
{
    VT_RUN(keeps_texel_precision_on_a_2_20_atlas);
    VT_RUN(moves_charts_of_ten_thousand_repeats_exactly);
    VT_RUN(warns_exactly_when_float32_loses_an_eighth_of_a_texel);
    VT_RUN(rejects_bad_input_before_writing);
    VT_RUN(random_scenes_agree_with_the_obj_reader);
    VT_RUN(file_and_memory_agree);
    return vt_test_main_result();
}
