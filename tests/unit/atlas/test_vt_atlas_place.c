/* Unit tests of the placement (lib/atlas/vt_atlas_place.c) on scenes built in memory: layers,
 * shared entries, wrap copies, density scales, grids, messages, and relative texture paths. Every
 * layout produced is checked by vt_layout_index() (cells inside the atlas, no overlaps...). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vt_atlas_place.h"
#include "vt_test.h"

static char tex_a[] = "tex/a.png", tex_n[] = "tex/n.png", tex_c[] = "tex/c.png";
static char id_a[] = "1:1", id_n[] = "1:2", id_c[] = "1:3";

/* A material named name with the given diffuse and normal textures (-1: none), UVs in
 * [u0,u1] x [v0,v1] once its charts are moved by whole repeats (u0, v0 in [0,1)) and the fills of
 * an MTL without constants. */
static struct vt_atlas_material material(char *name, int32_t diffuse, int32_t normal, double u0,
                                         double u1, double v0, double v1)
{
    struct vt_atlas_material m = {.name = name,
                                  .obj = "scene.obj",
                                  .defined = true,
                                  .has_uv = true,
                                  .umin = u0,
                                  .umax = u1,
                                  .vmin = v0,
                                  .vmax = v1,
                                  .raw_umin = u0 - 1, /* as written: one repeat lower */
                                  .raw_umax = u1 - 1,
                                  .raw_vmin = v0,
                                  .raw_vmax = v1,
                                  .first_line = 7,
                                  .uv_area = 1,
                                  .world_area = 1};
    for (unsigned k = 0; k < VT_ATLAS_KIND_COUNT; k++) {
        m.texture[k] = -1;
        m.fill[k][0] = m.fill[k][1] = m.fill[k][2] = 0;
        m.fill[k][3] = 1;
    }
    m.fill[VT_ATLAS_NORMAL][0] = m.fill[VT_ATLAS_NORMAL][1] = 0.5;
    m.fill[VT_ATLAS_NORMAL][2] = 1;
    m.texture[VT_ATLAS_DIFFUSE] = diffuse;
    m.texture[VT_ATLAS_NORMAL] = normal;
    return m;
}

static struct vt_atlas_place_options place_options(void)
{
    return (struct vt_atlas_place_options){.tile_content = 256,
                                           .border = 4,
                                           .max_edge = 1u << 20,
                                           .gutter = 4,
                                           .max_scale = 4,
                                           .max_repeat = 16,
                                           .output = "out/atlas.json",
                                           .generator = "test 1.0"};
}

static void check_valid(struct vt_layout *l)
{
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(vt_layout_index(l, &err), 0);
    VT_CHECK_STR_EQ(err.message, "");
}

/* red and alias: one file, no other layer -> one entry; blue wraps (charts moved to u 0..2,
 * v 0..3); plain is a constant. */
static void place_shares_entries_and_copies_wrapped_uvs(void)
{
    struct vt_atlas_texture textures[] = {{tex_a, id_a, 128, 64, 3, false, false, {0}},
                                          {tex_n, id_n, 256, 256, 3, false, false, {0}}};
    char red[] = "red", alias[] = "alias", blue[] = "blue", plain[] = "plain";
    struct vt_atlas_material materials[] = {
        material(red, 0, -1, 0, 1, 0, 1), material(blue, 0, 1, 0, 2, 0, 3),
        material(plain, -1, -1, 0, 1, 0, 1), material(alias, 0, -1, 0.25, 0.75, 0, 1)};
    materials[2].fill[VT_ATLAS_DIFFUSE][0] = 0.2;
    struct vt_atlas_scene scene = {
        .materials = materials, .material_count = 4, .textures = textures, .texture_count = 2};
    struct vt_atlas_place_options o = place_options();
    struct vt_layout l;
    struct vt_atlas_place_report r;
    struct vts_error err = {0};

    o.wrap = VT_ATLAS_WRAP_REPORT;
    VT_CHECK_INT_EQ(vt_atlas_place(&scene, &o, &l, &r, &err), VTS_ERR_BAD_INPUT);
    VT_CHECK_STR_EQ(err.message,
                    "'scene.obj':7: material 'blue' (u -1..1, v 0..3) has charts that leave one "
                    "copy of its texture (u 0..2, v 0..3 moved by whole repeats): use --wrap "
                    "auto, replicate or split");
    vt_layout_release(&l);

    o.wrap = VT_ATLAS_WRAP_REPLICATE;
    o.max_repeat = 2;
    VT_CHECK_INT_EQ(vt_atlas_place(&scene, &o, &l, &r, &err), VTS_ERR_LIMIT);
    VT_CHECK_STR_EQ(err.message, "'scene.obj':7: material 'blue' needs more than --max-repeat 2 "
                                 "copies (charts moved by whole repeats cover u 0..2, v 0..3): "
                                 "use --wrap auto or split");
    vt_layout_release(&l);

    /* auto: 2 x 3 copies cost 6 textures, more than VT_ATLAS_REPLICATE_MAX_AREA: split */
    o.wrap = VT_ATLAS_WRAP_AUTO;
    o.max_repeat = 16;
    err = (struct vts_error){0};
    VT_CHECK_INT_EQ(vt_atlas_place(&scene, &o, &l, &r, &err), 0);
    VT_CHECK_INT_EQ(r.split, 1);
    VT_CHECK_INT_EQ(r.replicated, 0);
    if (l.entry_count == 3) {
        VT_CHECK(l.entries[1].wrap);
        VT_CHECK_INT_EQ(l.entries[1].repeat_u, 1);
        VT_CHECK_INT_EQ(l.entries[1].repeat_v, 1);
        VT_CHECK_INT_EQ(l.entries[1].crop_width, 256);
        /* red (and alias) hold the whole of a.png in one copy: the entry wraps, as the
         * texture repeats in an engine; with -clamp on it would not (below) */
        VT_CHECK(l.entries[0].wrap);
        check_valid(&l);
    }
    vt_layout_release(&l);

    /* -clamp on in any material sharing the entry: clamped gutters */
    materials[3].clamp = true;
    VT_CHECK_INT_EQ(vt_atlas_place(&scene, &o, &l, &r, &err), 0);
    VT_CHECK(l.entry_count == 3 && !l.entries[0].wrap && l.entries[1].wrap);
    vt_layout_release(&l);
    materials[3].clamp = false;

    o.wrap = VT_ATLAS_WRAP_REPLICATE;
    err = (struct vts_error){0};
    VT_CHECK_INT_EQ(vt_atlas_place(&scene, &o, &l, &r, &err), 0);
    VT_CHECK_STR_EQ(err.message, "");
    VT_CHECK_INT_EQ(l.layer_count, 2);
    VT_CHECK_INT_EQ(l.entry_count, 3);
    VT_CHECK_INT_EQ(r.materials, 4);
    VT_CHECK_INT_EQ(r.shared, 2);
    VT_CHECK_INT_EQ(r.shared_cells, 1);
    VT_CHECK_INT_EQ(r.constant, 1);
    VT_CHECK_INT_EQ(r.replicated, 1);
    VT_CHECK_INT_EQ(r.scaled, 0);
    VT_CHECK_INT_EQ(l.width, r.pack.width);
    VT_CHECK_INT_EQ(l.height, r.pack.height);
    VT_CHECK_INT_EQ(l.tile_content, 256);
    VT_CHECK_INT_EQ(l.border, 4);
    VT_CHECK_STR_EQ(l.generator, "test 1.0");
    if (l.layer_count == 2 && l.entry_count == 3) {
        VT_CHECK_STR_EQ(l.layers[0].name, "diffuse");
        VT_CHECK_STR_EQ(l.layers[1].map, "norm");
        const struct vt_layout_entry *e0 = &l.entries[0], *e1 = &l.entries[1], *e2 = &l.entries[2];
        VT_CHECK_STR_EQ(e0->name, "red");
        VT_CHECK_INT_EQ(e0->alias_count, 1);
        VT_CHECK_STR_EQ(e0->alias_count ? e0->aliases[0] : NULL, "alias");
        VT_CHECK_INT_EQ(e0->width, 128);
        VT_CHECK_INT_EQ(e0->height, 64);
        VT_CHECK_STR_EQ(e0->textures[0].path, "../tex/a.png"); /* relative to out/ */
        VT_CHECK(e0->textures[1].path == NULL && e0->textures[1].fill[2] == 1);
        VT_CHECK_STR_EQ(e1->name, "blue");
        VT_CHECK_INT_EQ(e1->width, 256); /* its largest texture */
        VT_CHECK_INT_EQ(e1->repeat_u, 2);
        VT_CHECK_INT_EQ(e1->repeat_v, 3);
        VT_CHECK_INT_EQ(e1->origin_u, 0);
        VT_CHECK_INT_EQ(e1->origin_v, 0);
        VT_CHECK(!e1->wrap);
        VT_CHECK_INT_EQ(e1->crop_width, 512); /* the whole block: u 0..2 */
        VT_CHECK_INT_EQ(e1->crop_height, 768);
        VT_CHECK_STR_EQ(e1->textures[1].path, "../tex/n.png");
        VT_CHECK_INT_EQ(e1->textures[1].width, 256);
        VT_CHECK_STR_EQ(e2->name, "plain");
        VT_CHECK_INT_EQ(e2->width, 4);
        VT_CHECK(e2->textures[0].path == NULL && e2->textures[0].fill[0] == 0.2);
        check_valid(&l);
    }
    vt_layout_release(&l);
}

/* A texture used in its left half (u 0..0.5) and a chart repeating 1.5 times (u 0.25..1.75):
 * each entry holds only the texels its charts use, plus VT_ATLAS_CROP_MARGIN, aligned to
 * VT_ATLAS_CROP_ALIGN; the summary compares with whole textures. */
static void place_crops_to_the_texels_used(void)
{
    struct vt_atlas_texture textures[] = {{tex_a, id_a, 1024, 1024, 3, false, false, {0}},
                                          {tex_n, id_n, 256, 256, 3, false, false, {0}}};
    char half[] = "half", rep[] = "rep";
    struct vt_atlas_material materials[] = {material(half, 0, -1, 0, 0.5, 0, 1),
                                            material(rep, 1, -1, 0.25, 1.75, 0.5, 0.75)};
    struct vt_atlas_scene scene = {
        .materials = materials, .material_count = 2, .textures = textures, .texture_count = 2};
    struct vt_atlas_place_options o = place_options();
    struct vt_layout l;
    struct vt_atlas_place_report r;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(vt_atlas_place(&scene, &o, &l, &r, &err), 0);
    VT_CHECK_STR_EQ(err.message, "");
    VT_CHECK_INT_EQ(r.cropped, 2);
    VT_CHECK_INT_EQ(r.replicated, 1);
    VT_CHECK_INT_EQ(r.fit, 1);
    VT_CHECK(r.whole_area > (uint64_t)l.width * l.height); /* 18 tiles of 256^2 against 14 */
    printf("cropped atlas %ux%u, whole textures %llu texels\n", l.width, l.height,
           (unsigned long long)r.whole_area);
    if (l.entry_count == 2) {
        const struct vt_layout_entry *h = &l.entries[0], *p = &l.entries[1];
        VT_CHECK_INT_EQ(h->crop_x, 0);
        VT_CHECK_INT_EQ(h->crop_width, 520); /* 512 + 4, aligned to 8 */
        VT_CHECK_INT_EQ(h->crop_y, 0);
        VT_CHECK_INT_EQ(h->crop_height, 1024);
        VT_CHECK_INT_EQ(p->repeat_u, 2);
        VT_CHECK_INT_EQ(p->crop_x, 56);      /* texel 64, minus 4, aligned down to 8 */
        VT_CHECK_INT_EQ(p->crop_width, 400); /* to texel 448 + 4, aligned up to 456 */
        VT_CHECK_INT_EQ(p->crop_y, 56);      /* rows from the top: v 0.75 is row 64 */
        VT_CHECK_INT_EQ(p->crop_height, 80); /* to row 128 + 4, aligned up to 136 */
        double au, av;
        vt_layout_map_uv(&l, p, 0.25, 0.75, &au, &av); /* the used region's top-left corner */
        VT_CHECK(fabs(au * l.width - (p->x + 8)) < 1e-9);
        VT_CHECK(fabs((1 - av) * l.height - (p->y + 8)) < 1e-9);
        check_valid(&l);
    }
    vt_layout_release(&l);
}

/* Densities 65536, 4096, 4096 texels per unit^2: the median 4096; the dense one is scaled 1/4. */
static void place_evens_out_texel_density(void)
{
    struct vt_atlas_texture textures[] = {{tex_a, id_a, 256, 256, 3, false, false, {0}},
                                          {tex_n, id_n, 256, 256, 3, false, false, {0}},
                                          {tex_c, id_c, 64, 64, 3, false, false, {0}}};
    char a[] = "a", b[] = "b", c[] = "c";
    struct vt_atlas_material materials[] = {material(a, 0, -1, 0, 1, 0, 1),
                                            material(b, 1, -1, 0, 1, 0, 1),
                                            material(c, 2, -1, 0, 1, 0, 1)};
    materials[1].world_area = 16;
    struct vt_atlas_scene scene = {
        .materials = materials, .material_count = 3, .textures = textures, .texture_count = 3};
    struct vt_atlas_place_options o = place_options();
    o.density = true;
    struct vt_layout l;
    struct vt_atlas_place_report r;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(vt_atlas_place(&scene, &o, &l, &r, &err), 0);
    VT_CHECK(r.target_density == 4096);
    VT_CHECK_INT_EQ(r.scaled, 1);
    VT_CHECK_INT_EQ(l.entry_count, 3);
    if (l.entry_count == 3) {
        VT_CHECK(l.entries[0].scale == 0.25);
        VT_CHECK_INT_EQ(l.entries[0].width, 64);
        VT_CHECK(l.entries[1].scale == 1 && l.entries[2].scale == 1);
        VT_CHECK_INT_EQ(l.entries[1].width, 256);
        VT_CHECK_INT_EQ(l.entries[2].width, 64);
        check_valid(&l);
    }
    vt_layout_release(&l);

    o.max_scale = 2; /* 1/4 clamped to 1/2 */
    VT_CHECK_INT_EQ(vt_atlas_place(&scene, &o, &l, &r, &err), 0);
    VT_CHECK(l.entry_count == 3 && l.entries[0].scale == 0.5 && l.entries[0].width == 128);
    vt_layout_release(&l);
}

/* A 2x2 grid of 100x50 pieces laid edge to edge in one group; pieces must have one size. */
static void place_lays_grid_pieces_edge_to_edge(void)
{
    struct vt_atlas_texture textures[] = {{tex_a, id_a, 100, 50, 3, false, false, {0}},
                                          {tex_n, id_n, 100, 50, 3, false, false, {0}},
                                          {tex_c, id_c, 100, 50, 3, false, false, {0}},
                                          {tex_a, id_c, 100, 50, 3, false, false, {0}}};
    char n0[] = "p0", n1[] = "p1", n2[] = "p2", n3[] = "p3";
    struct vt_atlas_material materials[] = {
        material(n0, 0, -1, 0, 1, 0, 1), material(n1, 1, -1, 0, 1, 0, 1),
        material(n2, 2, -1, 0, 1, 0, 1), material(n3, 3, -1, 0, 1, 0, 1)};
    struct vt_atlas_scene scene = {
        .materials = materials, .material_count = 4, .textures = textures, .texture_count = 4};
    struct vt_atlas_place_options o = place_options();
    o.grid_rows = o.grid_cols = 2;
    struct vt_layout l;
    struct vt_atlas_place_report r;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(vt_atlas_place(&scene, &o, &l, &r, &err), 0);
    VT_CHECK_INT_EQ(l.entry_count, 4);
    if (l.entry_count == 4) {
        const struct vt_layout_entry *e = l.entries;
        VT_CHECK_INT_EQ(e[1].x - e[0].x, 100);
        VT_CHECK_INT_EQ(e[1].y, e[0].y);
        VT_CHECK_INT_EQ(e[2].y - e[0].y, 50);
        VT_CHECK_INT_EQ(e[3].x, e[1].x);
        VT_CHECK(e[0].group == 1 && e[3].group == 1);
        VT_CHECK_INT_EQ(e[0].alias_count, 0);
        check_valid(&l);
    }
    vt_layout_release(&l);

    textures[2].height = 60;
    VT_CHECK_INT_EQ(vt_atlas_place(&scene, &o, &l, &r, &err), VTS_ERR_BAD_INPUT);
    VT_CHECK_STR_EQ(
        err.message,
        "'tex/c.png' is 100x60, not 100x50 like 'tex/a.png': --grid pieces must have one "
        "size");
    vt_layout_release(&l);

    o.grid_cols = 3;
    VT_CHECK_INT_EQ(vt_atlas_place(&scene, &o, &l, &r, &err), VTS_ERR_ARG);
    VT_CHECK_STR_EQ(err.message, "--grid 2x3 needs 6 files, not 4");
    vt_layout_release(&l);

    scene.material_count = 0;
    VT_CHECK_INT_EQ(vt_atlas_place(&scene, &o, &l, &r, &err), VTS_ERR_BAD_INPUT);
    VT_CHECK_STR_EQ(err.message,
                    "nothing to place: no face uses a material and no texture is listed");
    vt_layout_release(&l);
}

static void check_relative(const char *output, const char *path, const char *want)
{
    char *got = vt_atlas_place_relative_path(output, path);
    VT_CHECK_STR_EQ(got, want);
    free(got);
}

static void place_makes_paths_relative_to_the_output(void)
{
    check_relative("atlas.json", "tex/a.png", "tex/a.png");
    check_relative("out/atlas.json", "tex/a.png", "../tex/a.png");
    check_relative("a/b/atlas.json", "a/c/../t.png", "../t.png");
    check_relative("./a/./atlas.json", "a/x/y.png", "x/y.png");
    check_relative("out/atlas.json", "/abs/t.png", "/abs/t.png");
}

int main(void)
{
    VT_RUN(place_shares_entries_and_copies_wrapped_uvs);
    VT_RUN(place_crops_to_the_texels_used);
    VT_RUN(place_evens_out_texel_density);
    VT_RUN(place_lays_grid_pieces_edge_to_edge);
    VT_RUN(place_makes_paths_relative_to_the_output);
    return vt_test_main_result();
}
