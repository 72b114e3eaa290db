/* Private to formats/input: the C ABI of the GDAL module libvt_gdal.so (vt_gdal_module.c),
 * resolved with dlsym() by vt_input_gdal.c. Plain C types only. */
#ifndef VT_GDAL_ABI_H
#define VT_GDAL_ABI_H

#include <stddef.h>
#include <stdint.h>

/* Bump VT_GDAL_ABI_VERSION on any change. */

#define VT_GDAL_ABI_VERSION 2
#define VT_GDAL_ERR_MAX     256

enum vt_gdal_result {
    VT_GDAL_OK = 0,
    VT_GDAL_UNKNOWN_FORMAT = 1, /* no GDAL driver recognises the file */
    VT_GDAL_BAD_FILE = 2,       /* a driver recognised it but failed (corrupt, truncated, I/O) */
    VT_GDAL_UNSUPPORTED = 3,    /* readable, but not as unsigned/float samples of one type */
    VT_GDAL_NOMEM = 4,
};

struct vt_gdal_info {
    uint32_t width, height;    /* texels of the dataset */
    uint32_t bands;            /* >= 1 */
    uint32_t sample;           /* enum vts_sample every band is converted to (the same for all) */
    uint32_t block_w, block_h; /* the first band's natural block size */
    uint32_t alpha_last;       /* 1 when the last band's colour interpretation is alpha */
    uint32_t photometric;      /* 1 when the bands are grey or RGB colour (+ alpha), not data */
    uint32_t has_geotransform; /* 1 when geotransform[] holds the dataset's */
    uint32_t has_nodata;       /* 1 when the first band has a nodata value */
    double geotransform[6];    /* GDAL's order: x0, dx/dcol, dx/drow, y0, dy/dcol, dy/drow */
    double nodata;
    char format[24];      /* the driver's short name ("GTiff", "VRT", "JP2OpenJPEG"...) */
    uint32_t has_scale;   /* 1 when the first band has a scale or an offset (GDAL's defaults 1, 0
                             for the other) */
    double scale, offset; /* its value = stored * scale + offset */
};

/* int vt_gdal_abi_version(void) */
typedef int (*vt_gdal_abi_version_fn)(void);
/* Opens path read-only; returns a handle and fills *info, or NULL with *result and err (one line)
 * set. */
typedef void *(*vt_gdal_open_fn)(const char *path, struct vt_gdal_info *info, int *result,
                                 char err[VT_GDAL_ERR_MAX]);
/* Copies band's (1-based) description into buf (NUL-terminated, truncated); "" when none. */
typedef void (*vt_gdal_band_name_fn)(void *handle, uint32_t band, char *buf, size_t size);
/* The dataset's CRS as WKT (malloc'ed, the caller frees it), or NULL when it has none. */
typedef char *(*vt_gdal_crs_wkt_fn)(void *handle);
/* Reads bands [first, first + count) (1-based) of texels [x, x + w) x [y, y + h), interleaved, as
 * info->sample into dst (rows dst_stride bytes apart). Returns enum vt_gdal_result, err set on
 * failure. */
typedef int (*vt_gdal_read_fn)(void *handle, uint32_t first, uint32_t count, uint32_t x, uint32_t y,
                               uint32_t w, uint32_t h, void *dst, size_t dst_stride,
                               char err[VT_GDAL_ERR_MAX]);
/* Closes the handle; accepts NULL. */
typedef void (*vt_gdal_close_fn)(void *handle);

/* The module's entry points (defined in vt_gdal_module.c, found with dlsym()), of the types above.
 */
int vt_gdal_abi_version(void);
void *vt_gdal_open(const char *path, struct vt_gdal_info *info, int *result,
                   char err[VT_GDAL_ERR_MAX]);
void vt_gdal_band_name(void *handle, uint32_t band, char *buf, size_t size);
char *vt_gdal_crs_wkt(void *handle);
int vt_gdal_read(void *handle, uint32_t first, uint32_t count, uint32_t x, uint32_t y, uint32_t w,
                 uint32_t h, void *dst, size_t dst_stride, char err[VT_GDAL_ERR_MAX]);
void vt_gdal_close(void *handle);

#endif
