/* The OpenImageIO fallback for formats without a native reader (TGA, HDR, PSD, DDS, WebP...):
 * loads libvt_oiio.so (vt_oiio_shim.cpp) with dlopen() when the first such file is opened, so that
 * a process that reads only TIFF/PNG/JPEG/EXR never maps OpenImageIO (~0.4 s and ~130 MB).
 * The module is searched at $VT_OIIO_MODULE, then: for an executable inside the build tree, at
 * its build-tree path only; for any other (installed, or moved with its prefix) at
 * <dir of the executable>/../<libdir>/vtpipe/, then at the install path. An installed tool never
 * loads a module from the build tree, and a build-tree tool never loads an older installed one.
 * It is opened with RTLD_NODELETE: each
 * source holds a reference, and closing the last one does not unload OpenImageIO (whose static
 * state does not survive unloading, and reloading costs the start-up again). No global state. */
#define _XOPEN_SOURCE 700 /* realpath */
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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

#include <dlfcn.h>
#include <limits.h>
#include <unistd.h>

struct oiio_input {
    void *module; /* dlopen() reference */
    void *handle; /* the module's open image */
    vt_oiio_read_fn read;
    vt_oiio_close_fn close;
    char name[256];
};

/* dlsym() into a function pointer without the object-to-function pointer cast. */
static bool oiio_symbol(void *module, const char *symbol, void *fn, size_t fn_size)
{
    void *p = dlsym(module, symbol);
    if (!p)
        return false;
    memcpy(fn, &p, fn_size);
    return true;
}

/* Tries one candidate path; on failure appends dlerror() to why. */
static void *oiio_try(const char *path, char *why, size_t why_size)
{
    if (!path || !path[0])
        return NULL;
    void *m = dlopen(path, RTLD_NOW | RTLD_LOCAL | RTLD_NODELETE);
    if (!m) {
        const char *e = dlerror();
        size_t used = strlen(why);
        if (used == 0) /* the first failure is the most telling (usually $VT_OIIO_MODULE) */
            snprintf(why + used, why_size - used, "%s", e ? e : path);
    }
    return m;
}

/* The directory of the executable, or "" if unknown. */
static void oiio_exe_dir(char *buf, size_t size)
{
    buf[0] = '\0';
    ssize_t n = readlink("/proc/self/exe", buf, size - 1);
    if (n <= 0)
        return;
    buf[n] = '\0';
    char *slash = strrchr(buf, '/');
    if (slash)
        *slash = '\0';
    else
        buf[0] = '\0';
}

/* True when dir is VT_BUILD_DIR or below it (both resolved: the build directory may be reached
 * through a link). */
static bool oiio_in_build_tree(const char *dir)
{
    char build[PATH_MAX];
    if (!dir[0] || !realpath(VT_BUILD_DIR, build))
        return false;
    size_t n = strlen(build);
    return strncmp(dir, build, n) == 0 && (dir[n] == '/' || dir[n] == '\0');
}

static void *oiio_load(char *why, size_t why_size)
{
    char dir[PATH_MAX], relative[PATH_MAX + 64];
    oiio_exe_dir(dir, sizeof dir);
    bool in_build = oiio_in_build_tree(dir);
    relative[0] = '\0';
    if (dir[0] && !in_build)
        snprintf(relative, sizeof relative, "%s/../%s", dir, VT_OIIO_RELATIVE_PATH);
    const char *candidates[] = {getenv("VT_OIIO_MODULE"), in_build ? VT_OIIO_BUILD_PATH : relative,
                                in_build ? NULL : VT_OIIO_INSTALL_PATH};
    why[0] = '\0';
    for (size_t i = 0; i < sizeof candidates / sizeof candidates[0]; i++) {
        void *m = oiio_try(candidates[i], why, why_size);
        if (m)
            return m;
    }
    return NULL;
}

static int oiio_read_region(void *ctx, uint32_t x, uint32_t y, struct vt_image *dst,
                            struct vts_error *err)
{
    struct oiio_input *t = ctx;
    char msg[VT_OIIO_ERR_MAX] = "";
    int r = t->read(t->handle, x, y, dst->width, dst->height, dst->pixels, dst->stride, msg);
    if (r == VT_OIIO_OK)
        return 0;
    return vt_error_set(err, r == VT_OIIO_NOMEM ? VTS_ERR_NOMEM : VTS_ERR_BAD_INPUT,
                        "cannot read '%s': rows %u-%u: %s", t->name, y, y + dst->height - 1, msg);
}

static void oiio_close(void *ctx)
{
    struct oiio_input *t = ctx;
    if (!t)
        return;
    if (t->handle)
        t->close(t->handle);
    if (t->module)
        dlclose(t->module);
    free(t);
}

static const struct vt_source_ops oiio_ops = {oiio_read_region, oiio_close};

static int oiio_status(int result)
{
    switch (result) {
    case VT_OIIO_UNKNOWN_FORMAT:
    case VT_OIIO_UNSUPPORTED:
        return VTS_ERR_UNSUPPORTED;
    case VT_OIIO_NOMEM:
        return VTS_ERR_NOMEM;
    default:
        return VTS_ERR_BAD_INPUT;
    }
}

/* Resolves the module's functions and opens path through it. */
static int oiio_open_with(struct oiio_input *t, const char *path, uint64_t max_pixels,
                          struct vt_source *out, struct vts_error *err)
{
    vt_oiio_abi_version_fn version;
    vt_oiio_open_fn open_fn;
    if (!oiio_symbol(t->module, "vt_oiio_abi_version", &version, sizeof version) ||
        !oiio_symbol(t->module, "vt_oiio_open", &open_fn, sizeof open_fn) ||
        !oiio_symbol(t->module, "vt_oiio_read", &t->read, sizeof t->read) ||
        !oiio_symbol(t->module, "vt_oiio_close", &t->close, sizeof t->close) ||
        version() != VT_OIIO_ABI_VERSION)
        return vt_error_set(
            err, VTS_ERR_UNSUPPORTED,
            "'%s': format not supported: the OpenImageIO module does not match this build", path);
    struct vt_oiio_info info;
    char msg[VT_OIIO_ERR_MAX] = "";
    int result = VT_OIIO_BAD_FILE;
    t->handle = open_fn(path, &info, &result, msg);
    if (!t->handle)
        return vt_error_set(err, oiio_status(result), "cannot read '%s': %s", path, msg);
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
