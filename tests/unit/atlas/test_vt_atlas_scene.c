/* Unit tests of the scene scan (lib/atlas/vt_atlas_scene.c): a small scene written to a temp dir
 * (the test runs inside it, so paths and messages are short), its texture headers given by a fake
 * opener through the callback. Texture files exist (the scan stats them) but are empty. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "vt_atlas_scene.h"
#include "vt_test.h"

static char tmp_dir[64];

static void write_file(const char *name, const char *text)
{
    FILE *f = fopen(name, "wb");
    VT_CHECK(f != NULL);
    if (!f)
        return;
    fputs(text, f);
    fclose(f);
}

/* ---- the fake opener: sizes by file name, "broken" files fail ---- */

struct fake_opener {
    int calls;
    char paths[8][64]; /* the first 8 paths opened */
};

static int fake_open(void *user, const char *path, struct vt_source *out, struct vts_error *err)
{
    struct fake_opener *f = user;
    if (f->calls < 8)
        snprintf(f->paths[f->calls], sizeof f->paths[0], "%s", path);
    f->calls++;
    memset(out, 0, sizeof *out);
    if (strstr(path, "broken"))
        return vt_error_set(err, VTS_ERR_BAD_INPUT, "'%s': not an image", path);
    bool big = strstr(path, "b.png") != NULL;
    out->info.width = big ? 256 : 128;
    out->info.height = big ? 256 : 64;
    out->info.channels = big ? 4 : 3;
    snprintf(out->name, sizeof out->name, "%s", path);
    return 0;
}

/* ---- warnings ---- */

struct warnings {
    int count;
    char last[VTS_ERROR_MESSAGE_MAX];
};

static void collect_warning(void *user, const char *message)
{
    struct warnings *w = user;
    w->count++;
    snprintf(w->last, sizeof w->last, "%s", message);
}

static struct vt_atlas_scene_options options(struct fake_opener *f, struct warnings *w)
{
    return (struct vt_atlas_scene_options){.max_textures = 100,
                                           .max_line_bytes = 1 << 16,
                                           .open = fake_open,
                                           .open_user = f,
                                           .warn = collect_warning,
                                           .warn_user = w};
}

/* Materials by line: red and blue share tex/shared.png, alias names it through another path
 * (the same file), blue has a bump and a norm map of one file, plain has no texture, gone names a
 * missing file, bad a file the opener rejects. */
static const char *const scene_mtl = "newmtl red\n"                    /* 1 */
                                     "Kd 1 0 0\n"                      /* 2 */
                                     "map_Kd tex/shared.png\n"         /* 3 */
                                     "\n"                              /* 4 */
                                     "newmtl blue\n"                   /* 5 */
                                     "Kd 0 0 1\n"                      /* 6 */
                                     "Ks 2 -1 0.5\n"                   /* 7 */
                                     "map_Kd tex/shared.png\n"         /* 8 */
                                     "bump -bm 2 tex/b.png\n"          /* 9 */
                                     "norm tex/b.png\n"                /* 10 */
                                     "newmtl plain\n"                  /* 11 */
                                     "Kd 0.2 0.4 0.6\n"                /* 12 */
                                     "d 0.5\n"                         /* 13 */
                                     "newmtl gone\n"                   /* 14 */
                                     "Kd 1 1 1\n"                      /* 15 */
                                     "map_Kd -s 2 2 tex/missing.png\n" /* 16 */
                                     "newmtl alias\n"                  /* 17 */
                                     "map_Kd tex/../tex/link.png\n"    /* 18 */
                                     "newmtl bad\n"                    /* 19 */
                                     "map_Ks tex/broken.png\n";        /* 20 */

/* vt 5 (-1, 3) puts blue's UVs outside [0,1]. */
static const char *const scene_vertices = "mtllib scene.mtl\n"
                                          "v 0 0 0\nv 2 0 0\nv 2 2 0\nv 0 2 0\n"
                                          "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt -1 3\n";

static void write_scene(const char *faces)
{
    write_file("scene.mtl", scene_mtl);
    char obj[1024];
    snprintf(obj, sizeof obj, "%s%s", scene_vertices, faces);
    write_file("scene.obj", obj);
}

static void scene_shares_files_and_measures_uvs(void)
{
    write_scene("usemtl red\n"
                "f 1/1 2/2 3/3 4/4\n" /* line 12: world area 4, UV area 1 */
                "usemtl blue\n"
                "f 1/1 2/2 3/5\n" /* UVs u -1..1, v 0..3 */
                "usemtl plain\n"
                "f 1 2 3\n" /* no texcoords */
                "usemtl nowhere\n"
                "f 1/1 2/2 3/3\n" /* line 18 */
                "usemtl alias\n"
                "f 1/1 2/2 3/3\n"
                "usemtl red\n"
                "f 1/1 2/2 3/3\n"); /* world 2, UV 0.5 more for red */
    struct fake_opener f = {0};
    struct warnings w = {0};
    struct vt_atlas_scene_options o = options(&f, &w);
    struct vt_atlas_scene s = {0};
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(vt_atlas_scene_scan_obj(&s, "scene.obj", &o, &err), 0);
    VT_CHECK_STR_EQ(err.message, "");
    VT_CHECK_INT_EQ(s.material_count, 5);
    VT_CHECK_INT_EQ(s.texture_count, 2);
    VT_CHECK_INT_EQ(f.calls, 2); /* one open per file, whatever the paths and uses */
    if (s.material_count != 5 || s.texture_count != 2) {
        vt_atlas_scene_release(&s);
        return;
    }
    const struct vt_atlas_material *red = &s.materials[0], *blue = &s.materials[1],
                                   *plain = &s.materials[2], *nowhere = &s.materials[3],
                                   *alias = &s.materials[4];
    VT_CHECK_STR_EQ(red->name, "red");
    VT_CHECK_STR_EQ(blue->name, "blue");
    VT_CHECK_STR_EQ(plain->name, "plain");
    VT_CHECK_STR_EQ(nowhere->name, "nowhere");
    VT_CHECK_STR_EQ(alias->name, "alias");
    VT_CHECK_STR_EQ(s.textures[0].path, "tex/shared.png");
    VT_CHECK_INT_EQ(s.textures[0].width, 128);
    VT_CHECK_INT_EQ(s.textures[0].height, 64);
    VT_CHECK_INT_EQ(s.textures[0].channels, 3);
    VT_CHECK_STR_EQ(s.textures[1].path, "tex/b.png");
    VT_CHECK_INT_EQ(s.textures[1].width, 256);
    VT_CHECK_INT_EQ(s.textures[1].channels, 4);
    /* Shared file: red, blue and alias (another path to the same inode) use texture 0. */
    VT_CHECK_INT_EQ(red->texture[VT_ATLAS_DIFFUSE], 0);
    VT_CHECK_INT_EQ(blue->texture[VT_ATLAS_DIFFUSE], 0);
    VT_CHECK_INT_EQ(alias->texture[VT_ATLAS_DIFFUSE], 0);
    VT_CHECK_INT_EQ(blue->texture[VT_ATLAS_NORMAL], 1);
    VT_CHECK_INT_EQ(red->texture[VT_ATLAS_NORMAL], -1);
    /* A material without textures keeps its constants (d as alpha). */
    VT_CHECK(plain->defined);
    for (unsigned k = 0; k < VT_ATLAS_KIND_COUNT; k++)
        VT_CHECK_INT_EQ(plain->texture[k], -1);
    VT_CHECK(plain->fill[VT_ATLAS_DIFFUSE][0] == 0.2 && plain->fill[VT_ATLAS_DIFFUSE][1] == 0.4 &&
             plain->fill[VT_ATLAS_DIFFUSE][2] == 0.6 && plain->fill[VT_ATLAS_DIFFUSE][3] == 1);
    VT_CHECK(plain->fill[VT_ATLAS_ALPHA][0] == 0.5 && plain->fill[VT_ATLAS_ALPHA][3] == 1);
    VT_CHECK(!plain->has_uv && plain->uv_area == 0 && plain->world_area == 0);
    /* Constants are clamped into [0,1]; a flat normal without a normal map. */
    VT_CHECK(blue->fill[VT_ATLAS_SPECULAR][0] == 1 && blue->fill[VT_ATLAS_SPECULAR][1] == 0 &&
             blue->fill[VT_ATLAS_SPECULAR][2] == 0.5);
    VT_CHECK(red->fill[VT_ATLAS_NORMAL][0] == 0.5 && red->fill[VT_ATLAS_NORMAL][2] == 1);
    /* UV ranges and areas. */
    VT_CHECK(blue->has_uv && blue->raw_umin == -1 && blue->raw_umax == 1 && blue->raw_vmin == 0 &&
             blue->raw_vmax == 3);
    /* one chart, moved by one repeat in u: u 0..2, v 0..3 */
    VT_CHECK(blue->umin == 0 && blue->umax == 2 && blue->vmin == 0 && blue->vmax == 3);
    VT_CHECK_INT_EQ(blue->charts, 1);
    VT_CHECK_INT_EQ(blue->moved_charts, 1);
    VT_CHECK(red->umin == 0 && red->umax == 1 && red->vmin == 0 && red->vmax == 1);
    VT_CHECK_INT_EQ(red->charts, 1); /* its two faces share vt 1, 2 and 3 */
    VT_CHECK_INT_EQ(red->moved_charts, 0);
    VT_CHECK(fabs(red->world_area - 6) < 1e-12 && fabs(red->uv_area - 1.5) < 1e-12);
    /* An undefined material: grey, one warning naming the OBJ line of its first face. */
    VT_CHECK(!nowhere->defined && nowhere->fill[VT_ATLAS_DIFFUSE][0] == 0.8);
    VT_CHECK_INT_EQ(nowhere->first_line, 18);
    VT_CHECK_INT_EQ(red->first_line, 12);
    VT_CHECK_STR_EQ(red->obj, "scene.obj");
    VT_CHECK_INT_EQ(w.count, 1);
    VT_CHECK_STR_EQ(
        w.last, "'scene.obj':18: material 'nowhere' is not defined in any mtllib: constant grey");
    /* Every file read, once, in order; the second path to the shared file too. */
    VT_CHECK_INT_EQ(s.dep_count, 5);
    if (s.dep_count == 5) {
        VT_CHECK_STR_EQ(s.deps[0], "scene.obj");
        VT_CHECK_STR_EQ(s.deps[1], "scene.mtl");
        VT_CHECK_STR_EQ(s.deps[2], "tex/shared.png");
        VT_CHECK_STR_EQ(s.deps[3], "tex/b.png");
        VT_CHECK_STR_EQ(s.deps[4], "tex/../tex/link.png");
    }
    vt_atlas_scene_release(&s);
    VT_CHECK(s.materials == NULL && s.material_count == 0 && s.index == NULL);
}

static void scene_missing_texture_fails_or_is_skipped(void)
{
    write_scene("usemtl gone\nf 1/1 2/2 3/3\nusemtl red\nf 1/1 2/2 3/3\n");
    struct fake_opener f = {0};
    struct warnings w = {0};
    struct vt_atlas_scene_options o = options(&f, &w);
    struct vt_atlas_scene s = {0};
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(vt_atlas_scene_scan_obj(&s, "scene.obj", &o, &err), VTS_ERR_IO);
    VT_CHECK_STR_EQ(err.message,
                    "'scene.mtl':16: map_Kd 'tex/missing.png': No such file or directory");
    VT_CHECK_INT_EQ(f.calls, 0);
    vt_atlas_scene_release(&s);

    o.missing_skip = true;
    err = (struct vts_error){0};
    VT_CHECK_INT_EQ(vt_atlas_scene_scan_obj(&s, "scene.obj", &o, &err), 0);
    VT_CHECK_INT_EQ(w.count, 1);
    VT_CHECK_STR_EQ(w.last,
                    "'scene.mtl':16: map_Kd 'tex/missing.png': No such file or directory (skipped: "
                    "the material's constant)");
    VT_CHECK_INT_EQ(s.material_count, 2);
    VT_CHECK_INT_EQ(s.texture_count, 1);
    if (s.material_count == 2) {
        VT_CHECK_INT_EQ(s.materials[0].texture[VT_ATLAS_DIFFUSE], -1);
        VT_CHECK(s.materials[0].defined && s.materials[0].fill[VT_ATLAS_DIFFUSE][0] == 1);
        VT_CHECK_INT_EQ(s.materials[1].texture[VT_ATLAS_DIFFUSE], 0);
    }
    VT_CHECK_INT_EQ(s.dep_count, 3); /* obj, mtl, shared: not the missing file */
    vt_atlas_scene_release(&s);
}

static void scene_prefixes_opener_errors_and_counts_textures(void)
{
    write_scene("usemtl bad\nf 1/1 2/2 3/3\n");
    struct fake_opener f = {0};
    struct warnings w = {0};
    struct vt_atlas_scene_options o = options(&f, &w);
    struct vt_atlas_scene s = {0};
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(vt_atlas_scene_scan_obj(&s, "scene.obj", &o, &err), VTS_ERR_BAD_INPUT);
    VT_CHECK_STR_EQ(err.message, "'scene.mtl':20: map_Ks: 'tex/broken.png': not an image");
    VT_CHECK_INT_EQ(f.calls, 1);
    vt_atlas_scene_release(&s);

    write_scene("usemtl red\nf 1/1 2/2 3/3\nusemtl blue\nf 1/1 2/2 3/3\n");
    o.max_textures = 1;
    err = (struct vts_error){0};
    VT_CHECK_INT_EQ(vt_atlas_scene_scan_obj(&s, "scene.obj", &o, &err), VTS_ERR_LIMIT);
    VT_CHECK_STR_EQ(err.message,
                    "'scene.mtl':10: norm 'tex/b.png': more than 1 textures (--max-textures)");
    vt_atlas_scene_release(&s);

    write_file("nolib.obj", "mtllib none.mtl\n");
    err = (struct vts_error){0};
    VT_CHECK_INT_EQ(vt_atlas_scene_scan_obj(&s, "nolib.obj", &o, &err), VTS_ERR_IO);
    VT_CHECK_STR_EQ(err.message,
                    "'nolib.obj':1: mtllib: cannot open 'none.mtl': No such file or directory");
    vt_atlas_scene_release(&s);
}

static void scene_list_names_entries_by_line(void)
{
    VT_CHECK_INT_EQ(system("mkdir -p lists && cp tex/shared.png lists/x.png"), 0);
    write_file("lists/l.txt", "# textures\n\n  x.png  \n../tex/b.png\n");
    struct fake_opener f = {0};
    struct warnings w = {0};
    struct vt_atlas_scene_options o = options(&f, &w);
    struct vt_atlas_scene s = {0};
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(vt_atlas_scene_scan_list(&s, "lists/l.txt", &o, &err), 0);
    VT_CHECK_INT_EQ(s.material_count, 2);
    VT_CHECK_INT_EQ(s.texture_count, 2);
    if (s.material_count == 2 && s.texture_count == 2) {
        VT_CHECK_STR_EQ(s.materials[0].name, "x.png");
        VT_CHECK_STR_EQ(s.textures[0].path, "lists/x.png");
        VT_CHECK_STR_EQ(s.materials[1].name, "../tex/b.png");
        VT_CHECK_INT_EQ(s.textures[1].width, 256);
        VT_CHECK(s.materials[1].defined && s.materials[1].texture[VT_ATLAS_DIFFUSE] == 1);
    }
    vt_atlas_scene_release(&s);

    write_file("lists/twice.txt", "x.png\nx.png\n");
    err = (struct vts_error){0};
    VT_CHECK_INT_EQ(vt_atlas_scene_scan_list(&s, "lists/twice.txt", &o, &err), VTS_ERR_BAD_INPUT);
    VT_CHECK_STR_EQ(err.message, "'lists/twice.txt':2: 'x.png' is listed twice");
    vt_atlas_scene_release(&s);

    char shared[] = "tex/shared.png", nothere[] = "tex/nothere.png";
    char *const files[] = {shared, nothere};
    err = (struct vts_error){0};
    VT_CHECK_INT_EQ(vt_atlas_scene_scan_files(&s, files, 2, &o, &err), VTS_ERR_IO);
    VT_CHECK_STR_EQ(err.message, "texture 'tex/nothere.png': No such file or directory");
    VT_CHECK_INT_EQ(s.material_count, 1);
    vt_atlas_scene_release(&s);
}

int main(void)
{
    snprintf(tmp_dir, sizeof tmp_dir, "/tmp/vt_atlas_scene_XXXXXX");
    if (!mkdtemp(tmp_dir) || chdir(tmp_dir) != 0) {
        fprintf(stderr, "cannot create a temp dir\n");
        return 1;
    }
    if (system("mkdir tex && : > tex/shared.png && : > tex/b.png && : > tex/broken.png && "
               "ln tex/shared.png tex/link.png") != 0) {
        fprintf(stderr, "cannot create the texture files\n");
        return 1;
    }
    VT_RUN(scene_shares_files_and_measures_uvs);
    VT_RUN(scene_missing_texture_fails_or_is_skipped);
    VT_RUN(scene_prefixes_opener_errors_and_counts_textures);
    VT_RUN(scene_list_names_entries_by_line);
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmp_dir);
    if (chdir("/") != 0 || system(cmd) != 0)
        fprintf(stderr, "cannot remove %s\n", tmp_dir);
    return vt_test_main_result();
}
