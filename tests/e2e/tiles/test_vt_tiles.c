/* vt-tiles end to end: runs the tool on generated images and checks the stores it writes texel by
 * texel: level sizes, borders equal to neighbours (clamp and wrap), box levels against a double
 * reference, linear-light sRGB, premultiplied alpha, precision of 16-bit and float inputs, normal
 * lengths, empty tiles, determinism across -j, and bad input; vt-info --verify passes on every
 * store. usage: test_vt_tiles VT-TILES VT-INFO */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "tiles_check.h"
#include "vt_synth_images.h"
#include "vt_test.h"

static uint32_t rng = 12345;

static uint32_t next_random(void)
{
    rng = rng * 1664525u + 1013904223u;
    return rng >> 8;
}

static void fill_random(struct vt_image *img)
{
    size_t n = (size_t)img->width * img->height * vt_image_texel_bytes(img);
    for (size_t i = 0; i < n; i++)
        ((unsigned char *)img->pixels)[i] = (unsigned char)next_random();
}

static int64_t clamp64(int64_t v, int64_t lo, int64_t hi)
{
    return v < lo ? lo : (v > hi ? hi : v);
}

static int64_t wrap64(int64_t v, int64_t n)
{
    return ((v % n) + n) % n;
}

/* Every payload texel equals the level texel at its (clamped or wrapped) position, and the
 * stitched level 0 equals the input. */
static void check_borders(const struct vts_store *s, const struct vt_image *input, bool wrap)
{
    const struct vts_geometry *g = vts_store_geometry(s);
    int64_t c = g->tile_content_px, b = g->border_px;
    for (uint32_t level = 0; level < g->level_count; level++) {
        struct vts_level lv;
        vts_store_level(s, level, &lv);
        struct vt_image whole;
        VT_CHECK_INT_EQ(tiles_read_level(s, level, &whole), 0);
        size_t tb = vt_image_texel_bytes(&whole);
        if (level == 0 && input)
            for (uint32_t y = 0; y < input->height; y++)
                VT_CHECK(memcmp(vt_image_at(&whole, 0, y), vt_image_at(input, 0, y),
                                tb * input->width) == 0);
        int bad = 0;
        for (uint32_t ty = 0; ty < lv.tiles_y; ty++)
            for (uint32_t tx = 0; tx < lv.tiles_x; tx++) {
                struct vt_image t;
                bool empty;
                VT_CHECK_INT_EQ(tiles_read_payload(s, level, tx, ty, &t, &empty), 0);
                for (uint32_t py = 0; py < t.height; py++)
                    for (uint32_t px = 0; px < t.width; px++) {
                        int64_t x = tx * c - b + px, y = ty * c - b + py;
                        x = wrap ? wrap64(x, lv.width) : clamp64(x, 0, lv.width - 1);
                        y = wrap ? wrap64(y, lv.height) : clamp64(y, 0, lv.height - 1);
                        bad += memcmp(vt_image_at(&t, px, py),
                                      vt_image_at(&whole, (uint32_t)x, (uint32_t)y), tb) != 0;
                    }
                vt_image_release(&t);
            }
        VT_CHECK_INT_EQ(bad, 0);
        vt_image_release(&whole);
    }
}

static void level_sizes_and_borders_for_odd_inputs(void)
{
    static const uint32_t sizes[][2] = {{1, 1}, {3, 5}, {257, 129}, {4097, 3}, {1000, 600}};
    for (size_t i = 0; i < sizeof sizes / sizeof sizes[0]; i++) {
        uint32_t w = sizes[i][0], h = sizes[i][1];
        struct vt_image img;
        vt_image_alloc(&img, w, h, 3, VTS_SAMPLE_U8, NULL);
        fill_random(&img);
        VT_CHECK_INT_EQ(tiles_write_png(tiles_path("odd.png"), &img), 0);
        VT_CHECK_INT_EQ(
            tiles_run(tiles_path("odd.png"), tiles_path("odd.vts"),
                      "--tile-size 64 --keep payload --border 2 --codec raw --filter triangle"),
            0);
        struct vts_store *s = vts_open(tiles_path("odd.vts"), NULL);
        VT_CHECK(s != NULL);
        if (s) {
            const struct vts_geometry *g = vts_store_geometry(s);
            VT_CHECK_INT_EQ(g->width, w);
            VT_CHECK_INT_EQ(g->height, h);
            VT_CHECK_INT_EQ(g->tile_content_px, 60);
            VT_CHECK_INT_EQ(g->level_count, vts_full_level_count(w, h, 60));
            struct vts_level top;
            vts_store_level(s, g->level_count - 1, &top);
            VT_CHECK(top.width <= 60 && top.height <= 60);
            VT_CHECK_INT_EQ(top.width,
                            (w + (1u << (g->level_count - 1)) - 1) >> (g->level_count - 1));
            VT_CHECK_INT_EQ(vts_store_layer(s, 0)->channels, 3);
            check_borders(s, &img, false);
            vts_close(s);
        }
        vt_image_release(&img);
    }
}

static void wrapped_borders_come_from_the_opposite_edge(void)
{
    struct vt_image img;
    vt_image_alloc(&img, 128, 64, 4, VTS_SAMPLE_U8, NULL);
    fill_random(&img);
    for (uint32_t i = 0; i < 128 * 64; i++)
        ((unsigned char *)img.pixels)[i * 4 + 3] = 255; /* opaque: alpha dropped */
    tiles_write_png(tiles_path("wrap.png"), &img);
    VT_CHECK_INT_EQ(tiles_run(tiles_path("wrap.png"), tiles_path("wrap.vts"),
                              "--tile-size 36 --border 2 --codec raw --wrap"),
                    0);
    struct vts_store *s = vts_open(tiles_path("wrap.vts"), NULL);
    VT_CHECK(s != NULL);
    if (s) {
        VT_CHECK_INT_EQ(vts_store_layer(s, 0)->channels, 3);
        VT_CHECK(vts_store_geometry(s)->flags & VTS_STORE_WRAP_X);
        check_borders(s, NULL, true);
        vts_close(s);
    }
    vt_image_release(&img);
}

/* Box levels of a data image equal a double-precision mean of 2x2 finer texels (clamped at odd
 * edges), to the nearest integer. */
static void box_levels_match_a_double_reference(void)
{
    uint32_t w = 301, h = 203;
    struct vt_image img;
    vt_image_alloc(&img, w, h, 3, VTS_SAMPLE_U8, NULL);
    fill_random(&img);
    tiles_write_png(tiles_path("box.png"), &img);
    VT_CHECK_INT_EQ(tiles_run(tiles_path("box.png"), tiles_path("box.vts"),
                              "--tile-size 64 --border 1 --codec raw --colour data --filter box"),
                    0);
    double *ref = malloc(sizeof(double) * w * h * 3), *next = malloc(sizeof(double) * w * h * 3);
    for (size_t i = 0; i < (size_t)w * h * 3; i++)
        ref[i] = ((unsigned char *)img.pixels)[i] / 255.0;
    struct vts_store *s = vts_open(tiles_path("box.vts"), NULL);
    VT_CHECK(s != NULL);
    uint32_t lw = w, lh = h;
    for (uint32_t level = 1; s && level < vts_store_geometry(s)->level_count; level++) {
        uint32_t nw = (lw + 1) / 2, nh = (lh + 1) / 2;
        for (uint32_t y = 0; y < nh; y++)
            for (uint32_t x = 0; x < nw; x++)
                for (int c = 0; c < 3; c++) {
                    uint32_t x0 = 2 * x, x1 = 2 * x + 1 < lw ? 2 * x + 1 : lw - 1;
                    uint32_t y0 = 2 * y, y1 = 2 * y + 1 < lh ? 2 * y + 1 : lh - 1;
                    next[((size_t)y * nw + x) * 3 + c] =
                        (ref[((size_t)y0 * lw + x0) * 3 + c] + ref[((size_t)y0 * lw + x1) * 3 + c] +
                         ref[((size_t)y1 * lw + x0) * 3 + c] +
                         ref[((size_t)y1 * lw + x1) * 3 + c]) /
                        4;
                }
        double *t = ref;
        ref = next;
        next = t;
        lw = nw;
        lh = nh;
        struct vt_image got;
        VT_CHECK_INT_EQ(tiles_read_level(s, level, &got), 0);
        int off = 0;
        for (uint32_t y = 0; y < lh; y++)
            for (uint32_t x = 0; x < lw; x++)
                for (int c = 0; c < 3; c++) {
                    double want = ref[((size_t)y * lw + x) * 3 + c] * 255.0;
                    off += fabs(((unsigned char *)vt_image_at(&got, x, y))[c] - want) > 0.5 + 1e-3;
                }
        VT_CHECK_INT_EQ(off, 0);
        vt_image_release(&got);
    }
    vts_close(s);
    free(ref);
    free(next);
    vt_image_release(&img);
}

static void srgb_checkerboard_averages_to_188(void)
{
    struct vt_image img;
    vt_image_alloc(&img, 64, 64, 3, VTS_SAMPLE_U8, NULL);
    for (uint32_t y = 0; y < 64; y++)
        for (uint32_t x = 0; x < 64; x++)
            memset(vt_image_at(&img, x, y), (x + y) % 2 ? 255 : 0, 3);
    tiles_write_png(tiles_path("check.png"), &img);
    VT_CHECK_INT_EQ(tiles_run(tiles_path("check.png"), tiles_path("check.vts"),
                              "--tile-size 20 --border 2 --codec png --filter box"),
                    0);
    struct vts_store *s = vts_open(tiles_path("check.vts"), NULL);
    VT_CHECK(s != NULL);
    if (s) {
        struct vt_image l1;
        VT_CHECK_INT_EQ(tiles_read_level(s, 1, &l1), 0);
        int not188 = 0;
        for (size_t i = 0; i < 32 * 32 * 3; i++)
            not188 += ((unsigned char *)l1.pixels)[i] != 188;
        VT_CHECK_INT_EQ(not188, 0);
        vt_image_release(&l1);
        vts_close(s);
    }
    vt_image_release(&img);
}

/* Red on the left 33 columns, fully transparent black on the right: reduced levels keep red,
 * with partial alpha at the boundary, and no darkened colour anywhere. */
static void transparent_half_leaves_no_dark_fringe(void)
{
    struct vt_image img;
    vt_image_alloc(&img, 128, 64, 4, VTS_SAMPLE_U8, NULL);
    for (uint32_t y = 0; y < 64; y++)
        for (uint32_t x = 0; x < 33; x++) {
            unsigned char *p = vt_image_at(&img, x, y);
            p[0] = 255;
            p[3] = 255;
        }
    tiles_write_png(tiles_path("fringe.png"), &img);
    VT_CHECK_INT_EQ(tiles_run(tiles_path("fringe.png"), tiles_path("fringe.vts"),
                              "--tile-size 32 --border 2 --filter triangle"),
                    0);
    struct vts_store *s = vts_open(tiles_path("fringe.vts"), NULL);
    VT_CHECK(s != NULL);
    if (!s)
        return;
    VT_CHECK_INT_EQ(vts_store_layer(s, 0)->channels, 4);
    VT_CHECK_INT_EQ(vts_store_layer(s, 0)->codec, VTS_CODEC_PNG); /* auto: png for alpha */
    int dark = 0, partial = 0;
    for (uint32_t level = 1; level < vts_store_geometry(s)->level_count; level++) {
        struct vt_image l;
        VT_CHECK_INT_EQ(tiles_read_level(s, level, &l), 0);
        for (uint32_t y = 0; y < l.height; y++)
            for (uint32_t x = 0; x < l.width; x++) {
                const unsigned char *p = vt_image_at(&l, x, y);
                if (p[3] > 0)
                    dark += p[0] != 255 || p[1] != 0 || p[2] != 0;
                partial += p[3] > 0 && p[3] < 255;
            }
        vt_image_release(&l);
    }
    VT_CHECK_INT_EQ(dark, 0);
    VT_CHECK(partial > 0);
    /* level-0 tiles entirely in the transparent part are stored as empty */
    struct vts_tile_entry e;
    VT_CHECK_INT_EQ(vts_store_tile(s, 0, 0, 3, 0, &e, NULL), 0);
    VT_CHECK_INT_EQ(e.length, 0);
    VT_CHECK_INT_EQ(vts_store_tile(s, 0, 0, 0, 0, &e, NULL), 0);
    VT_CHECK(e.length > 0);
    vts_close(s);
    vt_image_release(&img);
}

static void sixteen_bit_and_float_inputs_keep_their_precision(void)
{
    struct vt_image img;
    vt_image_alloc(&img, 150, 70, 1, VTS_SAMPLE_U16, NULL);
    fill_random(&img);
    tiles_write_png(tiles_path("u16.png"), &img);
    VT_CHECK_INT_EQ(tiles_run(tiles_path("u16.png"), tiles_path("u16.vts"),
                              "--tile-size 64 --border 2 --codec raw"),
                    0);
    struct vts_store *s = vts_open(tiles_path("u16.vts"), NULL);
    VT_CHECK(s != NULL);
    if (s) {
        VT_CHECK_INT_EQ(vts_store_layer(s, 0)->sample, VTS_SAMPLE_U16);
        check_borders(s, &img, false);
        vts_close(s);
    }
    vt_image_release(&img);

    struct vt_synth_image_options o;
    vt_synth_image_defaults(&o);
    o.format = VT_SYNTH_TIFF;
    o.width = 97;
    o.height = 61;
    o.channels = 3;
    o.sample = VTS_SAMPLE_F32;
    struct vts_error err;
    VT_CHECK_INT_EQ(vt_synth_image_write(tiles_path("f32.tif"), &o, &err), 0);
    VT_CHECK_INT_EQ(
        tiles_run(tiles_path("f32.tif"), tiles_path("f32.vts"), "--tile-size 32 --border 1"), 0);
    s = vts_open(tiles_path("f32.vts"), NULL);
    VT_CHECK(s != NULL);
    if (s) {
        VT_CHECK_INT_EQ(vts_store_layer(s, 0)->codec, VTS_CODEC_RAW); /* auto: raw for float */
        VT_CHECK_INT_EQ(vts_store_layer(s, 0)->sample, VTS_SAMPLE_F32);
        VT_CHECK_INT_EQ(vts_store_layer(s, 0)->colour, VTS_COLOUR_LINEAR);
        vt_image_alloc(&img, 97, 61, 3, VTS_SAMPLE_F32, NULL);
        vt_synth_image_expected(&o, 0, 0, &img);
        check_borders(s, &img, false);
        vt_image_release(&img);
        vts_close(s);
    }
}

/* OpenEXR RGBA is premultiplied already: filtered as is (not premultiplied twice) and the layer
 * says so; level 1 is then the plain box mean of the stored values. */
static void premultiplied_exr_is_not_premultiplied_again(void)
{
    struct vt_synth_image_options o;
    vt_synth_image_defaults(&o);
    o.format = VT_SYNTH_EXR;
    o.width = 64;
    o.height = 32;
    o.channels = 4;
    o.sample = VTS_SAMPLE_F32;
    o.compression = VT_SYNTH_EXR_NONE;
    struct vts_error err;
    VT_CHECK_INT_EQ(vt_synth_image_write(tiles_path("pm.exr"), &o, &err), 0);
    VT_CHECK_INT_EQ(tiles_run(tiles_path("pm.exr"), tiles_path("pm.vts"),
                              "--tile-size 16 --border 1 --codec raw --filter box"),
                    0);
    struct vts_store *s = vts_open(tiles_path("pm.vts"), NULL);
    VT_CHECK(s != NULL);
    if (!s)
        return;
    VT_CHECK(vts_store_layer(s, 0)->flags & VTS_LAYER_PREMULTIPLIED);
    struct vt_image l0, l1;
    VT_CHECK_INT_EQ(tiles_read_level(s, 0, &l0), 0);
    VT_CHECK_INT_EQ(tiles_read_level(s, 1, &l1), 0);
    int off = 0;
    for (uint32_t y = 0; y < l1.height; y++)
        for (uint32_t x = 0; x < l1.width; x++)
            for (int c = 0; c < 4; c++) {
                double sum = 0;
                for (int k = 0; k < 4; k++)
                    sum += ((float *)vt_image_at(&l0, 2 * x + k % 2, 2 * y + k / 2))[c];
                off += fabs(((float *)vt_image_at(&l1, x, y))[c] - sum / 4) > 1e-6;
            }
    VT_CHECK_INT_EQ(off, 0);
    vt_image_release(&l0);
    vt_image_release(&l1);
    vts_close(s);
}

static void normal_map_mips_stay_unit_length(void)
{
    struct vt_image img;
    vt_image_alloc(&img, 128, 96, 3, VTS_SAMPLE_U8, NULL);
    for (uint32_t y = 0; y < 96; y++)
        for (uint32_t x = 0; x < 128; x++) {
            double a = (next_random() % 1000) / 1000.0 * 6.2832, t = 0.2 + (x % 7) * 0.1;
            double n[3] = {sin(t) * cos(a), sin(t) * sin(a), cos(t)};
            for (int c = 0; c < 3; c++)
                ((unsigned char *)vt_image_at(&img, x, y))[c] =
                    (unsigned char)lround((n[c] * 0.5 + 0.5) * 255);
        }
    tiles_write_png(tiles_path("normal.png"), &img);
    VT_CHECK_INT_EQ(tiles_run(tiles_path("normal.png"), tiles_path("normal.vts"),
                              "--tile-size 32 --border 2 --colour normal --filter lanczos3"),
                    0);
    struct vts_store *s = vts_open(tiles_path("normal.vts"), NULL);
    VT_CHECK(s != NULL);
    for (uint32_t level = 1; s && level < vts_store_geometry(s)->level_count; level++) {
        struct vt_image l;
        VT_CHECK_INT_EQ(tiles_read_level(s, level, &l), 0);
        int off = 0;
        for (uint32_t y = 0; y < l.height; y++)
            for (uint32_t x = 0; x < l.width; x++) {
                const unsigned char *p = vt_image_at(&l, x, y);
                double len2 = 0;
                for (int c = 0; c < 3; c++)
                    len2 += pow(p[c] / 255.0 * 2 - 1, 2);
                off += fabs(sqrt(len2) - 1) > 0.01;
            }
        VT_CHECK_INT_EQ(off, 0);
        vt_image_release(&l);
    }
    vts_close(s);
    vt_image_release(&img);
}

static void output_does_not_depend_on_threads(void)
{
    struct vt_image img;
    vt_image_alloc(&img, 1000, 600, 3, VTS_SAMPLE_U8, NULL);
    fill_random(&img);
    tiles_write_png(tiles_path("det.png"), &img);
    const char *args1 = "--tile-size 64 --border 4 --filter lanczos3 --codec png -j 1";
    const char *args3 = "--tile-size 64 --border 4 --filter lanczos3 --codec png -j 3";
    VT_CHECK_INT_EQ(tiles_run(tiles_path("det.png"), tiles_path("det1.vts"), args1), 0);
    VT_CHECK_INT_EQ(tiles_run(tiles_path("det.png"), tiles_path("det3.vts"), args3), 0);
    VT_CHECK_INT_EQ(tiles_run(tiles_path("det.png"), tiles_path("det1b.vts"), args1), 0);
    VT_CHECK(tiles_same_file(tiles_path("det1.vts"), tiles_path("det3.vts")));
    VT_CHECK(tiles_same_file(tiles_path("det1.vts"), tiles_path("det1b.vts")));
    vt_image_release(&img);
}

static void bad_input_fails_cleanly_without_output(void)
{
    struct vt_image img;
    vt_image_alloc(&img, 300, 300, 3, VTS_SAMPLE_U8, NULL);
    fill_random(&img);
    tiles_write_png(tiles_path("whole.png"), &img);
    vt_image_release(&img);
    char cmd[1200];
    snprintf(cmd, sizeof cmd, "head -c 20000 '%s' > '%s'", tiles_path("whole.png"),
             tiles_path("cut.png"));
    VT_CHECK(system(cmd) == 0);
    VT_CHECK_INT_EQ(tiles_run(tiles_path("cut.png"), tiles_path("cut.vts"), ""), 1);
    VT_CHECK_STR_CONTAINS(tiles_stderr(), "vt-tiles: ");
    VT_CHECK_STR_CONTAINS(tiles_stderr(), "cut.png");
    VT_CHECK(access(tiles_path("cut.vts"), F_OK) != 0);
    VT_CHECK_INT_EQ(tiles_run(tiles_path("whole.png"), tiles_path("big.vts"), "--max-pixels 1000"),
                    1);
    VT_CHECK_STR_CONTAINS(tiles_stderr(), "whole.png");
    VT_CHECK(access(tiles_path("big.vts"), F_OK) != 0);
    VT_CHECK_INT_EQ(tiles_run(tiles_path("absent.png"), tiles_path("absent.vts"), ""), 1);
    VT_CHECK_STR_CONTAINS(tiles_stderr(), "absent.png");
    VT_CHECK_INT_EQ(tiles_run(tiles_path("whole.png"), tiles_path("x.vts"), "--filter sharp"), 2);
    VT_CHECK_STR_CONTAINS(tiles_stderr(), "--filter");
    VT_CHECK_INT_EQ(tiles_run(tiles_path("whole.png"), tiles_path("x.vts"), "--tile-size 4"), 2);
    VT_CHECK(access(tiles_path("x.vts"), F_OK) != 0);
}

/* SIGINT in the middle of a run: no output, no hidden temporary left, an old output intact. The
 * signal goes once vt-tiles is seen writing (its unnamed spool, or a hidden temporary of sig.vts,
 * open in the output directory: /proc/PID/fd), not after a fixed 0.5 s: a loaded machine may not
 * have set the tool's handler by then (a background job starts with SIGINT ignored, so the signal
 * is lost and the run finishes), a fast one may have finished the run. */
static void interrupted_run_leaves_nothing_behind(void)
{
    struct vt_image img;
    vt_image_alloc(&img, 2500, 2500, 3, VTS_SAMPLE_U8, NULL);
    fill_random(&img);
    tiles_write_png(tiles_path("sig.png"), &img);
    vt_image_release(&img);
    FILE *old = fopen(tiles_path("sig.vts"), "w");
    fputs("previous output", old);
    fclose(old);
    char cmd[4096];
    snprintf(cmd, sizeof cmd,
             "'%s' '%s' -o '%s' -q --codec png --mode best -j 1 & pid=$!; "
             "dir=$(cd '%s' && pwd -P); seen=0; i=0; "
             "while [ $i -lt 30000 ]; do " /* 300 s: only stops a hung tool */
             "  if [ -n \"$(find /proc/$pid/fd -maxdepth 1 \\( -lname \"$dir/#*\" -o "
             "-lname \"$dir/.sig.vts.*\" \\) -print -quit 2>/dev/null)\" ]; then "
             "    kill -INT $pid; seen=1; break; "
             "  fi; "
             "  state=$(cut -d ' ' -f 3 /proc/$pid/stat 2>/dev/null); "
             "  if [ -z \"$state\" ] || [ \"$state\" = Z ]; then break; fi; "
             "  sleep 0.01; i=$((i + 1)); "
             "done; "
             "wait $pid; echo $? $seen > '%s'",
             tiles_tool, tiles_path("sig.png"), tiles_path("sig.vts"), tiles_dir,
             tiles_path("sig.status"));
    VT_CHECK(system(cmd) == 0);
    FILE *f = fopen(tiles_path("sig.status"), "r");
    int status = -1, seen = 0;
    VT_CHECK(f && fscanf(f, "%d %d", &status, &seen) == 2);
    if (f)
        fclose(f);
    VT_CHECK_INT_EQ(seen, 1);         /* caught writing */
    VT_CHECK_INT_EQ(status, 128 + 2); /* died of SIGINT, not finished */
    char text[32] = {0};
    f = fopen(tiles_path("sig.vts"), "r");
    VT_CHECK(f && fgets(text, sizeof text, f));
    if (f)
        fclose(f);
    VT_CHECK(strcmp(text, "previous output") == 0);
    snprintf(cmd, sizeof cmd, "ls -a '%s' | grep -c '^\\.sig\\.vts\\.' > '%s'", tiles_dir,
             tiles_path("sig.count"));
    VT_CHECK(system(cmd) != -1);
    f = fopen(tiles_path("sig.count"), "r");
    int leftovers = -1;
    VT_CHECK(f && fscanf(f, "%d", &leftovers) == 1);
    if (f)
        fclose(f);
    VT_CHECK_INT_EQ(leftovers, 0);
}

int main(int argc, char **argv)
{
    int rc = tiles_start(argc, argv, "test_vt_tiles");
    if (rc != 0)
        return rc;
    VT_RUN(level_sizes_and_borders_for_odd_inputs);
    VT_RUN(wrapped_borders_come_from_the_opposite_edge);
    VT_RUN(box_levels_match_a_double_reference);
    VT_RUN(srgb_checkerboard_averages_to_188);
    VT_RUN(transparent_half_leaves_no_dark_fringe);
    VT_RUN(sixteen_bit_and_float_inputs_keep_their_precision);
    VT_RUN(premultiplied_exr_is_not_premultiplied_again);
    VT_RUN(normal_map_mips_stay_unit_length);
    VT_RUN(output_does_not_depend_on_threads);
    VT_RUN(bad_input_fails_cleanly_without_output);
    VT_RUN(interrupted_run_leaves_nothing_behind);
    tiles_finish(vt_test_failures != 0);
    return vt_test_main_result();
}
