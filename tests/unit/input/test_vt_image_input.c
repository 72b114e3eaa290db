/* Image input: every reader against seeded files from vt_synth_images (exact texels, JPEG against
 * a full libjpeg decode), region shapes and orders, info fields, refusals, truncated and corrupted
 * files, limits, concurrency, and that OpenImageIO is loaded only for a fallback file. */
#include <errno.h>
#include <pthread.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "vt_image_input.h"
#include "vt_synth_images.h"
#include "vt_test.h"

static char tmp_dir[64];

static void tmp_path(char *buf, size_t size, const char *name)
{
    snprintf(buf, size, "%s/%s", tmp_dir, name);
}

static bool oiio_is_loaded(void)
{
    FILE *f = fopen("/proc/self/maps", "r");
    char line[1024];
    bool found = false;
    while (f && fgets(line, sizeof line, f))
        if (strstr(line, "libOpenImageIO"))
            found = true;
    if (f)
        fclose(f);
    return found;
}

/* Writes the synthetic image o as name in the temp dir; path gets its path. */
static bool write_image(const struct vt_synth_image_options *o, const char *name, char *path,
                        size_t path_size)
{
    struct vts_error err = {0};
    tmp_path(path, path_size, name);
    int rc = vt_synth_image_write(path, o, &err);
    if (rc < 0)
        fprintf(stderr, "cannot write %s: %s\n", name, err.message);
    VT_CHECK_INT_EQ(rc, 0);
    return rc == 0;
}

static bool write_bytes(const char *path, const void *data, size_t len)
{
    FILE *f = fopen(path, "wb");
    bool ok = f && fwrite(data, 1, len, f) == len;
    if (f && fclose(f) != 0)
        ok = false;
    return ok;
}

static unsigned char *read_bytes(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    rewind(f);
    unsigned char *p = malloc(n > 0 ? (size_t)n : 1);
    *len = p ? fread(p, 1, (size_t)n, f) : 0;
    fclose(f);
    return p;
}

/* Reads [x, x + w) x [y, y + h) and compares it with the pattern (or with ref, a full decode). */
static bool region_matches(struct vt_source *src, const struct vt_synth_image_options *o,
                           const struct vt_image *ref, uint32_t x, uint32_t y, uint32_t w,
                           uint32_t h)
{
    struct vt_image got, want;
    struct vts_error err = {0};
    w = x + w > o->width ? o->width - x : w; /* regions chosen for tile sizes may stick out */
    h = y + h > o->height ? o->height - y : h;
    if (vt_image_alloc(&got, w, h, src->info.channels, src->info.sample, NULL) < 0)
        return false;
    int rc = vt_source_read(src, x, y, &got, &err);
    bool same = rc == 0;
    if (rc < 0)
        fprintf(stderr, "read %ux%u at %u,%u of %s: %s\n", w, h, x, y, src->name, err.message);
    size_t row = (size_t)w * vt_image_texel_bytes(&got);
    if (same && ref) {
        for (uint32_t r = 0; r < h && same; r++)
            same = memcmp(vt_image_at(&got, 0, r), vt_image_at(ref, x, y + r), row) == 0;
    } else if (same && vt_image_alloc(&want, w, h, o->channels, o->sample, NULL) == 0) {
        vt_synth_image_expected(o, x, y, &want);
        same = memcmp(got.pixels, want.pixels, row * h) == 0;
        vt_image_release(&want);
    }
    if (rc == 0 && !same)
        fprintf(stderr, "texels differ in %ux%u at %u,%u of %s\n", w, h, x, y, src->name);
    vt_image_release(&got);
    return same;
}

/* Regions every reader must get right, in an order that goes backwards on purpose. */
static void check_regions(struct vt_source *src, const struct vt_synth_image_options *o,
                          const struct vt_image *ref)
{
    uint32_t w = o->width, h = o->height;
    uint32_t tw = o->tile_w ? o->tile_w : 16, th = o->tile_h ? o->tile_h : 16;
    VT_CHECK(region_matches(src, o, ref, 0, 0, w, h));
    VT_CHECK(region_matches(src, o, ref, 0, 0, 1, 1));
    VT_CHECK(region_matches(src, o, ref, w - 1, h - 1, 1, 1));
    VT_CHECK(region_matches(src, o, ref, w - 7, 0, 7, 5));
    VT_CHECK(region_matches(src, o, ref, 0, h - 5, 7, 5));
    VT_CHECK(region_matches(src, o, ref, w - 7, h - 5, 7, 5));
    VT_CHECK(region_matches(src, o, ref, tw - 3, th - 2, 9, 7)); /* crosses tile/strip borders */
    VT_CHECK(region_matches(src, o, ref, 1, th + 1, w - 2, th + 3));
    VT_CHECK(region_matches(src, o, ref, 0, 3, w, 1));
    VT_CHECK(region_matches(src, o, ref, w / 2, 0, 1, h));
}

/* Seeded random regions, in random order. */
static void check_random_regions(struct vt_source *src, const struct vt_synth_image_options *o,
                                 const struct vt_image *ref, int count)
{
    uint32_t state = o->seed * 2654435761u + o->width;
    for (int i = 0; i < count; i++) {
        uint32_t v[4];
        for (int k = 0; k < 4; k++) {
            state = state * 1103515245u + 12345u;
            v[k] = state >> 8;
        }
        uint32_t x = v[0] % o->width, y = v[1] % o->height;
        uint32_t w = 1 + v[2] % (o->width - x), h = 1 + v[3] % (o->height - y);
        VT_CHECK(region_matches(src, o, ref, x, y, w, h));
    }
}

/* Full-width bands, top-down: how the pyramid reads sequential sources. */
static void check_bands(struct vt_source *src, const struct vt_synth_image_options *o,
                        const struct vt_image *ref, uint32_t band)
{
    for (uint32_t y = 0; y < o->height; y += band) {
        uint32_t n = o->height - y < band ? o->height - y : band;
        VT_CHECK(region_matches(src, o, ref, 0, y, o->width, n));
    }
}

static void check_info(const struct vt_source *src, const struct vt_synth_image_options *o,
                       const char *format, bool sequential, bool has_alpha)
{
    const struct vt_source_info *in = &src->info;
    bool is_float = o->sample == VTS_SAMPLE_F16 || o->sample == VTS_SAMPLE_F32;
    VT_CHECK_INT_EQ(in->width, o->width);
    VT_CHECK_INT_EQ(in->height, o->height);
    VT_CHECK_INT_EQ(in->channels, o->channels);
    VT_CHECK_INT_EQ(in->sample, o->sample);
    VT_CHECK_INT_EQ(in->colour, is_float ? VTS_COLOUR_LINEAR : VTS_COLOUR_SRGB);
    VT_CHECK_INT_EQ(in->has_alpha, has_alpha);
    VT_CHECK_INT_EQ(in->sequential, sequential);
    VT_CHECK_INT_EQ(in->tile_w, sequential ? 0 : o->tile_w);
    VT_CHECK_INT_EQ(in->tile_h, sequential ? 0 : o->tile_h);
    VT_CHECK_STR_CONTAINS(in->format, format);
}

/* Opens a synthetic file, checks its info and regions. */
static void check_file(const struct vt_synth_image_options *o, const char *name, const char *format,
                       bool sequential, bool has_alpha)
{
    char path[256];
    if (!write_image(o, name, path, sizeof path))
        return;
    struct vt_source src;
    struct vts_error err = {0};
    int rc = vt_image_input_open(path, NULL, &src, &err);
    if (rc < 0)
        fprintf(stderr, "%s: %s\n", name, err.message);
    VT_CHECK_INT_EQ(rc, 0);
    if (rc < 0)
        return;
    check_info(&src, o, format, sequential, has_alpha);
    check_regions(&src, o, NULL);
    check_bands(&src, o, NULL, 13);
    check_random_regions(&src, o, NULL, 20);
    vt_source_close(&src);
}

static struct vt_synth_image_options synth(uint32_t format, uint32_t channels, uint32_t sample)
{
    struct vt_synth_image_options o;
    vt_synth_image_defaults(&o);
    o.format = format;
    o.channels = channels;
    o.sample = sample;
    if (format == VT_SYNTH_EXR)
        o.compression = VT_SYNTH_EXR_ZIP;
    return o;
}

/* ---- TIFF ---- */

static void tiff_reads_every_layout_and_sample_type(void)
{
    struct vt_synth_image_options o = synth(VT_SYNTH_TIFF, 4, VTS_SAMPLE_U8);
    check_file(&o, "rgba8_strips.tif", "tiff", true, true);

    o = synth(VT_SYNTH_TIFF, 3, VTS_SAMPLE_U8);
    o.tile_w = 32, o.tile_h = 16, o.compression = VT_SYNTH_TIFF_LZW;
    check_file(&o, "rgb8_tiles_lzw.tif", "tiff", false, false);

    o = synth(VT_SYNTH_TIFF, 1, VTS_SAMPLE_U16);
    o.tile_w = 16, o.tile_h = 32, o.bigtiff = true;
    check_file(&o, "grey16_tiles.btf", "bigtiff", false, false);

    o = synth(VT_SYNTH_TIFF, 4, VTS_SAMPLE_U16);
    o.separate_planes = true, o.rows_per_strip = 7;
    check_file(&o, "rgba16_planes.tif", "tiff", true, true);

    o = synth(VT_SYNTH_TIFF, 3, VTS_SAMPLE_F32);
    o.tile_w = 48, o.tile_h = 16, o.separate_planes = true;
    check_file(&o, "rgbf32_tiles_planes.tif", "tiff", false, false);

    o = synth(VT_SYNTH_TIFF, 2, VTS_SAMPLE_F16);
    o.compression = VT_SYNTH_TIFF_NONE, o.rows_per_strip = 5;
    check_file(&o, "gaf16_strips.tif", "tiff", true, true);

    o = synth(VT_SYNTH_TIFF, 4, VTS_SAMPLE_F16);
    o.tile_w = 16, o.tile_h = 16, o.bigtiff = true, o.compression = VT_SYNTH_TIFF_NONE;
    check_file(&o, "rgbaf16_tiles.btf", "bigtiff", false, true);

    o = synth(VT_SYNTH_TIFF, 3, VTS_SAMPLE_U8);
    o.rows_per_strip = o.height, o.compression = VT_SYNTH_TIFF_NONE;
    check_file(&o, "rgb8_one_strip.tif", "tiff", true, false);

    o = synth(VT_SYNTH_TIFF, 3, VTS_SAMPLE_U8);
    o.rows_per_strip = 3, o.compression = VT_SYNTH_TIFF_PACKBITS, o.bigtiff = true;
    check_file(&o, "rgb8_packbits.btf", "bigtiff", true, false);
}

static void tiff_expands_low_bits_palettes_and_min_is_white(void)
{
    const uint32_t bits[] = {1, 2, 4};
    for (int i = 0; i < 3; i++) {
        struct vt_synth_image_options o = synth(VT_SYNTH_TIFF, 1, VTS_SAMPLE_U8);
        o.bits = bits[i];
        o.min_is_white = bits[i] == 1;
        if (bits[i] == 4)
            o.tile_w = 16, o.tile_h = 16;
        char name[32];
        snprintf(name, sizeof name, "grey%u.tif", bits[i]);
        check_file(&o, name, "tiff", bits[i] != 4, false);
    }
    struct vt_synth_image_options o = synth(VT_SYNTH_TIFF, 1, VTS_SAMPLE_U8);
    o.min_is_white = true;
    check_file(&o, "grey8_miniswhite.tif", "tiff", true, false);

    o = synth(VT_SYNTH_TIFF, 2, VTS_SAMPLE_U16);
    o.min_is_white = true, o.separate_planes = true;
    check_file(&o, "ga16_miniswhite.tif", "tiff", true, true);

    o = synth(VT_SYNTH_TIFF, 3, VTS_SAMPLE_U8);
    o.palette = true;
    check_file(&o, "palette8.tif", "tiff", true, false);

    o = synth(VT_SYNTH_TIFF, 3, VTS_SAMPLE_U8);
    o.palette = true, o.bits = 4, o.tile_w = 32, o.tile_h = 32;
    o.separate_planes = true; /* one sample per texel: PLANARCONFIG_SEPARATE changes nothing */
    check_file(&o, "palette4_tiles.tif", "tiff", false, false);
}

/* ---- PNG ---- */

/* PNG: all colour types and depths, bands top-down, then backwards and partial-width reads. */
static void png_reads_every_colour_type(void)
{
    static const struct {
        uint32_t channels, sample, bits;
        bool palette, interlaced;
        const char *name;
    } cases[] = {
        {4, VTS_SAMPLE_U8, 0, false, false, "rgba8.png"},
        {3, VTS_SAMPLE_U16, 0, false, false, "rgb16.png"},
        {1, VTS_SAMPLE_U8, 0, false, false, "grey8.png"},
        {2, VTS_SAMPLE_U8, 0, false, false, "ga8.png"},
        {2, VTS_SAMPLE_U16, 0, false, false, "ga16.png"},
        {4, VTS_SAMPLE_U16, 0, false, false, "rgba16.png"},
        {1, VTS_SAMPLE_U8, 1, false, false, "grey1.png"},
        {1, VTS_SAMPLE_U8, 2, false, false, "grey2.png"},
        {1, VTS_SAMPLE_U8, 4, false, false, "grey4.png"},
        {4, VTS_SAMPLE_U8, 0, true, false, "palette8_trns.png"},
        {3, VTS_SAMPLE_U8, 4, true, false, "palette4.png"},
        {4, VTS_SAMPLE_U8, 2, true, false, "palette2_trns.png"},
        {3, VTS_SAMPLE_U8, 0, false, true, "rgb8_adam7.png"},
        {2, VTS_SAMPLE_U16, 0, false, true, "ga16_adam7.png"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        struct vt_synth_image_options o = synth(VT_SYNTH_PNG, cases[i].channels, cases[i].sample);
        o.bits = cases[i].bits;
        o.palette = cases[i].palette;
        o.interlaced = cases[i].interlaced;
        check_file(&o, cases[i].name, "png", true, o.channels == 2 || o.channels == 4);
    }
}

/* ---- JPEG ---- */

static void jpeg_regions_equal_a_full_decode(void)
{
    static const struct {
        uint32_t channels, width, height;
        bool sub420, progressive;
        const char *name;
    } cases[] = {
        {1, 97, 61, false, false, "grey.jpg"},
        {3, 97, 61, false, false, "rgb444.jpg"},
        {3, 301, 203, true, false, "rgb420.jpg"},
        {3, 131, 77, true, true, "rgb420_progressive.jpg"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        struct vt_synth_image_options o = synth(VT_SYNTH_JPEG, cases[i].channels, VTS_SAMPLE_U8);
        o.width = cases[i].width, o.height = cases[i].height;
        o.jpeg_420 = cases[i].sub420, o.progressive = cases[i].progressive;
        char path[256];
        if (!write_image(&o, cases[i].name, path, sizeof path))
            continue;
        struct vt_image ref;
        struct vts_error err = {0};
        VT_CHECK_INT_EQ(vt_synth_jpeg_decode(path, &ref, &err), 0);
        struct vt_source src;
        int rc = vt_image_input_open(path, NULL, &src, &err);
        VT_CHECK_INT_EQ(rc, 0);
        if (rc == 0 && ref.pixels) {
            check_info(&src, &o, "jpeg", true, false);
            check_regions(&src, &o, &ref);
            check_bands(&src, &o, &ref, 16);
            /* a partial-width sequence top-down, then one going backwards */
            VT_CHECK(region_matches(&src, &o, &ref, 17, 0, 40, 9));
            VT_CHECK(region_matches(&src, &o, &ref, 17, 9, 40, 30));
            VT_CHECK(region_matches(&src, &o, &ref, 33, 5, 20, 20));
            check_random_regions(&src, &o, &ref, 40);
            vt_source_close(&src);
        }
        vt_image_release(&ref);
    }
}

/* ---- EXR ---- */

static void exr_maps_channels_by_name_in_every_layout(void)
{
    static const struct {
        uint32_t channels, sample, tile;
        const char *names;
        uint32_t compression;
        int32_t origin_x, origin_y;
        bool alpha;
        const char *file;
    } cases[] = {
        {4, VTS_SAMPLE_F16, 0, "R,G,B,A", VT_SYNTH_EXR_ZIP, 0, 0, true, "rgba_half_scan.exr"},
        {4, VTS_SAMPLE_F32, 0, "A,B,G,R", VT_SYNTH_EXR_ZIPS, 0, 0, true, "rgba_float_scan.exr"},
        {3, VTS_SAMPLE_F32, 32, "R,G,B", VT_SYNTH_EXR_ZIP, 0, 0, false, "rgb_float_tiles.exr"},
        {3, VTS_SAMPLE_F16, 16, "B,G,R", VT_SYNTH_EXR_NONE, 0, 0, false, "rgb_half_tiles.exr"},
        {4, VTS_SAMPLE_F16, 16, "R,G,B,A", VT_SYNTH_EXR_PIZ, -5, 7, true, "rgba_half_piz.exr"},
        {1, VTS_SAMPLE_F16, 0, "Y", VT_SYNTH_EXR_RLE, 0, 0, false, "y_half_scan.exr"},
        {2, VTS_SAMPLE_F32, 32, "Y,A", VT_SYNTH_EXR_ZIP, 3, -2, true, "ya_float_tiles.exr"},
        {4, VTS_SAMPLE_F16, 0, "R,G,B,A,Z", VT_SYNTH_EXR_PIZ, 0, 0, true, "rgbaz_half_scan.exr"},
        {2, VTS_SAMPLE_F32, 0, "U,V", VT_SYNTH_EXR_NONE, 0, 0, false, "uv_float_scan.exr"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        struct vt_synth_image_options o = synth(VT_SYNTH_EXR, cases[i].channels, cases[i].sample);
        o.tile_w = o.tile_h = cases[i].tile;
        o.exr_channels = cases[i].names;
        o.compression = cases[i].compression;
        o.exr_origin_x = cases[i].origin_x, o.exr_origin_y = cases[i].origin_y;
        check_file(&o, cases[i].file, "exr", cases[i].tile == 0, cases[i].alpha);
    }
}

/* ---- fallback ---- */

static void fallback_reads_tga_and_loads_oiio_only_then(void)
{
    struct vt_synth_image_options o = synth(VT_SYNTH_TGA, 4, VTS_SAMPLE_U8);
    char path[256];
    if (!write_image(&o, "rgba.tga", path, sizeof path))
        return;
    VT_CHECK(!oiio_is_loaded());
    struct vt_source src;
    struct vts_error err = {0};
    int rc = vt_image_input_open(path, NULL, &src, &err);
#ifdef VT_TEST_HAVE_OIIO
    if (rc < 0)
        fprintf(stderr, "%s\n", err.message);
    VT_CHECK_INT_EQ(rc, 0);
    if (rc == 0) {
        VT_CHECK(oiio_is_loaded());
        check_info(&src, &o, "oiio:", true, true);
        check_regions(&src, &o, NULL);
        check_bands(&src, &o, NULL, 16);
        vt_source_close(&src);
    }
    o.channels = 3;
    if (write_image(&o, "rgb.tga", path, sizeof path)) {
        rc = vt_image_input_open(path, NULL, &src, &err);
        VT_CHECK_INT_EQ(rc, 0);
        if (rc == 0) {
            check_info(&src, &o, "oiio:", true, false);
            check_regions(&src, &o, NULL);
            vt_source_close(&src);
        }
    }
#else
    VT_CHECK_INT_EQ(rc, VTS_ERR_UNSUPPORTED);
    VT_CHECK_STR_CONTAINS(err.message, "built without OpenImageIO");
    VT_CHECK(!oiio_is_loaded());
#endif
}

/* ---- errors ---- */

/* Opens path and reads all of it: 0, or the first failure's status (err filled). */
static int open_and_read_all(const char *path, const struct vt_input_limits *limits,
                             struct vts_error *err, struct vt_synth_image_options *check)
{
    struct vt_source src;
    int rc = vt_image_input_open(path, limits, &src, err);
    if (rc < 0)
        return rc;
    struct vt_image img;
    rc = vt_image_alloc(&img, src.info.width, src.info.height, src.info.channels, src.info.sample,
                        err);
    if (rc == 0)
        rc = vt_source_read(&src, 0, 0, &img, err);
    if (rc == 0 && check) {
        struct vt_image want;
        if (vt_image_alloc(&want, img.width, img.height, img.channels, img.sample, NULL) == 0) {
            vt_synth_image_expected(check, 0, 0, &want);
            bool same = memcmp(want.pixels, img.pixels, img.stride * img.height) == 0;
            if (!same)
                fprintf(stderr, "texels of %s differ\n", path);
            VT_CHECK(same);
            vt_image_release(&want);
        }
    }
    vt_image_release(&img);
    vt_source_close(&src);
    return rc;
}

/* Every prefix (from the magic bytes on, in steps) fails cleanly naming the file, or reads
 * correct texels; then seeded byte corruptions (150, or $VT_TEST_DAMAGE_ROUNDS) must not crash
 * and must fail naming the file (ASan checks the reads). */
static void check_damaged_copies(const struct vt_synth_image_options *o, const char *name)
{
    char path[256], bad[256];
    if (!write_image(o, name, path, sizeof path))
        return;
    size_t len = 0;
    unsigned char *bytes = read_bytes(path, &len);
    VT_CHECK(bytes && len > 16);
    if (!bytes || len <= 16) {
        free(bytes);
        return;
    }
    snprintf(bad, sizeof bad, "%s/damaged_%s", tmp_dir, name);
    struct vt_input_limits limits = {1u << 16}; /* a corrupt size must not allocate gigabytes */
    size_t step = len / 97 + 1;
    bool exact = o->format != VT_SYNTH_JPEG;
    for (size_t n = 8; n < len; n += (n < 64 ? 1 : step)) {
        struct vts_error err = {0};
        VT_CHECK(write_bytes(bad, bytes, n));
        struct vt_synth_image_options copy = *o;
        int rc = open_and_read_all(bad, &limits, &err, exact ? &copy : NULL);
        if (rc < 0 && rc != VTS_ERR_BAD_INPUT)
            fprintf(stderr, "prefix %zu of %s: %s\n", n, name, err.message);
        VT_CHECK(rc == 0 || rc == VTS_ERR_BAD_INPUT);
        VT_CHECK(rc == 0 || strstr(err.message, bad));
    }
    uint32_t state = 12345;
    unsigned char *copy = malloc(len);
    const char *env = getenv("VT_TEST_DAMAGE_ROUNDS"); /* more for a long soak under ASan */
    int rounds = env ? atoi(env) : 150;
    for (int i = 0; copy && i < rounds; i++) {
        memcpy(copy, bytes, len);
        for (int k = 0; k < 1 + i % 4; k++) {
            state = state * 1103515245u + 12345u;
            size_t at = 8 + (state >> 8) % (len - 8);
            copy[at] ^= (unsigned char)(1u << (state >> 28) % 8 | (i % 3 == 0 ? 0xff : 0));
        }
        struct vts_error err = {0};
        VT_CHECK(write_bytes(bad, copy, len));
        int rc = open_and_read_all(bad, &limits, &err, NULL);
        VT_CHECK(rc == 0 || strstr(err.message, bad));
    }
    free(copy);
    free(bytes);
}

static void damaged_files_fail_cleanly(void)
{
    struct vt_synth_image_options o = synth(VT_SYNTH_TIFF, 3, VTS_SAMPLE_U8);
    check_damaged_copies(&o, "strips.tif");
    o.tile_w = o.tile_h = 16, o.compression = VT_SYNTH_TIFF_NONE, o.bigtiff = true;
    check_damaged_copies(&o, "tiles.btf");
    o = synth(VT_SYNTH_TIFF, 2, VTS_SAMPLE_U16);
    o.separate_planes = true, o.compression = VT_SYNTH_TIFF_LZW;
    check_damaged_copies(&o, "planes.tif");
    o = synth(VT_SYNTH_PNG, 4, VTS_SAMPLE_U8);
    check_damaged_copies(&o, "rgba.png");
    o = synth(VT_SYNTH_PNG, 3, VTS_SAMPLE_U8);
    o.palette = true, o.interlaced = true;
    check_damaged_copies(&o, "palette_adam7.png");
    o = synth(VT_SYNTH_JPEG, 3, VTS_SAMPLE_U8);
    o.jpeg_420 = true;
    check_damaged_copies(&o, "rgb.jpg");
    o.progressive = true;
    check_damaged_copies(&o, "progressive.jpg");
    o = synth(VT_SYNTH_EXR, 4, VTS_SAMPLE_F16);
    o.compression = VT_SYNTH_EXR_ZIP;
    check_damaged_copies(&o, "scan.exr");
    o.tile_w = o.tile_h = 16, o.compression = VT_SYNTH_EXR_PIZ;
    check_damaged_copies(&o, "tiles.exr");
}

/* A PNG of IHDR and IEND only, claiming width x height. */
static void write_png_header(const char *path, uint32_t width, uint32_t height)
{
    unsigned char b[] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0,   0, 0, 13,
                         'I',  'H', 'D', 'R', 0,    0,    0,    0,    0,   0, 0, 0,
                         8,    2,   0,   0,   0,    0,    0,    0,    0,   0, 0, 0,
                         0,    'I', 'E', 'N', 'D',  0xae, 0x42, 0x60, 0x82};
    for (int i = 0; i < 4; i++) {
        b[16 + i] = (unsigned char)(width >> (24 - 8 * i));
        b[20 + i] = (unsigned char)(height >> (24 - 8 * i));
    }
    uint32_t crc = 0xffffffffu; /* CRC-32 of "IHDR" + data */
    for (int i = 12; i < 29; i++) {
        crc ^= b[i];
        for (int k = 0; k < 8; k++)
            crc = crc & 1 ? (crc >> 1) ^ 0xedb88320u : crc >> 1;
    }
    crc ^= 0xffffffffu;
    for (int i = 0; i < 4; i++)
        b[29 + i] = (unsigned char)(crc >> (24 - 8 * i));
    VT_CHECK(write_bytes(path, b, sizeof b));
}

static void limits_are_checked_before_decoding(void)
{
    char path[256];
    struct vts_error err = {0};
    struct vt_source src;
    struct vt_input_limits low = {1000000};
    tmp_path(path, sizeof path, "huge.png");
    write_png_header(path, 100000, 100000);
    VT_CHECK_INT_EQ(vt_image_input_open(path, &low, &src, &err), VTS_ERR_LIMIT);
    VT_CHECK_STR_CONTAINS(err.message, "100000x100000 texels exceeds --max-pixels 1000000");
    write_png_header(path, 200000, 200000);
    VT_CHECK_INT_EQ(vt_image_input_open(path, NULL, &src, &err), VTS_ERR_LIMIT);
    char want[400];
    snprintf(want, sizeof want, "'%s': 200000x200000 texels exceeds --max-pixels 17179869184",
             path);
    VT_CHECK_STR_CONTAINS(err.message, want);
    write_png_header(path, 1000, 1000); /* within limits: the missing IDAT is the error */
    VT_CHECK_INT_EQ(open_and_read_all(path, &low, &err, NULL), VTS_ERR_BAD_INPUT);
    VT_CHECK_STR_CONTAINS(err.message, path);

    const uint32_t formats[] = {VT_SYNTH_TIFF, VT_SYNTH_JPEG, VT_SYNTH_EXR};
    const char *names[] = {"limit.tif", "limit.jpg", "limit.exr"};
    struct vt_input_limits tiny = {97 * 61 - 1};
    for (int i = 0; i < 3; i++) {
        struct vt_synth_image_options o =
            synth(formats[i], 3, formats[i] == VT_SYNTH_EXR ? VTS_SAMPLE_F16 : VTS_SAMPLE_U8);
        if (!write_image(&o, names[i], path, sizeof path))
            continue;
        VT_CHECK_INT_EQ(vt_image_input_open(path, &tiny, &src, &err), VTS_ERR_LIMIT);
        VT_CHECK_STR_CONTAINS(err.message, "97x61 texels exceeds --max-pixels 5916");
        tiny.max_pixels++;
        VT_CHECK_INT_EQ(open_and_read_all(path, &tiny, &err, NULL), 0);
        tiny.max_pixels--;
    }
}

/* Overwrites the value of the first IFD entry with tag in a little-endian classic TIFF. */
static bool patch_tiff_tag(unsigned char *b, size_t len, uint16_t tag, uint32_t value)
{
    uint32_t ifd = b[4] | b[5] << 8 | b[6] << 16 | (uint32_t)b[7] << 24;
    if (ifd + 2 > len)
        return false;
    uint32_t count = b[ifd] | b[ifd + 1] << 8;
    for (uint32_t i = 0; i < count && ifd + 2 + 12 * (i + 1) <= len; i++) {
        unsigned char *e = b + ifd + 2 + 12 * i;
        if ((e[0] | e[1] << 8) == tag) {
            for (int k = 0; k < 4; k++)
                e[8 + k] = (unsigned char)(value >> (8 * k));
            return true;
        }
    }
    return false;
}

static void bad_headers_are_refused(void)
{
    char path[256];
    struct vts_error err = {0};
    struct vt_source src;
    struct vt_synth_image_options o = synth(VT_SYNTH_TIFF, 1, VTS_SAMPLE_U8);
    o.compression = VT_SYNTH_TIFF_NONE;
    if (write_image(&o, "zero_width.tif", path, sizeof path)) {
        size_t len;
        unsigned char *b = read_bytes(path, &len);
        VT_CHECK(b && patch_tiff_tag(b, len, 256, 0));
        VT_CHECK(b && write_bytes(path, b, len));
        free(b);
        VT_CHECK_INT_EQ(vt_image_input_open(path, NULL, &src, &err), VTS_ERR_BAD_INPUT);
        VT_CHECK_STR_CONTAINS(err.message, path);
    }
    o = synth(VT_SYNTH_TIFF, 4, VTS_SAMPLE_U8);
    o.extra_channels = 1;
    if (write_image(&o, "five_channels.tif", path, sizeof path)) {
        VT_CHECK_INT_EQ(vt_image_input_open(path, NULL, &src, &err), VTS_ERR_UNSUPPORTED);
        VT_CHECK_STR_CONTAINS(err.message, "5 channels");
    }
    o = synth(VT_SYNTH_EXR, 4, VTS_SAMPLE_F16);
    o.exr_channels = "P,Q,S,T,U";
    if (write_image(&o, "five_channels.exr", path, sizeof path)) {
        VT_CHECK_INT_EQ(vt_image_input_open(path, NULL, &src, &err), VTS_ERR_UNSUPPORTED);
        VT_CHECK_STR_CONTAINS(err.message, "5 channels");
    }
    tmp_path(path, sizeof path, "empty.png");
    VT_CHECK(write_bytes(path, "", 0));
    VT_CHECK_INT_EQ(vt_image_input_open(path, NULL, &src, &err), VTS_ERR_BAD_INPUT);
    tmp_path(path, sizeof path, "missing.tif");
    VT_CHECK_INT_EQ(vt_image_input_open(path, NULL, &src, &err), VTS_ERR_IO);
    VT_CHECK_STR_CONTAINS(err.message, path);
    VT_CHECK(src.ops == NULL && src.ctx == NULL);
}

static void unknown_bytes_are_refused(void)
{
    char path[256];
    struct vts_error err = {0};
    struct vt_source src;
    const char text[] = "this is not an image, whatever the name says\n";
    tmp_path(path, sizeof path, "notes.bin");
    VT_CHECK(write_bytes(path, text, sizeof text - 1));
    VT_CHECK_INT_EQ(vt_image_input_open(path, NULL, &src, &err), VTS_ERR_UNSUPPORTED);
    VT_CHECK_STR_CONTAINS(err.message, path);
    /* named .tga: OpenImageIO's TGA reader takes it and reports what is wrong */
    tmp_path(path, sizeof path, "notes.tga");
    VT_CHECK(write_bytes(path, text, sizeof text - 1));
#ifdef VT_TEST_HAVE_OIIO
    VT_CHECK_INT_EQ(vt_image_input_open(path, NULL, &src, &err), VTS_ERR_BAD_INPUT);
#else
    VT_CHECK_INT_EQ(vt_image_input_open(path, NULL, &src, &err), VTS_ERR_UNSUPPORTED);
#endif
    VT_CHECK_STR_CONTAINS(err.message, path);
}

/* ---- threads ---- */

struct thread_job {
    struct vt_synth_image_options o;
    char path[256];
    int failures;
};

static void *thread_read(void *arg)
{
    struct thread_job *job = arg;
    for (int round = 0; round < 3; round++) {
        struct vts_error err = {0};
        if (open_and_read_all(job->path, NULL, &err, &job->o) != 0)
            job->failures++;
    }
    return NULL;
}

static void sources_in_different_threads_work(void)
{
    struct thread_job jobs[4];
    const uint32_t formats[] = {VT_SYNTH_TIFF, VT_SYNTH_PNG, VT_SYNTH_EXR, VT_SYNTH_TIFF};
    pthread_t threads[4];
    for (int i = 0; i < 4; i++) {
        memset(&jobs[i], 0, sizeof jobs[i]);
        jobs[i].o =
            synth(formats[i], 4, formats[i] == VT_SYNTH_EXR ? VTS_SAMPLE_F32 : VTS_SAMPLE_U16);
        jobs[i].o.width = 300, jobs[i].o.height = 200, jobs[i].o.seed = (uint32_t)i + 7;
        if (i == 3)
            jobs[i].o.tile_w = jobs[i].o.tile_h = 64;
        char name[32];
        snprintf(name, sizeof name, "thread%d", i);
        write_image(&jobs[i].o, name, jobs[i].path, sizeof jobs[i].path);
    }
    for (int i = 0; i < 4; i++)
        VT_CHECK_INT_EQ(pthread_create(&threads[i], NULL, thread_read, &jobs[i]), 0);
    for (int i = 0; i < 4; i++) {
        pthread_join(threads[i], NULL);
        VT_CHECK_INT_EQ(jobs[i].failures, 0);
    }
}

static void remove_tmp_dir(void)
{
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmp_dir);
    if (system(cmd) != 0)
        fprintf(stderr, "cannot remove %s\n", tmp_dir);
}

int main(void)
{
    snprintf(tmp_dir, sizeof tmp_dir, "/tmp/test_vt_image_input.XXXXXX");
    if (!mkdtemp(tmp_dir)) {
        perror("mkdtemp");
        return 1;
    }
    VT_CHECK(!oiio_is_loaded()); /* the test binary does not link OpenImageIO */
    VT_RUN(tiff_reads_every_layout_and_sample_type);
    VT_RUN(tiff_expands_low_bits_palettes_and_min_is_white);
    VT_RUN(png_reads_every_colour_type);
    VT_RUN(jpeg_regions_equal_a_full_decode);
    VT_RUN(exr_maps_channels_by_name_in_every_layout);
    VT_RUN(limits_are_checked_before_decoding);
    VT_RUN(bad_headers_are_refused);
    VT_RUN(damaged_files_fail_cleanly);
    VT_RUN(sources_in_different_threads_work);
    VT_CHECK(!oiio_is_loaded()); /* the native readers never load it */
    VT_RUN(fallback_reads_tga_and_loads_oiio_only_then);
    VT_RUN(unknown_bytes_are_refused);
    remove_tmp_dir();
    return vt_test_main_result();
}
