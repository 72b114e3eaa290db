/* Private to formats/input: the C ABI of the OpenImageIO module libvt_oiio.so (vt_oiio_shim.cpp),
 * resolved with dlsym() by vt_input_oiio.c. Plain C types only: also compiled as C++. */
#ifndef VT_OIIO_ABI_H
#define VT_OIIO_ABI_H

#include <stddef.h>
#include <stdint.h>

/* Bump VT_OIIO_ABI_VERSION on any change. */

#define VT_OIIO_ABI_VERSION 1
#define VT_OIIO_ERR_MAX     256

enum vt_oiio_result {
    VT_OIIO_OK = 0,
    VT_OIIO_UNKNOWN_FORMAT = 1, /* no OpenImageIO reader recognises the file */
    VT_OIIO_BAD_FILE = 2,       /* a reader recognised it but failed (corrupt, truncated, I/O) */
    VT_OIIO_UNSUPPORTED = 3,    /* readable, but not as 1..4 channels of one sample type */
    VT_OIIO_NOMEM = 4,
};

struct vt_oiio_info {
    uint32_t width, height;  /* texels of subimage 0, level 0 (its data window) */
    uint32_t channels;       /* 1..4 */
    uint32_t sample;         /* enum vts_sample the module converts to */
    uint32_t has_alpha;      /* 1 when the last channel is alpha */
    uint32_t tile_w, tile_h; /* 0 for scanline files */
    char format[32];         /* OpenImageIO's format name ("targa", "hdr"...) */
};

/* int vt_oiio_abi_version(void) */
typedef int (*vt_oiio_abi_version_fn)(void);
/* Opens path; returns a handle and fills *info, or NULL with *result and err (one line) set. */
typedef void *(*vt_oiio_open_fn)(const char *path, struct vt_oiio_info *info, int *result,
                                 char err[VT_OIIO_ERR_MAX]);
/* Reads texels [x, x + w) x [y, y + h) as info->channels samples of info->sample into dst (rows
 * dst_stride bytes apart). Returns enum vt_oiio_result, err set on failure. */
typedef int (*vt_oiio_read_fn)(void *handle, uint32_t x, uint32_t y, uint32_t w, uint32_t h,
                               void *dst, size_t dst_stride, char err[VT_OIIO_ERR_MAX]);
/* Closes the handle; accepts NULL. */
typedef void (*vt_oiio_close_fn)(void *handle);

#endif
