/* vt_image_input_open(): recognises the format by its first bytes and hands the file to its
 * reader; checks shared by the readers. */
#include "vt_image_input.h"

#include <errno.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>

#include "internal/vt_input_impl.h"
#include "vt_checked.h"
#include "vt_error.h"

enum input_kind { INPUT_OTHER, INPUT_TIFF, INPUT_PNG, INPUT_JPEG, INPUT_EXR };

static enum input_kind input_kind_of(const unsigned char *magic, size_t len)
{
    static const unsigned char png[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    static const unsigned char exr[4] = {0x76, 0x2f, 0x31, 0x01};
    if (len >= 4 && ((magic[0] == 'I' && magic[1] == 'I' && magic[3] == 0 &&
                      (magic[2] == 42 || magic[2] == 43)) ||
                     (magic[0] == 'M' && magic[1] == 'M' && magic[2] == 0 &&
                      (magic[3] == 42 || magic[3] == 43))))
        return INPUT_TIFF;
    if (len >= 8 && memcmp(magic, png, 8) == 0)
        return INPUT_PNG;
    if (len >= 3 && magic[0] == 0xff && magic[1] == 0xd8 && magic[2] == 0xff)
        return INPUT_JPEG;
    if (len >= 4 && memcmp(magic, exr, 4) == 0)
        return INPUT_EXR;
    return INPUT_OTHER;
}

/* Reads up to 8 bytes from the start of path into magic; *len gets the count. */
static int input_read_magic(const char *path, unsigned char magic[8], size_t *len,
                            struct vts_error *err)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return vt_error_set(err, VTS_ERR_IO, "cannot open '%s': %s", path, strerror(errno));
    *len = fread(magic, 1, 8, f);
    int read_failed = ferror(f);
    fclose(f);
    if (read_failed)
        return vt_error_set(err, VTS_ERR_IO, "cannot read '%s': read error", path);
    if (*len == 0)
        return vt_error_set(err, VTS_ERR_BAD_INPUT, "cannot read '%s': empty file", path);
    return 0;
}

int vt_image_input_open(const char *path, const struct vt_input_limits *limits,
                        struct vt_source *out, struct vts_error *err)
{
    memset(out, 0, sizeof *out);
    if (!path || !path[0])
        return vt_error_set(err, VTS_ERR_ARG, "cannot open an image: empty path");
    uint64_t max_pixels =
        limits && limits->max_pixels ? limits->max_pixels : VT_INPUT_DEFAULT_MAX_PIXELS;
    unsigned char magic[8];
    size_t len = 0;
    int rc = input_read_magic(path, magic, &len, err);
    if (rc < 0)
        return rc;
    switch (input_kind_of(magic, len)) {
    case INPUT_TIFF:
        rc = vt_input_tiff_open(path, max_pixels, out, err);
        break;
    case INPUT_PNG:
        rc = vt_input_png_open(path, max_pixels, out, err);
        break;
    case INPUT_JPEG:
        rc = vt_input_jpeg_open(path, max_pixels, out, err);
        break;
    case INPUT_EXR:
        rc = vt_input_exr_open(path, max_pixels, out, err);
        break;
    default:
        rc = vt_input_oiio_open(path, max_pixels, out, err);
        break;
    }
    if (rc < 0) {
        memset(out, 0, sizeof *out);
        return rc;
    }
    vt_input_copy_name(out->name, sizeof out->name, path);
    return 0;
}

int vt_input_check_size(const char *path, uint64_t width, uint64_t height, uint64_t max_pixels,
                        struct vts_error *err)
{
    if (width == 0 || height == 0)
        return vt_error_set(err, VTS_ERR_BAD_INPUT, "cannot read '%s': image size %llux%llu", path,
                            (unsigned long long)width, (unsigned long long)height);
    uint64_t pixels;
    if (width > UINT32_MAX || height > UINT32_MAX || !vt_u64_mul(width, height, &pixels) ||
        pixels > max_pixels)
        return vt_error_set(err, VTS_ERR_LIMIT, "'%s': %llux%llu texels exceeds --max-pixels %llu",
                            path, (unsigned long long)width, (unsigned long long)height,
                            (unsigned long long)max_pixels);
    return 0;
}

void vt_input_copy_name(char *dst, size_t dst_size, const char *path)
{
    snprintf(dst, dst_size, "%s", path);
}

void vt_input_set_info(struct vt_source_info *info, uint32_t width, uint32_t height,
                       uint32_t channels, uint32_t sample, bool sequential, uint32_t tile_w,
                       uint32_t tile_h, const char *format)
{
    memset(info, 0, sizeof *info);
    info->width = width;
    info->height = height;
    info->channels = channels;
    info->sample = sample;
    info->colour = (sample == VTS_SAMPLE_F16 || sample == VTS_SAMPLE_F32) ? VTS_COLOUR_LINEAR
                                                                          : VTS_COLOUR_SRGB;
    info->has_alpha = channels == 2 || channels == 4;
    info->sequential = sequential;
    info->tile_w = tile_w;
    info->tile_h = tile_h;
    snprintf(info->format, sizeof info->format, "%s", format);
}
