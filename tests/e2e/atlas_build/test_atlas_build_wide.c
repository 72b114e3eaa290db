/* vt-tiles --layout with 16-bit and float textures: a layout of three entries and three layers,
 * each layer mixing an 8-bit texture with wider ones (a 16-bit PNG, a float EXR, a half EXR; the
 * third entry two copies side by side of a half-width wide texture, built from the whole decoded
 * texture instead of the row stream).
 * The layers come out u16 (sRGB), f32 (data, one channel) and f16 (the layout's sRGB made
 * linear); level-0 texels equal the sources' values (8-bit ones as v * 257 in u16, v / 255 in
 * f32, decoded to linear light in f16); levels 1 and 2 equal a reference 2x2 box reduction
 * computed here in double precision (linear light for the sRGB u16 layer). Each comparison is
 * also run against a deliberately wrong expectation, which must fail. Codecs that cannot hold the
 * sample types are refused, naming the layer. -j1 and -j2 give the same bytes, and so do shards
 * merged by vt-merge.
 * Usage: test_atlas_build_wide VT_TILES WORKDIR VT_MERGE */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "atlas_build_fixture.h"
#include "vt_layout.h"
#include "vt_png_file.h"
#include "vt_synth_images.h"
#include "vt_test.h"
#include "vts.h"

#define SIZE    64 /* every entry: SIZE x SIZE (the third: 2 copies of SIZE/2 x SIZE) */
#define ENTRIES 3
#define CONTENT 32
#define BORDER  2
#define LEVELS  4 /* 192x64, 96x32, 48x16, 24x8 */

enum { T_U16, T_U8A, T_F32, T_U8G, T_F16, T_U8B, T_U16C, T_F32C, T_F16C, T_COUNT };
struct tex {
    const char *name;
    uint32_t format, channels, sample;
    struct vt_synth_image_options o;
    struct vt_image img;
    char path[600];
};
#define TEX(n, f, c, s)                                                                            \
    {                                                                                              \
        .name = n, .format = f, .channels = c, .sample = s                                         \
    }
static struct tex texs[T_COUNT] = {
    TEX("u16", VT_SYNTH_PNG, 3, VTS_SAMPLE_U16),  TEX("u8a", VT_SYNTH_PNG, 3, VTS_SAMPLE_U8),
    TEX("f32", VT_SYNTH_EXR, 1, VTS_SAMPLE_F32),  TEX("u8g", VT_SYNTH_PNG, 1, VTS_SAMPLE_U8),
    TEX("f16", VT_SYNTH_EXR, 3, VTS_SAMPLE_F16),  TEX("u8b", VT_SYNTH_PNG, 3, VTS_SAMPLE_U8),
    TEX("u16c", VT_SYNTH_PNG, 3, VTS_SAMPLE_U16), TEX("f32c", VT_SYNTH_EXR, 1, VTS_SAMPLE_F32),
    TEX("f16c", VT_SYNTH_EXR, 3, VTS_SAMPLE_F16),
};
/* layer -> the textures of entries 0 and 1 */
static const uint32_t layer_tex[3][ENTRIES] = {
    {T_U16, T_U8A, T_U16C}, {T_F32, T_U8G, T_F32C}, {T_F16, T_U8B, T_F16C}};
#define COPIES_W (SIZE / 2) /* the copied textures' width */
static const char *layer_name[3] = {"diffuse", "height", "emission"};
static const uint32_t layer_colour[3] = {VTS_COLOUR_SRGB, VTS_COLOUR_DATA, VTS_COLOUR_SRGB};

static void make_textures(void)
{
    for (uint32_t i = 0; i < T_COUNT; i++) {
        struct tex *t = &texs[i];
        vt_synth_image_defaults(&t->o);
        t->o.format = t->format;
        t->o.width = i >= T_U16C ? COPIES_W : SIZE;
        t->o.height = SIZE;
        t->o.channels = t->channels;
        t->o.sample = t->sample;
        t->o.seed = 40 + i;
        t->o.compression = t->format == VT_SYNTH_EXR ? VT_SYNTH_EXR_NONE : t->o.compression;
        snprintf(t->path, sizeof t->path, "%s/%s.%s", abuild_dir, t->name,
                 t->format == VT_SYNTH_EXR ? "exr" : "png");
        struct vts_error err;
        VT_CHECK_INT_EQ(vt_synth_image_write(t->path, &t->o, &err), 0);
        VT_CHECK_INT_EQ(vt_image_alloc(&t->img, t->o.width, SIZE, t->channels, t->sample, &err), 0);
        vt_synth_image_expected(&t->o, 0, 0, &t->img);
    }
}

static void write_layout(const char *path)
{
    struct vt_layout l;
    struct vts_error err;
    VT_CHECK_INT_EQ(vt_layout_alloc(&l, 3, ENTRIES, &err), 0);
    l.width = ENTRIES * SIZE, l.height = SIZE, l.tile_content = CONTENT, l.border = BORDER;
    for (uint32_t k = 0; k < 3; k++)
        l.layers[k] = (struct vt_layout_layer){abuild_strdup(layer_name[k]),
                                               abuild_strdup("map_Kd"), layer_colour[k]};
    static const char *const names[ENTRIES] = {"left", "middle", "copies"};
    for (uint32_t e = 0; e < ENTRIES; e++) {
        struct vt_layout_entry *en = &l.entries[e];
        en->name = abuild_strdup(names[e]);
        en->x = e * SIZE, en->y = 0, en->width = e == 2 ? COPIES_W : SIZE, en->height = SIZE;
        en->repeat_u = e == 2 ? 2 : 1, en->repeat_v = 1;
        en->cell_width = en->cell_height = SIZE, en->alignment = SIZE;
        for (uint32_t k = 0; k < 3; k++) {
            en->textures[k].path = abuild_strdup(texs[layer_tex[k][e]].path);
            en->textures[k].width = en->width, en->textures[k].height = SIZE;
        }
    }
    VT_CHECK_INT_EQ(vt_layout_write(path, &l, &err), 0);
    vt_layout_release(&l);
}

/* ---- values ---- */

static double srgb_to_linear(double s)
{
    return s <= 0.04045 ? s / 12.92 : pow((s + 0.055) / 1.055, 2.4);
}

static double linear_to_srgb(double v)
{
    v = v < 0 ? 0 : v > 1 ? 1 : v;
    return v <= 0.0031308 ? v * 12.92 : 1.055 * pow(v, 1 / 2.4) - 0.055;
}

static double half_to_double(uint16_t h)
{
    int e = (h >> 10) & 31, m = h & 1023;
    double v = e == 0 ? ldexp(m, -24) : e == 31 ? INFINITY : ldexp(m + 1024, e - 25);
    return h & 0x8000 ? -v : v;
}

/* Sample c of texel i of a stored row as a double (integers as their codes). */
static double sample_at(const void *px, uint32_t sample, size_t i)
{
    const uint8_t *p = px;
    switch (sample) {
    case VTS_SAMPLE_U8:
        return p[i];
    case VTS_SAMPLE_U16: {
        uint16_t v;
        memcpy(&v, p + 2 * i, 2);
        return v;
    }
    case VTS_SAMPLE_F16: {
        uint16_t v;
        memcpy(&v, p + 2 * i, 2);
        return half_to_double(v);
    }
    default: {
        float f;
        memcpy(&f, p + 4 * i, 4);
        return f;
    }
    }
}

/* What level 0 of layer k must hold at texel (x, y) of entry e (the third entry: x modulo the
 * copies' width), per channel, as the layer's stored value
 * (codes for u16), and the working value (linear light, 0..1 for u16) the reduction averages.
 * wrong: a deliberately wrong rule (8-bit as v * 256 or v / 256, float data halved, no sRGB
 * decoding). */
static void level0(uint32_t k, uint32_t e, uint32_t x, uint32_t y, uint32_t c, bool wrong,
                   double *stored, double *working)
{
    const struct tex *tx = &texs[layer_tex[k][e]];
    double v = sample_at(vt_image_at(&tx->img, x % tx->img.width, y), tx->sample, c);
    if (k == 0) { /* u16 sRGB */
        double code = tx->sample == VTS_SAMPLE_U8 ? v * (wrong ? 256 : 257) : v;
        *stored = code;
        *working = srgb_to_linear(code / 65535.0);
    } else if (k == 1) { /* f32 data */
        *stored = *working = tx->sample == VTS_SAMPLE_U8 ? v / (wrong ? 256.0 : 255.0)
                             : wrong                     ? v / 2
                                                         : v;
    } else { /* f16 linear */
        *stored = *working =
            tx->sample == VTS_SAMPLE_U8 ? (wrong ? v / 255.0 : srgb_to_linear(v / 255.0)) : v;
    }
}

/* The expected stored values of level L of layer k over entry e (SIZE >> L squared, channels),
 * from the working values of level 0 averaged 2x2 L times in double. nearest: the reduction
 * replaced by the top-left texel (a wrong rule). */
static double *expected_level(uint32_t k, uint32_t e, uint32_t L, uint32_t ch, bool wrong,
                              bool nearest)
{
    uint32_t n = SIZE;
    double *w = malloc(sizeof(double) * n * n * ch);
    double *out = malloc(sizeof(double) * n * n * ch);
    for (uint32_t y = 0; y < n; y++)
        for (uint32_t x = 0; x < n; x++)
            for (uint32_t c = 0; c < ch; c++) {
                size_t i = ((size_t)y * n + x) * ch + c;
                level0(k, e, x, y, c, wrong, &out[i], &w[i]);
                if (k == 0 && wrong && L > 0)
                    w[i] = out[i] / 65535.0; /* averaged without linearising */
            }
    for (uint32_t l = 0; l < L; l++) {
        uint32_t m = n / 2;
        for (uint32_t y = 0; y < m; y++)
            for (uint32_t x = 0; x < m; x++)
                for (uint32_t c = 0; c < ch; c++) {
                    const double *r0 = w + ((size_t)(2 * y) * n + 2 * x) * ch + c;
                    const double *r1 = r0 + (size_t)n * ch;
                    double a = nearest ? r0[0] : (r0[0] + r0[ch] + r1[0] + r1[ch]) / 4;
                    w[((size_t)y * m + x) * ch + c] = a; /* in place: rows already read */
                }
        n = m;
    }
    if (L > 0)
        for (size_t i = 0; i < (size_t)n * n * ch; i++)
            out[i] = k == 0 ? (wrong ? w[i] * 65535.0 : linear_to_srgb(w[i]) * 65535.0) : w[i];
    free(w);
    return out;
}

/* Texels of level L of layer k over entry e that differ from the expectation by more than the
 * layer's tolerance (u16: 1 code for reduced levels, 0 at level 0; f32: 1e-6; f16: half's
 * precision). */
static uint64_t mismatches(struct abuild_reader *r, uint32_t k, uint32_t e, uint32_t L, bool wrong,
                           bool nearest)
{
    const struct vts_layer *ly = vts_store_layer(r->s, k);
    uint32_t ch = ly->channels, n = SIZE >> L;
    double *exp = expected_level(k, e, L, ch, wrong, nearest);
    uint64_t bad = 0;
    for (uint32_t y = 0; y < n; y++)
        for (uint32_t x = 0; x < n; x++) {
            const uint8_t *p = abuild_reader_texel(r, L, e * n + x, y);
            for (uint32_t c = 0; c < ch; c++) {
                double want = exp[((size_t)y * n + x) * ch + c];
                double got = p ? sample_at(p, ly->sample, c) : NAN;
                double tol = ly->sample == VTS_SAMPLE_U16   ? (L ? 1.0 : 0.0)
                             : ly->sample == VTS_SAMPLE_F32 ? 1e-6 + 1e-6 * fabs(want)
                                                            : 1e-6 + fabs(want) / 1024;
                if (!(fabs(got - want) <= tol)) {
                    if (!wrong && !nearest && bad < 3)
                        fprintf(stderr, "layer %u entry %u level %u (%u,%u).%u: %.9g, want %.9g\n",
                                k, e, L, x, y, c, got, want);
                    bad++;
                }
            }
        }
    free(exp);
    return bad;
}

/* ---- tests ---- */

static char layout_path[700], store_path[700];

static void test_layer_formats(void)
{
    char args[2400];
    snprintf(args, sizeof args, "-v --layout %s -o %s", layout_path, store_path);
    VT_CHECK_INT_EQ(abuild_run(args), 0);
    VT_CHECK_STR_CONTAINS(abuild_stderr, "layer 'diffuse': 3 channels (srgb), u16 samples");
    VT_CHECK_STR_CONTAINS(abuild_stderr, "layer 'height': 1 channels (data), f32 samples");
    VT_CHECK_STR_CONTAINS(abuild_stderr, "layer 'emission': 3 channels (linear), f16 samples");
    VT_CHECK_STR_CONTAINS(abuild_stderr, "textures: 1 u8, 2 u16, 0 f16, 0 f32");
    VT_CHECK(strstr(abuild_stderr, "not 8-bit") == NULL);
    struct vts_error err;
    struct vts_store *s = vts_open(store_path, &err);
    VT_CHECK(s != NULL);
    if (!s)
        return;
    VT_CHECK_INT_EQ(vts_store_geometry(s)->layer_count, 3);
    VT_CHECK_INT_EQ(vts_store_geometry(s)->level_count, LEVELS);
    static const uint32_t want[3][4] = {
        {VTS_SAMPLE_U16, 3, VTS_COLOUR_SRGB, VTS_CODEC_PNG},
        {VTS_SAMPLE_F32, 1, VTS_COLOUR_DATA, VTS_CODEC_RAW},
        {VTS_SAMPLE_F16, 3, VTS_COLOUR_LINEAR, VTS_CODEC_RAW},
    };
    for (uint32_t k = 0; k < 3; k++) {
        const struct vts_layer *l = vts_store_layer(s, k);
        VT_CHECK_INT_EQ(l->sample, want[k][0]);
        VT_CHECK_INT_EQ(l->channels, want[k][1]);
        VT_CHECK_INT_EQ(l->colour, want[k][2]);
        VT_CHECK_INT_EQ(l->codec, want[k][3]);
    }
    vts_close(s);
}

/* The smallest and largest colour value of level 0 of layer k over every entry (by level0()). */
static void level0_range(uint32_t k, uint32_t ch, bool wrong, double out[2])
{
    out[0] = INFINITY, out[1] = -INFINITY;
    for (uint32_t e = 0; e < ENTRIES; e++)
        for (uint32_t y = 0; y < SIZE; y++)
            for (uint32_t x = 0; x < SIZE; x++)
                for (uint32_t c = 0; c < ch; c++) {
                    double v, w;
                    level0(k, e, x, y, c, wrong, &v, &w);
                    out[0] = v < out[0] ? v : out[0];
                    out[1] = v > out[1] ? v : out[1];
                }
}

/* The "range" metadata: per layer "-" (u16 sRGB) or MIN:MAX of level 0's values. */
static void test_range_metadata(void)
{
    struct vts_error err;
    struct vts_store *s = vts_open(store_path, &err);
    VT_CHECK(s != NULL);
    if (!s)
        return;
    const char *m = vts_store_meta_find(s, "range");
    VT_CHECK(m != NULL);
    VT_CHECK(m && strncmp(m, "-,", 2) == 0); /* the sRGB u16 layer has none */
    const char *p = m ? strchr(m, ',') : NULL;
    for (uint32_t k = 1; p && k < 3; k++) {
        double got[2], want[2], wrong[2];
        VT_CHECK_INT_EQ(sscanf(p + 1, "%lf:%lf", &got[0], &got[1]), 2);
        level0_range(k, vts_store_layer(s, k)->channels, false, want);
        level0_range(k, vts_store_layer(s, k)->channels, true, wrong);
        for (int i = 0; i < 2; i++) {
            VT_CHECK(fabs(got[i] - want[i]) <= 1e-6 * (1 + fabs(want[i])));
            if (k == 1) /* the f32 layer: halved floats give another range */
                VT_CHECK(fabs(got[i] - wrong[i]) > 1e-3);
        }
        p = strchr(p + 1, ',');
    }
    vts_close(s);
}

static void test_texels(void)
{
    for (uint32_t k = 0; k < 3; k++) {
        struct abuild_reader r;
        VT_CHECK(abuild_reader_open(&r, store_path, k));
        for (uint32_t e = 0; e < ENTRIES; e++)
            for (uint32_t L = 0; L < LEVELS; L++) {
                VT_CHECK_INT_EQ(mismatches(&r, k, e, L, false, false), 0);
                /* the comparison catches a wrong rule: every wider texture at level 0 and every
                 * 8-bit one in each layer; the reduction at the coarser levels */
                bool wide = texs[layer_tex[k][e]].sample != VTS_SAMPLE_U8;
                if (L == 0 && (!wide || k == 1) && mismatches(&r, k, e, L, true, false) == 0) {
                    fprintf(stderr, "layer %u entry %u: a wrong level 0 passes\n", k, e);
                    VT_CHECK(false);
                }
                if (L > 0) {
                    VT_CHECK(mismatches(&r, k, e, L, false, true) > 0);
                    if (k == 0)
                        VT_CHECK(mismatches(&r, k, e, L, true, false) > 0);
                }
            }
        abuild_reader_close(&r);
    }
}

static void test_threads_same_bytes(void)
{
    char args[2400], other[700];
    snprintf(other, sizeof other, "%s/wide_j2.vts", abuild_dir);
    snprintf(args, sizeof args, "-q -j2 --cache-size 1M --layout %s -o %s", layout_path, other);
    VT_CHECK_INT_EQ(abuild_run(args), 0);
    snprintf(args, sizeof args, "cmp -s %s %s", store_path, other);
    VT_CHECK_INT_EQ(system(args), 0);
}

static void test_codec_refused(void)
{
    char args[2400], out[700];
    snprintf(out, sizeof out, "%s/wide_jpeg.vts", abuild_dir);
    snprintf(args, sizeof args, "-q --codec jpeg --layout %s -o %s", layout_path, out);
    VT_CHECK_INT_EQ(abuild_run(args), 1);
    VT_CHECK_STR_CONTAINS(abuild_stderr, "layer 'diffuse' of '");
    VT_CHECK_STR_CONTAINS(abuild_stderr, "holds u16 samples: jpeg stores 8-bit samples only");
    struct stat st;
    VT_CHECK(stat(out, &st) != 0);
    snprintf(args, sizeof args, "-q --codec png --layer height --layout %s -o %s", layout_path,
             out);
    VT_CHECK_INT_EQ(abuild_run(args), 1);
    VT_CHECK_STR_CONTAINS(abuild_stderr, "layer 'height' of '");
    VT_CHECK_STR_CONTAINS(abuild_stderr, "holds f32 samples");
}

/* Shards of the wide layers (--shard I/N, then vt-merge) give the single build's bytes; each
 * shard's range is of the textures it read (they differ), the merge writes their union. */
static const char *merge_tool;
static void test_shards_merge_equal(void)
{
    static const uint32_t counts[] = {2, 4, 16};
    for (size_t c = 0; c < sizeof counts / sizeof counts[0]; c++) {
        uint32_t n = counts[c];
        char args[2400], shard[700], merged[700], all[16 * 720] = "";
        bool ranges_differ = false;
        char first[200] = "";
        for (uint32_t i = 1; i <= n; i++) {
            snprintf(shard, sizeof shard, "%s/wide_s%u_%u.vts", abuild_dir, n, i);
            snprintf(args, sizeof args, "-q -j%u --layout %s --shard %u/%u -o %s", 1 + i % 2,
                     layout_path, i, n, shard);
            VT_CHECK_INT_EQ(abuild_run(args), 0);
            size_t len = strlen(all);
            snprintf(all + len, sizeof all - len, " %s", shard);
            struct vts_error err;
            struct vts_store *s = vts_open(shard, &err);
            VT_CHECK(s != NULL);
            const char *r = s ? vts_store_meta_find(s, "shard.range") : NULL;
            VT_CHECK(r != NULL);
            VT_CHECK(s && vts_store_meta_find(s, "range") == NULL);
            if (r && i == 1)
                snprintf(first, sizeof first, "%s", r);
            else if (r && strcmp(r, first) != 0)
                ranges_differ = true;
            vts_close(s);
        }
        VT_CHECK(ranges_differ); /* else the union is not exercised */
        snprintf(merged, sizeof merged, "%s/wide_m%u.vts", abuild_dir, n);
        snprintf(args, sizeof args, "%s -q -o %s%s", merge_tool, merged, all);
        VT_CHECK_INT_EQ(system(args), 0);
        snprintf(args, sizeof args, "cmp -s %s %s", store_path, merged);
        VT_CHECK_INT_EQ(system(args), 0);
    }
}

/* --export-atlas keeps 16 bits (PNG), refuses f16 naming the layer. */
static void test_export(void)
{
    char args[2400], png[700], out[700];
    snprintf(png, sizeof png, "%s/diffuse16.png", abuild_dir);
    snprintf(out, sizeof out, "%s/export.vts", abuild_dir);
    snprintf(args, sizeof args, "-q --layer diffuse --export-atlas %s --layout %s -o %s", png,
             layout_path, out);
    VT_CHECK_INT_EQ(abuild_run(args), 0);
    struct vt_image img = {0};
    struct vts_error err;
    VT_CHECK_INT_EQ(vt_png_file_read(png, &img, &err), 0);
    VT_CHECK_INT_EQ(img.sample, VTS_SAMPLE_U16);
    uint64_t bad = 0, bad_wrong = 0;
    for (uint32_t y = 0; img.pixels && y < SIZE; y++)
        for (uint32_t x = 0; x < ENTRIES * SIZE; x++)
            for (uint32_t c = 0; c < 3; c++) {
                double want, wrong, wk;
                level0(0, x / SIZE, x % SIZE, y, c, false, &want, &wk);
                level0(0, x / SIZE, x % SIZE, y, c, true, &wrong, &wk);
                double got = sample_at(vt_image_at(&img, x, y), VTS_SAMPLE_U16, c);
                bad += got != want;
                bad_wrong += got != wrong;
            }
    VT_CHECK_INT_EQ(bad, 0);
    VT_CHECK(bad_wrong > 0);
    vt_image_release(&img);
    snprintf(png, sizeof png, "%s/emission.tif", abuild_dir);
    snprintf(args, sizeof args, "-q --layer emission --export-atlas %s --layout %s -o %s", png,
             layout_path, out);
    VT_CHECK_INT_EQ(abuild_run(args), 1);
    VT_CHECK_STR_CONTAINS(abuild_stderr, "layer 'emission' holds f16 samples");
}

int main(int argc, char **argv)
{
    if (argc < 4) {
        fprintf(stderr, "usage: test_atlas_build_wide VT_TILES WORKDIR VT_MERGE\n");
        return 2;
    }
    abuild_tool = argv[1];
    abuild_dir = argv[2];
    merge_tool = argv[3];
    mkdir(abuild_dir, 0777);
    make_textures();
    snprintf(layout_path, sizeof layout_path, "%s/wide.json", abuild_dir);
    snprintf(store_path, sizeof store_path, "%s/wide.vts", abuild_dir);
    write_layout(layout_path);
    VT_RUN(test_layer_formats);
    VT_RUN(test_texels);
    VT_RUN(test_range_metadata);
    VT_RUN(test_threads_same_bytes);
    VT_RUN(test_shards_merge_equal);
    VT_RUN(test_codec_refused);
    VT_RUN(test_export);
    for (uint32_t i = 0; i < T_COUNT; i++)
        vt_image_release(&texs[i].img);
    return vt_test_main_result();
}
