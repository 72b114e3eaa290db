/* The GDAL input (GeoTIFF, JPEG 2000, VRT mosaics, and TIFFs the native reader does not take):
 * loads libvt_gdal.so (vt_gdal_module.c) with dlopen() when the first such file is met, so that a
 * process that reads only the native formats never maps GDAL. The module is searched at
 * $VT_GDAL_MODULE, then where internal/vt_input_module.h says. Each source is one GDAL dataset
 * handle reading one group of up to 4 bands, region by region (GDAL reads the blocks under the
 * region through its bounded block cache): out of core. No global state. */
#include "internal/vt_input_gdal.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "internal/vt_input_util.h"
#include "vt_error.h"

#ifndef VT_HAVE_GDAL

bool vt_input_gdal_sniff(const unsigned char *magic, size_t len)
{
    (void)magic;
    (void)len;
    return false;
}

bool vt_input_gdal_available(char *why, size_t why_size)
{
    snprintf(why, why_size, "built without GDAL");
    return false;
}

int vt_input_gdal_open(const char *path, uint64_t max_pixels, uint32_t first, uint32_t count,
                       struct vt_source *out, struct vts_error *err)
{
    (void)max_pixels;
    (void)first;
    (void)count;
    (void)out;
    return vt_error_set(err, VTS_ERR_UNSUPPORTED, "'%s': needs GDAL (built without it)", path);
}

int vt_input_gdal_describe(const char *path, uint64_t max_pixels, struct vt_input_raster *out,
                           struct vts_error *err)
{
    (void)max_pixels;
    (void)out;
    return vt_error_set(err, VTS_ERR_UNSUPPORTED, "'%s': needs GDAL (built without it)", path);
}

#else

#include <dlfcn.h>

#include "internal/vt_gdal_abi.h"
#include "internal/vt_input_module.h"

struct gdal_input {
    void *module; /* dlopen() reference */
    void *handle; /* the module's open dataset */
    struct vt_gdal_info info;
    uint32_t first, count; /* 1-based first band, bands read */
    vt_gdal_read_fn read;
    vt_gdal_close_fn close;
    vt_gdal_band_name_fn band_name;
    vt_gdal_crs_wkt_fn crs_wkt;
    char name[256];
};

static const struct vt_input_module_paths gdal_paths = {
    "VT_GDAL_MODULE", VT_GDAL_BUILD_PATH, VT_GDAL_RELATIVE_PATH, VT_GDAL_INSTALL_PATH};

bool vt_input_gdal_sniff(const unsigned char *magic, size_t len)
{
    static const unsigned char jp2[8] = {0, 0, 0, 12, 'j', 'P', ' ', ' '};
    static const unsigned char j2k[4] = {0xff, 0x4f, 0xff, 0x51};
    return (len >= 8 && memcmp(magic, "<VRTData", 8) == 0) ||
           (len >= 8 && memcmp(magic, jp2, 8) == 0) || (len >= 4 && memcmp(magic, j2k, 4) == 0);
}

bool vt_input_gdal_available(char *why, size_t why_size)
{
    void *m = vt_input_module_load(&gdal_paths, why, why_size);
    if (m)
        dlclose(m);
    return m != NULL;
}

static int gdal_read_region(void *ctx, uint32_t x, uint32_t y, struct vt_image *dst,
                            struct vts_error *err)
{
    struct gdal_input *t = ctx;
    char msg[VT_GDAL_ERR_MAX] = "";
    int r = t->read(t->handle, t->first, t->count, x, y, dst->width, dst->height, dst->pixels,
                    dst->stride, msg);
    return vt_input_module_read_error(r, t->name, y, dst->height, msg, err);
}

static void gdal_close(void *ctx)
{
    struct gdal_input *t = ctx;
    if (!t)
        return;
    vt_input_module_close(t->module, t->handle, t->close);
    free(t);
}

static const struct vt_source_ops gdal_ops = {gdal_read_region, gdal_close};

_Static_assert((int)VT_GDAL_OK == VT_INPUT_MODULE_OK &&
                   (int)VT_GDAL_UNKNOWN_FORMAT == VT_INPUT_MODULE_UNKNOWN_FORMAT &&
                   (int)VT_GDAL_BAD_FILE == VT_INPUT_MODULE_BAD_FILE &&
                   (int)VT_GDAL_UNSUPPORTED == VT_INPUT_MODULE_UNSUPPORTED &&
                   (int)VT_GDAL_NOMEM == VT_INPUT_MODULE_NOMEM,
               "the module's results are vt_input_module.h's");

/* Loads the module, resolves its functions and opens path: a gdal_input to gdal_close(). */
static int gdal_load_open(const char *path, uint64_t max_pixels, struct gdal_input **out,
                          struct vts_error *err)
{
    *out = NULL;
    struct gdal_input *t = calloc(1, sizeof *t);
    if (!t)
        return vt_error_set(err, VTS_ERR_NOMEM, "cannot read '%s': out of memory", path);
    vt_input_copy_name(t->name, sizeof t->name, path);
    char why[200];
    int rc;
    t->module = vt_input_module_load(&gdal_paths, why, sizeof why);
    if (!t->module) {
        rc = vt_error_set(err, VTS_ERR_UNSUPPORTED,
                          "'%s': needs GDAL: cannot load the GDAL module (%s)", path, why);
        goto out_close;
    }
    vt_gdal_abi_version_fn version;
    vt_gdal_open_fn open_fn;
    void *m = t->module;
    if (!vt_input_module_symbol(m, "vt_gdal_abi_version", &version, sizeof version) ||
        !vt_input_module_symbol(m, "vt_gdal_open", &open_fn, sizeof open_fn) ||
        !vt_input_module_symbol(m, "vt_gdal_read", &t->read, sizeof t->read) ||
        !vt_input_module_symbol(m, "vt_gdal_close", &t->close, sizeof t->close) ||
        !vt_input_module_symbol(m, "vt_gdal_band_name", &t->band_name, sizeof t->band_name) ||
        !vt_input_module_symbol(m, "vt_gdal_crs_wkt", &t->crs_wkt, sizeof t->crs_wkt) ||
        version() != VT_GDAL_ABI_VERSION) {
        rc = vt_error_set(err, VTS_ERR_UNSUPPORTED,
                          "'%s': needs GDAL: the GDAL module does not match this build", path);
        goto out_close;
    }
    char msg[VT_GDAL_ERR_MAX] = "";
    int result = VT_GDAL_BAD_FILE;
    t->handle = open_fn(path, &t->info, &result, msg);
    if (!t->handle) {
        rc = vt_error_set(err, vt_input_module_open_status(result), "cannot read '%s': %s", path,
                          msg);
        goto out_close;
    }
    rc = vt_input_check_size(path, t->info.width, t->info.height, max_pixels, err);
    if (rc == 0 && t->info.bands > VT_INPUT_MAX_BANDS)
        rc = vt_error_set(err, VTS_ERR_UNSUPPORTED, "cannot read '%s': %u bands (at most %u)", path,
                          t->info.bands, VT_INPUT_MAX_BANDS);
    if (rc < 0)
        goto out_close;
    *out = t;
    return 0;

out_close:
    gdal_close(t);
    return rc;
}

int vt_input_gdal_open(const char *path, uint64_t max_pixels, uint32_t first, uint32_t count,
                       struct vt_source *out, struct vts_error *err)
{
    struct gdal_input *t;
    int rc = gdal_load_open(path, max_pixels, &t, err);
    if (rc < 0)
        return rc;
    const struct vt_gdal_info *in = &t->info;
    if (count == 0 && in->bands > 4) {
        rc = vt_error_set(
            err, VTS_ERR_UNSUPPORTED,
            "cannot read '%s': %u channels (1 to 4 per layer: vt-tiles makes one layer per 4 bands)",
            path, in->bands);
        goto out_close;
    }
    if (count == 0)
        count = in->bands;
    if (count > 4 || first >= in->bands || count > in->bands - first) {
        rc = vt_error_set(err, VTS_ERR_ARG, "cannot read '%s': bands %u..%u of %u", path, first + 1,
                          first + count, in->bands);
        goto out_close;
    }
    t->first = first + 1;
    t->count = count;
    /* striped files (a block as wide as the image) are read in full-width bands */
    bool sequential = in->block_w >= in->width && in->block_h < in->height;
    char format[32];
    snprintf(format, sizeof format, "gdal:%s", in->format);
    vt_input_set_info(&out->info, in->width, in->height, count, in->sample, sequential,
                      sequential ? 0 : in->block_w, sequential ? 0 : in->block_h, format);
    bool last = first + count == in->bands;
    out->info.has_alpha = last && in->alpha_last && (count == 2 || count == 4);
    if (!in->photometric || in->bands > 4)
        out->info.colour = VTS_COLOUR_DATA;
    out->ops = &gdal_ops;
    out->ctx = t;
    return 0;

out_close:
    gdal_close(t);
    return rc;
}

int vt_input_gdal_describe(const char *path, uint64_t max_pixels, struct vt_input_raster *out,
                           struct vts_error *err)
{
    struct gdal_input *t;
    int rc = gdal_load_open(path, max_pixels, &t, err);
    if (rc < 0)
        return rc;
    out->band_count = t->info.bands;
    for (uint32_t b = 0; b < t->info.bands; b++)
        t->band_name(t->handle, b + 1, out->band_names[b], sizeof out->band_names[b]);
    out->has_geotransform = t->info.has_geotransform != 0;
    memcpy(out->geotransform, t->info.geotransform, sizeof out->geotransform);
    out->has_nodata = t->info.has_nodata != 0;
    out->nodata = t->info.nodata;
    out->has_scale = t->info.has_scale != 0;
    out->scale = t->info.scale;
    out->offset = t->info.offset;
    out->crs_wkt = t->crs_wkt(t->handle);
    gdal_close(t);
    return 0;
}

#endif
