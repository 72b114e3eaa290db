/* Private to the image input files of formats/ (vt_image_input.c, vt_input_*.c, vt_oiio_shim.cpp):
 * the readers' entry points, shared checks and the C ABI of the OpenImageIO module. Not installed.
 */
#ifndef VT_INPUT_IMPL_H
#define VT_INPUT_IMPL_H

#include <stddef.h>
#include <stdint.h>

/* ---- ABI of libvt_oiio.so (vt_oiio_shim.cpp), resolved with dlsym() by vt_input_oiio.c ----
 * Plain C types only: this part is also compiled as C++. Bump VT_OIIO_ABI_VERSION on any change. */

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

#ifndef __cplusplus

#include <stdbool.h>

#include "vt_error.h"
#include "vt_image.h"
#include "vt_source.h"

/* Bytes above which a single decode buffer (a TIFF strip or tile, a de-interlaced PNG) is
 * refused: hostile headers can declare huge tiles. */
#define VT_INPUT_MAX_BUFFER_BYTES (1ull << 30)

/* Reader entry points: path is already known to carry the format's magic. Each fills out->info,
 * out->ops and out->ctx (not out->name) and returns 0, or a negative status with err naming path
 * and leaves *out untouched. max_pixels is the resolved limit (never 0). */
int vt_input_tiff_open(const char *path, uint64_t max_pixels, struct vt_source *out,
                       struct vts_error *err);
int vt_input_png_open(const char *path, uint64_t max_pixels, struct vt_source *out,
                      struct vts_error *err);
int vt_input_jpeg_open(const char *path, uint64_t max_pixels, struct vt_source *out,
                       struct vts_error *err);
int vt_input_exr_open(const char *path, uint64_t max_pixels, struct vt_source *out,
                      struct vts_error *err);
/* The fallback: loads libvt_oiio.so (see vt_input_oiio.c for where it is searched). */
int vt_input_oiio_open(const char *path, uint64_t max_pixels, struct vt_source *out,
                       struct vts_error *err);

/* Checks a header's size: 0 in either direction is VTS_ERR_BAD_INPUT, more than max_pixels texels
 * VTS_ERR_LIMIT ("'x.tif': 200000x200000 texels exceeds --max-pixels 17179869184"). */
int vt_input_check_size(const char *path, uint64_t width, uint64_t height, uint64_t max_pixels,
                        struct vts_error *err);

/* Copies path into a reader's name buffer (for messages), truncating if needed. */
void vt_input_copy_name(char *dst, size_t dst_size, const char *path);

/* Fills the parts of info every reader sets the same way (colour from the sample type, has_alpha
 * from the channel count, tiling, format name). */
void vt_input_set_info(struct vt_source_info *info, uint32_t width, uint32_t height,
                       uint32_t channels, uint32_t sample, bool sequential, uint32_t tile_w,
                       uint32_t tile_h, const char *format);

#endif /* !__cplusplus */
#endif
