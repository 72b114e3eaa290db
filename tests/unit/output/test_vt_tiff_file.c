/* Tests of the streaming TIFF file writer (formats/output/vt_tiff_file.c): files read back with
 * libtiff, texel for texel; failures leave no file and say why. */
#include <dirent.h>
#include <errno.h>
#include <signal.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <tiffio.h>
#include <unistd.h>

#include "output_fixture.h"
#include "vt_test.h"
#include "vt_tiff_file.h"

/* Writes the rows of pixels (stride bytes apart) in chunks of chunk_rows; returns finish's status.
 */
static int write_tiff(const char *path, uint32_t w, uint32_t h, uint32_t channels,
                      const unsigned char *pixels, size_t stride, uint32_t chunk_rows,
                      struct vts_error *err)
{
    struct vt_tiff_file_writer *wr = vt_tiff_file_writer_create(path, w, h, channels, err);
    if (!wr)
        return err->status;
    int rc = 0;
    for (uint32_t y = 0; y < h && rc == 0; y += chunk_rows) {
        uint32_t n = h - y < chunk_rows ? h - y : chunk_rows;
        rc = vt_tiff_file_writer_rows(wr, pixels + (size_t)y * stride, n, stride, err);
    }
    if (rc == 0)
        rc = vt_tiff_file_writer_finish(wr, err);
    vt_tiff_file_writer_destroy(wr);
    return rc;
}

/* Opens path with libtiff and checks its tags and every texel against pixels (stride apart). */
static void check_tiff(const char *path, uint32_t w, uint32_t h, uint32_t channels,
                       const unsigned char *pixels, size_t stride)
{
    TIFF *tif = TIFFOpen(path, "r");
    VT_CHECK(tif != NULL);
    if (!tif)
        return;
    uint32_t tw = 0, th = 0, rps = 0;
    uint16_t spp = 0, bps = 0, photometric = 0, planar = 0, compression = 0, extra_n = 0;
    uint16_t *extra = NULL;
    TIFFGetField(tif, TIFFTAG_IMAGEWIDTH, &tw);
    TIFFGetField(tif, TIFFTAG_IMAGELENGTH, &th);
    TIFFGetField(tif, TIFFTAG_SAMPLESPERPIXEL, &spp);
    TIFFGetField(tif, TIFFTAG_BITSPERSAMPLE, &bps);
    TIFFGetField(tif, TIFFTAG_PHOTOMETRIC, &photometric);
    TIFFGetField(tif, TIFFTAG_PLANARCONFIG, &planar);
    TIFFGetField(tif, TIFFTAG_COMPRESSION, &compression);
    TIFFGetField(tif, TIFFTAG_ROWSPERSTRIP, &rps);
    TIFFGetFieldDefaulted(tif, TIFFTAG_EXTRASAMPLES, &extra_n, &extra);
    VT_CHECK_INT_EQ(tw, w);
    VT_CHECK_INT_EQ(th, h);
    VT_CHECK_INT_EQ(spp, channels);
    VT_CHECK_INT_EQ(bps, 8);
    VT_CHECK_INT_EQ(photometric, channels >= 3 ? PHOTOMETRIC_RGB : PHOTOMETRIC_MINISBLACK);
    VT_CHECK_INT_EQ(planar, PLANARCONFIG_CONTIG);
    VT_CHECK_INT_EQ(compression, COMPRESSION_ADOBE_DEFLATE);
    VT_CHECK_INT_EQ(rps, VT_TIFF_FILE_ROWS_PER_STRIP);
    VT_CHECK_INT_EQ(extra_n, channels == 2 || channels == 4 ? 1 : 0);
    if (extra_n == 1)
        VT_CHECK_INT_EQ(extra[0], EXTRASAMPLE_UNASSALPHA);
    VT_CHECK(!TIFFIsBigTIFF(tif));
    size_t row_bytes = (size_t)w * channels;
    unsigned char *row = malloc(row_bytes);
    int bad_rows = 0;
    for (uint32_t y = 0; row && y < h; y++)
        if (TIFFReadScanline(tif, row, y, 0) < 0 ||
            memcmp(row, pixels + (size_t)y * stride, row_bytes) != 0)
            bad_rows++;
    VT_CHECK_INT_EQ(bad_rows, 0);
    free(row);
    TIFFClose(tif);
}

/* ---- writer ---- */

static void writer_round_trips_every_channel_count(void)
{
    const uint32_t w = 203, h = 150; /* 3 strips, the last one short */
    for (uint32_t channels = 1; channels <= 4; channels++) {
        const size_t stride = w * channels + 5;
        unsigned char *pixels = malloc(stride * h);
        rng_state = channels;
        rng_fill(pixels, stride * h);
        struct vts_error err = {0};
        char name[32];
        snprintf(name, sizeof name, "c%u.tif", channels);
        const char *path = test_path(name);
        VT_CHECK_INT_EQ(write_tiff(path, w, h, channels, pixels, stride, 37, &err), 0);
        check_tiff(path, w, h, channels, pixels, stride);
        VT_CHECK_INT_EQ(dir_entry_count(), 1); /* no temporary file left behind */
        unlink(path);
        free(pixels);
    }
}

static void writer_destroyed_unfinished_leaves_no_file(void)
{
    unsigned char rows[4][40 * 3] = {{0}};
    struct vts_error err = {0};
    const char *path = test_path("unfinished.tif");
    struct vt_tiff_file_writer *w = vt_tiff_file_writer_create(path, 40, 4, 3, &err);
    VT_CHECK(w != NULL);
    if (!w)
        return;
    VT_CHECK_INT_EQ(vt_tiff_file_writer_rows(w, rows, 2, sizeof rows[0], &err), 0);
    VT_CHECK_INT_EQ(vt_tiff_file_writer_rows(w, rows, 3, sizeof rows[0], &err), VTS_ERR_ARG);
    VT_CHECK_INT_EQ(vt_tiff_file_writer_finish(w, &err), VTS_ERR_ARG); /* 2 of 4 rows */
    VT_CHECK_STR_CONTAINS(err.message, "2 of 4 rows");
    vt_tiff_file_writer_destroy(w);
    VT_CHECK(!file_exists(path));
    VT_CHECK_INT_EQ(dir_entry_count(), 0);
    w = vt_tiff_file_writer_create(path, 40, 4, 3, &err); /* destroyed before any row */
    vt_tiff_file_writer_destroy(w);
    VT_CHECK(!file_exists(path));
    VT_CHECK_INT_EQ(dir_entry_count(), 0);
    vt_tiff_file_writer_destroy(NULL);
}

static void writer_keeps_previous_file_until_finish(void)
{
    const char *path = test_path("previous.tif");
    FILE *f = fopen(path, "wb");
    VT_CHECK(f != NULL);
    if (f) {
        fputs("old", f);
        fclose(f);
    }
    unsigned char row[2 * 2] = {1, 2, 3, 4};
    struct vts_error err = {0};
    struct vt_tiff_file_writer *w = vt_tiff_file_writer_create(path, 2, 1, 2, &err);
    VT_CHECK_INT_EQ(vt_tiff_file_writer_rows(w, row, 1, 0, &err), 0);
    vt_tiff_file_writer_destroy(w);
    struct stat st;
    VT_CHECK(stat(path, &st) == 0 && st.st_size == 3);
    VT_CHECK_INT_EQ(write_tiff(path, 2, 1, 2, row, 4, 1, &err), 0);
    check_tiff(path, 2, 1, 2, row, 4);
    unlink(path);
}

/* A directory that cannot take the file: one line naming the path, and no file anywhere. */
static void writer_into_unwritable_directory_fails_with_path(void)
{
    char path[512];
    snprintf(path, sizeof path, "%s/no-such-dir/out.tif", test_dir);
    struct vts_error err = {0};
    VT_CHECK(vt_tiff_file_writer_create(path, 4, 4, 4, &err) == NULL);
    VT_CHECK_INT_EQ(err.status, VTS_ERR_IO);
    VT_CHECK_STR_CONTAINS(err.message, path);
    VT_CHECK_STR_CONTAINS(err.message, "No such file or directory");
    VT_CHECK(strchr(err.message, '\n') == NULL);
    VT_CHECK_INT_EQ(dir_entry_count(), 0);
    /* a read-only directory (root writes anyway: only checked when the mode is obeyed) */
    char dir[400];
    snprintf(dir, sizeof dir, "%s/read-only", test_dir);
    snprintf(path, sizeof path, "%s/out.tif", dir);
    VT_CHECK_INT_EQ(mkdir(dir, 0555), 0);
    if (access(dir, W_OK) != 0) {
        VT_CHECK(vt_tiff_file_writer_create(path, 4, 4, 4, &err) == NULL);
        VT_CHECK_INT_EQ(err.status, VTS_ERR_IO);
        VT_CHECK_STR_CONTAINS(err.message, path);
        VT_CHECK_STR_CONTAINS(err.message, "Permission denied");
        DIR *d = opendir(dir);
        int entries = 0;
        for (struct dirent *e; d && (e = readdir(d));)
            entries += strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0;
        if (d)
            closedir(d);
        VT_CHECK_INT_EQ(entries, 0);
    }
    rmdir(dir);
    VT_CHECK(vt_tiff_file_writer_create(path, 0, 4, 4, &err) == NULL);
    VT_CHECK_INT_EQ(err.status, VTS_ERR_ARG);
    VT_CHECK(vt_tiff_file_writer_create(path, 4, 4, 5, &err) == NULL);
    VT_CHECK_INT_EQ(err.status, VTS_ERR_ARG);
    VT_CHECK_INT_EQ(dir_entry_count(), 0);
}

/* A file size limit makes write() fail (EFBIG) the way a full disk does (ENOSPC): libtiff's
 * reason in the message, nothing printed by libtiff, no file left. */
static void writer_reports_write_errors_with_path(void)
{
    const uint32_t w = 1024, h = 512;
    unsigned char *pixels = malloc((size_t)w * 4 * h);
    rng_state = 9;
    rng_fill(pixels, (size_t)w * 4 * h); /* noise: deflate cannot shrink it */
    struct rlimit old_limit, limit;
    VT_CHECK_INT_EQ(getrlimit(RLIMIT_FSIZE, &old_limit), 0);
    limit = old_limit;
    limit.rlim_cur = 256 * 1024;
    void (*old_handler)(int) = signal(SIGXFSZ, SIG_IGN);
    VT_CHECK_INT_EQ(setrlimit(RLIMIT_FSIZE, &limit), 0);
    struct vts_error err = {0};
    const char *path = test_path("too-big.tif");
    int rc = write_tiff(path, w, h, 4, pixels, (size_t)w * 4, 64, &err);
    setrlimit(RLIMIT_FSIZE, &old_limit);
    signal(SIGXFSZ, old_handler);
    VT_CHECK_INT_EQ(rc, VTS_ERR_IO);
    VT_CHECK_STR_CONTAINS(err.message, "cannot write '");
    VT_CHECK_STR_CONTAINS(err.message, path);
    VT_CHECK(!file_exists(path));
    VT_CHECK_INT_EQ(dir_entry_count(), 0);
    free(pixels);
}

/* libtiff's own handlers print; the writer's must not reach them. */
static int printed_by_libtiff;

static void count_libtiff_message(const char *module, const char *fmt, va_list ap)
{
    (void)module, (void)fmt, (void)ap;
    printed_by_libtiff++;
}

int main(void)
{
    const char *tmp = getenv("TMPDIR");
    snprintf(test_dir, sizeof test_dir, "%s/test_vt_tiff_file.XXXXXX", tmp && *tmp ? tmp : "/tmp");
    if (!mkdtemp(test_dir)) {
        perror("mkdtemp");
        return 1;
    }
    TIFFSetErrorHandler(count_libtiff_message);
    TIFFSetWarningHandler(count_libtiff_message);
    VT_RUN(writer_round_trips_every_channel_count);
    VT_RUN(writer_destroyed_unfinished_leaves_no_file);
    VT_RUN(writer_keeps_previous_file_until_finish);
    VT_RUN(writer_into_unwritable_directory_fails_with_path);
    VT_RUN(writer_reports_write_errors_with_path);
    VT_CHECK_INT_EQ(printed_by_libtiff, 0);
    if (rmdir(test_dir) != 0)
        fprintf(stderr, "cannot remove %s: %s\n", test_dir, strerror(errno));
    return vt_test_main_result();
}
