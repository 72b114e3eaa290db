/* Private to formats/input: finding and loading a reader module (libvt_oiio.so, libvt_gdal.so)
 * with dlopen() when the first file that needs it is met. */
#ifndef VT_INPUT_MODULE_H
#define VT_INPUT_MODULE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "vt_error.h"

/* Where a module may be. */
struct vt_input_module_paths {
    const char *env;           /* an environment variable naming it ("VT_OIIO_MODULE") */
    const char *build_path;    /* its path in the build tree */
    const char *relative_path; /* <libdir>/vtpipe/<file>, relative to the install prefix */
    const char *install_path;  /* its installed path */
};

/* Loads the module: the file named by $env, then for an executable inside the build tree its
 * build-tree path only, for any other (installed, or moved with its prefix)
 * <dir of the executable>/../relative_path, then install_path. An installed tool never loads a
 * module from the build tree, and a build-tree tool never loads an older installed one. Opened
 * with RTLD_NODELETE (the libraries' static state does not survive unloading). Returns the
 * handle (dlclose() it), or NULL with why (the first failure's dlerror()) filled. */
void *vt_input_module_load(const struct vt_input_module_paths *paths, char *why, size_t why_size);

/* dlsym() into a function pointer (fn, fn_size bytes) without an object-to-function cast. */
bool vt_input_module_symbol(void *module, const char *symbol, void *fn, size_t fn_size);

/* The results of every module's open and read: the values vt_oiio_abi.h's and vt_gdal_abi.h's
 * enums pin (each reader checks its own against these with _Static_assert). */
enum vt_input_module_result {
    VT_INPUT_MODULE_OK = 0,
    VT_INPUT_MODULE_UNKNOWN_FORMAT = 1,
    VT_INPUT_MODULE_BAD_FILE = 2,
    VT_INPUT_MODULE_UNSUPPORTED = 3,
    VT_INPUT_MODULE_NOMEM = 4,
};

/* The status of a module open's failed result: VTS_ERR_UNSUPPORTED for an unknown format or an
 * unsupported layout, VTS_ERR_NOMEM, else VTS_ERR_BAD_INPUT. */
int vt_input_module_open_status(int result);

/* 0 for a module read's VT_INPUT_MODULE_OK, else fills err (VTS_ERR_NOMEM or VTS_ERR_BAD_INPUT)
 * with "cannot read 'name': rows y-(y + height - 1): msg" and returns its status. */
int vt_input_module_read_error(int result, const char *name, uint32_t y, uint32_t height,
                               const char *msg, struct vts_error *err);

/* Closes a module's open handle with the module's close function (when both are set), then drops
 * the module reference (when set). */
void vt_input_module_close(void *module, void *handle, void (*close_fn)(void *));

#endif
