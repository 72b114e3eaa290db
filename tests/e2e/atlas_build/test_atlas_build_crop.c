/* vt-tiles --layout end to end (store side), entries that hold a crop of their block of copies and
 * entries that wrap: every texel of each entry's cell and every tile border texel next to it, at
 * each level the entry owns, against the chain the rules give (computed here from the texture):
 *   crop: level 0 texel (a, b) = texel ((crop_x + a) mod W, (crop_y + b) mod H) of the texture at
 *     the entry's size, coarser levels the reduction of the crop, edges clamped;
 *   wrap: the chain reduced with wrap-around edges, and positions outside the texture (gutter,
 *     padding, tile borders, also past the atlas's edge) read modulo the level's size.
 * Non-wrap entries with the same textures sit next to the wrap ones and must still clamp.
 * Usage: test_atlas_build_crop VT_TILES WORKDIR */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "atlas_build_fixture.h"
#include "vt_filter.h"
#include "vt_layout.h"
#include "vt_test.h"
#include "vts.h"

#define ATLAS_W 256
#define ATLAS_H 128
#define CONTENT 32
#define BORDER  4
#define LEVELS  4 /* 256 / 32 = 8: levels 0..3 */

enum { TEX_WA, TEX_WB, TEX_CA, TEX_CB, TEX_CC, TEX_WBIG, TEX_WHALF, TEX_COUNT };
static struct abuild_tex texs[TEX_COUNT];
static const uint32_t tex_size[TEX_COUNT][2] = {{32, 32}, {25, 23},  {40, 30}, {20, 12},
                                                {64, 64}, {119, 55}, {33, 27}};

/* One entry: texture, scale (-1: 0.5, 0: 1, 1: 2), placement, crop (0 x 0: the whole block). */
struct ent {
    const char *name;
    uint32_t tex;
    int scale_log2;
    uint32_t x, y, ru, rv;
    uint32_t crop[4];
    uint32_t gutter, cell_w, cell_h, align;
    bool wrap;
};
static const struct ent ents[] = {
    /* the atlas's top-left corner: its left and top borders lie past the atlas's edge */
    {"wrapA", TEX_WA, 0, 0, 0, 1, 1, {0, 0, 0, 0}, 0, 32, 32, 32, true},
    {"clampA", TEX_WA, 0, 32, 0, 1, 1, {0, 0, 0, 0}, 0, 32, 32, 32, false},
    /* odd sizes, a gutter of 4 and 3..4 texels of padding; 25 -> 13 and 23 -> 12 at level 1 */
    {"wrapB", TEX_WB, 0, 68, 4, 1, 1, {0, 0, 0, 0}, 4, 32, 32, 4, true},
    {"clampB", TEX_WB, 0, 100, 4, 1, 1, {0, 0, 0, 0}, 4, 32, 32, 4, false},
    /* 3x2 copies of 40x30 (120x60), the crop starting in the middle of the first copy */
    {"cropA", TEX_CA, 0, 128, 0, 3, 2, {27, 13, 70, 40}, 0, 96, 64, 32, false},
    /* scale 2 (texels replicated): 40x24, cropped inside the one copy */
    {"cropB", TEX_CB, 1, 224, 0, 1, 1, {3, 5, 30, 16}, 0, 32, 32, 32, false},
    /* scale 0.5 (the texture's mip level 1, 32x32), 2x1 copies, crop across the seam */
    {"cropC", TEX_CC, -1, 128, 64, 2, 1, {16, 8, 40, 20}, 0, 64, 32, 32, false},
    /* larger than a tile, 119 wide (not a multiple of 32), padding to 128x64 */
    {"wrapBig", TEX_WBIG, 0, 0, 64, 1, 1, {0, 0, 0, 0}, 0, 128, 64, 64, true},
    /* scale 0.5 of a 33x27 texture: its own mip level 1 (17x14), reduced with wrap-around too */
    {"wrapHalf", TEX_WHALF, -1, 192, 64, 1, 1, {0, 0, 0, 0}, 0, 32, 32, 32, true},
};
#define NENTS (sizeof ents / sizeof ents[0])

static uint32_t ent_w(const struct ent *e)
{
    uint32_t w = tex_size[e->tex][0];
    return e->scale_log2 < 0 ? (w + 1) >> 1 : w << e->scale_log2;
}
static uint32_t ent_h(const struct ent *e)
{
    uint32_t h = tex_size[e->tex][1];
    return e->scale_log2 < 0 ? (h + 1) >> 1 : h << e->scale_log2;
}

static void write_layout(const char *path)
{
    struct vt_layout l;
    struct vts_error err;
    VT_CHECK_INT_EQ(vt_layout_alloc(&l, 1, NENTS, &err), 0);
    l.width = ATLAS_W, l.height = ATLAS_H, l.tile_content = CONTENT, l.border = BORDER;
    l.layers[0] = (struct vt_layout_layer){abuild_strdup("diffuse"), abuild_strdup("map_Kd"),
                                           VTS_COLOUR_SRGB};
    for (uint32_t i = 0; i < NENTS; i++) {
        const struct ent *p = &ents[i];
        struct vt_layout_entry *e = &l.entries[i];
        e->name = abuild_strdup(p->name);
        e->x = p->x, e->y = p->y, e->width = ent_w(p), e->height = ent_h(p);
        e->repeat_u = p->ru, e->repeat_v = p->rv;
        e->crop_x = p->crop[0], e->crop_y = p->crop[1];
        e->crop_width = p->crop[2], e->crop_height = p->crop[3];
        e->cell_left = e->cell_top = p->gutter;
        e->cell_width = p->cell_w, e->cell_height = p->cell_h, e->alignment = p->align;
        e->scale = p->scale_log2 < 0 ? 0.5 : (double)(1u << p->scale_log2);
        e->wrap = p->wrap;
        e->textures[0].path = abuild_strdup(texs[p->tex].path);
        e->textures[0].width = tex_size[p->tex][0], e->textures[0].height = tex_size[p->tex][1];
    }
    VT_CHECK_INT_EQ(vt_layout_write(path, &l, &err), 0);
    vt_layout_release(&l);
}

/* ---- the chains the rules give ---- */

static int64_t mod(int64_t v, int64_t n)
{
    int64_t r = v % n;
    return r < 0 ? r + n : r;
}

static const struct vt_pixel_mode srgb3 = {3, VTS_COLOUR_SRGB, false};

/* One reduction of a w x h float image with every tap read modulo the size (the filter's own
 * order of operations: horizontal sums first, taps added in order), written here from the
 * kernel's taps rather than through vt_filter_reduce. */
static float *reduce_wrapped(const float *in, uint32_t w, uint32_t h, const struct vt_kernel *k)
{
    uint32_t dw = (w + 1) / 2, dh = (h + 1) / 2;
    float *rows = malloc((size_t)h * dw * 3 * sizeof(float));
    float *out = malloc((size_t)dw * dh * 3 * sizeof(float));
    for (uint32_t y = 0; y < h; y++)
        for (uint32_t X = 0; X < dw; X++)
            for (uint32_t c = 0; c < 3; c++) {
                float acc = 0;
                for (int t = 0; t < k->count; t++) {
                    int64_t x = mod(2 * (int64_t)X + k->first + t, w);
                    float p = k->weights[t] * in[((size_t)y * w + (size_t)x) * 3 + c];
                    acc = t ? acc + p : p;
                }
                rows[((size_t)y * dw + X) * 3 + c] = acc;
            }
    for (uint32_t Y = 0; Y < dh; Y++)
        for (uint32_t X = 0; X < dw; X++)
            for (uint32_t c = 0; c < 3; c++) {
                float acc = 0;
                for (int t = 0; t < k->count; t++) {
                    int64_t y = mod(2 * (int64_t)Y + k->first + t, h);
                    float p = k->weights[t] * rows[((size_t)y * dw + X) * 3 + c];
                    acc = t ? acc + p : p;
                }
                out[((size_t)Y * dw + X) * 3 + c] = acc;
            }
    free(rows);
    return out;
}

/* Levels 0..n-1 of a wrap chain from its level 0 (kept in floats between levels, as the
 * compositor does). */
static void wrap_chain(const struct vt_image *l0, enum vt_filter_kind f, uint32_t n,
                       struct vt_image *out)
{
    struct vt_kernel k;
    vt_kernel_init(&k, f);
    uint32_t w = l0->width, h = l0->height;
    float *cur = malloc((size_t)w * h * 3 * sizeof(float));
    for (uint32_t y = 0; y < h; y++)
        vt_filter_to_working(&srgb3, VTS_SAMPLE_U8, vt_image_at(l0, 0, y), cur + (size_t)y * w * 3,
                             w);
    vt_image_alloc(&out[0], w, h, 3, VTS_SAMPLE_U8, NULL);
    memcpy(out[0].pixels, l0->pixels, (size_t)w * h * 3);
    for (uint32_t L = 1; L < n; L++) {
        float *next = reduce_wrapped(cur, w, h, &k);
        free(cur);
        cur = next, w = (w + 1) / 2, h = (h + 1) / 2;
        vt_image_alloc(&out[L], w, h, 3, VTS_SAMPLE_U8, NULL);
        for (uint32_t y = 0; y < h; y++)
            vt_filter_from_working(&srgb3, VTS_SAMPLE_U8, cur + (size_t)y * w * 3,
                                   vt_image_at(&out[L], 0, y), w);
    }
    free(cur);
}

/* Level 0 of entry e's chain: its crop of the copies of the texture at the entry's size (the
 * texture's own mip level 1 at scale 0.5, reduced with wrap-around for a wrap entry). */
static void crop_level0(const struct ent *e, enum vt_filter_kind f, struct vt_image *out)
{
    const struct vt_image *t = &texs[e->tex].img;
    struct vt_image half = {0}, two[2];
    if (e->scale_log2 < 0 && e->wrap) {
        wrap_chain(t, f, 2, two);
        half = two[1];
        vt_image_release(&two[0]);
    } else if (e->scale_log2 < 0) {
        abuild_reduce(t, 1, &half); /* box: only wrap entries are checked with another filter */
    }
    uint32_t W = ent_w(e), H = ent_h(e);
    uint32_t cx = e->crop[0], cy = e->crop[1], cw = e->crop[2], chh = e->crop[3];
    if (cw == 0)
        cw = W * e->ru, chh = H * e->rv;
    vt_image_alloc(out, cw, chh, 3, VTS_SAMPLE_U8, NULL);
    for (uint32_t b = 0; b < chh; b++)
        for (uint32_t a = 0; a < cw; a++) {
            uint32_t x = (cx + a) % W, y = (cy + b) % H; /* texel of the copy at the entry's size */
            const uint8_t *p = e->scale_log2 < 0 ? vt_image_at(&half, x, y)
                               : e->scale_log2 > 0
                                   ? vt_image_at(t, x >> e->scale_log2, y >> e->scale_log2)
                                   : vt_image_at(t, x, y);
            memcpy(vt_image_at(out, a, b), p, 3);
        }
    vt_image_release(&half);
}

static uint32_t log2u(uint32_t v)
{
    uint32_t l = 0;
    while ((2u << l) <= v)
        l++;
    return l;
}

/* Levels the entry owns in the store (down to its alignment). */
static uint32_t owned_levels(const struct ent *e)
{
    uint32_t n = log2u(e->align) + 1;
    return n < LEVELS ? n : LEVELS;
}

static void entry_chain(const struct ent *e, enum vt_filter_kind f, struct vt_image *chain)
{
    struct vt_image l0;
    crop_level0(e, f, &l0);
    uint32_t n = owned_levels(e);
    if (e->wrap) {
        wrap_chain(&l0, f, n, chain);
    } else {
        vt_image_alloc(&chain[0], l0.width, l0.height, 3, VTS_SAMPLE_U8, NULL);
        memcpy(chain[0].pixels, l0.pixels, (size_t)l0.width * l0.height * 3);
        for (uint32_t L = 1; L < n; L++)
            abuild_reduce(&l0, L, &chain[L]); /* box, clamped at the crop's edges */
    }
    vt_image_release(&l0);
}

/* ---- the check ---- */

struct tally {
    uint64_t checked, bad;
    uint64_t outside; /* texels outside the texture (gutter, padding, borders) checked */
    uint64_t telling; /* of those, texels where wrap and clamp give different values */
};

/* The texel of level-L chain c at chain position (i, j) by entry e's rule, and whether the
 * other rule (clamp for a wrap entry, wrap for the others) gives another value there. */
static const uint8_t *rule_texel(const struct ent *e, const struct vt_image *c, int64_t i,
                                 int64_t j, bool *telling)
{
    int64_t wi = mod(i, c->width), wj = mod(j, c->height);
    int64_t ci = i < 0 ? 0 : i >= c->width ? c->width - 1 : i;
    int64_t cj = j < 0 ? 0 : j >= c->height ? c->height - 1 : j;
    const uint8_t *w = vt_image_at(c, (uint32_t)wi, (uint32_t)wj);
    const uint8_t *k = vt_image_at(c, (uint32_t)ci, (uint32_t)cj);
    *telling = memcmp(w, k, 3) != 0;
    return e->wrap ? w : k;
}

static void check_texel(struct tally *t, const struct ent *e, const struct vt_image *c, uint32_t L,
                        int64_t X, int64_t Y, const uint8_t *got)
{
    int64_t i = X - (e->x >> L), j = Y - (e->y >> L);
    bool telling, outside = i < 0 || j < 0 || i >= c->width || j >= c->height;
    const uint8_t *want = rule_texel(e, c, i, j, &telling);
    t->checked++;
    t->outside += outside;
    t->telling += outside && telling;
    if (!got || memcmp(got, want, 3) != 0) {
        if (t->bad++ < 4)
            fprintf(stderr, "%s level %u texel (%lld, %lld): %d %d %d, want %d %d %d\n", e->name, L,
                    (long long)X, (long long)Y, got ? got[0] : -1, got ? got[1] : -1,
                    got ? got[2] : -1, want[0], want[1], want[2]);
    }
}

/* Every texel of e's cell at level L, and every border texel of every tile whose nearest content
 * texel lies in the cell: it reads e's chain at its own position (for a non-wrap entry clamped to
 * the level first, as at the atlas's edge; a wrap entry's is not clamped). */
static void check_entry_level(struct abuild_reader *r, const struct ent *e,
                              const struct vt_image *c, uint32_t L, struct tally *content,
                              struct tally *border)
{
    int64_t cx0 = (e->x - e->gutter) >> L, cy0 = (e->y - e->gutter) >> L;
    int64_t cx1 = cx0 + (e->cell_w >> L), cy1 = cy0 + (e->cell_h >> L);
    for (int64_t Y = cy0; Y < cy1; Y++)
        for (int64_t X = cx0; X < cx1; X++)
            check_texel(content, e, c, L, X, Y,
                        abuild_reader_texel(r, L, (uint32_t)X, (uint32_t)Y));
    int64_t lw = ATLAS_W >> L, lh = ATLAS_H >> L;
    for (uint32_t ty = 0; ty * CONTENT < lh; ty++)
        for (uint32_t tx = 0; tx * CONTENT < lw; tx++) {
            const struct vt_image *tile = abuild_reader_tile(r, L, tx, ty);
            int64_t x0 = (int64_t)tx * CONTENT, y0 = (int64_t)ty * CONTENT;
            int64_t cw = lw - x0 < CONTENT ? lw - x0 : CONTENT;  /* a tile past the level's end */
            int64_t chh = lh - y0 < CONTENT ? lh - y0 : CONTENT; /* holds less content */
            for (uint32_t pj = 0; pj < CONTENT + 2 * BORDER; pj++)
                for (uint32_t pi = 0; pi < CONTENT + 2 * BORDER; pi++) {
                    int64_t X = x0 - BORDER + pi, Y = y0 - BORDER + pj;
                    if (X >= x0 && X < x0 + cw && Y >= y0 && Y < y0 + chh)
                        continue; /* content: checked above */
                    int64_t Xc = X < x0 ? x0 : X >= x0 + cw ? x0 + cw - 1 : X;
                    int64_t Yc = Y < y0 ? y0 : Y >= y0 + chh ? y0 + chh - 1 : Y;
                    if (Xc < cx0 || Xc >= cx1 || Yc < cy0 || Yc >= cy1)
                        continue;
                    int64_t Xr = e->wrap ? X : X < 0 ? 0 : X >= lw ? lw - 1 : X;
                    int64_t Yr = e->wrap ? Y : Y < 0 ? 0 : Y >= lh ? lh - 1 : Y;
                    check_texel(border, e, c, L, Xr, Yr, tile ? vt_image_at(tile, pi, pj) : NULL);
                }
        }
}

static void build(const char *layout, const char *store, const char *filter)
{
    char args[2048];
    snprintf(args, sizeof args, "--layout %s -o %s --codec png --filter %s -j2 -q", layout, store,
             filter);
    VT_CHECK_INT_EQ(abuild_run(args), 0);
    if (abuild_stderr[0])
        fprintf(stderr, "%s", abuild_stderr);
}

/* Checks the entries `only` selects (wrap entries, or all) at each level they own; every entry
 * must show texels outside its texture where wrap and clamp differ, at levels 0 and 1, in its
 * cell or in the borders (so that the check tells the rules apart). */
static void check_store(const char *store, enum vt_filter_kind f, bool wrap_only,
                        uint64_t min_texels)
{
    uint64_t total = 0;
    struct abuild_reader r;
    if (!abuild_reader_open(&r, store, 0)) {
        VT_CHECK(false);
        return;
    }
    VT_CHECK_INT_EQ(r.g.level_count, LEVELS);
    for (uint32_t i = 0; i < NENTS; i++) {
        const struct ent *e = &ents[i];
        if (wrap_only && !e->wrap)
            continue;
        struct vt_image chain[LEVELS] = {{0}};
        entry_chain(e, f, chain);
        for (uint32_t L = 0; L < owned_levels(e); L++) {
            struct tally content = {0}, border = {0};
            check_entry_level(&r, e, &chain[L], L, &content, &border);
            total += content.checked + border.checked;
            if (content.bad || border.bad)
                fprintf(stderr,
                        "%s (%s) level %u: %llu of %llu cell texels, %llu of %llu border "
                        "texels differ\n",
                        e->name, vt_filter_name(f), L, (unsigned long long)content.bad,
                        (unsigned long long)content.checked, (unsigned long long)border.bad,
                        (unsigned long long)border.checked);
            VT_CHECK_INT_EQ(content.bad, 0);
            VT_CHECK_INT_EQ(border.bad, 0);
            if (L <= 1 && border.checked == 0)
                fprintf(stderr, "%s level %u: no border texel checked\n", e->name, L);
            if (L <= 1)
                VT_CHECK(border.checked > 0 && border.telling + content.telling > 0);
            if (L <= 1 && (e->gutter || e->cell_w > chain[0].width))
                VT_CHECK(content.telling > 0); /* the gutter or the padding tells them apart */
        }
        for (uint32_t L = 0; L < LEVELS; L++)
            vt_image_release(&chain[L]);
    }
    VT_CHECK(total > min_texels);
    abuild_reader_close(&r);
}

static char layout_path[600];

static void test_crop_and_wrap_box(void)
{
    char store[600];
    snprintf(store, sizeof store, "%s/crop_box.vts", abuild_dir);
    build(layout_path, store, "box");
    check_store(store, VT_FILTER_BOX, false, 22528); /* more than the level-0 cells */
}

/* The triangle kernel reads one texel past each side: the wrap chain's reduction reads the
 * opposite edge even on even sizes. */
static void test_wrap_triangle(void)
{
    char store[600];
    snprintf(store, sizeof store, "%s/crop_triangle.vts", abuild_dir);
    build(layout_path, store, "triangle");
    check_store(store, VT_FILTER_TRIANGLE, true, 11264);
}

/* Spot checks of the rules in the plainest terms, independent of the generic check: texel -1 of a
 * wrap entry is texel W - 1, a non-wrap entry's is texel 0; a crop's first texel is the block's
 * texel (crop_x, crop_y). */
static void test_spot_texels(void)
{
    char store[600];
    snprintf(store, sizeof store, "%s/crop_box.vts", abuild_dir);
    struct abuild_reader r;
    if (!abuild_reader_open(&r, store, 0)) {
        VT_CHECK(false);
        return;
    }
    const struct vt_image *wa = &texs[TEX_WA].img, *wb = &texs[TEX_WB].img;
    /* wrapA's right neighbour column x = 32 is clampA's; the border of tile (0, 0) past x = 31
     * shows wrapA's column 0, and the border of tile (1, 0) before x = 32 shows clampA's column
     * 0 (clamped), not wrapA's column 31 */
    const struct vt_image *t = abuild_reader_tile(&r, 0, 0, 0);
    VT_CHECK(t &&
             memcmp(vt_image_at(t, BORDER + CONTENT, BORDER + 5), vt_image_at(wa, 0, 5), 3) == 0);
    VT_CHECK(t && memcmp(vt_image_at(t, BORDER - 1, BORDER + 5), vt_image_at(wa, 31, 5), 3) == 0);
    VT_CHECK(t && memcmp(vt_image_at(t, BORDER + 5, 0), vt_image_at(wa, 5, 28), 3) == 0);
    t = abuild_reader_tile(&r, 0, 1, 0);
    VT_CHECK(t && memcmp(vt_image_at(t, BORDER - 1, BORDER + 5), vt_image_at(wa, 0, 5), 3) == 0);
    VT_CHECK(t &&
             memcmp(vt_image_at(t, BORDER + CONTENT, BORDER + 5), vt_image_at(wa, 31, 5), 3) == 0);
    /* wrapB's gutter column x = 67 is its column 24, its padding column x = 93 its column 0 */
    const uint8_t *p = abuild_reader_texel(&r, 0, 67, 10);
    VT_CHECK(p && memcmp(p, vt_image_at(wb, 24, 6), 3) == 0);
    p = abuild_reader_texel(&r, 0, 93, 10);
    VT_CHECK(p && memcmp(p, vt_image_at(wb, 0, 6), 3) == 0);
    p = abuild_reader_texel(&r, 0, 99, 10); /* clampB's gutter: its column 0 */
    VT_CHECK(p && memcmp(p, vt_image_at(wb, 0, 6), 3) == 0);
    /* cropA's texel (0, 0) is copy texel (27, 13); (13, 17) crosses into the next copy: (0, 0) */
    const struct vt_image *ca = &texs[TEX_CA].img;
    p = abuild_reader_texel(&r, 0, 128, 0);
    VT_CHECK(p && memcmp(p, vt_image_at(ca, 27, 13), 3) == 0);
    p = abuild_reader_texel(&r, 0, 128 + 13, 17);
    VT_CHECK(p && memcmp(p, vt_image_at(ca, 0, 0), 3) == 0);
    p = abuild_reader_texel(&r, 0, 128 + 69, 39); /* the last: block (96, 52) = copy (16, 22) */
    VT_CHECK(p && memcmp(p, vt_image_at(ca, 16, 22), 3) == 0);
    abuild_reader_close(&r);
}

/* --max-pixels counts the crop, not the block: a 70x40 crop (2800 texels) of 3x2 copies of
 * 40x30 (7200 texels) builds under a limit of 5000 and is refused under 2000. */
static void test_limit_counts_crop(void)
{
    struct vt_layout l;
    struct vts_error err;
    VT_CHECK_INT_EQ(vt_layout_alloc(&l, 1, 1, &err), 0);
    l.width = l.height = 128, l.tile_content = 32, l.border = 2;
    l.layers[0] = (struct vt_layout_layer){abuild_strdup("diffuse"), abuild_strdup("map_Kd"),
                                           VTS_COLOUR_SRGB};
    struct vt_layout_entry *e = &l.entries[0];
    e->name = abuild_strdup("crop");
    e->width = 40, e->height = 30, e->repeat_u = 3, e->repeat_v = 2;
    e->crop_x = 27, e->crop_y = 13, e->crop_width = 70, e->crop_height = 40;
    e->cell_width = 96, e->cell_height = 64, e->alignment = 32;
    e->textures[0].path = abuild_strdup(texs[TEX_CA].path);
    e->textures[0].width = 40, e->textures[0].height = 30;
    char path[600], args[2048];
    snprintf(path, sizeof path, "%s/limit.json", abuild_dir);
    VT_CHECK_INT_EQ(vt_layout_write(path, &l, &err), 0);
    vt_layout_release(&l);
    snprintf(args, sizeof args, "--layout %s -o %s/limit.vts --max-pixels 5000 -q", path,
             abuild_dir);
    VT_CHECK_INT_EQ(abuild_run(args), 0);
    snprintf(args, sizeof args, "--layout %s -o %s/limit2.vts --max-pixels 2000 -q", path,
             abuild_dir);
    VT_CHECK_INT_EQ(abuild_run(args), 1);
    VT_CHECK_STR_CONTAINS(abuild_stderr, "crop of 70x40 texels");
}

int main(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: test_atlas_build_crop VT_TILES WORKDIR\n");
        return 2;
    }
    abuild_tool = argv[1];
    abuild_dir = argv[2];
    mkdir(abuild_dir, 0777);
    static const char *names[TEX_COUNT] = {"wA", "wB", "cA", "cB", "cC", "wBig", "wHalf"};
    for (uint32_t i = 0; i < TEX_COUNT; i++)
        abuild_texture(&texs[i], names[i], tex_size[i][0], tex_size[i][1], 3, 50 + i);
    snprintf(layout_path, sizeof layout_path, "%s/crop.json", abuild_dir);
    write_layout(layout_path);
    VT_RUN(test_crop_and_wrap_box);
    VT_RUN(test_wrap_triangle);
    VT_RUN(test_spot_texels);
    VT_RUN(test_limit_counts_crop);
    for (uint32_t i = 0; i < TEX_COUNT; i++)
        vt_image_release(&texs[i].img);
    return vt_test_main_result();
}
