/* Unit tests of the tile-aware packer (lib/atlas/vt_atlas_pack.c): every placement checked for
 * overlaps, alignment, cells inside the atlas, power-of-two sub-tile cells and whole free tiles. */
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>

#include "vt_atlas_pack.h"
#include "vt_test.h"

static uint32_t rng_state = 12345;

static uint32_t rng(void)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 17;
    rng_state ^= rng_state << 5;
    return rng_state;
}

static bool is_pow2(uint32_t v)
{
    return v && !(v & (v - 1));
}

/* Checks every rule of the header on a placement. */
static void check_placement(const struct vt_atlas_rect *r, uint32_t n, uint32_t T,
                            const struct vt_atlas_pack_stats *s)
{
    int bad_cell = 0, bad_align = 0, bad_inside = 0, bad_sub = 0, overlaps = 0;
    for (uint32_t i = 0; i < n; i++) {
        bool small = r[i].width <= T && r[i].height <= T;
        bad_cell += r[i].cell_width < r[i].width || r[i].cell_height < r[i].height;
        bad_align += !is_pow2(r[i].alignment) || r[i].x % r[i].alignment ||
                     r[i].y % r[i].alignment || r[i].cell_width % r[i].alignment ||
                     r[i].cell_height % r[i].alignment;
        bad_inside += r[i].x + r[i].cell_width > s->width || r[i].y + r[i].cell_height > s->height;
        if (small)
            bad_sub += r[i].cell_width != vt_atlas_next_pow2(r[i].width) ||
                       r[i].cell_height != vt_atlas_next_pow2(r[i].height) ||
                       r[i].x % r[i].cell_width || r[i].y % r[i].cell_height ||
                       r[i].x / T != (r[i].x + r[i].cell_width - 1) / T ||
                       r[i].y / T != (r[i].y + r[i].cell_height - 1) / T;
        else
            bad_sub += r[i].alignment != T || r[i].cell_width % T || r[i].cell_height % T;
    }
    /* Overlaps and tile sharing: mark every tile with the kind of cells in it. */
    uint64_t tiles = (uint64_t)s->tiles_x * s->tiles_y;
    int32_t *owner = malloc(tiles * sizeof *owner); /* -1 free, -2 sub-tile, i large */
    for (uint64_t t = 0; t < tiles; t++)
        owner[t] = -1;
    uint64_t used = 0;
    for (uint32_t i = 0; i < n; i++) {
        bool small = r[i].width <= T && r[i].height <= T;
        for (uint32_t ty = r[i].y / T; ty <= (r[i].y + r[i].cell_height - 1) / T; ty++)
            for (uint32_t tx = r[i].x / T; tx <= (r[i].x + r[i].cell_width - 1) / T; tx++) {
                int32_t *o = &owner[(uint64_t)ty * s->tiles_x + tx];
                if (*o == -1)
                    used++;
                if (small)
                    overlaps += *o >= 0, *o = -2;
                else
                    overlaps += *o != -1, *o = (int32_t)i;
            }
    }
    free(owner);
    /* Sub-tile cells against each other (quadratic, small n only). */
    if (n <= 3000)
        for (uint32_t i = 0; i < n; i++)
            for (uint32_t j = i + 1; j < n; j++)
                overlaps +=
                    r[i].x < r[j].x + r[j].cell_width && r[j].x < r[i].x + r[i].cell_width &&
                    r[i].y < r[j].y + r[j].cell_height && r[j].y < r[i].y + r[i].cell_height;
    VT_CHECK_INT_EQ(bad_cell, 0);
    VT_CHECK_INT_EQ(bad_align, 0);
    VT_CHECK_INT_EQ(bad_inside, 0);
    VT_CHECK_INT_EQ(bad_sub, 0);
    VT_CHECK_INT_EQ(overlaps, 0);
    VT_CHECK_INT_EQ(used, s->tiles_used);
    uint64_t content = 0;
    for (uint32_t i = 0; i < n; i++)
        content += (uint64_t)r[i].width * r[i].height;
    VT_CHECK_INT_EQ(s->content_area, content);
    VT_CHECK(s->fill_ratio == (double)content / ((double)s->width * s->height));
    VT_CHECK_INT_EQ(s->tiles_empty, tiles - used);
}

static void packs_random_mixed_sizes_without_overlap(void)
{
    enum { N = 1500 };
    struct vt_atlas_rect *r = calloc(N, sizeof *r);
    for (uint32_t i = 0; i < N; i++) {
        r[i].width = 1 + rng() % ((rng() & 1) ? 64 : 900);
        r[i].height = 1 + rng() % ((rng() & 1) ? 64 : 900);
    }
    struct vt_atlas_pack_options o = {.tile_content = 128, .max_edge = 1u << 20};
    struct vt_atlas_pack_stats s;
    VT_CHECK_INT_EQ(vt_atlas_pack(r, N, &o, &s, NULL), 0);
    check_placement(r, N, 128, &s);
    VT_CHECK(s.width % 128 == 0 && s.height % 128 == 0);
    VT_CHECK(s.fill_ratio > 0 && s.fill_ratio <= 1);
    VT_CHECK(s.area_over_cells >= 1 && s.area_over_cells < 1.3);
    free(r);
}

static void subtile_cells_are_power_of_two_and_share_tiles(void)
{
    /* 16 cells of 30x20: 32x32 cells, four per 64x64 tile. */
    struct vt_atlas_rect r[16];
    for (int i = 0; i < 16; i++)
        r[i] = (struct vt_atlas_rect){.width = 30, .height = 20};
    struct vt_atlas_pack_options o = {.tile_content = 64, .max_edge = 4096};
    struct vt_atlas_pack_stats s;
    VT_CHECK_INT_EQ(vt_atlas_pack(r, 16, &o, &s, NULL), 0);
    check_placement(r, 16, 64, &s);
    VT_CHECK_INT_EQ(r[0].cell_width, 32);
    VT_CHECK_INT_EQ(r[0].cell_height, 32);
    VT_CHECK_INT_EQ(r[0].alignment, 32);
    VT_CHECK_INT_EQ(s.subtile_tiles, 4); /* 4 cells of 32x32 per 64x64 tile */
    VT_CHECK_INT_EQ(s.tiles_used, 4);
    VT_CHECK_INT_EQ(s.tiles_empty, 0);
    VT_CHECK_INT_EQ(s.width, 128);
    VT_CHECK_INT_EQ(s.height, 128);
    VT_CHECK_INT_EQ(s.cell_area, 16 * 32 * 32);
}

static void non_square_subtile_cells_align_to_the_smaller_edge(void)
{
    struct vt_atlas_rect r[3] = {
        {.width = 100, .height = 5}, {.width = 3, .height = 60}, {.width = 9, .height = 9}};
    struct vt_atlas_pack_options o = {.tile_content = 128, .max_edge = 4096};
    struct vt_atlas_pack_stats s;
    VT_CHECK_INT_EQ(vt_atlas_pack(r, 3, &o, &s, NULL), 0);
    check_placement(r, 3, 128, &s);
    VT_CHECK_INT_EQ(r[0].cell_width, 128);
    VT_CHECK_INT_EQ(r[0].cell_height, 8);
    VT_CHECK_INT_EQ(r[0].alignment, 8);
    VT_CHECK_INT_EQ(r[1].alignment, 4);
    VT_CHECK_INT_EQ(r[2].alignment, 16);
    /* One tile: the atlas shrinks to the used corner. */
    VT_CHECK_INT_EQ(s.width, 128);
    VT_CHECK_INT_EQ(s.height, 128);
    VT_CHECK_INT_EQ(s.tiles_used, 1);
    /* A 128-wide row and a 128-tall column cannot share a tile. */
    r[1].height = 70;
    VT_CHECK_INT_EQ(vt_atlas_pack(r, 3, &o, &s, NULL), 0);
    check_placement(r, 3, 128, &s);
    VT_CHECK_INT_EQ(s.tiles_used, 2);
}

static void large_cells_round_up_to_whole_tiles(void)
{
    struct vt_atlas_rect r[3] = {
        {.width = 257, .height = 100}, {.width = 512, .height = 512}, {.width = 10, .height = 10}};
    struct vt_atlas_pack_options o = {.tile_content = 256, .max_edge = 1u << 16};
    struct vt_atlas_pack_stats s;
    VT_CHECK_INT_EQ(vt_atlas_pack(r, 3, &o, &s, NULL), 0);
    check_placement(r, 3, 256, &s);
    VT_CHECK_INT_EQ(r[0].cell_width, 512);
    VT_CHECK_INT_EQ(r[0].cell_height, 256);
    VT_CHECK_INT_EQ(r[1].cell_width, 512);
    VT_CHECK_INT_EQ(r[1].alignment, 256);
    VT_CHECK_INT_EQ(r[2].cell_width, 16);
    VT_CHECK_INT_EQ(s.tiles_used, 2 + 4 + 1);
    /* 7 tiles: a 3x3 or 4x2 atlas at best (area 8 or 9). */
    VT_CHECK(s.tiles_x * s.tiles_y <= 9);
    VT_CHECK_INT_EQ(s.content_area, 257 * 100 + 512 * 512 + 100);
}

static void refuses_bad_tile_size_and_too_small_limit(void)
{
    struct vt_atlas_rect r[1] = {{.width = 5000, .height = 10}};
    struct vt_atlas_pack_options o = {.tile_content = 100, .max_edge = 4096};
    struct vts_error err;
    VT_CHECK_INT_EQ(vt_atlas_pack(r, 1, &o, NULL, &err), VTS_ERR_ARG);
    VT_CHECK_STR_CONTAINS(err.message, "not a power of two");
    o.tile_content = 128;
    VT_CHECK_INT_EQ(vt_atlas_pack(r, 1, &o, NULL, &err), VTS_ERR_LIMIT);
    VT_CHECK_STR_CONTAINS(err.message, "atlas size limit 4096");
    r[0].width = 0;
    VT_CHECK_INT_EQ(vt_atlas_pack(r, 1, &o, NULL, &err), VTS_ERR_ARG);
    /* Many tiles that do not fit in a 2x2-tile limit. */
    struct vt_atlas_rect many[5];
    for (int i = 0; i < 5; i++)
        many[i] = (struct vt_atlas_rect){.width = 128, .height = 128};
    o.max_edge = 256;
    VT_CHECK_INT_EQ(vt_atlas_pack(many, 5, &o, NULL, &err), VTS_ERR_LIMIT);
    VT_CHECK_STR_CONTAINS(err.message, "do not fit");
}

static void is_deterministic(void)
{
    enum { N = 300 };
    struct vt_atlas_rect a[N], b[N];
    for (uint32_t i = 0; i < N; i++)
        a[i] = b[i] = (struct vt_atlas_rect){.width = 1 + rng() % 700, .height = 1 + rng() % 700};
    struct vt_atlas_pack_options o = {.tile_content = 256, .max_edge = 1u << 20};
    VT_CHECK_INT_EQ(vt_atlas_pack(a, N, &o, NULL, NULL), 0);
    VT_CHECK_INT_EQ(vt_atlas_pack(b, N, &o, NULL, NULL), 0);
    VT_CHECK(memcmp(a, b, sizeof a) == 0);
}

/* --gutter: every sub-tile content sits G texels inside its cell on each side (or, on an axis
 * where content + 2G exceeds the tile, fills a tile-wide cell); cells stay inside one tile, apart
 * from each other and inside the atlas; every position is a multiple of the alignment. */
static void gutter_cells_surround_subtile_content(void)
{
    enum { N = 1200 };
    const uint32_t T = 128, G = 4;
    struct vt_atlas_rect *r = calloc(N, sizeof *r);
    for (uint32_t i = 0; i < N; i++) {
        r[i].width = 1 + rng() % ((rng() & 1) ? 128 : 600);
        r[i].height = 1 + rng() % ((rng() & 1) ? 128 : 600);
    }
    r[0].width = 128, r[0].height = 64;  /* x: tile-wide, no gutter; y: gutter */
    r[1].width = 122, r[1].height = 122; /* both tile-wide */
    struct vt_atlas_pack_options o = {.tile_content = T, .max_edge = 1u << 20, .gutter = G};
    struct vt_atlas_pack_stats s;
    VT_CHECK_INT_EQ(vt_atlas_pack(r, N, &o, &s, NULL), 0);
    int bad_gutter = 0, bad_align = 0, bad_inside = 0, bad_tile = 0, overlaps = 0;
    for (uint32_t i = 0; i < N; i++) {
        const struct vt_atlas_rect *a = &r[i];
        bool small = a->width <= T && a->height <= T;
        uint32_t gx = a->x - a->cell_x, gy = a->y - a->cell_y;
        if (a->cell_x > a->x || a->cell_y > a->y) {
            bad_gutter++;
            continue;
        }
        if (small) {
            bad_gutter += a->width + 2 * G <= T ? gx != G || a->cell_width < a->width + 2 * G
                                                : gx != 0 || a->cell_width != T;
            bad_gutter += a->height + 2 * G <= T ? gy != G || a->cell_height < a->height + 2 * G
                                                 : gy != 0 || a->cell_height != T;
            bad_tile += a->cell_x / T != (a->cell_x + a->cell_width - 1) / T ||
                        a->cell_y / T != (a->cell_y + a->cell_height - 1) / T;
        } else {
            bad_gutter += gx || gy || a->alignment != T;
        }
        bad_align += !is_pow2(a->alignment) || a->x % a->alignment || a->y % a->alignment ||
                     a->cell_x % a->alignment || a->cell_y % a->alignment ||
                     a->cell_width % a->alignment || a->cell_height % a->alignment;
        bad_inside += a->cell_x + a->cell_width > s.width || a->cell_y + a->cell_height > s.height;
        for (uint32_t j = i + 1; j < N; j++) {
            const struct vt_atlas_rect *b = &r[j];
            overlaps +=
                a->cell_x < b->cell_x + b->cell_width && b->cell_x < a->cell_x + a->cell_width &&
                a->cell_y < b->cell_y + b->cell_height && b->cell_y < a->cell_y + a->cell_height;
        }
    }
    VT_CHECK_INT_EQ(bad_gutter, 0);
    VT_CHECK_INT_EQ(bad_align, 0);
    VT_CHECK_INT_EQ(bad_inside, 0);
    VT_CHECK_INT_EQ(bad_tile, 0);
    VT_CHECK_INT_EQ(overlaps, 0);
    VT_CHECK(r[0].cell_width == T && r[0].x == r[0].cell_x && r[0].y == r[0].cell_y + G);
    VT_CHECK(r[1].cell_width == T && r[1].cell_height == T && r[1].alignment == T);
    VT_CHECK(s.area_over_cells >= 1 && s.area_over_cells < 1.3);
    VT_CHECK(s.area_over_base > 0 && s.base_cell_area > 0);
    /* Four 24x24 textures with gutter 4: 32x32 cells on one shelf of the tile. */
    struct vt_atlas_rect q[4];
    for (int i = 0; i < 4; i++)
        q[i] = (struct vt_atlas_rect){.width = 24, .height = 24};
    o.tile_content = 256;
    VT_CHECK_INT_EQ(vt_atlas_pack(q, 4, &o, &s, NULL), 0);
    VT_CHECK(s.width == 128 && s.height == 32); /* one shelf; the atlas shrinks to it */
    for (int i = 0; i < 4; i++)
        VT_CHECK(q[i].cell_width == 32 && q[i].x == q[i].cell_x + 4 && q[i].alignment == 4);
    /* Bad gutters. */
    struct vts_error err;
    o.gutter = 3;
    VT_CHECK_INT_EQ(vt_atlas_pack(q, 4, &o, NULL, &err), VTS_ERR_ARG);
    VT_CHECK_STR_CONTAINS(err.message, "gutter 3 is not 0 or a power of two");
    o.gutter = 256;
    VT_CHECK_INT_EQ(vt_atlas_pack(q, 4, &o, NULL, &err), VTS_ERR_ARG);
    /* Without gutter the cell starts at the content. */
    o.gutter = 0;
    VT_CHECK_INT_EQ(vt_atlas_pack(q, 4, &o, NULL, NULL), 0);
    for (int i = 0; i < 4; i++)
        VT_CHECK(q[i].cell_x == q[i].x && q[i].cell_y == q[i].y && q[i].cell_width == 32);
    free(r);
}

int main(void)
{
    VT_RUN(packs_random_mixed_sizes_without_overlap);
    VT_RUN(subtile_cells_are_power_of_two_and_share_tiles);
    VT_RUN(non_square_subtile_cells_align_to_the_smaller_edge);
    VT_RUN(large_cells_round_up_to_whole_tiles);
    VT_RUN(refuses_bad_tile_size_and_too_small_limit);
    VT_RUN(is_deterministic);
    VT_RUN(gutter_cells_surround_subtile_content);
    return vt_test_main_result();
}
