/* vt-tiles --layout end to end (store side), cells: coarse texels that span several cells
 * (mixed), groups whose borders cross between pieces, and gutters that repeat a texture's own
 * edge on all four sides. Usage: test_atlas_build_cells VT_TILES WORKDIR */
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

/* Coarse levels above the entries' alignment mix the cells they cover: a mixed texel is the
 * average (linear light) of its covered children one level down; empty children do not count. */
static void test_mixed_coarse_texels(void)
{
    struct abuild_tex small[6];
    static const uint32_t xy[6][2] = {{0, 0}, {8, 0}, {0, 8}, {8, 8}, {32, 0}, {40, 0}};
    struct vt_layout l;
    struct vts_error err;
    VT_CHECK_INT_EQ(vt_layout_alloc(&l, 1, 6, &err), 0);
    l.width = 256, l.height = 256, l.tile_content = 16, l.border = 2;
    l.layers[0] = (struct vt_layout_layer){abuild_strdup("diffuse"), abuild_strdup("map_Kd"),
                                           VTS_COLOUR_SRGB};
    for (uint32_t i = 0; i < 6; i++) {
        char name[16];
        snprintf(name, sizeof name, "tiny%u", i);
        abuild_texture(&small[i], name, 6, 6, 3, 10 + i);
        struct vt_layout_entry *e = &l.entries[i];
        e->name = abuild_strdup(name);
        e->x = xy[i][0], e->y = xy[i][1], e->width = e->height = 6;
        e->cell_width = e->cell_height = e->alignment = 8;
        e->textures[0].path = abuild_strdup(small[i].path);
        e->textures[0].width = e->textures[0].height = 6;
    }
    char path[600], out[600], args[2048];
    snprintf(path, sizeof path, "%s/tiny.json", abuild_dir);
    snprintf(out, sizeof out, "%s/tiny.vts", abuild_dir);
    VT_CHECK_INT_EQ(vt_layout_write(path, &l, &err), 0);
    vt_layout_release(&l);
    snprintf(args, sizeof args, "--layout %s -o %s --codec png -j2 -q", path, out);
    VT_CHECK_INT_EQ(abuild_run(args), 0);
    struct abuild_reader r;
    if (!abuild_reader_open(&r, out, 0))
        return;
    VT_CHECK_INT_EQ(r.g.level_count, 5);
    struct vt_pixel_mode m = {3, VTS_COLOUR_SRGB, false};
    /* level 4 texel (0, 0): four owned children at level 3; texel (2, 0): two of four */
    uint32_t xs[2] = {0, 2}, counts[2] = {4, 2};
    for (int c = 0; c < 2; c++) {
        float sum[3] = {0, 0, 0};
        uint32_t n = 0;
        for (uint32_t d = 0; d < 4; d++) {
            const uint8_t *p = abuild_reader_texel(&r, 3, 2 * xs[c] + (d & 1), d >> 1);
            uint32_t X = (2 * xs[c] + (d & 1)) * 8, Y = (d >> 1) * 8;
            bool owned = false;
            for (int i = 0; i < 6; i++)
                owned |= xy[i][0] == X && xy[i][1] == Y;
            if (!owned || !p)
                continue;
            float v[3];
            vt_filter_to_working(&m, VTS_SAMPLE_U8, p, v, 1);
            for (int k = 0; k < 3; k++)
                sum[k] += v[k];
            n++;
        }
        VT_CHECK_INT_EQ(n, counts[c]);
        for (int k = 0; k < 3; k++)
            sum[k] /= (float)n;
        uint8_t want[3];
        vt_filter_from_working(&m, VTS_SAMPLE_U8, sum, want, 1);
        const uint8_t *got = abuild_reader_texel(&r, 4, xs[c], 0);
        VT_CHECK(got != NULL);
        for (int k = 0; got && k < 3; k++)
            VT_CHECK(abs((int)got[k] - (int)want[k]) <= 1);
    }
    /* the 1x1 level-3 texel of a 6x6 texture is its own mip level 3 */
    struct vt_image e;
    abuild_reduce(&small[0].img, 3, &e);
    const uint8_t *t = abuild_reader_texel(&r, 3, 0, 0);
    VT_CHECK(t && memcmp(t, e.pixels, 3) == 0);
    vt_image_release(&e);
    abuild_reader_close(&r);
    for (int i = 0; i < 6; i++)
        vt_image_release(&small[i].img);
}

/* Entries of one group (terrain pieces edge to edge) are one surface: borders cross between them;
 * without a group they clamp to each piece. */
static void build_pieces(uint32_t group, const char *name, struct abuild_tex *pieces)
{
    struct vt_layout l;
    struct vts_error err;
    VT_CHECK_INT_EQ(vt_layout_alloc(&l, 1, 2, &err), 0);
    l.width = 128, l.height = 64, l.tile_content = 32, l.border = 4;
    l.layers[0] = (struct vt_layout_layer){abuild_strdup("diffuse"), abuild_strdup("map_Kd"),
                                           VTS_COLOUR_SRGB};
    for (uint32_t i = 0; i < 2; i++) {
        struct vt_layout_entry *e = &l.entries[i];
        e->name = abuild_strdup(pieces[i].name);
        e->x = 64 * i, e->width = e->height = e->cell_width = e->cell_height = e->alignment = 64;
        e->group = group;
        e->textures[0].path = abuild_strdup(pieces[i].path);
        e->textures[0].width = e->textures[0].height = 64;
    }
    char path[600], args[2048];
    snprintf(path, sizeof path, "%s/%s.json", abuild_dir, name);
    VT_CHECK_INT_EQ(vt_layout_write(path, &l, &err), 0);
    vt_layout_release(&l);
    snprintf(args, sizeof args, "--layout %s -o %s/%s.vts --codec png -q", path, abuild_dir, name);
    VT_CHECK_INT_EQ(abuild_run(args), 0);
}

static void test_group_borders_cross_pieces(void)
{
    struct abuild_tex pieces[2];
    abuild_texture(&pieces[0], "pieceA", 64, 64, 3, 21);
    abuild_texture(&pieces[1], "pieceB", 64, 64, 3, 22);
    build_pieces(1, "grouped", pieces);
    build_pieces(0, "separate", pieces);
    struct vt_image a1, b1;
    abuild_reduce(&pieces[0].img, 1, &a1);
    abuild_reduce(&pieces[1].img, 1, &b1);
    for (int grouped = 1; grouped >= 0; grouped--) {
        char out[600];
        snprintf(out, sizeof out, "%s/%s.vts", abuild_dir, grouped ? "grouped" : "separate");
        struct abuild_reader r;
        if (!abuild_reader_open(&r, out, 0))
            continue;
        uint32_t bad = 0;
        /* level 0, tile (2, 0) starts at piece B: its left border */
        const struct vt_image *t = abuild_reader_tile(&r, 0, 2, 0);
        VT_CHECK(t != NULL);
        for (uint32_t j = 4; t && j < 36; j++)
            for (uint32_t i = 0; i < 4; i++) {
                const uint8_t *want = grouped ? vt_image_at(&pieces[0].img, 60 + i, j - 4)
                                              : vt_image_at(&pieces[1].img, 0, j - 4);
                bad += memcmp(vt_image_at(t, i, j), want, 3) != 0;
            }
        /* level 1, tile (1, 0) starts at piece B's level 1 */
        t = abuild_reader_tile(&r, 1, 1, 0);
        VT_CHECK(t != NULL);
        for (uint32_t j = 4; t && j < 36; j++)
            for (uint32_t i = 0; i < 4; i++) {
                const uint8_t *want =
                    grouped ? vt_image_at(&a1, 28 + i, j - 4) : vt_image_at(&b1, 0, j - 4);
                bad += memcmp(vt_image_at(t, i, j), want, 3) != 0;
            }
        if (bad)
            fprintf(stderr, "%s: %u border texels differ\n", grouped ? "grouped" : "separate", bad);
        VT_CHECK_INT_EQ(bad, 0);
        abuild_reader_close(&r);
    }
    vt_image_release(&a1);
    vt_image_release(&b1);
    vt_image_release(&pieces[0].img);
    vt_image_release(&pieces[1].img);
}

/* --gutter: four 24x24 textures, each 4 texels inside its 32x32 cell, the cells touching in one
 * 64x64 tile (as vt-atlas --gutter 4 lays them out; the atlas's second tile is empty). Every texel
 * of a cell at levels 0 and 1 is the texture's own texel (its mip level 1 at level 1) clamped to
 * the texture's rectangle: the gutter repeats the texture's edge on all four sides and holds
 * nothing of a neighbour. */
static void test_gutter_repeats_edges(void)
{
    enum { N = 4, G = 4, S = 24, C = 32 };
    struct abuild_tex t[N];
    struct vt_image m1[N];
    static const char *names[N] = {"gutA", "gutB", "gutC", "gutD"};
    struct vt_layout l;
    struct vts_error err;
    VT_CHECK_INT_EQ(vt_layout_alloc(&l, 1, N, &err), 0);
    l.width = 128, l.height = 64, l.tile_content = 64, l.border = 4; /* 2 levels */
    l.layers[0] = (struct vt_layout_layer){abuild_strdup("diffuse"), abuild_strdup("map_Kd"),
                                           VTS_COLOUR_SRGB};
    for (uint32_t i = 0; i < N; i++) {
        abuild_texture(&t[i], names[i], S, S, 3, 30 + i);
        abuild_reduce(&t[i].img, 1, &m1[i]);
        struct vt_layout_entry *e = &l.entries[i];
        e->name = abuild_strdup(names[i]);
        e->x = (i % 2) * C + G, e->y = (i / 2) * C + G, e->width = e->height = S;
        e->cell_left = e->cell_top = G, e->cell_width = e->cell_height = C, e->alignment = G;
        e->textures[0].path = abuild_strdup(t[i].path);
        e->textures[0].width = e->textures[0].height = S;
    }
    char path[600], store[600], args[2048];
    snprintf(path, sizeof path, "%s/gutter.json", abuild_dir);
    snprintf(store, sizeof store, "%s/gutter.vts", abuild_dir);
    VT_CHECK_INT_EQ(vt_layout_write(path, &l, &err), 0);
    vt_layout_release(&l);
    snprintf(args, sizeof args, "--layout %s -o %s --codec png -q", path, store);
    VT_CHECK_INT_EQ(abuild_run(args), 0);
    struct abuild_reader r;
    if (abuild_reader_open(&r, store, 0)) {
        for (uint32_t L = 0; L <= 1; L++) {
            uint32_t bad = 0, gutter = 0;
            for (uint32_t i = 0; i < N; i++) {
                const struct vt_image *src = L ? &m1[i] : &t[i].img;
                uint32_t cx = (i % 2) * C >> L, cy = (i / 2) * C >> L, g = G >> L;
                for (uint32_t y = 0; y < (uint32_t)C >> L; y++)
                    for (uint32_t x = 0; x < (uint32_t)C >> L; x++) {
                        int64_t u = (int64_t)x - g, v = (int64_t)y - g;
                        bool edge = u < 0 || v < 0 || u >= src->width || v >= src->height;
                        u = u < 0 ? 0 : u >= src->width ? src->width - 1 : u;
                        v = v < 0 ? 0 : v >= src->height ? src->height - 1 : v;
                        const uint8_t *got = abuild_reader_texel(&r, L, cx + x, cy + y);
                        bad +=
                            !got || memcmp(got, vt_image_at(src, (uint32_t)u, (uint32_t)v), 3) != 0;
                        gutter += edge;
                    }
            }
            if (bad)
                fprintf(stderr, "gutter level %u: %u texels differ\n", L, bad);
            VT_CHECK_INT_EQ(bad, 0);
            VT_CHECK_INT_EQ(gutter, L ? N * (16 * 16 - 12 * 12) : N * (32 * 32 - 24 * 24));
        }
        abuild_reader_close(&r);
    }
    for (uint32_t i = 0; i < N; i++) {
        vt_image_release(&t[i].img);
        vt_image_release(&m1[i]);
    }
}

int main(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: test_atlas_build_cells VT_TILES WORKDIR\n");
        return 2;
    }
    abuild_tool = argv[1];
    abuild_dir = argv[2];
    mkdir(abuild_dir, 0777);
    VT_RUN(test_mixed_coarse_texels);
    VT_RUN(test_group_borders_cross_pieces);
    VT_RUN(test_gutter_repeats_edges);
    return vt_test_main_result();
}
