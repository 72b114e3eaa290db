/* libvt_gdal.so: the GDAL input of formats/input (GeoTIFF, JPEG 2000, VRT mosaics...), behind the
 * plain C ABI in internal/vt_gdal_abi.h. Built as a module and dlopen()ed by vt_input_gdal.c only
 * when a file that needs GDAL is met, so that the tools never link libgdal. Pixels are read with
 * GDALDatasetRasterIOEx of the regions asked for: GDAL reads the blocks under them (and a VRT the
 * parts of its sources under them) through its block cache, which this module bounds to
 * VT_GDAL_CACHE_BYTES unless GDAL_CACHEMAX is set. GDAL's messages never reach stderr: the last
 * one is returned with the failure. */
#define _POSIX_C_SOURCE 200809L
#include <gdal.h>

#include <cpl_conv.h>
#include <cpl_error.h>
#include <ogr_srs_api.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "internal/vt_gdal_abi.h"
#include "vts.h"

#define VT_GDAL_EXPORT __attribute__((visibility("default")))

/* GDAL's default block cache is 5% of the RAM: bounded here so that RSS stays flat in the size of
 * the input (docs/geospatial.md). */
#define VT_GDAL_CACHE_BYTES (16ll << 20)

struct gdal_handle {
    GDALDatasetH ds;
    GDALDataType type; /* what the caller gets */
    uint32_t bands;
};

static void gdal_error(char *err, const char *what)
{
    const char *msg = CPLGetLastErrorMsg();
    snprintf(err, VT_GDAL_ERR_MAX, "%s%s%s", what, msg && msg[0] ? ": " : "", msg ? msg : "");
    for (char *p = err; *p; p++)
        if (*p == '\n' || *p == '\r')
            *p = ' ';
}

static void gdal_quiet(CPLErr cls, CPLErrorNum num, const char *msg)
{
    (void)cls;
    (void)num;
    (void)msg;
}

VT_GDAL_EXPORT int vt_gdal_abi_version(void)
{
    return VT_GDAL_ABI_VERSION;
}

/* The caller's type for a stored one: 8/16-bit unsigned as stored, everything else (signed
 * integers, 32-bit integers, 64-bit floats) as 32-bit float; complex types are refused. */
static int gdal_choose_type(GDALDataType stored, GDALDataType *type, uint32_t *sample)
{
    switch (stored) {
    case GDT_Byte:
        *type = GDT_Byte;
        *sample = VTS_SAMPLE_U8;
        return 0;
    case GDT_UInt16:
        *type = GDT_UInt16;
        *sample = VTS_SAMPLE_U16;
        return 0;
    case GDT_Int16:
    case GDT_UInt32:
    case GDT_Int32:
    case GDT_Float32:
    case GDT_Float64:
        *type = GDT_Float32;
        *sample = VTS_SAMPLE_F32;
        return 0;
    default:
        return -1;
    }
}

static bool gdal_photometric(GDALDatasetH ds, uint32_t bands, bool alpha_last)
{
    uint32_t colour = bands - alpha_last;
    if (bands > 4 || colour == 2)
        return false;
    for (uint32_t b = 1; b <= colour; b++) {
        GDALColorInterp ci = GDALGetRasterColorInterpretation(GDALGetRasterBand(ds, (int)b));
        bool ok =
            colour == 1 ? ci == GCI_GrayIndex : ci == (GDALColorInterp)(GCI_RedBand + (int)(b - 1));
        if (!ok)
            return false;
    }
    return true;
}

static void gdal_set_cache(void)
{
    if (!CPLGetConfigOption("GDAL_CACHEMAX", NULL))
        GDALSetCacheMax64(VT_GDAL_CACHE_BYTES);
}

VT_GDAL_EXPORT void *vt_gdal_open(const char *path, struct vt_gdal_info *info, int *result,
                                  char err[VT_GDAL_ERR_MAX])
{
    memset(info, 0, sizeof *info);
    err[0] = '\0';
    GDALAllRegister();
    gdal_set_cache();
    CPLPushErrorHandler(gdal_quiet);
    CPLErrorReset();
    struct gdal_handle *h = calloc(1, sizeof *h);
    if (!h) {
        *result = VT_GDAL_NOMEM;
        snprintf(err, VT_GDAL_ERR_MAX, "out of memory");
        goto out_pop;
    }
    h->ds = GDALOpenEx(path, GDAL_OF_RASTER | GDAL_OF_READONLY, NULL, NULL, NULL);
    if (!h->ds) {
        *result =
            CPLGetLastErrorNo() == CPLE_OpenFailed ? VT_GDAL_UNKNOWN_FORMAT : VT_GDAL_BAD_FILE;
        gdal_error(err, "GDAL cannot open it");
        goto out_free;
    }
    int bands = GDALGetRasterCount(h->ds);
    int w = GDALGetRasterXSize(h->ds), ht = GDALGetRasterYSize(h->ds);
    *result = VT_GDAL_UNSUPPORTED;
    if (bands < 1 || w < 1 || ht < 1) {
        snprintf(err, VT_GDAL_ERR_MAX, "no raster bands");
        goto out_free;
    }
    GDALRasterBandH b1 = GDALGetRasterBand(h->ds, 1);
    GDALDataType stored = GDALGetRasterDataType(b1);
    for (int b = 2; b <= bands; b++)
        if (GDALGetRasterDataType(GDALGetRasterBand(h->ds, b)) != stored) {
            snprintf(err, VT_GDAL_ERR_MAX, "bands of different sample types");
            goto out_free;
        }
    if (gdal_choose_type(stored, &h->type, &info->sample) < 0) {
        snprintf(err, VT_GDAL_ERR_MAX, "%s samples are not supported", GDALGetDataTypeName(stored));
        goto out_free;
    }
    h->bands = (uint32_t)bands;
    info->width = (uint32_t)w;
    info->height = (uint32_t)ht;
    info->bands = (uint32_t)bands;
    int bw = 0, bh = 0;
    GDALGetBlockSize(b1, &bw, &bh);
    info->block_w = bw > 0 ? (uint32_t)bw : 0;
    info->block_h = bh > 0 ? (uint32_t)bh : 0;
    GDALColorInterp last = GDALGetRasterColorInterpretation(GDALGetRasterBand(h->ds, bands));
    info->alpha_last = bands > 1 && last == GCI_AlphaBand;
    info->photometric = gdal_photometric(h->ds, h->bands, info->alpha_last);
    info->has_geotransform = GDALGetGeoTransform(h->ds, info->geotransform) == CE_None;
    int has_nodata = 0;
    info->nodata = GDALGetRasterNoDataValue(b1, &has_nodata);
    info->has_nodata = has_nodata != 0;
    int has_scale = 0, has_offset = 0;
    info->scale = GDALGetRasterScale(b1, &has_scale);
    info->offset = GDALGetRasterOffset(b1, &has_offset);
    info->has_scale = (has_scale || has_offset) && info->scale != 0.0;
    GDALDriverH drv = GDALGetDatasetDriver(h->ds);
    snprintf(info->format, sizeof info->format, "%s", drv ? GDALGetDriverShortName(drv) : "?");
    *result = VT_GDAL_OK;
    CPLPopErrorHandler();
    return h;

out_free:
    if (h->ds)
        GDALClose(h->ds);
    free(h);
out_pop:
    CPLPopErrorHandler();
    return NULL;
}

VT_GDAL_EXPORT void vt_gdal_band_name(void *handle, uint32_t band, char *buf, size_t size)
{
    struct gdal_handle *h = handle;
    buf[0] = '\0';
    if (band < 1 || band > h->bands)
        return;
    const char *d = GDALGetDescription(GDALGetRasterBand(h->ds, (int)band));
    snprintf(buf, size, "%s", d ? d : "");
}

VT_GDAL_EXPORT char *vt_gdal_crs_wkt(void *handle)
{
    struct gdal_handle *h = handle;
    OGRSpatialReferenceH srs = GDALGetSpatialRef(h->ds);
    if (!srs)
        return NULL;
    /* the form gdalinfo -json shows (WKT2 2019), on one line */
    const char *const options[] = {"FORMAT=WKT2_2019", "MULTILINE=NO", NULL};
    char *wkt = NULL;
    if (OSRExportToWktEx(srs, &wkt, options) != OGRERR_NONE || !wkt) {
        CPLFree(wkt);
        return NULL;
    }
    char *copy = strdup(wkt); /* the caller frees with free(), not CPLFree() */
    CPLFree(wkt);
    return copy;
}

VT_GDAL_EXPORT int vt_gdal_read(void *handle, uint32_t first, uint32_t count, uint32_t x,
                                uint32_t y, uint32_t w, uint32_t h, void *dst, size_t dst_stride,
                                char err[VT_GDAL_ERR_MAX])
{
    struct gdal_handle *g = handle;
    int map[4];
    if (count < 1 || count > 4 || first < 1 || first + count - 1 > g->bands) {
        snprintf(err, VT_GDAL_ERR_MAX, "bands %u..%u of %u", first, first + count - 1, g->bands);
        return VT_GDAL_UNSUPPORTED;
    }
    for (uint32_t i = 0; i < count; i++)
        map[i] = (int)(first + i);
    int bytes = GDALGetDataTypeSizeBytes(g->type);
    CPLPushErrorHandler(gdal_quiet);
    CPLErrorReset();
    CPLErr e = GDALDatasetRasterIOEx(g->ds, GF_Read, (int)x, (int)y, (int)w, (int)h, dst, (int)w,
                                     (int)h, g->type, (int)count, map, (GSpacing)bytes * count,
                                     (GSpacing)dst_stride, bytes, NULL);
    if (e != CE_None)
        gdal_error(err, "GDAL read failed");
    CPLPopErrorHandler();
    return e == CE_None ? VT_GDAL_OK : VT_GDAL_BAD_FILE;
}

VT_GDAL_EXPORT void vt_gdal_close(void *handle)
{
    struct gdal_handle *h = handle;
    if (!h)
        return;
    GDALClose(h->ds);
    free(h);
}
