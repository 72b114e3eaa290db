/* Unit tests of lib/obj/vt_obj.c: small OBJ/MTL files written to a temp dir, exact results checked.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "vt_obj.h"
#include "vt_test.h"

static char tmp_dir[64];

/* Writes text to tmp_dir/name and returns the full path (static buffer, one at a time). */
static const char *write_file(const char *name, const char *text)
{
    static char path[256];
    snprintf(path, sizeof path, "%s/%s", tmp_dir, name);
    FILE *f = fopen(path, "wb");
    if (!f)
        return path;
    fwrite(text, 1, strlen(text), f);
    fclose(f);
    return path;
}

#define MAX_CORNERS 64
#define MAX_NAMES   8

/* What the callbacks saw. */
struct seen {
    int faces;
    uint32_t corner_counts[16];
    struct vt_obj_corner corners[MAX_CORNERS];
    int corner_total;
    char face_material[16][32];
    char face_group[16][32];
    char face_object[16][32];
    uint64_t face_line[16];
    char mtllibs[MAX_NAMES][256];
    int mtllib_count;
    char usemtls[MAX_NAMES][32];
    int usemtl_count;
};

static int on_face(void *user, const struct vt_obj *obj, const struct vt_obj_face *f,
                   struct vts_error *err)
{
    struct seen *s = user;
    (void)obj, (void)err;
    if (s->faces < 16) {
        s->corner_counts[s->faces] = f->corner_count;
        snprintf(s->face_material[s->faces], 32, "%s", f->material);
        snprintf(s->face_group[s->faces], 32, "%s", f->group);
        snprintf(s->face_object[s->faces], 32, "%s", f->object);
        s->face_line[s->faces] = f->line;
    }
    for (uint32_t i = 0; i < f->corner_count && s->corner_total < MAX_CORNERS; i++)
        s->corners[s->corner_total++] = f->corners[i];
    s->faces++;
    return 0;
}

static int on_mtllib(void *user, const struct vt_obj *obj, const char *path, uint64_t line,
                     struct vts_error *err)
{
    struct seen *s = user;
    (void)obj, (void)line, (void)err;
    if (s->mtllib_count < MAX_NAMES)
        snprintf(s->mtllibs[s->mtllib_count++], 256, "%s", path);
    return 0;
}

static int on_usemtl(void *user, const struct vt_obj *obj, const char *name, uint64_t line,
                     struct vts_error *err)
{
    struct seen *s = user;
    (void)obj, (void)line, (void)err;
    if (s->usemtl_count < MAX_NAMES)
        snprintf(s->usemtls[s->usemtl_count++], 32, "%s", name);
    return 0;
}

/* Parses text (from memory, named name) with fresh callbacks; returns the status. */
static int parse_text(const char *text, const char *name, const struct vt_obj_limits *limits,
                      struct seen *s, struct vt_obj **out, struct vts_error *err)
{
    memset(s, 0, sizeof *s);
    struct vt_obj_callbacks cb = {on_mtllib, on_usemtl, on_face, s};
    struct vt_obj *obj = vt_obj_create(limits, err);
    int rc = obj ? vt_obj_parse_memory(obj, text, strlen(text), name, &cb, err) : VTS_ERR_NOMEM;
    if (out)
        *out = obj;
    else
        vt_obj_destroy(obj);
    return rc;
}

static void check_corner(const struct vt_obj_corner *c, uint32_t v, uint32_t vt, uint32_t vn)
{
    VT_CHECK_INT_EQ(c->v, v);
    VT_CHECK_INT_EQ(c->vt, vt);
    VT_CHECK_INT_EQ(c->vn, vn);
}

static void obj_resolves_negative_indices(void)
{
    struct seen s;
    struct vts_error err;
    const char *text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvn 0 0 1\n"
                       "f -3/-3/-1 -2/-2/-1 -1/-1/-1\n"
                       "v 0 1 0\nf 1/1/1 -1/-1/-1 3/3/1\n";
    VT_CHECK_INT_EQ(parse_text(text, "neg.obj", NULL, &s, NULL, &err), 0);
    VT_CHECK_INT_EQ(s.faces, 2);
    check_corner(&s.corners[0], 0, 0, 0);
    check_corner(&s.corners[1], 1, 1, 0);
    check_corner(&s.corners[2], 2, 2, 0);
    check_corner(&s.corners[3], 0, 0, 0);
    check_corner(&s.corners[4], 3, 2, 0); /* -1 after the 4th v is v index 3; vt still 2 */
    check_corner(&s.corners[5], 2, 2, 0);
}

static void obj_reads_faces_without_texcoords_or_normals(void)
{
    struct seen s;
    struct vts_error err;
    const char *text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nvn 0 0 1\nvt 0.5 0.5\n"
                       "f 1//1 2//1 3//1\nf 1 2 3\nf 1/1 2/1 3/1\n";
    VT_CHECK_INT_EQ(parse_text(text, "novt.obj", NULL, &s, NULL, &err), 0);
    VT_CHECK_INT_EQ(s.faces, 3);
    check_corner(&s.corners[0], 0, VT_OBJ_NONE, 0);
    check_corner(&s.corners[4], 1, VT_OBJ_NONE, VT_OBJ_NONE);
    check_corner(&s.corners[8], 2, 0, VT_OBJ_NONE);
}

static void obj_delivers_quads_and_ngons_whole(void)
{
    struct seen s;
    struct vts_error err;
    const char *text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 1.5 0\n"
                       "f 1 2 3 4\nf 1 2 3 5 4\n";
    VT_CHECK_INT_EQ(parse_text(text, "quads.obj", NULL, &s, NULL, &err), 0);
    VT_CHECK_INT_EQ(s.faces, 2);
    VT_CHECK_INT_EQ(s.corner_counts[0], 4);
    VT_CHECK_INT_EQ(s.corner_counts[1], 5);
    VT_CHECK_INT_EQ(s.corners[7].v, 4);
    VT_CHECK_INT_EQ(s.corners[8].v, 3);
}

static void obj_keeps_three_component_texcoords_and_exponents(void)
{
    struct seen s;
    struct vts_error err;
    struct vt_obj *obj;
    const char *text = "vt 0.25 0.75 0.5\nvt 1e-3 2.5E+1\nvt 0.125\nv 1.5e2 -2 3e-2 1.0\n";
    VT_CHECK_INT_EQ(parse_text(text, "vt3.obj", NULL, &s, &obj, &err), 0);
    VT_CHECK_INT_EQ(vt_obj_texcoord_count(obj), 3);
    const double *t = vt_obj_texcoords(obj);
    VT_CHECK(t[0] == 0.25 && t[1] == 0.75 && t[2] == 0.5);
    VT_CHECK(t[3] == 1e-3 && t[4] == 25.0 && t[5] == 0.0);
    VT_CHECK(t[6] == 0.125 && t[7] == 0.0);
    VT_CHECK_INT_EQ(vt_obj_texcoord_components(obj, 0), 3);
    VT_CHECK_INT_EQ(vt_obj_texcoord_components(obj, 1), 2);
    VT_CHECK_INT_EQ(vt_obj_texcoord_components(obj, 2), 1);
    VT_CHECK_INT_EQ(vt_obj_texcoord_components(obj, 3), 0);
    const double *p = vt_obj_positions(obj);
    VT_CHECK(p[0] == 150.0 && p[1] == -2.0 && p[2] == 3e-2);
    vt_obj_destroy(obj);
}

static void obj_joins_continuations_and_strips_crlf(void)
{
    struct seen s;
    struct vts_error err;
    struct vt_obj *obj;
    const char *text = "# comment\r\n\r\nv 0 0 0\r\nv 1 0 0\r\nv \\\r\n 1 1 0\r\n"
                       "g  a\tb \r\nf 1 \\\n2 \\\n 3\r\nf\t1\t2  3 # trailing comment\r\n"
                       "vt 0.5\\\n0.25\n";
    VT_CHECK_INT_EQ(parse_text(text, "crlf.obj", NULL, &s, &obj, &err), 0);
    VT_CHECK_INT_EQ(vt_obj_position_count(obj), 3);
    VT_CHECK(vt_obj_positions(obj)[6] == 1.0 && vt_obj_positions(obj)[7] == 1.0);
    VT_CHECK_INT_EQ(s.faces, 2);
    VT_CHECK_INT_EQ(s.face_line[0], 8);
    VT_CHECK_INT_EQ(s.face_line[1], 11);
    VT_CHECK(strcmp(s.face_group[0], "a\tb") == 0);
    VT_CHECK_INT_EQ(s.corners[2].v, 2);
    struct vt_obj_stats st;
    vt_obj_stats(obj, &st);
    VT_CHECK_INT_EQ(st.lines, 13);
    VT_CHECK_INT_EQ(vt_obj_texcoord_components(obj, 0), 2); /* the '\\' separates like a space */
    VT_CHECK(vt_obj_texcoords(obj)[1] == 0.25);
    vt_obj_destroy(obj);
}

static void obj_reports_usemtl_before_mtllib_and_several_libraries(void)
{
    struct seen s;
    struct vts_error err;
    struct vt_obj *obj;
    const char *text = "usemtl early\nv 0 0 0\nv 1 0 0\nv 1 1 0\no thing\nf 1 2 3\n"
                       "mtllib a.mtl\nmtllib sub/b.mtl  ../c.mtl\nmtllib my scene.mtl\n"
                       "mtllib /abs/d.mtl\nmtllib tex\\win.mtl\nusemtl late name\nf 1 2 3\n"
                       "l 1 2\np 1\ns off\ncstype bezier\n";
    VT_CHECK_INT_EQ(parse_text(text, "dir/scene.obj", NULL, &s, &obj, &err), 0);
    VT_CHECK_INT_EQ(s.mtllib_count, 6);
    VT_CHECK(strcmp(s.mtllibs[0], "dir/a.mtl") == 0);
    VT_CHECK(strcmp(s.mtllibs[1], "dir/sub/b.mtl") == 0);
    VT_CHECK(strcmp(s.mtllibs[2], "dir/../c.mtl") == 0);
    VT_CHECK(strcmp(s.mtllibs[3], "dir/my scene.mtl") == 0);
    VT_CHECK(strcmp(s.mtllibs[4], "/abs/d.mtl") == 0);
    VT_CHECK(strcmp(s.mtllibs[5], "dir/tex/win.mtl") == 0);
    VT_CHECK_INT_EQ(s.usemtl_count, 2);
    VT_CHECK(strcmp(s.face_material[0], "early") == 0);
    VT_CHECK(strcmp(s.face_object[0], "thing") == 0);
    VT_CHECK(strcmp(s.face_material[1], "late name") == 0);
    struct vt_obj_stats st;
    vt_obj_stats(obj, &st);
    VT_CHECK_INT_EQ(st.ignored_statements, 3);
    VT_CHECK_INT_EQ(st.unknown_statements, 1);
    vt_obj_destroy(obj);
}

/* Parses text expecting status; the message must contain want. */
static void check_error(const char *text, const struct vt_obj_limits *limits, int status,
                        const char *want)
{
    struct seen s;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(parse_text(text, "scene.obj", limits, &s, NULL, &err), status);
    VT_CHECK_INT_EQ(err.status, status);
    VT_CHECK_STR_CONTAINS(err.message, want);
}

static void obj_errors_name_file_and_line(void)
{
    const char *tri = "v 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\n";
    char text[256];
    snprintf(text, sizeof text, "%sf 1/1 2/1 4/1\n", tri);
    check_error(text, NULL, VTS_ERR_BAD_INPUT,
                "'scene.obj':5: vertex index 4 in '4/1' out of range");
    snprintf(text, sizeof text, "%sf 1/1 2/1 -4/1\n", tri);
    check_error(text, NULL, VTS_ERR_BAD_INPUT, "'scene.obj':5: vertex index -4");
    snprintf(text, sizeof text, "%sf 1/1 2/2 3/1\n", tri);
    check_error(text, NULL, VTS_ERR_BAD_INPUT, "'scene.obj':5: texture index 2 in '2/2' out of");
    snprintf(text, sizeof text, "%sf 1/1 0/1 3/1\n", tri);
    check_error(text, NULL, VTS_ERR_BAD_INPUT, "'scene.obj':5: vertex index 0");
    snprintf(text, sizeof text, "%s\nf 1/1 2/x 3/1\n", tri);
    check_error(text, NULL, VTS_ERR_BAD_INPUT, "'scene.obj':6: bad texture index '2/x'");
    snprintf(text, sizeof text, "%sf 1/1/1 2/1 3/1\n", tri);
    check_error(text, NULL, VTS_ERR_BAD_INPUT, "'scene.obj':5: normal index 1 in '1/1/1' out of");
    check_error("v 0 0 0\nv 1 0.5x 0\n", NULL, VTS_ERR_BAD_INPUT,
                "'scene.obj':2: bad number '0.5x' in 'v'");
    check_error("vt nan 0\n", NULL, VTS_ERR_BAD_INPUT, "'scene.obj':1: bad number 'nan'");
    check_error("vt 1e999 0\n", NULL, VTS_ERR_BAD_INPUT, "bad number '1e999'");
    check_error("v 1 2\n", NULL, VTS_ERR_BAD_INPUT, "'scene.obj':1: 'v' needs 3 to 7 numbers");
    check_error("v 0 0 0\nf 1 1\n", NULL, VTS_ERR_BAD_INPUT, "'scene.obj':2: face with 2 corners");
}

static void obj_limits_fail_with_limit_status(void)
{
    struct vt_obj_limits limits;
    vt_obj_limits_default(&limits);
    limits.max_line_bytes = 16;
    check_error("v 0 0 0\n# this comment is far too long\n", &limits, VTS_ERR_LIMIT,
                "'scene.obj':2: line longer than the limit of 16 bytes");
    check_error("v 0 0 0\nv 0.000000000 \\\n 0.000000 0\n", &limits, VTS_ERR_LIMIT,
                "'scene.obj':2: line longer");
    vt_obj_limits_default(&limits);
    limits.max_vertices = 2;
    check_error("vt 0 0\nv 0 0 0\nv 1 0 0\nvt 1 1\nv 2 0 0\n", &limits, VTS_ERR_LIMIT,
                "'scene.obj':5: more than 2 vertices (the limit)");
}

static void obj_accepts_empty_and_comment_only_files(void)
{
    struct seen s;
    struct vts_error err;
    struct vt_obj *obj;
    VT_CHECK_INT_EQ(parse_text("", "empty.obj", NULL, &s, &obj, &err), 0);
    VT_CHECK_INT_EQ(vt_obj_position_count(obj), 0);
    vt_obj_destroy(obj);
    VT_CHECK_INT_EQ(parse_text("# a\n#b\r\n\n   \n# c", "c.obj", NULL, &s, &obj, &err), 0);
    VT_CHECK_INT_EQ(s.faces, 0);
    struct vt_obj_stats st;
    vt_obj_stats(obj, &st);
    VT_CHECK_INT_EQ(st.lines, 5);
    VT_CHECK_INT_EQ(st.unknown_statements, 0);
    vt_obj_destroy(obj);
}

static int stop_at_second_face(void *user, const struct vt_obj *obj, const struct vt_obj_face *f,
                               struct vts_error *err)
{
    (void)user, (void)obj, (void)err;
    return f->line == 5 ? 1 : 0;
}

static void obj_reads_files_and_stops_when_a_callback_asks(void)
{
    const char *path = write_file("file.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\nf 3 2 1\n");
    struct vts_error err;
    struct vt_obj *obj = vt_obj_create(NULL, &err);
    struct vt_obj_callbacks cb = {NULL, NULL, stop_at_second_face, NULL};
    VT_CHECK_INT_EQ(vt_obj_read(obj, path, &cb, &err), VTS_ERR_CANCELLED);
    VT_CHECK_STR_CONTAINS(err.message, "file.obj':5: stopped by the face callback");
    VT_CHECK_INT_EQ(vt_obj_read(obj, path, NULL, &err), 0);
    VT_CHECK_INT_EQ(vt_obj_position_count(obj), 3);
    VT_CHECK_INT_EQ(vt_obj_read(obj, "/nonexistent/x.obj", NULL, &err), VTS_ERR_IO);
    VT_CHECK_STR_CONTAINS(err.message, "cannot open '/nonexistent/x.obj'");
    vt_obj_destroy(obj);
}

static void mtl_reads_colours_and_keeps_d_and_tr_raw(void)
{
    char dir[128];
    snprintf(dir, sizeof dir, "%s/m", tmp_dir);
    VT_CHECK_INT_EQ(mkdir(dir, 0700), 0);
    const char *path = write_file("m/a.mtl", "# exported\nnewmtl red\nKd 1 0 0\nKa 0.1\n"
                                             "Ks 0.5 0.5 0.5\nd 0.5\nillum 2\nNs 10\n"
                                             "Ke 0.25 0.5 2\nNi 1.45\nvt_alpha test\n"
                                             "newmtl meshlab\nTr 1.000000\nKd 0.2 0.4 0.6\n"
                                             "Ke 0.5\nvt_alpha blend\nnewmtl plain\n");
    struct vt_mtl mtl;
    struct vts_error err;
    VT_CHECK_INT_EQ(vt_mtl_read(path, NULL, &mtl, &err), 0);
    const struct vt_mtl_material *red = vt_mtl_find(&mtl, "red");
    VT_CHECK(red && red->kd[0] == 1 && red->kd[1] == 0 && red->ka[2] == 0.1);
    VT_CHECK(red && red->d == 0.5 && red->illum == 2 && red->line == 2);
    VT_CHECK(red && (red->flags & VT_MTL_HAS_TR) == 0 && red->tr == 0);
    const struct vt_mtl_material *ml = vt_mtl_find(&mtl, "meshlab");
    VT_CHECK(ml && ml->tr == 1.0 && ml->d == 1.0 && (ml->flags & VT_MTL_HAS_TR));
    VT_CHECK(ml && (ml->flags & VT_MTL_HAS_D) == 0 && ml->kd[2] == 0.6);
    VT_CHECK(ml && ml->maps[VT_MTL_MAP_KD].file == NULL);
    VT_CHECK(vt_mtl_find(&mtl, "blue") == NULL);
    /* Ns, Ke and vtpipe's vt_alpha are kept; Ni is not */
    VT_CHECK(red && red->ns == 10 && (red->flags & VT_MTL_HAS_NS) && red->ke[0] == 0.25 &&
             red->ke[1] == 0.5 && red->ke[2] == 2 && (red->flags & VT_MTL_HAS_KE));
    VT_CHECK(red && red->alpha == VT_MTL_ALPHA_TEST);
    VT_CHECK(ml && ml->ke[0] == 0.5 && ml->ke[2] == 0.5 && ml->alpha == VT_MTL_ALPHA_BLEND);
    VT_CHECK(ml && (ml->flags & VT_MTL_HAS_NS) == 0 && ml->ns == 0);
    const struct vt_mtl_material *pl = vt_mtl_find(&mtl, "plain");
    VT_CHECK(pl && pl->alpha == VT_MTL_ALPHA_AUTO && pl->flags == 0 && pl->ke[1] == 0);
    VT_CHECK_INT_EQ(mtl.material_count, 3);
    VT_CHECK_INT_EQ(mtl.unknown_statements, 1);
    vt_mtl_release(&mtl);
}

static void mtl_parses_map_options_and_paths_with_spaces(void)
{
    const char *text = "newmtl wall\r\n"
                       "map_Kd -s 2 3 1 -o 0.5 0.25 -clamp on -blendu off -imfchan r -mm 0.1 2 "
                       "-texres 512 -t 1 -cc on -boost 1.5 textures/brick wall 01.png  \r\n"
                       "map_Bump -bm 0.75 normals\\brick n.png\n"
                       "bump other.png\nmap_d -imfchan m /abs/alpha.png\nnorm  C:\\tex\\n.png\n"
                       "disp -o -1 d.png\nmap_Ka -s 2 1.png\nmap_Ks \\\n spec.png\n";
    struct vt_mtl mtl;
    struct vts_error err;
    VT_CHECK_INT_EQ(vt_mtl_parse_memory(text, strlen(text), "scene/mat/w.mtl", NULL, &mtl, &err),
                    0);
    VT_CHECK_INT_EQ(mtl.material_count, 1);
    const struct vt_mtl_material *m = vt_mtl_find(&mtl, "wall");
    if (!m) {
        VT_CHECK(m != NULL);
        vt_mtl_release(&mtl);
        return;
    }
    const struct vt_mtl_map *kd = &m->maps[VT_MTL_MAP_KD];
    VT_CHECK(kd->file && strcmp(kd->file, "textures/brick wall 01.png") == 0);
    VT_CHECK(kd->path && strcmp(kd->path, "scene/mat/textures/brick wall 01.png") == 0);
    VT_CHECK(kd->s[0] == 2 && kd->s[1] == 3 && kd->s[2] == 1);
    VT_CHECK(kd->o[0] == 0.5 && kd->o[1] == 0.25 && kd->o[2] == 0);
    VT_CHECK(kd->clamp && !kd->blendu && kd->blendv && kd->cc);
    VT_CHECK(kd->imfchan == 'r' && kd->mm[0] == 0.1 && kd->mm[1] == 2 && kd->texres == 512);
    VT_CHECK(kd->t[0] == 1 && kd->t[1] == 0 && kd->boost == 1.5);
    VT_CHECK_INT_EQ(kd->options, VT_MTL_OPT_S | VT_MTL_OPT_O | VT_MTL_OPT_CLAMP |
                                     VT_MTL_OPT_BLENDU | VT_MTL_OPT_IMFCHAN | VT_MTL_OPT_MM |
                                     VT_MTL_OPT_TEXRES | VT_MTL_OPT_T | VT_MTL_OPT_CC |
                                     VT_MTL_OPT_BOOST);
    const struct vt_mtl_map *bump = &m->maps[VT_MTL_MAP_BUMP];
    VT_CHECK(bump->path && strcmp(bump->path, "scene/mat/other.png") == 0); /* the later wins */
    const struct vt_mtl_map *d = &m->maps[VT_MTL_MAP_D];
    VT_CHECK(d->path && strcmp(d->path, "/abs/alpha.png") == 0 && d->imfchan == 'm');
    const struct vt_mtl_map *norm = &m->maps[VT_MTL_MAP_NORM];
    VT_CHECK(norm->path && strcmp(norm->path, "C:/tex/n.png") == 0);
    const struct vt_mtl_map *disp = &m->maps[VT_MTL_MAP_DISP];
    VT_CHECK(disp->o[0] == -1 && disp->path && strcmp(disp->path, "scene/mat/d.png") == 0);
    const struct vt_mtl_map *ka = &m->maps[VT_MTL_MAP_KA];
    VT_CHECK(ka->s[0] == 2 && ka->s[1] == 1 && ka->file && strcmp(ka->file, "1.png") == 0);
    const struct vt_mtl_map *ks = &m->maps[VT_MTL_MAP_KS];
    VT_CHECK(ks->path && strcmp(ks->path, "scene/mat/spec.png") == 0);
    vt_mtl_release(&mtl);
}

static void mtl_backslash_paths_and_bump_options(void)
{
    const char *text = "newmtl n\nmap_Bump -bm 0.75 normals\\brick n.png\n";
    struct vt_mtl mtl;
    struct vts_error err;
    VT_CHECK_INT_EQ(vt_mtl_parse_memory(text, strlen(text), "w.mtl", NULL, &mtl, &err), 0);
    const struct vt_mtl_map *b =
        mtl.material_count ? &mtl.materials[0].maps[VT_MTL_MAP_BUMP] : NULL;
    VT_CHECK(b && b->bm == 0.75 && b->path && strcmp(b->path, "normals/brick n.png") == 0);
    vt_mtl_release(&mtl);
}

/* Each map keeps the line its statement starts on: the last of a repeated kind (map_Bump, bump
 * and MAP_BUMP are one kind), the first physical line of a continued statement, per material. */
static void mtl_maps_keep_the_line_of_their_statement(void)
{
    const char *text = "# two materials\n"           /* 1 */
                       "newmtl a\n"                  /* 2 */
                       "map_Kd first.png\n"          /* 3 */
                       "Kd 1 1 1\n"                  /* 4 */
                       "map_Kd \\\n"                 /* 5 */
                       "  second.png\n"              /* 6 */
                       "map_Bump -bm 2 b1.png\n"     /* 7 */
                       "\n"                          /* 8 */
                       "MAP_BUMP b2.png\n"           /* 9 */
                       "newmtl b\n"                  /* 10 */
                       "bump b3.png\n"               /* 11 */
                       "  norm  n with space.png\n"; /* 12 */
    struct vt_mtl mtl;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(vt_mtl_parse_memory(text, strlen(text), "l.mtl", NULL, &mtl, &err), 0);
    VT_CHECK_INT_EQ(mtl.material_count, 2);
    if (mtl.material_count != 2) {
        vt_mtl_release(&mtl);
        return;
    }
    const struct vt_mtl_material *a = &mtl.materials[0], *b = &mtl.materials[1];
    VT_CHECK_INT_EQ(a->line, 2);
    VT_CHECK_INT_EQ(a->maps[VT_MTL_MAP_KD].line, 5);
    VT_CHECK(a->maps[VT_MTL_MAP_KD].path && strcmp(a->maps[VT_MTL_MAP_KD].path, "second.png") == 0);
    VT_CHECK_INT_EQ(a->maps[VT_MTL_MAP_BUMP].line, 9);
    VT_CHECK(a->maps[VT_MTL_MAP_BUMP].bm == 1); /* the later statement replaced -bm 2 */
    VT_CHECK_INT_EQ(a->maps[VT_MTL_MAP_KS].line, 0);
    VT_CHECK_INT_EQ(a->maps[VT_MTL_MAP_NORM].line, 0);
    VT_CHECK_INT_EQ(b->line, 10);
    VT_CHECK_INT_EQ(b->maps[VT_MTL_MAP_BUMP].line, 11);
    VT_CHECK_INT_EQ(b->maps[VT_MTL_MAP_NORM].line, 12);
    VT_CHECK(b->maps[VT_MTL_MAP_NORM].path &&
             strcmp(b->maps[VT_MTL_MAP_NORM].path, "n with space.png") == 0);
    VT_CHECK_INT_EQ(b->maps[VT_MTL_MAP_KD].line, 0);
    vt_mtl_release(&mtl);
}

/* The same lines from a file, CRLF line ends included (the reader vt-atlas uses). */
static void mtl_file_maps_keep_their_line(void)
{
    char path[600];
    snprintf(path, sizeof path, "%s/lines.mtl", tmp_dir);
    FILE *f = fopen(path, "wb");
    VT_CHECK(f != NULL);
    if (!f)
        return;
    fputs("newmtl m\r\nKd 0.5 0.5 0.5\r\n\r\nmap_Ks s.png\r\nmap_d a.png\r\n", f);
    fclose(f);
    struct vt_mtl mtl;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(vt_mtl_read(path, NULL, &mtl, &err), 0);
    const struct vt_mtl_material *m = vt_mtl_find(&mtl, "m");
    VT_CHECK(m != NULL);
    if (m) {
        VT_CHECK_INT_EQ(m->maps[VT_MTL_MAP_KS].line, 4);
        VT_CHECK_INT_EQ(m->maps[VT_MTL_MAP_D].line, 5);
    }
    vt_mtl_release(&mtl);
}

static void check_mtl_error(const char *text, const struct vt_obj_limits *limits, int status,
                            const char *want)
{
    struct vt_mtl mtl;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(vt_mtl_parse_memory(text, strlen(text), "x.mtl", limits, &mtl, &err), status);
    VT_CHECK_STR_CONTAINS(err.message, want);
    vt_mtl_release(&mtl);
}

/* vtpipe's vt_wang PACK [scale S] (docs/wang.md, "Packs in scenes"): the path resolved like a
 * map's, scale 1 by default, a repeated statement replaces the earlier one. */
static void mtl_reads_vt_wang(void)
{
    const char *text = "newmtl grass\nKd 1 1 1\nvt_wang packs/grass.vts scale 0.25\n"
                       "newmtl sand\nvt_wang a.vts\nvt_wang /abs/sand.vts\nnewmtl plain\n";
    struct vt_mtl mtl;
    struct vts_error err;
    VT_CHECK_INT_EQ(vt_mtl_parse_memory(text, strlen(text), "scene/w.mtl", NULL, &mtl, &err), 0);
    const struct vt_mtl_material *g = vt_mtl_find(&mtl, "grass");
    VT_CHECK(g && g->wang_path && strcmp(g->wang_path, "scene/packs/grass.vts") == 0);
    VT_CHECK(g && g->wang_scale == 0.25 && g->kd[0] == 1);
    const struct vt_mtl_material *s = vt_mtl_find(&mtl, "sand");
    VT_CHECK(s && s->wang_path && strcmp(s->wang_path, "/abs/sand.vts") == 0 && s->wang_scale == 1);
    const struct vt_mtl_material *p = vt_mtl_find(&mtl, "plain");
    VT_CHECK(p && p->wang_path == NULL);
    VT_CHECK_INT_EQ(mtl.unknown_statements, 0);
    vt_mtl_release(&mtl);
}

static void mtl_errors_name_file_and_line(void)
{
    check_mtl_error("newmtl a\nKd 1 x 0\n", NULL, VTS_ERR_BAD_INPUT, "'x.mtl':2: bad number 'x'");
    check_mtl_error("newmtl a\nNs high\n", NULL, VTS_ERR_BAD_INPUT, "'x.mtl':2: bad number 'high'");
    check_mtl_error("newmtl a\nKe 1 2\n", NULL, VTS_ERR_BAD_INPUT,
                    "'x.mtl':2: needs 1 or 3 numbers: 'Ke'");
    check_mtl_error("newmtl a\n\nvt_alpha cutout\n", NULL, VTS_ERR_BAD_INPUT,
                    "'x.mtl':3: vt_alpha must be none, test or blend, not 'cutout'");
    check_mtl_error("newmtl a\nvt_alpha test blend\n", NULL, VTS_ERR_BAD_INPUT,
                    "'x.mtl':2: vt_alpha must be none, test or blend, not 'test'");
    check_mtl_error("newmtl a\nvt_wang\n", NULL, VTS_ERR_BAD_INPUT,
                    "'x.mtl':2: missing pack after 'vt_wang'");
    check_mtl_error("newmtl a\nvt_wang p.vts scale 0\n", NULL, VTS_ERR_BAD_INPUT,
                    "'x.mtl':2: vt_wang scale must be a number > 0, not '0'");
    check_mtl_error("newmtl a\nvt_wang p.vts scale 2x\n", NULL, VTS_ERR_BAD_INPUT,
                    "'x.mtl':2: vt_wang scale must be a number > 0, not '2x'");
    check_mtl_error("newmtl a\nvt_wang p.vts 2\n", NULL, VTS_ERR_BAD_INPUT,
                    "'x.mtl':2: vt_wang takes 'scale S' after the pack, not '2'");
    check_mtl_error("newmtl a\nvt_wang p.vts scale 2 3\n", NULL, VTS_ERR_BAD_INPUT,
                    "'x.mtl':2: unexpected after vt_wang scale '3'");
    check_mtl_error("newmtl a\n\nmap_Kd -clamp maybe a.png\n", NULL, VTS_ERR_BAD_INPUT,
                    "'x.mtl':3: expected on or off after '-clamp'");
    check_mtl_error("newmtl a\nmap_Kd -zz 1 a.png\n", NULL, VTS_ERR_BAD_INPUT,
                    "'x.mtl':2: unknown map option '-zz'");
    check_mtl_error("newmtl a\nmap_Kd -s 1 2\n", NULL, VTS_ERR_BAD_INPUT,
                    "'x.mtl':2: map statement without a file name");
    check_mtl_error("newmtl a\nmap_Kd -s a.png\n", NULL, VTS_ERR_BAD_INPUT,
                    "'x.mtl':2: missing number after '-s'");
    struct vt_obj_limits limits;
    vt_obj_limits_default(&limits);
    limits.max_materials = 2;
    check_mtl_error("newmtl a\nnewmtl b\nnewmtl c\n", &limits, VTS_ERR_LIMIT,
                    "'x.mtl':3: more than 2 materials");
    struct vt_mtl mtl;
    struct vts_error err;
    VT_CHECK_INT_EQ(vt_mtl_read("/nonexistent/x.mtl", NULL, &mtl, &err), VTS_ERR_IO);
    vt_mtl_release(&mtl);
}

int main(void)
{
    snprintf(tmp_dir, sizeof tmp_dir, "/tmp/vt_obj_test_XXXXXX");
    if (!mkdtemp(tmp_dir)) {
        fprintf(stderr, "cannot create a temp dir\n");
        return 1;
    }
    VT_RUN(obj_resolves_negative_indices);
    VT_RUN(obj_reads_faces_without_texcoords_or_normals);
    VT_RUN(obj_delivers_quads_and_ngons_whole);
    VT_RUN(obj_keeps_three_component_texcoords_and_exponents);
    VT_RUN(obj_joins_continuations_and_strips_crlf);
    VT_RUN(obj_reports_usemtl_before_mtllib_and_several_libraries);
    VT_RUN(obj_errors_name_file_and_line);
    VT_RUN(obj_limits_fail_with_limit_status);
    VT_RUN(obj_accepts_empty_and_comment_only_files);
    VT_RUN(obj_reads_files_and_stops_when_a_callback_asks);
    VT_RUN(mtl_reads_colours_and_keeps_d_and_tr_raw);
    VT_RUN(mtl_parses_map_options_and_paths_with_spaces);
    VT_RUN(mtl_backslash_paths_and_bump_options);
    VT_RUN(mtl_errors_name_file_and_line);
    VT_RUN(mtl_reads_vt_wang);
    VT_RUN(mtl_maps_keep_the_line_of_their_statement);
    VT_RUN(mtl_file_maps_keep_their_line);
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmp_dir);
    if (system(cmd) != 0)
        fprintf(stderr, "cannot remove %s\n", tmp_dir);
    return vt_test_main_result();
}
