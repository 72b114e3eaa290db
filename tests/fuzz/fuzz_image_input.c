/* libFuzzer target for image input (formats/input/vt_image_input.c and the TIFF, PNG, JPEG and
 * OpenEXR readers, scripts/fuzz). vt_image_input_open() takes a path, so each input is written to
 * one temporary file per process (reused) and opened with max_pixels = 2^22, so that huge headers
 * are refused before anything is decoded. An image that opens is read whole when small, else its
 * four corners and a middle band, top-down (how the pyramid reads sequential sources). Inputs whose
 * magic is not TIFF, PNG, JPEG or EXR are skipped: the OpenImageIO fallback is not exercised here
 * (it costs ~0.4 s to load). Invariants, not only crashes: open and every read return 0 or a
 * negative status with a one-line message naming the file; an opened image has 1..4 channels, a
 * known sample type and a size within the limit.
 *
 * Built with -DVT_FUZZ_NO_ENTRY, the file gives fuzz_image_input_one() to the regression test. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "vt_image_input.h"
#include "vts.h"

#define MAX_PIXELS     (1ull << 22)
#define SMALL_PIXELS   (256u * 256u)
#define CORNER         48u
#define BAND_ROWS      16u
#define BAND_MAX_WIDTH 2048u

/* Runs one input written at path (the caller writes it); returns the first failing status or 0. */
int fuzz_image_input_file(const char *path, struct vts_error *err);
/* Writes data to a per-process temporary file and runs it; 0 for a skipped (non-native) input. */
int fuzz_image_input_one(const uint8_t *data, size_t size, struct vts_error *err);

static void check_failure(int rc, const struct vts_error *err, const char *path)
{
    if (rc >= 0 || err->message[0] == '\0' || strchr(err->message, '\n') ||
        !strstr(err->message, path))
        abort();
}

static int native_magic(const uint8_t *m, size_t n)
{
    static const uint8_t png[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    static const uint8_t exr[4] = {0x76, 0x2f, 0x31, 0x01};
    return (n >= 4 && ((m[0] == 'I' && m[1] == 'I' && m[3] == 0 && (m[2] == 42 || m[2] == 43)) ||
                       (m[0] == 'M' && m[1] == 'M' && m[2] == 0 && (m[3] == 42 || m[3] == 43)))) ||
           (n >= 8 && memcmp(m, png, 8) == 0) ||
           (n >= 3 && m[0] == 0xff && m[1] == 0xd8 && m[2] == 0xff) ||
           (n >= 4 && memcmp(m, exr, 4) == 0);
}

static int read_region(struct vt_source *src, uint32_t x, uint32_t y, uint32_t w, uint32_t h,
                       struct vts_error *err)
{
    struct vt_image img = {0};
    if (vt_image_alloc(&img, w, h, src->info.channels, src->info.sample, err) != 0)
        abort(); /* at most 2048 x 16 or 256 x 256 texels of 16 bytes */
    int rc = vt_source_read(src, x, y, &img, err);
    vt_image_release(&img);
    if (rc != 0)
        check_failure(rc, err, src->name);
    return rc;
}

static uint32_t min_u32(uint32_t a, uint32_t b)
{
    return a < b ? a : b;
}

int fuzz_image_input_file(const char *path, struct vts_error *err)
{
    struct vt_source src = {0};
    int rc =
        vt_image_input_open(path, &(struct vt_input_limits){.max_pixels = MAX_PIXELS}, &src, err);
    if (rc != 0) {
        check_failure(rc, err, path);
        return rc;
    }
    const struct vt_source_info *in = &src.info;
    if (in->width == 0 || in->height == 0 || (uint64_t)in->width * in->height > MAX_PIXELS ||
        in->channels < 1 || in->channels > 4 || vts_sample_bytes(in->sample) == 0)
        abort();
    uint32_t w = in->width, h = in->height;
    if ((uint64_t)w * h <= SMALL_PIXELS) {
        rc = read_region(&src, 0, 0, w, h, err);
    } else {
        uint32_t cw = min_u32(w, CORNER), ch = min_u32(h, CORNER), bh = min_u32(h, BAND_ROWS);
        uint32_t bw = min_u32(w, BAND_MAX_WIDTH);
        if (!(rc = read_region(&src, 0, 0, cw, ch, err)) &&
            !(rc = read_region(&src, w - cw, 0, cw, ch, err)) &&
            !(rc = read_region(&src, (w - bw) / 2, (h - bh) / 2, bw, bh, err)) &&
            !(rc = read_region(&src, 0, h - ch, cw, ch, err)))
            rc = read_region(&src, w - cw, h - ch, cw, ch, err);
    }
    vt_source_close(&src);
    return rc;
}

static char tmp_path[512];

static void remove_tmp(void)
{
    if (tmp_path[0])
        unlink(tmp_path);
}

int fuzz_image_input_one(const uint8_t *data, size_t size, struct vts_error *err)
{
    if (!native_magic(data, size))
        return 0;
    if (!tmp_path[0]) {
        const char *dir = access("/dev/shm", W_OK) == 0 ? "/dev/shm" : getenv("TMPDIR");
        snprintf(tmp_path, sizeof tmp_path, "%s/fuzz_image_input.%ld", dir ? dir : "/tmp",
                 (long)getpid());
        atexit(remove_tmp);
    }
    FILE *f = fopen(tmp_path, "wb");
    if (!f || fwrite(data, 1, size, f) != size || fclose(f) != 0)
        abort();
    return fuzz_image_input_file(tmp_path, err);
}

#ifndef VT_FUZZ_NO_ENTRY
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    struct vts_error err = {0};
    fuzz_image_input_one(data, size, &err);
    return 0;
}
#endif
