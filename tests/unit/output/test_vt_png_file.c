/* Tests of the streaming PNG file writer and the PNG file reader (formats/output/vt_png_file.c). */
#include <dirent.h>
#include <errno.h>
#include <signal.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include "output_fixture.h"
#include "vt_codec.h"
#include "vt_png_file.h"
#include "vt_test.h"

static void write_bytes(const char *path, const void *data, size_t len)
{
    FILE *f = fopen(path, "wb");
    VT_CHECK(f != NULL);
    if (f) {
        VT_CHECK_INT_EQ(fwrite(data, 1, len, f), len);
        fclose(f);
    }
}

static unsigned char *read_bytes(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    fseek(f, 0, SEEK_END);
    *len = (size_t)ftell(f);
    fseek(f, 0, SEEK_SET);
    unsigned char *p = malloc(*len + 1);
    if (fread(p, 1, *len, f) != *len) {
        free(p);
        p = NULL;
    }
    fclose(f);
    return p;
}

/* Writes the rows of pixels (stride bytes apart) in chunks of chunk_rows; returns finish's status.
 */
static int write_png(const char *path, uint32_t w, uint32_t h, uint32_t channels, uint32_t depth,
                     const unsigned char *pixels, size_t stride, uint32_t chunk_rows,
                     struct vts_error *err)
{
    struct vt_png_file_writer *wr = vt_png_file_writer_create(path, w, h, channels, depth, err);
    if (!wr)
        return err->status;
    int rc = 0;
    for (uint32_t y = 0; y < h && rc == 0; y += chunk_rows) {
        uint32_t n = h - y < chunk_rows ? h - y : chunk_rows;
        rc = vt_png_file_writer_rows(wr, pixels + (size_t)y * stride, n, stride, err);
    }
    if (rc == 0)
        rc = vt_png_file_writer_finish(wr, err);
    vt_png_file_writer_destroy(wr);
    return rc;
}

/* True when img holds w x h x channels texels of depth bits equal to pixels (stride apart). */
static bool image_matches(const struct vt_image *img, uint32_t w, uint32_t h, uint32_t channels,
                          uint32_t depth, const unsigned char *pixels, size_t stride)
{
    size_t row = (size_t)w * channels * (depth / 8);
    if (img->width != w || img->height != h || img->channels != channels ||
        img->sample != (depth == 16 ? VTS_SAMPLE_U16 : VTS_SAMPLE_U8))
        return false;
    for (uint32_t y = 0; y < h; y++)
        if (memcmp((const char *)img->pixels + y * img->stride, pixels + y * stride, row) != 0)
            return false;
    return true;
}

/* ---- writer ---- */

static void writer_round_trips_rgba8_in_row_chunks(void)
{
    const uint32_t w = 300, h = 7;
    const size_t stride = w * 4 + 16;
    unsigned char *pixels = malloc(stride * h);
    rng_state = 1;
    rng_fill(pixels, stride * h);
    struct vts_error err = {0};
    const char *path = test_path("rgba8.png");
    VT_CHECK_INT_EQ(write_png(path, w, h, 4, 8, pixels, stride, 3, &err), 0);
    struct vt_image img;
    VT_CHECK_INT_EQ(vt_png_file_read(path, &img, &err), 0);
    VT_CHECK(image_matches(&img, w, h, 4, 8, pixels, stride));
    vt_image_release(&img);
    VT_CHECK_INT_EQ(dir_entry_count(), 1); /* no temporary file left behind */
    unlink(path);
    free(pixels);
}

static void writer_round_trips_gray16(void)
{
    const uint32_t w = 257, h = 5;
    uint16_t *pixels = malloc(sizeof *pixels * w * h);
    rng_state = 2;
    rng_fill(pixels, sizeof *pixels * w * h);
    pixels[0] = 0x0102; /* bytes that differ, so a swap shows */
    struct vts_error err = {0};
    const char *path = test_path("gray16.png");
    VT_CHECK_INT_EQ(write_png(path, w, h, 1, 16, (unsigned char *)pixels, w * 2, 2, &err), 0);
    struct vt_image img;
    VT_CHECK_INT_EQ(vt_png_file_read(path, &img, &err), 0);
    VT_CHECK(image_matches(&img, w, h, 1, 16, (unsigned char *)pixels, w * 2));
    vt_image_release(&img);
    /* the same bytes decode through the tile codec (a second libpng read path) */
    size_t len = 0;
    unsigned char *file = read_bytes(path, &len);
    VT_CHECK(file != NULL);
    VT_CHECK_INT_EQ(vt_image_alloc(&img, w, h, 1, VTS_SAMPLE_U16, &err), 0);
    VT_CHECK_INT_EQ(vt_codec_find("png")->decode(file, len, &img, &err), 0);
    VT_CHECK(image_matches(&img, w, h, 1, 16, (unsigned char *)pixels, w * 2));
    vt_image_release(&img);
    free(file);
    unlink(path);
    free(pixels);
}

static void writer_destroyed_unfinished_leaves_no_file(void)
{
    unsigned char row[40 * 3] = {0};
    struct vts_error err = {0};
    const char *path = test_path("unfinished.png");
    struct vt_png_file_writer *w = vt_png_file_writer_create(path, 40, 4, 3, 8, &err);
    VT_CHECK(w != NULL);
    VT_CHECK_INT_EQ(vt_png_file_writer_rows(w, row, 1, sizeof row, &err), 0);
    VT_CHECK_INT_EQ(vt_png_file_writer_rows(w, row, 1, 0, &err), 0);
    VT_CHECK_INT_EQ(vt_png_file_writer_finish(w, &err), VTS_ERR_ARG); /* 2 of 4 rows */
    VT_CHECK_STR_CONTAINS(err.message, "2 of 4 rows");
    VT_CHECK_INT_EQ(vt_png_file_writer_rows(w, row, 3, sizeof row, &err), VTS_ERR_ARG);
    VT_CHECK_INT_EQ(vt_png_file_writer_rows(w, row, 2, sizeof row - 1, &err), VTS_ERR_ARG);
    vt_png_file_writer_destroy(w);
    VT_CHECK(!file_exists(path));
    VT_CHECK_INT_EQ(dir_entry_count(), 0);
    w = vt_png_file_writer_create(path, 40, 4, 3, 8, &err); /* destroyed before any row */
    vt_png_file_writer_destroy(w);
    VT_CHECK(!file_exists(path));
    VT_CHECK_INT_EQ(dir_entry_count(), 0);
    vt_png_file_writer_destroy(NULL);
}

static void writer_keeps_previous_file_until_finish(void)
{
    const char *path = test_path("previous.png");
    write_bytes(path, "old", 3);
    unsigned char row[2 * 2] = {1, 2, 3, 4};
    struct vts_error err = {0};
    struct vt_png_file_writer *w = vt_png_file_writer_create(path, 2, 1, 2, 8, &err);
    VT_CHECK_INT_EQ(vt_png_file_writer_rows(w, row, 1, 0, &err), 0);
    vt_png_file_writer_destroy(w);
    size_t len = 0;
    unsigned char *old = read_bytes(path, &len);
    VT_CHECK(old && len == 3 && memcmp(old, "old", 3) == 0);
    free(old);
    VT_CHECK_INT_EQ(write_png(path, 2, 1, 2, 8, row, 4, 1, &err), 0);
    struct vt_image img;
    VT_CHECK_INT_EQ(vt_png_file_read(path, &img, &err), 0);
    VT_CHECK(image_matches(&img, 2, 1, 2, 8, row, 4));
    vt_image_release(&img);
    unlink(path);
}

static void writer_into_missing_directory_fails_with_path(void)
{
    char path[512];
    snprintf(path, sizeof path, "%s/no-such-dir/out.png", test_dir);
    struct vts_error err = {0};
    VT_CHECK(vt_png_file_writer_create(path, 4, 4, 4, 8, &err) == NULL);
    VT_CHECK_INT_EQ(err.status, VTS_ERR_IO);
    VT_CHECK_STR_CONTAINS(err.message, path);
    VT_CHECK(vt_png_file_writer_create(path, 0, 4, 4, 8, &err) == NULL);
    VT_CHECK_INT_EQ(err.status, VTS_ERR_ARG);
    VT_CHECK(vt_png_file_writer_create(path, 4, 4, 5, 8, &err) == NULL);
    VT_CHECK_INT_EQ(err.status, VTS_ERR_ARG);
    VT_CHECK(vt_png_file_writer_create(path, 4, 4, 4, 12, &err) == NULL);
    VT_CHECK_INT_EQ(err.status, VTS_ERR_ARG);
}

/* A file size limit makes write() fail (EFBIG) the way a full disk does (ENOSPC). */
static void writer_reports_write_errors_with_path(void)
{
    const uint32_t w = 1024, h = 512;
    unsigned char *pixels = malloc((size_t)w * 4 * h);
    rng_state = 3;
    rng_fill(pixels, (size_t)w * 4 * h); /* noise: ~2 MiB of PNG */
    struct rlimit old_limit, limit;
    VT_CHECK_INT_EQ(getrlimit(RLIMIT_FSIZE, &old_limit), 0);
    limit = old_limit;
    limit.rlim_cur = 256 * 1024;
    void (*old_handler)(int) = signal(SIGXFSZ, SIG_IGN);
    VT_CHECK_INT_EQ(setrlimit(RLIMIT_FSIZE, &limit), 0);
    struct vts_error err = {0};
    const char *path = test_path("too-big.png");
    int rc = write_png(path, w, h, 4, 8, pixels, (size_t)w * 4, 64, &err);
    setrlimit(RLIMIT_FSIZE, &old_limit);
    signal(SIGXFSZ, old_handler);
    VT_CHECK_INT_EQ(rc, VTS_ERR_IO);
    VT_CHECK_STR_CONTAINS(err.message, path);
    VT_CHECK(!file_exists(path));
    VT_CHECK_INT_EQ(dir_entry_count(), 0);
    free(pixels);
}

/* ---- reader ---- */

/* Hand-made PNGs (written by a Python script, not by libpng). */
static const unsigned char fixture_gray16_2x1[] = {/* samples 0x0102, 0xa0b0 */
                                                   0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a,
                                                   0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44, 0x52,
                                                   0x00, 0x00, 0x00, 0x02, 0x00, 0x00, 0x00, 0x01,
                                                   0x10, 0x00, 0x00, 0x00, 0x00, 0x81, 0xd9, 0xfc,
                                                   0x15, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x44, 0x41,
                                                   0x54, 0x78, 0x9c, 0x63, 0x60, 0x64, 0x5a, 0xb0,
                                                   0x01, 0x00, 0x01, 0xff, 0x01, 0x54, 0x8e, 0x7d,
                                                   0x8e, 0x40, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45,
                                                   0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
/* 4x1 palette {red, green, blue}, tRNS {128, 255}; indices 0 1 2 0 */
static const unsigned char fixture_palette_trns_4x1[] = {
    0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44,
    0x52, 0x00, 0x00, 0x00, 0x04, 0x00, 0x00, 0x00, 0x01, 0x08, 0x03, 0x00, 0x00, 0x00, 0xce,
    0xe2, 0xff, 0xff, 0x00, 0x00, 0x00, 0x09, 0x50, 0x4c, 0x54, 0x45, 0xff, 0x00, 0x00, 0x00,
    0xff, 0x00, 0x00, 0x00, 0xff, 0x2d, 0x4a, 0xcd, 0x8a, 0x00, 0x00, 0x00, 0x02, 0x74, 0x52,
    0x4e, 0x53, 0x80, 0xff, 0x60, 0x12, 0xba, 0xfe, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x44, 0x41,
    0x54, 0x78, 0x9c, 0x63, 0x60, 0x60, 0x64, 0x62, 0x00, 0x00, 0x00, 0x0c, 0x00, 0x04, 0xc9,
    0x98, 0x95, 0x93, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
/* 8x1 1-bit gray, bits 10110000 */
static const unsigned char fixture_gray1_8x1[] = {
    0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48,
    0x44, 0x52, 0x00, 0x00, 0x00, 0x08, 0x00, 0x00, 0x00, 0x01, 0x01, 0x00, 0x00, 0x00,
    0x00, 0xcb, 0x7b, 0xd2, 0xee, 0x00, 0x00, 0x00, 0x0a, 0x49, 0x44, 0x41, 0x54, 0x78,
    0x9c, 0x63, 0xd8, 0x00, 0x00, 0x00, 0xb2, 0x00, 0xb1, 0x55, 0x0a, 0xe8, 0x2a, 0x00,
    0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
/* IHDR of a 65536x32769 RGBA8 image (2^31 + 2^16 texels), then a short IDAT and IEND */
static const unsigned char fixture_huge_header[] = {
    0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48,
    0x44, 0x52, 0x00, 0x01, 0x00, 0x00, 0x00, 0x00, 0x80, 0x01, 0x08, 0x06, 0x00, 0x00,
    0x00, 0xe3, 0x64, 0x09, 0x2a, 0x00, 0x00, 0x00, 0x0b, 0x49, 0x44, 0x41, 0x54, 0x78,
    0x9c, 0x63, 0x60, 0x80, 0x01, 0x00, 0x00, 0x0a, 0x00, 0x01, 0x7f, 0x80, 0x74, 0x5e,
    0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};

/* Writes data to a file and reads it back with vt_png_file_read(). */
static int read_fixture(const char *name, const unsigned char *data, size_t len,
                        struct vt_image *img, struct vts_error *err)
{
    const char *path = test_path(name);
    write_bytes(path, data, len);
    int rc = vt_png_file_read(path, img, err);
    unlink(path);
    return rc;
}

static void reader_keeps_16bit_samples_in_host_order(void)
{
    struct vt_image img;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(
        read_fixture("g16.png", fixture_gray16_2x1, sizeof fixture_gray16_2x1, &img, &err), 0);
    VT_CHECK(img.width == 2 && img.height == 1 && img.channels == 1 &&
             img.sample == VTS_SAMPLE_U16);
    const uint16_t *t = img.pixels;
    VT_CHECK(t && t[0] == 0x0102 && t[1] == 0xa0b0);
    vt_image_release(&img);
}

static void reader_expands_palette_transparency_and_low_bit_gray(void)
{
    struct vt_image img;
    struct vts_error err = {0};
    VT_CHECK_INT_EQ(read_fixture("pal.png", fixture_palette_trns_4x1,
                                 sizeof fixture_palette_trns_4x1, &img, &err),
                    0);
    static const unsigned char rgba[16] = {255, 0, 0,   128, 0,   255, 0, 255,
                                           0,   0, 255, 255, 255, 0,   0, 128};
    VT_CHECK(image_matches(&img, 4, 1, 4, 8, rgba, sizeof rgba));
    vt_image_release(&img);
    VT_CHECK_INT_EQ(read_fixture("g1.png", fixture_gray1_8x1, sizeof fixture_gray1_8x1, &img, &err),
                    0);
    static const unsigned char gray[8] = {255, 0, 255, 255, 0, 0, 0, 0};
    VT_CHECK(image_matches(&img, 8, 1, 1, 8, gray, sizeof gray));
    vt_image_release(&img);
}

static void reader_rejects_missing_and_non_png_files(void)
{
    struct vt_image img;
    struct vts_error err = {0};
    const char *path = test_path("missing.png");
    VT_CHECK_INT_EQ(vt_png_file_read(path, &img, &err), VTS_ERR_IO);
    VT_CHECK_STR_CONTAINS(err.message, path);
    VT_CHECK(img.pixels == NULL);
    VT_CHECK_INT_EQ(read_fixture("text.png", (const unsigned char *)"hello, world", 12, &img, &err),
                    VTS_ERR_BAD_INPUT);
    VT_CHECK_STR_CONTAINS(err.message, "text.png': not a PNG file");
    VT_CHECK_INT_EQ(read_fixture("empty.png", (const unsigned char *)"", 0, &img, &err),
                    VTS_ERR_BAD_INPUT);
    VT_CHECK_STR_CONTAINS(err.message, "not a PNG file");
    VT_CHECK_INT_EQ(
        read_fixture("huge.png", fixture_huge_header, sizeof fixture_huge_header, &img, &err),
        VTS_ERR_LIMIT);
    VT_CHECK_STR_CONTAINS(err.message, "huge.png");
    VT_CHECK(img.pixels == NULL);
}

static void reader_rejects_truncated_files(void)
{
    const uint32_t w = 37, h = 11;
    unsigned char pixels[37 * 11 * 3];
    rng_state = 4;
    rng_fill(pixels, sizeof pixels);
    struct vts_error err = {0};
    const char *path = test_path("whole.png");
    VT_CHECK_INT_EQ(write_png(path, w, h, 3, 8, pixels, w * 3, 4, &err), 0);
    size_t len = 0;
    unsigned char *file = read_bytes(path, &len);
    unlink(path);
    int failures = 0;
    for (size_t cut = 8; file && cut < len; cut += 7) {
        struct vt_image img;
        int rc = read_fixture("cut.png", file, cut, &img, &err);
        if (rc != VTS_ERR_BAD_INPUT || !strstr(err.message, "cut.png") || img.pixels) {
            fprintf(stderr, "  cut %zu of %zu: rc %d '%s'\n", cut, len, rc, err.message);
            failures++;
        }
    }
    VT_CHECK_INT_EQ(failures, 0);
    free(file);
}

int main(void)
{
    const char *tmp = getenv("TMPDIR");
    snprintf(test_dir, sizeof test_dir, "%s/test_vt_png_file.XXXXXX", tmp && *tmp ? tmp : "/tmp");
    if (!mkdtemp(test_dir)) {
        perror("mkdtemp");
        return 1;
    }
    VT_RUN(writer_round_trips_rgba8_in_row_chunks);
    VT_RUN(writer_round_trips_gray16);
    VT_RUN(writer_destroyed_unfinished_leaves_no_file);
    VT_RUN(writer_keeps_previous_file_until_finish);
    VT_RUN(writer_into_missing_directory_fails_with_path);
    VT_RUN(writer_reports_write_errors_with_path);
    VT_RUN(reader_keeps_16bit_samples_in_host_order);
    VT_RUN(reader_expands_palette_transparency_and_low_bit_gray);
    VT_RUN(reader_rejects_missing_and_non_png_files);
    VT_RUN(reader_rejects_truncated_files);
    if (rmdir(test_dir) != 0)
        fprintf(stderr, "cannot remove %s: %s\n", test_dir, strerror(errno));
    return vt_test_main_result();
}
