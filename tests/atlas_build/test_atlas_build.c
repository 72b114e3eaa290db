/* vt-tiles --layout end to end (store side): generated textures and layouts, the build run as a
 * process (the stand-in driver or vt-tiles), the store read back through libvts texel by texel.
 * Usage: test_atlas_build TOOL WORKDIR [--layout-flag] */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "vt_codec.h"
#include "vt_filter.h"
#include "vt_image_input.h"
#include "vt_layout.h"
#include "vt_png_file.h"
#include "vt_test.h"
#include "vts.h"

static const char *tool, *dir;
static char last_stderr[8192];

/* ---- textures ---- */

static uint32_t hash3(uint32_t a, uint32_t b, uint32_t c)
{
    uint32_t h = a * 0x9e3779b1u ^ (b + 0x7f4a7c15u) * 0x85ebca6bu ^ c * 0xc2b2ae35u;
    h ^= h >> 15;
    h *= 0x2c1b3c6du;
    h ^= h >> 12;
    return h;
}

struct tex {
    const char *name;
    struct vt_image img;
    char path[512];
};

/* A texture with smooth gradients plus noise (every texel distinct enough to catch offsets). */
static void make_texture(struct tex *t, const char *name, uint32_t w, uint32_t h, uint32_t ch,
                         uint32_t seed)
{
    t->name = name;
    VT_CHECK_INT_EQ(vt_image_alloc(&t->img, w, h, ch, VTS_SAMPLE_U8, NULL), 0);
    for (uint32_t y = 0; y < h; y++)
        for (uint32_t x = 0; x < w; x++) {
            uint8_t *p = vt_image_at(&t->img, x, y);
            uint32_t r = hash3(x, y, seed);
            p[0] = (uint8_t)(x * 255 / w ^ (r & 15));
            p[1] = (uint8_t)(y * 255 / h ^ ((r >> 4) & 15));
            p[2] = (uint8_t)(seed * 40 + (r >> 8));
            if (ch == 4)
                p[3] = (uint8_t)(x < w / 4 ? 0 : 64 + ((r >> 16) & 127));
        }
    snprintf(t->path, sizeof t->path, "%s/%s.png", dir, name);
    struct vt_error err;
    struct vt_png_file_writer *pw = vt_png_file_writer_create(t->path, w, h, ch, 8, &err);
    VT_CHECK(pw != NULL);
    if (!pw)
        return;
    VT_CHECK_INT_EQ(vt_png_file_writer_rows(pw, t->img.pixels, h, t->img.stride, &err), 0);
    VT_CHECK_INT_EQ(vt_png_file_writer_finish(pw, &err), 0);
    vt_png_file_writer_destroy(pw);
}

/* ---- running the tool ---- */

static int run_tool(const char *args)
{
    char cmd[4096], errfile[600];
    snprintf(errfile, sizeof errfile, "%s/stderr.txt", dir);
    snprintf(cmd, sizeof cmd, "%s %s 2>%s", tool, args, errfile);
    int rc = system(cmd);
    last_stderr[0] = 0;
    FILE *f = fopen(errfile, "r");
    if (f) {
        size_t n = fread(last_stderr, 1, sizeof last_stderr - 1, f);
        last_stderr[n] = 0;
        fclose(f);
    }
    return rc == -1 ? -1 : WEXITSTATUS(rc);
}

/* ---- reading the store ---- */

struct reader {
    struct vts_store *s;
    struct vts_geometry g;
    uint32_t layer, level, tx, ty;
    struct vt_image tile;
    bool valid, empty;
    unsigned char *buf;
};

static bool reader_open(struct reader *r, const char *path, uint32_t layer)
{
    memset(r, 0, sizeof *r);
    struct vt_error err;
    r->s = vts_open(path, &err);
    if (!r->s) {
        fprintf(stderr, "%s\n", err.message);
        return false;
    }
    r->g = *vts_store_geometry(r->s);
    r->layer = layer;
    const struct vts_layer *l = vts_store_layer(r->s, layer);
    vt_image_alloc(&r->tile, r->g.tile_payload_px, r->g.tile_payload_px, l->channels, l->sample,
                   NULL);
    r->buf = malloc(vts_store_max_payload(r->s) + 1);
    return true;
}

static void reader_close(struct reader *r)
{
    vts_close(r->s);
    vt_image_release(&r->tile);
    free(r->buf);
}

/* The payload of a tile (NULL when empty). */
static const struct vt_image *reader_tile(struct reader *r, uint32_t level, uint32_t tx,
                                          uint32_t ty)
{
    if (r->valid && r->level == level && r->tx == tx && r->ty == ty)
        return r->empty ? NULL : &r->tile;
    struct vt_error err;
    size_t len;
    r->valid = false;
    if (vts_store_read(r->s, r->layer, level, tx, ty, r->buf, vts_store_max_payload(r->s) + 1, &len,
                       0, &err))
        return NULL;
    r->level = level, r->tx = tx, r->ty = ty, r->valid = true, r->empty = len == 0;
    if (len == 0)
        return NULL;
    const struct vt_codec *c = vt_codec_by_fourcc(vts_store_layer(r->s, r->layer)->codec);
    if (c->decode(r->buf, len, &r->tile, &err)) {
        r->valid = false;
        return NULL;
    }
    return &r->tile;
}

/* Texel (X, Y) of a level, from the tile that owns it; NULL when that tile is empty. */
static const uint8_t *reader_texel(struct reader *r, uint32_t level, uint32_t X, uint32_t Y)
{
    uint32_t c = r->g.tile_content_px, b = r->g.border_px;
    const struct vt_image *t = reader_tile(r, level, X / c, Y / c);
    return t ? vt_image_at(t, b + X % c, b + Y % c) : NULL;
}

/* ---- the layout ---- */

enum { T_BIG, T_MID, T_SMALL, T_WRAP, T_BOX, T_ALPHA, T_HALF, T_COUNT };
static struct tex texs[T_COUNT];
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

static char *xstrdup(const char *s)
{
    char *d = malloc(strlen(s) + 1);
    strcpy(d, s);
    return d;
}

/* Writes atlas.json with layers diffuse (all textures, opaque) and mask (the alpha texture on
 * T_MID, constant fills elsewhere); missing != NULL replaces T_SMALL's path. */
static void write_layout(const char *name, const char *missing)
{
    struct vt_layout l;
    struct vt_error err;
    VT_CHECK_INT_EQ(vt_layout_alloc(&l, 2, NPLACES + 1, &err), 0);
    l.width = 2048, l.height = 1024, l.tile_content = CONTENT, l.border = BORDER;
    l.layers[0] = (struct vt_layout_layer){xstrdup("diffuse"), xstrdup("map_Kd"), VTS_COLOUR_SRGB};
    l.layers[1] = (struct vt_layout_layer){xstrdup("mask"), xstrdup("map_d"), VTS_COLOUR_SRGB};
    for (uint32_t i = 0; i < NPLACES; i++) {
        const struct place *p = &places[i];
        struct vt_layout_entry *e = &l.entries[i];
        const struct tex *t = &texs[p->tex];
        e->name = xstrdup(t->name);
        e->x = p->x, e->y = p->y, e->width = t->img.width, e->height = t->img.height;
        e->repeat_u = p->ru, e->repeat_v = p->rv;
        e->cell_width = p->cw, e->cell_height = p->chh, e->alignment = p->align;
        const char *path = missing && p->tex == T_SMALL ? missing : t->path;
        e->textures[0].path = xstrdup(path);
        e->textures[0].width = t->img.width, e->textures[0].height = t->img.height;
        if (p->tex == T_MID) {
            e->textures[1].path = xstrdup(texs[T_ALPHA].path);
            e->textures[1].width = t->img.width, e->textures[1].height = t->img.height;
        } else {
            e->textures[1].fill[0] = 0.25, e->textures[1].fill[1] = 0.5;
            e->textures[1].fill[2] = 0.75, e->textures[1].fill[3] = 1;
        }
    }
    struct vt_layout_entry *h = &l.entries[NPLACES];
    h->name = xstrdup("half");
    h->x = HALF_X, h->y = HALF_Y, h->width = 100, h->height = 60, h->scale = 0.5;
    h->cell_width = 128, h->cell_height = 64, h->alignment = 64;
    h->textures[0].path = xstrdup(texs[T_HALF].path);
    h->textures[0].width = 200, h->textures[0].height = 120;
    h->textures[1].fill[3] = 1;
    char path[600];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    VT_CHECK_INT_EQ(vt_layout_write(path, &l, &err), 0);
    vt_layout_release(&l);
}

/* ---- tests ---- */

static char store_j1[600], store_j2[600], layout_path[600];

static void test_build_runs(void)
{
    char args[2048];
    snprintf(args, sizeof args, "--layout %s -o %s --codec png -j1 -q", layout_path, store_j1);
    VT_CHECK_INT_EQ(run_tool(args), 0);
    snprintf(args, sizeof args, "--layout %s -o %s --codec png -j2 -q", layout_path, store_j2);
    VT_CHECK_INT_EQ(run_tool(args), 0);
    if (last_stderr[0])
        fprintf(stderr, "%s", last_stderr);
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
    struct vt_error err;
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
    struct reader r;
    if (!reader_open(&r, store_j1, 0))
        return;
    uint64_t bad = 0, checked = 0;
    for (uint32_t i = 0; i < NPLACES; i++) {
        const struct place *p = &places[i];
        const struct vt_image *t = &texs[p->tex].img;
        for (uint32_t Y = 0; Y < t->height * p->rv; Y++)
            for (uint32_t X = 0; X < t->width * p->ru; X++) {
                const uint8_t *s = reader_texel(&r, 0, p->x + X, p->y + Y);
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
    reader_close(&r);
    /* the alpha layer: RGBA texels of the alpha texture exactly, fills elsewhere */
    if (!reader_open(&r, store_j1, 1))
        return;
    bad = 0;
    const struct vt_image *a = &texs[T_ALPHA].img;
    for (uint32_t Y = 0; Y < a->height; Y++)
        for (uint32_t X = 0; X < a->width; X++) {
            const uint8_t *s = reader_texel(&r, 0, 1024 + X, Y);
            bad += !s || memcmp(s, vt_image_at(a, X, Y), 4) != 0;
        }
    VT_CHECK_INT_EQ(bad, 0);
    const uint8_t *f = reader_texel(&r, 0, 1024 + 5, 256 + 5);
    VT_CHECK(f && f[0] == 64 && f[1] == 128 && f[2] == 191 && f[3] == 255);
    reader_close(&r);
}

/* Borders on a texture's edge repeat that texture's edge texels, not the neighbour's. */
static void test_borders_clamp_to_texture(void)
{
    struct reader r;
    if (!reader_open(&r, store_j1, 0))
        return;
    const struct vt_image *big = &texs[T_BIG].img, *mid = &texs[T_MID].img;
    const struct vt_image *small = &texs[T_SMALL].img;
    uint32_t bad = 0;
    /* tile (8, 0) starts at x = 1024 (T_MID); its left border lies in T_BIG's cell padding */
    const struct vt_image *t = reader_tile(&r, 0, 8, 0);
    VT_CHECK(t != NULL);
    for (uint32_t j = BORDER; t && j < BORDER + CONTENT; j++)
        for (uint32_t i = 0; i < BORDER; i++)
            bad += memcmp(vt_image_at(t, i, j), vt_image_at(mid, 0, j - BORDER), 3) != 0;
    /* tile (7, 0) ends at x = 1024: its right border repeats T_BIG's right column (x = 999) */
    t = reader_tile(&r, 0, 7, 0);
    VT_CHECK(t != NULL);
    for (uint32_t j = BORDER; t && j < BORDER + CONTENT; j++)
        for (uint32_t i = BORDER + CONTENT; i < CONTENT + 2 * BORDER; i++)
            bad += memcmp(vt_image_at(t, i, j), vt_image_at(big, 999, j - BORDER), 3) != 0;
    /* tile (8, 2) holds T_SMALL's cell: top border = its first row, right border = its last
     * column (through the cell padding), not T_MID's or T_WRAP's texels */
    t = reader_tile(&r, 0, 8, 2);
    VT_CHECK(t != NULL);
    for (uint32_t i = BORDER; t && i < BORDER + 100; i++)
        for (uint32_t j = 0; j < BORDER; j++)
            bad += memcmp(vt_image_at(t, i, j), vt_image_at(small, i - BORDER, 0), 3) != 0;
    for (uint32_t j = BORDER; t && j < BORDER + 60; j++)
        for (uint32_t i = BORDER + CONTENT; i < CONTENT + 2 * BORDER; i++)
            bad += memcmp(vt_image_at(t, i, j), vt_image_at(small, 99, j - BORDER), 3) != 0;
    /* inside a texture, borders equal the neighbour tile's texels */
    const uint8_t *n = reader_texel(&r, 0, 2 * CONTENT, CONTENT + 7);
    uint8_t neighbour[3] = {0, 0, 0};
    VT_CHECK(n != NULL);
    if (n)
        memcpy(neighbour, n, 3); /* the reader holds one tile at a time */
    t = reader_tile(&r, 0, 1, 1);
    VT_CHECK(t && memcmp(vt_image_at(t, BORDER + CONTENT, BORDER + 7), neighbour, 3) == 0);
    VT_CHECK(t && memcmp(vt_image_at(t, BORDER + CONTENT, BORDER + 7),
                         vt_image_at(big, 2 * CONTENT, CONTENT + 7), 3) == 0);
    VT_CHECK_INT_EQ(bad, 0);
    reader_close(&r);
}

static void test_empty_tiles_are_empty(void)
{
    struct vt_error err;
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

/* A texture reduced k times with the box filter in linear light, as 8-bit sRGB. */
static void reduce_expected(const struct vt_image *src, uint32_t k, struct vt_image *out)
{
    struct vt_pixel_mode m = {3, VTS_COLOUR_SRGB, false};
    struct vt_kernel kern;
    vt_kernel_init(&kern, VT_FILTER_BOX);
    uint32_t w = src->width, h = src->height;
    float *cur = malloc((size_t)w * h * 3 * sizeof(float));
    for (uint32_t y = 0; y < h; y++)
        vt_filter_to_working(&m, VTS_SAMPLE_U8, vt_image_at(src, 0, y), cur + (size_t)y * w * 3, w);
    for (uint32_t i = 0; i < k; i++) {
        uint32_t dw = (w + 1) / 2, dh = (h + 1) / 2;
        struct vt_fregion s = {0, 0, w, h, 3, cur}, d = {0, 0, dw, dh, 3, NULL};
        d.px = malloc((size_t)dw * dh * 3 * sizeof(float));
        size_t sn = vt_filter_reduce_scratch(&kern, &s, &d);
        float *scratch = malloc((sn + 1) * sizeof(float));
        struct vt_edges edges = {w, h, false, false};
        VT_CHECK_INT_EQ(vt_filter_reduce(&kern, &edges, &s, &d, scratch, sn, NULL), 0);
        free(scratch);
        free(cur);
        cur = d.px, w = dw, h = dh;
    }
    vt_image_alloc(out, w, h, 3, VTS_SAMPLE_U8, NULL);
    for (uint32_t y = 0; y < h; y++)
        vt_filter_from_working(&m, VTS_SAMPLE_U8, cur + (size_t)y * w * 3, vt_image_at(out, 0, y),
                               w);
    free(cur);
}

/* Coarse levels stay texel-aligned: a texture's texels at level L are its own mip level L. */
static void test_coarse_levels_aligned(void)
{
    struct reader r;
    if (!reader_open(&r, store_j1, 0))
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
        reduce_expected(&texs[cases[c].tex].img, cases[c].level, &e);
        uint32_t bad = 0, L = cases[c].level;
        for (uint32_t y = 0; y < e.height; y++)
            for (uint32_t x = 0; x < e.width; x++) {
                const uint8_t *s =
                    reader_texel(&r, L, (cases[c].x >> L) + x, (cases[c].y >> L) + y);
                bad += !s || memcmp(s, vt_image_at(&e, x, y), 3) != 0;
            }
        if (bad)
            fprintf(stderr, "%s level %u: %u texels differ\n", texs[cases[c].tex].name, L, bad);
        VT_CHECK_INT_EQ(bad, 0);
        vt_image_release(&e);
    }
    /* scale 0.5: level 0 of the entry is the texture's own mip level 1 */
    struct vt_image e;
    reduce_expected(&texs[T_HALF].img, 1, &e);
    uint32_t bad = 0;
    VT_CHECK_INT_EQ(e.width, 100);
    for (uint32_t y = 0; y < e.height; y++)
        for (uint32_t x = 0; x < e.width; x++) {
            const uint8_t *s = reader_texel(&r, 0, HALF_X + x, HALF_Y + y);
            bad += !s || memcmp(s, vt_image_at(&e, x, y), 3) != 0;
        }
    VT_CHECK_INT_EQ(bad, 0);
    vt_image_release(&e);
    reader_close(&r);
}

static void test_export_matches_level0(void)
{
    char args[2048], png[600];
    snprintf(png, sizeof png, "%s/atlas.png", dir);
    snprintf(args, sizeof args,
             "--layout %s -o %s/diffuse.vts --layer diffuse --export-atlas %s -q", layout_path, dir,
             png);
    VT_CHECK_INT_EQ(run_tool(args), 0);
    struct vt_image img;
    struct vt_error err;
    if (vt_png_file_read(png, &img, &err)) {
        VT_CHECK(false);
        return;
    }
    VT_CHECK_INT_EQ(img.width, 2048);
    VT_CHECK_INT_EQ(img.channels, 3);
    struct reader r;
    if (reader_open(&r, store_j1, 0)) {
        uint64_t bad = 0;
        for (uint32_t y = 0; y < img.height; y += 3)
            for (uint32_t x = 0; x < img.width; x++) {
                const uint8_t *s = reader_texel(&r, 0, x, y);
                static const uint8_t zero[3];
                bad += memcmp(s ? s : zero, vt_image_at(&img, x, y), 3) != 0;
            }
        VT_CHECK_INT_EQ(bad, 0);
        reader_close(&r);
    }
    vt_image_release(&img);
}

/* --export-atlas to TIFF: the RGBA mask layer, read back through vt_image_input. */
static void test_export_tiff_rgba(void)
{
    char args[2048], tif[600];
    snprintf(tif, sizeof tif, "%s/mask.tif", dir);
    snprintf(args, sizeof args, "--layout %s -o %s/mask_only.vts --layer mask --export-atlas %s -q",
             layout_path, dir, tif);
    VT_CHECK_INT_EQ(run_tool(args), 0);
    struct vt_source src;
    struct vt_error err;
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
    struct reader r;
    if (reader_open(&r, store_j1, 1)) {
        uint64_t bad = 0;
        static const uint8_t zero[4];
        for (uint32_t y = 1; y < 1024; y += 7)
            for (uint32_t x = 0; x < 2048; x++) {
                const uint8_t *t = reader_texel(&r, 0, x, y);
                bad += memcmp(t ? t : zero, vt_image_at(&img, x, y), 4) != 0;
            }
        VT_CHECK_INT_EQ(bad, 0);
        reader_close(&r);
    }
    vt_image_release(&img);
}

static void test_missing_texture_names_file(void)
{
    char args[2048], out[600], missing[600];
    snprintf(missing, sizeof missing, "%s/no_such_texture.png", dir);
    write_layout("missing.json", missing);
    snprintf(out, sizeof out, "%s/missing.vts", dir);
    snprintf(args, sizeof args, "--layout %s/missing.json -o %s -q", dir, out);
    VT_CHECK_INT_EQ(run_tool(args), 1);
    VT_CHECK_STR_CONTAINS(last_stderr, "no_such_texture.png");
    struct stat st;
    VT_CHECK(stat(out, &st) != 0); /* nothing written */
}

static void test_conflicting_geometry_is_usage_error(void)
{
    char args[2048];
    snprintf(args, sizeof args, "--layout %s -o %s/x.vts --border 2 -q", layout_path, dir);
    VT_CHECK_INT_EQ(run_tool(args), 2);
    VT_CHECK_STR_CONTAINS(last_stderr, "--border 2 conflicts with the layout's border 4");
    snprintf(args, sizeof args, "--layout %s -o %s/x.vts --tile-size 136 --border 4 -q",
             layout_path, dir);
    VT_CHECK_INT_EQ(run_tool(args), 0);
    snprintf(args, sizeof args, "--layout %s -o %s/x.vts --layer nope -q", layout_path, dir);
    VT_CHECK_INT_EQ(run_tool(args), 2);
    VT_CHECK_STR_CONTAINS(last_stderr, "--layer 'nope'");
}

static void test_single_layer_store(void)
{
    char args[2048], out[600];
    snprintf(out, sizeof out, "%s/mask.vts", dir);
    snprintf(args, sizeof args, "--layout %s -o %s --layer mask -q", layout_path, out);
    VT_CHECK_INT_EQ(run_tool(args), 0);
    struct vt_error err;
    struct vts_store *s = vts_open(out, &err);
    VT_CHECK(s != NULL);
    if (!s)
        return;
    VT_CHECK_INT_EQ(vts_store_geometry(s)->layer_count, 1);
    VT_CHECK(strcmp(vts_store_layer(s, 0)->name, "mask") == 0);
    VT_CHECK_INT_EQ(vts_store_layer(s, 0)->codec, VTS_CODEC_PNG); /* auto: alpha -> png */
    vts_close(s);
}

/* Coarse levels above the entries' alignment mix the cells they cover: a mixed texel is the
 * average (linear light) of its covered children one level down; empty children do not count. */
static void test_mixed_coarse_texels(void)
{
    struct tex small[6];
    static const uint32_t xy[6][2] = {{0, 0}, {8, 0}, {0, 8}, {8, 8}, {32, 0}, {40, 0}};
    struct vt_layout l;
    struct vt_error err;
    VT_CHECK_INT_EQ(vt_layout_alloc(&l, 1, 6, &err), 0);
    l.width = 256, l.height = 256, l.tile_content = 16, l.border = 2;
    l.layers[0] = (struct vt_layout_layer){xstrdup("diffuse"), xstrdup("map_Kd"), VTS_COLOUR_SRGB};
    for (uint32_t i = 0; i < 6; i++) {
        char name[16];
        snprintf(name, sizeof name, "tiny%u", i);
        make_texture(&small[i], name, 6, 6, 3, 10 + i);
        struct vt_layout_entry *e = &l.entries[i];
        e->name = xstrdup(name);
        e->x = xy[i][0], e->y = xy[i][1], e->width = e->height = 6;
        e->cell_width = e->cell_height = e->alignment = 8;
        e->textures[0].path = xstrdup(small[i].path);
        e->textures[0].width = e->textures[0].height = 6;
    }
    char path[600], out[600], args[2048];
    snprintf(path, sizeof path, "%s/tiny.json", dir);
    snprintf(out, sizeof out, "%s/tiny.vts", dir);
    VT_CHECK_INT_EQ(vt_layout_write(path, &l, &err), 0);
    vt_layout_release(&l);
    snprintf(args, sizeof args, "--layout %s -o %s --codec png -j2 -q", path, out);
    VT_CHECK_INT_EQ(run_tool(args), 0);
    struct reader r;
    if (!reader_open(&r, out, 0))
        return;
    VT_CHECK_INT_EQ(r.g.level_count, 5);
    struct vt_pixel_mode m = {3, VTS_COLOUR_SRGB, false};
    /* level 4 texel (0, 0): four owned children at level 3; texel (2, 0): two of four */
    uint32_t xs[2] = {0, 2}, counts[2] = {4, 2};
    for (int c = 0; c < 2; c++) {
        float sum[3] = {0, 0, 0};
        uint32_t n = 0;
        for (uint32_t d = 0; d < 4; d++) {
            const uint8_t *p = reader_texel(&r, 3, 2 * xs[c] + (d & 1), d >> 1);
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
        const uint8_t *got = reader_texel(&r, 4, xs[c], 0);
        VT_CHECK(got != NULL);
        for (int k = 0; got && k < 3; k++)
            VT_CHECK(abs((int)got[k] - (int)want[k]) <= 1);
    }
    /* the 1x1 level-3 texel of a 6x6 texture is its own mip level 3 */
    struct vt_image e;
    reduce_expected(&small[0].img, 3, &e);
    const uint8_t *t = reader_texel(&r, 3, 0, 0);
    VT_CHECK(t && memcmp(t, e.pixels, 3) == 0);
    vt_image_release(&e);
    reader_close(&r);
    for (int i = 0; i < 6; i++)
        vt_image_release(&small[i].img);
}

/* Entries of one group (terrain pieces edge to edge) are one surface: borders cross between them;
 * without a group they clamp to each piece. */
static void build_pieces(uint32_t group, const char *name, struct tex *pieces)
{
    struct vt_layout l;
    struct vt_error err;
    VT_CHECK_INT_EQ(vt_layout_alloc(&l, 1, 2, &err), 0);
    l.width = 128, l.height = 64, l.tile_content = 32, l.border = 4;
    l.layers[0] = (struct vt_layout_layer){xstrdup("diffuse"), xstrdup("map_Kd"), VTS_COLOUR_SRGB};
    for (uint32_t i = 0; i < 2; i++) {
        struct vt_layout_entry *e = &l.entries[i];
        e->name = xstrdup(pieces[i].name);
        e->x = 64 * i, e->width = e->height = e->cell_width = e->cell_height = e->alignment = 64;
        e->group = group;
        e->textures[0].path = xstrdup(pieces[i].path);
        e->textures[0].width = e->textures[0].height = 64;
    }
    char path[600], args[2048];
    snprintf(path, sizeof path, "%s/%s.json", dir, name);
    VT_CHECK_INT_EQ(vt_layout_write(path, &l, &err), 0);
    vt_layout_release(&l);
    snprintf(args, sizeof args, "--layout %s -o %s/%s.vts --codec png -q", path, dir, name);
    VT_CHECK_INT_EQ(run_tool(args), 0);
}

static void test_group_borders_cross_pieces(void)
{
    struct tex pieces[2];
    make_texture(&pieces[0], "pieceA", 64, 64, 3, 21);
    make_texture(&pieces[1], "pieceB", 64, 64, 3, 22);
    build_pieces(1, "grouped", pieces);
    build_pieces(0, "separate", pieces);
    struct vt_image a1, b1;
    reduce_expected(&pieces[0].img, 1, &a1);
    reduce_expected(&pieces[1].img, 1, &b1);
    for (int grouped = 1; grouped >= 0; grouped--) {
        char out[600];
        snprintf(out, sizeof out, "%s/%s.vts", dir, grouped ? "grouped" : "separate");
        struct reader r;
        if (!reader_open(&r, out, 0))
            continue;
        uint32_t bad = 0;
        /* level 0, tile (2, 0) starts at piece B: its left border */
        const struct vt_image *t = reader_tile(&r, 0, 2, 0);
        VT_CHECK(t != NULL);
        for (uint32_t j = 4; t && j < 36; j++)
            for (uint32_t i = 0; i < 4; i++) {
                const uint8_t *want = grouped ? vt_image_at(&pieces[0].img, 60 + i, j - 4)
                                              : vt_image_at(&pieces[1].img, 0, j - 4);
                bad += memcmp(vt_image_at(t, i, j), want, 3) != 0;
            }
        /* level 1, tile (1, 0) starts at piece B's level 1 */
        t = reader_tile(&r, 1, 1, 0);
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
        reader_close(&r);
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
    struct tex t[N];
    struct vt_image m1[N];
    static const char *names[N] = {"gutA", "gutB", "gutC", "gutD"};
    struct vt_layout l;
    struct vt_error err;
    VT_CHECK_INT_EQ(vt_layout_alloc(&l, 1, N, &err), 0);
    l.width = 128, l.height = 64, l.tile_content = 64, l.border = 4; /* 2 levels */
    l.layers[0] = (struct vt_layout_layer){xstrdup("diffuse"), xstrdup("map_Kd"), VTS_COLOUR_SRGB};
    for (uint32_t i = 0; i < N; i++) {
        make_texture(&t[i], names[i], S, S, 3, 30 + i);
        reduce_expected(&t[i].img, 1, &m1[i]);
        struct vt_layout_entry *e = &l.entries[i];
        e->name = xstrdup(names[i]);
        e->x = (i % 2) * C + G, e->y = (i / 2) * C + G, e->width = e->height = S;
        e->cell_left = e->cell_top = G, e->cell_width = e->cell_height = C, e->alignment = G;
        e->textures[0].path = xstrdup(t[i].path);
        e->textures[0].width = e->textures[0].height = S;
    }
    char path[600], store[600], args[2048];
    snprintf(path, sizeof path, "%s/gutter.json", dir);
    snprintf(store, sizeof store, "%s/gutter.vts", dir);
    VT_CHECK_INT_EQ(vt_layout_write(path, &l, &err), 0);
    vt_layout_release(&l);
    snprintf(args, sizeof args, "--layout %s -o %s --codec png -q", path, store);
    VT_CHECK_INT_EQ(run_tool(args), 0);
    struct reader r;
    if (reader_open(&r, store, 0)) {
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
                        const uint8_t *got = reader_texel(&r, L, cx + x, cy + y);
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
        reader_close(&r);
    }
    for (uint32_t i = 0; i < N; i++) {
        vt_image_release(&t[i].img);
        vt_image_release(&m1[i]);
    }
}

int main(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: test_atlas_build TOOL WORKDIR\n");
        return 2;
    }
    tool = argv[1];
    dir = argv[2];
    mkdir(dir, 0777);
    make_texture(&texs[T_BIG], "big", 1000, 700, 3, 1);
    make_texture(&texs[T_MID], "mid", 300, 200, 3, 2);
    make_texture(&texs[T_SMALL], "small", 100, 60, 3, 3);
    make_texture(&texs[T_WRAP], "wrap", 40, 30, 3, 4);
    make_texture(&texs[T_BOX], "box", 64, 64, 3, 5);
    make_texture(&texs[T_ALPHA], "alpha", 300, 200, 4, 6);
    make_texture(&texs[T_HALF], "half", 200, 120, 3, 7);
    write_layout("atlas.json", NULL);
    snprintf(layout_path, sizeof layout_path, "%s/atlas.json", dir);
    snprintf(store_j1, sizeof store_j1, "%s/atlas_j1.vts", dir);
    snprintf(store_j2, sizeof store_j2, "%s/atlas_j2.vts", dir);
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
    VT_RUN(test_mixed_coarse_texels);
    VT_RUN(test_group_borders_cross_pieces);
    VT_RUN(test_gutter_repeats_edges);
    for (int i = 0; i < T_COUNT; i++)
        vt_image_release(&texs[i].img);
    return vt_test_main_result();
}
