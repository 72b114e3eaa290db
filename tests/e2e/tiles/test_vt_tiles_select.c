/* vt-tiles with the selections (docs/filters.md, "Selections"): a generated land-class map with
 * thin roads and rivers (--colour index, mode or nearest) keeps its value set at every level and
 * every level texel is one of the finer texels it covers; mode keeps the majority class that
 * nearest drops; a float32 elevation raster is exact at level 0 and its min/max pyramids bound
 * every level-0 texel each coarser texel covers; borders copy the level's neighbours; -j1 and -j2
 * give the same bytes; lossy codecs and wrong combinations are refused. Negative controls: the box
 * filter fails the value-set and bound checks. usage: test_vt_tiles_select VT-TILES VT-INFO */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "tiles_check.h"
#include "vt_test.h"
#include "vt_tiff_file.h"
#include "vts.h"

static uint32_t rng = 777;

static uint32_t next_random(void)
{
    rng = rng * 1664525u + 1013904223u;
    return rng >> 8;
}

/* ---- inputs ---- */

static const uint16_t classes[] = {3, 7, 12, 40, 41, 200, 1000, 40000, 65535};
#define ROAD  5 /* index in classes */
#define RIVER 4

/* Land classes in irregular patches (a coarse random grid, one class per 13 x 11 cell, cells
 * shifted by row), a 1-texel road every 37 columns, a 1-texel diagonal river, single-texel
 * specks; u8 maps use the classes below 256. */
static void land_classes(struct vt_image *img)
{
    uint32_t n = img->sample == VTS_SAMPLE_U8 ? 6 : 9;
    for (uint32_t y = 0; y < img->height; y++)
        for (uint32_t x = 0; x < img->width; x++) {
            uint32_t cx = (x + 5 * (y / 11)) / 13, cy = y / 11;
            uint32_t c = (cx * 2654435761u ^ cy * 40503u) % n;
            if (c == ROAD || c == RIVER)
                c = 0;
            if (x % 37 == 17)
                c = ROAD;
            if ((x + 2 * y) % 301 == 0 || (x + 2 * y) % 301 == 1)
                c = RIVER;
            if (next_random() % 97 == 0)
                c = next_random() % n;
            if (img->sample == VTS_SAMPLE_U8)
                *(uint8_t *)vt_image_at(img, x, y) = (uint8_t)classes[c];
            else
                *(uint16_t *)vt_image_at(img, x, y) = classes[c];
        }
}

/* Terrain-like heights in metres: hills, a ridge line, a cliff, noise, a few extreme spikes. */
static void elevation(struct vt_image *img)
{
    for (uint32_t y = 0; y < img->height; y++)
        for (uint32_t x = 0; x < img->width; x++) {
            float h = 800.0f * sinf((float)x * 0.013f) * cosf((float)y * 0.021f) +
                      300.0f * expf(-fabsf((float)x - 0.7f * (float)y - 100.0f) * 0.05f) +
                      (x > 2 * y ? 250.0f : 0.0f) + (float)(next_random() % 1000) * 0.01f;
            if (next_random() % 5000 == 0)
                h = next_random() % 2 ? 8848.86f : -430.5f;
            *(float *)vt_image_at(img, x, y) = h;
        }
}

static int write_tiff(const char *path, const struct vt_image *img)
{
    struct vts_error err = {0};
    struct vt_tiff_file_writer *w = vt_tiff_file_writer_create_sample(
        path, img->width, img->height, img->channels, img->sample, &err);
    int rc = w ? vt_tiff_file_writer_rows(w, img->pixels, img->height, img->stride, &err) : -1;
    if (rc == 0)
        rc = vt_tiff_file_writer_finish(w, &err);
    vt_tiff_file_writer_destroy(w);
    if (rc)
        fprintf(stderr, "%s\n", err.message);
    return rc;
}

/* ---- checks ---- */

static double texel(const struct vt_image *img, uint32_t x, uint32_t y)
{
    const void *p = vt_image_at(img, x, y);
    switch (img->sample) {
    case VTS_SAMPLE_U8:
        return *(const uint8_t *)p;
    case VTS_SAMPLE_U16:
        return *(const uint16_t *)p;
    default:
        return *(const float *)p;
    }
}

/* Texels of a level (1 channel) whose value is not in the input's set. */
static size_t outside_value_set(const struct vt_image *level, const bool *in_set)
{
    size_t bad = 0;
    for (uint32_t y = 0; y < level->height; y++)
        for (uint32_t x = 0; x < level->width; x++)
            bad += !in_set[(size_t)texel(level, x, y)];
    return bad;
}

/* Texels of coarse (a level) that are none of the finer texels (the level below) they cover. */
static size_t not_covered(const struct vt_image *fine, const struct vt_image *coarse)
{
    size_t bad = 0;
    for (uint32_t y = 0; y < coarse->height; y++)
        for (uint32_t x = 0; x < coarse->width; x++) {
            double v = texel(coarse, x, y);
            bool found = false;
            for (uint32_t fy = 2 * y; fy < 2 * y + 2 && fy < fine->height; fy++)
                for (uint32_t fx = 2 * x; fx < 2 * x + 2 && fx < fine->width; fx++)
                    found |= texel(fine, fx, fy) == v;
            bad += !found;
        }
    return bad;
}

/* Texels of level `level` (coarse) that do not bound (max: >=, else <=) every level-0 texel they
 * cover, [x << level, (x + 1) << level) clipped to level 0. */
static size_t bound_violations(const struct vt_image *level0, const struct vt_image *coarse,
                               uint32_t level, bool max)
{
    size_t bad = 0;
    for (uint32_t y = 0; y < level0->height; y++)
        for (uint32_t x = 0; x < level0->width; x++) {
            double f = texel(level0, x, y), v = texel(coarse, x >> level, y >> level);
            bad += max ? !(v >= f) : !(v <= f);
        }
    return bad;
}

/* Payload texels that differ from the level texel at their clamped position. */
static size_t border_mismatches(const struct vts_store *s, uint32_t level,
                                const struct vt_image *whole)
{
    const struct vts_geometry *g = vts_store_geometry(s);
    struct vts_level lv;
    vts_store_level(s, level, &lv);
    size_t bad = 0, tb = vt_image_texel_bytes(whole);
    for (uint32_t ty = 0; ty < lv.tiles_y; ty++)
        for (uint32_t tx = 0; tx < lv.tiles_x; tx++) {
            struct vt_image t;
            bool empty;
            if (tiles_read_payload(s, level, tx, ty, &t, &empty) != 0)
                return SIZE_MAX;
            for (uint32_t py = 0; py < t.height; py++)
                for (uint32_t px = 0; px < t.width; px++) {
                    int64_t x = (int64_t)tx * g->tile_content_px - g->border_px + px;
                    int64_t y = (int64_t)ty * g->tile_content_px - g->border_px + py;
                    x = x < 0 ? 0 : (x >= lv.width ? lv.width - 1 : x);
                    y = y < 0 ? 0 : (y >= lv.height ? lv.height - 1 : y);
                    bad += memcmp(vt_image_at(&t, px, py),
                                  vt_image_at(whole, (uint32_t)x, (uint32_t)y), tb) != 0;
                }
            vt_image_release(&t);
        }
    return bad;
}

/* Builds input into name.vts with args and reads every level; returns the store (NULL on
 * failure) and levels[0 .. level_count - 1]. */
static struct vts_store *build(const char *input, const char *name, const char *args,
                               struct vt_image *levels, uint32_t max_levels)
{
    int rc = tiles_run(input, tiles_path(name), args);
    VT_CHECK_INT_EQ(rc, 0);
    if (rc) {
        fprintf(stderr, "vt-tiles %s: %s\n", args, tiles_stderr());
        return NULL;
    }
    struct vts_store *s = vts_open(tiles_path(name), NULL);
    VT_CHECK(s != NULL);
    if (!s)
        return NULL;
    uint32_t n = vts_store_geometry(s)->level_count;
    VT_CHECK(n >= 4 && n <= max_levels);
    for (uint32_t l = 0; l < n && l < max_levels; l++)
        VT_CHECK_INT_EQ(tiles_read_level(s, l, &levels[l]), 0);
    return s;
}

static void release_levels(struct vts_store *s, struct vt_image *levels)
{
    uint32_t n = s ? vts_store_geometry(s)->level_count : 0;
    for (uint32_t l = 0; l < n; l++)
        vt_image_release(&levels[l]);
    vts_close(s);
}

/* ---- tests ---- */

#define MAX_LEVELS 16

static void land_classes_keep_their_value_set_at_every_level(void)
{
    static const uint32_t samples[] = {VTS_SAMPLE_U8, VTS_SAMPLE_U16};
    for (int si = 0; si < 2; si++) {
        struct vt_image in;
        VT_CHECK_INT_EQ(vt_image_alloc(&in, 1001, 619, 1, samples[si], NULL), 0);
        land_classes(&in);
        char png[512]; /* tiles_path() rotates its buffers */
        snprintf(png, sizeof png, "%s", tiles_path("classes.png"));
        VT_CHECK_INT_EQ(tiles_write_png(png, &in), 0);
        bool *in_set = calloc(65536, 1);
        for (uint32_t y = 0; y < in.height; y++)
            for (uint32_t x = 0; x < in.width; x++)
                in_set[(size_t)texel(&in, x, y)] = true;
        static const char *const args[] = {"--colour index --tile-size 32",
                                           "--colour index --filter nearest --tile-size 32",
                                           "--colour data --filter box --tile-size 32"};
        for (int a = 0; a < 3; a++) {
            struct vt_image lv[MAX_LEVELS];
            struct vts_store *s = build(png, "classes.vts", args[a], lv, MAX_LEVELS);
            if (!s)
                continue;
            uint32_t n = vts_store_geometry(s)->level_count;
            VT_CHECK(memcmp(lv[0].pixels, in.pixels, in.stride * in.height) == 0);
            size_t outside = 0, uncovered = 0;
            for (uint32_t l = 0; l < n; l++) {
                outside += outside_value_set(&lv[l], in_set);
                if (l > 0)
                    uncovered += not_covered(&lv[l - 1], &lv[l]);
                VT_CHECK_INT_EQ(border_mismatches(s, l, &lv[l]), 0);
            }
            if (a < 2) {
                VT_CHECK_INT_EQ(outside, 0);
                VT_CHECK_INT_EQ(uncovered, 0);
                const char *filter = vts_store_meta_find(s, "filter");
                VT_CHECK_STR_EQ(filter, a == 0 ? "mode" : "nearest");
                VT_CHECK_STR_EQ(vts_store_meta_find(s, "colour"), "index");
                VT_CHECK_INT_EQ(vts_store_layer(s, 0)->colour, VTS_COLOUR_DATA);
                VT_CHECK(vts_store_layer(s, 0)->codec == VTS_CODEC_PNG);
            } else { /* negative control: the box averages classes into new values */
                VT_CHECK(outside > 0 && uncovered > 0);
            }
            release_levels(s, lv);
        }
        free(in_set);
        vt_image_release(&in);
    }
}

/* Every 2x2 block: class 3 at its top-left, class 7 in the other three. */
static void mode_keeps_the_majority_that_nearest_drops(void)
{
    struct vt_image in;
    VT_CHECK_INT_EQ(vt_image_alloc(&in, 302, 204, 1, VTS_SAMPLE_U8, NULL), 0);
    for (uint32_t y = 0; y < in.height; y++)
        for (uint32_t x = 0; x < in.width; x++)
            *(uint8_t *)vt_image_at(&in, x, y) = x % 2 == 0 && y % 2 == 0 ? 3 : 7;
    VT_CHECK_INT_EQ(tiles_write_png(tiles_path("majority.png"), &in), 0);
    struct vt_image mode[MAX_LEVELS], nearest[MAX_LEVELS];
    char png[512];
    snprintf(png, sizeof png, "%s", tiles_path("majority.png"));
    struct vts_store *sm =
        build(png, "mode.vts", "--colour index --tile-size 16", mode, MAX_LEVELS);
    struct vts_store *sn = build(
        png, "nearest.vts", "--colour index --filter nearest --tile-size 16", nearest, MAX_LEVELS);
    if (sm && sn) {
        size_t mode7 = 0, nearest7 = 0, n = (size_t)mode[1].width * mode[1].height;
        for (uint32_t y = 0; y < mode[1].height; y++)
            for (uint32_t x = 0; x < mode[1].width; x++) {
                mode7 += texel(&mode[1], x, y) == 7;
                nearest7 += texel(&nearest[1], x, y) == 7;
            }
        VT_CHECK_INT_EQ(mode7, n);    /* the majority class everywhere */
        VT_CHECK_INT_EQ(nearest7, 0); /* gone: every top-left texel is 3 */
    }
    release_levels(sm, mode);
    release_levels(sn, nearest);
    vt_image_release(&in);
}

static void float_elevation_is_exact_and_min_max_bound_every_texel(void)
{
    struct vt_image in;
    VT_CHECK_INT_EQ(vt_image_alloc(&in, 777, 501, 1, VTS_SAMPLE_F32, NULL), 0);
    elevation(&in);
    char tif[512];
    snprintf(tif, sizeof tif, "%s", tiles_path("dem.tif"));
    VT_CHECK_INT_EQ(write_tiff(tif, &in), 0);
    static const char *const args[] = {"--filter min --tile-size 32", "--filter max --tile-size 32",
                                       "--colour data --filter box --tile-size 32"};
    for (int a = 0; a < 3; a++) {
        struct vt_image lv[MAX_LEVELS];
        struct vts_store *s = build(tif, "dem.vts", args[a], lv, MAX_LEVELS);
        if (!s)
            continue;
        const struct vts_layer *L = vts_store_layer(s, 0);
        VT_CHECK(L->codec == VTS_CODEC_RAW && L->sample == VTS_SAMPLE_F32 &&
                 L->colour == VTS_COLOUR_DATA);
        VT_CHECK(memcmp(lv[0].pixels, in.pixels, in.stride * in.height) == 0);
        uint32_t n = vts_store_geometry(s)->level_count;
        size_t bad = 0, fine_bad = 0, uncovered = 0;
        for (uint32_t l = 1; l < n; l++) {
            bad += bound_violations(&lv[0], &lv[l], l, a == 1);
            /* level l also bounds level l - 1 texel by texel */
            for (uint32_t y = 0; y < lv[l - 1].height; y++)
                for (uint32_t x = 0; x < lv[l - 1].width; x++) {
                    double f = texel(&lv[l - 1], x, y), v = texel(&lv[l], x / 2, y / 2);
                    fine_bad += a == 1 ? !(v >= f) : !(v <= f);
                }
            uncovered += not_covered(&lv[l - 1], &lv[l]);
            VT_CHECK_INT_EQ(border_mismatches(s, l, &lv[l]), 0);
        }
        if (a < 2) {
            VT_CHECK_INT_EQ(bad, 0);
            VT_CHECK_INT_EQ(fine_bad, 0);
            VT_CHECK_INT_EQ(uncovered, 0);
            /* the top level is the extreme of the whole raster */
            double ext = texel(&in, 0, 0);
            for (uint32_t y = 0; y < in.height; y++)
                for (uint32_t x = 0; x < in.width; x++)
                    ext = a == 1 ? fmax(ext, texel(&in, x, y)) : fmin(ext, texel(&in, x, y));
            struct vt_image *top = &lv[n - 1];
            double top_ext = texel(top, 0, 0);
            for (uint32_t y = 0; y < top->height; y++)
                for (uint32_t x = 0; x < top->width; x++)
                    top_ext =
                        a == 1 ? fmax(top_ext, texel(top, x, y)) : fmin(top_ext, texel(top, x, y));
            VT_CHECK(top_ext == ext);
        } else { /* negative control: box means lie above some of the texels they cover */
            VT_CHECK(bad > 0 && fine_bad > 0);
        }
        release_levels(s, lv);
    }
    vt_image_release(&in);
}

static void selections_do_not_depend_on_threads(void)
{
    char tif[512], png[512];
    snprintf(tif, sizeof tif, "%s", tiles_path("dem.tif"));
    snprintf(png, sizeof png, "%s", tiles_path("classes.png"));
    VT_CHECK_INT_EQ(tiles_run(tif, tiles_path("j1.vts"), "--filter max --tile-size 16 -j1"), 0);
    VT_CHECK_INT_EQ(tiles_run(tif, tiles_path("j2.vts"), "--filter max --tile-size 16 -j2"), 0);
    VT_CHECK(tiles_same_file(tiles_path("j1.vts"), tiles_path("j2.vts")));
    VT_CHECK_INT_EQ(tiles_run(png, tiles_path("c1.vts"), "--colour index --tile-size 16 -j1"), 0);
    VT_CHECK_INT_EQ(tiles_run(png, tiles_path("c2.vts"), "--colour index --tile-size 16 -j2"), 0);
    VT_CHECK(tiles_same_file(tiles_path("c1.vts"), tiles_path("c2.vts")));
    /* and a different filter does change them (the comparison can fail) */
    VT_CHECK_INT_EQ(tiles_run(png, tiles_path("c3.vts"),
                              "--colour index --filter nearest "
                              "--tile-size 16 -j2"),
                    0);
    VT_CHECK(!tiles_same_file(tiles_path("c1.vts"), tiles_path("c3.vts")));
}

static void lossy_codecs_and_wrong_combinations_are_refused(void)
{
    char tif[512], png[512], out[512];
    snprintf(tif, sizeof tif, "%s", tiles_path("dem.tif"));
    snprintf(png, sizeof png, "%s", tiles_path("classes.png"));
    snprintf(out, sizeof out, "%s", tiles_path("refused.vts"));
    struct {
        const char *input, *args, *message;
    } cases[] = {
        {png, "--colour index --codec jpeg", "--filter mode keeps exact values: codec jpeg"},
        {png, "--filter min --codec bc1", "--filter min keeps exact values: codec bc1"},
        {tif, "--filter max --codec png", "would store f32 samples converted (use raw)"},
        {png, "--colour index --filter box", "--colour index needs --filter mode or nearest"},
        {png, "--filter mode --colour srgb", "use --colour data or index, not srgb"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        VT_CHECK_INT_EQ(tiles_run(cases[i].input, out, cases[i].args), 2);
        VT_CHECK_STR_CONTAINS(tiles_stderr(), cases[i].message);
        VT_CHECK(access(out, F_OK) != 0);
    }
}

int main(int argc, char **argv)
{
    int rc = tiles_start(argc, argv, "test_vt_tiles_select");
    if (rc != 0)
        return rc;
    VT_RUN(land_classes_keep_their_value_set_at_every_level);
    VT_RUN(mode_keeps_the_majority_that_nearest_drops);
    VT_RUN(float_elevation_is_exact_and_min_max_bound_every_texel);
    VT_RUN(selections_do_not_depend_on_threads);
    VT_RUN(lossy_codecs_and_wrong_combinations_are_refused);
    tiles_finish(vt_test_failures != 0);
    return vt_test_main_result();
}
