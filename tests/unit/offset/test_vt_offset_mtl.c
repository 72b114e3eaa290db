/* vt-offset's materials: usemtl lines kept (options.material NULL), the materials the faces use
 * (vt_offset_used), and the MTL (vt_offset_write_mtl) read back with lib/obj's MTL reader: every
 * constant, the alpha mode and one STORE#layer map per layer the material has. */
#include <stdlib.h>
#include <string.h>

#include "offset_fixture.h"
#include "vt_obj.h"
#include "vt_test.h"

static char *xstrdup(const char *s)
{
    char *d = malloc(strlen(s) + 1);
    strcpy(d, s);
    return d;
}

/* Entries "a" (alias "b") and "const" on a 64x64 atlas; materials a (specular), b (blend), const
 * (test, forced). */
static void make_layout(struct vt_layout *l, bool materials)
{
    static const struct spec specs[] = {{"a", 0, 0, 16, 16, 1, 1, 0, 0},
                                        {"const", 32, 0, 4, 4, 1, 1, 0, 0}};
    offset_fixture_layout(l, 64, 64, specs, 2);
    struct vt_layout_entry *e = &l->entries[0];
    e->aliases = malloc(sizeof *e->aliases);
    e->aliases[0] = xstrdup("b");
    e->alias_count = 1;
    if (materials) {
        VT_CHECK_INT_EQ(vt_layout_alloc_materials(l, 3, NULL), 0);
        struct vt_layout_material *m = l->materials;
        m[0] = (struct vt_layout_material){.name = xstrdup("a"),
                                           .entry = 0,
                                           .layer_mask = 1,
                                           .kd = {0.5, 0.25, 1},
                                           .ks = {0.75, 0.75, 0.75},
                                           .ns = 96,
                                           .d = 1,
                                           .illum = 2};
        m[1] = (struct vt_layout_material){.name = xstrdup("b"),
                                           .entry = 0,
                                           .layer_mask = 1,
                                           .kd = {1, 1, 1},
                                           .ke = {0, 2, 0},
                                           .d = 0.5,
                                           .illum = 4,
                                           .alpha = VT_LAYOUT_ALPHA_BLEND};
        m[2] = (struct vt_layout_material){.name = xstrdup("const"),
                                           .entry = 1,
                                           .kd = {0.1, 0.2, 0.3},
                                           .ka = {0.125, 0, 0},
                                           .d = 1,
                                           .illum = 1,
                                           .alpha = VT_LAYOUT_ALPHA_TEST};
    }
    VT_CHECK_INT_EQ(vt_layout_index(l, NULL), 0);
}

static const char *const scene = "mtllib s.mtl\nv 0 0 0\nvt 0.5 0.5\n"
                                 "  usemtl b\r\nf 1/1 1/1 1/1\n"
                                 "usemtl unused\n" /* no face follows */
                                 "usemtl const\nf 1 1 1\n"
                                 "usemtl a\nf 1/1 1/1 1/1\n"
                                 "usemtl zz_plain\nf 1 1 1\nusemtl yy\nf 1 1 1\n"
                                 "usemtl zz_plain\nf 1 1 1\n";

static int rewrite(const struct vt_layout *l, struct membuf *obj, struct vt_offset_used *used)
{
    struct vt_offset_options opt;
    vt_offset_options_default(&opt);
    opt.mtllib = "s.vt.mtl";
    opt.material = NULL;
    opt.used = used;
    struct vt_offset_sink sink = {offset_fixture_write, obj};
    struct vts_error err;
    return vt_offset_rewrite_memory(scene, strlen(scene), "s.obj", l, &opt, &sink, NULL, &err);
}

static void faces_keep_their_materials(void)
{
    struct vt_layout l;
    make_layout(&l, true);
    struct membuf obj = {0};
    struct vt_offset_used used;
    VT_CHECK_INT_EQ(rewrite(&l, &obj, &used), 0);
    /* usemtl lines byte for byte (indentation, CRLF) */
    VT_CHECK(obj.data && strstr(obj.data, "\n  usemtl b\r\nf 1/1 1/1 1/1\nusemtl unused\n"
                                          "usemtl const\nf 1 1 1\nusemtl a\nf 1/1 1/1 1/1\n"));
    /* a and b share the cell but map the vt once each: same entry, same move, one vt line */
    VT_CHECK(obj.data && strstr(obj.data, "vt_atlas") == NULL);
    /* used: every name of the layout but 'unused' (not in it), in slot order; the names it
     * lacks sorted, once */
    VT_CHECK_INT_EQ(used.slot_count, 3);
    for (uint32_t i = 0; i < used.slot_count && i < 3; i++)
        VT_CHECK_INT_EQ(used.slots[i], i);
    VT_CHECK_INT_EQ(used.unknown_count, 2);
    if (used.unknown_count == 2) {
        VT_CHECK_STR_EQ(used.unknown[0], "yy");
        VT_CHECK_STR_EQ(used.unknown[1], "zz_plain");
    }
    vt_offset_used_release(&used);
    vt_offset_used_release(&used); /* twice is harmless */
    free(obj.data);
    vt_layout_release(&l);
}

static void mtl_reads_back_with_every_constant(void)
{
    struct vt_layout l;
    make_layout(&l, true);
    struct membuf obj = {0}, mtl = {0};
    struct vt_offset_used used;
    VT_CHECK_INT_EQ(rewrite(&l, &obj, &used), 0);
    struct vt_offset_sink sink = {offset_fixture_write, &mtl};
    struct vts_error err;
    VT_CHECK_INT_EQ(vt_offset_write_mtl(&l, &used, "s.vts", "from s.obj\nline two", &sink, &err),
                    0);
    VT_CHECK(mtl.data && strncmp(mtl.data, "# from s.obj\n# line two\n", 24) == 0);
    struct vt_mtl m;
    VT_CHECK_INT_EQ(vt_mtl_parse_memory(mtl.data, mtl.len, "s.vt.mtl", NULL, &m, &err), 0);
    VT_CHECK_INT_EQ(m.material_count, 5);
    VT_CHECK_INT_EQ(m.unknown_statements, 0);
    for (uint32_t i = 0; i < l.material_count; i++) {
        const struct vt_layout_material *want = &l.materials[i];
        const struct vt_mtl_material *got = vt_mtl_find(&m, want->name);
        VT_CHECK(got != NULL);
        if (!got)
            continue;
        for (int k = 0; k < 3; k++)
            VT_CHECK(got->kd[k] == want->kd[k] && got->ka[k] == want->ka[k] &&
                     got->ks[k] == want->ks[k] && got->ke[k] == want->ke[k]);
        VT_CHECK(got->ns == want->ns && got->d == want->d && got->illum == (int)want->illum);
        VT_CHECK_INT_EQ(got->alpha, VT_MTL_ALPHA_NONE + want->alpha);
        const char *map = got->maps[VT_MTL_MAP_KD].file;
        VT_CHECK(want->layer_mask ? map && strcmp(map, "s.vts#diffuse") == 0 : map == NULL);
    }
    const struct vt_mtl_material *plain = vt_mtl_find(&m, "zz_plain");
    VT_CHECK(plain && plain->kd[0] == 0.8 && plain->d == 1 && !plain->maps[VT_MTL_MAP_KD].file);
    vt_mtl_release(&m);
    vt_offset_used_release(&used);
    free(obj.data);
    free(mtl.data);
    vt_layout_release(&l);
}

static void layouts_without_materials_get_implied_ones(void)
{
    struct vt_layout l;
    make_layout(&l, false);
    struct membuf obj = {0}, mtl = {0};
    struct vt_offset_used used;
    VT_CHECK_INT_EQ(rewrite(&l, &obj, &used), 0);
    struct vt_offset_sink sink = {offset_fixture_write, &mtl};
    struct vts_error err;
    VT_CHECK_INT_EQ(vt_offset_write_mtl(&l, &used, "s.vts", NULL, &sink, &err), 0);
    struct vt_mtl m;
    VT_CHECK_INT_EQ(vt_mtl_parse_memory(mtl.data, mtl.len, "s.vt.mtl", NULL, &m, &err), 0);
    const struct vt_mtl_material *b = vt_mtl_find(&m, "b"), *c = vt_mtl_find(&m, "const");
    VT_CHECK(b && b->kd[0] == 1 && b->d == 1 && b->alpha == VT_MTL_ALPHA_NONE);
    VT_CHECK(b && b->maps[VT_MTL_MAP_KD].file &&
             !strcmp(b->maps[VT_MTL_MAP_KD].file, "s.vts#diffuse"));
    VT_CHECK(c && !c->maps[VT_MTL_MAP_KD].file);
    vt_mtl_release(&m);
    vt_offset_used_release(&used);
    free(obj.data);
    free(mtl.data);
    vt_layout_release(&l);
}

int main(void)
{
    VT_RUN(faces_keep_their_materials);
    VT_RUN(mtl_reads_back_with_every_constant);
    VT_RUN(layouts_without_materials_get_implied_ones);
    return vt_test_main_result();
}
