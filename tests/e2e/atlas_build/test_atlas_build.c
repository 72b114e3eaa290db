/* vt-tiles --layout end to end (store side), on one layout of several entries and two layers:
 * exact level-0 texels, borders clamped to each texture, empty tiles, texel-aligned coarse levels,
 * exports, errors, -j1 == -j2. Cells, groups and gutters: test_atlas_build_cells.c.
 * Usage: test_atlas_build VT_TILES WORKDIR */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "atlas_build_fixture.h"
#include "vt_codec.h"
#include "vt_filter.h"
#include "vt_image_input.h"
#include "vt_layout.h"
#include "vt_png_file.h"
#include "vt_test.h"
#include "vts.h"

/* ---- the layout ---- */

enum { T_BIG, T_MID, T_SMALL, T_WRAP, T_BOX, T_ALPHA, T_HALF, T_COUNT };
static struct abuild_tex texs[T_COUNT];
#define CONTENT 128
#define BORDER  4

struct place {
    uint32_t tex, x, y, ru, rv, cw, chh, align;
};
static const struct place places[] = {
    {T_BIG, 0, 0, 1, 1, 1024, 768, 256},     {T_MID, 1024, 0, 1, 1, 512, 256, 256},
    {T_SMALL, 1024, 256, 1, 1, 128, 64, 64}, {T_WRAP, 1152, 256, 3, 2, 128, 64, 64},
    {T_BOX, 1280, 256, 1, 1, 64, 64, 64},
};
/* T_HALF (200x120) at scale 0.5: a 100x60 entry showing its mip level 1 */
#define HALF_X  1408
#define HALF_Y  256
#define NPLACES (sizeof places / sizeof places[0])

/* Writes atlas.json with layers diffuse (all textures, opaque) and mask (the alpha texture on
 * T_MID, constant fills elsewhere); missing != NULL replaces T_SMALL's path. */
static void write_layout(const char *name, const char *missing)
{
    struct vt_layout l;
    struct vts_error err;
    VT_CHECK_INT_EQ(vt_layout_alloc(&l, 2, NPLACES + 1, &err), 0);
    l.width = 2048, l.height = 1024, l.tile_content = CONTENT, l.border = BORDER;
    l.layers[0] = (struct vt_layout_layer){abuild_strdup("diffuse"), abuild_strdup("map_Kd"),
                                           VTS_COLOUR_SRGB};
    l.layers[1] =
        (struct vt_layout_layer){abuild_strdup("mask"), abuild_strdup("map_d"), VTS_COLOUR_SRGB};
    for (uint32_t i = 0; i < NPLACES; i++) {
        const struct place *p = &places[i];
        struct vt_layout_entry *e = &l.entries[i];
        const struct abuild_tex *t = &texs[p->tex];
        e->name = abuild_strdup(t->name);
        e->x = p->x, e->y = p->y, e->width = t->img.width, e->height = t->img.height;
        e->repeat_u = p->ru, e->repeat_v = p->rv;
        e->cell_width = p->cw, e->cell_height = p->chh, e->alignment = p->align;
        const char *path = missing && p->tex == T_SMALL ? missing : t->path;
        e->textures[0].path = abuild_strdup(path);
        e->textures[0].width = t->img.width, e->textures[0].height = t->img.height;
        if (p->tex == T_MID) {
            e->textures[1].path = abuild_strdup(texs[T_ALPHA].path);
            e->textures[1].width = t->img.width, e->textures[1].height = t->img.height;
        } else {
            e->textures[1].fill[0] = 0.25, e->textures[1].fill[1] = 0.5;
            e->textures[1].fill[2] = 0.75, e->textures[1].fill[3] = 1;
        }
    }
    struct vt_layout_entry *h = &l.entries[NPLACES];
    h->name = abuild_strdup("half");
    h->x = HALF_X, h->y = HALF_Y, h->width = 100, h->height = 60, h->scale = 0.5;
    h->cell_width = 128, h->cell_height = 64, h->alignment = 64;
    h->textures[0].path = abuild_strdup(texs[T_HALF].path);
    h->textures[0].width = 200, h->textures[0].height = 120;
    h->textures[1].fill[3] = 1;
    char path[600];
    snprintf(path, sizeof path, "%s/%s", abuild_dir, name);
    VT_CHECK_INT_EQ(vt_layout_write(path, &l, &err), 0);
    vt_layout_release(&l);
}

/* ---- tests ---- */

static char store_j1[600], store_j2[600], layout_path[600];

static void test_build_runs(void)
{
    char args[2048];
    snprintf(args, sizeof args, "--layout %s -o %s --codec png -j1 -q", layout_path, store_j1);
    VT_CHECK_INT_EQ(abuild_run(args), 0);
    snprintf(args, sizeof args, "--layout %s -o %s --codec png -j2 -q", layout_path, store_j2);
    VT_CHECK_INT_EQ(abuild_run(args), 0);
    if (abuild_stderr[0])
        fprintf(stderr, "%s", abuild_stderr);
}

static bool files_equal(const char *a, const char *b)
{
    FILE *fa = fopen(a, "rb"), *fb = fopen(b, "rb");
    bool eq = fa && fb;
    while (eq) {
        int ca = fgetc(fa), cb = fgetc(fb);
        eq = ca == cb;
        if (ca == EOF || cb == EOF)
            break;
    }
    if (fa)
        fclose(fa);
    if (fb)
        fclose(fb);
    return eq;
}

static void test_threads_give_identical_bytes(void)
{
    VT_CHECK(files_equal(store_j1, store_j2));
}

static void test_layer_formats(void)
{
    struct vts_error err;
    struct vts_store *s = vts_open(store_j1, &err);
    VT_CHECK(s != NULL);
    if (!s)
        return;
    const struct vts_geometry *g = vts_store_geometry(s);
    VT_CHECK_INT_EQ(g->layer_count, 2);
    VT_CHECK_INT_EQ(g->tile_content_px, CONTENT);
    VT_CHECK_INT_EQ(g->border_px, BORDER);
    VT_CHECK_INT_EQ(g->width, 2048);
    VT_CHECK_INT_EQ(g->level_count, 5);                  /* 2048 / 128 = 16 -> levels 0..4 */
    VT_CHECK_INT_EQ(vts_store_layer(s, 0)->channels, 3); /* opaque: no alpha */
    VT_CHECK_INT_EQ(vts_store_layer(s, 1)->channels, 4);
    VT_CHECK(strcmp(vts_store_layer(s, 0)->name, "diffuse") == 0);
    VT_CHECK(strcmp(vts_store_layer(s, 1)->name, "mask") == 0);
    const char *layers = vts_store_meta_find(s, "layers");
    VT_CHECK(layers && strcmp(layers, "diffuse,mask") == 0);
    vts_close(s);
}

static void test_level0_texels_exact(void)
{
    struct abuild_reader r;
    if (!abuild_reader_open(&r, store_j1, 0))
        return;
    uint64_t bad = 0, checked = 0;
    for (uint32_t i = 0; i < NPLACES; i++) {
        const struct place *p = &places[i];
        const struct vt_image *t = &texs[p->tex].img;
        for (uint32_t Y = 0; Y < t->height * p->rv; Y++)
            for (uint32_t X = 0; X < t->width * p->ru; X++) {
                const uint8_t *s = abuild_reader_texel(&r, 0, p->x + X, p->y + Y);
                const uint8_t *o = vt_image_at(t, X % t->width, Y % t->height);
                checked++;
                if (!s || memcmp(s, o, 3) != 0) {
                    if (bad++ < 5)
                        fprintf(stderr, "%s texel %u,%u differs\n", texs[p->tex].name, X, Y);
                }
            }
    }
    VT_CHECK_INT_EQ(bad, 0);
    VT_CHECK(checked > 700000);
    abuild_reader_close(&r);
    /* the alpha layer: RGBA texels of the alpha texture exactly, fills elsewhere */
    if (!abuild_reader_open(&r, store_j1, 1))
        return;
    bad = 0;
    const struct vt_image *a = &texs[T_ALPHA].img;
    for (uint32_t Y = 0; Y < a->height; Y++)
        for (uint32_t X = 0; X < a->width; X++) {
            const uint8_t *s = abuild_reader_texel(&r, 0, 1024 + X, Y);
            bad += !s || memcmp(s, vt_image_at(a, X, Y), 4) != 0;
        }
    VT_CHECK_INT_EQ(bad, 0);
    const uint8_t *f = abuild_reader_texel(&r, 0, 1024 + 5, 256 + 5);
    VT_CHECK(f && f[0] == 64 && f[1] == 128 && f[2] == 191 && f[3] == 255);
    abuild_reader_close(&r);
}

/* Borders on a texture's edge repeat that texture's edge texels, not the neighbour's. */
static void test_borders_clamp_to_texture(void)
{
    struct abuild_reader r;
    if (!abuild_reader_open(&r, store_j1, 0))
        return;
    const struct vt_image *big = &texs[T_BIG].img, *mid = &texs[T_MID].img;
    const struct vt_image *small = &texs[T_SMALL].img;
    uint32_t bad = 0;
    /* tile (8, 0) starts at x = 1024 (T_MID); its left border lies in T_BIG's cell padding */
    const struct vt_image *t = abuild_reader_tile(&r, 0, 8, 0);
    VT_CHECK(t != NULL);
    for (uint32_t j = BORDER; t && j < BORDER + CONTENT; j++)
        for (uint32_t i = 0; i < BORDER; i++)
            bad += memcmp(vt_image_at(t, i, j), vt_image_at(mid, 0, j - BORDER), 3) != 0;
    /* tile (7, 0) ends at x = 1024: its right border repeats T_BIG's right column (x = 999) */
    t = abuild_reader_tile(&r, 0, 7, 0);
    VT_CHECK(t != NULL);
    for (uint32_t j = BORDER; t && j < BORDER + CONTENT; j++)
        for (uint32_t i = BORDER + CONTENT; i < CONTENT + 2 * BORDER; i++)
            bad += memcmp(vt_image_at(t, i, j), vt_image_at(big, 999, j - BORDER), 3) != 0;
    /* tile (8, 2) holds T_SMALL's cell: top border = its first row, right border = its last
     * column (through the cell padding), not T_MID's or T_WRAP's texels */
    t = abuild_reader_tile(&r, 0, 8, 2);
    VT_CHECK(t != NULL);
    for (uint32_t i = BORDER; t && i < BORDER + 100; i++)
        for (uint32_t j = 0; j < BORDER; j++)
            bad += memcmp(vt_image_at(t, i, j), vt_image_at(small, i - BORDER, 0), 3) != 0;
    for (uint32_t j = BORDER; t && j < BORDER + 60; j++)
        for (uint32_t i = BORDER + CONTENT; i < CONTENT + 2 * BORDER; i++)
            bad += memcmp(vt_image_at(t, i, j), vt_image_at(small, 99, j - BORDER), 3) != 0;
    /* inside a texture, borders equal the neighbour tile's texels */
    const uint8_t *n = abuild_reader_texel(&r, 0, 2 * CONTENT, CONTENT + 7);
    uint8_t neighbour[3] = {0, 0, 0};
    VT_CHECK(n != NULL);
    if (n)
        memcpy(neighbour, n, 3); /* the reader holds one tile at a time */
    t = abuild_reader_tile(&r, 0, 1, 1);
    VT_CHECK(t && memcmp(vt_image_at(t, BORDER + CONTENT, BORDER + 7), neighbour, 3) == 0);
    VT_CHECK(t && memcmp(vt_image_at(t, BORDER + CONTENT, BORDER + 7),
                         vt_image_at(big, 2 * CONTENT, CONTENT + 7), 3) == 0);
    VT_CHECK_INT_EQ(bad, 0);
    abuild_reader_close(&r);
}

static void test_empty_tiles_are_empty(void)
{
    struct vts_error err;
    struct vts_store *s = vts_open(store_j1, &err);
    if (!s)
        return;
    struct vts_tile_entry e;
    uint32_t empty[][3] = {{0, 15, 7}, {0, 12, 0}, {0, 0, 7}, {1, 7, 3}};
    for (size_t i = 0; i < sizeof empty / sizeof empty[0]; i++)
        for (uint32_t layer = 0; layer < 2; layer++) {
            VT_CHECK_INT_EQ(
                vts_store_tile(s, layer, empty[i][0], empty[i][1], empty[i][2], &e, &err), 0);
            VT_CHECK_INT_EQ(e.length, 0);
        }
    VT_CHECK_INT_EQ(vts_store_tile(s, 0, 0, 8, 2, &e, &err), 0);
    VT_CHECK(e.length > 0);
    vts_close(s);
}

/* Coarse levels stay texel-aligned: a texture's texels at level L are its own mip level L. */
static void test_coarse_levels_aligned(void)
{
    struct abuild_reader r;
    if (!abuild_reader_open(&r, store_j1, 0))
        return;
    struct {
        uint32_t tex, x, y, level;
    } cases[] = {{T_BOX, 1280, 256, 3},
                 {T_BOX, 1280, 256, 4},
                 {T_BIG, 0, 0, 2},
                 {T_MID, 1024, 0, 4},
                 {T_SMALL, 1024, 256, 2}};
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        struct vt_image e;
        abuild_reduce(&texs[cases[c].tex].img, cases[c].level, &e);
        uint32_t bad = 0, L = cases[c].level;
        for (uint32_t y = 0; y < e.height; y++)
            for (uint32_t x = 0; x < e.width; x++) {
                const uint8_t *s =
                    abuild_reader_texel(&r, L, (cases[c].x >> L) + x, (cases[c].y >> L) + y);
                bad += !s || memcmp(s, vt_image_at(&e, x, y), 3) != 0;
            }
        if (bad)
            fprintf(stderr, "%s level %u: %u texels differ\n", texs[cases[c].tex].name, L, bad);
        VT_CHECK_INT_EQ(bad, 0);
        vt_image_release(&e);
    }
    /* scale 0.5: level 0 of the entry is the texture's own mip level 1 */
    struct vt_image e;
    abuild_reduce(&texs[T_HALF].img, 1, &e);
    uint32_t bad = 0;
    VT_CHECK_INT_EQ(e.width, 100);
    for (uint32_t y = 0; y < e.height; y++)
        for (uint32_t x = 0; x < e.width; x++) {
            const uint8_t *s = abuild_reader_texel(&r, 0, HALF_X + x, HALF_Y + y);
            bad += !s || memcmp(s, vt_image_at(&e, x, y), 3) != 0;
        }
    VT_CHECK_INT_EQ(bad, 0);
    vt_image_release(&e);
    abuild_reader_close(&r);
}

static void test_export_matches_level0(void)
{
    char args[2048], png[600];
    snprintf(png, sizeof png, "%s/atlas.png", abuild_dir);
    snprintf(args, sizeof args,
             "--layout %s -o %s/diffuse.vts --layer diffuse --export-atlas %s -q", layout_path,
             abuild_dir, png);
    VT_CHECK_INT_EQ(abuild_run(args), 0);
    struct vt_image img;
    struct vts_error err;
    if (vt_png_file_read(png, &img, &err)) {
        VT_CHECK(false);
        return;
    }
    VT_CHECK_INT_EQ(img.width, 2048);
    VT_CHECK_INT_EQ(img.channels, 3);
    struct abuild_reader r;
    if (abuild_reader_open(&r, store_j1, 0)) {
        uint64_t bad = 0;
        for (uint32_t y = 0; y < img.height; y += 3)
            for (uint32_t x = 0; x < img.width; x++) {
                const uint8_t *s = abuild_reader_texel(&r, 0, x, y);
                static const uint8_t zero[3];
                bad += memcmp(s ? s : zero, vt_image_at(&img, x, y), 3) != 0;
            }
        VT_CHECK_INT_EQ(bad, 0);
        abuild_reader_close(&r);
    }
    vt_image_release(&img);
}

/* --export-atlas to TIFF: the RGBA mask layer, read back through vt_image_input. */
static void test_export_tiff_rgba(void)
{
    char args[2048], tif[600];
    snprintf(tif, sizeof tif, "%s/mask.tif", abuild_dir);
    snprintf(args, sizeof args, "--layout %s -o %s/mask_only.vts --layer mask --export-atlas %s -q",
             layout_path, abuild_dir, tif);
    VT_CHECK_INT_EQ(abuild_run(args), 0);
    struct vt_source src;
    struct vts_error err;
    if (vt_image_input_open(tif, NULL, &src, &err)) {
        fprintf(stderr, "%s\n", err.message);
        VT_CHECK(false);
        return;
    }
    VT_CHECK_INT_EQ(src.info.channels, 4);
    VT_CHECK_INT_EQ(src.info.width, 2048);
    struct vt_image img;
    vt_image_alloc(&img, 2048, 1024, 4, VTS_SAMPLE_U8, NULL);
    VT_CHECK_INT_EQ(vt_source_read(&src, 0, 0, &img, &err), 0);
    vt_source_close(&src);
    struct abuild_reader r;
    if (abuild_reader_open(&r, store_j1, 1)) {
        uint64_t bad = 0;
        static const uint8_t zero[4];
        for (uint32_t y = 1; y < 1024; y += 7)
            for (uint32_t x = 0; x < 2048; x++) {
                const uint8_t *t = abuild_reader_texel(&r, 0, x, y);
                bad += memcmp(t ? t : zero, vt_image_at(&img, x, y), 4) != 0;
            }
        VT_CHECK_INT_EQ(bad, 0);
        abuild_reader_close(&r);
    }
    vt_image_release(&img);
}

static void test_missing_texture_names_file(void)
{
    char args[2048], out[600], missing[600];
    snprintf(missing, sizeof missing, "%s/no_such_texture.png", abuild_dir);
    write_layout("missing.json", missing);
    snprintf(out, sizeof out, "%s/missing.vts", abuild_dir);
    snprintf(args, sizeof args, "--layout %s/missing.json -o %s -q", abuild_dir, out);
    VT_CHECK_INT_EQ(abuild_run(args), 1);
    VT_CHECK_STR_CONTAINS(abuild_stderr, "no_such_texture.png");
    struct stat st;
    VT_CHECK(stat(out, &st) != 0); /* nothing written */
}

static void test_conflicting_geometry_is_usage_error(void)
{
    char args[2048];
    snprintf(args, sizeof args, "--layout %s -o %s/x.vts --border 2 -q", layout_path, abuild_dir);
    VT_CHECK_INT_EQ(abuild_run(args), 2);
    VT_CHECK_STR_CONTAINS(abuild_stderr, "--border 2 conflicts with the layout's border 4");
    /* --tile-size is the content edge (128 in this layout), as in vt-atlas; --keep payload
     * takes the stored edge (128 + 2 * 4) */
    snprintf(args, sizeof args, "--layout %s -o %s/x.vts --tile-size 128 --border 4 -q",
             layout_path, abuild_dir);
    VT_CHECK_INT_EQ(abuild_run(args), 0);
    snprintf(args, sizeof args, "--layout %s -o %s/x.vts --tile-size 136 --keep payload -q",
             layout_path, abuild_dir);
    VT_CHECK_INT_EQ(abuild_run(args), 0);
    snprintf(args, sizeof args, "--layout %s -o %s/x.vts --tile-size 136 -q", layout_path,
             abuild_dir);
    VT_CHECK_INT_EQ(abuild_run(args), 2);
    VT_CHECK_STR_CONTAINS(abuild_stderr, "--tile-size 136 conflicts with the layout's tiles "
                                         "(content 128, border 4: --tile-size 128; or omit it)");
    snprintf(args, sizeof args, "--layout %s -o %s/x.vts --layer nope -q", layout_path, abuild_dir);
    VT_CHECK_INT_EQ(abuild_run(args), 2);
    VT_CHECK_STR_CONTAINS(abuild_stderr, "--layer 'nope'");
}

static void test_single_layer_store(void)
{
    char args[2048], out[600];
    snprintf(out, sizeof out, "%s/mask.vts", abuild_dir);
    snprintf(args, sizeof args, "--layout %s -o %s --layer mask -q", layout_path, out);
    VT_CHECK_INT_EQ(abuild_run(args), 0);
    struct vts_error err;
    struct vts_store *s = vts_open(out, &err);
    VT_CHECK(s != NULL);
    if (!s)
        return;
    VT_CHECK_INT_EQ(vts_store_geometry(s)->layer_count, 1);
    VT_CHECK(strcmp(vts_store_layer(s, 0)->name, "mask") == 0);
    VT_CHECK_INT_EQ(vts_store_layer(s, 0)->codec, VTS_CODEC_PNG); /* auto: alpha -> png */
    vts_close(s);
}

int main(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: test_atlas_build TOOL WORKDIR\n");
        return 2;
    }
    abuild_tool = argv[1];
    abuild_dir = argv[2];
    mkdir(abuild_dir, 0777);
    abuild_texture(&texs[T_BIG], "big", 1000, 700, 3, 1);
    abuild_texture(&texs[T_MID], "mid", 300, 200, 3, 2);
    abuild_texture(&texs[T_SMALL], "small", 100, 60, 3, 3);
    abuild_texture(&texs[T_WRAP], "wrap", 40, 30, 3, 4);
    abuild_texture(&texs[T_BOX], "box", 64, 64, 3, 5);
    abuild_texture(&texs[T_ALPHA], "alpha", 300, 200, 4, 6);
    abuild_texture(&texs[T_HALF], "half", 200, 120, 3, 7);
    write_layout("atlas.json", NULL);
    snprintf(layout_path, sizeof layout_path, "%s/atlas.json", abuild_dir);
    snprintf(store_j1, sizeof store_j1, "%s/atlas_j1.vts", abuild_dir);
    snprintf(store_j2, sizeof store_j2, "%s/atlas_j2.vts", abuild_dir);
    VT_RUN(test_build_runs);
    VT_RUN(test_threads_give_identical_bytes);
    VT_RUN(test_layer_formats);
    VT_RUN(test_level0_texels_exact);
    VT_RUN(test_borders_clamp_to_texture);
    VT_RUN(test_empty_tiles_are_empty);
    VT_RUN(test_coarse_levels_aligned);
    VT_RUN(test_export_matches_level0);
    VT_RUN(test_export_tiff_rgba);
    VT_RUN(test_missing_texture_names_file);
    VT_RUN(test_conflicting_geometry_is_usage_error);
    VT_RUN(test_single_layer_store);
    for (int i = 0; i < T_COUNT; i++)
        vt_image_release(&texs[i].img);
    return vt_test_main_result();
}
