/* Private to formats/input: finding and loading a reader module (libvt_oiio.so, libvt_gdal.so)
 * with dlopen() when the first file that needs it is met. */
#ifndef VT_INPUT_MODULE_H
#define VT_INPUT_MODULE_H

#include <stdbool.h>
#include <stddef.h>

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

#endif
