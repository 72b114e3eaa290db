/* vt_image_input_open(): recognises the format by its first bytes (each reader's sniff()) and
 * hands the file to that reader, to GDAL (VRT, JPEG 2000, TIFFs libtiff's reader does not take) or
 * to the OpenImageIO fallback; GeoTIFFs libtiff reads as GDAL would keep their pixels native. */
#include "vt_image_input.h"

#include <errno.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>

#include "internal/vt_input_gdal.h"
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

/* Where a file goes (docs/geospatial.md, "Routing"): its pixels to a native reader, GDAL or the
 * OpenImageIO fallback; its bands' names and georeferencing to GDAL or nowhere. */
struct input_plan {
    const struct vt_input_reader *reader; /* the native reader or the fallback */
    bool pixels_gdal;                     /* pixels through GDAL */
    bool describe_gdal;                   /* band names and georeferencing through GDAL */
    bool geo;                             /* a GeoTIFF */
    bool gdal_missing;                    /* GDAL wanted, but its module cannot be loaded (why) */
    char why[160];
};

static int input_plan(const char *path, const unsigned char *magic, size_t len,
                      struct input_plan *p, struct vts_error *err)
{
    memset(p, 0, sizeof *p);
    p->reader = input_reader_for(magic, len);
    enum vt_tiff_route tiff = VT_TIFF_NATIVE;
    if (p->reader == &vt_input_reader_tiff) {
        int rc = vt_input_tiff_route(path, &tiff, err);
        if (rc < 0)
            return rc;
        p->geo = tiff != VT_TIFF_NATIVE; /* VT_TIFF_GDAL: at least needs GDAL */
        if (tiff == VT_TIFF_NATIVE)
            return 0;
    } else if (!(p->reader == &vt_input_reader_oiio && vt_input_gdal_sniff(magic, len))) {
        return 0;
    }
    if (!vt_input_gdal_available(p->why, sizeof p->why)) {
        p->gdal_missing = true;
        return 0;
    }
    p->describe_gdal = true;
    p->pixels_gdal = tiff != VT_TIFF_GEO_NATIVE;
    return 0;
}

/* Checks the path, resolves the limit, reads the magic bytes and plans where the file goes. */
static int input_start(const char *path, const struct vt_input_limits *limits, uint64_t *max_pixels,
                       struct input_plan *plan, struct vts_error *err)
{
    if (!path || !path[0])
        return vt_error_set(err, VTS_ERR_ARG, "cannot open an image: empty path");
    *max_pixels = limits && limits->max_pixels ? limits->max_pixels : VT_INPUT_DEFAULT_MAX_PIXELS;
    unsigned char magic[8];
    size_t len = 0;
    int rc = input_read_magic(path, magic, &len, err);
    if (rc < 0)
        return rc;
    return input_plan(path, magic, len, plan, err);
}

int vt_image_input_open(const char *path, const struct vt_input_limits *limits,
                        struct vt_source *out, struct vts_error *err)
{
    return vt_image_input_open_bands(path, limits, 0, 0, out, err);
}

int vt_image_input_open_bands(const char *path, const struct vt_input_limits *limits,
                              uint32_t first, uint32_t count, struct vt_source *out,
                              struct vts_error *err)
{
    memset(out, 0, sizeof *out);
    uint64_t max_pixels = 0;
    struct input_plan plan;
    int rc = input_start(path, limits, &max_pixels, &plan, err);
    if (rc < 0)
        return rc;
    if (plan.pixels_gdal) {
        rc = vt_input_gdal_open(path, max_pixels, first, count, out, err);
    } else {
        rc = plan.reader->open(path, max_pixels, out, err);
        if (rc < 0 && plan.gdal_missing) /* what GDAL would have read */
            vt_error_set(err, VTS_ERR_UNSUPPORTED,
                         "'%s': needs GDAL: cannot load the GDAL module (%s)", path, plan.why);
        if (rc == 0 && count && (first != 0 || count != out->info.channels)) {
            uint32_t bands = out->info.channels; /* before the close clears it */
            vt_source_close(out);
            /* a part of the bands (--band-layers): GDAL reads any band of what it knows */
            struct vts_error why = {0};
            rc = vt_input_gdal_open(path, max_pixels, first, count, out, &why);
            if (rc < 0)
                rc = vt_error_set(err, VTS_ERR_ARG, "cannot read '%s': bands %u..%u of %u (%s)",
                                  path, first + 1, first + count, bands, why.message);
        }
    }
    if (rc < 0) {
        memset(out, 0, sizeof *out);
        return rc;
    }
    vt_input_copy_name(out->name, sizeof out->name, path);
    return 0;
}

int vt_image_input_describe(const char *path, const struct vt_input_limits *limits,
                            struct vt_input_raster *out, struct vts_error *err)
{
    memset(out, 0, sizeof *out);
    uint64_t max_pixels = 0;
    struct input_plan plan;
    int rc = input_start(path, limits, &max_pixels, &plan, err);
    if (rc < 0)
        return rc;
    out->geo_unread = plan.geo && plan.gdal_missing;
    snprintf(out->why, sizeof out->why, "%s", plan.why);
    if (plan.describe_gdal) {
        rc = vt_input_gdal_describe(path, max_pixels, out, err);
        if (rc < 0 || plan.pixels_gdal)
            return rc;
    }
    /* the native reader's channels (a palette becomes 3) */
    struct vt_source src;
    memset(&src, 0, sizeof src);
    rc = plan.reader->open(path, max_pixels, &src, err);
    if (rc < 0 && plan.gdal_missing)
        return vt_error_set(err, VTS_ERR_UNSUPPORTED,
                            "'%s': needs GDAL: cannot load the GDAL module (%s)", path, plan.why);
    if (rc < 0)
        return rc;
    out->band_count = src.info.channels;
    vt_source_close(&src);
    return 0;
}
