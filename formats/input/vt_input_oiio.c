/* The OpenImageIO fallback for formats without a native reader (TGA, HDR, PSD, DDS, WebP...):
 * loads libvt_oiio.so (vt_oiio_shim.cpp) with dlopen() when the first such file is opened, so that
 * a process that reads only TIFF/PNG/JPEG/EXR never maps OpenImageIO (~0.4 s and ~130 MB).
 * The module is searched at $VT_OIIO_MODULE, then where internal/vt_input_module.h says. It is
 * opened with RTLD_NODELETE: each source holds a reference, and closing the last one does not
 * unload OpenImageIO (whose static state does not survive unloading, and reloading costs the
 * start-up again). No global state. */
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "internal/vt_input_module.h"
#include "internal/vt_input_readers.h"
#include "internal/vt_input_util.h"
#include "internal/vt_oiio_abi.h"
#include "vt_error.h"

#ifndef VT_HAVE_OIIO

static int oiio_open(const char *path, uint64_t max_pixels, struct vt_source *out,
                     struct vts_error *err)
{
    (void)max_pixels;
    (void)out;
    return vt_error_set(err, VTS_ERR_UNSUPPORTED,
                        "'%s': format not supported (built without OpenImageIO)", path);
}

#else

struct oiio_input {
    void *module; /* dlopen() reference */
    void *handle; /* the module's open image */
    vt_oiio_read_fn read;
    vt_oiio_close_fn close;
    char name[256];
};

static void *oiio_load(char *why, size_t why_size)
{
    const struct vt_input_module_paths paths = {"VT_OIIO_MODULE", VT_OIIO_BUILD_PATH,
                                                VT_OIIO_RELATIVE_PATH, VT_OIIO_INSTALL_PATH};
    return vt_input_module_load(&paths, why, why_size);
}

static int oiio_read_region(void *ctx, uint32_t x, uint32_t y, struct vt_image *dst,
                            struct vts_error *err)
{
    struct oiio_input *t = ctx;
    char msg[VT_OIIO_ERR_MAX] = "";
    int r = t->read(t->handle, x, y, dst->width, dst->height, dst->pixels, dst->stride, msg);
    return vt_input_module_read_error(r, t->name, y, dst->height, msg, err);
}

static void oiio_close(void *ctx)
{
    struct oiio_input *t = ctx;
    if (!t)
        return;
    vt_input_module_close(t->module, t->handle, t->close);
    free(t);
}

static const struct vt_source_ops oiio_ops = {oiio_read_region, oiio_close};

_Static_assert((int)VT_OIIO_OK == VT_INPUT_MODULE_OK &&
                   (int)VT_OIIO_UNKNOWN_FORMAT == VT_INPUT_MODULE_UNKNOWN_FORMAT &&
                   (int)VT_OIIO_BAD_FILE == VT_INPUT_MODULE_BAD_FILE &&
                   (int)VT_OIIO_UNSUPPORTED == VT_INPUT_MODULE_UNSUPPORTED &&
                   (int)VT_OIIO_NOMEM == VT_INPUT_MODULE_NOMEM,
               "the module's results are vt_input_module.h's");

/* Resolves the module's functions and opens path through it. */
static int oiio_open_with(struct oiio_input *t, const char *path, uint64_t max_pixels,
                          struct vt_source *out, struct vts_error *err)
{
    vt_oiio_abi_version_fn version;
    vt_oiio_open_fn open_fn;
    if (!vt_input_module_symbol(t->module, "vt_oiio_abi_version", &version, sizeof version) ||
        !vt_input_module_symbol(t->module, "vt_oiio_open", &open_fn, sizeof open_fn) ||
        !vt_input_module_symbol(t->module, "vt_oiio_read", &t->read, sizeof t->read) ||
        !vt_input_module_symbol(t->module, "vt_oiio_close", &t->close, sizeof t->close) ||
        version() != VT_OIIO_ABI_VERSION)
        return vt_error_set(
            err, VTS_ERR_UNSUPPORTED,
            "'%s': format not supported: the OpenImageIO module does not match this build", path);
    struct vt_oiio_info info;
    char msg[VT_OIIO_ERR_MAX] = "";
    int result = VT_OIIO_BAD_FILE;
    t->handle = open_fn(path, &info, &result, msg);
    if (!t->handle)
        return vt_error_set(err, vt_input_module_open_status(result), "cannot read '%s': %s", path,
                            msg);
    int rc = vt_input_check_size(path, info.width, info.height, max_pixels, err);
    if (rc < 0)
        return rc;
    if (info.channels < 1 || info.channels > 4 || vts_sample_bytes(info.sample) == 0)
        return vt_error_set(err, VTS_ERR_UNSUPPORTED, "cannot read '%s': %u channels", path,
                            info.channels);
    char format[32];
    snprintf(format, sizeof format, "oiio:%.*s", 10, info.format);
    vt_input_set_info(&out->info, info.width, info.height, info.channels, info.sample,
                      info.tile_w == 0, info.tile_w, info.tile_h, format);
    out->info.has_alpha = info.has_alpha != 0;
    return 0;
}

static int oiio_open(const char *path, uint64_t max_pixels, struct vt_source *out,
                     struct vts_error *err)
{
    struct oiio_input *t = calloc(1, sizeof *t);
    if (!t)
        return vt_error_set(err, VTS_ERR_NOMEM, "cannot read '%s': out of memory", path);
    vt_input_copy_name(t->name, sizeof t->name, path);
    char why[200];
    t->module = oiio_load(why, sizeof why);
    int rc;
    if (!t->module) {
        rc = vt_error_set(err, VTS_ERR_UNSUPPORTED,
                          "'%s': format not supported: cannot load the OpenImageIO module (%s)",
                          path, why);
        goto out_close;
    }
    rc = oiio_open_with(t, path, max_pixels, out, err);
    if (rc < 0)
        goto out_close;
    out->ops = &oiio_ops;
    out->ctx = t;
    return 0;

out_close:
    oiio_close(t);
    return rc;
}

#endif

const struct vt_input_reader vt_input_reader_oiio = {"oiio", NULL, oiio_open};
