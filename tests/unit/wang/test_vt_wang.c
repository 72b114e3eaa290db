/* lib/wang: tiles made from a photo-like sample keep their edge colour's patch on every edge, the
 * virtual output assembled by the hash is seamless across tile edges while a shuffled pack is not
 * seamless in the pack itself, and the metadata parser takes what vt-wang writes and refuses bad
 * values. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vt_synth_photo.h"
#include "vt_test.h"
#include "vt_wang.h"

/* Mean squared difference between texel rows (or columns) a and b of img over n texels. */
static double line_mse(const struct vt_image *img, bool rows, uint32_t a, uint32_t b, uint32_t from,
                       uint32_t n)
{
    double sum = 0;
    for (uint32_t i = from; i < from + n; i++) {
        const uint8_t *p = rows ? vt_image_at(img, i, a) : vt_image_at(img, a, i);
        const uint8_t *q = rows ? vt_image_at(img, i, b) : vt_image_at(img, b, i);
        for (uint32_t c = 0; c < img->channels; c++)
            sum += ((double)p[c] - q[c]) * ((double)p[c] - q[c]);
    }
    return sum / (n * img->channels);
}

/* Mean squared step across every tile edge of img (tiles of t, wrapping), and across the rows and
 * columns in the middle of the tiles (the texture's own roughness). The texels at tile corners are
 * left out: there four diamonds meet and edge tiles do not match (the corner problem that corner
 * tiles solve). */
static void seam_steps(const struct vt_image *img, uint32_t t, double *across, double *inside)
{
    double a = 0, in = 0;
    unsigned n = 0;
    for (uint32_t k = 0; k < img->height / t; k++)
        for (uint32_t j = 0; j < img->width / t; j++) {
            uint32_t edge = k * t, prev = (edge + img->height - 1) % img->height;
            a += line_mse(img, true, prev, edge, j * t + 1, t - 2);
            in += line_mse(img, true, edge + t / 4, edge + t / 4 + 1, j * t + 1, t - 2);
            n++;
        }
    for (uint32_t k = 0; k < img->width / t; k++)
        for (uint32_t j = 0; j < img->height / t; j++) {
            uint32_t edge = k * t, prev = (edge + img->width - 1) % img->width;
            a += line_mse(img, false, prev, edge, j * t + 1, t - 2);
            in += line_mse(img, false, edge + t / 4, edge + t / 4 + 1, j * t + 1, t - 2);
            n++;
        }
    *across = a / n;
    *inside = in / n;
}

static void edge_rows_are_the_colour_patch(void)
{
    struct vt_image sample = vt_synth_photo(300, 260, 3, 11, 1.0), pack;
    struct vt_wang_params p = {64, 2, 3, false, 5, false, 0};
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(vt_wang_build(&sample, &p, &pack, NULL, &err), 0);
    VT_CHECK(pack.width == 9 * 64 && pack.height == 4 * 64);
    /* every tile whose north edge has colour c starts with the same row, and so on */
    unsigned mismatches = 0;
    for (uint32_t row = 0; row < 4; row++)
        for (uint32_t col = 0; col < 9; col++) {
            struct vts_wang_edges e;
            vts_wang_tile_edges(col, row, &e);
            /* the first tile with the same N colour, W colour */
            for (uint32_t r2 = 0; r2 < 4; r2++)
                for (uint32_t c2 = 0; c2 < 9; c2++) {
                    struct vts_wang_edges f;
                    vts_wang_tile_edges(c2, r2, &f);
                    if (f.n == e.n)
                        mismatches += memcmp(vt_image_at(&pack, col * 64, row * 64),
                                             vt_image_at(&pack, c2 * 64, r2 * 64), 64 * 3) != 0;
                    if (f.w == e.w)
                        for (uint32_t y = 1; y < 63; y++)
                            mismatches += memcmp(vt_image_at(&pack, col * 64, row * 64 + y),
                                                 vt_image_at(&pack, c2 * 64, r2 * 64 + y), 3) != 0;
                }
        }
    VT_CHECK_INT_EQ(mismatches, 0);
    /* the pack is seamless: steps across tile edges like steps inside the texture */
    double across, inside;
    seam_steps(&pack, 64, &across, &inside);
    fprintf(stderr, "pack: across %.1f inside %.1f\n", across, inside);
    VT_CHECK(across < 2 * inside + 1);
    /* a shuffled pack is not (the checker catches a wrong packing) */
    struct vt_image shuffled;
    uint32_t order[36];
    p.shuffle = true;
    p.shuffle_seed = 3;
    VT_CHECK_INT_EQ(vt_wang_build(&sample, &p, &shuffled, order, &err), 0);
    double s_across, s_inside;
    seam_steps(&shuffled, 64, &s_across, &s_inside);
    fprintf(stderr, "shuffled: across %.1f inside %.1f\n", s_across, s_inside);
    VT_CHECK(s_across > 4 * across);
    vt_image_release(&shuffled);
    vt_image_release(&pack);
    free(sample.pixels);
}

static const char *meta_get(void *user, const char *key)
{
    const char *const *kv = user;
    for (; kv[0]; kv += 2)
        if (strcmp(kv[0], key) == 0)
            return kv[1];
    return NULL;
}

/* Builds a pack, assembles an 8 x 8 tile output, checks each tile is the located pack tile and
 * the output is seamless; with order (a shuffled pack) too. */
static void check_output(bool corners, bool shuffle)
{
    struct vt_image sample = vt_synth_photo(256, 256, 3, 4, 1.0), pack, out;
    struct vt_wang_params p = {32, 2, 2, corners, 9, shuffle, 77};
    struct vts_error err = {0};
    uint32_t cols, rows, order[64], perm[16];
    vt_wang_grid(&p, &cols, &rows);
    VT_CHECK_INT_EQ(vt_wang_build(&sample, &p, &pack, shuffle ? order : NULL, &err), 0);
    vts_wang_permutation(9, 8, perm);
    struct vt_wang_info info = {corners, 2, 2, 32, cols, rows, 9, 8, perm, shuffle ? order : NULL};
    VT_CHECK_INT_EQ(vt_image_alloc(&out, 8 * 32, 8 * 32, 3, VTS_SAMPLE_U8, &err), 0);
    vt_wang_assemble(&info, &pack, 0, 0, 0, &out);
    unsigned bad = 0;
    for (uint32_t y = 0; y < 8; y++)
        for (uint32_t x = 0; x < 8; x++) {
            uint32_t col, row;
            vt_wang_info_locate(&info, x, y, &col, &row);
            for (uint32_t r = 0; r < 32; r++)
                bad += memcmp(vt_image_at(&out, x * 32, y * 32 + r),
                              vt_image_at(&pack, col * 32, row * 32 + r), 32 * 3) != 0;
        }
    VT_CHECK_INT_EQ(bad, 0);
    double across, inside;
    seam_steps(&out, 32, &across, &inside); /* the hash repeats every 8 tiles: wraps too */
    VT_CHECK(across < 2 * inside + 1);
    /* an offset region is the same texels */
    struct vt_image part;
    vt_image_alloc(&part, 40, 30, 3, VTS_SAMPLE_U8, &err);
    vt_wang_assemble(&info, &pack, 0, 8 * 32 + 50, 8 * 32 * 3 + 70, &part);
    for (uint32_t r = 0; r < 30; r++)
        VT_CHECK(memcmp(vt_image_at(&part, 0, r), vt_image_at(&out, 50, 70 + r), 40 * 3) == 0);
    vt_image_release(&part);
    vt_image_release(&out);
    vt_image_release(&pack);
    free(sample.pixels);
}

static void assembled_output_is_seamless(void)
{
    check_output(false, false);
    check_output(false, true);
    check_output(true, false);
}

static void metadata_parses_and_refuses(void)
{
    const char *good[] = {"wang.kind", "edge", "wang.colours", "2x3",   "wang.tile", "64",
                          "wang.grid", "9x4",  "wang.hash",    "2 0 1", NULL};
    struct vt_wang_info info;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(vt_wang_info_parse(meta_get, good, &info, &err), 0);
    VT_CHECK(info.kh == 2 && info.kv == 3 && info.tile_px == 64 && info.hash_n == 3);
    VT_CHECK(info.hash && info.hash[0] == 2 && !info.order);
    vt_wang_info_release(&info);
    const char *none[] = {"tool", "vt-tiles", NULL};
    VT_CHECK_INT_EQ(vt_wang_info_parse(meta_get, none, &info, &err), VTS_ERR_ARG);
    VT_CHECK_STR_CONTAINS(err.message, "not a Wang pack");
    const char *bad[][2] = {{"wang.hash", "2 0 0"},  {"wang.hash", "0 1 x"},
                            {"wang.grid", "4x4"},    {"wang.colours", "2x17"},
                            {"wang.kind", "square"}, {"wang.order", "0 1"}};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        const char *kv[14];
        memcpy(kv, good, sizeof good);
        size_t k = 0;
        while (kv[k] && strcmp(kv[k], bad[i][0]) != 0)
            k += 2;
        kv[k] = bad[i][0];
        kv[k + 1] = bad[i][1];
        if (k == 10)
            kv[12] = NULL;
        VT_CHECK_INT_EQ(vt_wang_info_parse(meta_get, kv, &info, &err), VTS_ERR_CORRUPT);
        VT_CHECK_STR_CONTAINS(err.message, bad[i][0]);
        vt_wang_info_release(&info);
    }
}

static void bad_parameters_are_refused(void)
{
    struct vt_image sample = vt_synth_photo(40, 40, 3, 1, 1.0), pack;
    struct vts_error err = {0};
    struct vt_wang_params p = {64, 2, 2, false, 1, false, 0};
    VT_CHECK_INT_EQ(vt_wang_build(&sample, &p, &pack, NULL, &err), VTS_ERR_ARG);
    VT_CHECK_STR_CONTAINS(err.message, "smaller than a patch");
    p.tile_px = 31;
    VT_CHECK_INT_EQ(vt_wang_build(&sample, &p, &pack, NULL, &err), VTS_ERR_ARG);
    p = (struct vt_wang_params){16, 2, 3, true, 1, false, 0};
    VT_CHECK_INT_EQ(vt_wang_build(&sample, &p, &pack, NULL, &err), VTS_ERR_ARG);
    VT_CHECK_STR_CONTAINS(err.message, "one colour count");
    free(sample.pixels);
}

int main(void)
{
    VT_RUN(edge_rows_are_the_colour_patch);
    VT_RUN(assembled_output_is_seamless);
    VT_RUN(metadata_parses_and_refuses);
    VT_RUN(bad_parameters_are_refused);
    return vt_test_main_result();
}
