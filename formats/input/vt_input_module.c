/* Reader modules loaded with dlopen() (see internal/vt_input_module.h). No global state. */
#define _XOPEN_SOURCE 700 /* realpath */
#include "internal/vt_input_module.h"

#include <dlfcn.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

bool vt_input_module_symbol(void *module, const char *symbol, void *fn, size_t fn_size)
{
    void *p = dlsym(module, symbol);
    if (!p)
        return false;
    memcpy(fn, &p, fn_size);
    return true;
}

/* Tries one candidate path; on failure appends dlerror() to why. */
static void *module_try(const char *path, char *why, size_t why_size)
{
    if (!path || !path[0])
        return NULL;
    void *m = dlopen(path, RTLD_NOW | RTLD_LOCAL | RTLD_NODELETE);
    if (!m) {
        const char *e = dlerror();
        size_t used = strlen(why);
        if (used == 0) /* the first failure is the most telling (usually the environment's) */
            snprintf(why + used, why_size - used, "%s", e ? e : path);
    }
    return m;
}

/* The directory of the executable, or "" if unknown. */
static void module_exe_dir(char *buf, size_t size)
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
static bool module_in_build_tree(const char *dir)
{
    char build[PATH_MAX];
    if (!dir[0] || !realpath(VT_BUILD_DIR, build))
        return false;
    size_t n = strlen(build);
    return strncmp(dir, build, n) == 0 && (dir[n] == '/' || dir[n] == '\0');
}

void *vt_input_module_load(const struct vt_input_module_paths *p, char *why, size_t why_size)
{
    char dir[PATH_MAX], relative[PATH_MAX + 64];
    module_exe_dir(dir, sizeof dir);
    bool in_build = module_in_build_tree(dir);
    relative[0] = '\0';
    if (dir[0] && !in_build)
        snprintf(relative, sizeof relative, "%s/../%s", dir, p->relative_path);
    const char *candidates[] = {getenv(p->env), in_build ? p->build_path : relative,
                                in_build ? NULL : p->install_path};
    why[0] = '\0';
    for (size_t i = 0; i < sizeof candidates / sizeof candidates[0]; i++) {
        void *m = module_try(candidates[i], why, why_size);
        if (m)
            return m;
    }
    return NULL;
}

int vt_input_module_open_status(int result)
{
    switch (result) {
    case VT_INPUT_MODULE_UNKNOWN_FORMAT:
    case VT_INPUT_MODULE_UNSUPPORTED:
        return VTS_ERR_UNSUPPORTED;
    case VT_INPUT_MODULE_NOMEM:
        return VTS_ERR_NOMEM;
    default:
        return VTS_ERR_BAD_INPUT;
    }
}

int vt_input_module_read_error(int result, const char *name, uint32_t y, uint32_t height,
                               const char *msg, struct vts_error *err)
{
    if (result == VT_INPUT_MODULE_OK)
        return 0;
    return vt_error_set(err, result == VT_INPUT_MODULE_NOMEM ? VTS_ERR_NOMEM : VTS_ERR_BAD_INPUT,
                        "cannot read '%s': rows %u-%u: %s", name, y, y + height - 1, msg);
}

void vt_input_module_close(void *module, void *handle, void (*close_fn)(void *))
{
    if (handle)
        close_fn(handle);
    if (module)
        dlclose(module);
}
