/* vt_image_input_open(): recognises the format by its first bytes (each reader's sniff()) and
 * hands the file to that reader, or to the OpenImageIO fallback. */
#include "vt_image_input.h"

#include <errno.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>

#include "internal/vt_input_readers.h"
#include "internal/vt_input_util.h"
#include "vt_error.h"

/* Asked in this order; the first whose magic matches opens the file. */
static const struct vt_input_reader *const input_readers[] = {
    &vt_input_reader_tiff,
    &vt_input_reader_png,
    &vt_input_reader_jpeg,
    &vt_input_reader_exr,
};

static const struct vt_input_reader *input_reader_for(const unsigned char *magic, size_t len)
{
    for (size_t i = 0; i < sizeof input_readers / sizeof input_readers[0]; i++)
        if (input_readers[i]->sniff(magic, len))
            return input_readers[i];
    return &vt_input_reader_oiio;
}

/* Reads up to 8 bytes from the start of path into magic; *len gets the count. */
static int input_read_magic(const char *path, unsigned char magic[8], size_t *len,
                            struct vts_error *err)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return vt_error_set(err, VTS_ERR_IO, "cannot open '%s': %s", path, strerror(errno));
    *len = fread(magic, 1, 8, f);
    int read_errno = ferror(f) ? errno : 0;
    fclose(f);
    if (read_errno)
        return vt_error_set(err, VTS_ERR_IO, "cannot read '%s': %s", path, strerror(read_errno));
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
    rc = input_reader_for(magic, len)->open(path, max_pixels, out, err);
    if (rc < 0) {
        memset(out, 0, sizeof *out);
        return rc;
    }
    vt_input_copy_name(out->name, sizeof out->name, path);
    return 0;
}
